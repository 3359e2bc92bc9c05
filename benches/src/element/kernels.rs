//! The per-element kernels of every [`Method`], for triangles and tets.
//!
//! Each returns (ψ_e, ∇ψ_e, ∇²ψ_e) as plain vectors for the accuracy study;
//! [`Element2`] / [`Element3`] also carry the precomputed B used by the
//! numeric F-projection. The timing loop calls the same functions.

use ecc_runtime::reference::project_psd_numeric;
use ecc_runtime::{
    Energy, Filter, Rest, element_eval, element_f, gradient_f, hessian_f, signed_svd,
};
use nalgebra::SMatrix;

use super::Method;
use crate::generic_kernel::GenericEnergy;

/// A method's output: ψ, gradient (N) and row-major Hessian (N×N).
pub type Output = (f64, Vec<f64>, Vec<f64>);

/// One element type per size (the dense B is d² × d(d + 1), sizes stable Rust
/// cannot derive from d); every kernel called is the runtime's generic one.
macro_rules! element_kind {
    ($name:ident, $d:literal, $k:literal, $r:literal, $n:literal) => {
        /// One element: rest data, nodes, and dense ∂vec(F)/∂x.
        #[derive(Clone, Debug)]
        pub struct $name {
            pub rest: Rest<$d>,
            pub x: [[f64; $d]; $k],
            /// ∂vec(F)/∂x (column-major vec, node-major x).
            pub b: SMatrix<f64, $r, $n>,
        }

        impl $name {
            /// Element from rest data and deformed nodes.
            pub fn new(rest: Rest<$d>, x: [[f64; $d]; $k]) -> Self {
                let f0 = element_f(&rest, &[[0.0; $d]; $k]);
                let b = SMatrix::from_fn(|i, col| {
                    let mut e = [[0.0; $d]; $k];
                    e[col / $d][col % $d] = 1.0;
                    let fk = element_f(&rest, &e) - f0;
                    fk[(i % $d, i / $d)]
                });
                $name { rest, x, b }
            }

            /// Dm⁻¹ row-major.
            pub fn dm_inv(&self) -> Vec<f64> {
                (0..$d * $d)
                    .map(|i| self.rest.dm_inv[(i / $d, i % $d)])
                    .collect()
            }

            /// Rest measure.
            pub fn measure(&self) -> f64 {
                self.rest.measure
            }

            /// Node-major positions.
            pub fn x_flat(&self) -> Vec<f64> {
                self.x.iter().flatten().copied().collect()
            }

            /// Runtime kernel (analytic or raw).
            #[inline]
            pub fn runtime<E: Energy<$d> + ?Sized>(
                &self,
                e: &E,
                filter: Filter,
            ) -> (f64, [f64; $n], SMatrix<f64, $n, $n>) {
                let ev = element_eval(e, &self.rest, &self.x, filter, true);
                (ev.psi, ev.grad.into(), ev.hess)
            }

            /// Numeric projection of the raw element Hessian.
            #[inline]
            pub fn numeric_element<E: Energy<$d> + ?Sized>(
                &self,
                e: &E,
            ) -> (f64, [f64; $n], SMatrix<f64, $n, $n>) {
                let ev = element_eval(e, &self.rest, &self.x, Filter::None, true);
                (
                    ev.psi,
                    ev.grad.into(),
                    project_psd_numeric(&ev.hess, Filter::Clamp),
                )
            }

            /// Numeric projection of the raw F-space Hessian + dense chain rule.
            #[inline]
            pub fn numeric_f<E: Energy<$d> + ?Sized>(
                &self,
                e: &E,
            ) -> (f64, [f64; $n], SMatrix<f64, $n, $n>) {
                let f = element_f(&self.rest, &self.x);
                let svd = signed_svd(&f);
                let m = self.rest.measure;
                if !svd.is_finite() {
                    return (f64::NAN, [0.0; $n], SMatrix::zeros());
                }
                let s = e.spectral(&svd.sigma);
                if !s.psi.is_finite() {
                    return (m * s.psi, [0.0; $n], SMatrix::zeros());
                }
                let g = gradient_f(&svd, &s);
                let h = project_psd_numeric(&hessian_f(&svd, &s, Filter::None), Filter::Clamp);
                let bt = self.b.transpose() * m;
                let grad = bt * g;
                (m * s.psi, grad.into(), bt * h * self.b)
            }

            /// The generic kernel in f64 or f32.
            pub fn generic(&self, e: &GenericEnergy, single: bool) -> Output {
                let dm = self.dm_inv();
                let x = self.x_flat();
                if single {
                    let dm32: Vec<f64> = dm.iter().map(|&v| v as f32 as f64).collect();
                    let x32: Vec<f32> = x.iter().map(|&v| v as f32).collect();
                    let r =
                        e.element::<f32>(&dm32, self.measure() as f32 as f64, &x32, Filter::Clamp);
                    let w = |v: Vec<f32>| v.into_iter().map(f64::from).collect::<Vec<f64>>();
                    (r.psi as f64, w(r.grad), w(r.hess))
                } else {
                    let r = e.element::<f64>(&dm, self.measure(), &x, Filter::Clamp);
                    (r.psi, r.grad, r.hess)
                }
            }

            /// Run `method` (energies: generated, interpreted, generic).
            pub fn run(
                &self,
                method: Method,
                generated: &dyn Energy<$d>,
                interp: &dyn Energy<$d>,
                generic: &GenericEnergy,
            ) -> Output {
                let flat = |(p, g, h): (f64, [f64; $n], SMatrix<f64, $n, $n>)| {
                    // symmetric: column-major storage = row-major
                    (p, g.to_vec(), h.as_slice().to_vec())
                };
                match method {
                    Method::Analytic => flat(self.runtime(generated, Filter::Clamp)),
                    Method::Interpreted => flat(self.runtime(interp, Filter::Clamp)),
                    Method::NumericF => flat(self.numeric_f(generated)),
                    Method::NumericElement => flat(self.numeric_element(generated)),
                    Method::Unprojected => flat(self.runtime(generated, Filter::None)),
                    Method::GenericF64 => self.generic(generic, false),
                    Method::GenericF32 => self.generic(generic, true),
                }
            }
        }
    };
}

element_kind!(Element2, 2, 3, 4, 6);
element_kind!(Element3, 3, 4, 9, 12);
