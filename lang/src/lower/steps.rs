//! `step` items -> `model::Step` (chained exactly in time, Newton defaults filled in).

use super::{Lowerer, DEFAULT_MIN_FRACTION};
use crate::ast;
use crate::validate::step_label;
use ctc_engine::model::{ContactMass, Dynamic, MassMatrix, NewtonSettings, Scheme, Step};

impl Lowerer<'_> {
    pub(super) fn steps(&mut self) -> Vec<Step> {
        let mut out = Vec::new();
        for (i, s) in self.deck.steps.iter().enumerate() {
            if self.has_error_in(s.span) {
                continue;
            }
            let Some(t) = &s.time else {
                self.missing("the step time", s.keyword);
                continue;
            };
            let mut newton = NewtonSettings::default();
            if let Some(n) = &s.newton {
                if let Some(x) = &n.tol {
                    newton.tol = x.value;
                }
                if let Some(x) = &n.tol_displacement {
                    newton.tol_displacement = x.value;
                }
                if let Some(x) = &n.max_iter {
                    newton.max_iter = x.value.max(1) as usize;
                }
                if let Some(x) = &n.line_search {
                    newton.line_search = x.value;
                }
                if let Some(x) = &n.predictor {
                    newton.predictor = x.value;
                }
                if let Some(x) = &n.stabilize {
                    newton.stabilize = Some(x.value);
                }
            }
            let name = s
                .name
                .as_ref()
                .map(|n| n.name.clone())
                .unwrap_or_else(|| step_label(s, i).replace(' ', "_"));
            // Contiguity was validated; chain exactly so no rounding gap remains.
            let t_start = match out.last() {
                Some(Step { t_end, .. }) => *t_end,
                None => t.value[0].value,
            };
            let increments = s.increments.as_ref().map_or(1, |n| n.value.max(1) as usize);
            let min_fraction = s
                .min_increment
                .as_ref()
                .map_or(DEFAULT_MIN_FRACTION, |x| x.value);
            let t_end = t.value[1].value;
            let dt0 = (t_end - t_start) / increments as f64;
            out.push(Step {
                name,
                t_start,
                t_end,
                increments,
                min_fraction,
                newton,
                dynamic: s.dynamic.as_ref().map(|d| dynamic(d, dt0, min_fraction)),
            });
        }
        out
    }
}

/// The engine's integrator of a `dynamic` block, defaults filled in
/// (`tables::DYNAMIC`; adaptive stepping's bounds from the step's initial
/// increment `dt0` and `min_fraction`).
fn dynamic(d: &ast::Dynamic, dt0: f64, min_fraction: f64) -> Dynamic {
    let v = |x: &Option<crate::span::Spanned<f64>>, default: f64| {
        x.as_ref().map_or(default, |x| x.value)
    };
    let rho_inf = v(&d.rho_inf, ctc_engine::solve::dynamics::DEFAULT_RHO_INF);
    let scheme = match d.scheme.as_ref().map(|s| s.value) {
        Some(ast::DynamicScheme::Newmark) => Scheme::Newmark {
            beta: v(&d.beta, 0.25),
            gamma: v(&d.gamma, 0.5),
        },
        Some(ast::DynamicScheme::Hht) => Scheme::Hht { rho_inf },
        None | Some(ast::DynamicScheme::GeneralizedAlpha) => Scheme::GeneralizedAlpha { rho_inf },
    };
    Dynamic {
        scheme,
        mass: d.mass.as_ref().map_or(MassMatrix::Consistent, |m| m.value),
        contact_mass: d
            .contact_mass
            .as_ref()
            .map_or(ContactMass::Redistributed, |m| m.value),
        rayleigh: ctc_engine::model::Rayleigh {
            alpha: v(&d.rayleigh_alpha, 0.0),
            beta: v(&d.rayleigh_beta, 0.0),
        },
        adaptive: d
            .adaptive
            .as_ref()
            .filter(|a| a.value)
            .map(|_| ctc_engine::model::Adaptive {
                dt_min: v(&d.dt_min, dt0 * min_fraction),
                dt_max: v(&d.dt_max, 10.0 * dt0),
                error_tol: v(&d.error_tol, 1e-2),
            }),
        max_rotation: d.max_rotation.as_ref().map(|m| m.value),
        // absent: the default; 0: no control
        energy_tol: d
            .energy_tol
            .as_ref()
            .map_or(Some(ctc_engine::model::DEFAULT_ENERGY_TOL), |m| {
                (m.value > 0.0).then_some(m.value)
            }),
    }
}
