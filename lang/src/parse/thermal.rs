//! Thermal constructs:
//! - `material m { .. thermal { conductivity = ..  capacity = ..  density = ..
//!   expansion = ..  reference = ..  taylor_quinney = ..  young = table(..)
//!   yield = table(..) } }`;
//! - `body b { .. thermal { initial = .. } }`;
//! - `contact a.s -> t { .. thermal { conductance = h | power { h0 = .. h1 = ..
//!   n = .. } | table((p, h), ..)  gap_conductivity = ..  gap_min = ..
//!   friction_split = ..  tool_temperature = .. } }`;
//! - items `temperature a.s { value = .. }`, `heat_flux a.s { q = .. }`,
//!   `convection a.s { h = ..  ambient = .. }`.
//!
//! Ranges are checked by validation ([`crate::validate::thermal`]).

use super::fields::Fields;
use super::values::{self, Diags};
use super::ItemParts;
use crate::ast::syntax::{Block, Value, ValueKind};
use crate::ast::thermal::{
    BodyThermal, Conductance, ContactThermal, MaterialThermal, ThermalLoad, ThermalLoadKind,
};
use crate::ast::TimeFn;
use crate::diagnostics::Diagnostic;
use crate::span::Spanned;

/// Keywords of the thermal load items.
pub const ITEMS: [&str; 3] = ["temperature", "heat_flux", "convection"];

/// A table of (x, y) points: `table((x, y), ..)` with increasing `x`, or a
/// plain number (a constant).
fn table(v: &Value, what: &str, diags: &mut Diags) -> Option<Spanned<Vec<(f64, f64)>>> {
    let f = values::time_fn(v, diags)?;
    let points = match &f.value {
        TimeFn::Number(y) | TimeFn::Constant(y) => vec![(0.0, *y)],
        TimeFn::Table(p) => p.iter().map(|s| s.value).collect(),
        TimeFn::Ramp { .. } => {
            diags.push(Diagnostic::error(
                format!("{what} must be a number or `table((x, y), ..)`"),
                v.span,
                "a ramp is a function of time",
            ));
            return None;
        }
    };
    Some(Spanned::new(points, v.span))
}

/// The `thermal` block of a material.
pub fn material_block(b: &Block, diags: &mut Diags) -> MaterialThermal {
    let mut f = Fields::keyed(
        b,
        "material `thermal` block",
        &crate::tables::MATERIAL_THERMAL,
    );
    let conductivity = f.number("conductivity", diags);
    let capacity = f.number("capacity", diags);
    let density = f.number("density", diags);
    let expansion = f.number("expansion", diags);
    let reference = f.number("reference", diags);
    let taylor_quinney = f.number("taylor_quinney", diags);
    let young = f
        .value("young", diags)
        .and_then(|v| table(v, "the `young` factor", diags));
    let yield_factor = f
        .value("yield", diags)
        .and_then(|v| table(v, "the `yield` factor", diags));
    f.require(
        &conductivity,
        "conductivity",
        b.span,
        "add the thermal conductivity, e.g. `conductivity = 50`",
        diags,
    );
    f.finish(diags);
    MaterialThermal {
        conductivity,
        capacity,
        density,
        expansion,
        reference,
        taylor_quinney,
        young,
        yield_factor,
        span: b.span,
    }
}

/// The `thermal` block of a body.
pub fn body_block(b: &Block, diags: &mut Diags) -> BodyThermal {
    let mut f = Fields::keyed(b, "body `thermal` block", &crate::tables::BODY_THERMAL);
    let initial = f.number("initial", diags);
    f.finish(diags);
    BodyThermal {
        initial,
        span: b.span,
    }
}

fn conductance(v: &Value, diags: &mut Diags) -> Option<Spanned<Conductance>> {
    let law = match &v.kind {
        ValueKind::Ctor { name, block } if name.name == "power" => {
            let mut f = Fields::keyed(
                block,
                "`power` conductance",
                &crate::tables::POWER_CONDUCTANCE,
            );
            let h0 = f.number("h0", diags);
            let h1 = f.number("h1", diags);
            let n = f.number("n", diags);
            f.finish(diags);
            Conductance::Power { h0, h1, n }
        }
        ValueKind::Number(_) => Conductance::Constant(values::number(v, diags)?),
        _ => {
            let t = table(v, "the conductance table", diags);
            let Some(t) = t else {
                diags.push(
                    Diagnostic::error(
                        "expected a conductance",
                        v.span,
                        "expected `h`, `power { h0 = ..  h1 = ..  n = .. }` or \
                         `table((p, h), ..)`",
                    )
                    .with_help("e.g. `conductance = power { h0 = 1e3  h1 = 10  n = 1 }`"),
                );
                return None;
            };
            Conductance::Table(t.value)
        }
    };
    Some(Spanned::new(law, v.span))
}

/// The `thermal` block of a contact.
pub fn contact_block(b: &Block, diags: &mut Diags) -> ContactThermal {
    let mut f = Fields::keyed(
        b,
        "contact `thermal` block",
        &crate::tables::CONTACT_THERMAL,
    );
    let conductance = f
        .value("conductance", diags)
        .and_then(|v| conductance(v, diags));
    let gap_conductivity = f.number("gap_conductivity", diags);
    let gap_min = f.number("gap_min", diags);
    let friction_split = f.number("friction_split", diags);
    let tool_temperature = f.time_fn("tool_temperature", diags);
    f.require(
        &conductance,
        "conductance",
        b.span,
        "add e.g. `conductance = power { h0 = 1e3  h1 = 10  n = 1 }`",
        diags,
    );
    f.finish(diags);
    ContactThermal {
        conductance,
        gap_conductivity,
        gap_min,
        friction_split,
        tool_temperature,
        span: b.span,
    }
}

/// A `temperature`, `heat_flux` or `convection` item.
pub fn item(parts: ItemParts, diags: &mut Diags) -> Option<ThermalLoad> {
    let kind = match parts.keyword_text.as_str() {
        "temperature" => ThermalLoadKind::Temperature,
        "heat_flux" => ThermalLoadKind::HeatFlux,
        _ => ThermalLoadKind::Convection,
    };
    let word = parts.keyword_text.clone();
    let Some(target) = parts.target.as_ref() else {
        diags.push(Diagnostic::error(
            format!("`{word}` needs a set, e.g. `{word} bar.left {{ .. }}`"),
            parts.keyword,
            "no set",
        ));
        return None;
    };
    let target = values::set_ref(target, diags)?;
    let Some(block) = parts.block.as_ref() else {
        diags.push(Diagnostic::error(
            format!("`{word}` needs a block"),
            parts.span,
            "no block",
        ));
        return None;
    };
    let (value, film) = match kind {
        ThermalLoadKind::Temperature => {
            let mut f = Fields::new(block, "`temperature` item", &["value"]);
            let v = f.time_fn("value", diags);
            f.require(&v, "value", block.span, "add `value = 100`", diags);
            f.finish(diags);
            (v, None)
        }
        ThermalLoadKind::HeatFlux => {
            let mut f = Fields::new(block, "`heat_flux` item", &["q"]);
            let v = f.time_fn("q", diags);
            f.require(
                &v,
                "q",
                block.span,
                "add the flux into the body `q = 1e3`",
                diags,
            );
            f.finish(diags);
            (v, None)
        }
        ThermalLoadKind::Convection => {
            let mut f = Fields::new(block, "`convection` item", &["h", "ambient"]);
            let h = f.number("h", diags);
            let v = f.time_fn("ambient", diags);
            f.require(
                &h,
                "h",
                block.span,
                "add the film coefficient `h = 10`",
                diags,
            );
            f.require(
                &v,
                "ambient",
                block.span,
                "add the ambient temperature `ambient = 20`",
                diags,
            );
            f.finish(diags);
            (v, h)
        }
    };
    Some(ThermalLoad {
        kind,
        target,
        value,
        film,
        span: parts.span,
    })
}

#[cfg(test)]
mod tests {
    use crate::ast::thermal::{Conductance, ThermalLoadKind};
    use crate::parse::test_support::{parse_messages, parse_ok};

    #[test]
    fn thermal_blocks_and_items_parse() {
        let deck = parse_ok(
            "material st { elastic { E = 1 nu = 0.3 }\n thermal { conductivity = 50 capacity = 460 density = 7.8e-9 expansion = 1.2e-5 young = table((20, 1), (600, 0.5)) } }\n\
             contact b.bottom -> floor { method = penalty { stiffness = 1 }\n thermal { conductance = power { h0 = 1 h1 = 2 n = 0.5 } tool_temperature = 20 } }\n\
             temperature b.left { value = ramp(0, 100) }\nheat_flux b.right { q = 5 }\nconvection b.top { h = 10 ambient = 20 }",
        );
        let t = deck.materials[0].thermal.as_ref().unwrap();
        assert_eq!(t.conductivity.as_ref().unwrap().value, 50.0);
        assert_eq!(
            t.young.as_ref().unwrap().value,
            vec![(20.0, 1.0), (600.0, 0.5)]
        );
        let c = deck.contacts[0].thermal.as_ref().unwrap();
        let Conductance::Power { h0, h1, n } = &c.conductance.as_ref().unwrap().value else {
            panic!()
        };
        let v = |x: &Option<crate::span::Spanned<f64>>| x.as_ref().map(|x| x.value);
        assert_eq!((v(h0), v(h1), v(n)), (Some(1.0), Some(2.0), Some(0.5)));
        let kinds: Vec<_> = deck.thermal_loads.iter().map(|l| l.kind).collect();
        assert_eq!(
            kinds,
            [
                ThermalLoadKind::Temperature,
                ThermalLoadKind::HeatFlux,
                ThermalLoadKind::Convection
            ]
        );
    }

    #[test]
    fn thermal_mistakes_are_reported() {
        assert_eq!(
            parse_messages(
                "material st { elastic { E = 1 nu = 0.3 } thermal { conductivity = -1 capacty = 1 } }"
            ),
            ["unknown key `capacty` in the material `thermal` block"]
        );
        assert_eq!(
            parse_messages("convection b.top { ambient = 20 }"),
            ["missing `h` in the `convection` item"]
        );
    }
}
