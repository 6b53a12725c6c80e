//! `material name { elastic { E = .. nu = .. } }`, or
//! `neo_hookean { E = .. nu = .. }` (or `{ mu = .. kappa = .. }`) instead of
//! `elastic`, optionally with
//! `plastic { yield = ..  hardening = linear { H = .. } | swift { K = ..
//! eps0 = ..  n = .. } | voce { sigma_inf = ..  delta = .. } }` and
//! `viscoplastic { eta = .. }` (Perzyna), and `thermal { .. }`
//! ([`super::thermal`]).

use super::fields::Fields;
use super::values::Diags;
use super::ItemParts;
use crate::ast::syntax::{Block, Value, ValueKind};
use crate::ast::{Elastic, Hardening, Material, NortonHoff, Plastic, Viscoplastic};
use crate::diagnostics::Diagnostic;
use crate::span::{Ident, Spanned};
use crate::suggest::did_you_mean;

/// Material blocks that parse but are not supported yet.
pub const RESERVED: [&str; 0] = [];

/// Hardening law names.
pub const HARDENINGS: [&str; 4] = ["linear", "swift", "voce", "johnson_cook"];

/// `E` and `nu` of an `elastic` or `neo_hookean` block.
fn elastic(b: &Block, what: &str, diags: &mut Diags) -> Elastic {
    let mut e = Fields::keyed(b, format!("`{what}` block"), &crate::tables::ELASTIC);
    let young = e.number("E", diags);
    let poisson = e.number("nu", diags);
    e.require(
        &young,
        "E",
        b.span,
        "add Young's modulus, e.g. `E = 210e3`",
        diags,
    );
    e.require(
        &poisson,
        "nu",
        b.span,
        "add Poisson's ratio, e.g. `nu = 0.3`",
        diags,
    );
    e.finish(diags);
    Elastic {
        young,
        poisson,
        span: b.span,
    }
}

/// `neo_hookean { E = ..  nu = .. }` or `neo_hookean { mu = ..  kappa = .. }`
/// (shear and bulk moduli, converted to `E = 9 kappa mu / (3 kappa + mu)`,
/// `nu = (3 kappa - 2 mu) / (2 (3 kappa + mu))`).
fn neo_hookean(b: &Block, diags: &mut Diags) -> Elastic {
    let uses_moduli = b
        .entries
        .iter()
        .any(|e| e.key.name == "mu" || e.key.name == "kappa");
    if !uses_moduli {
        return elastic(b, "neo_hookean", diags);
    }
    let mut e = Fields::keyed(b, "`neo_hookean` block", &crate::tables::NEO_HOOKEAN_MODULI);
    let mu = e.number("mu", diags);
    let kappa = e.number("kappa", diags);
    e.require(&mu, "mu", b.span, "add the shear modulus `mu = ..`", diags);
    e.require(
        &kappa,
        "kappa",
        b.span,
        "add the bulk modulus `kappa = ..`",
        diags,
    );
    e.finish(diags);
    let (mut young, mut poisson) = (None, None);
    if let (Some(m), Some(k)) = (&mu, &kappa) {
        if m.value > 0.0 && k.value > 0.0 {
            let (mv, kv) = (m.value, k.value);
            young = Some(Spanned::new(9.0 * kv * mv / (3.0 * kv + mv), m.span));
            poisson = Some(Spanned::new(
                (3.0 * kv - 2.0 * mv) / (2.0 * (3.0 * kv + mv)),
                k.span,
            ));
        } else {
            diags.push(Diagnostic::error(
                "the moduli mu and kappa must be positive",
                if m.value > 0.0 { k.span } else { m.span },
                "must be > 0",
            ));
        }
    }
    Elastic {
        young,
        poisson,
        span: b.span,
    }
}

fn hardening(v: &Value, diags: &mut Diags) -> Option<Spanned<Hardening>> {
    let (name, block): (&Ident, &Block) = match &v.kind {
        ValueKind::Ctor { name, block } => (name, block),
        other => {
            diags.push(Diagnostic::error(
                format!("expected a hardening law, found {}", other.describe()),
                v.span,
                "expected `linear { H = .. }`, `swift { K = ..  eps0 = ..  n = .. }` or \
                 `voce { sigma_inf = ..  delta = .. }`",
            ));
            return None;
        }
    };
    let law = match name.name.as_str() {
        "linear" => {
            let mut f = Fields::keyed(
                block,
                "`linear` hardening",
                &crate::tables::LINEAR_HARDENING,
            );
            let modulus = f.number("H", diags);
            f.require(
                &modulus,
                "H",
                name.span,
                "add the plastic modulus `H = ..`",
                diags,
            );
            f.finish(diags);
            Hardening::Linear { modulus }
        }
        "swift" => {
            let mut f = Fields::keyed(block, "`swift` hardening", &crate::tables::SWIFT_HARDENING);
            let k = f.number("K", diags);
            let eps0 = f.number("eps0", diags);
            let n = f.number("n", diags);
            f.require(
                &k,
                "K",
                name.span,
                "add `K = ..` (sigma_y = K (eps0 + ep)^n)",
                diags,
            );
            f.require(&eps0, "eps0", name.span, "add `eps0 = ..`", diags);
            f.require(&n, "n", name.span, "add `n = ..`", diags);
            f.finish(diags);
            Hardening::Swift { k, eps0, n }
        }
        "voce" => {
            let mut f = Fields::keyed(block, "`voce` hardening", &crate::tables::VOCE_HARDENING);
            let sigma_inf = f.number("sigma_inf", diags);
            let delta = f.number("delta", diags);
            f.require(
                &sigma_inf,
                "sigma_inf",
                name.span,
                "add the saturation stress `sigma_inf = ..`",
                diags,
            );
            f.require(
                &delta,
                "delta",
                name.span,
                "add the saturation rate `delta = ..`",
                diags,
            );
            f.finish(diags);
            Hardening::Voce { sigma_inf, delta }
        }
        "johnson_cook" => {
            let table = &crate::tables::JOHNSON_COOK_HARDENING;
            let mut f = Fields::keyed(block, "`johnson_cook` hardening", table);
            let values: [Option<Spanned<f64>>; 8] = std::array::from_fn(|i| {
                let key = table[i].name;
                let x = f.number(key, diags);
                f.require(&x, key, name.span, &format!("add `{key} = ..`"), diags);
                x
            });
            f.finish(diags);
            Hardening::JohnsonCook { values }
        }
        other => {
            diags.push(
                Diagnostic::error(
                    format!("unknown hardening law `{other}`"),
                    name.span,
                    "not a hardening law",
                )
                .with_help(did_you_mean(other, HARDENINGS).unwrap_or_else(|| {
                    "expected `linear`, `swift`, `voce` or `johnson_cook`".into()
                })),
            );
            return None;
        }
    };
    Some(Spanned::new(law, v.span))
}

/// Converts a `material` item.
pub fn parse(item: ItemParts, diags: &mut Diags) -> Option<Material> {
    let name = item.name?;
    let block = item.block?;
    let mut f = Fields::keyed(
        &block,
        format!("material `{}`", name.name),
        &crate::tables::MATERIAL,
    );
    let elastic_block = f
        .block("elastic", diags)
        .map(|b| elastic(b, "elastic", diags));
    let neo_hookean = f.block("neo_hookean", diags).map(|b| neo_hookean(b, diags));
    let plastic = f.block("plastic", diags).map(|b| {
        let mut p = Fields::keyed(b, "`plastic` block", &crate::tables::PLASTIC);
        let yield_stress = p.number("yield", diags);
        let hardening = p
            .value("hardening", diags)
            .and_then(|v| hardening(v, diags));
        p.finish(diags);
        Plastic {
            yield_stress,
            hardening,
            span: b.span,
        }
    });
    let viscoplastic = f.block("viscoplastic", diags).map(|b| {
        let mut p = Fields::keyed(b, "`viscoplastic` block", &crate::tables::VISCOPLASTIC);
        let eta = p.number("eta", diags);
        let rate = p.number("rate", diags);
        let exponent = p.number("exponent", diags);
        if rate.is_none() && exponent.is_none() {
            p.require(
                &eta,
                "eta",
                b.span,
                "add the Perzyna viscosity `eta = ..` (stress x time), or `rate = ..  \
                 exponent = ..` for the power law",
                diags,
            );
        }
        p.finish(diags);
        Viscoplastic {
            eta,
            rate,
            exponent,
            span: b.span,
        }
    });
    let norton_hoff = f.block("norton_hoff", diags).map(|b| {
        let mut p = Fields::keyed(b, "`norton_hoff` block", &crate::tables::NORTON_HOFF);
        let stress = p.number("stress", diags);
        let rate = p.number("rate", diags);
        let m = p.number("m", diags);
        for (found, key) in [(&stress, "stress"), (&rate, "rate"), (&m, "m")] {
            let help = crate::tables::NORTON_HOFF
                .iter()
                .find(|k| k.name == key)
                .and_then(|k| k.required)
                .unwrap_or("add it");
            p.require(found, key, b.span, help, diags);
        }
        p.finish(diags);
        NortonHoff {
            stress,
            rate,
            m,
            span: b.span,
        }
    });
    let density = f.number("density", diags);
    let thermal = f
        .block("thermal", diags)
        .map(|b| super::thermal::material_block(b, diags));
    let reserved: Vec<_> = f
        .take_all(&RESERVED)
        .into_iter()
        .map(|e| e.key.clone())
        .collect();
    if reserved.is_empty() && neo_hookean.is_none() {
        f.require(
            &elastic_block,
            "elastic",
            name.span,
            "add `elastic { E = ..  nu = .. }`",
            diags,
        );
    }
    f.finish(diags);
    Some(Material {
        name,
        elastic: elastic_block,
        neo_hookean,
        plastic,
        viscoplastic,
        norton_hoff,
        reserved,
        span: item.span,
        thermal,
        density,
    })
}

#[cfg(test)]
mod tests {
    use crate::ast::Hardening;
    use crate::parse::test_support::{parse_messages, parse_ok};

    #[test]
    fn elastic_material() {
        let deck = parse_ok("material steel { elastic { E = 210e3  nu = 0.3 } }");
        let m = &deck.materials[0];
        assert_eq!(m.name.name, "steel");
        let e = m.elastic.as_ref().unwrap();
        assert_eq!(e.young.as_ref().unwrap().value, 210e3);
        assert_eq!(e.poisson.as_ref().unwrap().value, 0.3);
        assert!(m.reserved.is_empty() && m.plastic.is_none());
    }

    #[test]
    fn plastic_material_with_each_hardening_law() {
        let deck = parse_ok(
            "material al { elastic { E = 70e3 nu = 0.33 }\n plastic { yield = 250 hardening = linear { H = 1000 } } }\n\
             material st { elastic { E = 200e3 nu = 0.3 }\n plastic { hardening = swift { K = 500 eps0 = 0.01 n = 0.2 } }\n viscoplastic { eta = 10 } }\n\
             material cu { elastic { E = 120e3 nu = 0.34 }\n plastic { yield = 100 hardening = voce { sigma_inf = 300 delta = 8 } } }",
        );
        let p = deck.materials[0].plastic.as_ref().unwrap();
        assert_eq!(p.yield_stress.as_ref().unwrap().value, 250.0);
        assert!(matches!(
            &p.hardening.as_ref().unwrap().value,
            Hardening::Linear { modulus: Some(h) } if h.value == 1000.0
        ));
        let m = &deck.materials[1];
        assert!(matches!(
            &m.plastic.as_ref().unwrap().hardening.as_ref().unwrap().value,
            Hardening::Swift { n: Some(n), .. } if n.value == 0.2
        ));
        assert_eq!(
            m.viscoplastic.as_ref().unwrap().eta.as_ref().unwrap().value,
            10.0
        );
        assert!(matches!(
            &deck.materials[2]
                .plastic
                .as_ref()
                .unwrap()
                .hardening
                .as_ref()
                .unwrap()
                .value,
            Hardening::Voce { .. }
        ));
    }

    #[test]
    fn johnson_cook_hardening_reads_its_eight_parameters() {
        let deck = parse_ok(
            "material cu { elastic { E = 124e3 nu = 0.34 }\n plastic { hardening = johnson_cook { \
             A = 90 B = 292 n = 0.31 C = 0.025 rate0 = 1 m = 1.09 T_ref = 298 T_melt = 1356 } } }",
        );
        let h = &deck.materials[0].plastic.as_ref().unwrap().hardening;
        let Hardening::JohnsonCook { values } = &h.as_ref().unwrap().value else {
            panic!("{h:?}")
        };
        assert_eq!(values[7].as_ref().unwrap().value, 1356.0);
        assert_eq!(
            parse_messages(
                "material cu { elastic { E = 1 nu = 0 } plastic { hardening = johnson_cook { \
                 A = 90 B = 292 n = 0.31 C = 0 rate0 = 1 m = 1 T_ref = 0 } } }"
            ),
            ["missing `T_melt` in the `johnson_cook` hardening"]
        );
    }

    #[test]
    fn neo_hookean_material_needs_no_elastic_block() {
        let deck = parse_ok("material rubber { neo_hookean { E = 10  nu = 0.45 } }");
        assert!(deck.materials[0].neo_hookean.is_some());
        assert!(deck.materials[0].elastic.is_none());
    }

    #[test]
    fn neo_hookean_from_shear_and_bulk_moduli() {
        let deck = parse_ok("material rubber { neo_hookean { mu = 3  kappa = 5 } }");
        let e = deck.materials[0].neo_hookean.as_ref().unwrap();
        let (young, nu) = (
            e.young.as_ref().unwrap().value,
            e.poisson.as_ref().unwrap().value,
        );
        // back to mu and kappa
        assert!((young / (2.0 * (1.0 + nu)) - 3.0).abs() < 1e-12);
        assert!((young / (3.0 * (1.0 - 2.0 * nu)) - 5.0).abs() < 1e-12);
        assert_eq!(
            parse_messages("material r { neo_hookean { mu = 3 } }"),
            ["missing `kappa` in the `neo_hookean` block"]
        );
    }

    #[test]
    fn unknown_hardening_law_gets_a_suggestion() {
        let m = parse_messages(
            "material a { elastic { E = 1 nu = 0.3 } plastic { yield = 1 hardening = swfit { K = 1 } } }",
        );
        assert_eq!(m, ["unknown hardening law `swfit`"]);
    }

    #[test]
    fn thermal_block_is_read() {
        let deck = parse_ok(
            "material al { elastic { E = 70e3 nu = 0.33 }\n thermal { conductivity = 1 } }",
        );
        assert!(deck.materials[0].thermal.is_some());
        assert!(deck.materials[0].reserved.is_empty());
    }

    #[test]
    fn missing_elastic_block() {
        assert_eq!(
            parse_messages("material steel { }"),
            ["missing `elastic` in the material `steel`"]
        );
    }
}
