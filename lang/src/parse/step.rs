//! `step name { time = t0 .. t1  increments = n  min_increment = f  newton { .. } }`.

use super::fields::Fields;
use super::values::{self, Diags};
use super::ItemParts;
use crate::ast::syntax::ValueKind;
use crate::ast::{Dynamic, Newton, Step};
use crate::diagnostics::Diagnostic;
use crate::span::Spanned;

/// Converts a `step` item.
pub fn parse(item: ItemParts, diags: &mut Diags) -> Option<Step> {
    let block = item.block?;
    let what = match &item.name {
        Some(n) => format!("step `{}`", n.name),
        None => "`step` block".to_string(),
    };
    let mut f = Fields::keyed(&block, what, &crate::tables::STEP);
    let time = f.value("time", diags).and_then(|v| match &v.kind {
        ValueKind::Range(a, b) => {
            let t0 = values::number(a, diags);
            let t1 = values::number(b, diags);
            Some(Spanned::new([t0?, t1?], v.span))
        }
        other => {
            diags.push(
                Diagnostic::error(
                    format!("expected a time range, found {}", other.describe()),
                    v.span,
                    "expected `t0 .. t1`",
                )
                .with_help("write e.g. `time = 0 .. 1`"),
            );
            None
        }
    });
    let increments = f.integer("increments", diags);
    let min_increment = f.number("min_increment", diags);
    let newton = f.block("newton", diags).map(|b| {
        let mut n = Fields::keyed(b, "`newton` block", &crate::tables::NEWTON);
        let out = Newton {
            tol: n.number("tol", diags),
            tol_displacement: n.number("tol_displacement", diags),
            max_iter: n.integer("max_iter", diags),
            line_search: n.boolean("line_search", diags),
            predictor: n.boolean("predictor", diags),
            stabilize: stabilize(&mut n, diags),
            span: b.span,
        };
        n.finish(diags);
        out
    });
    let dynamic = dynamic(&mut f, diags);
    let at = item.name.as_ref().map(|n| n.span).unwrap_or(item.keyword);
    f.require(&time, "time", at, "add e.g. `time = 0 .. 1`", diags);
    f.finish(diags);
    Some(Step {
        name: item.name,
        keyword: item.keyword,
        time,
        increments,
        min_increment,
        newton,
        dynamic,
        span: item.span,
    })
}

/// `dynamic { .. }`, or a bare `dynamic` (every default).
fn dynamic(f: &mut Fields, diags: &mut Diags) -> Option<Dynamic> {
    use crate::ast::syntax::EntryBody;
    use crate::ast::DynamicScheme;
    use ctc_engine::model::{ContactMass, MassMatrix};
    if !f.mentions("dynamic") {
        return None;
    }
    let e = f.entry("dynamic", diags)?;
    let b = match &e.body {
        EntryBody::Flag => {
            return Some(Dynamic {
                scheme: None,
                rho_inf: None,
                beta: None,
                gamma: None,
                mass: None,
                contact_mass: None,
                rayleigh_alpha: None,
                rayleigh_beta: None,
                adaptive: None,
                dt_min: None,
                dt_max: None,
                error_tol: None,
                max_rotation: None,
                energy_tol: None,
                span: e.span,
            })
        }
        EntryBody::Block(b) => b,
        _ => {
            diags.push(
                Diagnostic::error(
                    "`dynamic` is a block",
                    e.span,
                    "expected `dynamic { .. }` or a bare `dynamic`",
                )
                .with_help("write e.g. `dynamic { scheme = generalized_alpha  rho_inf = 0.9 }`"),
            );
            return None;
        }
    };
    let mut d = Fields::keyed(b, "`dynamic` block", &crate::tables::DYNAMIC);
    let out = Dynamic {
        scheme: d.choice(
            "scheme",
            "time integration scheme",
            &[
                ("newmark", DynamicScheme::Newmark),
                ("hht", DynamicScheme::Hht),
                ("generalized_alpha", DynamicScheme::GeneralizedAlpha),
            ],
            diags,
        ),
        rho_inf: d.number("rho_inf", diags),
        beta: d.number("beta", diags),
        gamma: d.number("gamma", diags),
        mass: d.choice(
            "mass",
            "mass matrix",
            &[
                ("consistent", MassMatrix::Consistent),
                ("lumped", MassMatrix::Lumped),
            ],
            diags,
        ),
        contact_mass: d.choice(
            "contact_mass",
            "mass of the contact-surface nodes",
            &[
                ("redistributed", ContactMass::Redistributed),
                ("full", ContactMass::Full),
                ("normal", ContactMass::Normal),
            ],
            diags,
        ),
        rayleigh_alpha: d.number("rayleigh_alpha", diags),
        rayleigh_beta: d.number("rayleigh_beta", diags),
        adaptive: d.boolean("adaptive", diags),
        dt_min: d.number("dt_min", diags),
        dt_max: d.number("dt_max", diags),
        error_tol: d.number("error_tol", diags),
        max_rotation: d.number("max_rotation", diags),
        energy_tol: d.number("energy_tol", diags),
        span: e.span,
    };
    d.finish(diags);
    Some(out)
}

/// `stabilize = c`, or a bare `stabilize`: the default factor.
fn stabilize(n: &mut Fields, diags: &mut Diags) -> Option<Spanned<f64>> {
    if !n.mentions("stabilize") {
        return None;
    }
    let e = n.entry("stabilize", diags)?;
    match &e.body {
        crate::ast::syntax::EntryBody::Flag => Some(Spanned::new(
            ctc_engine::solve::stabilize::DEFAULT_FACTOR,
            e.span,
        )),
        _ => n.number("stabilize", diags),
    }
}

#[cfg(test)]
mod tests {
    use crate::parse::test_support::{parse_messages, parse_ok};

    #[test]
    fn step_with_newton_block() {
        let deck = parse_ok(
            "step press {\n  time = 0 .. 1\n  increments = 4\n  min_increment = 1e-3\n  newton { tol = 1e-9  max_iter = 20  line_search = true }\n}\nstep { time = 1..2 }",
        );
        let s = &deck.steps[0];
        assert_eq!(s.name.as_ref().unwrap().name, "press");
        let t = s.time.as_ref().unwrap();
        assert_eq!((t.value[0].value, t.value[1].value), (0.0, 1.0));
        assert_eq!(s.increments.as_ref().unwrap().value, 4);
        assert_eq!(s.min_increment.as_ref().unwrap().value, 1e-3);
        let n = s.newton.as_ref().unwrap();
        assert_eq!(n.tol.as_ref().unwrap().value, 1e-9);
        assert_eq!(n.max_iter.as_ref().unwrap().value, 20);
        assert!(n.line_search.as_ref().unwrap().value);
        assert!(deck.steps[1].name.is_none());
        let t = deck.steps[1].time.as_ref().unwrap();
        assert_eq!((t.value[0].value, t.value[1].value), (1.0, 2.0));
    }

    #[test]
    fn stabilize_is_a_factor_or_a_bare_key() {
        let newton = |text: &str| {
            let deck = parse_ok(&format!("step s {{ time = 0 .. 1  newton {{ {text} }} }}"));
            deck.steps[0]
                .newton
                .as_ref()
                .unwrap()
                .stabilize
                .as_ref()
                .map(|x| x.value)
        };
        assert_eq!(
            newton("stabilize"),
            Some(ctc_engine::solve::stabilize::DEFAULT_FACTOR)
        );
        assert_eq!(newton("tol = 1e-9  stabilize = 2e-4"), Some(2e-4));
        assert_eq!(newton("tol = 1e-9"), None);
        assert_eq!(
            parse_messages("step s { time = 0 .. 1 newton { stabilize { } } }"),
            ["`stabilize` needs a value"]
        );
        assert_eq!(
            parse_messages("step s { time = 0 .. 1 newton { stabilise } }"),
            ["unknown key `stabilise` in the `newton` block"]
        );
        assert_eq!(
            crate::validate::test_support::messages(
                "step s2 { time = 1 .. 2 newton { stabilize = -1 } }"
            )
            .last()
            .map(String::as_str),
            Some("stabilize must be positive")
        );
    }

    #[test]
    fn dynamic_block_or_bare_key() {
        use crate::ast::DynamicScheme;
        let deck = parse_ok(
            "step a { time = 0 .. 1  dynamic { scheme = hht  rho_inf = 0.8  mass = lumped } }\n\
             step b { time = 1 .. 2  dynamic }\nstep c { time = 2 .. 3 }",
        );
        let d = deck.steps[0].dynamic.as_ref().unwrap();
        assert_eq!(d.scheme.as_ref().unwrap().value, DynamicScheme::Hht);
        assert_eq!(d.rho_inf.as_ref().unwrap().value, 0.8);
        assert_eq!(
            d.mass.as_ref().unwrap().value,
            ctc_engine::model::MassMatrix::Lumped
        );
        assert!(deck.steps[1].dynamic.as_ref().unwrap().scheme.is_none());
        assert!(deck.steps[2].dynamic.is_none());
        assert_eq!(
            parse_messages("step s { time = 0 .. 1 dynamic { scheme = newmrk } }"),
            ["unknown time integration scheme `newmrk`"]
        );
        assert_eq!(
            parse_messages("step s { time = 0 .. 1 dynamic { rho = 0.5 } }"),
            ["unknown key `rho` in the `dynamic` block"]
        );
    }

    #[test]
    fn step_mistakes() {
        assert_eq!(
            parse_messages("step s { time = 1 }"),
            ["expected a time range, found a number"]
        );
        assert_eq!(
            parse_messages("step s { increments = 2 }"),
            ["missing `time` in the step `s`"]
        );
        assert_eq!(
            parse_messages("step s { time = 0 .. 1 newton { tol = 1e-9 max_iters = 3 } }"),
            ["unknown key `max_iters` in the `newton` block"]
        );
    }
}
