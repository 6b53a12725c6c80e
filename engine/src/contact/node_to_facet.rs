//! Contact between two deformable solids in 3D: node-to-facet elements,
//! the 3D form of [`super::node_to_segment`] (seed slides, "Contact between
//! two deformable bodies", "Three usual strategies", "Part I - Geometrical
//! aspects").
//!
//! A pair has two surfaces of boundary facets (tri3 and quad4: the faces
//! of tet4 and hex8 bodies): side 0 (the deck's left of `->`) and side 1
//! (the master, right of `->`). A slave node `x_s` is projected on the
//! candidate facets of the opposite side (a [`BroadPhase`] over the facet
//! boxes inflated by `prof`, plus its memory: the facet of the last
//! evaluation, the facets sharing a node with it and the facets walked
//! from it towards the node's foot, [`FacetSurface::memory_walk`], so a
//! node that penetrated deeper than `prof` is not lost). On a facet `x(xi) = sum N_a(xi) x_a`
//! (linear triangle, bilinear quadrilateral) the foot point solves
//!
//! `r_alpha = (x_s - x(xi)) . a_alpha = 0`, `a_alpha = dx/dxi_alpha`
//!
//! by Newton (`J_ab = -a_a . a_b + (x_s - x) . x_,ab`); the gap is
//! `g = (x_s - x(xi)) . n`, `n = a_1 x a_2 / |a_1 x a_2|` the outward
//! normal of the facet (its nodes counter-clockwise seen from outside).
//!
//! Choice of the projection (several candidates, a node outside every
//! facet), as the 2D kink rule:
//! 1. the facet of the previous evaluation (memory) if the foot stays on it
//!    within [`SEAM_TOL`] of its parametric width past an interior edge
//!    (hysteresis across seams: a node on a seam keeps one facet's smooth
//!    element instead of hopping between two normals); otherwise, among
//!    the candidates whose foot falls inside the facet (round-off
//!    tolerance [`INSIDE_TOL`]; across a **free** edge of the surface, the
//!    facet extended by [`FREE_EDGE_TOL`] of its parametric width, so a
//!    node sitting on the rim of the master does not chatter in and out),
//!    the one with the smallest `|g|`, ties to the lower facet index;
//! 2. otherwise (the node lies in the wedge in front of an edge, or the
//!    corner in front of a vertex, where every foot falls outside its
//!    facet) the nearest interior edge as a **cylinder of radius 0** or
//!    interior vertex as a **sphere of radius 0**: `g = s |x_s - p|`,
//!    `n = s (x_s - p) / |x_s - p|` with `p` the closest point of the edge
//!    (vertex), `s` the side of the facet it belongs to. The normal turns
//!    continuously from one facet's normal to the next across the wedge,
//!    so a node above a seam of a curved master does not jump;
//! 3. penetrations deeper than `prof` (the pair's search window; by
//!    default the longest edge of the pair's faces in the reference
//!    configuration) are ignored (a node of the far side of a thin body),
//!    except
//!    on the node's memory ([`FacetSurface::memory_walk`]): a node that
//!    had a projection on this surface at the last evaluation (in
//!    contact, or open within the window) and is now deeper crossed the
//!    face during one Newton step; it is not on the far side (the rule
//!    of [`super::node_to_segment`] in 2D). Dropping it left it inside
//!    the master for good: the 3D ironing slide (issue 18), where a
//!    Newton step threw slab nodes 35 and 195 0.537 into the die (radial
//!    thickness 1) and the increment converged with them past the window
//!    (1.04), open, no force; every later increment found them at gap
//!    -1.040 and cut back 25 times. The same holds for Nagata patches
//!    and for the beside test ([`FacetSurface::below_past_rim`]). The
//!    window was `max(prof, h)` (`h` the facet's longest edge) so that a
//!    node that crossed deeper than `prof` in one step was not lost; the
//!    memory keeps such a node, and the window is `prof`, which a deck
//!    can set below a thin body's thickness (`h` could not be: the 3D
//!    tube's outer self contact, whose 8.2 mm chords let outer nodes of
//!    one arm of the bulge match the other arm's outer facets from
//!    behind at -7.8 mm, through two walls of 2 mm). 3D
//!    mortar's facet pairs keep the window for every pair (no memory:
//!    its pieces are rebuilt at each evaluation from the broad phase, and
//!    a pair is left out only when all its integration-point gaps lie
//!    deeper, a whole slave facet through the master; no run has shown
//!    it, the ironing benchmark's mortar variants reach the end).
//!
//! Free-edge band: a penalty node whose foot lies past a free edge, in the
//! [`FREE_EDGE_TOL`] band of the extended facet, gets the force `w R_N G`
//! with `w` the C2 smootherstep of the excess past the rim ([`edge_fade`]:
//! 1 on the edge, 0 at the band's outer boundary, where the node leaves
//! the surface), so the force goes to zero continuously instead of jumping
//! from `R_N` to 0 (the 3D blade loss stopped on a blade corner 1.0 mm
//! inside the casing at that boundary: moves of 5e-5 mm switched the
//! force of a 1 mm penetration on and off). `w` depends on the slave's and
//! the facet's positions through the foot's parameters: its gradient, a
//! dual number carried through the foot's `dxi/dx`, enters the tangent
//! `w (-dR_N/dg G G^T - R_N H) - R_N G (dw/dx)^T` (not symmetric), and the
//! friction cone is `mu w R_N` ([`super::friction_facet`]). The band keeps
//! its width (2 % of the facet's parametric width): Abaqus/Standard's
//! node-to-surface contact extends an open master by an extension zone of
//! 10 % of the end facet's edge by default (0 to 0.2 allowed), with the
//! geometry extrapolated and contact lost outside it (no fade documented);
//! LS-DYNA's automatic contacts wrap a shell's free edge in a half-cylinder
//! of radius half the contact thickness, a continuous surface. Lagrange
//! multipliers and the augmented Lagrangian keep the hard edge (a
//! multiplier, or its Uzawa update, is not faded), and so do Nagata
//! patches.
//!
//! Kinematics ([`FacetElement`]): with `N_a` the shape functions at the
//! foot (edge: `1 - t`, `t`; vertex: 1), `G = dg/dx = [n, -N_1 n, ..,
//! -N_k n]` over `[x_s, x_1 .. x_k]` exactly (the foot-point equations make
//! the variation of `xi` drop out). The force `f = R_N G` (`R_N >= 0` the
//! normal force) balances forces and moments (`sum f = 0`, `sum x_a x f_a =
//! R_N (x_s - x) x n = 0`), and the tangent `K = -df/dx = -dR_N/dg G G^T -
//! R_N H` with `H = dG/dx = d^2 g / dx^2` (symmetric) comes out exactly from
//! the dual numbers of [`super::mortar::ad`] carried through one Newton
//! step of the foot-point equations at the converged foot (that step's
//! derivative is the implicit derivative `dxi/dx = -J^-1 dr/dx`).
//! Proptests check `G` and `K` against finite differences and the
//! equilibrium of the forces.
//!
//! Strategies (as in 2D): single pass (side-0 nodes against side-1
//! facets), double pass (the sides swap at every converged increment),
//! modified double pass (both directions at every evaluation, each node
//! with half its tributary area). Each closed node gives one
//! [`super::mortar::Coupling`] over the slave and the facet nodes (force,
//! tangent, the Lagrange row `G`); the 3D solver
//! ([`crate::solve::surface_assembly`]) scatters those, grows the sparsity
//! pattern and builds the Lagrange rows from them.

use super::broad::BroadPhase;
use super::friction::FrictionStatus;
use super::mortar::ad::Ad;
use super::mortar::Coupling;
use super::surface::{alpha, normal_force, tributary_areas, SurfacePair};
use super::{ContactStatus, NodeContact};
use crate::geom::Aabb;
use crate::mesh::Facet;
use crate::model::{ContactMaster, ContactMethod, ContactStrategy, Model, NormalSmoothing};

/// Coordinates an element depends on: the slave node and up to 4 facet
/// nodes.
pub const NDOF: usize = 15;

type A = Ad<NDOF>;

/// Round-off tolerance (fraction of the facet's parametric width) on
/// "the foot lies inside the facet".
pub const INSIDE_TOL: f64 = 1e-10;

/// How far (fraction of the facet's parametric width) a foot may fall
/// beyond a free edge of the master surface and keep the extended facet;
/// across that band the penalty force fades to zero ([`edge_fade`]).
pub const FREE_EDGE_TOL: f64 = 0.02;

/// How far (fraction of the facet's parametric width) the foot on the
/// facet of the previous evaluation (the node's memory) may fall beyond an
/// interior edge and keep that facet: a node sitting on a seam (a slave
/// node on the diagonal of a master quad split in two triangles) would
/// otherwise hop between the two facets' normals at every Newton
/// iteration and stall the convergence.
pub const SEAM_TOL: f64 = 0.01;

/// How far (fraction of the parametric width) the foot on a Nagata patch
/// may fall past an interior edge when no patch holds it inside.
pub const NAGATA_OUTSIDE: f64 = 0.1;

/// Newton iterations of the foot-point equations before giving up.
const MAX_FOOT_ITERATIONS: usize = 30;

/// The part of a facet a slave node projects on (local node indices).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Feature {
    /// The facet's interior (or its extension across a free edge).
    Face,
    /// The edge between local nodes `a` and `b` (radius-0 cylinder).
    Edge(usize, usize),
    /// Local node `a` (radius-0 sphere).
    Vertex(usize),
}

/// A node-to-facet element at the current coordinates: gap, normal,
/// `G = dg/dx` and `H = d^2 g/dx^2` over `[x_s, x_1 .. x_k]` (local dofs
/// `3 a + c`, `a = 0` the slave; unused slots zero).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacetElement {
    /// Where the foot lies.
    pub feature: Feature,
    /// Facet parameters of the foot (face feature; `[0, 0]` otherwise).
    pub xi: [f64; 2],
    /// Signed gap (negative: penetration).
    pub gap: f64,
    /// Unit normal into free space of the master.
    pub normal: [f64; 3],
    /// Weight `N_a` of facet node `a` at the foot (sum 1).
    pub weights: [f64; 4],
    /// `dg/dx`.
    pub gradient: [f64; NDOF],
    /// `d^2 g / dx^2` (symmetric).
    pub hessian: [[f64; NDOF]; NDOF],
    /// The free-edge fade `w` of the foot ([`edge_fade`]; 1 inside the
    /// facet, at an edge or vertex element and where no edge fades).
    pub fade: f64,
    /// `dw/dx` (zero where `w` is 1 or 0).
    pub fade_gradient: [f64; NDOF],
}

pub(crate) fn cross<const N: usize>(a: [Ad<N>; 3], b: [Ad<N>; 3]) -> [Ad<N>; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(crate) fn dot<const N: usize>(a: [Ad<N>; 3], b: [Ad<N>; 3]) -> Ad<N> {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn sub<const N: usize>(a: [Ad<N>; 3], b: [Ad<N>; 3]) -> [Ad<N>; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Shape functions and their parameter derivatives at `xi` of a facet of
/// `n` nodes (3: `1 - xi - eta, xi, eta`; 4: bilinear on `[-1, 1]^2`,
/// nodes at `(-1,-1), (1,-1), (1,1), (-1,1)`); unused slots zero.
fn shapes<const N: usize>(
    n: usize,
    xi: [Ad<N>; 2],
) -> ([Ad<N>; 4], [[f64; 2]; 4], [[Ad<N>; 2]; 4]) {
    let z = Ad::cst(0.0);
    let one = Ad::cst(1.0);
    if n == 3 {
        let dn = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0], [0.0, 0.0]];
        let c = |v: f64| Ad::cst(v);
        (
            [one - xi[0] - xi[1], xi[0], xi[1], z],
            [[0.0; 2]; 4],
            dn.map(|d| [c(d[0]), c(d[1])]),
        )
    } else {
        const S: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
        let f = |s: [f64; 2]| {
            let a = one + xi[0] * s[0];
            let b = one + xi[1] * s[1];
            (a * b * 0.25, [b * (0.25 * s[0]), a * (0.25 * s[1])])
        };
        let v = S.map(f);
        (
            v.map(|p| p.0),
            S.map(|s| [0.25 * s[0] * s[1]; 2]),
            v.map(|p| p.1),
        )
    }
}

/// Point, tangents `a_1`, `a_2` and the mixed derivative `x_,12` of the
/// facet `pts` at `xi`.
#[allow(clippy::type_complexity)]
pub(crate) fn surface_point<const N: usize>(
    pts: &[[Ad<N>; 3]],
    xi: [Ad<N>; 2],
) -> ([Ad<N>; 4], [Ad<N>; 3], [Ad<N>; 3], [Ad<N>; 3], [Ad<N>; 3]) {
    let (sh, d12, dn) = shapes(pts.len(), xi);
    let z = Ad::cst(0.0);
    let (mut x, mut a1, mut a2, mut x12) = ([z; 3], [z; 3], [z; 3], [z; 3]);
    for (a, p) in pts.iter().enumerate() {
        for c in 0..3 {
            x[c] += sh[a] * p[c];
            a1[c] += dn[a][0] * p[c];
            a2[c] += dn[a][1] * p[c];
            x12[c] += p[c] * d12[a][0];
        }
    }
    (sh, x, a1, a2, x12)
}

/// Residual and Jacobian of the foot-point equations at `xi`.
#[allow(clippy::type_complexity)]
pub(super) fn foot_system<const N: usize>(
    xs: [Ad<N>; 3],
    pts: &[[Ad<N>; 3]],
    xi: [Ad<N>; 2],
) -> ([Ad<N>; 2], [[Ad<N>; 2]; 2]) {
    let (_, x, a1, a2, x12) = surface_point(pts, xi);
    let d = sub(xs, x);
    let j12 = dot(d, x12) - dot(a1, a2);
    (
        [dot(d, a1), dot(d, a2)],
        [[-dot(a1, a1), j12], [j12, -dot(a2, a2)]],
    )
}

/// The Newton step `-J^-1 r`, `None` for a singular `J`.
pub(crate) fn newton_step<const N: usize>(r: [Ad<N>; 2], j: [[Ad<N>; 2]; 2]) -> Option<[Ad<N>; 2]> {
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let scale = (j[0][0].v.abs() + j[1][1].v.abs()).powi(2);
    if det.v.is_nan() || det.v.abs() <= 1e-14 * scale {
        return None;
    }
    Some([
        -(j[1][1] * r[0] - j[0][1] * r[1]) / det,
        -(j[0][0] * r[1] - j[1][0] * r[0]) / det,
    ])
}

fn constants(p: [f64; 3]) -> [Ad<0>; 3] {
    p.map(Ad::cst)
}

/// The foot of `xs` on the (extended) facet `pts` by Newton on the
/// foot-point equations from the facet's centre: its parameters and the
/// iterations, `None` if Newton does not converge.
pub fn foot(xs: [f64; 3], pts: &[[f64; 3]]) -> Option<([f64; 2], usize)> {
    let p: Vec<[Ad<0>; 3]> = pts.iter().map(|&q| constants(q)).collect();
    let xs = constants(xs);
    let mut xi = if pts.len() == 3 {
        [1.0 / 3.0; 2]
    } else {
        [0.0; 2]
    };
    for it in 1..=MAX_FOOT_ITERATIONS {
        let (r, j) = foot_system(xs, &p, xi.map(Ad::cst));
        let step = newton_step(r, j)?;
        xi[0] += step[0].v;
        xi[1] += step[1].v;
        if xi.iter().any(|v| v.is_nan() || v.abs() >= 1e3) {
            return None;
        }
        if step[0].v.abs().max(step[1].v.abs()) <= 1e-13 {
            return Some((xi, it));
        }
    }
    None
}

/// How far the foot `xi` lies beyond each local edge `(a, a + 1)` of a
/// facet of `n` nodes, in fractions of the parametric width (<= 0 inside).
pub fn edge_excess(n: usize, xi: [f64; 2]) -> [f64; 4] {
    if n == 3 {
        [-xi[1], xi[0] + xi[1] - 1.0, -xi[0], f64::NEG_INFINITY]
    } else {
        [
            0.5 * (-1.0 - xi[1]),
            0.5 * (xi[0] - 1.0),
            0.5 * (xi[1] - 1.0),
            0.5 * (-1.0 - xi[0]),
        ]
    }
}

/// The weight of the free-edge band at the excess `e` past a free edge
/// (fraction of the parametric width): 1 for `e <= 0`, 0 for `e >=`
/// [`FREE_EDGE_TOL`], the C2 smootherstep `1 - s^3 (10 - 15 s + 6 s^2)`
/// (`s = e / FREE_EDGE_TOL`) in between, with its derivative. C2, not C1:
/// with the C1 smoothstep `1 - 3 s^2 + 2 s^3` a node lying on the rim (`e`
/// = 0, every corner node of a matching mesh) sat on a jump of the second
/// derivative, so the tangent differed from central differences by 9.1e-6
/// (`self_contact_3d`, 9.3e-10 without the fade) and Newton lost its
/// quadratic rate in the sliding blocks of `friction_ntf_3d`
/// (`newton_converges_quadratically_while_the_block_slides`: 1.3e-6 ->
/// 5.1e-11).
pub fn fade<const N: usize>(e: Ad<N>) -> Ad<N> {
    if e.v <= 0.0 {
        Ad::cst(1.0)
    } else if e.v >= FREE_EDGE_TOL {
        Ad::cst(0.0)
    } else {
        let s = e * (1.0 / FREE_EDGE_TOL);
        Ad::cst(1.0) - s * s * s * (Ad::cst(10.0) - s * 15.0 + s * s * 6.0)
    }
}

/// The free-edge fade of a foot `xi` on a facet of `n` nodes whose local
/// edges `(a, a + 1)` with `free[a]` lie on the rim of the surface: the
/// product of [`fade`] of the excess past each free edge
/// ([`edge_excess`]), so that a node whose foot slides off a free edge
/// into the band of the extended facet loses its penalty force
/// continuously (and with a continuous derivative) instead of all at once
/// at the band's outer boundary (the product keeps C2 at a corner of two
/// free edges). Carried as a dual number through the foot's derivative
/// `dxi/dx`, so its gradient is the weight's dependence on the slave's and
/// the facet's positions.
pub fn edge_fade<const N: usize>(n: usize, xi: [Ad<N>; 2], free: [bool; 4]) -> Ad<N> {
    let excess = if n == 3 {
        [
            -xi[1],
            xi[0] + xi[1] + (-1.0),
            -xi[0],
            Ad::cst(f64::NEG_INFINITY),
        ]
    } else {
        [
            (xi[1] + 1.0) * -0.5,
            (xi[0] + (-1.0)) * 0.5,
            (xi[1] + (-1.0)) * 0.5,
            (xi[0] + 1.0) * -0.5,
        ]
    };
    let mut w = Ad::cst(1.0);
    for (a, e) in excess.iter().enumerate().take(n) {
        if free[a] && e.v > 0.0 {
            w = w * fade(*e);
        }
    }
    w
}

/// The dual variables of an element: slave `x_s` (dofs 0..3) and the
/// facet nodes (dofs `3 + 3a + c`).
fn variables(xs: [f64; 3], pts: &[[f64; 3]]) -> ([A; 3], Vec<[A; 3]>) {
    let xs = std::array::from_fn(|c| A::var(xs[c], c));
    let p = pts
        .iter()
        .enumerate()
        .map(|(a, q)| std::array::from_fn(|c| A::var(q[c], 3 + 3 * a + c)))
        .collect();
    (xs, p)
}

/// Fills gap, normal, `G` and `H` from the dual gap, normal and weights.
fn finish(feature: Feature, xi: [f64; 2], gap: A, n: [A; 3], w: [A; 4]) -> FacetElement {
    let mut gv = [A::cst(0.0); NDOF];
    gv[..3].copy_from_slice(&n);
    for a in 0..4 {
        for c in 0..3 {
            gv[3 + 3 * a + c] = -(w[a] * n[c]);
        }
    }
    FacetElement {
        feature,
        xi,
        gap: gap.v,
        normal: n.map(|v| v.v),
        weights: w.map(|v| v.v),
        gradient: gv.map(|v| v.v),
        hessian: gv.map(|v| v.d),
        fade: 1.0,
        fade_gradient: [0.0; NDOF],
    }
}

/// The element of `xs` on the face of facet `pts` at the converged foot
/// `xi` ([`foot`]); `None` for a degenerate facet.
pub fn face_element(xs: [f64; 3], pts: &[[f64; 3]], xi: [f64; 2]) -> Option<FacetElement> {
    face_element_faded(xs, pts, xi, [false; 4])
}

/// [`face_element`] with the free-edge fade of the local edges `free`
/// ([`edge_fade`]): its weight and gradient in the element.
pub fn face_element_faded(
    xs: [f64; 3],
    pts: &[[f64; 3]],
    xi: [f64; 2],
    free: [bool; 4],
) -> Option<FacetElement> {
    let (xs_d, p) = variables(xs, pts);
    // one Newton step at the converged foot: value xi, derivative dxi/dx
    let (r, j) = foot_system(xs_d, &p, xi.map(A::cst));
    let step = newton_step(r, j)?;
    let xi_d = [A::cst(xi[0]) + step[0], A::cst(xi[1]) + step[1]];
    let (w, x, a1, a2, _) = surface_point(&p, xi_d);
    let m = cross(a1, a2);
    let len = dot(m, m).sqrt();
    if len.v.is_nan() || len.v <= 0.0 {
        return None;
    }
    let n = m.map(|v| v / len);
    let gap = dot(sub(xs_d, x), n);
    let mut el = finish(Feature::Face, xi, gap, n, w);
    let wf = edge_fade(pts.len(), xi_d, free);
    el.fade = wf.v;
    el.fade_gradient = wf.d;
    Some(el)
}

/// The element of `xs` on local edge `(a, b)` (a radius-0 cylinder) or,
/// `b = None`, on local vertex `a` (a radius-0 sphere) of facet `pts`;
/// `side` (+1 or -1) is the side of the facet `xs` lies on. `None` when
/// `xs` lies on the edge or vertex (no normal there).
pub fn edge_element(
    xs: [f64; 3],
    pts: &[[f64; 3]],
    a: usize,
    b: Option<usize>,
    side: f64,
) -> Option<FacetElement> {
    let (xs_d, p) = variables(xs, pts);
    let z = A::cst(0.0);
    let mut w = [z; 4];
    let (foot, feature) = match b {
        Some(b) => {
            let e = sub(p[b], p[a]);
            let t = dot(sub(xs_d, p[a]), e) / dot(e, e);
            w[a] = A::cst(1.0) - t;
            w[b] = t;
            ([0, 1, 2].map(|c| p[a][c] + e[c] * t), Feature::Edge(a, b))
        }
        None => {
            w[a] = A::cst(1.0);
            (p[a], Feature::Vertex(a))
        }
    };
    let d = sub(xs_d, foot);
    let len = dot(d, d).sqrt();
    if len.v.is_nan() || len.v <= 1e-300 {
        return None;
    }
    let n = d.map(|v| v * side / len);
    Some(finish(feature, [0.0; 2], len * side, n, w))
}

/// The outward unit normal of facet `pts` at its centre.
fn centre_normal(pts: &[[f64; 3]]) -> [f64; 3] {
    let p: Vec<[Ad<0>; 3]> = pts.iter().map(|&q| constants(q)).collect();
    let c = if pts.len() == 3 { 1.0 / 3.0 } else { 0.0 };
    let (_, _, a1, a2, _) = surface_point(&p, [Ad::cst(c), Ad::cst(c)]);
    let m = cross(a1, a2).map(|v| v.v);
    let l = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
    if l > 0.0 {
        m.map(|v| v / l)
    } else {
        [0.0; 3]
    }
}

/// One surface of a deformable pair: its facets, their topology and the
/// broad phase over their boxes.
#[derive(Debug, Clone, Default)]
pub struct FacetSurface {
    /// Facets (tri3, quad4), outward normal by the right-hand rule.
    pub faces: Vec<Facet>,
    /// Per facet: the other facets sharing a node with it (sorted).
    pub neighbours: Vec<Vec<usize>>,
    /// Edges `(min, max)` of one facet only (the rim), sorted.
    free_edges: Vec<(usize, usize)>,
    /// Nodes on a free edge, sorted.
    free_nodes: Vec<usize>,
    /// `(node, facet)` for every facet node, sorted (the facets around a
    /// node: its nodal normal).
    by_node: Vec<(usize, usize)>,
    /// Rim nodes on symmetry planes and the coordinates their Nagata
    /// nodal normals drop (`smoothing = nagata`, [`super::symmetry`]),
    /// sorted; set by [`FacetSurface::mirror_rim`].
    mirror: Vec<(usize, [bool; 3])>,
    /// Broad phase over the facet boxes at the current coordinates.
    grid: BroadPhase<3>,
    /// Scratch: facet boxes.
    boxes: Vec<Aabb<3>>,
}

impl FacetSurface {
    /// The surface of `faces` (3- and 4-node facets; others are ignored).
    pub fn new(faces: &[Facet]) -> Self {
        Self::of(
            faces
                .iter()
                .copied()
                .filter(|f| matches!(f.nodes().len(), 3 | 4))
                .collect(),
        )
    }

    /// The surface of the quadratic faces of `faces` (tri6, quad8, quad9;
    /// and tri3 / quad4 for a linear side of a mixed-order pair: every face
    /// of [`super::mortar::quadratic3d::is_mortar_face`]), for 3D mortar on quadratic faces
    /// ([`super::mortar::quadratic3d`]): its faces, neighbours and broad
    /// phase (the rim, read by node-to-facet only, joins consecutive nodes
    /// of the node lists and has no meaning here).
    pub fn quadratic(faces: &[Facet]) -> Self {
        Self::of(
            faces
                .iter()
                .copied()
                .filter(|f| super::mortar::quadratic3d::is_mortar_face(f.nodes().len()))
                .collect(),
        )
    }

    fn of(faces: Vec<Facet>) -> Self {
        // sorted (node, facet) lists: deterministic, no hash map
        let mut by_node: Vec<(usize, usize)> = faces
            .iter()
            .enumerate()
            .flat_map(|(k, f)| f.nodes().iter().map(move |&n| (n, k)))
            .collect();
        by_node.sort_unstable();
        let neighbours = faces
            .iter()
            .enumerate()
            .map(|(k, f)| {
                let mut out: Vec<usize> = Vec::new();
                for n in f.nodes() {
                    let s = by_node.partition_point(|&(m, _)| m < *n);
                    out.extend(
                        by_node[s..]
                            .iter()
                            .take_while(|&&(m, _)| m == *n)
                            .map(|&(_, g)| g)
                            .filter(|&g| g != k),
                    );
                }
                out.sort_unstable();
                out.dedup();
                out
            })
            .collect();
        let mut edges: Vec<(usize, usize)> = faces
            .iter()
            .flat_map(|f| {
                let n = f.nodes();
                (0..n.len()).map(move |k| {
                    let (a, b) = (n[k], n[(k + 1) % n.len()]);
                    (a.min(b), a.max(b))
                })
            })
            .collect();
        edges.sort_unstable();
        let free_edges: Vec<(usize, usize)> = edges
            .iter()
            .enumerate()
            .filter(|&(k, e)| {
                (k == 0 || edges[k - 1] != *e) && edges.get(k + 1).is_none_or(|n| n != e)
            })
            .map(|(_, &e)| e)
            .collect();
        let mut free_nodes: Vec<usize> = free_edges.iter().flat_map(|&(a, b)| [a, b]).collect();
        free_nodes.sort_unstable();
        free_nodes.dedup();
        FacetSurface {
            by_node,
            mirror: Vec::new(),
            neighbours,
            free_edges,
            free_nodes,
            grid: BroadPhase::default(),
            boxes: Vec::with_capacity(faces.len()),
            faces,
        }
    }

    /// Whether the edge between global nodes `a` and `b` is on the rim.
    pub fn is_free_edge(&self, a: usize, b: usize) -> bool {
        self.free_edges.binary_search(&(a.min(b), a.max(b))).is_ok()
    }

    /// Sets the rim nodes on the symmetry planes of body `body` (the rule
    /// of [`super::symmetry`]): their Nagata nodal normals drop the
    /// planes' coordinates ([`Self::nagata_ring`]).
    pub fn mirror_rim(&mut self, model: &Model<3>, body: usize) {
        let masks = super::symmetry::masks(model, body, &self.free_nodes);
        self.mirror = self
            .free_nodes
            .iter()
            .zip(masks)
            .filter(|(_, m)| m.iter().any(|&v| v))
            .map(|(&n, m)| (n, m))
            .collect();
    }

    /// The facets around global node `n` and its symmetry planes (the
    /// nodal normal of a Nagata patch, [`super::nagata::Ring`]).
    pub fn nagata_ring(&self, n: usize) -> super::nagata::Ring<'_> {
        super::nagata::Ring {
            facets: self.ring(n),
            mirror: self
                .mirror
                .binary_search_by_key(&n, |&(m, _)| m)
                .map_or([false; 3], |i| self.mirror[i].1),
        }
    }

    /// The facets holding global node `n` (their node lists).
    pub fn ring(&self, n: usize) -> Vec<&[usize]> {
        let s = self.by_node.partition_point(|&(m, _)| m < n);
        self.by_node[s..]
            .iter()
            .take_while(|&&(m, _)| m == n)
            .map(|&(_, k)| self.faces[k].nodes())
            .collect()
    }

    /// The Nagata element kept for slave node `node` at `xs` among the
    /// facets `candidates` (`smoothing = nagata`): the projection on each
    /// candidate's patch; the facet of the previous evaluation (`memory`)
    /// while its foot stays within [`SEAM_TOL`] past an interior edge;
    /// else the feet inside their patch (round-off; [`FREE_EDGE_TOL`] past
    /// a free edge) by smallest `|g|`; else the foot least outside its
    /// patch within [`NAGATA_OUTSIDE`] (the projection may fall slightly
    /// outside a patch where two patches' tangent planes part along their
    /// common edge). `None`: no patch holds the node (the faceted rules
    /// apply) or a penetration deeper than `prof` on a facet not
    /// in `exempt` (the node's memory, sorted: [`Self::memory_walk`]).
    #[allow(clippy::too_many_arguments)]
    pub fn closest_nagata(
        &self,
        x: &[[f64; 3]],
        node: usize,
        xs: [f64; 3],
        candidates: &[usize],
        memory: Option<usize>,
        exempt: &[usize],
        prof: f64,
        tests: &mut usize,
    ) -> Option<(usize, super::nagata::NagataElement)> {
        use super::nagata;
        let mut inside: Option<(f64, usize, [f64; 2])> = None;
        let mut outside: Option<(f64, usize, [f64; 2])> = None;
        let mut kept_memory = None;
        for &k in candidates {
            let nodes = self.faces[k].nodes();
            let n = nodes.len();
            let rings: Vec<nagata::Ring<'_>> = nodes.iter().map(|&m| self.nagata_ring(m)).collect();
            let Some(patch) = nagata::patch_of(nodes, &rings, x) else {
                continue;
            };
            *tests += 1;
            let Some(xi) = nagata::project(xs, &patch, None) else {
                continue;
            };
            let (p, t, _) = patch.at(xi);
            let m = [
                t[0][1] * t[1][2] - t[0][2] * t[1][1],
                t[0][2] * t[1][0] - t[0][0] * t[1][2],
                t[0][0] * t[1][1] - t[0][1] * t[1][0],
            ];
            let ml = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
            if ml.is_nan() || ml <= 0.0 {
                continue;
            }
            let gap = (0..3).map(|c| (xs[c] - p[c]) * m[c]).sum::<f64>() / ml;
            if gap < -prof && exempt.binary_search(&k).is_err() {
                continue;
            }
            let seam = if memory == Some(k) {
                SEAM_TOL
            } else {
                INSIDE_TOL
            };
            let excess = edge_excess(n, xi);
            let is_inside = excess.iter().enumerate().all(|(a, &e)| {
                let free = a < n && self.is_free_edge(nodes[a], nodes[(a + 1) % n]);
                e <= seam || (free && e <= FREE_EDGE_TOL)
            });
            if is_inside {
                if memory == Some(k) {
                    kept_memory = Some((k, xi));
                    break;
                }
                if inside.is_none_or(|(g, ..)| gap.abs() < g) {
                    inside = Some((gap.abs(), k, xi));
                }
                continue;
            }
            // beyond an interior edge only: the free rim ends the surface
            let worst = excess
                .iter()
                .enumerate()
                .filter(|&(a, &e)| a < n && e > 0.0)
                .map(|(a, &e)| {
                    if self.is_free_edge(nodes[a], nodes[(a + 1) % n]) {
                        f64::INFINITY
                    } else {
                        e
                    }
                })
                .fold(0.0, f64::max);
            if worst <= NAGATA_OUTSIDE && outside.is_none_or(|(w, ..)| worst < w) {
                outside = Some((worst, k, xi));
            }
        }
        let (k, xi) = kept_memory
            .or(inside.map(|(_, k, xi)| (k, xi)))
            .or(outside.map(|(_, k, xi)| (k, xi)))?;
        let nodes = self.faces[k].nodes();
        let rings: Vec<nagata::Ring<'_>> = nodes.iter().map(|&m| self.nagata_ring(m)).collect();
        nagata::element(node, xs, nodes, &rings, x, xi).map(|e| (k, e))
    }

    /// The memory of a slave node at `xs` whose last evaluation kept facet
    /// `start`, in `out` (cleared first; sorted, without duplicates): `start`,
    /// the facets sharing a node with it, and the facets walked from
    /// `start` towards the node's foot across shared edges (from a facet
    /// to the one across the edge its foot lies farthest past; the walk
    /// ends on a facet holding the foot, at a free edge, when it would
    /// step back to the facet it came from (the wedge in front of an
    /// edge) or onto a facet it walked, and after at most as many steps as
    /// the surface has facets) with the facets sharing a node with the
    /// last one (its edges and vertices, rule 2 of the module). The facets
    /// a node can have reached by crossing the face since the last
    /// evaluation, however far it slid along it: exempt from the depth
    /// window (rule 3 of the module documentation), as
    /// [`super::node_to_segment`]'s walk in 2D. `tests` counts the
    /// projections.
    pub fn memory_walk(
        &self,
        x: &[[f64; 3]],
        xs: [f64; 3],
        start: usize,
        tests: &mut usize,
        out: &mut Vec<usize>,
    ) {
        out.clear();
        out.push(start);
        out.extend_from_slice(&self.neighbours[start]);
        let mut walked = vec![start];
        let mut k = start;
        for _ in 0..self.faces.len() {
            let (p, n) = self.points(k, x);
            *tests += 1;
            let Some((xi, _)) = foot(xs, &p[..n]) else {
                break;
            };
            // the edge the foot lies farthest past (the first on ties)
            let excess = edge_excess(n, xi);
            let mut far: Option<(usize, f64)> = None;
            for (a, &e) in excess.iter().enumerate().take(n) {
                if e > INSIDE_TOL && far.is_none_or(|(_, f)| e > f) {
                    far = Some((a, e));
                }
            }
            let Some((a, _)) = far else {
                break;
            };
            let nodes = self.faces[k].nodes();
            let (u, v) = (nodes[a], nodes[(a + 1) % n]);
            let across = self.neighbours[k].iter().copied().find(|&g| {
                let m = self.faces[g].nodes();
                m.contains(&u) && m.contains(&v)
            });
            let Some(next) = across else {
                break;
            };
            // back to the facet it came from (a wedge) or round a loop
            if walked.contains(&next) {
                break;
            }
            walked.push(next);
            out.push(next);
            k = next;
        }
        out.extend_from_slice(&self.neighbours[k]);
        out.sort_unstable();
        out.dedup();
    }

    /// Whether the point `xs` lies beside the surface, past its free rim
    /// and below its extension: the foot on the extension of one of the
    /// facets `candidates` falls outside the facet across free edges only,
    /// beyond the free-edge band ([`FREE_EDGE_TOL`]) of at least one, and
    /// the gap to that extension lies in `[-prof, -below)` (the depth
    /// window of [`Self::closest`]; below `-below` at any depth on the
    /// facets of `exempt`, the node's memory, sorted, as in
    /// [`Self::closest`]). Such
    /// a node has no element (the nearest feature is the free rim), but if
    /// it moves into the band, or over the facet, while still below, its
    /// penetration is not one it made through the surface: see
    /// [`DeformablePair::beside`].
    pub fn below_past_rim(
        &self,
        x: &[[f64; 3]],
        xs: [f64; 3],
        candidates: &[usize],
        exempt: &[usize],
        prof: f64,
        below: f64,
    ) -> bool {
        candidates.iter().any(|&k| {
            let (p, n) = self.points(k, x);
            let pts = &p[..n];
            let Some((xi, _)) = foot(xs, pts) else {
                return false;
            };
            let nodes = self.faces[k].nodes();
            let excess = edge_excess(n, xi);
            let free = |a: usize| self.is_free_edge(nodes[a], nodes[(a + 1) % n]);
            let past_rim = (0..n).any(|a| free(a) && excess[a] > FREE_EDGE_TOL);
            let only_free = (0..n).all(|a| excess[a] <= INSIDE_TOL || free(a));
            if !past_rim || !only_free {
                return false;
            }
            let q: Vec<[Ad<0>; 3]> = pts.iter().map(|&v| constants(v)).collect();
            let (_, foot_x, a1, a2, _) = surface_point(&q, xi.map(Ad::cst));
            let m = cross(a1, a2);
            let len = dot(m, m).sqrt().v;
            if len.is_nan() || len <= 0.0 {
                return false;
            }
            let gap = (0..3)
                .map(|c| (xs[c] - foot_x[c].v) * m[c].v / len)
                .sum::<f64>();
            gap < -below && (gap >= -prof || exempt.binary_search(&k).is_ok())
        })
    }

    /// Whether global node `n` is on the rim.
    pub fn is_free_node(&self, n: usize) -> bool {
        self.free_nodes.binary_search(&n).is_ok()
    }

    /// The distinct nodes of the facets, sorted.
    pub fn nodes(&self) -> Vec<usize> {
        let mut n: Vec<usize> = self.faces.iter().flat_map(|f| f.nodes().to_vec()).collect();
        n.sort_unstable();
        n.dedup();
        n
    }

    /// Rebuilds the broad phase at the current coordinates `x`; `radius` is
    /// the expected query radius.
    pub fn update(&mut self, x: &[[f64; 3]], radius: f64) {
        self.boxes.clear();
        for f in &self.faces {
            let mut b = Aabb::empty();
            for &n in f.nodes() {
                b.include(x[n]);
            }
            self.boxes.push(b);
        }
        self.grid.rebuild(&self.boxes, radius);
    }

    /// The facets whose current box lies within `radius` of `p` (broad
    /// phase of the last [`FacetSurface::update`]), ascending.
    pub fn query(&self, p: [f64; 3], radius: f64, out: &mut Vec<usize>) {
        self.grid.query(p, radius, out);
    }

    /// Coordinates of facet `k`'s nodes.
    pub(crate) fn points(&self, k: usize, x: &[[f64; 3]]) -> ([[f64; 3]; 4], usize) {
        let n = self.faces[k].nodes();
        let mut p = [[0.0; 3]; 4];
        for (a, &m) in n.iter().enumerate() {
            p[a] = x[m];
        }
        (p, n.len())
    }

    /// The element kept for the point `xs` among the facets `candidates`
    /// (rules 1-3 of the module; `memory` the facet of the previous
    /// evaluation, `exempt` the facets of the node's memory, sorted,
    /// exempt from the depth window: [`Self::memory_walk`]), with its
    /// facet; `tests` counts the projections.
    #[allow(clippy::too_many_arguments)]
    pub fn closest(
        &self,
        x: &[[f64; 3]],
        xs: [f64; 3],
        candidates: &[usize],
        memory: Option<usize>,
        exempt: &[usize],
        prof: f64,
        tests: &mut usize,
    ) -> Option<(usize, FacetElement)> {
        let mut best: Option<(usize, FacetElement)> = None;
        let depth_of = |k: usize| {
            if exempt.binary_search(&k).is_ok() {
                f64::INFINITY
            } else {
                prof
            }
        };
        for &k in candidates {
            let (p, n) = self.points(k, x);
            let pts = &p[..n];
            *tests += 1;
            let Some((xi, _)) = foot(xs, pts) else {
                continue;
            };
            let nodes = self.faces[k].nodes();
            let seam = if memory == Some(k) {
                SEAM_TOL
            } else {
                INSIDE_TOL
            };
            let inside = edge_excess(n, xi).iter().enumerate().all(|(a, &e)| {
                let free = a < n && self.is_free_edge(nodes[a], nodes[(a + 1) % n]);
                e <= seam || (free && e <= FREE_EDGE_TOL)
            });
            if !inside {
                continue;
            }
            let free: [bool; 4] =
                std::array::from_fn(|a| a < n && self.is_free_edge(nodes[a], nodes[(a + 1) % n]));
            let Some(el) = face_element_faded(xs, pts, xi, free) else {
                continue;
            };
            if el.gap < -depth_of(k) {
                continue;
            }
            if memory == Some(k) {
                return Some((k, el));
            }
            if best
                .as_ref()
                .is_none_or(|(_, b)| el.gap.abs() < b.gap.abs())
            {
                best = Some((k, el));
            }
        }
        if best.is_some() {
            return best;
        }
        // every foot outside: the nearest edge or vertex of the candidates;
        // when it lies on the surface's free boundary (a free edge or
        // vertex) the node has left the surface (no element: open), else
        // the edge or vertex element of that interior feature. Looking for
        // the nearest *interior* feature only would pair a node that slid
        // off a free edge with an interior edge a whole facet away, with
        // that distance as a penetration (measured: a block sliding 2.75 %
        // of a facet past its master's edge got gaps of -0.256 on 0.25
        // facets, and the Newton loop lost every contact).
        let mut near: Option<(f64, usize, usize, Option<usize>, bool)> = None;
        for &k in candidates {
            let (p, n) = self.points(k, x);
            let nodes = self.faces[k].nodes();
            for a in 0..n {
                let b = (a + 1) % n;
                let e: [f64; 3] = std::array::from_fn(|c| p[b][c] - p[a][c]);
                let ee: f64 = e.iter().map(|v| v * v).sum();
                if ee.is_nan() || ee <= 0.0 {
                    continue;
                }
                let t =
                    ((0..3).map(|c| (xs[c] - p[a][c]) * e[c]).sum::<f64>() / ee).clamp(0.0, 1.0);
                let (which, other) = if t <= 0.0 {
                    (a, None)
                } else if t >= 1.0 {
                    (b, None)
                } else {
                    (a, Some(b))
                };
                let interior = match other {
                    Some(b) => !self.is_free_edge(nodes[a], nodes[b]),
                    None => !self.is_free_node(nodes[which]),
                };
                let d: f64 = (0..3)
                    .map(|c| (xs[c] - p[a][c] - t * e[c]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                if near.is_none_or(|(best, ..)| d < best) {
                    near = Some((d, k, which, other, interior));
                }
            }
        }
        let (_, k, a, b, interior) = near?;
        if !interior {
            return None;
        }
        let (p, n) = self.points(k, x);
        let pts = &p[..n];
        // the side from the feature's pseudo-normal, not from facet k's
        // normal alone: a node in front of one facet of a convex edge and
        // behind the other's plane is outside ([`Self::feature_normal`])
        let nodes = self.faces[k].nodes();
        let nrm = self.feature_normal(x, nodes[a], b.map(|b| nodes[b]));
        let nrm = if nrm.iter().all(|v| *v == 0.0) {
            centre_normal(pts)
        } else {
            nrm
        };
        let side = if (0..3).map(|c| (xs[c] - p[a][c]) * nrm[c]).sum::<f64>() < 0.0 {
            -1.0
        } else {
            1.0
        };
        *tests += 1;
        let el = edge_element(xs, pts, a, b, side)?;
        (el.gap >= -depth_of(k)).then_some((k, el))
    }

    /// The pseudo-normal of an interior feature of the surface at the
    /// coordinates `x`: for the edge between global nodes `ga` and `gb`
    /// the sum of the centre normals of the facets holding both, for the
    /// vertex `ga` (`gb = None`) the sum of the facets' centre normals
    /// weighted by their angle at the vertex (Baerentzen & Aanaes, "Signed
    /// distance computation using the angle weighted pseudonormal", IEEE
    /// TVCG 11 (2005) 243). For a point whose nearest feature is that edge
    /// or vertex, the sign of its distance along this normal says whether
    /// it lies in front of the surface; one facet's normal does not: a
    /// node in front of the end face of a block, past its edge with a side
    /// face, lies behind the side face's plane. Measured in the 3D blade
    /// loss flown to 20 ms (examples/blade_loss_3d.ctc): blade 6's tip
    /// nodes 452 and 467, 7.8 mm in front of the released blade's end face
    /// and just past its edge with a side face, were paired with that edge
    /// through the side face (gap -7.8 mm, closed) or through the end face
    /// (open) depending on which facet the candidate order put first, which
    /// the search memory changed from one Newton iteration to the next:
    /// the residual went back to its start value every 6 to 8 iterations
    /// and the run stopped at 9.42 ms on "chattering" nodes 452, 465-467.
    /// Zero when no facet holds the feature (the caller falls back to the
    /// facet's normal).
    pub fn feature_normal(&self, x: &[[f64; 3]], ga: usize, gb: Option<usize>) -> [f64; 3] {
        let s = self.by_node.partition_point(|&(m, _)| m < ga);
        let mut sum = [0.0; 3];
        for &(_, j) in self.by_node[s..].iter().take_while(|&&(m, _)| m == ga) {
            let nodes = self.faces[j].nodes();
            if gb.is_some_and(|g| !nodes.contains(&g)) {
                continue;
            }
            let (p, n) = self.points(j, x);
            let cn = centre_normal(&p[..n]);
            let weight = match gb {
                Some(_) => 1.0,
                None => {
                    let Some(i) = nodes.iter().position(|&m| m == ga) else {
                        continue;
                    };
                    let e1: [f64; 3] = std::array::from_fn(|c| p[(i + 1) % n][c] - p[i][c]);
                    let e2: [f64; 3] = std::array::from_fn(|c| p[(i + n - 1) % n][c] - p[i][c]);
                    let l = (e1.iter().map(|v| v * v).sum::<f64>()
                        * e2.iter().map(|v| v * v).sum::<f64>())
                    .sqrt();
                    if l.is_nan() || l <= 0.0 {
                        continue;
                    }
                    let cos = (0..3).map(|c| e1[c] * e2[c]).sum::<f64>() / l;
                    cos.clamp(-1.0, 1.0).acos()
                }
            };
            for c in 0..3 {
                sum[c] += weight * cn[c];
            }
        }
        sum
    }
}

/// Slave nodes `slaves` that moved farther than the window `prof` relative
/// to the master surface `master` between the coordinates `x0` (start of
/// the increment) and `x1` (end): the rule of [`super::jump`] in 3D (the
/// relative displacement is the node's minus that of the master point
/// under its end position, interpolated with the facet's weights; the
/// master within that distance of the end position; the normal component
/// larger than `prof`). Stateless (the surface's broad phase is rebuilt at
/// `x1`), ascending node order.
pub fn jumps(
    master: &mut FacetSurface,
    slaves: &[usize],
    prof: f64,
    x0: &[[f64; 3]],
    x1: &[[f64; 3]],
) -> Vec<super::jump::Jump> {
    let mut out = Vec::new();
    let mut candidates = Vec::new();
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let mut built = false;
    for &node in slaves {
        let (Some(&a), Some(&b)) = (x0.get(node), x1.get(node)) else {
            continue;
        };
        let moved: [f64; 3] = std::array::from_fn(|c| b[c] - a[c]);
        let reach = norm(moved) * (1.0 + 1e-12);
        if reach <= prof * (1.0 + 1e-12) {
            continue;
        }
        if !built {
            master.update(x1, prof);
            built = true;
        }
        master.grid.query(b, reach, &mut candidates);
        // the node's own facets are not a master for it
        candidates.retain(|&k| !master.faces[k].nodes().contains(&node));
        let mut tests = 0;
        let Some((k, el)) = master.closest(x1, b, &candidates, None, &[], reach, &mut tests) else {
            continue;
        };
        let face = master.faces[k].nodes();
        let mut under = [0.0; 3];
        for (w, &m) in el.weights.iter().zip(face) {
            let (Some(p0), Some(p1)) = (x0.get(m), x1.get(m)) else {
                continue;
            };
            for c in 0..3 {
                under[c] += w * (p1[c] - p0[c]);
            }
        }
        let d: [f64; 3] = std::array::from_fn(|c| moved[c] - under[c]);
        let distance = norm(d);
        let normal = (0..3).map(|c| d[c] * el.normal[c]).sum::<f64>().abs();
        if distance > prof && normal > prof && el.gap.abs() <= distance * (1.0 + 1e-12) {
            out.push(super::jump::Jump {
                node,
                distance,
                normal,
            });
        }
    }
    out
}

/// Prepared data of a 3D pair whose master is a deformable surface.
#[derive(Debug, Clone, Default)]
pub struct DeformablePair {
    /// Side 0 (the deck's slave faces) and side 1 (its master faces).
    pub sides: [FacetSurface; 2],
    /// Per slave index: the side the node belongs to.
    pub side_of: Vec<u8>,
    /// Converged increments so far (double pass: parity picks the side).
    pub increments: usize,
    committed_increments: usize,
    /// Per slave index: facet of the latest evaluation (search memory).
    pub last: Vec<Option<usize>>,
    committed_last: Vec<Option<usize>>,
    /// Closed nodes of the latest evaluation: force, tangent and Lagrange
    /// row over the slave and its facet's nodes, in slave order.
    pub couplings: Vec<Coupling>,
    /// Projections of the latest evaluation.
    pub tests: usize,
    /// `increments` at the latest evaluation (`usize::MAX`: none since the
    /// start or the last rollback): the first evaluation of the run and of
    /// each double-pass swap brings the new slaves that touch into the
    /// Lagrange active set.
    evaluated: usize,
    /// Gap within which a node counts as touching there:
    /// [`super::penalty::TOUCH_FRACTION`] of the smallest facet edge.
    touch: f64,
    /// Scratch: candidate facets of one query.
    candidates: Vec<usize>,
    /// Scratch: the memory facets of one query
    /// ([`FacetSurface::memory_walk`]).
    memory_facets: Vec<usize>,
    /// Self contact (the deck's `a.s -> a.s`): both sides are the same
    /// surface, every node is slave and master at once.
    pub self_contact: bool,
    /// Per slave index, self contact only: the facets excluded for the
    /// node (see [`excluded_facets`]), sorted.
    pub excluded: Vec<Vec<usize>>,
    /// Per slave index, penalty: the node lay beside the master surface at
    /// the latest evaluation — past its free rim below its extension
    /// ([`FacetSurface::below_past_rim`]), or, having been beside at the
    /// last converged increment, still deeper than `touch` under the
    /// facet it now projects on. Such a node gets no force: its
    /// penetration was not made through the surface (it came round the
    /// rim, beside the master), and the penalty `k g^2 / 2` switched on at
    /// that depth as it slides into the free-edge band, or over the facet,
    /// is energy the contact creates. Measured in the 3D blade loss
    /// (examples/blade_loss_3d.ctc) flown to 20 ms: the released blade,
    /// tumbled out of the slice's plane, had corner nodes beside the
    /// casing (z < 0, 1.8 to 7.8 mm radially past its inner face) slide
    /// axially into the band of its rim `z = 0`; the fade turned their
    /// force on with no work done against it (the force is normal, the
    /// motion axial), and pushed out radially they gave the bodies +6.0e5,
    /// +8.5e5, +7.0e6 and +8.5e6 mJ of contact work in single increments
    /// (kinetic energy 2.5e6 -> 1.27e7 mJ) before the run stopped at
    /// 10.875 ms. The flag clears once the node is in front of the
    /// surface again (gap `>= -touch`); with no facet in reach it keeps
    /// its value.
    pub beside: Vec<bool>,
    committed_beside: Vec<bool>,
    /// Mortar friction: current coordinates of every node at the latest
    /// evaluation (empty for other pairs).
    pub positions: Vec<[f64; 3]>,
    /// Mortar friction: coordinates at the last converged increment (the
    /// committed configuration of the weighted slip).
    pub committed_positions: Vec<[f64; 3]>,
    /// Mortar friction: the slave nodes' pairings in the committed
    /// configuration ([`super::mortar::friction3d`], recomputed once per
    /// increment from `committed_positions`).
    pub pairing: Option<super::mortar::friction3d::CommittedPairing>,
    /// Mortar friction on quadratic faces: the slave nodes' committed
    /// pairings ([`super::mortar::friction_quadratic`], once per increment).
    pub quadratic_pairing: Option<super::mortar::friction_quadratic::CommittedPairing3>,
    /// Mortar friction: per slave index, the tangential force vector of
    /// the latest evaluation (the augmented Lagrangian's next shift).
    pub tangential: Vec<[f64; 3]>,
    /// 3D mortar (linear faces): `(increments, cap)`, the cap on the
    /// pressure of the rows' load-stiffness term `p dB/dx` in the
    /// increment after `increments` converged ones, set by its first
    /// evaluation (at the committed state; see
    /// `mortar::LOAD_STIFFNESS_CAP`).
    pub load_stiffness_cap: Option<(usize, f64)>,
    /// Penalty pairs (3D mortar rows on linear faces, node-to-facet
    /// rows): per slave index, the node carried a normal force at the last
    /// accepted Newton iterate (at the Newton loop's first evaluation, then
    /// after each accepted iterate: [`DeformablePair::accept_iterate`]);
    /// such a node found open within `mortar::HOLD_BAND` keeps the closed
    /// branch of the penalty law for that iterate.
    pub hold_closed: Vec<bool>,
    /// The same flags at the latest evaluation (set by every evaluation of
    /// a pair that holds; copied into [`DeformablePair::hold_closed`] when
    /// its iterate is accepted).
    pub hold_last: Vec<bool>,
    /// Node-to-facet penalty pairs with friction: per slave index, the
    /// normal force `R_N` (before the free-edge fade, which the friction
    /// law applies) at the last accepted Newton iterate, recorded with
    /// [`DeformablePair::hold_closed`]: a held node's friction is the
    /// law's with the cone of that constant force (see the hold in
    /// [`evaluate`]).
    pub hold_force: Vec<f64>,
    /// The same forces at the latest evaluation (copied into
    /// [`DeformablePair::hold_force`] with the flags).
    pub hold_force_last: Vec<f64>,
    /// The hold keeps frictional nodes too (node-to-facet penalty pairs,
    /// their friction in the cone of [`DeformablePair::hold_force`]): set
    /// by the scene at the start of each Newton loop of a quasi-static
    /// step. Not in dynamic steps: measured on `ctc verify blade_loss_3d`
    /// (the released blade's rub on the casing, faceted), 450 -> 481 and
    /// 750 -> 883 Newton iterations at levels 0 and 1 with the same
    /// increments and cutbacks.
    pub hold_friction: bool,
    /// Set by [`DeformablePair::guard_start`]: the next evaluation is a
    /// Newton loop's first (no hold; it records
    /// [`DeformablePair::hold_closed`]).
    pub hold_fresh: bool,
    /// The nodes held at the latest evaluation (open, with the closed
    /// branch's tensile force): a converged iterate must have none
    /// ([`DeformablePair::guard_consistent`]).
    pub holds: usize,
    /// Penalty cycling guard ([`DeformablePair::guard_cycle`]): per slave
    /// index, the node's contact status cycled in the current Newton loop
    /// and is frozen closed for the rest of it: the penalty `R_N = -alpha_N
    /// g` at any gap (tensile above the master) with its exact tangent;
    /// its friction frozen sticking (the trial force `-k_T g_T` at any
    /// size, no return map) unless [`DeformablePair::held_slip`]. A smooth
    /// law, whose converged state is a solution of the contact law only
    /// where it agrees with it ([`DeformablePair::guard_consistent`]).
    /// Cleared at the start of every Newton loop.
    pub held: Vec<bool>,
    /// Per slave index, a held node whose friction follows the law (the
    /// return map) instead of sticking: a node that slipped at either
    /// iterate of its cycle, or one held sticking found slipping at a
    /// converged iterate ([`DeformablePair::guard_cycle`],
    /// [`DeformablePair::guard_consistent`]).
    pub held_slip: Vec<bool>,
    /// Status codes of the slaves at the last two accepted Newton iterates
    /// of the current Newton loop (the guard's memory).
    guard_keys: Vec<Vec<u8>>,
    /// The guard released its nodes in the current Newton loop (a held
    /// node open or above its master at convergence): it holds no more.
    guard_released: bool,
}

impl DeformablePair {
    /// The forces of the latest evaluation's couplings and their tangent
    /// times `v`, scattered over `nodes` nodes (three dofs each): what a
    /// finite-difference check of the pair compares (the engine's tests
    /// and the verification suite's).
    pub fn forces_and_tangent_times(&self, nodes: usize, v: &[[f64; 3]]) -> (Vec<f64>, Vec<f64>) {
        let mut f = vec![0.0; 3 * nodes];
        let mut kv = vec![0.0; 3 * nodes];
        for c in &self.couplings {
            let nd = 3 * c.nodes.len();
            for r in 0..nd {
                let gr = 3 * c.nodes[r / 3] + r % 3;
                f[gr] += c.force[r];
                for col in 0..nd {
                    kv[gr] += c.tangent[r * nd + col] * v[c.nodes[col / 3]][col % 3];
                }
            }
        }
        (f, kv)
    }

    /// Which sides act as slave now: `[side 0 is slave, side 1 is slave]`.
    pub fn slave_sides(&self, strategy: ContactStrategy) -> [bool; 2] {
        if self.self_contact {
            return [true, false];
        }
        strategy.slave_sides(self.increments)
    }

    /// Called when an increment has converged.
    pub fn commit(&mut self) {
        self.increments += 1;
        self.committed_increments = self.increments;
        self.committed_last.clone_from(&self.last);
        self.committed_beside.clone_from(&self.beside);
        self.committed_positions.clone_from(&self.positions);
    }

    /// Called when an increment is cut back.
    pub fn rollback(&mut self) {
        self.increments = self.committed_increments;
        self.last.clone_from(&self.committed_last);
        self.beside.clone_from(&self.committed_beside);
        self.positions.clone_from(&self.committed_positions);
        self.evaluated = usize::MAX;
    }

    /// Restart: `increments` converged increments were done, `memory` the
    /// committed facet of each slave ([`DeformablePair::memory`]),
    /// `positions` the committed coordinates of every node (kept by mortar
    /// friction pairs only), `beside` the committed [`Self::beside`] flags
    /// ([`DeformablePair::committed_beside`]; empty, from a restart file
    /// of a format without them: cleared, a node beside the master is
    /// found again once it lies past the rim).
    pub fn restore(
        &mut self,
        increments: usize,
        memory: &[Option<usize>],
        positions: &[[f64; 3]],
        beside: &[bool],
    ) {
        self.increments = increments;
        self.committed_beside = if beside.len() == memory.len() {
            beside.to_vec()
        } else {
            vec![false; memory.len()]
        };
        self.beside.clone_from(&self.committed_beside);
        self.committed_increments = increments;
        self.committed_last = memory.to_vec();
        self.last = memory.to_vec();
        self.evaluated = usize::MAX;
        if !self.committed_positions.is_empty() {
            self.committed_positions = positions.to_vec();
            self.positions = positions.to_vec();
            self.pairing = None;
            self.quadratic_pairing = None;
        }
    }

    /// The committed beside flags of each slave ([`Self::beside`] at the
    /// last converged increment), for restart points.
    pub fn committed_beside(&self) -> &[bool] {
        &self.committed_beside
    }

    /// A Newton loop starts: nothing held, no memory.
    pub fn guard_start(&mut self) {
        self.hold_closed.clear();
        self.hold_force.clear();
        self.holds = 0;
        self.hold_fresh = true;
        self.held.clear();
        self.held_slip.clear();
        self.guard_keys.clear();
        self.guard_released = false;
    }

    /// After an accepted Newton iterate (penalty pairs): the nodes carrying
    /// a normal force there are those a hold may keep at the next iterate
    /// ([`DeformablePair::hold_closed`]).
    pub fn accept_iterate(&mut self) {
        self.hold_closed.clone_from(&self.hold_last);
        self.hold_force.clone_from(&self.hold_force_last);
    }

    /// Whether the frozen state of the held nodes agrees with the contact
    /// law at the converged iterate whose contact is `contact`: each held
    /// node closed (`g < 0`) and, held sticking, inside its friction cone.
    /// A held node closed but outside its cone keeps its hold with the
    /// law's friction ([`DeformablePair::held_slip`]; not consistent yet,
    /// Newton goes on). A held node open or above its master releases
    /// every node (the Newton loop goes on with the law, and this loop
    /// holds no more).
    pub fn guard_consistent(&mut self, slaves: &[usize], contact: &[NodeContact<3>]) -> bool {
        if self.holds > 0 {
            // holds (`mortar::HOLD_BAND`): their tensile forces are no
            // solution; the iterate is accepted (`accept_iterate`) and the
            // next evaluation holds none of them
            return false;
        }
        if !self.held.contains(&true) {
            return true;
        }
        let debug = super::log::debug_enabled();
        let n = self.held.len();
        self.held_slip.resize(n, false);
        let mut seen = vec![false; n];
        let mut released = false;
        let mut freed = false;
        for nc in contact {
            let Ok(i) = slaves.binary_search(&nc.node) else {
                continue;
            };
            if !self.held.get(i).copied().unwrap_or(false) {
                continue;
            }
            seen[i] = true;
            if nc.status != ContactStatus::Closed || nc.gap >= 0.0 {
                released = true;
            } else if nc.friction.status == FrictionStatus::Slip && !self.held_slip[i] {
                self.held_slip[i] = true;
                freed = true;
                if debug {
                    eprintln!(
                        "[ctc ntf] cycling guard: node {} held sticking slips at convergence \
                         (T {:.3e}, p {:.3e}): its friction back to the law",
                        nc.node, nc.friction.tangential_force, nc.pressure
                    );
                }
            }
        }
        released |= self.held.iter().zip(&seen).any(|(&h, &s)| h && !s);
        if released {
            if debug {
                eprintln!(
                    "[ctc ntf] cycling guard: a held node open or above its master at \
                     convergence, all released"
                );
            }
            self.held.clear();
            self.held_slip.clear();
            self.guard_released = true;
        }
        !released && !freed
    }

    /// The cycling guard of a penalty pair, after an accepted Newton
    /// iterate whose contact is `contact` (`slaves` the pair's slave nodes):
    /// when the statuses of the slaves (open, closed sticking, closed
    /// slipping) come back to those of two iterates ago after a change
    /// (A -> B -> A), the nodes that switch are held closed (see
    /// [`DeformablePair::held`]): sticking, or with the law's friction if
    /// slipping at either of the two iterates
    /// ([`DeformablePair::held_slip`]). Returns the number of nodes newly
    /// held.
    pub fn guard_cycle(&mut self, slaves: &[usize], contact: &[NodeContact<3>]) -> usize {
        let mut key = vec![0u8; slaves.len()];
        for nc in contact {
            if nc.status != ContactStatus::Closed {
                continue;
            }
            if let Ok(i) = slaves.binary_search(&nc.node) {
                key[i] = match nc.friction.status {
                    FrictionStatus::Slip => 2,
                    _ => 1,
                };
            }
        }
        let mut newly = 0;
        if self.guard_keys.len() == 2 && !self.guard_released {
            let (a, b) = (&self.guard_keys[0], &self.guard_keys[1]);
            if *a == key && *b != key {
                // the nodes that switched between B and A
                self.held.resize(slaves.len(), false);
                self.held_slip.resize(slaves.len(), false);
                for (((held, slip), &k), &was) in self
                    .held
                    .iter_mut()
                    .zip(self.held_slip.iter_mut())
                    .zip(&key)
                    .zip(b)
                {
                    if was != k && !*held {
                        *held = true;
                        *slip = was == 2 || k == 2;
                        newly += 1;
                    }
                }
            }
        }
        if self.guard_keys.len() == 2 {
            self.guard_keys.remove(0);
        }
        self.guard_keys.push(key);
        newly
    }

    /// The committed facet of each slave (the search memory), for restart
    /// points.
    pub fn memory(&self) -> &[Option<usize>] {
        &self.committed_last
    }

    /// The nodes near facet `k` of the side opposite to slave index `i`
    /// (the facet and the facets sharing a node with it): the solver
    /// couples the slave to all of them when the pattern grows, so that
    /// sliding to a neighbouring facet does not grow it again.
    pub fn neighbourhood(&self, i: usize, k: usize, out: &mut Vec<usize>) {
        let side = &self.sides[1 - self.side_of.get(i).copied().unwrap_or(0) as usize];
        let Some(f) = side.faces.get(k) else {
            return;
        };
        out.extend_from_slice(f.nodes());
        for &g in &side.neighbours[k] {
            out.extend_from_slice(side.faces[g].nodes());
        }
    }
}

/// The slave nodes of 3D pair `pair` (sorted): the slave faces' nodes,
/// plus the master faces' nodes for the double-pass strategies.
pub fn slave_nodes(model: &Model<3>, pair: usize) -> Vec<usize> {
    let cp = &model.contacts[pair];
    let mut nodes = cp.nodes.clone();
    if let ContactMaster::Surface { faces, .. } = &cp.master {
        if cp.strategy != ContactStrategy::SinglePass && !is_self_contact(model, pair) {
            nodes.extend(faces.iter().flat_map(|f| f.nodes().to_vec()));
            nodes.sort_unstable();
            nodes.dedup();
        }
    }
    nodes
}

/// Tributary areas `int N_a dA` of the slave nodes: over the slave faces
/// for side-0 nodes, the master faces for side-1 nodes; halved for the
/// modified double pass and for self contact (both directions carry the
/// load, so that the reported pressure is the interface pressure and a
/// penalty gap is `p / k`).
pub fn areas(model: &Model<3>, pair: usize, slaves: &[usize]) -> Vec<f64> {
    let cp = &model.contacts[pair];
    if quadratic_mortar(model, pair) {
        // the positive weights `int N~_j dA` of the quadratic mortar rows
        let faces: Vec<&[usize]> = cp.faces.iter().map(|f| f.nodes()).collect();
        return super::mortar::quadratic3d::supports(&model.mesh.nodes, &faces, slaves);
    }
    let mut area = tributary_areas(&model.mesh, &cp.faces, slaves);
    if is_self_contact(model, pair) {
        for a in &mut area {
            *a *= 0.5;
        }
        return area;
    }
    if let ContactMaster::Surface { faces, .. } = &cp.master {
        let side1: Vec<usize> = slaves
            .iter()
            .copied()
            .filter(|n| cp.nodes.binary_search(n).is_err())
            .collect();
        let a1 = tributary_areas(&model.mesh, faces, &side1);
        for (n, a) in side1.iter().zip(a1) {
            if let Ok(i) = slaves.binary_search(n) {
                area[i] = a;
            }
        }
        if cp.strategy == ContactStrategy::ModifiedDoublePass {
            for a in &mut area {
                *a *= 0.5;
            }
        }
    }
    area
}

/// Whether 3D pair `pair` is self contact: its master faces are its slave
/// faces (the deck's `a.s -> a.s`).
pub fn is_self_contact(model: &Model<3>, pair: usize) -> bool {
    let cp = &model.contacts[pair];
    matches!(&cp.master, ContactMaster::Surface { faces, .. } if faces == &cp.faces)
}

/// The facets of `surface` excluded for its node `node` in self contact:
/// the facets that hold the node and the facets sharing a node with those
/// (the 2D rule, "its own segments and the adjacent ones", on a surface:
/// a node never contacts the patch of facets around it, which its own
/// deformation bends), sorted.
pub fn excluded_facets(surface: &FacetSurface, node: usize) -> Vec<usize> {
    let mut out = Vec::new();
    for (k, f) in surface.faces.iter().enumerate() {
        if f.nodes().contains(&node) {
            out.push(k);
            out.extend_from_slice(&surface.neighbours[k]);
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// The area vector `1/2 sum x_i x x_(i+1)` of facet `k` of `surface` at the
/// coordinates `x` (its outward normal times its area; exact for a warped
/// quadrilateral).
fn area_vector(surface: &FacetSurface, k: usize, x: &[[f64; 3]]) -> [f64; 3] {
    let n = surface.faces[k].nodes();
    let mut m = [0.0; 3];
    for (a, &i) in n.iter().enumerate() {
        let (p, q) = (x[i], x[n[(a + 1) % n.len()]]);
        m[0] += 0.5 * (p[1] * q[2] - p[2] * q[1]);
        m[1] += 0.5 * (p[2] * q[0] - p[0] * q[2]);
        m[2] += 0.5 * (p[0] * q[1] - p[1] * q[0]);
    }
    m
}

/// Self contact: keeps the candidate facets whose outward normal opposes
/// the outward normal of the node (the sum of the area vectors of the
/// node's own facets, `own`): two parts of a surface touch face to face, a
/// node never contacts a facet that looks the same way (the far side of a
/// fold, the next facets along a bend).
fn facing(
    surface: &FacetSurface,
    own: &[usize],
    node: usize,
    x: &[[f64; 3]],
    cand: &mut Vec<usize>,
) {
    let mut ns = [0.0; 3];
    for &k in own {
        if surface.faces[k].nodes().contains(&node) {
            let m = area_vector(surface, k, x);
            for c in 0..3 {
                ns[c] += m[c];
            }
        }
    }
    cand.retain(|&k| {
        let m = area_vector(surface, k, x);
        (0..3).map(|c| m[c] * ns[c]).sum::<f64>() < 0.0
    });
}

/// Whether 3D pair `pair` is mortar on quadratic faces (its slave or its
/// master faces have midside nodes: [`super::mortar::quadratic3d`], which
/// also takes the linear side of a mixed-order pair).
pub fn quadratic_mortar(model: &Model<3>, pair: usize) -> bool {
    model.contacts.get(pair).is_some_and(|cp| {
        let quadratic = |faces: &[crate::mesh::Facet]| {
            faces
                .first()
                .is_some_and(|f| super::mortar::quadratic3d::is_quadratic_face(f.nodes().len()))
        };
        cp.formulation == crate::model::ContactFormulation::Mortar
            && matches!(&cp.master, ContactMaster::Surface { faces, .. }
                if quadratic(&cp.faces) || quadratic(faces))
    })
}

/// The friction of one element as `evaluate` assembles it: the record,
/// the global node of each local node of the forces (`None`: an unused
/// slot), the forces and `-d forces / dx` (row-major).
struct FrictionForces {
    friction: super::friction::NodeFriction<3>,
    owners: Vec<Option<usize>>,
    forces: Vec<f64>,
    tangent: Vec<f64>,
}

/// Prepares a 3D pair; `None` if the master is a rigid tool.
pub fn prepare(model: &Model<3>, pair: usize, slaves: &[usize]) -> Option<DeformablePair> {
    let cp = model.contacts.get(pair)?;
    let ContactMaster::Surface { faces, .. } = &cp.master else {
        return None;
    };
    let h = cp
        .faces
        .iter()
        .chain(faces)
        .flat_map(|f| {
            let n = f.nodes();
            (0..n.len()).map(move |k| (n[k], n[(k + 1) % n.len()]))
        })
        .filter_map(|(a, b)| {
            let (pa, pb) = (model.mesh.nodes.get(a)?, model.mesh.nodes.get(b)?);
            Some((0..3).map(|c| (pb[c] - pa[c]).powi(2)).sum::<f64>().sqrt())
        })
        .filter(|l| *l > 0.0)
        .fold(f64::INFINITY, f64::min);
    let self_contact = is_self_contact(model, pair);
    let mortar_friction =
        cp.formulation == crate::model::ContactFormulation::Mortar && cp.friction.is_some();
    let sides = if quadratic_mortar(model, pair) {
        [
            FacetSurface::quadratic(&cp.faces),
            FacetSurface::quadratic(faces),
        ]
    } else {
        let mut sides = [FacetSurface::new(&cp.faces), FacetSurface::new(faces)];
        if cp.smoothing == crate::model::NormalSmoothing::Nagata {
            sides[0].mirror_rim(model, cp.body);
            if let ContactMaster::Surface { body, .. } = &cp.master {
                sides[1].mirror_rim(model, *body);
            }
        }
        sides
    };
    let excluded = if self_contact {
        slaves
            .iter()
            .map(|&n| excluded_facets(&sides[1], n))
            .collect()
    } else {
        Vec::new()
    };
    Some(DeformablePair {
        self_contact,
        excluded,
        evaluated: usize::MAX,
        touch: if h.is_finite() {
            super::penalty::TOUCH_FRACTION * h
        } else {
            0.0
        },
        sides,
        side_of: slaves
            .iter()
            .map(|n| u8::from(cp.nodes.binary_search(n).is_err()))
            .collect(),
        last: vec![None; slaves.len()],
        committed_last: vec![None; slaves.len()],
        beside: vec![false; slaves.len()],
        committed_beside: vec![false; slaves.len()],
        // mortar friction: the committed configuration of the weighted slip
        positions: if mortar_friction {
            model.mesh.nodes.clone()
        } else {
            Vec::new()
        },
        committed_positions: if mortar_friction {
            model.mesh.nodes.clone()
        } else {
            Vec::new()
        },
        ..DeformablePair::default()
    })
}

/// The normal force and `dR_N/dg` of a node (`None`: open).
fn response(
    method: &ContactMethod,
    alpha: f64,
    multiplier: f64,
    active: bool,
    gap: f64,
) -> Option<(f64, f64)> {
    let rn = normal_force(method, alpha, multiplier, active, gap)?;
    let slope = match method {
        ContactMethod::Lagrange { .. } => 0.0,
        _ => -alpha,
    };
    Some((rn, slope))
}

/// Evaluates the node-to-facet pair `pair` at current coordinates `x`:
/// one entry per slave node within the window (or active), the couplings
/// of the closed ones in `state.deformable`.
pub fn evaluate(
    model: &Model<3>,
    pair: usize,
    x: &[[f64; 3]],
    state: &mut SurfacePair,
) -> Vec<NodeContact<3>> {
    let mut out = Vec::new();
    let cp = &model.contacts[pair];
    let Some(mut fp) = state.deformable.take() else {
        return out;
    };
    state.evaluations += 1;
    state.friction.impact = None;
    let sides = fp.slave_sides(cp.strategy);
    let prof = state.prof;
    let nagata = cp.smoothing == NormalSmoothing::Nagata;
    for s in 0..2 {
        // side s is master when the other side is slave
        if sides[1 - s] {
            fp.sides[s].update(x, prof);
        }
    }
    fp.couplings.clear();
    fp.tests = 0;
    // the hold (`mortar::HOLD_BAND`): a Newton loop's first evaluation
    // records the nodes carrying a force, later ones may hold them
    let hold_fresh = std::mem::take(&mut fp.hold_fresh);
    let mut holds = 0;
    fp.hold_last.clear();
    fp.hold_last.resize(state.slaves.len(), false);
    fp.hold_force_last.clear();
    fp.hold_force_last.resize(state.slaves.len(), 0.0);
    // Lagrange: the first evaluation of the run, and of a double-pass swap
    // (the new slave side was not evaluated in the last increment: none of
    // its nodes is active, and a body that only this contact holds would
    // be free), brings the touching slaves into the active set
    let fresh = fp.evaluated != fp.increments
        && (fp.increments == 0 || cp.strategy == ContactStrategy::DoublePass);
    fp.evaluated = fp.increments;
    let mut candidates = std::mem::take(&mut fp.candidates);
    let mut memory_facets = std::mem::take(&mut fp.memory_facets);
    // `CTC_LOG=debug`: the closed nodes of this evaluation (node, facet,
    // feature, gap, free-edge fade), to find a node that cycles
    let debug = super::log::debug_enabled();
    let mut closed_log = String::new();
    for (i, &node) in state.slaves.iter().enumerate() {
        let side = fp.side_of[i] as usize;
        let Some(&xs) = x.get(node) else {
            continue;
        };
        if !sides[side] {
            fp.last[i] = None;
            state.friction.open(i, xs);
            continue;
        }
        let surface = &fp.sides[1 - side];
        candidates.clear();
        surface.grid.query(xs, prof, &mut candidates);
        // memory: the last facet, its neighbours and the walk from it
        // towards the node's foot are always tested, at any depth (rule 3)
        memory_facets.clear();
        if let Some(k) = fp.last[i].filter(|&k| k < surface.faces.len()) {
            surface.memory_walk(x, xs, k, &mut fp.tests, &mut memory_facets);
            candidates.extend_from_slice(&memory_facets);
            candidates.sort_unstable();
            candidates.dedup();
        }
        if fp.self_contact {
            // not the node's own patch, only the facets facing it
            let ex = &fp.excluded[i];
            candidates.retain(|k| ex.binary_search(k).is_err());
            facing(surface, ex, node, x, &mut candidates);
        }
        state.counters.queries += 1;
        let penalty_node = matches!(cp.method, ContactMethod::Penalty { .. });
        let memory = fp.last[i];
        // Nagata patches first; the faceted rules where no patch holds the
        // node's foot (the wedges of a patch-less corner)
        let smooth = if nagata {
            surface.closest_nagata(
                x,
                node,
                xs,
                &candidates,
                memory,
                &memory_facets,
                prof,
                &mut fp.tests,
            )
        } else {
            None
        };
        let faceted = if smooth.is_none() {
            surface.closest(
                x,
                xs,
                &candidates,
                memory,
                &memory_facets,
                prof,
                &mut fp.tests,
            )
        } else {
            None
        };
        let (k, gap, normal) = match (&smooth, &faceted) {
            (Some((k, e)), _) => (*k, e.gap, e.normal),
            (None, Some((k, el))) => (*k, el.gap, el.normal),
            (None, None) => {
                fp.last[i] = None;
                if penalty_node && !candidates.is_empty() {
                    fp.beside[i] =
                        surface.below_past_rim(x, xs, &candidates, &memory_facets, prof, fp.touch);
                }
                state.friction.open(i, xs);
                continue;
            }
        };
        fp.last[i] = Some(k);
        if penalty_node {
            // a node that came round the rim stays open while it is below
            // ([`DeformablePair::beside`])
            fp.beside[i] = fp.committed_beside[i] && gap < -fp.touch;
            if fp.beside[i] {
                if debug {
                    closed_log.push_str(&format!(" {node}:{k}beside:{gap:.3e}"));
                }
                state.friction.open(i, xs);
                continue;
            }
        }
        let active = state.active[i];
        if gap > prof && !active {
            state.friction.open(i, xs);
            continue;
        }
        let method = cp.method_at(node);
        let a = alpha(&method, state.area[i]);
        // closed-gap start: a touching node of a body only this contact
        // holds joins with zero force (penalty, AL: the tangent alpha G G^T;
        // Lagrange: the active set, its row holds the body)
        let touching = state.touching > 0.0 && (0.0..=state.touching).contains(&gap);
        let touching_start = fresh && gap <= fp.touch;
        if (touching || touching_start)
            && matches!(method, ContactMethod::Lagrange { .. })
            && !state.active[i]
        {
            state.active[i] = true;
            state.multiplier[i] = 0.0;
        }
        let active = state.active[i];
        let mut nc = NodeContact {
            node,
            gap,
            normal,
            force: [0.0; 3],
            stiffness: [[0.0; 3]; 3],
            pressure: 0.0,
            status: ContactStatus::Open,
            entity: k,
            master: None,
            friction: Default::default(),
        };
        // the cycling guard: a held penalty node is frozen closed, `R_N =
        // -alpha_N g` at any gap ([`DeformablePair::held`])
        let held = penalty_node && a > 0.0 && fp.held.get(i).copied().unwrap_or(false);
        let closed = if held {
            Some((-a * gap, -a))
        } else {
            response(&method, a, state.multiplier[i], active, gap)
                .or_else(|| (touching && a > 0.0).then_some((0.0, -a)))
        };
        // the hold (`mortar::HOLD_BAND`): a node of a penalty pair that
        // carried a normal force at the last accepted iterate and is open
        // within the band keeps the closed branch, the tensile `-alpha_N g`
        // and its tangent, for this iterate; reported open. With friction,
        // its friction is the law's (the return map from its stick point)
        // in the cone of the normal force it carried at that iterate, a
        // constant: `|T| <= mu R_N^acc`, the tangent without the normal
        // force's derivative (exact for that constant); quasi-static steps
        // only ([`DeformablePair::hold_friction`])
        let hold = closed.is_none()
            && !hold_fresh
            && (cp.friction.is_none() || fp.hold_friction)
            && matches!(method, ContactMethod::Penalty { .. })
            && a > 0.0
            && fp.hold_closed.get(i).copied().unwrap_or(false)
            && gap <= super::mortar::HOLD_BAND * state.area[i].max(0.0).sqrt();
        let closed = if hold { Some((-a * gap, -a)) } else { closed };
        if let Some((rn, slope)) = closed {
            let face = surface.faces[k].nodes();
            // the element's nodes (slave first), G and H over them
            let (local, grad, hess): (Vec<usize>, Vec<f64>, Vec<f64>) = match (&smooth, &faceted) {
                (Some((_, e)), _) => (e.nodes.clone(), e.gradient.clone(), e.hessian.clone()),
                (_, Some((_, el))) => {
                    let dofs = 3 * (1 + face.len());
                    (
                        std::iter::once(node).chain(face.iter().copied()).collect(),
                        el.gradient[..dofs].to_vec(),
                        (0..dofs)
                            .flat_map(|r| (0..dofs).map(move |c| el.hessian[r][c]))
                            .collect(),
                    )
                }
                (None, None) => unreachable!("a kept element"),
            };
            let dofs = grad.len();
            // the free-edge band (penalty, faceted face element): the
            // normal force is `w R_N` with `w` the fade of the foot past
            // the rim ([`edge_fade`]), `-d(w R_N G)/dx = w (-dR_N/dg) G G^T
            // - w R_N H - R_N G (dw/dx)^T`; Lagrange and the augmented
            // Lagrangian keep the hard edge of the band (a multiplier, or
            // its Uzawa update, is not faded)
            let penalty = matches!(method, ContactMethod::Penalty { .. });
            // (a Nagata element spans more than NDOF coordinates: no fade)
            let (fw, dfw): (f64, Option<&[f64]>) = match &faceted {
                Some((_, el)) if penalty && smooth.is_none() => {
                    (el.fade, Some(&el.fade_gradient[..dofs]))
                }
                _ => (1.0, None),
            };
            let free_edges: [bool; 4] = if penalty && smooth.is_none() {
                std::array::from_fn(|a| {
                    a < face.len() && surface.is_free_edge(face[a], face[(a + 1) % face.len()])
                })
            } else {
                [false; 4]
            };
            // Coulomb friction (penalty, augmented Lagrangian): its forces
            // over the slave, the facet and the stick point's facet
            // (faceted), or over the nodes of both patches' rings (Nagata,
            // `super::friction_nagata`); as (record, the global node of
            // each local node, forces, tangent)
            let held_law = held && !fp.held_slip.get(i).copied().unwrap_or(false);
            // a held node: the cone of the normal force it carried at the
            // last accepted iterate, a constant (the hold above)
            let (rn_f, slope_f) = if hold {
                (fp.hold_force.get(i).copied().unwrap_or(0.0), 0.0)
            } else {
                (rn, slope)
            };
            let friction: Option<FrictionForces> = match (cp.friction.as_ref(), &smooth, &faceted) {
                (Some(law), Some((_, e)), _) => {
                    let pts: Vec<[f64; 3]> = face.iter().map(|&m| x[m]).collect();
                    let contact = super::friction_facet::FacetContact {
                        slave: i,
                        xs,
                        facet: k,
                        pts: &pts,
                        xi: e.xi,
                        at: super::friction_facet::Projection::FACE,
                        gap: e.gap,
                        normal_force: rn_f,
                        normal_stiffness: -slope_f,
                        area: state.area[i],
                        free_edges,
                        held: held_law,
                    };
                    let patches = super::friction_nagata::Patches {
                        surface,
                        x,
                        slave: node,
                    };
                    super::friction_facet::apply_on(
                        law,
                        &method,
                        &contact,
                        surface.faces.len(),
                        &patches,
                        &mut state.friction,
                    )
                    .map(|(r, _)| FrictionForces {
                        owners: r.nodes.iter().map(|&n| Some(n)).collect(),
                        friction: r.friction,
                        forces: r.forces,
                        tangent: r.tangent,
                    })
                }
                (Some(law), None, Some((_, el))) => {
                    let pts: Vec<[f64; 3]> = face.iter().map(|&m| x[m]).collect();
                    // an edge or vertex element: the foot on the extended facet
                    let xi = match el.feature {
                        Feature::Face => Some(el.xi),
                        _ => foot(xs, &pts).map(|f| f.0),
                    };
                    match xi {
                        None => {
                            state.friction.anchor[i] = state.friction.committed_anchor[i];
                            state.friction.position[i] = xs;
                            None
                        }
                        Some(xi) => {
                            let contact = super::friction_facet::FacetContact {
                                slave: i,
                                xs,
                                facet: k,
                                pts: &pts,
                                xi,
                                // the normal that gives the gap (an edge's or
                                // vertex's at such a projection: `gap = side
                                // |x_s - p|`)
                                at: super::friction_facet::Projection {
                                    feature: el.feature,
                                    side: if el.gap < 0.0 { -1.0 } else { 1.0 },
                                },
                                gap: el.gap,
                                normal_force: rn_f,
                                normal_stiffness: -slope_f,
                                area: state.area[i],
                                free_edges,
                                held: held_law,
                            };
                            let points =
                                |f: usize| surface.faces[f].nodes().iter().map(|&m| x[m]).collect();
                            super::friction_facet::apply(
                                law,
                                &method,
                                &contact,
                                surface.faces.len(),
                                points,
                                &mut state.friction,
                            )
                            .map(|(r, ka)| {
                                let anchor_face = surface.faces[ka].nodes();
                                // friction dof -> node: the slave, facet k,
                                // facet k_a
                                let owners = (0..super::friction_facet::NDOF / 3)
                                    .map(|a| match a {
                                        0 => Some(node),
                                        1..=4 => face.get(a - 1).copied(),
                                        _ => anchor_face.get(a - 5).copied(),
                                    })
                                    .collect();
                                FrictionForces {
                                    owners,
                                    friction: r.friction,
                                    forces: r.forces.to_vec(),
                                    tangent: r.tangent,
                                }
                            })
                        }
                    }
                }
                _ => None,
            };
            let mut nodes = local.clone();
            if let Some(f) = &friction {
                nodes.extend(f.owners.iter().flatten());
            }
            nodes.sort_unstable();
            nodes.dedup();
            let nd = 3 * nodes.len();
            let pos = |l: usize| 3 * nodes.binary_search(&local[l / 3]).unwrap_or(0) + l % 3;
            let mut force = vec![0.0; nd];
            let mut row = vec![0.0; nd];
            let mut tangent = vec![0.0; nd * nd];
            let g = &grad;
            let k_rc = |r: usize, c: usize| {
                fw * (-slope * g[r] * g[c] - rn * hess[r * dofs + c])
                    - dfw.map_or(0.0, |d| rn * g[r] * d[c])
            };
            for (r, &gr) in g.iter().enumerate() {
                let pr = pos(r);
                force[pr] += fw * rn * gr;
                row[pr] += gr;
                for c in 0..dofs {
                    tangent[pr * nd + pos(c)] += k_rc(r, c);
                }
            }
            for (r, &gr) in g.iter().enumerate().take(3) {
                nc.force[r] = fw * rn * gr;
                for c in 0..3 {
                    nc.stiffness[r][c] = k_rc(r, c);
                }
            }
            if let Some(r) = friction {
                let fd = r.forces.len();
                // friction dof -> position in `nodes`
                let at: Vec<Option<usize>> = (0..fd)
                    .map(|d| {
                        let n = r.owners.get(d / 3).copied().flatten()?;
                        Some(3 * nodes.binary_search(&n).ok()? + d % 3)
                    })
                    .collect();
                for (d, pd) in at.iter().enumerate() {
                    let Some(pd) = *pd else { continue };
                    force[pd] += r.forces[d];
                    for (e, pe) in at.iter().enumerate() {
                        if let Some(pe) = *pe {
                            tangent[pd * nd + pe] += r.tangent[d * fd + e];
                        }
                    }
                }
                for a in 0..3 {
                    nc.force[a] += r.forces[a];
                    for b in 0..3 {
                        nc.stiffness[a][b] += r.tangent[a * fd + b];
                    }
                }
                nc.friction = r.friction;
            } else if cp.friction.is_some() {
                state.friction.position[i] = xs;
            }
            if hold {
                holds += 1;
            } else {
                nc.pressure = if state.area[i] > 0.0 {
                    fw * rn / state.area[i]
                } else {
                    0.0
                };
                nc.status = ContactStatus::Closed;
                fp.hold_last[i] = fw * rn > 0.0;
                fp.hold_force_last[i] = rn;
            }
            if debug {
                let feature = match faceted.as_ref().map(|f| f.1.feature) {
                    Some(Feature::Face) => "f",
                    Some(Feature::Edge(..)) => "e",
                    Some(Feature::Vertex(..)) => "v",
                    None => "n",
                };
                let tag = if hold { ":held" } else { "" };
                closed_log.push_str(&format!(" {node}:{k}{feature}:{gap:.3e}:{fw:.3}{tag}"));
            }
            fp.couplings.push(Coupling {
                nodes,
                force,
                tangent,
                slave: node,
                gap_gradient: row,
                force_direction: Vec::new(),
            });
        } else {
            state.friction.open(i, xs);
        }
        out.push(nc);
    }
    fp.candidates = candidates;
    fp.memory_facets = memory_facets;
    fp.holds = holds;
    if hold_fresh {
        // the Newton loop's first evaluation: the nodes a hold may keep at
        // its first iterate
        fp.hold_closed.clone_from(&fp.hold_last);
        fp.hold_force.clone_from(&fp.hold_force_last);
    }
    if debug {
        eprintln!(
            "[ctc ntf] pair '{}' evaluation {}: closed (node:facet feature:gap:fade){closed_log}",
            cp.name, state.evaluations
        );
    }
    if cp.strategy == ContactStrategy::ModifiedDoublePass || fp.self_contact {
        // both passes at once (self contact: both directions): report the
        // interface pressure (the total force on each node over its full
        // area, `super::interface_pressures`)
        let elements: Vec<super::ElementForces<'_>> = fp
            .couplings
            .iter()
            .map(super::ElementForces::of_coupling)
            .collect();
        let (slaves, areas) = (&state.slaves, &state.area);
        super::interface_pressures(&mut out, &elements, |n| {
            slaves
                .binary_search(&n)
                .ok()
                .and_then(|i| areas.get(i).copied())
        });
    }
    state.counters.faces_tested += fp.tests as u64;
    state.deformable = Some(fp);
    out
}

/// Drops the redundant Lagrange rows of a two-way pair (modified double
/// pass, self contact; [`super::redundancy`]), after the evaluation,
/// before the forces are assembled: the rows `G` of the active nodes'
/// couplings in slave order over the free coordinates (`free(node,
/// component)`). A redundant node keeps its place in the active set but
/// loses its multiplier, its force and its coupling (so its row: the
/// solver builds the rows from the couplings), flagged in
/// `state.redundant`. Other pairs: nothing.
pub fn drop_redundant(
    cp: &crate::model::ContactPair,
    state: &mut SurfacePair,
    out: &mut [NodeContact<3>],
    free: &dyn Fn(usize, usize) -> bool,
) {
    let Some(mut fp) = state.deformable.take() else {
        return;
    };
    state.redundant.clear();
    state.redundant.resize(state.slaves.len(), false);
    if matches!(cp.method, ContactMethod::Lagrange { .. })
        && (cp.strategy == ContactStrategy::ModifiedDoublePass || fp.self_contact)
    {
        let couplings = &mut fp.couplings;
        let mut owners = Vec::new();
        let mut rows: Vec<Vec<super::rows::NodeTerm>> = Vec::new();
        for (k, nc) in out.iter().enumerate() {
            let Some(i) = state.slave_index(nc.node) else {
                continue;
            };
            if !state.active.get(i).copied().unwrap_or(false) {
                continue;
            }
            let Ok(j) = couplings.binary_search_by_key(&nc.node, |c| c.slave) else {
                continue;
            };
            let c = &couplings[j];
            owners.push((k, i));
            rows.push(super::redundancy::free_row(
                &c.nodes,
                &c.gap_gradient,
                3,
                free,
            ));
        }
        let drop = super::redundancy::redundant_rows_of(&cp.name, &rows);
        for (&(k, i), _) in owners.iter().zip(&drop).filter(|(_, &d)| d) {
            state.redundant[i] = true;
            state.multiplier[i] = 0.0;
            let nc = &mut out[k];
            nc.force = [0.0; 3];
            nc.stiffness = [[0.0; 3]; 3];
            if let Ok(j) = couplings.binary_search_by_key(&nc.node, |c| c.slave) {
                couplings.remove(j);
            }
        }
    }
    state.deformable = Some(fp);
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::contact::friction::FrictionStatus;
    use proptest::prelude::*;

    /// Force `R G` of a penalty element (`R = -k g`) on the feature
    /// `feature` of facet `pts`, for the finite differences.
    fn element_at(
        xs: [f64; 3],
        pts: &[[f64; 3]],
        feature: Feature,
        side: f64,
    ) -> Option<FacetElement> {
        match feature {
            Feature::Face => {
                let (xi, _) = foot(xs, pts)?;
                face_element(xs, pts, xi)
            }
            Feature::Edge(a, b) => edge_element(xs, pts, a, Some(b), side),
            Feature::Vertex(a) => edge_element(xs, pts, a, None, side),
        }
    }

    fn pack(xs: [f64; 3], pts: &[[f64; 3]]) -> Vec<f64> {
        xs.iter().chain(pts.iter().flatten()).copied().collect()
    }

    fn unpack(v: &[f64], n: usize) -> ([f64; 3], Vec<[f64; 3]>) {
        let xs = [v[0], v[1], v[2]];
        let pts = (0..n)
            .map(|a| [v[3 + 3 * a], v[4 + 3 * a], v[5 + 3 * a]])
            .collect();
        (xs, pts)
    }

    /// Checks `G` against finite differences of `g`, the tangent
    /// `k G G^T - R H` (`R = -k g`) against finite differences of the
    /// force `R G`, and the force and moment balance; returns the largest
    /// relative errors `(G, K)`.
    fn check(xs: [f64; 3], pts: &[[f64; 3]], feature: Feature, side: f64) -> (f64, f64) {
        let k = 3.0;
        let n = pts.len();
        let dofs = 3 * (1 + n);
        let el = element_at(xs, pts, feature, side).expect("element");
        let v0 = pack(xs, pts);
        let force = |el: &FacetElement| -> Vec<f64> {
            (0..dofs).map(|r| -k * el.gap * el.gradient[r]).collect()
        };
        let f0 = force(&el);
        // balance: sum f = 0, sum x x f = 0
        let mut sum = [0.0; 3];
        let mut moment = [0.0; 3];
        for a in 0..=n {
            let p = [v0[3 * a], v0[3 * a + 1], v0[3 * a + 2]];
            let f = [f0[3 * a], f0[3 * a + 1], f0[3 * a + 2]];
            for c in 0..3 {
                sum[c] += f[c];
            }
            moment[0] += p[1] * f[2] - p[2] * f[1];
            moment[1] += p[2] * f[0] - p[0] * f[2];
            moment[2] += p[0] * f[1] - p[1] * f[0];
        }
        let fmax = f0.iter().fold(1e-12, |m: f64, v| m.max(v.abs()));
        for c in 0..3 {
            assert!(sum[c].abs() <= 1e-10 * fmax, "force balance {sum:?}");
            assert!(
                moment[c].abs() <= 1e-9 * fmax * 10.0,
                "moment balance {moment:?}"
            );
        }
        let h = 1e-6;
        let (mut eg, mut ek) = (0.0f64, 0.0f64);
        let gmax = el.gradient.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let kmax = (0..dofs)
            .flat_map(|r| (0..dofs).map(move |c| (r, c)))
            .map(|(r, c)| {
                (k * el.gradient[r] * el.gradient[c] + k * el.gap * el.hessian[r][c]).abs()
            })
            .fold(1e-12, f64::max);
        for c in 0..dofs {
            let mut vp = v0.clone();
            let mut vm = v0.clone();
            vp[c] += h;
            vm[c] -= h;
            let (xp, pp) = unpack(&vp, n);
            let (xm, pm) = unpack(&vm, n);
            let ep = element_at(xp, &pp, feature, side).expect("element +h");
            let em = element_at(xm, &pm, feature, side).expect("element -h");
            let dg = (ep.gap - em.gap) / (2.0 * h);
            eg = eg.max((dg - el.gradient[c]).abs() / gmax);
            let (fp, fm) = (force(&ep), force(&em));
            for r in 0..dofs {
                // K = -df/dx
                let fd = -(fp[r] - fm[r]) / (2.0 * h);
                let an = k * el.gradient[r] * el.gradient[c] + k * el.gap * el.hessian[r][c];
                ek = ek.max((fd - an).abs() / kmax);
            }
        }
        // H is symmetric
        for r in 0..dofs {
            for c in 0..dofs {
                assert!(
                    (el.hessian[r][c] - el.hessian[c][r]).abs() <= 1e-9 * (1.0 + kmax),
                    "H not symmetric at {r},{c}"
                );
            }
        }
        (eg, ek)
    }

    /// A random facet of `n` nodes near the unit square in the plane z = 0
    /// (corners moved by up to `warp`), counter-clockwise seen from +z.
    pub(crate) fn facet(n: usize, jitter: &[f64]) -> Vec<[f64; 3]> {
        let base: &[[f64; 3]] = if n == 3 {
            &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        } else {
            &[
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ]
        };
        base.iter()
            .enumerate()
            .map(|(a, p)| {
                [
                    p[0] + 0.2 * jitter[3 * a],
                    p[1] + 0.2 * jitter[3 * a + 1],
                    p[2] + 0.3 * jitter[3 * a + 2],
                ]
            })
            .collect()
    }

    #[test]
    fn flat_quad_gap_normal_and_weights() {
        let pts = facet(4, &[0.0; 12]);
        let (xi, it) = foot([0.25, 0.75, -0.1], &pts).unwrap();
        assert!(it <= 3);
        let el = face_element([0.25, 0.75, -0.1], &pts, xi).unwrap();
        assert!((el.gap + 0.1).abs() < 1e-14);
        assert!((el.normal[2] - 1.0).abs() < 1e-14);
        let w = el.weights;
        assert!((w[0] - 0.1875).abs() < 1e-14 && (w[3] - 0.5625).abs() < 1e-14);
        assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-14);
    }

    #[test]
    fn node_above_a_convex_ridge_takes_the_edge_cylinder() {
        // two quads folded along the y axis (a roof), a node above the ridge
        // outside both facets' prisms: the edge, normal along (x_s - p)
        let faces = [Facet::new(&[0, 1, 2, 3]), Facet::new(&[1, 4, 5, 2])];
        let mut x = vec![
            [-1.0, 0.0, -0.5],
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-1.0, 1.0, -0.5],
            [1.0, 0.0, -0.5],
            [1.0, 1.0, -0.5],
        ];
        x.push([0.05, 0.5, 0.3]);
        let s = FacetSurface::new(&faces);
        assert!(!s.is_free_edge(1, 2) && s.is_free_edge(0, 1));
        let mut tests = 0;
        let (_, el) = s
            .closest(&x, x[6], &[0, 1], None, &[], 1.0, &mut tests)
            .unwrap();
        assert!(matches!(el.feature, Feature::Edge(..)), "{:?}", el.feature);
        let d = (0.05f64 * 0.05 + 0.09).sqrt();
        assert!((el.gap - d).abs() < 1e-14, "{}", el.gap);
        // inside a prism: the face
        let (k, el) = s
            .closest(&x, [0.5, 0.5, 0.0], &[0, 1], None, &[], 1.0, &mut tests)
            .unwrap();
        assert_eq!((k, el.feature), (1, Feature::Face));
    }

    #[test]
    fn a_node_past_a_sharp_edge_is_outside_whichever_facet_comes_first() {
        // a wedge of two quads along the edge x = 1, z = 0 (63 degrees
        // inside): the top z = 0 (normal +z) and a face going down and back
        // (normal (1, 0, -0.5) / |.|). The node (1.5, 0.5, -0.1) lies in
        // front of the sloping face, past both facets' edges (its nearest
        // feature the edge) and below the top's plane: outside the wedge.
        // With the top's normal alone its gap was -0.51 (closed) when the
        // top came first among the candidates, +0.51 (open) otherwise; the
        // edge's pseudo-normal gives +0.51 either way (the 3D blade loss's
        // chatter of blade 6's tip nodes on the released blade's end)
        let faces = [Facet::new(&[0, 1, 2, 3]), Facet::new(&[1, 4, 5, 2])];
        let x = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.0, -1.0],
            [0.5, 1.0, -1.0],
        ];
        let s = FacetSurface::new(&faces);
        assert!(!s.is_free_edge(1, 2));
        let xs = [1.5, 0.5, -0.1];
        let d = (0.5f64 * 0.5 + 0.1 * 0.1).sqrt();
        let mut tests = 0;
        for order in [[0, 1], [1, 0]] {
            let (_, el) = s
                .closest(&x, xs, &order, None, &[], 1.0, &mut tests)
                .unwrap();
            assert!(matches!(el.feature, Feature::Edge(..)), "{:?}", el.feature);
            assert!((el.gap - d).abs() < 1e-14, "{order:?}: {}", el.gap);
        }
        // inside the wedge, nearest the edge (behind both planes): negative
        let inside = [0.95, 0.5, -0.02];
        for order in [[0, 1], [1, 0]] {
            let (_, el) = s
                .closest(&x, inside, &order, None, &[], 1.0, &mut tests)
                .unwrap();
            assert!(el.gap < 0.0, "{order:?}: {}", el.gap);
        }
    }

    #[test]
    fn memory_keeps_its_facet_across_a_seam() {
        // two triangles of a flat square split along its diagonal, a node
        // just past the diagonal: the remembered facet keeps it within
        // SEAM_TOL, the closest rule alone takes the other one
        let faces = [Facet::new(&[0, 1, 2]), Facet::new(&[0, 2, 3])];
        let x = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let s = FacetSurface::new(&faces);
        let mut tests = 0;
        let xs = [0.5, 0.504, -0.01];
        assert_eq!(
            s.closest(&x, xs, &[0, 1], None, &[], 1.0, &mut tests)
                .unwrap()
                .0,
            1
        );
        assert_eq!(
            s.closest(&x, xs, &[0, 1], Some(0), &[], 1.0, &mut tests)
                .unwrap()
                .0,
            0
        );
        // beyond the tolerance the memory lets go
        let far = [0.4, 0.6, -0.01];
        assert_eq!(
            s.closest(&x, far, &[0, 1], Some(0), &[], 1.0, &mut tests)
                .unwrap()
                .0,
            1
        );
    }

    /// The die of the 3D ironing as a strip of a cylinder (radius 3, axis
    /// z, 200..340 degrees in 28 facets of 5 degrees, two rows of 0.4 in z:
    /// facet `k + 28 j`, outward normal away from the axis) centred at
    /// `c`, and its nodes (`k + 29 j`).
    fn die_strip(c: [f64; 2]) -> (FacetSurface, Vec<[f64; 3]>) {
        let id = |k: usize, j: usize| k + 29 * j;
        let faces: Vec<Facet> = (0..2)
            .flat_map(|j| {
                (0..28).map(move |k| {
                    Facet::new(&[id(k, j), id(k + 1, j), id(k + 1, j + 1), id(k, j + 1)])
                })
            })
            .collect();
        let x = (0..3)
            .flat_map(|j| {
                (0..=28).map(move |k| {
                    let t = (200.0 + 5.0 * k as f64).to_radians();
                    [c[0] + 3.0 * t.cos(), c[1] + 3.0 * t.sin(), 0.4 * j as f64]
                })
            })
            .collect();
        (FacetSurface::new(&faces), x)
    }

    /// A node thrown deep into a thin sliding master keeps its facet (issue
    /// 18, the 3D ironing slide: slab nodes 35 and 195 thrown 0.537 into
    /// the die, past `max(prof, h)`, converged open inside it). The 2D
    /// case of `node_to_segment` (`node_deep_inside_a_convex_sliding_master_keeps_its_segment`)
    /// on a strip of the die ([`die_strip`], `h` = 0.4, `prof` 0.5): a slab
    /// node touching facet 14 (272.5 deg) at depth 1e-3; the die slides
    /// 0.6 along x (2.3 facet widths) and a Newton step puts the node 0.56
    /// inside it. Searched from its memory it keeps the facet under it at
    /// its depth (a flat facet: the depth below the 2D chord); the same
    /// node without memory is not taken (rule 3: the far side of a thin
    /// body), nor from the last facet and its neighbours alone (the
    /// search before the walk); memory exempts only its own facets. The
    /// same with Nagata patches (the gap to the curved patch).
    #[test]
    fn a_node_thrown_deep_into_a_thin_sliding_master_keeps_its_facet() {
        let (r, prof, z) = (3.0f64, 0.5, 0.2);
        let (s, x) = die_strip([0.0, 3.0]);
        let mut tests = 0;
        let t = 272.5f64.to_radians();
        let chord = r * 2.5f64.to_radians().cos();
        let xs = [(chord - 1e-3) * t.cos(), 3.0 + (chord - 1e-3) * t.sin(), z];
        let near = [13, 14, 15];
        let (k, el) = s
            .closest(&x, xs, &near, None, &[], prof, &mut tests)
            .unwrap();
        assert_eq!(k, 14);
        assert!((el.gap + 1e-3).abs() < 1e-12, "{}", el.gap);
        // the die slides 0.6 along x, the node is 0.56 inside it
        let c1 = [0.6, 3.0];
        let (_, x) = die_strip(c1);
        let xs = [xs[0], xs[1] + 0.6, z];
        let (dx, dy) = (xs[0] - c1[0], xs[1] - c1[1]);
        let angle = dy.atan2(dx).to_degrees().rem_euclid(360.0);
        let under = ((angle - 200.0) / 5.0).floor() as usize;
        assert!(under + 2 <= 14, "the foot is 2+ facets away: {under}");
        let mid = (200.0 + 5.0 * under as f64 + 2.5).to_radians();
        let depth = chord - (dx * mid.cos() + dy * mid.sin());
        let h = 0.4f64.max(2.0 * r * 2.5f64.to_radians().sin());
        assert!(depth > prof.max(h), "{depth}");
        // the last facet and its neighbours alone: lost
        let mut around = vec![14];
        around.extend_from_slice(&s.neighbours[14]);
        assert!(s
            .closest(&x, xs, &around, Some(14), &[], prof, &mut tests)
            .is_none());
        // no memory, every facet a candidate: not taken (too deep)
        let all: Vec<usize> = (0..56).collect();
        assert!(s
            .closest(&x, xs, &all, None, &[], prof, &mut tests)
            .is_none());
        // from its memory: the walk reaches the facet under it
        let mut memory = Vec::new();
        s.memory_walk(&x, xs, 14, &mut tests, &mut memory);
        assert!(memory.contains(&under), "{memory:?} lacks {under}");
        assert!(memory.windows(2).all(|w| w[0] < w[1]), "{memory:?}");
        let (k, el) = s
            .closest(&x, xs, &memory, Some(14), &memory, prof, &mut tests)
            .expect("kept");
        assert_eq!((k, el.feature), (under, Feature::Face));
        assert!((el.gap + depth).abs() < 1e-12, "{} vs {depth}", el.gap);
        // memory exempts from the depth window only its own facets
        let (_, e) = s
            .closest(&x, xs, &all, Some(14), &memory, prof, &mut tests)
            .unwrap();
        assert!((e.gap + depth).abs() < 1e-12, "{}", e.gap);
        assert!(s
            .closest(&x, xs, &all, Some(14), &[14], prof, &mut tests)
            .is_none());
        // Nagata patches: the same rule
        let node = 999;
        let nagata = |cand: &[usize], exempt: &[usize], tests: &mut usize| {
            s.closest_nagata(&x, node, xs, cand, Some(14), exempt, prof, tests)
        };
        let (k, e) = nagata(&memory, &memory, &mut tests).expect("kept");
        assert_eq!(k, under);
        assert!(
            e.gap < -prof.max(h) && (e.gap + depth).abs() < 0.05,
            "{}",
            e.gap
        );
        assert!(nagata(&all, &[], &mut tests).is_none());
        assert!(nagata(&all, &[14], &mut tests).is_none());
    }

    /// The walk of [`FacetSurface::memory_walk`] ends (a ring of 36
    /// facets round the z axis, radius 1, z in [0, 1], outward normals):
    /// on the facet holding the foot, seen from inside the tube 30 degrees
    /// past the start facet's centre; in the wedge in front of a convex
    /// edge (a point outside the ring on the edge between facets 9 and 10:
    /// each foot lies past the edge towards the other facet) after one
    /// step, without going round; at the rim (a point far past z = 1: no
    /// facet across the free edge) at once.
    #[test]
    fn the_memory_walk_stops_on_the_foot_at_a_wedge_and_at_the_rim() {
        let id = |k: usize, j: usize| k % 36 + 36 * j;
        let faces: Vec<Facet> = (0..36)
            .map(|k| Facet::new(&[id(k, 0), id(k + 1, 0), id(k + 1, 1), id(k, 1)]))
            .collect();
        let x: Vec<[f64; 3]> = (0..2)
            .flat_map(|j| {
                (0..36).map(move |k| {
                    let t = (10.0 * k as f64).to_radians();
                    [t.cos(), t.sin(), j as f64]
                })
            })
            .collect();
        let s = FacetSurface::new(&faces);
        let polar = |r: f64, deg: f64, z: f64| {
            let t = deg.to_radians();
            [r * t.cos(), r * t.sin(), z]
        };
        let mut tests = 0;
        let mut memory = Vec::new();
        // inside, at 124 degrees, r 0.9: facets 9 -> 10 -> 11 -> 12, whose
        // foot it holds (4 projections)
        s.memory_walk(&x, polar(0.9, 124.0, 0.5), 9, &mut tests, &mut memory);
        assert_eq!(tests, 4);
        assert_eq!(memory, (8..=13).collect::<Vec<_>>());
        // outside on the edge at 100 degrees: 9 -> 10, whose foot lies back
        // past the same edge (2 projections)
        s.memory_walk(&x, polar(2.0, 100.0, 0.5), 9, &mut tests, &mut memory);
        assert_eq!(tests, 6);
        assert_eq!(memory, (8..=11).collect::<Vec<_>>());
        // far past the rim: one projection, the facet and its neighbours
        s.memory_walk(&x, polar(1.0, 5.0, 50.0), 0, &mut tests, &mut memory);
        assert_eq!(tests, 7);
        assert_eq!(memory, vec![0, 1, 35]);
    }

    #[test]
    fn a_node_crossing_the_master_in_one_increment_is_a_jump() {
        // a flat master of two quads; node 6 goes from 0.05 above it to 0.05
        // below (crossing, window 0.01), node 7 slides 0.5 along it at a
        // gap of 0.005, node 8 approaches from 0.9 above to 0.6 above
        let faces = [Facet::new(&[0, 1, 2, 3]), Facet::new(&[1, 4, 5, 2])];
        let x0 = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [0.5, 0.5, 0.05],
            [0.5, 0.5, 0.005],
            [1.5, 0.5, 0.9],
        ];
        let mut x1 = x0.clone();
        x1[6][2] = -0.05;
        x1[7][0] = 1.0;
        x1[8][2] = 0.6;
        let mut s = FacetSurface::new(&faces);
        let j = jumps(&mut s, &[6, 7, 8], 0.01, &x0, &x1);
        assert_eq!(j.len(), 1, "{j:?}");
        assert_eq!(j[0].node, 6);
        assert!((j[0].distance - 0.1).abs() < 1e-12 && (j[0].normal - 0.1).abs() < 1e-12);
        // the master moving with the node: no relative motion, no jump
        let mut x2 = x1.clone();
        for p in x2.iter_mut().take(6) {
            p[2] -= 0.1;
        }
        assert!(jumps(&mut s, &[6], 0.01, &x0, &x2).is_empty());
    }

    /// A flat `n x n` grid of unit quads in z = 0, normal +z (node `i + (n
    /// + 1) j` at `(i, j, 0)`, facet `i + n j`).
    fn grid(n: usize) -> Vec<Facet> {
        let id = |i: usize, j: usize| i + (n + 1) * j;
        (0..n * n)
            .map(|k| {
                let (i, j) = (k % n, k / n);
                Facet::new(&[id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)])
            })
            .collect()
    }

    #[test]
    fn a_node_past_a_free_edge_leaves_the_surface() {
        // 4 x 4 unit grid (x, y in [0, 4], z = 0): a node slid past the free
        // edge x = 4 by more than FREE_EDGE_TOL, just below the plane. The
        // nearest feature is the free edge: no element. (The rule once took
        // the nearest *interior* edge, x = 3, one facet away: gap -1.0.)
        let s = FacetSurface::new(&grid(4));
        let x: Vec<[f64; 3]> = (0..25)
            .map(|n| [(n % 5) as f64, (n / 5) as f64, 0.0])
            .collect();
        let mut tests = 0;
        let all: Vec<usize> = (0..16).collect();
        let past = [4.0 + 2.0 * FREE_EDGE_TOL, 1.5, -1e-3];
        assert!(s
            .closest(&x, past, &all, None, &[], 2.0, &mut tests)
            .is_none());
        // past a free corner too
        let corner = [4.1, 4.1, -1e-3];
        assert!(s
            .closest(&x, corner, &all, None, &[], 2.0, &mut tests)
            .is_none());
        // within FREE_EDGE_TOL the extended facet keeps it
        let (k, el) = s
            .closest(
                &x,
                [4.0 + 0.5 * FREE_EDGE_TOL, 1.5, -1e-3],
                &all,
                None,
                &[],
                2.0,
                &mut tests,
            )
            .unwrap();
        assert_eq!((k, el.feature), (7, Feature::Face));
        assert!((el.gap + 1e-3).abs() < 1e-15, "{}", el.gap);
    }

    #[test]
    fn self_contact_excludes_the_node_s_patch_and_keeps_facing_facets() {
        // 6 x 6 grid: the centre node (3, 3) owns facets (2..=3, 2..=3);
        // with the facets sharing a node with those: (1..=4, 1..=4), 16
        let s = FacetSurface::new(&grid(6));
        let ex = excluded_facets(&s, 3 + 7 * 3);
        let want: Vec<usize> = (1..=4)
            .flat_map(|j| (1..=4).map(move |i| i + 6 * j))
            .collect();
        assert_eq!(ex, want);
        // a corner node: its facet and the three around it
        assert_eq!(excluded_facets(&s, 0), vec![0, 1, 6, 7]);
        // a strip folded onto itself: facets 0..3 along x at z = 0 (normal
        // +z), facets 3..6 back along x at z = 0.1 (normal -z); node 0 sees
        // the facets of the upper part, never those beside it
        let faces = [
            Facet::new(&[0, 1, 5, 4]),
            Facet::new(&[1, 2, 6, 5]),
            Facet::new(&[2, 3, 7, 6]),
            Facet::new(&[8, 12, 13, 9]),
            Facet::new(&[9, 13, 14, 10]),
            Facet::new(&[10, 14, 15, 11]),
        ];
        let mut x = Vec::new();
        for z in [0.0, 0.1] {
            for y in [0.0, 1.0] {
                for i in 0..4 {
                    x.push([i as f64, y, z]);
                }
            }
        }
        let s = FacetSurface::new(&faces);
        let ex = excluded_facets(&s, 1);
        assert_eq!(ex, vec![0, 1, 2]);
        let mut cand: Vec<usize> = (0..6).filter(|k| ex.binary_search(k).is_err()).collect();
        facing(&s, &ex, 1, &x, &mut cand);
        assert_eq!(cand, vec![3, 4, 5]);
        // a node of the upper part sees the lower part only
        let mut cand: Vec<usize> = (0..3).collect();
        facing(&s, &excluded_facets(&s, 13), 13, &x, &mut cand);
        assert_eq!(cand, vec![0, 1, 2]);
        let mut cand: Vec<usize> = vec![4, 5];
        facing(&s, &[3], 13, &x, &mut cand);
        assert!(cand.is_empty());
    }

    /// A penalty pair (nodal `alpha_N = 100`) of one slave triangle
    /// (nodes 9, 10, 11; 10 and 11 far above, out of the window) against a
    /// 2 x 2 grid of unit quads in `z ~ 0` (slightly warped, so the foot,
    /// the normal and the fade's gradient are not trivial), whose rim has
    /// the free edge `x = 2`; with Coulomb friction `mu = 0.3`, `alpha_T =
    /// 25` if `friction`. The slave node 9 at `xs`.
    fn band_pair(xs: [f64; 3], friction: bool) -> Model<3> {
        use crate::model::{ContactPair, FirstImpact, Friction, PenaltyKind};
        let mut nodes: Vec<[f64; 3]> = (0..9)
            .map(|n| {
                let (i, j) = ((n % 3) as f64, (n / 3) as f64);
                [i, j, 0.02 * (1.3 * i + 0.7 * j).sin()]
            })
            .collect();
        nodes.extend([xs, [0.0, 0.0, 3.0], [0.0, 1.0, 3.0]]);
        let mesh = crate::mesh::Mesh::new(nodes, vec![]);
        let mut m = crate::testkit::ModelBuilder::solid()
            .elastic("m", 1.0, 0.3)
            .body("b", mesh, "m")
            .build();
        let id = |i: usize, j: usize| i + 3 * j;
        let faces: Vec<Facet> = (0..4)
            .map(|k| {
                let (i, j) = (k % 2, k / 2);
                Facet::new(&[id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)])
            })
            .collect();
        m.contacts.push(ContactPair {
            name: "slave -> grid".into(),
            body: 0,
            edges: vec![],
            faces: vec![Facet::new(&[9, 10, 11])],
            nodes: vec![9, 10, 11],
            master: ContactMaster::Surface {
                body: 0,
                edges: vec![],
                faces,
                nodes: (0..9).collect(),
            },
            strategy: ContactStrategy::SinglePass,
            search: Default::default(),
            formulation: Default::default(),
            smoothing: Default::default(),
            method: ContactMethod::Penalty {
                kind: PenaltyKind::Nodal,
                stiffness: 100.0,
            },
            prof: Some(0.5),
            friction: friction.then_some(Friction {
                mu: 0.3,
                stiffness: Some(25.0),
                first_impact: FirstImpact::Intersect,
                cut_at_impact: false,
            }),
            local_penalty: Vec::new(),
        });
        m
    }

    /// The coupling of slave node 9 at the coordinates `x` (`None`: open).
    fn band_coupling(m: &Model<3>, x: &[[f64; 3]], state: &SurfacePair) -> Option<Coupling> {
        let mut st = state.clone();
        evaluate(m, 0, x, &mut st);
        let fp = st.deformable.as_ref()?;
        fp.couplings.iter().find(|c| c.slave == 9).cloned()
    }

    #[test]
    fn a_node_sliding_across_the_free_edge_band_loses_its_force_continuously() {
        // node 9 slides along y = 0.5 at 0.01 below the master from x =
        // 1.97 (inside facet 1) to 2.03 (past the band, which ends at x =
        // 2 + FREE_EDGE_TOL: unit facets). Before the fade its normal
        // force, alpha_N 0.01 = 1.0, dropped to 0 at x = 2.02 between two
        // samples whatever the sampling; now the largest jump between
        // consecutive samples falls as the sampling refines (C1 weight:
        // ~ 1 / samples).
        let m = band_pair([1.97, 0.5, -0.01], false);
        let state = SurfacePair::new(&m, 0);
        let force = |xn: f64| {
            let mut x = m.mesh.nodes.clone();
            let z = 0.02 * (1.3 * 2.0 + 0.7 * 0.5f64).sin();
            x[9] = [xn, 0.5, z - 0.01];
            band_coupling(&m, &x, &state).map_or(0.0, |c| {
                let k = c.nodes.binary_search(&9).unwrap();
                c.force[3 * k + 2]
            })
        };
        // full force inside the facet, none past the band
        assert!((force(1.99) - 1.0).abs() < 0.05, "{}", force(1.99));
        assert_eq!(force(2.0 + 1.01 * FREE_EDGE_TOL), 0.0);
        let max_jump = |samples: usize| {
            let xs: Vec<f64> = (0..=samples)
                .map(|k| 1.97 + 0.06 * k as f64 / samples as f64)
                .collect();
            xs.windows(2)
                .map(|w| (force(w[1]) - force(w[0])).abs())
                .fold(0.0, f64::max)
        };
        let (j1, j2, j3) = (max_jump(60), max_jump(240), max_jump(960));
        // expected ~ 1.875 alpha_N |g| dx / band (the smootherstep's
        // largest slope): 0.094, 0.023, 0.0059 (the hard edge: 1.0 at any
        // sampling); the bounds ask for a fall at least ~ 1 / samples
        assert!(j1 < 0.1 && j2 < 0.3 * j1 && j3 < 0.3 * j2, "{j1} {j2} {j3}");
    }

    /// `-d f / d x` of slave node 9's coupling against central differences
    /// over every coordinate it couples, the forces' sum and (frictionless)
    /// moment; returns the largest relative error of the tangent.
    fn band_fd(m: &Model<3>, state: &SurfacePair, friction: bool) -> f64 {
        let x0 = m.mesh.nodes.clone();
        let c = band_coupling(m, &x0, state).expect("closed in the band");
        let nd = c.force.len();
        let scale = c.tangent.iter().fold(1e-12, |a: f64, v| a.max(v.abs()));
        let fmax = c.force.iter().fold(1e-12, |a: f64, v| a.max(v.abs()));
        let mut sum = [0.0; 3];
        let mut moment = [0.0; 3];
        for (k, &n) in c.nodes.iter().enumerate() {
            let (p, f) = (x0[n], &c.force[3 * k..3 * k + 3]);
            for a in 0..3 {
                sum[a] += f[a];
            }
            moment[0] += p[1] * f[2] - p[2] * f[1];
            moment[1] += p[2] * f[0] - p[0] * f[2];
            moment[2] += p[0] * f[1] - p[1] * f[0];
        }
        for a in 0..3 {
            assert!(sum[a].abs() <= 1e-13 * fmax, "force balance {sum:?}");
            if !friction {
                assert!(moment[a].abs() <= 1e-12 * fmax, "moment balance {moment:?}");
            }
        }
        let h = 1e-7;
        let mut err = 0.0f64;
        for col in 0..nd {
            let f = |s: f64| {
                let mut x = x0.clone();
                x[c.nodes[col / 3]][col % 3] += s;
                let e = band_coupling(m, &x, state).expect("closed at +-h");
                assert_eq!(e.nodes, c.nodes);
                e.force
            };
            let (fp, fm) = (f(h), f(-h));
            for r in 0..nd {
                let fd = -(fp[r] - fm[r]) / (2.0 * h);
                err = err.max((fd - c.tangent[r * nd + col]).abs() / scale);
            }
        }
        err
    }

    #[test]
    fn a_node_that_came_round_the_free_rim_below_the_master_gets_no_force() {
        // node 9 lies past the free edge x = 2 (beyond the band) 0.3 below
        // the grid's extension, then moves into the band and over facet 1
        // at that depth: it came round the rim, not through the surface,
        // and stays open until it is in front again; then pressed in it
        // closes. Without the flag the band switched on alpha_N 0.3 w at
        // that depth with no work done against it: pushed out along the
        // normal the node gained alpha_N 0.3^2 / 2 = 4.5 w.
        let m = band_pair([2.1, 0.5, -0.3], false);
        let z = |xn: f64, yn: f64| 0.02 * (1.3 * xn + 0.7 * yn).sin();
        let at = |xn: f64, dz: f64| {
            let mut x = m.mesh.nodes.clone();
            x[9] = [xn, 0.5, z(xn, 0.5) + dz];
            x
        };
        let normal_force = |c: &Coupling| {
            let k = c.nodes.binary_search(&9).unwrap();
            c.force[3 * k + 2]
        };
        let slave = |st: &SurfacePair| st.slaves.binary_search(&9).unwrap();
        let fresh = SurfacePair::new(&m, 0);
        // a node found in the band for the first time keeps the old rule
        // (nothing says where it came from): the faded force at 0.3
        let old = band_coupling(&m, &at(2.005, -0.3), &fresh).expect("band element");
        assert!(normal_force(&old) > 1.0, "{}", normal_force(&old));
        let mut st = fresh.clone();
        let step = |x: Vec<[f64; 3]>, st: &mut SurfacePair| {
            evaluate(&m, 0, &x, st);
            let coupled = st
                .deformable
                .as_ref()
                .and_then(|f| f.couplings.iter().find(|c| c.slave == 9).cloned());
            let beside = st.deformable.as_ref().unwrap().beside[slave(st)];
            st.commit();
            (coupled, beside)
        };
        // past the band, below the extension: no element, beside
        let (c, beside) = step(at(2.1, -0.3), &mut st);
        assert!(c.is_none() && beside);
        // into the band, then over the facet, still 0.3 below: open
        for xn in [2.005, 1.99, 1.5] {
            let (c, beside) = step(at(xn, -0.3), &mut st);
            assert!(c.is_none() && beside, "x = {xn}");
        }
        // a rollback keeps the committed flag
        st.rollback();
        assert!(st.deformable.as_ref().unwrap().beside[slave(&st)]);
        // in front of the surface: cleared; pressed in again: closed
        let (c, beside) = step(at(1.5, 0.01), &mut st);
        assert!(c.is_none() && !beside);
        let (c, beside) = step(at(1.5, -0.3), &mut st);
        let c = c.expect("closed from the front");
        assert!(
            !beside && (normal_force(&c) - 30.0).abs() < 1.0,
            "{}",
            normal_force(&c)
        );
        // past the rim above the extension, or within touch (1e-3 of the
        // unit facets) below it: not beside (the extension of facet 1 at
        // x = 2.1, y = 0.5 lies at z = 0.00207, the warp's z there is
        // 0.00123: dz = 0.00034 is 0.0005 below it)
        let mut st = SurfacePair::new(&m, 0);
        assert!(!step(at(2.1, 0.3), &mut st).1);
        assert!(!step(at(2.1, 0.00034), &mut st).1);
        assert!(step(at(2.1, -0.01), &mut st).1);
    }

    /// The penalty cycling guard ([`DeformablePair::guard_cycle`]): node 9
    /// over the middle of the warped grid (penalty 100, mu 0.3) accepted
    /// closed 0.05 deep, open 0.05 above, closed again: the third status
    /// set repeats the first (A -> B -> A) and node 9 is held; a monotone
    /// sequence holds nothing. Held above the master it stays closed with
    /// the tensile penalty force `-alpha_N g n`, which the consistency
    /// check refuses (the node is released and no more held in that
    /// Newton loop); held below it, sticking, it is consistent; a new
    /// Newton loop forgets it (open above the master, no coupling).
    #[test]
    fn the_cycling_guard_holds_a_node_whose_status_comes_back() {
        let m = band_pair([1.5, 1.5, -0.05], true);
        let at = |dz: f64| {
            let mut x = m.mesh.nodes.clone();
            x[9] = [1.5, 1.5, dz];
            x
        };
        let coupling = |st: &SurfacePair| {
            let fp = st.deformable.as_ref().unwrap();
            fp.couplings.iter().find(|c| c.slave == 9).cloned()
        };
        let accept = |st: &mut SurfacePair, dz: f64| {
            let out = evaluate(&m, 0, &at(dz), st);
            let slaves = st.slaves.clone();
            st.deformable.as_mut().unwrap().guard_cycle(&slaves, &out)
        };
        let mut st = SurfacePair::new(&m, 0);
        let i = st.slave_index(9).unwrap();
        for dz in [-0.05, -0.04, 0.05, 0.06] {
            assert_eq!(accept(&mut st, dz), 0, "monotone: {dz}");
        }
        st.deformable.as_mut().unwrap().guard_start();
        assert_eq!(accept(&mut st, -0.05), 0);
        assert_eq!(accept(&mut st, 0.05), 0);
        assert_eq!(accept(&mut st, -0.05), 1);
        assert!(st.deformable.as_ref().unwrap().held[i]);
        // held below the master: closed, sticking, consistent
        let out = evaluate(&m, 0, &at(-0.05), &mut st);
        let slaves = st.slaves.clone();
        let fp = st.deformable.as_mut().unwrap();
        assert!(fp.guard_consistent(&slaves, &out) && fp.held[i]);
        // held above it: closed, pulled in by -alpha_N g n; inconsistent,
        // released, and no more held in this Newton loop
        let out = evaluate(&m, 0, &at(0.05), &mut st);
        let nc = out.iter().find(|c| c.node == 9).unwrap();
        assert!(
            nc.gap > 0.04 && nc.status == ContactStatus::Closed,
            "{nc:?}"
        );
        // (the friction force, frozen sticking, lies in the tangent plane)
        let fnormal: f64 = (0..3).map(|c| nc.force[c] * nc.normal[c]).sum();
        assert!(
            (fnormal + 100.0 * nc.gap).abs() < 1e-9,
            "{fnormal} {}",
            nc.gap
        );
        assert!(coupling(&st).is_some());
        let fp = st.deformable.as_mut().unwrap();
        assert!(!fp.guard_consistent(&slaves, &out) && !fp.held.contains(&true));
        for dz in [0.05, -0.05, 0.05, -0.05] {
            assert_eq!(accept(&mut st, dz), 0, "released: {dz}");
        }
        // a new Newton loop: open, no coupling
        st.deformable.as_mut().unwrap().guard_start();
        evaluate(&m, 0, &at(0.05), &mut st);
        assert!(coupling(&st).is_none());
    }

    /// The hold of node-to-facet penalty rows (`mortar::HOLD_BAND`, issue
    /// 18: the 3D ironing benchmark's slide, where the die's prescribed
    /// step opened the closed slab nodes and the next step threw them
    /// through the die): node 9 over the middle of the warped grid
    /// (penalty 100, nodal; the master's z there 0.0021), 0.012 deep at a
    /// Newton loop's first evaluation (closed, `R_N` 1.2), then lifted
    /// 0.0131, about 1e-3 above the master (within the band `5e-2
    /// sqrt(T)`): it keeps the closed branch, the tensile `-alpha_N g`
    /// along the normal and the penalty tangent (`n . K n = alpha_N`),
    /// reported open with no pressure, and the iterate is not a converged
    /// one. Lifted 0.1 (past the band): nothing. The hold lasts one
    /// iterate (accepted held, the next evaluation holds none), a new
    /// Newton loop's first evaluation holds none, a node open at the
    /// loop's start is not held; the same with friction in a quasi-static
    /// step (mu 0.3, its friction force in the tangent plane: the normal
    /// part is the hold's), none in a dynamic one.
    #[test]
    fn a_node_closed_at_the_last_iterate_and_open_within_the_band_keeps_the_closed_branch() {
        for friction in [false, true] {
            let m = band_pair([1.5, 1.5, -0.01], friction);
            let at = |dz: f64| {
                let mut x = m.mesh.nodes.clone();
                x[9][2] = m.mesh.nodes[9][2] + dz;
                x
            };
            // (the node's coupling, its entry, consistent)
            let eval = |st: &mut SurfacePair, dz: f64| {
                let out = evaluate(&m, 0, &at(dz), st);
                let slaves = st.slaves.clone();
                let fp = st.deformable.as_mut().unwrap();
                let ok = fp.guard_consistent(&slaves, &out);
                let c = fp.couplings.iter().find(|c| c.slave == 9).cloned();
                (c, out.into_iter().find(|c| c.node == 9), ok)
            };
            // (a quasi-static step: frictional nodes are held too)
            let start = |st: &mut SurfacePair| {
                let fp = st.deformable.as_mut().unwrap();
                fp.hold_friction = true;
                fp.guard_start();
                let (c, nc, _) = eval(st, 0.0);
                let nc = nc.unwrap();
                assert!(c.is_some() && nc.status == ContactStatus::Closed, "{nc:?}");
            };
            let accept = |st: &mut SurfacePair| st.deformable.as_mut().unwrap().accept_iterate();
            let mut st = SurfacePair::new(&m, 0);
            let i = st.slave_index(9).unwrap();
            let band = crate::contact::mortar::HOLD_BAND * st.area[i].sqrt();
            assert!(band > 2e-3, "band {band}");
            // a dynamic step: a frictional pair holds nothing
            let mut dynamic = st.clone();
            start(&mut dynamic);
            dynamic.deformable.as_mut().unwrap().hold_friction = false;
            let (c, _, ok) = eval(&mut dynamic, 0.0131);
            assert_eq!(
                c.is_some() && !ok,
                !friction,
                "dynamic, friction {friction}"
            );
            start(&mut st);
            let (c, nc, ok) = eval(&mut st, 0.0131);
            let nc = nc.unwrap();
            assert!(nc.gap > 5e-4 && nc.gap < 1.5e-3, "{nc:?}");
            assert!(nc.status == ContactStatus::Open && nc.pressure == 0.0);
            let c = c.expect("held");
            assert!(!ok, "an iterate with a hold is not converged");
            let fnormal: f64 = (0..3).map(|k| nc.force[k] * nc.normal[k]).sum();
            let ftotal: f64 = nc.force.iter().map(|f| f * f).sum::<f64>().sqrt();
            // K v for v = the normal at node 9: alpha_N (the curvature
            // term `R_N H` is of the order 0.1 x 0.02)
            let nd = 3 * c.nodes.len();
            let p = 3 * c.nodes.iter().position(|&n| n == 9).unwrap();
            let kv: f64 = (0..3)
                .map(|r| {
                    (0..3)
                        .map(|q| c.tangent[(p + r) * nd + p + q] * nc.normal[q])
                        .sum::<f64>()
                        * nc.normal[r]
                })
                .sum();
            println!(
                "held: gap {:.4e}, f.n {fnormal:.4e}, |f| {ftotal:.4e}, n.K n {kv:.4e}",
                nc.gap
            );
            assert!((fnormal + 100.0 * nc.gap).abs() < 1e-12, "{fnormal}");
            assert!(
                friction || (ftotal - fnormal.abs()).abs() < 1e-12,
                "along the normal"
            );
            assert!((kv - 100.0).abs() < 0.1, "{kv}");
            // past the band
            let mut st = SurfacePair::new(&m, 0);
            start(&mut st);
            let (c, _, ok) = eval(&mut st, 0.1);
            assert!(c.is_none() && ok);
            // one iterate only: accepted held, the next holds none
            let mut st = SurfacePair::new(&m, 0);
            start(&mut st);
            assert!(eval(&mut st, 0.0131).0.is_some());
            accept(&mut st);
            assert!(eval(&mut st, 0.0131).0.is_none());
            // accepted closed, the next iterate holds
            accept(&mut st);
            assert!(eval(&mut st, 0.0).0.is_some());
            accept(&mut st);
            assert!(eval(&mut st, 0.0131).0.is_some());
            // a new Newton loop's first evaluation holds none; open at
            // that start, the next iterate holds none either
            st.deformable.as_mut().unwrap().guard_start();
            assert!(eval(&mut st, 0.0131).0.is_none());
            assert!(eval(&mut st, 0.0131).0.is_none());
        }
    }

    /// The friction of a held node (the hold, `mortar::HOLD_BAND`, on a
    /// frictional pair; issue 18, friction on Nagata patches converging
    /// slowly on the ironing benchmark): node 9 over facet 3 of the warped
    /// grid (penalty 100, mu 0.3, k_T 25), faceted and on Nagata patches,
    /// 0.012 deep at a Newton loop's first evaluation (`R_N^acc` about
    /// 1.2), then lifted 1e-3 above the master and moved 0.01 along x:
    /// held, its friction is the law's in the cone of `R_N^acc`, a
    /// constant. Stick point 0.4 behind its foot (slip): `|T| = mu
    /// R_N^acc` exactly; 0.005 behind (stick): the trial force `k_T |s|`,
    /// inside the cone. Both in the tangent plane (`f . n` is the hold's `-alpha_N
    /// g`), the iterate not converged, and the coupling's tangent against
    /// central differences of its forces (the same hold state at every
    /// perturbed position) below 1e-6 of its largest entry, its forces in
    /// balance.
    #[test]
    fn a_held_node_s_friction_takes_the_cone_of_its_last_normal_force_and_its_tangent_is_exact() {
        use super::super::friction_facet::{decode, encode};
        for nagata in [false, true] {
            for want in [FrictionStatus::Slip, FrictionStatus::Stick] {
                let pair = |z: f64| {
                    let mut m = band_pair([1.51, 1.5, z], true);
                    if nagata {
                        m.contacts[0].smoothing = NormalSmoothing::Nagata;
                    }
                    m
                };
                // the held position: 1e-3 above the master at (1.51, 1.5),
                // 0.01 along x from the start's
                let m = pair(0.0);
                let g0 = evaluate(&m, 0, &m.mesh.nodes, &mut SurfacePair::new(&m, 0))
                    .iter()
                    .find(|c| c.node == 9)
                    .map(|c| c.gap / c.normal[2])
                    .unwrap();
                let m = pair(1e-3 - g0);
                let mut x = m.mesh.nodes.clone();
                x[9] = [1.5, 1.5, -0.01];
                let start = |anchor: Option<[f64; 3]>| {
                    let mut st = SurfacePair::new(&m, 0);
                    let i = st.slave_index(9).unwrap();
                    st.friction.committed_anchor[i] = anchor;
                    let fp = st.deformable.as_mut().unwrap();
                    fp.hold_friction = true;
                    fp.guard_start();
                    let out = evaluate(&m, 0, &x, &mut st);
                    (st, out)
                };
                // the held position's foot on facet 3 (no stick point: the
                // first touch's, the foot of a node in front of the master)
                let (mut st, _) = start(None);
                evaluate(&m, 0, &m.mesh.nodes, &mut st);
                let i = st.slave_index(9).unwrap();
                let (k, foot) = decode(st.friction.base[i], 4).unwrap();
                assert_eq!(k, 3);
                // the stick point 0.8 (slip) or 0.01 (stick) of facet 3's
                // half width behind the foot along xi_1 (facet 3 spans [1,
                // 2] x [1, 2])
                let back = if want == FrictionStatus::Slip {
                    0.8
                } else {
                    0.01
                };
                let (st, out) = start(Some(encode(3, [foot[0] - back, foot[1]])));
                let nc = out.iter().find(|c| c.node == 9).unwrap();
                assert_eq!(nc.status, ContactStatus::Closed);
                let rn_acc = nc.pressure * st.area[i];
                assert!(rn_acc > 1.0 && rn_acc < 1.5, "{rn_acc}");
                // the held evaluation
                let mut held = st.clone();
                let out = evaluate(&m, 0, &m.mesh.nodes, &mut held);
                let nc = out.iter().find(|c| c.node == 9).unwrap();
                let slaves = held.slaves.clone();
                let fp = held.deformable.as_mut().unwrap();
                assert!(fp.holds == 1 && !fp.guard_consistent(&slaves, &out));
                // faceted: the slave and facet 3; Nagata: and both patches'
                // rings (the whole grid)
                let c = fp.couplings.iter().find(|c| c.slave == 9).unwrap();
                assert_eq!(c.nodes.len(), if nagata { 10 } else { 5 }, "{:?}", c.nodes);
                assert!(nc.status == ContactStatus::Open && nc.pressure == 0.0);
                assert!(nc.gap > 9e-4 && nc.gap < 1.1e-3, "{nc:?}");
                let fnormal: f64 = (0..3).map(|k| nc.force[k] * nc.normal[k]).sum();
                assert!(
                    (fnormal + 100.0 * nc.gap).abs() < 1e-12,
                    "{fnormal} {}",
                    nc.gap
                );
                let t = nc.friction.traction;
                let tn: f64 = (0..3).map(|k| t[k] * nc.normal[k]).sum();
                assert!(tn.abs() < 1e-12, "{tn}");
                assert_eq!(
                    nc.friction.status, want,
                    "nagata {nagata}: {:?}",
                    nc.friction
                );
                let tf = nc.friction.tangential_force;
                if want == FrictionStatus::Slip {
                    assert!((tf - 0.3 * rn_acc).abs() < 1e-12, "{tf} vs {rn_acc}");
                } else {
                    assert!(tf > 0.05 && tf < 0.3 * rn_acc, "{tf} vs {rn_acc}");
                }
                let e = band_fd(&m, &st, true);
                println!(
                    "held, nagata {nagata}, {want:?}: |T| {tf:.4e}, mu R_N^acc {:.4e}, \
                     fd error {e:.2e}",
                    0.3 * rn_acc
                );
                assert!(e < 1e-6, "nagata {nagata}, {want:?}: {e}");
            }
        }
    }

    /// The cycling guard's friction (issue 18, the ironing slide: nodes
    /// held sticking came out of their cones at every convergence of
    /// `ctc verify ironing_ntf_3d`): node 9 over the middle of facet 3
    /// (penalty 100, mu 0.3, k_T 25, R_N 5, mu R_N 1.5), its committed
    /// stick point there. Cycling closed sticking / open / closed sticking
    /// it is held sticking; moved 0.4 along x at a converged iterate it
    /// slips (trial about 10 > 1.5): not consistent, but still held, with the
    /// law's friction (`held_slip`); the next evaluation gives `|T| = mu
    /// R_N`, consistent. With its stick point 0.4 away it cycles closed
    /// slipping / open and is held with the law's friction from the start.
    #[test]
    fn a_held_node_that_slips_keeps_its_hold_with_the_law_s_friction() {
        use super::super::friction_facet::encode;
        let m = band_pair([1.5, 1.5, -0.05], true);
        let at = |dx: f64, dz: f64| {
            let mut x = m.mesh.nodes.clone();
            x[9] = [1.5 + dx, 1.5, dz];
            x
        };
        let accept = |st: &mut SurfacePair, dx: f64, dz: f64| {
            let out = evaluate(&m, 0, &at(dx, dz), st);
            let slaves = st.slaves.clone();
            let n = st.deformable.as_mut().unwrap().guard_cycle(&slaves, &out);
            (n, out.into_iter().find(|c| c.node == 9))
        };
        let consistent = |st: &mut SurfacePair, dx: f64| {
            let out = evaluate(&m, 0, &at(dx, -0.05), st);
            let slaves = st.slaves.clone();
            let ok = st
                .deformable
                .as_mut()
                .unwrap()
                .guard_consistent(&slaves, &out);
            (ok, out.into_iter().find(|c| c.node == 9).unwrap())
        };
        let mut st = SurfacePair::new(&m, 0);
        let i = st.slave_index(9).unwrap();
        // facet 3 spans [1, 2] x [1, 2]: its centre is xi = (0, 0)
        st.friction.committed_anchor[i] = Some(encode(3, [0.0, 0.0]));
        st.deformable.as_mut().unwrap().guard_start();
        let (_, c) = accept(&mut st, 0.0, -0.05);
        assert_eq!(c.unwrap().friction.status, FrictionStatus::Stick);
        assert_eq!(accept(&mut st, 0.0, 0.05).0, 0);
        assert_eq!(accept(&mut st, 0.0, -0.05).0, 1);
        let fp = st.deformable.as_ref().unwrap();
        assert!(fp.held[i] && !fp.held_slip[i]);
        // moved 0.4: frozen sticking it carries the trial force, outside
        // its cone: friction given back to the law, not consistent yet
        let (ok, c) = consistent(&mut st, 0.4);
        assert!(!ok && c.friction.status == FrictionStatus::Slip);
        assert!(c.friction.tangential_force > 5.0, "{c:?}");
        let fp = st.deformable.as_ref().unwrap();
        assert!(fp.held[i] && fp.held_slip[i]);
        let (ok, c) = consistent(&mut st, 0.4);
        let rn = c.pressure * st.area[i];
        assert!(ok && c.status == ContactStatus::Closed);
        assert!(
            (c.friction.tangential_force - 0.3 * rn).abs() < 1e-12,
            "{} vs {rn}",
            c.friction.tangential_force
        );
        // slipping when the set comes back: held with the law's friction
        let mut st = SurfacePair::new(&m, 0);
        st.friction.committed_anchor[i] = Some(encode(3, [-0.8, 0.0]));
        st.deformable.as_mut().unwrap().guard_start();
        let (_, c) = accept(&mut st, 0.0, -0.05);
        assert_eq!(c.unwrap().friction.status, FrictionStatus::Slip);
        assert_eq!(accept(&mut st, 0.0, 0.05).0, 0);
        assert_eq!(accept(&mut st, 0.0, -0.05).0, 1);
        let fp = st.deformable.as_ref().unwrap();
        assert!(fp.held[i] && fp.held_slip[i]);
        assert!(consistent(&mut st, 0.0).0);
    }

    #[test]
    fn the_band_s_tangent_matches_finite_differences_and_its_forces_balance() {
        // node 9 at x = 2.01 (the middle of the band: w = 0.5, its slope
        // the largest), 0.01 under the warped grid
        let z = 0.02 * (1.3 * 2.0 + 0.7 * 0.5f64).sin();
        let xs = [2.0 + 0.5 * FREE_EDGE_TOL, 0.5, z - 0.01];
        let m = band_pair(xs, false);
        let state = SurfacePair::new(&m, 0);
        let x0 = m.mesh.nodes.clone();
        let mut st = state.clone();
        let out = evaluate(&m, 0, &x0, &mut st);
        let nc = out.iter().find(|c| c.node == 9).unwrap();
        // about half the force alpha_N |g| (the warp moves the foot)
        let f = nc.force.iter().map(|v| v * v).sum::<f64>().sqrt();
        let w = f / (100.0 * nc.gap.abs());
        assert!(nc.gap < 0.0 && w > 0.3 && w < 0.7, "{w} {:?}", nc.force);
        // the reported pressure is the faded force's
        let rn = nc.pressure * st.area[0];
        assert!((rn - nc.force[2]).abs() < 0.01 * nc.force[2], "{rn}");
        let e = band_fd(&m, &state, false);
        // the tolerance of the module's other finite-difference checks
        assert!(e < 1e-6, "frictionless: {e}");
        // friction: stick point on facet 1 near (stick) or far from (slip)
        // the foot
        let m = band_pair(xs, true);
        for (xi_a, want) in [
            ([1.019, 0.0], FrictionStatus::Stick),
            ([0.5, 0.3], FrictionStatus::Slip),
        ] {
            let mut state = SurfacePair::new(&m, 0);
            state.friction.committed_anchor[0] =
                Some(super::super::friction_facet::encode(1, xi_a));
            let mut st = state.clone();
            let out = evaluate(&m, 0, &x0, &mut st);
            let nc = out.iter().find(|c| c.node == 9).unwrap();
            assert_eq!(nc.friction.status, want);
            if want == FrictionStatus::Slip {
                // the cone of the faded normal force
                let rn = nc.pressure * st.area[0];
                assert!(
                    (nc.friction.tangential_force - 0.3 * rn).abs() < 1e-12,
                    "{} vs {rn}",
                    nc.friction.tangential_force
                );
            }
            let e = band_fd(&m, &state, true);
            // the tolerance of the module's other finite-difference checks
            assert!(e < 1e-6, "{want:?}: {e}");
        }
    }

    #[test]
    fn free_edge_extends_only_by_the_tolerance() {
        let faces = [Facet::new(&[0, 1, 2, 3])];
        let x = facet(4, &[0.0; 12]);
        let s = FacetSurface::new(&faces);
        let mut tests = 0;
        assert!(s
            .closest(&x, [1.01, 0.5, -0.01], &[0], None, &[], 1.0, &mut tests)
            .is_some());
        assert!(s
            .closest(&x, [1.05, 0.5, -0.01], &[0], None, &[], 1.0, &mut tests)
            .is_none());
    }

    #[test]
    fn hex_faces_point_outward() {
        // the top face of a unit hex8 in the mesh's face order has normal +z
        let mesh = crate::mesh::Mesh::new(
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
            vec![crate::mesh::Cell::hex([0, 1, 2, 3, 4, 5, 6, 7])],
        );
        for f in mesh.boundary_facets(0..1) {
            let pts: Vec<[f64; 3]> = f.nodes().iter().map(|&n| mesh.nodes[n]).collect();
            let n = centre_normal(&pts);
            let c: [f64; 3] = std::array::from_fn(|k| {
                pts.iter().map(|p| p[k]).sum::<f64>() / pts.len() as f64 - 0.5
            });
            assert!(
                n.iter().zip(&c).map(|(a, b)| a * b).sum::<f64>() > 0.0,
                "{f:?}"
            );
        }
    }

    /// The largest finite-difference errors of `G` and `K` over 2000
    /// seeded random facets and slave positions per feature (printed for
    /// the record: `cargo test -p ctc-engine --lib
    /// contact::node_to_facet::tests::fd_errors -- --nocapture`).
    #[test]
    fn fd_errors_over_seeded_random_elements() {
        let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
        let mut rnd = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for (name, quad, feature) in [
            ("tri3 face", false, Feature::Face),
            ("quad4 face", true, Feature::Face),
            ("tri3 edge", false, Feature::Edge(0, 1)),
            ("quad4 edge", true, Feature::Edge(0, 1)),
            ("quad4 vertex", true, Feature::Vertex(0)),
        ] {
            let n = if quad { 4 } else { 3 };
            let (mut eg, mut ek, mut count) = (0.0f64, 0.0f64, 0);
            for _ in 0..2000 {
                let jitter: Vec<f64> = (0..12).map(|_| rnd()).collect();
                let pts = facet(n, &jitter);
                let (u, v, w) = (0.5 + 0.4 * rnd(), 0.5 + 0.4 * rnd(), 0.3 * rnd());
                let (xs, side) = match feature {
                    Feature::Face if !quad => ([0.45 * u, 0.45 * v, w], 1.0),
                    Feature::Face => ([u, v, w], 1.0),
                    _ => (
                        [u, -0.2 - 0.5 * v.abs(), w],
                        if w < 0.0 { -1.0 } else { 1.0 },
                    ),
                };
                if feature == Feature::Face && foot(xs, &pts).is_none() {
                    continue;
                }
                let (g, k) = check(xs, &pts, feature, side);
                eg = eg.max(g);
                ek = ek.max(k);
                count += 1;
            }
            println!("{name}: {count} elements, max rel. FD error G {eg:.2e}, K {ek:.2e}");
            assert!(
                count > 1500 && eg <= 1e-6 && ek <= 1e-6,
                "{name}: {eg} {ek}"
            );
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        #[test]
        fn face_tangent_matches_finite_differences(
            quad in any::<bool>(),
            jitter in proptest::collection::vec(-1.0f64..1.0, 12),
            s in (0.05f64..0.9, 0.05f64..0.9, -0.3f64..0.3),
        ) {
            let n = if quad { 4 } else { 3 };
            let pts = facet(n, &jitter);
            let (u, v) = if quad { (s.0, s.1) } else { (0.9 * s.0 * (1.0 - s.1), s.1 * 0.9) };
            let xs = [u, v, s.2];
            let Some((xi, _)) = foot(xs, &pts) else { return Ok(()) };
            prop_assume!(xi[0].abs() < 5.0 && xi[1].abs() < 5.0);
            let (eg, ek) = check(xs, &pts, Feature::Face, 1.0);
            prop_assert!(eg <= 1e-6, "G error {eg}");
            prop_assert!(ek <= 1e-6, "K error {ek}");
        }

        #[test]
        fn edge_and_vertex_tangents_match_finite_differences(
            quad in any::<bool>(),
            jitter in proptest::collection::vec(-1.0f64..1.0, 12),
            s in (-0.5f64..1.5, 0.2f64..1.0, 0.2f64..1.0),
            vertex in any::<bool>(),
            side in any::<bool>(),
        ) {
            let n = if quad { 4 } else { 3 };
            let pts = facet(n, &jitter);
            // below the edge (0, 1) at y = 0, or around vertex 0
            let xs = [s.0, -s.1, if side { s.2 } else { -s.2 }];
            let sign = if side { 1.0 } else { -1.0 };
            let feature = if vertex { Feature::Vertex(0) } else { Feature::Edge(0, 1) };
            let (eg, ek) = check(xs, &pts, feature, sign);
            prop_assert!(eg <= 1e-6, "G error {eg}");
            prop_assert!(ek <= 1e-6, "K error {ek}");
        }
    }
}
