//! Rules of `pressure`, `traction`, `force` and `gravity` items.

use super::{sets, time_fns, Ctx, Need};
use crate::ast::{KinematicsKind, LoadDef, LoadKind};
use crate::diagnostics::Diagnostic;

/// Checks every `pressure`, `traction`, `force` and `gravity` item:
/// pressures and tractions need edges (planar) or faces (3d).
pub fn check(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    for l in &deck.loads {
        let (need, user) = match l.kind {
            LoadKind::Pressure => (Need::Edges, "pressure"),
            LoadKind::Traction => (Need::Edges, "traction"),
            LoadKind::Force => (Need::Nodes, "force"),
        };
        sets::set_ref(&l.target, need, user, ctx);
        for (c, f) in &l.values {
            if let Some(c) = c {
                let word = if l.kind == LoadKind::Traction {
                    "tz"
                } else {
                    "fz"
                };
                super::boundaries::z_only_in_3d(*c, word, f.span, ctx);
            }
            time_fns::ramp_and_table_times_increase(f, ctx);
        }
        follower_on_a_finite_strain_body(l, ctx);
        control_on_a_follower_pressure(l, ctx);
    }
    for g in &deck.gravity {
        for (c, f) in &g.values {
            if let Some(c) = c {
                super::boundaries::z_only_in_3d(*c, "gz", f.span, ctx);
            }
            time_fns::ramp_and_table_times_increase(f, ctx);
        }
        gravity_acts_on_a_mass(g, ctx);
    }
}

/// `control = strain_rate { .. }` drives a follower pressure (a gas
/// pressure on the deformed sheet), with `exponent` in (0, 1] and
/// `max_change` > 1.
pub fn control_on_a_follower_pressure(l: &LoadDef, ctx: &mut Ctx<'_>) {
    let Some(c) = &l.control else {
        return;
    };
    if !l.follower.as_ref().is_some_and(|f| f.value) {
        ctx.err(
            Diagnostic::error(
                "a pressure controller needs a follower pressure",
                c.span,
                "controller on a dead pressure",
            )
            .with_help(
                "add `follower = true` (the gas pressure of blow forming follows the sheet)",
            ),
        );
    }
    // the monitored rate is a plastic strain rate: the body must flow
    let deck = ctx.deck;
    let material = deck
        .bodies
        .iter()
        .find(|b| b.name.name == l.target.body.name)
        .and_then(|b| b.material.as_ref())
        .and_then(|m| deck.materials.iter().find(|x| x.name.name == m.name));
    if let Some(m) = material.filter(|m| m.plastic.is_none() && m.norton_hoff.is_none()) {
        ctx.err(
            Diagnostic::error(
                format!(
                    "the controlled body `{}` never flows: its material `{}` has no plastic or \
                     Norton-Hoff law",
                    l.target.body.name, m.name.name
                ),
                c.span,
                "no plastic strain rate to control",
            )
            .with_help("give the material `norton_hoff { .. }` (superplastic) or `plastic { .. }`"),
        );
    }
    ctx.must_be_positive(&c.value.target, "the target strain rate");
    if let Some(e) = c
        .value
        .exponent
        .as_ref()
        .filter(|e| !(e.value > 0.0 && e.value <= 1.0))
    {
        ctx.err(
            Diagnostic::error(
                "the controller's exponent must be in (0, 1]",
                e.span,
                format!("exponent = {}", crate::ast::num(e.value)),
            )
            .with_help("use the body's Norton-Hoff m (about 0.5), or less to under-relax"),
        );
    }
    let solid = super::analysis::is_solid(ctx);
    if let Some(at) = c
        .value
        .at
        .as_ref()
        .filter(|p| p.len() != if solid { 3 } else { 2 })
    {
        let (want, span) = (if solid { "(x, y, z)" } else { "(x, y)" }, at.span());
        ctx.err(
            Diagnostic::error(
                format!("the monitored point has {} coordinates", at.len()),
                span,
                format!("expected `{want}` in this analysis"),
            )
            .with_help("`at` is the point whose nearest node's cells the controller watches"),
        );
    }
    if let Some(m) = c
        .value
        .max_change
        .as_ref()
        .filter(|m| m.value.is_nan() || m.value <= 1.0)
    {
        ctx.err(
            Diagnostic::error(
                "the controller's max_change must be > 1",
                m.span,
                format!("max_change = {}", crate::ast::num(m.value)),
            )
            .with_help("the pressure may change by at most this factor per increment (e.g. 2)"),
        );
    }
}

/// `gravity` needs something to pull: a body whose material has a
/// `density`, or a `point_mass`.
pub fn gravity_acts_on_a_mass(g: &crate::ast::Gravity, ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    let dense = deck.bodies.iter().any(|b| {
        b.material.as_ref().is_some_and(|mname| {
            deck.materials.iter().any(|m| {
                m.name.name == mname.name && m.density.as_ref().is_some_and(|r| r.value > 0.0)
            })
        })
    });
    let point_mass = deck
        .discrete
        .iter()
        .any(|d| d.kind == crate::ast::DiscreteKind::PointMass);
    if !dense && !point_mass {
        ctx.err(
            Diagnostic::error(
                "`gravity` acts on no mass",
                g.keyword,
                "no body has a density and there is no point mass",
            )
            .with_help("give a material a `density = ..` or add a `point_mass`"),
        );
    }
}

/// `follower = true` needs a body with `kinematics = finite`: at small
/// strain the surface does not move in the equations.
pub fn follower_on_a_finite_strain_body(l: &LoadDef, ctx: &mut Ctx<'_>) {
    let Some(f) = l.follower.as_ref().filter(|f| f.value) else {
        return;
    };
    let deck = ctx.deck;
    let Some(body) = deck
        .bodies
        .iter()
        .find(|b| b.name.name == l.target.body.name)
    else {
        return; // an unknown body is reported by the set rules
    };
    if body.kinematics.as_ref().map(|k| k.value) != Some(KinematicsKind::Finite) {
        ctx.err(
            Diagnostic::error(
                format!(
                    "a follower pressure on `{}`, a body with small kinematics",
                    body.name.name
                ),
                f.span,
                "the surface does not move in small-strain equations",
            )
            .with_help(format!(
                "give body `{}` `kinematics = finite`, or drop `follower = true`",
                body.name.name
            )),
        );
    }
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    #[test]
    fn gravity_needs_a_mass_and_gz_needs_3d() {
        let m = messages("gravity { gy = -9.81  gz = 1 }");
        assert!(
            m.contains(&"`gravity` acts on no mass".to_string()),
            "{m:?}"
        );
        assert!(
            m.contains(&"`gz` in a planar analysis".to_string()),
            "{m:?}"
        );
        let m = messages("gravity { gy = -9.81 }\npoint_mass block.top { mass = 1 }");
        assert!(!m.iter().any(|s| s.contains("gravity")), "{m:?}");
    }
}
