//! Warnings after a run that converged but whose contact may not be what
//! the user meant (issue 14, "silent runs"): a pair that never closed,
//! penetrations larger than a fraction of the local element size, and a
//! tool whose travel went mostly into penetration (E and the penalty in
//! mixed units: E = 210e9 with a penalty of 1e6 gave a penetration of 97 %
//! of the stroke and "done"). The warnings go to `summary.json`
//! (`warnings`) and to the observer (the console).

use crate::contact::{ContactStatus, NodeContact};
use crate::model::{ContactMaster, ContactMethod, Model};

/// Penetration, as a fraction of the local element size, above which a
/// pair is reported.
pub const PENETRATION_OF_ELEMENT: f64 = 0.1;
/// Penetration, as a fraction of the tool's travel, above which a pair is
/// reported as probably mis-scaled.
pub const PENETRATION_OF_TRAVEL: f64 = 0.5;
/// Penetration suggested as the target of a stiffer penalty (fraction of
/// the element size).
const TARGET_OF_ELEMENT: f64 = 0.01;

/// What one pair did over the converged increments.
#[derive(Debug, Clone, Default)]
struct PairHealth {
    closed: bool,
    /// Largest penetration, its node and time.
    worst: Option<(f64, usize, f64)>,
    /// Largest travel of the tool from the start of the analysis.
    travel: f64,
}

/// The contact health of a run, recorded at each converged increment.
#[derive(Debug, Clone, Default)]
pub struct RunHealth {
    pairs: Vec<PairHealth>,
    increments: usize,
}

impl RunHealth {
    /// Nothing recorded yet, for the pairs of `model`.
    pub fn new<const D: usize>(model: &Model<D>) -> Self {
        RunHealth {
            pairs: vec![PairHealth::default(); model.contacts.len()],
            increments: 0,
        }
    }

    /// Records the converged state at time `t`.
    pub fn record<const D: usize>(
        &mut self,
        model: &Model<D>,
        contact: &[Vec<NodeContact<D>>],
        t: f64,
    ) {
        self.increments += 1;
        let t0 = model.steps.first().map_or(0.0, |s| s.t_start);
        for ((h, list), cp) in self.pairs.iter_mut().zip(contact).zip(&model.contacts) {
            for nc in list {
                if nc.status == ContactStatus::Closed {
                    h.closed = true;
                }
                let pen = -nc.gap;
                if nc.status == ContactStatus::Closed
                    && pen > 0.0
                    && h.worst.is_none_or(|w| pen > w.0)
                {
                    h.worst = Some((pen, nc.node, t));
                }
            }
            if let ContactMaster::Tool(i) = cp.master {
                if let Some(tool) = model.tools.get(i) {
                    let m = &tool.motion;
                    // the translation only (a rotation is not counted: the
                    // travel is a lower bound, the warning conservative)
                    let d = [m.ux.eval(t) - m.ux.eval(t0), m.uy.eval(t) - m.uy.eval(t0)];
                    h.travel = h.travel.max(d[0].hypot(d[1]));
                }
            }
        }
    }

    /// The warnings of the run so far.
    pub fn warnings<const D: usize>(&self, model: &Model<D>) -> Vec<String> {
        let mut out = Vec::new();
        if self.increments == 0 {
            return out;
        }
        for (h, cp) in self.pairs.iter().zip(&model.contacts) {
            if !h.closed {
                out.push(format!(
                    "contact pair `{}` never closed over the {} converged increment(s): its \
                     surfaces never touched (check the tool's position and motion, the pair's \
                     sets, or which side of the tool is free: `ctc check --explain`)",
                    cp.name, self.increments
                ));
                continue;
            }
            let Some((pen, node, t)) = h.worst else {
                continue;
            };
            let stiffness = match cp.method {
                ContactMethod::Penalty { stiffness, .. } => Some(stiffness),
                ContactMethod::AugmentedLagrange { penalty, .. } => Some(penalty),
                ContactMethod::Lagrange { .. } => None,
            };
            let size = element_size(model, &cp.edges, node);
            let mixed = h.travel > 0.0 && pen > PENETRATION_OF_TRAVEL * h.travel;
            if mixed {
                out.push(format!(
                    "contact pair `{}`: a penetration of {pen:.3e} (node {node}, t = {t:.4e}) is \
                     {:.0}% of the tool's travel {:.3e}: the motion went into penetration, not \
                     into deformation; the penalty is far too soft for the material (are E and \
                     the penalty stiffness in the same units?)",
                    cp.name,
                    100.0 * pen / h.travel,
                    h.travel
                ));
            } else if size > 0.0 && pen > PENETRATION_OF_ELEMENT * size {
                let suggestion = stiffness.map_or(String::new(), |k| {
                    format!(
                        "; for a penetration of {:.0}% of it try a stiffness of ~{:.1e} (now \
                         {k:.1e})",
                        100.0 * TARGET_OF_ELEMENT,
                        k * pen / (TARGET_OF_ELEMENT * size)
                    )
                });
                out.push(format!(
                    "contact pair `{}`: a penetration of {pen:.3e} (node {node}, t = {t:.4e}) is \
                     {:.0}% of the local element size {size:.3e}: the contact is soft for this \
                     mesh{suggestion}",
                    cp.name,
                    100.0 * pen / size
                ));
            }
        }
        out
    }
}

/// Mean length of the slave edges at `node` in the reference mesh (0:
/// none).
fn element_size<const D: usize>(model: &Model<D>, edges: &[[usize; 2]], node: usize) -> f64 {
    let p = &model.mesh.nodes;
    let (sum, n) = edges
        .iter()
        .filter(|e| e.contains(&node))
        .map(|e| (p[e[0]][0] - p[e[1]][0]).hypot(p[e[0]][1] - p[e[1]][1]))
        .fold((0.0, 0usize), |(s, n), l| (s + l, n + 1));
    if n == 0 {
        0.0
    } else {
        sum / n as f64
    }
}

/// Slave nodes that start inside a rigid tool (gap below `-1e-6` of the
/// local element size at the start of the analysis), per pair: "N of M
/// slave nodes start inside tool T (deepest D at node n)". Many nodes, or
/// nodes deeper than their element, usually mean the tool's free side is
/// reversed (a polyline or NURBS walked the wrong way, a plane normal
/// pointing into the body, `side = inside` for `outside`): the run then
/// fails with "chattering" or inverted elements. Reported before the
/// first increment (console, `summary.json` warnings) and by `ctc check`.
pub fn start_inside<const D: usize>(model: &Model<D>) -> Vec<String> {
    let mut out = Vec::new();
    if D != 2 {
        return out;
    }
    let t0 = model.steps.first().map_or(0.0, |s| s.t_start);
    for cp in &model.contacts {
        let ContactMaster::Tool(i) = cp.master else {
            continue;
        };
        let Some(tool) = model.tools.get(i) else {
            continue;
        };
        let Ok(shape) = crate::contact::geometry::ToolShape::new(&tool.geometry) else {
            continue;
        };
        let placement = crate::contact::motion::Placement::at(&tool.motion, t0);
        let mut tests = 0;
        let (mut inside, mut deep) = (0usize, 0usize);
        let mut deepest: Option<(f64, usize, f64)> = None;
        for &n in &cp.nodes {
            let p = model.mesh.nodes[n];
            let x = [p[0], p[1]];
            let Some(found) =
                crate::contact::search::brute_force(&shape, placement.to_reference(x), &mut tests)
            else {
                continue;
            };
            let size = element_size(model, &cp.edges, n);
            let depth = -found.projection.gap;
            if depth > 1e-6 * size.max(f64::MIN_POSITIVE) {
                inside += 1;
                if depth > size {
                    deep += 1;
                }
                if deepest.is_none_or(|d| depth > d.0) {
                    deepest = Some((depth, n, size));
                }
            }
        }
        let Some((depth, node, size)) = deepest else {
            continue;
        };
        let reversed = 2 * inside > cp.nodes.len() || deep > 0;
        out.push(format!(
            "contact pair `{}`: {inside} of {} slave nodes start inside tool `{}` (deepest \
             {depth:.3e} at node {node}, local element size {size:.3e}){}",
            cp.name,
            cp.nodes.len(),
            tool.name,
            if reversed {
                format!(
                    ": is the tool's side reversed? ({}; `ctc check --explain` says which side \
                     is free)",
                    free_side_rule(&tool.geometry)
                )
            } else {
                " (an initial overlap: it is pushed out in the first increment)".to_string()
            }
        ));
    }
    out
}

/// Which side of a tool is free, in words.
pub fn free_side_rule(geometry: &crate::model::ToolGeometry) -> &'static str {
    use crate::model::{ToolGeometry, ToolSide};
    match geometry {
        ToolGeometry::Plane { .. } => "the free side of a plane is where its normal points",
        ToolGeometry::Polyline { .. } => {
            "the free side of a polyline is on the left of its walk from the first point to \
             the last"
        }
        ToolGeometry::Nurbs { .. } => {
            "the free side of a NURBS curve is on the left of its walk along the parameter"
        }
        ToolGeometry::Arc { .. } => {
            "an arc walked counter-clockwise (end > start) is free inside, clockwise outside"
        }
        ToolGeometry::Circle { side, .. } => match side {
            ToolSide::Outside => "this circle's free side is outside (`side = outside`)",
            ToolSide::Inside => "this circle's free side is inside (`side = inside`)",
        },
    }
}
