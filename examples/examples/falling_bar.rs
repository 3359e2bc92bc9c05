//! Smith et al. 2019 §6.5: a Stable Neo-Hookean bar dropped at an angle onto a barrier ground (BDF2).
//!
//! `cargo run --release -p ecc-examples --example falling_bar -- [--reduced] [OUT_DIR]`
//! (same as `ecc sim scenes/falling_bar.toml`); writes frames, `result.png`,
//! `convergence.png` and `summary.json` to `ecc-out/falling_bar` by default.

fn main() {
    let (size, out) = ecc_examples::cli_args("falling_bar");
    ecc_examples::report(ecc_examples::falling_bar(size, &out));
}
