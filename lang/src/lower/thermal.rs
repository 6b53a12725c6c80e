//! Lowering the thermal constructs into `ctc_engine::model::thermal::ThermalScene`.
//!
//! A deck without any `thermal` block and without thermal load items
//! lowers to `Model::thermal = None`: no temperature unknowns at all.
//! Checks that need the whole scene are made here: a thermal body, load or
//! contact needs a material with a `thermal` block; a thermal contact with a
//! rigid tool needs the tool's temperature.

use super::sets::Resolved;
use super::time_function;
use crate::ast::thermal::{self as ast, ThermalLoadKind};
use crate::ast::{Deck, SetRef};
use crate::diagnostics::Diagnostic;
use crate::validate::Need;
use ctc_engine::mesh::Facet;
use ctc_engine::model::thermal::{
    Conductance, ContactThermal, Convection, CouplingScheme, HeatFlux, MaterialThermal,
    PrescribedTemperature, ThermalScene,
};
use ctc_engine::model::{Body, ContactPair, Material};
use std::collections::BTreeMap;
use std::ops::Range;

/// Default Taylor-Quinney factor.
pub const DEFAULT_TAYLOR_QUINNEY: f64 = 0.9;
/// Default share of the frictional heat going to the slave side.
pub const DEFAULT_FRICTION_SPLIT: f64 = 0.5;
/// Default smallest gap in the gap conductance `k_gap / g`.
pub const DEFAULT_GAP_MIN: f64 = 1e-9;

/// Whether the deck uses heat at all.
pub fn has_thermal(deck: &Deck) -> bool {
    deck.materials.iter().any(|m| m.thermal.is_some())
        || deck.bodies.iter().any(|b| b.thermal.is_some())
        || deck.contacts.iter().any(|c| c.thermal.is_some())
        || !deck.thermal_loads.is_empty()
}

/// The thermal scene of `deck` (`None` when it has no thermal construct),
/// planar or solid: `resolve` resolves a set in the model's mesh (boundary
/// edges of a planar mesh, faces of a solid one).
#[allow(clippy::too_many_arguments)]
pub fn lower(
    deck: &Deck,
    mut resolve: impl FnMut(&SetRef, Need, &str) -> Result<Resolved, Diagnostic>,
    body_nodes: &BTreeMap<String, Range<usize>>,
    bodies: &[Body],
    materials: &[Material],
    contacts: &[ContactPair],
    window: (f64, f64),
    diags: &mut Vec<Diagnostic>,
) -> Option<ThermalScene> {
    if !has_thermal(deck) {
        return None;
    }
    let tf = |f: &crate::span::Spanned<crate::ast::TimeFn>| time_function(&f.value, window);
    let materials_out: Vec<Option<MaterialThermal>> = materials
        .iter()
        .map(|m| {
            let def = deck.materials.iter().find(|d| d.name.name == m.name)?;
            let t = def.thermal.as_ref()?;
            let v =
                |x: &Option<crate::span::Spanned<f64>>, d: f64| x.as_ref().map_or(d, |x| x.value);
            Some(MaterialThermal {
                conductivity: v(&t.conductivity, 1.0),
                capacity: v(&t.capacity, 0.0),
                density: v(&t.density, 0.0),
                expansion: v(&t.expansion, 0.0),
                reference: v(&t.reference, 0.0),
                taylor_quinney: v(&t.taylor_quinney, DEFAULT_TAYLOR_QUINNEY),
                young_factor: t.young.as_ref().map(|s| s.value.clone()),
                yield_factor: t.yield_factor.as_ref().map(|s| s.value.clone()),
            })
        })
        .collect();
    let thermal_body = |name: &str| {
        bodies
            .iter()
            .find(|b| b.name == name)
            .is_some_and(|b| materials_out[b.material].is_some())
    };
    let mut initial = vec![0.0; bodies.len()];
    for b in &deck.bodies {
        let Some(t) = &b.thermal else { continue };
        let Some(i) = bodies.iter().position(|x| x.name == b.name.name) else {
            continue;
        };
        if !thermal_body(&b.name.name) {
            diags.push(
                Diagnostic::error(
                    format!(
                        "body `{}` has a `thermal` block but its material has none",
                        b.name.name
                    ),
                    t.span,
                    "no thermal properties",
                )
                .with_help("add `thermal { conductivity = .. }` to the body's material"),
            );
        }
        initial[i] = t.initial.as_ref().map_or(0.0, |x| x.value);
    }
    let mut scene = ThermalScene {
        materials: materials_out.clone(),
        initial,
        temperatures: Vec::new(),
        fluxes: Vec::new(),
        convection: Vec::new(),
        contacts: vec![None; contacts.len()],
        scheme: CouplingScheme::Staggered,
    };
    for l in &deck.thermal_loads {
        let word = match l.kind {
            ThermalLoadKind::Temperature => "temperature",
            ThermalLoadKind::HeatFlux => "heat_flux",
            ThermalLoadKind::Convection => "convection",
        };
        if body_nodes.contains_key(&l.target.body.name) && !thermal_body(&l.target.body.name) {
            diags.push(
                Diagnostic::error(
                    format!(
                        "`{word}` on body `{}`, whose material has no `thermal` block",
                        l.target.body.name
                    ),
                    l.target.span,
                    "no temperature here",
                )
                .with_help("add `thermal { conductivity = .. }` to the body's material"),
            );
            continue;
        }
        let need = match l.kind {
            ThermalLoadKind::Temperature => Need::Nodes,
            _ => Need::Edges,
        };
        let r = match resolve(&l.target, need, word) {
            Ok(r) => r,
            Err(d) => {
                diags.push(d);
                continue;
            }
        };
        let Some(value) = l.value.as_ref().map(tf) else {
            continue;
        };
        let label = format!("{word} {}", l.target);
        let facets = || -> Vec<Facet> {
            match (&r.faces, &r.edges) {
                (Some(f), _) => f.clone(),
                (None, Some(e)) => e.iter().map(|e| Facet::new(e)).collect(),
                (None, None) => Vec::new(),
            }
        };
        match l.kind {
            ThermalLoadKind::Temperature => scene.temperatures.push(PrescribedTemperature {
                label,
                nodes: r.nodes,
                value,
            }),
            ThermalLoadKind::HeatFlux => scene.fluxes.push(HeatFlux {
                facets: facets(),
                label,
                value,
            }),
            ThermalLoadKind::Convection => scene.convection.push(Convection {
                facets: facets(),
                label,
                film: l.film.as_ref().map_or(0.0, |h| h.value),
                ambient: value,
            }),
        }
    }
    for c in &deck.contacts {
        let Some(t) = &c.thermal else { continue };
        let name = format!("{} -> {}", c.target, c.tool.name);
        let Some(p) = contacts.iter().position(|x| x.name == name) else {
            continue;
        };
        let pair = &contacts[p];
        if !thermal_body(&bodies[pair.body].name) {
            diags.push(
                Diagnostic::error(
                    format!(
                        "contact `{name}` has a `thermal` block but body `{}` has no thermal \
                         material",
                        bodies[pair.body].name
                    ),
                    t.span,
                    "no temperature on the slave side",
                )
                .with_help("add `thermal { conductivity = .. }` to the body's material"),
            );
            continue;
        }
        let tool_temperature = t.tool_temperature.as_ref().map(tf);
        if pair.master.tool().is_some() && tool_temperature.is_none() {
            diags.push(
                Diagnostic::error(
                    format!("thermal contact `{name}` with a rigid tool needs its temperature"),
                    t.span,
                    "missing `tool_temperature`",
                )
                .with_help("add e.g. `tool_temperature = 20` (a number or a time function)"),
            );
            continue;
        }
        let Some(law) = &t.conductance else { continue };
        scene.contacts[p] = Some(ContactThermal {
            conductance: match &law.value {
                ast::Conductance::Constant(h) => Conductance::Power {
                    h0: h.value,
                    h1: 0.0,
                    n: 1.0,
                },
                ast::Conductance::Power { h0, h1, n } => {
                    let v = |x: &Option<crate::span::Spanned<f64>>, d: f64| {
                        x.as_ref().map_or(d, |x| x.value)
                    };
                    Conductance::Power {
                        h0: v(h0, 0.0),
                        h1: v(h1, 0.0),
                        n: v(n, 1.0),
                    }
                }
                ast::Conductance::Table(points) => Conductance::Table(points.clone()),
            },
            gap_conductivity: t.gap_conductivity.as_ref().map_or(0.0, |x| x.value),
            gap_min: t.gap_min.as_ref().map_or(DEFAULT_GAP_MIN, |x| x.value),
            friction_split: t
                .friction_split
                .as_ref()
                .map_or(DEFAULT_FRICTION_SPLIT, |x| x.value),
            tool_temperature,
        });
    }
    Some(scene)
}

#[cfg(test)]
mod tests {
    use ctc_engine::model::AnyModel;

    #[test]
    fn a_3d_deck_lowers_heat_flux_and_convection_on_faces() {
        let text = "analysis { dimension = 3d }\n\
            material m { elastic { E = 1 nu = 0.3 } thermal { conductivity = 2 expansion = 1e-5 } }\n\
            body b { mesh = box { size = (1, 1, 1) divisions = (2, 2, 2) } material = m thermal { initial = 7 } }\n\
            tool floor = plane { point = (0, 0, 0) normal = (0, 0, 1) }\n\
            contact b.zmin -> floor { method = penalty { stiffness = 1 } thermal { conductance = 3 tool_temperature = 20 } }\n\
            fix b.xmin { ux uy uz }\n\
            temperature b.xmin { value = 100 }\n\
            heat_flux b.xmax { q = 5 }\n\
            convection b.ymax + b.zmax { h = 10 ambient = 20 }\n\
            step s { time = 0 .. 1 }\n";
        let src = crate::Source::new("t.ctc", text);
        let model = match crate::compile_any(&src) {
            Ok(AnyModel::D3(m)) => m,
            Ok(AnyModel::D2(_)) => panic!("a 3d deck lowered to 2d"),
            Err(d) => panic!("{}", d.render(&src)),
        };
        let t = model.thermal.expect("a thermal scene");
        assert_eq!(t.initial, vec![7.0]);
        assert_eq!(t.temperatures[0].nodes.len(), 9);
        // 2 x 2 quad faces on x = 1; 4 + 4 on y = 1 and z = 1
        assert_eq!(t.fluxes[0].facets.len(), 4);
        assert!(t.fluxes[0].facets.iter().all(|f| f.nodes().len() == 4));
        assert_eq!(t.convection[0].facets.len(), 8);
        let c = t.contacts[0].as_ref().expect("a thermal pair");
        assert!(c.tool_temperature.is_some());
        // `ctc check --explain` describes the heat part of a 3d scene
        let model = match crate::compile_any(&src) {
            Ok(AnyModel::D3(m)) => m,
            _ => unreachable!(),
        };
        let text = crate::explain::explain_solid(&model);
        for line in [
            "heat: conduction on 1 thermal material(s), 1 prescribed temperature(s), 1 flux(es), 1 convection(s), 1 thermal contact pair(s)",
            "temperature b.xmin: T = 100 on 9 nodes",
            "heat_flux b.xmax: q = 5 into the body on 4 faces",
            "convection b.ymax + b.zmax: q = h (T_ambient - T), h = 10, T_ambient = 20 on 8 faces",
            "thermal contact b.zmin -> floor",
            "tool at T = 20",
        ] {
            assert!(text.contains(line), "{line}\n{text}");
        }
        assert!(!text.contains("thermal unknowns"), "{text}");
    }
}
