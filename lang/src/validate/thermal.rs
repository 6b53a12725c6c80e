//! Rules of the thermal constructs: the ranges of the `thermal` blocks of
//! materials and contacts, and of `convection` items. (Rules that need the
//! lowered scene — a thermal body needs a thermal material, a rigid tool
//! needs its temperature — are checked by [`crate::lower::thermal`].)

use super::Ctx;
use crate::ast::thermal::{Conductance, ContactThermal, MaterialThermal, ThermalLoadKind};
use crate::ast::Spanned;
use crate::diagnostics::Diagnostic;

/// Checks every thermal block and thermal load.
pub fn check(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    for m in &deck.materials {
        if let Some(t) = &m.thermal {
            material_properties_in_range(t, ctx);
        }
    }
    for c in &deck.contacts {
        if let Some(t) = &c.thermal {
            contact_properties_in_range(t, ctx);
        }
    }
    for l in &deck.thermal_loads {
        if l.kind == ThermalLoadKind::Convection {
            in_range(
                &l.film,
                |x| x >= 0.0,
                "the film coefficient must be >= 0",
                ctx,
            );
        }
    }
}

/// Error "`what` (got x)" unless `ok(x)`.
fn in_range(v: &Option<Spanned<f64>>, ok: impl Fn(f64) -> bool, what: &str, ctx: &mut Ctx<'_>) {
    if let Some(x) = v {
        if !(x.value.is_finite() && ok(x.value)) {
            ctx.err(Diagnostic::error(
                format!("{what} (got {})", x.value),
                x.span,
                "out of range",
            ));
        }
    }
}

/// The abscissas of a table strictly increase.
fn abscissas_increase(t: &Spanned<Vec<(f64, f64)>>, what: &str, ctx: &mut Ctx<'_>) -> bool {
    if t.value.windows(2).any(|w| w[1].0 <= w[0].0) {
        ctx.err(Diagnostic::error(
            format!("the points of {what} must have strictly increasing abscissas"),
            t.span,
            "not increasing",
        ));
        return false;
    }
    true
}

/// Conductivity > 0; capacity, density, expansion >= 0; Taylor-Quinney in
/// [0, 1]; temperature factor tables increasing and > 0.
pub fn material_properties_in_range(t: &MaterialThermal, ctx: &mut Ctx<'_>) {
    in_range(
        &t.conductivity,
        |x| x > 0.0,
        "the conductivity must be > 0",
        ctx,
    );
    in_range(&t.capacity, |x| x >= 0.0, "the capacity must be >= 0", ctx);
    in_range(&t.density, |x| x >= 0.0, "the density must be >= 0", ctx);
    in_range(
        &t.expansion,
        |x| x >= 0.0,
        "the expansion coefficient must be >= 0",
        ctx,
    );
    in_range(
        &t.taylor_quinney,
        |x| (0.0..=1.0).contains(&x),
        "the Taylor-Quinney factor must be in [0, 1]",
        ctx,
    );
    for (t, what) in [
        (&t.young, "the `young` factor"),
        (&t.yield_factor, "the `yield` factor"),
    ] {
        let Some(t) = t else { continue };
        if abscissas_increase(t, what, ctx)
            && t.value.iter().any(|p| !(p.1 > 0.0 && p.1.is_finite()))
        {
            ctx.err(Diagnostic::error(
                "temperature factors must be > 0",
                t.span,
                "out of range",
            ));
        }
    }
}

/// Conductance laws non-negative (exponent > 0), gap conductivity >= 0,
/// gap_min > 0, friction_split in [0, 1].
pub fn contact_properties_in_range(t: &ContactThermal, ctx: &mut Ctx<'_>) {
    if let Some(c) = &t.conductance {
        match &c.value {
            Conductance::Constant(h) => in_range(
                &Some(h.clone()),
                |x| x >= 0.0,
                "the conductance must be >= 0",
                ctx,
            ),
            Conductance::Power { h0, h1, n } => {
                in_range(h0, |x| x >= 0.0, "h0 must be >= 0", ctx);
                in_range(h1, |x| x >= 0.0, "h1 must be >= 0", ctx);
                in_range(n, |x| x > 0.0, "the exponent n must be > 0", ctx);
            }
            Conductance::Table(points) => {
                let t = Spanned::new(points.clone(), c.span);
                if abscissas_increase(&t, "the conductance table", ctx)
                    && points.iter().any(|p| p.1 < 0.0)
                {
                    ctx.err(Diagnostic::error(
                        "conductances must be >= 0",
                        c.span,
                        "out of range",
                    ));
                }
            }
        }
    }
    in_range(
        &t.gap_conductivity,
        |x| x >= 0.0,
        "the gap conductivity must be >= 0",
        ctx,
    );
    in_range(&t.gap_min, |x| x > 0.0, "gap_min must be > 0", ctx);
    in_range(
        &t.friction_split,
        |x| (0.0..=1.0).contains(&x),
        "friction_split must be in [0, 1]",
        ctx,
    );
}

#[cfg(test)]
mod tests {
    use crate::parse::parse;
    use crate::validate::validate;

    fn thermal_messages(text: &str) -> Vec<String> {
        let (deck, _) = parse(text);
        let mut m: Vec<String> = validate(&deck, text)
            .into_iter()
            .map(|d| d.message)
            .collect();
        m.retain(|x| !x.starts_with("the deck has no") && !x.contains("not used by any"));
        m
    }

    #[test]
    fn thermal_ranges_are_checked_by_validation() {
        assert_eq!(
            thermal_messages(
                "material st { elastic { E = 1 nu = 0.3 } thermal { conductivity = -1 capacity = 1 young = table((20, 1), (10, 2)) } }"
            ),
            [
                "the conductivity must be > 0 (got -1)",
                "the points of the `young` factor must have strictly increasing abscissas"
            ]
        );
        assert_eq!(
            thermal_messages(
                "contact b.s -> t { method = penalty { stiffness = 1 } thermal { conductance = 1 friction_split = 2 } }"
            )
            .last()
            .map(String::as_str),
            Some("friction_split must be in [0, 1] (got 2)")
        );
        assert!(thermal_messages(
            "contact b.s -> t { method = penalty { stiffness = 1 } thermal { conductance = power { h0 = -1 n = 0 } } }"
        )
        .ends_with(&[
            "h0 must be >= 0 (got -1)".to_string(),
            "the exponent n must be > 0 (got 0)".to_string()
        ]));
    }
}
