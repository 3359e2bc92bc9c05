//! What the scene fuzz target does with its input (shared with the corpus
//! replay test `app/scene/tests/bad_input_fuzz_corpus.rs`): TOML
//! parsing, key checking with did-you-mean and the location of every error
//! (`ecc_scene::SceneFile::parse`). Rendering the error must not panic
//! either (it slices the text at the reported span).

/// Run one input (any bytes; non-UTF-8 is skipped).
pub fn run(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Err(e) = ecc_scene::SceneFile::parse(text, "fuzz.toml", ".") {
        let _ = e.to_string();
    }
}
