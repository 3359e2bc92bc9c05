//! Whether a numeric factorisation runs on one thread, on rayon's pool, or
//! as two halves of a separator on two threads.
//!
//! faer's supernodal LLᵀ walks the supernodes one after the other and hands
//! its `Par` to the dense kernels of each supernode (the update products, the
//! dense Cholesky of the diagonal block, the triangular solve). On mesh
//! matrices most supernodes are a few columns wide, so with two threads the
//! time goes into fork/join and waking the other worker per kernel, and
//! [`ThreadPolicy::Parallel`] was slower than one thread on every mesh
//! measured, 2D and 3D, AMD and METIS, up to a 1M-triangle disk
//! (docs/benchmarks/ordering.md).
//!
//! The default is [`ThreadPolicy::Split`]: tree-level parallelism, decided
//! from the symbolic analysis alone (`tree.rs`), which falls back to the
//! sequential factorisation whenever the split is not estimated to pay, so
//! two threads are never slower than one by construction of the estimate,
//! and the bits are the same run to run for a given number of threads. On a
//! quiet machine it made the whole Newton solve 1.6–1.9× faster on two
//! threads than on one (camelhead, armadillo_cut_low; threads.md).
//!
//! [`ThreadPolicy::Auto`] (opt-in) measures instead: the first factorisation
//! of a pattern runs sequentially, the second in parallel, and the faster
//! one is used from then on, measured again every [`REPROBE_EVERY`]
//! factorisations. It adapts to the machine but is not bitwise
//! reproducible. A simplicial factor (faer ignores `Par` there) and a
//! one-thread pool are always sequential.

use faer::Par;
use serde::{Deserialize, Serialize};

/// Whether the numeric factorisation and the solves use rayon's threads.
/// The names (`"auto"`, `"sequential"`, `"parallel"`, `"split"`) are stable.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ThreadPolicy {
    /// Time one sequential and one parallel factorisation, keep the faster
    /// (see the module docs; not bitwise reproducible).
    Auto,
    /// Always one thread.
    Sequential,
    /// Always all threads of the current rayon pool.
    Parallel,
    /// Tree-level parallelism: the two halves of a vertex separator are
    /// factorised concurrently, each on one thread, and the separator densely
    /// (`split.rs`), when the pool has at least two threads at the symbolic
    /// analysis, the factorisation is large enough to pay
    /// ([`super::SPLIT_MIN_FLOPS`]) and the split's estimated critical path
    /// is at most 0.9 of the plain factorisation's flops (`tree.rs`);
    /// otherwise as [`ThreadPolicy::Sequential`]. Decided from the symbolic
    /// analysis alone, and the same bits run to run for a given number of
    /// threads. The default.
    #[default]
    Split,
}

/// [`ThreadPolicy::Auto`] times both modes again after this many
/// factorisations (the load of a shared machine changes).
pub const REPROBE_EVERY: usize = 32;

impl ThreadPolicy {
    /// Every policy.
    pub const ALL: [ThreadPolicy; 4] = [
        ThreadPolicy::Auto,
        ThreadPolicy::Sequential,
        ThreadPolicy::Parallel,
        ThreadPolicy::Split,
    ];

    /// The stable name.
    pub fn name(self) -> &'static str {
        match self {
            ThreadPolicy::Auto => "auto",
            ThreadPolicy::Sequential => "sequential",
            ThreadPolicy::Parallel => "parallel",
            ThreadPolicy::Split => "split",
        }
    }

    /// The policy with this stable name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }
}

/// Per-factor state of a [`ThreadPolicy`]: the last measured time of a
/// sequential and of a parallel factorisation.
#[derive(Clone, Debug)]
pub(crate) struct ThreadChooser {
    policy: ThreadPolicy,
    /// Supernodal factor (faer's simplicial factorisation ignores `Par`).
    supernodal: bool,
    seq: Option<f64>,
    par: Option<f64>,
    recorded: usize,
}

impl ThreadChooser {
    pub(crate) fn new(policy: ThreadPolicy, supernodal: bool) -> Self {
        ThreadChooser {
            policy,
            supernodal,
            seq: None,
            par: None,
            recorded: 0,
        }
    }

    /// The parallelism for the next numeric factorisation (sequential in a
    /// one-thread pool, whatever the policy).
    pub(crate) fn next(&self) -> Par {
        let parallel = self.supernodal
            && rayon::current_num_threads() > 1
            && match self.policy {
                // a split factor does not ask; without one, it is sequential
                ThreadPolicy::Sequential | ThreadPolicy::Split => false,
                ThreadPolicy::Parallel => true,
                ThreadPolicy::Auto => match (self.seq, self.par) {
                    (None, _) => false,
                    (Some(_), None) => true,
                    (Some(s), Some(p)) => p < s,
                },
            };
        if parallel { Par::rayon(0) } else { Par::Seq }
    }

    /// Record that a successful factorisation with `par` took `secs`.
    pub(crate) fn record(&mut self, par: Par, secs: f64) {
        match par {
            Par::Seq => self.seq = Some(secs),
            _ => self.par = Some(secs),
        }
        self.recorded += 1;
        if self.recorded.is_multiple_of(REPROBE_EVERY) {
            self.seq = None;
            self.par = None;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn is_seq(p: Par) -> bool {
        matches!(p, Par::Seq)
    }

    #[test]
    fn names_round_trip() {
        for p in ThreadPolicy::ALL {
            assert_eq!(ThreadPolicy::from_name(p.name()), Some(p));
            assert_eq!(
                serde_json::to_string(&p).unwrap(),
                format!("\"{}\"", p.name())
            );
        }
        assert_eq!(ThreadPolicy::from_name("2"), None);
    }

    /// Runs `f` in a pool of `n` threads.
    fn in_pool<R: Send>(n: usize, f: impl FnOnce() -> R + Send) -> R {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap()
            .install(f)
    }

    #[test]
    fn auto_probes_both_then_keeps_the_faster_and_probes_again() {
        in_pool(2, || {
            let mut c = ThreadChooser::new(ThreadPolicy::Auto, true);
            assert!(is_seq(c.next()), "first: sequential");
            c.record(c.next(), 1.0);
            assert!(!is_seq(c.next()), "second: parallel");
            c.record(c.next(), 2.0);
            for _ in 2..REPROBE_EVERY {
                assert!(is_seq(c.next()), "sequential was faster");
                c.record(c.next(), 1.0);
            }
            assert!(is_seq(c.next()), "re-probe starts sequential");
            c.record(c.next(), 3.0);
            assert!(!is_seq(c.next()));
            c.record(c.next(), 1.5);
            assert!(!is_seq(c.next()), "now parallel is faster");
        });
    }

    #[test]
    fn fixed_policies_and_the_cases_where_threads_cannot_matter() {
        in_pool(2, || {
            assert!(!is_seq(
                ThreadChooser::new(ThreadPolicy::Parallel, true).next()
            ));
            assert!(is_seq(
                ThreadChooser::new(ThreadPolicy::Sequential, true).next()
            ));
            let mut simplicial = ThreadChooser::new(ThreadPolicy::Parallel, false);
            assert!(is_seq(simplicial.next()));
            simplicial.record(Par::Seq, 1.0);
            assert!(is_seq(simplicial.next()));
        });
        in_pool(1, || {
            let mut c = ThreadChooser::new(ThreadPolicy::Auto, true);
            c.record(c.next(), 1.0);
            assert!(is_seq(c.next()), "one thread: never parallel");
        });
    }
}
