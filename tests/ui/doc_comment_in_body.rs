// A doc comment among the statements is a `#[doc]` attribute, hence a `#`.
fn main() {
    let _e = ecc_macros::energy!(
        param k = 2;
        /// the energy
        psi = k*(I2 - 2*I1 + d)
    );
}
