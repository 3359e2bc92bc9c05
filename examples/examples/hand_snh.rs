//! Smith et al. 2019 §6.2: volume deformation of hand.mesh with Stable Neo-Hookean: the
//! wrist is pinned and the fingertips turn towards the palm.
//!
//! `cargo run --release -p ecc-examples --example hand_snh -- [--reduced] [OUT_DIR]`
//! (same as `ecc sim scenes/hand_snh.toml`); writes to `ecc-out/hand_snh` by default.

fn main() {
    let (size, out) = ecc_examples::cli_args("hand_snh");
    ecc_examples::report(ecc_examples::hand("snh", size, &out));
}
