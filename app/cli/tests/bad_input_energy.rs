//! The energy-file and command-line rows of `docs/ERRORS.md`: each test
//! feeds one kind of bad input to the `ecc` binary and checks the exit
//! status, the key part of the message (what is wrong and where) and that
//! no output file was created or changed.

mod bad_input_support;

use bad_input_support::{Scratch, only_inputs, says};

const F2: &str = "1 0; 0 1";
const F3: &str = "1 0 0; 0 1 0; 0 0 1";

/// A `.psi` energy that fails to compile fails the same way in `eval`,
/// `check` and `--emit rs|report -o FILE`, and `-o` creates nothing.
fn every_command_refuses(s: &Scratch, file: &str, parts: &[&str]) {
    let out = s.join("out.rs");
    for args in [
        vec!["eval", file, "--F", F3],
        vec!["eval", file, "--F", F2, "--json"],
        vec!["check", file, "--samples", "1"],
        vec![file, "--emit", "rs", "-o", out.as_str()],
        vec![file, "--emit", "report", "-o", out.as_str()],
    ] {
        let e = s.fails(&args);
        says(&e, parts);
    }
}

#[test]
fn psi_syntax_error() {
    let s = Scratch::new();
    let f = s.write("bad.psi", "param mu = 1\npsi = mu*(I2 - 3\n");
    every_command_refuses(&s, &f, &["syntax error", "bad.psi:2:", "psi = mu*(I2 - 3"]);
    only_inputs(&s, &["bad.psi"]);
}

#[test]
fn psi_not_isotropic() {
    let s = Scratch::new();
    let f = s.write("aniso.psi", "psi = s1^2 + 2*s2^2 + s3^2\n");
    every_command_refuses(
        &s,
        &f,
        &[
            "is not isotropic",
            "swapping s1 and s2 changes psi",
            "aniso.psi:1:7",
        ],
    );
    only_inputs(&s, &["aniso.psi"]);
}

#[test]
fn psi_unknown_identifier_with_suggestion() {
    let s = Scratch::new();
    let f = s.write("typo.psi", "param lambda = 1\npsi = lamda*I2\n");
    every_command_refuses(
        &s,
        &f,
        &[
            "unknown identifier `lamda`",
            "typo.psi:2:7",
            "did you mean `lambda`?",
        ],
    );
    only_inputs(&s, &["typo.psi"]);
}

#[test]
fn psi_unknown_function() {
    let s = Scratch::new();
    let f = s.write("fn.psi", "psi = foo(I2)\n");
    every_command_refuses(
        &s,
        &f,
        &["unknown function `foo`", "fn.psi:1:7", "known functions"],
    );
    only_inputs(&s, &["fn.psi"]);
}

#[test]
fn psi_stretch_beyond_the_dimension() {
    let s = Scratch::new();
    let f = s.write("s4.psi", "psi = s1 + s2 + s3 + s4\n");
    every_command_refuses(&s, &f, &["unknown identifier `s4`", "s4.psi:1:"]);
    only_inputs(&s, &["s4.psi"]);
}

#[test]
fn psi_missing_or_repeated_definition() {
    let s = Scratch::new();
    let f = s.write("none.psi", "param mu = 1\n");
    every_command_refuses(&s, &f, &["missing `psi = ...`", "none.psi:1:"]);
    let f = s.write("twice.psi", "psi = I2\npsi = I3\n");
    every_command_refuses(
        &s,
        &f,
        &["`psi` is defined more than once", "twice.psi:2:1"],
    );
    let f = s.write("reserved.psi", "param d = 1\npsi = I2\n");
    every_command_refuses(&s, &f, &["`d` is a built-in variable", "reserved.psi:1:7"]);
    only_inputs(&s, &["none.psi", "reserved.psi", "twice.psi"]);
}

#[test]
fn psi_division_by_zero_and_non_finite_parameter_default() {
    let s = Scratch::new();
    let f = s.write("div.psi", "param mu = 1/0\npsi = mu*I2\n");
    every_command_refuses(&s, &f, &["division by zero", "div.psi:1:14"]);
    let f = s.write("inf.psi", "param mu = 10^400\npsi = mu*I2\n");
    every_command_refuses(
        &s,
        &f,
        &[
            "the default of parameter `mu` is not finite",
            "inf.psi:1:12",
        ],
    );
    only_inputs(&s, &["div.psi", "inf.psi"]);
}

#[test]
fn psi_energy_without_the_requested_dimension() {
    let s = Scratch::new();
    let f = s.write(
        "sd3.psi",
        "dim 3\npsi = I2/2 + ((I1^2 - I2)/I3)^2/8 - I1/I3\n",
    );
    let e = s.fails(&["eval", &f, "--F", F2]);
    says(&e, &["no 2D energy", "dim 3"]);
    let e = s.fails(&["check", &f, "--dim", "2"]);
    says(&e, &["no 2D energy"]);
    only_inputs(&s, &["sd3.psi"]);
}

#[test]
fn psi_file_missing_unreadable_or_not_text() {
    let s = Scratch::new();
    let e = s.fails(&["eval", "missing.psi", "--F", F2]);
    says(&e, &["cannot read `missing.psi`", "No such file"]);
    std::fs::create_dir(s.path().join("folder.psi")).unwrap();
    let e = s.fails(&["eval", "folder.psi", "--F", F2]);
    says(&e, &["cannot read `folder.psi`", "directory"]);
    s.write("binary.psi", [0xff, 0xfe, 0x00, b'p', b's', b'i']);
    let e = s.fails(&["binary.psi", "--emit", "rs", "-o", "out.rs"]);
    says(&e, &["cannot read `binary.psi`", "UTF-8"]);
    only_inputs(&s, &["binary.psi"]);
}

#[test]
fn param_unknown_name() {
    let s = Scratch::new();
    let f = s.write(
        "snh.psi",
        "param mu = 1\nparam lambda = 10\npsi = mu*(I2 - 3) + lambda*(I3 - 1)^2\n",
    );
    let e = s.fails(&["eval", &f, "--F", F3, "--param", "nu=1"]);
    says(&e, &["unknown parameter `nu`", "mu", "lambda"]);
    let e = s.fails(&["check", &f, "--samples", "1", "--param", "nu=1"]);
    says(&e, &["unknown parameter `nu`"]);
    let e = s.fails(&["eval", &f, "--F", F3, "--param", "mu=1", "--param", "mu=2"]);
    says(&e, &["--param mu is given more than once"]);
    only_inputs(&s, &["snh.psi"]);
}

#[test]
fn param_nan_infinite_or_not_a_number() {
    let s = Scratch::new();
    let f = s.write("nh.psi", "param mu = 1\npsi = mu*(I2 - 3)\n");
    for (value, parts) in [
        ("mu=nan", &["--param mu", "`nan` is not finite"][..]),
        ("mu=-inf", &["--param mu", "not finite"][..]),
        ("mu=1e999", &["--param mu", "`1e999` is not finite"][..]),
        ("mu=abc", &["`abc` is not a number"][..]),
        ("mu", &["NAME=VALUE"][..]),
    ] {
        let e = s.fails(&["eval", &f, "--F", F3, "--param", value]);
        says(&e, parts);
    }
    only_inputs(&s, &["nh.psi"]);
}

#[test]
fn deformation_gradient_nan_or_wrong_shape() {
    let s = Scratch::new();
    let f = s.write("arap.psi", "psi = I2 - 2*I1 + d\n");
    for (m, parts) in [
        (
            "1 0 0; 0 nan 0; 0 0 1",
            &["row 2, column 2", "not finite"][..],
        ),
        ("1 0 0; 0 1e999 0; 0 0 1", &["not finite"][..]),
        ("1 0 0; 0 x 0; 0 0 1", &["`x`", "not a number"][..]),
        (
            "1 0 0; 0 1; 0 0 1",
            &["row 2 has 2 entries, expected 3"][..],
        ),
        (
            "1 0 0 0; 0 1 0 0; 0 0 1 0; 0 0 0 1",
            &["4 rows", "only 2×2 and 3×3"][..],
        ),
        ("", &["--F is empty"][..]),
    ] {
        let e = s.fails(&["eval", &f, "--F", m]);
        says(&e, parts);
    }
    let e = s.fails(&["eval", &f, "--dim", "2", "--F", F3]);
    says(&e, &["3 rows", "2D"]);
    only_inputs(&s, &["arap.psi"]);
}

#[test]
fn command_line_usage_errors_exit_2() {
    let s = Scratch::new();
    let f = s.write("arap.psi", "psi = I2 - 2*I1 + d\n");
    let e = s.fails_with(2, &["eval", &f, "--dim", "4", "--F", F2]);
    says(&e, &["'--dim", "4 is not in 2..=3"]);
    let e = s.fails_with(2, &["eval", &f, "--frobnicate"]);
    says(&e, &["unexpected argument '--frobnicate'"]);
    let e = s.fails_with(2, &[&f, "--emit", "py"]);
    says(&e, &["py"]);
    only_inputs(&s, &["arap.psi"]);
}

#[test]
fn emit_to_an_unwritable_path_or_with_a_bad_type_name() {
    let s = Scratch::new();
    let f = s.write("arap.psi", "psi = I2 - 2*I1 + d\n");
    s.write("a_file", "not a folder");
    let e = s.fails(&[&f, "--emit", "rs", "-o", "a_file/out.rs"]);
    says(&e, &["cannot write `a_file/out.rs`", "Not a directory"]);
    let e = s.fails(&[&f, "--emit", "rs", "--name", "My Type", "-o", "out.rs"]);
    says(&e, &["`My Type` is not a valid Rust type name"]);
    only_inputs(&s, &["a_file", "arap.psi"]);
}

#[test]
fn a_failed_emit_leaves_an_existing_output_untouched() {
    let s = Scratch::new();
    let f = s.write("bad.psi", "psi = (I2\n");
    s.write("keep.rs", "// the previous output\n");
    let e = s.fails(&[&f, "--emit", "rs", "-o", "keep.rs"]);
    says(&e, &["syntax error", "unclosed `(`"]);
    let kept = std::fs::read_to_string(s.path().join("keep.rs")).unwrap();
    assert_eq!(kept, "// the previous output\n");
    only_inputs(&s, &["bad.psi", "keep.rs"]);
}
