// A literal that does not fit an f64 is an error at the literal (it used to
// compile to Ψ ≡ +∞).
fn main() {
    let _e = ecc_macros::energy!(1e400*I2 - 2*I1 + d);
}
