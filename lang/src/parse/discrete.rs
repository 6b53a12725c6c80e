//! `spring NODES { stiffness = ..  damping = .. }` (to the ground), `spring
//! NODES -> NODES { .. }` (between two node sets) and `point_mass NODES {
//! mass = .. }`: discrete elements at nodes, and `rigid_body NODES { .. }`
//! (carried by the generic item rule, like `initial_velocity`).

use super::fields::Fields;
use super::values::{self, Diags};
use super::ItemParts;
use crate::ast::{DiscreteItem, DiscreteKind, RigidKeys};
use crate::diagnostics::Diagnostic;

/// The item keywords.
pub const KEYWORDS: [&str; 3] = ["spring", "point_mass", "rigid_body"];

/// Converts a `spring`, `point_mass` or `rigid_body` item.
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
                        "this item takes no `->`"
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
    let (kind, table, what) = match item.keyword_text.as_str() {
        "spring" => (
            DiscreteKind::Spring,
            &crate::tables::SPRING[..],
            "`spring` block",
        ),
        "point_mass" => (
            DiscreteKind::PointMass,
            &crate::tables::POINT_MASS[..],
            "`point_mass` block",
        ),
        _ => (
            DiscreteKind::RigidBody,
            &crate::tables::RIGID_BODY[..],
            "`rigid_body` block",
        ),
    };
    let mut f = Fields::keyed(&block, what, table);
    let (mut stiffness, mut damping, mut mass, mut release_at, mut rigid) =
        (None, None, None, None, None);
    match kind {
        DiscreteKind::Spring => {
            stiffness = f.number("stiffness", diags);
            damping = f.number("damping", diags);
            release_at = f.number("release_at", diags);
        }
        DiscreteKind::PointMass => mass = f.number("mass", diags),
        DiscreteKind::RigidBody => {
            mass = f.number("mass", diags);
            stiffness = f.number("stiffness", diags);
            damping = f.number("damping", diags);
            rigid = Some(RigidKeys {
                center: f.point("center", diags),
                inertia: f.number("inertia", diags),
                rotation: f.time_fn("rotation", diags),
                angular_velocity: f.time_fn("angular_velocity", diags),
                moment: f.time_fn("moment", diags),
                tie_stiffness: f.number("tie_stiffness", diags),
            });
        }
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
        release_at,
        rigid,
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
            ["this item takes no `->`"]
        );
        let deck = parse_ok("spring a.tip -> b.tip { stiffness = 4  release_at = 0.5 }");
        assert_eq!(deck.discrete[0].release_at.as_ref().unwrap().value, 0.5);
        let deck = parse_ok(
            "rigid_body d.hub { center = (1, 2)  mass = 3  inertia = 0.5  \
             angular_velocity = ramp(0, 10, 0, 1)  stiffness = 7  damping = 0.1  \
             tie_stiffness = 1e6 }",
        );
        let r = &deck.discrete[0];
        assert_eq!(r.kind, DiscreteKind::RigidBody);
        assert_eq!(r.mass.as_ref().unwrap().value, 3.0);
        let keys = r.rigid.as_ref().unwrap();
        assert_eq!(keys.center.as_ref().unwrap().value, [1.0, 2.0]);
        assert_eq!(keys.inertia.as_ref().unwrap().value, 0.5);
        assert!(keys.angular_velocity.is_some() && keys.rotation.is_none());
        assert_eq!(keys.tie_stiffness.as_ref().unwrap().value, 1e6);
        assert_eq!(
            parse_messages("rigid_body d.hub { center = (0, 0)  spin = 3 }"),
            ["unknown key `spin` in the `rigid_body` block"]
        );
        assert_eq!(
            parse_messages("spring bar.left { stifness = 4 }"),
            ["unknown key `stifness` in the `spring` block"]
        );
    }
}
