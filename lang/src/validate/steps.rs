//! Rules of `step` items.

use super::{step_label, Ctx};
use crate::ast::{num, Span};
use crate::diagnostics::Diagnostic;

/// Checks every step: at least one, unique names, contiguous non-empty
/// time ranges, increments and Newton settings in range.
pub fn check(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    if deck.steps.is_empty()
        && !deck.has_broken("step")
        && !deck.broken.iter().any(|b| b.keyword.is_empty())
    {
        ctx.err(
            Diagnostic::error(
                "the deck has no `step`",
                Span::new(0, 0),
                "expected a `step`",
            )
            .with_help("add e.g. `step load { time = 0 .. 1  increments = 10 }`"),
        );
    }
    ctx.names_are_unique(deck.steps.iter().filter_map(|s| s.name.as_ref()), "step");
    let mut previous: Option<(String, f64)> = None;
    for (i, s) in deck.steps.iter().enumerate() {
        let label = step_label(s, i);
        if let Some(t) = &s.time {
            let [t0, t1] = &t.value;
            if t1.value <= t0.value {
                ctx.err(
                    Diagnostic::error(
                        format!("empty time range in {label}"),
                        t.span,
                        format!("{} .. {} is empty", num(t0.value), num(t1.value)),
                    )
                    .with_help("the end time must be larger than the start time"),
                );
            }
            if let Some((prev, end)) = &previous {
                let tol = 1e-12 * end.abs().max(1.0);
                if t0.value < end - tol {
                    ctx.err(
                        Diagnostic::error(
                            format!("{label} starts at {} before {prev} ends", num(t0.value)),
                            t0.span,
                            format!("{prev} ends at {}", num(*end)),
                        )
                        .with_help(format!(
                            "steps follow each other in time: start this one at {}",
                            num(*end)
                        )),
                    );
                } else if t0.value > end + tol {
                    ctx.err(
                        Diagnostic::error(
                            format!("{label} leaves a gap after {prev}"),
                            t0.span,
                            format!("{prev} ends at {}", num(*end)),
                        )
                        .with_help(format!(
                            "steps follow each other in time: start this one at {}",
                            num(*end)
                        )),
                    );
                }
            }
            previous = Some((label.clone(), t1.value));
        }
        ctx.at_least(&s.increments, 1, "increments");
        if let Some(m) = s
            .min_increment
            .as_ref()
            .filter(|m| !(m.value > 0.0 && m.value <= 1.0))
        {
            ctx.err(
                    Diagnostic::error("`min_increment` must lie in (0, 1]", m.span, format!("min_increment = {}", num(m.value)))
                        .with_help("it is the smallest cutback increment as a fraction of the initial increment, e.g. 1e-3"),
                );
        }
        if let Some(n) = &s.newton {
            ctx.must_be_positive(&n.tol, "tol");
            ctx.must_be_positive(&n.tol_displacement, "tol_displacement");
            ctx.at_least(&n.max_iter, 1, "max_iter");
            ctx.must_be_positive(&n.stabilize, "stabilize");
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    #[test]
    fn step_times_must_be_contiguous() {
        let m = messages("step b { time = 0.5 .. 2 }\nstep c { time = 3 .. 3 }");
        assert_eq!(
            m,
            [
                "step `b` starts at 0.5 before step `load` ends",
                "empty time range in step `c`",
                "step `c` leaves a gap after step `b`"
            ]
        );
    }
}
