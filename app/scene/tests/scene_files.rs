//! Every scene shipped in `scenes/` parses and passes the value checks.

use ecc_scene::SceneFile;
use ecc_scene::spec::validate;

#[test]
fn shipped_scenes_parse_and_validate() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let f = SceneFile::read(&path).unwrap_or_else(|e| panic!("{e}"));
            validate::check(&f.scene).unwrap_or_else(|e| panic!("{}", f.locate(e)));
            n += 1;
        }
    }
    assert!(
        n >= 6,
        "expected the demo and the examples' scenes, found {n}"
    );
}
