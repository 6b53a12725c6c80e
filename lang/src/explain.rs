//! `ctc check --explain`: the plan of a lowered scene in plain words.
//!
//! Only what the scene contains is described, followed by one line naming
//! what it leaves out ("leave out what a scene does not need").

use crate::ast::num;
use ctc_engine::mesh::CellKind;
use ctc_engine::model::{
    AnalysisKind, ContactMethod, Field, Formulation, Hardening, HistoryRequest, Kinematics,
    LagrangeFormulation, Load, MaterialLaw, Model, MultiplierUpdate, PenaltyKind, TimeFunction,
    ToolGeometry, ToolSide, Viscosity,
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
        AnalysisKind::Solid => {
            let _ = writeln!(o, "analysis: 3d solid (x, y, z)");
        }
    }
    // ------------------------------------------------------------ bodies
    let _ = writeln!(o, "bodies: {}", model.bodies.len());
    for b in &model.bodies {
        // cell counts by kind, in the order of `CellKind`
        let mut counts: Vec<(CellKind, usize)> = Vec::new();
        for c in b.cells.clone() {
            let k = model.mesh.cells.kind(c);
            match counts.iter_mut().find(|(q, _)| *q == k) {
                Some(e) => e.1 += 1,
                None => counts.push((k, 1)),
            }
        }
        counts.sort_by_key(|&(k, _)| (k != CellKind::Quad4, k as usize));
        let kinds: Vec<String> = counts
            .iter()
            .map(|(k, n)| format!("{n} {}", k.name()))
            .collect();
        let selective = b.formulation == Formulation::SelectiveReduced
            && counts.iter().any(|(k, _)| *k == CellKind::Quad4);
        let rules: Vec<&str> = counts
            .iter()
            .map(|&(k, _)| match k {
                CellKind::Quad4 if selective => {
                    "selective reduced integration (quad4: 2x2 deviatoric, 1-point volumetric)"
                }
                CellKind::Quad4 => "full integration (quad4: 2x2 Gauss)",
                CellKind::Tri3 => "full integration (tri3: 1 point)",
                CellKind::Tri6 => "full integration (tri6: 3 points)",
                CellKind::Quad8 => "full integration (quad8: 3x3 Gauss)",
                CellKind::Quad8R => "reduced integration (quad8R: 2x2 Gauss)",
                CellKind::Quad9 => "full integration (quad9: 3x3 Gauss)",
                _ => "solid cells",
            })
            .collect();
        let formulation = rules.join(" + ");
        let _ = writeln!(
            o,
            "  {}: {}, {} ({}), {formulation}",
            b.name,
            plural(b.nodes.len(), "node", "nodes"),
            plural(b.cells.len(), "cell", "cells"),
            kinds.join(" + ")
        );
        if let Some(m) = model.materials.get(b.material) {
            let _ = writeln!(
                o,
                "    material {}: {}",
                m.name,
                material_law(&m.law, b.kinematics)
            );
            let _ = writeln!(o, "    kinematics: {}", kinematics(b.kinematics));
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
                Load::Gravity {
                    label,
                    component: c,
                    value,
                } => {
                    let _ = writeln!(
                        o,
                        "  {label}: g{} = {} on every body with a density and every point \
                         mass (consistent nodal forces)",
                        component(*c),
                        time_function(value)
                    );
                }
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
                Load::FacetPressure {
                    label,
                    facets,
                    value,
                } => {
                    let _ = writeln!(
                        o,
                        "  {label}: p = {} on {} (positive pushes into the body)",
                        time_function(value),
                        plural(facets.len(), "3-node edge", "3-node edges")
                    );
                }
                Load::FollowerPressure {
                    label,
                    facets,
                    value,
                    control,
                } => {
                    let _ = writeln!(
                        o,
                        "  {label}: p = {} on {} of the deformed surface (follower: turns with \
                         it, with its load stiffness; positive pushes into the body){}",
                        time_function(value),
                        plural(facets.len(), "edge", "edges"),
                        controller(control)
                    );
                }
                Load::FacetTraction {
                    label,
                    facets,
                    component: c,
                    value,
                } => {
                    let per = if axi {
                        "per unit reference area, total over 2*pi"
                    } else {
                        "per unit reference area"
                    };
                    let _ = writeln!(
                        o,
                        "  {label}: t{} = {} {per} (dead load), on {}",
                        component(*c),
                        time_function(value),
                        plural(facets.len(), "edge", "edges")
                    );
                }
                Load::RigidMoment { label, value, .. } => {
                    let _ = writeln!(o, "  {label}: M = {}", time_function(value));
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
            let _ = writeln!(
                o,
                "    free side (where bodies may be): {}",
                ctc_engine::solve::health::free_side_rule(&t.geometry)
            );
            if !matches!(t.geometry, ToolGeometry::Circle { .. }) {
                // (a circle's side is stated by the rule above)
                let _ = writeln!(o, "    {}", free_side_here(t, &model.mesh.nodes));
            }
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
            if let Some(f) = &t.free_rotation {
                let _ = writeln!(
                    o,
                    "    turns freely about {} (its angle is an unknown, pilot node {}): the \
                     contact moment balances the applied moment {}",
                    point(m.center),
                    f.node,
                    time_function(&f.moment)
                );
            }
        }
    }
    // ------------------------------------------------------------ contact
    if !model.contacts.is_empty() {
        let _ = writeln!(o, "contact pairs: {}", model.contacts.len());
        for c in &model.contacts {
            let method = method_plan(c);
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
            if let Some(f) = &c.friction {
                let _ = writeln!(
                    o,
                    "    {}",
                    friction_plan(f, &c.method, c.master.tool().is_some())
                );
            }
            if let Some(line) = crate::explain_surface::describe(model, c) {
                let _ = writeln!(o, "    {line}");
            }
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
        if !n.predictor {
            let _ = writeln!(
                o,
                "    predictor: off (each increment starts from the converged state)"
            );
        }
        if let Some(c) = n.stabilize {
            let _ = writeln!(
                o,
                "    stabilize: springs of {} x the mean stiffness diagonal on the increment \
                 displacement of the bodies held only by contact, ramped to 0 at t = {}",
                num(c),
                num(s.t_end)
            );
        }
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
            Field::Velocity => "velocity",
            Field::Acceleration => "acceleration",
        })
        .collect();
    let _ = writeln!(
        o,
        "output: VTU{} every {} (and the last), fields {}",
        if out.format == ctc_engine::model::VtuFormat::Ascii {
            " (ascii)"
        } else {
            ""
        },
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
                | HistoryRequest::Displacement { label, nodes }
                | HistoryRequest::Roughness { label, nodes, .. } => {
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
    let law_present = |f: &dyn Fn(&MaterialLaw) -> bool| {
        model
            .bodies
            .iter()
            .filter_map(|b| model.materials.get(b.material))
            .any(|m| f(&m.law))
    };
    if !law_present(&|l| matches!(l, MaterialLaw::ElastoPlastic { .. })) {
        absent.push("plasticity");
    }
    if !law_present(&|l| {
        matches!(
            l,
            MaterialLaw::ElastoPlastic {
                viscosity: Some(_),
                ..
            }
        )
    }) {
        absent.push("viscoplasticity");
    }
    if model.contacts.iter().all(|c| c.friction.is_none()) {
        absent.push("friction");
    }
    match &model.thermal {
        None => absent.push("thermal unknowns"),
        Some(t) => {
            let _ = writeln!(o, "{}", heat_line(t));
        }
    }
    if !model
        .bodies
        .iter()
        .any(|b| b.kinematics == Kinematics::Finite)
    {
        absent.push("finite strain");
    }
    absent.push("inertia");
    let _ = writeln!(o, "not in this scene: {}", absent.join(", "));
    o
}

/// Where the free side of `tool` is at t = 0, concretely: the walk's
/// middle point and the normal there pointing into free space (the
/// geometry written to `tool_<k>_NNNN.vtu`, free side on the left).
fn free_side_here(tool: &ctc_engine::model::RigidTool, nodes: &[[f64; 2]]) -> String {
    let extent = ctc_engine::output::tool_vtu::extent(nodes, &vec![[0.0; 2]; nodes.len()]);
    let pts = ctc_engine::output::tool_vtu::current_points(tool, 0.0, extent);
    if pts.len() < 2 {
        return "free side at t = 0: undefined (empty geometry)".into();
    }
    let k = (pts.len() - 1) / 2;
    let (a, b) = (pts[k], pts[k + 1]);
    let d = [b[0] - a[0], b[1] - a[1]];
    let l = d[0].hypot(d[1]);
    if l.is_nan() || l <= 0.0 {
        return "free side at t = 0: undefined (zero-length piece)".into();
    }
    let n = [-d[1] / l, d[0] / l];
    let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
    let word = if n[1] >= n[0].abs() {
        "+y (above)"
    } else if -n[1] >= n[0].abs() {
        "-y (below)"
    } else if n[0] > 0.0 {
        "+x (to the right)"
    } else {
        "-x (to the left)"
    };
    // four significant digits: a place and a direction, not data
    let r4 = |v: f64| {
        if v.abs() < 1e-12 {
            return 0.0;
        }
        let e = 10f64.powi(3 - v.abs().log10().floor() as i32);
        (v * e).round() / e
    };
    format!(
        "free side at t = 0: at {} the normal into free space is {} ({word}); a slave \
         node on the other side starts inside the tool",
        point([r4(mid[0]), r4(mid[1])]),
        point([r4(n[0]), r4(n[1])])
    )
}

/// A pair's friction law in words.
fn friction_plan(f: &ctc_engine::model::Friction, method: &ContactMethod, tool: bool) -> String {
    let how = match method {
        ContactMethod::Lagrange { .. } => {
            "tangential Lagrange multipliers, stick/slip status loop".to_string()
        }
        _ => {
            let shift = if matches!(method, ContactMethod::AugmentedLagrange { .. }) {
                " plus a tangential multiplier shift (Uzawa)"
            } else {
                ""
            };
            match f.stiffness {
                Some(s) => format!("penalty-regularized, alpha_T = {}{shift}", num(s)),
                None => format!("penalty-regularized, alpha_T = alpha_N / 10{shift}"),
            }
        }
    };
    format!(
        "friction: Coulomb mu = {} ({how}); first impact: {}{}",
        num(f.mu),
        match f.first_impact {
            ctc_engine::model::FirstImpact::Intersect =>
                if tool {
                    "stick point where the node met the tool (its straight path from the last \
                     converged increment, in the tool's frame), friction from there on"
                } else {
                    "stick point where the node met the master segment (node and segment ends \
                     moving at constant velocity from the last converged increment; a node \
                     touching at the start sticks where it was), friction from there on"
                },
            ctc_engine::model::FirstImpact::Frictionless => "frictionless in that increment",
        },
        if f.cut_at_impact {
            "; increments cut at the first impact"
        } else {
            ""
        }
    )
}

/// A body's kinematics in words.
fn kinematics(k: Kinematics) -> &'static str {
    match k {
        Kinematics::Small => "small strain (linear kinematics)",
        Kinematics::Finite => {
            "finite strain (total Lagrangian, deformation gradient F, exact tangent incl. \
             geometric stiffness; selective_reduced quad4 = F-bar)"
        }
    }
}

/// A material law in words.
fn material_law(law: &MaterialLaw, k: Kinematics) -> String {
    match law {
        MaterialLaw::LinearElastic { young, poisson } => match k {
            Kinematics::Small => format!(
                "small-strain linear elastic, E = {}, nu = {}",
                num(*young),
                num(*poisson)
            ),
            Kinematics::Finite => format!(
                "Hencky (logarithmic strain) elastic, E = {}, nu = {}",
                num(*young),
                num(*poisson)
            ),
        },
        MaterialLaw::NeoHookean { young, poisson } => format!(
            "compressible Neo-Hookean W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2, \
             E = {}, nu = {}",
            num(*young),
            num(*poisson)
        ),
        MaterialLaw::ElastoPlastic {
            young,
            poisson,
            hardening,
            viscosity,
        } => {
            let h = match hardening {
                Hardening::Linear {
                    yield_stress,
                    modulus,
                } => format!("sigma_y = {} + {} ep", num(*yield_stress), num(*modulus)),
                Hardening::Swift { k, eps0, n } => {
                    format!(
                        "Swift sigma_y = {} ({} + ep)^{}",
                        num(*k),
                        num(*eps0),
                        num(*n)
                    )
                }
                Hardening::JohnsonCook {
                    a,
                    b,
                    n,
                    c,
                    rate0,
                    m,
                    t_ref,
                    t_melt,
                    ..
                } => format!(
                    "Johnson-Cook sigma_y = ({} + {} ep^{}) (1 + {} ln(rate / {})) (1 - T*^{}), \
                     T* = (T - {}) / ({} - {})",
                    num(*a),
                    num(*b),
                    num(*n),
                    num(*c),
                    num(*rate0),
                    num(*m),
                    num(*t_ref),
                    num(*t_melt),
                    num(*t_ref)
                ),
                Hardening::Voce {
                    yield_stress,
                    sigma_inf,
                    delta,
                } => format!(
                    "Voce sigma_y = {} + ({} - {}) (1 - exp(-{} ep))",
                    num(*yield_stress),
                    num(*sigma_inf),
                    num(*yield_stress),
                    num(*delta)
                ),
            };
            let split = match k {
                Kinematics::Small => "small-strain J2 plasticity (additive split, radial return)",
                Kinematics::Finite => {
                    "finite-strain J2 plasticity (multiplicative split, Hencky elastic strain, \
                     exponential-map return)"
                }
            };
            let visc = match viscosity {
                Some(Viscosity::Perzyna { eta }) => {
                    format!(", Perzyna viscosity eta = {}", num(*eta))
                }
                Some(Viscosity::PerzynaPower { rate, exponent }) => format!(
                    ", Perzyna power law d(ep)/dt = {} (q / sigma_y - 1)^{}",
                    num(*rate),
                    num(*exponent)
                ),
                Some(Viscosity::NortonHoff { stress, rate, m }) => format!(
                    ", Norton-Hoff q = sigma_y + {} (d(ep)/dt / {})^{} (K = {})",
                    num(*stress),
                    num(*rate),
                    num(*m),
                    num(*stress / (3f64.sqrt() * (3f64.sqrt() * rate).powf(*m)))
                ),
                None => String::new(),
            };
            format!(
                "{split}, E = {}, nu = {}, {h}{visc}; consistent tangent",
                num(*young),
                num(*poisson)
            )
        }
    }
}

/// The enforcement of a contact pair in words.
fn method_plan(c: &ctc_engine::model::ContactPair) -> String {
    // a relative penalty (`10 * E / h`): its range over the nodes
    let coefficient = |k: f64| {
        let ks = c.local_penalty.iter().map(|&(_, k)| k);
        match (ks.clone().reduce(f64::min), ks.reduce(f64::max)) {
            (Some(lo), Some(hi)) => format!(
                "{} to {} (relative to E and the local element size h, per node, {} nodes)",
                num(lo),
                num(hi),
                c.local_penalty.len()
            ),
            _ => num(k),
        }
    };
    match &c.method {
        ContactMethod::Penalty { kind, stiffness } => match kind {
            PenaltyKind::Nodal => {
                format!(
                    "penalty, nodal: {} force per unit gap",
                    coefficient(*stiffness)
                )
            }
            PenaltyKind::Area => format!(
                "penalty, area-weighted: {} pressure per unit gap",
                coefficient(*stiffness)
            ),
        },
        ContactMethod::Lagrange { formulation } => match formulation {
            LagrangeFormulation::Single => "Lagrange multipliers (exact, active set), \
                saddle-point system [K G^T; G 0] by sparse LU"
                .to_string(),
            LagrangeFormulation::Doubled => "Lagrange multipliers (exact, active set), \
                doubled multipliers (lambda1, q, lambda2) by LDL^T without pivoting"
                .to_string(),
            LagrangeFormulation::Condensed => "Lagrange multipliers (exact, active set), \
                condensed at the slave nodes: the displacements alone by sparse LU, the \
                multipliers recovered after each solve"
                .to_string(),
        },
        ContactMethod::AugmentedLagrange {
            kind,
            penalty,
            tolerance,
            update,
        } => format!(
            "augmented Lagrangian, {}: {} {} per unit gap, penetration tolerance {}, \
             multipliers updated {}",
            match kind {
                PenaltyKind::Nodal => "nodal",
                PenaltyKind::Area => "area-weighted",
            },
            coefficient(*penalty),
            match kind {
                PenaltyKind::Nodal => "force",
                PenaltyKind::Area => "pressure",
            },
            num(*tolerance),
            match update {
                MultiplierUpdate::Converged => "after each converged Newton loop (Uzawa)",
                MultiplierUpdate::Newton => "at every Newton iteration",
            }
        ),
    }
}

/// The plan of a lowered solid (3D) scene: mesh, bodies, conditions,
/// loads and steps (`ctc check --explain` of a `3d` deck).
pub fn explain_solid(model: &ctc_engine::model::Model<3>) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "analysis: 3d solid (x, y, z)");
    let _ = writeln!(
        o,
        "mesh: {} nodes, {} cells",
        model.mesh.nodes.len(),
        model.mesh.cells.len()
    );
    for b in &model.bodies {
        let mut kinds: Vec<&str> = b
            .cells
            .clone()
            .map(|c| model.mesh.cells.kind(c).name())
            .collect();
        kinds.sort_unstable();
        kinds.dedup();
        let _ = writeln!(
            o,
            "  body {}: {} nodes, {} cells ({}), material {}, {:?} kinematics",
            b.name,
            b.nodes.len(),
            b.cells.len(),
            kinds.join(", "),
            model.materials[b.material].name,
            b.kinematics
        );
    }
    let _ = writeln!(o, "boundary conditions: {}", model.constraints.len());
    for d in &model.constraints {
        let _ = writeln!(
            o,
            "  {}: u{} = {} on {}",
            d.label,
            ["x", "y", "z"][d.component.min(2)],
            time_function(&d.value),
            plural(d.nodes.len(), "node", "nodes")
        );
    }
    let _ = writeln!(o, "loads: {}", model.loads.len());
    for l in &model.loads {
        match l {
            Load::Gravity {
                label,
                component: c,
                value,
            } => {
                let _ = writeln!(
                    o,
                    "  {label}: g{} = {} on every body with a density and every point mass \
                     (consistent nodal forces)",
                    ["x", "y", "z"][(*c).min(2)],
                    time_function(value)
                );
            }
            Load::FacetPressure {
                label,
                facets,
                value,
            } => {
                let _ = writeln!(
                    o,
                    "  {label}: p = {} on {} (positive pushes into the body)",
                    time_function(value),
                    plural(facets.len(), "face", "faces")
                );
            }
            Load::RigidMoment {
                label, axis, value, ..
            } => {
                let _ = writeln!(
                    o,
                    "  {label}: M = {} along ({:.4}, {:.4}, {:.4}) (fixed in space), on the \
                     body's rotation (work-conjugate)",
                    time_function(value),
                    axis[0],
                    axis[1],
                    axis[2]
                );
            }
            Load::NodalForce {
                label,
                nodes,
                component: c,
                value,
            } => {
                let _ = writeln!(
                    o,
                    "  {label}: f{} = {} per node, on {}",
                    ["x", "y", "z"][(*c).min(2)],
                    time_function(value),
                    plural(nodes.len(), "node", "nodes")
                );
            }
            Load::FacetTraction {
                label,
                facets,
                component: c,
                value,
            } => {
                let _ = writeln!(
                    o,
                    "  {label}: t{} = {} per unit reference area (dead load), on {}",
                    ["x", "y", "z"][(*c).min(2)],
                    time_function(value),
                    plural(facets.len(), "face", "faces")
                );
            }
            Load::FollowerPressure {
                label,
                facets,
                value,
                control,
            } => {
                let _ = writeln!(
                    o,
                    "  {label}: p = {} on {} of the deformed surface (follower: turns with it, \
                     with its load stiffness; positive pushes into the body){}",
                    time_function(value),
                    plural(facets.len(), "face", "faces"),
                    controller(control)
                );
            }
            Load::Pressure { label, .. } => {
                let _ = writeln!(o, "  {label}: pressure on edges (planar only)");
            }
        }
    }
    if !model.surfaces.is_empty() {
        let _ = writeln!(o, "rigid surface tools: {}", model.surfaces.len());
        for t in &model.surfaces {
            let _ = writeln!(o, "  {}: {}", t.name, surface_words(&t.geometry));
            let m = &t.motion;
            let mut parts = Vec::new();
            for (name, f) in ["ux", "uy", "uz"].iter().zip(&m.translation) {
                if !is_zero(f) {
                    parts.push(format!("{name} = {}", time_function(f)));
                }
            }
            if !is_zero(&m.rotation) {
                parts.push(format!(
                    "rotation (radians) about the axis {} through {} = {}",
                    point3(m.axis),
                    point3(m.center),
                    time_function(&m.rotation)
                ));
            }
            if parts.is_empty() {
                let _ = writeln!(o, "    fixed");
            } else {
                let _ = writeln!(o, "    moves: {}", parts.join(", "));
            }
        }
    }
    if !model.contacts.is_empty() {
        let _ = writeln!(o, "contact pairs: {}", model.contacts.len());
        for c in &model.contacts {
            let prof = match c.prof {
                Some(p) => format!("search within prof = {}", num(p)),
                None => "search within an automatic prof (the longest slave face edge)".into(),
            };
            let friction = match &c.friction {
                Some(f) => format!(
                    "{} (on the tangent plane, stick point in the tool's frame)",
                    friction_plan(f, &c.method, true)
                ),
                None => "frictionless".to_string(),
            };
            let _ = writeln!(
                o,
                "  {}: {}; {} slave nodes on {}; {friction}, node-to-surface; {prof}",
                c.name,
                method_plan(c),
                c.nodes.len(),
                plural(c.faces.len(), "face", "faces")
            );
        }
    }
    let _ = writeln!(o, "steps: {}", model.steps.len());
    for s in &model.steps {
        let _ = writeln!(
            o,
            "  {}: t = {} .. {} in {} increments",
            s.name, s.t_start, s.t_end, s.increments
        );
    }
    let mut absent = Vec::new();
    if model.surfaces.is_empty() {
        absent.push("rigid tools");
    }
    if model.contacts.is_empty() {
        absent.push("contact");
    } else if model.contacts.iter().all(|c| c.friction.is_none()) {
        absent.push("friction");
    }
    match &model.thermal {
        None => absent.push("thermal unknowns"),
        Some(t) => {
            let _ = writeln!(o, "{}", heat_line(t));
            let _ = writeln!(
                o,
                "  conduction: every cell kind through its reference cell (lumped capacity), \
                 backward Euler; temperature-dependent moduli and flow stress at the cell's \
                 mean temperature; thermal strain alpha (T - T_ref) in the six strain \
                 components; Taylor-Quinney plastic heating"
            );
            for b in &t.temperatures {
                let _ = writeln!(
                    o,
                    "  {}: T = {} on {}",
                    b.label,
                    time_function(&b.value),
                    plural(b.nodes.len(), "node", "nodes")
                );
            }
            for f in &t.fluxes {
                let _ = writeln!(
                    o,
                    "  {}: q = {} into the body on {}",
                    f.label,
                    time_function(&f.value),
                    plural(f.facets.len(), "face", "faces")
                );
            }
            for c in &t.convection {
                let _ = writeln!(
                    o,
                    "  {}: q = h (T_ambient - T), h = {}, T_ambient = {} on {}",
                    c.label,
                    num(c.film),
                    time_function(&c.ambient),
                    plural(c.facets.len(), "face", "faces")
                );
            }
            for (c, th) in model.contacts.iter().zip(&t.contacts) {
                let Some(th) = th else { continue };
                let tool = match &th.tool_temperature {
                    Some(f) => format!("tool at T = {}", time_function(f)),
                    None => "adiabatic tool".to_string(),
                };
                let _ = writeln!(
                    o,
                    "  thermal contact {}: heat h (T_tool - T) A per slave node (A: its \
                     tributary face area), h from the contact pressure when closed, \
                     k_gap / gap = {} / gap when open; {tool}",
                    c.name,
                    num(th.gap_conductivity)
                );
            }
        }
    }
    let _ = writeln!(o, "not in this scene: {}", absent.join(", "));
    o
}

/// The one-line summary of a thermal scene (both dimensions).
fn heat_line(t: &ctc_engine::model::thermal::ThermalScene) -> String {
    format!(
        "heat: conduction on {} thermal material(s), {} prescribed temperature(s), \
         {} flux(es), {} convection(s), {} thermal contact pair(s); coupling: staggered \
         (isothermal split: mechanics at fixed temperature, then heat)",
        t.materials.iter().flatten().count(),
        t.temperatures.len(),
        t.fluxes.len(),
        t.convection.len(),
        t.contacts.iter().flatten().count()
    )
}

fn point3(p: [f64; 3]) -> String {
    format!("({}, {}, {})", num(p[0]), num(p[1]), num(p[2]))
}

/// A surface tool's geometry in words (free side included).
fn surface_words(g: &ctc_engine::model::SurfaceShape) -> String {
    use ctc_engine::model::SurfaceShape;
    use ctc_geom::analytic::Analytic;
    use ctc_geom::Side;
    let g = match g {
        SurfaceShape::Analytic(a) => a,
        SurfaceShape::Mesh(m) => {
            let b = m.bounding_box();
            let v = |x: &ctc_geom::Vec3| point3([x[0], x[1], x[2]]);
            let free = m.edge_free.iter().filter(|&&f| f).count();
            return format!(
                "triangulated surface (STL): {}, {}, {} in the box {} .. {}; flat \
                 triangles, a foot on an edge or a vertex is a cylinder or a sphere of radius 0, \
                 inside / outside by angle-weighted pseudonormals",
                plural(m.triangles.len(), "triangle", "triangles"),
                plural(m.vertices.len(), "vertex", "vertices"),
                if free == 0 {
                    "closed".to_string()
                } else {
                    format!("open ({})", plural(free, "free edge", "free edges"))
                },
                v(&b.min),
                v(&b.max)
            );
        }
        SurfaceShape::Brep(b) => {
            let holes: usize = b
                .faces
                .iter()
                .filter_map(|f| f.boundary.as_ref())
                .map(|bd| bd.holes.len())
                .sum();
            let trimmed = b.faces.iter().filter(|f| f.boundary.is_some()).count();
            let v = |x: &ctc_geom::Vec3| point3([x[0], x[1], x[2]]);
            return format!(
                "CAD faces: {} ({} trimmed, {}), {} in the box {} .. {}; free side \
                 along S_u x S_v of the first face (oriented across shared edges); a foot on \
                 an edge or a vertex is a cylinder or a sphere of radius 0",
                plural(b.faces.len(), "NURBS face", "NURBS faces"),
                trimmed,
                plural(holes, "hole", "holes"),
                plural(b.vertices.len(), "vertex", "vertices"),
                v(&b.bbox.min),
                v(&b.bbox.max)
            );
        }
    };
    let side = |s: Side| match s {
        Side::Outside => "bodies outside",
        Side::Inside => "bodies inside",
    };
    let v = |x: &ctc_geom::Vec3| point3([x[0], x[1], x[2]]);
    match g {
        Analytic::Plane(p) => format!(
            "plane through {}, normal {} (bodies on the normal's side)",
            v(&p.point),
            v(&p.normal)
        ),
        Analytic::Sphere(s) => format!(
            "sphere, center {}, radius {}, {}",
            v(&s.center),
            num(s.radius),
            side(s.side)
        ),
        Analytic::Cylinder(c) => format!(
            "cylinder, axis {} through {}, radius {}, {}",
            v(&c.axis),
            v(&c.point),
            num(c.radius),
            side(c.side)
        ),
        Analytic::Cone(c) => format!(
            "cone, apex {}, axis {}, half angle {} degrees, {}",
            v(&c.apex),
            v(&c.axis),
            num(c.half_angle.to_degrees()),
            side(c.side)
        ),
        Analytic::Torus(t) => format!(
            "torus, center {}, axis {}, radii {} and {}, {}",
            v(&t.center),
            v(&t.axis),
            num(t.major),
            num(t.minor),
            side(t.side)
        ),
    }
}

/// A pressure controller in words (empty without one).
fn controller(control: &Option<ctc_engine::model::RateControl>) -> String {
    control.as_ref().map_or_else(String::new, |c| {
        let region = if c.at.is_empty() {
            "its body".to_string()
        } else {
            format!("the cells around node {}", c.at[0])
        };
        format!(
            ", scaled after each increment by (target / rate)^{} within a factor {} so that \
             the largest equivalent plastic strain rate of {region} holds {} (pressure-cycle \
             control)",
            num(c.exponent),
            num(c.max_factor),
            num(c.target)
        )
    })
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
