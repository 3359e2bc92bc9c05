//! Replays the committed cargo-fuzz corpus of scene files
//! (`fuzz/corpus/scene`, minimised) and the seeds (the shipped scenes)
//! through exactly the code the fuzz target runs
//! (`fuzz/fuzz_targets/scene_common.rs`: parse, check keys, locate and
//! render errors). Any panic fails the test. See `fuzz/README.md`.

#[path = "../../../fuzz/fuzz_targets/scene_common.rs"]
mod scene_common;

use std::path::PathBuf;

#[test]
fn scene_corpus() {
    let root = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../fuzz"));
    let mut n = 0;
    for dir in ["corpus/scene", "seeds/scene"] {
        let Ok(entries) = std::fs::read_dir(root.join(dir)) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            let bytes = std::fs::read(&p).unwrap();
            let r = std::panic::catch_unwind(|| scene_common::run(&bytes));
            assert!(r.is_ok(), "{} panics", p.display());
            n += 1;
        }
    }
    assert!(n >= 5, "only {n} inputs found");
    println!("{n} scene inputs replayed");
}
