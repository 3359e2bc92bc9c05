// A constant left in Ψ after folding must fit an f64 too (10^400*I2 compiled
// to Ψ ≡ +∞): the error spans the formula.
fn main() {
    let _e = ecc_macros::energy!(10^400*I2 - 2*I1 + d);
}
