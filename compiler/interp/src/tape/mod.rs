//! A flat register program ("tape") compiled once from an expression DAG.
//!
//! # Register file
//!
//! ```text
//! [ σ0 σ1 σ2 I1 I2 I3 | frozen block: params, constants, parameter-only nodes | per-point nodes ]
//!   0  1  2  3  4  5    6 ..                                                     ..n_regs
//! ```
//!
//! Nodes that depend on neither σ nor the invariants (rational constants,
//! `log 2`, `μ/λ`, Stable Neo-Hookean's α, …) are evaluated once by the
//! *prelude* when the parameters are bound ([`Tape::freeze`]); per point only
//! the *main* code runs, on a register file that is reused (no allocation per
//! evaluation).
//!
//! # Instruction selection
//!
//! The DAG's canonical n-ary sums and products become chains of binary
//! operations; `a + (−1)·b` becomes `a − b` and factors `y^(−n)` of a product
//! become one division by `y^n`. Powers x^(p/q) with an exact rational
//! exponent are lowered without `powf` whenever possible:
//!
//! * integer p (q = 1): repeated squaring, x^n = multiplications only
//!   (|n| ≤ [`MAX_CHAIN_EXPONENT`]), negative n as 1/x^|n|;
//! * q = 2: (√x)^p;
//! * q = 3: (∛x)^p with the real, sign-preserving cube root;
//! * other odd q: the real q-th root sign(x)·|x|^(1/q), then ^p;
//! * otherwise `powf`.
//!
//! These follow the DSL evaluator's semantics exactly: odd roots of negative
//! bases are real (−8)^(1/3) = −2, even roots of negative bases are NaN, and
//! 1/0 = +∞ (IEEE). Every intermediate power x^k is computed once and shared.

mod lower;

use std::cell::RefCell;

pub use lower::MAX_CHAIN_EXPONENT;

/// Number of input registers: σ0, σ1, σ2, I1, I2, I3.
pub const N_INPUTS: usize = 6;

/// One register instruction: `dst ← f(operands)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Op {
    /// dst ← constant.
    Const { dst: u32, value: f64 },
    /// dst ← params\[k\] (prelude only).
    Param { dst: u32, k: u32 },
    /// dst ← a + b.
    Add { dst: u32, a: u32, b: u32 },
    /// dst ← a − b.
    Sub { dst: u32, a: u32, b: u32 },
    /// dst ← a · b.
    Mul { dst: u32, a: u32, b: u32 },
    /// dst ← a / b.
    Div { dst: u32, a: u32, b: u32 },
    /// dst ← a + c.
    AddC { dst: u32, a: u32, c: f64 },
    /// dst ← a · c.
    MulC { dst: u32, a: u32, c: f64 },
    /// dst ← c / a.
    CDiv { dst: u32, c: f64, a: u32 },
    /// dst ← −a.
    Neg { dst: u32, a: u32 },
    /// dst ← √a.
    Sqrt { dst: u32, a: u32 },
    /// dst ← ∛a (real).
    Cbrt { dst: u32, a: u32 },
    /// dst ← sign(a)·|a|^e (real odd root, e = 1/q).
    RootOdd { dst: u32, a: u32, e: f64 },
    /// dst ← a^e as the DSL evaluates a rational exponent e = p/q:
    /// |a|^e with the sign of a when q and p are odd, `powf` otherwise.
    PowRat {
        dst: u32,
        a: u32,
        e: f64,
        odd_q: bool,
        odd_p: bool,
    },
    /// dst ← a^b (`powf`).
    Powf { dst: u32, a: u32, b: u32 },
    /// dst ← ln a.
    Log { dst: u32, a: u32 },
    /// dst ← exp a.
    Exp { dst: u32, a: u32 },
}

/// A compiled straight-line program computing some roots of a graph.
#[derive(Clone, Debug)]
pub struct Tape {
    /// Instructions that depend only on parameters and constants.
    prelude: Vec<Op>,
    /// Instructions run per point.
    main: Vec<Op>,
    /// Registers `N_INPUTS .. N_INPUTS + n_frozen` are filled by the prelude.
    n_frozen: usize,
    /// Total register count.
    n_regs: usize,
    /// Register of each root, in the order the roots were given.
    outputs: Vec<u32>,
    /// Number of parameters the prelude reads.
    n_params: usize,
}

thread_local! {
    /// Per-thread register file reused by every evaluation.
    static SCRATCH: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
}

impl Tape {
    /// Number of roots (outputs) the tape computes.
    pub fn n_outputs(&self) -> usize {
        self.outputs.len()
    }

    /// Number of per-point instructions (a cost measure).
    pub fn main_len(&self) -> usize {
        self.main.len()
    }

    /// Number of prelude (parameter-only) instructions.
    pub fn prelude_len(&self) -> usize {
        self.prelude.len()
    }

    /// Total number of registers.
    pub fn n_regs(&self) -> usize {
        self.n_regs
    }

    /// Run the prelude for parameter values `params` (indexed like the
    /// graph's `Param(k)`; missing values read as NaN) and return the frozen
    /// register block that [`Tape::eval`] needs.
    pub fn freeze(&self, params: &[f64]) -> Vec<f64> {
        let mut regs = vec![0.0; self.n_regs];
        for op in &self.prelude {
            if let Op::Param { dst, k } = *op {
                regs[dst as usize] = params.get(k as usize).copied().unwrap_or(f64::NAN);
            } else {
                step(&mut regs, op);
            }
        }
        regs[N_INPUTS..N_INPUTS + self.n_frozen].to_vec()
    }

    /// Number of parameters the tape was compiled for.
    pub fn n_params(&self) -> usize {
        self.n_params
    }

    /// Evaluate the roots at σ (the first `dim` entries used by the graph)
    /// and the invariants `inv = [I1, I2, I3]`, writing them to `out`
    /// (`out.len()` must be [`Tape::n_outputs`]; extra entries are left
    /// untouched). `frozen` is the block returned by [`Tape::freeze`].
    ///
    /// No allocation once the calling thread's register file is large enough.
    pub fn eval(&self, frozen: &[f64], sigma: [f64; 3], inv: [f64; 3], out: &mut [f64]) {
        SCRATCH.with(|cell| match cell.try_borrow_mut() {
            Ok(mut regs) => self.eval_in(&mut regs, frozen, sigma, inv, out),
            // Only reachable if an evaluation re-entered itself on this thread.
            Err(_) => self.eval_in(&mut Vec::new(), frozen, sigma, inv, out),
        });
    }

    fn eval_in(
        &self,
        regs: &mut Vec<f64>,
        frozen: &[f64],
        sigma: [f64; 3],
        inv: [f64; 3],
        out: &mut [f64],
    ) {
        if regs.len() < self.n_regs {
            regs.resize(self.n_regs, 0.0);
        }
        regs[..3].copy_from_slice(&sigma);
        regs[3..N_INPUTS].copy_from_slice(&inv);
        let n = self.n_frozen.min(frozen.len());
        regs[N_INPUTS..N_INPUTS + n].copy_from_slice(&frozen[..n]);
        for op in &self.main {
            step(regs, op);
        }
        for (o, &r) in out.iter_mut().zip(&self.outputs) {
            *o = regs[r as usize];
        }
    }
}

/// Execute one instruction.
#[inline(always)]
fn step(r: &mut [f64], op: &Op) {
    let (dst, v) = match *op {
        Op::Const { dst, value } => (dst, value),
        // Params are handled by `freeze`; a stray one reads NaN.
        Op::Param { dst, .. } => (dst, f64::NAN),
        Op::Add { dst, a, b } => (dst, r[a as usize] + r[b as usize]),
        Op::Sub { dst, a, b } => (dst, r[a as usize] - r[b as usize]),
        Op::Mul { dst, a, b } => (dst, r[a as usize] * r[b as usize]),
        Op::Div { dst, a, b } => (dst, r[a as usize] / r[b as usize]),
        Op::AddC { dst, a, c } => (dst, r[a as usize] + c),
        Op::MulC { dst, a, c } => (dst, r[a as usize] * c),
        Op::CDiv { dst, c, a } => (dst, c / r[a as usize]),
        Op::Neg { dst, a } => (dst, -r[a as usize]),
        Op::Sqrt { dst, a } => (dst, r[a as usize].sqrt()),
        Op::Cbrt { dst, a } => (dst, r[a as usize].cbrt()),
        Op::RootOdd { dst, a, e } => {
            let x = r[a as usize];
            (dst, x.abs().powf(e).copysign(x))
        }
        Op::PowRat {
            dst,
            a,
            e,
            odd_q,
            odd_p,
        } => {
            let x = r[a as usize];
            let v = if odd_q {
                let m = x.abs().powf(e);
                if x < 0.0 && odd_p { -m } else { m }
            } else {
                x.powf(e)
            };
            (dst, v)
        }
        Op::Powf { dst, a, b } => (dst, r[a as usize].powf(r[b as usize])),
        Op::Log { dst, a } => (dst, r[a as usize].ln()),
        Op::Exp { dst, a } => (dst, r[a as usize].exp()),
    };
    r[dst as usize] = v;
}
