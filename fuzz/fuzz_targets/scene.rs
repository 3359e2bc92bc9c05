//! Fuzz scene files (see `scene_common.rs`).
#![no_main]

mod scene_common;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    scene_common::run(data);
});
