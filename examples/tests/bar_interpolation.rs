//! §6.3 at reduced size: symmetric ARAP interpolation between a straight
//! bar and a twisted, bent copy keeps every tet uninverted (barrier), hits
//! zero energy at both ends (each end is its own rest shape, up to a rigid
//! motion) and stores energy in between.

use ecc_examples::{Output, Size, bar_interpolation};

#[test]
fn sarap_interpolation_is_inversion_free_and_exact_at_the_ends() {
    let r = bar_interpolation(Size::Reduced, &Output::Nowhere).unwrap();
    let s = &r.summary;
    assert_eq!(s.mode, "interpolation");
    assert!(s.energy.barrier, "SARAP is a barrier energy");
    assert_eq!(s.terms.len(), 1);
    assert_eq!(s.terms[0].name, "interpolation");
    let t: Vec<f64> = s.frames.iter().map(|f| f.t.unwrap()).collect();
    assert_eq!(t, [0.0, 0.25, 0.5, 0.75, 1.0]);
    for f in &s.frames {
        assert_eq!(f.inverted, 0, "t = {:?}", f.t);
        assert!(f.min_measure > 0.0);
        assert!(f.converged, "t = {:?}: {:?}", f.t, f.statuses);
    }
    let e: Vec<f64> = s.frames.iter().map(|f| f.elastic_energy).collect();
    assert!(e[0].abs() < 1e-12 && e[4].abs() < 1e-8, "{e:?}");
    assert!(e[1..4].iter().all(|v| *v > 1e-3), "{e:?}");
}
