//! Print the generated Rust (or, with `--report`, the Markdown report) of a
//! `.psi` file: `cargo run -p ecc-codegen --example emit -- energies/psi/snh.psi`.

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let report = args.iter().any(|a| a == "--report");
    let Some(path) = args.iter().find(|a| !a.starts_with("--")) else {
        eprintln!("usage: emit [--report] FILE.psi");
        return ExitCode::FAILURE;
    };
    let source = match std::fs::read_to_string(path) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{path}: {e}");
            return ExitCode::FAILURE;
        }
    };
    let stem = std::path::Path::new(path)
        .file_stem()
        .map_or("energy".into(), |s| s.to_string_lossy().into_owned());
    let module = match ecc_dsl::compile(&source, &stem) {
        Ok(m) => m,
        Err(d) => {
            eprint!("{}", d.render(path, &source));
            return ExitCode::FAILURE;
        }
    };
    if report {
        print!("{}", ecc_codegen::report_markdown(&module, &stem));
        return ExitCode::SUCCESS;
    }
    let opts = ecc_codegen::GenOptions::named(ecc_codegen::type_name_from_stem(&stem));
    match ecc_codegen::generate_pretty(&module, &opts) {
        Ok(text) => {
            print!("{text}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("{path}: {e}");
            ExitCode::FAILURE
        }
    }
}
