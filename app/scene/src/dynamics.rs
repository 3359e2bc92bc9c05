//! Time integration as incremental potentials (Smith et al. 2019 §6.5).
//!
//! Each step minimises
//!
//!   Φ(x) = ½ w ‖x − x̃‖²_M + E(x) + ½ a (x − y)ᵀ C (x − y),
//!
//! where E holds the elastic, gravity and ground terms, C = αM + βK the
//! Rayleigh damping, and the new velocity is v_{n+1} = a (x − y):
//!
//! | | x̃ | w | a | y |
//! |---|---|---|---|---|
//! | implicit Euler | x_n + h v_n | 1/h² | 1/h | x_n |
//! | BDF2 | (4x_n − x_{n−1})/3 + h(8v_n − 2v_{n−1})/9 | 9/(4h²) | 3/(2h) | (4x_n − x_{n−1})/3 |
//!
//! Derivation (BDF2): v_{n+1} = (3x − 4x_n + x_{n−1})/(2h) and
//! M(3v_{n+1} − 4v_n + v_{n−1}) = 2h f(x) give x − x̃ = (4/9) h² M⁻¹ f, the
//! stationarity condition of Φ with w = 9/(4h²). The first BDF2 step has no
//! history and uses implicit Euler. The stationarity condition of Φ is
//! exactly the integrator's update, so Newton's tolerance is the only
//! approximation.

use crate::spec::Integrator;

/// (x_{n−1}, v_{n−1}).
type History<const D: usize> = (Vec<[f64; D]>, Vec<[f64; D]>);

/// Integrator state: positions and velocities at t_n and t_{n−1}.
#[derive(Clone, Debug)]
pub struct Dynamics<const D: usize> {
    /// Integrator.
    pub kind: Integrator,
    /// Time step h.
    pub h: f64,
    /// x_n.
    pub x: Vec<[f64; D]>,
    /// v_n.
    pub v: Vec<[f64; D]>,
    /// (x_{n−1}, v_{n−1}) once a step was taken.
    prev: Option<History<D>>,
    /// Steps taken.
    pub steps: usize,
}

/// Per-step coefficients (see the module table).
#[derive(Clone, Debug)]
pub struct StepPlan<const D: usize> {
    /// Inertia target x̃.
    pub predicted: Vec<[f64; D]>,
    /// Inertia weight w.
    pub inertia_weight: f64,
    /// Velocity factor a.
    pub a: f64,
    /// Velocity anchor y.
    pub anchor: Vec<[f64; D]>,
}

impl<const D: usize> Dynamics<D> {
    /// Start at positions `x` with velocity `v0` everywhere.
    pub fn new(kind: Integrator, h: f64, x: Vec<[f64; D]>, v0: [f64; D]) -> Self {
        let v = vec![v0; x.len()];
        Dynamics {
            kind,
            h,
            x,
            v,
            prev: None,
            steps: 0,
        }
    }

    /// Whether this step uses BDF2 (history available).
    fn bdf2(&self) -> bool {
        self.kind == Integrator::Bdf2 && self.prev.is_some()
    }

    /// Coefficients of the next step.
    pub fn plan(&self) -> StepPlan<D> {
        let h = self.h;
        match (&self.prev, self.bdf2()) {
            (Some((xp, vp)), true) => {
                let anchor: Vec<[f64; D]> = self
                    .x
                    .iter()
                    .zip(xp)
                    .map(|(xn, xm)| std::array::from_fn(|c| (4.0 * xn[c] - xm[c]) / 3.0))
                    .collect();
                let predicted = anchor
                    .iter()
                    .zip(self.v.iter().zip(vp))
                    .map(|(y, (vn, vm))| {
                        std::array::from_fn(|c| y[c] + h * (8.0 * vn[c] - 2.0 * vm[c]) / 9.0)
                    })
                    .collect();
                StepPlan {
                    predicted,
                    inertia_weight: 9.0 / (4.0 * h * h),
                    a: 1.5 / h,
                    anchor,
                }
            }
            _ => StepPlan {
                predicted: self
                    .x
                    .iter()
                    .zip(&self.v)
                    .map(|(x, v)| std::array::from_fn(|c| x[c] + h * v[c]))
                    .collect(),
                inertia_weight: 1.0 / (h * h),
                a: 1.0 / h,
                anchor: self.x.clone(),
            },
        }
    }

    /// Accept the step's solution `x_new` (v_{n+1} = a (x_new − y)).
    pub fn advance(&mut self, plan: &StepPlan<D>, x_new: &[[f64; D]]) {
        let v_new: Vec<[f64; D]> = x_new
            .iter()
            .zip(&plan.anchor)
            .map(|(x, y)| std::array::from_fn(|c| plan.a * (x[c] - y[c])))
            .collect();
        let x_old = std::mem::replace(&mut self.x, x_new.to_vec());
        let v_old = std::mem::replace(&mut self.v, v_new);
        self.prev = Some((x_old, v_old));
        self.steps += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Free fall of one unit mass under g, solved exactly (the potential is
    /// quadratic in x): x = x̃ + g/w.
    fn fall(kind: Integrator, steps: usize, h: f64) -> (f64, f64) {
        let g = -9.81;
        let mut d = Dynamics::<1>::new(kind, h, vec![[0.0]], [0.0]);
        for _ in 0..steps {
            let p = d.plan();
            let x = [[p.predicted[0][0] + g / p.inertia_weight]];
            d.advance(&p, &x);
        }
        (d.x[0][0], d.v[0][0])
    }

    #[test]
    fn free_fall_velocity_is_exact_and_bdf2_position_is_second_order() {
        let (h, n) = (0.01, 100);
        let t = h * n as f64;
        for kind in [Integrator::Euler, Integrator::Bdf2] {
            let (_, v) = fall(kind, n, h);
            assert!((v + 9.81 * t).abs() < 1e-9, "{kind:?}: v = {v}");
        }
        let exact = -0.5 * 9.81 * t * t;
        let (xe, _) = fall(Integrator::Euler, n, h);
        let (xb, _) = fall(Integrator::Bdf2, n, h);
        // Euler is off by O(h) (−g t h / 2), BDF2 by much less
        assert!((xe - exact).abs() > 0.03, "{xe} vs {exact}");
        assert!(
            (xb - exact).abs() < 0.2 * (xe - exact).abs(),
            "{xb} vs {exact}"
        );
    }
}
