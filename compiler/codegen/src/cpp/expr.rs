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
use crate::syntax::{self, BinOp, Prec, Syntax};

/// The C++ text of an expression.
pub(crate) fn cpp(e: &Ex) -> String {
    syntax::render(&Cpp, e).0
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

/// C++ text for the shared printer ([`syntax`]).
struct Cpp;

impl Syntax for Cpp {
    type Out = String;

    fn lit(&self, v: f64, _receiver: bool) -> (String, Prec) {
        let t = lit(v);
        let p = if t.starts_with('-') {
            Prec::Unary
        } else {
            Prec::Atom
        };
        (t, p)
    }

    fn var(&self, name: &str) -> String {
        name.to_string()
    }

    fn int(&self, n: i32) -> (String, Prec) {
        if n < 0 {
            (format!("-{}", n.unsigned_abs()), Prec::Unary)
        } else {
            (n.to_string(), Prec::Atom)
        }
    }

    /// A `<cmath>` function of the receiver and the arguments.
    fn call(&self, (recv, _): (String, Prec), method: &str, args: Vec<String>) -> String {
        let f = match method {
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
        let mut parts = vec![recv];
        parts.extend(args);
        format!("std::{f}({})", parts.join(", "))
    }

    fn paren(&self, t: String) -> String {
        format!("({t})")
    }

    /// `-t`, parenthesising `t` when it starts with a minus (never `--`).
    fn neg(&self, t: String) -> String {
        if t.starts_with('-') {
            format!("-({t})")
        } else {
            format!("-{t}")
        }
    }

    fn bin(&self, a: String, op: BinOp, b: String) -> String {
        let op = match op {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
        };
        format!("{a} {op} {b}")
    }
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
