//! Fuzz the `.psi` front end and the interpreter (see `psi_common.rs`).
#![no_main]

mod psi_common;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    psi_common::run(data);
});
