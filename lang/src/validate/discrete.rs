//! Rules of the `spring`, `point_mass` and `rigid_body` items.

use super::{sets, Ctx, Need};
use crate::ast::{num, DiscreteItem, DiscreteKind};
use crate::diagnostics::Diagnostic;

/// Checks every `spring`, `point_mass` and `rigid_body` item.
pub fn check(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    for d in &deck.discrete {
        let what = match d.kind {
            DiscreteKind::Spring => "spring",
            DiscreteKind::PointMass => "point_mass",
            DiscreteKind::RigidBody => "rigid_body",
        };
        sets::set_ref(&d.target, Need::Nodes, what, ctx);
        if let Some(o) = &d.other {
            sets::set_ref(o, Need::Nodes, what, ctx);
        }
        values_not_negative(d, ctx);
        discrete_item_gives_a_value(d, what, ctx);
        release_needs_a_link(d, ctx);
        rigid_body_is_complete(d, ctx);
    }
}

/// `release_at` releases links: a spring between two sets, without a
/// dashpot.
pub fn release_needs_a_link(d: &DiscreteItem, ctx: &mut Ctx<'_>) {
    let Some(r) = &d.release_at else { return };
    if d.other.is_none() {
        ctx.err(
            Diagnostic::error(
                "`release_at` releases links between two sets",
                r.span,
                "a spring to the ground",
            )
            .with_help("write `spring a.root -> b.rim { stiffness = ..  release_at = .. }`"),
        );
    }
    if let Some(c) = d.damping.as_ref().filter(|c| c.value != 0.0) {
        ctx.err(
            Diagnostic::error("a released link carries no dashpot", c.span, "damping")
                .with_secondary(r.span, "released here")
                .with_help("remove `damping`, or give the dashpot its own `spring` item"),
        );
    }
}

/// A rigid body: a plane strain, plane stress or 3d analysis, a centre
/// with the analysis' coordinates, a tie stiffness, at most one of
/// `rotation` / `angular_velocity`, and `moment` only when free (3d: along
/// `axis`); the 3d keys (`axis`, `inertia_diagonal`, `inertia_products`)
/// only in 3d, and an inertia tensor that a body with the given mass can
/// have.
pub fn rigid_body_is_complete(d: &DiscreteItem, ctx: &mut Ctx<'_>) {
    let Some(keys) = &d.rigid else { return };
    let dimension = ctx
        .deck
        .analysis
        .first()
        .and_then(|a| a.dimension.as_ref())
        .map(|d| d.value);
    if matches!(dimension, Some(crate::ast::Dimension::Axisymmetric)) {
        ctx.err(
            Diagnostic::error(
                "a rigid body needs a plane strain, plane stress or 3d analysis",
                d.keyword,
                "rigid_body",
            )
            .with_help("in an axisymmetric model a cross-section does not turn as a rigid body"),
        );
    }
    let solid = matches!(dimension, Some(crate::ast::Dimension::ThreeD));
    if let Some(c) = &keys.center {
        let want = if solid { 3 } else { 2 };
        if c.len() != want {
            ctx.err(
                Diagnostic::error(
                    format!(
                        "the centre has {} coordinates, the analysis {want}",
                        c.len()
                    ),
                    c.span(),
                    "center",
                )
                .with_help(if solid {
                    "write `center = (x, y, z)`"
                } else {
                    "write `center = (x, y)`"
                }),
            );
        }
    }
    if solid {
        rigid_body_3d_keys(d, keys, ctx);
    } else {
        for (x, key) in [
            (&keys.axis, "axis"),
            (&keys.inertia_diagonal, "inertia_diagonal"),
            (&keys.inertia_products, "inertia_products"),
        ] {
            if let Some(x) = x {
                ctx.err(
                    Diagnostic::error(format!("`{key}` is for 3d rigid bodies"), x.span, key)
                        .with_help(
                            "a planar body turns about the normal to its plane: give `inertia`",
                        ),
                );
            }
        }
    }
    for (missing, what) in [
        (
            keys.center.is_none(),
            if solid {
                "add `center = (x, y, z)`"
            } else {
                "add `center = (x, y)`"
            },
        ),
        (
            keys.tie_stiffness.is_none(),
            "add `tie_stiffness = <force/length>` (e.g. 1e3 x the element stiffness)",
        ),
    ] {
        if missing {
            ctx.err(
                Diagnostic::error("`rigid_body` is incomplete", d.keyword, "here").with_help(what),
            );
        }
    }
    // a small-strain body turned by the rigid body strains spuriously
    // (its linear strain of a rotation by theta is cos(theta) - 1)
    let turns = keys.rotation.as_ref().is_none_or(|r| {
        !matches!(
            r.value,
            crate::ast::TimeFn::Number(0.0) | crate::ast::TimeFn::Constant(0.0)
        )
    });
    if let Some(b) = ctx
        .deck
        .bodies
        .iter()
        .find(|b| b.name.name == d.target.body.name)
    {
        let finite = b
            .kinematics
            .as_ref()
            .is_some_and(|k| k.value == crate::ast::KinematicsKind::Finite);
        if turns && !finite {
            ctx.err(
                Diagnostic::error(
                    "a rigid body turns a small-strain body",
                    d.target.span,
                    format!("body `{}` has small-strain kinematics", b.name.name),
                )
                .with_help(
                    "set `kinematics = finite` in the body (a rotation strains a small-strain \
                     body spuriously), or `rotation = 0`",
                ),
            );
        }
    }
    if let (Some(r), Some(w)) = (&keys.rotation, &keys.angular_velocity) {
        ctx.err(
            Diagnostic::error(
                "a rigid body's rotation is prescribed twice",
                w.span,
                "angular_velocity",
            )
            .with_secondary(r.span, "rotation")
            .with_help("give `rotation` or `angular_velocity`"),
        );
    }
    if let Some(m) = &keys.moment {
        if let Some(p) = keys.rotation.as_ref().or(keys.angular_velocity.as_ref()) {
            ctx.err(
                Diagnostic::error("a moment turns a free rotation only", m.span, "moment")
                    .with_secondary(p.span, "the rotation is prescribed")
                    .with_help("remove `moment`, or the prescribed rotation"),
            );
        }
    }
    for x in [&keys.inertia, &keys.tie_stiffness].into_iter().flatten() {
        if x.value < 0.0 || x.value.is_nan() {
            ctx.err(Diagnostic::error(
                "must be non-negative",
                x.span,
                num(x.value).to_string(),
            ));
        }
    }
}

/// The keys of a 3d rigid body: one inertia, a non-zero axis (of the
/// prescribed rotation, or of the moment of a free body: a moment fixed
/// in space, work-conjugate to the body's rotation), an inertia tensor that a body of the given mass can have
/// (`inertia_points::inertia_points`).
fn rigid_body_3d_keys(d: &DiscreteItem, keys: &crate::ast::RigidKeys, ctx: &mut Ctx<'_>) {
    if let (Some(i), Some(t)) = (&keys.inertia, &keys.inertia_diagonal) {
        ctx.err(
            Diagnostic::error("the inertia is given twice", t.span, "inertia_diagonal")
                .with_secondary(i.span, "inertia")
                .with_help("give `inertia` (the same about every axis) or the tensor"),
        );
        return;
    }
    if let Some(a) = &keys.axis {
        let n = a.value.iter().map(|x| x * x).sum::<f64>();
        if !(n.is_finite() && n > 0.0) {
            ctx.err(
                Diagnostic::error("the rotation axis is zero", a.span, "axis")
                    .with_help("give a direction, e.g. `axis = (0, 0, 1)`"),
            );
        }
    }
    let diagonal = match (&keys.inertia, &keys.inertia_diagonal) {
        (Some(i), _) => Some(([i.value; 3], i.span)),
        (None, Some(t)) => Some((t.value, t.span)),
        (None, None) => None,
    };
    let products = keys.inertia_products.as_ref().map_or([0.0; 3], |p| p.value);
    let span = match (diagonal, &keys.inertia_products) {
        (Some((_, s)), _) => s,
        (None, Some(p)) => p.span,
        (None, None) => return,
    };
    let j = diagonal.map_or([0.0; 3], |x| x.0);
    let tensor = [
        [j[0], products[0], products[2]],
        [products[0], j[1], products[1]],
        [products[2], products[1], j[2]],
    ];
    let mass = d.mass.as_ref().map_or(0.0, |m| m.value);
    if let Err(e) = ctc_engine::solve::inertia_points::inertia_points(mass, tensor) {
        ctx.err(
            Diagnostic::error("this rotary inertia cannot be modelled", span, e).with_help(
                "a 3d body's mass and inertia are carried by six point masses tied to it: give \
                 `mass`, and principal moments each at most the sum of the other two",
            ),
        );
    }
}

/// Stiffness, damping and mass are `>= 0` (a negative one feeds energy
/// in), a mass `> 0`.
pub fn values_not_negative(d: &DiscreteItem, ctx: &mut Ctx<'_>) {
    for (x, key) in [
        (&d.stiffness, "stiffness"),
        (&d.damping, "damping"),
        (&d.mass, "mass"),
    ] {
        let Some(x) = x else { continue };
        let bad = if key == "mass" {
            x.value <= 0.0 || x.value.is_nan()
        } else {
            x.value < 0.0 || x.value.is_nan()
        };
        if bad {
            ctx.err(Diagnostic::error(
                format!(
                    "{key} must be {}",
                    if key == "mass" {
                        "positive"
                    } else {
                        "non-negative"
                    }
                ),
                x.span,
                format!("{key} = {}", num(x.value)),
            ));
        }
    }
}

/// A spring needs `stiffness` or `damping`, a point mass its `mass`.
pub fn discrete_item_gives_a_value(d: &DiscreteItem, what: &str, ctx: &mut Ctx<'_>) {
    let (missing, help) = match d.kind {
        DiscreteKind::Spring => (
            d.stiffness.is_none() && d.damping.is_none(),
            "write e.g. `spring bar.left { stiffness = 1e3  damping = 2 }`",
        ),
        DiscreteKind::PointMass => (
            d.mass.is_none(),
            "write e.g. `point_mass bar.tip { mass = 2 }`",
        ),
        DiscreteKind::RigidBody => return,
    };
    if missing {
        ctx.err(
            Diagnostic::error(
                format!("`{what}` gives no value"),
                d.keyword,
                if d.kind == DiscreteKind::Spring {
                    "no `stiffness` or `damping`"
                } else {
                    "no `mass`"
                },
            )
            .with_help(help),
        );
    }
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    #[test]
    fn springs_and_point_masses_need_valid_values() {
        let m = messages(
            "spring block.bottom { stiffness = -1 }\npoint_mass block.top { }\n\
             point_mass block.nowhere { mass = 1 }",
        );
        assert!(
            m.contains(&"stiffness must be non-negative".to_string()),
            "{m:?}"
        );
        assert!(
            m.contains(&"`point_mass` gives no value".to_string()),
            "{m:?}"
        );
        assert!(m.iter().any(|s| s.contains("nowhere")), "{m:?}");
    }

    #[test]
    fn rigid_bodies_and_releases_are_checked() {
        let m = messages(
            "rigid_body block.bottom { mass = 1  rotation = 1  angular_velocity = 2 }\n\
             rigid_body block.top { center = (0, 0)  tie_stiffness = 1  rotation = 1  moment = 3 }\n\
             spring block.top { stiffness = 1  release_at = 1 }\n\
             spring block.top -> block.bottom { stiffness = 1  damping = 1  release_at = 1 }",
        );
        for want in [
            "`rigid_body` is incomplete",
            "a rigid body's rotation is prescribed twice",
            "a moment turns a free rotation only",
            "`release_at` releases links between two sets",
            "a released link carries no dashpot",
            "a rigid body turns a small-strain body",
        ] {
            assert!(m.contains(&want.to_string()), "{want}: {m:?}");
        }
        // 3d keys in a planar deck
        let m = messages(
            "rigid_body block.top { center = (0, 0, 1)  axis = (0, 0, 1)  tie_stiffness = 1  \
             rotation = 0 }",
        );
        for want in [
            "the centre has 3 coordinates, the analysis 2",
            "`axis` is for 3d rigid bodies",
        ] {
            assert!(m.contains(&want.to_string()), "{want}: {m:?}");
        }
    }

    #[test]
    fn rigid_bodies_in_3d_are_checked() {
        let deck = |item: &str| {
            crate::validate::test_support::messages_of(&format!(
                "analysis {{ dimension = 3d }}\n\
                 material m {{ neo_hookean {{ E = 1  nu = 0.3 }} }}\n\
                 body b {{ mesh = box {{ origin = (0, 0, 0)  size = (1, 1, 1)  divisions = (1, 1, 1) }}  \
                 material = m  kinematics = finite }}\n\
                 {item}\nstep s {{ time = 0 .. 1  increments = 1 }}\n"
            ))
        };
        assert!(
            deck("rigid_body b.all { center = (0, 0, 0)  mass = 1  inertia_diagonal = (1, 1, 1.5)  tie_stiffness = 1 }")
                .is_empty()
        );
        let m = deck(
            "rigid_body b.all { center = (0, 0)  inertia = 1  inertia_diagonal = (1, 1, 1)  \
             tie_stiffness = 1  moment = 1 }",
        );
        for want in [
            "the centre has 2 coordinates, the analysis 3",
            "the inertia is given twice",
        ] {
            assert!(m.contains(&want.to_string()), "{want}: {m:?}");
        }
        // a moment along an axis turns a free 3d body
        assert!(deck(
            "rigid_body b.all { center = (0, 0, 0)  mass = 1  inertia = 1  axis = (1, 2, 2)  \
             moment = ramp(0, 3)  tie_stiffness = 1 }"
        )
        .is_empty());
        let m = deck(
            "rigid_body b.all { center = (0, 0, 0)  inertia_diagonal = (1, 1, 3)  mass = 1  \
             axis = (0, 0, 0)  rotation = 1  tie_stiffness = 1 }",
        );
        for want in [
            "this rotary inertia cannot be modelled",
            "the rotation axis is zero",
        ] {
            assert!(m.contains(&want.to_string()), "{want}: {m:?}");
        }
        let m = deck("rigid_body b.all { center = (0, 0, 0)  inertia = 1  tie_stiffness = 1 }");
        assert!(
            m.contains(&"this rotary inertia cannot be modelled".to_string()),
            "{m:?}"
        );
    }
}
