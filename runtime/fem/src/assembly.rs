//! Parallel assembly of the reduced gradient and the filtered Hessian.
//!
//! For each term and each colour of its stencil colouring, stencils are
//! evaluated in parallel (rayon); each writes its scaled local gradient into
//! the reduced gradient through the DOF→unknown table and its local Hessian
//! (upper part) into the value array through the precomputed stencil→slot
//! map. Stencils of one colour share no free vertex, so their writes are
//! disjoint (greedy colouring, once per mesh). Per-stencil energies go to a per-term
//! buffer and are summed deterministically. Local buffers live on the stack
//! of each rayon job: the hot loop does not allocate.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use ecc_runtime::filter::Filter;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::dofs::DofMap;
use crate::error::FemError;
use crate::order::choose_order;
use crate::parallel::{SharedMut, min_indexed, min_len, sum_indexed};
use crate::pattern::{NO_SLOT, Pattern, StencilSet, TermPlan, build, validate};
use crate::term::{MAX_STENCIL_DOFS, Term};

/// Values zeroed per task before an assembly (a pass of stores; splitting a
/// smaller one costs more than it saves).
const ZERO_GRAIN: usize = 1 << 16;

/// A stencil produced a non-finite value where a finite one was required.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NonFiniteStencil {
    /// Name of the term.
    pub term: String,
    /// Stencil (element) index within the term.
    pub stencil: usize,
    /// Which quantity: "energy", "gradient" or "hessian".
    pub quantity: String,
}

/// Accumulated evaluation cost of one term.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TermTiming {
    /// Name of the term.
    pub name: String,
    /// Number of stencils.
    pub stencils: usize,
    /// Number of colours of its stencil colouring.
    pub colours: usize,
    /// Value-only passes (line search) and their total wall time.
    pub value_passes: usize,
    pub value_seconds: f64,
    /// Gradient(+Hessian) passes and their total wall time.
    pub assembly_passes: usize,
    pub assembly_seconds: f64,
}

/// Pattern, slot maps, colourings and per-term buffers for one problem.
pub struct Assembler<const D: usize> {
    dofs: DofMap,
    pattern: Pattern,
    plans: Vec<TermPlan>,
    psi: Vec<Vec<f64>>,
    partials: Vec<f64>,
    timings: Vec<TermTiming>,
}

const NONE: u32 = u32::MAX;

impl<const D: usize> Assembler<D> {
    /// Validate the terms' stencils and build everything that depends only on
    /// the mesh and the fixed set.
    pub fn new(terms: &[Box<dyn Term<D>>], dofs: DofMap) -> Result<Self, FemError> {
        FemError::check_len("DOF map dimension", D, dofs.dim())?;
        let sets: Vec<StencilSet<'_>> = terms
            .iter()
            .map(|t| StencilSet {
                name: t.name(),
                arity: t.arity(),
                stencils: t.stencils(),
            })
            .collect();
        for set in &sets {
            validate(set, dofs.n_vertices(), D)?;
        }
        let dofs = match choose_order(dofs.n_vertices(), &sets) {
            Some(order) => dofs.renumbered(&order),
            None => dofs,
        };
        let (pattern, plans) = build(&sets, &dofs)?;
        let psi = terms
            .iter()
            .map(|t| vec![0.0; t.stencils().len() / t.arity()])
            .collect();
        let timings = terms
            .iter()
            .zip(&plans)
            .map(|(t, p)| TermTiming {
                name: t.name().to_string(),
                stencils: t.stencils().len() / t.arity(),
                colours: p.colouring.n_colours(),
                ..TermTiming::default()
            })
            .collect();
        Ok(Assembler {
            dofs,
            pattern,
            plans,
            psi,
            partials: Vec::new(),
            timings,
        })
    }

    /// The DOF map.
    pub fn dofs(&self) -> &DofMap {
        &self.dofs
    }

    /// The Hessian pattern.
    pub fn pattern(&self) -> &Pattern {
        &self.pattern
    }

    /// Accumulated per-term timings.
    pub fn timings(&self) -> &[TermTiming] {
        &self.timings
    }

    /// Reset the per-term timings.
    pub fn reset_timings(&mut self) {
        for t in &mut self.timings {
            *t = TermTiming {
                name: std::mem::take(&mut t.name),
                stencils: t.stencils,
                colours: t.colours,
                ..TermTiming::default()
            };
        }
    }

    /// scale · E(x). `+∞` if any stencil is outside its domain (a NaN stencil
    /// value is treated as `+∞`, i.e. "step too long").
    pub fn energy(&mut self, terms: &[Box<dyn Term<D>>], x: &[[f64; D]], scale: f64) -> f64 {
        let mut total = 0.0;
        for (ti, term) in terms.iter().enumerate() {
            let t0 = Instant::now();
            let n = self.psi[ti].len();
            let e = sum_indexed(n, &mut self.partials, |s| {
                let v = term.value(s, x);
                if v.is_nan() { f64::INFINITY } else { v }
            });
            let tm = &mut self.timings[ti];
            tm.value_passes += 1;
            tm.value_seconds += t0.elapsed().as_secs_f64();
            total += e;
        }
        scale * total
    }

    /// Largest step α such that every barrier term stays finite on [x, x + α·dx).
    pub fn max_step(&self, terms: &[Box<dyn Term<D>>], x: &[[f64; D]], dx: &[[f64; D]]) -> f64 {
        let mut a = f64::INFINITY;
        for (ti, term) in terms.iter().enumerate() {
            if term.is_barrier() {
                let m = min_indexed(self.psi[ti].len(), |s| term.max_step(s, x, dx));
                a = a.min(if m.is_nan() { 0.0 } else { m });
            }
        }
        a
    }

    /// Assemble scale·E, the reduced gradient `grad` (length n_unknowns) and,
    /// if `hessian` is `Some((filter, values))`, the filtered reduced Hessian
    /// values (length nnz) — all overwritten. Isolated unknowns get a unit
    /// diagonal so the system stays nonsingular (their gradient is zero).
    pub fn assemble(
        &mut self,
        terms: &[Box<dyn Term<D>>],
        x: &[[f64; D]],
        scale: f64,
        grad: &mut [f64],
        mut hessian: Option<(Filter, &mut [f64])>,
    ) -> Result<f64, NonFiniteStencil> {
        // memory-bound: a thread per 64k values at most
        grad.par_iter_mut()
            .with_min_len(ZERO_GRAIN)
            .for_each(|g| *g = 0.0);
        if let Some((_, v)) = hessian.as_mut() {
            v.par_iter_mut()
                .with_min_len(ZERO_GRAIN)
                .for_each(|h| *h = 0.0);
        }
        let gptr = SharedMut::new(grad);
        let hptr = hessian.as_mut().map(|(_, v)| SharedMut::new(v));
        let filter = hessian.as_ref().map(|(f, _)| *f);
        let mut total = 0.0;
        for (ti, term) in terms.iter().enumerate() {
            let t0 = Instant::now();
            let plan = &self.plans[ti];
            let k = plan.k;
            let n_local = plan.n_local;
            let psi_ptr = SharedMut::new(&mut self.psi[ti]);
            // first bad stencil, encoded as s·4 + what (what: 1 energy, 2 gradient, 3 hessian)
            let bad = AtomicUsize::new(usize::MAX);
            let grain = min_len(self.psi[ti].len(), 64);
            for c in 0..plan.colouring.n_colours() {
                let (lo, hi) = (plan.colouring.ptr[c], plan.colouring.ptr[c + 1]);
                (lo..hi).into_par_iter().with_min_len(grain).for_each_init(
                    || {
                        (
                            [0.0f64; MAX_STENCIL_DOFS],
                            [0.0f64; MAX_STENCIL_DOFS * MAX_STENCIL_DOFS],
                        )
                    },
                    |(lg, lh), p| {
                        let s = plan.colouring.order[p] as usize;
                        let lg = &mut lg[..k];
                        let lh = &mut lh[..k * k];
                        let psi = term.evaluate(
                            s,
                            x,
                            filter.unwrap_or(Filter::Clamp),
                            lg,
                            filter.map(|_| &mut *lh),
                        );
                        // SAFETY: index s is owned by this task (each stencil appears once).
                        unsafe { psi_ptr.set(s, psi) };
                        let what = non_finite_kind(psi, lg, filter.map(|_| &*lh));
                        if what != 0 {
                            bad.fetch_min(s * 4 + what, Ordering::Relaxed);
                            return;
                        }
                        for (&u, &ga) in plan.unknowns[p * k..(p + 1) * k].iter().zip(lg.iter()) {
                            if u != NONE {
                                // SAFETY: stencils of one colour share no free vertex,
                                // so unknown u is written by this task only.
                                unsafe { gptr.add(u as usize, scale * ga) };
                            }
                        }
                        if let Some(hp) = hptr {
                            let slots = &plan.slots[p * n_local..(p + 1) * n_local];
                            let mut q = 0;
                            for a in 0..k {
                                for b in a..k {
                                    let sl = slots[q];
                                    if sl != NO_SLOT {
                                        // SAFETY: as above, slot sl couples two free
                                        // vertices of this stencil only within this colour.
                                        unsafe { hp.add(sl as usize, scale * lh[a * k + b]) };
                                    }
                                    q += 1;
                                }
                            }
                        }
                    },
                );
            }
            let b = bad.load(Ordering::Relaxed);
            if b != usize::MAX {
                return Err(non_finite_stencil(term.name(), b));
            }
            let psi = &self.psi[ti];
            total += sum_indexed(psi.len(), &mut self.partials, |s| psi[s]);
            let tm = &mut self.timings[ti];
            tm.assembly_passes += 1;
            tm.assembly_seconds += t0.elapsed().as_secs_f64();
        }
        if let Some((_, v)) = hessian {
            for &j in self.pattern.isolated() {
                v[self.pattern.diag_slot(j)] = 1.0;
            }
        }
        Ok(scale * total)
    }

    /// Σ_s d_sᵀ H_s d_s with the *unfiltered* stencil Hessians (times scale),
    /// for the trust-region ratio of the adaptive filter, from
    /// [`Term::curvature`] per stencil. `d` is a full per-vertex direction
    /// (zero on fixed DOFs). Non-finite stencils contribute `+∞`.
    pub fn raw_curvature(
        &mut self,
        terms: &[Box<dyn Term<D>>],
        x: &[[f64; D]],
        d: &[[f64; D]],
        scale: f64,
    ) -> f64 {
        let mut total = 0.0;
        for (ti, term) in terms.iter().enumerate() {
            let t0 = Instant::now();
            let n = self.psi[ti].len();
            total += sum_indexed(n, &mut self.partials, |s| term.curvature(s, x, d));
            let tm = &mut self.timings[ti];
            tm.assembly_passes += 1;
            tm.assembly_seconds += t0.elapsed().as_secs_f64();
        }
        scale * total
    }
}

/// What a stencil produced that is not finite: 0 nothing, 1 its energy,
/// 2 its gradient, 3 its (requested) Hessian — the first in that order.
#[inline]
fn non_finite_kind(psi: f64, lg: &[f64], lh: Option<&[f64]>) -> usize {
    if !psi.is_finite() {
        1
    } else if lg.iter().any(|v| !v.is_finite()) {
        2
    } else if lh.is_some_and(|h| h.iter().any(|v| !v.is_finite())) {
        3
    } else {
        0
    }
}

/// The error for the first bad stencil, encoded as `stencil·4 + kind`
/// (kind from [`non_finite_kind`]).
fn non_finite_stencil(term: &str, code: usize) -> NonFiniteStencil {
    let quantity = match code % 4 {
        1 => "energy",
        2 => "gradient",
        _ => "hessian",
    };
    NonFiniteStencil {
        term: term.to_string(),
        stencil: code / 4,
        quantity: quantity.into(),
    }
}
