//! Export of the exact problem ctc solves (mesh, node numbering, boundary
//! conditions per increment, contact surfaces with their tributary areas,
//! rigid tool placement per increment) to a JSON file read by the FEniCSx
//! reference scripts in `verification/fenicsx/`, so both codes solve the
//! same discretized problem on the same mesh with the same node numbers.
//!
//! Only what the reference scripts support is exported; anything else
//! (several materials, nonlinear laws, finite strain, rotating tools,
//! Lagrange multipliers, nodal forces, tools other than planes and circles)
//! is an error with a clear message rather than a silently different
//! problem.

use ctc_engine::contact::tributary::tributary_areas;
use ctc_engine::mesh::CellKind;
use ctc_engine::model::{
    AnalysisKind, ContactMethod, Kinematics, Load, MaterialLaw, Model, PenaltyKind, ToolGeometry,
    ToolSide,
};
use serde::{Deserialize, Serialize};

/// Format tag written into every export (bumped when the layout changes).
pub const EXPORT_FORMAT: &str = "ctc-fenicsx-problem-1";

/// The problem handed to a FEniCSx reference script.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ProblemExport {
    /// [`EXPORT_FORMAT`].
    pub format: String,
    /// Case name (e.g. `fenicsx_rigid_cylinder`).
    pub case: String,
    /// `plane_strain` or `axisymmetric`.
    pub analysis: String,
    /// Out-of-plane thickness (plane strain; 1 for axisymmetric).
    pub thickness: f64,
    /// Young's modulus of the (single) linear elastic material.
    pub young: f64,
    /// Poisson's ratio.
    pub poisson: f64,
    /// `tri3` or `quad4` (all cells the same kind).
    pub cell_kind: String,
    /// Node coordinates, ctc numbering.
    pub nodes: Vec<[f64; 2]>,
    /// Cells: node numbers, counter-clockwise (3 or 4 per cell).
    pub cells: Vec<Vec<usize>>,
    /// End times of the increments, in order (no cutbacks assumed).
    pub times: Vec<f64>,
    /// Newton tolerance of the (last) step.
    pub newton_tol: f64,
    /// Newton iteration limit of the (last) step.
    pub newton_max_iter: usize,
    /// Prescribed displacement components.
    pub dirichlet: Vec<DirichletExport>,
    /// Pressure loads on boundary edges.
    pub pressure: Vec<PressureExport>,
    /// Contact pairs against rigid tools.
    pub contacts: Vec<ContactExport>,
}

/// One prescribed displacement component on a node set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DirichletExport {
    /// Origin in the deck.
    pub label: String,
    /// Node numbers.
    pub nodes: Vec<usize>,
    /// 0 = x (r), 1 = y (z).
    pub component: usize,
    /// Prescribed value at each of [`ProblemExport::times`].
    pub values: Vec<f64>,
}

/// A pressure (positive into the body) on boundary edges.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PressureExport {
    /// Origin in the deck.
    pub label: String,
    /// Edges `[a, b]`, body on the left.
    pub edges: Vec<[usize; 2]>,
    /// Pressure at each of [`ProblemExport::times`].
    pub values: Vec<f64>,
}

/// A penalty contact pair against a rigid plane or circle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactExport {
    /// Pair name.
    pub name: String,
    /// Slave edges `[a, b]`, body on the left.
    pub edges: Vec<[usize; 2]>,
    /// Slave nodes, sorted.
    pub nodes: Vec<usize>,
    /// ctc's tributary area of each slave node (for the scripts to check
    /// their own).
    pub tributary: Vec<f64>,
    /// `area` (pressure per gap times tributary area) or `nodal`.
    pub penalty_kind: String,
    /// Penalty coefficient as written in the deck.
    pub stiffness: f64,
    /// `plane` or `circle`.
    pub tool: String,
    /// Plane: a point; circle: the centre (reference placement).
    pub point: [f64; 2],
    /// Plane: unit normal to free space (zero for a circle).
    pub normal: [f64; 2],
    /// Circle radius (zero for a plane).
    pub radius: f64,
    /// Tool translation at each of [`ProblemExport::times`].
    pub translation: Vec<[f64; 2]>,
}

/// End times of every increment of every step (uniform increments, no
/// cutbacks).
pub fn increment_times(model: &Model) -> Vec<f64> {
    let mut times = Vec::new();
    for s in &model.steps {
        let n = s.increments.max(1);
        for k in 1..=n {
            times.push(s.t_start + (s.t_end - s.t_start) * k as f64 / n as f64);
        }
    }
    times
}

/// Exports `model` as the problem of case `case`. Errors name the feature
/// the reference scripts do not support.
pub fn export(model: &Model, case: &str) -> Result<ProblemExport, String> {
    let analysis = match model.analysis.kind {
        AnalysisKind::PlaneStrain => "plane_strain",
        AnalysisKind::Axisymmetric => "axisymmetric",
        AnalysisKind::PlaneStress => {
            return Err(
                "FEniCSx export: plane stress is not supported (plane strain and axisymmetric are)"
                    .into(),
            )
        }
        AnalysisKind::Solid => {
            return Err("FEniCSx export: 3D solids are not supported (planar cases only)".into())
        }
    };
    let [body] = model.bodies.as_slice() else {
        return Err(format!(
            "FEniCSx export: exactly one body is supported, the model has {}",
            model.bodies.len()
        ));
    };
    if body.kinematics != Kinematics::Small {
        return Err("FEniCSx export: finite-strain bodies are not supported yet".into());
    }
    let (young, poisson) = match model.materials.get(body.material).map(|m| &m.law) {
        Some(MaterialLaw::LinearElastic { young, poisson }) => (*young, *poisson),
        _ => return Err("FEniCSx export: only linear elastic materials are supported".into()),
    };
    let kinds: Vec<CellKind> = model.mesh.cells.iter().map(|c| c.kind).collect();
    let cell_kind = match kinds.first() {
        Some(CellKind::Tri3) if kinds.iter().all(|&k| k == CellKind::Tri3) => "tri3",
        Some(CellKind::Quad4) if kinds.iter().all(|&k| k == CellKind::Quad4) => "quad4",
        _ => return Err("FEniCSx export: the mesh must be all tri3 or all quad4".into()),
    };
    let times = increment_times(model);
    let Some(step) = model.steps.last() else {
        return Err("FEniCSx export: the model has no step".into());
    };
    let dirichlet = model
        .constraints
        .iter()
        .map(|d| DirichletExport {
            label: d.label.clone(),
            nodes: d.nodes.clone(),
            component: d.component,
            values: times.iter().map(|&t| d.value.eval(t)).collect(),
        })
        .collect();
    let mut pressure = Vec::new();
    for load in &model.loads {
        match load {
            Load::Pressure {
                label,
                edges,
                value,
            } => pressure.push(PressureExport {
                label: label.clone(),
                edges: edges.clone(),
                values: times.iter().map(|&t| value.eval(t)).collect(),
            }),
            Load::NodalForce { label, .. } => {
                return Err(format!(
                    "FEniCSx export: nodal forces ({label}) are not supported"
                ))
            }
            Load::Gravity { label, .. } => {
                return Err(format!(
                    "FEniCSx export: gravity ({label}) is not supported"
                ))
            }
            Load::FacetTraction { label, .. } => {
                return Err(format!(
                    "FEniCSx export: tractions ({label}) are not supported"
                ))
            }
            Load::FacetPressure { label, .. } => {
                return Err(format!(
                    "FEniCSx export: pressure on faces ({label}) is planar-only"
                ))
            }
            Load::FollowerPressure { label, .. } => {
                return Err(format!(
                    "FEniCSx export: follower pressure ({label}) is not supported"
                ))
            }
            Load::RigidMoment { label, .. } => {
                return Err(format!(
                    "FEniCSx export: a rigid body's moment ({label}) is not supported"
                ))
            }
        }
    }
    let mut contacts = Vec::new();
    for (i, cp) in model.contacts.iter().enumerate() {
        let ContactMethod::Penalty { kind, stiffness } = cp.method else {
            return Err(format!(
                "FEniCSx export: contact '{}' must use the penalty method",
                cp.name
            ));
        };
        let tool = model
            .tools
            .get(cp.master.tool().unwrap_or(usize::MAX))
            .ok_or_else(|| format!("contact '{}' has no tool", cp.name))?;
        let (kind_name, point, normal, radius) = match &tool.geometry {
            ToolGeometry::Plane { point, normal } => ("plane", *point, *normal, 0.0),
            ToolGeometry::Circle {
                center,
                radius,
                side: ToolSide::Outside,
            } => ("circle", *center, [0.0, 0.0], *radius),
            _ => {
                return Err(format!(
                    "FEniCSx export: tool '{}' must be a plane or a circle with side = outside",
                    tool.name
                ))
            }
        };
        if times.iter().any(|&t| tool.motion.rotation.eval(t) != 0.0) {
            return Err(format!(
                "FEniCSx export: tool '{}' rotates (not supported)",
                tool.name
            ));
        }
        contacts.push(ContactExport {
            name: cp.name.clone(),
            edges: cp.edges.clone(),
            nodes: cp.nodes.clone(),
            tributary: tributary_areas(model, i),
            penalty_kind: match kind {
                PenaltyKind::Area => "area",
                PenaltyKind::Nodal => "nodal",
            }
            .into(),
            stiffness,
            tool: kind_name.into(),
            point,
            normal,
            radius,
            translation: times
                .iter()
                .map(|&t| [tool.motion.ux.eval(t), tool.motion.uy.eval(t)])
                .collect(),
        });
    }
    Ok(ProblemExport {
        format: EXPORT_FORMAT.into(),
        case: case.into(),
        analysis: analysis.into(),
        thickness: if analysis == "axisymmetric" {
            1.0
        } else {
            model.analysis.thickness
        },
        young,
        poisson,
        cell_kind: cell_kind.into(),
        nodes: model.mesh.nodes.clone(),
        cells: model.mesh.cells.iter().map(|c| c.nodes.to_vec()).collect(),
        times,
        newton_tol: step.newton.tol,
        newton_max_iter: step.newton.max_iter,
        dirichlet,
        pressure,
        contacts,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::deck::compile_text;
    use std::path::Path;

    const DECK: &str = r#"
analysis { dimension = axisymmetric }
material m { elastic { E = 100  nu = 0.25 } }
body b {
  mesh = rectangle { origin = (0, 0)  size = (2, 1)  divisions = (2, 1)  element = tri3 }
  material = m
}
tool floor = plane { point = (0, 0)  normal = (0, 1) }
contact b.bottom -> floor { method = penalty { kind = area  stiffness = 10 } }
fix b.left { ux }
displace b.top { uy = ramp(0, -0.1) }
step s { time = 0 .. 1  increments = 2 }
"#;

    #[test]
    fn export_axisymmetric_tri3_block_on_plane() {
        let model = compile_text(Path::new("t.ctc"), DECK).unwrap();
        let e = export(&model, "t").unwrap();
        assert_eq!(e.analysis, "axisymmetric");
        assert_eq!(e.cell_kind, "tri3");
        assert_eq!(e.times, vec![0.5, 1.0]);
        assert_eq!(e.nodes.len(), 6);
        assert!(e.cells.iter().all(|c| c.len() == 3));
        let top = e.dirichlet.iter().find(|d| d.component == 1).unwrap();
        assert_eq!(top.values, vec![-0.05, -0.1]);
        let c = &e.contacts[0];
        assert_eq!((c.tool.as_str(), c.normal), ("plane", [0.0, 1.0]));
        // Consistent axisymmetric tributaries sum to the ring area pi r^2.
        let total: f64 = c.tributary.iter().sum();
        assert!((total - std::f64::consts::PI * 4.0).abs() < 1e-12);
        let json = serde_json::to_string(&e).unwrap();
        let back: ProblemExport = serde_json::from_str(&json).unwrap();
        assert_eq!(back, e);
    }

    #[test]
    fn export_rejects_nodal_forces() {
        let deck = DECK.replace(
            "fix b.left { ux }",
            "fix b.left { ux }\nforce b.node(near(0, 1)) { fx = 1 }",
        );
        let model = compile_text(Path::new("t.ctc"), &deck).unwrap();
        let err = export(&model, "t").unwrap_err();
        assert!(err.contains("nodal forces"), "{err}");
    }
}
