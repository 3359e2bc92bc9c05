// `#` starts a comment in .psi files but not inside Rust tokens: without
// this error, everything after it would be dropped (Ψ = I2).
fn main() {
    let _e = ecc_macros::energy!(I2 # note
        - 2*I1 + d);
}
