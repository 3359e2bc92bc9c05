//! The `ecc` binary: a thin dispatcher (see `CLI.md` for usage and the JSON
//! contract). Each subcommand lives in its own module; every failure prints
//! one clear message on stderr and exits non-zero.

mod check;
mod cli;
mod demo;
mod emit;
mod error;
mod eval;
mod eval_fibre;
mod eval_json;
mod input;
mod output;
mod point;
mod progress;
mod sim;
mod source;

use clap::Parser;

use cli::{Cli, Command};
use error::CliError;

fn run(cli: &Cli) -> Result<(), CliError> {
    match &cli.command {
        Some(Command::Eval(args)) => eval::run(args),
        Some(Command::Check(args)) => check::run(args),
        Some(Command::Sim(args)) => match &args.scene {
            Some(path) => sim::run(path, args),
            None => demo::run_demo(args),
        },
        Some(Command::Demo(args)) => demo::run(args),
        None => emit::run(&cli.emit),
    }
}

fn main() {
    // A panic is a bug; report it as one line instead of a backtrace dump.
    std::panic::set_hook(Box::new(|info| {
        eprintln!("error: internal error (please report this bug): {info}");
    }));
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => e.exit(),
    };
    let code = match std::panic::catch_unwind(|| run(&cli)) {
        Ok(Ok(())) => 0,
        Ok(Err(e)) => {
            eprintln!("{e}");
            e.exit_code()
        }
        Err(_) => 101,
    };
    std::process::exit(code);
}
