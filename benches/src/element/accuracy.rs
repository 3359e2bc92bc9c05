//! Accuracy of every [`Method`] against the double-double reference
//! ([`crate::reference`]) over random and hard F ([`crate::cases`]).
//!
//! Per sample: the Hessian error is max|H − H_ref| / max|H_ref| with H_ref
//! the exact version of *what the method computes* ([`super::Target`]); the
//! gradient error is max|g − g_ref| / max(max|g_ref|, max|H_ref|·L) with L
//! the element size (the floor keeps the rest state, where g_ref = 0,
//! meaningful). The tables report the worst sample of each class.

use rayon::prelude::*;
use serde::Serialize;

use super::kernels::{Element2, Element3, Output};
use super::{Method, Target};
use crate::cases::{CLASSES, REST_TET, REST_TRI, deform, samples2, samples3};
use crate::energies::{EnergySetError, energies2, energies3};
use crate::reference::{ElementRef, element as reference, rel_err};
use ecc_runtime::Rest;

/// Worst errors of one method on one (dimension, energy, class).
#[derive(Clone, Debug, Serialize)]
pub struct AccuracyRow {
    pub dim: usize,
    pub energy: String,
    pub class: String,
    pub method: Method,
    pub hess_err: f64,
    pub grad_err: f64,
    /// Samples with a finite reference.
    pub samples: usize,
}

/// The reference's own error estimate on one (dimension, energy, class).
#[derive(Clone, Debug, Serialize)]
pub struct RefRow {
    pub dim: usize,
    pub energy: String,
    pub class: String,
    pub hess_self_err: f64,
    pub grad_self_err: f64,
}

/// Everything the accuracy study measured.
#[derive(Clone, Debug, Default, Serialize)]
pub struct AccuracyResult {
    pub rows: Vec<AccuracyRow>,
    pub refs: Vec<RefRow>,
    pub samples_per_class: usize,
    pub seconds: f64,
}

fn errors(out: &Output, r: &ElementRef, target: Target, size: f64) -> Option<(f64, f64)> {
    let h_ref = match target {
        Target::FProjection => &r.fproj,
        Target::ElementProjection => &r.eproj,
        Target::Raw => &r.raw,
    };
    if !h_ref.iter().chain(&r.grad).all(|x| x.is_finite()) {
        return None;
    }
    let hmax = r.raw.iter().map(|x| x.abs()).fold(0.0, f64::max);
    let gmax = r.grad.iter().map(|x| x.abs()).fold(0.0, f64::max);
    let gscale = gmax.max(hmax * size).max(f64::MIN_POSITIVE);
    let gdiff = out
        .1
        .iter()
        .zip(&r.grad)
        .map(|(a, b)| {
            if a.is_finite() {
                (a - b).abs()
            } else {
                f64::INFINITY
            }
        })
        .fold(0.0, f64::max);
    Some((rel_err(&out.2, h_ref), gdiff / gscale))
}

/// One sample: its reference and each method's (Hessian, gradient) errors.
type Sample = (ElementRef, Vec<(Method, Option<(f64, f64)>)>);

struct Acc {
    hess: f64,
    grad: f64,
    n: usize,
}

fn fold_rows(
    dim: usize,
    energy: &str,
    class: &str,
    per_sample: &[Sample],
    result: &mut AccuracyResult,
) {
    for m in Method::ALL {
        let mut acc = Acc {
            hess: 0.0,
            grad: 0.0,
            n: 0,
        };
        for (_, errs) in per_sample {
            if let Some((_, Some((h, g)))) = errs.iter().find(|(mm, _)| *mm == m) {
                acc.hess = acc.hess.max(*h);
                acc.grad = acc.grad.max(*g);
                acc.n += 1;
            }
        }
        result.rows.push(AccuracyRow {
            dim,
            energy: energy.into(),
            class: class.into(),
            method: m,
            hess_err: acc.hess,
            grad_err: acc.grad,
            samples: acc.n,
        });
    }
    let finite = |x: f64| if x.is_finite() { x } else { 0.0 };
    result.refs.push(RefRow {
        dim,
        energy: energy.into(),
        class: class.into(),
        hess_self_err: per_sample
            .iter()
            .map(|(r, _)| finite(r.self_error))
            .fold(0.0, f64::max),
        grad_self_err: per_sample
            .iter()
            .map(|(r, _)| finite(r.grad_self_error))
            .fold(0.0, f64::max),
    });
}

/// Run the accuracy study with `n` samples per class (≥ 1), both dimensions.
pub fn run(n: usize) -> Result<AccuracyResult, EnergySetError> {
    run_limited(n, usize::MAX, usize::MAX)
}

/// [`run`] on the first `energies` energies and `classes` case classes only (smoke tests).
pub fn run_limited(
    n: usize,
    energies: usize,
    classes: usize,
) -> Result<AccuracyResult, EnergySetError> {
    let t0 = std::time::Instant::now();
    let n = n.max(1);
    let mut result = AccuracyResult {
        samples_per_class: n,
        ..Default::default()
    };
    let rest2 = Rest::<2>::new(REST_TRI).map_err(|e| EnergySetError(e.to_string()))?;
    let rest3 = Rest::<3>::new(REST_TET).map_err(|e| EnergySetError(e.to_string()))?;
    // One study per dimension: the element types are distinct structs (see
    // `kernels::element_kind!`), so the loop is written once as a macro.
    macro_rules! study {
        ($dim:literal, $energies:expr, $samples:ident, $element:ident, $rest:expr, $nodes:expr, $seed:literal) => {
            for e in $energies.into_iter().take(energies) {
                for (ci, c) in CLASSES.iter().enumerate().take(classes) {
                    if e.barrier && c.inverted && !c.random {
                        continue;
                    }
                    let fs = $samples(c, n, e.barrier, $seed + ci as u64);
                    let per: Vec<_> = fs
                        .par_iter()
                        .map(|f| {
                            let el = $element::new($rest, deform(f, &$nodes));
                            let size = el
                                .x_flat()
                                .iter()
                                .fold(0.0f64, |a, v| a.max(v.abs()))
                                .max(1.0);
                            let r = reference(&e.generic, &el.dm_inv(), el.measure(), &el.x_flat());
                            let errs = Method::ALL
                                .iter()
                                .map(|&m| {
                                    let out = el.run(m, &*e.generated, &*e.interp, &e.generic);
                                    (m, errors(&out, &r, m.target(), size))
                                })
                                .collect();
                            (r, errs)
                        })
                        .collect();
                    fold_rows($dim, e.name, c.name, &per, &mut result);
                }
            }
        };
    }
    study!(2, energies2()?, samples2, Element2, rest2, REST_TRI, 100);
    study!(3, energies3()?, samples3, Element3, rest3, REST_TET, 200);
    result.seconds = t0.elapsed().as_secs_f64();
    Ok(result)
}
