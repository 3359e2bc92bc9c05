//! Per-element fibre fields: generators, MEDIT reference tables, checks.
//!
//! A fibre field is one direction per element (`Vec<[f64; D]>`, element
//! order). It comes from a file ([`read_vtk_fibres`]: VTK cell data;
//! [`crate::io::fibres::parse_medit_references`] + [`from_references`]: a
//! MEDIT reference table) or from a generator evaluated at the element
//! centroids ([`FibreGenerator`]). Directions need not be unit (the FEM term
//! normalises them); [`check_directions`] rejects zero and non-finite ones
//! with the element's id. Every error names its element.

use std::path::Path;

use crate::error::MeshError;
use crate::io::fibres::parse_vtk_cell_vectors;

/// A fibre field could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FibreError {
    /// A direction is zero or not finite.
    #[error("element {element}: fibre direction {direction:?} is zero or not finite")]
    BadDirection {
        /// Element index (0-based).
        element: usize,
        /// The offending direction.
        direction: Vec<f64>,
    },
    /// A MEDIT reference has no entry in the table.
    #[error(
        "element {element}: reference {reference} has no fibre direction (the table has {known:?})"
    )]
    UnmappedReference {
        /// Element index (0-based).
        element: usize,
        /// Its MEDIT reference.
        reference: i64,
        /// The references the table maps.
        known: Vec<i64>,
    },
    /// The generator's direction is undefined at an element's centroid.
    #[error("element {element}: {reason}")]
    Undefined {
        /// Element index (0-based).
        element: usize,
        /// Why.
        reason: String,
    },
    /// The field has the wrong number of entries.
    #[error("{what}: {got} entries for {expected} elements")]
    Count {
        /// Which field.
        what: String,
        /// Number of elements.
        expected: usize,
        /// Entries found.
        got: usize,
    },
    /// The generator itself is invalid (zero axis, too few curve points, …).
    #[error("fibre generator: {0}")]
    Generator(String),
}

/// How to generate a fibre per element from its centroid c.
#[derive(Clone, Debug, PartialEq)]
pub enum FibreGenerator<const D: usize> {
    /// The same direction everywhere.
    Constant([f64; D]),
    /// Circumferential around the axis through `point` along `axis`:
    /// a = axis × (c − point) (3D); in 2D the axis is ignored and a is
    /// (c − point) turned by +90°.
    Around {
        /// A point on the axis.
        point: [f64; D],
        /// Axis direction (3D; unused in 2D).
        axis: [f64; D],
    },
    /// Helical around the same axis: a = cos θ t + sin θ â with t the
    /// circumferential unit direction and θ the angle (radians) from it
    /// towards the axis (3D only; θ = 0 is [`FibreGenerator::Around`]).
    Helix {
        /// A point on the axis.
        point: [f64; D],
        /// Axis direction.
        axis: [f64; D],
        /// Angle from the circumferential direction towards the axis.
        angle: f64,
    },
    /// Along a polyline: the tangent of the segment nearest to c.
    Curve(Vec<[f64; D]>),
}

fn sub<const D: usize>(a: &[f64; D], b: &[f64; D]) -> [f64; D] {
    std::array::from_fn(|i| a[i] - b[i])
}

fn dot<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    (0..D).map(|i| a[i] * b[i]).sum()
}

fn unit<const D: usize>(a: &[f64; D]) -> Option<[f64; D]> {
    let n = dot(a, a).sqrt();
    (n > 0.0 && n.is_finite()).then(|| a.map(|x| x / n))
}

/// Element centroids.
pub fn centroids<const D: usize, const K: usize>(
    positions: &[[f64; D]],
    elements: &[[usize; K]],
) -> Vec<[f64; D]> {
    elements
        .iter()
        .map(|el| {
            std::array::from_fn(|i| el.iter().map(|&v| positions[v][i]).sum::<f64>() / K as f64)
        })
        .collect()
}

/// The circumferential unit direction around (point, axis) at c.
fn around<const D: usize>(c: &[f64; D], point: &[f64; D], axis: &[f64; D]) -> Option<[f64; D]> {
    let r = sub(c, point);
    let t: [f64; D] = if D == 3 {
        std::array::from_fn(|i| {
            axis[(i + 1) % 3] * r[(i + 2) % 3] - axis[(i + 2) % 3] * r[(i + 1) % 3]
        })
    } else {
        std::array::from_fn(|i| if i == 0 { -r[1] } else { r[0] })
    };
    unit(&t)
}

/// Tangent of the polyline segment nearest to c.
fn curve_tangent<const D: usize>(c: &[f64; D], pts: &[[f64; D]]) -> [f64; D] {
    let mut best = (f64::INFINITY, [0.0; D]);
    for w in pts.windows(2) {
        let d = sub(&w[1], &w[0]);
        let t = (dot(&sub(c, &w[0]), &d) / dot(&d, &d)).clamp(0.0, 1.0);
        let q: [f64; D] = std::array::from_fn(|i| w[0][i] + t * d[i]);
        let dist = dot(&sub(c, &q), &sub(c, &q));
        if dist < best.0 {
            best = (dist, d);
        }
    }
    best.1
}

impl<const D: usize> FibreGenerator<D> {
    fn validate(&self) -> Result<(), FibreError> {
        let bad = |m: &str| Err(FibreError::Generator(m.to_string()));
        match self {
            FibreGenerator::Constant(d) if unit(d).is_none() => {
                bad("the constant direction is zero or not finite")
            }
            FibreGenerator::Around { axis, .. } | FibreGenerator::Helix { axis, .. }
                if D == 3 && unit(axis).is_none() =>
            {
                bad("the axis is zero or not finite")
            }
            FibreGenerator::Helix { angle, .. } if !angle.is_finite() || D != 3 => {
                bad("a helix needs 3D and a finite angle")
            }
            FibreGenerator::Curve(p)
                if p.len() < 2 || p.windows(2).any(|w| unit(&sub(&w[1], &w[0])).is_none()) =>
            {
                bad("a curve needs at least two points and no repeated consecutive points")
            }
            _ => Ok(()),
        }
    }

    /// One unit direction per centroid.
    pub fn generate(&self, centroids: &[[f64; D]]) -> Result<Vec<[f64; D]>, FibreError> {
        self.validate()?;
        let on_axis = |element| FibreError::Undefined {
            element,
            reason: "its centroid lies on the axis, where the direction around it is undefined"
                .into(),
        };
        centroids
            .iter()
            .enumerate()
            .map(|(q, c)| match self {
                FibreGenerator::Constant(d) => Ok(unit(d).unwrap_or(*d)),
                FibreGenerator::Around { point, axis } => {
                    around(c, point, axis).ok_or_else(|| on_axis(q))
                }
                FibreGenerator::Helix { point, axis, angle } => {
                    let t = around(c, point, axis).ok_or_else(|| on_axis(q))?;
                    let a = unit(axis).unwrap_or(*axis);
                    Ok(std::array::from_fn(|i| {
                        angle.cos() * t[i] + angle.sin() * a[i]
                    }))
                }
                FibreGenerator::Curve(p) => Ok(unit(&curve_tangent(c, p)).unwrap_or([0.0; D])),
            })
            .collect()
    }
}

/// Directions from per-element MEDIT references and a reference → direction table.
pub fn from_references<const D: usize>(
    refs: &[i64],
    table: &[(i64, [f64; D])],
) -> Result<Vec<[f64; D]>, FibreError> {
    let dirs = refs
        .iter()
        .enumerate()
        .map(|(q, r)| {
            table
                .iter()
                .find(|(k, _)| k == r)
                .map(|(_, d)| *d)
                .ok_or_else(|| FibreError::UnmappedReference {
                    element: q,
                    reference: *r,
                    known: table.iter().map(|(k, _)| *k).collect(),
                })
        })
        .collect::<Result<Vec<_>, _>>()?;
    check_directions(&dirs, refs.len(), "references")?;
    Ok(dirs)
}

/// `n` entries, none zero or non-finite.
pub fn check_directions<const D: usize>(
    dirs: &[[f64; D]],
    n: usize,
    what: &str,
) -> Result<(), FibreError> {
    if dirs.len() != n {
        return Err(FibreError::Count {
            what: what.to_string(),
            expected: n,
            got: dirs.len(),
        });
    }
    match dirs.iter().position(|d| unit(d).is_none()) {
        Some(q) => Err(FibreError::BadDirection {
            element: q,
            direction: dirs[q].to_vec(),
        }),
        None => Ok(()),
    }
}

/// Per-cell directions from a legacy ASCII VTK file's cell data (the first
/// of `names` present, see [`crate::io::fibres`]).
pub fn read_vtk_fibres<const D: usize>(
    path: impl AsRef<Path>,
    names: &[&str],
) -> Result<Vec<[f64; D]>, MeshError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|source| MeshError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse_vtk_cell_vectors(&text, names).map_err(|e| e.at(path))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generators() {
        let c = [[1.0, 0.0, 0.5], [0.0, 2.0, 0.0]];
        let g = FibreGenerator::Constant([2.0, 0.0, 0.0])
            .generate(&c)
            .unwrap();
        assert_eq!(g, vec![[1.0, 0.0, 0.0]; 2]);
        let around = FibreGenerator::Around {
            point: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
        };
        assert_eq!(
            around.generate(&c).unwrap(),
            vec![[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]]
        );
        let h = FibreGenerator::Helix {
            point: [0.0; 3],
            axis: [0.0, 0.0, 2.0],
            angle: std::f64::consts::FRAC_PI_4,
        };
        let d = h.generate(&c).unwrap()[0];
        let s = std::f64::consts::FRAC_1_SQRT_2;
        assert!((d[0]).abs() < 1e-15 && (d[1] - s).abs() < 1e-15 && (d[2] - s).abs() < 1e-15);
        let curve = FibreGenerator::Curve(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 3.0, 0.0]]);
        assert_eq!(
            curve.generate(&[[0.5, 0.1, 0.0], [1.2, 2.0, 0.0]]).unwrap(),
            vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        );
        let a2 = FibreGenerator::Around {
            point: [0.0, 0.0],
            axis: [0.0, 0.0],
        };
        assert_eq!(a2.generate(&[[2.0, 0.0]]).unwrap(), vec![[0.0, 1.0]]);
    }

    #[test]
    fn errors_name_their_element() {
        let around = FibreGenerator::Around {
            point: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
        };
        let e = around
            .generate(&[[1.0, 0.0, 0.0], [0.0, 0.0, 3.0]])
            .unwrap_err();
        assert!(matches!(e, FibreError::Undefined { element: 1, .. }), "{e}");
        assert!(
            FibreGenerator::Constant([0.0; 3])
                .generate(&[[0.0; 3]])
                .is_err()
        );
        assert!(
            FibreGenerator::Curve(vec![[0.0; 2]])
                .generate(&[[0.0; 2]])
                .is_err()
        );
        let e = from_references(&[1, 2, 7], &[(1, [1.0, 0.0]), (2, [0.0, 1.0])]).unwrap_err();
        assert_eq!(
            e,
            FibreError::UnmappedReference {
                element: 2,
                reference: 7,
                known: vec![1, 2]
            }
        );
        let e = check_directions(&[[1.0, 0.0], [0.0, f64::NAN]], 2, "x").unwrap_err();
        assert!(e.to_string().starts_with("element 1:"), "{e}");
        assert!(matches!(
            check_directions(&[[1.0, 0.0]], 2, "x"),
            Err(FibreError::Count {
                expected: 2,
                got: 1,
                ..
            })
        ));
        let e = read_vtk_fibres::<3>("/nonexistent/x.vtk", &["fiber"]).unwrap_err();
        assert!(e.to_string().contains("/nonexistent/x.vtk"), "{e}");
    }
}
