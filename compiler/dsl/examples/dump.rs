//! Print everything the compiler derives for an energy.
//!
//! `cargo run -p ecc-dsl --example dump -- <file.psi | 'formula'>`

use ecc_dsl::{PairIr, ScaleIr, compile};

fn main() {
    let arg = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "I2 - 2*I1 + d".into());
    let (name, src) = match std::fs::read_to_string(&arg) {
        Ok(s) => (arg.clone(), s),
        Err(_) => ("<formula>".to_string(), arg.clone()),
    };
    let m = match compile(&src, &name) {
        Ok(m) => m,
        Err(d) => {
            eprint!("{}", d.render(&name, &src));
            std::process::exit(1);
        }
    };
    for (d, why) in &m.skipped {
        println!("skipped {d}D: {why}");
    }
    for ir in &m.dims {
        let g = &ir.graph;
        let t = |id| g.to_text(id);
        println!("== {}D  path {:?}  nodes {}", ir.dim, ir.path, g.len());
        println!(
            "barrier {} svd_free {} sign_symmetric {} decoupled {} isotropy_numeric_only {}",
            ir.barrier, ir.svd_free, ir.sign_symmetric, ir.decoupled, ir.isotropy_numeric_only
        );
        println!("psi = {}", t(ir.psi));
        if let Some(d) = &ir.d_inv {
            for (n, x) in ["Psi1", "Psi2", "Psi3"].iter().zip(d.d1) {
                println!("{n} = {}", t(x));
            }
            for (n, x) in ["Psi11", "Psi22", "Psi33", "Psi12", "Psi13", "Psi23"]
                .iter()
                .zip(d.d2)
            {
                println!("{n} = {}", t(x));
            }
        }
        for (i, x) in ir.spectral.grad.iter().enumerate() {
            println!("grad[{i}] = {}", t(*x));
        }
        match &ir.spectral.scale {
            ScaleIr::Diagonal(a) => {
                for (i, x) in a.iter().enumerate() {
                    println!("A[{i}][{i}] = {}", t(*x));
                }
            }
            ScaleIr::Full(a) => {
                for (i, row) in a.iter().enumerate() {
                    for (j, x) in row.iter().enumerate().skip(i) {
                        println!("A[{i}][{j}] = {}", t(*x));
                    }
                }
            }
        }
        for (name, v) in [("twist", &ir.spectral.twist), ("flip", &ir.spectral.flip)] {
            for (k, p) in v.iter().enumerate() {
                match p {
                    PairIr::Exact(x) => println!("{name}[{k}] = {}", t(*x)),
                    PairIr::Guarded { direct, limit, den } => {
                        println!(
                            "{name}[{k}] = {}  |  limit {}  when {} ~ 0",
                            t(*direct),
                            t(*limit),
                            t(*den)
                        )
                    }
                }
            }
        }
        let s: Vec<String> = ir.singularities.iter().map(|x| t(*x)).collect();
        println!("singularities: {}", s.join(", "));
    }
}
