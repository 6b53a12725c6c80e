//! Nagata patches on the master facets of node-to-facet contact (3D,
//! `smoothing = nagata`; issue 18).
//!
//! T. Nagata, "Simple local interpolation of surfaces using normal
//! vectors", Computer Aided Geometric Design 22 (2005) 327-347; for
//! contact on quadrilateral Nagata patches: Neto, Oliveira, Menezes,
//! Alves, "Applying Nagata patches to smooth discretized surfaces used in
//! 3D frictional contact problems", CMAME 271 (2014) 296-320.
//!
//! Each master node `a` gets the nodal normal `n_a = m / |m|`, `m = sum_f
//! m_f` over the facets `f` that hold it, `m_f = 1/2 sum x_i x x_(i+1)`
//! the facet's area vector (area-weighted average; exact for warped
//! quadrilaterals). A rim node on a symmetry plane of a half, quarter or
//! octant model (or on two: an octant's pole) has the facets of one side
//! only: `m` is projected off the planes' normals, `m = P sum_f m_f`
//! ([`Ring::mirror`], the rule of [`super::symmetry`]), which is the
//! mirrored whole's nodal normal (the mirror images' area vectors double
//! the in-plane parts and cancel the rest). On each edge `a -> b` (`d = x_b - x_a`) the quadratic
//! curve `x(t) = x_a + (d - c) t + c t^2` is tangent to the planes of
//! `n_a` and `n_b` at its ends: `c` is the smallest vector with `n_a . c =
//! n_a . d`, `n_b . c = -n_b . d` (in the span of the two normals):
//!
//! `c = [(p_a + s p_b) n_a - (p_b + s p_a) n_b] / (1 - s^2)`,
//! `p_a = n_a . d`, `p_b = n_b . d`, `s = n_a . n_b`
//!
//! (Nagata's curvature coefficient; regularized where the normals are
//! nearly parallel, [`TWIST`]). The patch adds the edge corrections to the
//! facet's linear (bilinear) interpolation, no added unknowns:
//!
//! - tri3 (`L_a` the barycentric coordinates `1 - xi - eta, xi, eta`):
//!   `x = sum L_a x_a - c_01 L_0 L_1 - c_12 L_1 L_2 - c_20 L_2 L_0`;
//! - quad4 (`u = (1 + xi) / 2`, `v = (1 + eta) / 2`, nodes at `(0,0),
//!   (1,0), (1,1), (0,1)`): `x = sum N_a x_a - c_01 u (1-u) (1-v) - c_12 u
//!   v (1-v) - c_23 u (1-u) v - c_30 (1-u) v (1-v)`.
//!
//! Both patches hold the edge curves, so neighbouring patches share their
//! edges (continuous surface) and the surface normal is `n_a` at each node
//! (quasi-G1: the tangent planes of two patches agree at the nodes and
//! nearly along the edges).
//!
//! Projection of a slave node `x_s`: the closest point, `r_alpha = (x_s -
//! x(xi)) . a_alpha = 0`, by Newton (`J_ab = -a_a . a_b + (x_s - x) .
//! x_,ab`) from the facet's centre; the gap `g = (x_s - x) . n`, `n = a_1
//! x a_2 / |a_1 x a_2|`. At the foot `x_s - x = g n`, so `g` is stationary
//! in `xi` and `dg/dY = [n, -(dx/dY)^T n]` at fixed `xi` over `Y = [x_s,
//! x_a, n_a]` (the node coordinates and the nodal normals of the patch);
//! those are written out here for any scalar, and carried in dual numbers
//! [`Ad`]`<27>` through one Newton step at the foot (whose derivative is
//! the implicit `dxi/dY`), which gives `d^2 g / dY^2` exactly. The nodal
//! normals depend on the node coordinates of their facets: the chain rule
//! to the coordinates `X` of every node involved (the slave, the patch
//! and the facets around the patch's nodes) adds `J_a^T dg/dn_a` to the
//! gradient and `lambda_a . d^2 n_a / dX^2` (`lambda_a = dg/dn_a`, closed
//! form: `m` is bilinear in `X`) to the Hessian. The force `R_N dg/dX`
//! sums to zero and has zero moment (`g` is invariant under rigid motions
//! of all the nodes); the tangent `-dR_N/dg G G^T - R_N H` is symmetric.

use super::mortar::ad::Ad;
use super::node_to_facet::{cross, dot, newton_step, sub};

/// Variables of the patch element: `x_s`, 4 patch nodes, 4 nodal normals.
pub const NY: usize = 27;

type A = Ad<NY>;

/// Regularization of the tilt part of the curvature coefficient
/// ([`coefficient`]): Nagata's exact coefficient divides by `1 - s^2`, `s
/// = n_a . n_b`; where two nodal normals are nearly parallel (a straight
/// edge of the master, deformed a little) a chord that is not quite square
/// to them gives a coefficient of the edge's own length whose direction
/// turns with round-off: the patch bulged by ~0.1 of the edge under a
/// perturbation of 1e-7 of one node, its normal jumped by 0.026, and the
/// ironing runs stalled at the first touch (measured with a whole-pair
/// finite-difference check). The tilt part `v (u . d) / |v|^2` (`|v| ~`
/// the angle between the normals) becomes `v (u . d) / (|v|^2 +
/// TWIST^2)`: exact to `TWIST^2 / |v|^2` for edges whose normals differ by
/// more than a few degrees, vanishing smoothly for parallel ones. The bend
/// part `u (v . d) / (2 (1 + s))` (the only part on circles, cylinders and
/// spheres: there `u . d = 0`) is unchanged.
pub const TWIST: f64 = 0.05;

/// Newton iterations of the projection before giving up.
const MAX_ITERATIONS: usize = 40;

/// Scalar operations of the patch, for `f64` and [`Ad`].
pub trait Scalar:
    Copy
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::Mul<Output = Self>
    + std::ops::Div<Output = Self>
{
    /// A constant.
    fn of(v: f64) -> Self;
    /// The value.
    fn val(&self) -> f64;
}

impl Scalar for f64 {
    fn of(v: f64) -> Self {
        v
    }
    fn val(&self) -> f64 {
        *self
    }
}

impl<const N: usize> Scalar for Ad<N> {
    fn of(v: f64) -> Self {
        Ad::cst(v)
    }
    fn val(&self) -> f64 {
        self.v
    }
}

type V<T> = [T; 3];

fn vdot<T: Scalar>(a: V<T>, b: V<T>) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn scale<T: Scalar>(a: V<T>, s: T) -> V<T> {
    [a[0] * s, a[1] * s, a[2] * s]
}

fn add<T: Scalar>(a: V<T>, b: V<T>) -> V<T> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn minus<T: Scalar>(a: V<T>, b: V<T>) -> V<T> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Local edges `(a, b)` of a facet of `n` nodes.
pub fn edges(n: usize) -> &'static [(usize, usize)] {
    if n == 3 {
        &[(0, 1), (1, 2), (2, 0)]
    } else {
        &[(0, 1), (1, 2), (2, 3), (3, 0)]
    }
}

/// Nagata's curvature coefficient of edge `d = x_b - x_a` with the nodal
/// normals `na`, `nb`, regularized ([`TWIST`]):
///
/// `c = u (v . d) / (2 (1 + s)) + v (u . d) / (v . v + TWIST^2)`,
/// `u = n_a + n_b`, `v = n_a - n_b`, `s = n_a . n_b`.
///
/// With `TWIST = 0` this is Nagata's exact `c` (the `u` part bends the
/// edge between two normals that turn about it, well conditioned; the `v`
/// part tilts it where the chord is not square to the mean normal).
pub fn coefficient<T: Scalar>(d: V<T>, na: V<T>, nb: V<T>) -> V<T> {
    coefficient_with(d, na, nb, TWIST)
}

/// [`coefficient`] with the regularization `twist` (0: Nagata's exact
/// coefficient, for the tests).
pub fn coefficient_with<T: Scalar>(d: V<T>, na: V<T>, nb: V<T>, twist: f64) -> V<T> {
    let (u, v) = (add(na, nb), minus(na, nb));
    let d1 = T::of(2.0) * (T::of(1.0) + vdot(na, nb));
    let d2 = vdot(v, v) + T::of(twist * twist);
    if d1.val() <= 0.0 || d2.val() <= 0.0 || d1.val().is_nan() || d2.val().is_nan() {
        return [T::of(0.0); 3];
    }
    add(scale(u, vdot(v, d) / d1), scale(v, vdot(u, d) / d2))
}

/// Derivatives of `w . c(d, na, nb)` ([`coefficient`]) with respect to
/// `d`, `na` and `nb` (`w` held fixed).
#[allow(clippy::type_complexity)]
fn coefficient_derivatives<T: Scalar>(d: V<T>, na: V<T>, nb: V<T>, w: V<T>) -> (V<T>, V<T>, V<T>) {
    let z = [T::of(0.0); 3];
    let (u, v) = (add(na, nb), minus(na, nb));
    let d1 = T::of(2.0) * (T::of(1.0) + vdot(na, nb));
    let d2 = vdot(v, v) + T::of(TWIST * TWIST);
    if d1.val() <= 0.0 || d2.val() <= 0.0 || d1.val().is_nan() || d2.val().is_nan() {
        return (z, z, z);
    }
    // w . c = A + B, A = (w.u)(v.d) / d1, B = (w.v)(u.d) / d2
    let (wu, wv, vd, ud) = (vdot(w, u), vdot(w, v), vdot(v, d), vdot(u, d));
    let (ia, ib) = (T::of(1.0) / d1, T::of(1.0) / d2);
    let dd = add(scale(v, wu * ia), scale(u, wv * ib));
    // dA/dna = [w (v.d) + (w.u) d] / d1 - 2 A nb / d1, dA/dnb with -d, na
    let a2 = T::of(2.0) * wu * vd * ia * ia;
    let da_a = minus(scale(add(scale(w, vd), scale(d, wu)), ia), scale(nb, a2));
    let da_b = minus(scale(minus(scale(w, vd), scale(d, wu)), ia), scale(na, a2));
    // dB/dna = [w (u.d) + (w.v) d] / d2 - 2 B v / d2, dB/dnb = [-w (u.d) +
    // (w.v) d] / d2 + 2 B v / d2
    let b2 = T::of(2.0) * wv * ud * ib * ib;
    let db_a = minus(scale(add(scale(w, ud), scale(d, wv)), ib), scale(v, b2));
    let db_b = add(scale(minus(scale(d, wv), scale(w, ud)), ib), scale(v, b2));
    (dd, add(da_a, db_a), add(da_b, db_b))
}

/// Values, first and second parameter derivatives (`[11, 22, 12]`) of the
/// shape functions (slots 0..4) and the edge blends (slots 4..8, in the
/// order of [`edges`]) of a facet of `n` nodes at `xi`.
#[allow(clippy::type_complexity)]
fn basis<T: Scalar>(n: usize, xi: [T; 2]) -> ([T; 8], [[T; 2]; 8], [[T; 3]; 8]) {
    let z = T::of(0.0);
    let one = T::of(1.0);
    let mut v = [z; 8];
    let mut d1 = [[z; 2]; 8];
    let mut d2 = [[z; 3]; 8];
    if n == 3 {
        let l = [one - xi[0] - xi[1], xi[0], xi[1]];
        let dl = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
        for a in 0..3 {
            v[a] = l[a];
            d1[a] = [T::of(dl[a][0]), T::of(dl[a][1])];
        }
        for (e, &(a, b)) in edges(3).iter().enumerate() {
            v[4 + e] = l[a] * l[b];
            d1[4 + e] = [
                l[b] * T::of(dl[a][0]) + l[a] * T::of(dl[b][0]),
                l[b] * T::of(dl[a][1]) + l[a] * T::of(dl[b][1]),
            ];
            d2[4 + e] = [
                T::of(2.0 * dl[a][0] * dl[b][0]),
                T::of(2.0 * dl[a][1] * dl[b][1]),
                T::of(dl[a][0] * dl[b][1] + dl[a][1] * dl[b][0]),
            ];
        }
    } else {
        let half = T::of(0.5);
        let u = (xi[0] + one) * half;
        let w = (xi[1] + one) * half;
        // univariate factors: 0 = 1 - t, 1 = t, 2 = t (1 - t): value,
        // first and second derivative in t
        let f = |k: usize, t: T| -> [T; 3] {
            match k {
                0 => [one - t, T::of(-1.0), z],
                1 => [t, one, z],
                _ => [t * (one - t), one - t - t, T::of(-2.0)],
            }
        };
        // (u factor, v factor) of N_0..N_3 and the blends of edges 01, 12,
        // 23, 30
        const F: [(usize, usize); 8] = [
            (0, 0),
            (1, 0),
            (1, 1),
            (0, 1),
            (2, 0),
            (1, 2),
            (2, 1),
            (0, 2),
        ];
        for (k, &(i, j)) in F.iter().enumerate() {
            let (a, b) = (f(i, u), f(j, w));
            v[k] = a[0] * b[0];
            // d/dxi = 1/2 d/du
            d1[k] = [half * a[1] * b[0], half * a[0] * b[1]];
            let q = T::of(0.25);
            d2[k] = [q * a[2] * b[0], q * a[0] * b[2], q * a[1] * b[1]];
        }
    }
    (v, d1, d2)
}

/// One Nagata patch: the facet's node coordinates and nodal normals.
#[derive(Debug, Clone, Copy)]
pub struct Patch<T> {
    /// Nodes (3 or 4 used).
    pub x: [V<T>; 4],
    /// Nodal normals (unit).
    pub n: [V<T>; 4],
    /// Nodes of the facet (3 or 4).
    pub count: usize,
    /// Curvature coefficients of the edges ([`edges`] order).
    c: [V<T>; 4],
}

/// Point, tangents and second derivatives `[x_11, x_22, x_12]` of a patch.
pub type Surface<T> = (V<T>, [V<T>; 2], [V<T>; 3]);

impl<T: Scalar> Patch<T> {
    /// The patch of nodes `x` with nodal normals `n` (the first `count`).
    pub fn new(x: [V<T>; 4], n: [V<T>; 4], count: usize) -> Self {
        let mut c = [[T::of(0.0); 3]; 4];
        for (e, &(a, b)) in edges(count).iter().enumerate() {
            c[e] = coefficient(minus(x[b], x[a]), n[a], n[b]);
        }
        Patch { x, n, count, c }
    }

    /// The surface at `xi`.
    pub fn at(&self, xi: [T; 2]) -> Surface<T> {
        let (v, d1, d2) = basis(self.count, xi);
        let z = [T::of(0.0); 3];
        let (mut p, mut t, mut s) = (z, [z; 2], [z; 3]);
        let ne = edges(self.count).len();
        for k in 0..4 + ne {
            if k < 4 && k >= self.count {
                continue;
            }
            // nodes add, edge corrections subtract
            let (q, sign) = if k < 4 {
                (self.x[k], T::of(1.0))
            } else {
                (self.c[k - 4], T::of(-1.0))
            };
            for c in 0..3 {
                let qc = q[c] * sign;
                p[c] = p[c] + v[k] * qc;
                t[0][c] = t[0][c] + d1[k][0] * qc;
                t[1][c] = t[1][c] + d1[k][1] * qc;
                for m in 0..3 {
                    s[m][c] = s[m][c] + d2[k][m] * qc;
                }
            }
        }
        (p, t, s)
    }
}

/// Residual and Jacobian of the closest-point equations at `xi`.
pub(crate) fn system<T: Scalar>(xs: V<T>, patch: &Patch<T>, xi: [T; 2]) -> ([T; 2], [[T; 2]; 2]) {
    let (p, t, s) = patch.at(xi);
    let d = minus(xs, p);
    let j12 = vdot(d, s[2]) - vdot(t[0], t[1]);
    (
        [vdot(d, t[0]), vdot(d, t[1])],
        [
            [vdot(d, s[0]) - vdot(t[0], t[0]), j12],
            [j12, vdot(d, s[1]) - vdot(t[1], t[1])],
        ],
    )
}

/// The closest point of `xs` on `patch` by Newton from the facet's centre
/// (or `start`): its parameters, `None` if Newton does not converge.
pub fn project(xs: [f64; 3], patch: &Patch<f64>, start: Option<[f64; 2]>) -> Option<[f64; 2]> {
    let c = if patch.count == 3 { 1.0 / 3.0 } else { 0.0 };
    let mut xi = start.unwrap_or([c, c]);
    let xs_a: [Ad<0>; 3] = xs.map(Ad::cst);
    let lift = |p: &Patch<f64>| -> Patch<Ad<0>> {
        Patch {
            x: p.x.map(|q| q.map(Ad::cst)),
            n: p.n.map(|q| q.map(Ad::cst)),
            count: p.count,
            c: p.c.map(|q| q.map(Ad::cst)),
        }
    };
    let pa = lift(patch);
    for _ in 0..MAX_ITERATIONS {
        let (r, j) = system(xs_a, &pa, xi.map(Ad::cst));
        let step = newton_step(r, j)?;
        // damped: at most half the parametric width per step
        let len = step[0].v.abs().max(step[1].v.abs());
        let f = if len > 0.5 { 0.5 / len } else { 1.0 };
        xi[0] += f * step[0].v;
        xi[1] += f * step[1].v;
        if xi.iter().any(|v| v.is_nan() || v.abs() >= 10.0) {
            return None;
        }
        if len <= 1e-13 {
            return Some(xi);
        }
    }
    None
}

/// A projection on a Nagata patch with its derivatives over `Y = [x_s,
/// x_0..x_3, n_0..n_3]` (unused slots zero).
#[derive(Debug, Clone, Copy)]
pub struct PatchGap {
    /// Parameters of the foot.
    pub xi: [f64; 2],
    /// Signed gap.
    pub gap: f64,
    /// Unit normal of the patch at the foot.
    pub normal: [f64; 3],
    /// `dg/dY`.
    pub gradient: [f64; NY],
    /// `d^2 g/dY^2`.
    pub hessian: [[f64; NY]; NY],
}

/// `-(dx/dY)^T w` at the patch point `x(xi)` (`xi` held), over the
/// patch's node coordinates (slots 0..12) and nodal normals (12..24): the
/// reaction on the patch of a force `w` on the slave at the foot (the
/// normal force with `w = n`, the friction force with `w = t`): `-N_a w`
/// on the nodes, plus the edge corrections' `beta_e d(w . c_e)/dY`.
pub(crate) fn reaction<T: Scalar>(patch: &Patch<T>, xi: [T; 2], w: V<T>) -> [T; 24] {
    let count = patch.count;
    let (v, _, _) = basis(count, xi);
    let z = T::of(0.0);
    let mut g = [z; 24];
    for a in 0..count {
        for c in 0..3 {
            g[3 * a + c] = z - v[a] * w[c];
        }
    }
    for (e, &(a, b)) in edges(count).iter().enumerate() {
        let (dd, da, db) =
            coefficient_derivatives(minus(patch.x[b], patch.x[a]), patch.n[a], patch.n[b], w);
        let we = v[4 + e];
        for c in 0..3 {
            // x = .. - beta_e c_e: -d(x.w)/dY = + beta_e d(w.c_e)/dY
            g[3 * b + c] = g[3 * b + c] + we * dd[c];
            g[3 * a + c] = g[3 * a + c] - we * dd[c];
            g[12 + 3 * a + c] = g[12 + 3 * a + c] + we * da[c];
            g[12 + 3 * b + c] = g[12 + 3 * b + c] + we * db[c];
        }
    }
    g
}

/// The gap of `xs` on the patch of nodes `x` and nodal normals `n` at the
/// solved foot `xi` ([`project`]), with its first and second derivatives
/// over `Y`; `None` for a degenerate patch.
pub fn differentiate(
    xs: [f64; 3],
    x: [[f64; 3]; 4],
    n: [[f64; 3]; 4],
    count: usize,
    xi: [f64; 2],
) -> Option<PatchGap> {
    let var = |p: [f64; 3], k: usize| -> [A; 3] { std::array::from_fn(|c| A::var(p[c], k + c)) };
    let xs_d = var(xs, 0);
    let xd: [[A; 3]; 4] = std::array::from_fn(|a| var(x[a], 3 + 3 * a));
    let nd: [[A; 3]; 4] = std::array::from_fn(|a| var(n[a], 15 + 3 * a));
    let patch = Patch::new(xd, nd, count);
    let (r, j) = system(xs_d, &patch, xi.map(A::cst));
    let step = newton_step(r, j)?;
    let xi_d = [A::cst(xi[0]) + step[0], A::cst(xi[1]) + step[1]];
    let (p, t, _) = patch.at(xi_d);
    let m = cross(t[0], t[1]);
    let len = dot(m, m).sqrt();
    if len.v.is_nan() || len.v <= 0.0 {
        return None;
    }
    let nrm = m.map(|v| v / len);
    let gap = dot(sub(xs_d, p), nrm);
    // dg/dY at fixed xi: n on x_s; -(dx/dY)^T n on the patch
    let z = A::cst(0.0);
    let mut g = [z; NY];
    g[..3].copy_from_slice(&nrm);
    g[3..].copy_from_slice(&reaction(&patch, xi_d, nrm));
    Some(PatchGap {
        xi,
        gap: gap.v,
        normal: nrm.map(|v| v.v),
        gradient: g.map(|v| v.v),
        hessian: g.map(|v| v.d),
    })
}

/// The area vector `1/2 sum x_i x x_(i+1)` of the facet of nodes `f` at
/// coordinates `x`.
pub fn area_vector(f: &[usize], x: &[[f64; 3]]) -> [f64; 3] {
    let mut m = [0.0; 3];
    for (a, &i) in f.iter().enumerate() {
        let (p, q) = (x[i], x[f[(a + 1) % f.len()]]);
        m[0] += 0.5 * (p[1] * q[2] - p[2] * q[1]);
        m[1] += 0.5 * (p[2] * q[0] - p[0] * q[2]);
        m[2] += 0.5 * (p[0] * q[1] - p[1] * q[0]);
    }
    m
}

/// The facets around a master node (their node lists, outward) and the
/// coordinates its nodal normal drops: the normals of the symmetry planes
/// through it ([`super::symmetry`]; none off the rim).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Ring<'a> {
    /// The facets holding the node.
    pub facets: Vec<&'a [usize]>,
    /// `mirror[k]`: the node is on a symmetry plane `x_k = c`.
    pub mirror: [bool; 3],
}

impl<'a> Ring<'a> {
    /// The facets `facets` with no symmetry plane.
    pub fn plain(facets: Vec<&'a [usize]>) -> Self {
        Ring {
            facets,
            mirror: [false; 3],
        }
    }

    /// The sum `m` of the facets' area vectors, and the mask of the
    /// coordinates dropped from it: [`Ring::mirror`], unless that leaves
    /// less than 1e-6 of `|m|` (the facets lie in the plane: kept whole).
    fn sum(&self, x: &[[f64; 3]]) -> ([f64; 3], [bool; 3]) {
        let mut m = [0.0; 3];
        for f in &self.facets {
            let a = area_vector(f, x);
            for c in 0..3 {
                m[c] += a[c];
            }
        }
        let whole = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
        let kept: f64 = (0..3)
            .filter(|&c| !self.mirror[c])
            .map(|c| m[c] * m[c])
            .sum();
        let mask = if kept > 1e-12 * whole {
            self.mirror
        } else {
            [false; 3]
        };
        for c in 0..3 {
            if mask[c] {
                m[c] = 0.0;
            }
        }
        (m, mask)
    }
}

/// The nodal normal of a node whose facets are `ring` (node lists,
/// outward): the unit sum of their area vectors, without the coordinates
/// of its symmetry planes ([`Ring::mirror`]); `None` when they cancel.
pub fn nodal_normal(ring: &Ring<'_>, x: &[[f64; 3]]) -> Option<[f64; 3]> {
    let (m, _) = ring.sum(x);
    let r = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
    (r > 0.0 && r.is_finite()).then(|| m.map(|v| v / r))
}

/// `[v]x`, the matrix of `w -> v x w`.
fn skew(v: [f64; 3]) -> [[f64; 3]; 3] {
    [[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]]
}

/// The nodal normal of a node whose facets are `ring` (`n = m / |m|`, `m`
/// the sum of their area vectors, projected off its symmetry planes: `m =
/// P sum`, `P` constant) differentiated over the local dofs of an element
/// (`at(node)` the local node of a global one, `nn` local nodes): returns
/// `J = dn/dX` (one `[f64; 3]` per local dof) and adds `lambda . d^2 n /
/// dX^2` (closed form: `m` is bilinear in `X`) into `hess` (row-major, `3
/// nn` square).
pub(crate) fn normal_chain(
    ring: &Ring<'_>,
    x: &[[f64; 3]],
    at: &impl Fn(usize) -> usize,
    nn: usize,
    lam: [f64; 3],
    hess: &mut [f64],
) -> Vec<[f64; 3]> {
    let nd = 3 * nn;
    // dm/dx_k = 1/2 sum_f P [x_prev - x_next]x (the rows of P's dropped
    // coordinates zero)
    let mut dm = vec![[[0.0; 3]; 3]; nn];
    let (m, mask) = ring.sum(x);
    for f in &ring.facets {
        for (i, &k) in f.iter().enumerate() {
            let prev = x[f[(i + f.len() - 1) % f.len()]];
            let next = x[f[(i + 1) % f.len()]];
            let s = skew([0, 1, 2].map(|c| 0.5 * (prev[c] - next[c])));
            let l = at(k);
            for r in (0..3).filter(|&r| !mask[r]) {
                for c in 0..3 {
                    dm[l][r][c] += s[r][c];
                }
            }
        }
    }
    let r = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
    let nv = m.map(|v| v / r);
    // dn/dm = (I - n n^T) / r
    let p: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| (f64::from(u8::from(i == j)) - nv[i] * nv[j]) / r)
    });
    // J = P dm, per local node a 3x3 block: column = local dof
    let mut j = vec![[0.0; 3]; nd];
    for l in 0..nn {
        for c in 0..3 {
            for i in 0..3 {
                j[3 * l + c][i] = (0..3).map(|q| p[i][q] * dm[l][q][c]).sum();
            }
        }
    }
    if lam == [0.0; 3] {
        return j;
    }
    let ln = (0..3).map(|c| lam[c] * nv[c]).sum::<f64>();
    // dpsi/dm projected: P mu (the second derivative of P m is P's)
    let mu: [f64; 3] = std::array::from_fn(|c| {
        if mask[c] {
            0.0
        } else {
            (lam[c] - ln * nv[c]) / r
        }
    });
    // d^2 psi / dm^2 = -[lam n^T + n lam^T + (lam.n)(I - 3 n n^T)] / r^2
    let hm: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|k| {
            -(lam[i] * nv[k]
                + nv[i] * lam[k]
                + ln * (f64::from(u8::from(i == k)) - 3.0 * nv[i] * nv[k]))
                / (r * r)
        })
    });
    // dm^T hm dm
    let mut hmd = vec![[0.0; 3]; nd];
    for (col, h) in hmd.iter_mut().enumerate() {
        let (l, c) = (col / 3, col % 3);
        for i in 0..3 {
            h[i] = (0..3).map(|q| hm[i][q] * dm[l][q][c]).sum();
        }
    }
    for row in 0..nd {
        let (l, c) = (row / 3, row % 3);
        for col in 0..nd {
            hess[row * nd + col] += (0..3).map(|i| dm[l][i][c] * hmd[col][i]).sum::<f64>();
        }
    }
    // mu . d^2 m / dX^2: 1/2 sum over facet edges (i, i+1) of
    // -[mu]x on block (i, i+1) and [mu]x on (i+1, i)
    let sk = skew(mu);
    for f in &ring.facets {
        for (i, &k) in f.iter().enumerate() {
            let (li, lj) = (at(k), at(f[(i + 1) % f.len()]));
            for r in 0..3 {
                for c in 0..3 {
                    hess[(3 * li + r) * nd + 3 * lj + c] -= 0.5 * sk[r][c];
                    hess[(3 * lj + r) * nd + 3 * li + c] += 0.5 * sk[r][c];
                }
            }
        }
    }
    j
}

/// A node-to-patch element over global nodes: gap, normal, `G = dg/dX`
/// and `H = d^2 g/dX^2` over `nodes` (local dofs `3 a + c`).
#[derive(Debug, Clone, PartialEq)]
pub struct NagataElement {
    /// Parameters of the foot on the patch.
    pub xi: [f64; 2],
    /// Signed gap (negative: penetration).
    pub gap: f64,
    /// Unit normal of the patch at the foot.
    pub normal: [f64; 3],
    /// Weights of the facet nodes at the foot (shape functions; the patch
    /// point is not their combination, the corrections aside).
    pub weights: [f64; 4],
    /// Global nodes: the slave first, then the others sorted.
    pub nodes: Vec<usize>,
    /// `dg/dX`, `3 nodes.len()`.
    pub gradient: Vec<f64>,
    /// `d^2 g/dX^2`, row-major, symmetric.
    pub hessian: Vec<f64>,
}

/// The global nodes of an element over slave node `slave` and the nodes
/// `others` (any order, repeats allowed): the slave first, then the
/// others sorted, each once. [`local_index`] gives a node's place.
pub(crate) fn element_nodes(slave: usize, others: impl Iterator<Item = usize>) -> Vec<usize> {
    let mut rest: Vec<usize> = others.filter(|&n| n != slave).collect();
    rest.sort_unstable();
    rest.dedup();
    let mut nodes = Vec::with_capacity(1 + rest.len());
    nodes.push(slave);
    nodes.extend(rest);
    nodes
}

/// The place of `node` in `nodes` of [`element_nodes`] (0 for the slave;
/// every node the callers ask for is in the list).
pub(crate) fn local_index(nodes: &[usize], node: usize) -> usize {
    if node == nodes[0] {
        0
    } else {
        1 + nodes[1..].binary_search(&node).unwrap_or(0)
    }
}

/// The element of slave node `slave` at `xs` on the patch of facet
/// `facet` (its global nodes), `rings[a]` the facets (global node lists)
/// around facet node `a` and its symmetry planes, at coordinates `x`, with
/// the foot `xi` (from [`project`] on [`patch_of`]). `None` for a
/// degenerate patch.
pub fn element(
    slave: usize,
    xs: [f64; 3],
    facet: &[usize],
    rings: &[Ring<'_>],
    x: &[[f64; 3]],
    xi: [f64; 2],
) -> Option<NagataElement> {
    let count = facet.len();
    let (xp, np) = patch_data(facet, rings, x)?;
    let pg = differentiate(xs, xp, np, count, xi)?;
    // global nodes: slave, then every node of the rings (the facet's own
    // nodes are in them)
    let nodes = element_nodes(
        slave,
        rings
            .iter()
            .flat_map(|r| r.facets.iter())
            .flat_map(|f| f.iter().copied())
            .chain(facet.iter().copied()),
    );
    let nn = nodes.len();
    let nd = 3 * nn;
    let at = |node: usize| local_index(&nodes, node);
    // Y index -> (local node, component) for the coordinates; normal slots
    // go through the chain rule
    let ymap: Vec<Option<usize>> = (0..15)
        .map(|k| match k / 3 {
            0 => Some(k % 3),
            a if a - 1 < count => Some(3 * at(facet[a - 1]) + k % 3),
            _ => None,
        })
        .collect();
    // J_a = dn_a/dX (3 x nd) per patch node, and the pieces of the second
    // derivative of lambda . n_a
    let mut jac: Vec<Vec<[f64; 3]>> = Vec::with_capacity(count);
    let mut grad = vec![0.0; nd];
    let mut hess = vec![0.0; nd * nd];
    for (a, ring) in rings.iter().enumerate().take(count) {
        // lambda = dg/dn_a; lambda . d^2 n / dX^2 into H, J_a = dn_a/dX
        let lam: [f64; 3] = std::array::from_fn(|c| pg.gradient[15 + 3 * a + c]);
        let j = normal_chain(ring, x, &at, nn, lam, &mut hess);
        for (col, jc) in j.iter().enumerate() {
            grad[col] += (0..3).map(|i| lam[i] * jc[i]).sum::<f64>();
        }
        jac.push(j);
    }
    // P^T dg/dY: coordinates directly, normals through J_a
    for (k, slot) in ymap.iter().enumerate() {
        if let Some(s) = slot {
            grad[*s] += pg.gradient[k];
        }
    }
    // P^T H_Y P: the 27 Y variables as columns of P (nd x 27)
    let mut pm = vec![[0.0; NY]; nd];
    for (k, slot) in ymap.iter().enumerate() {
        if let Some(s) = slot {
            pm[*s][k] = 1.0;
        }
    }
    for (a, j) in jac.iter().enumerate() {
        for (col, jc) in j.iter().enumerate() {
            for i in 0..3 {
                pm[col][15 + 3 * a + i] += jc[i];
            }
        }
    }
    // H_Y P (27 x nd), then P^T (H_Y P)
    let used: Vec<usize> = (0..NY)
        .filter(|&k| k < 3 + 3 * count || (15..15 + 3 * count).contains(&k))
        .collect();
    let mut hp = vec![[0.0; NY]; nd];
    for (col, pc) in pm.iter().enumerate() {
        for &r in &used {
            hp[col][r] = used.iter().map(|&k| pg.hessian[r][k] * pc[k]).sum();
        }
    }
    for row in 0..nd {
        for col in 0..nd {
            hess[row * nd + col] += used.iter().map(|&k| pm[row][k] * hp[col][k]).sum::<f64>();
        }
    }
    let (v, _, _) = basis(count, xi);
    let mut weights = [0.0; 4];
    weights[..count].copy_from_slice(&v[..count]);
    Some(NagataElement {
        xi: pg.xi,
        gap: pg.gap,
        normal: pg.normal,
        weights,
        nodes,
        gradient: grad,
        hessian: hess,
    })
}

/// The node coordinates and nodal normals of the patch of `facet`.
#[allow(clippy::type_complexity)]
pub(crate) fn patch_data(
    facet: &[usize],
    rings: &[Ring<'_>],
    x: &[[f64; 3]],
) -> Option<([[f64; 3]; 4], [[f64; 3]; 4])> {
    let mut xp = [[0.0; 3]; 4];
    let mut np = [[0.0; 3]; 4];
    for (a, &k) in facet.iter().enumerate() {
        xp[a] = x[k];
        np[a] = nodal_normal(rings.get(a)?, x)?;
    }
    Some((xp, np))
}

/// The Nagata patch of `facet` with the nodal normals from `rings`.
pub fn patch_of(facet: &[usize], rings: &[Ring<'_>], x: &[[f64; 3]]) -> Option<Patch<f64>> {
    let (xp, np) = patch_data(facet, rings, x)?;
    Some(Patch::new(xp, np, facet.len()))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A curved surface: a grid of `(n + 1)^2` nodes on the sphere of
    /// radius 2 about `(0, 0, -2)` near its pole, quads (or each split in
    /// two triangles), outward (+z at the pole); nodes moved by `jitter`.
    pub(crate) fn dome(
        n: usize,
        tri: bool,
        jitter: f64,
        seed: &mut u64,
    ) -> (Vec<[f64; 3]>, Vec<Vec<usize>>) {
        let mut rnd = || {
            *seed ^= *seed << 13;
            *seed ^= *seed >> 7;
            *seed ^= *seed << 17;
            (*seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut x = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                let (u, v) = (
                    i as f64 / n as f64 - 0.5 + jitter * rnd(),
                    j as f64 / n as f64 - 0.5 + jitter * rnd(),
                );
                let z = (4.0 - u * u - v * v).sqrt() - 2.0;
                x.push([u, v, z + jitter * rnd()]);
            }
        }
        let id = |i: usize, j: usize| i + (n + 1) * j;
        let mut f = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
                if tri {
                    f.push(vec![q[0], q[1], q[2]]);
                    f.push(vec![q[0], q[2], q[3]]);
                } else {
                    f.push(q.to_vec());
                }
            }
        }
        (x, f)
    }

    pub(crate) fn rings<'a>(faces: &'a [Vec<usize>], facet: &[usize]) -> Vec<Ring<'a>> {
        facet
            .iter()
            .map(|&k| {
                Ring::plain(
                    faces
                        .iter()
                        .filter(|f| f.contains(&k))
                        .map(|f| f.as_slice())
                        .collect(),
                )
            })
            .collect()
    }

    #[test]
    fn flat_facets_give_the_faceted_gap_and_a_sphere_is_followed() {
        // flat: every nodal normal +z, every c = 0: the bilinear facet
        let mut seed = 7u64;
        let (mut x, faces) = dome(2, false, 0.0, &mut seed);
        for p in &mut x {
            p[2] = 0.0;
        }
        let f = &faces[0];
        let r = rings(&faces, f);
        let patch = patch_of(f, &r, &x).unwrap();
        let xs = [-0.3, -0.2, 0.1];
        let xi = project(xs, &patch, None).unwrap();
        let mut y = x.clone();
        y.push(xs);
        let e = element(y.len() - 1, xs, f, &r, &y, xi).unwrap();
        assert!((e.gap - 0.1).abs() < 1e-14 && (e.normal[2] - 1.0).abs() < 1e-14);
        // on the dome the patch points lie far closer to the sphere than the
        // facet's: at the centre of a facet of a 4 x 4 grid
        let (x, faces) = dome(4, false, 0.0, &mut seed);
        let f = &faces[5];
        let r = rings(&faces, f);
        let patch = patch_of(f, &r, &x).unwrap();
        let (p, _, _) = patch.at([0.0, 0.0]);
        let flat: [f64; 3] = std::array::from_fn(|c| f.iter().map(|&k| x[k][c]).sum::<f64>() / 4.0);
        let radius = |q: [f64; 3]| (q[0] * q[0] + q[1] * q[1] + (q[2] + 2.0).powi(2)).sqrt() - 2.0;
        assert!(
            radius(p).abs() < 0.05 * radius(flat).abs(),
            "{} {}",
            radius(p),
            radius(flat)
        );
    }

    /// A quarter of the dome (the facets in `u >= 0`, `v >= 0`: a quarter
    /// model cut by the planes `x = 0`, `y = 0`): a node on `x = 0` with
    /// `x` dropped has the whole dome's nodal normal (the mirrored facets'
    /// area vectors only double its `y`, `z` parts), the pole with `x` and
    /// `y` dropped the axis; without, they tilt by about half a facet
    /// angle and a whole one.
    #[test]
    fn a_node_on_a_symmetry_plane_gets_the_whole_models_normal() {
        let mut seed = 3u64;
        let (x, faces) = dome(4, false, 0.0, &mut seed);
        let id = |i: usize, j: usize| i + 5 * j;
        let quarter: Vec<Vec<usize>> = faces
            .iter()
            .filter(|f| f.iter().all(|&k| x[k][0] >= -1e-12 && x[k][1] >= -1e-12))
            .cloned()
            .collect();
        assert_eq!(quarter.len(), 4);
        fn ring(fs: &[Vec<usize>], k: usize) -> Ring<'_> {
            Ring::plain(
                fs.iter()
                    .filter(|f| f.contains(&k))
                    .map(|f| f.as_slice())
                    .collect(),
            )
        }
        let (edge, pole) = (id(2, 3), id(2, 2));
        let whole = nodal_normal(&ring(&faces, edge), &x).unwrap();
        let half = nodal_normal(&ring(&quarter, edge), &x).unwrap();
        let mut mirrored = ring(&quarter, edge);
        mirrored.mirror = [true, false, false];
        let m = nodal_normal(&mirrored, &x).unwrap();
        let angle = |a: [f64; 3], b: [f64; 3]| vdot(a, b).min(1.0).acos();
        assert!(
            (0..3).all(|c| (m[c] - whole[c]).abs() < 1e-15),
            "{m:?} {whole:?}"
        );
        // half the facet angle along x (0.25 / 2 rad) about; the pole:
        // the facet centre, (0.125, 0.125) / 2 rad
        assert!(angle(half, whole) > 0.03, "{}", angle(half, whole));
        let mut p = ring(&quarter, pole);
        assert!(angle(nodal_normal(&p, &x).unwrap(), [0.0, 0.0, 1.0]) > 0.08);
        p.mirror = [true, true, false];
        assert_eq!(nodal_normal(&p, &x).unwrap(), [0.0, 0.0, 1.0]);
        assert_eq!(
            nodal_normal(&ring(&faces, pole), &x).unwrap(),
            [0.0, 0.0, 1.0]
        );
    }

    /// Largest relative FD errors of `G` and `H` of elements on random
    /// jittered domes (tri3 and quad4), random slave positions; with
    /// `mirror`, the facet's first node on a plane `x = c` and its second
    /// on `x = c` and `y = c` (an octant's pole: the normal along z).
    fn fd_errors(tri: bool, mirror: bool, count: usize, seed: &mut u64) -> (f64, f64, usize) {
        let (mut eg, mut eh, mut done) = (0.0f64, 0.0f64, 0);
        for t in 0..count {
            let (mut x, faces) = dome(3, tri, 0.05, seed);
            let k = if tri { 8 + t % 2 } else { 4 };
            let f = faces[k].clone();
            let mut r = rings(&faces, &f);
            if mirror {
                r[0].mirror = [true, false, false];
                r[1].mirror = [true, true, false];
            }
            let c: [f64; 3] =
                std::array::from_fn(|q| f.iter().map(|&n| x[n][q]).sum::<f64>() / f.len() as f64);
            let h = [0.37, -0.61, 0.29][t % 3] * 0.1;
            let s = x.len();
            x.push([
                c[0] + 0.05 * (t as f64 * 0.7).sin(),
                c[1] + 0.04 * (t as f64).cos(),
                c[2] + h,
            ]);
            let g = |y: &[[f64; 3]]| -> Option<NagataElement> {
                let p = patch_of(&f, &r, y)?;
                let xi = project(y[s], &p, None)?;
                element(s, y[s], &f, &r, y, xi)
            };
            let Some(e) = g(&x) else { continue };
            let nd = e.gradient.len();
            let gmax = e.gradient.iter().fold(1e-12, |m: f64, v| m.max(v.abs()));
            let hmax = e.hessian.iter().fold(1e-12, |m: f64, v| m.max(v.abs()));
            let step = 1e-6;
            let mut ok = true;
            for col in 0..nd {
                let (node, comp) = (e.nodes[col / 3], col % 3);
                let mut xp = x.clone();
                let mut xm = x.clone();
                xp[node][comp] += step;
                xm[node][comp] -= step;
                let (Some(ep), Some(em)) = (g(&xp), g(&xm)) else {
                    ok = false;
                    break;
                };
                if ep.nodes != e.nodes {
                    ok = false;
                    break;
                }
                let fd = (ep.gap - em.gap) / (2.0 * step);
                eg = eg.max((fd - e.gradient[col]).abs() / gmax);
                for row in 0..nd {
                    let fd = (ep.gradient[row] - em.gradient[row]) / (2.0 * step);
                    eh = eh.max((fd - e.hessian[row * nd + col]).abs() / hmax);
                }
            }
            if !ok {
                continue;
            }
            // symmetric H, balanced forces and moments
            for row in 0..nd {
                for col in 0..nd {
                    assert!(
                        (e.hessian[row * nd + col] - e.hessian[col * nd + row]).abs()
                            <= 1e-9 * hmax,
                        "H not symmetric"
                    );
                }
            }
            let mut sum = [0.0; 3];
            let mut mom = [0.0; 3];
            for (a, &n) in e.nodes.iter().enumerate() {
                let q = [
                    e.gradient[3 * a],
                    e.gradient[3 * a + 1],
                    e.gradient[3 * a + 2],
                ];
                let p = x[n];
                for c in 0..3 {
                    sum[c] += q[c];
                }
                mom[0] += p[1] * q[2] - p[2] * q[1];
                mom[1] += p[2] * q[0] - p[0] * q[2];
                mom[2] += p[0] * q[1] - p[1] * q[0];
            }
            // the planes are fixed in space: no rotation invariance there
            for c in 0..3 {
                assert!(
                    sum[c].abs() < 1e-12 && (mirror || mom[c].abs() < 1e-11),
                    "{sum:?} {mom:?}"
                );
            }
            done += 1;
        }
        (eg, eh, done)
    }

    /// `G = dg/dX` and `H = d^2 g/dX^2` (nodal normals' dependence on the
    /// ring nodes included) against central differences (printed:
    /// `cargo test -p ctc-engine --lib contact::nagata -- --nocapture`).
    #[test]
    fn gradient_and_hessian_match_finite_differences() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        for (tri, mirror) in [(false, false), (true, false), (false, true), (true, true)] {
            let (eg, eh, done) = fd_errors(tri, mirror, 12, &mut seed);
            println!(
                "nagata {}{}: {done} elements, max rel. FD error G {eg:.2e}, H {eh:.2e}",
                if tri { "tri3" } else { "quad4" },
                if mirror { " on symmetry planes" } else { "" }
            );
            assert!(
                done >= 8 && eg < 1e-7 && eh < 1e-6,
                "{tri} {mirror}: {done} {eg} {eh}"
            );
        }
    }

    #[test]
    fn coefficient_makes_the_edge_curve_tangent_to_the_nodal_planes() {
        let na = [0.3f64, 0.1, 1.0];
        let nb = [-0.2f64, 0.3, 1.0];
        let u = |v: [f64; 3]| {
            let l = vdot(v, v).sqrt();
            v.map(|c| c / l)
        };
        let (na, nb) = (u(na), u(nb));
        let d = [1.0, 0.2, -0.1];
        let c = coefficient_with(d, na, nb, 0.0);
        // tangents d - c at t = 0 and d + c at t = 1
        assert!(vdot(minus(d, c), na).abs() < 1e-14);
        assert!(vdot(add(d, c), nb).abs() < 1e-14);
        // the regularized coefficient is close for normals this far apart
        let r = coefficient(d, na, nb);
        let l = vdot(c, c).sqrt();
        assert!(
            vdot(minus(r, c), minus(r, c)).sqrt() < 0.05 * l,
            "{r:?} {c:?}"
        );
        // on an arc (u . d = 0) it is exact
        let (t0, t1) = (0.3f64, 0.45f64);
        let na = [t0.cos(), t0.sin(), 0.0];
        let nb = [t1.cos(), t1.sin(), 0.0];
        let d = [
            3.0 * (t1.cos() - t0.cos()),
            3.0 * (t1.sin() - t0.sin()),
            0.0,
        ];
        let (c, r) = (coefficient_with(d, na, nb, 0.0), coefficient(d, na, nb));
        assert!((0..3).all(|k| (c[k] - r[k]).abs() < 1e-15), "{r:?} {c:?}");
    }

    #[test]
    fn nearly_parallel_normals_give_a_small_continuous_coefficient() {
        // a straight edge along z whose end normals differ by 1e-4 rad, the
        // chord tilted by 1e-5 against them: Nagata's exact coefficient
        // is of the edge's length and turns with the perturbation; the
        // regularized one is tiny and moves by the perturbation's order
        let d = [0.0, 0.0, 1.04];
        let unit = |v: [f64; 3]| {
            let l = vdot(v, v).sqrt();
            v.map(|c| c / l)
        };
        let na = unit([0.0, -1.0, 1e-5]);
        for (dx, tilt) in [(1e-4, 1e-5), (1e-4 + 1e-7, 1e-5), (-1e-4, 1e-5)] {
            let nb = unit([dx, -1.0, tilt]);
            let exact = coefficient_with(d, na, nb, 0.0);
            let c = coefficient(d, na, nb);
            let norm = |v: [f64; 3]| vdot(v, v).sqrt();
            assert!(norm(exact) > 0.05, "{exact:?}");
            assert!(norm(c) < 1e-5, "{c:?}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        /// The whole penalty element on a patch (force `R G`, `R = -k g`,
        /// tangent `k G G^T + k g H` over the slave, the patch and the
        /// nodes around it) against central differences of the force, on
        /// a dome (tri3 or quad4) whose nodes are all moved at random, with
        /// the slave at a random place above or below the patch; plus force
        /// and moment balance.
        #[test]
        fn penalty_element_matches_finite_differences(
            tri in any::<bool>(),
            moves in proptest::collection::vec(-1.0f64..1.0, 48),
            slave in (-0.4f64..0.4, -0.4f64..0.4, -0.06f64..0.06),
        ) {
            let mut seed = 11u64;
            let (mut x, faces) = dome(3, tri, 0.0, &mut seed);
            for (p, m) in x.iter_mut().zip(moves.chunks(3)) {
                for c in 0..3 {
                    p[c] += 0.03 * m[c];
                }
            }
            let f = faces[if tri { 8 } else { 4 }].clone();
            let r = rings(&faces, &f);
            let centre: [f64; 3] =
                std::array::from_fn(|q| f.iter().map(|&n| x[n][q]).sum::<f64>() / f.len() as f64);
            let h0 = 1.0 / 3.0;
            let s = x.len();
            x.push([
                centre[0] + slave.0 * h0,
                centre[1] + slave.1 * h0,
                centre[2] + slave.2,
            ]);
            let at = |y: &[[f64; 3]]| -> Option<NagataElement> {
                let p = patch_of(&f, &r, y)?;
                let xi = project(y[s], &p, None)?;
                element(s, y[s], &f, &r, y, xi)
            };
            let Some(e) = at(&x) else { return Ok(()) };
            // the foot on the patch (inside or just past an edge)
            prop_assume!(crate::contact::node_to_facet::edge_excess(f.len(), e.xi).iter().all(|&v| v < 0.2));
            let k = 7.0;
            let force = |e: &NagataElement| -> Vec<f64> {
                e.gradient.iter().map(|gv| -k * e.gap * gv).collect()
            };
            let nd = e.gradient.len();
            let kt: Vec<f64> = (0..nd * nd)
                .map(|i| k * e.gradient[i / nd] * e.gradient[i % nd] + k * e.gap * e.hessian[i])
                .collect();
            let kmax = kt.iter().fold(1e-12, |m: f64, v| m.max(v.abs()));
            let step = 1e-6;
            let mut worst = 0.0f64;
            for col in 0..nd {
                let (node, comp) = (e.nodes[col / 3], col % 3);
                let mut xp = x.clone();
                let mut xm = x.clone();
                xp[node][comp] += step;
                xm[node][comp] -= step;
                let (Some(ep), Some(em)) = (at(&xp), at(&xm)) else {
                    return Ok(());
                };
                prop_assume!(ep.nodes == e.nodes && em.nodes == e.nodes);
                let (fp, fm) = (force(&ep), force(&em));
                for row in 0..nd {
                    let fd = -(fp[row] - fm[row]) / (2.0 * step);
                    worst = worst.max((fd - kt[row * nd + col]).abs() / kmax);
                }
            }
            prop_assert!(worst < 1e-6, "tangent vs FD {worst:e}");
            // balance of the forces and their moments
            let f0 = force(&e);
            let fmax = f0.iter().fold(1e-12, |m: f64, v| m.max(v.abs()));
            let (mut sum, mut mom) = ([0.0; 3], [0.0; 3]);
            for (a, &n) in e.nodes.iter().enumerate() {
                let (q, p) = ([f0[3 * a], f0[3 * a + 1], f0[3 * a + 2]], x[n]);
                for c in 0..3 {
                    sum[c] += q[c];
                }
                mom[0] += p[1] * q[2] - p[2] * q[1];
                mom[1] += p[2] * q[0] - p[0] * q[2];
                mom[2] += p[0] * q[1] - p[1] * q[0];
            }
            for c in 0..3 {
                prop_assert!(sum[c].abs() < 1e-11 * fmax && mom[c].abs() < 1e-10 * fmax);
            }
        }
    }
}
