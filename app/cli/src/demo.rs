//! `ecc demo` (= `ecc sim` without a scene): the built-in demo scene
//! (`scenes/demo.toml`, compiled in): a Stable Neo-Hookean bar clamped at
//! one end and twisted by a full turn at the other, 24 frames, written to
//! ./ecc-out/demo/ (pictures included). Runs in a few seconds in release.

use clap::Args;
use ecc_scene::SceneFile;

use crate::error::CliError;
use crate::sim::{SimArgs, run_file};

/// The demo scene's text.
pub const DEMO_SCENE: &str = include_str!("../../../scenes/demo.toml");

/// `ecc demo` arguments.
#[derive(Args, Debug, Clone, Default)]
pub struct DemoArgs {
    /// Output folder (default ./ecc-out/demo).
    #[arg(long, short = 'o', value_name = "DIR")]
    pub out: Option<std::path::PathBuf>,
    /// Override the number of frames (e.g. a quick preview).
    #[arg(long, value_name = "N")]
    pub frames: Option<usize>,
    /// No progress bar.
    #[arg(long, short = 'q')]
    pub quiet: bool,
    /// Print the terms evaluated, the counters and the time split.
    #[arg(long)]
    pub stats: bool,
}

/// Run the demo with `sim`-style options.
pub fn run_demo(args: &SimArgs) -> Result<(), CliError> {
    let file = SceneFile::parse(DEMO_SCENE, "<demo>", ".").map_err(CliError::DemoScene)?;
    run_file(file, args)
}

/// `ecc demo`.
pub fn run(args: &DemoArgs) -> Result<(), CliError> {
    run_demo(&SimArgs {
        scene: None,
        out: args.out.clone(),
        frames: args.frames,
        quiet: args.quiet,
        stats: args.stats,
        json: false,
        no_pictures: false,
        allow_unconverged: false,
    })
}
