//! Tiny timing of the element kernels (ns per call), for checking that the
//! generic API costs nothing: `cargo run --release -p ecc-runtime --example element_timing`.

use std::hint::black_box;
use std::time::Instant;

use ecc_runtime::energies::StableNeoHookean;
use ecc_runtime::{Filter, Rest, element_eval, gradient_f, hessian_f, signed_svd};
use nalgebra::Matrix3;

/// Median of `runs` timings of `n` calls of `f`, in ns per call.
fn time(n: usize, runs: usize, mut f: impl FnMut(usize) -> f64) -> f64 {
    let mut t: Vec<f64> = (0..runs)
        .map(|_| {
            let start = Instant::now();
            let mut acc = 0.0;
            for k in 0..n {
                acc += f(k);
            }
            black_box(acc);
            start.elapsed().as_secs_f64() * 1e9 / n as f64
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[runs / 2]
}

fn main() {
    let e = StableNeoHookean::new(1.0, 1.0);
    let rest =
        Rest::<3>::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).unwrap();
    let rest2 = Rest::<2>::new([[0.0; 2], [1.0, 0.0], [0.0, 1.0]]).unwrap();
    let xs: Vec<[[f64; 3]; 4]> = (0..64)
        .map(|k| {
            let a = 0.01 * k as f64;
            [
                [0.0; 3],
                [1.1 + a, 0.1, 0.0],
                [0.2 * a, 0.9, 0.1],
                [0.1, -a, 1.2],
            ]
        })
        .collect();
    let xs2: Vec<[[f64; 2]; 3]> = (0..64)
        .map(|k| [[0.0; 2], [1.1 + 0.01 * k as f64, 0.1], [0.2, 0.9]])
        .collect();
    let n = 200_000;
    let tet = time(n, 15, |k| {
        element_eval(&e, &rest, black_box(&xs[k % 64]), Filter::Clamp, true).hess[(3, 5)]
    });
    let tri = time(n, 15, |k| {
        element_eval(&e, &rest2, black_box(&xs2[k % 64]), Filter::Clamp, true).hess[(1, 4)]
    });
    let point = time(n, 15, |k| {
        let f = Matrix3::new(
            1.1 + 1e-3 * (k % 64) as f64,
            0.1,
            0.0,
            0.0,
            0.9,
            0.1,
            0.1,
            0.0,
            1.2,
        );
        let svd = signed_svd(&black_box(f));
        let s = ecc_runtime::Energy::<3>::spectral(&e, &svd.sigma);
        gradient_f(&svd, &s)[2] + hessian_f(&svd, &s, Filter::Clamp)[(4, 7)]
    });
    println!("tet element_eval (SNH, Clamp, Hessian): {tet:.1} ns");
    println!("tri element_eval (SNH, Clamp, Hessian): {tri:.1} ns");
    println!("3D F-space gradient + filtered Hessian: {point:.1} ns");
}
