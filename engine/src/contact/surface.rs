//! Contact of solid (3D) bodies with rigid surface tools: the slave nodes of
//! a face set against an exact surface of `ctc-geom` in its current
//! placement (seed slides, "Part I – Geometrical aspects" and "Rigid tool
//! defined by a CAD file"): an analytical surface (plane, sphere, cylinder,
//! cone, torus: closed-form projection), a triangulated surface (STL:
//! `ctc_geom::trimesh`, BVH search, pseudonormal sign) or CAD faces
//! (trimmed NURBS faces with holes from IGES: `ctc_geom::brep::BrepTool`,
//! Newton on the
//! foot-point equations seeded by each node's search memory, edges and
//! vertices as cylinders and spheres of radius 0).
//!
//! Each slave node is brought into the tool's reference frame, projected
//! there, and the projection is mapped back ([`ctc_geom::Placement`]). A
//! CAD projection that does not converge is not guessed: the node is left
//! out of the evaluation and the failure is returned (the run warns). The one projection gives the gap `g`, the
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
//! Lagrange: `-lambda W`); pressure `R_N / A`. A pair with Coulomb
//! friction adds the tangential force and its (non-symmetric) tangent of
//! [`super::friction_surface`] at every closed node (penalty, augmented
//! Lagrangian, and Lagrange multipliers: two tangential rows per sticking
//! node, [`SurfacePair::stick`], and the stick/slip status loop of
//! [`super::friction_lagrange`]).

use super::face_integrated::{self, FacetPair, FacetRule, PointProjection};
use super::friction::{FrictionState, NodeFriction};
use super::friction_surface::{self, StickRows, SurfaceContact};
use super::mortar::Coupling;
use super::node_to_facet::{self, DeformablePair};
use super::{ContactStatus, NodeContact};
use crate::mesh::{Facet, Mesh};
use crate::model::{
    ContactFormulation, ContactMaster, ContactMethod, ContactPair, Model, PenaltyKind,
    SurfaceMotion, SurfaceShape, SurfaceTool,
};
use ctc_geom::brep::{Counters, SearchState};
use ctc_geom::{Placement, Projection, ProjectionError, Vec3};

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
    /// Per slave node: the CAD search memory (face and parameter of the
    /// last foot; unused by analytical tools).
    pub search: Vec<SearchState>,
    /// Work of the projections since the start of the run (every
    /// evaluation, converged or not; analytical tools count queries only).
    pub counters: Counters,
    /// Evaluations of the pair since the start of the run.
    pub evaluations: u64,
    /// Friction history (stick points and shifts in the tool's reference
    /// frame; [`super::friction_surface`]).
    pub friction: FrictionState<3>,
    /// Per slave node at the last evaluation: the tangential constraint
    /// rows of a sticking node of a Lagrange pair with friction.
    pub stick: Vec<Option<StickRows>>,
    /// Deformable master (node-to-facet, [`super::node_to_facet`]): the
    /// two surfaces, the strategy state and the couplings of the latest
    /// evaluation; `None` against a surface tool.
    pub deformable: Option<DeformablePair>,
    /// Closed-gap start of node-to-facet pairs (as
    /// `crate::contact::PairState::touching` in 2D): slave nodes whose gap
    /// lies in `[0, touching]` count as closed with zero force; set by the
    /// solver for the first iteration of the analysis only, on
    /// frictionless pairs of bodies held only by contact (0: off).
    pub touching: f64,
    /// Quadratic slave faces: the face-integrated state
    /// ([`super::face_integrated`]: the gap at the faces' integration
    /// points); `None` on linear faces.
    pub facets: Option<FacetPair>,
    /// Face-integrated pairs: the CAD search memory of each integration
    /// point.
    pub point_search: Vec<SearchState>,
    /// Face-integrated pairs: the rows of the latest evaluation (one per
    /// face with a closed point), which the solver scatters instead of the
    /// nodal forces.
    pub couplings: Vec<Coupling>,
    /// Face-integrated pairs with friction: the points' responses at the
    /// latest evaluation (`node` is the point's index; the friction
    /// history `friction` is then per point), read by the Uzawa update.
    pub point_contact: Vec<NodeContact<3>>,
    /// Per slave node: its Lagrange row was redundant at the last
    /// evaluation (modified double pass, self contact:
    /// [`super::redundancy`]): active, without multiplier or force.
    pub redundant: Vec<bool>,
    /// Per slave node: switches of the semi-smooth active set in the
    /// current increment attempt ([`super::semismooth::MAX_SWITCHES`]:
    /// the cycle guard); cleared at commit and rollback.
    pub switches: Vec<u8>,
    committed_multiplier: Vec<f64>,
    committed_active: Vec<bool>,
    committed_search: Vec<SearchState>,
}

impl SurfacePair {
    /// The state of pair `pair` of `model` at the start of a run.
    pub fn new(model: &Model<3>, pair: usize) -> Self {
        let cp = &model.contacts[pair];
        // a deformable master: the double passes add its nodes as slaves
        let slaves = node_to_facet::slave_nodes(model, pair);
        let deformable = node_to_facet::prepare(model, pair, &slaves);
        let area = node_to_facet::areas(model, pair, &slaves);
        let prof = match cp.prof {
            Some(p) if p.is_finite() && p >= 0.0 => p,
            _ => match &cp.master {
                ContactMaster::Surface { faces, .. } => {
                    default_prof(&model.mesh, &cp.faces).max(default_prof(&model.mesh, faces))
                }
                ContactMaster::Tool(_) => default_prof(&model.mesh, &cp.faces),
            },
        };
        let n = slaves.len();
        // reference-frame positions at t = 0 (start of the first impact path)
        let start = cp
            .master
            .tool()
            .and_then(|i| model.surfaces.get(i))
            .map_or(Placement::identity(), |tool| placement(&tool.motion, 0.0));
        let positions = slaves
            .iter()
            .map(|&k| {
                let x = model.mesh.nodes.get(k).copied().unwrap_or([0.0; 3]);
                start.to_reference(&Vec3::from(x)).into()
            })
            .collect();
        // Lagrange multipliers: a node that overlaps the tool at the start
        // is in the active set from the first Newton loop on (a body held
        // only by that contact is then held from the start)
        let active: Vec<bool> = match cp.master.tool().and_then(|i| model.surfaces.get(i)) {
            Some(tool) if matches!(cp.method, ContactMethod::Lagrange { .. }) => cp
                .nodes
                .iter()
                .map(|&k| {
                    let x = model.mesh.nodes.get(k).copied().unwrap_or([0.0; 3]);
                    let mut search = SearchState::new();
                    search.reach = prof;
                    matches!(
                        project(tool, 0.0, &x, &mut search, &mut Counters::default()),
                        Ok(Some(p)) if p.gap < 0.0
                    )
                })
                .collect(),
            _ => vec![false; n],
        };
        // quadratic slave faces against the tool: integrated at points
        let facets = (cp.master.tool().is_some()
            && face_integrated::body_is_quadratic(model, cp.body))
        .then(|| {
            let rule = FacetRule::solid(
                &model.mesh.nodes,
                cp.faces.iter().map(|f| f.nodes().to_vec()).collect(),
            );
            FacetPair::new(rule, |node| {
                face_integrated::pressure_stiffness(&cp.method_at(node))
            })
        });
        // face-integrated friction: the history is per integration point
        let positions = match &facets {
            Some(fp) if cp.friction.is_some() => fp
                .point_positions(&model.mesh.nodes)
                .into_iter()
                .map(|x| start.to_reference(&Vec3::from(x)).into())
                .collect(),
            _ => positions,
        };
        SurfacePair {
            slaves,
            deformable,
            touching: 0.0,
            point_search: vec![
                SearchState::new();
                facets.as_ref().map_or(0, |f| f.rule.points.len())
            ],
            facets,
            couplings: Vec::new(),
            point_contact: Vec::new(),
            area,
            prof,
            multiplier: vec![0.0; n],
            committed_active: active.clone(),
            active,
            search: vec![SearchState::new(); n],
            counters: Counters::default(),
            evaluations: 0,
            friction: FrictionState::new(positions),
            stick: vec![None; n],
            committed_multiplier: vec![0.0; n],
            committed_search: vec![SearchState::new(); n],
            redundant: vec![false; n],
            switches: vec![0; n],
        }
    }

    /// Keeps the trial multipliers and active set (converged increment).
    pub fn commit(&mut self) {
        self.committed_multiplier.clone_from(&self.multiplier);
        self.committed_active.clone_from(&self.active);
        self.committed_search.clone_from(&self.search);
        self.switches.fill(0);
        self.friction.commit();
        if let Some(f) = &mut self.deformable {
            f.commit();
        }
        if let Some(fp) = &mut self.facets {
            fp.commit();
        }
    }

    /// Returns to the committed multipliers, active set and search memory.
    pub fn rollback(&mut self) {
        self.multiplier.clone_from(&self.committed_multiplier);
        self.active.clone_from(&self.committed_active);
        self.search.clone_from(&self.committed_search);
        self.switches.fill(0);
        self.friction.rollback();
        if let Some(f) = &mut self.deformable {
            f.rollback();
        }
        if let Some(fp) = &mut self.facets {
            fp.rollback();
        }
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

/// Search and projection figures of a pair against a surface tool over
/// the run (`summary.json`, `surface_search`): the health of the CAD
/// search (issue 17: projections per node, Newton iterations of the
/// projections, faces tested, projections that did not converge).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct SearchFigures {
    /// The pair's name.
    pub pair: String,
    /// The tool's name.
    pub tool: String,
    /// Evaluations of the pair (Newton iterations of every attempt).
    pub evaluations: u64,
    /// Node projections (queries).
    pub projections: u64,
    /// Projections per slave node and evaluation (nodes farther than the
    /// window are still projected: 1 for a tool near every node).
    pub projections_per_node: f64,
    /// Newton iterations of the surface and edge projections (0 for the
    /// closed forms of analytical tools).
    pub newton_iterations: u64,
    /// Newton iterations per projection.
    pub newton_per_projection: f64,
    /// CAD faces whose surface was projected on.
    pub faces_tested: u64,
    /// CAD faces skipped by their bounding box.
    pub faces_skipped: u64,
    /// Faces tested per projection.
    pub faces_per_projection: f64,
    /// Projections on boundary edges (radius-0 cylinders).
    pub edge_projections: u64,
    /// Rays of the trimming parity test.
    pub parity_rays: u64,
    /// Surface projections that did not converge (each a run warning when
    /// it left a node out).
    pub not_converged: u64,
}

impl SurfacePair {
    /// The search figures of this pair, named `pair` against `tool`.
    pub fn figures(&self, pair: &str, tool: &str) -> SearchFigures {
        let c = &self.counters;
        let per = |a: u64, b: u64| if b > 0 { a as f64 / b as f64 } else { 0.0 };
        SearchFigures {
            pair: pair.into(),
            tool: tool.into(),
            evaluations: self.evaluations,
            projections: c.queries,
            projections_per_node: per(c.queries, self.evaluations * self.slaves.len() as u64),
            newton_iterations: c.newton_iterations,
            newton_per_projection: per(c.newton_iterations, c.queries),
            faces_tested: c.faces_tested,
            faces_skipped: c.faces_skipped,
            faces_per_projection: per(c.faces_tested, c.queries),
            edge_projections: c.edge_projections,
            parity_rays: c.parity_rays,
            not_converged: c.not_converged,
        }
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
/// current frame; `Ok(None)` where no foot exists within reach or the
/// closest point is not unique (the centre of a sphere, the axis of a
/// cylinder: no normal exists there); an error when a CAD projection did
/// not converge. `search` is the node's CAD search memory (its `reach`
/// bounds the faces tested).
pub fn project(
    tool: &SurfaceTool,
    t: f64,
    x: &[f64; 3],
    search: &mut SearchState,
    counters: &mut Counters,
) -> Result<Option<Projection>, ProjectionError> {
    let p = placement(&tool.motion, t);
    let xr = p.to_reference(&Vec3::from(*x));
    let r = match &tool.geometry {
        SurfaceShape::Analytic(a) => {
            counters.queries += 1;
            a.project(&xr)
        }
        SurfaceShape::Brep(b) => b.project(&xr, search, counters),
        SurfaceShape::Mesh(m) => {
            counters.queries += 1;
            m.project(&xr)
        }
    };
    match r {
        Ok(pr) => Ok(Some(p.to_current(&pr))),
        Err(ProjectionError::Singular { .. } | ProjectionError::OutOfReach) => Ok(None),
        Err(e) => Err(e),
    }
}

/// The gap of the tool-frame point `xr` to `tool` (`None` where no foot is
/// found): the start of a first-impact path.
fn reference_gap(
    tool: &SurfaceTool,
    xr: &Vec3,
    search: &mut SearchState,
    counters: &mut Counters,
) -> Option<f64> {
    match &tool.geometry {
        SurfaceShape::Analytic(a) => a.project(xr),
        SurfaceShape::Brep(b) => b.project(xr, search, counters),
        SurfaceShape::Mesh(m) => m.project(xr),
    }
    .ok()
    .map(|p| p.gap)
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
/// order); the CAD projections that failed, by global node.
pub fn evaluate_pair(
    model: &Model<3>,
    pair: usize,
    x: &[[f64; 3]],
    t: f64,
    state: &mut SurfacePair,
) -> (Vec<NodeContact<3>>, Vec<(usize, ProjectionError)>) {
    let cp = &model.contacts[pair];
    let mut failed = Vec::new();
    if state.deformable.is_some() {
        if cp.formulation == ContactFormulation::Mortar {
            return (super::mortar::evaluate_3d(model, pair, x, state), failed);
        }
        return (node_to_facet::evaluate(model, pair, x, state), failed);
    }
    let Some(tool) = cp.master.tool().and_then(|i| model.surfaces.get(i)) else {
        return (Vec::new(), failed);
    };
    if state.facets.is_some() {
        return evaluate_facets(cp, tool, t, x, state);
    }
    let mut out = Vec::with_capacity(state.slaves.len());
    let placed = placement(&tool.motion, t);
    state.friction.impact = None;
    state.evaluations += 1;
    state.stick.iter_mut().for_each(|r| *r = None);
    for (i, &node) in state.slaves.iter().enumerate() {
        let xr = placed.to_reference(&Vec3::from(x[node]));
        // an active Lagrange node is projected whatever its distance
        state.search[i].reach = if state.active[i] {
            f64::INFINITY
        } else {
            state.prof
        };
        let p = match project(tool, t, &x[node], &mut state.search[i], &mut state.counters) {
            Ok(Some(p)) => p,
            Ok(None) => {
                state.friction.open(i, xr.into());
                continue;
            }
            Err(e) => {
                state.friction.open(i, xr.into());
                failed.push((node, e));
                continue;
            }
        };
        let active = state.active[i];
        if p.gap > state.prof && !active {
            state.friction.open(i, xr.into());
            continue;
        }
        let method = cp.method_at(node);
        let a = alpha(&method, state.area[i]);
        let rn = normal_force(&method, a, state.multiplier[i], active, p.gap);
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
            if let Some(law) = &cp.friction {
                let c = SurfaceContact {
                    placement: &placed,
                    x: Vec3::from(x[node]),
                    reference: xr,
                    projection: &p,
                    normal_force: rn,
                    normal_stiffness: a,
                    area: state.area[i],
                };
                let mut search = state.search[i];
                search.reach = f64::INFINITY;
                let mut counters = Counters::default();
                let start_gap = |x0: &Vec3| reference_gap(tool, x0, &mut search, &mut counters);
                nc.friction = friction_surface::respond(
                    law,
                    &method,
                    i,
                    &c,
                    start_gap,
                    &mut state.friction,
                    &mut nc.force,
                    &mut nc.stiffness,
                    &mut state.stick[i],
                );
            }
        } else {
            state.friction.open(i, xr.into());
        }
        out.push(nc);
    }
    (out, failed)
}

/// [`evaluate_pair`] of a face-integrated pair (quadratic slave faces,
/// [`super::face_integrated`]): fills `state.couplings` (the forces) and
/// returns one entry per slave node within the window or loaded by a face
/// (output: the node's gap, the pressure field there, its force).
fn evaluate_facets(
    cp: &ContactPair,
    tool: &SurfaceTool,
    t: f64,
    x: &[[f64; 3]],
    state: &mut SurfacePair,
) -> (Vec<NodeContact<3>>, Vec<(usize, ProjectionError)>) {
    let mut failed = Vec::new();
    let Some(mut fp) = state.facets.take() else {
        return (Vec::new(), failed);
    };
    state.evaluations += 1;
    let prof = state.prof;
    let placed = placement(&tool.motion, t);
    let law = cp.friction.as_ref();
    state.friction.impact = None;
    let np = fp.rule.points.len();
    let mut point_friction: Vec<Option<NodeFriction<3>>> =
        vec![None; if law.is_some() { np } else { 0 }];
    let mut point_contact = Vec::new();
    let (searches, counters, history) = (
        &mut state.point_search,
        &mut state.counters,
        &mut state.friction,
    );
    let mut point_failures = Vec::new();
    let mut project_point = |g: usize, xg: [f64; 3]| {
        searches[g].reach = prof;
        match project(tool, t, &xg, &mut searches[g], counters) {
            Ok(Some(p)) if p.gap <= prof => Some((
                PointProjection {
                    gap: p.gap,
                    normal: [p.normal[0], p.normal[1], p.normal[2]],
                    curvature: std::array::from_fn(|i| {
                        std::array::from_fn(|j| p.curvature[(i, j)])
                    }),
                },
                p,
            )),
            Ok(_) => None,
            Err(e) => {
                point_failures.push((g, e));
                None
            }
        }
    };
    let lagrange = matches!(cp.method, ContactMethod::Lagrange { .. });
    let couplings = if lagrange {
        // the multipliers of the active slave nodes, in the pair's order
        let multiplier: Vec<Option<f64>> = fp
            .nodes
            .iter()
            .map(|&n| {
                let i = state.slaves.binary_search(&n).ok()?;
                state
                    .active
                    .get(i)
                    .copied()
                    .unwrap_or(false)
                    .then(|| state.multiplier[i])
            })
            .collect();
        fp.evaluate_lagrange(x, prof, &multiplier, |g, xg| {
            project_point(g, xg).map(|p| p.0)
        })
    } else {
        fp.evaluate_with(x, 0.0, project_point, |load, ft, kt| {
            let Some(law) = law else {
                return false;
            };
            let g = load.point;
            let xr = placed.to_reference(&Vec3::from(load.x));
            let (Some((pr, p)), true) = (load.found, load.normal_force > 0.0) else {
                history.open(g, xr.into());
                return false;
            };
            let method = face_integrated::point_method(&cp.method, load.stiffness);
            let c = SurfaceContact {
                placement: &placed,
                x: Vec3::from(load.x),
                reference: xr,
                projection: p,
                normal_force: load.normal_force,
                normal_stiffness: load.normal_stiffness,
                area: load.weight,
            };
            let mut search = SearchState::new();
            search.reach = f64::INFINITY;
            let mut scratch = Counters::default();
            let start_gap = |x0: &Vec3| reference_gap(tool, x0, &mut search, &mut scratch);
            let mut rows = None;
            let nf = friction_surface::respond(
                law, &method, g, &c, start_gap, history, ft, kt, &mut rows,
            );
            point_friction[g] = Some(nf);
            point_contact.push(NodeContact {
                node: g,
                gap: pr.gap,
                normal: pr.normal,
                force: *ft,
                stiffness: *kt,
                pressure: load.normal_force / load.weight,
                status: ContactStatus::Closed,
                entity: p.entity,
                master: None,
                friction: nf,
            });
            true
        })
    };
    // a point whose CAD projection failed is reported at its facet's
    // first node
    for (g, e) in point_failures {
        let f = fp.rule.points[g].facet;
        failed.push((fp.rule.facets[f][0], e));
    }
    let mut out = Vec::with_capacity(state.slaves.len());
    for (i, &node) in state.slaves.iter().enumerate() {
        // a Lagrange node with a constraint is projected whatever its
        // distance (output: its normal)
        state.search[i].reach = if lagrange && fp.node_weighted_gap(node).is_finite() {
            f64::INFINITY
        } else {
            prof
        };
        let p = match project(tool, t, &x[node], &mut state.search[i], &mut state.counters) {
            Ok(Some(p)) => p,
            Ok(None) => continue,
            Err(e) => {
                failed.push((node, e));
                continue;
            }
        };
        let (force, stiffness) = FacetPair::node_force::<3>(&couplings, node);
        if lagrange {
            // the node's constraint: its weighted gap (no row: left out,
            // and released if active)
            let gap = fp.node_weighted_gap(node);
            if !gap.is_finite() {
                continue;
            }
            out.push(NodeContact {
                node,
                gap,
                normal: [p.normal[0], p.normal[1], p.normal[2]],
                force,
                stiffness,
                pressure: fp.node_pressure(node),
                status: if state.active[i] {
                    ContactStatus::Closed
                } else {
                    ContactStatus::Open
                },
                entity: p.entity,
                master: None,
                friction: NodeFriction::default(),
            });
            continue;
        }
        if p.gap > prof && force == [0.0; 3] {
            continue;
        }
        let pressure = fp.node_pressure(node);
        let mut friction = fp.node_friction(node, &point_friction);
        friction.tangential_force = Vec3::from(friction.traction).norm();
        out.push(NodeContact {
            node,
            gap: p.gap,
            normal: [p.normal[0], p.normal[1], p.normal[2]],
            force,
            stiffness,
            pressure,
            status: if pressure > 0.0 {
                ContactStatus::Closed
            } else {
                ContactStatus::Open
            },
            entity: p.entity,
            master: None,
            friction,
        });
    }
    state.couplings = couplings;
    state.point_contact = point_contact;
    state.facets = Some(fp);
    (out, failed)
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
        let ball = Analytic::Sphere(Sphere::new(Vec3::zeros(), 1.0, Side::Outside).unwrap());
        let mut motion = SurfaceMotion::fixed();
        motion.translation = translation.map(TimeFunction::Constant);
        model_with(method, ball, motion, None)
    }

    /// The triangle of [`model`] against `tool` in placement `motion`, with
    /// friction `friction`.
    fn model_with(
        method: ContactMethod,
        tool: Analytic,
        motion: SurfaceMotion,
        friction: Option<crate::model::Friction>,
    ) -> Model<3> {
        let mesh = Mesh::new(
            vec![[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]],
            vec![],
        );
        let mut m = crate::testkit::ModelBuilder::solid()
            .elastic("m", 1.0, 0.3)
            .body("b", mesh, "m")
            .build();
        m.surfaces.push(SurfaceTool {
            name: "ball".into(),
            geometry: tool.into(),
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
            friction,
            local_penalty: Vec::new(),
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
        let mut state = SurfacePair::new(&m, 0);
        let x = m.mesh.nodes.clone();
        let r = evaluate_pair(&m, 0, &x, 0.0, &mut state).0;
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
            let base = evaluate_pair(&m, 0, &x0, 0.0, &mut state).0;
            let h = 1e-6;
            for nc in base.iter().filter(|c| c.status == ContactStatus::Closed) {
                for b in 0..3 {
                    let f = |s: f64| {
                        let mut x = x0.clone();
                        x[nc.node][b] += s;
                        let r = evaluate_pair(&m, 0, &x, 0.0, &mut state.clone()).0;
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

        /// 3D Coulomb friction ([`super::friction_surface`]): the tangent of
        /// the frictional contact force (normal + tangential) is `-d f / d x`
        /// by central differences to a relative error of 1e-6 (of the
        /// largest entry), against a plane and a sphere placed by an
        /// arbitrary rotation and translation, in stick and in slip, for the
        /// penalty, the augmented Lagrangian (tangential shift) and Lagrange
        /// multipliers (stick: the multiplier vector, slip: `mu lambda_N`
        /// along its direction; and the two stick rows `t_k . g_T` against
        /// differences of `g_T`), with the stick point fixed or on the
        /// first-impact path.
        #[test]
        fn friction_tangent_matches_finite_differences(
            sphere in any::<bool>(), kind in 0usize..3, first in any::<bool>(),
            slipping in any::<bool>(),
            mu in 0.05f64..1.0, angle in -0.4f64..0.4,
            dx in -0.3f64..0.3, dy in -0.3f64..0.3, dz in 0.02f64..0.3,
            ax in -0.3f64..0.3, ay in -0.3f64..0.3,
            sx in -3.0f64..3.0, sy in -3.0f64..3.0, lambda in 0.0f64..3.0,
        ) {
            use crate::model::{FirstImpact, Friction};
            let augmented = kind == 1;
            let lagrange = kind == 2;
            let method = if lagrange {
                ContactMethod::Lagrange {
                    formulation: crate::model::LagrangeFormulation::Single,
                }
            } else if augmented {
                ContactMethod::AugmentedLagrange {
                    kind: PenaltyKind::Area,
                    penalty: 60.0,
                    tolerance: 1e-3,
                    update: crate::model::MultiplierUpdate::Converged,
                }
            } else {
                ContactMethod::Penalty { kind: PenaltyKind::Area, stiffness: 60.0 }
            };
            let tool = if sphere {
                Analytic::Sphere(Sphere::new(Vec3::zeros(), 1.0, Side::Outside).unwrap())
            } else {
                use ctc_geom::analytic::Plane;
                let n = Vec3::new(0.2, -0.1, 1.0);
                Analytic::Plane(Plane::new(Vec3::new(0.0, 0.0, 1.0), n, Side::Outside).unwrap())
            };
            let mut motion = SurfaceMotion::fixed();
            motion.translation = [dx, dy, dz].map(TimeFunction::Constant);
            motion.rotation = TimeFunction::Constant(angle);
            motion.axis = [0.3, 1.0, 0.5];
            motion.center = [0.1, 0.2, 0.3];
            let law = Friction {
                mu,
                stiffness: Some(25.0),
                first_impact: FirstImpact::Intersect,
                cut_at_impact: false,
            };
            let m = model_with(method, tool, motion, Some(law));
            let mut state = SurfacePair::new(&m, 0);
            state.multiplier = vec![lambda; 3];
            let x0 = m.mesh.nodes.clone();
            let p = placement(&m.surfaces[0].motion, 0.0);
            // node 0: stick point (tool frame) offset in the tangent plane, or
            // a first impact from a point above the tool
            let xr = p.to_reference(&Vec3::from(x0[0]));
            if first {
                state.friction.committed_position[0] = (xr + Vec3::new(ax, ay, 0.5)).into();
            } else {
                state.friction.committed_anchor[0] = Some((xr + Vec3::new(ax, ay, 0.0)).into());
                state.friction.base = state.friction.committed_anchor.clone();
            }
            if augmented || lagrange {
                state.friction.shift[0] = [sx, sy, 0.3 * sx];
            }
            if lagrange {
                state.active = vec![true; 3];
                state.friction.sliding[0] = if slipping { 1.0 } else { 0.0 };
                // slipping since an earlier increment (the force follows
                // the slip) or switched in this one (the kept direction)
                state.friction.committed_sliding[0] = if slipping && sy > 0.0 { 1.0 } else { 0.0 };
            }
            let eval = |x: &[[f64; 3]]| {
                let mut st = state.clone();
                let r = evaluate_pair(&m, 0, x, 0.0, &mut st).0;
                r.into_iter().find(|c| c.node == 0).map(|c| (c, st.stick[0]))
            };
            let eval_rows = |x: &[[f64; 3]]| eval(x).and_then(|r| r.1);
            let eval = |x: &[[f64; 3]]| eval(x).map(|r| r.0);
            let Some(nc) = eval(&x0) else { return Ok(()) };
            if nc.status != ContactStatus::Closed {
                return Ok(());
            }
            let kmax = nc.stiffness.iter().flatten().fold(0.0f64, |a, k| a.max(k.abs()));
            let h = 1e-6;
            for b in 0..3 {
                let f = |s: f64| {
                    let mut x = x0.clone();
                    x[0][b] += s;
                    eval(&x)
                };
                let (Some(fp), Some(fm)) = (f(h), f(-h)) else { continue };
                // skip points where the status changes within +-h
                if fp.status != nc.status || fm.status != nc.status
                    || fp.friction.status != nc.friction.status
                    || fm.friction.status != nc.friction.status
                {
                    continue;
                }
                for a in 0..3 {
                    let fd = -(fp.force[a] - fm.force[a]) / (2.0 * h);
                    prop_assert!((fd - nc.stiffness[a][b]).abs() <= 1e-6 * kmax.max(1.0),
                        "{:?} K[{a}][{b}] = {} vs {fd}", nc.friction.status, nc.stiffness[a][b]);
                }
                // stick rows: t_k . d g_T / d x_b, g_T rebuilt from the rows
                let q = *p.rotation.matrix();
                let gap_vector = |r: StickRows| {
                    (0..2).fold(Vec3::zeros(), |g, k| g + q * r.directions[k] * r.gaps[k])
                };
                let r0 = eval_rows(&x0);
                prop_assert_eq!(r0.is_some(), lagrange && !slipping);
                let rows_at = |s: f64| {
                    let mut x = x0.clone();
                    x[0][b] += s;
                    eval_rows(&x)
                };
                if let (Some(r0), Some(rp), Some(rm)) = (r0, rows_at(h), rows_at(-h)) {
                    let dg = (gap_vector(rp) - gap_vector(rm)) / (2.0 * h);
                    for k in 0..2 {
                        let fd = (q * r0.directions[k]).dot(&dg);
                        prop_assert!((fd - r0.gradients[k][b]).abs() <= 1e-6,
                            "row {k} column {b}: {} vs {fd}", r0.gradients[k][b]);
                    }
                }
            }
        }
    }

    /// A hex20 (quad8 top face), hex27 (quad9) or tet10 (tri6 face) cell
    /// whose face at `z = 1` (tet: `x + y + z = 1`) is the slave surface
    /// of a pair against `tool` with friction `law`.
    use super::super::friction::FrictionStatus;
    fn quadratic_model(
        kind: usize,
        method: ContactMethod,
        tool: Analytic,
        motion: SurfaceMotion,
        law: crate::model::Friction,
    ) -> Model<3> {
        use crate::mesh::{elevate::elevate, Cell, CellKind};
        let (linear, target) = if kind == 2 {
            let mut m = Mesh::new(
                vec![
                    [0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [0.0, 0.0, 1.0],
                ],
                vec![Cell::tet([0, 1, 2, 3])],
            );
            m.face_sets
                .insert("top".into(), vec![Facet::new(&[1, 2, 3])]);
            (m, CellKind::Tet10)
        } else {
            let mut m = Mesh::new(
                vec![
                    [0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [1.0, 1.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [0.0, 0.0, 1.0],
                    [1.0, 0.0, 1.0],
                    [1.0, 1.0, 1.0],
                    [0.0, 1.0, 1.0],
                ],
                vec![Cell::hex([0, 1, 2, 3, 4, 5, 6, 7])],
            );
            m.face_sets
                .insert("top".into(), vec![Facet::new(&[4, 5, 6, 7])]);
            (
                m,
                if kind == 0 {
                    CellKind::Hex20
                } else {
                    CellKind::Hex27
                },
            )
        };
        let mesh = elevate(&linear, target).unwrap();
        let faces = mesh.face_sets["top"].clone();
        let mut nodes: Vec<usize> = faces.iter().flat_map(|f| f.nodes().to_vec()).collect();
        nodes.sort_unstable();
        let mut m = crate::testkit::ModelBuilder::solid()
            .elastic("m", 1.0, 0.3)
            .body("b", mesh, "m")
            .build();
        m.surfaces.push(SurfaceTool {
            name: "tool".into(),
            geometry: tool.into(),
            motion,
        });
        m.contacts.push(ContactPair {
            name: "b.top -> tool".into(),
            body: 0,
            edges: vec![],
            faces,
            nodes,
            master: ContactMaster::Tool(0),
            strategy: Default::default(),
            search: Default::default(),
            formulation: Default::default(),
            smoothing: Default::default(),
            method,
            prof: Some(10.0),
            friction: Some(law),
            local_penalty: Vec::new(),
        });
        m
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(16))]

        /// Friction on quadratic faces (face-integrated, one stick point
        /// per integration point): the rows' tangent is minus the
        /// derivative of their forces (central differences) for tri6,
        /// quad8 and quad9 faces against a sphere or an inclined plane,
        /// penalty and augmented Lagrangian (tangential shifts), stick
        /// points offset in the tangent plane (a mix of stick and slip) or
        /// on the first-impact path.
        #[test]
        fn quadratic_face_friction_tangent_matches_finite_differences(
            kind in 0usize..3, sphere in any::<bool>(), augmented in any::<bool>(),
            first in any::<bool>(), mu in 0.05f64..1.0, dz in 0.02f64..0.2,
            offsets in proptest::collection::vec(-0.05f64..0.05, 54),
            shift in proptest::collection::vec(-0.05f64..0.05, 27),
        ) {
            use crate::model::{FirstImpact, Friction};
            let method = if augmented {
                ContactMethod::AugmentedLagrange {
                    kind: PenaltyKind::Area,
                    penalty: 60.0,
                    tolerance: 1e-3,
                    update: crate::model::MultiplierUpdate::Converged,
                }
            } else {
                ContactMethod::Penalty { kind: PenaltyKind::Area, stiffness: 60.0 }
            };
            let tool = if sphere {
                Analytic::Sphere(Sphere::new(Vec3::new(0.4, 0.3, -0.3), 1.0, Side::Outside)
                    .unwrap())
            } else {
                use ctc_geom::analytic::Plane;
                let n = Vec3::new(0.2, -0.1, 1.0);
                Analytic::Plane(Plane::new(Vec3::new(0.0, 0.0, 0.75), n, Side::Outside)
                    .unwrap())
            };
            let mut motion = SurfaceMotion::fixed();
            motion.translation = [0.0, 0.0, dz].map(TimeFunction::Constant);
            let law = Friction {
                mu,
                stiffness: Some(25.0),
                first_impact: FirstImpact::Intersect,
                cut_at_impact: false,
            };
            let m = quadratic_model(kind, method, tool, motion, law);
            let mut state = SurfacePair::new(&m, 0);
            let np = state.facets.as_ref().unwrap().rule.points.len();
            prop_assert_eq!(state.friction.committed_anchor.len(), np);
            for g in 0..np {
                let xr = Vec3::from(state.friction.committed_position[g]);
                let o = Vec3::new(offsets[(2 * g) % 54], offsets[(2 * g + 1) % 54], 0.0);
                if first {
                    state.friction.committed_position[g] = (xr + o + Vec3::new(0.0, 0.0, 0.5)).into();
                } else {
                    state.friction.committed_anchor[g] = Some((xr + o).into());
                }
                if augmented {
                    state.friction.shift[g] = [shift[g % 27], shift[(g + 7) % 27], 0.0];
                    state.facets.as_mut().unwrap().multiplier[g] = 0.5 + shift[(g + 3) % 27];
                }
            }
            state.friction.base = state.friction.committed_anchor.clone();
            let x0 = m.mesh.nodes.clone();
            let nn = x0.len();
            let forces = |x: &[[f64; 3]]| {
                let mut st = state.clone();
                let r = evaluate_pair(&m, 0, x, 0.0, &mut st).0;
                let mut f = vec![0.0; 3 * nn];
                for c in &st.couplings {
                    for (a, &node) in c.nodes.iter().enumerate() {
                        for i in 0..3 { f[3 * node + i] += c.force[3 * a + i]; }
                    }
                }
                let status: Vec<_> = st.point_contact.iter()
                    .map(|c| (c.node, c.friction.status)).collect();
                (f, st.couplings, status, r)
            };
            let (_, couplings, status, out) = forces(&x0);
            prop_assume!(!couplings.is_empty());
            // the nodes' tangential forces sum to the points'
            let mut k = vec![0.0; 9 * nn * nn];
            for c in &couplings {
                let nd = 3 * c.nodes.len();
                for (a, &na) in c.nodes.iter().enumerate() {
                    for (b, &nb) in c.nodes.iter().enumerate() {
                        for i in 0..3 {
                            for j in 0..3 {
                                k[(3 * na + i) * 3 * nn + 3 * nb + j] +=
                                    c.tangent[(3 * a + i) * nd + 3 * b + j];
                            }
                        }
                    }
                }
            }
            let scale = k.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let h = 1e-6;
            let nodes = &m.contacts[0].nodes;
            // the friction acts: some point rubs, the nodes carry it
            prop_assert!(status.iter().any(|s| s.1 != FrictionStatus::Frictionless));
            prop_assert!(out.iter().any(|c| c.friction.traction != [0.0; 3]));
            let mut compared = 0;
            for &nb in nodes {
                for j in 0..3 {
                    let (mut xp, mut xm) = (x0.clone(), x0.clone());
                    xp[nb][j] += h;
                    xm[nb][j] -= h;
                    let (fp, _, sp, _) = forces(&xp);
                    let (fm, _, sm, _) = forces(&xm);
                    // skip where a point changes status within +-h
                    if sp != status || sm != status {
                        continue;
                    }
                    compared += 1;
                    for &na in nodes {
                        for i in 0..3 {
                            let fd = -(fp[3 * na + i] - fm[3 * na + i]) / (2.0 * h);
                            let kk = k[(3 * na + i) * 3 * nn + 3 * nb + j];
                            prop_assert!((fd - kk).abs() <= 1e-6 * scale.max(1.0),
                                "K[{na}{i}][{nb}{j}] = {kk} vs {fd} ({status:?})");
                        }
                    }
                }
            }
            prop_assert!(compared > 0);
        }
    }
}
