//! §6.5 at reduced size: a bar dropped onto a barrier ground never goes
//! below it, falls, lands and settles, and (with BDF2 and damping) its total
//! energy — kinetic + elastic + gravitational + contact — never grows.

use ecc_examples::{Output, Size, falling_bar};

#[test]
fn bar_falls_lands_and_never_passes_the_ground() {
    let r = falling_bar(Size::Reduced, &Output::Nowhere).unwrap();
    let s = &r.summary;
    assert_eq!(s.mode, "dynamic");
    let names: Vec<&str> = s.terms.iter().map(|t| t.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "elastic",
            "gravity",
            "inertia",
            "damping_stiffness",
            "ground"
        ]
    );
    assert_eq!(s.counters.mass_matrix_builds, 1);
    assert_eq!(s.converged_frames, 40, "{:?}", s.warnings);
    // nothing below the ground, ever
    for f in &s.frames {
        assert!(f.min_ground_distance.unwrap() > 0.0, "frame {}", f.frame);
        assert_eq!(f.inverted, 0, "frame {}", f.frame);
    }
    let d: Vec<f64> = s
        .frames
        .iter()
        .map(|f| f.min_ground_distance.unwrap())
        .collect();
    let g: Vec<f64> = s
        .frames
        .iter()
        .map(|f| f.gravity_potential.unwrap())
        .collect();
    // it falls (potential drops) and lands (touches the barrier zone, dhat = 0.01)
    assert!(g[10] < g[0] && d.iter().any(|x| *x < 0.01), "{d:?}");
    // total energy is non-increasing up to the solver tolerance
    let total: Vec<f64> = s.frames.iter().map(|f| f.total_energy).collect();
    let scale = g[0].abs();
    for (k, w) in total.windows(2).enumerate() {
        assert!(
            w[1] <= w[0] + 1e-6 * scale,
            "frame {}: total energy grew {} -> {}",
            k + 1,
            w[0],
            w[1]
        );
    }
    // and much of it was dissipated by the end
    assert!(total[0] - total[40] > 0.2 * (g[0] - g.iter().copied().fold(f64::INFINITY, f64::min)));
}
