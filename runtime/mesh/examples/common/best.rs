//! The timing helper of the `setup_timing` and `write_timing` examples
//! (included by `#[path]`; not an example itself).

use std::time::Instant;

/// Runs per measurement; the best is reported.
pub const REPEATS: usize = 3;

/// The fastest of [`REPEATS`] runs of `f` (seconds) and the last result.
pub fn best<T>(mut f: impl FnMut() -> T) -> (f64, T) {
    let mut out = None;
    let mut t_best = f64::INFINITY;
    for _ in 0..REPEATS {
        let t = Instant::now();
        let r = f();
        t_best = t_best.min(t.elapsed().as_secs_f64());
        out = Some(r);
    }
    (t_best, out.expect("REPEATS > 0"))
}
