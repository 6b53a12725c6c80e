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
            let mut three = |key: &str, diags: &mut Diags| {
                f.value(key, diags).and_then(|v| triple(v, key, diags))
            };
            let axis = three("axis", diags);
            let inertia_diagonal = three("inertia_diagonal", diags);
            let inertia_products = three("inertia_products", diags);
            rigid = Some(RigidKeys {
                center: f
                    .value("center", diags)
                    .and_then(|v| values::coords(v, diags)),
                axis,
                inertia: f.number("inertia", diags),
                inertia_diagonal,
                inertia_products,
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

/// Three numbers `(a, b, c)` (an axis, the inertia's diagonal or
/// products).
fn triple(
    v: &crate::ast::syntax::Value,
    key: &str,
    diags: &mut Diags,
) -> Option<crate::ast::Point3> {
    match &v.kind {
        crate::ast::syntax::ValueKind::Tuple(items) if items.len() == 3 => values::point3(v, diags),
        _ => {
            diags.push(
                Diagnostic::error(
                    format!("`{key}` takes three numbers `(a, b, c)`"),
                    v.span,
                    "expected three numbers",
                )
                .with_help("a 3d rigid body's axis and inertia have three components"),
            );
            None
        }
    }
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
        assert_eq!(keys.center.as_ref().unwrap().values(), [1.0, 2.0]);
        assert_eq!(keys.inertia.as_ref().unwrap().value, 0.5);
        assert!(keys.angular_velocity.is_some() && keys.rotation.is_none());
        assert_eq!(keys.tie_stiffness.as_ref().unwrap().value, 1e6);
        let deck = parse_ok(
            "rigid_body d.hub { center = (1, 2, 3)  axis = (0, 0, 1)  mass = 3  \
             inertia_diagonal = (1, 2, 2.5)  inertia_products = (0.1, 0, 0)  rotation = 1  \
             tie_stiffness = 1e6 }",
        );
        let keys = deck.discrete[0].rigid.as_ref().unwrap();
        assert_eq!(keys.center.as_ref().unwrap().values(), [1.0, 2.0, 3.0]);
        assert_eq!(keys.axis.as_ref().unwrap().value, [0.0, 0.0, 1.0]);
        assert_eq!(
            keys.inertia_diagonal.as_ref().unwrap().value,
            [1.0, 2.0, 2.5]
        );
        assert_eq!(
            keys.inertia_products.as_ref().unwrap().value,
            [0.1, 0.0, 0.0]
        );
        assert_eq!(
            parse_messages("rigid_body d.hub { center = (0, 0)  axis = (1, 0) }"),
            ["`axis` takes three numbers `(a, b, c)`"]
        );
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
