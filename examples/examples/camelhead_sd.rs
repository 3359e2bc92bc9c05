//! Smith et al. 2019 §6.1: parameterise camelhead.off with symmetric Dirichlet from a Tutte start.
//!
//! `cargo run --release -p ecc-examples --example camelhead_sd -- [--reduced] [OUT_DIR]`
//! (same as `ecc sim scenes/camelhead_sd.toml`); writes frames, `result.png`,
//! `convergence.png` and `summary.json` to `ecc-out/camelhead_sd` by default.

fn main() {
    let (size, out) = ecc_examples::cli_args("camelhead_sd");
    ecc_examples::report(ecc_examples::camelhead_sd(size, &out));
}
