//! Rules of `initial_velocity` items.

use super::{sets, Ctx, Need};
use crate::ast::InitialVelocity;
use crate::diagnostics::Diagnostic;

/// Checks every `initial_velocity` item: a node set, `vz` only in 3d, and
/// a dynamic step to use it.
pub fn check(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    for v in &deck.initial_velocities {
        sets::set_ref(&v.target, Need::Nodes, "initial_velocity", ctx);
        for (c, x) in &v.values {
            super::boundaries::z_only_in_3d(*c, "vz", x.span, ctx);
        }
        initial_velocity_needs_a_dynamic_step(v, ctx);
    }
}

/// An initial velocity means nothing without inertia: some step must be
/// `dynamic`.
pub fn initial_velocity_needs_a_dynamic_step(v: &InitialVelocity, ctx: &mut Ctx<'_>) {
    if ctx.deck.steps.iter().any(|s| s.dynamic.is_some()) {
        return;
    }
    ctx.err(
        Diagnostic::error(
            "an initial velocity without a dynamic step",
            v.keyword,
            "no step has inertia",
        )
        .with_help("add `dynamic { .. }` to the step (quasi-static steps have no velocities)"),
    );
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    #[test]
    fn initial_velocity_needs_a_dynamic_step() {
        let m = messages("initial_velocity block.all { vx = 1 }");
        assert!(
            m.contains(&"an initial velocity without a dynamic step".to_string()),
            "{m:?}"
        );
    }
}
