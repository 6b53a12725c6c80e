//! `ctc check --explain`: the plan of a lowered scene in plain words.
//!
//! Only what the scene contains is described, followed by one line naming
//! what it leaves out ("leave out what a scene does not need").

use crate::ast::num;
use ctc_engine::mesh::CellKind;
use ctc_engine::model::{
    AnalysisKind, ContactMethod, Field, Formulation, HistoryRequest, Load, MaterialLaw, Model,
    PenaltyKind, TimeFunction, ToolGeometry, ToolSide,
};
use std::collections::BTreeSet;
use std::fmt::Write as _;

/// A time function in words, e.g. `ramp 0 -> -0.05 over t = 0 .. 1`.
pub fn time_function(f: &TimeFunction) -> String {
    match f {
        TimeFunction::Constant(v) => num(*v),
        TimeFunction::Ramp { t0, t1, v0, v1 } => format!(
            "ramp {} -> {} over t = {} .. {}",
            num(*v0),
            num(*v1),
            num(*t0),
            num(*t1)
        ),
        TimeFunction::Table(points) => {
            let pts: Vec<String> = points
                .iter()
                .map(|(t, v)| format!("({}, {})", num(*t), num(*v)))
                .collect();
            format!("table {}", pts.join(", "))
        }
    }
}

fn point(p: [f64; 2]) -> String {
    format!("({}, {})", num(p[0]), num(p[1]))
}

fn plural(n: usize, one: &str, many: &str) -> String {
    if n == 1 {
        format!("1 {one}")
    } else {
        format!("{n} {many}")
    }
}

fn component(c: usize) -> &'static str {
    if c == 0 {
        "x"
    } else {
        "y"
    }
}

fn is_zero(f: &TimeFunction) -> bool {
    matches!(f, TimeFunction::Constant(v) if *v == 0.0)
}

/// The plan of `model` in plain text (deterministic).
pub fn explain(model: &Model) -> String {
    let mut o = String::new();
    let axi = model.analysis.kind == AnalysisKind::Axisymmetric;
    // ------------------------------------------------------------ analysis
    match model.analysis.kind {
        AnalysisKind::PlaneStrain | AnalysisKind::PlaneStress => {
            let kind = if model.analysis.kind == AnalysisKind::PlaneStrain {
                "plane strain"
            } else {
                "plane stress"
            };
            let t = num(model.analysis.thickness);
            let _ = writeln!(o, "analysis: {kind}, thickness {t}");
            let _ = writeln!(
                o,
                "  forces, reactions and contact forces are totals over the thickness {t}"
            );
        }
        AnalysisKind::Axisymmetric => {
            let _ = writeln!(o, "analysis: axisymmetric (x = r >= 0, y = z)");
            let _ = writeln!(
                o,
                "  forces, reactions and contact forces are totals over the full 2*pi"
            );
        }
    }
    // ------------------------------------------------------------ bodies
    let _ = writeln!(o, "bodies: {}", model.bodies.len());
    for b in &model.bodies {
        let cells = &model.mesh.cells[b.cells.clone()];
        let tri = cells.iter().filter(|c| c.kind == CellKind::Tri3).count();
        let quad = cells.len() - tri;
        let mut kinds = Vec::new();
        if quad > 0 {
            kinds.push(format!("{quad} quad4"));
        }
        if tri > 0 {
            kinds.push(format!("{tri} tri3"));
        }
        let formulation = match (b.formulation, quad > 0) {
            (Formulation::SelectiveReduced, true) => {
                "selective reduced integration (quad4: 2x2 deviatoric, 1-point volumetric)"
            }
            (_, true) => "full integration (quad4: 2x2 Gauss)",
            (_, false) => "full integration (tri3: 1 point)",
        };
        let _ = writeln!(
            o,
            "  {}: {}, {} ({}), {formulation}",
            b.name,
            plural(b.nodes.len(), "node", "nodes"),
            plural(cells.len(), "cell", "cells"),
            kinds.join(" + ")
        );
        if let Some(m) = model.materials.get(b.material) {
            match &m.law {
                MaterialLaw::LinearElastic { young, poisson } => {
                    let _ = writeln!(
                        o,
                        "    material {}: small-strain linear elastic, E = {}, nu = {}",
                        m.name,
                        num(*young),
                        num(*poisson)
                    );
                }
            }
        }
    }
    // ------------------------------------------------------------ unknowns
    let dofs = 2 * model.mesh.nodes.len();
    let constrained: BTreeSet<(usize, usize)> = model
        .constraints
        .iter()
        .flat_map(|c| c.nodes.iter().map(move |&n| (n, c.component)))
        .collect();
    let _ = writeln!(
        o,
        "unknowns: {dofs} displacement dofs (2 per node): {} free, {} prescribed",
        dofs - constrained.len(),
        constrained.len()
    );
    // ------------------------------------------------------------ constraints
    if !model.constraints.is_empty() {
        let _ = writeln!(o, "prescribed displacements: {}", model.constraints.len());
        for c in &model.constraints {
            let _ = writeln!(
                o,
                "  {}: u{} = {} on {}",
                c.label,
                component(c.component),
                time_function(&c.value),
                plural(c.nodes.len(), "node", "nodes")
            );
        }
    }
    // ------------------------------------------------------------ loads
    if !model.loads.is_empty() {
        let _ = writeln!(o, "loads: {}", model.loads.len());
        for l in &model.loads {
            match l {
                Load::Pressure {
                    label,
                    edges,
                    value,
                } => {
                    let _ = writeln!(
                        o,
                        "  {label}: p = {} on {} (positive pushes into the body)",
                        time_function(value),
                        plural(edges.len(), "edge", "edges")
                    );
                }
                Load::NodalForce {
                    label,
                    nodes,
                    component: c,
                    value,
                } => {
                    let per = if axi {
                        "per node, total over 2*pi"
                    } else {
                        "per node"
                    };
                    let _ = writeln!(
                        o,
                        "  {label}: f{} = {} {per}, on {}",
                        component(*c),
                        time_function(value),
                        plural(nodes.len(), "node", "nodes")
                    );
                }
            }
        }
    }
    // ------------------------------------------------------------ tools
    if !model.tools.is_empty() {
        let _ = writeln!(o, "rigid tools: {}", model.tools.len());
        for t in &model.tools {
            let g = match &t.geometry {
                ToolGeometry::Plane { point: p, normal } => {
                    format!("plane through {}, normal {}", point(*p), point(*normal))
                }
                ToolGeometry::Polyline { points } => {
                    format!(
                        "polyline of {} from {} to {}",
                        plural(points.len().saturating_sub(1), "segment", "segments"),
                        points.first().map_or(String::new(), |p| point(*p)),
                        points.last().map_or(String::new(), |p| point(*p))
                    )
                }
                ToolGeometry::Arc {
                    center,
                    radius,
                    start_angle,
                    end_angle,
                } => format!(
                    "arc, center {}, radius {}, from {} to {} degrees",
                    point(*center),
                    num(*radius),
                    num(start_angle.to_degrees()),
                    num(end_angle.to_degrees())
                ),
                ToolGeometry::Circle {
                    center,
                    radius,
                    side,
                } => format!(
                    "circle, center {}, radius {}, body {}",
                    point(*center),
                    num(*radius),
                    match side {
                        ToolSide::Outside => "outside",
                        ToolSide::Inside => "inside",
                    }
                ),
                ToolGeometry::Nurbs {
                    degree,
                    control_points,
                    weights,
                    ..
                } => format!(
                    "{} of degree {degree}, {}",
                    if weights.iter().all(|w| *w == 1.0) {
                        "B-spline"
                    } else {
                        "NURBS"
                    },
                    plural(control_points.len(), "control point", "control points")
                ),
            };
            let _ = writeln!(o, "  {}: {g}", t.name);
            let m = &t.motion;
            if is_zero(&m.ux) && is_zero(&m.uy) && is_zero(&m.rotation) {
                let _ = writeln!(o, "    fixed");
            } else {
                let mut parts = Vec::new();
                for (name, f) in [("ux", &m.ux), ("uy", &m.uy)] {
                    if !is_zero(f) {
                        parts.push(format!("{name} = {}", time_function(f)));
                    }
                }
                if !is_zero(&m.rotation) {
                    parts.push(format!(
                        "rotation (radians) about {} = {}",
                        point(m.center),
                        time_function(&m.rotation)
                    ));
                }
                let _ = writeln!(o, "    moves: {}", parts.join(", "));
            }
        }
    }
    // ------------------------------------------------------------ contact
    if !model.contacts.is_empty() {
        let _ = writeln!(o, "contact pairs: {}", model.contacts.len());
        for c in &model.contacts {
            let method = match &c.method {
                ContactMethod::Penalty { kind, stiffness } => match kind {
                    PenaltyKind::Nodal => {
                        format!("penalty, nodal: {} force per unit gap", num(*stiffness))
                    }
                    PenaltyKind::Area => format!(
                        "penalty, area-weighted: {} pressure per unit gap",
                        num(*stiffness)
                    ),
                },
            };
            let prof = match c.prof {
                Some(p) => format!("search within prof = {}", num(p)),
                None => "search within an automatic prof".to_string(),
            };
            let _ = writeln!(
                o,
                "  {}: {method}; {} slave nodes on {}; {prof}",
                c.name,
                c.nodes.len(),
                plural(c.edges.len(), "edge", "edges")
            );
        }
    }
    // ------------------------------------------------------------ steps
    let _ = writeln!(o, "steps: {}", model.steps.len());
    for s in &model.steps {
        let dt = (s.t_end - s.t_start) / s.increments.max(1) as f64;
        let n = &s.newton;
        let _ = writeln!(
            o,
            "  {}: t = {} .. {}, {} (dt = {}), cutback down to {} dt",
            s.name,
            num(s.t_start),
            num(s.t_end),
            plural(s.increments, "increment", "increments"),
            num(dt),
            num(s.min_fraction)
        );
        let _ = writeln!(
            o,
            "    newton: tol {} (residual), {} (displacement), at most {} iterations, line search {}",
            num(n.tol),
            num(n.tol_displacement),
            n.max_iter,
            if n.line_search { "on" } else { "off" }
        );
    }
    // ------------------------------------------------------------ output
    let out = &model.output;
    let fields: Vec<&str> = out
        .fields
        .iter()
        .map(|f| match f {
            Field::Displacement => "displacement",
            Field::Stress => "stress",
            Field::Strain => "strain",
            Field::VonMises => "von_mises",
            Field::Reaction => "reaction",
            Field::Contact => "contact",
        })
        .collect();
    let _ = writeln!(
        o,
        "output: VTU every {} (and the last), fields {}",
        plural(out.every, "increment", "increments"),
        if fields.is_empty() {
            "none".to_string()
        } else {
            fields.join(", ")
        }
    );
    if !out.history.is_empty() {
        let labels: Vec<String> = out
            .history
            .iter()
            .map(|h| match h {
                HistoryRequest::Reaction { label, nodes }
                | HistoryRequest::Displacement { label, nodes } => {
                    format!("{label} over {}", plural(nodes.len(), "node", "nodes"))
                }
                HistoryRequest::ContactForce { label, .. } => label.clone(),
            })
            .collect();
        let _ = writeln!(o, "  history.csv: {}", labels.join("; "));
    }
    // ------------------------------------------------------------ left out
    let mut absent: Vec<&str> = Vec::new();
    if model.contacts.is_empty() {
        absent.push("contact search (no contact pairs)");
    }
    if model.tools.is_empty() {
        absent.push("rigid tools");
    }
    if model.loads.is_empty() {
        absent.push("external loads");
    }
    if model.constraints.is_empty() {
        absent.push("prescribed displacements");
    }
    absent.extend([
        "plasticity",
        "viscoplasticity",
        "friction",
        "thermal unknowns",
        "finite strain",
        "inertia",
    ]);
    let _ = writeln!(o, "not in this scene: {}", absent.join(", "));
    o
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_functions_in_words() {
        assert_eq!(time_function(&TimeFunction::Constant(-1.0)), "-1");
        assert_eq!(
            time_function(&TimeFunction::Ramp {
                t0: 0.0,
                t1: 1.0,
                v0: 0.0,
                v1: -0.05
            }),
            "ramp 0 -> -0.05 over t = 0 .. 1"
        );
        assert_eq!(
            time_function(&TimeFunction::Table(vec![(0.0, 0.0), (1.0, 2.0)])),
            "table (0, 0), (1, 2)"
        );
    }
}
