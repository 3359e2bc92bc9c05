//! Every standard-library energy, in every dimension it compiles for:
//! derivatives against central differences at random points, the spectral
//! quantities against their definitions, and invariant path = stretch path.

use ecc_dsl::{DimIr, Env, Module, PairIr, Path, ScaleIr, Tape, compile, compile_dim, slot_pairs};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const LIBRARY: &[&str] = &[
    "arap",
    "corotational",
    "sd2",
    "sd3",
    "sarap2",
    "sarap3",
    "mips2",
    "stvk",
    "neohookean",
    "snh",
    "ogden",
    "ogden2",
    "hencky",
    "hencky2",
    "poly",
    "poly2",
    "polyneg",
    "polyneg2",
];

fn source(name: &str) -> String {
    let path = format!(
        "{}/../../energies/psi/{name}.psi",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn module(name: &str) -> Module {
    let src = source(name);
    compile(&src, name).unwrap_or_else(|d| panic!("{}", d.render(name, &src)))
}

/// Evaluates expressions of one DimIr at σ (invariants derived from σ).
struct Eval<'a> {
    ir: &'a DimIr,
    params: Vec<f64>,
}

impl Eval<'_> {
    fn at(&self, id: ecc_dsl::Id, s: &[f64]) -> f64 {
        Tape::new(&self.ir.graph, &[id]).eval(&Env::new(self.ir.dim, s, &self.params))[0]
    }

    fn at_inv(&self, id: ecc_dsl::Id, s: &[f64], inv: [f64; 3]) -> f64 {
        let mut env = Env::new(self.ir.dim, s, &self.params);
        env.inv = inv;
        Tape::new(&self.ir.graph, &[id]).eval(&env)[0]
    }

    fn pair(&self, p: &PairIr, s: &[f64]) -> f64 {
        match p {
            PairIr::Exact(x) => self.at(*x, s),
            PairIr::Guarded { direct, limit, den } => {
                if self.at(*den, s).abs() < 1e-6 {
                    self.at(*limit, s)
                } else {
                    self.at(*direct, s)
                }
            }
        }
    }
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

/// Random σ in the domain: positive and well separated (so divided
/// differences are well conditioned), descending.
fn point(rng: &mut ChaCha8Rng, dim: u8) -> Vec<f64> {
    loop {
        let mut s: Vec<f64> = (0..dim).map(|_| rng.gen_range(0.55..1.9)).collect();
        s.sort_by(|a, b| b.total_cmp(a));
        if s.windows(2).all(|w| w[0] - w[1] > 0.05) {
            return s;
        }
    }
}

fn params(m: &Module, rng: &mut ChaCha8Rng) -> Vec<f64> {
    m.params
        .iter()
        .map(|p| p.default * rng.gen_range(0.7..1.4))
        .collect()
}

const H: f64 = 1e-5;
const TOL: f64 = 2e-6;

#[allow(clippy::needless_range_loop)] // index-based loops mirror the maths
fn check_dim(name: &str, m: &Module, ir: &DimIr, rng: &mut ChaCha8Rng) {
    let n = ir.dim as usize;
    let ev = Eval {
        ir,
        params: params(m, rng),
    };
    for _ in 0..6 {
        let s = point(rng, ir.dim);
        let shift = |i: usize, h: f64| {
            let mut t = s.clone();
            t[i] += h;
            t
        };
        // ∂Ψ/∂σ and ∂²Ψ/∂σ² against central differences.
        for i in 0..n {
            let fd = (ev.at(ir.psi, &shift(i, H)) - ev.at(ir.psi, &shift(i, -H))) / (2.0 * H);
            let g = ev.at(ir.d_sigma[i], &s);
            assert!(
                close(g, fd, TOL),
                "{name} {}D grad[{i}] at {s:?}: {g} vs fd {fd}",
                ir.dim
            );
            for j in 0..n {
                let fd = (ev.at(ir.d_sigma[i], &shift(j, H)) - ev.at(ir.d_sigma[i], &shift(j, -H)))
                    / (2.0 * H);
                let h = ev.at(ir.h_sigma[i][j], &s);
                assert!(
                    close(h, fd, TOL),
                    "{name} {}D A[{i}][{j}] at {s:?}: {h} vs fd {fd}",
                    ir.dim
                );
                assert_eq!(ir.h_sigma[i][j], ir.h_sigma[j][i], "{name}: A is symmetric");
            }
        }
        // Invariant path: Ψ_a and Ψ_ab against differences in the invariants.
        if let Some(d) = &ir.d_inv {
            let inv = ecc_dsl::Env::new(ir.dim, &s, &[]).inv;
            let dinv = |x: ecc_dsl::Id, a: usize| {
                let (mut p, mut q) = (inv, inv);
                let h = H * (1.0 + inv[a].abs());
                p[a] += h;
                q[a] -= h;
                (ev.at_inv(x, &s, p) - ev.at_inv(x, &s, q)) / (2.0 * h)
            };
            for a in 0..3 {
                let fd = dinv(ir.psi, a);
                let v = ev.at(d.d1[a], &s);
                assert!(
                    close(v, fd, TOL),
                    "{name} {}D Psi{} : {v} vs fd {fd}",
                    ir.dim,
                    a + 1
                );
            }
            let pairs = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];
            for (k, (a, b)) in pairs.into_iter().enumerate() {
                let fd = dinv(d.d1[a], b);
                let v = ev.at(d.d2[k], &s);
                assert!(
                    close(v, fd, TOL),
                    "{name} {}D Psi{}{}: {v} vs fd {fd}",
                    ir.dim,
                    a + 1,
                    b + 1
                );
            }
        }
        // Spectral data: grad, scale, twist and flip against their definitions.
        let g: Vec<f64> = (0..n).map(|i| ev.at(ir.d_sigma[i], &s)).collect();
        for i in 0..n {
            assert_eq!(ir.spectral.grad[i], ir.d_sigma[i]);
        }
        match &ir.spectral.scale {
            ScaleIr::Diagonal(a) => {
                assert!(ir.decoupled);
                for i in 0..n {
                    assert_eq!(a[i], ir.h_sigma[i][i]);
                    for j in 0..n {
                        if i != j {
                            assert!(
                                ir.graph.is_int(ir.h_sigma[i][j], 0),
                                "{name}: decoupled off-diagonal is 0"
                            );
                        }
                    }
                }
            }
            ScaleIr::Full(a) => assert_eq!(a, &ir.h_sigma),
        }
        for (k, (i, j)) in slot_pairs(ir.dim).into_iter().enumerate() {
            let twist = (g[i] + g[j]) / (s[i] + s[j]);
            let flip = (g[i] - g[j]) / (s[i] - s[j]);
            let t = ev.pair(&ir.spectral.twist[k], &s);
            let f = ev.pair(&ir.spectral.flip[k], &s);
            assert!(
                close(t, twist, 1e-9),
                "{name} {}D twist[{k}]: {t} vs {twist}",
                ir.dim
            );
            assert!(
                close(f, flip, 1e-7),
                "{name} {}D flip[{k}]: {f} vs {flip}",
                ir.dim
            );
        }
    }
}

#[test]
fn library_derivatives_match_central_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(2019);
    for name in LIBRARY {
        let m = module(name);
        assert!(!m.dims.is_empty(), "{name}");
        for ir in &m.dims {
            check_dim(name, &m, ir, &mut rng);
        }
    }
}

/// Energies outside the library that reach the remaining code paths:
/// guarded twists on both paths, a parameterised exponent, mixed s/I.
const EXTRA: &[(&str, &str)] = &[
    (
        "sqrt_stretch",
        "psi = sqrt(1 + s1^2) + sqrt(1 + s2^2) + sqrt(1 + s3^2)",
    ),
    ("log_iic", "dim 3\npsi = log(IIC + 1)"),
    (
        "exp_i2",
        "param k = 0.3\npsi = exp(k*(I2 - d)) + (I3 - 1)^2",
    ),
    (
        "param_power",
        "param a = 2.5\npsi = s1^a + s2^a + s3^a - 3 + (I3 - 1)^2",
    ),
    (
        "mixed",
        "dim 2\nlet J = s1*s2\npsi = (s1 - 1)^2 + (s2 - 1)^2 + IC*J^-2",
    ),
];

#[test]
fn extra_energies_match_central_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for (name, src) in EXTRA {
        let m = compile(src, name).unwrap_or_else(|d| panic!("{}", d.render(name, src)));
        for ir in &m.dims {
            check_dim(name, &m, ir, &mut rng);
        }
    }
}

#[test]
fn flip_and_twist_limits_at_repeated_and_opposite_stretches() {
    // At σi = σj the flip must be finite and equal the limit of the divided
    // difference; at σi = −σj the same for the twist of sign-symmetric energies.
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mods = LIBRARY
        .iter()
        .map(|n| (n.to_string(), module(n)))
        .chain(EXTRA.iter().map(|(n, src)| {
            (
                n.to_string(),
                compile(src, n).unwrap_or_else(|d| panic!("{}", d.render(n, src))),
            )
        }));
    for (name, m) in mods {
        for ir in &m.dims {
            let ev = Eval {
                ir,
                params: params(&m, &mut rng),
            };
            for (k, (i, j)) in slot_pairs(ir.dim).into_iter().enumerate() {
                let mut s = point(&mut rng, ir.dim);
                s[j] = s[i];
                let at = ev.pair(&ir.spectral.flip[k], &s);
                let mut near = s.clone();
                near[j] = s[i] * (1.0 + 1e-6);
                let g = |x: &[f64], a: usize| ev.at(ir.d_sigma[a], x);
                let dd = (g(&near, i) - g(&near, j)) / (near[i] - near[j]);
                assert!(
                    at.is_finite(),
                    "{name} {}D flip[{k}] finite at s_i = s_j",
                    ir.dim
                );
                assert!(
                    close(at, dd, 1e-4),
                    "{name} {}D flip[{k}] at s_i = s_j: {at} vs {dd}",
                    ir.dim
                );
                // σj = −σi makes det F < 0 in 2D (outside a barrier energy's
                // domain); in 3D the third stretch is negated too.
                if ir.sign_symmetric && !(ir.barrier && ir.dim == 2) {
                    let mut s = point(&mut rng, ir.dim);
                    s[j] = -s[i];
                    if ir.barrier {
                        s[3 - i - j] *= -1.0;
                    }
                    let at = ev.pair(&ir.spectral.twist[k], &s);
                    let mut near = s.clone();
                    near[j] = -s[i] * (1.0 + 1e-6);
                    let dd = (g(&near, i) + g(&near, j)) / (near[i] + near[j]);
                    assert!(
                        close(at, dd, 1e-4),
                        "{name} {}D twist[{k}] at s_i = -s_j: {at} vs {dd}",
                        ir.dim
                    );
                }
            }
        }
    }
}

/// The invariants and aliases of `dim`, written in the stretches.
fn stretch_form(src: &str, dim: u8) -> String {
    let (i1, i2, i3, iic) = if dim == 2 {
        ("(s1 + s2)", "(s1^2 + s2^2)", "(s1*s2)", "(s1^4 + s2^4)")
    } else {
        (
            "(s1 + s2 + s3)",
            "(s1^2 + s2^2 + s3^2)",
            "(s1*s2*s3)",
            "(s1^4 + s2^4 + s3^4)",
        )
    };
    let mut out = String::new();
    let mut word = String::new();
    let flush = |w: &mut String, out: &mut String| {
        out.push_str(match w.as_str() {
            "I1" => i1,
            "I2" | "IC" => i2,
            "I3" | "J" => i3,
            "IIC" => iic,
            "IIIC" => "(s1*s2*s3)^2",
            _ => w,
        });
        w.clear();
    };
    let mut comment = false;
    for ch in src.chars() {
        comment = (comment || ch == '#') && ch != '\n';
        if !comment && (ch.is_ascii_alphanumeric() || ch == '_') {
            word.push(ch);
        } else {
            flush(&mut word, &mut out);
            out.push(ch);
        }
    }
    flush(&mut word, &mut out);
    out.replace(
        "(s1*s2*s3)",
        if dim == 2 { "(s1*s2)" } else { "(s1*s2*s3)" },
    )
}

#[test]
fn invariant_and_stretch_paths_agree() {
    let mut rng = ChaCha8Rng::seed_from_u64(99);
    for name in [
        "arap",
        "corotational",
        "sd2",
        "sd3",
        "sarap2",
        "sarap3",
        "mips2",
        "stvk",
        "neohookean",
        "snh",
    ] {
        let m = module(name);
        for ir in &m.dims {
            assert_eq!(ir.path, Path::Invariant, "{name}");
            let src = stretch_form(&source(name), ir.dim);
            let st = compile_dim(&src, name, ir.dim)
                .unwrap_or_else(|d| panic!("{}", d.render(name, &src)));
            assert_eq!(st.path, Path::Stretch, "{name}: {src}");
            assert_eq!(st.decoupled, ir.decoupled, "{name} {}D decoupled", ir.dim);
            assert_eq!(
                st.sign_symmetric, ir.sign_symmetric,
                "{name} {}D sign symmetry",
                ir.dim
            );
            assert_eq!(st.barrier, ir.barrier, "{name} {}D barrier", ir.dim);
            let p = params(&m, &mut rng);
            let a = Eval {
                ir,
                params: p.clone(),
            };
            let b = Eval { ir: &st, params: p };
            for _ in 0..5 {
                let s = point(&mut rng, ir.dim);
                let n = ir.dim as usize;
                assert!(
                    close(a.at(ir.psi, &s), b.at(st.psi, &s), 1e-12),
                    "{name} psi"
                );
                for i in 0..n {
                    let (x, y) = (a.at(ir.d_sigma[i], &s), b.at(st.d_sigma[i], &s));
                    assert!(
                        close(x, y, 1e-11),
                        "{name} {}D grad[{i}]: {x} vs {y}",
                        ir.dim
                    );
                    for j in 0..n {
                        let (x, y) = (a.at(ir.h_sigma[i][j], &s), b.at(st.h_sigma[i][j], &s));
                        assert!(
                            close(x, y, 1e-10),
                            "{name} {}D A[{i}][{j}]: {x} vs {y}",
                            ir.dim
                        );
                    }
                }
                for k in 0..slot_pairs(ir.dim).len() {
                    let (x, y) = (
                        a.pair(&ir.spectral.twist[k], &s),
                        b.pair(&st.spectral.twist[k], &s),
                    );
                    assert!(
                        close(x, y, 1e-9),
                        "{name} {}D twist[{k}]: {x} vs {y}",
                        ir.dim
                    );
                    let (x, y) = (
                        a.pair(&ir.spectral.flip[k], &s),
                        b.pair(&st.spectral.flip[k], &s),
                    );
                    assert!(
                        close(x, y, 1e-9),
                        "{name} {}D flip[{k}]: {x} vs {y}",
                        ir.dim
                    );
                }
            }
        }
    }
}

#[test]
fn library_flags() {
    let flags = |name: &str, dim: u8| {
        let m = module(name);
        let ir = m.dim(dim).unwrap_or_else(|| panic!("{name} has no {dim}D"));
        (ir.barrier, ir.svd_free, ir.sign_symmetric, ir.decoupled)
    };
    // (barrier, svd_free, sign_symmetric, decoupled)
    assert_eq!(flags("arap", 2), (false, false, false, true));
    assert_eq!(flags("arap", 3), (false, false, false, true));
    assert_eq!(flags("sd2", 2), (true, true, true, true));
    assert_eq!(flags("sd3", 3), (true, false, true, true));
    assert_eq!(flags("mips2", 2), (true, true, true, false));
    assert_eq!(flags("neohookean", 3), (true, true, true, false));
    assert_eq!(flags("snh", 3), (false, true, true, false));
    assert_eq!(flags("stvk", 2), (false, true, true, false));
    assert_eq!(flags("stvk", 3), (false, false, true, false));
    assert_eq!(flags("sarap3", 3), (true, false, false, true));
    assert_eq!(flags("poly", 3), (false, false, true, true));
    assert_eq!(flags("hencky", 3), (true, false, false, false));
    assert_eq!(flags("ogden", 3), (true, false, false, false));
    // Isotropy of the library's stretch energies is proved (canonical forms or
    // exact rational identity), not just sampled.
    for name in [
        "ogden", "ogden2", "hencky", "hencky2", "poly", "poly2", "polyneg", "polyneg2",
    ] {
        assert!(
            module(name).dims.iter().all(|d| !d.isotropy_numeric_only),
            "{name}"
        );
    }
    // Symmetric, but not provably so by canonical forms: checked numerically.
    let ir = compile_dim(
        "psi = log(s1*s2) + log(s3) + s1^1.5 + s2^1.5 + s3^1.5",
        "x",
        3,
    )
    .unwrap_or_else(|d| panic!("{d}"));
    assert!(ir.isotropy_numeric_only);
}
