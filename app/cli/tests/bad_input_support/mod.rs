//! Shared by the `bad_input_*` tests: run `ecc` in a scratch folder and
//! check that it failed the way `docs/ERRORS.md` says — exit status 1 (2 for
//! command-line usage errors), a message on stderr that names what is wrong
//! and where, no panic, nothing on stdout, and no output file left behind.
#![allow(dead_code)]

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A scratch folder with the inputs of one test.
pub struct Scratch {
    dir: tempfile::TempDir,
}

impl Scratch {
    pub fn new() -> Self {
        Scratch {
            dir: tempfile::tempdir().expect("a temporary folder"),
        }
    }

    /// The folder.
    pub fn path(&self) -> &Path {
        self.dir.path()
    }

    /// Write a file (relative to the folder) and return its path as text.
    pub fn write(&self, name: &str, contents: impl AsRef<[u8]>) -> String {
        let p = self.dir.path().join(name);
        if let Some(parent) = p.parent() {
            fs::create_dir_all(parent).unwrap();
        }
        fs::write(&p, contents).unwrap();
        p.display().to_string()
    }

    /// A path inside the folder (not created).
    pub fn join(&self, name: &str) -> String {
        self.dir.path().join(name).display().to_string()
    }

    /// Run `ecc args…` in the folder, expecting exit status `code`; returns stderr.
    pub fn fails_with(&self, code: i32, args: &[&str]) -> String {
        let out = Command::new(env!("CARGO_BIN_EXE_ecc"))
            .args(args)
            .current_dir(self.dir.path())
            .env("ECC_DATA_DIR", self.dir.path().join("no-data-here"))
            .output()
            .expect("the ecc binary runs");
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert_eq!(
            out.status.code(),
            Some(code),
            "ecc {args:?}: exit status {:?}, stderr:\n{stderr}",
            out.status.code()
        );
        assert!(
            !stderr.contains("panicked") && !stderr.contains("internal error"),
            "ecc {args:?} panicked:\n{stderr}"
        );
        assert!(
            stderr.trim_start().starts_with("error"),
            "ecc {args:?}: the message must start with `error`:\n{stderr}"
        );
        assert!(
            out.stdout.is_empty(),
            "ecc {args:?} printed on stdout: {}",
            String::from_utf8_lossy(&out.stdout)
        );
        stderr
    }

    /// Run `ecc args…`, expecting exit status 1.
    pub fn fails(&self, args: &[&str]) -> String {
        self.fails_with(1, args)
    }

    /// Every regular file under the folder (relative paths), sorted.
    pub fn files(&self) -> Vec<String> {
        let mut out = Vec::new();
        walk(self.dir.path(), self.dir.path(), &mut out);
        out.sort();
        out
    }
}

fn walk(root: &Path, dir: &Path, out: &mut Vec<String>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p: PathBuf = e.path();
        if p.is_dir() {
            walk(root, &p, out);
        } else {
            out.push(p.strip_prefix(root).unwrap().display().to_string());
        }
    }
}

/// Every part must occur in the message.
pub fn says(stderr: &str, parts: &[&str]) {
    for p in parts {
        assert!(stderr.contains(p), "expected `{p}` in:\n{stderr}");
    }
}

/// Nothing was written: the folder holds exactly the inputs the test wrote.
pub fn only_inputs(s: &Scratch, inputs: &[&str]) {
    let mut want: Vec<String> = inputs.iter().map(|x| x.to_string()).collect();
    want.sort();
    assert_eq!(s.files(), want, "files left behind");
}
