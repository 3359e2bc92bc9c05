//! Name resolution and statement-level checks.
//!
//! Walks the statements in order. Lets and params are visible below their
//! definition. Lets/params may shadow the *alias* names (IC, IIC, IIIC, J)
//! but not the built-in variables (I1, I2, I3, s1, s2, s3, d), the functions
//! or the keywords. Every problem found is recorded; resolution continues
//! with a poisoned placeholder so one mistake does not cause a cascade.
//!
//! Its output types live in [`super::resolved`] (re-exported here), so that
//! [`super::lower`] depends on them and not on this module: the dependency
//! goes one way, sema → lower (parameter defaults are lowered and
//! evaluated here).

use std::collections::HashMap;

use super::ast::{Expr, Stmt};
use super::fibre;
pub use super::resolved::{Func, LetInfo, ParamInfo, Program, RExpr, Var, mentions_d};
use super::suggest::suggest;
use crate::cas::{Graph, eval};
use crate::diag::Error;
use crate::span::Span;

const BUILTINS: [(&str, Var); 7] = [
    ("I1", Var::I1),
    ("I2", Var::I2),
    ("I3", Var::I3),
    ("s1", Var::S(0)),
    ("s2", Var::S(1)),
    ("s3", Var::S(2)),
    ("d", Var::D),
];
const ALIASES: [(&str, Var); 4] = [
    ("IC", Var::IC),
    ("IIC", Var::IIC),
    ("IIIC", Var::IIIC),
    ("J", Var::J),
];
const FUNCS: [(&str, Func, usize); 5] = [
    ("sqrt", Func::Sqrt, 1),
    ("log", Func::Log, 1),
    ("exp", Func::Exp, 1),
    ("pow", Func::Pow, 2),
    ("sign", Func::Sign, 1),
];
const KEYWORDS: [&str; 6] = ["psi", "param", "let", "dim", "fiber", "fibre"];

#[derive(Clone, Copy)]
enum Def {
    Param(u16, Span),
    Let(usize, Span),
    /// The fibre direction's name (`fiber a`).
    Fiber(Span),
}

impl Def {
    fn span(self) -> Span {
        match self {
            Def::Param(_, s) | Def::Let(_, s) | Def::Fiber(s) => s,
        }
    }
}

struct Resolver<'a> {
    /// Names declared by statements that failed to parse.
    poisoned: Vec<String>,
    scope: HashMap<String, Def>,
    all_defs: &'a HashMap<String, Span>,
    errors: Vec<Error>,
    lets_mention_d: Vec<bool>,
    stretch_uses: Vec<(u8, Span)>,
    /// `Some(param name)` while resolving a parameter default (constants only).
    constant_of: Option<String>,
    /// Test mode: unknown identifiers become new parameters.
    free_params: bool,
    params: Vec<ParamInfo>,
    /// `fiber a`, if declared anywhere (I4, I5 are usable everywhere then).
    fiber: Option<(String, Span)>,
    lets: Vec<LetInfo>,
    /// ψ, its key's span and its expression's span.
    psi: Option<(RExpr, Span, Span)>,
    dim: Option<(u8, Span)>,
}

/// Resolve `stmts`. `failed` are the source texts of statements that did not
/// parse: names they were declaring resolve silently to a poisoned value, and
/// no "missing psi" is reported if one of them may have been psi.
///
/// Always returns a program (with `Poison` where something failed) and the
/// errors found, so later stages can still report their own errors.
pub fn resolve(
    stmts: &[Stmt],
    failed: &[&str],
    free_params: bool,
    source: &str,
) -> (Program, Vec<Error>) {
    let all_defs = all_definitions(stmts);
    let poisoned: Vec<String> = failed.iter().filter_map(|t| declared_name(t)).collect();
    let mut r = Resolver {
        poisoned,
        scope: HashMap::new(),
        all_defs: &all_defs,
        errors: Vec::new(),
        lets_mention_d: Vec::new(),
        stretch_uses: Vec::new(),
        constant_of: None,
        free_params,
        params: Vec::new(),
        fiber: fibre::declaration(stmts),
        lets: Vec::new(),
        psi: None,
        dim: None,
    };
    for s in stmts {
        r.statement(s);
    }
    r.finish(failed, source)
}

/// The first definition of every `param`/`let` name (for "defined later").
fn all_definitions(stmts: &[Stmt]) -> HashMap<String, Span> {
    let mut all_defs: HashMap<String, Span> = HashMap::new();
    for s in stmts {
        if let Stmt::Param {
            name, name_span, ..
        }
        | Stmt::Let {
            name, name_span, ..
        } = s
        {
            all_defs.entry(name.clone()).or_insert(*name_span);
        }
    }
    all_defs
}

impl Resolver<'_> {
    fn statement(&mut self, s: &Stmt) {
        match s {
            Stmt::Dim {
                value,
                value_span,
                span,
            } => self.dim_stmt(value, *value_span, *span),
            Stmt::Param {
                name,
                name_span,
                expr,
                span,
            } => self.param_stmt(name, *name_span, expr, *span),
            Stmt::Let {
                name,
                name_span,
                expr,
                ..
            } => self.let_stmt(name, *name_span, expr),
            Stmt::Fiber {
                name,
                name_span,
                span,
            } => self.fiber_stmt(name, *name_span, *span),
            Stmt::Psi { expr, key_span, .. } => {
                let e = self.expr(expr);
                if let Some((_, first, _)) = &self.psi {
                    self.errors.push(Error::Redefinition {
                        span: *key_span,
                        first: *first,
                        name: "psi".into(),
                    });
                } else {
                    self.psi = Some((e, *key_span, expr.span()));
                }
            }
        }
    }

    fn dim_stmt(&mut self, value: &str, value_span: Span, span: Span) {
        if let Some((_, first)) = self.dim {
            self.errors.push(Error::Redefinition {
                span,
                first,
                name: "dim".into(),
            });
            return;
        }
        match value {
            "2" => self.dim = Some((2, span)),
            "3" => self.dim = Some((3, span)),
            _ => self.errors.push(Error::BadDim {
                span: value_span,
                found: value.to_string(),
            }),
        }
    }

    fn param_stmt(&mut self, name: &str, name_span: Span, expr: &Expr, span: Span) {
        let ok_name = self.check_new_name(name, name_span);
        self.constant_of = Some(name.to_string());
        let e = self.expr(expr);
        self.constant_of = None;
        let default = self.constant_value(name, &e, expr.span());
        if ok_name {
            let k = self.params.len() as u16;
            self.params.push(ParamInfo {
                name: name.to_string(),
                default: default.unwrap_or(f64::NAN),
                span,
            });
            self.scope
                .insert(name.to_string(), Def::Param(k, name_span));
        }
    }

    fn let_stmt(&mut self, name: &str, name_span: Span, expr: &Expr) {
        let ok_name = self.check_new_name(name, name_span);
        let (e, md) = self.expr_tracking_d(expr);
        if ok_name {
            self.scope
                .insert(name.to_string(), Def::Let(self.lets.len(), name_span));
            self.lets_mention_d.push(md);
            self.lets.push(LetInfo {
                name: name.to_string(),
                expr: e,
                mentions_d: md,
            });
        }
    }

    /// `fiber a`: only the first one counts ([`fibre::declaration`]); a
    /// second is a redefinition, and the name must be free.
    fn fiber_stmt(&mut self, name: &str, name_span: Span, span: Span) {
        match &self.fiber {
            Some((_, first)) if *first != span => self.errors.push(Error::Redefinition {
                span,
                first: *first,
                name: "fiber".into(),
            }),
            _ => {
                if self.check_new_name(name, name_span) {
                    self.scope.insert(name.to_string(), Def::Fiber(name_span));
                }
            }
        }
    }

    /// Missing psi, stretches beyond a declared `dim 2`, and the program.
    fn finish(mut self, failed: &[&str], source: &str) -> (Program, Vec<Error>) {
        let may_be_psi = failed.iter().any(|t| {
            let t = t.trim_start();
            !["param", "let", "dim", "fiber", "fibre"]
                .iter()
                .any(|kw| t.starts_with(kw))
        });
        if self.psi.is_none() && !may_be_psi {
            let end = source.trim_end().len();
            let start = source[..end]
                .char_indices()
                .next_back()
                .map_or(0, |(i, _)| i);
            self.errors.push(Error::MissingPsi {
                span: Span::new(start, end),
            });
        }
        if let Some((2, dspan)) = self.dim {
            for (k, span) in &self.stretch_uses {
                if *k >= 2 {
                    self.errors.push(Error::StretchOutOfDim {
                        span: *span,
                        name: format!("s{}", k + 1),
                        dim: 2,
                        declared: Some(dspan),
                    });
                }
            }
        }
        self.errors.sort_by_key(|e| e.span().start);
        let (psi, _, psi_span) =
            self.psi
                .unwrap_or((RExpr::Poison, Span::default(), Span::default()));
        let prog = Program {
            params: self.params,
            lets: self.lets,
            psi,
            psi_span,
            dim: self.dim,
            stretch_uses: self.stretch_uses,
            fiber: self.fiber,
        };
        (prog, self.errors)
    }
}

/// `name` in a statement text starting with `param name` or `let name`.
fn declared_name(text: &str) -> Option<String> {
    let t = text.trim_start();
    let rest = t.strip_prefix("param").or_else(|| t.strip_prefix("let"))?;
    if !rest.starts_with(char::is_whitespace) {
        return None;
    }
    let name: String = rest
        .trim_start()
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect();
    (!name.is_empty()).then_some(name)
}

impl Resolver<'_> {
    /// Check that `name` may be defined here; records the error if not.
    fn check_new_name(&mut self, name: &str, span: Span) -> bool {
        let builtin = BUILTINS.iter().chain(fibre::VARS.iter());
        let what = if builtin.clone().any(|(n, _)| *n == name) {
            Some("a built-in variable")
        } else if FUNCS.iter().any(|(n, ..)| *n == name) {
            Some("a function")
        } else if KEYWORDS.contains(&name) {
            Some("a keyword")
        } else {
            None
        };
        if let Some(what) = what {
            self.errors.push(Error::Reserved {
                span,
                name: name.into(),
                what,
            });
            return false;
        }
        if let Some(def) = self.scope.get(name) {
            self.errors.push(Error::Redefinition {
                span,
                first: def.span(),
                name: name.into(),
            });
            return false;
        }
        true
    }

    fn expr_tracking_d(&mut self, e: &Expr) -> (RExpr, bool) {
        let r = self.expr(e);
        let md = mentions_d(&r, &self.lets_mention_d);
        (r, md)
    }

    fn expr(&mut self, e: &Expr) -> RExpr {
        match e {
            Expr::Num(r, _) => RExpr::Num(r.clone()),
            Expr::Ident(name, span) => self.ident(name, *span),
            Expr::Neg(x, _) => RExpr::Neg(Box::new(self.expr(x))),
            Expr::Chain(first, rest, _) => {
                let f = self.expr(first);
                let rest = rest
                    .iter()
                    .map(|(op, _, x)| (*op, self.expr(x), x.span()))
                    .collect();
                RExpr::Chain(Box::new(f), rest)
            }
            Expr::Pow(b, x, span) => {
                RExpr::Pow(Box::new(self.expr(b)), Box::new(self.expr(x)), *span)
            }
            Expr::Call(name, name_span, args, span) => {
                let args_r: Vec<RExpr> = args.iter().map(|a| self.expr(a)).collect();
                let Some((_, f, arity)) = FUNCS.iter().find(|(n, ..)| n == name) else {
                    let suggestion = suggest(
                        name,
                        FUNCS.iter().map(|(n, ..)| *n),
                        &[("ln", "log"), ("power", "pow"), ("sqr", "sqrt")],
                    );
                    self.errors.push(Error::UnknownFunction {
                        span: *name_span,
                        name: name.clone(),
                        suggestion,
                    });
                    return RExpr::Poison;
                };
                if args.len() != *arity {
                    self.errors.push(Error::Arity {
                        span: *span,
                        name: name.clone(),
                        expected: *arity,
                        found: args.len(),
                    });
                    return RExpr::Poison;
                }
                let mut it = args_r.into_iter();
                match (f, it.next(), it.next()) {
                    (Func::Pow, Some(a), Some(b)) => RExpr::Pow(Box::new(a), Box::new(b), *span),
                    (Func::Sign, Some(a), _) => {
                        fibre::sign_of(a, args[0].span()).unwrap_or_else(|e| {
                            self.errors.push(e);
                            RExpr::Poison
                        })
                    }
                    (f, Some(a), _) => RExpr::Call(*f, Box::new(a), args[0].span()),
                    _ => RExpr::Poison,
                }
            }
        }
    }

    fn ident(&mut self, name: &str, span: Span) -> RExpr {
        if let Some(pname) = &self.constant_of
            && (BUILTINS
                .iter()
                .chain(ALIASES.iter())
                .any(|(n, _)| *n == name)
                || fibre::is_fibre_name(name)
                || self.scope.contains_key(name))
        {
            self.errors.push(Error::ParamNotConstant {
                span,
                name: pname.clone(),
                uses: name.into(),
            });
            return RExpr::Poison;
        }
        if let Some((_, v)) = BUILTINS.iter().find(|(n, _)| *n == name) {
            if let Var::S(k) = v {
                self.stretch_uses.push((*k, span));
            }
            return RExpr::Var(*v);
        }
        if let Some((_, v)) = fibre::VARS.iter().find(|(n, _)| *n == name) {
            return self.fibre_var(name, *v, span);
        }
        if let Some(def) = self.scope.get(name) {
            return match def {
                Def::Param(k, _) => RExpr::Param(*k),
                Def::Let(k, _) => RExpr::Let(*k),
                Def::Fiber(_) => {
                    let decl = self.fiber.as_ref().map_or(span, |(_, s)| *s);
                    self.errors.push(fibre::direction_used(name, span, decl));
                    RExpr::Poison
                }
            };
        }
        if let Some((_, v)) = ALIASES.iter().find(|(n, _)| *n == name) {
            return RExpr::Var(*v);
        }
        if let Some((_, v)) = fibre::ALIASES.iter().find(|(n, _)| *n == name) {
            return self.fibre_var(name, *v, span);
        }
        if name == fibre::C2 {
            self.errors.push(fibre::c_squared(span));
            return RExpr::Poison;
        }
        if self.poisoned.iter().any(|p| p == name) {
            return RExpr::Poison;
        }
        if self.free_params && self.constant_of.is_none() {
            let k = self.params.len() as u16;
            self.params.push(ParamInfo {
                name: name.into(),
                default: 1.0,
                span,
            });
            self.scope.insert(name.into(), Def::Param(k, span));
            return RExpr::Param(k);
        }
        self.unknown_ident(name, span)
    }

    /// An identifier that names nothing: a located error with a suggestion
    /// (or the later definition it would need), then poison.
    fn unknown_ident(&mut self, name: &str, span: Span) -> RExpr {
        let known: Vec<&str> = BUILTINS
            .iter()
            .chain(ALIASES.iter())
            .chain(fibre::VARS.iter().filter(|_| self.fiber.is_some()))
            .map(|(n, _)| *n)
            .chain(self.scope.keys().map(|s| s.as_str()))
            .chain(self.all_defs.keys().map(|s| s.as_str()))
            .collect();
        let suggestion = suggest(
            name,
            known.into_iter(),
            &[
                ("sigma1", "s1"),
                ("sigma2", "s2"),
                ("sigma3", "s3"),
                ("dim", "d"),
            ],
        );
        let defined_later = self
            .all_defs
            .get(name)
            .copied()
            .filter(|s| s.start > span.start);
        let suggestion = if defined_later.is_some() {
            None
        } else {
            suggestion
        };
        if let Some(pname) = &self.constant_of {
            self.errors.push(Error::ParamNotConstant {
                span,
                name: pname.clone(),
                uses: name.into(),
            });
        } else {
            self.errors.push(Error::UnknownIdent {
                span,
                name: name.into(),
                suggestion,
                defined_later,
            });
        }
        RExpr::Poison
    }

    /// A fibre variable: itself after `fiber a`, else a located error.
    fn fibre_var(&mut self, name: &str, v: Var, span: Span) -> RExpr {
        if self.fiber.is_some() {
            RExpr::Var(v)
        } else {
            self.errors.push(fibre::undeclared(name, span));
            RExpr::Poison
        }
    }

    /// Evaluate a parameter default; records non-finite / division-by-zero errors.
    fn constant_value(&mut self, name: &str, e: &RExpr, span: Span) -> Option<f64> {
        let mut g = Graph::new(Vec::new());
        let mut errs = Vec::new();
        let id = super::lower::lower_expr(&mut g, e, 3, &[], &[], &mut errs);
        self.errors.extend(errs);
        let id = id?;
        let v = eval(&g, id, &crate::cas::Env::new(3, &[], &[]));
        if !v.is_finite() {
            self.errors.push(Error::ParamNotFinite {
                span,
                name: name.into(),
                value: format!("{v}"),
            });
            return None;
        }
        Some(v)
    }
}
