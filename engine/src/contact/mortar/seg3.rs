//! Mortar integrals of one quadratic slave segment against one quadratic
//! master segment (2D, seg3 on both sides: the faces of tri6, quad8 and
//! quad9 cells).
//!
//! A seg3 segment `[a, b, m]` (corners `a`, `b`, midside `m`; body on the
//! left of `a -> b`) is the curve `x(xi) = sum_k N_k(xi) x_k`, `xi` in `[0,
//! 1]`, `N = ((1 - xi)(1 - 2 xi), xi (2 xi - 1), 4 xi (1 - xi))`. At a
//! slave point `xi` the tangent is `t = x'(xi) / J` (`J = |x'(xi)|`, `ds =
//! J dxi`) and the outward normal `n = (t_y, -t_x)`.
//!
//! **Segmentation** (curved faces): a master point faces slave point `xi`
//! when it lies on the slave normal line there, `(x_m - x_s(xi)) . t(xi) =
//! 0`. The master ends `c`, `d` land at the slave parameters `xi_c`, `xi_d`
//! solving that equation for `x_m = x_c` (`x_d`) (Newton on `xi`); the
//! master faces the slave when `xi_d < xi_c` (the bodies walk their
//! boundaries in opposite directions) and the **mortar segment** is `[lo,
//! hi] = [max(0, xi_d), min(1, xi_c)]`. At each integration point `xi` of
//! the mortar segment the master parameter `eta` solves `(x_m(eta) -
//! x_s(xi)) . t(xi) = 0` (Newton on `eta` from the affine guess between the
//! ends, where `eta` is 0 at `xi_c` and 1 at `xi_d`: the same equation, so
//! the segmentation and the point pairing agree), and the gap is `g(xi) =
//! n(xi) . (x_m(eta) - x_s(xi))`.
//!
//! **Integrals** over the mortar segment (weight `w`: thickness, or `2 pi
//! r(xi)` on the curved slave in axisymmetry), rows weighted by the
//! multiplier functions `psi_j` ([`Basis`]):
//!
//! `D_jk = int psi_j N_k w ds`, `g~_j = int psi_j g w ds`, and the force
//! coefficients (vectors, the normal varies along a curved slave)
//! `B_jk = -int psi_j N_k n w ds` on the slave nodes, `B_jl = int psi_j
//! N^_l(eta) n w ds` on the master ones: `B_j . dx` is the variation of
//! `g~_j` with the multiplier's integrals and the normal held fixed (the
//! mortar virtual work, as the seg2 rows `-D n`, `M n`).
//!
//! **Dual basis**: `psi_j = sum_k A_jk N_k`, `A = D_e M_e^-1` from the slave
//! segment's mass matrix `M_e = int N N^T w ds` (with the curved segment's
//! `J` and, in axisymmetry, its radius) and `D_e = diag(int N_j w ds)`
//! (Wohlmuth 2000; Popp, Gee & Wall, IJNME 79 (2009) 1354, full-segment
//! variant as the seg2 code). For seg3 the integrals `int N_j w ds` are all
//! positive (`L / 6, L / 6, 2 L / 3` on a straight segment of constant
//! weight; in axisymmetry positive for `r >= 0`), so the plain dual basis
//! exists and `D_jj > 0` (unlike the quad8 face in 3D, whose corner
//! integrals are negative): `int psi_j N_k w ds = delta_jk int N_j w ds`.
//!
//! Quadrature: [`GAUSS`] (5 points) on the mortar segment and on the full
//! segment for `M_e`: exact for straight segments with midside nodes at
//! the middle (integrands of degree <= 6 in `xi`, the master map affine),
//! so a uniform pressure across non-matching flat interfaces is
//! transmitted exactly (the patch test). Every quantity is an [`Ad12`]
//! over the 12 coordinates `[x_a, y_a, x_b, y_b, x_m, y_m, x_c, y_c, x_d,
//! y_d, x_m', y_m']`: the exact derivative, the segmentation and the
//! projections included (one Newton step in dual numbers at the converged
//! parameter: the implicit-function derivative).

use super::ad::Ad;
use super::integrals::{Basis, Weight};
use crate::model::Model;
use std::f64::consts::PI;

/// Dual numbers over the 12 coordinates of a seg3 pair.
pub type Ad12 = Ad<12>;

/// A point or vector in dual numbers.
type V = [Ad12; 2];

/// Nodes per seg3 segment.
pub const NODES: usize = 3;

/// 5-point Gauss rule on `[0, 1]`: (abscissa, weight).
pub const GAUSS: [(f64, f64); 5] = [
    (0.046_910_077_030_668, 0.118_463_442_528_094_5),
    (0.230_765_344_947_158_5, 0.239_314_335_249_683_2),
    (0.5, 0.284_444_444_444_444_4),
    (0.769_234_655_052_841_5, 0.239_314_335_249_683_2),
    (0.953_089_922_969_332, 0.118_463_442_528_094_5),
];

/// Newton iterations allowed for a projection.
const NEWTON: usize = 30;

/// Largest `|xi|` a master end may project to (a master segment up to
/// ~1000 slave segments long still finds the slave's part under it).
const MAX_PARAM: f64 = 1e3;

/// Newton tolerance on a parameter.
const PARAM_TOL: f64 = 1e-14;

/// Smallest projected master length accepted, relative to the master's
/// chord (a master nearly perpendicular to the slave projects on a point).
const MIN_PROJECTED: f64 = 1e-6;

/// The seg3 shape functions at `xi`.
pub fn shape(xi: f64) -> [f64; 3] {
    [
        (1.0 - xi) * (1.0 - 2.0 * xi),
        xi * (2.0 * xi - 1.0),
        4.0 * xi * (1.0 - xi),
    ]
}

fn shape_ad(xi: Ad12) -> [Ad12; 3] {
    let one = Ad12::cst(1.0);
    [
        (one - xi) * (one - xi * 2.0),
        xi * (xi * 2.0 - one),
        xi * (one - xi) * 4.0,
    ]
}

fn dshape_ad(xi: Ad12) -> [Ad12; 3] {
    [xi * 4.0 + (-3.0), xi * 4.0 + (-1.0), -(xi * 8.0) + 4.0]
}

/// Second derivatives of the shape functions (constants).
const DDSHAPE: [f64; 3] = [4.0, 4.0, -8.0];

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot(a: V, b: V) -> Ad12 {
    a[0] * b[0] + a[1] * b[1]
}

fn combine(n: &[Ad12; 3], x: &[V; 3]) -> V {
    std::array::from_fn(|c| n[0] * x[0][c] + n[1] * x[1][c] + n[2] * x[2][c])
}

/// Values only (for the Newton iterations).
fn at(x: &[[f64; 2]; 3], n: [f64; 3]) -> [f64; 2] {
    std::array::from_fn(|c| n[0] * x[0][c] + n[1] * x[1][c] + n[2] * x[2][c])
}

/// The derivatives of the seg3 shape functions at `xi`.
pub fn dshape(xi: f64) -> [f64; 3] {
    [4.0 * xi - 3.0, 4.0 * xi - 1.0, 4.0 - 8.0 * xi]
}

/// The slave parameter `xi` whose normal line passes through `p`:
/// `(p - x(xi)) . x'(xi) = 0`, Newton from `guess`; `None` if it does not
/// converge.
fn project_on_curve(x: &[[f64; 2]; 3], p: [f64; 2], guess: f64) -> Option<f64> {
    let mut xi = guess;
    for _ in 0..NEWTON {
        let q = at(x, shape(xi));
        let d1 = at(x, dshape(xi));
        let d2 = at(x, DDSHAPE);
        let r = [p[0] - q[0], p[1] - q[1]];
        let f = r[0] * d1[0] + r[1] * d1[1];
        let df = -(d1[0] * d1[0] + d1[1] * d1[1]) + r[0] * d2[0] + r[1] * d2[1];
        if df.abs() < 1e-300 || !df.is_finite() {
            return None;
        }
        let step = f / df;
        xi -= step;
        if !xi.is_finite() || xi.abs() > MAX_PARAM {
            return None;
        }
        if step.abs() < PARAM_TOL {
            return Some(xi);
        }
    }
    None
}

/// The master parameter `eta` with `(x_m(eta) - s) . t = 0`, Newton from
/// `guess`.
fn project_along(m: &[[f64; 2]; 3], s: [f64; 2], t: [f64; 2], guess: f64) -> Option<f64> {
    let mut eta = guess;
    for _ in 0..NEWTON {
        let q = at(m, shape(eta));
        let d1 = at(m, dshape(eta));
        let f = (q[0] - s[0]) * t[0] + (q[1] - s[1]) * t[1];
        let df = d1[0] * t[0] + d1[1] * t[1];
        if df.abs() < 1e-300 || !df.is_finite() {
            return None;
        }
        let step = f / df;
        eta -= step;
        if !eta.is_finite() || eta.abs() > 10.0 {
            return None;
        }
        if step.abs() < PARAM_TOL {
            return Some(eta);
        }
    }
    None
}

/// The slave curve at `xi`: point, tangent `x'`, its length `J`, unit
/// normal.
fn slave_frame(xs: &[V; 3], xi: Ad12) -> (V, Ad12, V) {
    let p = combine(&shape_ad(xi), xs);
    let d = combine(&dshape_ad(xi), xs);
    let j = dot(d, d).sqrt();
    let n = [d[1] / j, -(d[0] / j)];
    (p, j, n)
}

/// The slave parameter of master end `p` in dual numbers: the converged
/// `xi0` plus one Newton step evaluated in dual numbers.
fn end_parameter(xs: &[V; 3], p: V, xi0: f64) -> Ad12 {
    let xi = Ad12::cst(xi0);
    let q = combine(&shape_ad(xi), xs);
    let d1 = combine(&dshape_ad(xi), xs);
    let d2: V = std::array::from_fn(|c| {
        xs[0][c] * DDSHAPE[0] + xs[1][c] * DDSHAPE[1] + xs[2][c] * DDSHAPE[2]
    });
    let r = sub(p, q);
    let f = dot(r, d1);
    let df = -dot(d1, d1) + dot(r, d2);
    xi - f / df
}

/// The integration weight at slave point `p`.
fn weight_at(weight: Weight, p: V) -> Ad12 {
    match weight {
        Weight::Thickness(th) => Ad12::cst(th),
        Weight::Axisymmetric => p[0] * (2.0 * PI),
    }
}

/// The coefficients `A` of the dual functions `psi_j = sum_k A_jk N_k` of
/// the slave segment `xs` (module doc); the identity for
/// [`Basis::Standard`]. `None` when the mass matrix is singular (a
/// degenerate segment).
pub fn dual_coefficients(basis: Basis, weight: Weight, xs: &[V; 3]) -> Option<[[Ad12; 3]; 3]> {
    let one = Ad12::cst(1.0);
    let zero = Ad12::cst(0.0);
    if basis == Basis::Standard {
        return Some(std::array::from_fn(|j| {
            std::array::from_fn(|k| if j == k { one } else { zero })
        }));
    }
    let mut me = [[zero; 3]; 3];
    for (s, gw) in GAUSS {
        let xi = Ad12::cst(s);
        let (p, j, _) = slave_frame(xs, xi);
        let w = weight_at(weight, p) * j * gw;
        let n = shape_ad(xi);
        for r in 0..3 {
            for c in 0..3 {
                me[r][c] += n[r] * n[c] * w;
            }
        }
    }
    let de: [Ad12; 3] = std::array::from_fn(|r| me[r][0] + me[r][1] + me[r][2]);
    // the inverse by cofactors (symmetric 3 x 3)
    let cof = |r: usize, c: usize| {
        let (r0, r1) = ((r + 1) % 3, (r + 2) % 3);
        let (c0, c1) = ((c + 1) % 3, (c + 2) % 3);
        me[r0][c0] * me[r1][c1] - me[r0][c1] * me[r1][c0]
    };
    let det = me[0][0] * cof(0, 0) + me[0][1] * cof(0, 1) + me[0][2] * cof(0, 2);
    let scale = de.iter().map(|d| d.v.abs()).fold(0.0, f64::max);
    if !det.v.is_finite() || det.v.abs() <= 1e-12 * scale.powi(3) {
        return None;
    }
    // inv[k][c] = cof(c, k) / det; A_jc = de_j inv[j][c]
    Some(std::array::from_fn(|j| {
        std::array::from_fn(|c| de[j] * cof(c, j) / det)
    }))
}

/// The coefficients `A` of the seg2 dual functions `psi_j = sum_k A_jk
/// N_k` (`N = (1 - xi, xi)`) of a linear slave segment `xs` (its midside
/// slot the middle), in the 3 x 3 layout of [`dual_coefficients`] with row
/// and column 2 zero: `A = D_e M_e^-1` from the 2 x 2 mass matrix with the
/// weight (constant weight: `[[2, -1], [-1, 2]]`); the identity on the
/// corners for [`Basis::Standard`]. `None` for a singular mass matrix.
pub fn dual_coefficients_linear(
    basis: Basis,
    weight: Weight,
    xs: &[V; 3],
) -> Option<[[Ad12; 3]; 3]> {
    let one = Ad12::cst(1.0);
    let zero = Ad12::cst(0.0);
    if basis == Basis::Standard {
        return Some(std::array::from_fn(|j| {
            std::array::from_fn(|k| if j == k && j < 2 { one } else { zero })
        }));
    }
    let mut me = [[zero; 2]; 2];
    for (s, gw) in GAUSS {
        let xi = Ad12::cst(s);
        let (p, j, _) = slave_frame(xs, xi);
        let w = weight_at(weight, p) * j * gw;
        let n = [one - xi, xi];
        for r in 0..2 {
            for c in 0..2 {
                me[r][c] += n[r] * n[c] * w;
            }
        }
    }
    let de = [me[0][0] + me[0][1], me[1][0] + me[1][1]];
    let det = me[0][0] * me[1][1] - me[0][1] * me[1][0];
    let scale = de[0].v.abs().max(de[1].v.abs());
    if !det.v.is_finite() || det.v.abs() <= 1e-12 * scale * scale {
        return None;
    }
    let inv = [
        [me[1][1] / det, -(me[0][1] / det)],
        [-(me[1][0] / det), me[0][0] / det],
    ];
    Some(std::array::from_fn(|j| {
        std::array::from_fn(|c| {
            if j < 2 && c < 2 {
                de[j] * inv[j][c]
            } else {
                zero
            }
        })
    }))
}

/// Mortar integrals of one slave seg3 segment against one master seg3
/// segment (module doc).
#[derive(Debug, Clone, Copy)]
pub struct Seg3Segment {
    /// Mortar segment on the slave, `0 <= lo < hi <= 1`.
    pub lo: f64,
    /// Upper end of the mortar segment.
    pub hi: f64,
    /// `D_jk = int psi_j N_k w ds` (slave `j`, slave `k`).
    pub d: [[Ad12; 3]; 3],
    /// `B_jk` of the slave nodes `k` (`-int psi_j N_k n w ds`) and of the
    /// master nodes (`int psi_j N^_l n w ds`), slots as the variables.
    pub b: [[V; 6]; 3],
    /// Weighted gaps `g~_j = int psi_j g w ds`.
    pub gap: [Ad12; 3],
    /// The smallest and the largest gap at the integration points.
    pub gap_range: [f64; 2],
    /// The integration points (values): where the weighted tangential
    /// slip of mortar friction is measured ([`super::friction_quadratic`]).
    pub points: [Seg3Point; GAUSS.len()],
}

/// One integration point of a seg3 segment pair (values): the slave
/// parameter `xi`, the master parameter `eta` of the point facing it, and
/// per row `j` the weight `psi_j(xi) w J dxi` (the dual weight of the
/// integrals `D_jk`, `g~_j`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Seg3Point {
    /// Slave parameter.
    pub xi: f64,
    /// Master parameter.
    pub eta: f64,
    /// Per row: `psi_j w ds`.
    pub weight: [f64; 3],
}

/// The mortar integrals of slave segment `[x_a, x_b, x_m]` against master
/// segment `[x_c, x_d, x_m']` (`x` in that order), rows weighted by the
/// functions of `basis`; `None` when the master does not face the slave,
/// its projection misses it, or a projection fails.
pub fn segment_pair(x: [[f64; 2]; 6], weight: Weight, basis: Basis) -> Option<Seg3Segment> {
    segment_pair_orders(x, weight, basis, [false, false])
}

/// [`segment_pair`] with either side possibly linear (`linear[0]`: the
/// slave, `linear[1]`: the master; mixed-order pairs, issue 23): a linear
/// side is a seg2 `[a, b]` taken as the seg3 whose midside node is its
/// middle (its slot in `x` is ignored and carries no derivative), so the
/// curve and the projections are the straight segment's, and its own
/// shape functions `(1 - xi, xi, 0)` weigh the integrals; a linear slave's
/// rows are the two corners' (row 2 is zero), weighted by the seg2 dual
/// functions ([`dual_coefficients_linear`]).
pub fn segment_pair_orders(
    x: [[f64; 2]; 6],
    weight: Weight,
    basis: Basis,
    linear: [bool; 2],
) -> Option<Seg3Segment> {
    let mut x = x;
    let mut p: [V; 6] =
        std::array::from_fn(|k| [Ad12::var(x[k][0], 2 * k), Ad12::var(x[k][1], 2 * k + 1)]);
    for (side, &lin) in linear.iter().enumerate() {
        if lin {
            let (a, b, m) = (3 * side, 3 * side + 1, 3 * side + 2);
            p[m] = std::array::from_fn(|c| (p[a][c] + p[b][c]) * 0.5);
            x[m] = std::array::from_fn(|c| 0.5 * (x[a][c] + x[b][c]));
        }
    }
    let values = |lin: bool, xi: Ad12| {
        if lin {
            [Ad12::cst(1.0) - xi, xi, Ad12::cst(0.0)]
        } else {
            shape_ad(xi)
        }
    };
    let xs = [p[0], p[1], p[2]];
    let xm = [p[3], p[4], p[5]];
    let sv = [x[0], x[1], x[2]];
    let mv = [x[3], x[4], x[5]];
    let chord = |a: [f64; 2], b: [f64; 2]| (b[0] - a[0]).hypot(b[1] - a[1]);
    let len = chord(sv[0], sv[1]);
    let len_m = chord(mv[0], mv[1]);
    if !(len > 0.0 && len_m > 0.0) {
        return None;
    }
    // the master ends on the slave: start from the chord's projection
    let guess = |q: [f64; 2]| {
        ((q[0] - sv[0][0]) * (sv[1][0] - sv[0][0]) + (q[1] - sv[0][1]) * (sv[1][1] - sv[0][1]))
            / (len * len)
    };
    // an end whose chord projection lies far beyond the slave only says on
    // which side it is (the mortar segment stops at the slave's end)
    let end = |q: [f64; 2]| {
        let g = guess(q);
        if (-0.5..=1.5).contains(&g) {
            project_on_curve(&sv, q, g)
        } else {
            Some(g)
        }
    };
    let xi_c0 = end(mv[0])?;
    let xi_d0 = end(mv[1])?;
    if (xi_c0 - xi_d0) * len <= MIN_PROJECTED * len_m {
        return None;
    }
    let lo = if xi_d0 > 0.0 {
        end_parameter(&xs, xm[1], xi_d0)
    } else {
        Ad12::cst(0.0)
    };
    let hi = if xi_c0 < 1.0 {
        end_parameter(&xs, xm[0], xi_c0)
    } else {
        Ad12::cst(1.0)
    };
    if hi.v.is_nan() || lo.v.is_nan() || hi.v <= lo.v {
        return None;
    }
    let coef = if linear[0] {
        dual_coefficients_linear(basis, weight, &xs)?
    } else {
        dual_coefficients(basis, weight, &xs)?
    };
    let span = hi - lo;
    let zero = Ad12::cst(0.0);
    let mut d = [[zero; 3]; 3];
    let mut b = [[[zero; 2]; 6]; 3];
    let mut gap = [zero; 3];
    let mut gap_range = [f64::INFINITY, f64::NEG_INFINITY];
    let mut points = [Seg3Point::default(); GAUSS.len()];
    for (q, (s, gw)) in GAUSS.into_iter().enumerate() {
        let xi = lo + span * s;
        let (ps, j, n) = slave_frame(&xs, xi);
        let t = [-n[1], n[0]];
        // the master point on the slave normal line at xi
        let eta_guess = (xi.v - xi_c0) / (xi_d0 - xi_c0);
        let tv = [t[0].v, t[1].v];
        let eta0 = project_along(&mv, [ps[0].v, ps[1].v], tv, eta_guess)?;
        let e0 = Ad12::cst(eta0);
        let qm = combine(&shape_ad(e0), &xm);
        let dm = combine(&dshape_ad(e0), &xm);
        let eta = e0 - dot(sub(qm, ps), t) / dot(dm, t);
        let pm = combine(&shape_ad(eta), &xm);
        let g = dot(sub(pm, ps), n);
        gap_range = [gap_range[0].min(g.v), gap_range[1].max(g.v)];
        let jw = span * j * weight_at(weight, ps) * gw;
        let ns = values(linear[0], xi);
        let nm = values(linear[1], eta);
        points[q].xi = xi.v;
        points[q].eta = eta.v;
        for r in 0..3 {
            let psi = coef[r][0] * ns[0] + coef[r][1] * ns[1] + coef[r][2] * ns[2];
            let pw = psi * jw;
            points[q].weight[r] = pw.v;
            gap[r] += pw * g;
            for k in 0..3 {
                d[r][k] += pw * ns[k];
                for c in 0..2 {
                    b[r][k][c] += -(pw * ns[k] * n[c]);
                    b[r][3 + k][c] += pw * nm[k] * n[c];
                }
            }
        }
    }
    Some(Seg3Segment {
        lo: lo.v,
        hi: hi.v,
        d,
        b,
        gap,
        gap_range,
        points,
    })
}

/// The midside node of every edge of `edges` when body `body` has
/// quadratic cells (`None` for a linear body, or when an edge has no
/// midside node).
pub fn edge_midsides(model: &Model, body: usize, edges: &[[usize; 2]]) -> Option<Vec<usize>> {
    if !crate::contact::face_integrated::body_is_quadratic(model, body) {
        return None;
    }
    let midsides = model.mesh.edge_midsides();
    edges
        .iter()
        .map(|&[a, b]| midsides.get(&(a.min(b), a.max(b))).copied())
        .collect()
}

/// The reference tributary area `int N_j w ds` of each node of `nodes`
/// (sorted) over the seg3 segments `[a, b, m]` of `edges` / `midsides`
/// (reference coordinates, [`GAUSS`]: exact on straight segments); zero
/// for a node on no segment.
pub fn reference_areas(
    model: &Model,
    edges: &[[usize; 2]],
    midsides: &[usize],
    nodes: &[usize],
) -> Vec<f64> {
    let weight = super::weight(model);
    let x = &model.mesh.nodes;
    let mut area = vec![0.0; nodes.len()];
    for (&[a, b], &m) in edges.iter().zip(midsides) {
        let (Some(&pa), Some(&pb), Some(&pm)) = (x.get(a), x.get(b), x.get(m)) else {
            continue;
        };
        let seg = [pa, pb, pm];
        let mut part = [0.0; 3];
        for (s, gw) in GAUSS {
            let n = shape(s);
            let d = at(&seg, dshape(s));
            let w = match weight {
                Weight::Thickness(t) => t,
                Weight::Axisymmetric => 2.0 * PI * at(&seg, n)[0].max(0.0),
            };
            let jw = d[0].hypot(d[1]) * w * gw;
            for (p, nk) in part.iter_mut().zip(n) {
                *p += nk * jw;
            }
        }
        // a corner on the axis integrates to 0 up to round-off: exactly 0
        let total: f64 = part.iter().sum();
        for (node, p) in [a, b, m].into_iter().zip(part) {
            if let Ok(i) = nodes.binary_search(&node) {
                if p > 1e-12 * total {
                    area[i] += p;
                }
            }
        }
    }
    area
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A straight seg3 from `a` to `b` with its midside node at the middle.
    fn straight(a: [f64; 2], b: [f64; 2]) -> [[f64; 2]; 3] {
        [a, b, [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]]
    }

    fn join(s: [[f64; 2]; 3], m: [[f64; 2]; 3]) -> [[f64; 2]; 6] {
        [s[0], s[1], s[2], m[0], m[1], m[2]]
    }

    fn vars(x: &[[f64; 2]; 3]) -> [V; 3] {
        x.map(|p| [Ad12::cst(p[0]), Ad12::cst(p[1])])
    }

    /// The 3-node mass matrix integrals `int N_j w ds` of a straight
    /// segment are positive: the plain dual basis exists.
    #[test]
    fn dual_functions_are_biorthogonal_with_positive_diagonal() {
        for (weight, a, b) in [
            (Weight::Thickness(1.5), [2.0, 0.0], [1.0, 0.0]),
            (Weight::Axisymmetric, [2.0, 0.0], [1.0, 0.0]),
            (Weight::Axisymmetric, [1.0, 0.0], [0.0, 0.0]),
            (Weight::Axisymmetric, [3.0, 0.5], [2.9, 0.1]),
        ] {
            for bulge in [0.0, 0.08] {
                // the midside node moved off the chord along its normal
                let mut s = straight(a, b);
                let len = (b[0] - a[0]).hypot(b[1] - a[1]);
                s[2][0] += bulge * (b[1] - a[1]) / len;
                s[2][1] -= bulge * (b[0] - a[0]) / len;
                let a_ = dual_coefficients(Basis::Dual, weight, &vars(&s)).unwrap();
                // independent 8-point Gauss-Legendre check by sampling
                let rule = gauss_legendre_8();
                let total: f64 = rule
                    .iter()
                    .map(|&(xi, gw)| {
                        let d = at(&s, dshape(xi));
                        let w = match weight {
                            Weight::Thickness(t) => t,
                            Weight::Axisymmetric => 2.0 * PI * at(&s, shape(xi))[0],
                        };
                        w * d[0].hypot(d[1]) * gw
                    })
                    .sum();
                for j in 0..3 {
                    let mut nj = 0.0;
                    for k in 0..3 {
                        let mut bi = 0.0;
                        for &(xi, gw) in &rule {
                            let n = shape(xi);
                            let d = at(&s, dshape(xi));
                            let jac = d[0].hypot(d[1]);
                            let w = match weight {
                                Weight::Thickness(t) => t,
                                Weight::Axisymmetric => 2.0 * PI * at(&s, n)[0],
                            };
                            let psi: f64 = (0..3).map(|c| a_[j][c].v * n[c]).sum();
                            bi += psi * n[k] * w * jac * gw;
                            if k == 0 {
                                nj += n[j] * w * jac * gw;
                            }
                        }
                        let expected = if j == k { nj } else { 0.0 };
                        // curved: the 5-point rule's error on `J` (not polynomial), 3e-5
                        // of the segment's area for a sagitta of 8 % of the chord
                        let tol = if bulge == 0.0 { 1e-13 } else { 1e-4 };
                        assert!(
                            (bi - expected).abs() < tol * total,
                            "{weight:?} bulge {bulge} {j}{k}: {bi} vs {expected}"
                        );
                    }
                    // positive, but 0 at a corner on the axis
                    let on_axis = weight == Weight::Axisymmetric && s[j][0] == 0.0;
                    assert!(
                        nj > 1e-3 * total || (on_axis && nj.abs() < 1e-14 * total),
                        "{weight:?}: int N_{j} = {nj}"
                    );
                }
            }
        }
        // constant weight, straight: D_e M_e^-1 with M_e = L / 30 [[4, -1,
        // 2], [-1, 4, 2], [2, 2, 16]], D_e = L diag(1/6, 1/6, 2/3) (by
        // hand): psi_a = 3/2 N_a + 1/2 N_b - 1/4 N_m, psi_m = 3/2 N_m - N_a - N_b
        let s = straight([1.0, 0.0], [0.0, 0.0]);
        let a = dual_coefficients(Basis::Dual, Weight::Thickness(1.0), &vars(&s)).unwrap();
        let expect = [[1.5, 0.5, -0.25], [0.5, 1.5, -0.25], [-1.0, -1.0, 1.5]];
        for j in 0..3 {
            for k in 0..3 {
                assert!(
                    (a[j][k].v - expect[j][k]).abs() < 1e-12,
                    "{j}{k}: {}",
                    a[j][k].v
                );
            }
        }
    }

    fn gauss_legendre_8() -> Vec<(f64, f64)> {
        let pts = [
            (0.183_434_642_495_649_8, 0.362_683_783_378_362),
            (0.525_532_409_916_329, 0.313_706_645_877_887_3),
            (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
            (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
        ];
        let mut out = Vec::new();
        for (x, w) in pts {
            out.push((0.5 - 0.5 * x, 0.5 * w));
            out.push((0.5 + 0.5 * x, 0.5 * w));
        }
        out
    }

    #[test]
    fn flat_overlap_gives_the_overlap_integrals_and_nodal_gaps() {
        // slave on y = 0 walking -x over [0, 1]; master above at gap 0.1
        // walking +x over [0.2, 0.9]: mortar segment xi in [0.1, 0.8]
        let s = straight([1.0, 0.0], [0.0, 0.0]);
        let m = straight([0.2, 0.1], [0.9, 0.1]);
        let seg = segment_pair(join(s, m), Weight::Thickness(2.0), Basis::Standard).unwrap();
        assert!((seg.lo - 0.1).abs() < 1e-14 && (seg.hi - 0.8).abs() < 1e-14);
        let total: f64 = seg.d.iter().flatten().map(|v| v.v).sum();
        assert!((total - 2.0 * 0.7).abs() < 1e-13);
        for j in 0..3 {
            let dj: f64 = seg.d[j].iter().map(|v| v.v).sum();
            assert!((seg.gap[j].v - 0.1 * dj).abs() < 1e-14);
            // B along +y: slave -D_j, master sum = D_j
            let bs: f64 = (0..3).map(|k| seg.b[j][k][1].v).sum();
            let bm: f64 = (3..6).map(|k| seg.b[j][k][1].v).sum();
            assert!((bs + dj).abs() < 1e-13 && (bm - dj).abs() < 1e-13);
        }
        // covered, dual: D diagonal, nodal gap of a quadratic gap field
        // g = 0.1 + 0.05 x + 0.03 x^2 is its nodal value (the master has
        // that shape exactly: its midside node at the curve)
        let gfun = |x: f64| 0.1 + 0.05 * x + 0.03 * x * x;
        let m = [[-0.5, gfun(-0.5)], [1.5, gfun(1.5)], [0.5, gfun(0.5)]];
        for weight in [Weight::Thickness(1.0), Weight::Axisymmetric] {
            let s = straight([2.0, 0.0], [1.0, 0.0]);
            let m = m.map(|p| [p[0] + 1.0, gfun(p[0] + 1.0)]);
            let seg = segment_pair(join(s, m), weight, Basis::Dual).unwrap();
            for (j, node) in s.iter().enumerate() {
                for k in 0..3 {
                    if j != k {
                        assert!(seg.d[j][k].v.abs() < 1e-13, "{weight:?} D_{j}{k}");
                    }
                }
                let g = seg.gap[j].v / seg.d[j][j].v;
                assert!((g - gfun(node[0])).abs() < 1e-12, "{weight:?} {j}: {g}");
            }
        }
        // a master 25 times longer than a curved slave covers it whole
        let mut curved = s;
        curved[2][1] += 0.05;
        let long = straight([-10.0, 0.1], [15.0, 0.1]);
        let seg = segment_pair(join(curved, long), Weight::Thickness(1.0), Basis::Dual).unwrap();
        assert!(seg.lo == 0.0 && seg.hi == 1.0);
        // a master walking the same way does not face the slave
        let m = straight([0.9, 0.1], [0.2, 0.1]);
        assert!(segment_pair(join(s, m), Weight::Thickness(1.0), Basis::Dual).is_none());
    }

    fn pair_coords() -> impl Strategy<Value = [[f64; 2]; 6]> {
        (
            -0.2f64..0.2,
            0.0f64..std::f64::consts::TAU,
            -0.2f64..0.2,
            0.4f64..1.4,
            -0.2f64..0.2,
            0.5f64..1.5,
            -0.08f64..0.08,
            -0.08f64..0.08,
        )
            .prop_map(|(tilt, rot, g, lm, shift, ls, bs, bm)| {
                let (c, s) = (rot.cos(), rot.sin());
                let r = |p: [f64; 2]| [c * p[0] - s * p[1] + 2.0, s * p[0] + c * p[1]];
                let xa = [ls, 0.0];
                let xb = [0.0, 0.0];
                let sm = [0.5 * ls, bs];
                let mc = [shift, g];
                let md = [shift + lm * tilt.cos(), g + lm * tilt.sin()];
                let mm = [
                    0.5 * (mc[0] + md[0]) - bm * tilt.sin(),
                    0.5 * (mc[1] + md[1]) + bm * tilt.cos(),
                ];
                [r(xa), r(xb), r(sm), r(mc), r(md), r(mm)]
            })
    }

    proptest! {
        #[test]
        fn integrals_match_finite_differences(x in pair_coords(), dual in proptest::bool::ANY) {
            let w = Weight::Axisymmetric;
            let basis = if dual { Basis::Dual } else { Basis::Standard };
            let Some(s) = segment_pair(x, w, basis) else { return Ok(()) };
            prop_assume!(s.lo > 1e-4 || s.lo == 0.0);
            prop_assume!(s.hi < 1.0 - 1e-4 || s.hi == 1.0);
            let h = 1e-6;
            for k in 0..12 {
                let mut xp = x;
                let mut xm = x;
                xp[k / 2][k % 2] += h;
                xm[k / 2][k % 2] -= h;
                let (Some(p), Some(m)) = (segment_pair(xp, w, basis), segment_pair(xm, w, basis)) else {
                    continue;
                };
                prop_assume!((p.lo == 0.0) == (s.lo == 0.0) && (m.lo == 0.0) == (s.lo == 0.0));
                prop_assume!((p.hi == 1.0) == (s.hi == 1.0) && (m.hi == 1.0) == (s.hi == 1.0));
                let close = |fd: f64, ad: f64| (fd - ad).abs() < 1e-5 * (1.0 + fd.abs());
                for j in 0..3 {
                    let fd = (p.gap[j].v - m.gap[j].v) / (2.0 * h);
                    prop_assert!(close(fd, s.gap[j].d[k]), "gap {j} var {k}: {fd} vs {}", s.gap[j].d[k]);
                    for l in 0..3 {
                        let fd = (p.d[j][l].v - m.d[j][l].v) / (2.0 * h);
                        prop_assert!(close(fd, s.d[j][l].d[k]), "D {j}{l} var {k}");
                    }
                    for l in 0..6 {
                        for c in 0..2 {
                            let fd = (p.b[j][l][c].v - m.b[j][l][c].v) / (2.0 * h);
                            prop_assert!(close(fd, s.b[j][l][c].d[k]), "B {j}{l}{c} var {k}: {fd} vs {}", s.b[j][l][c].d[k]);
                        }
                    }
                }
            }
        }
    }
    /// Mixed orders (issue 23): a linear slave on a curved quadratic
    /// master has the seg2 dual rows (`D` diagonal on a covered segment,
    /// row and column 2 zero) and the nodal gap of a linear gap field; a
    /// quadratic slave under a linear master the nodal values of its
    /// linear gap; the linear side's midside slot is ignored.
    #[test]
    fn mixed_orders_give_the_linear_sides_own_rows() {
        for weight in [Weight::Thickness(1.0), Weight::Axisymmetric] {
            // linear slave [2, 1] on y = 0, master curve y = gfun(x) above
            let gfun = |x: f64| 0.1 + 0.05 * x;
            let mut s = straight([2.0, 0.0], [1.0, 0.0]);
            s[2] = [7.0, 3.0]; // ignored
            let m = [[0.5, gfun(0.5)], [2.5, gfun(2.5)], [1.5, gfun(1.5)]];
            let seg = segment_pair_orders(join(s, m), weight, Basis::Dual, [true, false]).unwrap();
            for j in 0..3 {
                for k in 0..3 {
                    if j != k || j == 2 {
                        assert!(seg.d[j][k].v.abs() < 1e-13, "{weight:?} D_{j}{k}");
                    }
                }
                // the ignored slot carries no derivative, row 2 is zero
                assert!(seg.gap[j].d[4] == 0.0 && seg.gap[j].d[5] == 0.0);
                assert!(seg.gap[2].v == 0.0 && seg.gap[2].d.iter().all(|&d| d == 0.0));
            }
            for (j, node) in s.iter().take(2).enumerate() {
                let g = seg.gap[j].v / seg.d[j][j].v;
                assert!((g - gfun(node[0])).abs() < 1e-12, "{weight:?} {j}: {g}");
            }
            // quadratic slave, linear master (its midside slot ignored)
            let s = straight([2.0, 0.0], [1.0, 0.0]);
            let m = [[0.5, gfun(0.5)], [2.5, gfun(2.5)], [-4.0, 9.0]];
            let seg = segment_pair_orders(join(s, m), weight, Basis::Dual, [false, true]).unwrap();
            for (j, node) in s.iter().enumerate() {
                let g = seg.gap[j].v / seg.d[j][j].v;
                assert!((g - gfun(node[0])).abs() < 1e-12, "{weight:?} {j}: {g}");
                assert!(seg.gap[j].d[10] == 0.0 && seg.gap[j].d[11] == 0.0);
                // forces on the master corners only
                assert!(seg.b[j][5].iter().all(|b| b.v == 0.0));
            }
        }
    }

    proptest! {
        #[test]
        fn mixed_order_integrals_match_finite_differences(
            x in pair_coords(),
            slave_linear in proptest::bool::ANY,
            axi in proptest::bool::ANY,
        ) {
            let w = if axi { Weight::Axisymmetric } else { Weight::Thickness(1.0) };
            let linear = [slave_linear, !slave_linear];
            let basis = Basis::Dual;
            let Some(s) = segment_pair_orders(x, w, basis, linear) else { return Ok(()) };
            prop_assume!(s.lo > 1e-4 || s.lo == 0.0);
            prop_assume!(s.hi < 1.0 - 1e-4 || s.hi == 1.0);
            let h = 1e-6;
            for k in 0..12 {
                let mut xp = x;
                let mut xm = x;
                xp[k / 2][k % 2] += h;
                xm[k / 2][k % 2] -= h;
                let (Some(p), Some(m)) = (
                    segment_pair_orders(xp, w, basis, linear),
                    segment_pair_orders(xm, w, basis, linear),
                ) else {
                    continue;
                };
                prop_assume!((p.lo == 0.0) == (s.lo == 0.0) && (m.lo == 0.0) == (s.lo == 0.0));
                prop_assume!((p.hi == 1.0) == (s.hi == 1.0) && (m.hi == 1.0) == (s.hi == 1.0));
                let close = |fd: f64, ad: f64| (fd - ad).abs() < 1e-5 * (1.0 + fd.abs());
                for j in 0..3 {
                    let fd = (p.gap[j].v - m.gap[j].v) / (2.0 * h);
                    prop_assert!(close(fd, s.gap[j].d[k]), "gap {j} var {k}: {fd} vs {}", s.gap[j].d[k]);
                    for l in 0..3 {
                        let fd = (p.d[j][l].v - m.d[j][l].v) / (2.0 * h);
                        prop_assert!(close(fd, s.d[j][l].d[k]), "D {j}{l} var {k}");
                    }
                    for l in 0..6 {
                        for c in 0..2 {
                            let fd = (p.b[j][l][c].v - m.b[j][l][c].v) / (2.0 * h);
                            prop_assert!(close(fd, s.b[j][l][c].d[k]), "B {j}{l}{c} var {k}: {fd} vs {}", s.b[j][l][c].d[k]);
                        }
                    }
                }
            }
        }
    }
}
