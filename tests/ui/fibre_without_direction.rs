// `I4` is a fibre invariant: without `fiber a` the error says so, at `I4`.
ecc_macros::energy! {
    pub struct Bad;
    param mu = 1.0;
    psi = mu*(I4 - 2*I1 + d);
}

fn main() {}
