//! The command line (clap). Each subcommand's arguments live in its module.

use clap::{Parser, Subcommand};

use crate::check::CheckArgs;
use crate::demo::DemoArgs;
use crate::emit::EmitArgs;
use crate::eval::EvalArgs;
use crate::sim::SimArgs;

/// ecc: exact, PSD-projected eigensystems for isotropic energies written as formulas.
#[derive(Parser, Debug)]
#[command(
    name = "ecc",
    version,
    arg_required_else_help = true,
    args_conflicts_with_subcommands = true,
    subcommand_negates_reqs = true,
    after_help = "Examples:\n  ecc energies/psi/snh.psi --emit rs -o snh.rs\n  ecc energies/psi/snh.psi --emit cpp -o snh.hpp\n  ecc energies/psi/sd3.psi --emit report\n  ecc eval energies/psi/arap.psi --dim 2 --F \"1.2 0.1; 0 0.9\" --json\n  ecc check energies/psi/ogden.psi --samples 64"
)]
pub struct Cli {
    /// A subcommand; without one, `ecc FILE.psi --emit rs|cpp|report`.
    #[command(subcommand)]
    pub command: Option<Command>,
    /// The emit form's arguments.
    #[command(flatten)]
    pub emit: EmitArgs,
}

/// The subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Evaluate Ψ, the gradient, raw/projected Hessian and eigenvalues at one F.
    Eval(EvalArgs),
    /// Check the eigensystem against central differences and a numeric eigensolve.
    Check(CheckArgs),
    /// Run a scene file (deformation, dynamics, interpolation, parameterisation); without one, the demo.
    Sim(SimArgs),
    /// Run the built-in demo scene and write its pictures to ./ecc-out/demo/.
    Demo(DemoArgs),
}
