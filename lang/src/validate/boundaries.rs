//! Rules of `fix` and `displace` items.

use super::{sets, time_fns, Ctx, Need};
use crate::ast::{BoundaryKind, Component, Span};
use crate::diagnostics::Diagnostic;

/// The z component (`uz`, `fz`) exists in 3d analyses only.
pub fn z_only_in_3d(c: Component, word: &str, span: Span, ctx: &mut Ctx<'_>) {
    if c == Component::Z && !super::analysis::is_solid(ctx) {
        ctx.err(
            Diagnostic::error(
                format!("`{word}` in a planar analysis"),
                span,
                "no z component in 2D",
            )
            .with_help("planar analyses have x and y only; use `dimension = 3d` for solids"),
        );
    }
}

/// Checks every `fix` and `displace` item: its set exists, its time
/// functions are well formed.
pub fn check(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    for b in &deck.boundaries {
        let user = match b.kind {
            BoundaryKind::Fix => "fix",
            BoundaryKind::Displace => "displace",
        };
        sets::set_ref(&b.target, Need::Nodes, user, ctx);
        for (c, f) in &b.components {
            z_only_in_3d(c.value, "uz", c.span, ctx);
            time_fns::ramp_and_table_times_increase(f, ctx);
        }
    }
}
