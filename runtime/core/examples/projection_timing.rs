//! Per-element cost of the three ways to project an element Hessian (ns per
//! call, best of 3 runs): F-space (`element_eval`, analytic filter), exact
//! element projection (`element_eval_projected`, d²×d² congruence) and the
//! numeric projection of the raw 6×6 / 12×12 (`element_eval` with
//! `Filter::None`, then `reference::project_psd_numeric`), on 64 mildly
//! stretched and 64 compressed/sheared points; the last column is the share
//! of points whose F-space Hessian is indefinite (only those can need the
//! exact path's eigensolve).
//! `cargo run --release -p ecc-runtime --example projection_timing`.

use std::hint::black_box;
use std::time::Instant;

use ecc_runtime::energies::{StableNeoHookean, SymmetricDirichlet};
use ecc_runtime::reference::project_psd_numeric;
use ecc_runtime::{Energy, Filter, Rest, element_eval, element_eval_projected};

/// Best of 3 timings of `n` calls of `f`, in ns per call.
fn time(n: usize, mut f: impl FnMut(usize) -> f64) -> f64 {
    (0..3)
        .map(|_| {
            let start = Instant::now();
            let mut acc = 0.0;
            for k in 0..n {
                acc += f(k);
            }
            black_box(acc);
            start.elapsed().as_secs_f64() * 1e9 / n as f64
        })
        .fold(f64::INFINITY, f64::min)
}

/// 64 deformed positions x_n = F_k p_n: mild stretches (`indefinite` = false)
/// or compressions with shear (ARAP/SNH/SD indefinite there).
fn tets(indefinite: bool) -> Vec<[[f64; 3]; 4]> {
    let p = [[0.0; 3], [1.0, 0.1, 0.0], [0.2, 0.8, 0.1], [0.3, 0.1, 1.4]];
    (0..64)
        .map(|k| {
            let a = 0.005 * k as f64;
            let f = if indefinite {
                [
                    [0.45 + a, 0.35, 0.1],
                    [-0.2, 0.5, 0.3],
                    [0.1, -0.3, 0.6 - a],
                ]
            } else {
                [
                    [1.1 + a, 0.05, 0.0],
                    [0.0, 1.05, 0.02],
                    [0.01, 0.0, 1.2 - a],
                ]
            };
            p.map(|q| std::array::from_fn(|i| (0..3).map(|j| f[i][j] * q[j]).sum()))
        })
        .collect()
}

fn tris(indefinite: bool) -> Vec<[[f64; 2]; 3]> {
    let p = [[0.0; 2], [1.0, 0.1], [0.3, 1.6]];
    (0..64)
        .map(|k| {
            let a = 0.005 * k as f64;
            let f = if indefinite {
                [[0.4 + a, 0.35], [-0.25, 0.5]]
            } else {
                [[1.1 + a, 0.05], [0.0, 1.2 - a]]
            };
            p.map(|q| std::array::from_fn(|i| (0..2).map(|j| f[i][j] * q[j]).sum()))
        })
        .collect()
}

fn row3(name: &str, e: &dyn Energy<3>, indefinite: bool) {
    let xs = tets(indefinite);
    let rest =
        Rest::<3>::new([[0.0; 3], [1.0, 0.1, 0.0], [0.2, 0.8, 0.1], [0.3, 0.1, 1.4]]).unwrap();
    let cg = rest.congruence();
    let n = 100_000;
    let x = |k: usize| black_box(&xs[k % 64]);
    let fs = time(n, |k| {
        element_eval(e, &rest, x(k), Filter::Clamp, true).hess[(3, 5)]
    });
    let ex = time(n, |k| {
        element_eval_projected(e, &rest, &cg, x(k), Filter::Clamp, true).hess[(3, 5)]
    });
    let nu = time(n, |k| {
        let raw = element_eval(e, &rest, x(k), Filter::None, true).hess;
        project_psd_numeric::<12>(&raw, Filter::Clamp)[(3, 5)]
    });
    let ind = (0..64)
        .filter(|&k| {
            let raw = element_eval(e, &rest, &xs[k], Filter::None, true).hess;
            raw != element_eval(e, &rest, &xs[k], Filter::Clamp, true).hess
        })
        .count();
    let kind = if indefinite {
        "compressed"
    } else {
        "stretched"
    };
    println!(
        "| tet | {name} | {kind} | {fs:.0} | {ex:.0} | {nu:.0} | {:.1}x | {ind}/64 |",
        nu / ex
    );
}

fn row2(name: &str, e: &dyn Energy<2>, indefinite: bool) {
    let xs = tris(indefinite);
    let rest = Rest::<2>::new([[0.0; 2], [1.0, 0.1], [0.3, 1.6]]).unwrap();
    let cg = rest.congruence();
    let n = 200_000;
    let x = |k: usize| black_box(&xs[k % 64]);
    let fs = time(n, |k| {
        element_eval(e, &rest, x(k), Filter::Clamp, true).hess[(1, 4)]
    });
    let ex = time(n, |k| {
        element_eval_projected(e, &rest, &cg, x(k), Filter::Clamp, true).hess[(1, 4)]
    });
    let nu = time(n, |k| {
        let raw = element_eval(e, &rest, x(k), Filter::None, true).hess;
        project_psd_numeric::<6>(&raw, Filter::Clamp)[(1, 4)]
    });
    let ind = (0..64)
        .filter(|&k| {
            let raw = element_eval(e, &rest, &xs[k], Filter::None, true).hess;
            raw != element_eval(e, &rest, &xs[k], Filter::Clamp, true).hess
        })
        .count();
    let kind = if indefinite {
        "compressed"
    } else {
        "stretched"
    };
    println!(
        "| tri | {name} | {kind} | {fs:.0} | {ex:.0} | {nu:.0} | {:.1}x | {ind}/64 |",
        nu / ex
    );
}

fn main() {
    let snh = StableNeoHookean::new(1.0, 10.0);
    println!(
        "| element | energy | points | F-space (ns) | exact element (ns) | numeric (ns) | numeric / exact | indefinite |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for indefinite in [false, true] {
        row3("SNH", &snh, indefinite);
        row3("SD", &SymmetricDirichlet, indefinite);
        row2("SD", &SymmetricDirichlet, indefinite);
        row2("SNH", &snh, indefinite);
    }
}
