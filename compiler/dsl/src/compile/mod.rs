//! The compiler driver: source → [`Module`] / [`DimIr`].

mod checks;
mod cost;
mod derivs;
mod dim;
mod domain;
mod fibre;
mod poles;

pub use checks::Rng;
pub use cost::{cost, cost_many};
pub use dim::slot_pairs;

use crate::diag::{Diagnostics, Error};
use crate::front::{lower, parse, sema, split};
use crate::ir::{DimIr, Module, ParamDecl};
use crate::span::Span;

/// Parse and resolve a source text (all syntax and name errors at once).
pub fn front_end(source: &str, free_params: bool) -> Result<sema::Program, Diagnostics> {
    let (prog, errors) = front_end_partial(source, free_params);
    if errors.is_empty() {
        Ok(prog)
    } else {
        Err(Diagnostics { errors })
    }
}

/// Parse and resolve, returning the (possibly poisoned) program and every
/// syntax and name error.
fn front_end_partial(source: &str, free_params: bool) -> (sema::Program, Vec<Error>) {
    let (stmts, mut errors) = parse::parse_source(source);
    let failed: Vec<&str> = errors
        .iter()
        .filter_map(|e| source.get(failed_statement(source, e.span())))
        .collect();
    let (prog, more) = sema::resolve(&stmts, &failed, free_params, source);
    errors.extend(more);
    errors.sort_by_key(|e| e.span().start);
    (prog, errors)
}

/// The statement containing `span` (for "what was this failed statement?").
fn failed_statement(source: &str, span: Span) -> std::ops::Range<usize> {
    split::split_statements(source)
        .into_iter()
        .find(|s| s.start <= span.start && span.start <= s.end)
        .map_or(0..0, |s| s.range())
}

fn push_unique(errors: &mut Vec<Error>, more: Vec<Error>) {
    for e in more {
        if !errors.contains(&e) {
            errors.push(e);
        }
    }
}

/// `errors` plus the lowering errors (division by zero, …) of every
/// dimension in `dims`, so that one run reports everything.
fn with_lowering_errors(prog: &sema::Program, mut errors: Vec<Error>, dims: &[u8]) -> Diagnostics {
    for &d in dims {
        if let Err(es) = lower::lower_program(prog, d) {
            push_unique(&mut errors, es);
        }
    }
    errors.sort_by_key(|e| e.span().start);
    Diagnostics { errors }
}

fn dim_of(prog: &sema::Program, dim: u8) -> Result<DimIr, Vec<Error>> {
    let (mut g, psi, guards) = lower::lower_with_domain(prog, dim)?;
    let Some((direction, _)) = &prog.fiber else {
        return iso_dim(prog, dim, g, psi, guards);
    };
    let parts = fibre::split(&mut g, psi, guards, prog)?;
    let fib = fibre::build(&mut g, parts.fibre, parts.fibre_guards, direction);
    let mut ir = iso_dim(prog, dim, g, parts.iso, parts.iso_guards)?;
    ir.fibre = Some(fib);
    Ok(ir)
}

/// The isotropic part's [`DimIr`] (all of Ψ without a fibre).
fn iso_dim(
    prog: &sema::Program,
    dim: u8,
    g: crate::cas::Graph,
    psi: crate::cas::Id,
    mut guards: Vec<crate::ir::DomainGuard>,
) -> Result<DimIr, Vec<Error>> {
    domain::mark_enforced(&g, psi, &mut guards);
    let params: Vec<f64> = prog.params.iter().map(|p| p.default).collect();
    let input = dim::DimInput {
        dim,
        params: &params,
        domain: &guards,
        psi_span: prog.psi_span,
        no_s3: !prog.stretch_uses.iter().any(|(k, _)| *k == 2),
    };
    dim::build_dim(g, psi, &input).map_err(|e| vec![e])
}

/// The dimensions `compile` builds, and the ones it skips with the reason.
fn applicable_dims(prog: &sema::Program) -> (Vec<u8>, Vec<(u8, String)>) {
    match prog.dim {
        Some((d, _)) => (vec![d], vec![(5 - d, format!("declared dim {d}"))]),
        None if prog.stretch_uses.iter().any(|(k, _)| *k == 2) => {
            (vec![3], vec![(2, "uses s3".to_string())])
        }
        None => (vec![2, 3], Vec::new()),
    }
}

/// Compile `source` for dimension `dim` (2 or 3).
///
/// Errors: everything [`compile`] reports, plus `s3` used in 2D and a
/// declared `dim` other than `dim`.
pub fn compile_dim(source: &str, name: &str, dim: u8) -> Result<DimIr, Diagnostics> {
    let _ = name;
    if dim != 2 && dim != 3 {
        return Err(Error::BadDim {
            span: Span::new(0, 0),
            found: dim.to_string(),
        }
        .into());
    }
    let (prog, mut errors) = front_end_partial(source, false);
    if let Some((declared, span)) = prog.dim
        && declared != dim
    {
        errors.push(Error::DimMismatch {
            span,
            declared,
            requested: dim,
        });
    }
    if dim == 2 && prog.dim.is_none() {
        for (k, span) in &prog.stretch_uses {
            if *k == 2 {
                errors.push(Error::StretchOutOfDim {
                    span: *span,
                    name: "s3".into(),
                    dim: 2,
                    declared: None,
                });
            }
        }
    }
    if !errors.is_empty() {
        let dims: &[u8] = if prog.dim.is_some_and(|(d, _)| d != dim) {
            &[]
        } else {
            &[dim]
        };
        return Err(with_lowering_errors(&prog, errors, dims));
    }
    dim_of(&prog, dim).map_err(|errors| Diagnostics { errors })
}

/// Compile `source` for every dimension that applies: the declared `dim`,
/// else 3 only if `s3` is used, else 2 and 3. All errors of all dimensions
/// are reported together.
pub fn compile(source: &str, name: &str) -> Result<Module, Diagnostics> {
    let (prog, errors) = front_end_partial(source, false);
    let (dims, skipped) = applicable_dims(&prog);
    if !errors.is_empty() {
        return Err(with_lowering_errors(&prog, errors, &dims));
    }
    let mut out = Vec::new();
    let mut errors = Vec::new();
    for d in dims {
        match dim_of(&prog, d) {
            Ok(ir) => out.push(ir),
            Err(es) => push_unique(&mut errors, es),
        }
    }
    if !errors.is_empty() {
        errors.sort_by_key(|e| e.span().start);
        return Err(Diagnostics { errors });
    }
    let params = prog
        .params
        .iter()
        .map(|p| ParamDecl {
            name: p.name.clone(),
            default: p.default,
            span: p.span,
        })
        .collect();
    Ok(Module {
        source: source.to_string(),
        name: name.to_string(),
        params,
        dims: out,
        skipped,
    })
}
