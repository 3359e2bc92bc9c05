//! Every kind of bad input: non-zero exit, a clear message on stderr, no panic.

mod common;

use common::{fails, lib};

const F3: &str = "1 0 0; 0 1 0; 0 0 1";

fn contains_all(stderr: &str, parts: &[&str]) {
    for p in parts {
        assert!(stderr.contains(p), "expected `{p}` in:\n{stderr}");
    }
}

#[test]
fn unreadable_and_invalid_energy_files() {
    let e = fails(&["eval", "/no/such/energy.psi", "--F", F3]);
    contains_all(&e, &["cannot read", "/no/such/energy.psi"]);
    let e = fails(&["/no/such/energy.psi", "--emit", "rs"]);
    contains_all(&e, &["cannot read"]);
    let e = fails(&["check", "/no/such/energy.psi"]);
    contains_all(&e, &["cannot read"]);

    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.psi");
    std::fs::write(
        &bad,
        "param mu = 1\nlet J = I3\npsi = mu*(I2 - 3) + lambda*log(J)^2\n",
    )
    .unwrap();
    let bad = bad.display().to_string();
    for args in [
        vec!["eval", bad.as_str(), "--F", F3, "--json"],
        vec![bad.as_str(), "--emit", "rs"],
        vec![bad.as_str(), "--emit", "report"],
        vec!["check", bad.as_str()],
    ] {
        let e = fails(&args);
        // Rendered with file:line:column and the offending source line.
        contains_all(
            &e,
            &[
                "unknown identifier `lambda`",
                "bad.psi:3:",
                "psi = mu*(I2 - 3) + lambda*log(J)^2",
            ],
        );
    }
    let syntax = dir.path().join("syntax.psi");
    std::fs::write(&syntax, "psi = (I2 - 3\n").unwrap();
    let e = fails(&["eval", &syntax.display().to_string(), "--F", F3]);
    contains_all(&e, &["syntax error", "syntax.psi:1:"]);
    let binary = dir.path().join("binary.psi");
    std::fs::write(&binary, [0xff, 0xfe, 0x00, 0x41]).unwrap();
    let e = fails(&["eval", &binary.display().to_string(), "--F", F3]);
    contains_all(&e, &["cannot read"]);
}

#[test]
fn malformed_deformation_gradients() {
    let arap = lib("arap");
    let cases: &[(&str, &[&str])] = &[
        ("1 0 0; 0 nan 0; 0 0 1", &["row 2, column 2", "not finite"]),
        ("1 0 0; 0 inf 0; 0 0 1", &["not finite"]),
        ("1 0 0; 0 1e999 0; 0 0 1", &["not finite"]),
        ("1 0 0; 0 x 0; 0 0 1", &["`x`", "not a number"]),
        ("1 0 0; 0 1; 0 0 1", &["row 2 has 2 entries, expected 3"]),
        ("1 0 0; 0 1 0", &["2 rows", "3"]),
        (
            "1 0 0 0; 0 1 0 0; 0 0 1 0; 0 0 0 1",
            &["4 rows", "only 2×2 and 3×3"],
        ),
        ("", &["--F is empty"]),
        (" ; ", &["--F is empty"]),
    ];
    for (f, parts) in cases {
        let mut args = vec!["eval", arap.as_str(), "--F", f];
        if f.starts_with("1 0 0; 0 1 0") && !f.contains("0 0 1") {
            args.extend(["--dim", "3"]);
        }
        let e = fails(&args);
        contains_all(&e, parts);
    }
    let e = fails(&["eval", &arap, "--dim", "2", "--F", F3]);
    contains_all(&e, &["3 rows", "2D"]);
    let e = fails(&["eval", &arap, "--dim", "4", "--F", F3]);
    contains_all(&e, &["--dim", "4"]);
    let e = fails(&["eval", &arap, "--dim", "1", "--F", "1"]);
    contains_all(&e, &["--dim"]);
    let e = fails(&["eval", &arap]);
    contains_all(&e, &["--F"]);
}

#[test]
fn bad_parameters() {
    let snh = lib("snh");
    let cases: &[(&str, &[&str])] = &[
        ("nu=1", &["unknown parameter `nu`", "mu", "lambda"]),
        ("mu=nan", &["mu", "not finite"]),
        ("mu=-inf", &["not finite"]),
        ("mu=abc", &["`abc` is not a number"]),
        ("mu", &["NAME=VALUE"]),
        ("=2", &["NAME=VALUE"]),
    ];
    for (p, parts) in cases {
        let e = fails(&["eval", &snh, "--F", F3, "--param", p]);
        contains_all(&e, parts);
        let e = fails(&["check", &snh, "--samples", "1", "--param", p]);
        contains_all(&e, parts);
    }
    let e = fails(&[
        "eval", &snh, "--F", F3, "--param", "mu=1", "--param", "mu=2",
    ]);
    contains_all(&e, &["mu", "more than once"]);
    let e = fails(&["eval", &lib("arap"), "--F", F3, "--param", "mu=1"]);
    contains_all(&e, &["unknown parameter `mu`", "no parameters"]);
}

#[test]
fn dimensions_the_energy_does_not_have() {
    let e = fails(&["eval", &lib("sd3"), "--F", "1 0; 0 1"]);
    contains_all(&e, &["no 2D energy", "dim 3"]);
    let e = fails(&["eval", &lib("mips2"), "--F", F3]);
    contains_all(&e, &["no 3D energy"]);
    let e = fails(&["check", &lib("sd2"), "--dim", "3"]);
    contains_all(&e, &["no 3D energy"]);
}

#[test]
fn bad_emit_requests() {
    let arap = lib("arap");
    let e = fails(&[&arap, "--emit", "py"]);
    contains_all(&e, &["py"]);
    let e = fails(&[&arap]);
    contains_all(&e, &["--emit"]);
    let e = fails(&[&arap, "--emit", "rs", "--name", "not a type"]);
    contains_all(&e, &["not a type"]);
    let e = fails(&[&arap, "--emit", "rs", "-o", "/no/such/dir/out.rs"]);
    contains_all(&e, &["cannot write", "/no/such/dir/out.rs"]);
    let e = fails(&[]);
    contains_all(&e, &["Usage"]);
    let e = fails(&["frobnicate", "--emit", "rs"]);
    contains_all(&e, &["cannot read", "frobnicate"]);
}

/// `ecc … | head`: the reader closing the pipe is not an error — no message,
/// no panic, and the exit status is the command's own (0 here).
#[test]
fn closed_stdout_pipe_is_not_an_error() {
    use std::process::{Command, Stdio};
    let snh = lib("snh");
    let cases: [&[&str]; 2] = [
        &["eval", &snh, "--dim", "3", "--F", F3, "--json"],
        &[&snh, "--emit", "rs"],
    ];
    for args in cases {
        let mut child = Command::new(env!("CARGO_BIN_EXE_ecc"))
            .args(args)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Close the read end before the energy is compiled and anything is written.
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{args:?}: {stderr}");
        assert!(stderr.is_empty(), "{args:?}: {stderr}");
    }
}
