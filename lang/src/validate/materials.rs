//! Rules of `material` items: elastic constants, the combination of laws,
//! hardening parameters, and whether a material is used.

use super::Ctx;
use crate::ast::{num, Hardening, Material, NortonHoff, Viscoplastic};
use crate::diagnostics::Diagnostic;

/// Checks every material.
pub fn check(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    ctx.names_are_unique(deck.materials.iter().map(|m| &m.name), "material");
    for m in &deck.materials {
        reserved_blocks_not_supported(m, ctx);
        one_elastic_law(m, ctx);
        no_plasticity_on_neo_hookean(m, ctx);
        viscoplastic_needs_plastic(m, ctx);
        if let Some(v) = &m.viscoplastic {
            ctx.must_be_positive(&v.eta, "the viscosity eta");
            ctx.must_be_positive(&v.rate, "the Perzyna reference rate");
            ctx.must_be_positive(&v.exponent, "the Perzyna exponent");
            perzyna_is_linear_or_power(v, ctx);
        }
        if let Some(n) = &m.norton_hoff {
            ctx.must_be_positive(&n.stress, "the Norton-Hoff stress");
            ctx.must_be_positive(&n.rate, "the Norton-Hoff reference rate");
            norton_hoff_m_in_range(n, ctx);
        }
        one_rate_law(m, ctx);
        yield_stress_fits_hardening(m, ctx);
        hardening_in_range(m, ctx);
        density_not_negative(m, ctx);
        if m.elastic.is_none() && m.neo_hookean.is_none() {
            continue;
        }
        young_is_positive(m, ctx);
        poisson_in_range(m, ctx);
        is_used(m, ctx);
    }
}

/// The mass density is `>= 0`.
pub fn density_not_negative(m: &Material, ctx: &mut Ctx<'_>) {
    if let Some(d) = m
        .density
        .as_ref()
        .filter(|d| d.value < 0.0 || d.value.is_nan())
    {
        ctx.err(
            Diagnostic::error(
                "the density must not be negative",
                d.span,
                format!("density = {}", num(d.value)),
            )
            .with_help("a mass density is >= 0 (0: no inertia)"),
        );
    }
}

/// Reserved material blocks are reported as not supported yet.
pub fn reserved_blocks_not_supported(m: &Material, ctx: &mut Ctx<'_>) {
    for r in &m.reserved {
        ctx.err(
            Diagnostic::error(
                format!("`{}` materials are not supported yet", r.name),
                r.span,
                "not supported yet",
            )
            .with_help("use `elastic`, `neo_hookean`, `plastic` and `viscoplastic` blocks"),
        );
    }
}

/// Either `elastic` or `neo_hookean`, not both.
pub fn one_elastic_law(m: &Material, ctx: &mut Ctx<'_>) {
    if let (Some(n), Some(_)) = (&m.neo_hookean, &m.elastic) {
        ctx.err(
            Diagnostic::error(
                "a material has either `elastic` or `neo_hookean`, not both",
                n.span,
                "second elastic law",
            )
            .with_help("remove one of the two blocks"),
        );
    }
}

/// Plasticity is built on Hencky elasticity, not on Neo-Hookean.
pub fn no_plasticity_on_neo_hookean(m: &Material, ctx: &mut Ctx<'_>) {
    if let (Some(_), Some(p)) = (&m.neo_hookean, &m.plastic) {
        ctx.err(
            Diagnostic::error(
                "plasticity on a Neo-Hookean material is not supported yet",
                p.span,
                "not supported yet",
            )
            .with_help(
                "use `elastic { .. }` with `plastic { .. }` (Hencky elasticity at finite strain)",
            ),
        );
    }
}

/// A `viscoplastic` block is either the linear law (`eta`) or the power
/// law (`rate` and `exponent` together).
pub fn perzyna_is_linear_or_power(v: &Viscoplastic, ctx: &mut Ctx<'_>) {
    match (&v.eta, &v.rate, &v.exponent) {
        (Some(eta), Some(_), _) | (Some(eta), _, Some(_)) => ctx.err(
            Diagnostic::error(
                "`eta` and the power law's `rate` / `exponent` exclude each other",
                eta.span,
                "linear law",
            )
            .with_help("keep `eta` (linear over-stress) or `rate` and `exponent` (power law)"),
        ),
        (None, Some(r), None) => ctx.err(
            Diagnostic::error(
                "the power law needs its `exponent`",
                r.span,
                "no `exponent`",
            )
            .with_help("add `exponent = ..` (1: over-stress linear in the rate)"),
        ),
        (None, None, Some(e)) => ctx.err(
            Diagnostic::error(
                "the power law needs its reference `rate`",
                e.span,
                "no `rate`",
            )
            .with_help("add `rate = ..` (1 / time)"),
        ),
        _ => {}
    }
}

/// The Norton-Hoff rate sensitivity `m` is in (0, 1].
pub fn norton_hoff_m_in_range(n: &NortonHoff, ctx: &mut Ctx<'_>) {
    if let Some(m) = n.m.as_ref().filter(|m| !(m.value > 0.0 && m.value <= 1.0)) {
        ctx.err(
            Diagnostic::error(
                "the Norton-Hoff rate sensitivity m must be in (0, 1]",
                m.span,
                format!("m = {}", num(m.value)),
            )
            .with_help(
                "superplastic alloys have m of about 0.3 to 0.8; m = 1 is a Newtonian fluid",
            ),
        );
    }
}

/// One rate law per material: `norton_hoff` and `viscoplastic` exclude
/// each other, and Norton-Hoff is not available on Neo-Hookean elasticity.
pub fn one_rate_law(m: &Material, ctx: &mut Ctx<'_>) {
    // Johnson-Cook hardening carries its own rate factor
    let johnson_cook = m
        .plastic
        .as_ref()
        .and_then(|p| p.hardening.as_ref())
        .is_some_and(|h| matches!(h.value, Hardening::JohnsonCook { .. }));
    if johnson_cook {
        let other = m
            .viscoplastic
            .as_ref()
            .map(|v| v.span)
            .or(m.norton_hoff.as_ref().map(|n| n.span));
        if let Some(span) = other {
            ctx.err(
                Diagnostic::error(
                    "Johnson-Cook hardening has its own rate factor: a second rate law would \
                     count the rate twice",
                    span,
                    "second rate law",
                )
                .with_help("keep `hardening = johnson_cook { .. }` or this block, not both"),
            );
        }
    }
    let Some(n) = &m.norton_hoff else {
        return;
    };
    if m.viscoplastic.is_some() {
        ctx.err(
            Diagnostic::error(
                "`norton_hoff` and `viscoplastic` exclude each other",
                n.span,
                "second rate law",
            )
            .with_help("keep one rate law per material"),
        );
    }
    if m.neo_hookean.is_some() {
        ctx.err(
            Diagnostic::error(
                "Norton-Hoff on a Neo-Hookean material is not supported",
                n.span,
                "not supported",
            )
            .with_help("use `elastic { .. }` with `norton_hoff { .. }`"),
        );
    }
}

/// Perzyna viscoplasticity needs the static yield stress and hardening.
pub fn viscoplastic_needs_plastic(m: &Material, ctx: &mut Ctx<'_>) {
    if let (Some(v), None) = (&m.viscoplastic, &m.plastic) {
        ctx.err(
            Diagnostic::error(
                "`viscoplastic` needs a `plastic` block (the static yield stress and hardening)",
                v.span,
                "no `plastic` block",
            )
            .with_help("add e.g. `plastic { yield = 250  hardening = linear { H = 1000 } }`"),
        );
    }
}

/// `yield` is given (and positive) except with Swift hardening, where the
/// initial yield stress is `K eps0^n`.
pub fn yield_stress_fits_hardening(m: &Material, ctx: &mut Ctx<'_>) {
    let Some(p) = &m.plastic else { return };
    let own = match p.hardening.as_ref().map(|h| &h.value) {
        Some(Hardening::Swift { .. }) => Some(("Swift", "K eps0^n")),
        Some(Hardening::JohnsonCook { .. }) => Some(("Johnson-Cook", "A")),
        _ => None,
    };
    match (&p.yield_stress, own) {
        (Some(y), Some((law, initial))) => ctx.err(
            Diagnostic::error(
                format!("`yield` is not used with {law} hardening"),
                y.span,
                format!("the initial yield stress is {initial}"),
            )
            .with_help("remove `yield` (or use `linear` / `voce` hardening)"),
        ),
        (None, None) => ctx.err(
            Diagnostic::error(
                "missing `yield` in the `plastic` block",
                p.span,
                "no yield stress",
            )
            .with_help("add the initial yield stress, e.g. `yield = 250`"),
        ),
        _ => ctx.must_be_positive(&p.yield_stress, "the yield stress"),
    }
}

/// Hardening parameters: `H >= 0`; Swift `K, eps0 > 0`, `n` in [0, 1];
/// Voce `delta > 0`, `sigma_inf >= yield`.
pub fn hardening_in_range(m: &Material, ctx: &mut Ctx<'_>) {
    let Some(p) = &m.plastic else { return };
    let Some(h) = &p.hardening else { return };
    match &h.value {
        Hardening::Linear { modulus } => {
            if let Some(v) = modulus.as_ref().filter(|v| v.value < 0.0) {
                ctx.err(
                    Diagnostic::error("the hardening modulus H must be >= 0", v.span, "negative")
                        .with_help(
                            "softening is not supported: it makes the solution mesh dependent",
                        ),
                );
            }
        }
        Hardening::Swift { k, eps0, n } => {
            ctx.must_be_positive(k, "Swift K");
            ctx.must_be_positive(eps0, "Swift eps0");
            if let Some(v) = n.as_ref().filter(|v| !(0.0..=1.0).contains(&v.value)) {
                ctx.err(Diagnostic::error(
                    "Swift n must lie in [0, 1]",
                    v.span,
                    format!("n = {}", num(v.value)),
                ));
            }
        }
        Hardening::JohnsonCook { values } => {
            if let (Some(t_ref), Some(t_melt)) = (&values[6], &values[7]) {
                if t_melt.value <= t_ref.value {
                    ctx.err(Diagnostic::error(
                        "the Johnson-Cook T_melt must exceed T_ref",
                        t_melt.span,
                        format!(
                            "T_melt = {} <= T_ref = {}",
                            num(t_melt.value),
                            num(t_ref.value)
                        ),
                    ));
                }
            }
            if let Some(v) = values[2].as_ref().filter(|v| v.value <= 0.0) {
                ctx.err(Diagnostic::error(
                    "Johnson-Cook n must lie in (0, 1]",
                    v.span,
                    format!("n = {}", num(v.value)),
                ));
            }
        }
        Hardening::Voce { sigma_inf, delta } => {
            ctx.must_be_positive(delta, "Voce delta");
            if let (Some(si), Some(y)) = (sigma_inf, &p.yield_stress) {
                if si.value < y.value {
                    ctx.err(Diagnostic::error(
                        "Voce sigma_inf must be at least the yield stress",
                        si.span,
                        format!("sigma_inf = {} < yield = {}", num(si.value), num(y.value)),
                    ));
                }
            }
        }
    }
}

/// The elastic law of a material (`elastic` or `neo_hookean`).
fn elastic(m: &Material) -> Option<&crate::ast::Elastic> {
    m.elastic.as_ref().or(m.neo_hookean.as_ref())
}

/// `E > 0`.
pub fn young_is_positive(m: &Material, ctx: &mut Ctx<'_>) {
    if let Some(e) = elastic(m) {
        ctx.must_be_positive(&e.young, "Young's modulus E");
    }
}

/// `-1 < nu < 0.5`.
pub fn poisson_in_range(m: &Material, ctx: &mut Ctx<'_>) {
    let Some(nu) = elastic(m)
        .and_then(|e| e.poisson.as_ref())
        .filter(|nu| !(nu.value > -1.0 && nu.value < 0.5))
    else {
        return;
    };
    let help = if nu.value == 0.5 {
        "nu = 0.5 is incompressible, which a displacement formulation cannot represent; \
         use e.g. nu = 0.499 with `formulation = selective_reduced`"
    } else {
        "Poisson's ratio of an isotropic elastic material lies strictly between -1 and 0.5"
    };
    ctx.err(
        Diagnostic::error(
            "Poisson's ratio nu must lie in (-1, 0.5)",
            nu.span,
            format!("nu = {}", num(nu.value)),
        )
        .with_help(help),
    );
}

/// Warning for a material no body uses (unless a body names an unknown
/// material or none, which probably meant this one).
pub fn is_used(m: &Material, ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    let used = deck
        .bodies
        .iter()
        .any(|b| b.material.as_ref().is_some_and(|n| n.name == m.name.name));
    let dangling = deck.bodies.iter().any(|b| {
        b.material
            .as_ref()
            .is_some_and(|n| !deck.materials.iter().any(|m| m.name.name == n.name))
    });
    let unassigned = deck.bodies.iter().any(|b| b.material.is_none());
    if !used && !dangling && !unassigned && !deck.has_broken("body") {
        ctx.err(Diagnostic::warning(
            format!("material `{}` is not used by any body", m.name.name),
            m.name.span,
            "unused",
        ));
    }
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::{material_messages, messages_of};

    #[test]
    fn plastic_and_finite_strain_decks_validate() {
        let ok = [
            ("plane_strain", "elastic { E = 200e3 nu = 0.3 } plastic { yield = 250 hardening = linear { H = 1000 } }", "formulation = selective_reduced"),
            ("axisymmetric", "elastic { E = 200e3 nu = 0.3 } plastic { hardening = swift { K = 500 eps0 = 0.01 n = 0.2 } }", "kinematics = finite formulation = selective_reduced"),
            ("plane_strain", "elastic { E = 200e3 nu = 0.3 } plastic { yield = 200 hardening = voce { sigma_inf = 300 delta = 5 } } viscoplastic { eta = 10 }", "kinematics = finite formulation = selective_reduced"),
            ("plane_strain", "neo_hookean { E = 10 nu = 0.45 }", "kinematics = finite"),
            ("plane_strain", "elastic { E = 200e3 nu = 0.3 } plastic { yield = 250 }", "formulation = selective_reduced"),
        ];
        for (dim, m, b) in ok {
            assert!(
                material_messages(dim, m, b).is_empty(),
                "{m}: {:?}",
                material_messages(dim, m, b)
            );
        }
    }

    #[test]
    fn unsupported_or_inconsistent_plasticity_is_explained() {
        let el = "elastic { E = 200e3 nu = 0.3 }";
        let cases = [
            ("plane_stress", format!("{el} plastic {{ yield = 250 }}"), "", "plasticity in plane stress is not supported yet"),
            ("plane_stress", el.to_string(), "kinematics = finite", "finite strain in plane stress is not supported yet"),
            ("plane_strain", "neo_hookean { E = 10 nu = 0.4 }".to_string(), "", "material `m` is Neo-Hookean, a finite-strain law: body `b` needs `kinematics = finite`"),
            ("plane_strain", format!("{el} plastic {{ yield = 250 hardening = swift {{ K = 500 eps0 = 0.01 n = 0.2 }} }}"), "", "`yield` is not used with Swift hardening"),
            ("plane_strain", format!("{el} plastic {{ hardening = linear {{ H = 1 }} }}"), "", "missing `yield` in the `plastic` block"),
            ("plane_strain", format!("{el} viscoplastic {{ eta = 1 }}"), "", "`viscoplastic` needs a `plastic` block (the static yield stress and hardening)"),
            ("plane_strain", format!("{el} plastic {{ yield = 250 hardening = voce {{ sigma_inf = 100 delta = 1 }} }}"), "", "Voce sigma_inf must be at least the yield stress"),
            ("plane_strain", format!("{el} plastic {{ yield = 250 hardening = swift {{ K = 5 eps0 = 0.01 n = 2 }} }}"), "", "`yield` is not used with Swift hardening"),
        ];
        for (dim, m, b, expected) in cases {
            let got = material_messages(dim, &m, b);
            assert!(got.iter().any(|g| g == expected), "{m}: {got:?}");
        }
        let got = material_messages(
            "plane_strain",
            &format!("{el} plastic {{ hardening = swift {{ K = 5 eps0 = 0.01 n = 2 }} }}"),
            "formulation = selective_reduced",
        );
        assert_eq!(got, ["Swift n must lie in [0, 1]"]);
    }

    #[test]
    fn plastic_flow_on_fully_integrated_quads_is_a_locking_warning() {
        let plastic = "elastic { E = 200e3 nu = 0.3 } plastic { yield = 250 }";
        let warning = "fully integrated quad4 cells lock under plastic flow";
        for (dim, m, b, warns) in [
            ("plane_strain", plastic, "", true),
            ("axisymmetric", plastic, "formulation = full", true),
            (
                "plane_strain",
                plastic,
                "formulation = selective_reduced",
                false,
            ),
            ("plane_strain", "elastic { E = 200e3 nu = 0.3 }", "", false),
        ] {
            let got = material_messages(dim, m, b);
            assert_eq!(
                got.iter().any(|g| g == warning),
                warns,
                "{dim} {m} {b}: {got:?}"
            );
        }
    }

    #[test]
    fn out_of_range_material_values() {
        let text = "analysis { dimension = plane_strain }\nmaterial m { elastic { E = 0 nu = 0.5 } }\nbody b { mesh = rectangle { size = (1, 1) divisions = (1, 1) } material = m }\nstep { time = 0 .. 1 }";
        assert_eq!(
            messages_of(text),
            [
                "Young's modulus E must be positive",
                "Poisson's ratio nu must lie in (-1, 0.5)"
            ]
        );
    }
}
