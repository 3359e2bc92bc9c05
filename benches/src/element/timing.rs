//! Time per element of every [`Method`], measured *interleaved*: each round
//! runs one pass of every method over the same batch back to back, so all
//! methods see the same machine load; the table shows the fastest round per
//! method (least disturbed) and the median over rounds of the per-round
//! ratio to the analytic kernel (the robust number on a shared machine).
//!
//! Batch: random rest elements (coordinates U(−1, 1), measure above a
//! floor) deformed by F = I + U(−0.4, 0.4)^{d×d}; every 8th inverted for
//! non-barrier energies. Energies are called through `dyn Energy` by every
//! method alike.

use std::hint::black_box;
use std::time::Instant;

use ecc_runtime::{Filter, Rest};
use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

use super::Method;
use super::kernels::{Element2, Element3};
use crate::energies::{BenchEnergy, EnergySetError, energies2, energies3};

/// Timing of one method on one (dimension, energy).
#[derive(Clone, Debug, Serialize)]
pub struct TimingRow {
    pub dim: usize,
    pub energy: String,
    pub method: Method,
    /// Fastest round, ns per element.
    pub ns: f64,
    /// Median over rounds of (this method's time / analytic time) in the same round.
    pub ratio: f64,
}

/// Everything the timing study measured.
#[derive(Clone, Debug, Default, Serialize)]
pub struct TimingResult {
    pub rows: Vec<TimingRow>,
    pub batch: usize,
    pub rounds: usize,
    pub seconds: f64,
}

/// Triangles: random rest shapes and F (every 8th inverted when `inverted`).
pub(crate) fn batch2(n: usize, inverted: bool, seed: u64) -> Vec<Element2> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let p: [[f64; 2]; 3] =
            std::array::from_fn(|_| std::array::from_fn(|_| r.gen_range(-1.0..1.0)));
        let Ok(rest) = Rest::<2>::new(p) else {
            continue;
        };
        if rest.measure < 0.05 {
            continue;
        }
        let mut f = Matrix2::identity() + Matrix2::from_fn(|_, _| r.gen_range(-0.4..0.4));
        if inverted && out.len() % 8 == 0 {
            f.column_mut(1).neg_mut();
        }
        if !inverted && f.determinant() <= 0.05 {
            continue;
        }
        let x = std::array::from_fn(|k| {
            let y = f * Vector2::from(p[k]);
            [y[0], y[1]]
        });
        out.push(Element2::new(rest, x));
    }
    out
}

/// Tets: random rest shapes and F (every 8th inverted when `inverted`).
pub(crate) fn batch3(n: usize, inverted: bool, seed: u64) -> Vec<Element3> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let p: [[f64; 3]; 4] =
            std::array::from_fn(|_| std::array::from_fn(|_| r.gen_range(-1.0..1.0)));
        let Ok(rest) = Rest::<3>::new(p) else {
            continue;
        };
        if rest.measure < 0.02 {
            continue;
        }
        let mut f = Matrix3::identity() + Matrix3::from_fn(|_, _| r.gen_range(-0.4..0.4));
        if inverted && out.len() % 8 == 0 {
            f.column_mut(2).neg_mut();
        }
        if !inverted && f.determinant() <= 0.05 {
            continue;
        }
        let x = std::array::from_fn(|k| {
            let y = f * Vector3::from(p[k]);
            [y[0], y[1], y[2]]
        });
        out.push(Element3::new(rest, x));
    }
    out
}

type Kernel<'a, T> = Box<dyn Fn(&T) -> f64 + 'a>;

macro_rules! kernels {
    ($e:expr, $el:ty) => {{
        let e = $e;
        let k: Vec<(Method, Kernel<'_, $el>)> = vec![
            (
                Method::Analytic,
                Box::new(move |el: &$el| {
                    let r = el.runtime(&*e.generated, Filter::Clamp);
                    r.0 + r.1[0] + r.2[(0, 0)]
                }),
            ),
            (
                Method::Interpreted,
                Box::new(move |el: &$el| {
                    let r = el.runtime(&*e.interp, Filter::Clamp);
                    r.0 + r.1[0] + r.2[(0, 0)]
                }),
            ),
            (
                Method::NumericF,
                Box::new(move |el: &$el| {
                    let r = el.numeric_f(&*e.generated);
                    r.0 + r.1[0] + r.2[(0, 0)]
                }),
            ),
            (
                Method::NumericElement,
                Box::new(move |el: &$el| {
                    let r = el.numeric_element(&*e.generated);
                    r.0 + r.1[0] + r.2[(0, 0)]
                }),
            ),
            (
                Method::Unprojected,
                Box::new(move |el: &$el| {
                    let r = el.runtime(&*e.generated, Filter::None);
                    r.0 + r.1[0] + r.2[(0, 0)]
                }),
            ),
            (
                Method::GenericF64,
                Box::new(move |el: &$el| {
                    let r = el.generic(&e.generic, false);
                    r.0 + r.1[0] + r.2[0]
                }),
            ),
            (
                Method::GenericF32,
                Box::new(move |el: &$el| {
                    let r = el.generic(&e.generic, true);
                    r.0 + r.1[0] + r.2[0]
                }),
            ),
        ];
        k
    }};
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

/// Interleaved timing of `kernels` over `els`; returns (min ns, median ratio to kernel 0).
fn interleaved<T>(
    els: &[T],
    kernels: &[(Method, Kernel<'_, T>)],
    rounds: usize,
) -> Vec<(f64, f64)> {
    let mut t = vec![Vec::with_capacity(rounds); kernels.len()];
    for round in 0..rounds {
        for i in 0..kernels.len() {
            // rotate the order so no method is always first
            let k = (i + round) % kernels.len();
            let f = &kernels[k].1;
            let start = Instant::now();
            for el in els {
                black_box(f(black_box(el)));
            }
            t[k].push(start.elapsed().as_secs_f64() * 1e9 / els.len() as f64);
        }
    }
    (0..kernels.len())
        .map(|k| {
            let min = t[k].iter().copied().fold(f64::INFINITY, f64::min);
            let ratios: Vec<f64> = t[k].iter().zip(&t[0]).map(|(a, b)| a / b).collect();
            (min, median(ratios))
        })
        .collect()
}

fn push<const D: usize>(res: &mut TimingResult, e: &BenchEnergy<D>, out: Vec<(f64, f64)>) {
    for (m, (ns, ratio)) in Method::ALL.iter().zip(out) {
        res.rows.push(TimingRow {
            dim: D,
            energy: e.name.into(),
            method: *m,
            ns,
            ratio,
        });
    }
}

/// Time every method on a batch of `batch` elements, `rounds` interleaved rounds.
pub fn run(batch: usize, rounds: usize) -> Result<TimingResult, EnergySetError> {
    run_limited(batch, rounds, usize::MAX)
}

/// [`run`] on the first `energies` energies only (smoke tests).
pub fn run_limited(
    batch: usize,
    rounds: usize,
    energies: usize,
) -> Result<TimingResult, EnergySetError> {
    let t0 = Instant::now();
    let mut res = TimingResult {
        batch,
        rounds,
        ..Default::default()
    };
    let (b2i, b2) = (batch2(batch, true, 21), batch2(batch, false, 22));
    for e in energies2()?.into_iter().take(energies) {
        let els = if e.barrier { &b2 } else { &b2i };
        let k = kernels!(&e, Element2);
        let out = interleaved(els, &k, rounds.max(1));
        push(&mut res, &e, out);
    }
    let (b3i, b3) = (batch3(batch, true, 31), batch3(batch, false, 32));
    for e in energies3()?.into_iter().take(energies) {
        let els = if e.barrier { &b3 } else { &b3i };
        let k = kernels!(&e, Element3);
        let out = interleaved(els, &k, rounds.max(1));
        push(&mut res, &e, out);
    }
    res.seconds = t0.elapsed().as_secs_f64();
    Ok(res)
}
