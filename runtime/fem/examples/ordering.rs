//! Fill, flops and numeric factorisation time of the sparse Cholesky per
//! fill-reducing ordering and thread policy, on the Newton pattern of a mesh
//! (2 unknowns per vertex for a triangle mesh: the parameterisation; 3 for a
//! tet mesh). The values are a diagonally dominant matrix on that pattern
//! (factor time depends on the structure only).
//!
//! `cargo run --release -p ecc-fem [--features metis] --example ordering -- MESH|disk:RINGS [REPEATS]`
//!
//! Prints one markdown row per (ordering, thread policy): n, nnz(L), flops,
//! supernodes, the widest one, analysis time and the best numeric
//! factorisation time of REPEATS (default 3) for one thread (`sequential`)
//! and two (`parallel`; run with RAYON_NUM_THREADS=2), alternating so the
//! machine's load hits both alike, and the mean time of REPEATS
//! factorisations under the `auto` policy after its two probes.
//!
//! `ordering MESH|disk:RINGS REPEATS --split [ORDERING]` (run with
//! RAYON_NUM_THREADS=2) compares instead, per factorisation, the plain
//! sequential factor (ORDERING, default: the default ordering) on one thread (a 1-thread pool)
//! and in the 2-thread pool with the two-way split ([`ThreadPolicy::Split`])
//! in the 2-thread pool, and the split in the 1-thread pool (its halves one
//! after the other): best of REPEATS, the four alternating. From the last,
//! the best time of each phase (half 1, half 2, Schur complement + dense
//! factor) and the projected two-thread time max(half) + dense, which the
//! load of a shared machine does not distort. Then one solve each (plain
//! 1T, split 2T) and the largest difference between their solutions.

use std::sync::Arc;
use std::time::Instant;

use ecc_fem::linear::cholesky::{CholeskyFactor, CholeskyParams, ThreadPolicy};
use ecc_fem::linear::ordering::{Coordinates, FillOrdering};
use ecc_fem::{Assembler, DofMap, Elastic, Pattern, Term};
use ecc_mesh::{AnyMesh, read_mesh};
use ecc_runtime::energies::{StableNeoHookean, SymmetricDirichlet};

/// The vertex of every unknown, in the assembler's (renumbered) order.
fn vertex_of<const D: usize>(a: &Assembler<D>) -> impl Iterator<Item = usize> + '_ {
    let dofs = a.dofs();
    (0..dofs.n_unknowns()).map(move |u| dofs.dof(u) / D)
}

/// The Newton pattern of the mesh and the position of every unknown (for
/// the `geometric` ordering).
fn pattern(spec: &str) -> Result<(Pattern, Coordinates), String> {
    let mesh = match spec.strip_prefix("disk:") {
        Some(rings) => {
            let rings = rings.parse().map_err(|e| format!("{spec}: {e}"))?;
            AnyMesh::Tri(ecc_mesh::disk_tri(rings, 1.0))
        }
        None => read_mesh(spec).map_err(|e| e.to_string())?,
    };
    let (p, coords) = match mesh {
        AnyMesh::Tri(m) => {
            let term = Elastic::surface(Arc::new(SymmetricDirichlet), &m.positions, &m.triangles)
                .map_err(|e| e.to_string())?;
            let terms: Vec<Box<dyn Term<2>>> = vec![Box::new(term)];
            let dofs = DofMap::all_free(m.positions.len(), 2).map_err(|e| e.to_string())?;
            let a = Assembler::new(&terms, dofs).map_err(|e| e.to_string())?;
            let v = vertex_of(&a);
            (a.pattern().clone(), v.map(|v| m.positions[v]).collect())
        }
        AnyMesh::Tet(m) => {
            let term = Elastic::new(
                Arc::new(StableNeoHookean::new(1.0, 1.0)),
                &m.positions,
                &m.tets,
            )
            .map_err(|e| e.to_string())?;
            let terms: Vec<Box<dyn Term<3>>> = vec![Box::new(term)];
            let dofs = DofMap::all_free(m.positions.len(), 3).map_err(|e| e.to_string())?;
            let a = Assembler::new(&terms, dofs).map_err(|e| e.to_string())?;
            let v = vertex_of(&a);
            (a.pattern().clone(), v.map(|v| m.positions[v]).collect())
        }
    };
    Ok((p, coords))
}

/// Off-diagonals −1, diagonal = 1 + number of off-diagonals in the row: SPD.
fn values(p: &Pattern) -> Vec<f64> {
    let n = p.n();
    let mut deg = vec![1.0; n];
    let mut v = vec![-1.0; p.nnz()];
    for j in 0..n {
        for (k, &i) in p.row_idx()[p.col_ptr()[j]..p.col_ptr()[j + 1]]
            .iter()
            .enumerate()
        {
            if i != j {
                deg[i] += 1.0;
                deg[j] += 1.0;
            } else {
                v[p.col_ptr()[j] + k] = 0.0;
            }
        }
    }
    for j in 0..n {
        v[p.diag_slot(j)] = deg[j];
    }
    v
}

/// Best of `repeats` of `f` for each closure, alternating.
fn best_of(repeats: usize, fs: &mut [&mut dyn FnMut()]) -> Vec<f64> {
    let mut best = vec![f64::INFINITY; fs.len()];
    for _ in 0..repeats {
        for (f, b) in fs.iter_mut().zip(&mut best) {
            let t = Instant::now();
            f();
            *b = b.min(t.elapsed().as_secs_f64());
        }
    }
    best
}

/// The `--split` comparison (see the module docs).
fn split_row(
    spec: &str,
    (p, coords): (&Pattern, &Coordinates),
    v: &[f64],
    repeats: usize,
    ordering: FillOrdering,
) {
    let analyze = |params| CholeskyFactor::analyze_at(p, params, Some(coords.clone())).unwrap();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let seq_params = CholeskyParams {
        ordering,
        threads: ThreadPolicy::Sequential,
        ..Default::default()
    };
    let t = Instant::now();
    let mut seq1 = one.install(|| analyze(seq_params));
    let t_seq = t.elapsed().as_secs_f64();
    let mut seq2 = analyze(seq_params);
    let t = Instant::now();
    let split_params = CholeskyParams {
        ordering,
        threads: ThreadPolicy::Split,
        ..Default::default()
    };
    let mut split = analyze(split_params);
    let t_split = t.elapsed().as_secs_f64();
    let mut split1 = analyze(split_params);
    let Some((k, critical)) = split.split() else {
        println!("{spec}: not split (flops {:.3e})", split.factor_flops());
        return;
    };
    // phases of the split run on one thread (halves one after the other):
    // best of each, for the projected critical path max(half) + dense
    let mut phases = [f64::INFINITY; 4];
    let fac = best_of(
        repeats,
        &mut [
            &mut || one.install(|| seq1.factorize(p, v).unwrap()),
            &mut || seq2.factorize(p, v).unwrap(),
            &mut || split.factorize(p, v).unwrap(),
            &mut || {
                one.install(|| split1.factorize(p, v).unwrap());
                let ph = split1.split_phases().unwrap();
                phases.iter_mut().zip(ph).for_each(|(b, t)| *b = b.min(t));
            },
        ],
    );
    let projected = phases[0].max(phases[1]) + phases[3];
    let rhs: Vec<f64> = (0..p.n()).map(|i| (0.3 * i as f64).cos()).collect();
    let (mut x1, mut x2) = (rhs.clone(), rhs.clone());
    let sol = best_of(
        repeats,
        &mut [
            &mut || {
                x1.copy_from_slice(&rhs);
                one.install(|| assert!(seq1.solve_in_place(&mut x1)));
            },
            &mut || {
                x2.copy_from_slice(&rhs);
                assert!(split.solve_in_place(&mut x2));
            },
        ],
    );
    let scale = x1.iter().fold(0.0f64, |m, a| m.max(a.abs()));
    let diff = x1
        .iter()
        .zip(&x2)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    println!(
        "| {spec} | {} | {} | {:.3e} | {:.3e} | {:.3e} | {k} | {t_seq:.3} | {t_split:.3} | {:.4} | {:.4} | {:.4} | {:.2} | {:.4} | {:.4} {:.4} {:.4} | {:.4} | {:.2} | {:.4} | {:.4} | {:.1e} |",
        p.n(),
        ordering.name(),
        seq1.factor_flops(),
        split.factor_flops(),
        critical,
        fac[0],
        fac[1],
        fac[2],
        fac[0] / fac[2],
        fac[3],
        phases[0],
        phases[1],
        phases[3],
        projected,
        fac[0] / projected,
        sol[0],
        sol[1],
        diff / scale,
    );
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(spec) = args.first() else {
        eprintln!("usage: ordering MESH|disk:RINGS [REPEATS]");
        std::process::exit(2);
    };
    let repeats: usize = args.get(1).and_then(|r| r.parse().ok()).unwrap_or(3);
    let (p, coords) = match pattern(spec) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    };
    let v = values(&p);
    if let Some(at) = args.iter().position(|a| a == "--split") {
        let ordering = args
            .get(at + 1)
            .and_then(|o| FillOrdering::from_name(o))
            .unwrap_or_default();
        split_row(spec, (&p, &coords), &v, repeats, ordering);
        return;
    }
    println!(
        "{spec}: n = {}, nnz(A upper) = {}, rayon threads = {}",
        p.n(),
        p.nnz(),
        rayon::current_num_threads()
    );
    println!(
        "| ordering | nnz(L) | flops | supernodes | widest | analysis s | factor s (1T) | factor s (2T) |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for ordering in FillOrdering::ALL.into_iter().filter(|o| o.is_available()) {
        let mk = |threads| {
            let t = Instant::now();
            let params = CholeskyParams {
                ordering,
                threads,
                ..Default::default()
            };
            let f = CholeskyFactor::analyze_at(&p, params, Some(coords.clone())).unwrap();
            (f, t.elapsed().as_secs_f64())
        };
        let (mut seq, t_an) = mk(ThreadPolicy::Sequential);
        let (mut par, _) = mk(ThreadPolicy::Parallel);
        let (mut best_seq, mut best_par) = (f64::INFINITY, f64::INFINITY);
        for _ in 0..repeats {
            for (f, best) in [(&mut seq, &mut best_seq), (&mut par, &mut best_par)] {
                let t = Instant::now();
                f.factorize(&p, &v).unwrap();
                *best = best.min(t.elapsed().as_secs_f64());
            }
        }
        let rhs: Vec<f64> = (0..p.n()).map(|i| (0.3 * i as f64).cos()).collect();
        let (mut xs, mut xp) = (rhs.clone(), rhs);
        assert!(seq.solve_in_place(&mut xs) && par.solve_in_place(&mut xp));
        let same = xs.iter().zip(&xp).all(|(a, b)| a.to_bits() == b.to_bits());
        eprintln!(
            "{}: 1T and 2T solutions bitwise equal: {same}",
            ordering.name()
        );
        drop((seq, par));
        let (mut auto, _) = mk(ThreadPolicy::Auto);
        for _ in 0..2 {
            auto.factorize(&p, &v).unwrap();
        }
        let t = Instant::now();
        for _ in 0..repeats {
            auto.factorize(&p, &v).unwrap();
        }
        let t_auto = t.elapsed().as_secs_f64() / repeats as f64;
        let (ns, widest) = auto.supernodes().unwrap_or((0, 0));
        println!(
            "| {} | {} | {:.3e} | {ns} | {widest} | {t_an:.3} | {best_seq:.4} | {best_par:.4} | {t_auto:.4} |",
            ordering.name(),
            auto.factor_nnz(),
            auto.factor_flops(),
        );
    }
}
