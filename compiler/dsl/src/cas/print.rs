//! The deterministic canonical printer.
//!
//! The text depends only on the expression's structure, never on node ids or
//! insertion order: sum terms are ordered by (total degree descending, text),
//! product factors by (parameters, invariants, stretches, then the rest; text). Coefficients
//! are exact (`I2/2`, `-3*I1/(2*I3)`), negative powers print as divisions,
//! `x^(1/2)` prints as `sqrt(x)`. Parameters print by name, σk as `s{k+1}`.

use std::collections::HashMap;

use num_rational::BigRational;
use num_traits::{One, Signed};

use super::graph::Graph;
use super::node::{Id, Node, Sym};
use super::rat;

/// Binding strength of a printed fragment.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Prec {
    Sum = 1,
    Product = 2,
    Power = 3,
    Atom = 4,
}

/// A sum term for sorting: (−degree, monomial key, text).
type SumTerm = (i64, Vec<(u8, String, i64)>, String);

#[derive(Clone)]
struct Printed {
    text: String,
    prec: Prec,
    degree: i64,
}

impl Graph {
    /// The canonical text of `id`.
    pub fn to_text(&self, id: Id) -> String {
        let mut memo: HashMap<Id, Printed> = HashMap::new();
        for n in self.reachable(&[id]) {
            let p = self.print_node(n, &memo);
            memo.insert(n, p);
        }
        memo.remove(&id).map(|p| p.text).unwrap_or_default()
    }

    /// The printed name of a symbol.
    pub fn sym_name(&self, s: Sym) -> String {
        match s {
            Sym::I1 => "I1".into(),
            Sym::I2 => "I2".into(),
            Sym::I3 => "I3".into(),
            Sym::Sigma(k) => format!("s{}", k + 1),
            Sym::I4 => "I4".into(),
            Sym::I5 => "I5".into(),
            Sym::SignI4 => "sign(I4)".into(),
            Sym::Param(k) => self
                .param_names()
                .get(k as usize)
                .cloned()
                .unwrap_or_else(|| format!("p{k}")),
        }
    }

    fn print_node(&self, id: Id, memo: &HashMap<Id, Printed>) -> Printed {
        let get = |c: &Id| memo[c].clone();
        match self.get(id) {
            Node::Num(r) => print_num(r),
            Node::Sym(s) => Printed {
                text: self.sym_name(*s),
                prec: Prec::Atom,
                degree: 1,
            },
            Node::Log(x) => Printed {
                text: format!("log({})", get(x).text),
                prec: Prec::Atom,
                degree: 1,
            },
            Node::Exp(x) => Printed {
                text: format!("exp({})", get(x).text),
                prec: Prec::Atom,
                degree: 1,
            },
            Node::Pow([b, e]) => self.print_pow_node(*b, *e, memo),
            Node::Add(children) => self.print_sum(children, memo),
            Node::Mul(children) => self.print_product(children, memo),
        }
    }

    /// A power node: a negative numeric exponent prints as `1/base^|e|`
    /// (a product-level fragment), anything else through `print_pow`.
    fn print_pow_node(&self, b: Id, e: Id, memo: &HashMap<Id, Printed>) -> Printed {
        let get = |c: &Id| memo[c].clone();
        let ne = self.as_num(e).filter(|r| r.is_negative()).cloned();
        match ne {
            Some(neg) => {
                let den = self.print_pow(&get(&b), &(-neg), None);
                Printed {
                    text: format!("1/{}", wrap(&den, Prec::Power)),
                    prec: Prec::Product,
                    degree: -den.degree,
                }
            }
            None => {
                let en = self.as_num(e).cloned();
                self.print_pow(
                    &get(&b),
                    en.as_ref().unwrap_or(&BigRational::one()),
                    en.is_none().then(|| get(&e)),
                )
            }
        }
    }

    /// A sum: terms in graded order (degree descending, then monomial key,
    /// then text), the numeric constant last, `a - b` for negative terms.
    fn print_sum(&self, children: &[Id], memo: &HashMap<Id, Printed>) -> Printed {
        let get = |c: &Id| memo[c].clone();
        let mut terms: Vec<SumTerm> = Vec::new();
        let mut constant: Option<String> = None;
        for c in children {
            if let Node::Num(r) = self.get(*c) {
                constant = Some(print_num(r).text);
                continue;
            }
            let p = get(c);
            let key = self.term_key(*c, memo);
            terms.push((-p.degree, key, p.text));
        }
        terms.sort_by(grlex);
        let mut text = String::new();
        let mut degree = 0;
        let all = terms
            .into_iter()
            .map(|(d, _, t)| (d, t))
            .chain(constant.map(|t| (0, t)));
        for (i, (d, t)) in all.enumerate() {
            degree = degree.max(-d);
            if i == 0 {
                text.push_str(&t);
            } else if let Some(rest) = t.strip_prefix('-') {
                text.push_str(" - ");
                text.push_str(rest);
            } else {
                text.push_str(" + ");
                text.push_str(&t);
            }
        }
        Printed {
            text,
            prec: Prec::Sum,
            degree,
        }
    }

    /// A product: the exact coefficient first, factors ordered by rank then
    /// text, negative numeric powers gathered into one denominator.
    fn print_product(&self, children: &[Id], memo: &HashMap<Id, Printed>) -> Printed {
        let get = |c: &Id| memo[c].clone();
        let mut coef = BigRational::one();
        let mut num: Vec<(u8, String)> = Vec::new();
        let mut den: Vec<(u8, String)> = Vec::new();
        let mut degree = 0;
        for c in children {
            match self.get(*c) {
                Node::Num(r) => coef = r.clone(),
                Node::Pow([b, e]) if self.as_num(*e).is_some_and(|r| r.is_negative()) => {
                    let neg = -self.as_num(*e).cloned().unwrap_or_else(BigRational::one);
                    let p = self.print_pow(&get(b), &neg, None);
                    degree -= p.degree;
                    den.push((self.rank(*b), wrap(&p, Prec::Power)));
                }
                _ => {
                    let p = get(c);
                    degree += p.degree;
                    let base = match self.get(*c) {
                        Node::Pow([b, _]) => *b,
                        _ => *c,
                    };
                    num.push((self.rank(base), wrap(&p, Prec::Power)));
                }
            }
        }
        num.sort();
        den.sort();
        let mut num: Vec<String> = num.into_iter().map(|(_, t)| t).collect();
        let mut den: Vec<String> = den.into_iter().map(|(_, t)| t).collect();
        let sign = if coef.is_negative() { "-" } else { "" };
        let (p, q) = (coef.numer().abs(), coef.denom().clone());
        if !p.is_one() {
            num.insert(0, p.to_string());
        }
        if !q.is_one() {
            den.insert(0, q.to_string());
        }
        let num_text = if num.is_empty() {
            "1".to_string()
        } else {
            num.join("*")
        };
        let text = match den.len() {
            0 => format!("{sign}{num_text}"),
            1 => format!("{sign}{num_text}/{}", den[0]),
            _ => format!("{sign}{num_text}/({})", den.join("*")),
        };
        let prec = if sign.is_empty() && den.is_empty() && num.len() == 1 {
            Prec::Power
        } else {
            Prec::Product
        };
        Printed { text, prec, degree }
    }

    /// `base^e` for a non-negative exponent `e` (or the symbolic `sym_exp`).
    fn print_pow(&self, base: &Printed, e: &BigRational, sym_exp: Option<Printed>) -> Printed {
        if let Some(se) = sym_exp {
            return Printed {
                text: format!("{}^{}", wrap(base, Prec::Atom), wrap(&se, Prec::Atom)),
                prec: Prec::Power,
                degree: 1,
            };
        }
        if e.is_one() {
            return base.clone();
        }
        let half = BigRational::new(1.into(), 2.into());
        if *e == half {
            return Printed {
                text: format!("sqrt({})", base.text),
                prec: Prec::Atom,
                degree: 1,
            };
        }
        let degree = rat::as_i64(e).map_or(1, |n| n * base.degree);
        let et = if e.is_integer() {
            e.to_string()
        } else {
            format!("({e})")
        };
        Printed {
            text: format!("{}^{et}", wrap(base, Prec::Atom)),
            prec: Prec::Power,
            degree,
        }
    }

    /// Ordering rank of a product factor's base: parameters, then I1, I2, I3,
    /// σ's, then everything else.
    fn rank(&self, base: Id) -> u8 {
        match self.get(base) {
            Node::Sym(Sym::Param(_)) => 0,
            Node::Sym(Sym::I1) => 1,
            Node::Sym(Sym::I2) => 2,
            Node::Sym(Sym::I3) => 3,
            Node::Sym(Sym::Sigma(k)) => 4 + k.min(&2),
            _ => 7,
        }
    }

    /// Sort key of a sum term: its text without the rational coefficient.
    fn term_key(&self, t: Id, memo: &HashMap<Id, Printed>) -> Vec<(u8, String, i64)> {
        let factors: Vec<Id> = match self.get(t) {
            Node::Mul(children) => children
                .iter()
                .copied()
                .filter(|c| !matches!(self.get(*c), Node::Num(_)))
                .collect(),
            _ => vec![t],
        };
        let mut key: Vec<(u8, String, i64)> = factors
            .into_iter()
            .map(|f| match self.get(f) {
                Node::Pow([b, e]) => match self.as_num(*e).and_then(rat::as_i64) {
                    Some(n) => (self.rank(*b), memo[b].text.clone(), n),
                    None => (self.rank(f), memo[&f].text.clone(), 1),
                },
                _ => (self.rank(f), memo[&f].text.clone(), 1),
            })
            .collect();
        key.sort();
        key
    }
}

/// Graded lexicographic order of sum terms: higher degree first, then the
/// larger power of the earliest symbol first (`s1^3 + s1^2*s2 + s1*s2^2 + s2^3`).
fn grlex(
    a: &(i64, Vec<(u8, String, i64)>, String),
    b: &(i64, Vec<(u8, String, i64)>, String),
) -> std::cmp::Ordering {
    a.0.cmp(&b.0).then_with(|| {
        let (mut i, mut j) = (0, 0);
        let (x, y) = (&a.1, &b.1);
        while i < x.len() && j < y.len() {
            let (ka, kb) = ((x[i].0, &x[i].1), (y[j].0, &y[j].1));
            match ka.cmp(&kb) {
                std::cmp::Ordering::Equal => {
                    if x[i].2 != y[j].2 {
                        return y[j].2.cmp(&x[i].2);
                    }
                    i += 1;
                    j += 1;
                }
                // `a` has a symbol earlier in the order that `b` lacks.
                std::cmp::Ordering::Less => return std::cmp::Ordering::Less,
                std::cmp::Ordering::Greater => return std::cmp::Ordering::Greater,
            }
        }
        (x.len() - i)
            .cmp(&(y.len() - j))
            .reverse()
            .then_with(|| a.2.cmp(&b.2))
    })
}

fn print_num(r: &BigRational) -> Printed {
    let prec = if r.is_integer() && !r.is_negative() {
        Prec::Atom
    } else {
        Prec::Product
    };
    Printed {
        text: r.to_string(),
        prec,
        degree: 0,
    }
}

fn wrap(p: &Printed, min: Prec) -> String {
    if p.prec < min {
        format!("({})", p.text)
    } else {
        p.text.clone()
    }
}
