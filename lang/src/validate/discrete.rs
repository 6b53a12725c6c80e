//! Rules of the `spring` and `point_mass` items.

use super::{sets, Ctx, Need};
use crate::ast::{num, DiscreteItem, DiscreteKind};
use crate::diagnostics::Diagnostic;

/// Checks every `spring` and `point_mass` item.
pub fn check(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    for d in &deck.discrete {
        let what = match d.kind {
            DiscreteKind::Spring => "spring",
            DiscreteKind::PointMass => "point_mass",
        };
        sets::set_ref(&d.target, Need::Nodes, what, ctx);
        if let Some(o) = &d.other {
            sets::set_ref(o, Need::Nodes, what, ctx);
        }
        values_not_negative(d, ctx);
        discrete_item_gives_a_value(d, what, ctx);
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
}
