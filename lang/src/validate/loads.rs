//! Rules of `pressure`, `traction` and `force` items.

use super::{sets, time_fns, Ctx, Need};
use crate::ast::{KinematicsKind, LoadDef, LoadKind};
use crate::diagnostics::Diagnostic;

/// Checks every `pressure`, `traction` and `force` item: pressures and
/// tractions need edges (planar) or faces (3d).
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
