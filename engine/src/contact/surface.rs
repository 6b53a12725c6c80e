//! Contact of solid (3D) bodies with rigid surface tools: the slave nodes of
//! a face set against an analytical surface of `ctc-geom` (plane, sphere,
//! cylinder, cone, torus) in its current placement (seed slides, "Part I –
//! Geometrical aspects" and "Rigid tool defined by a CAD file").
//!
//! Each slave node is brought into the tool's reference frame, projected
//! there in closed form, and the projection is mapped back
//! ([`ctc_geom::Placement`]). The one projection gives the gap `g`, the
//! unit normal `n = dg/dx` into free space and the curvature `W = dn/dx`
//! (symmetric, `W n = 0`): the same function decides contact, gives the
//! force and the tangent, and is written as output.
//!
//! Per slave node, with the tributary area `A = int N_a dA` over the slave
//! faces (reference configuration) and the normal force `R_N >= 0`:
//!
//! - penalty: `R_N = -alpha g` where `g < 0` (`alpha = k` nodal, `k A`
//!   area);
//! - augmented Lagrangian: `R_N = max(0, lambda* - alpha g)`;
//! - Lagrange multipliers: `R_N = lambda` on the active set, constraint row
//!   `dg/dx = n`.
//!
//! Force of the tool on the node `f = R_N n`; tangent
//! `K = -df/dx = alpha n ⊗ n - R_N W` (penalty: `alpha (n ⊗ n + g W)`,
//! Lagrange: `-lambda W`); pressure `R_N / A`.

use super::{ContactStatus, NodeContact};
use crate::mesh::{Facet, Mesh};
use crate::model::{ContactMethod, Model, PenaltyKind, SurfaceMotion, SurfaceTool};
use ctc_geom::{Placement, Projection, Vec3};

/// Contact state of one pair against a surface tool: slave nodes, their
/// tributary areas, the search window, and the multipliers and active set
/// of the Lagrange and augmented-Lagrangian methods (trial and committed).
#[derive(Debug, Clone)]
pub struct SurfacePair {
    /// Slave nodes (`ContactPair::nodes`).
    pub slaves: Vec<usize>,
    /// Tributary area of each slave node (reference configuration).
    pub area: Vec<f64>,
    /// Search window `prof`: nodes farther than this from the tool (and
    /// not in the active set) are not evaluated.
    pub prof: f64,
    /// Per slave node: `lambda` (Lagrange) or `lambda*` (augmented
    /// Lagrangian), force units.
    pub multiplier: Vec<f64>,
    /// Per slave node: in the Lagrange active set.
    pub active: Vec<bool>,
    committed_multiplier: Vec<f64>,
    committed_active: Vec<bool>,
}

impl SurfacePair {
    /// The state of pair `pair` of `model` at the start of a run.
    pub fn new(model: &Model<3>, pair: usize) -> Self {
        let cp = &model.contacts[pair];
        let area = tributary_areas(&model.mesh, &cp.faces, &cp.nodes);
        let prof = match cp.prof {
            Some(p) if p.is_finite() && p >= 0.0 => p,
            _ => default_prof(&model.mesh, &cp.faces),
        };
        let n = cp.nodes.len();
        SurfacePair {
            slaves: cp.nodes.clone(),
            area,
            prof,
            multiplier: vec![0.0; n],
            active: vec![false; n],
            committed_multiplier: vec![0.0; n],
            committed_active: vec![false; n],
        }
    }

    /// Keeps the trial multipliers and active set (converged increment).
    pub fn commit(&mut self) {
        self.committed_multiplier.clone_from(&self.multiplier);
        self.committed_active.clone_from(&self.active);
    }

    /// Returns to the committed multipliers and active set.
    pub fn rollback(&mut self) {
        self.multiplier.clone_from(&self.committed_multiplier);
        self.active.clone_from(&self.committed_active);
    }

    /// The committed multipliers and active set (restart points).
    pub fn committed(&self) -> (&[f64], &[bool]) {
        (&self.committed_multiplier, &self.committed_active)
    }

    /// Sets the committed multipliers and active set (restart points) and
    /// rolls back to them.
    pub fn restore(&mut self, multiplier: &[f64], active: &[bool]) {
        self.committed_multiplier = multiplier.to_vec();
        self.committed_active = active.to_vec();
        self.rollback();
    }

    /// Index of global node `node` among the slaves.
    pub fn slave_index(&self, node: usize) -> Option<usize> {
        self.slaves.binary_search(&node).ok()
    }
}

/// The placement of a tool of motion `motion` at time `t`.
pub fn placement(motion: &SurfaceMotion, t: f64) -> Placement {
    let u = Vec3::from_fn(|k, _| motion.translation[k].eval(t));
    let c = Vec3::from(motion.center);
    Placement::about_axis(Vec3::from(motion.axis), motion.rotation.eval(t), c, u)
        .unwrap_or_else(|| Placement::translation(u))
}

/// The projection of the current point `x` on `tool` at time `t`, in the
/// current frame; `None` where the closest point is not unique (the centre
/// of a sphere, the axis of a cylinder: no normal exists there).
pub fn project(tool: &SurfaceTool, t: f64, x: &[f64; 3]) -> Option<Projection> {
    let p = placement(&tool.motion, t);
    let xr = p.to_reference(&Vec3::from(*x));
    tool.geometry.project(&xr).ok().map(|pr| p.to_current(&pr))
}

/// Tributary area `int N_a dA` of each node of `nodes` (sorted) over the
/// faces `faces` of `mesh` (reference configuration): a third of the area
/// of a triangle, 2x2 Gauss points on a bilinear quadrilateral (a quarter
/// of a parallelogram's area). Zero for a node on no face.
pub fn tributary_areas(mesh: &Mesh<3>, faces: &[Facet], nodes: &[usize]) -> Vec<f64> {
    use crate::element::reference::{Quad4, ReferenceCell, Tri3};
    fn add<const NN: usize, C: ReferenceCell<2, NN>>(
        mesh: &Mesh<3>,
        face: &[usize],
        nodes: &[usize],
        area: &mut [f64],
    ) {
        for (xi, w) in C::QUADRATURE {
            let (n, g) = (C::shape(xi), C::gradients(xi));
            let (mut t1, mut t2) = (Vec3::zeros(), Vec3::zeros());
            for (a, &node) in face.iter().enumerate() {
                let x = Vec3::from(mesh.nodes[node]);
                t1 += x * g[a][0];
                t2 += x * g[a][1];
            }
            let da = t1.cross(&t2).norm() * w;
            for (a, node) in face.iter().enumerate() {
                if let Ok(i) = nodes.binary_search(node) {
                    area[i] += n[a] * da;
                }
            }
        }
    }
    let mut area = vec![0.0; nodes.len()];
    for f in faces {
        match f.nodes().len() {
            3 => add::<3, Tri3>(mesh, f.nodes(), nodes, &mut area),
            4 => add::<4, Quad4>(mesh, f.nodes(), nodes, &mut area),
            _ => {}
        }
    }
    area
}

/// Default search window: the longest edge of the slave faces
/// (reference configuration), as in 2D ([`super::prof`]).
pub fn default_prof(mesh: &Mesh<3>, faces: &[Facet]) -> f64 {
    let mut h: f64 = 0.0;
    for f in faces {
        let n = f.nodes();
        for (k, &a) in n.iter().enumerate() {
            let b = n[(k + 1) % n.len()];
            h = h.max((Vec3::from(mesh.nodes[a]) - Vec3::from(mesh.nodes[b])).norm());
        }
    }
    h
}

/// Penalty coefficient (force per unit gap) of a node of tributary area
/// `area` for `method`; 0 for Lagrange multipliers.
pub fn alpha(method: &ContactMethod, area: f64) -> f64 {
    match method {
        ContactMethod::Penalty { kind, stiffness }
        | ContactMethod::AugmentedLagrange {
            kind,
            penalty: stiffness,
            ..
        } => match kind {
            PenaltyKind::Nodal => *stiffness,
            PenaltyKind::Area => *stiffness * area,
        },
        ContactMethod::Lagrange { .. } => 0.0,
    }
}

/// The normal force `R_N` of a node of gap `gap` for `method`, with
/// penalty `alpha`, multiplier `multiplier` and active flag `active`
/// (Lagrange: `lambda` on the active set, even if momentarily negative;
/// the active-set loop then releases the node).
pub fn normal_force(
    method: &ContactMethod,
    alpha: f64,
    multiplier: f64,
    active: bool,
    gap: f64,
) -> Option<f64> {
    match method {
        ContactMethod::Penalty { .. } => (gap < 0.0).then_some(-alpha * gap),
        ContactMethod::AugmentedLagrange { .. } => {
            let rn = multiplier - alpha * gap;
            (rn > 0.0).then_some(rn)
        }
        ContactMethod::Lagrange { .. } => active.then_some(multiplier),
    }
}

/// Evaluates the slave nodes of pair `pair` at current coordinates `x` and
/// time `t` (one entry per node within the window or active, in slave
/// order).
pub fn evaluate_pair(
    model: &Model<3>,
    pair: usize,
    x: &[[f64; 3]],
    t: f64,
    state: &SurfacePair,
) -> Vec<NodeContact<3>> {
    let cp = &model.contacts[pair];
    let Some(tool) = cp.master.tool().and_then(|i| model.surfaces.get(i)) else {
        return Vec::new();
    };
    let mut out = Vec::with_capacity(state.slaves.len());
    for (i, &node) in state.slaves.iter().enumerate() {
        let Some(p) = project(tool, t, &x[node]) else {
            continue;
        };
        let active = state.active[i];
        if p.gap > state.prof && !active {
            continue;
        }
        let a = alpha(&cp.method, state.area[i]);
        let rn = normal_force(&cp.method, a, state.multiplier[i], active, p.gap);
        let n = p.normal;
        let mut nc = NodeContact {
            node,
            gap: p.gap,
            normal: [n[0], n[1], n[2]],
            force: [0.0; 3],
            stiffness: [[0.0; 3]; 3],
            pressure: 0.0,
            status: ContactStatus::Open,
            entity: p.entity,
            master: None,
            friction: Default::default(),
        };
        if let Some(rn) = rn {
            let k = n * n.transpose() * a - p.curvature * rn;
            for r in 0..3 {
                nc.force[r] = rn * n[r];
                for c in 0..3 {
                    nc.stiffness[r][c] = k[(r, c)];
                }
            }
            nc.pressure = if state.area[i] > 0.0 {
                rn / state.area[i]
            } else {
                0.0
            };
            nc.status = ContactStatus::Closed;
        }
        out.push(nc);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{ContactMaster, ContactPair, TimeFunction};
    use ctc_geom::analytic::{Analytic, Sphere};
    use ctc_geom::Side;
    use proptest::prelude::*;

    /// One slave node (a single triangle face) against a rigid sphere of
    /// radius 1 at the origin, moved by `translation`.
    fn model(method: ContactMethod, translation: [f64; 3]) -> Model<3> {
        let mesh = Mesh::new(
            vec![[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]],
            vec![],
        );
        let mut m = crate::testkit::ModelBuilder::solid()
            .elastic("m", 1.0, 0.3)
            .body("b", mesh, "m")
            .build();
        let mut motion = SurfaceMotion::fixed();
        motion.translation = translation.map(TimeFunction::Constant);
        m.surfaces.push(SurfaceTool {
            name: "ball".into(),
            geometry: Analytic::Sphere(Sphere::new(Vec3::zeros(), 1.0, Side::Outside).unwrap()),
            motion,
        });
        m.contacts.push(ContactPair {
            name: "b.top -> ball".into(),
            body: 0,
            edges: vec![],
            faces: vec![Facet::new(&[0, 1, 2])],
            nodes: vec![0, 1, 2],
            master: ContactMaster::Tool(0),
            strategy: Default::default(),
            search: Default::default(),
            formulation: Default::default(),
            smoothing: Default::default(),
            method,
            prof: Some(10.0),
            friction: None,
        });
        m
    }

    #[test]
    fn tributary_areas_of_a_triangle_and_a_quad_sum_to_their_areas() {
        let mesh = Mesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [2.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
                [3.0, 0.0, 0.0],
            ],
            vec![],
        );
        let faces = [Facet::new(&[0, 1, 2, 3]), Facet::new(&[1, 4, 2])];
        let a = tributary_areas(&mesh, &faces, &[0, 1, 2, 3, 4]);
        let want = [0.5, 0.5 + 0.5 / 3.0, 0.5 + 0.5 / 3.0, 0.5, 0.5 / 3.0];
        for (a, w) in a.iter().zip(want) {
            assert!((a - w).abs() < 1e-15, "{a} vs {w}");
        }
        assert_eq!(default_prof(&mesh, &faces), 1.0f64.hypot(1.0).max(2.0));
    }

    #[test]
    fn penalty_force_pushes_a_penetrating_node_out_along_the_normal() {
        // sphere moved up by 0.1: node 0 at (0, 0, 1) penetrates by 0.1
        let m = model(
            ContactMethod::Penalty {
                kind: PenaltyKind::Nodal,
                stiffness: 100.0,
            },
            [0.0, 0.0, 0.1],
        );
        let state = SurfacePair::new(&m, 0);
        let x = m.mesh.nodes.clone();
        let r = evaluate_pair(&m, 0, &x, 0.0, &state);
        let n0 = r.iter().find(|c| c.node == 0).unwrap();
        assert!((n0.gap + 0.1).abs() < 1e-14);
        assert_eq!(n0.status, ContactStatus::Closed);
        assert!((n0.force[2] - 10.0).abs() < 1e-12 && n0.force[0].abs() < 1e-14);
        // the other two nodes are outside the moved sphere: open, no force
        assert!(r
            .iter()
            .filter(|c| c.node != 0)
            .all(|c| c.status == ContactStatus::Open && c.force == [0.0; 3]));
    }

    proptest! {
        /// The contact tangent is `-d f / d x` (central differences), for
        /// penalty and augmented Lagrangian, at nodes near a sphere moved
        /// arbitrarily, and it is symmetric.
        #[test]
        fn tangent_matches_finite_differences_of_the_force(
            dx in -0.3f64..0.3, dy in -0.3f64..0.3, dz in 0.05f64..0.4,
            lambda in 0.0f64..5.0, augmented in any::<bool>(),
        ) {
            let method = if augmented {
                ContactMethod::AugmentedLagrange {
                    kind: PenaltyKind::Area,
                    penalty: 30.0,
                    tolerance: 1e-3,
                    update: crate::model::MultiplierUpdate::Converged,
                }
            } else {
                ContactMethod::Penalty { kind: PenaltyKind::Area, stiffness: 30.0 }
            };
            let m = model(method, [dx, dy, dz]);
            let mut state = SurfacePair::new(&m, 0);
            state.multiplier = vec![lambda; 3];
            let x0 = m.mesh.nodes.clone();
            let base = evaluate_pair(&m, 0, &x0, 0.0, &state);
            let h = 1e-6;
            for nc in base.iter().filter(|c| c.status == ContactStatus::Closed) {
                for b in 0..3 {
                    let f = |s: f64| {
                        let mut x = x0.clone();
                        x[nc.node][b] += s;
                        let r = evaluate_pair(&m, 0, &x, 0.0, &state);
                        r.iter().find(|c| c.node == nc.node).unwrap().force
                    };
                    let (fp, fm) = (f(h), f(-h));
                    // skip points where the status changes within +-h
                    if (fp == [0.0; 3]) != (fm == [0.0; 3]) {
                        continue;
                    }
                    for a in 0..3 {
                        let fd = -(fp[a] - fm[a]) / (2.0 * h);
                        prop_assert!((fd - nc.stiffness[a][b]).abs() < 1e-5 * (1.0 + fd.abs()),
                            "K[{a}][{b}] = {} vs {fd}", nc.stiffness[a][b]);
                        prop_assert!((nc.stiffness[a][b] - nc.stiffness[b][a]).abs() < 1e-12);
                    }
                }
            }
        }
    }
}
