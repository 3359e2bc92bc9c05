//! `[fibers]` (alias `[fibres]`): a fibre term ψ(I4, I5) added to the body
//! (issue #16). Exactly one source of directions:
//!
//! | key | directions |
//! |---|---|
//! | `direction = [1, 0, 0]` | the same everywhere |
//! | `field = "fiber"` | VTK cell data of `mesh.file` (a `.vtk`) |
//! | `references = { 1 = [1, 0, 0], 2 = [0, 1, 0] }` | MEDIT element references of `mesh.file` (a `.mesh`) |
//! | `around = { point = [..], axis = [..], angle = 30 }` | circumferential around the axis, turned by `angle` degrees towards it (a helix; 3D) |
//! | `curve = [[x, y, z], ..]` | the tangent of the nearest polyline segment |
//!
//! `energy` is a fibre energy of the scene's provider by name (`fibre-stvk`
//! (default), `fibre-arap`, `fibre-fung`) with `params` (`mu`; `k1`, `k2`),
//! or a `.psi` file whose fibre part ψ(I4, I5) is taken (a file with a
//! non-zero isotropic part is refused there). The fibre part of
//! `[energy] psi` needs this table for its directions and refuses `energy`
//! and `params` here (see `crate::terms::fibre`).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// The `[fibers]` table.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FibreSpec {
    /// `fibre-stvk` (default), `fibre-arap`, `fibre-fung`, or a `.psi` path.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub energy: Option<String>,
    /// Parameter values by name.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub params: BTreeMap<String, f64>,
    /// One direction for every element.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<Vec<f64>>,
    /// Name of a VTK cell-data array of `mesh.file`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field: Option<String>,
    /// MEDIT reference → direction.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub references: Option<BTreeMap<String, Vec<f64>>>,
    /// Circumferential / helical fibres around an axis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub around: Option<AroundSpec>,
    /// Fibres along a polyline.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curve: Option<Vec<Vec<f64>>>,
}

/// `around = { point, axis, angle }`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AroundSpec {
    /// A point on the axis.
    pub point: Vec<f64>,
    /// The axis direction (3D; unused in 2D).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis: Option<Vec<f64>>,
    /// Degrees from the circumferential direction towards the axis (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angle: Option<f64>,
}
