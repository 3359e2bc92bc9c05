//! A fingerprint of everything the compiler produces, for checking that a
//! change (e.g. a speed-up of the CAS) leaves every result *exactly* as it
//! was: for each input, the outcome of `compile` (every graph node in order,
//! every root id and flag of every dimension, or the rendered errors) is
//! hashed and printed as one line `hash name`. Diff two runs' outputs.
//!
//! `cargo run --release -p ecc-dsl --example ir_digest -- [--text] [--show] [DIR|FILE…] > before.txt`
//!
//! Default inputs: `energies/psi/*.psi`, the fuzz corpus `fuzz/corpus/psi/*`
//! and the generated scaling energies at small sizes.

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

#[path = "common/scaling_gen.rs"]
mod scaling_gen;

fn files_in(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| rd.filter_map(|e| e.ok()).map(|e| e.path()).collect())
        .unwrap_or_default();
    v.retain(|p| p.is_file());
    v.sort();
    v
}

/// `text` with every `Id(k)` replaced by the canonical text of node k
/// (which does not depend on node ids or insertion order).
fn ids_as_text(g: &ecc_dsl::Graph, text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(i) = rest.find("Id(") {
        out.push_str(&rest[..i]);
        let tail = &rest[i + 3..];
        let end = tail.find(')').unwrap_or(0);
        match tail[..end].parse::<u32>() {
            Ok(k) => out.push_str(&format!("`{}`", g.to_text(ecc_dsl::Id(k)))),
            Err(_) => out.push_str(&rest[i..i + 3 + end + 1]),
        }
        rest = &tail[end + 1..];
    }
    out.push_str(rest);
    out
}

/// `text` without the (emptied) `graph: Graph { … }, ` field, so the
/// fingerprint does not depend on the graph's private fields.
fn without_graph(text: &str) -> String {
    let Some(start) = text.find("graph: Graph {") else {
        return text.to_string();
    };
    let mut depth = 0;
    for (i, c) in text[start..].char_indices() {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    let end = start + i + 1;
                    let end = end + usize::from(text[end..].starts_with(", ")) * 2;
                    return format!("{}{}", &text[..start], &text[end..]);
                }
            }
            _ => {}
        }
    }
    text.to_string()
}

/// The fingerprint text of one compile (`by_text`: roots as canonical
/// texts, so node numbering does not matter).
fn fingerprint(src: &str, by_text: bool) -> String {
    match ecc_dsl::compile(src, "digest") {
        Ok(m) => {
            let mut out = format!("{:?} {:?}\n", m.params, m.skipped);
            for ir in &m.dims {
                let mut rest = ir.clone();
                rest.graph = ecc_dsl::cas::Graph::new(Vec::new());
                let rest = without_graph(&format!("{rest:?}"));
                if by_text {
                    out.push_str(&ids_as_text(&ir.graph, &rest));
                } else {
                    out.push_str(&format!("{:?}\n{rest}", ir.graph.nodes()));
                }
                out.push('\n');
            }
            out
        }
        Err(d) => d.render("digest", src),
    }
}

fn main() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    // `--text`: roots as canonical texts (independent of node numbering);
    // `--show`: print the fingerprinted text itself instead of its hash.
    let mut flag = |f: &str| match args.iter().position(|a| a == f) {
        Some(i) => {
            args.remove(i);
            true
        }
        None => false,
    };
    let by_text = flag("--text");
    let show = flag("--show");
    let mut inputs: Vec<(String, String)> = Vec::new();
    let paths: Vec<PathBuf> = if args.is_empty() {
        let mut v = files_in(&Path::new(root).join("energies/psi"));
        v.extend(files_in(&Path::new(root).join("fuzz/corpus/psi")));
        v
    } else {
        args.iter()
            .flat_map(|a| {
                let p = PathBuf::from(a);
                if p.is_dir() { files_in(&p) } else { vec![p] }
            })
            .collect()
    };
    for p in paths {
        let bytes = std::fs::read(&p).unwrap_or_default();
        let name = p.file_name().map(|n| n.to_string_lossy().into_owned());
        inputs.push((
            name.unwrap_or_default(),
            String::from_utf8_lossy(&bytes).into_owned(),
        ));
    }
    if args.is_empty() {
        use scaling_gen::{Family, energy};
        for f in [Family::Inv, Family::Sig, Family::Trans] {
            for n in [3, 10, 40] {
                inputs.push((format!("gen-{}-{n}", f.name()), energy(f, n)));
            }
        }
        // Many distinct transcendental subterms (sizes where the rational
        // content of a sum, lcm(1…n), is small, medium and beyond 2^64).
        for f in [Family::Exps, Family::Logs, Family::ExpPoly] {
            for n in [3, 10, 40, 100] {
                inputs.push((format!("gen-{}-{n}", f.name()), energy(f, n)));
            }
        }
    }
    for (name, src) in inputs {
        if show {
            println!("== {name}\n{}", fingerprint(&src, by_text));
            continue;
        }
        let mut h = DefaultHasher::new();
        fingerprint(&src, by_text).hash(&mut h);
        println!("{:016x} {name}", h.finish());
    }
}
