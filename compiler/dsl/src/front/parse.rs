//! Source text → statements → syntax trees.
//!
//! The source is first cut into statements at `;` and at newlines outside
//! parentheses (a line ending in an operator, `=`, `(` or `,`, or a next line
//! starting with an operator, continues the statement). Each statement is
//! parsed on its own, so one syntax error never hides the others.

use num_rational::BigRational;
use num_traits::Zero;
use pest::Parser;
use pest::iterators::Pair;

use super::ast::{BinOp, Expr, Stmt};
use crate::cas::rat;
use crate::diag::Error;
use crate::span::Span;

#[derive(pest_derive::Parser)]
#[grammar = "front/grammar.pest"]
struct EnergyParser;

/// Nesting limit for parentheses and `^` chains per statement (keeps the
/// recursive descent far from the stack limit on adversarial input).
const MAX_NESTING: usize = 100;

/// Parse a whole source text: the statements that parsed, and one error per
/// statement that did not.
pub fn parse_source(source: &str) -> (Vec<Stmt>, Vec<Error>) {
    let mut stmts = Vec::new();
    let mut errors = Vec::new();
    for span in super::split::split_statements(source) {
        match parse_statement(source, span) {
            Ok(s) => stmts.push(s),
            Err(e) => errors.push(e),
        }
    }
    (stmts, errors)
}

fn parse_statement(source: &str, span: Span) -> Result<Stmt, Error> {
    let text = &source[span.range()];
    check_nesting(text, span)?;
    check_header(text, span)?;
    let mut pairs = EnergyParser::parse(Rule::statement, text)
        .map_err(|e| syntax_error(&e, text, span.start))?;
    let stmt = pairs
        .next()
        .and_then(|p| p.into_inner().next())
        .ok_or_else(|| Error::Syntax {
            span,
            message: "empty statement".into(),
        })?;
    let b = Builder { base: span.start };
    b.statement(stmt)
}

/// Parenthesis balance and nesting depth, checked before the grammar so the
/// messages can point at the culprit parenthesis.
///
/// A `^` chain (`a^b^c`, right-associative) nests the parser; `+`, `-`, `*`,
/// `/` and `,` end it, so only the carets of the chains still open at each
/// parenthesis level count (a long sum of powers is flat).
fn check_nesting(text: &str, span: Span) -> Result<(), Error> {
    let mut open: Vec<usize> = Vec::new();
    let mut chains: Vec<usize> = vec![0];
    let mut carets = 0usize;
    let mut in_comment = false;
    let (mut prev, mut prev2, mut last) = (' ', ' ', ' ');
    for (i, c) in text.char_indices() {
        if in_comment {
            in_comment = c != '\n';
            continue;
        }
        let ends_chain = match c {
            '*' | '/' | ',' => true,
            // Binary `+`/`-` (after an operand), not the sign of `1e-3`.
            '+' | '-' => {
                let exponent =
                    matches!(prev, 'e' | 'E') && (prev2.is_ascii_digit() || prev2 == '.');
                (last.is_alphanumeric() || matches!(last, '_' | '.' | ')')) && !exponent
            }
            _ => false,
        };
        if ends_chain && let Some(n) = chains.last_mut() {
            carets -= std::mem::take(n);
        }
        match c {
            '#' => in_comment = true,
            '(' => {
                open.push(i);
                chains.push(0);
            }
            ')' if open.pop().is_none() => {
                let at = span.start + i;
                return Err(Error::Syntax {
                    span: Span::new(at, at + 1),
                    message: "unmatched `)`".into(),
                });
            }
            ')' => carets -= chains.pop().unwrap_or(0),
            '^' => {
                carets += 1;
                if let Some(n) = chains.last_mut() {
                    *n += 1;
                }
            }
            _ => {}
        }
        (prev2, prev) = (prev, c);
        if !c.is_whitespace() {
            last = c;
        }
        if open.len() > MAX_NESTING || carets > MAX_NESTING {
            let at = span.start + i;
            return Err(Error::Syntax {
                span: Span::new(at, at + 1),
                message: format!(
                    "expression nested too deeply (more than {MAX_NESTING} levels of parentheses or `^`)"
                ),
            });
        }
    }
    if let Some(&i) = open.last() {
        let at = span.start + i;
        return Err(Error::Syntax {
            span: Span::new(at, at + 1),
            message: "unclosed `(`".into(),
        });
    }
    Ok(())
}

/// `param NAME = …`, `let NAME = …` and `psi = …` checked by hand for
/// precise messages (the grammar alone would blame a later token).
fn check_header(text: &str, span: Span) -> Result<(), Error> {
    let word_end = |s: &str| {
        s.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .unwrap_or(s.len())
    };
    let skip_ws = |p: usize| p + text[p..].len() - text[p..].trim_start().len();
    let lead = skip_ws(0);
    let kw_len = word_end(&text[lead..]);
    let kw = &text[lead..lead + kw_len];
    if !matches!(kw, "param" | "let" | "psi") {
        return Ok(());
    }
    let token_at = |p: usize| -> (String, Span) {
        let rest = &text[p..];
        let n = rest
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '.'))
            .unwrap_or(rest.len())
            .max(rest.chars().next().map_or(0, char::len_utf8));
        let tok = &rest[..n.min(rest.len())];
        let shown = if tok.is_empty() {
            "end of statement".to_string()
        } else {
            format!("`{tok}`")
        };
        // An empty token is the end of the statement: an empty span there
        // (one byte wide would reach past the end of the text).
        (shown, Span::new(span.start + p, span.start + p + tok.len()))
    };
    let mut pos = skip_ws(lead + kw_len);
    if kw != "psi" {
        let name_len = word_end(&text[pos..]);
        if name_len == 0 || text[pos..].starts_with(|c: char| c.is_ascii_digit()) {
            let (found, at) = token_at(pos);
            return Err(Error::Syntax {
                span: at,
                message: format!("expected a name after `{kw}`, found {found}"),
            });
        }
        pos = skip_ws(pos + name_len);
    }
    if !text[pos..].starts_with('=') {
        let (found, at) = token_at(pos);
        let what = if kw == "psi" { "`psi`" } else { "the name" };
        return Err(Error::Syntax {
            span: at,
            message: format!("expected `=` after {what}, found {found}"),
        });
    }
    Ok(())
}

fn rule_name(r: &Rule) -> Option<&'static str> {
    Some(match r {
        Rule::expr
        | Rule::term
        | Rule::unary
        | Rule::power
        | Rule::paren
        | Rule::call
        | Rule::number
        | Rule::sign => "an expression",
        Rule::ident => "a name",
        Rule::add_op | Rule::mul_op => "an operator",
        Rule::EOI => "end of statement",
        Rule::dim_value => "a dimension (2 or 3)",
        _ => return None,
    })
}

fn syntax_error(e: &pest::error::Error<Rule>, text: &str, base: usize) -> Error {
    let pos = match e.location {
        pest::error::InputLocation::Pos(p) => p,
        pest::error::InputLocation::Span((s, _)) => s,
    };
    let mut expected: Vec<&str> = match &e.variant {
        pest::error::ErrorVariant::ParsingError { positives, .. } => {
            positives.iter().filter_map(rule_name).collect()
        }
        pest::error::ErrorVariant::CustomError { .. } => Vec::new(),
    };
    expected.sort_unstable();
    expected.dedup();
    // Put "an expression" first, "end of statement" last.
    expected.sort_by_key(|s| match *s {
        "an expression" => 0,
        "end of statement" => 2,
        _ => 1,
    });
    let found = text[pos..].trim_start();
    let (found_text, len) = match found.chars().next() {
        None => ("end of statement".to_string(), 0),
        Some(_) => {
            let tok: String = found
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == '.')
                .collect();
            let tok = if tok.is_empty() {
                found.chars().next().map(String::from).unwrap_or_default()
            } else {
                tok
            };
            let len = tok.len();
            (format!("`{tok}`"), len)
        }
    };
    let start = base + pos + (text[pos..].len() - found.len());
    let message = if expected.is_empty() {
        format!("unexpected {found_text}")
    } else {
        format!("expected {}, found {found_text}", join_or(&expected))
    };
    Error::Syntax {
        span: Span::new(
            start,
            start + len.max(usize::from(found_text != "end of statement")),
        ),
        message,
    }
}

fn join_or(items: &[&str]) -> String {
    match items {
        [] => String::new(),
        [a] => a.to_string(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

struct Builder {
    base: usize,
}

impl Builder {
    fn span(&self, p: &Pair<Rule>) -> Span {
        let s = p.as_span();
        Span::new(self.base + s.start(), self.base + s.end())
    }

    fn statement(&self, p: Pair<Rule>) -> Result<Stmt, Error> {
        let span = self.span(&p);
        let rule = p.as_rule();
        if rule == Rule::expr {
            let expr = self.expr(p)?;
            return Ok(Stmt::Psi {
                key_span: expr.span(),
                expr,
                bare: true,
            });
        }
        let mut inner = p.into_inner();
        let mut next = || {
            inner.next().ok_or_else(|| Error::Syntax {
                span,
                message: "incomplete statement".into(),
            })
        };
        Ok(match rule {
            Rule::dim_stmt => {
                let _kw = next()?;
                let v = next()?;
                Stmt::Dim {
                    value: v.as_str().to_string(),
                    value_span: self.span(&v),
                    span,
                }
            }
            Rule::fiber_stmt => {
                let _kw = next()?;
                let name = next()?;
                Stmt::Fiber {
                    name: name.as_str().to_string(),
                    name_span: self.span(&name),
                    span,
                }
            }
            Rule::param_stmt | Rule::let_stmt => {
                let _kw = next()?;
                let name = next()?;
                let expr = self.expr(next()?)?;
                let (n, ns) = (name.as_str().to_string(), self.span(&name));
                if rule == Rule::param_stmt {
                    Stmt::Param {
                        name: n,
                        name_span: ns,
                        expr,
                        span,
                    }
                } else {
                    Stmt::Let {
                        name: n,
                        name_span: ns,
                        expr,
                        span,
                    }
                }
            }
            _ => {
                let kw = next()?;
                let expr = self.expr(next()?)?;
                Stmt::Psi {
                    expr,
                    key_span: self.span(&kw),
                    bare: false,
                }
            }
        })
    }

    /// `expr`, `term`, `unary`, `power` and atoms.
    fn expr(&self, p: Pair<Rule>) -> Result<Expr, Error> {
        let span = self.span(&p);
        match p.as_rule() {
            Rule::expr | Rule::term => self.chain(p, span),
            Rule::unary => self.unary(p, span),
            Rule::power => self.power(p, span),
            Rule::paren => match p.into_inner().next() {
                Some(e) => self.expr(e),
                None => Err(Error::Syntax {
                    span,
                    message: "empty parentheses".into(),
                }),
            },
            Rule::call => self.call(p, span),
            Rule::ident => Ok(Expr::Ident(p.as_str().to_string(), span)),
            Rule::number => match rat::parse_decimal(p.as_str()) {
                Some(r) => fits_f64(&r, p.as_str(), span).map(|()| Expr::Num(r, span)),
                None => Err(Error::Syntax {
                    span,
                    message:
                        "number out of range (more than 4096 digits or an exponent beyond ±4096)"
                            .into(),
                }),
            },
            _ => Err(Error::Syntax {
                span,
                message: "unexpected input".into(),
            }),
        }
    }

    /// A run of `+ -` (`expr`) or of `* /` (`term`), kept flat.
    fn chain(&self, p: Pair<Rule>, span: Span) -> Result<Expr, Error> {
        let mut inner = p.into_inner();
        let first = match inner.next() {
            Some(f) => self.expr(f)?,
            None => {
                return Err(Error::Syntax {
                    span,
                    message: "empty expression".into(),
                });
            }
        };
        let mut rest = Vec::new();
        while let (Some(op), Some(rhs)) = (inner.next(), inner.next()) {
            let bop = match op.as_str() {
                "+" => BinOp::Add,
                "-" => BinOp::Sub,
                "*" => BinOp::Mul,
                _ => BinOp::Div,
            };
            rest.push((bop, self.span(&op), self.expr(rhs)?));
        }
        Ok(if rest.is_empty() {
            first
        } else {
            Expr::Chain(Box::new(first), rest, span)
        })
    }

    /// Signs in front of a power (`--x` is `x`).
    fn unary(&self, p: Pair<Rule>, span: Span) -> Result<Expr, Error> {
        let mut negative = false;
        let mut body = None;
        for q in p.into_inner() {
            match q.as_rule() {
                Rule::sign => negative ^= q.as_str() == "-",
                _ => body = Some(self.expr(q)?),
            }
        }
        let body = body.ok_or(Error::Syntax {
            span,
            message: "expected an expression".into(),
        })?;
        Ok(if negative {
            Expr::Neg(Box::new(body), span)
        } else {
            body
        })
    }

    /// `base` or `base ^ exponent`.
    fn power(&self, p: Pair<Rule>, span: Span) -> Result<Expr, Error> {
        let mut inner = p.into_inner();
        let base = match inner.next() {
            Some(b) => self.expr(b)?,
            None => {
                return Err(Error::Syntax {
                    span,
                    message: "expected an expression".into(),
                });
            }
        };
        Ok(match inner.next() {
            Some(e) => Expr::Pow(Box::new(base), Box::new(self.expr(e)?), span),
            None => base,
        })
    }

    /// `name(args)`.
    fn call(&self, p: Pair<Rule>, span: Span) -> Result<Expr, Error> {
        let mut inner = p.into_inner();
        let name = inner.next().ok_or(Error::Syntax {
            span,
            message: "expected a function name".into(),
        })?;
        let args = inner.map(|a| self.expr(a)).collect::<Result<Vec<_>, _>>()?;
        Ok(Expr::Call(
            name.as_str().to_string(),
            self.span(&name),
            args,
            span,
        ))
    }
}

/// A literal must be exactly representable to f64 precision where the
/// generated code will evaluate it: not ±∞ after rounding, and, if nonzero,
/// at least the smallest normal f64 (below it the value rounds to 0 or to a
/// subnormal with fewer than 53 significant bits, silently changing Ψ).
fn fits_f64(r: &BigRational, text: &str, span: Span) -> Result<(), Error> {
    let v = rat::to_f64(r);
    let overflow = !v.is_finite();
    if overflow || (!r.is_zero() && v.abs() < f64::MIN_POSITIVE) {
        return Err(Error::NumberNotF64 {
            span,
            text: text.to_string(),
            overflow,
        });
    }
    Ok(())
}
