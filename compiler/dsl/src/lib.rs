//! ecc-dsl: the energy language front end and the hand-rolled CAS.
//!
//! A user types an isotropic energy density Ψ as a formula in the invariants
//! I1 = tr S, I2 = ‖F‖², I3 = det F (or the principal stretches s1..s3);
//! this crate parses it, checks it, and derives exact, simplified symbolic
//! derivatives and stretch-space eigen data that code generation, the
//! run-time interpreter and the solver consume. The language is documented in
//! `compiler/dsl/LANGUAGE.md`; the standard library of energies is `energies/psi/*.psi`.
//!
//! ```
//! let src = "param mu = 1.0\nparam lambda = 10.0\n\
//!            psi = mu/2*(IC - d) - mu*log(J) + lambda/2*log(J)^2";
//! let module = ecc_dsl::compile(src, "neohookean").map_err(|d| d.render("neohookean", src)).unwrap();
//! let ir = module.dim(3).unwrap();
//! assert!(ir.barrier && ir.svd_free && !ir.decoupled);
//! let env = ecc_dsl::Env::new(3, &[1.0, 1.0, 1.0], &module.param_defaults());
//! assert_eq!(ecc_dsl::eval(&ir.graph, ir.psi, &env), 0.0); // rest state
//! assert_eq!(ir.graph.to_text(ir.d_inv.as_ref().unwrap().d1[2]), "lambda*log(I3)/I3 - mu/I3");
//! ```
//!
//! # Pipeline
//!
//! * [`front`]: statements are cut at newlines/`;` and parsed one by one with
//!   a pest grammar into an AST with byte spans; names are resolved (with
//!   suggestions for typos) and the program is lowered into the CAS per
//!   dimension, rewriting the Cauchy–Green aliases (Smith et al. 2019, App. A).
//! * [`cas`]: a hash-consed expression DAG ([`Graph`], children before
//!   parents, one `add()` that dedups) with canonicalising constructors over
//!   exact rationals, a deterministic printer, differentiation, substitution
//!   and an f64 evaluator ([`eval`], [`Tape`]).
//! * [`poly`]: sparse multivariate polynomials over ℚ and rational functions
//!   in σ; exact identity tests ([`Proof`]) and exact division by σi ± σj.
//! * [`compile`](mod@compile): builds the [`DimIr`] of each dimension — the
//!   invariant path (Smith et al. 2019, eqs. 22–27 and App. D) or the stretch
//!   path (Zhu 2020) — and proves what it can (decoupled scaling modes, sign
//!   symmetry, isotropy, barrier) to specialise the [`SpectralIr`].
//! * [`diag`]: every error carries a span; [`Diagnostics::render`] prints them
//!   all, compiler-style, with codespan-reporting.
//! * [`testing`]: parser-backed helpers so CAS tests are one-liners.
//!
//! # Guarantees
//!
//! Nothing panics on any input; expression blow-ups are bounded (the
//! polynomial machinery answers "unknown" beyond [`poly::MAX_TERMS`] terms).
//! Compiling any standard-library energy for all its dimensions takes a few
//! milliseconds to ~20 ms in a release build (`examples/compile_times.rs`).

pub mod cas;
pub mod compile;
pub mod diag;
pub mod front;
pub mod ir;
pub mod load;
pub mod poly;
pub mod span;
pub mod testing;

pub use cas::{Env, Graph, Id, Node, Sym, Tape, eval, eval_many, sign_i4};
pub use compile::{compile, compile_dim, slot_pairs};
pub use diag::{Diagnostics, Error};
pub use ir::{
    DimIr, DomainCond, DomainGuard, FibreIr, FibreUses, InvariantDerivs, Module, PairIr, PairKind,
    ParamDecl, Path, ScaleIr, SpectralIr,
};
pub use load::{LoadError, Source, energy_name, load_file, load_text};
pub use poly::Proof;
pub use span::Span;
