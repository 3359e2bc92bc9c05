//! Value checks that need no mesh: ranges, finiteness, exclusive choices,
//! effects that need other effects. Each error names its dotted key
//! (positions are filled in by [`super::SceneFile::locate`]). Checks that
//! need the mesh (vector lengths, handle selections, file contents) happen
//! when the scene is built.

use super::model::*;
use crate::error::SceneError;

type R = Result<(), SceneError>;

fn bad(key: &str, msg: impl Into<String>) -> SceneError {
    SceneError::invalid(key, msg)
}

fn positive(key: &str, v: Option<f64>) -> R {
    match v {
        Some(x) if !(x.is_finite() && x > 0.0) => Err(bad(
            key,
            format!("must be a positive finite number, got {x}"),
        )),
        _ => Ok(()),
    }
}

fn non_negative(key: &str, x: f64) -> R {
    if x.is_finite() && x >= 0.0 {
        Ok(())
    } else {
        Err(bad(key, format!("must be a finite number ≥ 0, got {x}")))
    }
}

fn finite_vec(key: &str, v: &Option<Vec<f64>>) -> R {
    if let Some(v) = v
        && let Some(i) = v.iter().position(|c| !c.is_finite())
    {
        return Err(bad(key, format!("component {i} is not finite")));
    }
    Ok(())
}

/// The largest generated mesh a scene may ask for (elements). Far beyond
/// what a scene can simulate on one machine, and small enough that the
/// generator's index arithmetic and allocations cannot overflow or abort.
pub const MAX_GENERATED_ELEMENTS: u128 = 50_000_000;

/// The element count of a generated shape must be at most
/// [`MAX_GENERATED_ELEMENTS`] (computed without overflow).
fn generated_size(key: &str, elements: u128, formula: &str) -> R {
    if elements > MAX_GENERATED_ELEMENTS {
        return Err(bad(
            key,
            format!(
                "asks for {elements} elements ({formula}); at most {MAX_GENERATED_ELEMENTS} are supported"
            ),
        ));
    }
    Ok(())
}

/// The largest frame count, step count or key frame accepted (a guard
/// against typos such as `frames = 1e9`).
pub const MAX_FRAMES: usize = 1_000_000;

fn at_least_one(key: &str, v: Option<usize>) -> R {
    match v {
        Some(0) => Err(bad(key, "must be at least 1")),
        _ => Ok(()),
    }
}

/// A frame or step count: at least 1, at most [`MAX_FRAMES`].
fn count(key: &str, v: Option<usize>) -> R {
    at_least_one(key, v)?;
    match v {
        Some(n) if n > MAX_FRAMES => {
            Err(bad(key, format!("must be at most {MAX_FRAMES}, got {n}")))
        }
        _ => Ok(()),
    }
}

/// All mesh-independent checks of a scene.
pub fn check(scene: &Scene) -> R {
    count("frames", scene.frames)?;
    check_mesh(&scene.mesh)?;
    check_energy(&scene.energy)?;
    check_effects(&scene.effects)?;
    check_solver(&scene.solver)?;
    check_output(&scene.output)
}

fn check_mesh(m: &MeshSpec) -> R {
    match (&m.file, m.generate) {
        (Some(_), Some(_)) => {
            return Err(bad("mesh", "give either `file` or `generate`, not both"));
        }
        (None, None) => {
            return Err(bad(
                "mesh",
                "give a mesh `file` or a shape to `generate` (bar, box, disk, grid)",
            ));
        }
        _ => {}
    }
    let shape = m.generate;
    let only = |key: &str, present: bool, shapes: &[Shape], what: &str| -> R {
        if present && !shape.is_some_and(|s| shapes.contains(&s)) {
            return Err(bad(
                &format!("mesh.{key}"),
                format!("only applies to {what}"),
            ));
        }
        Ok(())
    };
    only(
        "resolution",
        m.resolution.is_some(),
        &[Shape::Bar],
        "generate = \"bar\"",
    )?;
    only(
        "cells",
        m.cells.is_some(),
        &[Shape::Box, Shape::Grid],
        "generate = \"box\" or \"grid\"",
    )?;
    only(
        "size",
        m.size.is_some(),
        &[Shape::Box, Shape::Grid],
        "generate = \"box\" or \"grid\"",
    )?;
    only(
        "rings",
        m.rings.is_some(),
        &[Shape::Disk],
        "generate = \"disk\"",
    )?;
    only(
        "radius",
        m.radius.is_some(),
        &[Shape::Disk],
        "generate = \"disk\"",
    )?;
    at_least_one("mesh.resolution", m.resolution)?;
    at_least_one("mesh.rings", m.rings)?;
    positive("mesh.radius", m.radius)?;
    positive("mesh.scale", m.scale)?;
    finite_vec("mesh.translate", &m.translate)?;
    finite_vec("mesh.rotate", &m.rotate)?;
    let want = match shape {
        Some(Shape::Box) => 3,
        _ => 2,
    };
    if let Some(c) = &m.cells {
        if c.len() != want {
            return Err(bad(
                "mesh.cells",
                format!("expected {want} entries, got {}", c.len()),
            ));
        }
        if c.contains(&0) {
            return Err(bad("mesh.cells", "every entry must be at least 1"));
        }
    }
    // sizes are checked before anything is generated
    check_generated_size(m, want)?;
    if let Some(s) = &m.size {
        if s.len() != want {
            return Err(bad(
                "mesh.size",
                format!("expected {want} entries, got {}", s.len()),
            ));
        }
        if s.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
            return Err(bad(
                "mesh.size",
                "every entry must be a positive finite number",
            ));
        }
    }
    Ok(())
}

/// The number of elements a generated shape would have, refused when too
/// large (before anything is generated).
fn check_generated_size(m: &MeshSpec, want: usize) -> R {
    let shape = m.generate;
    let n = |v: usize| v as u128;
    match shape {
        Some(Shape::Bar) => {
            let r = n(m.resolution.unwrap_or(2));
            let tets = r.saturating_mul(r).saturating_mul(r).saturating_mul(24);
            generated_size("mesh.resolution", tets, "24 resolution³ tets")?;
        }
        Some(Shape::Disk) => {
            let r = n(m.rings.unwrap_or(8));
            let tris = r.saturating_mul(r).saturating_mul(6);
            generated_size("mesh.rings", tris, "6 rings² triangles")?;
        }
        Some(Shape::Box) | Some(Shape::Grid)
            if m.cells.as_ref().is_some_and(|c| c.len() == want) =>
        {
            let c = m.cells.as_deref().unwrap_or_default();
            let cells = c.iter().fold(1u128, |p, &x| p.saturating_mul(n(x)));
            let (per, what) = if shape == Some(Shape::Box) {
                (6, "6 tets per cell")
            } else {
                (2, "2 triangles per cell")
            };
            generated_size("mesh.cells", cells.saturating_mul(per), what)?;
        }
        _ => {}
    }
    Ok(())
}

fn check_energy(e: &EnergySpec) -> R {
    match (&e.name, &e.psi) {
        (Some(_), Some(_)) => Err(bad("energy", "give either `name` or `psi`, not both")),
        (None, None) => Err(bad(
            "energy",
            "give a built-in energy `name` or a `.psi` file as `psi`",
        )),
        _ => {
            for (k, v) in &e.params {
                if !v.is_finite() {
                    return Err(bad(&format!("energy.params.{k}"), "must be finite"));
                }
            }
            Ok(())
        }
    }
}

fn check_effects(fx: &Effects) -> R {
    positive("effects.density", fx.density)?;
    finite_vec("effects.gravity", &fx.gravity)?;
    if let Some(i) = &fx.inertia {
        positive("effects.inertia.dt", Some(i.dt))?;
        count("effects.inertia.steps_per_frame", i.steps_per_frame)?;
        finite_vec("effects.inertia.velocity", &i.velocity)?;
    }
    if let Some(d) = &fx.damping {
        if fx.inertia.is_none() {
            return Err(bad(
                "effects.damping",
                "damping needs dynamics: add [effects.inertia]",
            ));
        }
        non_negative("effects.damping.alpha", d.alpha)?;
        non_negative("effects.damping.beta", d.beta)?;
    }
    if let Some(g) = &fx.ground {
        if !g.height.is_finite() {
            return Err(bad("effects.ground.height", "must be finite"));
        }
        finite_vec("effects.ground.normal", &g.normal)?;
        if g.normal
            .as_ref()
            .is_some_and(|n| n.iter().all(|c| *c == 0.0))
        {
            return Err(bad("effects.ground.normal", "must not be zero"));
        }
        positive("effects.ground.dhat", g.dhat)?;
        positive("effects.ground.stiffness", g.stiffness)?;
    }
    for (k, h) in fx.handles.iter().enumerate() {
        finite_vec(&format!("effects.handles[{k}].center"), &h.center)?;
        for (j, key) in h.keys.iter().enumerate() {
            if key.frame > MAX_FRAMES as f64 {
                return Err(bad(
                    &format!("effects.handles[{k}].keys[{j}].frame"),
                    format!("must be at most {MAX_FRAMES}"),
                ));
            }
        }
        if h.ids.as_ref().is_some_and(|ids| ids.is_empty()) {
            return Err(bad(
                &format!("effects.handles[{k}].ids"),
                "must not be empty",
            ));
        }
    }
    if let Some(i) = &fx.interpolate {
        check_interpolate(i, fx)?;
    }
    if fx.parameterize.is_some() {
        let others = [
            ("gravity", fx.gravity.is_some()),
            ("inertia", fx.inertia.is_some()),
            ("damping", fx.damping.is_some()),
            ("ground", fx.ground.is_some()),
            ("handles", !fx.handles.is_empty()),
            ("interpolate", fx.interpolate.is_some()),
        ];
        if let Some((k, _)) = others.iter().find(|(_, on)| *on) {
            return Err(bad(
                &format!("effects.{k}"),
                "a parameterisation takes no other effect",
            ));
        }
    }
    Ok(())
}

/// `[effects.interpolate]`: exactly one second rest shape, finite angles,
/// an axis, and no keyframed handles.
fn check_interpolate(i: &InterpolateSpec, fx: &Effects) -> R {
    let deform = i.twist.is_some() || i.bend.is_some();
    match (&i.target, deform) {
        (Some(_), true) => {
            return Err(bad(
                "effects.interpolate",
                "give either a `target` mesh or a `twist`/`bend` deformation, not both",
            ));
        }
        (None, false) => {
            return Err(bad(
                "effects.interpolate",
                "give the second rest shape: a `target` mesh, or `twist` and/or `bend` (degrees)",
            ));
        }
        _ => {}
    }
    for (key, v) in [("twist", i.twist), ("bend", i.bend)] {
        if let Some(v) = v
            && !v.is_finite()
        {
            return Err(bad(&format!("effects.interpolate.{key}"), "must be finite"));
        }
    }
    if let Some(a) = &i.axis
        && !matches!(a.as_str(), "x" | "y" | "z")
    {
        return Err(bad(
            "effects.interpolate.axis",
            format!("must be \"x\", \"y\" or \"z\", got \"{a}\""),
        ));
    }
    count("effects.interpolate.steps", i.steps)?;
    if fx.handles.iter().any(|h| !h.keys.is_empty()) {
        return Err(bad(
            "effects.handles",
            "keyframed handles cannot be combined with interpolation (pinned handles can)",
        ));
    }
    Ok(())
}

fn check_solver(s: &SolverSpec) -> R {
    positive("solver.tol", s.tol)?;
    if let Some(r) = s.tol_rel
        && !(r.is_finite() && (0.0..1.0).contains(&r))
    {
        return Err(bad("solver.tol_rel", format!("must be in [0, 1), got {r}")));
    }
    at_least_one("solver.max_iters", s.max_iters)?;
    if s.filter == FilterKind::Adaptive
        && s.filter_policy
            .is_some_and(|p| p != FilterPolicyKind::TrustRegion)
    {
        return Err(bad(
            "solver.filter_policy",
            "filter = \"adaptive\" is the trust-region policy: use filter_policy = \"trust-region\" or filter = \"clamp\"/\"abs\"",
        ));
    }
    count("solver.substeps", s.substeps)
}

fn check_output(o: &OutputSpec) -> R {
    count("output.every", o.every)?;
    if let Some(s) = &o.image_size
        && (s.len() != 2 || s.iter().any(|v| !(64..=2048).contains(v)))
    {
        return Err(bad(
            "output.image_size",
            "expected [width, height], each between 64 and 2048 pixels",
        ));
    }
    if let Some(c) = &o.camera
        && (c.len() != 2 || c.iter().any(|v| !v.is_finite()) || c[1].abs() >= 89.5)
    {
        return Err(bad(
            "output.camera",
            "expected [azimuth, elevation] in degrees, elevation within ±89",
        ));
    }
    Ok(())
}
