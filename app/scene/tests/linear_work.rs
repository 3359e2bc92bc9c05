//! `linear` in the summary (symbolic analyses, numeric factorisations, CG
//! iterations, reused-factor steps): present for every linear solver and
//! consistent with the Newton iterations and the per-solve entries.

use ecc_scene::summary::LinearWork;
use ecc_scene::{RunOptions, RunReport, RuntimeEnergies, SceneFile, Silent, Summary, run_scene};

fn run(text: &str) -> RunReport {
    let f = SceneFile::parse(text, "scene.toml", ".").unwrap();
    let opts = RunOptions {
        dry_run: true,
        ..Default::default()
    };
    run_scene(&f, &RuntimeEnergies, &opts, &mut Silent).unwrap()
}

fn disk(linear: &str) -> String {
    format!(
        "[mesh]\ngenerate = \"disk\"\nrings = 6\n[energy]\nname = \"sd\"\n\
         [effects.parameterize]\ntutte = \"uniform\"\n[solver]\ntol = 1e-8\nlinear = \"{linear}\"\n"
    )
}

/// Shift attempts per Newton step (`NewtonParams::shift_attempts`).
const SHIFT_ATTEMPTS: usize = 12;

/// The run totals are the sums of the solves' entries.
fn totals_match_solves(s: &Summary) {
    let sum = |f: fn(&LinearWork) -> usize| s.solves.iter().map(|l| f(&l.linear)).sum::<usize>();
    assert_eq!(
        s.linear.numeric_factorizations,
        sum(|l| l.numeric_factorizations)
    );
    assert_eq!(s.linear.cg_iterations, sum(|l| l.cg_iterations));
    assert_eq!(s.linear.reused_factor_steps, sum(|l| l.reused_factor_steps));
}

#[test]
fn every_linear_solver_reports_consistent_counts() {
    for linear in ["cholesky", "pcg", "auto"] {
        let s = run(&disk(linear)).summary;
        assert!(s.frames[1].converged, "{linear}");
        let (n, w) = (s.newton_iterations, s.linear);
        assert!(n > 0);
        totals_match_solves(&s);
        // every step factorises (with shift retries) or runs CG, or both
        assert!(
            w.numeric_factorizations <= n * SHIFT_ATTEMPTS,
            "{linear}: {w:?}"
        );
        assert!(
            w.numeric_factorizations + w.cg_iterations >= n,
            "{linear}: {w:?}"
        );
        assert_eq!(w.reused_factor_steps, 0);
        match linear {
            "cholesky" => {
                assert_eq!(w.symbolic_analyses, 1);
                assert!(w.numeric_factorizations >= n);
                assert_eq!(w.cg_iterations, 0);
            }
            "pcg" => {
                assert_eq!(w.symbolic_analyses, 0);
                assert_eq!(w.numeric_factorizations, 0);
                assert!(w.cg_iterations >= n);
            }
            // the analysis that priced the factor
            _ => assert_eq!(w.symbolic_analyses, 1),
        }
    }
}

#[test]
fn frame_scenes_sum_the_solves_and_keep_one_analysis() {
    let s = run(
        "frames = 2\n[mesh]\ngenerate = \"bar\"\nresolution = 1\n[energy]\nname = \"snh\"\n\
         [[effects.handles]]\nplane = { point = [-1.9, 0, 0], normal = [-1, 0, 0] }\n\
         [[effects.handles]]\nplane = { point = [1.9, 0, 0], normal = [1, 0, 0] }\n\
         keys = [ { frame = 2, rotate = [60, 0, 0] } ]\n\
         [solver]\ntol = 1e-8\nlinear = \"cholesky\"\nfactor_reuse = true\n",
    )
    .summary;
    assert!(s.solves.len() >= 2);
    totals_match_solves(&s);
    assert_eq!(s.linear.symbolic_analyses, 1);
    let w = s.linear;
    assert!(
        w.numeric_factorizations + w.reused_factor_steps >= s.newton_iterations,
        "{w:?}"
    );
    assert!(w.reused_factor_steps <= s.newton_iterations);
    let json = serde_json::to_value(&s).unwrap();
    for key in [
        "symbolic_analyses",
        "numeric_factorizations",
        "cg_iterations",
        "reused_factor_steps",
    ] {
        assert!(json["linear"][key].is_u64(), "{key}");
        assert!(json["solves"][0]["linear"][key].is_u64(), "{key}");
    }
}
