//! Rules of `fix` and `displace` items.

use super::{sets, time_fns, Ctx, Need};
use crate::ast::BoundaryKind;

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
        for (_, f) in &b.components {
            time_fns::ramp_and_table_times_increase(f, ctx);
        }
    }
}
