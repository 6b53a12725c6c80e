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
    if let Some(t) = &o.thickness {
        thickness_needs_faces_of_one_solid_body(t, ctx);
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
            History::Roughness(r) => {
                sets::set_ref(r, Need::Nodes, "roughness", ctx);
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

/// `thickness = (a, b)`: a 3d analysis, face sets (checked like a
/// pressure's), both of one body.
pub fn thickness_needs_faces_of_one_solid_body(
    t: &Spanned<[crate::ast::SetRef; 2]>,
    ctx: &mut Ctx<'_>,
) {
    if !super::analysis::is_solid(ctx) {
        ctx.err(
            Diagnostic::error(
                "`thickness` is measured between face sets of a 3d body",
                t.span,
                "a planar analysis",
            )
            .with_help("the thickness of a planar section is its mesh's extent; remove the key"),
        );
        return;
    }
    for r in &t.value {
        sets::set_ref(r, Need::Edges, "thickness", ctx);
    }
    let [a, b] = &t.value;
    if a.body.name != b.body.name {
        ctx.err(
            Diagnostic::error(
                format!(
                    "the thickness is measured within one body, not between `{}` and `{}`",
                    a.body.name, b.body.name
                ),
                t.span,
                "two bodies",
            )
            .with_help("name two face sets of the sheet, e.g. `(sheet.zmax, sheet.zmin)`"),
        );
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
    use crate::validate::test_support::{messages, messages_of};

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

    #[test]
    fn the_thickness_needs_face_sets_of_one_3d_body() {
        let m = messages("output { thickness = (a.top, a.bottom) }");
        assert!(
            m.contains(&"`thickness` is measured between face sets of a 3d body".to_string()),
            "{m:?}"
        );
        let solid = "analysis { dimension = 3d }
material m { elastic { E = 1  nu = 0.3 } }
body a { mesh = box { size = (1, 1, 1)  divisions = (1, 1, 1) }  material = m }
body b { mesh = box { origin = (2, 0, 0)  size = (1, 1, 1)  divisions = (1, 1, 1) }  material = m }
";
        let m = messages_of(&format!("{solid}output {{ thickness = (a.zmax, b.zmin) }}"));
        assert!(
            m.iter()
                .any(|s| s.contains("within one body, not between `a` and `b`")),
            "{m:?}"
        );
        let m = messages_of(&format!(
            "{solid}output {{ thickness = (a.zmax, a.origin) }}"
        ));
        assert!(
            m.iter().any(|s| s.contains("needs boundary faces")),
            "{m:?}"
        );
        let m = messages_of(&format!("{solid}output {{ thickness = (a.zmax, a.zmin) }}"));
        assert!(!m.iter().any(|s| s.contains("thickness")), "{m:?}");
    }
}
