//! The dimension as a type: everything that differs between 2D and 3D.
//!
//! [`Space<D>`] is a marker for d = `D`; the sealed trait [`Dim<D>`] is
//! implemented for `Space<2>` and `Space<3>` only and carries the types whose
//! sizes are functions of d that stable Rust cannot compute from `D`
//! (d² = [`Dim::N`] F-space entries, K = d + 1 simplex nodes, d·K element
//! unknowns) and the kernels instantiated at those sizes. Callers are written
//! once, generic over `D` with the bound `Space<D>: Dim<D>`, and call the
//! free functions [`gradient_f`](crate::gradient_f),
//! [`hessian_f`](crate::hessian_f), [`eigen_f`](crate::eigen_f),
//! [`element_eval`](crate::element_eval), [`Rest::new`], … Every
//! instantiation monomorphises to one concrete kernel per size (the same
//! code as hand-written 2D and 3D functions, `#[inline]` kept).
//!
//! Where a run-time value chooses the dimension (a file says `dim 2`), one
//! `match dim { 2 => f::<2>(..), 3 => f::<3>(..), .. }` at the edge suffices.

use std::fmt::Debug;
use std::ops::Index;

use nalgebra::{ArrayStorage, SMatrix, SVector};

use crate::assemble::{Filtered, modal_sum, modal_sum_nodes};
use crate::element::{Congruence, ElementEval, Rest, RestError, det};
use crate::energy::Energy;
use crate::filter::Filter;
use crate::modes::{Modes, gradient_vec, mode_vectors};
use crate::reference::{fd_hessian, project_psd_numeric};
use crate::spectral::Spectral;
use crate::svd::Svd;

/// The dimension d = `D` as a type (see [`Dim`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Space<const D: usize>;

mod sealed {
    pub trait Sealed {}
    impl Sealed for super::Space<2> {}
    impl Sealed for super::Space<3> {}
}

/// What forks between 2D and 3D; implemented for [`Space<2>`] and [`Space<3>`] only.
///
/// The methods are the per-size instantiations behind the generic free
/// functions of the crate; call those (they read better and carry the docs).
pub trait Dim<const D: usize>: sealed::Sealed + Copy + Debug + Send + Sync + 'static {
    /// d², the length of vec(F).
    const N: usize;
    /// K = d + 1, the nodes of the simplex.
    const NODES: usize;
    /// d·K, the unknowns of one element (node-major).
    const NE: usize;
    /// vec(F)-sized vector, `SVector<f64, d²>`.
    type FVec: Copy + Debug + PartialEq + Send + Sync + Index<usize, Output = f64>;
    /// d² × d² matrix, `SMatrix<f64, d², d²>`.
    type FMat: Copy + Debug + PartialEq + Send + Sync + Index<(usize, usize), Output = f64>;
    /// The d² eigenvalues, `[f64; d²]`.
    type FVals: Copy + Debug + PartialEq + AsRef<[f64]>;
    /// The d² eigenvectors, `[FVec; d²]`.
    type FVecs: Copy + Debug + PartialEq + AsRef<[Self::FVec]>;
    /// The K node positions of a simplex, `[[f64; D]; K]`.
    type Nodes: Copy + Debug + PartialEq + Send + Sync + AsRef<[[f64; D]]>;
    /// Element vector, `SVector<f64, d·K>`.
    type ElemVec: Copy + Debug + PartialEq + Send + Sync + Index<usize, Output = f64>;
    /// Element matrix, `SMatrix<f64, d·K, d·K>`.
    type ElemMat: Copy + Debug + PartialEq + Send + Sync + Index<(usize, usize), Output = f64>;

    /// See [`gradient_f`](crate::gradient_f).
    fn gradient_f(svd: &Svd<D>, s: &Spectral<D>) -> Self::FVec;
    /// See [`hessian_f`](crate::hessian_f).
    fn hessian_f(svd: &Svd<D>, s: &Spectral<D>, filter: Filter) -> Self::FMat;
    /// See [`eigen_f`](crate::eigen_f).
    fn eigen_f(svd: &Svd<D>, s: &Spectral<D>) -> (Self::FVals, Self::FVecs);
    /// vec(M), column-major (Smith et al. 2019, eq. 1).
    fn vec(m: &SMatrix<f64, D, D>) -> Self::FVec;
    /// The d²×d² matrix with entries `entry(i, j)`.
    fn fmat_from_fn(entry: &mut dyn FnMut(usize, usize) -> f64) -> Self::FMat;
    /// See [`fd_hessian_f`](crate::reference::fd_hessian_f).
    fn fd_hessian_f(
        psi: &dyn Fn(&SMatrix<f64, D, D>) -> f64,
        f: &SMatrix<f64, D, D>,
        scale: f64,
    ) -> Self::FMat;
    /// The nodes `x[idx[0]], …, x[idx[d]]` of one simplex.
    fn gather(x: &[[f64; D]], idx: &[usize]) -> Self::Nodes;
    /// det M (closed form, expanded along the first row).
    fn det(m: &SMatrix<f64, D, D>) -> f64;
    /// See [`project_psd_f`](crate::reference::project_psd_f).
    fn project_psd_numeric(h: &Self::FMat, filter: Filter) -> Self::FMat;
    /// See [`Rest::new`].
    fn rest(p: &Self::Nodes) -> Result<Rest<D>, RestError>;
    /// Element kernel behind [`element_eval`](crate::element_eval), from F = Ds Dm⁻¹.
    fn element_kernel<E: Energy<D> + ?Sized>(
        e: &E,
        f: &SMatrix<f64, D, D>,
        rest: &Rest<D>,
        filter: Filter,
        want_hessian: bool,
    ) -> ElementEval<D>
    where
        Space<D>: Dim<D>;
    /// Element kernel behind [`element_eval_projected`](crate::element_eval_projected).
    fn element_kernel_projected<E: Energy<D> + ?Sized>(
        e: &E,
        f: &SMatrix<f64, D, D>,
        rest: &Rest<D>,
        congruence: &Congruence<D>,
        filter: Filter,
        want_hessian: bool,
    ) -> ElementEval<D>
    where
        Space<D>: Dim<D>;
}

/// `<Space<D> as Dim<D>>::FVec`: vec(F)-sized vector.
pub type FVec<const D: usize> = <Space<D> as Dim<D>>::FVec;
/// `<Space<D> as Dim<D>>::FMat`: d² × d² matrix.
pub type FMat<const D: usize> = <Space<D> as Dim<D>>::FMat;
/// `<Space<D> as Dim<D>>::Nodes`: the d + 1 node positions of a simplex.
pub type Nodes<const D: usize> = <Space<D> as Dim<D>>::Nodes;
/// `<Space<D> as Dim<D>>::ElemVec`: element vector (d(d + 1) entries).
pub type ElemVec<const D: usize> = <Space<D> as Dim<D>>::ElemVec;
/// `<Space<D> as Dim<D>>::ElemMat`: element matrix.
pub type ElemMat<const D: usize> = <Space<D> as Dim<D>>::ElemMat;

/// Columns of a D×D matrix as arrays.
#[inline]
pub(crate) fn columns<const D: usize>(m: &SMatrix<f64, D, D>) -> [[f64; D]; D] {
    std::array::from_fn(|j| std::array::from_fn(|i| m[(i, j)]))
}

/// w_b = β v_b for each right singular vector v_b: w_b[n] = (Dm⁻¹ v_b)[n−1]
/// for n ≥ 1 and w_b[0] = −Σ_{n≥1} w_b[n] (K = d + 1 nodes). Shared by the
/// element kernels so that they agree to the bit.
#[inline]
pub(crate) fn node_weights<const D: usize, const K: usize>(
    dm_inv: &SMatrix<f64, D, D>,
    v: &SMatrix<f64, D, D>,
) -> [[f64; K]; D] {
    std::array::from_fn(|b| {
        let mut wb = [0.0; K];
        let mut sum = 0.0;
        for n in 1..K {
            let mut acc = 0.0;
            for c in 0..D {
                acc += dm_inv[(n - 1, c)] * v[(c, b)];
            }
            wb[n] = acc;
            sum += acc;
        }
        wb[0] = -sum;
        wb
    })
}

#[inline]
fn gradient_kernel<const D: usize, const N: usize>(svd: &Svd<D>, s: &Spectral<D>) -> [f64; N] {
    if !svd.is_finite() {
        return [0.0; N];
    }
    gradient_vec::<D, D, N>(&columns(&svd.u), &columns(&svd.v), &s.grad, 1.0)
}

#[inline]
fn hessian_kernel<const D: usize, const N: usize>(
    svd: &Svd<D>,
    s: &Spectral<D>,
    filter: Filter,
) -> [[f64; N]; N] {
    if !svd.is_finite() {
        let fill = if filter.is_raw() { f64::NAN } else { 0.0 };
        return [[fill; N]; N];
    }
    let (u, v) = (columns(&svd.u), columns(&svd.v));
    modal_sum::<D, D, N>(&u, &v, &Filtered::new(s, filter), 1.0)
}

fn eigen_kernel<const D: usize, const N: usize>(
    svd: &Svd<D>,
    s: &Spectral<D>,
) -> ([f64; N], [SVector<f64, N>; N]) {
    let (u, v) = (columns(&svd.u), columns(&svd.v));
    let (vals, vecs) = mode_vectors::<D, D, N>(&u, &v, &Modes::new(s));
    let mut order: [usize; N] = std::array::from_fn(|i| i);
    order.sort_by(|&a, &b| vals[a].total_cmp(&vals[b]));
    (
        std::array::from_fn(|k| vals[order[k]]),
        std::array::from_fn(|k| SVector::from_column_slice(&vecs[order[k]])),
    )
}

/// Element kernel: D = dimension, K = D + 1 nodes, R = D·D, N = D·K.
///
/// With w_b = β v_b (see [`crate::modes`]): ∇ψ_e = |q| Σ_b Ψ_b u_b ⊗ w_b and
/// ∇²ψ_e = |q| Σ λ g gᵀ over the x-space modes g.
#[inline]
fn element_kernel<
    const D: usize,
    const K: usize,
    const R: usize,
    const N: usize,
    E: Energy<D> + ?Sized,
>(
    e: &E,
    f: &SMatrix<f64, D, D>,
    rest: &Rest<D>,
    filter: Filter,
    want_hessian: bool,
) -> (f64, SVector<f64, N>, SMatrix<f64, N, N>) {
    let measure = rest.measure;
    let zero = |psi: f64| (psi, SVector::zeros(), SMatrix::zeros());
    let svd = crate::svd::signed_svd(f);
    if !svd.is_finite() {
        return zero(f64::NAN);
    }
    let s = e.spectral(&svd.sigma);
    if !s.psi.is_finite() {
        return zero(measure * s.psi);
    }
    let u = columns(&svd.u);
    let w = node_weights::<D, K>(&rest.dm_inv, &svd.v);
    let grad = gradient_vec::<D, K, N>(&u, &w, &s.grad, measure);
    let hess = if want_hessian {
        // Nodes 1…K−1 only (w restricted to them), node 0 from the zero node-sums.
        let wr: [[f64; D]; D] = std::array::from_fn(|b| std::array::from_fn(|n| w[b][n + 1]));
        let h = modal_sum_nodes::<D, K, R, N>(&u, &wr, &Filtered::new(&s, filter), measure);
        SMatrix::from_array_storage(ArrayStorage(h))
    } else {
        SMatrix::zeros()
    };
    (measure * s.psi, SVector::from(grad), hess)
}

/// Implements [`Dim`] for `Space<$d>`: d² = $n, K = $k nodes, d·K = $ne.
macro_rules! dim {
    ($d:literal, $n:literal, $k:literal, $ne:literal, $rest:path) => {
        impl Dim<$d> for Space<$d> {
            const N: usize = $n;
            const NODES: usize = $k;
            const NE: usize = $ne;
            type FVec = SVector<f64, $n>;
            type FMat = SMatrix<f64, $n, $n>;
            type FVals = [f64; $n];
            type FVecs = [SVector<f64, $n>; $n];
            type Nodes = [[f64; $d]; $k];
            type ElemVec = SVector<f64, $ne>;
            type ElemMat = SMatrix<f64, $ne, $ne>;

            #[inline]
            fn gradient_f(svd: &Svd<$d>, s: &Spectral<$d>) -> Self::FVec {
                SVector::from(gradient_kernel::<$d, $n>(svd, s))
            }

            #[inline]
            fn hessian_f(svd: &Svd<$d>, s: &Spectral<$d>, filter: Filter) -> Self::FMat {
                let h = hessian_kernel::<$d, $n>(svd, s, filter);
                SMatrix::from_fn(|i, j| h[i][j])
            }

            fn eigen_f(svd: &Svd<$d>, s: &Spectral<$d>) -> (Self::FVals, Self::FVecs) {
                eigen_kernel::<$d, $n>(svd, s)
            }

            fn vec(m: &SMatrix<f64, $d, $d>) -> Self::FVec {
                SVector::from_fn(|k, _| m[(k % $d, k / $d)])
            }

            fn fmat_from_fn(entry: &mut dyn FnMut(usize, usize) -> f64) -> Self::FMat {
                SMatrix::from_fn(|i, j| entry(i, j))
            }

            fn fd_hessian_f(
                psi: &dyn Fn(&SMatrix<f64, $d, $d>) -> f64,
                f: &SMatrix<f64, $d, $d>,
                scale: f64,
            ) -> Self::FMat {
                let of = |x: &SVector<f64, $n>| SMatrix::from_fn(|r, c| x[c * $d + r]);
                fd_hessian(|y| psi(&of(y)), &Self::vec(f), scale)
            }

            #[inline]
            fn gather(x: &[[f64; $d]], idx: &[usize]) -> Self::Nodes {
                std::array::from_fn(|n| x[idx[n]])
            }

            #[inline]
            fn det(m: &SMatrix<f64, $d, $d>) -> f64 {
                det::<$d>(m)
            }

            fn project_psd_numeric(h: &Self::FMat, filter: Filter) -> Self::FMat {
                project_psd_numeric(h, filter)
            }

            fn rest(p: &Self::Nodes) -> Result<Rest<$d>, RestError> {
                $rest(p)
            }

            #[inline]
            fn element_kernel<E: Energy<$d> + ?Sized>(
                e: &E,
                f: &SMatrix<f64, $d, $d>,
                rest: &Rest<$d>,
                filter: Filter,
                want_hessian: bool,
            ) -> ElementEval<$d> {
                let (psi, grad, hess) =
                    element_kernel::<$d, $k, $n, $ne, E>(e, f, rest, filter, want_hessian);
                ElementEval { psi, grad, hess }
            }

            #[inline]
            fn element_kernel_projected<E: Energy<$d> + ?Sized>(
                e: &E,
                f: &SMatrix<f64, $d, $d>,
                rest: &Rest<$d>,
                congruence: &Congruence<$d>,
                filter: Filter,
                want_hessian: bool,
            ) -> ElementEval<$d> {
                let (psi, grad, hess) = crate::element::congruence::kernel::<$d, $k, $n, $ne, E>(
                    e,
                    f,
                    rest,
                    congruence,
                    filter,
                    want_hessian,
                    crate::element::congruence::sym_eigen_n::<$n>,
                );
                ElementEval {
                    psi,
                    grad: SVector::from(grad),
                    hess: SMatrix::from_array_storage(ArrayStorage(hess)),
                }
            }
        }
    };
}

dim!(2, 4, 3, 6, crate::element::rest::planar_triangle);
dim!(3, 9, 4, 12, crate::element::rest::tetrahedron);
