//! `spring NODES { stiffness = ..  damping = .. }` (to the ground), `spring
//! NODES -> NODES { .. }` (between two node sets) and `point_mass NODES {
//! mass = .. }`: discrete elements at nodes (carried by the generic item
//! rule, like `initial_velocity`).

use super::fields::Fields;
use super::values::{self, Diags};
use super::ItemParts;
use crate::ast::{DiscreteItem, DiscreteKind};
use crate::diagnostics::Diagnostic;

/// The item keywords.
pub const KEYWORDS: [&str; 2] = ["spring", "point_mass"];

/// Converts a `spring` or `point_mass` item.
pub fn parse(item: ItemParts, diags: &mut Diags) -> Option<DiscreteItem> {
    let target = values::set_ref(item.target.as_ref()?, diags)?;
    let other = match (&item.master, item.names.first()) {
        (Some(m), _) if item.keyword_text == "spring" => Some(values::set_ref(m, diags)?),
        (None, None) => None,
        (m, n) => {
            let span = m
                .as_ref()
                .map_or_else(|| n.map(|n| n.span), |m| Some(m.span));
            diags.push(
                Diagnostic::error(
                    if item.keyword_text == "spring" {
                        "a spring links to a node set `body.set`"
                    } else {
                        "`point_mass` takes no `->`"
                    },
                    span.unwrap_or(item.keyword),
                    "here",
                )
                .with_help(if item.keyword_text == "spring" {
                    "write e.g. `spring a.tip -> b.tip { stiffness = 1e3 }`"
                } else {
                    "write e.g. `point_mass bar.tip { mass = 2 }`"
                }),
            );
            return None;
        }
    };
    let block = item.block?;
    let (kind, table, what) = if item.keyword_text == "spring" {
        (
            DiscreteKind::Spring,
            &crate::tables::SPRING[..],
            "`spring` block",
        )
    } else {
        (
            DiscreteKind::PointMass,
            &crate::tables::POINT_MASS[..],
            "`point_mass` block",
        )
    };
    let mut f = Fields::keyed(&block, what, table);
    let (mut stiffness, mut damping, mut mass) = (None, None, None);
    match kind {
        DiscreteKind::Spring => {
            stiffness = f.number("stiffness", diags);
            damping = f.number("damping", diags);
        }
        DiscreteKind::PointMass => mass = f.number("mass", diags),
    }
    f.finish(diags);
    Some(DiscreteItem {
        kind,
        keyword: item.keyword,
        target,
        other,
        stiffness,
        damping,
        mass,
        span: item.span,
    })
}

#[cfg(test)]
mod tests {
    use crate::ast::DiscreteKind;
    use crate::parse::test_support::{parse_messages, parse_ok};

    #[test]
    fn spring_and_point_mass_items() {
        let deck = parse_ok(
            "spring bar.left { stiffness = 4  damping = 0.1 }\npoint_mass bar.right { mass = 2 }",
        );
        let s = &deck.discrete[0];
        assert_eq!(s.kind, DiscreteKind::Spring);
        assert_eq!(s.stiffness.as_ref().unwrap().value, 4.0);
        assert_eq!(s.damping.as_ref().unwrap().value, 0.1);
        let m = &deck.discrete[1];
        assert_eq!(m.kind, DiscreteKind::PointMass);
        assert_eq!(m.mass.as_ref().unwrap().value, 2.0);
        let deck = parse_ok("spring a.tip -> b.tip { stiffness = 4 }");
        let l = &deck.discrete[0];
        assert_eq!(l.other.as_ref().unwrap().to_string(), "b.tip");
        assert_eq!(
            parse_messages("spring a.tip -> wall { stiffness = 4 }"),
            ["a spring links to a node set `body.set`"]
        );
        assert_eq!(
            parse_messages("point_mass a.tip -> b.tip { mass = 4 }"),
            ["`point_mass` takes no `->`"]
        );
        assert_eq!(
            parse_messages("spring bar.left { stifness = 4 }"),
            ["unknown key `stifness` in the `spring` block"]
        );
    }
}
