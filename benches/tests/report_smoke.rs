//! CI smoke test of the report at its tiny size (seconds): every part runs,
//! the folder holds the Markdown, the PNGs and parseable JSON.

use ecc_benches::report::{self, Config, Size};

#[test]
fn tiny_report_writes_markdown_pngs_and_json() {
    let dir = tempfile::tempdir().expect("temp dir");
    let cfg = Config {
        size: Size::Tiny,
        out: dir.path().to_path_buf(),
        data: ecc_mesh::data_dir(),
        command: "report smoke test".into(),
    };
    let r = report::run(&cfg, &mut |_| {}).expect("report runs");
    assert!(r.notes.is_empty(), "problems: {:?}", r.notes);
    assert!(!r.timing.rows.is_empty() && !r.accuracy.rows.is_empty());
    assert!(!r.traces.is_empty() && !r.scaling.is_empty());
    // the headline methods ran in two interleaved rounds and kept one trace each
    for t in &r.rounds {
        assert_eq!(
            (t.defaults.len(), t.one_thread.len(), t.autodiff.len()),
            (2, 2, 2),
            "{t:?}"
        );
        for m in ecc_benches::report::rounds::PAIRED {
            let kept = r
                .traces
                .iter()
                .filter(|x| x.problem == t.problem && x.method == m);
            assert_eq!(kept.count(), 1, "{} / {m:?}", t.problem);
        }
    }
    assert!(!r.rounds.is_empty());
    let md = std::fs::read_to_string(dir.path().join("BENCHMARKS.md")).expect("markdown");
    for section in [
        "## Headline numbers",
        "## 1. Per element",
        "## 2. Per solve",
        "### Autodiff baseline",
        "## 3. Scaling",
        "## How it is measured",
        "| CPU |",
    ] {
        assert!(md.contains(section), "missing {section}");
    }
    let pngs: Vec<_> = std::fs::read_dir(dir.path())
        .expect("listing")
        .filter_map(|e| e.ok())
        .filter(|e| e.path().extension().is_some_and(|x| x == "png"))
        .collect();
    assert!(pngs.len() >= 5, "{} PNGs", pngs.len());
    for p in &pngs {
        let bytes = std::fs::read(p.path()).expect("png");
        assert_eq!(&bytes[1..4], b"PNG");
        assert!(
            md.contains(&*p.file_name().to_string_lossy()),
            "{:?} not linked",
            p.file_name()
        );
    }
    let json: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("results.json")).expect("json"),
    )
    .expect("valid JSON");
    assert!(json["traces"].as_array().is_some_and(|t| !t.is_empty()));
    // the autodiff baseline: a row per energy it has a form for (the tiny run
    // builds all of them), raw Hessians equal to ecc's, and a solve
    assert_eq!(r.autodiff.rows.len(), 5, "{:?}", r.autodiff.rows);
    for x in &r.autodiff.rows {
        assert!(
            x.max_rel_diff <= 1e-10,
            "{}D {}: {:e}",
            x.dim,
            x.energy,
            x.max_rel_diff
        );
        assert!(x.autodiff_ns > 0.0 && x.analytic_ns > 0.0);
    }
    assert!(
        r.traces
            .iter()
            .any(|t| format!("{:?}", t.method) == "Autodiff" && t.points.len() > 1)
    );
    // the analytic kernel is at least as accurate as f32 on the measured classes
    let f32_err = r
        .accuracy
        .rows
        .iter()
        .filter(|x| format!("{:?}", x.method) == "GenericF32")
        .map(|x| x.hess_err)
        .fold(0.0, f64::max);
    let an_err = r
        .accuracy
        .rows
        .iter()
        .filter(|x| format!("{:?}", x.method) == "Analytic")
        .map(|x| x.hess_err)
        .fold(0.0, f64::max);
    assert!(
        an_err < 1e-10 && f32_err > an_err,
        "analytic {an_err:e}, f32 {f32_err:e}"
    );
}

#[test]
fn writing_into_a_file_path_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().expect("temp dir");
    let file = dir.path().join("not_a_folder");
    std::fs::write(&file, "x").expect("file");
    let r = report::Results {
        size: Size::Tiny,
        command: String::new(),
        machine: Default::default(),
        timing: Default::default(),
        accuracy: Default::default(),
        autodiff: Default::default(),
        problems: vec![],
        traces: vec![],
        rounds: vec![],
        solve_limits: (0.0, 0, 0),
        scaling: vec![],
        scaling_iters: 0,
        notes: vec![],
        seconds: 0.0,
    };
    let e = report::write(&r, &file).expect_err("a file is not a folder");
    assert!(e.to_string().contains("not_a_folder"), "{e}");
}
