//! Per-element time of the **autodiff baseline** ([`crate::autodiff`]:
//! forward-mode dual numbers + numeric element projection, what TinyAD does)
//! against ecc's analytic kernel, on the same batches as [`super::timing`]
//! and measured the same way (interleaved rounds; fastest round; median of
//! the per-round ratio to the analytic kernel).
//!
//! Each row also records how far the baseline's *raw* Hessian is from ecc's
//! raw element Hessian (`Filter::None`) over the batch: the worst
//! max|H_ad − H_ecc| / max|H_ecc|, so the two compute the same derivative.

use std::hint::black_box;
use std::time::Instant;

use ecc_runtime::{Dim, Energy, Filter, Nodes, Rest, Space, element_eval};
use nalgebra::{Const, DimSub, U1};
use serde::Serialize;

use super::kernels::{Element2, Element3};
use super::timing::{batch2, batch3};
use crate::autodiff::{AdEnergy, element_hessian, element_projected};
use crate::energies::{EnergySetError, energies2, energies3};

/// One (dimension, energy) row.
#[derive(Clone, Debug, Serialize)]
pub struct AutodiffRow {
    pub dim: usize,
    pub energy: String,
    /// Fastest round, ns per element: analytic kernel with `Filter::Clamp`.
    pub analytic_ns: f64,
    /// Analytic raw Hessian + numeric element projection.
    pub numeric_ns: f64,
    /// Autodiff Hessian + numeric element projection (the baseline).
    pub autodiff_ns: f64,
    /// Autodiff Hessian alone (no projection).
    pub autodiff_raw_ns: f64,
    /// Median over rounds of autodiff (projected) / analytic.
    pub ratio: f64,
    /// Median over rounds of autodiff (raw) / analytic.
    pub ratio_raw: f64,
    /// Worst relative difference of the raw Hessians over the batch.
    pub max_rel_diff: f64,
}

/// The study's result.
#[derive(Clone, Debug, Default, Serialize)]
pub struct AutodiffTiming {
    pub rows: Vec<AutodiffRow>,
    pub batch: usize,
    pub rounds: usize,
    pub seconds: f64,
}

/// One element of the batch: rest data, nodes, and the node-major
/// coordinates the baseline reads (flattened outside the timed loop).
struct Sample<const D: usize>
where
    Space<D>: Dim<D>,
{
    rest: Rest<D>,
    x: Nodes<D>,
    flat: Vec<f64>,
}

fn samples2(els: &[Element2]) -> Vec<Sample<2>> {
    els.iter()
        .map(|e| Sample {
            rest: e.rest,
            x: e.x,
            flat: e.x_flat(),
        })
        .collect()
}

fn samples3(els: &[Element3]) -> Vec<Sample<3>> {
    els.iter()
        .map(|e| Sample {
            rest: e.rest,
            x: e.x,
            flat: e.x_flat(),
        })
        .collect()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

/// Worst max|H_ad − H_ecc| / max|H_ecc| over `els` (raw Hessians, inside the domain).
fn max_rel_diff<const D: usize, const N: usize>(
    els: &[Sample<D>],
    ad: AdEnergy,
    e: &dyn Energy<D>,
) -> f64
where
    Space<D>: Dim<D>,
{
    els.iter()
        .filter_map(|el| {
            let (_, _, h) = element_hessian::<D, N>(ad, &el.rest, &el.flat)?;
            let ev = element_eval(e, &el.rest, &el.x, Filter::None, true);
            let (mut diff, mut scale) = (0.0f64, 0.0f64);
            for i in 0..N {
                for j in 0..N {
                    diff = diff.max((h[(i, j)] - ev.hess[(i, j)]).abs());
                    scale = scale.max(ev.hess[(i, j)].abs());
                }
            }
            Some(diff / scale)
        })
        .fold(0.0, f64::max)
}

type Kernel<'a, const D: usize> = Box<dyn Fn(&Sample<D>) -> f64 + 'a>;

/// The four kernels timed: analytic clamp, analytic raw + numeric
/// projection, autodiff + numeric projection, autodiff raw.
fn kernels<'a, const D: usize, const N: usize>(
    ad: AdEnergy,
    e: &'a dyn Energy<D>,
) -> [Kernel<'a, D>; 4]
where
    Space<D>: Dim<D>,
    Const<N>: DimSub<U1>,
    nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<nalgebra::DimDiff<Const<N>, U1>>,
{
    let sum = |r: Option<(f64, nalgebra::SVector<f64, N>, nalgebra::SMatrix<f64, N, N>)>| {
        r.map_or(f64::INFINITY, |(v, g, h)| v + g[0] + h[(0, 0)])
    };
    [
        Box::new(move |el: &Sample<D>| {
            let ev = element_eval(e, &el.rest, &el.x, Filter::Clamp, true);
            ev.psi + ev.grad[0] + ev.hess[(0, 0)]
        }),
        Box::new(move |el: &Sample<D>| {
            let ev = element_eval(e, &el.rest, &el.x, Filter::None, true);
            let cols: [[f64; N]; N] =
                std::array::from_fn(|j| std::array::from_fn(|i| ev.hess[(i, j)]));
            let h =
                nalgebra::SMatrix::<f64, N, N>::from_array_storage(nalgebra::ArrayStorage(cols));
            let p = ecc_runtime::reference::project_psd_numeric(&h, Filter::Clamp);
            ev.psi + ev.grad[0] + p[(0, 0)]
        }),
        Box::new(move |el: &Sample<D>| {
            sum(element_projected::<D, N>(
                ad,
                &el.rest,
                &el.flat,
                Filter::Clamp,
            ))
        }),
        Box::new(move |el: &Sample<D>| sum(element_hessian::<D, N>(ad, &el.rest, &el.flat))),
    ]
}

/// Interleaved rounds (order rotated); per kernel: (fastest ns, median ratio to kernel 0).
fn interleaved<const D: usize>(
    els: &[Sample<D>],
    ks: &[Kernel<'_, D>],
    rounds: usize,
) -> Vec<(f64, f64)>
where
    Space<D>: Dim<D>,
{
    let mut t = vec![Vec::with_capacity(rounds); ks.len()];
    for round in 0..rounds {
        for i in 0..ks.len() {
            let k = (i + round) % ks.len();
            let start = Instant::now();
            for el in els {
                black_box(ks[k](black_box(el)));
            }
            t[k].push(start.elapsed().as_secs_f64() * 1e9 / els.len() as f64);
        }
    }
    (0..ks.len())
        .map(|k| {
            let min = t[k].iter().copied().fold(f64::INFINITY, f64::min);
            let ratios = t[k].iter().zip(&t[0]).map(|(a, b)| a / b).collect();
            (min, median(ratios))
        })
        .collect()
}

/// Time and check one (dimension, energy).
fn row<const D: usize, const N: usize>(
    name: &str,
    e: &dyn Energy<D>,
    els: &[Sample<D>],
    rounds: usize,
) -> Option<AutodiffRow>
where
    Space<D>: Dim<D>,
    Const<N>: DimSub<U1>,
    nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<nalgebra::DimDiff<Const<N>, U1>>,
{
    let ad = AdEnergy::for_name(name, D)?;
    let ks = kernels::<D, N>(ad, e);
    let t = interleaved(els, &ks, rounds.max(1));
    Some(AutodiffRow {
        dim: D,
        energy: name.into(),
        analytic_ns: t[0].0,
        numeric_ns: t[1].0,
        autodiff_ns: t[2].0,
        autodiff_raw_ns: t[3].0,
        ratio: t[2].1,
        ratio_raw: t[3].1,
        max_rel_diff: max_rel_diff::<D, N>(els, ad, e),
    })
}

/// Time the baseline on `batch` elements per energy, `rounds` rounds, for the
/// energies it has a form for (2D ARAP, SD, SNH; 3D SD, SNH).
pub fn run(batch: usize, rounds: usize) -> Result<AutodiffTiming, EnergySetError> {
    let t0 = Instant::now();
    let mut res = AutodiffTiming {
        batch,
        rounds,
        ..Default::default()
    };
    let (b2i, b2) = (
        samples2(&batch2(batch, true, 21)),
        samples2(&batch2(batch, false, 22)),
    );
    for e in energies2()? {
        let els = if e.barrier { &b2 } else { &b2i };
        res.rows
            .extend(row::<2, 6>(e.name, &*e.generated, els, rounds));
    }
    let (b3i, b3) = (
        samples3(&batch3(batch, true, 31)),
        samples3(&batch3(batch, false, 32)),
    );
    for e in energies3()? {
        let els = if e.barrier { &b3 } else { &b3i };
        res.rows
            .extend(row::<3, 12>(e.name, &*e.generated, els, rounds));
    }
    res.seconds = t0.elapsed().as_secs_f64();
    Ok(res)
}
