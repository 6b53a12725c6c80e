//! Contact between deformable bodies and rigid analytical tools.
//!
//! The solver calls [`evaluate_pair`] at every Newton iteration with the
//! current nodal coordinates; each active slave node returns its gap, the
//! force the tool exerts on it and the consistent 2x2 tangent block.
//! The same gap function is used to decide contact, to compute forces and to
//! post-process pressure.
//!
//! Pieces (one concept per file):
//! - [`geometry`]: tool entities in the tool's reference frame (plane,
//!   polyline, arc, circle, NURBS), closest-point projection, signed gap,
//!   normal and normal rate (curvature) for the consistent tangent;
//! - [`motion`]: the tool's rigid placement at time `t`;
//! - [`aabb`] and [`search`]: bounding boxes and the memory-first search
//!   with the window `prof` ([`prof`]);
//! - [`penalty`]: force and consistent tangent;
//! - [`lagrange`], [`augmented`]: Lagrange multipliers (exact, active set)
//!   and augmented Lagrangian (penalty with a multiplier shift, Uzawa);
//!   [`rows`]: Lagrange constraint rows in node terms (the solver maps
//!   them to dofs); [`redundancy`]: the redundant rows of the modified
//!   double pass and self contact;
//! - [`tributary`]: tributary areas of slave nodes;
//! - [`friction`], [`friction_lagrange`], [`impact`]: Coulomb friction
//!   (return map, Lagrange stick/slip status loop) and the first impact
//!   (constant-velocity intersection);
//! - [`segment_search`]: candidate master segments of a deformable surface
//!   (broad phase + memory or circle local test);
//! - [`jump`]: slave nodes that moved farther than `prof` relative to the
//!   master in one increment (run warnings);
//! - [`segment`], [`node_to_segment`]: deformable masters (node-to-segment
//!   elements, single / double / modified double pass, self contact);
//!   [`node_to_facet`]: the 3D form (tri3 / quad4 master facets);
//!   [`smoothing`]: the nodal normal field of `smoothing = nodal`;
//!   [`nagata`]: Nagata patches on 3D master facets (`smoothing = nagata`),
//!   [`friction_nagata`] their Coulomb friction; [`symmetry`]: the
//!   symmetry planes and the axis their nodal normals are mirrored at;
//! - [`mortar`]: mortar segment-to-segment contact (weighted gaps, `D`
//!   and `M`, segmentation; penalty and augmented Lagrangian);
//! - [`face_integrated`]: quadratic slave faces against rigid tools (the
//!   gap at the faces' integration points; penalty and augmented
//!   Lagrangian);
//! - [`log`]: `CTC_LOG=debug` diagnostics on stderr.

pub mod augmented;
pub mod broad;
pub mod face_integrated;
pub mod friction;
pub mod friction_facet;
pub mod friction_lagrange;
pub mod friction_nagata;
pub mod friction_segment;
pub mod friction_surface;
pub mod geometry;
pub mod impact;
pub mod jump;
pub mod lagrange;
pub mod log;
pub mod mortar;
pub mod motion;
pub mod nagata;
pub mod node_to_facet;
pub mod node_to_segment;
pub mod penalty;
pub mod prof;
pub mod redundancy;
pub mod rows;
pub mod search;
pub mod segment;
pub mod segment_search;
pub mod semismooth;
pub mod smoothing;
pub mod surface;
pub mod symmetry;
pub mod tributary;
pub(crate) mod vec2;

use crate::model::{ContactFormulation, ContactMaster, ContactMethod, Model, NormalSmoothing};
use geometry::ToolShape;
use motion::Placement;

/// Contact status of a slave node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactStatus {
    /// Within `prof` of the tool but with a positive gap.
    Open,
    /// Negative gap: a contact force acts.
    Closed,
}

/// Evaluation of one slave node against the pair's master, in dimension
/// `D` (`NodeContact` without a parameter is the planar one).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeContact<const D: usize = 2> {
    /// Global node number.
    pub node: usize,
    /// Signed normal gap (negative = penetration).
    pub gap: f64,
    /// Unit outward normal of the tool at the projection (points to free space).
    pub normal: [f64; D],
    /// Force exerted by the tool on the node (total, axisymmetric: over 2*pi).
    pub force: [f64; D],
    /// Tangent block `K_c = -d force / d x` (add to the global stiffness),
    /// `stiffness[a][b] = -d force_a / d x_b`.
    pub stiffness: [[f64; D]; D],
    /// Contact pressure: normal force magnitude / tributary area (>= 0).
    pub pressure: f64,
    /// Open or closed.
    pub status: ContactStatus,
    /// Index of the tool entity (segment, span) the node projects on.
    pub entity: usize,
    /// Deformable master (node-to-segment, planar models): the segment's
    /// nodes and the coupling terms. `None` against a rigid tool (then
    /// `force` and `stiffness` are the whole contribution), and always in
    /// 3D.
    pub master: Option<MasterSegment>,
    /// Tangential (friction) part: status, tangential force (included in
    /// `force`), slip increment and dissipated work of the increment
    /// (planar rigid and deformable masters; 3D surface tools).
    pub friction: friction::NodeFriction<D>,
}

/// Master side of a node-to-segment contact element. Local dof order of
/// the 6-vectors and 6x6 blocks: `[slave x, slave y, m1 x, m1 y, m2 x, m2 y]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MasterSegment {
    /// Global node numbers of the segment ends `m1 -> m2`.
    pub nodes: [usize; 2],
    /// Projection parameter of the slave node on the segment, in `[0, 1]`
    /// (0 at `m1`).
    pub xi: f64,
    /// Forces exerted on `m1` and `m2` (with `NodeContact::force` they sum
    /// to zero, and so does their moment).
    pub forces: [[f64; 2]; 2],
    /// Full tangent `-d f / d x` of the element (its slave-slave block
    /// equals `NodeContact::stiffness`).
    pub tangent: [[f64; 6]; 6],
    /// `d g / d x` over the element dofs (the Lagrange constraint row).
    pub gap_gradient: [f64; 6],
}

/// Persistent per-pair state kept by the solver between iterations
/// (search history, tributary areas).
#[derive(Debug, Clone, Default)]
pub struct PairState {
    /// Tributary area of each slave node (`ContactPair::nodes` order).
    pub tributary: Vec<f64>,
    /// Pair this state was prepared for (`None`: not prepared yet).
    pub pair: Option<usize>,
    /// Search window `prof` in use (explicit or default, see [`prof`]).
    pub prof: f64,
    /// The tool geometry prepared for projection (`None` if invalid).
    pub shape: Option<ToolShape>,
    /// Why the tool geometry could not be prepared, if it could not.
    pub error: Option<String>,
    /// Per slave node: entity found at the latest evaluation (trial).
    pub last_entity: Vec<Option<usize>>,
    /// Per slave node: entity at the last converged increment.
    pub committed_entity: Vec<Option<usize>>,
    /// Projections computed by the latest [`evaluate_pair`] call.
    pub last_projection_tests: usize,
    /// Projections a brute-force search would have computed in that call
    /// (slave nodes x tool entities), for comparison.
    pub last_brute_force_tests: usize,
    /// Projections computed since the state was created.
    pub total_projection_tests: u64,
    /// Per slave node: contact multiplier in force units (Lagrange: the
    /// normal force `lambda >= 0`; augmented Lagrangian: `lambda*`).
    pub multiplier: Vec<f64>,
    /// Per slave node: multiplier at the last converged increment.
    pub committed_multiplier: Vec<f64>,
    /// Per slave node: in the Lagrange active set (trial).
    pub active: Vec<bool>,
    /// Per slave node: active set at the last converged increment.
    pub committed_active: Vec<bool>,
    /// Per slave node: its Lagrange row was redundant at the last
    /// evaluation (modified double pass, self contact: [`redundancy`]):
    /// active, without multiplier or force.
    pub redundant: Vec<bool>,
    /// Per slave node: switches of the semi-smooth active set in the
    /// current increment attempt ([`semismooth::MAX_SWITCHES`]: the cycle
    /// guard); cleared at commit and rollback.
    pub switches: Vec<u8>,
    /// Friction history (stick points, tangential multipliers, statuses).
    pub friction: friction::FrictionState,
    /// Broad phase over the tool's entities (reference frame, built once).
    pub tool_grid: search::ToolGrid,
    /// Scratch list of broad-phase hits (reused by every search).
    pub scratch: Vec<usize>,
    /// Slave nodes, sorted: `ContactPair::nodes`, plus the master surface's
    /// nodes for the double-pass strategies. Every per-slave vector above is
    /// in this order.
    pub slaves: Vec<usize>,
    /// Deformable master (node-to-segment): surfaces, strategy state.
    pub surface: Option<node_to_segment::SurfacePair>,
    /// Closed-gap start: slave nodes whose gap is within `[0, touching]`
    /// count as closed with zero force (penalty, augmented Lagrangian:
    /// the penalty stiffness along the normal; Lagrange: in the active
    /// set), so the first tangent holds a body that only this contact can
    /// hold. Set by the solver for the first iteration of the analysis
    /// only, on frictionless pairs of bodies held only by contact (0: off;
    /// see [`penalty::touching`]).
    pub touching: f64,
    /// Mortar pairs and smoothed node-to-segment pairs: the coupling rows
    /// of the latest evaluation (the solver scatters these instead of the
    /// `NodeContact` forces), in slave order; `None` for faceted
    /// node-to-segment and rigid tools. Face-integrated pairs: one row per
    /// slave edge with a closed integration point.
    pub couplings: Option<Vec<mortar::Coupling>>,
    /// Quadratic slave edges against a rigid tool: the face-integrated
    /// state ([`face_integrated`]); `None` otherwise.
    pub facets: Option<face_integrated::FacetPair>,
    /// Face-integrated pairs: the tool entity of each integration point
    /// at the latest evaluation (search memory).
    pub point_memory: Vec<Option<usize>>,
    /// Face-integrated pairs with friction: the points' responses at the
    /// latest evaluation (`node` is the point's index; the friction
    /// history `friction` is then per point), read by the Uzawa update.
    pub point_contact: Vec<NodeContact>,
    /// A tool with a free rotation (`model::FreeRotation`): its current
    /// angle, set by the solver from the pilot node before every
    /// evaluation (`solve/free_tool.rs`); `None`: the angle is
    /// `motion.rotation(t)`.
    pub angle: Option<f64>,
}

impl PairState {
    /// Prepares the state of pair `pair` of `model` (reference configuration).
    /// An invalid tool geometry leaves `shape = None` and the reason in
    /// `error` (the pair then produces no contact); see [`PairState::try_new`].
    pub fn new(model: &Model, pair: usize) -> Self {
        let Some(cp) = model.contacts.get(pair) else {
            return PairState {
                pair: Some(pair),
                error: Some(format!("contact pair {pair} does not exist")),
                ..PairState::default()
            };
        };
        let facets = face_integrated::planar_pair(model, pair);
        let mut slaves = node_to_segment::slave_nodes(model, pair);
        if let Some(fp) = &facets {
            slaves.extend(&fp.nodes);
            slaves.sort_unstable();
            slaves.dedup();
        }
        // seg3 mortar: the slave edges' midside nodes are slave nodes too
        let seg3 = cp.formulation == ContactFormulation::Mortar
            && matches!(cp.master, ContactMaster::Surface { .. });
        if seg3 {
            if let Some(m) = mortar::seg3::edge_midsides(model, cp.body, &cp.edges) {
                slaves.extend(m);
                slaves.sort_unstable();
                slaves.dedup();
            }
        }
        let n = slaves.len();
        let surface = node_to_segment::prepare(model, pair, &slaves);
        let tributary = match &surface {
            // a quadratic slave (against a quadratic or, mixed orders, a
            // linear master): the seg3 weights; a linear slave: its own
            Some(sp) if seg3 && !sp.midsides[0].is_empty() => {
                mortar::seg3::reference_areas(model, &cp.edges, &sp.midsides[0], &slaves)
            }
            _ => node_to_segment::tributary_areas(model, pair, &slaves),
        };
        let shape = match cp.master.tool().and_then(|t| model.tools.get(t)) {
            Some(tool) => {
                ToolShape::new(&tool.geometry).map_err(|e| format!("tool '{}': {e}", tool.name))
            }
            None => Err(format!(
                "contact pair '{}' has no rigid tool as master ({:?})",
                cp.name,
                cp.master.tool()
            )),
        };
        let (shape, error) = match shape {
            Ok(s) => (Some(s), None),
            Err(_) if surface.is_some() => (None, None),
            Err(e) => (None, Some(e)),
        };
        // reference-frame positions at t = 0 (start of the first impact path)
        let placement = cp
            .master
            .tool()
            .and_then(|t| model.tools.get(t))
            .map_or(Placement::identity(), |t| Placement::at(&t.motion, 0.0));
        // face-integrated friction: the history is per integration point
        let positions = match &facets {
            Some(fp) if cp.friction.is_some() => fp
                .point_positions(&model.mesh.nodes)
                .into_iter()
                .map(|x| placement.to_reference(x))
                .collect(),
            _ => slaves
                .iter()
                .map(|&k| {
                    placement.to_reference(model.mesh.nodes.get(k).copied().unwrap_or([0.0; 2]))
                })
                .collect(),
        };
        PairState {
            tributary,
            pair: Some(pair),
            prof: prof::effective_prof(model, pair),
            error,
            last_entity: vec![None; n],
            committed_entity: vec![None; n],
            last_projection_tests: 0,
            last_brute_force_tests: 0,
            total_projection_tests: 0,
            multiplier: vec![0.0; n],
            committed_multiplier: vec![0.0; n],
            active: vec![false; n],
            committed_active: vec![false; n],
            redundant: vec![false; n],
            switches: vec![0; n],
            friction: friction::FrictionState::new(positions),
            tool_grid: shape
                .as_ref()
                .map(search::ToolGrid::new)
                .unwrap_or_default(),
            scratch: Vec::new(),
            shape,
            slaves,
            touching: 0.0,
            couplings: (((cp.formulation == ContactFormulation::Mortar
                || cp.smoothing == NormalSmoothing::Nodal)
                && surface.is_some())
                || facets.is_some())
            .then(Vec::new),
            surface,
            point_memory: vec![None; facets.as_ref().map_or(0, |f| f.rule.points.len())],
            point_contact: Vec::new(),
            facets,
            angle: None,
        }
    }

    /// Like [`PairState::new`] but fails with a clear message when the
    /// pair or its tool geometry is invalid.
    pub fn try_new(model: &Model, pair: usize) -> Result<Self, String> {
        let s = PairState::new(model, pair);
        match s.error.clone() {
            Some(e) => Err(e),
            None => Ok(s),
        }
    }

    /// Called when an increment has converged: commits history variables.
    pub fn commit(&mut self) {
        self.committed_entity.clone_from(&self.last_entity);
        self.committed_multiplier.clone_from(&self.multiplier);
        self.committed_active.clone_from(&self.active);
        self.switches.fill(0);
        self.friction.commit();
        if let Some(sp) = &mut self.surface {
            sp.commit();
        }
        if let Some(fp) = &mut self.facets {
            fp.commit();
        }
    }

    /// Index of slave node `node` in the per-slave vectors, if it is one.
    pub fn slave_index(&self, node: usize) -> Option<usize> {
        self.slaves.binary_search(&node).ok()
    }

    /// Called when an increment is cut back: restores the committed state.
    pub fn rollback(&mut self) {
        self.last_entity.clone_from(&self.committed_entity);
        self.multiplier.clone_from(&self.committed_multiplier);
        self.active.clone_from(&self.committed_active);
        self.switches.fill(0);
        self.friction.rollback();
        if let Some(sp) = &mut self.surface {
            sp.rollback();
        }
        if let Some(fp) = &mut self.facets {
            fp.rollback();
        }
    }
}

/// Evaluates pair `pair` at time `t` for current coordinates `x` (all nodes).
/// Returns one entry per slave node within `prof` of the tool.
pub fn evaluate_pair(
    model: &Model,
    pair: usize,
    x: &[[f64; 2]],
    t: f64,
    state: &mut PairState,
) -> Vec<NodeContact> {
    let Some(cp) = model.contacts.get(pair) else {
        return Vec::new();
    };
    if state.pair != Some(pair)
        || state.last_entity.len() != state.slaves.len()
        || state.slaves.len() < cp.nodes.len()
    {
        *state = PairState::new(model, pair);
    }
    if state.couplings.is_some() && cp.formulation == ContactFormulation::Mortar {
        return mortar::evaluate(model, pair, x, state);
    }
    if state.surface.is_some() {
        return node_to_segment::evaluate(model, pair, x, state);
    }
    if state.facets.is_some() {
        return face_integrated::evaluate_planar(model, pair, x, t, state);
    }
    let tool = cp.master.tool().and_then(|t| model.tools.get(t));
    let (Some(shape), Some(tool)) = (state.shape.as_ref(), tool) else {
        return Vec::new();
    };
    let placement = match state.angle {
        Some(theta) => Placement::at(&tool.motion, t).with_angle(theta),
        None => Placement::at(&tool.motion, t),
    };
    let prof = state.prof;
    state.friction.impact = None;
    let mut tests = 0usize;
    let mut guess = None;
    let mut out = Vec::new();
    for (i, &node) in cp.nodes.iter().enumerate() {
        let Some(&xn) = x.get(node) else {
            debug_assert!(false, "node {node} outside the coordinate array");
            continue;
        };
        let xr = placement.to_reference(xn);
        let memory = state.last_entity[i];
        let request = search::Request {
            x: xr,
            window: prof,
            memory,
            guess,
            test: cp.search,
        };
        let Some(found) = search::closest_in(
            shape,
            &state.tool_grid,
            request,
            &mut state.scratch,
            &mut tests,
        ) else {
            state.friction.open(i, xr);
            continue;
        };
        state.last_entity[i] = Some(found.entity);
        guess = Some(found.entity);
        let p = found.projection;
        if p.gap > prof {
            state.friction.open(i, xr);
            continue;
        }
        let normal = placement.rotate(p.normal);
        let tributary = state.tributary.get(i).copied().unwrap_or(0.0);
        let lambda = state.multiplier.get(i).copied().unwrap_or(0.0);
        let method = cp.method_at(node);
        let mut r = match &method {
            ContactMethod::Penalty { .. } => {
                penalty::respond(&method, tributary, p.gap, normal, p.normal_rate)
            }
            ContactMethod::Lagrange { .. } => lagrange::respond(
                state.active.get(i).copied().unwrap_or(false),
                lambda,
                tributary,
                normal,
                p.normal_rate,
            ),
            ContactMethod::AugmentedLagrange { .. } => augmented::respond(
                penalty::effective_stiffness(&method, tributary),
                lambda,
                tributary,
                p.gap,
                normal,
                p.normal_rate,
            ),
        };
        if r.status == ContactStatus::Open && !matches!(method, ContactMethod::Lagrange { .. }) {
            let alpha = penalty::effective_stiffness(&method, tributary);
            if let Some(t) = penalty::touching(
                alpha,
                p.gap,
                state.touching,
                tributary,
                normal,
                p.normal_rate,
            ) {
                r = t;
            }
        }
        let friction = match &cp.friction {
            Some(law) => {
                let c = friction::ToolContact {
                    shape,
                    placement: &placement,
                    x: xn,
                    reference: xr,
                    projection: &p,
                    normal,
                    window: prof.max(vec2::norm(vec2::sub(
                        xr,
                        state.friction.committed_position[i],
                    ))) * 4.0,
                };
                friction::respond_tool(law, &method, tributary, i, &c, &mut state.friction, &mut r)
            }
            None => friction::NodeFriction::default(),
        };
        out.push(NodeContact {
            node,
            gap: p.gap,
            normal,
            force: r.force,
            stiffness: r.stiffness,
            pressure: r.pressure,
            status: r.status,
            entity: found.entity,
            master: None,
            friction,
        });
    }
    state.last_projection_tests = tests;
    state.last_brute_force_tests = cp.nodes.len() * shape.entity_count();
    state.total_projection_tests += tests as u64;
    if log::debug_enabled() {
        let closed = out
            .iter()
            .filter(|c| c.status == ContactStatus::Closed)
            .count();
        let min_gap = out.iter().map(|c| c.gap).fold(f64::INFINITY, f64::min);
        eprintln!(
            "[ctc contact] pair '{}' t={t:.6e}: {} slave nodes, {} entities, {} closed, {} open, \
             min gap {min_gap:.3e}, prof {prof:.3e}, projection tests {} (brute force {})",
            cp.name,
            cp.nodes.len(),
            shape.entity_count(),
            closed,
            out.len() - closed,
            tests,
            state.last_brute_force_tests
        );
    }
    out
}

/// Total force exerted by the tool on the body over a pair's evaluation
/// (axisymmetric: total over 2*pi). The force on the tool is its opposite.
pub fn pair_total_force(contacts: &[NodeContact]) -> [f64; 2] {
    contacts.iter().fold([0.0; 2], |acc, c| {
        [acc[0] + c.force[0], acc[1] + c.force[1]]
    })
}

/// Moment about `point` of the forces exerted by the tool on the body, the
/// forces acting at the current node positions `x` (the force of a node
/// acts along the normal through its projection, so its moment is the same
/// taken at the node or at the projection). The moment on the tool is its
/// opposite.
pub fn pair_total_moment(contacts: &[NodeContact], x: &[[f64; 2]], point: [f64; 2]) -> f64 {
    contacts
        .iter()
        .filter_map(|c| {
            let p = x.get(c.node)?;
            Some(vec2::cross(vec2::sub(*p, point), c.force))
        })
        .sum()
}

/// Penalty energy stored in the pair, `sum alpha_eff g^2 / 2` over closed
/// nodes (= `|force| |gap| / 2` per node); its derivative with respect to
/// the tool's motion is minus the load on the tool.
pub fn pair_penalty_energy(contacts: &[NodeContact]) -> f64 {
    contacts
        .iter()
        .filter(|c| c.status == ContactStatus::Closed)
        .map(|c| 0.5 * vec2::norm(c.force) * c.gap.abs())
        .sum()
}

/// One closed node-to-segment / node-to-facet element seen by
/// [`interface_pressures`]: its slave node, and the nodes of the element
/// with their forces and constraint gradient `dg/dx` (`D` per node).
pub struct ElementForces<'a> {
    /// The slave node.
    pub slave: usize,
    /// The element's nodes (slave included).
    pub nodes: &'a [usize],
    /// Forces on `nodes`.
    pub force: &'a [f64],
    /// `dg/dx` over `nodes`: on a master node `-N_a n` (its share of the
    /// foot point).
    pub gap_gradient: &'a [f64],
}

impl<'a> ElementForces<'a> {
    /// The element of one coupling row (a closed slave node and its master
    /// nodes).
    pub fn of_coupling(r: &'a mortar::Coupling) -> Self {
        ElementForces {
            slave: r.slave,
            nodes: &r.nodes,
            force: &r.force,
            gap_gradient: &r.gap_gradient,
        }
    }
}

/// The interface pressure of the modified double pass (both sides slave at
/// once, each node with half its tributary area), replacing each entry's
/// per-pass pressure:
/// 1. the nodal traction of every node: the normal component of the
///    **total** contact force on it (its own force as a slave plus its
///    shares as a master node of the other side's elements) over its
///    **full** tributary area (`2 half_area(node)`; a node without an
///    entry: the force's magnitude). It is what the body carries at the
///    node; a uniform pressure gives it exactly (the contact patch test),
///    while the per-pass pressure `f_s / (A / 2)` oscillates from node to
///    node on non-matching meshes (how much of the load each pass carries
///    at a node depends on where the other side's nodes project);
/// 2. a closed node reports the average of its own nodal traction and the
///    other side's nodal tractions interpolated at its foot point (the
///    weights `-dg/dx_a . n` of its element = the shape functions `N_a`
///    of the foot): both surfaces' estimates of the one interface pressure
///    at the same point. Where two nodes coincide (a symmetry plane) the
///    two passes' gaps are equal, so the load splits between them by
///    their areas, not by the pressure: measured on two Hertz cylinders
///    (`ctc verify hertz_two_cylinders_nts_smoothed --max-level 2`), the
///    axis node's nodal traction +4.7 % / -1.3 % on the two sides, their
///    average +1.7 %.
///
/// Sums in sorted order: the result does not depend on the evaluation
/// order of the elements.
pub fn interface_pressures<const D: usize>(
    out: &mut [NodeContact<D>],
    elements: &[ElementForces<'_>],
    half_area: impl Fn(usize) -> Option<f64>,
) {
    // total force per node
    let mut forces: Vec<(usize, [f64; D])> = Vec::new();
    for e in elements {
        for (a, &n) in e.nodes.iter().enumerate() {
            let mut f = [0.0; D];
            f.copy_from_slice(&e.force[D * a..D * a + D]);
            forces.push((n, f));
        }
    }
    forces.sort_by(|a, b| {
        a.1.iter()
            .zip(&b.1)
            .fold(a.0.cmp(&b.0), |o, (p, q)| o.then(p.total_cmp(q)))
    });
    let mut entry: Vec<(usize, usize)> = out.iter().enumerate().map(|(i, c)| (c.node, i)).collect();
    entry.sort_unstable();
    let mut traction: Vec<(usize, f64)> = Vec::new();
    let mut k = 0;
    while k < forces.len() {
        let n = forces[k].0;
        let mut total = [0.0; D];
        while k < forces.len() && forces[k].0 == n {
            for (t, f) in total.iter_mut().zip(&forces[k].1) {
                *t += f;
            }
            k += 1;
        }
        let area = 2.0 * half_area(n).unwrap_or(0.0);
        if area <= 0.0 {
            continue;
        }
        let own = entry.partition_point(|x| x.0 < n);
        let t = match entry.get(own).filter(|x| x.0 == n).map(|x| &out[x.1]) {
            Some(c) => (0..D).map(|d| total[d] * c.normal[d]).sum::<f64>().max(0.0),
            None => total.iter().map(|f| f * f).sum::<f64>().sqrt(),
        };
        traction.push((n, t / area));
    }
    let mut element: Vec<(usize, usize)> = elements
        .iter()
        .enumerate()
        .map(|(i, e)| (e.slave, i))
        .collect();
    element.sort_unstable();
    let at = |n: usize| {
        traction
            .binary_search_by_key(&n, |t| t.0)
            .map_or(0.0, |i| traction[i].1)
    };
    for c in out.iter_mut() {
        if half_area(c.node).is_none_or(|a| a <= 0.0) {
            continue;
        }
        let own = at(c.node);
        c.pressure = own;
        if c.status != ContactStatus::Closed {
            continue;
        }
        let first = element.partition_point(|x| x.0 < c.node);
        let Some(e) = element
            .get(first)
            .filter(|x| x.0 == c.node)
            .map(|x| &elements[x.1])
        else {
            continue;
        };
        let (mut sum, mut weight) = (0.0, 0.0);
        for (a, &n) in e.nodes.iter().enumerate() {
            if n == c.node {
                continue;
            }
            let w = -(0..D)
                .map(|d| e.gap_gradient[D * a + d] * c.normal[d])
                .sum::<f64>();
            if w > 0.0 {
                sum += w * at(n);
                weight += w;
            }
        }
        if weight > 0.0 {
            c.pressure = 0.5 * (own + sum / weight);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(node: usize, normal: [f64; 2]) -> NodeContact {
        NodeContact {
            node,
            gap: -1e-6,
            normal,
            force: [0.0; 2],
            stiffness: [[0.0; 2]; 2],
            pressure: 0.0,
            status: ContactStatus::Closed,
            entity: 0,
            master: None,
            friction: Default::default(),
        }
    }

    /// Two passes by hand: node 1 (side A, half area 1) on the segment
    /// 10-11 at N = (0.75, 0.25) with force 2; node 10 (side B, half area
    /// 0.5) on 1-2 at N = (0.5, 0.5) with force 1. Nodal tractions: node 1
    /// (2 + 0.5) / 2 = 1.25, node 10 (1.5 + 1) / 1 = 2.5, node 11 0.5 / 1,
    /// node 2 0.5 / 2; reported: node 1 (1.25 + 0.75 2.5 + 0.25 0.5) / 2,
    /// node 10 (2.5 + 0.5 1.25 + 0.5 0.25) / 2, both 1.625; the same bits
    /// whatever the order of the elements.
    #[test]
    fn interface_pressure_sums_both_passes_and_averages_the_sides() {
        let a = (
            [1, 10, 11],
            [0.0, 2.0, 0.0, -1.5, 0.0, -0.5],
            [0.0, 1.0, 0.0, -0.75, 0.0, -0.25],
        );
        let b = (
            [10, 1, 2],
            [0.0, -1.0, 0.0, 0.5, 0.0, 0.5],
            [0.0, -1.0, 0.0, 0.5, 0.0, 0.5],
        );
        let half = |n: usize| match n {
            1 | 2 => Some(1.0),
            10 | 11 => Some(0.5),
            _ => None,
        };
        let run = |order: [&([usize; 3], [f64; 6], [f64; 6]); 2]| {
            let elements: Vec<ElementForces<'_>> = order
                .iter()
                .map(|(nodes, force, grad)| ElementForces {
                    slave: nodes[0],
                    nodes,
                    force,
                    gap_gradient: grad,
                })
                .collect();
            let mut out = vec![entry(1, [0.0, 1.0]), entry(10, [0.0, -1.0])];
            interface_pressures(&mut out, &elements, half);
            [out[0].pressure, out[1].pressure]
        };
        let p = run([&a, &b]);
        assert!((p[0] - 1.625).abs() < 1e-15, "{p:?}");
        assert!((p[1] - 1.625).abs() < 1e-15, "{p:?}");
        assert_eq!(p, run([&b, &a]));
        // an open node reports its own nodal traction only
        let elements = [ElementForces {
            slave: a.0[0],
            nodes: &a.0,
            force: &a.1,
            gap_gradient: &a.2,
        }];
        let mut out = vec![entry(1, [0.0, 1.0]), entry(11, [0.0, -1.0])];
        out[1].status = ContactStatus::Open;
        interface_pressures(&mut out, &elements, half);
        assert!(
            (out[1].pressure - 0.5).abs() < 1e-15,
            "{:?}",
            out[1].pressure
        );
        // node 1: (2 / 2 + (0.75 1.5 + 0.25 0.5)) / 2
        assert!((out[0].pressure - 0.5 * (1.0 + 1.25)).abs() < 1e-15);
    }
}
