//! The tape against the DSL's own reference evaluator, on every library energy,
//! plus hand-built graphs for the lowering rules.

use ecc_dsl::{Env, Graph, Id, Node, Sym, eval_many};
use ecc_interp::Tape;
use num_rational::BigRational;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn library() -> Vec<(String, String)> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../energies/psi");
    let mut out: Vec<(String, String)> = std::fs::read_dir(dir)
        .expect("library directory")
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "psi"))
        .map(|p| {
            let name = p.file_stem().unwrap().to_string_lossy().into_owned();
            (name, std::fs::read_to_string(&p).unwrap())
        })
        .collect();
    out.sort();
    assert!(
        out.len() >= 12,
        "expected the whole library, found {}",
        out.len()
    );
    out
}

fn run(tape: &Tape, params: &[f64], dim: u8, sigma: &[f64]) -> Vec<f64> {
    let env = Env::new(dim, sigma, params);
    let frozen = tape.freeze(params);
    let mut out = vec![f64::NAN; tape.n_outputs()];
    tape.eval(&frozen, env.sigma, env.inv, &mut out);
    out
}

fn close(a: f64, b: f64) -> bool {
    if a.is_nan() || b.is_nan() {
        return a.is_nan() && b.is_nan();
    }
    if a.is_infinite() || b.is_infinite() {
        return a == b;
    }
    (a - b).abs() <= 1e-11 * a.abs().max(b.abs()).max(1.0)
}

#[test]
fn every_library_graph_matches_the_dsl_evaluator() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut checked = 0;
    for (name, src) in library() {
        let module = ecc_dsl::compile(&src, &name).unwrap_or_else(|d| panic!("{name}: {d}"));
        for ir in &module.dims {
            let mut roots = vec![ir.psi];
            roots.extend(&ir.d_sigma);
            roots.extend(ir.h_sigma.iter().flatten());
            if let Some(d) = &ir.d_inv {
                roots.extend(d.d1);
                roots.extend(d.d2);
            }
            let tape = Tape::compile(&ir.graph, &roots).unwrap();
            for trial in 0..20 {
                let params: Vec<f64> = module
                    .params
                    .iter()
                    .map(|_| rng.gen_range(0.5..3.0))
                    .collect();
                let mut sigma: Vec<f64> = (0..ir.dim).map(|_| rng.gen_range(0.3..2.0)).collect();
                if trial % 5 == 4 {
                    // Inverted points: NaN (log of a negative) must agree too.
                    let last = sigma.len() - 1;
                    sigma[last] = -sigma[last];
                }
                let want = eval_many(&ir.graph, &roots, &Env::new(ir.dim, &sigma, &params));
                let got = run(&tape, &params, ir.dim, &sigma);
                for (k, (a, b)) in got.iter().zip(&want).enumerate() {
                    assert!(
                        close(*a, *b),
                        "{name} {}D root {k} at {sigma:?}: tape {a} vs dsl {b}",
                        ir.dim
                    );
                }
                checked += 1;
            }
        }
    }
    assert!(checked > 200);
}

#[test]
fn parameter_only_work_is_hoisted_into_the_prelude() {
    let src = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../energies/psi/snh.psi"
    ))
    .unwrap();
    let module = ecc_dsl::compile(&src, "snh").unwrap();
    let ir = module.dim(3).unwrap();
    let tape = Tape::compile(&ir.graph, &[ir.psi]).unwrap();
    // alpha = 1 + mu/lambda - mu/(4 lambda) depends only on parameters.
    assert!(tape.prelude_len() >= 3, "prelude {}", tape.prelude_len());
    let frozen_a = tape.freeze(&[1.0, 10.0]);
    let frozen_b = tape.freeze(&[2.0, 10.0]);
    assert_ne!(frozen_a, frozen_b);
}

fn rat(p: i64, q: i64) -> BigRational {
    BigRational::new(p.into(), q.into())
}

/// x^e for a hand-built node, evaluated at x.
fn pow_at(e: BigRational, x: f64) -> f64 {
    let mut g = Graph::new(vec![]);
    let s = g.add(Node::Sym(Sym::Sigma(0)));
    let ex = g.add(Node::Num(e));
    let p = g.add(Node::Pow([s, ex]));
    run(&Tape::compile(&g, &[p]).unwrap(), &[], 2, &[x, 1.0])[0]
}

#[test]
fn rational_powers_follow_the_dsl_semantics() {
    assert_eq!(pow_at(rat(2, 1), -3.0), 9.0);
    assert_eq!(pow_at(rat(5, 1), 2.0), 32.0);
    assert_eq!(pow_at(rat(-3, 1), 2.0), 0.125);
    assert_eq!(pow_at(rat(-1, 1), 0.0), f64::INFINITY);
    assert_eq!(pow_at(rat(1, 3), -8.0), -2.0);
    assert_eq!(pow_at(rat(2, 3), -8.0), 4.0);
    assert!((pow_at(rat(1, 5), -32.0) + 2.0).abs() < 1e-15);
    assert!(pow_at(rat(1, 2), -4.0).is_nan());
    assert!(pow_at(rat(3, 4), -4.0).is_nan());
    assert!((pow_at(rat(3, 2), 4.0) - 8.0).abs() < 1e-15);
    assert!((pow_at(rat(-1, 2), 4.0) - 0.5).abs() < 1e-15);
    assert!((pow_at(rat(7, 4), 2.0) - 2f64.powf(1.75)).abs() < 1e-14);
    // Beyond the multiplication chain: powf with the same sign rules.
    assert_eq!(pow_at(rat(2001, 1), -1.0), -1.0);
    assert_eq!(pow_at(rat(2000, 1), -1.0), 1.0);
    for (e, x) in [
        (rat(2, 3), -8.0),
        (rat(-5, 3), -2.5),
        (rat(9, 2), 1.7),
        (rat(13, 1), -1.1),
    ] {
        let mut g = Graph::new(vec![]);
        let s = g.add(Node::Sym(Sym::Sigma(0)));
        let ex = g.add(Node::Num(e.clone()));
        let p = g.add(Node::Pow([s, ex]));
        let want = ecc_dsl::eval(&g, p, &Env::new(2, &[x, 1.0], &[]));
        let got = pow_at(e, x);
        assert!(close(got, want), "{x}^{:?}: {got} vs {want}", p);
    }
}

#[test]
fn sums_and_products_lower_to_subtraction_and_division() {
    // psi = 3 + I2 - 2*I1*I3^-2 (built by hand in canonical form).
    let mut g = Graph::new(vec!["mu".into()]);
    let i1 = g.add(Node::Sym(Sym::I1));
    let i2 = g.add(Node::Sym(Sym::I2));
    let i3 = g.add(Node::Sym(Sym::I3));
    let mu = g.add(Node::Sym(Sym::Param(0)));
    let three = g.add(Node::Num(rat(3, 1)));
    let m2 = g.add(Node::Num(rat(-2, 1)));
    let mone = g.add(Node::Num(rat(-1, 1)));
    let e2 = g.add(Node::Num(rat(-2, 1)));
    let inv = g.add(Node::Pow([i3, e2]));
    let prod = g.add(Node::Mul(vec![m2, i1, inv, mu]));
    let neg_i2 = g.add(Node::Mul(vec![mone, i2]));
    let sum = g.add(Node::Add(vec![three, neg_i2, prod]));
    let roots: [Id; 1] = [sum];
    let tape = Tape::compile(&g, &roots).unwrap();
    let sigma = [1.5, 0.5, 2.0];
    let env = Env::new(3, &sigma, &[1.25]);
    let want = 3.0 - env.inv[1] - 2.0 * env.inv[0] * 1.25 / (env.inv[2] * env.inv[2]);
    let got = run(&tape, &[1.25], 3, &sigma)[0];
    assert!((got - want).abs() < 1e-13, "{got} vs {want}");
    // No node for (-1)*I2 and no reciprocal of I3^2: a handful of instructions.
    assert!(tape.main_len() <= 6, "{} instructions", tape.main_len());
}

#[test]
fn roots_outside_the_graph_are_an_error() {
    let mut g = Graph::new(vec![]);
    let i2 = g.add(Node::Sym(Sym::I2));
    assert!(Tape::compile(&g, &[i2]).is_ok());
    assert_eq!(
        Tape::compile(&g, &[Id(7)]).err(),
        Some(ecc_interp::BuildError::BadId { id: 7 })
    );
}

#[test]
fn missing_parameters_read_as_nan_instead_of_panicking() {
    let mut g = Graph::new(vec!["mu".into()]);
    let mu = g.add(Node::Sym(Sym::Param(0)));
    let i2 = g.add(Node::Sym(Sym::I2));
    let p = g.add(Node::Mul(vec![mu, i2]));
    let tape = Tape::compile(&g, &[p]).unwrap();
    let frozen = tape.freeze(&[]);
    let mut out = [0.0];
    tape.eval(&frozen, [1.0; 3], [3.0; 3], &mut out);
    assert!(out[0].is_nan());
}
