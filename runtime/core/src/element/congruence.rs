//! Exact projection of the *element* Hessian from the analytic F-space
//! eigensystem, by a congruence of size d² (issue #11, item 5).
//!
//! **The element Hessian.** A linear simplex has F = Ds Dm⁻¹ = X β with
//! X = [x_0 … x_d] (d × K, K = d + 1) and β (K × d) the gradient operator:
//! row n of β is row n−1 of P = Dm⁻¹ for n ≥ 1 and β_0 = −Σ_{n≥1} β_n. With
//! column-major vec and node-major x (vec X = x),
//!
//! (1) f = vec F = B x,  B = βᵀ ⊗ I_d  (d² × dK),
//!
//! so the element Hessian is K = |q| Bᵀ H B with H = ∂²Ψ/∂f² (d² × d²).
//!
//! **The metric.** B's rows are not orthonormal:
//!
//! (2) G = B Bᵀ = (βᵀβ) ⊗ I_d = M ⊗ I_d,  M = βᵀβ = Pᵀ (I_d + 1 1ᵀ) P,
//!
//! a d × d SPD matrix fixed by the rest shape (β has rank d; 1ᵀβ = 0 so the d
//! translations span ker B). With U = G^{-½} B (orthonormal rows, U Uᵀ = I):
//!
//! (3) K = |q| Uᵀ C U,  C = G^{½} H G^{½} = (M^{½} ⊗ I) H (M^{½} ⊗ I).
//!
//! *Proof sketch.* B = G^{½} U, so Bᵀ H B = Uᵀ G^{½} H G^{½} U. If C y = c y
//! then K (Uᵀ y) = |q| Uᵀ C U Uᵀ y = |q| c Uᵀ y, and ‖Uᵀ y‖ = ‖y‖; Uᵀ maps an
//! orthonormal eigenbasis of C onto an orthonormal basis of range(Bᵀ), and
//! K vanishes on its complement ker B (the translations). Hence the spectrum of
//! K is |q|·spec(C) plus d zeros, and for a filter f with f(0) = 0
//!
//! (4) P(K) = |q| Uᵀ f(C) U = |q| Bᵀ G^{-½} f(C) G^{-½} B,
//!
//! the exact per-element projection, from a d² × d² problem (4×4 / 9×9)
//! instead of the 6×6 / 12×12 one. When M = m I, f(C) = m f(H) (with the floor
//! below) and (4) is |q| Bᵀ f(H) B: today's F-space projection
//! ([`crate::element_eval`]); they differ only on anisotropic rest shapes.
//!
//! **Evaluation.** (M^{½} ⊗ I) vec(u vᵀ) = vec(u (M^{½} v)ᵀ), so C is the modal
//! sum of the analytic modes with v_b replaced by M^{½} v_b (no d²×d² products).
//! For an eigenvector y = vec Y of C, Wᵀ y = vec(Y L) with
//! W = G^{-½} B_r = L ⊗ I, L = M^{-½} Pᵀ, B_r the columns of nodes 1…d; node 0
//! follows from the zero node sums. M^{½} and L are precomputed at rest
//! ([`Congruence`], from [`Rest::congruence`](crate::Rest::congruence)).
//!
//! **No eigensolve when H ⪰ floor.** C ⪰ λ_min(H) μ_min I (μ = eigenvalues of
//! M), so if every analytic eigenvalue is ≥ 0 (≥ ε·cond(M) for `ClampEps`),
//! f(C) = C and P(K) = K: the element is evaluated exactly as by
//! [`crate::element_eval`]. Only indefinite elements pay for the symmetric
//! eigensolve of C: a fixed-size cyclic Jacobi ([`super::jacobi`]; nalgebra's
//! `SymmetricEigen` only as its fallback). By Sylvester's law of inertia
//! C = S H S (S = M^{½} ⊗ I invertible) has exactly as many negative
//! eigenvalues as the analytic H, so these are the elements whose F-space
//! Hessian the clamp changes.
//!
//! **Filters** mean what they mean for [`crate::element_eval`]:
//! * `Clamp` max(c, 0), `Abs` |c|, `None` the raw K (no projection);
//! * `ClampEps(ε)`: the floor on the eigenvalues of C is ε·μ_max, so that
//!   P(K) ⪰ ε |q| BᵀB on range(Bᵀ) — the guarantee of the F-space
//!   `ClampEps(ε)` (|q| Bᵀ f(H) B ⪰ ε |q| BᵀB) — and (4) reduces to it when
//!   M ∝ I. As in F-space, the d translation modes (ker B, where every element
//!   energy is invariant) stay at 0 for every filter.
//! * A non-finite analytic eigenvalue (a singularity of the energy, e.g.
//!   ARAP's twist at σ_i + σ_j = 0) is dropped before the congruence (its mode
//!   contributes 0 to H), as the F-space filters drop it; the floor then
//!   applies to C as usual. No NaN or ∞ reaches the projected Hessian.
//!
//! **Accuracy.** The eigensolve of C is backward stable: the projected
//! Hessian is accurate to ≈ ε_mach·‖K‖ of the *raw* element Hessian, as a
//! numeric projection of K is. Where a huge negative mode is clamped (e.g.
//! ARAP's twist near σ_i + σ_j = 0) that is a larger relative error in P(K)
//! than the F-space path's, which drops the mode analytically.

use nalgebra::allocator::Allocator;
use nalgebra::{
    ArrayStorage, Const, DefaultAllocator, DimDiff, DimSub, SMatrix, SymmetricEigen, U1,
};

use super::rest::Rest;
use crate::assemble::{Filtered, expand_nodes, modal_sum};
use crate::dim::{Dim, Nodes, Space, columns, node_weights};
use crate::element::{ElementEval, element_f};
use crate::energy::Energy;
use crate::filter::Filter;
use crate::modes::{Modes, gradient_vec};
use crate::spectral::{ScaleBlock, Spectral};
use crate::sym::{sym2_eigen, sym3_eigen};

/// Rest-time factors of the congruence (4) of one element: M = βᵀβ (2) enters
/// through M^{½}, L = M^{-½} Dm⁻ᵀ and the extreme eigenvalues of M.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Congruence<const D: usize> {
    /// M^{½} (symmetric positive definite).
    pub sqrt_m: SMatrix<f64, D, D>,
    /// L = M^{-½} Pᵀ, P = Dm⁻¹: W = G^{-½} B_r = L ⊗ I_d (see the module docs).
    pub pull: SMatrix<f64, D, D>,
    /// Smallest eigenvalue of M (> 0).
    pub mu_min: f64,
    /// Largest eigenvalue of M.
    pub mu_max: f64,
}

/// M = Pᵀ (I + 1 1ᵀ) P (eq. 2) for P = Dm⁻¹.
pub fn metric<const D: usize>(dm_inv: &SMatrix<f64, D, D>) -> SMatrix<f64, D, D> {
    let ones = SMatrix::<f64, D, 1>::repeat(1.0);
    let s = dm_inv.transpose() * ones; // Pᵀ 1 = −β_0
    dm_inv.transpose() * dm_inv + s * s.transpose()
}

/// Eigenvalues (descending) and unit eigenvectors (columns) of a symmetric d×d matrix.
fn sym_eigen<const D: usize>(m: &SMatrix<f64, D, D>) -> ([f64; D], SMatrix<f64, D, D>) {
    if D == 2 {
        let (v, z) = sym2_eigen(m[(0, 0)], 0.5 * (m[(0, 1)] + m[(1, 0)]), m[(1, 1)]);
        (
            std::array::from_fn(|k| v[k]),
            SMatrix::from_fn(|i, k| z[k][i]),
        )
    } else {
        let a: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]));
        let (v, z) = sym3_eigen(&a);
        (
            std::array::from_fn(|k| v[k]),
            SMatrix::from_fn(|i, k| z[k][i]),
        )
    }
}

impl<const D: usize> Congruence<D> {
    /// The factors of an element with rest data `rest` (Dm⁻¹ of a checked,
    /// non-degenerate simplex, so M is SPD).
    pub fn new(rest: &Rest<D>) -> Self {
        let (mu, q) = sym_eigen(&metric(&rest.dm_inv));
        let pow = |p: f64| {
            let d = SMatrix::<f64, D, D>::from_fn(|i, j| if i == j { mu[i].powf(p) } else { 0.0 });
            q * d * q.transpose()
        };
        let sqrt_m = pow(0.5);
        let sqrt_m = 0.5 * (sqrt_m + sqrt_m.transpose());
        Congruence {
            sqrt_m,
            pull: pow(-0.5) * rest.dm_inv.transpose(),
            mu_min: mu[D - 1],
            mu_max: mu[0],
        }
    }

    /// cond(M) = μ_max / μ_min ≥ 1: 1 when the element's metric is isotropic
    /// (then the F-space projection is already exact).
    pub fn cond(&self) -> f64 {
        self.mu_max / self.mu_min
    }

    /// The filter applied to the eigenvalues c of C: the same kind, with the
    /// `ClampEps` floor scaled to ε·μ_max (see the module docs).
    fn filter_c(&self, filter: Filter) -> Filter {
        match filter {
            Filter::ClampEps(_) if filter.floor() > 0.0 => {
                Filter::ClampEps(filter.floor() * self.mu_max)
            }
            Filter::ClampEps(_) => Filter::Clamp,
            f => f,
        }
    }
}

/// Energy, gradient and (if `want_hessian`) Hessian of an element whose
/// Hessian is the exact projection P(K) of eq. (4) — instead of
/// [`crate::element_eval`]'s F-space projection |q| Bᵀ f(H) B. `congruence`
/// must be `rest.congruence()`. ψ and the gradient are the same as
/// [`crate::element_eval`]'s; so is the Hessian wherever the analytic
/// eigenvalues are ≥ the floor (no eigensolve then) or M ∝ I.
#[inline]
pub fn element_eval_projected<const D: usize, E: Energy<D> + ?Sized>(
    e: &E,
    rest: &Rest<D>,
    congruence: &Congruence<D>,
    x: &Nodes<D>,
    filter: Filter,
    want_hessian: bool,
) -> ElementEval<D>
where
    Space<D>: Dim<D>,
{
    let f = element_f(rest, x);
    <Space<D> as Dim<D>>::element_kernel_projected(e, &f, rest, congruence, filter, want_hessian)
}

/// True when filtering C cannot change it: every analytic eigenvalue is
/// finite and ≥ t, t = floor·cond(M) (0 without a floor), so C ⪰ t μ_min I.
fn unchanged<const D: usize>(s: &Spectral<D>, filter: Filter, cg: &Congruence<D>) -> bool {
    let floor = filter.floor();
    let t = if floor > 0.0 { floor * cg.cond() } else { 0.0 };
    let ok = |l: f64| l.is_finite() && l >= t;
    let pairs = (0..Spectral::<D>::PAIRS).all(|k| ok(s.twist[k]) && ok(s.flip[k]));
    pairs
        && match &s.scale {
            ScaleBlock::Diagonal(a) => a.iter().all(|&l| ok(l)),
            ScaleBlock::Full(a) => {
                a.iter().flatten().all(|x| x.is_finite())
                    && Modes::new(s).scale_vals.iter().all(|&l| ok(l))
            }
        }
}

/// `s` with every non-finite analytic eigenvalue replaced by 0 (its mode is
/// dropped, as the F-space filters drop it); a scaling block with a
/// non-finite entry keeps its diagonal (the F-space filters' fallback).
fn finite_modes<const D: usize>(s: &Spectral<D>) -> Spectral<D> {
    let z = |l: f64| if l.is_finite() { l } else { 0.0 };
    let scale = match &s.scale {
        ScaleBlock::Full(a) if a.iter().flatten().all(|x| x.is_finite()) => s.scale,
        other => ScaleBlock::Diagonal(std::array::from_fn(|i| z(other.get(i, i)))),
    };
    Spectral {
        scale,
        twist: s.twist.map(z),
        flip: s.flip.map(z),
        ..*s
    }
}

/// The nodes-1…d block of P(K) (eq. 4): eigensolve of C, then
/// |q| Σ f(c) vec(Y L) vec(Y L)ᵀ over the eigenvectors y = vec Y.
///
/// Not the cheaper-looking rank-k form |q| Wᵀ C W + |q| Σ_{f(c)≠c} (f(c) − c) z zᵀ
/// (k = number of negative analytic eigenvalues, by Sylvester's law of
/// inertia): where a huge negative mode is clamped (ARAP's twist at
/// σ_i + σ_j ≈ 0, c ≈ −1e16) it cancels the raw block to ε|c| and leaves the
/// result indefinite; the sum over eigenpairs is PSD by construction.
fn projected_block<const D: usize, const R: usize>(
    u: &[[f64; D]; D],
    v: &SMatrix<f64, D, D>,
    s: &Spectral<D>,
    cg: &Congruence<D>,
    filter: Filter,
    measure: f64,
    eigen: SymEigen<R>,
) -> [[f64; R]; R] {
    debug_assert_eq!(R, D * D);
    let ws = columns(&(cg.sqrt_m * v)); // M^{½} v_b
    let c = modal_sum::<D, D, R>(u, &ws, &Filtered::new(&finite_modes(s), Filter::None), 1.0);
    let (vals, vecs) = eigen(&c);
    let fc = cg.filter_c(filter);
    let mut out = [[0.0; R]; R];
    for k in 0..R {
        let lam = measure * fc.apply(vals[k]);
        if lam == 0.0 {
            continue;
        }
        let y = &vecs[k];
        // z = vec(Y L): z[n·d + i] = Σ_j Y_ij L_jn with Y_ij = y[j·d + i].
        let z: [f64; R] = std::array::from_fn(|idx| {
            let (n, i) = (idx / D, idx % D);
            (0..D).map(|j| y[j * D + i] * cg.pull[(j, n)]).sum()
        });
        for i in 0..R {
            let li = lam * z[i];
            for j in i..R {
                out[i][j] += li * z[j];
            }
        }
    }
    for i in 0..R {
        for j in 0..i {
            out[i][j] = out[j][i];
        }
    }
    out
}

/// Kernel behind [`element_eval_projected`]: D = dimension, K = D + 1 nodes,
/// R = D·D, N = D·K (the sizes of `Dim`'s instantiations).
#[inline]
pub(crate) fn kernel<
    const D: usize,
    const K: usize,
    const R: usize,
    const N: usize,
    E: Energy<D> + ?Sized,
>(
    e: &E,
    f: &SMatrix<f64, D, D>,
    rest: &Rest<D>,
    cg: &Congruence<D>,
    filter: Filter,
    want_hessian: bool,
    eigen: SymEigen<R>,
) -> (f64, [f64; N], [[f64; N]; N]) {
    let measure = rest.measure;
    let zero = |psi: f64| (psi, [0.0; N], [[0.0; N]; N]);
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
    let wr: [[f64; D]; D] = std::array::from_fn(|b| std::array::from_fn(|n| w[b][n + 1]));
    let grad = gradient_vec::<D, K, N>(&u, &w, &s.grad, measure);
    if !want_hessian {
        return (measure * s.psi, grad, [[0.0; N]; N]);
    }
    let hr = if filter.is_raw() || unchanged(&s, filter, cg) {
        // P(K) = K: the raw Hessian, no filtering needed.
        modal_sum::<D, D, R>(&u, &wr, &Filtered::new(&s, Filter::None), measure)
    } else {
        projected_block::<D, R>(&u, &svd.v, &s, cg, filter, measure, eigen)
    };
    (measure * s.psi, grad, expand_nodes::<D, K, R, N>(&hr))
}

/// A symmetric eigensolver of a fixed size R: (values, unit eigenvectors).
pub(crate) type SymEigen<const R: usize> = fn(&[[f64; R]; R]) -> ([f64; R], [[f64; R]; R]);

/// The symmetric eigensolver of the kernel (R = 4 or 9), as a [`SymEigen`]:
/// the cyclic Jacobi method of [`super::jacobi`] (fixed size, no heap), with
/// nalgebra's `SymmetricEigen` as the fallback should Jacobi refuse (a
/// non-finite entry) or not converge.
pub(crate) fn sym_eigen_n<const R: usize>(c: &[[f64; R]; R]) -> ([f64; R], [[f64; R]; R])
where
    Const<R>: DimSub<U1>,
    DefaultAllocator: Allocator<DimDiff<Const<R>, U1>>,
{
    super::jacobi::jacobi_eigen(c).unwrap_or_else(|| sym_eigen_nalgebra(c))
}

/// nalgebra's `SymmetricEigen` of a symmetric R×R matrix (R = 4 or 9), as a
/// [`SymEigen`]: the kernel stays free of nalgebra's size bounds.
pub(crate) fn sym_eigen_nalgebra<const R: usize>(c: &[[f64; R]; R]) -> ([f64; R], [[f64; R]; R])
where
    Const<R>: DimSub<U1>,
    DefaultAllocator: Allocator<DimDiff<Const<R>, U1>>,
{
    let eig = SymmetricEigen::<f64, Const<R>>::new(SMatrix::from_array_storage(ArrayStorage(*c)));
    (
        std::array::from_fn(|k| eig.eigenvalues[k]),
        std::array::from_fn(|k| std::array::from_fn(|i| eig.eigenvectors[(i, k)])),
    )
}

#[cfg(test)]
mod tests {
    use super::{SymEigen, kernel, sym_eigen_n, sym_eigen_nalgebra};
    use crate::energies::{Arap, StableNeoHookean, SymmetricDirichlet};
    use crate::reference::cases::{compose, hard_cases_2d, hard_cases_3d, rng, rotation};
    use crate::{Energy, Filter, Rest};

    /// The kernel with the Jacobi eigensolver equals the kernel with nalgebra's
    /// `SymmetricEigen` to 1e-12 of the raw element Hessian, at every hard case.
    fn jacobi_vs_nalgebra<const D: usize, const K: usize, const R: usize, const N: usize>(
        e: &dyn Energy<D>,
        rest: &Rest<D>,
        sigmas: &[(&str, [f64; D])],
        (jacobi, nalgebra): (SymEigen<R>, SymEigen<R>),
    ) -> usize {
        let cg = rest.congruence();
        let mut r = rng(31);
        let mut compared = 0;
        for (name, sigma) in sigmas {
            for _ in 0..3 {
                let f = compose(&rotation::<D>(&mut r), sigma, &rotation::<D>(&mut r));
                for filter in [Filter::Clamp, Filter::Abs, Filter::ClampEps(1e-3)] {
                    let run = |eig| kernel::<D, K, R, N, _>(e, &f, rest, &cg, filter, true, eig);
                    let (a, b) = (run(jacobi), run(nalgebra));
                    let raw =
                        kernel::<D, K, R, N, _>(e, &f, rest, &cg, Filter::None, true, jacobi).2;
                    let scale = raw.iter().flatten().fold(1.0f64, |m, x| m.max(x.abs()));
                    if !scale.is_finite() {
                        continue;
                    }
                    let err = (0..N)
                        .flat_map(|i| (0..N).map(move |j| (i, j)))
                        .fold(0.0f64, |m, (i, j)| m.max((a.2[i][j] - b.2[i][j]).abs()));
                    assert!(
                        err <= 1e-12 * scale,
                        "{} {name} {filter:?}: {err:e}",
                        e.name()
                    );
                    compared += 1;
                }
            }
        }
        compared
    }

    #[test]
    fn jacobi_equals_nalgebra_eigensolve_at_the_hard_cases() {
        let snh = StableNeoHookean::new(1.3, 4.1);
        let tri = Rest::<2>::new([[0.0, 0.0], [3.0, 0.0], [1.4, 0.08]]).unwrap();
        let tet =
            Rest::<3>::new([[0.0; 3], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.9, 1.1, 0.05]]).unwrap();
        let c2: Vec<_> = hard_cases_2d().iter().map(|c| (c.name, c.sigma)).collect();
        let c3: Vec<_> = hard_cases_3d().iter().map(|c| (c.name, c.sigma)).collect();
        let mut n = 0;
        for e in [&Arap as &dyn Energy<2>, &SymmetricDirichlet, &snh] {
            n += jacobi_vs_nalgebra::<2, 3, 4, 6>(e, &tri, &c2, (sym_eigen_n, sym_eigen_nalgebra));
        }
        for e in [&Arap as &dyn Energy<3>, &SymmetricDirichlet, &snh] {
            n += jacobi_vs_nalgebra::<3, 4, 9, 12>(e, &tet, &c3, (sym_eigen_n, sym_eigen_nalgebra));
        }
        assert!(n > 300, "only {n} comparisons");
    }
}
