//! Stretch-space description of an energy's derivatives at one point.

/// The index pairs (i, j) of the twist/flip modes, by pair slot `k`.
///
/// 3D follows Smith et al. 2019: slot k is the twist about axis k, so the
/// pair is the two *other* axes in cyclic order: k=0 → (1, 2), k=1 → (2, 0),
/// k=2 → (0, 1). 2D has the single slot k=0 → (0, 1).
pub const PAIRS_3D: [(usize, usize); 3] = [(1, 2), (2, 0), (0, 1)];
/// The single 2D pair (see [`PAIRS_3D`]).
pub const PAIRS_2D: [(usize, usize); 1] = [(0, 1)];

/// The pair (i, j) for slot `k` in dimension `D` (2 or 3).
#[inline]
pub const fn pair_indices<const D: usize>(k: usize) -> (usize, usize) {
    if D == 2 { PAIRS_2D[k] } else { PAIRS_3D[k] }
}

/// The d×d scaling block A = ∂²Ψ/∂σ² (Smith et al. 2019, App. D; Zhu 2020, §4).
///
/// `Diagonal` is used when the off-diagonals are known to vanish identically
/// (proved by the CAS, or known by hand): the scaling modes d_i are then
/// eigenvectors with eigenvalues A_ii and no eigensolve is needed.
/// `Full` is row-major and symmetric.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ScaleBlock<const D: usize> {
    /// A = diag(a): the scaling modes decouple.
    Diagonal([f64; D]),
    /// A general symmetric A (row-major, `a[i][j] == a[j][i]`).
    Full([[f64; D]; D]),
}

impl<const D: usize> ScaleBlock<D> {
    /// Entry A_ij.
    #[inline]
    pub fn get(&self, i: usize, j: usize) -> f64 {
        match self {
            ScaleBlock::Diagonal(a) => {
                if i == j {
                    a[i]
                } else {
                    0.0
                }
            }
            ScaleBlock::Full(a) => a[i][j],
        }
    }

    /// The block as a dense row-major matrix.
    pub fn to_dense(&self) -> [[f64; D]; D] {
        let mut m = [[0.0; D]; D];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = self.get(i, j);
            }
        }
        m
    }
}

/// Ψ and its stretch-space derivatives at one point, as an energy supplies them.
///
/// For `D == 2` only slot 0 of `twist`/`flip` is meaningful (pair (0, 1));
/// slots 1 and 2 must be ignored by consumers (energies set them to 0).
/// For `D == 3`, slot k holds the pair [`PAIRS_3D`]`[k]`.
///
/// Values must be exact limits on the singular sets: at σ_i = σ_j an energy
/// supplies lim (Ψ_i − Ψ_j)/(σ_i − σ_j); where a limit does not exist (a
/// genuine singularity of the energy, e.g. ARAP's 2Ψ_I1/(σ_i + σ_j) at
/// σ_i + σ_j = 0) it may return a non-finite value, and the runtime's filters
/// decide what to do with it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spectral<const D: usize> {
    /// Ψ(σ); `+∞` outside the energy's domain.
    pub psi: f64,
    /// ∂Ψ/∂σ_i.
    pub grad: [f64; D],
    /// A = ∂²Ψ/∂σ².
    pub scale: ScaleBlock<D>,
    /// λ_twist for each pair slot: (Ψ_i + Ψ_j)/(σ_i + σ_j).
    pub twist: [f64; 3],
    /// λ_flip for each pair slot: (Ψ_i − Ψ_j)/(σ_i − σ_j).
    pub flip: [f64; 3],
}

impl<const D: usize> Spectral<D> {
    /// The number of twist/flip pair slots in use: 1 in 2D, 3 in 3D.
    pub const PAIRS: usize = D * (D - 1) / 2;

    /// A point outside the energy's domain: Ψ = +∞, all derivatives NaN-free zeros.
    pub fn infinite() -> Self {
        Spectral {
            psi: f64::INFINITY,
            grad: [0.0; D],
            scale: ScaleBlock::Diagonal([0.0; D]),
            twist: [0.0; 3],
            flip: [0.0; 3],
        }
    }
}
