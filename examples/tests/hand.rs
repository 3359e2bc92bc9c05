//! §6.2 at reduced size (the middle finger of hand.mesh, 2k tets): the
//! handles are reached exactly, the stored energy grows with the motion,
//! every frame converges and no tet inverts, for ARAP and Stable Neo-Hookean.

use ecc_examples::{Output, Size, hand};
use ecc_scene::FinalState;

fn check(energy: &str) {
    let r = hand(energy, Size::Reduced, &Output::Nowhere).unwrap();
    let s = &r.summary;
    assert_eq!(s.mode, "quasi_static");
    assert_eq!(s.handles.len(), 2);
    assert!(
        s.mesh.elements > 1500 && s.mesh.elements < 2500,
        "{}",
        s.mesh.elements
    );
    assert_eq!(s.converged_frames, 2, "{:?}", s.warnings);
    for f in &s.frames {
        assert!(
            f.handle_error.unwrap() < 1e-12,
            "frame {}: {:?}",
            f.frame,
            f.handle_error
        );
        assert_eq!(f.inverted, 0, "frame {}", f.frame);
    }
    let e: Vec<f64> = s.frames.iter().map(|f| f.elastic_energy).collect();
    assert!(e[0] < e[1] && e[1] < e[2], "{energy}: {e:?}");
    // the tip moved, the base did not
    let FinalState::Volume { rest, x, .. } = &r.state else {
        panic!("a volume")
    };
    let moved = |vs: &[usize]| -> f64 {
        vs.iter()
            .map(|&v| {
                (0..3)
                    .map(|c| (x[v][c] - rest[v][c]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .fold(0.0, f64::max)
    };
    assert_eq!(moved(&r.handles[0]), 0.0);
    assert!(moved(&r.handles[1]) > 0.1);
}

#[test]
fn finger_bends_with_arap() {
    check("arap");
}

#[test]
fn finger_bends_with_stable_neo_hookean() {
    check("snh");
}
