//! Time ecc's sparse Cholesky (faer through `ecc_fem`'s `CholeskyFactor`)
//! on a Matrix Market file written by `export_hessians`: the counterpart of
//! benches/cholmod/cholmod_bench.c (same JSON shape, one line per run).
//!
//! ```text
//! cargo run --release -p ecc-benches --features metis --bin factor_bench -- FILE.mtx [--repeats R] [--pool T] [--ordering NAME]… [--threads NAME]…
//! ```
//!
//! For every fill-reducing ordering compiled in that needs no vertex
//! positions (`FillOrdering::ALL` but `geometric`, or the `--ordering` ones) the symbolic analysis is done once per thread
//! policy (`ThreadPolicy::ALL`, or the `--threads` ones), then each factor
//! is factorised twice untimed (warm-up; the `auto` policy's two probes)
//! and R times timed (default 5), the policies taking turns so the load of
//! a shared machine hits them alike. Everything runs in a rayon pool of T
//! threads (default 2): `sequential` is ecc's one-thread factorisation,
//! `parallel` faer's `Par::rayon` on the pool's T threads.
//!
//! Reported: nnz(A) (stored lower triangle, as CHOLMOD counts it), nnz(L)
//! (faer's stored values, supernodal blocks included), flops Σ_j c_j² over
//! the column counts of L (CHOLMOD's `Common->fl` is the same sum), the
//! analysis time, best and mean factorisation time, the 1-minute load.

use std::fs::File;
use std::io::BufReader;
use std::time::Instant;

use ecc_benches::mtx;
use ecc_fem::Pattern;
use ecc_fem::linear::cholesky::{CholeskyFactor, CholeskyParams, ThreadPolicy};
use ecc_fem::linear::ordering::FillOrdering;

struct Args {
    file: String,
    repeats: usize,
    pool: usize,
    orderings: Vec<FillOrdering>,
    threads: Vec<ThreadPolicy>,
}

const USAGE: &str = "usage: factor_bench FILE.mtx [--repeats R] [--pool T] [--ordering amd|block-amd|metis]… [--threads sequential|parallel|auto]…";

fn args() -> Result<Args, String> {
    let mut a = Args {
        file: String::new(),
        repeats: 5,
        pool: 2,
        orderings: Vec::new(),
        threads: Vec::new(),
    };
    let mut it = std::env::args().skip(1);
    while let Some(x) = it.next() {
        let mut value = |flag: &str| it.next().ok_or(format!("{flag} needs a value"));
        let count = |flag: &str, v: String| match v.parse::<usize>() {
            Ok(k) if k > 0 => Ok(k),
            _ => Err(format!("{flag}: `{v}` is not a positive integer")),
        };
        match x.as_str() {
            "--repeats" => a.repeats = count("--repeats", value("--repeats")?)?,
            "--pool" => a.pool = count("--pool", value("--pool")?)?,
            "--ordering" => {
                let v = value("--ordering")?;
                let o = FillOrdering::from_name(&v).ok_or(format!("unknown ordering `{v}`"))?;
                if !o.is_available() {
                    return Err(format!("ordering `{v}` needs --features metis"));
                }
                a.orderings.push(o);
            }
            "--threads" => {
                let v = value("--threads")?;
                a.threads.push(
                    ThreadPolicy::from_name(&v).ok_or(format!("unknown thread policy `{v}`"))?,
                );
            }
            f if a.file.is_empty() && !f.starts_with("--") => a.file = f.into(),
            f => return Err(format!("unexpected argument `{f}`\n{USAGE}")),
        }
    }
    if a.file.is_empty() {
        return Err(USAGE.into());
    }
    if a.orderings.is_empty() {
        // a matrix file has no vertex positions: not `geometric`
        a.orderings = FillOrdering::ALL
            .into_iter()
            .filter(|o| o.is_available() && !o.needs_positions())
            .collect();
    }
    if a.threads.is_empty() {
        a.threads = ThreadPolicy::ALL.to_vec();
    }
    Ok(a)
}

/// The 1-minute load average (Linux), if readable.
fn load() -> Option<f64> {
    std::fs::read_to_string("/proc/loadavg")
        .ok()?
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// One factor under test and its timings.
struct Run {
    policy: ThreadPolicy,
    factor: CholeskyFactor,
    analyze_s: f64,
    times: Vec<f64>,
}

fn factorize(f: &mut CholeskyFactor, p: &Pattern, v: &[f64]) -> Result<f64, String> {
    let t = Instant::now();
    f.factorize(p, v)
        .map_err(|e| format!("factorisation failed: {e:?}"))?;
    Ok(t.elapsed().as_secs_f64())
}

/// Analyse once per policy, warm up twice, then R timed rounds in turn.
fn time_ordering(
    a: &Args,
    p: &Pattern,
    v: &[f64],
    ordering: FillOrdering,
) -> Result<Vec<Run>, String> {
    let mut runs = Vec::new();
    for &policy in &a.threads {
        let t = Instant::now();
        let factor = CholeskyFactor::analyze_with(
            p,
            CholeskyParams {
                ordering,
                threads: policy,
                ..Default::default()
            },
        )
        .map_err(|e| e.to_string())?;
        runs.push(Run {
            policy,
            factor,
            analyze_s: t.elapsed().as_secs_f64(),
            times: Vec::new(),
        });
    }
    for r in &mut runs {
        for _ in 0..2 {
            factorize(&mut r.factor, p, v)?;
        }
    }
    for _ in 0..a.repeats {
        for r in &mut runs {
            let s = factorize(&mut r.factor, p, v)?;
            r.times.push(s);
        }
    }
    Ok(runs)
}

fn line(a: &Args, m: &mtx::UpperCsc, ordering: FillOrdering, r: &Run) -> serde_json::Value {
    let best = r.times.iter().copied().fold(f64::INFINITY, f64::min);
    let mean = r.times.iter().sum::<f64>() / r.times.len() as f64;
    let f = &r.factor;
    serde_json::json!({
        "solver": "ecc-faer",
        "matrix": a.file,
        "n": m.n,
        "nnz_a": m.row_idx.len(),
        "ordering": ordering.name(),
        "threads": r.policy.name(),
        "pool_threads": a.pool,
        "parallel_last": f.is_parallel(),
        "supernodal": f.is_supernodal(),
        "nnz_l": f.factor_nnz(),
        "flops": f.factor_flops(),
        "split_separator": f.split().map(|s| s.0),
        "critical_flops": f.split().map(|s| s.1),
        "analyze_s": r.analyze_s,
        "factor_best_s": best,
        "factor_mean_s": mean,
        "repeats": r.times.len(),
        "load1": load(),
    })
}

fn run() -> Result<(), String> {
    let a = args()?;
    let file = File::open(&a.file).map_err(|e| format!("{}: {e}", a.file))?;
    let m = mtx::read(BufReader::new(file)).map_err(|e| format!("{}: {e}", a.file))?;
    let p = Pattern::from_upper_csc(m.n, m.col_ptr.clone(), m.row_idx.clone())
        .map_err(|e| format!("{}: {e}", a.file))?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(a.pool)
        .build()
        .map_err(|e| e.to_string())?;
    pool.install(|| {
        for &ordering in &a.orderings {
            let runs = time_ordering(&a, &p, &m.values, ordering)?;
            for r in &runs {
                println!("{}", line(&a, &m, ordering, r));
            }
        }
        Ok(())
    })
}

fn main() {
    if let Err(e) = run() {
        eprintln!("factor_bench: {e}");
        std::process::exit(1);
    }
}
