//! The report's headline ratios, measured in interleaved rounds.
//!
//! A single solve is at the mercy of whatever else the machine did in those
//! seconds, and of which solve ran first in a cold process: the same commit
//! gave camelhead's one-thread/two-thread ratio 1.21×, 1.29× and 1.34× in
//! three reports, and 1.19×, 1.74×, 1.79× in three back-to-back pairs; its
//! autodiff/defaults ratio 4.02× in one report and 2.69× in the next
//! (3.6–3.8× in three back-to-back pairs). So the methods behind the
//! issue's criteria — [`SolveMethod::Defaults`] on the pool's two threads,
//! [`SolveMethod::DefaultsOneThread`] in a one-thread pool and
//! [`SolveMethod::Autodiff`] — run `rounds` times, the order rotating from
//! round to round (so a drift in the machine's speed, and the cold first
//! solve, fall on each in turn). The report gives each method's fastest
//! round and, for each ratio to the defaults, the **median of the
//! per-round ratios** (time to ‖∇E‖∞ ≤ 1e-4), with every round's ratio
//! beside it. A method that fails to set up (no autodiff form) is not
//! retried.

use serde::Serialize;

use crate::solve::{SolveMethod, Trace};

/// The tolerance the ratios are taken at (the report's).
const TOL: f64 = 1e-4;

/// The methods run in rounds; the first is the reference of the ratios.
pub const PAIRED: [SolveMethod; 3] = [
    SolveMethod::Defaults,
    SolveMethod::DefaultsOneThread,
    SolveMethod::Autodiff,
];

/// The rounds of one problem: times to [`TOL`] of each method of
/// [`PAIRED`], round by round (`None`: that round did not reach it or did
/// not run).
#[derive(Clone, Debug, Default, Serialize)]
pub struct Rounds {
    pub problem: String,
    pub defaults: Vec<Option<f64>>,
    pub one_thread: Vec<Option<f64>>,
    pub autodiff: Vec<Option<f64>>,
}

impl Rounds {
    /// An empty record for `problem`.
    pub fn new(problem: &str) -> Self {
        Rounds {
            problem: problem.into(),
            ..Default::default()
        }
    }

    fn column(&self, m: SolveMethod) -> &[Option<f64>] {
        match m {
            SolveMethod::DefaultsOneThread => &self.one_thread,
            SolveMethod::Autodiff => &self.autodiff,
            _ => &self.defaults,
        }
    }

    /// Number of rounds run.
    pub fn len(&self) -> usize {
        self.defaults.len()
    }

    /// Whether no round ran.
    pub fn is_empty(&self) -> bool {
        self.defaults.is_empty()
    }

    /// The per-round ratios t_m / t_defaults of the rounds where both
    /// reached [`TOL`].
    pub fn ratios(&self, m: SolveMethod) -> Vec<f64> {
        self.column(m)
            .iter()
            .zip(&self.defaults)
            .filter_map(|(a, b)| Some((*a)? / (*b)?))
            .collect()
    }

    /// The median of [`Self::ratios`]; `None` without a complete round.
    pub fn median_ratio(&self, m: SolveMethod) -> Option<f64> {
        median(self.ratios(m))
    }

    /// Record a round's result of `m` (`None`: it did not run or failed).
    pub fn push(&mut self, m: SolveMethod, t: Option<&Trace>) {
        let time = t.and_then(|t| t.time_to(TOL));
        match m {
            SolveMethod::DefaultsOneThread => self.one_thread.push(time),
            SolveMethod::Autodiff => self.autodiff.push(time),
            _ => self.defaults.push(time),
        }
    }
}

/// The median of `v` (the mean of the middle two for an even length).
pub fn median(mut v: Vec<f64>) -> Option<f64> {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    match n {
        0 => None,
        _ if n % 2 == 1 => Some(v[n / 2]),
        _ => Some(0.5 * (v[n / 2 - 1] + v[n / 2])),
    }
}

/// The methods of round `k` in the order they run: [`PAIRED`] rotated by
/// `k`, so each runs first in turn.
pub fn round_order(k: usize) -> [SolveMethod; 3] {
    let mut order = PAIRED;
    order.rotate_left(k % PAIRED.len());
    order
}

/// Whether `candidate` is a better representative of its method than
/// `kept`: it reached [`TOL`] sooner (or reached it where `kept` did not,
/// or neither did and it ran for less time).
pub fn faster(candidate: &Trace, kept: &Trace) -> bool {
    match (candidate.time_to(TOL), kept.time_to(TOL)) {
        (Some(a), Some(b)) => a < b,
        (Some(_), None) => true,
        (None, Some(_)) => false,
        (None, None) => candidate.seconds_measured < kept.seconds_measured,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trace(method: SolveMethod, reached: Option<f64>, seconds: f64) -> Trace {
        let mut points = vec![crate::solve::Point {
            iter: 0,
            seconds: 0.0,
            grad_inf: 1.0,
            energy: 1.0,
        }];
        if let Some(s) = reached {
            points.push(crate::solve::Point {
                iter: 1,
                seconds: s,
                grad_inf: 1e-5,
                energy: 0.5,
            });
        }
        Trace {
            problem: "p".into(),
            method,
            elements: 1,
            unknowns: 2,
            points,
            status: "Converged".into(),
            seconds_measured: seconds,
        }
    }

    #[test]
    fn a_ratio_is_the_median_of_complete_rounds() {
        let r = Rounds {
            problem: "p".into(),
            defaults: vec![Some(1.0), Some(0.5), Some(1.0), Some(1.0)],
            one_thread: vec![Some(1.2), Some(1.0), None, Some(3.0)],
            autodiff: vec![None, None, None, None],
        };
        assert_eq!(
            r.ratios(SolveMethod::DefaultsOneThread),
            vec![1.2, 2.0, 3.0]
        );
        assert_eq!(r.median_ratio(SolveMethod::DefaultsOneThread), Some(2.0));
        assert_eq!(r.median_ratio(SolveMethod::Autodiff), None);
        assert_eq!(r.median_ratio(SolveMethod::Defaults), Some(1.0));
        assert_eq!(median(vec![1.0, 4.0]), Some(2.5));
        assert_eq!((r.len(), Rounds::new("q").is_empty()), (4, true));
    }

    #[test]
    fn each_method_runs_first_in_turn() {
        let firsts: Vec<SolveMethod> = (0..3).map(|k| round_order(k)[0]).collect();
        assert_eq!(firsts, PAIRED.to_vec());
        assert_eq!(round_order(3), round_order(0));
        for k in 0..3 {
            let mut o = round_order(k).to_vec();
            o.sort_by_key(|m| PAIRED.iter().position(|p| p == m));
            assert_eq!(o, PAIRED.to_vec());
        }
    }

    #[test]
    fn the_kept_trace_is_the_one_that_reached_the_tolerance_soonest() {
        let m = SolveMethod::Defaults;
        assert!(faster(&trace(m, Some(1.0), 2.0), &trace(m, Some(1.5), 1.6)));
        assert!(!faster(
            &trace(m, Some(2.0), 2.0),
            &trace(m, Some(1.5), 1.6)
        ));
        assert!(faster(&trace(m, Some(9.0), 9.0), &trace(m, None, 1.0)));
        assert!(faster(&trace(m, None, 1.0), &trace(m, None, 2.0)));
        let mut r = Rounds::new("p");
        r.push(
            SolveMethod::DefaultsOneThread,
            Some(&trace(m, Some(2.0), 2.0)),
        );
        r.push(SolveMethod::Defaults, None);
        r.push(SolveMethod::Autodiff, Some(&trace(m, None, 2.0)));
        assert_eq!(
            (r.one_thread, r.defaults, r.autodiff),
            (vec![Some(2.0)], vec![None], vec![None])
        );
    }
}
