//! Per-element timing of the fibre energies: the analytic projected 12×12
//! (`fibre_element_eval`, `Filter::Clamp`: closed form for ψ(I5), or the
//! analytic raw Hessian + 9×9 eigensolve for ψ with I4 terms) against the
//! numeric baseline (the same raw 12×12 element Hessian projected by
//! nalgebra's `SymmetricEigen`), on 4096 random tetrahedra, best of 3.
//!
//! Run: `cargo run --release -p ecc-runtime --example fibre_timing`
//! (figures recorded in docs/benchmarks/fibre.md).

use std::hint::black_box;
use std::time::Instant;

use ecc_runtime::energies::{FibreArap, FibreFung, FibreStvk};
use ecc_runtime::fibre::{
    FibreDerivs, FibreEnergy, FibreUse, fibre_element_eval, fibre_f, unit_fibre,
};
use ecc_runtime::reference::project_psd_numeric;
use ecc_runtime::{Filter, Rest, element_f};
use nalgebra::SVector;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// ψ = (I4 − 1)² + 0.3 (I5 − 1)²: exercises the I4 path (9×9 eigensolve).
struct Mixed;
impl FibreEnergy<3> for Mixed {
    fn name(&self) -> &str {
        "mixed I4+I5"
    }
    fn fibre(&self, i4: f64, i5: f64) -> FibreDerivs {
        FibreDerivs {
            psi: (i4 - 1.0).powi(2) + 0.3 * (i5 - 1.0).powi(2),
            d4: 2.0 * (i4 - 1.0),
            d5: 0.6 * (i5 - 1.0),
            d44: 2.0,
            d45: 0.0,
            d55: 0.6,
        }
    }
    fn uses(&self) -> FibreUse {
        FibreUse::Both
    }
}

/// ψ = (I4 − 1)²: the I4-only path (7 × 7 block, eq. R4).
struct I4Only;
impl FibreEnergy<3> for I4Only {
    fn name(&self) -> &str {
        "I4 only"
    }
    fn fibre(&self, i4: f64, _i5: f64) -> FibreDerivs {
        FibreDerivs {
            psi: (i4 - 1.0).powi(2),
            d4: 2.0 * (i4 - 1.0),
            d44: 2.0,
            ..FibreDerivs::default()
        }
    }
    fn uses(&self) -> FibreUse {
        FibreUse::I4
    }
}

type Elem = (Rest<3>, [[f64; 3]; 4], SVector<f64, 3>);

fn elements(n: usize) -> Vec<Elem> {
    let mut r = ChaCha8Rng::seed_from_u64(7);
    let rest =
        Rest::<3>::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).unwrap();
    let base = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    (0..n)
        .map(|_| {
            let x = base.map(|p| p.map(|c| c + r.gen_range(-0.3..0.3)));
            let a = unit_fibre(&[
                r.gen_range(-1.0..1.0),
                r.gen_range(-1.0..1.0),
                r.gen_range(-1.0..1.0),
            ]);
            (rest, x, a.unwrap_or(SVector::x()))
        })
        .collect()
}

/// Best of 3: ns per element.
fn time(els: &[Elem], f: impl Fn(&Elem) -> f64) -> f64 {
    (0..3)
        .map(|_| {
            let t = Instant::now();
            let mut acc = 0.0;
            for e in els {
                acc += f(e);
            }
            black_box(acc);
            t.elapsed().as_secs_f64() * 1e9 / els.len() as f64
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    let els = elements(4096);
    let energies: [&dyn FibreEnergy<3>; 5] = [
        &FibreStvk { mu: 1.0 },
        &FibreFung { k1: 1.0, k2: 1.0 },
        &FibreArap { mu: 1.0 },
        &I4Only,
        &Mixed,
    ];
    println!(
        "| energy | analytic projected 12×12 (ns) | raw 12×12 + numeric projection (ns) | speed-up |"
    );
    println!("|---|---|---|---|");
    for e in energies {
        let analytic = time(&els, |(r, x, a)| {
            fibre_element_eval(e, r, x, a, Filter::Clamp, true).hess[(0, 0)]
        });
        let numeric = time(&els, |(r, x, a)| {
            let raw = fibre_element_eval(e, r, x, a, Filter::None, true).hess;
            project_psd_numeric(&raw, Filter::Clamp)[(0, 0)]
        });
        println!(
            "| {} | {analytic:.0} | {numeric:.0} | {:.1}× |",
            e.name(),
            numeric / analytic
        );
    }
    point_table(&els);
}

/// Per point (F-space 9 × 9) for the I4 energies: the reduced path of
/// `fibre/reduced.rs` (`Filter::Clamp`) against the previous one, the raw
/// F5 Hessian (`Filter::None`) plus a 9 × 9 `SymmetricEigen`.
fn point_table(els: &[Elem]) {
    let fs: Vec<_> = els
        .iter()
        .map(|(r, x, a)| (element_f::<3>(r, x), *a))
        .collect();
    println!();
    println!("| energy | reduced, 9×9 F-space (ns) | F5 + 9×9 eigensolve (ns) | speed-up |");
    println!("|---|---|---|---|");
    for e in [&I4Only as &dyn FibreEnergy<3>, &Mixed] {
        let best = |g: &dyn Fn(usize) -> f64| {
            (0..3)
                .map(|_| {
                    let t = Instant::now();
                    black_box((0..fs.len()).map(g).sum::<f64>());
                    t.elapsed().as_secs_f64() * 1e9 / fs.len() as f64
                })
                .fold(f64::INFINITY, f64::min)
        };
        let reduced = best(&|i| {
            let (f, a) = &fs[i];
            fibre_f(e, f, a, Filter::Clamp, true).hess[(0, 0)]
        });
        let previous = best(&|i| {
            let (f, a) = &fs[i];
            let raw = fibre_f(e, f, a, Filter::None, true).hess;
            project_psd_numeric(&raw, Filter::Clamp)[(0, 0)]
        });
        println!(
            "| {} | {reduced:.0} | {previous:.0} | {:.1}× |",
            e.name(),
            previous / reduced
        );
    }
}
