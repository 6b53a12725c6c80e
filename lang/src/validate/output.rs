//! Rules of the `output` block.

use super::{sets, Ctx, Need};
use crate::ast::{FieldName, History, Spanned};
use crate::diagnostics::Diagnostic;
use crate::suggest::did_you_mean;

/// Checks the `output` block: one at most, fields listed once, history
/// requests naming known sets and contact pairs.
pub fn check(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    for extra in deck.outputs.iter().skip(1) {
        let line = ctx.line(deck.outputs[0].keyword);
        ctx.err(
            Diagnostic::error(
                "more than one `output` block",
                extra.keyword,
                "second `output` block",
            )
            .with_help(format!("the first one is on line {line}; merge them")),
        );
    }
    let Some(o) = deck.outputs.first() else {
        return;
    };
    ctx.at_least(&o.every, 1, "every");
    if let Some(fields) = &o.fields {
        dynamic_fields_need_a_dynamic_step(fields, ctx);
        for (i, f) in fields.value.iter().enumerate() {
            if fields.value[..i].iter().any(|g| g.value == f.value) {
                ctx.err(Diagnostic::warning(
                    "output field listed twice",
                    f.span,
                    "already listed",
                ));
            }
        }
    }
    let pairs: Vec<String> = deck
        .contacts
        .iter()
        .map(|c| format!("{} -> {}", c.target, c.tool.name))
        .collect();
    for h in o.history.iter().flatten() {
        match &h.value {
            History::Reaction(r) => {
                sets::set_ref(r, Need::Nodes, "reaction", ctx);
            }
            History::Displacement(r) => {
                sets::set_ref(r, Need::Nodes, "displacement", ctx);
            }
            History::ContactForce(r, tool) => {
                let key = format!("{r} -> {}", tool.name);
                if !pairs.contains(&key) && !deck.has_broken("contact") {
                    ctx.err(
                        Diagnostic::error(
                            format!("no contact pair `{key}`"),
                            h.span,
                            "not a contact pair of this deck",
                        )
                        .with_help(
                            did_you_mean(&key, &pairs).unwrap_or_else(|| {
                                if pairs.is_empty() {
                                    "the deck has no contact pairs".to_string()
                                } else {
                                    format!(
                                        "the contact pairs are {}",
                                        crate::suggest::one_of(&pairs)
                                    )
                                }
                            }),
                        ),
                    );
                }
            }
        }
    }
}

/// `velocity` and `acceleration` exist only where some step is dynamic (a
/// quasi-static analysis has no inertia and no velocities).
pub fn dynamic_fields_need_a_dynamic_step(
    fields: &Spanned<Vec<Spanned<FieldName>>>,
    ctx: &mut Ctx<'_>,
) {
    if ctx.deck.steps.iter().any(|s| s.dynamic.is_some()) {
        return;
    }
    for f in &fields.value {
        let name = match f.value {
            FieldName::Velocity => "velocity",
            FieldName::Acceleration => "acceleration",
            _ => continue,
        };
        ctx.err(
            Diagnostic::error(
                format!("output field `{name}` in a quasi-static analysis"),
                f.span,
                "no step is dynamic",
            )
            .with_help(
                "velocities and accelerations belong to dynamic steps: add `dynamic { .. }` to a \
                 step, or remove the field",
            ),
        );
    }
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    #[test]
    fn velocity_and_acceleration_need_a_dynamic_step() {
        let m = messages("output { fields = [displacement, velocity, acceleration] }");
        assert!(
            m.contains(&"output field `velocity` in a quasi-static analysis".to_string())
                && m.contains(
                    &"output field `acceleration` in a quasi-static analysis".to_string()
                ),
            "{m:?}"
        );
        let m = messages("output { fields = [velocity] }\nstep d { time = 1 .. 2  dynamic }");
        assert!(!m.iter().any(|s| s.contains("quasi-static")), "{m:?}");
    }
}
