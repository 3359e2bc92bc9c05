// `I4` is not a variable: the error points at `I4` and suggests a name.
ecc_macros::energy! {
    pub struct Bad;
    param mu = 1.0;
    psi = mu*(I4 - 2*I1 + d);
}

fn main() {}
