//! Part 1 of the report: per-element time and accuracy of each way to get
//! a (projected) element Hessian. See [`Method`] for exactly what each runs.

pub mod accuracy;
pub mod autodiff;
pub mod kernels;
pub mod timing;

use serde::Serialize;

/// The ways of computing an element's energy, gradient and Hessian.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Method {
    /// Generated energy (ecc-energies) in `element_eval` with
    /// `Filter::Clamp`: signed SVD, closed-form eigenvalues, modal Hessian.
    Analytic,
    /// The same kernel with the energy interpreted at run time from its
    /// `.psi` text (ecc-interp, the `ecc eval` path).
    Interpreted,
    /// Numeric F-space projection: the raw d²×d² F-Hessian (analytic,
    /// generated energy) projected by nalgebra `SymmetricEigen`, then the
    /// dense chain rule m Bᵀ P(H) B with a precomputed B.
    NumericF,
    /// Numeric element projection: the raw (d+1)d element Hessian
    /// (`Filter::None`) projected by nalgebra `SymmetricEigen`.
    NumericElement,
    /// The raw element Hessian, not projected (`Filter::None`).
    Unprojected,
    /// This crate's precision-generic analytic kernel in f64 (reference
    /// point for the f32 row; not the runtime's code).
    GenericF64,
    /// The same generic kernel in f32 (inputs rounded to f32).
    GenericF32,
}

impl Method {
    /// All methods in table order.
    pub const ALL: [Method; 7] = [
        Method::Analytic,
        Method::Interpreted,
        Method::NumericF,
        Method::NumericElement,
        Method::Unprojected,
        Method::GenericF64,
        Method::GenericF32,
    ];

    /// Column label for dimension `d`.
    pub fn label(self, d: usize) -> String {
        let (nf, ne) = (d * d, d * (d + 1));
        match self {
            Method::Analytic => "analytic (generated)".into(),
            Method::Interpreted => "interpreted (ecc eval)".into(),
            Method::NumericF => format!("numeric {nf}×{nf} F-proj."),
            Method::NumericElement => format!("numeric {ne}×{ne} elem.-proj."),
            Method::Unprojected => "unprojected".into(),
            Method::GenericF64 => "generic kernel f64".into(),
            Method::GenericF32 => "generic kernel f32".into(),
        }
    }

    /// Which reference the method is compared with.
    pub fn target(self) -> Target {
        match self {
            Method::NumericElement => Target::ElementProjection,
            Method::Unprojected => Target::Raw,
            _ => Target::FProjection,
        }
    }
}

/// What a method's Hessian should equal exactly.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// m Bᵀ P(∂²Ψ/∂f²) B.
    FProjection,
    /// P(m Bᵀ ∂²Ψ/∂f² B).
    ElementProjection,
    /// m Bᵀ ∂²Ψ/∂f² B.
    Raw,
}
