//! Optional pointer from `BENCHMARKS.md` to the CHOLMOD comparison of the
//! factorisation (`cholmod.md`, made by `benches/cholmod/run.sh`, issue #11).
//! Its numbers come from separate runs (their own commit and load), so the
//! report links to them instead of copying them: every number in
//! `BENCHMARKS.md` stays from the report's one run.

use std::path::Path;

/// The section, or nothing when `out` holds no `cholmod.md`.
pub fn section(out: &Path) -> String {
    if !out.join("cholmod.md").is_file() {
        return String::new();
    }
    "\n## Sparse Cholesky against CHOLMOD\n\n\
     The factorisation on the same Newton matrices against CHOLMOD (supernodal, METIS/AMD, OpenBLAS, \
     1 and 2 threads) is measured separately with `benches/cholmod/run.sh` (not by this run; commit \
     and load are given there): [cholmod.md](cholmod.md).\n"
        .to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn links_only_when_the_results_file_exists() {
        let dir = tempfile::tempdir().unwrap();
        assert_eq!(section(dir.path()), "");
        std::fs::write(dir.path().join("cholmod.md"), "# x\n").unwrap();
        let s = section(dir.path());
        assert!(s.contains("## Sparse Cholesky against CHOLMOD"), "{s}");
        assert!(s.contains("](cholmod.md)"), "{s}");
    }
}
