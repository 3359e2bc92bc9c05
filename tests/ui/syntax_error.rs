// A dangling operator: the error points at the token where parsing stopped.
fn main() {
    let _e = ecc_macros::energy!(I2 - 2*I1 + * d);
}
