//! C++ rendering of the plan's expression trees ([`Ex`]), with the fewest
//! parentheses C++'s precedence allows (the same rules as the Rust printer in
//! `render.rs`: products keep numerator and denominator apart, sums subtract
//! negative terms).
//!
//! Method calls become `std::` functions of `<cmath>`: `x.ln()` → `std::log(x)`,
//! `x.powf(e)` / `x.powi(n)` → `std::pow(x, e)`, `x.abs()` → `std::fabs(x)`,
//! `x.max(y)` → `std::fmax(x, y)` (NaN-ignoring like Rust's), and any other
//! method `m` → `std::m(x, …)` (`sqrt`, `cbrt`, `exp`, `copysign`, …), so
//! expression kinds the Rust printer learns are printed here too.

use crate::render::Ex;

/// Binding strength of a rendered fragment (higher binds tighter).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Prec {
    Sum = 1,
    Prod = 2,
    Unary = 3,
    Atom = 4,
}

/// The C++ text of an expression.
pub(crate) fn cpp(e: &Ex) -> String {
    render(e).0
}

/// A `double` literal: shortest round-trip digits, always with a `.` or an
/// exponent; non-finite values through the runtime's `ecc::infinity()` and
/// `ecc::nan()` (usable in device code).
pub(crate) fn lit(v: f64) -> String {
    if v.is_nan() {
        return "::ecc::nan()".into();
    }
    if v.is_infinite() {
        let inf = "::ecc::infinity()";
        return if v > 0.0 {
            inf.into()
        } else {
            format!("-{inf}")
        };
    }
    // Rust's `{:?}` prints `1.0`, `0.5`, `1e-30`, `6.055454452393343e-6`:
    // all valid C++ double literals.
    format!("{v:?}")
}

fn wrap((t, p): (String, Prec), min: Prec) -> String {
    if p < min { format!("({t})") } else { t }
}

fn render(e: &Ex) -> (String, Prec) {
    match e {
        Ex::Lit(v) => {
            let t = lit(*v);
            let p = if t.starts_with('-') {
                Prec::Unary
            } else {
                Prec::Atom
            };
            (t, p)
        }
        Ex::Var(name) => (name.clone(), Prec::Atom),
        Ex::Int(n) => {
            if *n < 0 {
                (format!("-{}", n.unsigned_abs()), Prec::Unary)
            } else {
                (n.to_string(), Prec::Atom)
            }
        }
        Ex::Sum(terms) => render_sum(terms),
        Ex::Prod { neg, num, den } => render_prod(*neg, num, den),
        Ex::Method(recv, method, args) => {
            let f = match *method {
                "ln" => "log",
                "powf" | "powi" => "pow",
                "abs" => "fabs",
                "max" => "fmax",
                "min" => "fmin",
                "ln_1p" => "log1p",
                "exp_m1" => "expm1",
                "mul_add" => "fma",
                m => m,
            };
            let mut parts = vec![cpp(recv)];
            parts.extend(args.iter().map(cpp));
            (format!("std::{f}({})", parts.join(", ")), Prec::Atom)
        }
    }
}

/// Whether the expression is syntactically negative (see `render.rs`).
fn is_negative(e: &Ex) -> bool {
    match e {
        Ex::Lit(v) => v.is_sign_negative() && *v != 0.0,
        Ex::Prod { neg, .. } => *neg,
        _ => false,
    }
}

fn render_sum(terms: &[(bool, Ex)]) -> (String, Prec) {
    let norm: Vec<(bool, Ex)> = terms
        .iter()
        .map(|(n, t)| {
            if is_negative(t) {
                (!n, t.clone().negated())
            } else {
                (*n, t.clone())
            }
        })
        .collect();
    let mut order: Vec<usize> = (0..norm.len()).collect();
    if let Some(p) = norm.iter().position(|(n, _)| !n) {
        order.remove(p);
        order.insert(0, p);
    }
    if order.is_empty() {
        return (lit(0.0), Prec::Atom);
    }
    let mut out = String::new();
    for (k, &i) in order.iter().enumerate() {
        let (negated, term) = &norm[i];
        if k == 0 {
            if *negated {
                out.push_str(&wrap(render(&term.clone().negated()), Prec::Prod));
            } else {
                out.push_str(&wrap(render(term), Prec::Sum));
            }
        } else {
            let t = wrap(render(term), Prec::Prod);
            out.push_str(if *negated { " - " } else { " + " });
            out.push_str(&t);
        }
    }
    (out, Prec::Sum)
}

/// `-t`, parenthesising `t` when it starts with a minus (never `--`).
fn minus(t: &str) -> String {
    if t.starts_with('-') {
        format!("-({t})")
    } else {
        format!("-{t}")
    }
}

fn factors(list: &[Ex]) -> String {
    list.iter()
        .map(|f| wrap(render(f), Prec::Unary))
        .collect::<Vec<_>>()
        .join(" * ")
}

fn render_prod(neg: bool, num: &[Ex], den: &[Ex]) -> (String, Prec) {
    let mut out = if num.is_empty() {
        lit(1.0)
    } else {
        factors(num)
    };
    match den.len() {
        0 => {}
        1 => out = format!("{out} / {}", wrap(render(&den[0]), Prec::Unary)),
        _ => out = format!("{out} / ({})", factors(den)),
    }
    if neg {
        if num.len() == 1 && den.is_empty() {
            return (minus(&wrap(render(&num[0]), Prec::Unary)), Prec::Unary);
        }
        // `-a * b` parses as `(-a) * b`, which has the same value.
        return (minus(&out), Prec::Prod);
    }
    let p = if num.len() == 1 && den.is_empty() {
        render(&num[0]).1.max(Prec::Unary)
    } else {
        Prec::Prod
    };
    (out, p)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(s: &str) -> Ex {
        Ex::Var(s.into())
    }

    #[test]
    fn sums_products_and_calls() {
        let e = Ex::Sum(vec![
            (false, v("x")),
            (
                false,
                Ex::Prod {
                    neg: true,
                    num: vec![Ex::Lit(2.0), v("y")],
                    den: vec![],
                },
            ),
            (false, Ex::Lit(-3.0)),
        ]);
        assert_eq!(cpp(&e), "x - 2.0 * y - 3.0");
        let s = Ex::Sum(vec![(false, v("a")), (false, v("b"))]);
        let p = Ex::Prod {
            neg: false,
            num: vec![Ex::Lit(0.5), s.clone()],
            den: vec![v("c"), v("c")],
        };
        assert_eq!(cpp(&p), "0.5 * (a + b) / (c * c)");
        assert_eq!(
            cpp(&Ex::Method(Box::new(s), "ln", vec![])),
            "std::log(a + b)"
        );
        let pw = Ex::Method(Box::new(v("x")), "powi", vec![Ex::Int(3)]);
        assert_eq!(cpp(&pw), "std::pow(x, 3)");
        let n = Ex::Prod {
            neg: true,
            num: vec![v("x")],
            den: vec![v("y")],
        };
        let outer = Ex::Prod {
            neg: false,
            num: vec![v("z"), n],
            den: vec![],
        };
        assert_eq!(cpp(&outer), "z * (-x / y)");
        // Never `--`: a negated negative literal is parenthesised.
        let nn = Ex::Prod {
            neg: true,
            num: vec![Ex::Lit(-2.0)],
            den: vec![],
        };
        assert!(!cpp(&nn).contains("--"), "{}", cpp(&nn));
    }

    #[test]
    fn literals() {
        assert_eq!(lit(1e-30), "1e-30");
        assert_eq!(lit(1.0), "1.0");
        assert_eq!(lit(-0.25), "-0.25");
        assert_eq!(lit(f64::INFINITY), "::ecc::infinity()");
    }
}
