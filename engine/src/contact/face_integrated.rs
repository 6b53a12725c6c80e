//! Face-integrated contact of quadratic slave faces against rigid tools
//! (issue 23): the 3-node edges of tri6 / quad8 / quad9 bodies (plane and
//! axisymmetric) and the tri6 / quad8 / quad9 faces of tet10 / hex20 /
//! hex27 bodies.
//!
//! # Why not the nodal scheme
//!
//! The node-based schemes of the linear faces ([`super::penalty`],
//! [`super::surface`]) give each slave node the force `R_N(g_a) n_a`
//! with a tributary area `A_a = int N_a dA`. On quadratic faces these
//! shares of a uniform pressure are not all positive: 1/6, 4/6, 1/6 on a
//! 3-node edge, but 0 at the corners of a tri6 face (tet10) and -1/12 at
//! the corners of a quad8 face (hex20). A nodal area penalty then has a
//! zero or negative stiffness at the corners (a corner that penetrates is
//! pulled further in), and a collocated multiplier must be negative at a
//! quad8 corner to carry a uniform pressure, so the active set releases
//! it.
//!
//! # The formulation: the gap at the integration points
//!
//! The penalty energy is integrated over the slave faces in the reference
//! configuration with the gap of the *interpolated* current surface
//! `x(xi) = sum_a N_a(xi) x_a` at the integration points of each face:
//!
//! `Pi = sum_g w_g phi(g(x(xi_g)))`, `p_g = max(0, lambda*_g - k g_g)`,
//!
//! (`k` the pressure per unit gap, `lambda*_g = 0` for the penalty method,
//! the Uzawa multiplier of the point for the augmented Lagrangian, in
//! pressure units). With `dg/dx = n` and `dn/dx = W` (the tool's
//! curvature at the foot, planar `W = h t ⊗ t`), the forces and the exact
//! (symmetric) tangent of a face are
//!
//! `f_a = sum_g w_g N_a p_g n_g`,
//! `K_ab = -df_a/dx_b = sum_g w_g N_a N_b (k n_g ⊗ n_g - p_g W_g)`.
//!
//! A uniform gap therefore gives exactly the consistent nodal loads of a
//! uniform pressure (negative corner shares included: they are what a
//! uniform traction needs), so the contact patch test passes to round-off
//! on every quadratic face; the normal stiffness is `k` times the face's
//! mass matrix `int N_a N_b dA` (as integrated by the rule), positive
//! semi-definite whatever the signs of `int N_a dA`.
//!
//! The rule is exact for `N_a N_b` on flat faces (4 Gauss points on a
//! 3-node edge, the faces' mass rules: 16 collapsed points on tri6, 3x3 on
//! quad8 / quad9), so that the penalty energy `k/2 int g^2 dA` of a gap
//! that is quadratic along the face is integrated exactly. A rule with
//! only as many points as the face has nodes (2 per edge, 2x2) does not
//! see the mode `g ~ xi^2 - 1/3`, zero at both Gauss points: a curved
//! slave surface then keeps its curvature inside the contact zone
//! (measured on the axisymmetric quad8 Hertz sphere: corner gaps +1e-4,
//! midside gaps -5e-5, against a penetration of 4e-6).
//!
//! # Lagrange multipliers
//!
//! Multipliers at the integration points would over-constrain the faces
//! (4 points per 3-node edge, 9 or 16 per face, against the face's
//! nodes: the saddle-point system is singular), and collocated nodal
//! multipliers with the weights `int N_a dA` are wrong for the reasons
//! above (a quad8 corner's weighted gap is positive under a uniform
//! penetration, so the active set never takes it). The multipliers are
//! therefore nodal, `lambda_a` a force at every slave node (corners and
//! midsides), on the dual `Phi_a` ([`dualize`]) of the positive-weight
//! basis `N~_a` of [`multiplier_basis`] (the modified basis of Wohlmuth,
//! Popp, Gee and Wall 2012, `alpha = 1/5`): the pressure field `p = sum_a
//! Phi_a lambda_a / A_a` and the weighted gaps `g~_a = int Phi_a g dA /
//! A_a`, both integrated at the points of the penalty path
//! ([`FacetRule`]), `A_a = int Phi_a dA = int N~_a dA > 0`. The `N~_a`
//! span the same space as the `N_a`, so on a fully active face the
//! constraints `g~_a = 0` are those of the standard basis (a flat tool: `g
//! = 0` at every point of the face); the positive weights make `g~_a < 0`
//! mean penetration around the node, which is what the active set loops
//! test (introduce at `g~_a < 0`, release at `lambda_a < 0`), and the dual
//! keeps each constraint local (a corner's is its own gap on a flat tool).
//! See [`FacetPair::evaluate_lagrange`].
//!
//! # What it is not
//!
//! Deformable masters on quadratic faces, Lagrange-multiplier friction,
//! and a nodal penalty (a force per node has no meaning at integration
//! points) are refused (`solve::check`, and the deck lowering with a
//! caret).
//!
//! # Friction
//!
//! Coulomb friction is integrated like the pressure: every integration
//! point is a slave "node" of tributary area `w` with its own stick point
//! (the pair's `FrictionState` is per point), normal force `w p_g` and
//! normal stiffness `w k`, and the return map and exact tangent of the
//! linear faces ([`super::friction::respond_tool`] in 2D,
//! [`super::friction_surface::respond`] in 3D) give its tangential force
//! `f_T` and `K_T = -d f_T / d x_g`; the nodes get `N_a f_T` and `N_a N_b
//! K_T` ([`FacetPair::evaluate_with`]). A uniform slip therefore carries
//! exactly the consistent loads of a uniform shear traction, and in full
//! slip `|sum f_T| = mu sum w p_g` to round-off.
//!
//! The reported nodal values: the gap of the node itself, the force the
//! faces put on it, and the pressure: the L2 projection of the points'
//! pressures on the faces' shape functions (`M p = sum_g w N p_g`, `M` the
//! faces' mass matrix, by conjugate gradients; exact for a uniform
//! pressure), clamped at 0, kept at the nodes of loaded faces; closed
//! where it is positive. The penalty holds
//! the gap at the points, not at the nodes: `k max(0, -g_a)` at a node is
//! not the pressure (measured: 0 on the axis of the quad8 Hertz cylinder),
//! and a positive-weight mean over the node's faces smears the peak over a
//! face (measured: p0 38 % low on the coarsest hex27 Hertz block).

use super::friction::{self, FrictionStatus, NodeFriction};
use super::mortar::Coupling;
use super::motion::Placement;
use super::rows::NodeTerm;
use super::{search, ContactStatus, NodeContact, PairState};
use crate::model::{AnalysisKind, ContactMaster, ContactMethod, Model, PenaltyKind};

/// Gauss-Legendre points of a 3-node edge (4 points, degree 7: exact for
/// `N_a N_b` times the ring's `r`).
const EDGE_GAUSS: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_85),
    (-0.339_981_043_584_856_26, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_26, 0.652_145_154_862_546_1),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_85),
];

/// One integration point of a slave facet (reference configuration).
#[derive(Debug, Clone, PartialEq)]
pub struct FacetPoint {
    /// Facet of the point (index into [`FacetRule::facets`]).
    pub facet: usize,
    /// Shape values `N_a` at the point, in the facet's node order.
    pub shape: Vec<f64>,
    /// Reference measure of the point: weight x `|dX/dxi|` x (thickness or
    /// `2 pi r`) on an edge, weight x `|dX/dxi x dX/deta|` on a face.
    pub weight: f64,
    /// The multiplier basis at the point (Lagrange multipliers): the dual
    /// of the positive-weight basis `N~_a` of [`multiplier_basis`] on the
    /// point's facet ([`dualize`]), in the facet's node order.
    pub basis: Vec<f64>,
}

/// Weight `alpha` of the positive-weight multiplier basis of quadratic
/// facets ([`multiplier_basis`]).
pub const BASIS_ALPHA: f64 = 0.2;

/// The multiplier basis of a quadratic facet at one point, from its shape
/// values `shape` and its midside nodes `midsides` (`(midside, corner,
/// corner)`, local indices): `N~_c = N_c + alpha sum_{m adjacent} N_m`,
/// `N~_m = (1 - 2 alpha) N_m`, other nodes (a quad9's centre) unchanged,
/// `alpha` = [`BASIS_ALPHA`] (the transformation of Wohlmuth, Popp, Gee and
/// Wall 2012 for quadratic mortar contact). It keeps the partition of unity
/// and spans the same space as the `N_a` (so the constraints of a fully
/// active face are the same), but every node's weight `int N~_a dA` is
/// positive: corners 2/15 (tri6), 1/20 (quad8, against -1/12 for `N`) of
/// the face's area, a 3-node edge's corner on the axis of an
/// axisymmetric model `alpha int N_m 2 pi r dS` (0 for `N`).
pub fn multiplier_basis(shape: &[f64], midsides: &[(usize, usize, usize)]) -> Vec<f64> {
    let mut out = shape.to_vec();
    for &(m, a, b) in midsides {
        let nm = shape[m];
        out[a] += BASIS_ALPHA * nm;
        out[b] += BASIS_ALPHA * nm;
        out[m] = (1.0 - 2.0 * BASIS_ALPHA) * nm;
    }
    out
}

/// Replaces the multiplier basis `N~_a` of every facet's points by its
/// dual `Phi_a = sum_b (D M^-1)_ab N~_b` (per facet, `M_ab = int N~_a N~_b
/// dA`, `D = diag(int N~_a dA)`, both by the facet's own rule, so that
/// `int Phi_a N~_b dA = delta_ab int N~_a dA` holds to round-off): the
/// biorthogonal basis of Popp, Gee and Wall (2012, with the transformed
/// `N~` of Wohlmuth et al. on quadratic faces). It keeps the partition of
/// unity and the weights `int Phi_a dA = int N~_a dA`, and makes the
/// weighted gap of a node local: against a flat tool a corner's
/// constraint is its own gap, a midside's `(g_m - alpha (g_a + g_b)) / (1
/// - 2 alpha)`, so a node that lifts off at the edge of the contact zone
/// moves only its own face (with the `N~` themselves the constraints
/// couple through the faces' mass matrix and the lift-off propagated to
/// the axis: measured on the quad8 Hertz cylinder, nodal pressures
/// alternating by +-15 %, p0 11 % off). A facet whose matrix is singular
/// keeps its `N~`.
fn dualize(facets: &[Vec<usize>], points: &mut [FacetPoint]) {
    let mut start = 0;
    for (f, facet) in facets.iter().enumerate() {
        let n = facet.len();
        let end = start + points[start..].iter().take_while(|p| p.facet == f).count();
        let mut m = nalgebra::DMatrix::<f64>::zeros(n, n);
        let mut d = vec![0.0; n];
        for p in &points[start..end] {
            for a in 0..n {
                d[a] += p.weight * p.basis[a];
                for b in 0..n {
                    m[(a, b)] += p.weight * p.basis[a] * p.basis[b];
                }
            }
        }
        if let Some(inv) = m.try_inverse() {
            for p in &mut points[start..end] {
                let dual: Vec<f64> = (0..n)
                    .map(|a| d[a] * (0..n).map(|b| inv[(a, b)] * p.basis[b]).sum::<f64>())
                    .collect();
                p.basis = dual;
            }
        }
        start = end;
    }
}

/// The midside nodes of a facet of `len` nodes as `(midside, corner,
/// corner)` (local indices): a 3-node edge `[a, b, m]` (`planar`), tri6
/// and quad8 / quad9 faces (corners first, midside `k` between corners `k`
/// and `k + 1`); none for linear facets.
fn facet_midsides(len: usize, planar: bool) -> &'static [(usize, usize, usize)] {
    match (len, planar) {
        (3, true) => &[(2, 0, 1)],
        (6, false) => &[(3, 0, 1), (4, 1, 2), (5, 2, 0)],
        (8 | 9, false) => &[(4, 0, 1), (5, 1, 2), (6, 2, 3), (7, 3, 0)],
        _ => &[],
    }
}

/// The slave facets of a pair and their integration points.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FacetRule {
    /// Facet nodes: planar `[a, b, m]` (corners then midside) or `[a, b]`;
    /// solid faces corners then midsides (3, 4, 6, 8 or 9 nodes).
    pub facets: Vec<Vec<usize>>,
    /// The integration points, facet by facet.
    pub points: Vec<FacetPoint>,
}

impl FacetRule {
    /// The rule of the planar edges `facets` (`[a, b, m]` or `[a, b]`) of
    /// the reference nodes `nodes`: 4 Gauss points per edge, measure
    /// `thickness` or `2 pi r` (`axisymmetric`).
    pub fn planar(
        nodes: &[[f64; 2]],
        facets: Vec<Vec<usize>>,
        axisymmetric: bool,
        thickness: f64,
    ) -> Self {
        let mut points = Vec::new();
        for (f, facet) in facets.iter().enumerate() {
            for &(xi, w) in &EDGE_GAUSS {
                let (n, dn): (Vec<f64>, Vec<f64>) = if facet.len() == 3 {
                    (
                        vec![0.5 * xi * (xi - 1.0), 0.5 * xi * (xi + 1.0), 1.0 - xi * xi],
                        vec![xi - 0.5, xi + 0.5, -2.0 * xi],
                    )
                } else {
                    (vec![0.5 * (1.0 - xi), 0.5 * (1.0 + xi)], vec![-0.5, 0.5])
                };
                let (mut t, mut r) = ([0.0; 2], 0.0);
                for (a, &node) in facet.iter().enumerate() {
                    let x = nodes.get(node).copied().unwrap_or([0.0; 2]);
                    t[0] += dn[a] * x[0];
                    t[1] += dn[a] * x[1];
                    r += n[a] * x[0];
                }
                let measure = if axisymmetric {
                    2.0 * std::f64::consts::PI * r.max(0.0)
                } else {
                    thickness
                };
                points.push(FacetPoint {
                    facet: f,
                    basis: multiplier_basis(&n, facet_midsides(facet.len(), true)),
                    shape: n,
                    weight: w * t[0].hypot(t[1]) * measure,
                });
            }
        }
        dualize(&facets, &mut points);
        FacetRule { facets, points }
    }

    /// The rule of the solid faces `facets` of the reference nodes `nodes`:
    /// each face cell's mass rule (the 16-point collapsed rule on tri6,
    /// 3x3 Gauss points on quad8 / quad9), exact for `N_a N_b` on flat
    /// faces.
    pub fn solid(nodes: &[[f64; 3]], facets: Vec<Vec<usize>>) -> Self {
        use crate::element::reference::{Quad4, Quad8, Quad9, ReferenceCell, Tri3, Tri6};
        fn on<const NN: usize, C: ReferenceCell<2, NN>>(
            nodes: &[[f64; 3]],
            f: usize,
            face: &[usize],
            rule: &[([f64; 2], f64)],
            points: &mut Vec<FacetPoint>,
        ) {
            for (xi, w) in rule {
                let (n, g) = (C::shape(xi), C::gradients(xi));
                let mut t = [[0.0; 3]; 2];
                for (a, &node) in face.iter().enumerate() {
                    let x = nodes.get(node).copied().unwrap_or([0.0; 3]);
                    for (k, tk) in t.iter_mut().enumerate() {
                        for c in 0..3 {
                            tk[c] += g[a][k] * x[c];
                        }
                    }
                }
                let [t1, t2] = t;
                let an = [
                    t1[1] * t2[2] - t1[2] * t2[1],
                    t1[2] * t2[0] - t1[0] * t2[2],
                    t1[0] * t2[1] - t1[1] * t2[0],
                ];
                points.push(FacetPoint {
                    facet: f,
                    basis: multiplier_basis(&n, facet_midsides(NN, false)),
                    shape: n.to_vec(),
                    weight: w * (an[0] * an[0] + an[1] * an[1] + an[2] * an[2]).sqrt(),
                });
            }
        }
        let mut points = Vec::new();
        for (f, face) in facets.iter().enumerate() {
            match face.len() {
                3 => on::<3, Tri3>(nodes, f, face, Tri3::MASS_QUADRATURE, &mut points),
                4 => on::<4, Quad4>(nodes, f, face, Quad4::QUADRATURE, &mut points),
                6 => on::<6, Tri6>(nodes, f, face, Tri6::MASS_QUADRATURE, &mut points),
                8 => on::<8, Quad8>(nodes, f, face, Quad8::MASS_QUADRATURE, &mut points),
                9 => on::<9, Quad9>(nodes, f, face, Quad9::MASS_QUADRATURE, &mut points),
                _ => {}
            }
        }
        dualize(&facets, &mut points);
        FacetRule { facets, points }
    }

    /// `int N_a dA` of every node of the facets, as `(node, area)` sorted
    /// by node (zero or negative at the corners of tri6 / quad8 faces).
    pub fn consistent_areas(&self) -> Vec<(usize, f64)> {
        let mut out: Vec<(usize, f64)> = Vec::new();
        for p in &self.points {
            for (a, &node) in self.facets[p.facet].iter().enumerate() {
                out.push((node, p.shape[a] * p.weight));
            }
        }
        out.sort_by_key(|e| e.0);
        let mut merged: Vec<(usize, f64)> = Vec::new();
        for (n, a) in out {
            match merged.last_mut() {
                Some(last) if last.0 == n => last.1 += a,
                _ => merged.push((n, a)),
            }
        }
        merged
    }
}

/// The tool seen from one integration point (current frame): the signed
/// gap, the unit normal `n = dg/dx` into free space and the curvature
/// `W = dn/dx`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointProjection<const D: usize> {
    /// Signed gap (negative: penetration).
    pub gap: f64,
    /// Unit normal of the tool at the foot, into free space.
    pub normal: [f64; D],
    /// `dn/dx` (symmetric, `W n = 0`).
    pub curvature: [[f64; D]; D],
}

/// One integration point as the tangential law of
/// [`FacetPair::evaluate_with`] sees it.
#[derive(Debug, Clone, Copy)]
pub struct PointLoad<'a, const D: usize, E> {
    /// Index of the point in the rule.
    pub point: usize,
    /// Current position of the point (interpolated).
    pub x: [f64; D],
    /// The foot and the projection's extra data (`None`: open, no foot).
    pub found: Option<(&'a PointProjection<D>, &'a E)>,
    /// Normal force of the point `w p_g` (0: open).
    pub normal_force: f64,
    /// `-d (w p_g) / d g = w k`.
    pub normal_stiffness: f64,
    /// The facet's pressure per unit gap `k`.
    pub stiffness: f64,
    /// Reference measure `w` of the point (its tributary area).
    pub weight: f64,
}

/// State of a face-integrated pair: its rule, the penalty of each facet,
/// the point multipliers (augmented Lagrangian, pressure units; trial and
/// committed) and the points' last gaps and pressures.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FacetPair {
    /// Facets and integration points.
    pub rule: FacetRule,
    /// Pressure per unit gap of each facet (the mean of its nodes'
    /// coefficients: a relative penalty varies along the surface).
    pub stiffness: Vec<f64>,
    /// Per point: `lambda*` (augmented Lagrangian; 0 for the penalty).
    pub multiplier: Vec<f64>,
    /// Per point: the multiplier at the last converged increment.
    pub committed: Vec<f64>,
    /// Per point: the gap at the last evaluation (`+inf`: no foot within
    /// the window).
    pub gap: Vec<f64>,
    /// Per point: the pressure at the last evaluation.
    pub pressure: Vec<f64>,
    /// Slave nodes (sorted) and, per node, its points with `|N_a| w`.
    pub nodes: Vec<usize>,
    node_points: Vec<Vec<(usize, f64)>>,
    /// Per facet: the index in `nodes` of each of its nodes.
    facet_index: Vec<Vec<usize>>,
    /// Per slave node (`nodes` order): the L2 projection of the points'
    /// pressures at the last evaluation.
    nodal: Vec<f64>,
    /// Per slave node (`nodes` order): its weight `A_a = int Phi_a dA =
    /// int N~_a dA` of the multiplier basis (Lagrange multipliers,
    /// positive).
    pub support: Vec<f64>,
    /// Per slave node (`nodes` order): the weighted gap `int Phi_a g dA /
    /// A_a` at the last Lagrange evaluation (`+inf`: no point of its faces
    /// has a foot).
    pub weighted_gap: Vec<f64>,
    /// The constraint rows `d (int Phi_a g dA / A_a) / d x` of the last
    /// Lagrange evaluation, one per slave node with a point that has a
    /// foot, sorted by node.
    pub rows: Vec<LagrangeRow>,
}

/// The Lagrange constraint of one slave node of a face-integrated pair:
/// its weighted gap and the gap's gradient over the nodes of its faces.
#[derive(Debug, Clone, PartialEq)]
pub struct LagrangeRow {
    /// Global node number of the multiplier.
    pub node: usize,
    /// The weighted gap `int Phi_a g dA / A_a` (a length).
    pub gap: f64,
    /// `d gap / d x`, per (node, component).
    pub terms: Vec<NodeTerm>,
}

impl FacetPair {
    /// The state of `rule` with the pressure per unit gap `stiffness(node)`
    /// of every node (a facet takes the mean over its nodes).
    pub fn new(rule: FacetRule, stiffness: impl Fn(usize) -> f64) -> Self {
        let k = rule
            .facets
            .iter()
            .map(|f| f.iter().map(|&n| stiffness(n)).sum::<f64>() / f.len().max(1) as f64)
            .collect();
        let mut nodes: Vec<usize> = rule.facets.iter().flatten().copied().collect();
        nodes.sort_unstable();
        nodes.dedup();
        let mut node_points = vec![Vec::new(); nodes.len()];
        for (g, p) in rule.points.iter().enumerate() {
            for (a, node) in rule.facets[p.facet].iter().enumerate() {
                if let Ok(i) = nodes.binary_search(node) {
                    node_points[i].push((g, p.shape[a].abs() * p.weight));
                }
            }
        }
        let facet_index: Vec<Vec<usize>> = rule
            .facets
            .iter()
            .map(|f| {
                f.iter()
                    .map(|n| nodes.binary_search(n).unwrap_or(0))
                    .collect()
            })
            .collect();
        let np = rule.points.len();
        let mut support = vec![0.0; nodes.len()];
        for p in &rule.points {
            for (&i, b) in facet_index[p.facet].iter().zip(&p.basis) {
                support[i] += p.weight * b;
            }
        }
        FacetPair {
            weighted_gap: vec![f64::INFINITY; nodes.len()],
            rows: Vec::new(),
            support,
            facet_index,
            nodal: vec![0.0; nodes.len()],
            rule,
            stiffness: k,
            multiplier: vec![0.0; np],
            committed: vec![0.0; np],
            gap: vec![f64::INFINITY; np],
            pressure: vec![0.0; np],
            nodes,
            node_points,
        }
    }

    /// Evaluates every facet at the current coordinates `x`: the point
    /// projections by `project(point, x_point)` (`None`: no foot within
    /// the window, the point is open), and one [`Coupling`] (forces and
    /// tangent over the facet's nodes) per facet with a closed point.
    /// `touching > 0`: the closed-gap start, points with a gap in
    /// `[0, touching]` add `k n ⊗ n` with no force.
    pub fn evaluate<const D: usize>(
        &mut self,
        x: &[[f64; D]],
        touching: f64,
        mut project: impl FnMut(usize, [f64; D]) -> Option<PointProjection<D>>,
    ) -> Vec<Coupling> {
        self.evaluate_with(
            x,
            touching,
            |g, xg| project(g, xg).map(|p| (p, ())),
            |_, _, _| false,
        )
    }

    /// [`FacetPair::evaluate`] with a tangential law at the points
    /// (friction): `project` also returns what the law needs of the foot
    /// (`E`), and `tangential(point, force, tangent)` is called at every
    /// point, open ones included (so that the law forgets their history),
    /// with `force` and `tangent` at zero; a closed point (`normal_force >
    /// 0`) may put its tangential force `f_T` and `-d f_T / d x_g` there
    /// and return `true`. They act on the nodes as the normal force does:
    /// `f_a += N_a f_T`, `K_ab += N_a N_b (-d f_T / d x_g)` (exact, `x_g =
    /// sum N_b x_b` with reference weights).
    pub fn evaluate_with<const D: usize, E>(
        &mut self,
        x: &[[f64; D]],
        touching: f64,
        mut project: impl FnMut(usize, [f64; D]) -> Option<(PointProjection<D>, E)>,
        mut tangential: impl FnMut(&PointLoad<'_, D, E>, &mut [f64; D], &mut [[f64; D]; D]) -> bool,
    ) -> Vec<Coupling> {
        let mut out = Vec::new();
        let mut g = 0;
        for (f, facet) in self.rule.facets.iter().enumerate() {
            let nn = facet.len();
            let (mut c, pos) = facet_coupling::<D>(facet);
            let nd = c.force.len();
            let mut any = false;
            let k = self.stiffness[f];
            while g < self.rule.points.len() && self.rule.points[g].facet == f {
                let point = &self.rule.points[g];
                let mut xg = [0.0; D];
                for (a, &node) in facet.iter().enumerate() {
                    let xa = x.get(node).copied().unwrap_or([0.0; D]);
                    for (xc, xac) in xg.iter_mut().zip(xa) {
                        *xc += point.shape[a] * xac;
                    }
                }
                self.gap[g] = f64::INFINITY;
                self.pressure[g] = 0.0;
                let w = point.weight;
                let (mut ft, mut kt) = ([0.0; D], [[0.0; D]; D]);
                let Some((pr, extra)) = project(g, xg) else {
                    let load = PointLoad {
                        point: g,
                        x: xg,
                        found: None,
                        normal_force: 0.0,
                        normal_stiffness: 0.0,
                        stiffness: k,
                        weight: w,
                    };
                    tangential(&load, &mut ft, &mut kt);
                    g += 1;
                    continue;
                };
                self.gap[g] = pr.gap;
                let p = self.multiplier[g] - k * pr.gap;
                let closed = if p > 0.0 {
                    Some((p, k))
                } else if touching > 0.0 && (0.0..=touching).contains(&pr.gap) {
                    Some((0.0, k))
                } else {
                    None
                };
                let load = PointLoad {
                    point: g,
                    x: xg,
                    found: Some((&pr, &extra)),
                    normal_force: closed.map_or(0.0, |(p, _)| w * p),
                    normal_stiffness: w * k,
                    stiffness: k,
                    weight: w,
                };
                let rubs = tangential(&load, &mut ft, &mut kt);
                let Some((p, kn)) = closed else {
                    g += 1;
                    continue;
                };
                any = true;
                self.pressure[g] = p;
                for a in 0..nn {
                    let na = point.shape[a] * w;
                    for i in 0..D {
                        c.force[D * pos[a] + i] += na * p * pr.normal[i];
                    }
                    for b in 0..nn {
                        let nab = na * point.shape[b];
                        for i in 0..D {
                            for j in 0..D {
                                c.tangent[(D * pos[a] + i) * nd + D * pos[b] + j] += nab
                                    * (kn * pr.normal[i] * pr.normal[j] - p * pr.curvature[i][j]);
                            }
                        }
                    }
                }
                if rubs {
                    for a in 0..nn {
                        let na = point.shape[a];
                        for (i, fi) in ft.iter().enumerate() {
                            c.force[D * pos[a] + i] += na * fi;
                        }
                        for b in 0..nn {
                            let nab = na * point.shape[b];
                            for (i, ki) in kt.iter().enumerate() {
                                for (j, kij) in ki.iter().enumerate() {
                                    c.tangent[(D * pos[a] + i) * nd + D * pos[b] + j] += nab * kij;
                                }
                            }
                        }
                    }
                }
                g += 1;
            }
            if any {
                out.push(c);
            }
        }
        self.project_pressures();
        out
    }

    /// Lagrange multipliers: evaluates every facet at the current
    /// coordinates `x` with the multiplier `multiplier[i]` of each active
    /// slave node `nodes[i]` (`None`: inactive). The pressure field is `p =
    /// sum_a Phi_a lambda_a / A_a` (`Phi_a` = [`FacetPoint::basis`], the
    /// dual of [`multiplier_basis`]; `lambda_a` is the node's force, `A_a`
    /// = [`FacetPair::support`]); at a point with a
    /// foot it acts along the tool's normal: forces `f_b = sum_g w N_b p_g
    /// n_g`, tangent `K_bc = -sum_g w N_b N_c p_g W_g` (one [`Coupling`] per
    /// facet with a loaded point). The constraint of node `a` is its
    /// weighted gap `g~_a = sum_g w Phi_a g_g / A_a = 0` (a point without a
    /// foot counts with the gap `window`, the edge of the search window),
    /// its row `d g~_a / d x_b = sum_g w Phi_a N_b n_g / A_a` (exact against
    /// a rigid tool: `d g / d x = n`, reference weights), kept in
    /// [`FacetPair::rows`] for every node with a point that has a foot; the
    /// forces are `sum_a lambda_a d g~_a / d x`, so the saddle-point
    /// system is symmetric and the tangent above is the exact derivative
    /// of the forces. `project` as in [`FacetPair::evaluate`].
    pub fn evaluate_lagrange<const D: usize>(
        &mut self,
        x: &[[f64; D]],
        window: f64,
        multiplier: &[Option<f64>],
        mut project: impl FnMut(usize, [f64; D]) -> Option<PointProjection<D>>,
    ) -> Vec<Coupling> {
        let nn_all = self.nodes.len();
        // pressure coefficient lambda_a / A_a of every active node
        let mu: Vec<f64> = (0..nn_all)
            .map(|i| match multiplier.get(i).copied().flatten() {
                Some(l) if self.support[i] > 0.0 => l / self.support[i],
                _ => 0.0,
            })
            .collect();
        let mut gsum = vec![0.0; nn_all];
        let mut found_any = vec![false; nn_all];
        // the rows: per node, (global node, d g~ / d x) of its faces' nodes
        let mut rows: Vec<Vec<(usize, [f64; D])>> = vec![Vec::new(); nn_all];
        let mut out = Vec::new();
        let mut g = 0;
        for (f, facet) in self.rule.facets.iter().enumerate() {
            let nn = facet.len();
            let (mut c, pos) = facet_coupling::<D>(facet);
            let nd = c.force.len();
            let idx = &self.facet_index[f];
            let mut any = false;
            while g < self.rule.points.len() && self.rule.points[g].facet == f {
                let point = &self.rule.points[g];
                let mut xg = [0.0; D];
                for (a, &node) in facet.iter().enumerate() {
                    let xa = x.get(node).copied().unwrap_or([0.0; D]);
                    for (xc, xac) in xg.iter_mut().zip(xa) {
                        *xc += point.shape[a] * xac;
                    }
                }
                let w = point.weight;
                let found = project(g, xg);
                self.gap[g] = found.as_ref().map_or(f64::INFINITY, |p| p.gap);
                let p: f64 = idx.iter().zip(&point.basis).map(|(&i, b)| b * mu[i]).sum();
                self.pressure[g] = if found.is_some() { p } else { 0.0 };
                for (a, &i) in idx.iter().enumerate() {
                    let wb = w * point.basis[a];
                    gsum[i] += wb * found.as_ref().map_or(window, |p| p.gap);
                    let Some(pr) = &found else {
                        continue;
                    };
                    found_any[i] = true;
                    let support = self.support[i];
                    if support <= 0.0 {
                        continue;
                    }
                    for (b, &nb) in facet.iter().enumerate() {
                        let s = wb * point.shape[b] / support;
                        let row = &mut rows[i];
                        let k = match row.iter().position(|e| e.0 == nb) {
                            Some(k) => k,
                            None => {
                                row.push((nb, [0.0; D]));
                                row.len() - 1
                            }
                        };
                        for (r, nc) in row[k].1.iter_mut().zip(pr.normal) {
                            *r += s * nc;
                        }
                    }
                }
                g += 1;
                let Some(pr) = found else {
                    continue;
                };
                if p == 0.0 {
                    continue;
                }
                any = true;
                for a in 0..nn {
                    let na = point.shape[a] * w;
                    for i in 0..D {
                        c.force[D * pos[a] + i] += na * p * pr.normal[i];
                    }
                    for b in 0..nn {
                        let nab = na * point.shape[b];
                        for i in 0..D {
                            for j in 0..D {
                                c.tangent[(D * pos[a] + i) * nd + D * pos[b] + j] -=
                                    nab * p * pr.curvature[i][j];
                            }
                        }
                    }
                }
            }
            if any {
                out.push(c);
            }
        }
        self.rows.clear();
        for i in 0..nn_all {
            self.weighted_gap[i] = if found_any[i] && self.support[i] > 0.0 {
                gsum[i] / self.support[i]
            } else {
                f64::INFINITY
            };
            if !self.weighted_gap[i].is_finite() {
                continue;
            }
            let mut terms: Vec<(usize, [f64; D])> = std::mem::take(&mut rows[i]);
            terms.sort_by_key(|e| e.0);
            self.rows.push(LagrangeRow {
                node: self.nodes[i],
                gap: self.weighted_gap[i],
                terms: terms
                    .into_iter()
                    .flat_map(|(node, v)| {
                        (0..D).map(move |component| NodeTerm {
                            node,
                            component,
                            coefficient: v[component],
                        })
                    })
                    .collect(),
            });
        }
        self.project_pressures();
        out
    }

    /// The Lagrange row of slave node `node` at the last
    /// [`FacetPair::evaluate_lagrange`] (`None`: no point of its faces has
    /// a foot).
    pub fn row(&self, node: usize) -> Option<&LagrangeRow> {
        self.rows
            .binary_search_by_key(&node, |r| r.node)
            .ok()
            .map(|k| &self.rows[k])
    }

    /// The weighted gap of slave node `node` at the last
    /// [`FacetPair::evaluate_lagrange`] (`+inf`: none).
    pub fn node_weighted_gap(&self, node: usize) -> f64 {
        self.nodes
            .binary_search(&node)
            .map_or(f64::INFINITY, |i| self.weighted_gap[i])
    }

    /// Largest `|g|` over the points of the last Lagrange evaluation whose
    /// faces carry a multiplier (the pointwise gap the weighted constraints
    /// leave: 0 to round-off on a flat tool, where the gap is in the span
    /// of the `N_a`).
    pub fn loaded_point_gap(&self) -> f64 {
        self.gap
            .iter()
            .zip(&self.pressure)
            .filter(|(g, p)| g.is_finite() && **p != 0.0)
            .map(|(g, _)| g.abs())
            .fold(0.0, f64::max)
    }

    /// The reference positions of the integration points (`sum N_a X_a`
    /// over the reference nodes `nodes`).
    pub fn point_positions<const D: usize>(&self, nodes: &[[f64; D]]) -> Vec<[f64; D]> {
        self.rule
            .points
            .iter()
            .map(|p| {
                let mut x = [0.0; D];
                for (a, &node) in self.rule.facets[p.facet].iter().enumerate() {
                    let xa = nodes.get(node).copied().unwrap_or([0.0; D]);
                    for (xc, xac) in x.iter_mut().zip(xa) {
                        *xc += p.shape[a] * xac;
                    }
                }
                x
            })
            .collect()
    }

    /// The friction output of slave node `node` from the points' outputs
    /// `points` (integration-point order, `None`: no friction there): stick
    /// if any of its points sticks, else slip if any slips, the tangential force and dissipation
    /// the points put on it (`sum N_a t_g`, `sum N_a D_g`: the node shares
    /// sum to the points' totals), the `|N_a| w`-weighted means of the
    /// points' slips and tangential gaps. `tangential_force` is left to
    /// the caller (planar: the component along the node's tangent; 3D: the
    /// magnitude).
    pub fn node_friction<const D: usize>(
        &self,
        node: usize,
        points: &[Option<NodeFriction<D>>],
    ) -> NodeFriction<D> {
        let mut out = NodeFriction::<D>::default();
        let Ok(i) = self.nodes.binary_search(&node) else {
            return out;
        };
        let mut wsum = 0.0;
        for &(g, wg) in &self.node_points[i] {
            let Some(Some(pf)) = points.get(g) else {
                continue;
            };
            let p = &self.rule.points[g];
            let Some(a) = self.rule.facets[p.facet].iter().position(|&n| n == node) else {
                continue;
            };
            let na = p.shape[a];
            // a node sticks while any of its points sticks
            out.status = match (out.status, pf.status) {
                (FrictionStatus::Frictionless, s) | (s, FrictionStatus::Frictionless) => s,
                (a, b) => a.min(b),
            };
            for k in 0..D {
                out.traction[k] += na * pf.traction[k];
                out.slip_vector[k] += wg * pf.slip_vector[k];
            }
            out.dissipation += na * pf.dissipation;
            out.slip += wg * pf.slip;
            out.tangential_gap += wg * pf.tangential_gap;
            wsum += wg;
        }
        if wsum > 0.0 {
            out.slip /= wsum;
            out.tangential_gap /= wsum;
            out.slip_vector.iter_mut().for_each(|v| *v /= wsum);
        }
        out
    }

    /// `M v` with the slave surface's mass matrix `M_ab = sum w N_a N_b`
    /// (over the points; `nodes` order).
    fn mass_times(&self, v: &[f64], out: &mut [f64]) {
        out.iter_mut().for_each(|o| *o = 0.0);
        for p in &self.rule.points {
            let idx = &self.facet_index[p.facet];
            let s: f64 = idx.iter().zip(&p.shape).map(|(&i, n)| n * v[i]).sum();
            for (&i, n) in idx.iter().zip(&p.shape) {
                out[i] += p.weight * n * s;
            }
        }
    }

    /// The nodal pressures as the L2 projection of the points' pressures
    /// on the faces' shape functions: `M p = sum_g w N p_g`, solved by
    /// conjugate gradients with the diagonal of `M` (symmetric positive
    /// definite for the faces' mass rules; exact for a uniform pressure,
    /// as `M 1 = int N_a dA`), started from the `|N_a| w`-weighted means.
    fn project_pressures(&mut self) {
        let n = self.nodes.len();
        let (mut b, mut diag) = (vec![0.0; n], vec![0.0; n]);
        for (g, p) in self.rule.points.iter().enumerate() {
            for (&i, sh) in self.facet_index[p.facet].iter().zip(&p.shape) {
                b[i] += p.weight * sh * self.pressure[g];
                diag[i] += p.weight * sh * sh;
            }
        }
        let bnorm = b.iter().map(|v| v * v).sum::<f64>().sqrt();
        if bnorm == 0.0 {
            self.nodal.iter_mut().for_each(|v| *v = 0.0);
            return;
        }
        let mut x: Vec<f64> = self.nodes.iter().map(|&k| self.mean_pressure(k)).collect();
        let mut r = vec![0.0; n];
        self.mass_times(&x, &mut r);
        for (ri, bi) in r.iter_mut().zip(&b) {
            *ri = bi - *ri;
        }
        let precondition = |r: &[f64]| -> Vec<f64> {
            r.iter()
                .zip(&diag)
                .map(|(r, d)| if *d > 0.0 { r / d } else { 0.0 })
                .collect()
        };
        let mut z = precondition(&r);
        let mut d = z.clone();
        let mut rz: f64 = r.iter().zip(&z).map(|(a, b)| a * b).sum();
        let mut q = vec![0.0; n];
        for _ in 0..4 * n.max(10) {
            if r.iter().map(|v| v * v).sum::<f64>().sqrt() <= 1e-14 * bnorm {
                break;
            }
            self.mass_times(&d, &mut q);
            let dq: f64 = d.iter().zip(&q).map(|(a, b)| a * b).sum();
            if dq <= 0.0 {
                break;
            }
            let alpha = rz / dq;
            for k in 0..n {
                x[k] += alpha * d[k];
                r[k] -= alpha * q[k];
            }
            z = precondition(&r);
            let rz_next: f64 = r.iter().zip(&z).map(|(a, b)| a * b).sum();
            let beta = rz_next / rz;
            rz = rz_next;
            for k in 0..n {
                d[k] = z[k] + beta * d[k];
            }
        }
        // the projection is global: keep it at the nodes of the faces that
        // carry pressure (its tail elsewhere is not contact)
        for (k, v) in x.iter_mut().enumerate() {
            if !self.node_points[k]
                .iter()
                .any(|&(g, _)| self.pressure[g] > 0.0)
            {
                *v = 0.0;
            }
        }
        self.nodal = x;
    }

    /// The pressure at slave node `node`: the L2 projection of the points'
    /// pressures at the last evaluation, clamped at 0 (the projection of a
    /// pressure that vanishes across a face overshoots there), and 0 at a
    /// node none of whose faces has a loaded point.
    pub fn node_pressure(&self, node: usize) -> f64 {
        self.nodes
            .binary_search(&node)
            .map_or(0.0, |i| self.nodal[i].max(0.0))
    }

    /// The `|N_a| w`-weighted mean of the pressures of the points of slave
    /// node `node` (positive weights: exact for a uniform pressure).
    fn mean_pressure(&self, node: usize) -> f64 {
        let Ok(i) = self.nodes.binary_search(&node) else {
            return 0.0;
        };
        let (mut s, mut w) = (0.0, 0.0);
        for &(g, wg) in &self.node_points[i] {
            s += wg * self.pressure[g];
            w += wg;
        }
        if w > 0.0 {
            s / w
        } else {
            0.0
        }
    }

    /// Largest violation of the contact conditions over the points of the
    /// last evaluation: `|g|` where a pressure acts, the penetration
    /// elsewhere (the augmented-Lagrangian stopping test).
    pub fn violation(&self) -> f64 {
        self.gap
            .iter()
            .zip(&self.pressure)
            .filter(|(g, _)| g.is_finite())
            .map(|(g, p)| if *p > 0.0 { g.abs() } else { (-g).max(0.0) })
            .fold(0.0, f64::max)
    }

    /// Uzawa update `lambda*_g <- max(0, lambda*_g - k g_g)` (0 at points
    /// without a foot).
    pub fn uzawa_update(&mut self) {
        for (g, p) in self.rule.points.iter().enumerate() {
            let k = self.stiffness[p.facet];
            self.multiplier[g] = if self.gap[g].is_finite() {
                (self.multiplier[g] - k * self.gap[g]).max(0.0)
            } else {
                0.0
            };
        }
    }

    /// Keeps the trial multipliers (converged increment).
    pub fn commit(&mut self) {
        self.committed.clone_from(&self.multiplier);
    }

    /// Returns to the committed multipliers.
    pub fn rollback(&mut self) {
        self.multiplier.clone_from(&self.committed);
    }

    /// Sets the committed multipliers (restart points) and rolls back.
    pub fn restore(&mut self, multiplier: &[f64]) -> Result<(), String> {
        if multiplier.len() != self.committed.len() {
            return Err(
                "the restart point does not match the model (contact integration points)".into(),
            );
        }
        self.committed = multiplier.to_vec();
        self.rollback();
        Ok(())
    }

    /// Forces of `couplings` summed at slave node `node`, and its diagonal
    /// tangent block.
    pub fn node_force<const D: usize>(
        couplings: &[Coupling],
        node: usize,
    ) -> ([f64; D], [[f64; D]; D]) {
        let (mut f, mut k) = ([0.0; D], [[0.0; D]; D]);
        for c in couplings {
            let Ok(a) = c.nodes.binary_search(&node) else {
                continue;
            };
            let nd = D * c.nodes.len();
            for (i, (fi, ki)) in f.iter_mut().zip(k.iter_mut()).enumerate() {
                *fi += c.force[D * a + i];
                for (j, kij) in ki.iter_mut().enumerate() {
                    *kij += c.tangent[(D * a + i) * nd + D * a + j];
                }
            }
        }
        (f, k)
    }
}

/// The planar curvature `W = h t ⊗ t` (`t` the unit tangent) of a normal
/// `n` and normal rate `h`.
pub fn planar_curvature(normal: [f64; 2], h: f64) -> [[f64; 2]; 2] {
    let t = [normal[1], -normal[0]];
    [
        [h * t[0] * t[0], h * t[0] * t[1]],
        [h * t[1] * t[0], h * t[1] * t[1]],
    ]
}

/// Pressure per unit gap of `method` (0 for Lagrange multipliers).
pub fn pressure_stiffness(method: &ContactMethod) -> f64 {
    match method {
        ContactMethod::Penalty { stiffness, .. }
        | ContactMethod::AugmentedLagrange {
            penalty: stiffness, ..
        } => *stiffness,
        ContactMethod::Lagrange { .. } => 0.0,
    }
}

/// The method of one integration point of a facet of pressure per unit
/// gap `k`: `method` as an area penalty of coefficient `k` (the point's
/// weight is its tributary area), so that the friction laws of the nodes
/// ([`super::friction::tangential_stiffness`]: the law's `stiffness`
/// times the area, or a tenth of the normal one) apply unchanged.
pub fn point_method(method: &ContactMethod, k: f64) -> ContactMethod {
    match method {
        ContactMethod::AugmentedLagrange {
            tolerance, update, ..
        } => ContactMethod::AugmentedLagrange {
            kind: PenaltyKind::Area,
            penalty: k,
            tolerance: *tolerance,
            update: *update,
        },
        _ => ContactMethod::Penalty {
            kind: PenaltyKind::Area,
            stiffness: k,
        },
    }
}

/// Whether a body has quadratic cells (its contact faces have midside
/// nodes).
pub fn body_is_quadratic<const D: usize>(model: &Model<D>, body: usize) -> bool {
    model.bodies.get(body).is_some_and(|b| {
        b.cells
            .clone()
            .any(|c| c < model.mesh.cells.len() && model.mesh.cells.kind(c).order() > 1)
    })
}

/// The face-integrated state of planar pair `pair`: `Some` for a pair
/// against a rigid tool whose slave body has quadratic cells (its edges `[a, b]` become `[a, b, m]`).
pub fn planar_pair(model: &Model, pair: usize) -> Option<FacetPair> {
    let cp = model.contacts.get(pair)?;
    if !matches!(cp.master, ContactMaster::Tool(_)) || !body_is_quadratic(model, cp.body) {
        return None;
    }
    let midsides = model.mesh.edge_midsides();
    let facets = cp
        .edges
        .iter()
        .map(|&e| crate::mesh::Mesh::edge_facet(&midsides, e).nodes().to_vec())
        .collect();
    let rule = FacetRule::planar(
        &model.mesh.nodes,
        facets,
        model.analysis.kind == AnalysisKind::Axisymmetric,
        model.analysis.thickness,
    );
    Some(FacetPair::new(rule, |node| {
        pressure_stiffness(&cp.method_at(node))
    }))
}

/// Evaluates the face-integrated planar pair `pair` at current
/// coordinates `x` and time `t`: fills `state.couplings` (the forces the
/// solver scatters) and returns one entry per slave node within the
/// window or loaded by a face (output: gap, pressure field, force).
pub fn evaluate_planar(
    model: &Model,
    pair: usize,
    x: &[[f64; 2]],
    t: f64,
    state: &mut PairState,
) -> Vec<NodeContact> {
    let Some(cp) = model.contacts.get(pair) else {
        return Vec::new();
    };
    let tool = cp.master.tool().and_then(|i| model.tools.get(i));
    let (Some(tool), Some(mut fp)) = (tool, state.facets.take()) else {
        return Vec::new();
    };
    let Some(shape) = state.shape.as_ref() else {
        state.facets = Some(fp);
        return Vec::new();
    };
    let placement = match state.angle {
        Some(theta) => Placement::at(&tool.motion, t).with_angle(theta),
        None => Placement::at(&tool.motion, t),
    };
    let prof = state.prof;
    let mut tests = 0usize;
    state.friction.impact = None;
    let law = cp.friction.as_ref();
    let np = fp.rule.points.len();
    let mut point_friction: Vec<Option<NodeFriction>> =
        vec![None; if law.is_some() { np } else { 0 }];
    let mut point_contact = Vec::new();
    let (grid, scratch, memory, history) = (
        &state.tool_grid,
        &mut state.scratch,
        &mut state.point_memory,
        &mut state.friction,
    );
    let mut find = |xr: [f64; 2], memory: Option<usize>, tests: &mut usize| {
        let request = search::Request {
            x: xr,
            window: prof,
            memory,
            guess: None,
            test: cp.search,
        };
        search::closest_in(shape, grid, request, scratch, tests)
    };
    let mut project = |g: usize, xg: [f64; 2]| {
        let xr = placement.to_reference(xg);
        let found = find(xr, memory[g], &mut tests)?;
        memory[g] = Some(found.entity);
        let p = found.projection;
        if p.gap > prof {
            return None;
        }
        let normal = placement.rotate(p.normal);
        Some((
            PointProjection {
                gap: p.gap,
                normal,
                curvature: planar_curvature(normal, p.normal_rate),
            },
            (p, xr, found.entity),
        ))
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
        fp.evaluate_lagrange(x, prof, &multiplier, |g, xg| project(g, xg).map(|p| p.0))
    } else {
        fp.evaluate_with(x, state.touching, project, |load, ft, kt| {
            let Some(law) = law else {
                return false;
            };
            let g = load.point;
            let (Some((pr, (raw, xr, entity))), true) = (load.found, load.normal_force > 0.0)
            else {
                history.open(g, placement.to_reference(load.x));
                return false;
            };
            let method = point_method(&cp.method, load.stiffness);
            let contact = friction::ToolContact {
                shape,
                placement: &placement,
                x: load.x,
                reference: *xr,
                projection: raw,
                normal: pr.normal,
                window: prof.max(super::vec2::norm(super::vec2::sub(
                    *xr,
                    history.committed_position[g],
                ))) * 4.0,
            };
            let mut r = super::penalty::Response {
                force: [
                    load.normal_force * pr.normal[0],
                    load.normal_force * pr.normal[1],
                ],
                stiffness: [[0.0; 2]; 2],
                pressure: 0.0,
                status: ContactStatus::Closed,
            };
            let nf =
                friction::respond_tool(law, &method, load.weight, g, &contact, history, &mut r);
            *ft = nf.traction;
            *kt = r.stiffness;
            point_friction[g] = Some(nf);
            point_contact.push(NodeContact {
                node: g,
                gap: pr.gap,
                normal: pr.normal,
                force: nf.traction,
                stiffness: r.stiffness,
                pressure: load.normal_force / load.weight,
                status: ContactStatus::Closed,
                entity: *entity,
                master: None,
                friction: nf,
            });
            true
        })
    };
    let mut find = |xr: [f64; 2], memory: Option<usize>, tests: &mut usize| {
        let request = search::Request {
            x: xr,
            window: prof,
            memory,
            guess: None,
            test: cp.search,
        };
        search::closest_in(shape, &state.tool_grid, request, &mut state.scratch, tests)
    };
    let mut out = Vec::new();
    for (i, &node) in state.slaves.iter().enumerate() {
        let Some(&xn) = x.get(node) else {
            continue;
        };
        let found = find(placement.to_reference(xn), state.last_entity[i], &mut tests);
        if lagrange {
            // the node's constraint: its weighted gap (no row: left out,
            // and released if active)
            let gap = fp.node_weighted_gap(node);
            if !gap.is_finite() {
                continue;
            }
            if let Some(f) = &found {
                state.last_entity[i] = Some(f.entity);
            }
            // closed-gap start: touching nodes join the active set with a
            // zero multiplier
            if state.touching > 0.0 && gap <= state.touching && !state.active[i] {
                state.active[i] = true;
                state.multiplier[i] = 0.0;
            }
            let (force, stiffness) = FacetPair::node_force::<2>(&couplings, node);
            out.push(NodeContact {
                node,
                gap,
                normal: found
                    .as_ref()
                    .map_or([0.0; 2], |f| placement.rotate(f.projection.normal)),
                force,
                stiffness,
                pressure: fp.node_pressure(node),
                status: if state.active[i] {
                    ContactStatus::Closed
                } else {
                    ContactStatus::Open
                },
                entity: found.as_ref().map_or(0, |f| f.entity),
                master: None,
                friction: NodeFriction::default(),
            });
            continue;
        }
        let Some(found) = found else {
            continue;
        };
        state.last_entity[i] = Some(found.entity);
        let p = found.projection;
        let (force, stiffness) = FacetPair::node_force::<2>(&couplings, node);
        if p.gap > prof && force == [0.0; 2] {
            continue;
        }
        let pressure = fp.node_pressure(node);
        let normal = placement.rotate(p.normal);
        let mut friction = fp.node_friction(node, &point_friction);
        friction.tangential_force = super::vec2::dot(friction.traction, [normal[1], -normal[0]]);
        out.push(NodeContact {
            node,
            gap: p.gap,
            normal,
            force,
            stiffness,
            pressure,
            status: if pressure > 0.0 {
                ContactStatus::Closed
            } else {
                ContactStatus::Open
            },
            entity: found.entity,
            master: None,
            friction,
        });
    }
    state.last_projection_tests = tests;
    state.last_brute_force_tests =
        (fp.rule.points.len() + state.slaves.len()) * shape.entity_count();
    state.total_projection_tests += tests as u64;
    state.couplings = Some(couplings);
    state.point_contact = point_contact;
    state.facets = Some(fp);
    out
}

/// An empty coupling over the sorted distinct nodes of `facet`, and the
/// position of each facet node among them.
fn facet_coupling<const D: usize>(facet: &[usize]) -> (Coupling, Vec<usize>) {
    let mut sorted = facet.to_vec();
    sorted.sort_unstable();
    sorted.dedup();
    let pos = facet
        .iter()
        .map(|n| sorted.binary_search(n).unwrap_or(0))
        .collect();
    let nd = D * sorted.len();
    let c = Coupling {
        nodes: sorted,
        force: vec![0.0; nd],
        tangent: vec![0.0; nd * nd],
        slave: facet.first().copied().unwrap_or(0),
        gap_gradient: Vec::new(),
        force_direction: Vec::new(),
    };
    (c, pos)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A 3-node edge of length 2 along x: the consistent shares of a
    /// uniform pressure are 1/6, 4/6, 1/6; a tri6 face's corners 0 and a
    /// quad8 face's -1/12 (the reason for integrating at points).
    #[test]
    fn consistent_areas_of_quadratic_facets() {
        let nodes2 = [[0.0, 0.0], [2.0, 0.0], [1.0, 0.0]];
        let r = FacetRule::planar(&nodes2, vec![vec![0, 1, 2]], false, 3.0);
        let a = r.consistent_areas();
        for (node, expect) in [(0, 1.0), (1, 1.0), (2, 4.0)] {
            assert!((a[node].1 - expect).abs() < 1e-14, "{a:?}");
        }
        // quad8 face of the unit square: corners -1/12, midsides 1/3
        let q = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.0, 0.0],
            [1.0, 0.5, 0.0],
            [0.5, 1.0, 0.0],
            [0.0, 0.5, 0.0],
        ];
        let r = FacetRule::solid(&q, vec![(0..8).collect()]);
        let a = r.consistent_areas();
        for (node, area) in a {
            let expect = if node < 4 { -1.0 / 12.0 } else { 1.0 / 3.0 };
            assert!((area - expect).abs() < 1e-14, "{node}: {area}");
        }
        // tri6 face: corners 0, midsides 1/6 of the area 1/2
        let t = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.0, 0.0],
            [0.5, 0.5, 0.0],
            [0.0, 0.5, 0.0],
        ];
        let r = FacetRule::solid(&t, vec![(0..6).collect()]);
        for (node, area) in r.consistent_areas() {
            let expect = if node < 3 { 0.0 } else { 1.0 / 6.0 };
            assert!((area - expect).abs() < 1e-14, "{node}: {area}");
        }
    }

    /// Flat tool `z = 0` (normal +z): the penetration `d` of every point
    /// gives the consistent loads of the uniform pressure `k d`, and the
    /// normal tangent is `k int N_a N_b dA`.
    #[test]
    fn a_uniform_gap_gives_the_consistent_loads_of_a_uniform_pressure() {
        let q = flat_quad8();
        let mut fp = FacetPair::new(FacetRule::solid(&q, vec![(0..8).collect()]), |_| 100.0);
        let c = fp.evaluate(&q, 0.0, |_, x| {
            Some(PointProjection {
                gap: x[2],
                normal: [0.0, 0.0, 1.0],
                curvature: [[0.0; 3]; 3],
            })
        });
        assert_eq!(c.len(), 1);
        let p = 100.0 * 0.01;
        for (a, &node) in c[0].nodes.iter().enumerate() {
            let share = if node < 4 { -1.0 / 12.0 } else { 1.0 / 3.0 };
            assert!((c[0].force[3 * a + 2] - p * 2.0 * share).abs() < 1e-13);
            assert_eq!(c[0].force[3 * a], 0.0);
        }
        let total: f64 = (0..8).map(|a| c[0].force[3 * a + 2]).sum();
        assert!((total - 2.0 * p).abs() < 1e-13);
        assert!((fp.node_pressure(0) - p).abs() < 1e-13);
        assert!((fp.violation() - 0.01).abs() < 1e-15);
        fp.uzawa_update();
        assert!(fp.multiplier.iter().all(|m| (m - p).abs() < 1e-13));
    }

    /// The multiplier basis keeps the partition of unity and gives every
    /// node a positive weight: tri6 corners 2/15, quad8 corners 1/20 of
    /// the area, a 3-node edge's corner on the axis `alpha int N_m 2 pi r`
    /// (0 with the shape functions).
    #[test]
    fn multiplier_basis_weights_are_positive() {
        let quad8 = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.0, 0.0],
            [1.0, 0.5, 0.0],
            [0.5, 1.0, 0.0],
            [0.0, 0.5, 0.0],
            [0.5, 0.5, 0.0],
        ];
        let tri6 = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.0, 0.0],
            [0.5, 0.5, 0.0],
            [0.0, 0.5, 0.0],
        ];
        // (face nodes, node count, area, corner and midside weight / area)
        type Case<'a> = (&'a [[f64; 3]], usize, f64, f64, f64);
        let cases: [Case<'_>; 3] = [
            (&tri6, 6, 0.5, 2.0 / 15.0, 0.2),
            (&quad8, 8, 1.0, 0.05, 0.2),
            (&quad8, 9, 1.0, 1.0 / 36.0 + 0.4 / 9.0, 0.6 / 9.0),
        ];
        for (nodes, n, area, corner, midside) in cases {
            let fp = FacetPair::new(FacetRule::solid(nodes, vec![(0..n).collect()]), |_| 0.0);
            // partition of unity, and biorthogonal to the N~ of the face
            let mut dual = vec![0.0; n * n];
            for p in &fp.rule.points {
                assert!((p.basis.iter().sum::<f64>() - 1.0).abs() < 1e-13);
                let nt = multiplier_basis(&p.shape, facet_midsides(n, false));
                for a in 0..n {
                    for b in 0..n {
                        dual[a * n + b] += p.weight * p.basis[a] * nt[b];
                    }
                }
            }
            for a in 0..n {
                for b in 0..n {
                    let expect = if a == b { fp.support[a] } else { 0.0 };
                    assert!((dual[a * n + b] - expect).abs() < 1e-13, "{n}: {a} {b}");
                }
            }
            let nc = if n == 6 { 3 } else { 4 };
            for (a, s) in fp.support.iter().enumerate() {
                let expect = if a < nc {
                    corner * area
                } else if a < 2 * nc {
                    midside * area
                } else {
                    16.0 / 36.0
                };
                assert!((s - expect).abs() < 1e-14, "{n} node {a}: {s} vs {expect}");
            }
        }
        // axisymmetric edge from the axis: corner weight alpha int N_m 2 pi r
        let edge = [[0.0, 0.0], [1.0, 0.0], [0.5, 0.0]];
        let plain = FacetRule::planar(&edge, vec![vec![0, 1, 2]], true, 1.0);
        assert!(plain.consistent_areas()[0].1.abs() < 1e-14);
        let fp = FacetPair::new(plain, |_| 0.0);
        let mid = 2.0 * std::f64::consts::PI * (2.0 / 3.0) * 0.5;
        assert!(
            (fp.support[0] - BASIS_ALPHA * mid).abs() < 1e-13,
            "{:?}",
            fp.support
        );
        assert!(fp.support.iter().all(|s| *s > 0.0));
    }

    /// Lagrange on a flat tool: multipliers `lambda_a = p A_a` give the
    /// consistent loads of the uniform pressure `p`, and a uniform gap `d`
    /// is every node's weighted gap.
    #[test]
    fn uniform_lagrange_pressure_gives_the_consistent_loads() {
        let q = flat_quad8();
        let mut fp = FacetPair::new(FacetRule::solid(&q, vec![(0..8).collect()]), |_| 0.0);
        let p = 3.0;
        let lambda: Vec<Option<f64>> = fp.support.iter().map(|a| Some(p * a)).collect();
        let c = fp.evaluate_lagrange(&q, 1.0, &lambda, |_, x| {
            Some(PointProjection {
                gap: x[2],
                normal: [0.0, 0.0, 1.0],
                curvature: [[0.0; 3]; 3],
            })
        });
        assert_eq!(c.len(), 1);
        for (a, &node) in c[0].nodes.iter().enumerate() {
            let share = if node < 4 { -1.0 / 12.0 } else { 1.0 / 3.0 };
            assert!((c[0].force[3 * a + 2] - p * 2.0 * share).abs() < 1e-13);
        }
        assert!((fp.node_pressure(0) - p).abs() < 1e-13);
        assert_eq!(fp.rows.len(), 8);
        for r in &fp.rows {
            assert!((r.gap + 0.01).abs() < 1e-15, "{r:?}");
            // the row's z terms sum to 1 (a rigid motion changes g~ by it)
            let dz: f64 = r
                .terms
                .iter()
                .filter(|t| t.component == 2)
                .map(|t| t.coefficient)
                .sum();
            assert!((dz - 1.0).abs() < 1e-14);
        }
        assert!((fp.loaded_point_gap() - 0.01).abs() < 1e-15);
    }

    /// A 2 x 1 quad8 face in the plane z = -0.01 (0.01 into a flat tool
    /// `z = 0`).
    fn flat_quad8() -> Vec<[f64; 3]> {
        [
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [0.0, 1.0],
            [1.0, 0.0],
            [2.0, 0.5],
            [1.0, 1.0],
            [0.0, 0.5],
        ]
        .iter()
        .map(|p| [p[0], p[1], -0.01])
        .collect()
    }

    /// A quad8 (`kind` 0), tri6 (1) or quad9 (2) face in the plane z = 0
    /// (the reference) and its nodes moved by `wobble` (3 per node) and
    /// lowered by `depth` (the current positions).
    fn wobbled_face(kind: usize, depth: f64, wobble: &[f64]) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
        let base: Vec<[f64; 2]> = match kind {
            0 => vec![
                [0.0, 0.0],
                [1.0, 0.0],
                [1.0, 1.0],
                [0.0, 1.0],
                [0.5, 0.0],
                [1.0, 0.5],
                [0.5, 1.0],
                [0.0, 0.5],
            ],
            1 => vec![
                [0.0, 0.0],
                [1.0, 0.0],
                [0.0, 1.0],
                [0.5, 0.0],
                [0.5, 0.5],
                [0.0, 0.5],
            ],
            _ => vec![
                [0.0, 0.0],
                [1.0, 0.0],
                [1.0, 1.0],
                [0.0, 1.0],
                [0.5, 0.0],
                [1.0, 0.5],
                [0.5, 1.0],
                [0.0, 0.5],
                [0.5, 0.5],
            ],
        };
        let reference = base.iter().map(|p| [p[0], p[1], 0.0]).collect();
        let x = base
            .iter()
            .enumerate()
            .map(|(a, p)| {
                [
                    p[0] + wobble[3 * a],
                    p[1] + wobble[3 * a + 1],
                    wobble[3 * a + 2] - depth,
                ]
            })
            .collect();
        (reference, x)
    }

    fn sphere(x: [f64; 3], centre: [f64; 3], radius: f64) -> PointProjection<3> {
        let d: [f64; 3] = std::array::from_fn(|k| x[k] - centre[k]);
        let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let n = d.map(|v| v / r);
        let curvature = std::array::from_fn(|i| {
            std::array::from_fn(|j| (f64::from(u8::from(i == j)) - n[i] * n[j]) / r)
        });
        PointProjection {
            gap: r - radius,
            normal: n,
            curvature,
        }
    }

    fn circle(x: [f64; 2], centre: [f64; 2], radius: f64) -> PointProjection<2> {
        let d = [x[0] - centre[0], x[1] - centre[1]];
        let r = d[0].hypot(d[1]);
        let n = [d[0] / r, d[1] / r];
        PointProjection {
            gap: r - radius,
            normal: n,
            curvature: planar_curvature(n, 1.0 / r),
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]

        /// The tangent of a quad8 / tri6 / quad9 face pressed into a rigid
        /// sphere is minus the derivative of its forces (central
        /// differences), for the penalty and for the augmented Lagrangian
        /// with point multipliers.
        #[test]
        fn solid_tangent_matches_finite_differences(
            kind in 0usize..3,
            depth in 0.02f64..0.2,
            shift in -0.2f64..0.2,
            lambda in 0.0f64..2.0,
            wobble in proptest::collection::vec(-0.05f64..0.05, 27),
        ) {
            let (reference, x) = wobbled_face(kind, depth, &wobble);
            let n = x.len();
            let centre = [0.4 + shift, 0.45, -1.5];
            let mut fp = FacetPair::new(FacetRule::solid(&reference, vec![(0..n).collect()]),
                                        |_| 50.0);
            fp.multiplier.iter_mut().for_each(|m| *m = lambda);
            let forces = |fp: &mut FacetPair, x: &[[f64; 3]]| -> Vec<f64> {
                let c = fp.evaluate(x, 0.0, |_, p| Some(sphere(p, centre, 1.5)));
                let mut f = vec![0.0; 3 * n];
                for c in &c {
                    for (a, &node) in c.nodes.iter().enumerate() {
                        for i in 0..3 { f[3 * node + i] += c.force[3 * a + i]; }
                    }
                }
                f
            };
            let c = fp.evaluate(&x, 0.0, |_, p| Some(sphere(p, centre, 1.5)));
            prop_assume!(!c.is_empty());
            let c = &c[0];
            let h = 1e-7;
            let scale = c.tangent.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (b, &nb) in c.nodes.iter().enumerate() {
                for j in 0..3 {
                    let (mut xp, mut xm) = (x.clone(), x.clone());
                    xp[nb][j] += h;
                    xm[nb][j] -= h;
                    let (fp_, fm) = (forces(&mut fp, &xp), forces(&mut fp, &xm));
                    for (a, &na) in c.nodes.iter().enumerate() {
                        for i in 0..3 {
                            let fd = -(fp_[3 * na + i] - fm[3 * na + i]) / (2.0 * h);
                            let k = c.tangent[(3 * a + i) * 3 * n + 3 * b + j];
                            prop_assert!((fd - k).abs() < 1e-5 * scale.max(1.0),
                                "{a}{i},{b}{j}: fd {fd} vs {k}");
                        }
                    }
                }
            }
        }

        /// Lagrange multipliers on a quad8 / tri6 / quad9 face pressed into
        /// a rigid sphere: the forces are `sum_a lambda_a` times the rows,
        /// the rows are the derivatives of the weighted gaps and the
        /// tangent minus the derivative of the forces (central
        /// differences), with multipliers of both signs and inactive nodes.
        #[test]
        fn lagrange_rows_and_tangent_match_finite_differences(
            kind in 0usize..3,
            depth in 0.02f64..0.2,
            lambda in proptest::collection::vec(-0.5f64..2.0, 9),
            wobble in proptest::collection::vec(-0.05f64..0.05, 27),
        ) {
            let (reference, x) = wobbled_face(kind, depth, &wobble);
            let n = x.len();
            let centre = [0.4, 0.45, -1.5];
            let mut fp = FacetPair::new(FacetRule::solid(&reference, vec![(0..n).collect()]),
                                        |_| 0.0);
            // every third node inactive
            let lam: Vec<Option<f64>> =
                (0..n).map(|a| (a % 3 != 2).then_some(lambda[a])).collect();
            let evaluate = |fp: &mut FacetPair, x: &[[f64; 3]]| -> (Vec<f64>, Vec<f64>) {
                let c = fp.evaluate_lagrange(x, 10.0, &lam, |_, p| Some(sphere(p, centre, 1.5)));
                let mut f = vec![0.0; 3 * n];
                for c in &c {
                    for (a, &node) in c.nodes.iter().enumerate() {
                        for i in 0..3 { f[3 * node + i] += c.force[3 * a + i]; }
                    }
                }
                (f, fp.weighted_gap.clone())
            };
            let c = fp.evaluate_lagrange(&x, 10.0, &lam, |_, p| Some(sphere(p, centre, 1.5)));
            prop_assert_eq!(c.len(), 1);
            let c = &c[0];
            let rows = fp.rows.clone();
            prop_assert_eq!(rows.len(), n);
            // forces = sum_a lambda_a row_a
            let mut f0 = vec![0.0; 3 * n];
            for (a, r) in rows.iter().enumerate() {
                if let Some(l) = lam[a] {
                    for t in &r.terms { f0[3 * t.node + t.component] += l * t.coefficient; }
                }
            }
            for (a, &node) in c.nodes.iter().enumerate() {
                for i in 0..3 {
                    prop_assert!((f0[3 * node + i] - c.force[3 * a + i]).abs() < 1e-12);
                }
            }
            let h = 1e-7;
            let scale = c.tangent.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (b, &nb) in c.nodes.iter().enumerate() {
                for j in 0..3 {
                    let (mut xp, mut xm) = (x.clone(), x.clone());
                    xp[nb][j] += h;
                    xm[nb][j] -= h;
                    let ((fp_, gp), (fm, gm)) = (evaluate(&mut fp, &xp), evaluate(&mut fp, &xm));
                    for (a, &na) in c.nodes.iter().enumerate() {
                        for i in 0..3 {
                            let fd = -(fp_[3 * na + i] - fm[3 * na + i]) / (2.0 * h);
                            let k = c.tangent[(3 * a + i) * 3 * n + 3 * b + j];
                            prop_assert!((fd - k).abs() < 1e-5 * scale.max(1.0),
                                "{a}{i},{b}{j}: fd {fd} vs {k}");
                        }
                    }
                    for (a, r) in rows.iter().enumerate() {
                        let fd = (gp[a] - gm[a]) / (2.0 * h);
                        let k = r.terms.iter().find(|t| t.node == nb && t.component == j)
                            .map_or(0.0, |t| t.coefficient);
                        prop_assert!((fd - k).abs() < 1e-6, "row {a} {nb}{j}: fd {fd} vs {k}");
                    }
                }
            }
        }

        /// The same for a 3-node edge against a rigid circle (plane and
        /// axisymmetric measures).
        #[test]
        fn planar_tangent_matches_finite_differences(
            axi in proptest::bool::ANY,
            depth in 0.02f64..0.2,
            shift in -0.3f64..0.3,
            lambda in 0.0f64..2.0,
            wobble in proptest::collection::vec(-0.05f64..0.05, 6),
        ) {
            let reference = [[0.5, 0.0], [1.5, 0.0], [1.0, 0.0]];
            let x: Vec<[f64; 2]> = reference
                .iter()
                .enumerate()
                .map(|(a, p)| [p[0] + wobble[2 * a], p[1] + wobble[2 * a + 1] - depth])
                .collect();
            let centre = [1.0 + shift, -2.0];
            let mut fp = FacetPair::new(
                FacetRule::planar(&reference, vec![vec![0, 1, 2]], axi, 1.0), |_| 30.0);
            fp.multiplier.iter_mut().for_each(|m| *m = lambda);
            let forces = |fp: &mut FacetPair, x: &[[f64; 2]]| -> Vec<f64> {
                let c = fp.evaluate(x, 0.0, |_, p| Some(circle(p, centre, 2.0)));
                let mut f = vec![0.0; 6];
                for c in &c {
                    for (a, &node) in c.nodes.iter().enumerate() {
                        for i in 0..2 { f[2 * node + i] += c.force[2 * a + i]; }
                    }
                }
                f
            };
            let c = fp.evaluate(&x, 0.0, |_, p| Some(circle(p, centre, 2.0)));
            prop_assume!(!c.is_empty());
            let c = &c[0];
            let h = 1e-7;
            let scale = c.tangent.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for b in 0..3 {
                for j in 0..2 {
                    let (mut xp, mut xm) = (x.clone(), x.clone());
                    xp[b][j] += h;
                    xm[b][j] -= h;
                    let (fp_, fm) = (forces(&mut fp, &xp), forces(&mut fp, &xm));
                    for a in 0..3 {
                        for i in 0..2 {
                            let fd = -(fp_[2 * a + i] - fm[2 * a + i]) / (2.0 * h);
                            let k = c.tangent[(2 * a + i) * 6 + 2 * b + j];
                            prop_assert!((fd - k).abs() < 1e-5 * scale.max(1.0),
                                "{a}{i},{b}{j}: fd {fd} vs {k}");
                        }
                    }
                }
            }
        }
    }

    /// A quad8 / quad9 / tri6 cell whose bottom edge `y = 0` (corners 0
    /// and 1) is the slave edge of a pair against a rigid circle below it
    /// or an inclined plane, with friction `law` (plane strain or
    /// axisymmetric).
    fn planar_model(
        kind: usize,
        axisymmetric: bool,
        method: ContactMethod,
        circle: bool,
        law: crate::model::Friction,
    ) -> Model {
        use crate::mesh::{elevate::elevate, Cell, CellKind, Mesh};
        use crate::model::{ToolGeometry, ToolMotion, ToolSide};
        let (linear, target) = if kind == 2 {
            let m = Mesh::new(
                vec![[0.5, 0.0], [1.5, 0.0], [1.0, 1.0]],
                vec![Cell::tri(0, 1, 2)],
            );
            (m, CellKind::Tri6)
        } else {
            let m = Mesh::new(
                vec![[0.5, 0.0], [1.5, 0.0], [1.5, 1.0], [0.5, 1.0]],
                vec![Cell::quad(0, 1, 2, 3)],
            );
            (
                m,
                if kind == 0 {
                    CellKind::Quad8
                } else {
                    CellKind::Quad9
                },
            )
        };
        let mesh = elevate(&linear, target).unwrap();
        let kind = if axisymmetric {
            AnalysisKind::Axisymmetric
        } else {
            AnalysisKind::PlaneStrain
        };
        let geometry = if circle {
            ToolGeometry::Circle {
                center: [1.1, -2.0],
                radius: 2.0,
                side: ToolSide::Outside,
            }
        } else {
            let n: [f64; 2] = [-0.2, 1.0];
            let l = n[0] * n[0] + n[1] * n[1];
            ToolGeometry::Plane {
                point: [1.0, -0.05],
                normal: [n[0] / l.sqrt(), n[1] / l.sqrt()],
            }
        };
        crate::testkit::ModelBuilder::new(kind)
            .elastic("m", 1.0, 0.3)
            .body("b", mesh, "m")
            .tool("tool", geometry, ToolMotion::fixed())
            .contact_tool("b -> tool", "b", vec![[0, 1]], "tool", method)
            .friction(law)
            .prof(10.0)
            .build()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]

        /// Friction on 3-node edges (plane and axisymmetric, tri6 / quad8 /
        /// quad9 cells): the rows' tangent is minus the derivative of their
        /// forces (central differences), penalty and augmented Lagrangian,
        /// stick points offset along the tool (stick and slip mixed) or on
        /// the first-impact path (penalty, inclined plane).
        #[test]
        fn planar_friction_tangent_matches_finite_differences(
            kind in 0usize..3, axi in any::<bool>(), circle in any::<bool>(),
            augmented in any::<bool>(), first in any::<bool>(),
            mu in 0.05f64..1.0, depth in 0.02f64..0.15,
            wobble in proptest::collection::vec(-0.03f64..0.03, 6),
            offsets in proptest::collection::vec(-0.05f64..0.05, 8),
            shift in proptest::collection::vec(-0.5f64..0.5, 8),
        ) {
            use crate::model::{FirstImpact, Friction, PenaltyKind};
            let method = if augmented {
                ContactMethod::AugmentedLagrange {
                    kind: PenaltyKind::Area,
                    penalty: 40.0,
                    tolerance: 1e-3,
                    update: crate::model::MultiplierUpdate::Converged,
                }
            } else {
                ContactMethod::Penalty { kind: PenaltyKind::Area, stiffness: 40.0 }
            };
            let law = Friction {
                mu,
                stiffness: Some(15.0),
                first_impact: FirstImpact::Intersect,
                cut_at_impact: false,
            };
            // the first-impact path's rate is exact for a plane only (the
            // planar intersection is found by bisection on the tool), and
            // for a point that crossed the tool (an augmented-Lagrangian
            // point closed at a positive gap sticks at its foot, whose rate
            // `friction::respond_tool` leaves out, on linear faces too)
            let first = first && !circle && !augmented;
            let m = planar_model(kind, axi, method, circle, law);
            let mut state = PairState::new(&m, 0);
            let np = state.facets.as_ref().unwrap().rule.points.len();
            prop_assert_eq!(np, 4);
            prop_assert_eq!(state.friction.committed_anchor.len(), np);
            for g in 0..np {
                let xr = state.friction.committed_position[g];
                if first {
                    state.friction.committed_position[g] = [xr[0] + offsets[g], xr[1] + 0.3];
                } else {
                    state.friction.committed_anchor[g] = Some([xr[0] + offsets[g], xr[1]]);
                }
                if augmented {
                    state.friction.multiplier[g] = shift[g];
                    state.facets.as_mut().unwrap().multiplier[g] = 0.5 + shift[g + 4];
                }
            }
            state.friction.base = state.friction.committed_anchor.clone();
            let facet = state.facets.as_ref().unwrap().rule.facets[0].clone();
            let mut x0 = m.mesh.nodes.clone();
            for (a, &node) in facet.iter().enumerate() {
                x0[node][0] += wobble[2 * a];
                x0[node][1] += wobble[2 * a + 1] - depth;
            }
            let nn = x0.len();
            let forces = |x: &[[f64; 2]]| {
                let mut st = state.clone();
                let out = super::super::evaluate_pair(&m, 0, x, 0.0, &mut st);
                let couplings = st.couplings.clone().unwrap_or_default();
                let mut f = vec![0.0; 2 * nn];
                for c in &couplings {
                    for (a, &node) in c.nodes.iter().enumerate() {
                        for i in 0..2 { f[2 * node + i] += c.force[2 * a + i]; }
                    }
                }
                let status: Vec<_> = st.point_contact.iter()
                    .map(|c| (c.node, c.friction.status)).collect();
                (f, couplings, status, out)
            };
            let (_, couplings, status, out) = forces(&x0);
            prop_assume!(!couplings.is_empty());
            prop_assert!(status.iter().any(|s| s.1 != friction::FrictionStatus::Frictionless));
            prop_assert!(out.iter().any(|c| c.friction.traction != [0.0; 2]));
            let c = &couplings[0];
            let nd = 2 * c.nodes.len();
            let scale = c.tangent.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let h = 1e-7;
            let mut compared = 0;
            for (b, &nb) in c.nodes.iter().enumerate() {
                for j in 0..2 {
                    let (mut xp, mut xm) = (x0.clone(), x0.clone());
                    xp[nb][j] += h;
                    xm[nb][j] -= h;
                    let (fp_, _, sp, _) = forces(&xp);
                    let (fm, _, sm, _) = forces(&xm);
                    if sp != status || sm != status {
                        continue;
                    }
                    compared += 1;
                    for (a, &na) in c.nodes.iter().enumerate() {
                        for i in 0..2 {
                            let fd = -(fp_[2 * na + i] - fm[2 * na + i]) / (2.0 * h);
                            let k = c.tangent[(2 * a + i) * nd + 2 * b + j];
                            prop_assert!((fd - k).abs() < 1e-5 * scale.max(1.0),
                                "{na}{i},{nb}{j}: fd {fd} vs {k} ({status:?})");
                        }
                    }
                }
            }
            prop_assert!(compared > 0);
        }
    }
}
