//! Rules of `pressure` and `force` items.

use super::{sets, time_fns, Ctx, Need};
use crate::ast::LoadKind;

/// Checks every `pressure` and `force` item: pressures need edges.
pub fn check(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    for l in &deck.loads {
        let (need, user) = match l.kind {
            LoadKind::Pressure => (Need::Edges, "pressure"),
            LoadKind::Force => (Need::Nodes, "force"),
        };
        sets::set_ref(&l.target, need, user, ctx);
        for (c, f) in &l.values {
            if let Some(c) = c {
                super::boundaries::z_only_in_3d(*c, "fz", f.span, ctx);
            }
            time_fns::ramp_and_table_times_increase(f, ctx);
        }
    }
}
