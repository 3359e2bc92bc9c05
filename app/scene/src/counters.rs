//! Per-run counters that prove what was (and was not) computed.
//!
//! Every effect term holds an `Arc<Counters>` and counts its *passes*
//! (a pass = one sweep over its stencils, counted when stencil 0 is
//! evaluated, so the hot loop pays one branch, not an atomic per stencil).
//! Mass matrices count their constructions. A quasi-static run therefore
//! reports `mass_matrix_builds == 0`, and a run without a ground reports
//! `contact_passes == 0`; tests assert exactly that.

use std::sync::atomic::{AtomicUsize, Ordering};

use serde::{Deserialize, Serialize};

/// Shared counters of one run (all start at 0).
#[derive(Debug, Default)]
pub struct Counters {
    mass_matrix_builds: AtomicUsize,
    stiffness_snapshots: AtomicUsize,
    contact_passes: AtomicUsize,
    gravity_passes: AtomicUsize,
    inertia_passes: AtomicUsize,
    damping_passes: AtomicUsize,
    blend_passes: AtomicUsize,
}

/// Which counter to bump.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Counter {
    /// A mass matrix (lumped or consistent) was assembled.
    MassMatrixBuild,
    /// Element stiffness matrices were captured for Rayleigh damping.
    StiffnessSnapshot,
    /// The ground (contact) term ran over its stencils.
    ContactPass,
    /// The gravity term ran.
    GravityPass,
    /// The inertia term ran.
    InertiaPass,
    /// A damping term ran.
    DampingPass,
    /// The interpolation blend ran.
    BlendPass,
}

/// A snapshot of [`Counters`] (for summaries and tests).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct CounterValues {
    /// Mass matrices assembled.
    pub mass_matrix_builds: usize,
    /// Rayleigh stiffness snapshots taken.
    pub stiffness_snapshots: usize,
    /// Passes of the ground / contact term.
    pub contact_passes: usize,
    /// Passes of the gravity term.
    pub gravity_passes: usize,
    /// Passes of the inertia term.
    pub inertia_passes: usize,
    /// Passes of the damping terms.
    pub damping_passes: usize,
    /// Passes of the interpolation blend.
    pub blend_passes: usize,
}

impl Counters {
    fn slot(&self, c: Counter) -> &AtomicUsize {
        match c {
            Counter::MassMatrixBuild => &self.mass_matrix_builds,
            Counter::StiffnessSnapshot => &self.stiffness_snapshots,
            Counter::ContactPass => &self.contact_passes,
            Counter::GravityPass => &self.gravity_passes,
            Counter::InertiaPass => &self.inertia_passes,
            Counter::DampingPass => &self.damping_passes,
            Counter::BlendPass => &self.blend_passes,
        }
    }

    /// Add one.
    #[inline]
    pub fn bump(&self, c: Counter) {
        self.slot(c).fetch_add(1, Ordering::Relaxed);
    }

    /// Add one when `s` is the first stencil of a pass.
    #[inline]
    pub fn pass(&self, c: Counter, s: usize) {
        if s == 0 {
            self.bump(c);
        }
    }

    /// Current values.
    pub fn values(&self) -> CounterValues {
        let g = |a: &AtomicUsize| a.load(Ordering::Relaxed);
        CounterValues {
            mass_matrix_builds: g(&self.mass_matrix_builds),
            stiffness_snapshots: g(&self.stiffness_snapshots),
            contact_passes: g(&self.contact_passes),
            gravity_passes: g(&self.gravity_passes),
            inertia_passes: g(&self.inertia_passes),
            damping_passes: g(&self.damping_passes),
            blend_passes: g(&self.blend_passes),
        }
    }
}
