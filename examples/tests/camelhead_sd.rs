//! §6.1 at reduced size: symmetric Dirichlet decreases from the Tutte start
//! to a converged map, stays ≥ 2 (its value for an isometry) and never
//! flips a triangle (it is a barrier).

use ecc_examples::{Output, Size, camelhead_sd};
use ecc_scene::FinalState;

#[test]
fn camelhead_patch_parameterisation_is_flip_free_and_decreases_sd() {
    let r = camelhead_sd(Size::Reduced, &Output::Nowhere).unwrap();
    let s = &r.summary;
    assert_eq!(s.mode, "parameterization");
    assert!(
        s.mesh.elements > 3000 && s.mesh.elements < 3500,
        "{}",
        s.mesh.elements
    );
    let (start, end) = (&s.frames[0], &s.frames[1]);
    assert!(end.converged, "{:?}", end.statuses);
    assert!(
        end.elastic_energy < start.elastic_energy,
        "{} vs {}",
        end.elastic_energy,
        start.elastic_energy
    );
    // unit total area: the objective is the area-weighted mean SD, ≥ 2
    assert!(
        s.final_energy >= 2.0 && s.final_energy < 2.5,
        "{}",
        s.final_energy
    );
    assert_eq!(start.inverted, 0);
    assert_eq!(end.inverted, 0);
    let FinalState::Param { mesh, uv } = &r.state else {
        panic!("a parameterisation")
    };
    assert_eq!(uv.len(), mesh.positions.len());
    // the energy decreased monotonically along the Newton iterates
    let e: Vec<f64> = s.solves[0].points.iter().map(|p| p.energy).collect();
    assert!(e.windows(2).all(|w| w[1] <= w[0] + 1e-12), "{e:?}");
}
