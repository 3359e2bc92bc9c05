//! The compiler driver: source → [`Module`] / [`DimIr`].

mod checks;
mod cost;
mod derivs;
mod dim;

pub use checks::Rng;
pub use cost::{cost, cost_many};
pub use dim::slot_pairs;

use crate::diag::{Diagnostics, Error};
use crate::front::{lower, parse, sema};
use crate::ir::{DimIr, Module, ParamDecl};
use crate::span::Span;

/// Parse and resolve a source text (all syntax and name errors at once).
pub fn front_end(source: &str, free_params: bool) -> Result<sema::Program, Diagnostics> {
    let (stmts, mut errors) = parse::parse_source(source);
    let failed: Vec<&str> = errors
        .iter()
        .filter_map(|e| source.get(failed_statement(source, e.span())))
        .collect();
    match sema::resolve(&stmts, &failed, free_params, source.len()) {
        Ok(p) if errors.is_empty() => Ok(p),
        Ok(_) => Err(Diagnostics { errors }),
        Err(more) => {
            errors.extend(more);
            errors.sort_by_key(|e| e.span().start);
            Err(Diagnostics { errors })
        }
    }
}

/// The statement containing `span` (for "was this failed statement psi?").
fn failed_statement(source: &str, span: Span) -> std::ops::Range<usize> {
    parse::split_statements(source)
        .into_iter()
        .find(|s| s.start <= span.start && span.start <= s.end)
        .map_or(0..0, |s| s.range())
}

fn dim_of(prog: &sema::Program, dim: u8) -> Result<DimIr, Vec<Error>> {
    let (g, psi) = lower::lower_program(prog, dim)?;
    let params: Vec<f64> = prog.params.iter().map(|p| p.default).collect();
    let input = dim::DimInput {
        dim,
        params: &params,
        psi_span: prog.psi_span,
        no_s3: !prog.stretch_uses.iter().any(|(k, _)| *k == 2),
    };
    dim::build_dim(g, psi, &input).map_err(|e| vec![e])
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
    let prog = front_end(source, false)?;
    if let Some((declared, span)) = prog.dim
        && declared != dim
    {
        return Err(Error::DimMismatch {
            span,
            declared,
            requested: dim,
        }
        .into());
    }
    if dim == 2 {
        let errors: Vec<Error> = prog
            .stretch_uses
            .iter()
            .filter(|(k, _)| *k == 2)
            .map(|(_, span)| Error::StretchOutOfDim {
                span: *span,
                name: "s3".into(),
                dim: 2,
                declared: None,
            })
            .collect();
        if !errors.is_empty() {
            return Err(Diagnostics { errors });
        }
    }
    dim_of(&prog, dim).map_err(|errors| Diagnostics { errors })
}

/// Compile `source` for every dimension that applies: the declared `dim`,
/// else 3 only if `s3` is used, else 2 and 3. All errors of all dimensions
/// are reported together.
pub fn compile(source: &str, name: &str) -> Result<Module, Diagnostics> {
    let prog = front_end(source, false)?;
    let mut skipped = Vec::new();
    let dims: Vec<u8> = match prog.dim {
        Some((d, _)) => {
            skipped.push((5 - d, format!("declared dim {d}")));
            vec![d]
        }
        None if prog.stretch_uses.iter().any(|(k, _)| *k == 2) => {
            skipped.push((2, "uses s3".to_string()));
            vec![3]
        }
        None => vec![2, 3],
    };
    let mut out = Vec::new();
    let mut errors: Vec<Error> = Vec::new();
    for d in dims {
        match dim_of(&prog, d) {
            Ok(ir) => out.push(ir),
            Err(es) => {
                for e in es {
                    if !errors.contains(&e) {
                        errors.push(e);
                    }
                }
            }
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
