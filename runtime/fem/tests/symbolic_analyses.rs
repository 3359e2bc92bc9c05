//! The symbolic-analysis counter counts real analyses: 1 for a whole
//! solve (and for later solves with the same pattern), and one more each
//! time one is really done again — here forced by rebuilding the linear
//! backend, which runs a new analysis of the same pattern.

mod common;

use common::{OffsetSprings, edges, grid};
use ecc_fem::{LinearSolver, NewtonParams, NewtonSolver, Term};

fn problem() -> (Vec<[f64; 2]>, NewtonSolver<2>) {
    let m = 8;
    let (rest, tris) = grid(m);
    let terms: Vec<Box<dyn Term<2>>> =
        vec![Box::new(OffsetSprings::from_rest(&rest, edges(&tris), 3.0))];
    let fixed: Vec<usize> = (0..=m).map(|i| i * (m + 1)).collect();
    let params = NewtonParams {
        linear_solver: LinearSolver::Cholesky,
        ..Default::default()
    };
    let solver = NewtonSolver::new(rest.len(), terms, &fixed, params).unwrap();
    (rest, solver)
}

fn pulled(rest: &[[f64; 2]], amount: f64) -> Vec<[f64; 2]> {
    rest.iter().map(|p| [p[0] * (1.0 + amount), p[1]]).collect()
}

#[test]
fn one_analysis_per_pattern_across_solves() {
    let (rest, mut solver) = problem();
    let mut x = pulled(&rest, 0.3);
    let r = solver.solve(&mut x).unwrap();
    assert!(r.converged(), "{r:?}");
    assert_eq!(r.symbolic_analyses, 1);
    let mut y = pulled(&rest, -0.2);
    let r = solver.solve(&mut y).unwrap();
    assert!(r.converged(), "{r:?}");
    assert_eq!(
        r.symbolic_analyses, 1,
        "the second solve reuses the analysis"
    );
    assert_eq!(solver.linear_system().symbolic_analyses(), 1);
}

#[test]
fn a_second_analysis_is_counted() {
    let (rest, mut solver) = problem();
    let mut x = pulled(&rest, 0.3);
    solver.solve(&mut x).unwrap();
    // a new backend for the same pattern: a genuine second analysis
    solver.set_linear_solver(LinearSolver::Cholesky).unwrap();
    let mut y = pulled(&rest, -0.2);
    let r = solver.solve(&mut y).unwrap();
    assert!(r.converged(), "{r:?}");
    assert_eq!(r.symbolic_analyses, 2);
    // the new backend alone did one
    assert_eq!(solver.linear_system().symbolic_analyses(), 1);
}

#[test]
fn auto_counts_the_analysis_it_discards_for_pcg() {
    let (rest, mut solver) = problem();
    solver.params.auto_limits.max_factor_bytes = 8;
    solver.set_linear_solver(LinearSolver::Auto).unwrap();
    assert_eq!(solver.linear_solver(), LinearSolver::Pcg);
    let mut x = pulled(&rest, 0.3);
    let r = solver.solve(&mut x).unwrap();
    assert!(r.converged(), "{r:?}");
    // the Cholesky analysis of `problem()` and the one Auto ran to decide
    assert_eq!(r.symbolic_analyses, 2);
    assert_eq!(r.numeric_factorizations, 0);
}
