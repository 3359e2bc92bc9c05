//! Fast assembly of filtered F-space and element Hessians from the modes.
//!
//! **Scaling block without an eigensolve when possible.** The scaling part of
//! the Hessian is Σ_ij Â_ij d_i d_jᵀ with Â = filter(A) (filter applied to A's
//! eigenvalues). Every filter leaves an eigenvalue ≥ its floor unchanged, so
//! when A − floor·I is positive definite (checked by an LDLᵀ pivot test) Â = A
//! and no 3×3 eigensolve is needed; the raw Hessian never needs one either.
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

use crate::filter::Filter;
use crate::modes::{Modes, outer};
use crate::spectral::{ScaleBlock, Spectral, pair_indices};

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

/// A − floor·I is positive definite (LDLᵀ pivots all > 0); false on NaN.
fn positive_definite<const D: usize>(a: &[[f64; D]; D], floor: f64) -> bool {
    let d0 = a[0][0] - floor;
    if d0.is_nan() || d0 <= 0.0 {
        return false;
    }
    let l10 = a[1][0] / d0;
    let d1 = a[1][1] - floor - a[1][0] * l10;
    if d1.is_nan() || d1 <= 0.0 {
        return false;
    }
    if D == 2 {
        return d1.is_finite() && d0.is_finite();
    }
    let l20 = a[2][0] / d0;
    let l21 = (a[2][1] - a[2][0] * l10) / d1;
    let d2 = a[2][2] - floor - a[2][0] * l20 - l21 * l21 * d1;
    d2 > 0.0 && d2.is_finite() && d1.is_finite() && d0.is_finite()
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
                } else if filter.is_raw() || positive_definite(a, filter.floor()) {
                    for i in 0..D {
                        for j in 0..D {
                            scale[i][j] = 0.5 * (a[i][j] + a[j][i]);
                        }
                    }
                    diagonal = false;
                } else {
                    let m = Modes::new(s);
                    for (z, &lam) in m.scale_vecs.iter().zip(m.scale_vals.iter()) {
                        let l = filter.apply(lam);
                        for i in 0..D {
                            for j in 0..D {
                                scale[i][j] += l * z[i] * z[j];
                            }
                        }
                    }
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
/// w_b ∈ R^M; scaled by `weight`; exactly symmetric.
#[inline(always)]
pub(crate) fn modal_sum<const D: usize, const M: usize, const R: usize>(
    u: &[[f64; D]; D],
    w: &[[f64; M]; D],
    f: &Filtered<D>,
    weight: f64,
) -> [[f64; R]; R] {
    debug_assert_eq!(R, D * M);
    let pairs = Spectral::<D>::PAIRS;
    // Shift c: the most repeated non-zero value among the pair eigenvalues and,
    // when Â is diagonal, its diagonal.
    let mut cand = [0.0; 9];
    let mut nc = 0;
    for k in 0..pairs {
        cand[nc] = f.twist[k];
        cand[nc + 1] = f.flip[k];
        nc += 2;
    }
    if f.diagonal {
        for i in 0..D {
            cand[nc] = f.scale[i][i];
            nc += 1;
        }
    }
    let mut shift = 0.0;
    let mut best = 1usize;
    for a in 0..nc {
        if cand[a] != 0.0 && cand[a].is_finite() {
            let c = cand[..nc].iter().filter(|&&x| x == cand[a]).count();
            if c > best {
                best = c;
                shift = cand[a];
            }
        }
    }

    // Left/right vectors and coefficients of the updates H += coef · l rᵀ.
    let mut vecs = [[0.0; R]; 12];
    let mut upd: [(usize, usize, f64); 9] = [(0, 0, 0.0); 9];
    let (mut nv, mut nu) = (0usize, 0usize);
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
                upd[nu] = (nv, nv, sc[i][i] * weight);
                nv += 1;
                nu += 1;
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
            upd[nu] = (nv, nv, 0.5 * lt * weight);
            nv += 1;
            nu += 1;
        }
        if ll != 0.0 {
            for x in 0..R {
                vecs[nv][x] = pji[x] + pij[x];
            }
            upd[nu] = (nv, nv, 0.5 * ll * weight);
            nv += 1;
            nu += 1;
        }
    }
    // Upper triangle, row by row (the row stays in registers across updates).
    for i in 0..R {
        let mut row = h[i];
        for &(l, r, c) in &upd[..nu] {
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
    h
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
