//! Rules of `pressure`, `traction` and `force` items.

use super::{sets, time_fns, Ctx, Need};
use crate::ast::LoadKind;

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
    }
}
