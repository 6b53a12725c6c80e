//! `friction = coulomb { mu = ..  stiffness = ..  first_impact = ..
//! cut_at_impact = .. }` inside a `contact` block.
//!
//! - `mu` (required): Coulomb coefficient, >= 0;
//! - `stiffness`: tangential penalty `alpha_T` (same kind and units as the
//!   normal penalty; default `alpha_N / 10`; unused with `lagrange`);
//! - `first_impact`: `intersect` (default: the stick point is where the node
//!   met the master, constant-velocity intersection) or `frictionless` (no
//!   friction in the increment of the first touch);
//! - `cut_at_impact`: `true` cuts an increment in which a node first
//!   touches at the fraction where it meets the master (default `false`).

use super::fields::Fields;
use super::values::Diags;
use crate::ast::syntax::{Value, ValueKind};
use crate::ast::{FirstImpact, Friction};
use crate::diagnostics::Diagnostic;
use crate::span::Spanned;
use crate::suggest::did_you_mean;

/// Friction laws the language knows.
pub const LAWS: [&str; 1] = ["coulomb"];

const FIRST_IMPACT: [(&str, FirstImpact); 2] = [
    ("intersect", FirstImpact::Intersect),
    ("frictionless", FirstImpact::Frictionless),
];

/// Converts the value of `friction = ..`.
pub fn parse(v: &Value, diags: &mut Diags) -> Option<Spanned<Friction>> {
    let (name, block) = match &v.kind {
        ValueKind::Ctor { name, block } => (name, block),
        ValueKind::Path(p) if p.len() == 1 && p[0].name == "coulomb" => {
            diags.push(Diagnostic::error(
                "`coulomb` needs its friction coefficient",
                v.span,
                "expected `coulomb { mu = .. }`",
            ));
            return None;
        }
        other => {
            diags.push(Diagnostic::error(
                format!("expected a friction law, found {}", other.describe()),
                v.span,
                "expected `coulomb { mu = .. }`",
            ));
            return None;
        }
    };
    if name.name != "coulomb" {
        diags.push(
            Diagnostic::error(
                format!("unknown friction law `{}`", name.name),
                name.span,
                "not a friction law",
            )
            .with_help(
                did_you_mean(&name.name, LAWS)
                    .unwrap_or_else(|| "expected `coulomb { mu = .. }`".into()),
            ),
        );
        return None;
    }
    let mut f = Fields::keyed(block, "`coulomb` block", &crate::tables::COULOMB);
    let mu = f.number("mu", diags);
    let stiffness = f.number("stiffness", diags);
    let first_impact = f.choice(
        "first_impact",
        "first impact treatment",
        &FIRST_IMPACT,
        diags,
    );
    let cut_at_impact = f.boolean("cut_at_impact", diags);
    f.require(
        &mu,
        "mu",
        name.span,
        "add `mu = <friction coefficient>`",
        diags,
    );
    f.finish(diags);
    Some(Spanned::new(
        Friction {
            mu,
            stiffness,
            first_impact,
            cut_at_impact,
        },
        v.span,
    ))
}

#[cfg(test)]
mod tests {
    use crate::ast::FirstImpact;
    use crate::parse::test_support::{parse_messages, parse_ok};

    #[test]
    fn coulomb_friction_block() {
        let deck = parse_ok(
            "contact a.b -> t { method = penalty { stiffness = 1e6 }\n  friction = coulomb { mu = 0.3  \
             stiffness = 1e5  first_impact = frictionless  cut_at_impact = true } }",
        );
        let f = &deck.contacts[0].friction.as_ref().unwrap().value;
        assert_eq!(f.mu.as_ref().unwrap().value, 0.3);
        assert_eq!(f.stiffness.as_ref().unwrap().value, 1e5);
        assert_eq!(
            f.first_impact.as_ref().unwrap().value,
            FirstImpact::Frictionless
        );
        assert!(f.cut_at_impact.as_ref().unwrap().value);
        assert!(deck.contacts[0].reserved.is_empty());
    }

    #[test]
    fn friction_errors() {
        assert_eq!(
            parse_messages("contact a.b -> t { method = lagrange  friction = coulomb { } }"),
            ["missing `mu` in the `coulomb` block"]
        );
        assert_eq!(
            parse_messages("contact a.b -> t { method = lagrange  friction = coulomb }"),
            ["`coulomb` needs its friction coefficient"]
        );
        assert_eq!(
            parse_messages("contact a.b -> t { method = lagrange  friction = colomb { mu = 1 } }"),
            ["unknown friction law `colomb`"]
        );
        let m = parse_messages(
            "contact a.b -> t { method = lagrange  friction = coulomb { mu = 1  first_impact = now } }",
        );
        assert_eq!(m.len(), 1, "{m:?}");
        let m = parse_messages(
            "contact a.b -> t { method = lagrange  friction = coulomb { mu = 1  muu = 2 } }",
        );
        assert_eq!(m.len(), 1, "{m:?}");
    }
}
