//! `report`: run the benchmark report and write it to a folder.
//!
//! ```text
//! cargo run --release -p ecc-benches --bin report -- [--quick] [--out DIR]
//! ```
//!
//! Default output: `docs/benchmarks/` of the workspace. `--quick` finishes in
//! a few minutes; the default (full) run takes much longer (≥ 1M triangles,
//! ≥ 300k tets in the scaling part).

use std::path::PathBuf;
use std::process::ExitCode;

use ecc_benches::report::{self, Config, Size};

const USAGE: &str = "usage: report [--quick] [--out DIR]";

fn main() -> ExitCode {
    let mut size = Size::Full;
    let mut out = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../docs/benchmarks");
    let mut args = std::env::args().skip(1);
    let mut shown = vec!["cargo run --release -p ecc-benches --bin report --".to_string()];
    while let Some(a) = args.next() {
        match a.as_str() {
            "--quick" => {
                size = Size::Quick;
                shown.push(a);
            }
            "--out" => match args.next() {
                Some(d) => {
                    shown.push(format!("--out {d}"));
                    out = PathBuf::from(d);
                }
                None => {
                    eprintln!("error: --out needs a folder\n{USAGE}");
                    return ExitCode::from(2);
                }
            },
            "-h" | "--help" => {
                println!("{USAGE}");
                return ExitCode::SUCCESS;
            }
            other => {
                eprintln!("error: unknown argument `{other}`\n{USAGE}");
                return ExitCode::from(2);
            }
        }
    }
    let cfg = Config {
        size,
        out: out.clone(),
        data: ecc_mesh::data_dir(),
        command: shown.join(" "),
    };
    match report::run(&cfg, &mut |line| eprintln!("{line}")) {
        Ok(r) => {
            eprintln!(
                "wrote {} ({:.1} min)",
                out.join("BENCHMARKS.md").display(),
                r.seconds / 60.0
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
