//! The fibre kernels per dimension: [`FibreDim`] for `Space<2>` and `Space<3>`
//! and the generic entry points [`fibre_f`], [`fibre_element_eval`],
//! [`fibre_element_psi`] (same pattern as [`crate::dim`]).

use nalgebra::{SMatrix, SVector};

use super::element::{chain_matrix, closed_element, psi_kernel};
use super::frame::Frame;
use super::point::{FibrePath, Hess, point_kernel};
use super::reduced::{reduced_hessian, sym_eigen};
use crate::dim::{Dim, FMat, FVec, Nodes, Space};
use crate::element::{ElementEval, Rest, element_f};
use crate::fibre::FibreDerivs;
use crate::fibre::FibreEnergy;
use crate::filter::Filter;
use crate::reference::project_psd_numeric;

/// A fibre energy's ψ, vec(∂ψ/∂F) and filtered ∂²ψ/∂f² at one F.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FibrePoint<const D: usize>
where
    Space<D>: Dim<D>,
{
    /// ψ(I4, I5).
    pub psi: f64,
    /// vec(∂ψ/∂F), column-major.
    pub grad: FVec<D>,
    /// ∂²ψ/∂f², filtered (zero when not requested).
    pub hess: FMat<D>,
    /// Which eigensystem was used.
    pub path: FibrePath,
}

/// The per-size fibre kernels (sealed through [`Dim`]).
pub trait FibreDim<const D: usize>: Dim<D> {
    /// See [`fibre_f`].
    fn fibre_f<E: FibreEnergy<D> + ?Sized>(
        e: &E,
        f: &SMatrix<f64, D, D>,
        a: &SVector<f64, D>,
        filter: Filter,
        want_hessian: bool,
    ) -> FibrePoint<D>
    where
        Space<D>: Dim<D>;

    /// See [`fibre_element_eval`].
    fn fibre_element<E: FibreEnergy<D> + ?Sized>(
        e: &E,
        rest: &Rest<D>,
        x: &Nodes<D>,
        a: &SVector<f64, D>,
        filter: Filter,
        want_hessian: bool,
    ) -> (ElementEval<D>, FibrePath)
    where
        Space<D>: Dim<D>;
}

/// The reduced projection of `Space<$d>` ([`reduced_hessian`] with
/// K = d² − d + 1 for ψ(I4) and K = d² otherwise).
macro_rules! reduce_fn {
    ($d:literal, $n:literal, $k4:literal) => {
        |fr: &Frame<$d>, d: &FibreDerivs, filter: Filter, i4_only: bool| {
            if i4_only {
                reduced_hessian::<$d, $n, $k4>(fr, d, filter, true, sym_eigen::<$k4>)
            } else {
                reduced_hessian::<$d, $n, $n>(fr, d, filter, false, sym_eigen::<$n>)
            }
        }
    };
}

macro_rules! fibre_dim {
    ($d:literal, $n:literal, $k:literal, $ne:literal, $k4:literal) => {
        impl FibreDim<$d> for Space<$d> {
            fn fibre_f<E: FibreEnergy<$d> + ?Sized>(
                e: &E,
                f: &SMatrix<f64, $d, $d>,
                a: &SVector<f64, $d>,
                filter: Filter,
                want_hessian: bool,
            ) -> FibrePoint<$d> {
                let (psi, grad, hess, path) = point_kernel::<$d, $n, E>(
                    e,
                    f,
                    a,
                    filter,
                    want_hessian,
                    project_psd_numeric::<$n>,
                    reduce_fn!($d, $n, $k4),
                );
                FibrePoint {
                    psi,
                    grad,
                    hess: hess.matrix(a),
                    path,
                }
            }

            fn fibre_element<E: FibreEnergy<$d> + ?Sized>(
                e: &E,
                rest: &Rest<$d>,
                x: &Nodes<$d>,
                a: &SVector<f64, $d>,
                filter: Filter,
                want_hessian: bool,
            ) -> (ElementEval<$d>, FibrePath) {
                let f = element_f::<$d>(rest, x);
                let (psi, g, h, path) = point_kernel::<$d, $n, E>(
                    e,
                    &f,
                    a,
                    filter,
                    want_hessian,
                    project_psd_numeric::<$n>,
                    reduce_fn!($d, $n, $k4),
                );
                let w = chain_matrix::<$d, $k, $n, $ne>(rest);
                let m = rest.measure;
                let grad = w.transpose() * g * m;
                let hess = match h {
                    _ if !want_hessian => SMatrix::zeros(),
                    Hess::Closed(fl, n) => closed_element::<$d, $k, $ne>(rest, a, fl, &n),
                    Hess::Full(h) => {
                        let h = w.transpose() * h * w * m;
                        pole_infinite((h + h.transpose()) * 0.5)
                    }
                };
                (
                    ElementEval {
                        psi: m * psi,
                        grad,
                        hess,
                    },
                    path,
                )
            }
        }
    };
}

/// A raw element Hessian at an exact pole σᵢ + σⱼ = 0: the F-space Hessian
/// has ±∞ entries, and Wᵀ H W sums them to ∞ − ∞. Such an entry is reported
/// as +∞, as the F-space Hessian and the C++ runtime report it, never NaN.
fn pole_infinite<const N: usize>(mut h: SMatrix<f64, N, N>) -> SMatrix<f64, N, N> {
    h.iter_mut()
        .filter(|v| v.is_nan())
        .for_each(|v| *v = f64::INFINITY);
    h
}

fibre_dim!(2, 4, 3, 6, 3);
fibre_dim!(3, 9, 4, 12, 7);

/// ψ, vec(∂ψ/∂F) and the `filter`ed ∂²ψ/∂f² of a fibre energy at F for the
/// unit rest fibre `a` (see [`super::point`] for the eigensystems).
pub fn fibre_f<const D: usize, E: FibreEnergy<D> + ?Sized>(
    e: &E,
    f: &SMatrix<f64, D, D>,
    a: &SVector<f64, D>,
    filter: Filter,
    want_hessian: bool,
) -> FibrePoint<D>
where
    Space<D>: FibreDim<D>,
{
    <Space<D> as FibreDim<D>>::fibre_f(e, f, a, filter, want_hessian)
}

/// Element energy, node-major gradient and filtered Hessian of a fibre
/// energy (times the rest measure), for the unit rest fibre `a`.
pub fn fibre_element_eval<const D: usize, E: FibreEnergy<D> + ?Sized>(
    e: &E,
    rest: &Rest<D>,
    x: &Nodes<D>,
    a: &SVector<f64, D>,
    filter: Filter,
    want_hessian: bool,
) -> ElementEval<D>
where
    Space<D>: FibreDim<D>,
{
    <Space<D> as FibreDim<D>>::fibre_element(e, rest, x, a, filter, want_hessian).0
}

/// |q| ψ of one element (SVD only when ψ uses I4).
pub fn fibre_element_psi<const D: usize, E: FibreEnergy<D> + ?Sized>(
    e: &E,
    rest: &Rest<D>,
    x: &Nodes<D>,
    a: &SVector<f64, D>,
) -> f64
where
    Space<D>: FibreDim<D>,
{
    psi_kernel(e, &element_f(rest, x), a, rest.measure)
}

/// The unit fibre of a direction: `None` for a zero or non-finite vector.
pub fn unit_fibre<const D: usize>(dir: &[f64; D]) -> Option<SVector<f64, D>> {
    let v = SVector::<f64, D>::from_column_slice(dir);
    let n = v.norm();
    (n.is_finite() && n > 0.0 && v.iter().all(|x| x.is_finite())).then(|| v / n)
}
