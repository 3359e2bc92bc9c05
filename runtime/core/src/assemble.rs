//! Fast assembly of filtered F-space and element Hessians from the modes.
//!
//! **Scaling block without a full eigensolve.** The scaling part of the
//! Hessian is Σ_ij Â_ij d_i d_jᵀ with Â = filter(A) (filter applied to A's
//! eigenvalues). Every filter leaves an eigenvalue ≥ its floor unchanged, so
//! the number k of eigenvalues below the floor (the inertia of A − floor·I,
//! from LDLᵀ pivots) decides: k = 0 → Â = A; otherwise at most one eigenpair —
//! the best-separated one, from the trigonometric solution and a cross product —
//! is needed (see `filter_block3`), with the full 3×3 eigensolve as fallback.
//! The raw Hessian never needs an eigensolve.
//!
//! **Pairs.** λ_t t tᵀ + λ_l l lᵀ with t, l = (p_ji ∓ p_ij)/√2, p_ab = u_a ⊗ w_b.
//!
//! **Repeated values.** If a value c ≠ 0 repeats among the pair eigenvalues and
//! a diagonal Â (ARAP: six modes at 2), H = c·(I_d ⊗ G) + Σ (λ − c)(…) with
//! G_nm = Σ_b w_b,n w_b,m (the image of c·I), saving one update per repeat.
//!
//! **Translation reduction (elements).** With w_b,0 = −Σ_{n≥1} w_b,n every row
//! block of H_x sums to zero over the nodes, so only the (K−1)d × (K−1)d block
//! of nodes 1…K−1 is accumulated (45 instead of 78 entries per update for a
//! tet) and the node-0 rows/columns are filled as negated sums.
//!
//! Only the upper triangle is accumulated and then mirrored, so every returned
//! matrix is exactly symmetric.
//!
//! **Poles (raw Hessian only).** On an energy's true pole (e.g. σi + σj = 0
//! for a twist eigenvalue (Ψi + Ψj)/(σi + σj) whose numerator does not
//! vanish there) a mode's eigenvalue is ±∞ (+∞ by the back ends'
//! convention). The filters map it to their floor, so only `Filter::None`
//! sees it. Summed like the finite modes it would give ∞·0 = NaN wherever
//! the mode vector has a zero component. Instead the infinite modes are
//! kept apart: with P = Σ_k sign(λ_k) g_k g_kᵀ over the modes with
//! λ_k = ±∞ (unnormalised g as below; the limit of all of them growing at
//! one rate), the raw Hessian is
//!
//! H_xy = sign(P_xy)·∞ where P_xy ≠ 0, and Σ_{finite modes} λ g_x g_y elsewhere,
//!
//! so an entry is infinite exactly where an infinite mode reaches it (a zero
//! component contributes nothing) and never NaN unless an input was NaN.
//! For elements P is expanded to node 0 like H before it is applied
//! ([`modal_sum_nodes`]). The finite case pays one well-predicted test per
//! update.

use crate::filter::Filter;
use crate::modes::{Modes, outer};
use crate::spectral::{ScaleBlock, Spectral, pair_indices};
use crate::sym::{Isolated, complete_scaled, isolated_scaled, normalised};

/// The filtered stretch-space data needed for assembly.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Filtered<const D: usize> {
    /// Â, the filtered scaling block in the d_i basis (symmetric).
    pub scale: [[f64; D]; D],
    /// Â is diagonal.
    pub diagonal: bool,
    /// Filtered twist per pair slot.
    pub twist: [f64; 3],
    /// Filtered flip per pair slot.
    pub flip: [f64; 3],
}

/// The inertia of A − floor·I: how many eigenvalues of A lie below `floor`,
/// from the signs of the LDLᵀ pivots (Sylvester's law of inertia). `None` when a
/// pivot vanishes or is not finite (no pivoting is done; callers then fall back
/// to an eigensolve). A pivot within rounding of 0 may be mis-signed; that only
/// happens when an eigenvalue is within rounding of `floor`, where clamping it
/// or not changes Â by rounding only.
fn below_floor<const D: usize>(a: &[[f64; D]; D], floor: f64) -> Option<usize> {
    let d0 = a[0][0] - floor;
    if d0 == 0.0 || !d0.is_finite() {
        return None;
    }
    let l10 = a[1][0] / d0;
    let d1 = a[1][1] - floor - a[1][0] * l10;
    if d1 == 0.0 || !d1.is_finite() {
        return None;
    }
    let mut neg = (d0 < 0.0) as usize + (d1 < 0.0) as usize;
    if D == 3 {
        let l20 = a[2][0] / d0;
        let l21 = (a[2][1] - a[2][0] * l10) / d1;
        let d2 = a[2][2] - floor - a[2][0] * l20 - l21 * l21 * d1;
        if !d2.is_finite() {
            return None;
        }
        neg += (d2 < 0.0) as usize;
    }
    Some(neg)
}

/// Â = filter(A) for a finite symmetric 3×3 A with at least one eigenvalue
/// below the floor, needing at most one eigenpair. Every filter leaves the
/// eigenvalues ≥ floor unchanged, so with k eigenvalues below it:
///
/// * k = 1 (λ_min, vector z): Â = A + (f(λ_min) − λ_min) z zᵀ;
/// * k = 2 (λ_max ≥ floor, vector z): the other two are mapped together —
///   Clamp: Â = λ_max z zᵀ; ClampEps(ε): Â = λ_max z zᵀ + ε(I − z zᵀ);
///   Abs: Â = −A + 2λ_max z zᵀ (|·| of a negative definite part is its negation);
/// * k = 3: Clamp 0, ClampEps εI, Abs −A.
///
/// The eigenpair used (λ_min for k = 1, λ_max for k = 2) is the one alone on
/// its side of the floor, so its gap g to the nearest other eigenvalue is at
/// least the correction |f(λ) − λ| (half of it for Abs) and the ≈ ε‖A‖/g error of
/// its cross-product eigenvector costs at most ≈ 2ε‖A‖ in Â. It is used only
/// when it is also the best-separated eigenpair; otherwise the decomposition is
/// completed from that pair (complement + one 2×2 rotation). `None` only when
/// the LDLᵀ pivots break down (then the caller's general path runs).
fn filter_block3(a: &[[f64; 3]; 3], filter: Filter) -> Option<[[f64; 3]; 3]> {
    let floor = filter.floor();
    let k = below_floor(a, floor)?;
    let id = |i: usize, j: usize| if i == j { 1.0 } else { 0.0 };
    let build = |g: &dyn Fn(usize, usize) -> f64| -> [[f64; 3]; 3] {
        std::array::from_fn(|i| std::array::from_fn(|j| g(i, j)))
    };
    match k {
        0 => Some(*a),
        3 => Some(match filter {
            Filter::Abs => build(&|i, j| -a[i][j]),
            _ => build(&|i, j| floor * id(i, j)),
        }),
        _ => {
            let (an, scale) = normalised(a)?;
            let iso = isolated_scaled(&an);
            match iso {
                Some(Isolated {
                    value,
                    vector: z,
                    is_max,
                }) if (k == 1) != is_max => {
                    let l = value * scale;
                    Some(if k == 1 {
                        let c = filter.apply(l) - l;
                        build(&|i, j| a[i][j] + c * z[i] * z[j])
                    } else {
                        match filter {
                            Filter::Abs => build(&|i, j| -a[i][j] + 2.0 * l * z[i] * z[j]),
                            _ => build(&|i, j| l * z[i] * z[j] + floor * (id(i, j) - z[i] * z[j])),
                        }
                    })
                }
                // The needed eigenpair is not the best-separated one: finish the
                // decomposition from the isolated pair already computed.
                _ => {
                    let (vals, vecs) = complete_scaled(&an, iso.as_ref());
                    let mut out = [[0.0; 3]; 3];
                    for (z, &v) in vecs.iter().zip(vals.iter()) {
                        let l = filter.apply(v * scale);
                        for i in 0..3 {
                            for j in 0..3 {
                                out[i][j] += l * z[i] * z[j];
                            }
                        }
                    }
                    Some(out)
                }
            }
        }
    }
}

/// Â for a finite, symmetric block that the filter changes: the one-eigenpair
/// update in 3D when it applies, else the full eigensolve (closed form in 2D).
fn filter_block<const D: usize>(
    a: &[[f64; D]; D],
    s: &Spectral<D>,
    filter: Filter,
) -> [[f64; D]; D] {
    if D == 3 {
        let a3: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| a[i][j]));
        if let Some(h) = filter_block3(&a3, filter) {
            return std::array::from_fn(|i| std::array::from_fn(|j| h[i][j]));
        }
    }
    let m = Modes::new(s);
    let mut out = [[0.0; D]; D];
    for (z, &lam) in m.scale_vecs.iter().zip(m.scale_vals.iter()) {
        let l = filter.apply(lam);
        for i in 0..D {
            for j in 0..D {
                out[i][j] += l * z[i] * z[j];
            }
        }
    }
    out
}

impl<const D: usize> Filtered<D> {
    /// Filter the spectral data of one point.
    pub fn new(s: &Spectral<D>, filter: Filter) -> Self {
        let mut twist = [0.0; 3];
        let mut flip = [0.0; 3];
        for k in 0..Spectral::<D>::PAIRS {
            twist[k] = filter.apply(s.twist[k]);
            flip[k] = filter.apply(s.flip[k]);
        }
        let mut scale = [[0.0; D]; D];
        let mut diagonal = true;
        match &s.scale {
            ScaleBlock::Diagonal(a) => {
                for i in 0..D {
                    scale[i][i] = filter.apply(a[i]);
                }
            }
            ScaleBlock::Full(a) => {
                let finite = a.iter().flatten().all(|x| x.is_finite());
                if !finite {
                    // Documented fallback: keep the diagonal only.
                    for i in 0..D {
                        scale[i][i] = filter.apply(a[i][i]);
                    }
                } else {
                    let sym: [[f64; D]; D] =
                        std::array::from_fn(|i| std::array::from_fn(|j| 0.5 * (a[i][j] + a[j][i])));
                    scale = if filter.is_raw() || below_floor(&sym, filter.floor()) == Some(0) {
                        sym
                    } else {
                        filter_block(&sym, s, filter)
                    };
                    diagonal = false;
                }
            }
        }
        Filtered {
            scale,
            diagonal,
            twist,
            flip,
        }
    }
}

/// Σ over the modes, for vectors of length R = D·M built from u_a ⊗ w_b with
/// w_b ∈ R^M; scaled by `weight`; exactly symmetric. Infinite modes (poles,
/// raw Hessian only) give ±∞ entries, never NaN (see the module docs).
#[inline(always)]
pub(crate) fn modal_sum<const D: usize, const M: usize, const R: usize>(
    u: &[[f64; D]; D],
    w: &[[f64; M]; D],
    f: &Filtered<D>,
    weight: f64,
) -> [[f64; R]; R] {
    let (mut h, inf) = modal_parts::<D, M, R>(u, w, f, weight);
    if let Some(p) = inf {
        saturate(&mut h, &p);
    }
    h
}

/// [`modal_sum`] over the nodes 1…K−1 of an element (R = D(K−1)) expanded to
/// all K nodes (N = DK) by [`expand_nodes`]; the infinite modes' P is
/// expanded the same way before it is applied, so node-0 entries are ±∞
/// where an infinite mode reaches them (never ∞ − ∞).
#[inline(always)]
pub(crate) fn modal_sum_nodes<const D: usize, const K: usize, const R: usize, const N: usize>(
    u: &[[f64; D]; D],
    wr: &[[f64; D]; D],
    f: &Filtered<D>,
    weight: f64,
) -> [[f64; N]; N] {
    let (h, inf) = modal_parts::<D, D, R>(u, wr, f, weight);
    let mut out = expand_nodes::<D, K, R, N>(&h);
    if let Some(p) = inf {
        saturate(&mut out, &expand_nodes::<D, K, R, N>(&p));
    }
    out
}

/// H_xy = sign(P_xy)·∞ where P_xy ≠ 0 (a NaN entry stays NaN).
#[cold]
#[inline(never)]
fn saturate<const N: usize>(h: &mut [[f64; N]; N], p: &[[f64; N]; N]) {
    for (hr, pr) in h.iter_mut().zip(p.iter()) {
        for (x, &q) in hr.iter_mut().zip(pr.iter()) {
            if q != 0.0 && !x.is_nan() {
                *x = f64::INFINITY.copysign(q);
            }
        }
    }
}

/// P = Σ sign(c) v vᵀ over the infinite updates (index into `vecs`, c).
#[cold]
#[inline(never)]
fn infinite_part<const R: usize>(vecs: &[[f64; R]; 12], inf: &[(usize, f64)]) -> [[f64; R]; R] {
    let mut p = [[0.0; R]; R];
    for &(l, c) in inf {
        let (v, s) = (&vecs[l], c.signum());
        for i in 0..R {
            for j in 0..R {
                p[i][j] += s * v[i] * v[j];
            }
        }
    }
    p
}

/// Record the rank-one update c·v vᵀ (v = `vecs[l]`): with the finite ones,
/// or, for c = ±∞, with the infinite ones.
#[inline(always)]
fn push_update(
    upd: &mut [(usize, usize, f64); 9],
    nu: &mut usize,
    inf: &mut [(usize, f64); 9],
    ni: &mut usize,
    l: usize,
    c: f64,
) {
    if c.is_infinite() {
        inf[*ni] = (l, c);
        *ni += 1;
    } else {
        upd[*nu] = (l, l, c);
        *nu += 1;
    }
}

/// Shift c: a repeated non-zero value among the pair eigenvalues and, when Â
/// is diagonal, its diagonal (0 when no value repeats). Repeats come from
/// energies whose Hessian is c·I plus a low-rank part (ARAP, co-rotational:
/// flips = scales = 2μ), so only the first flip, twist and scale value are
/// tried as candidates.
#[inline(always)]
fn repeated_shift<const D: usize>(f: &Filtered<D>) -> f64 {
    let mut vals = [0.0; 9];
    let mut nc = 0;
    for k in 0..Spectral::<D>::PAIRS {
        vals[nc] = f.twist[k];
        vals[nc + 1] = f.flip[k];
        nc += 2;
    }
    if f.diagonal {
        for i in 0..D {
            vals[nc] = f.scale[i][i];
            nc += 1;
        }
    }
    let mut shift = 0.0;
    let mut best = 1usize;
    for c in [f.flip[0], f.twist[0], f.scale[0][0]] {
        if c != 0.0 && c.is_finite() {
            let count = vals[..nc].iter().filter(|&&x| x == c).count();
            if count > best {
                best = count;
                shift = c;
            }
        }
    }
    shift
}

/// The upper triangle of c·(G ⊗ I), c = shift·weight, G_nq = Σ_b w_b[n]
/// w_b[q]: the shift's share (all modes at once) of the element Hessian
/// (zero when the shift is 0).
#[inline(always)]
fn shifted_metric<const D: usize, const M: usize, const R: usize>(
    w: &[[f64; M]; D],
    shift: f64,
    weight: f64,
) -> [[f64; R]; R] {
    let mut h = [[0.0; R]; R];
    if shift != 0.0 {
        let c = shift * weight;
        for n in 0..M {
            for q in n..M {
                let mut g = 0.0;
                for wb in w.iter() {
                    g += wb[n] * wb[q];
                }
                for r in 0..D {
                    h[n * D + r][q * D + r] = c * g;
                }
            }
        }
    }
    h
}

/// H += Σ coef · l rᵀ over the updates, upper triangle row by row (the row
/// stays in registers across updates), then mirrored to the lower triangle.
#[inline(always)]
fn apply_updates<const R: usize>(
    h: &mut [[f64; R]; R],
    vecs: &[[f64; R]; 12],
    upd: &[(usize, usize, f64)],
) {
    for i in 0..R {
        let mut row = h[i];
        for &(l, r, c) in upd {
            let ci = c * vecs[l][i];
            let rv = &vecs[r];
            for j in 0..R {
                row[j] += ci * rv[j];
            }
        }
        h[i] = row;
    }
    for i in 0..R {
        for j in (i + 1)..R {
            h[j][i] = h[i][j];
        }
    }
}

/// The finite modes' sum (exactly symmetric) and, when some mode is ±∞,
/// the infinite modes' P (see the module docs).
#[inline(always)]
fn modal_parts<const D: usize, const M: usize, const R: usize>(
    u: &[[f64; D]; D],
    w: &[[f64; M]; D],
    f: &Filtered<D>,
    weight: f64,
) -> ([[f64; R]; R], Option<[[f64; R]; R]>) {
    debug_assert_eq!(R, D * M);
    let pairs = Spectral::<D>::PAIRS;
    let shift = repeated_shift(f);
    // Left/right vectors and coefficients of the updates H += coef · l rᵀ.
    let mut vecs = [[0.0; R]; 12];
    let mut upd: [(usize, usize, f64); 9] = [(0, 0, 0.0); 9];
    let mut inf: [(usize, f64); 9] = [(0, 0.0); 9];
    let (mut nv, mut nu, mut ni) = (0usize, 0usize, 0usize);
    let mut h = shifted_metric::<D, M, R>(w, shift, weight);
    // Scaling part: Σ_ij (Â − cI)_ij p_ii p_jjᵀ.
    let mut sc = f.scale;
    for i in 0..D {
        sc[i][i] -= shift;
    }
    let mut pii = [[0.0; R]; 3];
    for i in 0..D {
        pii[i] = outer::<D, M, R>(&u[i], &w[i]);
    }
    if f.diagonal {
        for i in 0..D {
            if sc[i][i] != 0.0 {
                vecs[nv] = pii[i];
                push_update(&mut upd, &mut nu, &mut inf, &mut ni, nv, sc[i][i] * weight);
                nv += 1;
            }
        }
    } else {
        // y_i = Σ_j Â'_ij p_jj; H += Σ_i p_ii y_iᵀ.
        for i in 0..D {
            let mut y = [0.0; R];
            for j in 0..D {
                let c = sc[i][j] * weight;
                for x in 0..R {
                    y[x] += c * pii[j][x];
                }
            }
            vecs[nv] = pii[i];
            vecs[nv + 1] = y;
            upd[nu] = (nv, nv + 1, 1.0);
            nv += 2;
            nu += 1;
        }
    }
    // Pairs: t = p_ji − p_ij, l = p_ji + p_ij (unnormalised: coefficient λ/2).
    for k in 0..pairs {
        let (i, j) = pair_indices::<D>(k);
        let lt = f.twist[k] - shift;
        let ll = f.flip[k] - shift;
        if lt == 0.0 && ll == 0.0 {
            continue;
        }
        let pji: [f64; R] = outer::<D, M, R>(&u[j], &w[i]);
        let pij: [f64; R] = outer::<D, M, R>(&u[i], &w[j]);
        if lt != 0.0 {
            for x in 0..R {
                vecs[nv][x] = pji[x] - pij[x];
            }
            push_update(&mut upd, &mut nu, &mut inf, &mut ni, nv, 0.5 * lt * weight);
            nv += 1;
        }
        if ll != 0.0 {
            for x in 0..R {
                vecs[nv][x] = pji[x] + pij[x];
            }
            push_update(&mut upd, &mut nu, &mut inf, &mut ni, nv, 0.5 * ll * weight);
            nv += 1;
        }
    }
    apply_updates(&mut h, &vecs, &upd[..nu]);
    let p = if ni > 0 {
        Some(infinite_part(&vecs, &inf[..ni]))
    } else {
        None
    };
    (h, p)
}

/// Expand the block of nodes 1…K−1 (R = D(K−1)) to all K nodes (N = DK) using
/// the zero node-sums of every row: node-0 entries are negated sums.
#[inline(always)]
pub(crate) fn expand_nodes<const D: usize, const K: usize, const R: usize, const N: usize>(
    h: &[[f64; R]; R],
) -> [[f64; N]; N] {
    debug_assert_eq!(R + D, N);
    let mut out = [[0.0; N]; N];
    for i in 0..R {
        out[D + i][D..].copy_from_slice(&h[i]);
    }
    // out[(0,r), j] = −Σ_{n≥1} out[(n,r), j] for j ≥ D.
    for r in 0..D {
        for j in D..N {
            let mut s = 0.0;
            for n in 1..K {
                s += out[n * D + r][j];
            }
            out[r][j] = -s;
            out[j][r] = -s;
        }
    }
    // out[(0,r),(0,s)] = −Σ_{m≥1} out[(0,r),(m,s)], upper then mirrored.
    for r in 0..D {
        for s2 in r..D {
            let mut s = 0.0;
            for m in 1..K {
                s += out[r][m * D + s2];
            }
            out[r][s2] = -s;
            out[s2][r] = -s;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::Filtered;
    use crate::filter::Filter;
    use crate::spectral::{ScaleBlock, Spectral};
    use nalgebra::{Matrix3, SymmetricEigen, Vector3};

    /// Deterministic pseudo-random numbers in [−1, 1) (no dev-dependency needed).
    fn lcg(state: &mut u64) -> f64 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    /// Â from Filtered::new equals Q f(Λ) Qᵀ from nalgebra for spectra with every
    /// count of eigenvalues below the floor, including near-repeated ones.
    #[test]
    fn scaling_block_filter_matches_numeric_reconstruction() {
        let mut st = 7u64;
        let filters = [Filter::Clamp, Filter::ClampEps(0.05), Filter::Abs];
        for it in 0..20_000 {
            // Random rotation from a normalised quaternion.
            let q: [f64; 4] = std::array::from_fn(|_| lcg(&mut st));
            let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
            let (w, x, y, z) = (q[0] / n, q[1] / n, q[2] / n, q[3] / n);
            let r = Matrix3::new(
                1.0 - 2.0 * (y * y + z * z),
                2.0 * (x * y - w * z),
                2.0 * (x * z + w * y),
                2.0 * (x * y + w * z),
                1.0 - 2.0 * (x * x + z * z),
                2.0 * (y * z - w * x),
                2.0 * (x * z - w * y),
                2.0 * (y * z + w * x),
                1.0 - 2.0 * (x * x + y * y),
            );
            let mut l = Vector3::new(lcg(&mut st), lcg(&mut st), lcg(&mut st));
            if it % 3 == 0 {
                l[1] = l[0] + 1e-9 * lcg(&mut st); // near-repeated pair
            }
            let a = r * Matrix3::from_diagonal(&l) * r.transpose();
            let a = (a + a.transpose()) * 0.5;
            let arr: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| a[(i, j)]));
            let s = Spectral::<3> {
                psi: 0.0,
                grad: [0.0; 3],
                scale: ScaleBlock::Full(arr),
                twist: [0.0; 3],
                flip: [0.0; 3],
            };
            let eig = SymmetricEigen::new(a);
            for f in filters {
                let got = Filtered::new(&s, f).scale;
                let fl = eig.eigenvalues.map(|v| f.apply(v));
                let want =
                    eig.eigenvectors * Matrix3::from_diagonal(&fl) * eig.eigenvectors.transpose();
                for i in 0..3 {
                    for j in 0..3 {
                        let e = (got[i][j] - want[(i, j)]).abs();
                        assert!(e < 1e-13, "{f:?} A = {a} Â error {e:e}");
                    }
                }
            }
        }
    }
}
