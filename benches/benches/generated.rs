//! Generated vs hand-written energies in the per-element tet kernel.
//!
//! `element_eval::<3>` (F, signed SVD, `spectral`, filtered 12×12 from the eigenmodes
//! with `Filter::Clamp`, plus ψ and gradient) for the generated ARAP,
//! Symmetric Dirichlet 3D and Stable Neo-Hookean of `ecc-energies` against
//! the runtime's hand-written `energies::{Arap, SymmetricDirichlet,
//! StableNeoHookean}`, on the same batch of random tets (1/8 inverted).
//! Both sides are statically dispatched. After criterion's groups, an
//! interleaved timing loop prints ns/element and generated/hand-written
//! ratios measured in the same run (target: ≤ 1.1×), and a `spectral`-only
//! table isolating the generated code itself.
//!
//! Run: `cargo bench -p ecc-benches --bench generated`.

use criterion::{BenchmarkId, Criterion};
use ecc_runtime::{Energy, Filter, Rest, element_eval, element_f};
use nalgebra::Matrix3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use std::time::{Duration, Instant};

const BATCH: usize = 256;

struct Element {
    rest: Rest<3>,
    x: [[f64; 3]; 4],
    /// Signed singular values of F (for the spectral-only table).
    sigma: [f64; 3],
}

fn batch() -> Vec<Element> {
    let mut r = ChaCha8Rng::seed_from_u64(11);
    let mut out = Vec::with_capacity(BATCH);
    while out.len() < BATCH {
        let p: [[f64; 3]; 4] =
            std::array::from_fn(|_| std::array::from_fn(|_| r.gen_range(-1.0..1.0)));
        let Ok(rest) = Rest::<3>::new(p) else {
            continue;
        };
        if rest.measure < 0.02 {
            continue;
        }
        let mut f = Matrix3::identity() + Matrix3::from_fn(|_, _| r.gen_range(-0.5..0.5));
        if out.len() % 8 == 0 {
            f.column_mut(2).neg_mut(); // inverted
        }
        let x = std::array::from_fn(|n| {
            let y = f * nalgebra::Vector3::from(p[n]);
            [y[0], y[1], y[2]]
        });
        let sigma = ecc_runtime::signed_svd3(&element_f(&rest, &x)).sigma;
        out.push(Element { rest, x, sigma });
    }
    out
}

/// The kernel both sides run.
fn kernel<E: Energy<3>>(e: &E, el: &Element) -> f64 {
    let r = element_eval(e, &el.rest, &el.x, Filter::Clamp, true);
    r.psi + r.grad[0] + r.hess[(0, 0)]
}

fn spectral_only<E: Energy<3>>(e: &E, el: &Element) -> f64 {
    let s = e.spectral(&el.sigma);
    s.psi + s.grad[0] + s.scale.get(0, 1) + s.twist[0] + s.flip[2]
}

type Kernel<'a> = Box<dyn Fn(&Element) -> f64 + 'a>;

struct Pair {
    name: &'static str,
    generated: Box<dyn Fn() -> (Kernel<'static>, Kernel<'static>)>,
    hand: Box<dyn Fn() -> (Kernel<'static>, Kernel<'static>)>,
}

fn pairs() -> Vec<Pair> {
    fn k<E: Energy<3> + Clone + 'static>(e: E) -> (Kernel<'static>, Kernel<'static>) {
        let e2 = e.clone();
        (
            Box::new(move |el| kernel(&e, el)),
            Box::new(move |el| spectral_only(&e2, el)),
        )
    }
    vec![
        Pair {
            name: "arap",
            generated: Box::new(|| k(ecc_energies::Arap::new())),
            hand: Box::new(|| k(ecc_runtime::energies::Arap)),
        },
        Pair {
            name: "symmetric_dirichlet",
            generated: Box::new(|| k(ecc_energies::SymmetricDirichlet3::new())),
            hand: Box::new(|| k(ecc_runtime::energies::SymmetricDirichlet)),
        },
        Pair {
            name: "stable_neo_hookean",
            generated: Box::new(|| k(ecc_energies::StableNeoHookean::new())),
            hand: Box::new(|| k(ecc_runtime::energies::StableNeoHookean::new(1.0, 10.0))),
        },
    ]
}

/// Generated and hand-written agree on every element (so the timing
/// compares equal work).
fn sanity(els: &[Element]) {
    for p in pairs() {
        let ((g, gs), (h, hs)) = ((p.generated)(), (p.hand)());
        for el in els {
            for (a, b) in [(g(el), h(el)), (gs(el), hs(el))] {
                let rel = (a - b).abs() / a.abs().max(b.abs()).max(1.0);
                assert!(rel < 1e-10, "{}: generated {a} vs hand-written {b}", p.name);
            }
        }
    }
}

fn criterion_groups(c: &mut Criterion, els: &[Element]) {
    for p in pairs() {
        let mut g = c.benchmark_group(format!("tet_eval_clamp/{}", p.name));
        for (side, make) in [("generated", &p.generated), ("hand_written", &p.hand)] {
            let (k, _) = make();
            g.bench_function(BenchmarkId::new(side, BATCH), |b| {
                b.iter(|| els.iter().map(|el| k(black_box(el))).sum::<f64>())
            });
        }
        g.finish();
    }
}

fn once_ns(items: usize, f: &mut dyn FnMut()) -> f64 {
    let start = Instant::now();
    f();
    start.elapsed().as_secs_f64() * 1e9 / items as f64
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

fn min(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::INFINITY, f64::min)
}

/// Interleaved timing (the machine is shared: each round times one short
/// pass of each side back to back, the ratio is the median of per-round
/// ratios, the times shown are the fastest rounds).
fn ratio(els: &[Element], a: &Kernel, b: &Kernel) -> (f64, f64, f64) {
    const ROUNDS: usize = 101;
    const PASSES: usize = 4;
    let n = els.len() * PASSES;
    let (mut ta, mut tb) = (Vec::new(), Vec::new());
    for round in 0..ROUNDS {
        let run = |k: &Kernel| {
            once_ns(n, &mut || {
                for _ in 0..PASSES {
                    black_box(els.iter().map(|el| k(black_box(el))).sum::<f64>());
                }
            })
        };
        // Alternate which side goes first.
        if round % 2 == 0 {
            ta.push(run(a));
            tb.push(run(b));
        } else {
            tb.push(run(b));
            ta.push(run(a));
        }
    }
    let mut r: Vec<f64> = ta.iter().zip(&tb).map(|(x, y)| x / y).collect();
    (min(&ta), min(&tb), median(&mut r))
}

fn ratio_table(els: &[Element]) {
    println!("\n== generated vs hand-written: ns per element, interleaved, same run ==");
    println!(
        "{:<22} {:>14} {:>14} {:>8}   {:>14} {:>14} {:>8}",
        "energy",
        "tet_eval gen",
        "tet_eval hand",
        "ratio",
        "spectral gen",
        "spectral hand",
        "ratio"
    );
    let mut worst: f64 = 0.0;
    for p in pairs() {
        let ((g, gs), (h, hs)) = ((p.generated)(), (p.hand)());
        let (tg, th, r) = ratio(els, &g, &h);
        let (sg, sh, rs) = ratio(els, &gs, &hs);
        worst = worst.max(r);
        println!(
            "{:<22} {:>11.1} ns {:>11.1} ns {:>7.3}×   {:>11.1} ns {:>11.1} ns {:>7.3}×",
            p.name, tg, th, r, sg, sh, rs
        );
    }
    println!(
        "target generated ≤ 1.1× hand-written (tet_eval, Filter::Clamp, Hessian): worst median ratio {worst:.3}× → {}",
        if worst <= 1.1 { "met" } else { "NOT met" }
    );
}

fn main() {
    let els = batch();
    sanity(&els);
    let mut c = Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .configure_from_args();
    criterion_groups(&mut c, &els);
    c.final_summary();
    ratio_table(&els);
}
