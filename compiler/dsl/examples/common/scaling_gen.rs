//! Generated polynomial energies of a given number of terms, for measuring
//! how compile time grows with the size of the energy (the
//! `compile_scaling` example and the CAS operation-count regression test).

// Each includer uses a different part.
#![allow(dead_code)]

/// A family of generated energies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    /// Σ c_k I1^a I2^b I3^c over distinct monomials in graded order.
    Inv,
    /// Σ c_k · (s1^a s2^b s3^c + its 5 permutations): isotropic in σ, 3D.
    Sig,
    /// [`Family::Inv`] with every 8th term replaced by an exp/log subterm.
    Trans,
    /// Σ_k c_k exp(I1/k): n distinct transcendental subterms.
    Exps,
    /// Σ_k c_k log(I2 + k): n distinct logarithms.
    Logs,
    /// Σ_k c_k (I2 − k)² exp(I3/k): distinct exponentials times polynomials.
    ExpPoly,
}

impl Family {
    /// The family named `s` (`inv`, `sig`, `trans`, `exps`, `logs`, `exppoly`).
    pub fn parse(s: &str) -> Option<Family> {
        match s {
            "inv" => Some(Family::Inv),
            "sig" => Some(Family::Sig),
            "trans" => Some(Family::Trans),
            "exps" => Some(Family::Exps),
            "logs" => Some(Family::Logs),
            "exppoly" => Some(Family::ExpPoly),
            _ => None,
        }
    }

    /// The family's name.
    pub fn name(self) -> &'static str {
        match self {
            Family::Inv => "inv",
            Family::Sig => "sig",
            Family::Trans => "trans",
            Family::Exps => "exps",
            Family::Logs => "logs",
            Family::ExpPoly => "exppoly",
        }
    }
}

/// Exponent triples (a, b, c) in graded order: total degree 1, 2, …, and
/// within a degree lexicographically; `a ≥ b ≥ c` when `sorted`.
fn exponents(n: usize, sorted: bool) -> Vec<(u32, u32, u32)> {
    let mut out = Vec::with_capacity(n);
    let mut deg = 1;
    while out.len() < n {
        for a in (0..=deg).rev() {
            for b in (0..=deg - a).rev() {
                let c = deg - a - b;
                if (!sorted || (a >= b && b >= c)) && out.len() < n {
                    out.push((a, b, c));
                }
            }
        }
        deg += 1;
    }
    out
}

/// A small exact coefficient for term k: (k mod 17 + 1)/(k mod 5 + 2), with
/// alternating sign.
fn coefficient(k: usize) -> String {
    let sign = if k % 3 == 2 { "-" } else { "+" };
    format!("{sign} {}/{}", k % 17 + 1, k % 5 + 2)
}

fn inv_monomial(a: u32, b: u32, c: u32) -> String {
    let mut f: Vec<String> = Vec::new();
    for (name, e) in [("I1", a), ("I2", b), ("I3", c)] {
        match e {
            0 => {}
            1 => f.push(name.to_string()),
            _ => f.push(format!("{name}^{e}")),
        }
    }
    f.join("*")
}

fn sig_symmetric(a: u32, b: u32, c: u32) -> String {
    let perms = [
        (a, b, c),
        (a, c, b),
        (b, a, c),
        (b, c, a),
        (c, a, b),
        (c, b, a),
    ];
    let terms: Vec<String> = perms
        .iter()
        .map(|(x, y, z)| format!("s1^{x}*s2^{y}*s3^{z}"))
        .collect();
    format!("({})", terms.join(" + "))
}

fn transcendental(k: usize) -> String {
    let m = k / 8 % 6 + 1;
    match k / 8 % 3 {
        0 => format!("exp(I1/{})", m + 2),
        1 => format!("log(I3)^{}", m % 3 + 2),
        _ => format!("I2^{m}*exp(-I3/{})", m + 1),
    }
}

/// The source of an energy of family `f` with `n` terms.
pub fn energy(f: Family, n: usize) -> String {
    let mut src = String::with_capacity(n * 24);
    if f == Family::Sig {
        src.push_str("dim 3\n");
    }
    src.push_str("psi = 0");
    let exps = exponents(n, f == Family::Sig);
    for (k, &(a, b, c)) in exps.iter().enumerate() {
        let term = match f {
            Family::Inv => inv_monomial(a, b, c),
            Family::Sig => sig_symmetric(a, b, c),
            Family::Trans if k % 8 == 7 => transcendental(k),
            Family::Trans => inv_monomial(a, b, c),
            Family::Exps => format!("exp(I1/{})", k + 1),
            Family::Logs => format!("log(I2 + {})", k + 1),
            Family::ExpPoly => format!("(I2 - {})^2*exp(I3/{})", k + 1, k + 1),
        };
        src.push_str(&format!("\n  {} * {term}", coefficient(k)));
    }
    src.push('\n');
    src
}
