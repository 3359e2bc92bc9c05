//! Time one compile of a formula for one dimension (default 3).
//!
//! `cargo run --release -p ecc-dsl --example time_one -- 'psi = I2/I3' 2`

fn main() {
    let Some(src) = std::env::args().nth(1) else {
        eprintln!("usage: time_one '<formula>' [dim]");
        std::process::exit(2);
    };
    let dim: u8 = std::env::args()
        .nth(2)
        .and_then(|d| d.parse().ok())
        .unwrap_or(3);
    let t = std::time::Instant::now();
    let r = ecc_dsl::compile_dim(&src, "formula", dim);
    let elapsed = t.elapsed();
    match r {
        Ok(ir) => println!("{dim}D compiled in {elapsed:?} ({} nodes)", ir.graph.len()),
        Err(d) => println!(
            "{dim}D rejected in {elapsed:?}\n{}",
            d.render("formula", &src)
        ),
    }
}
