//! Smith et al. 2019 §6.2: volume deformation of hand.mesh with ARAP: the
//! wrist is pinned and the fingertips turn towards the palm.
//!
//! `cargo run --release -p ecc-examples --example hand_arap -- [--reduced] [OUT_DIR]`
//! (same as `ecc sim scenes/hand_arap.toml`); writes to `ecc-out/hand_arap` by default.

fn main() {
    let (size, out) = ecc_examples::cli_args("hand_arap");
    ecc_examples::report(ecc_examples::hand("arap", size, &out));
}
