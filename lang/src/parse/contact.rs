//! `contact body.set -> tool { method = penalty { .. } prof = .. }`.

use super::fields::Fields;
use super::values::{self, Diags};
use super::ItemParts;
use crate::ast::syntax::{ArgKind, Value, ValueKind};
use crate::ast::{
    Contact, ContactFormulation, LagrangeFormulation, Method, MultiplierUpdate, PenaltyKind,
    RelativeStiffness, Search, Smoothing, Strategy, RELATIVE_NAMES,
};
use crate::diagnostics::Diagnostic;
use crate::span::{Ident, Spanned};
use crate::suggest::did_you_mean;

/// Contact methods the language knows.
pub const METHODS: [&str; 3] = ["penalty", "lagrange", "augmented_lagrange"];

const KINDS: [(&str, PenaltyKind); 2] =
    [("nodal", PenaltyKind::Nodal), ("area", PenaltyKind::Area)];

const FORMULATIONS: [(&str, LagrangeFormulation); 3] = [
    ("single", LagrangeFormulation::Single),
    ("doubled", LagrangeFormulation::Doubled),
    ("condensed", LagrangeFormulation::Condensed),
];

const STRATEGIES: [(&str, Strategy); 3] = [
    ("single_pass", Strategy::SinglePass),
    ("double_pass", Strategy::DoublePass),
    ("modified_double_pass", Strategy::ModifiedDoublePass),
];

const CONTACT_FORMULATIONS: [(&str, ContactFormulation); 2] = [
    ("node_to_segment", ContactFormulation::NodeToSegment),
    ("mortar", ContactFormulation::Mortar),
];

const SMOOTHINGS: [(&str, Smoothing); 3] = [
    ("none", Smoothing::None),
    ("nodal", Smoothing::Nodal),
    ("nagata", Smoothing::Nagata),
];

const SEARCHES: [(&str, Search); 2] = [("memory", Search::Memory), ("circle", Search::Circle)];

const UPDATES: [(&str, MultiplierUpdate); 2] = [
    ("converged", MultiplierUpdate::Converged),
    ("newton", MultiplierUpdate::Newton),
];

/// Converts a `contact` item.
pub fn parse(item: ItemParts, diags: &mut Diags) -> Option<Contact> {
    let target = values::set_ref(item.target.as_ref()?, diags)?;
    // master: a tool name, or a deformable surface `body.set`
    let (tool, master) = match &item.master {
        Some(v) => {
            let m = values::set_ref(v, diags)?;
            (Ident::new(m.to_string(), m.span), Some(m))
        }
        None => (item.names.into_iter().next()?, None),
    };
    let block = item.block?;
    let mut f = Fields::keyed(&block, "`contact` block", &crate::tables::CONTACT);
    let thermal = f
        .block("thermal", diags)
        .map(|b| super::thermal::contact_block(b, diags));
    let method = f.value("method", diags).and_then(|v| method(v, diags));
    let prof = f.number("prof", diags);
    let strategy = f.choice("strategy", "contact strategy", &STRATEGIES, diags);
    let search = f.choice("search", "contact search", &SEARCHES, diags);
    let formulation = f.choice(
        "formulation",
        "contact formulation",
        &CONTACT_FORMULATIONS,
        diags,
    );
    let smoothing = f.choice("smoothing", "normal smoothing", &SMOOTHINGS, diags);
    let friction = f
        .value("friction", diags)
        .and_then(|v| super::friction::parse(v, diags));
    let reserved = Vec::new();
    f.require(
        &method,
        "method",
        target.span.to(tool.span),
        "add `method = penalty { stiffness = .. }`",
        diags,
    );
    f.finish(diags);
    Some(Contact {
        target,
        tool,
        method,
        prof,
        reserved,
        span: item.span,
        thermal,
        friction,
        master,
        strategy,
        search,
        formulation,
        smoothing,
    })
}

fn method(v: &Value, diags: &mut Diags) -> Option<Spanned<Method>> {
    let (name, block) = match &v.kind {
        ValueKind::Ctor { name, block } => (name, Some(block)),
        ValueKind::Path(p) if p.len() == 1 => (&p[0], None),
        other => {
            diags.push(Diagnostic::error(
                format!("expected a contact method, found {}", other.describe()),
                v.span,
                "expected `penalty { stiffness = .. }`",
            ));
            return None;
        }
    };
    match name.name.as_str() {
        "penalty" => {
            let Some(block) = block else {
                diags.push(Diagnostic::error(
                    "`penalty` needs its stiffness",
                    v.span,
                    "expected `penalty { stiffness = .. }`",
                ));
                return None;
            };
            let mut f = Fields::keyed(block, "`penalty` block", &crate::tables::PENALTY);
            let kind = f.choice("kind", "penalty kind", &KINDS, diags);
            let (stiffness, relative) = coefficient(&mut f, "stiffness", diags);
            f.require(
                &stiffness,
                "stiffness",
                name.span,
                "add `stiffness = <penalty coefficient>`",
                diags,
            );
            f.finish(diags);
            Some(Spanned::new(
                Method::Penalty {
                    kind,
                    stiffness,
                    relative,
                },
                v.span,
            ))
        }
        "lagrange" => {
            let formulation = match block {
                Some(block) => {
                    let mut f = Fields::keyed(block, "`lagrange` block", &crate::tables::LAGRANGE);
                    let formulation =
                        f.choice("formulation", "Lagrange formulation", &FORMULATIONS, diags);
                    f.finish(diags);
                    formulation
                }
                None => None,
            };
            Some(Spanned::new(Method::Lagrange { formulation }, v.span))
        }
        "augmented_lagrange" => {
            let Some(block) = block else {
                diags.push(Diagnostic::error(
                    "`augmented_lagrange` needs its penalty and tolerance",
                    v.span,
                    "expected `augmented_lagrange { penalty = ..  tolerance = .. }`",
                ));
                return None;
            };
            let mut f = Fields::keyed(
                block,
                "`augmented_lagrange` block",
                &crate::tables::AUGMENTED_LAGRANGE,
            );
            let kind = f.choice("kind", "penalty kind", &KINDS, diags);
            let (penalty, relative) = coefficient(&mut f, "penalty", diags);
            let tolerance = f.number("tolerance", diags);
            let update = f.choice("update", "multiplier update", &UPDATES, diags);
            f.require(
                &penalty,
                "penalty",
                name.span,
                "add `penalty = <penalty coefficient>`",
                diags,
            );
            f.require(
                &tolerance,
                "tolerance",
                name.span,
                "add `tolerance = <largest accepted penetration>`",
                diags,
            );
            f.finish(diags);
            Some(Spanned::new(
                Method::AugmentedLagrange {
                    kind,
                    penalty,
                    relative,
                    tolerance,
                    update,
                },
                v.span,
            ))
        }
        other => {
            diags.push(
                Diagnostic::error(
                    format!("unknown contact method `{other}`"),
                    name.span,
                    "not a contact method",
                )
                .with_help(
                    did_you_mean(other, METHODS)
                        .unwrap_or_else(|| "expected `penalty { .. }`".into()),
                ),
            );
            None
        }
    }
}

/// `key = <number>`, or a penalty coefficient relative to the slave body's
/// Young's modulus `E` and the local element size `h`
/// (`stiffness = 10 * E / h`): such an expression is checked here with
/// `E = h = 1` (its number is that placeholder) and evaluated per slave
/// node when the deck is lowered.
fn coefficient(
    f: &mut Fields,
    key: &str,
    diags: &mut Diags,
) -> (Option<Spanned<f64>>, Option<RelativeStiffness>) {
    let Some(v) = f.value(key, diags) else {
        return (None, None);
    };
    let what = format!("`{key}`");
    if !mentions_relative_names(v) {
        return (values::number_of(v, f.dim(key), &what, diags), None);
    }
    for name in RELATIVE_NAMES {
        if let Some((p, _)) = diags.env.params.iter().rev().find(|(p, _)| p.name == name) {
            let at = p.span;
            diags.push(
                Diagnostic::warning(
                    format!(
                        "in a penalty coefficient `{name}` is the {}, not the parameter `{name}`",
                        if name == "E" {
                            "slave body's Young's modulus"
                        } else {
                            "local element size of the slave surface"
                        }
                    ),
                    v.span,
                    format!("`{name}` is evaluated per slave node here"),
                )
                .with_secondary(at, format!("the parameter `{name}`, not used there"))
                .with_help("rename the parameter to use it in this key"),
            );
        }
    }
    let mut env = diags.env.clone();
    for name in RELATIVE_NAMES {
        env.params
            .push((Ident::new(name, v.span), crate::expr::Quantity::plain(1.0)));
    }
    let (_, out) = diags.split();
    let checked = crate::expr::eval(v, &mut env, out)
        .and_then(|q| crate::expr::in_system(q, None, false, &what, v.span, &env, out));
    match checked {
        Some(x) => (
            Some(x),
            Some(RelativeStiffness {
                expr: v.clone(),
                env: diags.env.clone(),
            }),
        ),
        None => (None, None),
    }
}

/// Whether `v` refers to `E` or `h` (a relative penalty coefficient).
fn mentions_relative_names(v: &Value) -> bool {
    match &v.kind {
        ValueKind::Path(p) => p.len() == 1 && RELATIVE_NAMES.contains(&p[0].name.as_str()),
        ValueKind::Neg(x) => mentions_relative_names(x),
        ValueKind::Tuple(items) => items.iter().any(mentions_relative_names),
        ValueKind::Binary { lhs, rhs, .. } => {
            mentions_relative_names(lhs) || mentions_relative_names(rhs)
        }
        ValueKind::Call { args, .. } => args.iter().any(|a| match &a.kind {
            ArgKind::Positional(x) | ArgKind::Named(_, x) | ArgKind::Arrow(x, _) => {
                mentions_relative_names(x)
            }
        }),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use crate::ast::{LagrangeFormulation, Method, MultiplierUpdate, PenaltyKind, SetRefKind};
    use crate::parse::test_support::{parse_messages, parse_ok};

    #[test]
    fn penalty_contact_pair() {
        let deck = parse_ok(
            "contact block.top -> punch {\n  method = penalty { kind = nodal  stiffness = 1e4 }\n  prof = 0.5\n}",
        );
        let c = &deck.contacts[0];
        assert_eq!(c.tool.name, "punch");
        assert!(matches!(&c.target.kind, SetRefKind::Named(n) if n.name == "top"));
        assert_eq!(c.prof.as_ref().unwrap().value, 0.5);
        match &c.method.as_ref().unwrap().value {
            Method::Penalty {
                kind, stiffness, ..
            } => {
                assert_eq!(kind.as_ref().unwrap().value, PenaltyKind::Nodal);
                assert_eq!(stiffness.as_ref().unwrap().value, 1e4);
            }
            m => panic!("{m:?}"),
        }
    }

    #[test]
    fn deformable_master_with_strategy_and_search() {
        let deck = parse_ok(
            "contact top.bottom -> base.top {\n  method = penalty { stiffness = 1e8 }\n  strategy = modified_double_pass\n  search = circle\n}\ncontact ring.inner -> ring.inner { method = lagrange }",
        );
        let c = &deck.contacts[0];
        let m = c.master.as_ref().expect("deformable master");
        assert_eq!(m.body.name, "base");
        assert!(matches!(&m.kind, SetRefKind::Named(n) if n.name == "top"));
        assert_eq!(c.tool.name, "base.top");
        assert_eq!(
            c.strategy.as_ref().unwrap().value,
            crate::ast::Strategy::ModifiedDoublePass
        );
        assert_eq!(c.search.as_ref().unwrap().value, crate::ast::Search::Circle);
        let s = &deck.contacts[1];
        assert_eq!(s.master.as_ref().unwrap().to_string(), "ring.inner");
        assert!(s.strategy.is_none() && s.search.is_none());
        // a rigid tool keeps its name and no master surface
        let t = parse_ok("contact a.b -> punch { method = lagrange }");
        assert!(t.contacts[0].master.is_none());
        assert_eq!(t.contacts[0].tool.name, "punch");
    }

    #[test]
    fn lagrange_and_augmented_lagrange_methods() {
        let deck = parse_ok(
            "contact a.b -> t { method = lagrange { formulation = doubled } }\n\
             contact a.c -> t { method = lagrange { } }\n\
             contact a.e -> t { method = lagrange { formulation = condensed } }\n\
             contact a.d -> t { method = augmented_lagrange { penalty = 1e3  tolerance = 1e-6  \
             update = newton  kind = nodal } }",
        );
        assert!(matches!(
            &deck.contacts[0].method.as_ref().unwrap().value,
            Method::Lagrange { formulation: Some(f) } if f.value == LagrangeFormulation::Doubled
        ));
        assert!(matches!(
            &deck.contacts[1].method.as_ref().unwrap().value,
            Method::Lagrange { formulation: None }
        ));
        assert!(matches!(
            &deck.contacts[2].method.as_ref().unwrap().value,
            Method::Lagrange { formulation: Some(f) } if f.value == LagrangeFormulation::Condensed
        ));
        match &deck.contacts[3].method.as_ref().unwrap().value {
            Method::AugmentedLagrange {
                kind,
                penalty,
                tolerance,
                update,
                ..
            } => {
                assert_eq!(kind.as_ref().unwrap().value, PenaltyKind::Nodal);
                assert_eq!(penalty.as_ref().unwrap().value, 1e3);
                assert_eq!(tolerance.as_ref().unwrap().value, 1e-6);
                assert_eq!(update.as_ref().unwrap().value, MultiplierUpdate::Newton);
            }
            m => panic!("{m:?}"),
        }
        assert_eq!(
            parse_messages("contact a.b -> t { method = augmented_lagrange { penalty = 1 } }"),
            ["missing `tolerance` in the `augmented_lagrange` block"]
        );
        let m = parse_messages(
            "contact a.b -> t { method = augmented_lagrange { penalty = 1  tolerance = 1  update = newtn } }",
        );
        assert_eq!(m.len(), 1, "{m:?}");
        let m = parse_messages("contact a.b -> t { method = lagrange { formulaton = doubled } }");
        assert_eq!(m.len(), 1, "{m:?}");
    }

    #[test]
    fn friction_and_unknown_methods() {
        let deck =
            parse_ok("contact a.b -> t { method = lagrange  friction = coulomb { mu = 0.2 } }");
        assert!(matches!(
            &deck.contacts[0].method.as_ref().unwrap().value,
            Method::Lagrange { formulation: None }
        ));
        let f = &deck.contacts[0].friction.as_ref().unwrap().value;
        assert_eq!(f.mu.as_ref().unwrap().value, 0.2);
        assert_eq!(
            parse_messages("contact a.b -> t { method = penalti { stiffness = 1 } }"),
            ["unknown contact method `penalti`"]
        );
        assert_eq!(
            parse_messages("contact a.b -> t { method = penalty { kind = area } }"),
            ["missing `stiffness` in the `penalty` block"]
        );
    }
}
