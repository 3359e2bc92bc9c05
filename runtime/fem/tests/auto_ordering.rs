//! The `auto` ordering on the report's parameterisation meshes: METIS where
//! its factor is much cheaper than block AMD's (camelhead), block AMD where
//! AMD is already as good (armadillo_cut_low, a mesh cut open along seams)
//! and below the probing size (hand_1_i_f5000).

mod common;

use std::sync::Arc;

use common::data;
use ecc_fem::linear::cholesky::{CholeskyFactor, CholeskyParams, ThreadPolicy};
use ecc_fem::linear::ordering::{FillOrdering, METIS_MAX_RATIO};
use ecc_fem::{Assembler, DofMap, Elastic, Pattern, Term};
use ecc_mesh::{AnyMesh, read_mesh};
use ecc_runtime::energies::SymmetricDirichlet;

/// The Newton pattern of a parameterisation of `name` (2 unknowns a vertex).
fn pattern(name: &str) -> Pattern {
    let AnyMesh::Tri(m) = read_mesh(data(name)).unwrap() else {
        panic!("{name} is not a triangle mesh")
    };
    let term = Elastic::surface(Arc::new(SymmetricDirichlet), &m.positions, &m.triangles).unwrap();
    let terms: Vec<Box<dyn Term<2>>> = vec![Box::new(term)];
    let dofs = DofMap::all_free(m.positions.len(), 2).unwrap();
    Assembler::new(&terms, dofs).unwrap().pattern().clone()
}

/// The ordering `auto` used and the flops of its factor and of block AMD's
/// (one factor each, not split).
fn auto_against_block_amd(p: &Pattern) -> (FillOrdering, f64, f64) {
    let with = |ordering| {
        let params = CholeskyParams {
            ordering,
            threads: ThreadPolicy::Sequential,
            ..Default::default()
        };
        CholeskyFactor::analyze_with(p, params).unwrap()
    };
    let auto = with(FillOrdering::Auto);
    let amd = with(FillOrdering::BlockAmd);
    (
        auto.params().ordering,
        auto.factor_flops(),
        amd.factor_flops(),
    )
}

#[test]
fn auto_takes_metis_on_camelhead_only_where_it_is_much_cheaper() {
    let (used, flops, amd) = auto_against_block_amd(&pattern("camelhead.off"));
    if cfg!(feature = "metis") {
        assert_eq!(used, FillOrdering::Metis);
        // the whole factor (2×2 blocks) gains what the vertex graph promised
        assert!(flops < METIS_MAX_RATIO * amd, "{flops:e} vs {amd:e}");
    } else {
        assert_eq!(used, FillOrdering::BlockAmd);
    }
}

#[test]
fn auto_keeps_block_amd_where_metis_gains_little() {
    for name in ["armadillo_cut_low.obj", "hand_1_i_f5000.obj"] {
        let (used, flops, amd) = auto_against_block_amd(&pattern(name));
        assert_eq!(used, FillOrdering::BlockAmd, "{name}");
        assert_eq!(flops, amd, "{name}");
    }
}
