// A stretch energy that is not symmetric in s1, s2, s3: the error points at
// the psi expression.
fn main() {
    let _e = ecc_macros::energy!(s1^2 + 2*s2^2 + s3^2);
}
