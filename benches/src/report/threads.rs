//! One thread against two, measured in interleaved rounds.
//!
//! A single pair of solves is at the mercy of whatever else the machine did
//! in those seconds, and of which solve ran first in a cold process: the
//! same commit gave camelhead 1.21×, 1.29× and 1.34× in three reports, and
//! 1.19×, 1.74×, 1.79× in three back-to-back pairs. So the pair
//! ([`SolveMethod::Defaults`] on the pool's two threads,
//! [`SolveMethod::DefaultsOneThread`] in a one-thread pool) runs `rounds`
//! times, alternating which goes first (ABBA…, so a drift in the machine's
//! speed falls on both), and the report gives each method's fastest round
//! and the **median of the per-round ratios** t₁/t₂ (time to ‖∇E‖∞ ≤ 1e-4),
//! with every round's ratio beside it.

use serde::Serialize;

use crate::solve::{SolveMethod, Trace};

/// The tolerance the ratios are taken at (the report's).
const TOL: f64 = 1e-4;

/// The rounds of one problem: times to [`TOL`] on one and on two threads,
/// round by round (`None`: that round did not reach it).
#[derive(Clone, Debug, Default, Serialize)]
pub struct ThreadRounds {
    pub problem: String,
    pub one: Vec<Option<f64>>,
    pub two: Vec<Option<f64>>,
}

impl ThreadRounds {
    /// The per-round ratios t₁/t₂ of the rounds where both reached [`TOL`].
    pub fn ratios(&self) -> Vec<f64> {
        self.one
            .iter()
            .zip(&self.two)
            .filter_map(|(a, b)| Some((*a)? / (*b)?))
            .collect()
    }

    /// The median of [`Self::ratios`] (the mean of the middle two for an
    /// even count); `None` without a complete round.
    pub fn median_ratio(&self) -> Option<f64> {
        median(self.ratios())
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

/// The methods of round `k`, in the order they run: two threads first in
/// even rounds, one thread first in odd ones.
pub fn round_order(k: usize) -> [SolveMethod; 2] {
    let pair = [SolveMethod::Defaults, SolveMethod::DefaultsOneThread];
    if k.is_multiple_of(2) {
        pair
    } else {
        [pair[1], pair[0]]
    }
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

/// Record a round's trace of `method` into `rounds`.
pub fn push_round(rounds: &mut ThreadRounds, method: SolveMethod, t: Option<&Trace>) {
    let time = t.and_then(|t| t.time_to(TOL));
    match method {
        SolveMethod::DefaultsOneThread => rounds.one.push(time),
        _ => rounds.two.push(time),
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
    fn the_ratio_is_the_median_of_complete_rounds() {
        let r = ThreadRounds {
            problem: "p".into(),
            one: vec![Some(1.2), Some(1.0), None, Some(3.0)],
            two: vec![Some(1.0), Some(0.5), Some(1.0), Some(1.0)],
        };
        assert_eq!(r.ratios(), vec![1.2, 2.0, 3.0]);
        assert_eq!(r.median_ratio(), Some(2.0));
        assert_eq!(median(vec![1.0, 4.0]), Some(2.5));
        assert_eq!(ThreadRounds::default().median_ratio(), None);
    }

    #[test]
    fn rounds_alternate_which_runs_first() {
        assert_eq!(round_order(0)[0], SolveMethod::Defaults);
        assert_eq!(round_order(1)[0], SolveMethod::DefaultsOneThread);
        assert_eq!(round_order(2), round_order(0));
        assert_ne!(round_order(0)[1], round_order(0)[0]);
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
        let mut r = ThreadRounds::default();
        push_round(
            &mut r,
            SolveMethod::DefaultsOneThread,
            Some(&trace(m, Some(2.0), 2.0)),
        );
        push_round(&mut r, SolveMethod::Defaults, None);
        assert_eq!((r.one, r.two), (vec![Some(2.0)], vec![None]));
    }
}
