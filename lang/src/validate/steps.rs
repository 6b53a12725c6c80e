//! Rules of `step` items.

use super::{step_label, Ctx};
use crate::ast::{self, num, Span, Spanned};
use crate::diagnostics::Diagnostic;

/// Checks every step: at least one, unique names, contiguous non-empty
/// time ranges, increments and Newton settings in range.
pub fn check(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    if deck.steps.is_empty()
        && !deck.has_broken("step")
        && !deck.broken.iter().any(|b| b.keyword.is_empty())
    {
        ctx.err(
            Diagnostic::error(
                "the deck has no `step`",
                Span::new(0, 0),
                "expected a `step`",
            )
            .with_help("add e.g. `step load { time = 0 .. 1  increments = 10 }`"),
        );
    }
    ctx.names_are_unique(deck.steps.iter().filter_map(|s| s.name.as_ref()), "step");
    let mut previous: Option<(String, f64)> = None;
    for (i, s) in deck.steps.iter().enumerate() {
        let label = step_label(s, i);
        if let Some(t) = &s.time {
            let [t0, t1] = &t.value;
            if t1.value <= t0.value {
                ctx.err(
                    Diagnostic::error(
                        format!("empty time range in {label}"),
                        t.span,
                        format!("{} .. {} is empty", num(t0.value), num(t1.value)),
                    )
                    .with_help("the end time must be larger than the start time"),
                );
            }
            if let Some((prev, end)) = &previous {
                let tol = 1e-12 * end.abs().max(1.0);
                if t0.value < end - tol {
                    ctx.err(
                        Diagnostic::error(
                            format!("{label} starts at {} before {prev} ends", num(t0.value)),
                            t0.span,
                            format!("{prev} ends at {}", num(*end)),
                        )
                        .with_help(format!(
                            "steps follow each other in time: start this one at {}",
                            num(*end)
                        )),
                    );
                } else if t0.value > end + tol {
                    ctx.err(
                        Diagnostic::error(
                            format!("{label} leaves a gap after {prev}"),
                            t0.span,
                            format!("{prev} ends at {}", num(*end)),
                        )
                        .with_help(format!(
                            "steps follow each other in time: start this one at {}",
                            num(*end)
                        )),
                    );
                }
            }
            previous = Some((label.clone(), t1.value));
        }
        ctx.at_least(&s.increments, 1, "increments");
        if let Some(m) = s
            .min_increment
            .as_ref()
            .filter(|m| !(m.value > 0.0 && m.value <= 1.0))
        {
            ctx.err(
                    Diagnostic::error("`min_increment` must lie in (0, 1]", m.span, format!("min_increment = {}", num(m.value)))
                        .with_help("it is the smallest cutback increment as a fraction of the initial increment, e.g. 1e-3"),
                );
        }
        if let Some(d) = &s.dynamic {
            dynamic_parameters_fit_scheme(d, ctx);
            dynamic_bodies_have_density(d, ctx);
        }
        if let Some(n) = &s.newton {
            ctx.must_be_positive(&n.tol, "tol");
            ctx.must_be_positive(&n.tol_displacement, "tol_displacement");
            ctx.at_least(&n.max_iter, 1, "max_iter");
            ctx.must_be_positive(&n.stabilize, "stabilize");
        }
    }
}

/// `rho_inf` belongs to `hht` / `generalized_alpha` (in [0, 1]; hht in
/// [1/2, 1]), `beta` and `gamma` to `newmark` (`gamma >= 1/2`, `beta > 0`).
pub fn dynamic_parameters_fit_scheme(d: &ast::Dynamic, ctx: &mut Ctx<'_>) {
    use ast::DynamicScheme as S;
    let scheme = d.scheme.as_ref().map_or(S::GeneralizedAlpha, |s| s.value);
    let name = match scheme {
        S::Newmark => "newmark",
        S::Hht => "hht",
        S::GeneralizedAlpha => "generalized_alpha",
    };
    let misplaced: [(&Option<Spanned<f64>>, &str, bool); 3] = [
        (&d.rho_inf, "rho_inf", scheme == S::Newmark),
        (&d.beta, "beta", scheme != S::Newmark),
        (&d.gamma, "gamma", scheme != S::Newmark),
    ];
    for (x, key, wrong) in misplaced {
        if let (Some(x), true) = (x, wrong) {
            let help = if scheme == S::Newmark {
                "newmark takes `beta` and `gamma`; use `scheme = hht` or `generalized_alpha` for \
                 `rho_inf`"
            } else {
                "`beta` and `gamma` are given by `rho_inf` here; use `scheme = newmark` to set them"
            };
            ctx.err(
                Diagnostic::error(
                    format!("`{key}` does not apply to `scheme = {name}`"),
                    x.span,
                    format!("not a parameter of {name}"),
                )
                .with_help(help),
            );
        }
    }
    if let Some(r) = &d.rho_inf {
        let lo = if scheme == S::Hht { 0.5 } else { 0.0 };
        if !(lo..=1.0).contains(&r.value) {
            ctx.err(
                Diagnostic::error(
                    format!("rho_inf must lie in [{}, 1] for {name}", num(lo)),
                    r.span,
                    format!("rho_inf = {}", num(r.value)),
                )
                .with_help("1: no numerical dissipation; smaller values damp the high modes"),
            );
        }
    }
    if let Some(g) = d
        .gamma
        .as_ref()
        .filter(|g| g.value < 0.5 || g.value.is_nan())
    {
        ctx.err(
            Diagnostic::error(
                "gamma must be at least 1/2",
                g.span,
                format!("gamma = {}", num(g.value)),
            )
            .with_help("gamma < 1/2 makes Newmark unstable (negative damping); 1/2 is the average acceleration rule"),
        );
    }
    ctx.must_be_positive(&d.beta, "beta");
    ctx.must_be_positive(&d.max_rotation, "max_rotation");
    energy_tol_not_negative(d, ctx);
    rayleigh_damping_not_negative(d, ctx);
    adaptive_bounds(d, ctx);
}

/// `dt_min`, `dt_max` and `error_tol` belong to `adaptive = true`;
/// `dt_min > 0`, `dt_max > 0`, `dt_min <= dt_max`, `error_tol >= 0`.
pub fn adaptive_bounds(d: &ast::Dynamic, ctx: &mut Ctx<'_>) {
    let adaptive = d.adaptive.as_ref().is_some_and(|a| a.value);
    for (x, key) in [
        (&d.dt_min, "dt_min"),
        (&d.dt_max, "dt_max"),
        (&d.error_tol, "error_tol"),
    ] {
        if let (Some(x), false) = (x, adaptive) {
            ctx.err(
                Diagnostic::error(
                    format!("`{key}` needs adaptive time stepping"),
                    x.span,
                    "the step's increments are fixed without `adaptive = true`",
                )
                .with_help("add `adaptive = true` to the `dynamic` block, or remove the key"),
            );
        }
    }
    ctx.must_be_positive(&d.dt_min, "dt_min");
    ctx.must_be_positive(&d.dt_max, "dt_max");
    if let Some(e) = d
        .error_tol
        .as_ref()
        .filter(|e| e.value < 0.0 || e.value.is_nan())
    {
        ctx.err(Diagnostic::error(
            "error_tol must not be negative",
            e.span,
            format!("error_tol = {}", num(e.value)),
        ));
    }
    if let (Some(lo), Some(hi)) = (&d.dt_min, &d.dt_max) {
        if lo.value > hi.value {
            ctx.err(
                Diagnostic::error(
                    "dt_min is larger than dt_max",
                    lo.span,
                    format!("dt_min = {} > dt_max = {}", num(lo.value), num(hi.value)),
                )
                .with_help("adaptive stepping keeps the increment within [dt_min, dt_max]"),
            );
        }
    }
}

/// `rayleigh_alpha` and `rayleigh_beta` are `>= 0` (a negative one feeds
/// energy into the modes it acts on).
pub fn rayleigh_damping_not_negative(d: &ast::Dynamic, ctx: &mut Ctx<'_>) {
    for (x, key) in [
        (&d.rayleigh_alpha, "rayleigh_alpha"),
        (&d.rayleigh_beta, "rayleigh_beta"),
    ] {
        if let Some(x) = x.as_ref().filter(|x| x.value < 0.0 || x.value.is_nan()) {
            ctx.err(
                Diagnostic::error(
                    format!("{key} must not be negative"),
                    x.span,
                    format!("{key} = {}", num(x.value)),
                )
                .with_help(
                    "negative damping feeds energy into the modes; the damping ratio of a mode \
                     of circular frequency w is rayleigh_alpha / (2 w) + rayleigh_beta w / 2",
                ),
            );
        }
    }
}

/// A dynamic step needs a positive `density` on the material of every body
/// that carries no `point_mass` (a massless body whose mass sits at point
/// masses, e.g. a spring of finite elements, is accepted).
pub fn dynamic_bodies_have_density(d: &ast::Dynamic, ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    for b in &deck.bodies {
        let Some(mname) = b.material.as_ref() else {
            continue;
        };
        // a point mass on its nodes, or a rigid body with a mass tying them
        if deck.discrete.iter().any(|p| {
            p.target.body.name == b.name.name
                && (p.kind == ast::DiscreteKind::PointMass
                    || p.kind == ast::DiscreteKind::RigidBody
                        && p.mass.as_ref().is_some_and(|m| m.value > 0.0))
        }) {
            continue;
        }
        let Some(m) = deck.materials.iter().find(|m| m.name.name == mname.name) else {
            continue;
        };
        if m.density.as_ref().is_none_or(|r| r.value <= 0.0) {
            ctx.err(
                Diagnostic::error(
                    format!("body `{}` has no mass: material `{}` gives no density", b.name.name, m.name.name),
                    d.span,
                    "this step is dynamic",
                )
                .with_secondary(m.name.span, "add `density = ..` here")
                .with_help("write e.g. `material steel { elastic { E = 210e9  nu = 0.3 }  density = 7800 }`"),
            );
        }
    }
}

/// `energy_tol >= 0` (0: no energy control; absent: the default).
pub fn energy_tol_not_negative(d: &ast::Dynamic, ctx: &mut Ctx<'_>) {
    if let Some(e) = d.energy_tol.as_ref().filter(|e| e.value < 0.0) {
        ctx.err(
            Diagnostic::error("energy_tol must not be negative", e.span, "must be >= 0")
                .with_help("energy_tol = 0 turns the energy control off; absent, it is 1e-3"),
        );
    }
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    #[test]
    fn dynamic_steps_need_density_and_matching_parameters() {
        let m = messages(
            "step d { time = 1 .. 2 dynamic { scheme = newmark rho_inf = 0.5 gamma = 0.4 } }",
        );
        assert!(
            m.contains(&"`rho_inf` does not apply to `scheme = newmark`".to_string()),
            "{m:?}"
        );
        assert!(
            m.contains(&"gamma must be at least 1/2".to_string()),
            "{m:?}"
        );
        assert!(m.iter().any(|s| s.contains("has no mass")), "{m:?}");
        let m = messages("step d { time = 1 .. 2 dynamic { scheme = hht rho_inf = 0.2 } }");
        assert!(
            m.contains(&"rho_inf must lie in [0.5, 1] for hht".to_string()),
            "{m:?}"
        );
    }

    #[test]
    fn rayleigh_damping_must_not_be_negative() {
        let m = messages(
            "step d { time = 1 .. 2 dynamic { rayleigh_alpha = -0.1  rayleigh_beta = 0.01 } }",
        );
        assert!(
            m.contains(&"rayleigh_alpha must not be negative".to_string()),
            "{m:?}"
        );
        assert!(!m.iter().any(|s| s.contains("rayleigh_beta")), "{m:?}");
    }

    #[test]
    fn adaptive_keys_need_adaptive_and_ordered_bounds() {
        let m = messages("step d { time = 1 .. 2 dynamic { dt_max = 0.1 } }");
        assert!(
            m.contains(&"`dt_max` needs adaptive time stepping".to_string()),
            "{m:?}"
        );
        let m = messages(
            "step d { time = 1 .. 2 dynamic { adaptive = true  dt_min = 0.2  dt_max = 0.1  \
             error_tol = -1 } }",
        );
        assert!(
            m.contains(&"dt_min is larger than dt_max".to_string()),
            "{m:?}"
        );
        assert!(
            m.contains(&"error_tol must not be negative".to_string()),
            "{m:?}"
        );
        assert!(!m.iter().any(|s| s.contains("needs adaptive")), "{m:?}");
    }

    #[test]
    fn step_times_must_be_contiguous() {
        let m = messages("step b { time = 0.5 .. 2 }\nstep c { time = 3 .. 3 }");
        assert_eq!(
            m,
            [
                "step `b` starts at 0.5 before step `load` ends",
                "empty time range in step `c`",
                "step `c` leaves a gap after step `b`"
            ]
        );
    }
}
