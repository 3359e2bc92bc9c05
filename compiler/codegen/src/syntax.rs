//! The one expression printer of both back ends: [`Ex`] trees are walked
//! here (signs normalised, a sum led by a positive term, the fewest
//! parentheses precedence allows, products keeping numerator and
//! denominator apart); a [`Syntax`] supplies the target language's tokens —
//! Rust tokens in `render.rs`, C++ text in `cpp/expr.rs` (issue 15).

use crate::render::Ex;

/// Binding strength of a rendered fragment (higher binds tighter).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Prec {
    Sum = 1,
    Prod = 2,
    Unary = 3,
    Atom = 4,
}

/// A binary operator of sums and products.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
}

/// What differs between target languages.
pub(crate) trait Syntax {
    /// A rendered fragment.
    type Out;
    /// An `f64` literal and its strength; `receiver` when a method is
    /// called on it.
    fn lit(&self, v: f64, receiver: bool) -> (Self::Out, Prec);
    /// A local variable.
    fn var(&self, name: &str) -> Self::Out;
    /// An integer literal (the argument of `powi`) and its strength.
    fn int(&self, n: i32) -> (Self::Out, Prec);
    /// `recv.method(args…)` (or the target's function call); `recv` as
    /// rendered with its strength.
    fn call(&self, recv: (Self::Out, Prec), method: &str, args: Vec<Self::Out>) -> Self::Out;
    /// `(t)`.
    fn paren(&self, t: Self::Out) -> Self::Out;
    /// `-t` (t binds at least as tight as a unary minus).
    fn neg(&self, t: Self::Out) -> Self::Out;
    /// `a op b`.
    fn bin(&self, a: Self::Out, op: BinOp, b: Self::Out) -> Self::Out;
}

/// The fragment of `e` and its strength.
pub(crate) fn render<S: Syntax>(s: &S, e: &Ex) -> (S::Out, Prec) {
    match e {
        Ex::Lit(v) => s.lit(*v, false),
        Ex::Var(name) => (s.var(name), Prec::Atom),
        Ex::Int(n) => s.int(*n),
        Ex::Sum(terms) => render_sum(s, terms),
        Ex::Prod { neg, num, den } => render_prod(s, *neg, num, den),
        Ex::Method(recv, method, args) => {
            let r = match recv.as_ref() {
                Ex::Lit(v) => s.lit(*v, true),
                other => render(s, other),
            };
            let args = args.iter().map(|a| render(s, a).0).collect();
            (s.call(r, method, args), Prec::Atom)
        }
    }
}

/// `t`, parenthesised when it binds looser than `min`.
pub(crate) fn wrap<S: Syntax>(s: &S, (t, p): (S::Out, Prec), min: Prec) -> S::Out {
    if p < min { s.paren(t) } else { t }
}

fn render_sum<S: Syntax>(s: &S, terms: &[(bool, Ex)]) -> (S::Out, Prec) {
    // Normalise: a term that is itself negative flips its sign flag.
    let norm: Vec<(bool, Ex)> = terms
        .iter()
        .map(|(n, t)| {
            if t.is_negative() {
                (!n, t.clone().negated())
            } else {
                (*n, t.clone())
            }
        })
        .collect();
    // Lead with a positive term when there is one.
    let mut order: Vec<usize> = (0..norm.len()).collect();
    if let Some(p) = norm.iter().position(|(n, _)| !n) {
        order.remove(p);
        order.insert(0, p);
    }
    let mut out: Option<S::Out> = None;
    for &i in &order {
        let (negated, term) = &norm[i];
        out = Some(match out {
            None if *negated => wrap(s, render(s, &term.clone().negated()), Prec::Prod),
            None => wrap(s, render(s, term), Prec::Sum),
            // The right operand of + or - must bind tighter than a sum.
            Some(acc) => {
                let op = if *negated { BinOp::Sub } else { BinOp::Add };
                s.bin(acc, op, wrap(s, render(s, term), Prec::Prod))
            }
        });
    }
    match out {
        Some(t) => (t, Prec::Sum),
        None => s.lit(0.0, false),
    }
}

/// Factors joined by `*`, each binding at least as tight as a unary minus
/// (`a * (b / c)` keeps its parentheses).
fn factors<S: Syntax>(s: &S, list: &[Ex]) -> Option<S::Out> {
    list.iter().fold(None, |acc, f| {
        let t = wrap(s, render(s, f), Prec::Unary);
        Some(match acc {
            None => t,
            Some(a) => s.bin(a, BinOp::Mul, t),
        })
    })
}

fn render_prod<S: Syntax>(s: &S, neg: bool, num: &[Ex], den: &[Ex]) -> (S::Out, Prec) {
    let mut out = factors(s, num).unwrap_or_else(|| s.lit(1.0, false).0);
    match den {
        [] => {}
        [d] => out = s.bin(out, BinOp::Div, wrap(s, render(s, d), Prec::Unary)),
        _ => {
            if let Some(d) = factors(s, den) {
                out = s.bin(out, BinOp::Div, s.paren(d));
            }
        }
    }
    let single = num.len() == 1 && den.is_empty();
    if neg {
        if single {
            let t = wrap(s, render(s, &num[0]), Prec::Unary);
            return (s.neg(t), Prec::Unary);
        }
        // `-a * b` parses as `(-a) * b`, which has the same value.
        return (s.neg(out), Prec::Prod);
    }
    let p = if single {
        // Just the factor, already wrapped to at least unary strength.
        render(s, &num[0]).1.max(Prec::Unary)
    } else {
        Prec::Prod
    };
    (out, p)
}
