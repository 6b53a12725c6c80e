//! Rigid tools whose rotation about their centre is an unknown (free
//! rollers, `motion { rotation = free  moment = .. }`; issue 22).
//!
//! The angle `theta` is the x displacement of a **pilot node** appended to
//! the mesh at the tool's centre, attached to no cell, its y component held
//! at 0 (`model::FreeRotation`, [`make_free`]): the dof map, the Newton
//! state, line search, cutbacks, commits and restart points carry it like
//! any displacement (so a restart continues bit for bit), and the applied
//! moment is a nodal force on that component. Abaqus does the same with a
//! rigid body's reference node (`UR3` in plane).
//!
//! The contact of a node `a` against the tool is a function of the node's
//! position in the tool's frame only, `f_a(x, theta) = Q(theta) F(Q^T (x -
//! c - u) + c)` (gap, normal, stick point and slip are all measured there,
//! `contact::motion`), so with `K_a = -d f_a / d x` (the tangent the
//! contact law returns), `r_a = x_a - (c + u(t))` the arm from the current
//! centre and `J` the rotation by +90 degrees (`Q' = J Q`):
//!
//! - `d f_a / d theta = J f_a + K_a J r_a`;
//! - the tool's equation, the moment balance about the current centre,
//!   `R_theta = sum_a r_a x f_a - M(t) = 0` (`r_a x f_a` the moment of the
//!   force on the body: the tool receives its opposite); a frictionless
//!   penalty contact makes it the derivative of the penalty energy by
//!   `theta`, so the tangent below is symmetric there;
//! - `d R_theta / d x_a = -K_a^T J r_a - J f_a`,
//!   `d R_x_a / d theta = -(J f_a + K_a J r_a)`,
//!   `d R_theta / d theta = sum_a f_a . r_a + (J r_a)^T K_a (J r_a)`.
//!
//! Exact for every normal method and Coulomb friction of a node against a
//! rigid tool (penalty and augmented Lagrangian; Lagrange multipliers and
//! quadratic faces are refused by the lowering), FD-checked below. A
//! circle turning under frictionless contact leaves everything unchanged:
//! its row is zero (and a tool no node touches has none); the tangent
//! (never the residual) gets `1e-10` of the row's stiffness scale on its
//! diagonal, or 1 when the tool is not touched, so the angle stays put
//! where nothing turns it. A slipping node's force does not depend on the
//! angle (its magnitude is `mu R_N`), so a roller whose touching nodes all
//! slip one way has no tangent for its angle although its friction moment
//! is not balanced (the equilibrium needs some of them to stick): when no
//! node of the tool sticks, each slipping node adds its stick stiffness
//! `alpha_T (t . J r)^2` to the diagonal of the tangent (a secant term; the
//! residual stays exact, and the tangent is exact again as soon as a node
//! sticks, as a rolling contact does).

use super::dofs::DofMap;
use crate::contact::friction::{tangential_stiffness, FrictionStatus};
use crate::contact::mortar::Coupling;
use crate::contact::vec2::{cross, dot, sub};
use crate::contact::{NodeContact, PairState};
use crate::model::{AnalysisKind, Dirichlet, FreeRotation, Load, Model, TimeFunction};

/// Relative diagonal added to the angle's tangent (see the module notes).
pub const REGULARIZATION: f64 = 1e-10;

/// Makes tool `tool` of `model` free to rotate about its centre under the
/// applied moment `moment(t)`: appends the pilot node at the centre, holds
/// its y component, loads its x component with the moment. Refused in
/// axisymmetric models (a ring's cross-section does not turn as a body)
/// and for a tool that is free already.
pub fn make_free(model: &mut Model, tool: usize, moment: TimeFunction) -> Result<usize, String> {
    if model.analysis.kind == AnalysisKind::Axisymmetric {
        return Err(
            "a free rotation needs a plane strain or plane stress analysis: in an axisymmetric \
             model the tool is a ring, whose cross-section does not turn as a rigid body"
                .into(),
        );
    }
    let Some(t) = model.tools.get(tool) else {
        return Err(format!("tool {tool} does not exist"));
    };
    if t.free_rotation.is_some() {
        return Err(format!("tool '{}' is free to rotate already", t.name));
    }
    let name = t.name.clone();
    let node = model.mesh.nodes.len();
    model.mesh.nodes.push(t.motion.center);
    model.constraints.push(Dirichlet {
        label: format!("pilot node of tool '{name}' (y held)"),
        nodes: vec![node],
        component: 1,
        value: TimeFunction::Constant(0.0),
    });
    model.loads.push(Load::NodalForce {
        label: format!("moment on tool '{name}'"),
        nodes: vec![node],
        component: 0,
        value: moment.clone(),
    });
    let t = &mut model.tools[tool];
    t.motion.rotation = TimeFunction::Constant(0.0);
    t.free_rotation = Some(FreeRotation { node, moment });
    Ok(node)
}

/// Why the free tools of `model` cannot be solved, if they cannot: an
/// axisymmetric analysis, a dynamic step (no rotational inertia), heat
/// conduction, a pair by Lagrange multipliers or on quadratic faces (the
/// coupling is built on the nodal forces and tangents), a pilot node
/// attached to a cell or out of range.
pub fn refusals<const D: usize>(model: &Model<D>) -> Vec<String> {
    let mut out = Vec::new();
    for t in &model.tools {
        let Some(f) = &t.free_rotation else { continue };
        let name = &t.name;
        if model.analysis.kind == AnalysisKind::Axisymmetric {
            out.push(format!(
                "tool '{name}': a free rotation needs a plane strain or plane stress analysis"
            ));
        }
        if model.steps.iter().any(|s| s.dynamic.is_some()) {
            out.push(format!(
                "tool '{name}': a free rotation is solved in quasi-static steps only (no rotational \
                 inertia)"
            ));
        }
        if model.thermal.is_some() {
            out.push(format!(
                "tool '{name}': a free rotation with heat conduction is not available"
            ));
        }
        if f.node >= model.mesh.nodes.len()
            || model.mesh.cells.iter().any(|c| c.nodes.contains(&f.node))
        {
            out.push(format!(
                "tool '{name}': pilot node {} is not a free node of the mesh",
                f.node
            ));
        }
        let tool = model.tools.iter().position(|u| std::ptr::eq(u, t));
        for cp in model
            .contacts
            .iter()
            .filter(|c| c.master.tool().is_some() && c.master.tool() == tool)
        {
            if matches!(cp.method, crate::model::ContactMethod::Lagrange { .. }) {
                out.push(format!(
                    "pair '{}': Lagrange multipliers are not available against a tool free to \
                     rotate (use penalty or augmented Lagrangian)",
                    cp.name
                ));
            }
            let quadratic = cp.edges.iter().any(|e| {
                model.mesh.cells.iter().any(|c| {
                    c.nodes.len() > 4 && c.nodes.contains(&e[0]) && c.nodes.contains(&e[1])
                })
            });
            if quadratic {
                out.push(format!(
                    "pair '{}': quadratic slave faces are not available against a tool free to \
                     rotate",
                    cp.name
                ));
            }
        }
    }
    out
}

/// The pilot nodes of the model (attached to no cell, but unknowns).
pub fn pilot_nodes<const D: usize>(model: &Model<D>) -> impl Iterator<Item = usize> + '_ {
    model
        .tools
        .iter()
        .filter_map(|t| t.free_rotation.as_ref().map(|f| f.node))
}

/// The free tool of contact pair `pair`: (tool index, pilot node).
fn free_master(model: &Model, pair: usize) -> Option<(usize, usize)> {
    let t = model.contacts.get(pair)?.master.tool()?;
    Some((t, model.tools.get(t)?.free_rotation.as_ref()?.node))
}

/// Node couplings of the free tools for the sparsity pattern: each pilot
/// node with every slave node of the pairs against its tool.
pub fn couplings<const D: usize>(model: &Model<D>) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    for cp in &model.contacts {
        let Some(t) = cp.master.tool() else { continue };
        let Some(f) = model.tools.get(t).and_then(|t| t.free_rotation.as_ref()) else {
            continue;
        };
        for &a in &cp.nodes {
            if a != f.node {
                out.push((a.min(f.node), a.max(f.node)));
            }
        }
    }
    out
}

/// Sets the current angle of every pair against a free tool from the
/// pilot nodes' displacements (before the pairs are evaluated).
pub fn set_angles(model: &Model, u: &[[f64; 2]], pairs: &mut [PairState]) {
    for (p, state) in pairs.iter_mut().enumerate() {
        state.angle = free_master(model, p)
            .and_then(|(_, n)| u.get(n))
            .map(|v| v[0]);
    }
}

/// `J v`: `v` turned by +90 degrees.
fn turn(v: [f64; 2]) -> [f64; 2] {
    [-v[1], v[0]]
}

/// `K v` with `K[a][b]`.
fn times(k: &[[f64; 2]; 2], v: [f64; 2]) -> [f64; 2] {
    [
        k[0][0] * v[0] + k[0][1] * v[1],
        k[1][0] * v[0] + k[1][1] * v[1],
    ]
}

/// `K^T v`.
fn times_t(k: &[[f64; 2]; 2], v: [f64; 2]) -> [f64; 2] {
    [
        k[0][0] * v[0] + k[1][0] * v[1],
        k[0][1] * v[0] + k[1][1] * v[1],
    ]
}

/// The coupling of one node against a free tool: the moment `r x f` of its
/// force about the current centre (the body's side: the tool receives the
/// opposite) and the tangent terms (`dR_theta/dx`, `dR_x/dtheta`,
/// `dR_theta/dtheta`; see the module notes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeCoupling {
    /// `r_a x f_a`.
    pub moment: f64,
    /// `d R_theta / d x_a`.
    pub row: [f64; 2],
    /// `d R_x_a / d theta`.
    pub column: [f64; 2],
    /// This node's share of `d R_theta / d theta`.
    pub diagonal: f64,
}

/// The coupling terms of node contact `nc` at current position `x` with
/// the tool's current centre `centre`.
pub fn node_coupling(nc: &NodeContact, x: [f64; 2], centre: [f64; 2]) -> NodeCoupling {
    let r = sub(x, centre);
    let f = nc.force;
    let k = &nc.stiffness;
    let jr = turn(r);
    let jf = turn(f);
    let kjr = times(k, jr);
    let ktjr = times_t(k, jr);
    NodeCoupling {
        moment: cross(r, f),
        row: [-ktjr[0] - jf[0], -ktjr[1] - jf[1]],
        column: [-jf[0] - kjr[0], -jf[1] - kjr[1]],
        diagonal: dot(f, r) + dot(jr, kjr),
    }
}

/// The current centre `c + u(t)` of free tool `tool`.
pub fn centre(model: &Model, tool: usize, t: f64) -> [f64; 2] {
    let m = &model.tools[tool].motion;
    [m.center[0] + m.ux.eval(t), m.center[1] + m.uy.eval(t)]
}

/// Adds the free tools' equations to the contact forces `f_c` (the moment
/// of the body's contact forces on the tool, on the pilot's x dof: `R =
/// ... - f_c`) and returns the coupling rows of the tangent (scattered
/// like mortar rows: pilot node and one slave node each, plus the pilot's
/// diagonal).
#[allow(clippy::too_many_arguments)]
pub fn assemble(
    model: &Model,
    dofs: &DofMap,
    pairs: &[PairState],
    contact: &[Vec<NodeContact>],
    x: &[[f64; 2]],
    t: f64,
    f_c: &mut [f64],
    rows: &mut Vec<Coupling>,
) {
    rows.clear();
    for (k, tool) in model.tools.iter().enumerate() {
        let Some(free) = &tool.free_rotation else {
            continue;
        };
        let p = free.node;
        let c = centre(model, k, t);
        let mut moment = 0.0;
        let mut diagonal = 0.0;
        let mut scale = 0.0;
        let mut secant = 0.0;
        let mut sticking = false;
        for (pair, list) in contact.iter().enumerate() {
            if free_master(model, pair).map(|m| m.0) != Some(k) {
                continue;
            }
            let cp = &model.contacts[pair];
            for nc in list {
                sticking |= nc.friction.status == FrictionStatus::Stick;
                if let (FrictionStatus::Slip, Some(law), Some(state)) =
                    (nc.friction.status, &cp.friction, pairs.get(pair))
                {
                    let tributary = state
                        .slave_index(nc.node)
                        .and_then(|i| state.tributary.get(i))
                        .copied()
                        .unwrap_or(0.0);
                    let alpha = tangential_stiffness(law, &cp.method_at(nc.node), tributary);
                    let tangent = [nc.normal[1], -nc.normal[0]];
                    if let Some(&xa) = x.get(nc.node) {
                        let s = dot(tangent, turn(sub(xa, c)));
                        secant += alpha * s * s;
                    }
                }
                let Some(&xa) = x.get(nc.node) else { continue };
                let nk = node_coupling(nc, xa, c);
                moment += nk.moment;
                diagonal += nk.diagonal;
                let r = sub(xa, c);
                scale += dot(r, r) * (nc.stiffness[0][0].abs() + nc.stiffness[1][1].abs());
                let a = nc.node;
                // nodes sorted: [a, p] or [p, a]; row-major 4 x 4
                let (ia, ip) = if a < p { (0, 1) } else { (1, 0) };
                let mut tangent = vec![0.0; 16];
                for i in 0..2 {
                    tangent[(2 * ia + i) * 4 + 2 * ip] = nk.column[i];
                    tangent[(2 * ip) * 4 + 2 * ia + i] = nk.row[i];
                }
                rows.push(Coupling {
                    nodes: if a < p { vec![a, p] } else { vec![p, a] },
                    force: vec![0.0; 4],
                    tangent,
                    slave: a,
                    gap_gradient: Vec::new(),
                    force_direction: Vec::new(),
                });
            }
        }
        f_c[dofs.dof(p, 0)] -= moment;
        let hold = if sticking { 0.0 } else { secant }
            + if scale > 0.0 {
                REGULARIZATION * scale
            } else {
                1.0
            };
        rows.push(Coupling {
            nodes: vec![p],
            force: vec![0.0; 2],
            tangent: vec![diagonal + hold, 0.0, 0.0, 0.0],
            slave: p,
            gap_gradient: Vec::new(),
            force_direction: Vec::new(),
        });
    }
}

/// What a free tool did in a converged increment (history and summary).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ToolRecord {
    /// Angle (radians, counter-clockwise) at the end of the increment.
    pub angle: f64,
    /// Mean angular velocity over the increment, `(theta - theta_0) / dt`.
    pub angular_velocity: f64,
    /// Net moment of the contact forces on the tool about its current
    /// centre.
    pub moment: f64,
    /// Applied moment `M(t)`.
    pub applied: f64,
    /// Balance `moment + applied` (zero at equilibrium up to the Newton
    /// tolerance).
    pub balance: f64,
}

/// The records of the free tools (tool order) between the committed
/// displacements `u0` and the converged `u` of an increment `(t - dt, t]`
/// (planar models; 3D models have no curve tools, so none).
pub fn records<const D: usize>(
    model: &Model<D>,
    u0: &[[f64; D]],
    u: &[[f64; D]],
    contact: &[Vec<NodeContact<D>>],
    t: f64,
    dt: f64,
) -> Vec<ToolRecord> {
    let mut out = Vec::new();
    if D != 2 {
        return out;
    }
    let at = |n: usize| -> [f64; 2] {
        match (model.mesh.nodes.get(n), u.get(n)) {
            (Some(p), Some(v)) => [p[0] + v[0], p[1] + v[1]],
            _ => [0.0; 2],
        }
    };
    for (k, tool) in model.tools.iter().enumerate() {
        let Some(free) = &tool.free_rotation else {
            continue;
        };
        let m = &tool.motion;
        let c = [m.center[0] + m.ux.eval(t), m.center[1] + m.uy.eval(t)];
        let mut moment = 0.0;
        for (cp, list) in model.contacts.iter().zip(contact) {
            if cp.master.tool() != Some(k) {
                continue;
            }
            for nc in list {
                moment -= cross(sub(at(nc.node), c), [nc.force[0], nc.force[1]]);
            }
        }
        let angle = u.get(free.node).map_or(0.0, |v| v[0]);
        let angle0 = u0.get(free.node).map_or(0.0, |v| v[0]);
        let applied = free.moment.eval(t);
        out.push(ToolRecord {
            angle,
            angular_velocity: if dt > 0.0 { (angle - angle0) / dt } else { 0.0 },
            moment,
            applied,
            balance: moment + applied,
        });
    }
    out
}

/// The history columns of the free tools, [`ToolRecord`] order.
pub fn columns<const D: usize>(model: &Model<D>) -> Vec<String> {
    let mut out = Vec::new();
    for t in model.tools.iter().filter(|t| t.free_rotation.is_some()) {
        for c in ["angle", "angular_velocity", "moment", "applied_moment"] {
            out.push(format!("{c}[{}]", t.name));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{evaluate_pair, PairState};
    use crate::mesh::{Cell, Mesh};
    use crate::model::{
        ContactMethod, FirstImpact, Friction, PenaltyKind, ToolGeometry, ToolMotion, ToolSide,
    };
    use crate::testkit::ModelBuilder;

    /// A 0.2 x 1 block whose bottom edge is pressed into a circle tool (radius 1,
    /// centre (0.02, -1)) with Coulomb friction, the tool free to turn.
    fn model(mu: Option<f64>) -> Model {
        let mut b = ModelBuilder::plane_strain()
            .elastic("steel", 1e3, 0.3)
            .body(
                "s",
                Mesh::new(
                    vec![[-0.1, 0.0], [0.1, 0.0], [0.1, 1.0], [-0.1, 1.0]],
                    vec![Cell::quad(0, 1, 2, 3)],
                ),
                "steel",
            )
            .tool(
                "roller",
                ToolGeometry::Circle {
                    center: [0.02, -1.0],
                    radius: 1.0,
                    side: ToolSide::Outside,
                },
                ToolMotion {
                    center: [0.02, -1.0],
                    ..ToolMotion::fixed()
                },
            )
            .contact_tool(
                "s -> roller",
                "s",
                vec![[0, 1]],
                "roller",
                ContactMethod::Penalty {
                    stiffness: 1e3,
                    kind: PenaltyKind::Nodal,
                },
            );
        if let Some(mu) = mu {
            b = b.friction(Friction {
                mu,
                stiffness: None,
                first_impact: FirstImpact::Intersect,
                cut_at_impact: false,
            });
        }
        let mut m = b.build();
        make_free(&mut m, 0, TimeFunction::Constant(0.3)).unwrap();
        m
    }

    /// Residual entries `-f_c` of the two slave nodes and the pilot, and
    /// the dense tangent over those 6 dofs, at displacements `u`.
    fn evaluate(m: &Model, state: &mut PairState, u: &[[f64; 2]]) -> (Vec<f64>, Vec<f64>) {
        let dofs = DofMap::new(m);
        let x: Vec<[f64; 2]> = m
            .mesh
            .nodes
            .iter()
            .zip(u)
            .map(|(p, v)| [p[0] + v[0], p[1] + v[1]])
            .collect();
        let mut states = vec![state.clone()];
        set_angles(m, u, &mut states);
        let list = evaluate_pair(m, 0, &x, 0.0, &mut states[0]);
        let pilot = m.tools[0].free_rotation.as_ref().unwrap().node;
        let mut f_c = vec![0.0; 2 * m.mesh.nodes.len()];
        for nc in &list {
            f_c[2 * nc.node] += nc.force[0];
            f_c[2 * nc.node + 1] += nc.force[1];
        }
        let mut rows = Vec::new();
        assemble(
            m,
            &dofs,
            &states,
            std::slice::from_ref(&list),
            &x,
            0.0,
            &mut f_c,
            &mut rows,
        );
        let idx = [0, 1, 2, 3, 2 * pilot, 2 * pilot + 1];
        let r: Vec<f64> = idx.iter().map(|&g| -f_c[g]).collect();
        let mut k = vec![0.0; 36];
        let pos = |g: usize| idx.iter().position(|&i| i == g);
        for nc in &list {
            for a in 0..2 {
                for b in 0..2 {
                    k[(2 * nc.node + a) * 6 + 2 * nc.node + b] += nc.stiffness[a][b];
                }
            }
        }
        for c in &rows {
            let n = 2 * c.nodes.len();
            for (i, &na) in c.nodes.iter().enumerate() {
                for (j, &nb) in c.nodes.iter().enumerate() {
                    for a in 0..2 {
                        for b in 0..2 {
                            let v = c.tangent[(2 * i + a) * n + 2 * j + b];
                            if let (Some(p), Some(q)) = (pos(2 * na + a), pos(2 * nb + b)) {
                                k[p * 6 + q] += v;
                            }
                        }
                    }
                }
            }
        }
        // the hold term is not part of the exact derivative
        let scale: f64 = list
            .iter()
            .map(|nc| {
                let r = sub(x[nc.node], centre(m, 0, 0.0));
                dot(r, r) * (nc.stiffness[0][0].abs() + nc.stiffness[1][1].abs())
            })
            .sum();
        let sticking = list
            .iter()
            .any(|nc| nc.friction.status == FrictionStatus::Stick);
        let secant: f64 = list
            .iter()
            .filter(|_| !sticking)
            .filter(|nc| nc.friction.status == FrictionStatus::Slip)
            .map(|nc| {
                let law = m.contacts[0].friction.as_ref().unwrap();
                let i = states[0].slave_index(nc.node).unwrap();
                let alpha =
                    tangential_stiffness(law, &m.contacts[0].method, states[0].tributary[i]);
                let t = [nc.normal[1], -nc.normal[0]];
                let s = dot(t, turn(sub(x[nc.node], centre(m, 0, 0.0))));
                alpha * s * s
            })
            .sum();
        k[4 * 6 + 4] -= secant
            + if scale > 0.0 {
                REGULARIZATION * scale
            } else {
                1.0
            };
        *state = states.pop().unwrap();
        STATUS.with(|st| {
            *st.borrow_mut() = list
                .iter()
                .map(|nc| (nc.status, nc.friction.status))
                .collect();
        });
        (r, k)
    }

    thread_local! {
        /// Contact and friction statuses of the last `evaluate`.
        static STATUS: std::cell::RefCell<Vec<(crate::contact::ContactStatus, FrictionStatus)>> =
            const { std::cell::RefCell::new(Vec::new()) };
    }

    /// Central differences of the residual over the 2 x 2 slave dofs and
    /// the angle against the assembled tangent: stick (small slide) and
    /// slip (large slide), frictionless; worst relative error printed.
    #[test]
    fn rotation_coupling_matches_central_differences() {
        let mut worst: f64 = 0.0;
        for (mu, slide) in [(None, 0.01), (Some(0.3), 1e-4), (Some(0.3), 0.2)] {
            let m = model(mu);
            let pilot = m.tools[0].free_rotation.as_ref().unwrap().node;
            // a converged-looking start: commit the friction state at rest
            let mut state = PairState::new(&m, 0);
            let mut u = vec![[0.0; 2]; m.mesh.nodes.len()];
            u[0] = [0.0, -0.02];
            u[1] = [0.0, -0.03];
            let _ = evaluate(&m, &mut state, &u);
            state.commit();
            u[0] = [slide, -0.025];
            u[1] = [slide * 0.7, -0.032];
            u[pilot][0] = 0.013;
            let (_, k) = evaluate(&m, &mut state.clone(), &u);
            let expected = match (mu, slide > 0.1) {
                (None, _) => FrictionStatus::Frictionless,
                (Some(_), false) => FrictionStatus::Stick,
                (Some(_), true) => FrictionStatus::Slip,
            };
            STATUS.with(|st| {
                let st = st.borrow();
                assert_eq!(st.len(), 2);
                for &(c, f) in st.iter() {
                    assert_eq!(c, crate::contact::ContactStatus::Closed);
                    assert_eq!(f, expected, "mu {mu:?} slide {slide}");
                }
            });
            let h = 1e-7;
            let dofs = [(0, 0), (0, 1), (1, 0), (1, 1), (pilot, 0)];
            let cols = [0, 1, 2, 3, 4];
            let norm = k.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            for (&(n, c), &col) in dofs.iter().zip(&cols) {
                let mut up = u.clone();
                up[n][c] += h;
                let mut dn = u.clone();
                dn[n][c] -= h;
                let (rp, _) = evaluate(&m, &mut state.clone(), &up);
                let (rm, _) = evaluate(&m, &mut state.clone(), &dn);
                for row in 0..5 {
                    let fd = (rp[row] - rm[row]) / (2.0 * h);
                    let err = (fd - k[row * 6 + col]).abs() / norm;
                    worst = worst.max(err);
                    assert!(
                        err < 1e-6,
                        "mu {mu:?} slide {slide}: dR{row}/du{col}: fd {fd:e}, tangent {:e}",
                        k[row * 6 + col]
                    );
                }
            }
        }
        eprintln!("free-rotation tangent vs central differences: worst relative error {worst:.2e}");
    }

    /// A frictionless circle: turning it changes nothing, so its row is
    /// zero and the moment of its normal forces vanishes.
    #[test]
    fn frictionless_circle_has_no_moment() {
        let m = model(None);
        let mut state = PairState::new(&m, 0);
        let mut u = vec![[0.0; 2]; m.mesh.nodes.len()];
        u[0] = [0.01, -0.02];
        u[1] = [0.0, -0.03];
        let (r, k) = evaluate(&m, &mut state, &u);
        // the residual of the angle is minus nothing but the applied moment
        // (added by the loads, not here)
        assert!(r[4].abs() < 1e-12, "{}", r[4]);
        assert!(k[4 * 6 + 4].abs() < 1e-9, "{}", k[4 * 6 + 4]);
    }
}
