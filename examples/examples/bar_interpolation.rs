//! Smith et al. 2019 §6.3: symmetric ARAP interpolation between a straight and a twisted, bent bar.
//!
//! `cargo run --release -p ecc-examples --example bar_interpolation -- [--reduced] [OUT_DIR]`
//! (same as `ecc sim scenes/bar_interpolation.toml`); writes frames, `result.png`,
//! `convergence.png` and `summary.json` to `ecc-out/bar_interpolation` by default.

fn main() {
    let (size, out) = ecc_examples::cli_args("bar_interpolation");
    ecc_examples::report(ecc_examples::bar_interpolation(size, &out));
}
