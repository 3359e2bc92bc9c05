//! Run a scene file with the runtime's hand-written energies (arap, sd, snh):
//! `cargo run -p ecc-scene --example run_scene -- scenes/demo.toml [OUT]`.
//! The `ecc sim` command does the same with every built-in and `.psi` energy.

use ecc_scene::{FrameLines, RunOptions, RuntimeEnergies, SceneFile, run_scene};

fn main() {
    let mut args = std::env::args().skip(1);
    let Some(path) = args.next() else {
        eprintln!("usage: run_scene SCENE.toml [OUT_DIR]");
        std::process::exit(2);
    };
    let opts = RunOptions {
        out_dir: args.next().map(Into::into),
        ..Default::default()
    };
    let result = SceneFile::read(&path)
        .and_then(|f| run_scene(&f, &RuntimeEnergies, &opts, &mut FrameLines::default()));
    match result {
        Ok(r) => {
            print!("{}", r.summary.stats_table());
            if let Some(d) = r.out_dir {
                println!("wrote {}", d.display());
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
