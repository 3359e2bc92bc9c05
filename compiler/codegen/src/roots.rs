//! What both back ends (Rust in `energy.rs`, C++ in `cpp/energy.rs`) plan
//! the same way: Ψ's roots and the names of the invariant derivatives.

use std::collections::HashMap;

use ecc_dsl::{DimIr, Id};

use crate::plan::{Region, Root};

/// Names for the invariant derivatives Ψ1, Ψ2, Ψ3, Ψ11, ….
pub(crate) fn hints(d: &DimIr) -> HashMap<Id, String> {
    let mut h = HashMap::new();
    if let Some(inv) = &d.d_inv {
        for (k, &id) in inv.d1.iter().enumerate() {
            h.entry(id).or_insert(format!("psi_i{}", k + 1));
        }
        let names = ["i1i1", "i2i2", "i3i3", "i1i2", "i1i3", "i2i3"];
        for (n, &id) in names.iter().zip(&inv.d2) {
            h.entry(id).or_insert(format!("psi_{n}"));
        }
    }
    h
}

/// Ψ's root and the roots of its active domain conditions
/// ([`crate::domain`]), all computed before the domain check.
pub(crate) fn psi_roots(d: &DimIr) -> Vec<Root> {
    let mut roots = vec![Root {
        id: d.psi,
        region: Region::Psi,
        name: "psi".into(),
        bind: true,
    }];
    roots.extend(crate::domain::roots(d));
    roots
}
