//! `spring NODES { stiffness = ..  damping = .. }` and `point_mass NODES {
//! mass = .. }`: discrete elements at nodes (carried by the generic item
//! rule, like `initial_velocity`).

use super::fields::Fields;
use super::values::{self, Diags};
use super::ItemParts;
use crate::ast::{DiscreteItem, DiscreteKind};

/// The item keywords.
pub const KEYWORDS: [&str; 2] = ["spring", "point_mass"];

/// Converts a `spring` or `point_mass` item.
pub fn parse(item: ItemParts, diags: &mut Diags) -> Option<DiscreteItem> {
    let target = values::set_ref(item.target.as_ref()?, diags)?;
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
        assert_eq!(
            parse_messages("spring bar.left { stifness = 4 }"),
            ["unknown key `stifness` in the `spring` block"]
        );
    }
}
