//! Rules of time functions (`ramp(..)`, `table(..)`), wherever they are.

use super::Ctx;
use crate::ast::{num, Spanned, TimeFn};
use crate::diagnostics::Diagnostic;

/// A ramp's explicit window is not empty; table times strictly increase.
pub fn ramp_and_table_times_increase(f: &Spanned<TimeFn>, ctx: &mut Ctx<'_>) {
    match &f.value {
        TimeFn::Ramp {
            window: Some([t0, t1]),
            ..
        } if t1.value <= t0.value => {
            ctx.err(Diagnostic::error(
                "the ramp's time window is empty",
                t0.span.to(t1.span),
                format!("t1 = {} <= t0 = {}", num(t1.value), num(t0.value)),
            ));
        }
        TimeFn::Table(points) => {
            for w in points.windows(2) {
                if w[1].value.0 <= w[0].value.0 {
                    ctx.err(Diagnostic::error(
                        "table times must be strictly increasing",
                        w[1].span,
                        format!("t = {} after t = {}", num(w[1].value.0), num(w[0].value.0)),
                    ));
                    return;
                }
            }
        }
        _ => {}
    }
}
