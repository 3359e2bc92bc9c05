// `I7` is not a variable: the error points at `I7` and suggests a name.
ecc_macros::energy! {
    pub struct Bad;
    param mu = 1.0;
    psi = mu*(I7 - 2*I1 + d);
}

fn main() {}
