//! Coulomb friction on a node-to-facet element (3D, deformable master,
//! [`super::node_to_facet`]): the regularized law of
//! [`super::friction_surface`] with the stick point convected by the
//! master surface, the 3D form of [`super::friction_segment`].
//!
//! The stick point is a material point of the master surface, stored by
//! its facet and that facet's parametric coordinates, `(k_a, xi_a)`
//! (carried in [`FrictionState::anchor`] as `[k_a, xi_a1, xi_a2]`, so the
//! commit / rollback and the restart checkpoint of the rigid-tool friction
//! carry it unchanged). Its current position is `x_a = sum N_b(xi_a) x_b`
//! over facet `k_a`'s current nodes: the master's deformation and rigid
//! motion carry it. With the slave node `x_s` projected on facet `k` at
//! `xi` (normal `n`, `P = I - n ⊗ n`):
//!
//! - tangential gap `g_T = P (x_s - x_a)` (a vector of the tangent plane);
//! - trial force `t* = P m - k_T g_T` (`m` the augmented-Lagrangian shift,
//!   a vector of the current frame; 0 for the penalty method);
//! - return map onto the disc `|t| <= mu R_N` in the tangent plane: stick
//!   `t = t*`; slip `t = mu R_N t* / |t*|`, the stick point moving by
//!   `delta = (t - t*) / k_T` (re-expressed on facet `k` by the foot of
//!   `x_a + delta`), dissipation `-t . slip`.
//!
//! Forces over `[x_s, x_1 .. x_n (facet k), y_1 .. y_m (facet k_a)]`: `t`
//! on the slave, `-N_b(xi) t` on facet `k`'s nodes (the reaction at the
//! contact point), none on `k_a`'s (they only place the stick point); the
//! forces sum to zero, their moment is `(x_s - x(xi)) x t = g n x t`, the
//! lever arm of the penalty penetration (0 at `g = 0`). `R_N(x) = R_N +
//! alpha_N (g_now - g(x))` (penalty and augmented Lagrangian alike). The
//! tangent `-d f / d x` is exact (stick and slip, with the motion of the
//! foot point, the rotation of the normal and the motion of the stick
//! point's facet) by the dual numbers of [`super::mortar::ad`] carried
//! through one Newton step of the foot-point equations at the converged
//! foot, as [`super::node_to_facet::face_element`] does; it is not
//! symmetric.
//!
//! At an edge or vertex projection ([`Feature::Edge`], [`Feature::Vertex`]:
//! the node in the wedge in front of a convex edge or the corner in front
//! of a vertex, [`super::node_to_facet::edge_element`]) the normal that
//! gives the gap is the direction from the closest point `p` of the edge
//! (vertex) to the node, `n = s (x_s - p) / |x_s - p|`, and the friction
//! acts in *its* tangent plane ("one geometry everywhere", as
//! [`super::friction_segment::Vertex`] in 2D): `P = I - n ⊗ n` with that
//! `n`, the reaction `-N_b t` at `p` (edge weights `1 - t`, `t`; vertex 1),
//! so `t . n = 0` and the moment is still `g n x t`. The stick point stays
//! a material point of a facet; after a slip it is the point of facet `k`
//! (extended) on the line through `x_a + delta` along `n`, so that its
//! tangential gap `P (x_s - x_a)` is the elastic part `-t / k_T` (the
//! foot along the facet's own normal would add the tilt between the two
//! normals to it). The facet's tangent plane was used there before: off by
//! the turn of the normal across the wedge (up to the kink angle).
//!
//! First touch (no committed stick point): `first_impact = frictionless`
//! leaves that increment without tangential force (the stick point is the
//! foot at its end); `intersect` (the default) sticks the node where its
//! straight path from the converged position `x_0` crosses the tangent
//! plane of the iterate evaluated ([`FacetFriction::impact`]: `x_0 + tau
//! (x_s - x_0)`, `tau = g_0 / (g_0 - g)` recomputed at every evaluation),
//! with the stick point's motion (w.r.t. the slave and the facet's nodes)
//! in the tangent: the trial force `-k_T (1 - tau) P (x_s - x_0)` vanishes with
//! the gap, and the answer does not depend on the iterates. The stick
//! point recorded is the facet's material point at the crossing. That is
//! the penalty method's rule (as mortar's). A node behind the plane at the
//! start (`g_0 <= 0`) sticks at the facet's material point at the foot of
//! `x_0`, and with the augmented Lagrangian a node sticks at the foot of
//! the crossing (of `x_s` at a positive gap), all fixed at the first
//! closed evaluation and convected with the facet (held in
//! [`FrictionState::base`]; a spatial `x_0` would count the master's own
//! motion as slip: `friction_blocks_ntf_3d`, whose block overlaps its base
//! by 1e-6, then stopped in its press; and the crossing following the
//! iterate in the augmented Lagrangian's double pass, where every swap of
//! sides is a first touch, took 7.7 % off its `|F_t| / (mu F_n)`).
//! `g_0` is measured to the *current* plane: a master moving onto the node
//! (the ironing die's press) leaves `x_0` behind it, so those nodes take
//! the foot rule (the relative path, with the facet's committed
//! positions, would be needed there). Before, the crossing was computed
//! once, at the first closed iterate of the increment, and then held: a node closing deep in the first iterate
//! (`ironing_3d` level 0, press increment 2: gap -0.08, the converged one
//! -1.1e-4) kept a stick point 0.013 away from where it touched and
//! converged slipping at `mu R_N` (trial 0.67 against a limit of 0.016;
//! traced per evaluation with `ctc run -v` of that deck).

use super::friction::{tangential_stiffness, FrictionState, FrictionStatus, NodeFriction};
use super::mortar::ad::Ad;
use super::node_to_facet::{
    cross, dot, edge_fade, foot, foot_system, newton_step, sub, surface_point, Feature,
};
use crate::model::{ContactMethod, FirstImpact, Friction};

/// Coordinates a friction element depends on: the slave node, up to 4
/// nodes of the contact facet and up to 4 of the stick point's facet.
pub const NDOF: usize = 27;

/// A trial force within this fraction below the cone `mu R_N` slips
/// ([`respond`]). A node that slipped in the last increment starts the
/// next one with its stick point where the return map left it, so its
/// first trial force lies on the cone to round-off, and `|t*| <= mu R_N`
/// decided its tangent (stick: `k_T` along the surface; slip: none) by
/// the last bits. Two nodes mirror images of each other then got
/// different tangents for the increment's first step: the ironing deck
/// (`examples/ironing_3d.ctc`, symmetric about the slab's mid-width
/// plane) left that symmetry at its slide increment 19 (`t = 1.6`):
/// `|F_z|` up to 2.8e-8 before it, 6.0e-3 there; 1.9e-13 over the run
/// with this rule (`verification/src/programs/ironing_3d.rs` has the
/// trace). The force is continuous to this fraction.
pub const CONE_TIE: f64 = 1e-9;

type A = Ad<NDOF>;

/// Inputs of the friction law on one element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacetFriction {
    /// Friction coefficient.
    pub mu: f64,
    /// Tangential penalty `k_T` (force per unit slip).
    pub alpha_t: f64,
    /// Tangential shift `m` (augmented Lagrangian; 0 for penalty), current
    /// frame.
    pub shift: [f64; 3],
    /// Normal force law `R_N = normal_shift - normal_stiffness g`.
    pub normal_shift: f64,
    /// See `normal_shift`.
    pub normal_stiffness: f64,
    /// The facet's local edges across which the normal force fades
    /// ([`super::node_to_facet::edge_fade`]: the rim of a penalty pair's
    /// master; all `false` for none): `R_N` is `w R_N`, so the cone
    /// `mu w R_N` shrinks to zero across the band, with the derivative of
    /// `w` in the tangent.
    pub fade: [bool; 4],
    /// First touch in this increment (`first_impact = intersect`, no
    /// committed stick point): the slave's converged position `x_0`. The
    /// stick point is then where the straight path from `x_0` to `x_s`
    /// crosses the tangent plane at the contact point `x` (normal `n`),
    /// `x_0 + tau (x_s - x_0)`, `tau = g_0 / (g_0 - g)`, `g_0 = (x_0 - x)
    /// . n` (`x_s` itself at `g >= 0`, `x_0` at `g_0 <= 0`), a function of
    /// the current iterate with its derivative in the tangent (the anchor
    /// facet and `xi_a` unused). `None`: the stick point is `xi_a` on the
    /// anchor facet.
    pub impact: Option<[f64; 3]>,
    /// Held by the penalty cycling guard
    /// ([`super::node_to_facet::DeformablePair::held`]): frozen sticking,
    /// the force is the trial force at any size (no return map, the stick
    /// point does not move); the status reported is the law's (slip
    /// outside the cone), for the guard's consistency check.
    pub held: bool,
}

/// Friction contribution of one element.
#[derive(Debug, Clone, PartialEq)]
pub struct FacetResponse {
    /// Status, force, gap, slip and work (slip measured from the stick
    /// point the trial force starts from).
    pub friction: NodeFriction<3>,
    /// Forces over `[x_s, facet k, facet k_a]` (local dof `3 a + c`; the
    /// facet `k` nodes from dof 3, the `k_a` nodes from dof 15).
    pub forces: [f64; NDOF],
    /// `-d forces / d x` (row-major `NDOF x NDOF`).
    pub tangent: Vec<f64>,
    /// The stick point after the return map: parameters on facet `k` in
    /// slip, `None` in stick (it stays `(k_a, xi_a)`).
    pub moved: Option<[f64; 2]>,
    /// The stick point's current position after the return map.
    pub point: [f64; 3],
}

fn cst3<const N: usize>(p: [f64; 3]) -> [Ad<N>; 3] {
    p.map(Ad::cst)
}

/// Where the slave node projects on the contact facet: its interior
/// (`Feature::Face`: the facet's normal at the foot), or an edge or vertex
/// of it (the radius-0 cylinder or sphere of
/// [`super::node_to_facet::edge_element`], the node on the `side` (+1 or
/// -1) of the facet).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// The facet's part.
    pub feature: Feature,
    /// The side of the facet the node lies on (edge and vertex).
    pub side: f64,
}

impl Projection {
    /// The facet's interior.
    pub const FACE: Projection = Projection {
        feature: Feature::Face,
        side: 1.0,
    };
}

/// The closest point of the edge `(a, b)` (or vertex `a`, `b = None`) of
/// the facet `p` to `xs`, its weights over the facet's nodes and the unit
/// normal `side (xs - p) / |xs - p|`; `None` on the edge itself or for a
/// node index beyond the facet.
#[allow(clippy::type_complexity)]
fn edge_point<const N: usize>(
    xs: [Ad<N>; 3],
    p: &[[Ad<N>; 3]],
    a: usize,
    b: Option<usize>,
    side: f64,
) -> Option<([Ad<N>; 4], [Ad<N>; 3], [Ad<N>; 3])> {
    let z = Ad::cst(0.0);
    let mut w = [z; 4];
    let pa = *p.get(a)?;
    let x = match b {
        Some(b) => {
            let e = sub(*p.get(b)?, pa);
            let t = dot(sub(xs, pa), e) / dot(e, e);
            w[a] = Ad::cst(1.0) - t;
            w[b] = t;
            [0, 1, 2].map(|c| pa[c] + e[c] * t)
        }
        None => {
            w[a] = Ad::cst(1.0);
            pa
        }
    };
    let d = sub(xs, x);
    let len = dot(d, d).sqrt();
    if len.v.is_nan() || len.v <= 1e-300 {
        return None;
    }
    Some((w, x, d.map(|v| v * side / len)))
}

/// The edge / vertex of `at` as `(a, Some(b))` / `(a, None)`; `None` for
/// the face.
fn edge_of(at: Projection) -> Option<(usize, Option<usize>)> {
    match at.feature {
        Feature::Face => None,
        Feature::Edge(a, b) => Some((a, Some(b))),
        Feature::Vertex(a) => Some((a, None)),
    }
}

/// The parameters of the point of the (extended) facet `pts` on the line
/// `q + lambda n` (Newton on `x(xi) - q - lambda n = 0` from `xi`); `None`
/// when the line runs nearly along the facet (`|n . n_facet| < 0.1`, the
/// 2D rule's [`super::friction_segment`] `MIN_COSINE`) or Newton does not
/// converge.
fn along_normal(q: [f64; 3], n: [f64; 3], pts: &[[f64; 3]], xi: [f64; 2]) -> Option<[f64; 2]> {
    let p: Vec<[Ad<0>; 3]> = pts.iter().map(|&v| v.map(Ad::cst)).collect();
    let (mut xi, mut lambda) = (xi, 0.0);
    for _ in 0..30 {
        let (_, x, a1, a2, _) = surface_point(&p, xi.map(Ad::cst));
        let (x, a1, a2) = (x.map(|v| v.v), a1.map(|v| v.v), a2.map(|v| v.v));
        let r: [f64; 3] = std::array::from_fn(|c| x[c] - q[c] - lambda * n[c]);
        // J = [a1 a2 -n]: Cramer's rule for J d = -r
        let det3 = |c0: [f64; 3], c1: [f64; 3], c2: [f64; 3]| {
            c0[0] * (c1[1] * c2[2] - c1[2] * c2[1]) - c1[0] * (c0[1] * c2[2] - c0[2] * c2[1])
                + c2[0] * (c0[1] * c1[2] - c0[2] * c1[1])
        };
        let mn = [-n[0], -n[1], -n[2]];
        let det = det3(a1, a2, mn);
        let area = {
            let c = [
                a1[1] * a2[2] - a1[2] * a2[1],
                a1[2] * a2[0] - a1[0] * a2[2],
                a1[0] * a2[1] - a1[1] * a2[0],
            ];
            (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
        };
        if det.is_nan() || det.abs() < 0.1 * area || area <= 0.0 {
            return None;
        }
        let rhs = r.map(|v| -v);
        let d0 = det3(rhs, a2, mn) / det;
        let d1 = det3(a1, rhs, mn) / det;
        let dl = det3(a1, a2, rhs) / det;
        xi = [xi[0] + d0, xi[1] + d1];
        lambda += dl;
        if d0.abs().max(d1.abs()) <= 1e-13 {
            return Some(xi);
        }
    }
    None
}

/// The Coulomb law at a contact point: its state, the friction force `t`
/// (dual numbers over the element's variables), the tangential gap, the
/// stick point's move `delta` and its position after the return map.
pub(crate) struct Coulomb<const N: usize> {
    /// Stick or slip.
    pub status: FrictionStatus,
    /// The friction force on the slave.
    pub t: [Ad<N>; 3],
    /// Tangential gap `P (x_s - x_a)`.
    pub gt: [f64; 3],
    /// The stick point's move (the slip).
    pub delta: [f64; 3],
    /// The stick point after the return map.
    pub point: [f64; 3],
}

impl<const N: usize> Coulomb<N> {
    /// The friction record of the element.
    pub fn friction(&self) -> NodeFriction<3> {
        let tv = self.t.map(|v| v.v);
        let slip = self.delta;
        let dissipation = -(0..3).map(|c| tv[c] * slip[c]).sum::<f64>() + 0.0;
        let norm3 = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        NodeFriction {
            status: self.status,
            tangential_force: norm3(tv),
            tangential_gap: norm3(self.gt),
            slip: norm3(slip),
            traction: tv,
            slip_vector: slip,
            gap_gradient: [0.0; 3],
            dissipation,
        }
    }
}

/// The law of [`FacetFriction`] at the contact point `x` of normal `n` of
/// the slave `xs_d` (`faded` the free-edge fade of `R_N`), the stick point
/// `anchor()` (its current position on its facet), or the first touch's
/// crossing ([`FacetFriction::impact`]); the faceted element and the
/// Nagata element ([`super::friction_nagata`]) share it.
pub(crate) fn coulomb<const N: usize>(
    law: &FacetFriction,
    xs_d: [Ad<N>; 3],
    x: [Ad<N>; 3],
    n: [Ad<N>; 3],
    faded: Ad<N>,
    anchor: impl FnOnce() -> [Ad<N>; 3],
) -> Coulomb<N> {
    let gap = dot(sub(xs_d, x), n);
    let xa: [Ad<N>; 3] = match law.impact {
        // first touch: where the path from `x_0` crosses the tangent plane
        // of the current iterate
        Some(x0) => {
            let x0 = cst3(x0);
            let g0 = dot(sub(x0, x), n);
            if g0.v > 0.0 && gap.v < 0.0 {
                let tau = g0 / (g0 - gap);
                std::array::from_fn(|c| x0[c] + (xs_d[c] - x0[c]) * tau)
            } else if g0.v > 0.0 {
                // not there yet at a positive gap (augmented Lagrangian)
                xs_d
            } else {
                // behind the plane at the start
                x0
            }
        }
        // the stick point on its facet (convected)
        None => anchor(),
    };
    let d = sub(xs_d, xa);
    let dn = dot(d, n);
    let gt: [Ad<N>; 3] = std::array::from_fn(|c| d[c] - n[c] * dn);
    let shift = cst3(law.shift);
    let sn = dot(shift, n);
    let trial: [Ad<N>; 3] = std::array::from_fn(|c| shift[c] - n[c] * sn - gt[c] * law.alpha_t);
    let rn = gap * -law.normal_stiffness + law.normal_shift;
    let rn = if rn.v > 0.0 { rn * faded } else { Ad::cst(0.0) };
    let limit = rn * law.mu;
    let norm2 = dot(trial, trial);
    let zero = [Ad::cst(0.0); 3];
    let (status, t) = if law.alpha_t <= 0.0 {
        (FrictionStatus::Stick, zero)
    } else if limit.v <= 0.0 {
        // mu R_N = 0: slides freely
        (FrictionStatus::Slip, zero)
    } else if norm2.v.sqrt() <= limit.v * (1.0 - CONE_TIE) {
        (FrictionStatus::Stick, trial)
    } else {
        let norm = norm2.sqrt();
        let s = limit / norm;
        (FrictionStatus::Slip, trial.map(|v| v * s))
    };
    // held by the cycling guard: frozen sticking, the law's status kept
    let t = if law.held { trial } else { t };
    let tv = t.map(|v| v.v);
    let trial_v = trial.map(|v| v.v);
    let delta: [f64; 3] = if law.alpha_t > 0.0 {
        std::array::from_fn(|c| (tv[c] - trial_v[c]) / law.alpha_t)
    } else {
        std::array::from_fn(|c| -gt[c].v)
    };
    let point: [f64; 3] = std::array::from_fn(|c| xa[c].v + delta[c]);
    Coulomb {
        status,
        t,
        gt: gt.map(|v| v.v),
        delta,
        point,
    }
}

/// The friction law on the element: slave `xs` projected on the facet
/// `pts` at the converged foot `xi` (`at` the face; at an edge or vertex,
/// `xi` is the foot on the extended facet, the start of the stick point's
/// update); stick point at `xi_a` on the facet `anchor_pts`. `None` for a
/// degenerate facet, or a node on the edge (vertex) itself.
pub fn respond(
    law: &FacetFriction,
    xs: [f64; 3],
    pts: &[[f64; 3]],
    xi: [f64; 2],
    anchor_pts: &[[f64; 3]],
    xi_a: [f64; 2],
    at: Projection,
) -> Option<FacetResponse> {
    let xs_d: [A; 3] = std::array::from_fn(|c| A::var(xs[c], c));
    let p: Vec<[A; 3]> = pts
        .iter()
        .enumerate()
        .map(|(a, q)| std::array::from_fn(|c| A::var(q[c], 3 + 3 * a + c)))
        .collect();
    let pa: Vec<[A; 3]> = anchor_pts
        .iter()
        .enumerate()
        .map(|(a, q)| std::array::from_fn(|c| A::var(q[c], 15 + 3 * a + c)))
        .collect();
    let mut faded = A::cst(1.0);
    let (w, x, n) = match edge_of(at) {
        None => {
            // the foot and its derivative by one Newton step at the
            // converged foot
            let (r, j) = foot_system(xs_d, &p, xi.map(A::cst));
            let step = newton_step(r, j)?;
            let xi_d = [A::cst(xi[0]) + step[0], A::cst(xi[1]) + step[1]];
            faded = edge_fade(pts.len(), xi_d, law.fade);
            let (w, x, a1, a2, _) = surface_point(&p, xi_d);
            let m = cross(a1, a2);
            let len = dot(m, m).sqrt();
            if len.v.is_nan() || len.v <= 0.0 {
                return None;
            }
            (w, x, m.map(|v| v / len))
        }
        // the closest point of the edge (vertex) and its normal
        Some((a, b)) => edge_point(xs_d, &p, a, b, at.side)?,
    };
    let cl = coulomb(law, xs_d, x, n, faded, || {
        // the stick point on its facet (convected)
        surface_point(&pa, xi_a.map(A::cst)).1
    });
    let (status, t) = (cl.status, cl.t);
    let mut forces = [0.0; NDOF];
    let mut tangent = vec![0.0; NDOF * NDOF];
    let mut put = |row: usize, f: A| {
        forces[row] = f.v;
        for (k, dk) in f.d.iter().enumerate() {
            tangent[row * NDOF + k] = -dk;
        }
    };
    for (c, &tc) in t.iter().enumerate() {
        put(c, tc);
        for (a, wa) in w.iter().enumerate().take(pts.len()) {
            put(3 + 3 * a + c, -(*wa * tc));
        }
    }
    let point = cl.point;
    let moved = (status == FrictionStatus::Slip && !law.held).then(|| match at.feature {
        Feature::Face => foot(point, pts).map_or(xi, |(f, _)| f),
        // the facet's point on the line through `point` along `n`
        _ => along_normal(point, n.map(|v| v.v), pts, xi)
            .or_else(|| foot(point, pts).map(|f| f.0))
            .unwrap_or(xi),
    });
    Some(FacetResponse {
        friction: cl.friction(),
        forces,
        tangent,
        moved,
        point,
    })
}

/// A closed node-to-facet element as the friction law sees it.
#[derive(Debug, Clone, Copy)]
pub struct FacetContact<'a> {
    /// Slave index in the pair's per-slave vectors.
    pub slave: usize,
    /// Current slave position.
    pub xs: [f64; 3],
    /// The contact facet (index on the master side) and its current node
    /// coordinates.
    pub facet: usize,
    /// See `facet`.
    pub pts: &'a [[f64; 3]],
    /// Converged foot parameters on the facet (on the extended facet at an
    /// edge or vertex projection).
    pub xi: [f64; 2],
    /// Where the node projects (face, edge or vertex).
    pub at: Projection,
    /// Gap at the foot.
    pub gap: f64,
    /// Normal force `R_N >= 0`.
    pub normal_force: f64,
    /// `-d R_N / d g` (`alpha_N`; 0 for Lagrange multipliers).
    pub normal_stiffness: f64,
    /// Tributary area of the slave node.
    pub area: f64,
    /// The facet's local edges across which the normal force fades
    /// ([`FacetFriction::fade`]).
    pub free_edges: [bool; 4],
    /// Held by the penalty cycling guard ([`FacetFriction::held`]).
    pub held: bool,
}

/// The stick point `(facet, xi)` stored in a friction state's anchor.
pub fn decode(anchor: Option<[f64; 3]>, facets: usize) -> Option<(usize, [f64; 2])> {
    let a = anchor?;
    (a[0] >= 0.0 && a[0].fract() == 0.0 && (a[0] as usize) < facets)
        .then(|| (a[0] as usize, [a[1], a[2]]))
}

/// The anchor value of the stick point `(facet, xi)`.
pub fn encode(facet: usize, xi: [f64; 2]) -> [f64; 3] {
    [facet as f64, xi[0], xi[1]]
}

/// The master geometry a node-to-facet friction element lives on: the
/// flat facets ([`Faceted`]) or their Nagata patches
/// ([`super::friction_nagata::Patches`]). [`apply_on`] keeps the stick
/// point's bookkeeping (first touch, base, anchor, the slip of the
/// increment) the same on both.
pub trait Master {
    /// The element's response (forces and tangent over its coordinates).
    type Response;
    /// The contact point and unit normal at the converged foot (the plane
    /// a first touch crosses); `None` for a degenerate facet.
    fn frame(&self, c: &FacetContact<'_>) -> Option<([f64; 3], [f64; 3])>;
    /// The parameters on the contact facet of the foot of `q` (`c.xi` if
    /// the projection fails).
    fn foot_on(&self, c: &FacetContact<'_>, q: [f64; 3]) -> [f64; 2];
    /// The current position of the material point `xi` of facet `k`.
    fn point_on(&self, c: &FacetContact<'_>, k: usize, xi: [f64; 2]) -> [f64; 3];
    /// The law on the element with the stick point `xi_a` on facet `ka`.
    fn respond(
        &self,
        law: &FacetFriction,
        c: &FacetContact<'_>,
        ka: usize,
        xi_a: [f64; 2],
    ) -> Option<Self::Response>;
    /// The response's friction record, the stick point's parameters on the
    /// contact facet after a slip and its position.
    fn outcome(r: &mut Self::Response) -> (&mut NodeFriction<3>, Option<[f64; 2]>, [f64; 3]);
    /// The free-edge fade of the normal force at the foot.
    fn fade(&self, c: &FacetContact<'_>) -> f64;
}

/// Flat facets: `facet_points(k)` gives facet `k`'s current node
/// coordinates.
pub struct Faceted<F: Fn(usize) -> Vec<[f64; 3]>> {
    /// See the type.
    pub facet_points: F,
}

impl<F: Fn(usize) -> Vec<[f64; 3]>> Faceted<F> {
    fn points(&self, c: &FacetContact<'_>, k: usize) -> Vec<[f64; 3]> {
        if k == c.facet {
            c.pts.to_vec()
        } else {
            (self.facet_points)(k)
        }
    }
}

impl<F: Fn(usize) -> Vec<[f64; 3]>> Master for Faceted<F> {
    type Response = FacetResponse;

    fn frame(&self, c: &FacetContact<'_>) -> Option<([f64; 3], [f64; 3])> {
        let (_, x, ..) = surface_point(
            &c.pts
                .iter()
                .map(|&q| q.map(Ad::<0>::cst))
                .collect::<Vec<_>>(),
            c.xi.map(Ad::<0>::cst),
        );
        match edge_of(c.at) {
            None => Some((x.map(|v| v.v), facet_normal(c.pts, c.xi))),
            // the tangent plane of the edge's (vertex's) normal through its
            // closest point
            Some((a, b)) => {
                let p: Vec<[Ad<0>; 3]> = c.pts.iter().map(|&q| q.map(Ad::<0>::cst)).collect();
                let (_, x, n) = edge_point(c.xs.map(Ad::<0>::cst), &p, a, b, c.at.side)?;
                Some((x.map(|v| v.v), n.map(|v| v.v)))
            }
        }
    }

    fn foot_on(&self, c: &FacetContact<'_>, q: [f64; 3]) -> [f64; 2] {
        foot(q, c.pts).map_or(c.xi, |(f, _)| f)
    }

    fn point_on(&self, c: &FacetContact<'_>, k: usize, xi: [f64; 2]) -> [f64; 3] {
        point_at(&self.points(c, k), xi)
    }

    fn respond(
        &self,
        law: &FacetFriction,
        c: &FacetContact<'_>,
        ka: usize,
        xi_a: [f64; 2],
    ) -> Option<FacetResponse> {
        respond(law, c.xs, c.pts, c.xi, &self.points(c, ka), xi_a, c.at)
    }

    fn outcome(r: &mut FacetResponse) -> (&mut NodeFriction<3>, Option<[f64; 2]>, [f64; 3]) {
        (&mut r.friction, r.moved, r.point)
    }

    fn fade(&self, c: &FacetContact<'_>) -> f64 {
        match edge_of(c.at) {
            None => edge_fade::<0>(c.pts.len(), c.xi.map(Ad::cst), c.free_edges).v,
            Some(_) => 1.0,
        }
    }
}

/// Friction of a closed node-to-facet element on flat facets
/// ([`apply_on`] with [`Faceted`]); `facet_points(k)` gives facet `k`'s
/// current node coordinates on the master side, `facets` their number.
pub fn apply(
    law: &Friction,
    method: &ContactMethod,
    c: &FacetContact<'_>,
    facets: usize,
    facet_points: impl Fn(usize) -> Vec<[f64; 3]>,
    state: &mut FrictionState<3>,
) -> Option<(FacetResponse, usize)> {
    apply_on(law, method, c, facets, &Faceted { facet_points }, state)
}

/// Friction of a closed node-to-facet element: the stick point from the
/// committed state (or the Uzawa base, or the first touch), the law, the
/// trial state updated; `facets` the number of master facets. Returns the
/// response and the stick point's facet (whose nodes follow the contact
/// facet's in the forces), `None` when there is no tangential force
/// (Lagrange multipliers, first touch without friction, degenerate facet).
pub fn apply_on<M: Master>(
    law: &Friction,
    method: &ContactMethod,
    c: &FacetContact<'_>,
    facets: usize,
    master: &M,
    state: &mut FrictionState<3>,
) -> Option<(M::Response, usize)> {
    let i = c.slave;
    if i >= state.anchor.len() {
        return None;
    }
    state.position[i] = c.xs;
    let shift = match method {
        ContactMethod::Penalty { .. } => [0.0; 3],
        ContactMethod::AugmentedLagrange { .. } => state.shift[i],
        ContactMethod::Lagrange { .. } => return None,
    };
    // the base: the stick point after an augmented-Lagrangian update, or
    // of a node behind the facet's plane at the start
    let mut impact = None;
    let start =
        match decode(state.committed_anchor[i], facets).or_else(|| decode(state.base[i], facets)) {
            Some(a) => a,
            None => {
                // first touch in this increment
                let x0 = state.committed_position[i];
                let (x, n) = master.frame(c)?;
                let g0: f64 = (0..3).map(|k| (x0[k] - x[k]) * n[k]).sum();
                if c.gap < 0.0 {
                    let tau = if g0 > 0.0 { g0 / (g0 - c.gap) } else { 0.0 };
                    state.record_impact(tau);
                }
                if law.first_impact == FirstImpact::Frictionless {
                    state.anchor[i] = Some(encode(c.facet, c.xi));
                    return None;
                }
                let penalty = matches!(method, ContactMethod::Penalty { .. });
                if penalty && g0 > 0.0 && c.gap < 0.0 {
                    // the stick point follows the iterate (`FacetFriction::impact`)
                    impact = Some(x0);
                    (c.facet, c.xi)
                } else {
                    // behind the plane at the start (`x_0`), or the augmented
                    // Lagrangian (the crossing, or `x_s` at a positive gap): the
                    // facet's material point at the foot, held in the base
                    // and convected with the facet
                    let at = if g0 <= 0.0 {
                        x0
                    } else if c.gap < 0.0 {
                        let tau = g0 / (g0 - c.gap);
                        std::array::from_fn(|k| x0[k] + tau * (c.xs[k] - x0[k]))
                    } else {
                        c.xs
                    };
                    let first = (c.facet, master.foot_on(c, at));
                    state.base[i] = Some(encode(first.0, first.1));
                    first
                }
            }
        };
    let (ka, xi_a) = decode(state.base[i], facets).unwrap_or(start);
    let fl = FacetFriction {
        mu: law.mu,
        alpha_t: tangential_stiffness(law, method, c.area),
        shift,
        normal_shift: c.normal_force + c.normal_stiffness * c.gap,
        normal_stiffness: c.normal_stiffness,
        fade: c.free_edges,
        impact,
        held: c.held,
    };
    let mut r = master.respond(&fl, c, ka, xi_a)?;
    let (_, moved, point) = M::outcome(&mut r);
    state.anchor[i] = Some(match moved {
        Some(xi) => encode(c.facet, xi),
        // a first touch sticks at the crossing: the material point there
        None if impact.is_some() => encode(c.facet, master.foot_on(c, point)),
        None => encode(ka, xi_a),
    });
    // the slip of the increment: from the committed (or first-touch) stick
    // point, whose current position the base may have left (Uzawa)
    if (ka, xi_a) != start {
        let p0 = master.point_on(c, start.0, start.1);
        let slip: [f64; 3] = std::array::from_fn(|k| point[k] - p0[k]);
        // the augmented Lagrangian slides a node by moving the base of its
        // trial force: it ends on the cone (within k_T times the pair's gap
        // tolerance) with a slip, and is reported as slipping (as against
        // rigid tools, `friction_surface`)
        let near = match method {
            ContactMethod::AugmentedLagrange { tolerance, .. } => fl.alpha_t * tolerance,
            _ => 0.0,
        };
        let faded = master.fade(c);
        let limit = law.mu * c.normal_force * faded;
        let (f, ..) = M::outcome(&mut r);
        f.slip_vector = slip;
        f.slip = (slip[0] * slip[0] + slip[1] * slip[1] + slip[2] * slip[2]).sqrt();
        f.dissipation = -(0..3).map(|k| f.traction[k] * slip[k]).sum::<f64>() + 0.0;
        if f.status == FrictionStatus::Stick
            && limit > 0.0
            && f.tangential_force >= limit * (1.0 - CONE_TIE) - near
            && f.slip > 0.0
        {
            f.status = FrictionStatus::Slip;
        }
    }
    Some((r, ka))
}

/// The point at `xi` of the facet `pts`.
fn point_at(pts: &[[f64; 3]], xi: [f64; 2]) -> [f64; 3] {
    let p: Vec<[Ad<0>; 3]> = pts.iter().map(|&q| q.map(Ad::cst)).collect();
    let (_, x, ..) = surface_point(&p, xi.map(Ad::cst));
    x.map(|v| v.v)
}

/// The unit normal of the facet `pts` at `xi`.
fn facet_normal(pts: &[[f64; 3]], xi: [f64; 2]) -> [f64; 3] {
    let p: Vec<[Ad<0>; 3]> = pts.iter().map(|&q| q.map(Ad::cst)).collect();
    let (_, _, a1, a2, _) = surface_point(&p, xi.map(Ad::cst));
    let m = cross(a1, a2).map(|v| v.v);
    let l = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
    if l > 0.0 {
        m.map(|v| v / l)
    } else {
        [0.0; 3]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A facet of `n` nodes near the unit square in the plane z = 0,
    /// corners moved by `jitter` (node-to-facet's test facet), shifted by
    /// `offset`.
    fn facet(n: usize, jitter: &[f64], offset: [f64; 3]) -> Vec<[f64; 3]> {
        crate::contact::node_to_facet::tests::facet(n, jitter)
            .into_iter()
            .map(|p| [p[0] + offset[0], p[1] + offset[1], p[2] + offset[2]])
            .collect()
    }

    /// The law of the hand-made cases: `alpha_T = 10`, normal stiffness
    /// 100, no shift, no fade; `impact` the first-touch start, if any.
    fn plain_law(mu: f64, impact: Option<[f64; 3]>) -> FacetFriction {
        FacetFriction {
            mu,
            alpha_t: 10.0,
            shift: [0.0; 3],
            normal_shift: 0.0,
            normal_stiffness: 100.0,
            fade: [false; 4],
            impact,
            held: false,
        }
    }

    /// The forces of the element at the packed coordinates `v` (slave, the
    /// contact facet's `n` nodes, the anchor facet's `m` nodes), the foot
    /// found again by Newton.
    fn forces_at(
        law: &FacetFriction,
        v: &[f64],
        n: usize,
        m: usize,
        xi_a: [f64; 2],
        at: Projection,
    ) -> Option<FacetResponse> {
        let pt = |k: usize| [v[3 * k], v[3 * k + 1], v[3 * k + 2]];
        let xs = pt(0);
        let pts: Vec<[f64; 3]> = (1..=n).map(pt).collect();
        let apts: Vec<[f64; 3]> = (1 + n..=n + m).map(pt).collect();
        let (xi, _) = foot(xs, &pts)?;
        respond(law, xs, &pts, xi, &apts, xi_a, at)
    }

    /// The contact point of `xs` on `pts` at `at` (the foot, or the
    /// closest point of the edge / vertex) and its normal.
    fn contact_point(xs: [f64; 3], pts: &[[f64; 3]], at: Projection) -> ([f64; 3], [f64; 3]) {
        match edge_of(at) {
            None => {
                let (xi, _) = foot(xs, pts).unwrap();
                (point_at(pts, xi), facet_normal(pts, xi))
            }
            Some((a, b)) => {
                let p: Vec<[Ad<0>; 3]> = pts.iter().map(|&q| q.map(Ad::cst)).collect();
                let (_, x, n) = edge_point(xs.map(Ad::cst), &p, a, b, at.side).unwrap();
                (x.map(|v| v.v), n.map(|v| v.v))
            }
        }
    }

    /// Largest relative FD error of the tangent of one element (status
    /// checked unchanged at +-h), and the balance checks. `None` where the
    /// status changes within the step.
    fn check(
        law: &FacetFriction,
        xs: [f64; 3],
        pts: &[[f64; 3]],
        apts: &[[f64; 3]],
        xi_a: [f64; 2],
        at: Projection,
    ) -> Option<(f64, FrictionStatus)> {
        let (n, m) = (pts.len(), apts.len());
        let v0: Vec<f64> = xs
            .iter()
            .chain(pts.iter().flatten())
            .chain(apts.iter().flatten())
            .copied()
            .collect();
        let r0 = forces_at(law, &v0, n, m, xi_a, at)?;
        // local dof of packed coordinate j
        let dof = |j: usize| {
            let k = j / 3;
            if k <= n {
                j
            } else {
                15 + (j - 3 * (1 + n))
            }
        };
        // balance: sum of forces zero; moment = g n x t
        foot(xs, pts)?;
        let (x, _) = contact_point(xs, pts, at);
        let fmax = r0.forces.iter().fold(1e-300f64, |a, f| a.max(f.abs()));
        let (mut sum, mut moment) = ([0.0; 3], [0.0; 3]);
        for k in 0..(1 + n + m) {
            let p = [v0[3 * k], v0[3 * k + 1], v0[3 * k + 2]];
            let f: [f64; 3] = std::array::from_fn(|c| r0.forces[dof(3 * k + c)]);
            for c in 0..3 {
                sum[c] += f[c];
            }
            moment[0] += p[1] * f[2] - p[2] * f[1];
            moment[1] += p[2] * f[0] - p[0] * f[2];
            moment[2] += p[0] * f[1] - p[1] * f[0];
        }
        let t = r0.friction.traction;
        let lever: [f64; 3] = std::array::from_fn(|c| xs[c] - x[c]);
        let expect = [
            lever[1] * t[2] - lever[2] * t[1],
            lever[2] * t[0] - lever[0] * t[2],
            lever[0] * t[1] - lever[1] * t[0],
        ];
        for c in 0..3 {
            assert!(sum[c].abs() <= 1e-12 * fmax, "force balance {sum:?}");
            assert!(
                (moment[c] - expect[c]).abs() <= 1e-11 * fmax * 10.0,
                "moment {moment:?} vs g n x t {expect:?}"
            );
        }
        let h = 1e-6;
        let kmax = r0.tangent.iter().fold(1e-12f64, |a, k| a.max(k.abs()));
        let mut err = 0.0f64;
        for j in 0..v0.len() {
            let (mut vp, mut vm) = (v0.clone(), v0.clone());
            vp[j] += h;
            vm[j] -= h;
            let (rp, rm) = (
                forces_at(law, &vp, n, m, xi_a, at)?,
                forces_at(law, &vm, n, m, xi_a, at)?,
            );
            if rp.friction.status != r0.friction.status || rm.friction.status != r0.friction.status
            {
                return None;
            }
            for i in 0..v0.len() {
                let fd = -(rp.forces[dof(i)] - rm.forces[dof(i)]) / (2.0 * h);
                let an = r0.tangent[dof(i) * NDOF + dof(j)];
                err = err.max((fd - an).abs() / kmax);
            }
        }
        Some((err, r0.friction.status))
    }

    /// The largest finite-difference error of the friction tangent over
    /// seeded random elements (tri3 and quad4 contact facets, stick point
    /// on the same facet or on a neighbouring one, penalty and
    /// augmented-Lagrangian shift), stick and slip; printed for the record
    /// (`cargo test -p ctc-engine --lib contact::friction_facet --
    /// --nocapture`).
    #[test]
    fn fd_errors_over_seeded_random_elements_stick_and_slip() {
        let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut rnd = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let (mut worst_stick, mut worst_slip) = (0.0f64, 0.0f64);
        let (mut sticks, mut slips) = (0, 0);
        // first-touch elements (`FacetFriction::impact`)
        let (mut worst_touch, mut touch_sticks, mut touch_slips) = (0.0f64, 0, 0);
        for case in 0..1200 {
            let n = if case % 2 == 0 { 4 } else { 3 };
            let other = case % 3 == 0;
            let jitter: Vec<f64> = (0..12).map(|_| rnd()).collect();
            let pts = facet(n, &jitter, [0.0; 3]);
            let (apts, xi_a) = if other {
                let j2: Vec<f64> = (0..12).map(|_| 0.3 * rnd()).collect();
                let m = if case % 4 == 0 { 3 } else { 4 };
                let xi = if m == 4 {
                    [0.5 * rnd(), 0.5 * rnd()]
                } else {
                    [0.3 + 0.1 * rnd(), 0.3 + 0.1 * rnd()]
                };
                (facet(m, &j2, [-0.9, 0.1, 0.0]), xi)
            } else {
                let xi = if n == 4 {
                    [0.6 * rnd(), 0.6 * rnd()]
                } else {
                    [0.3 + 0.2 * rnd(), 0.3 + 0.2 * rnd()]
                };
                (pts.clone(), xi)
            };
            let (u, v) = (0.5 + 0.3 * rnd(), 0.5 + 0.3 * rnd());
            let xs = if n == 4 {
                [u, v, -0.05 - 0.05 * rnd().abs()]
            } else {
                [0.45 * u, 0.45 * v, -0.05 - 0.05 * rnd().abs()]
            };
            let law = FacetFriction {
                mu: 0.05 + 0.5 * rnd().abs(),
                alpha_t: 20.0 + 10.0 * rnd(),
                shift: if case % 5 == 0 {
                    [rnd(), rnd(), rnd()]
                } else {
                    [0.0; 3]
                },
                normal_shift: if case % 5 == 0 {
                    0.5 * rnd().abs()
                } else {
                    0.0
                },
                normal_stiffness: 100.0,
                fade: [false; 4],
                // a third of the elements touch in the increment: from a
                // converged position above the facet (g_0 0.08..0.12, the
                // path 0.15 long across it), the stick point follows the
                // iterate (the random stream left as it was)
                impact: (case % 3 == 1).then(|| {
                    let a = case as f64;
                    [
                        xs[0] + 0.15 * a.sin(),
                        xs[1] + 0.15 * a.cos(),
                        0.08 + 0.04 * (case % 7) as f64 / 6.0,
                    ]
                }),
                held: false,
            };
            let Some((err, status)) = check(&law, xs, &pts, &apts, xi_a, Projection::FACE) else {
                continue;
            };
            if law.impact.is_some() {
                worst_touch = worst_touch.max(err);
                match status {
                    FrictionStatus::Stick => touch_sticks += 1,
                    _ => touch_slips += 1,
                }
            }
            match status {
                FrictionStatus::Stick => {
                    sticks += 1;
                    worst_stick = worst_stick.max(err);
                }
                _ => {
                    slips += 1;
                    worst_slip = worst_slip.max(err);
                }
            }
        }
        println!(
            "friction_facet: {sticks} stick elements, max rel. FD error {worst_stick:.2e}; \
             {slips} slip elements, max rel. FD error {worst_slip:.2e}"
        );
        println!(
            "friction_facet first touch: {touch_sticks} stick, {touch_slips} slip elements, \
             max rel. FD error {worst_touch:.2e}"
        );
        assert!(sticks > 100 && slips > 100, "{sticks} {slips}");
        assert!(
            touch_sticks > 50 && touch_slips > 50,
            "{touch_sticks} {touch_slips}"
        );
        assert!(worst_stick <= 1e-6 && worst_slip <= 1e-6);
    }

    /// The penalty cycling guard (`node_to_facet::DeformablePair::held`):
    /// a held node outside its cone is frozen sticking: the forces and
    /// tangent of the same element with an unbounded cone (the trial force
    /// `-k_T g_T`, its tangent minus the central-difference derivative of
    /// those forces on the slave, h = 1e-6), the stick point unmoved, the
    /// law's status (slip) reported for the consistency check. Unheld:
    /// `|T| = mu R_N`, and the slip tangent holds nothing along the slip
    /// (0 in the x x entry).
    #[test]
    fn a_held_node_is_frozen_sticking_and_reports_the_law_s_status() {
        // the slip case below: 0.01 deep at (0.7, 0.5), stick point at the
        // centre, trial 2 against mu R_N = 0.3
        let pts = facet(4, &[0.0; 12], [0.0; 3]);
        let run = |law: &FacetFriction, xs: [f64; 3]| {
            let (xi, _) = foot(xs, &pts).unwrap();
            respond(law, xs, &pts, xi, &pts, [0.0, 0.0], Projection::FACE).unwrap()
        };
        let xs = [0.7, 0.5, -0.01];
        let plain = plain_law(0.3, None);
        let held = FacetFriction {
            held: true,
            ..plain
        };
        let unbounded = plain_law(1e6, None);
        let (slip, kept, stick) = (run(&plain, xs), run(&held, xs), run(&unbounded, xs));
        assert_eq!(kept.friction.status, FrictionStatus::Slip);
        assert_eq!(stick.friction.status, FrictionStatus::Stick);
        assert_eq!((kept.forces, kept.moved), (stick.forces, None));
        assert!((slip.friction.tangential_force - 0.3).abs() < 1e-12);
        assert!((kept.friction.tangential_force - 2.0).abs() < 1e-12);
        for r in 0..NDOF {
            for c in 0..NDOF {
                let (a, b) = (kept.tangent[r * NDOF + c], stick.tangent[r * NDOF + c]);
                assert!((a - b).abs() <= 1e-12, "row {r} col {c}: {a} vs {b}");
            }
        }
        let h = 1e-6;
        for c in 0..3 {
            let (mut p, mut m) = (xs, xs);
            p[c] += h;
            m[c] -= h;
            let (fp, fm) = (run(&unbounded, p), run(&unbounded, m));
            for r in 0..3 {
                let fd = -(fp.forces[r] - fm.forces[r]) / (2.0 * h);
                let k = kept.tangent[r * NDOF + c];
                assert!((fd - k).abs() <= 1e-5, "({r}, {c}): {k} vs {fd}");
            }
        }
        assert!(slip.tangent[0].abs() < 1e-9 && (kept.tangent[0] - 10.0).abs() < 1e-9);
    }

    #[test]
    fn slip_moves_the_stick_point_and_the_force_is_mu_rn() {
        // flat unit quad, node 0.01 below at (0.7, 0.5), stick point at
        // the centre (0.5, 0.5): g_T = 0.2 along x, R_N = 100 x 0.01 = 1
        let pts = facet(4, &[0.0; 12], [0.0; 3]);
        let law = plain_law(0.3, None);
        let xs = [0.7, 0.5, -0.01];
        let (xi, _) = foot(xs, &pts).unwrap();
        let r = respond(&law, xs, &pts, xi, &pts, [0.0, 0.0], Projection::FACE).unwrap();
        assert_eq!(r.friction.status, FrictionStatus::Slip);
        assert!(
            (r.friction.traction[0] + 0.3).abs() < 1e-12,
            "{:?}",
            r.friction
        );
        // elastic part 0.3 / 10: the stick point at x = 0.7 - 0.03
        let moved = r.moved.unwrap();
        assert!((0.5 * (moved[0] + 1.0) - 0.67).abs() < 1e-12, "{moved:?}");
        assert!((r.friction.dissipation - 0.3 * 0.17).abs() < 1e-12);
        // below the limit: stick, force -k_T g_T
        let xs = [0.52, 0.5, -0.01];
        let (xi, _) = foot(xs, &pts).unwrap();
        let r = respond(&law, xs, &pts, xi, &pts, [0.0, 0.0], Projection::FACE).unwrap();
        assert_eq!(r.friction.status, FrictionStatus::Stick);
        assert!((r.friction.traction[0] + 0.2).abs() < 1e-12);
        assert!(r.moved.is_none());
        // the master facet moved rigidly with the node: no slip, no force
        let shifted = facet(4, &[0.0; 12], [0.2, 0.0, 0.0]);
        let xs = [0.7, 0.5, -0.01];
        let (xi, _) = foot(xs, &shifted).unwrap();
        let r = respond(
            &law,
            xs,
            &shifted,
            xi,
            &shifted,
            [0.0, 0.0],
            Projection::FACE,
        )
        .unwrap();
        assert!(r.friction.tangential_force < 1e-12, "{:?}", r.friction);
    }

    /// `examples/ironing_3d.ctc`'s slide increment 19: a node that slipped
    /// in the last increment starts the next one with its stick point
    /// where the return map put it, so its trial force lies on the cone to
    /// round-off. Flat unit quad, node 0.01 below at (0.7, 0.5), stick
    /// point at the centre: slip (as in
    /// `slip_moves_the_stick_point_and_the_force_is_mu_rn`); from the
    /// moved stick point, the node moved by +-1e-13 along the slip (two
    /// mirror nodes' round-off) must get one status and one tangent, the
    /// slip's: before [`CONE_TIE`] the node moved back stuck (tangential
    /// stiffness `k_T` = 10 instead of 0).
    #[test]
    fn a_node_that_slipped_starts_the_next_increment_slipping_whatever_the_round_off() {
        let pts = facet(4, &[0.0; 12], [0.0; 3]);
        let law = plain_law(0.3, None);
        let xs = [0.7, 0.5, -0.01];
        let (xi, _) = foot(xs, &pts).unwrap();
        let r = respond(&law, xs, &pts, xi, &pts, [0.0, 0.0], Projection::FACE).unwrap();
        assert_eq!(r.friction.status, FrictionStatus::Slip);
        let committed = r.moved.unwrap();
        let mut tangents = Vec::new();
        for dx in [-1e-13, 0.0, 1e-13] {
            let xs = [0.7 + dx, 0.5, -0.01];
            let (xi, _) = foot(xs, &pts).unwrap();
            let r = respond(&law, xs, &pts, xi, &pts, committed, Projection::FACE).unwrap();
            assert_eq!(r.friction.status, FrictionStatus::Slip, "dx {dx:e}");
            assert!((r.friction.tangential_force - 0.3).abs() < 1e-9);
            tangents.push(r.tangent);
        }
        // the slave's own tangential stiffness along the slip: 0 in slip
        for k in &tangents {
            assert!(k[0].abs() < 1e-6, "K_xx {}", k[0]);
            let d = k
                .iter()
                .zip(&tangents[1])
                .fold(0.0f64, |a, (p, q)| a.max((p - q).abs()));
            assert!(d < 1e-6, "tangents differ by {d:e}");
        }
    }

    /// A node past the edge x = 1 of the flat unit quad (below its plane,
    /// in the wedge of a convex edge) and past its vertex (1, 1): the
    /// normal is the one of the radius-0 cylinder / sphere
    /// (`node_to_facet::edge_element`), the friction force is orthogonal
    /// to it, `|T| = mu R_N` in slip, the forces balance with the moment
    /// `g n x t`, and the tangent is minus the central-difference
    /// derivative of the forces (h = 1e-6) within 1e-6 of its largest
    /// entry, in stick and in slip (`cargo test -p ctc-engine --lib
    /// friction_facet -- --nocapture` prints the errors: 1e-9 and below).
    /// With the facet's tangent plane (the rule before) `|T . n|` was
    /// 0.74 |T| at the edge (`T` along `-(0.15, 0.1, 0)`, `n` 63 degrees
    /// off the facet's normal).
    #[test]
    fn friction_at_an_edge_or_vertex_acts_in_the_tangent_plane_of_its_normal() {
        let pts = facet(4, &[0.0; 12], [0.0; 3]);
        for (name, at, xs) in [
            (
                "edge",
                Projection {
                    feature: Feature::Edge(1, 2),
                    side: -1.0,
                },
                [1.1, 0.5, -0.05],
            ),
            (
                "vertex",
                Projection {
                    feature: Feature::Vertex(2),
                    side: -1.0,
                },
                [1.1, 1.08, -0.05],
            ),
        ] {
            let (p, n) = contact_point(xs, &pts, at);
            let dist = (0..3).map(|c| (xs[c] - p[c]).powi(2)).sum::<f64>().sqrt();
            for (mu, status) in [(0.5, FrictionStatus::Stick), (0.05, FrictionStatus::Slip)] {
                let law = plain_law(mu, None);
                // stick point at (0.95, 0.4, 0) on a copy of the facet
                let xi_a = [0.9, -0.2];
                let (xi, _) = foot(xs, &pts).unwrap();
                let r = respond(&law, xs, &pts, xi, &pts, xi_a, at).unwrap();
                assert_eq!(r.friction.status, status, "{name}: {:?}", r.friction);
                let t = r.friction.traction;
                let tl = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
                let tn: f64 = (0..3).map(|c| t[c] * n[c]).sum();
                assert!(
                    tl > 0.1 && tn.abs() <= 1e-14 * tl,
                    "{name}: T . n {tn:e}, |T| {tl:e}"
                );
                if status == FrictionStatus::Slip {
                    // R_N = alpha_N |x_s - p| (the gap -|x_s - p|)
                    let limit = mu * 100.0 * dist;
                    assert!(
                        (tl - limit).abs() <= 1e-13 * limit,
                        "{name}: {tl} vs {limit}"
                    );
                    let s = r.friction.slip_vector;
                    assert!((0..3).map(|c| s[c] * n[c]).sum::<f64>().abs() < 1e-15);
                    // the new stick point leaves the elastic part -t / k_T
                    // as the tangential gap
                    let moved = r.moved.unwrap();
                    let xa = point_at(&pts, moved);
                    let d: [f64; 3] = std::array::from_fn(|c| xs[c] - xa[c]);
                    let dn: f64 = (0..3).map(|c| d[c] * n[c]).sum();
                    for ((dc, nc), tc) in d.iter().zip(&n).zip(&t) {
                        let gt = dc - dn * nc;
                        assert!((gt + tc / law.alpha_t).abs() < 1e-12, "{name}: {gt} {t:?}");
                    }
                }
                let (err, st) = check(&law, xs, &pts, &pts, xi_a, at).unwrap();
                println!("friction_facet {name} {st:?}: max rel. FD error {err:.2e}");
                assert_eq!(st, status);
                assert!(err <= 1e-6, "{name} {status:?}: {err:e}");
            }
        }
    }

    /// A node open at the converged state (0.02 above the flat unit quad
    /// at x = 0.3) closes in the increment: its stick point is where its
    /// straight path from there crosses the facet's plane *at the iterate
    /// evaluated*, `tau = g_0 / (g_0 - g)`, whatever iterate closed it
    /// first (the rule before fixed it at the first closed iterate, so the
    /// same state gave another force after a deeper first iterate: here
    /// x = 0.36 instead of 0.3667); its tangential force `(1 - tau) k_T
    /// |P (x_s - x_0)|` vanishes with its gap, and the stick point
    /// recorded is the material point of the crossing.
    #[test]
    fn a_node_touching_in_the_increment_sticks_where_it_touched() {
        let pts = facet(4, &[0.0; 12], [0.0; 3]);
        let x0 = [0.3, 0.5, 0.02];
        let law = Friction {
            mu: 0.5,
            stiffness: Some(10.0),
            first_impact: FirstImpact::Intersect,
            cut_at_impact: false,
        };
        let method = ContactMethod::Penalty {
            kind: crate::model::PenaltyKind::Nodal,
            stiffness: 100.0,
        };
        let eval = |state: &mut FrictionState<3>, xs: [f64; 3]| {
            let (xi, _) = foot(xs, &pts).unwrap();
            let c = FacetContact {
                slave: 0,
                xs,
                facet: 0,
                pts: &pts,
                xi,
                at: Projection::FACE,
                gap: xs[2],
                normal_force: -100.0 * xs[2],
                normal_stiffness: 100.0,
                area: 1.0,
                free_edges: [false; 4],
                held: false,
            };
            apply(&law, &method, &c, 1, |_| pts.clone(), state)
                .unwrap()
                .0
        };
        // a deeper first iterate, then the one evaluated
        let (deep, xs) = ([0.45, 0.5, -0.03], [0.4, 0.5, -0.01]);
        let mut state = FrictionState::new(vec![x0]);
        let r_deep = eval(&mut state, deep);
        let r = eval(&mut state, xs);
        let fresh = eval(&mut FrictionState::new(vec![x0]), xs);
        assert_eq!(r.friction.status, FrictionStatus::Stick);
        assert_eq!(r.forces, fresh.forces);
        assert_eq!(r.tangent, fresh.tangent);
        // tau = 0.02 / 0.03: crossing at x = 0.3 + 0.1 tau, T = -k_T (1 -
        // tau) 0.1 along x
        let tau = 0.02 / 0.03;
        let t = r.friction.traction;
        assert!((t[0] + 10.0 * (1.0 - tau) * 0.1).abs() < 1e-13, "{t:?}");
        assert!(t[1].abs() < 1e-15 && t[2].abs() < 1e-15, "{t:?}");
        let deep_tau = 0.02 / 0.05;
        assert!(
            (r_deep.friction.traction[0] + 10.0 * (1.0 - deep_tau) * 0.15).abs() < 1e-13,
            "{:?}",
            r_deep.friction
        );
        let (k, xi_a) = decode(state.anchor[0], 1).unwrap();
        assert_eq!(k, 0);
        let crossing = point_at(&pts, xi_a);
        assert!(
            (crossing[0] - (0.3 + 0.1 * tau)).abs() < 1e-13,
            "{crossing:?}"
        );
        // closing: the force vanishes with the gap
        let grazing = eval(&mut FrictionState::new(vec![x0]), [0.4, 0.5, -1e-9]);
        let expected = 10.0 * 0.1 * 1e-9 / (0.02 + 1e-9);
        let f = grazing.friction.tangential_force;
        assert!((f - expected).abs() < 1e-6 * expected, "{f:e} {expected:e}");
        // the tangent of a first touch against central differences, stick
        // and slip (mu 0.5 and 0.01)
        for (mu, status) in [(0.5, FrictionStatus::Stick), (0.01, FrictionStatus::Slip)] {
            let fl = plain_law(mu, Some(x0));
            let (err, st) = check(&fl, xs, &pts, &pts, [0.0; 2], Projection::FACE).unwrap();
            println!("friction_facet first touch {st:?}: max rel. FD error {err:.2e}");
            assert_eq!(st, status);
            assert!(err <= 1e-6, "{status:?}: {err:e}");
        }
    }

    #[test]
    fn anchor_codes_round_trip() {
        let a = encode(7, [0.25, -0.5]);
        assert_eq!(decode(Some(a), 8), Some((7, [0.25, -0.5])));
        assert_eq!(decode(Some(a), 7), None);
        assert_eq!(decode(None, 8), None);
    }
}
