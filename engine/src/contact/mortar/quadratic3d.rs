//! Mortar integrals of one quadratic slave face against one quadratic
//! master face (3D: tri6, quad8, quad9 on both sides; issues 23 and 18).
//!
//! Method of Puso, Laursen & Solberg, "A segment-to-segment mortar contact
//! method for quadratic elements and large deformations", CMAME 197 (2008)
//! 555: the curved faces are split into flat sub-triangles for the
//! segmentation only, and the mortar integrals use the quadratic shape
//! functions at points mapped back to the curved faces.
//!
//! Segmentation: each face is cut into triangles through its nodes in the
//! parent domain (tri6: 4 triangles through the midside nodes; quad8 /
//! quad9: 8 triangles, the 4 quadrants through the midside nodes and the
//! centre `x(0, 0)` (a quad9's centre node), each halved). Per slave
//! sub-triangle its plane (centre, unit normal `n_S`, basis `t_1`, `t_2`);
//! every master sub-triangle facing it is projected on that plane and
//! clipped by it (Sutherland-Hodgman, [`super::facets`]), the (convex) clip
//! polygon cut into a fan of triangles from its first vertex, Dunavant's
//! 6-point degree-4 rule on each. A point `p` of the plane lies in the projected slave
//! sub-triangle at barycentric `lambda`: its slave parameters are `xi =
//! sum lambda_i xi_i` (the sub-triangle's corners in the parent domain: the
//! sub-triangles partition the parent domain exactly, so the integrals are
//! over the whole curved slave face), its measure `dA = |a_1 x a_2|(xi)
//! |dxi / dp| dA_p`. The master point is where the slave normal line at
//! `x_s(xi)` meets the curved master face (Newton on the master parameters
//! `eta`: `(x_m(eta) - x_s) . a_k = 0`, from the master sub-triangle's
//! barycentric guess), the gap `g = n . (x_m - x_s)` along the slave unit
//! normal `n(xi) = a_1 x a_2 / |a_1 x a_2|`.
//!
//! Weighting (the pressure's basis): the quadratic slave corner functions
//! of a tri6 integrate to zero (a quad8's to `-1/12` of the face), so the
//! rows are weighted by the dual `psi_j` of the positive-weight basis `N~`
//! of [`crate::contact::face_integrated::multiplier_basis`] (`N~_c = N_c +
//! alpha sum N_m`, `N~_m = (1 - 2 alpha) N_m`, `alpha = 1/5`, Wohlmuth,
//! Popp, Gee & Wall 2012), per slave face `psi_j = sum_m A_jm N~_m`, `A =
//! D_e M_e^-1`, `M_e = int N~ N~^T dA` and `D_e` its row sums over the
//! curved face (the face cell's mass rule): `int psi_j N~_k dA = delta_jk
//! int N~_j dA`, `int psi_j dA = int N~_j dA > 0`. The pressure field of
//! the pair is `p = sum_j p_j psi_j`. With the displacement functions `N`
//! (slave) and `N^` (master) the integrals of slave node `j` are
//!
//! `A_j = int psi_j dA` (the covered area), `g~_j = int psi_j g dA`,
//! `B_jk = -int psi_j N_k n dA`, `B_jl = int psi_j N^_l n dA`,
//!
//! so that `g~_j = sum B . x` with `n` held fixed (the forces `p_j B_j`).
//! On flat faces with affine cells the integrands are polynomials of
//! degree <= 4 in the plane and the rule is exact: a uniform pressure
//! gives the consistent nodal forces on both sides (the patch test).
//!
//! **Mixed orders** (a linear side against a quadratic one, issue 23): a
//! tri3 / quad4 face is a face of 3 / 4 nodes with its own (bi)linear
//! shape functions ([`shapes`]; parent domain the tri6's / quad9's
//! corners), cut into 1 / 4 sub-triangles (a quad4 through its centre
//! `x(0, 0)`); without midside nodes `N~ = N`, so a linear slave's rows are
//! weighted by the plain dual functions of its (bi)linear basis (positive
//! weights `int N_j dA`), and a linear master's forces go to its corners
//! by `N^_l`. On flat faces with affine cells the integrands stay
//! polynomials of degree <= 4 (patch test exact).
//!
//! Every quantity is an [`Ad54`] over the 54 coordinates `[slave node a,
//! component c] -> 3 a + c` and `[master node b, c] -> 27 + 3 b + c`: the
//! exact derivative of the segmentation, the mapping and the projections
//! (each ends with one Newton step in dual numbers).

use super::ad::Ad;
use super::facets::{clip, cross2, sub2, twice_area, MIN_FACING, MIN_OVERLAP, RULE};
use crate::contact::face_integrated::BASIS_ALPHA;
use crate::contact::node_to_facet::{cross, dot, newton_step, sub};
use crate::element::reference::{COLLAPSED_TRI16, GAUSS3X3};

/// Most nodes of a quadratic face (quad9).
pub const MAX_NODES: usize = 9;

/// Number of dual directions: 9 slave and 9 master nodes, 3 components.
pub const NVAR: usize = 54;

/// First variable of the master nodes.
pub const MASTER_BASE: usize = 27;

/// Dual numbers over the 54 coordinates of a face pair.
pub type Ad54 = Ad<NVAR>;

type P3<const N: usize> = [Ad<N>; 3];
type P2<const N: usize> = [Ad<N>; 2];

/// Newton iterations of the master projection before giving up.
const MAX_PROJECTION_ITERATIONS: usize = 30;

/// A master point farther than this outside its face's parent domain
/// (parent units) is no point of that face.
const OUTSIDE_PARENT: f64 = 0.5;

/// Sub-triangles of a tri6 (local nodes, counter-clockwise in the parent
/// domain).
const TRI6_SUB: [[usize; 3]; 4] = [[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]];

/// Sub-triangles of a quad4 (index 8: the centre `x(0, 0)`).
const QUAD4_SUB: [[usize; 3]; 4] = [[0, 1, 8], [1, 2, 8], [2, 3, 8], [3, 0, 8]];

/// Sub-triangles of a quad8 / quad9 (index 8: the centre).
const QUAD_SUB: [[usize; 3]; 8] = [
    [0, 4, 8],
    [0, 8, 7],
    [4, 1, 5],
    [4, 5, 8],
    [8, 5, 2],
    [8, 2, 6],
    [7, 8, 6],
    [7, 6, 3],
];

/// The midside nodes of a quadratic face as `(midside, corner, corner)`
/// (none on a linear face).
fn midsides(nn: usize) -> &'static [(usize, usize, usize)] {
    match nn {
        3 | 4 => &[],
        6 => &[(3, 0, 1), (4, 1, 2), (5, 2, 0)],
        _ => &[(4, 0, 1), (5, 1, 2), (6, 2, 3), (7, 3, 0)],
    }
}

/// Parent coordinates of local node `a` of a face of `nn` nodes (a quad's
/// index 8 is its centre; a tri3 / quad4 face: the corners).
fn parent(nn: usize, a: usize) -> [f64; 2] {
    use crate::element::reference::{quad9::Quad9, tri6::Tri6, ReferenceCell};
    if is_triangle(nn) {
        <Tri6 as ReferenceCell<2, 6>>::NODES[a]
    } else {
        <Quad9 as ReferenceCell<2, 9>>::NODES[a]
    }
}

/// Whether `nn` is the node count of a quadratic face.
pub fn is_quadratic_face(nn: usize) -> bool {
    matches!(nn, 6 | 8 | 9)
}

/// Whether `nn` is the node count of a face these integrals take: the
/// quadratic ones and, for mixed-order pairs (a linear side against a
/// quadratic one, issue 23), tri3 and quad4 with their own (bi)linear
/// shape functions (no midside nodes: `N~ = N`, the plain dual basis).
pub fn is_mortar_face(nn: usize) -> bool {
    matches!(nn, 3 | 4 | 6 | 8 | 9)
}

/// Whether a face of `nn` nodes is a triangle (tri3, tri6).
fn is_triangle(nn: usize) -> bool {
    matches!(nn, 3 | 6)
}

/// Shape functions and their parameter derivatives at `xi` of a quadratic
/// face of `nn` nodes (tri6 on the unit triangle, quad8 serendipity and
/// quad9 Lagrange on `[-1, 1]^2`, VTK node order); unused slots zero.
#[allow(clippy::type_complexity)]
pub fn shapes<const N: usize>(nn: usize, xi: [Ad<N>; 2]) -> ([Ad<N>; 9], [[Ad<N>; 2]; 9]) {
    let z = Ad::cst(0.0);
    let mut n = [z; 9];
    let mut g = [[z; 2]; 9];
    let [r, s] = xi;
    match nn {
        3 => {
            n[..3].copy_from_slice(&[Ad::cst(1.0) - r - s, r, s]);
            g[0] = [Ad::cst(-1.0), Ad::cst(-1.0)];
            g[1] = [Ad::cst(1.0), z];
            g[2] = [z, Ad::cst(1.0)];
        }
        4 => {
            for a in 0..4 {
                let [pi, qi] = parent(4, a);
                // 1/4 (1 + r ri)(1 + s si)
                let (u, v) = (Ad::cst(1.0) + r * pi, Ad::cst(1.0) + s * qi);
                n[a] = u * v * 0.25;
                g[a] = [v * (0.25 * pi), u * (0.25 * qi)];
            }
        }
        6 => {
            let l = [Ad::cst(1.0) - r - s, r, s];
            let dl = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
            for i in 0..3 {
                n[i] = l[i] * (l[i] * 2.0 + -1.0);
                let f = l[i] * 4.0 + -1.0;
                g[i] = [f * dl[i][0], f * dl[i][1]];
            }
            for (m, a, b) in [(3, 0, 1), (4, 1, 2), (5, 2, 0)] {
                n[m] = l[a] * l[b] * 4.0;
                for k in 0..2 {
                    g[m][k] = (l[b] * dl[a][k] + l[a] * dl[b][k]) * 4.0;
                }
            }
        }
        8 => {
            for a in 0..8 {
                let [pi, qi] = parent(8, a);
                if a < 4 {
                    // 1/4 (1 + r ri)(1 + s si)(r ri + s si - 1)
                    let (u, v) = (Ad::cst(1.0) + r * pi, Ad::cst(1.0) + s * qi);
                    let w = r * pi + s * qi + -1.0;
                    n[a] = u * v * w * 0.25;
                    g[a] = [
                        v * (r * (2.0 * pi) + s * qi) * (0.25 * pi),
                        u * (r * pi + s * (2.0 * qi)) * (0.25 * qi),
                    ];
                } else if pi == 0.0 {
                    let (u, v) = (Ad::cst(1.0) - r * r, Ad::cst(1.0) + s * qi);
                    n[a] = u * v * 0.5;
                    g[a] = [-(r * v), u * (0.5 * qi)];
                } else {
                    let (u, v) = (Ad::cst(1.0) + r * pi, Ad::cst(1.0) - s * s);
                    n[a] = u * v * 0.5;
                    g[a] = [v * (0.5 * pi), -(s * u)];
                }
            }
        }
        9 => {
            // 1D quadratic Lagrange functions at -1, 0, 1 and derivatives
            let lag = |t: Ad<N>, ti: f64| -> (Ad<N>, Ad<N>) {
                if ti < 0.0 {
                    (t * (t + -1.0) * 0.5, t + -0.5)
                } else if ti > 0.0 {
                    (t * (t + 1.0) * 0.5, t + 0.5)
                } else {
                    (Ad::cst(1.0) - t * t, -(t * 2.0))
                }
            };
            for a in 0..9 {
                let [pi, qi] = parent(9, a);
                let ((lr, dr), (ls, ds)) = (lag(r, pi), lag(s, qi));
                n[a] = lr * ls;
                g[a] = [dr * ls, lr * ds];
            }
        }
        _ => {}
    }
    (n, g)
}

/// The positive-weight basis `N~` of the shape values `n` of a face of
/// `nn` nodes (see [`crate::contact::face_integrated::multiplier_basis`]).
fn modified<const N: usize>(nn: usize, n: &[Ad<N>; 9]) -> [Ad<N>; 9] {
    let mut out = *n;
    for &(m, a, b) in midsides(nn) {
        out[a] += n[m] * BASIS_ALPHA;
        out[b] += n[m] * BASIS_ALPHA;
        out[m] = n[m] * (1.0 - 2.0 * BASIS_ALPHA);
    }
    out
}

/// Point, tangents `a_1`, `a_2` and shape values at `xi` of the face `x`.
#[allow(clippy::type_complexity)]
fn face_point<const N: usize>(x: &[P3<N>], xi: [Ad<N>; 2]) -> (P3<N>, [P3<N>; 2], [Ad<N>; 9]) {
    let (n, g) = shapes(x.len(), xi);
    let z = Ad::cst(0.0);
    let (mut p, mut a1, mut a2) = ([z; 3], [z; 3], [z; 3]);
    for (a, q) in x.iter().enumerate() {
        for c in 0..3 {
            p[c] += n[a] * q[c];
            a1[c] += g[a][0] * q[c];
            a2[c] += g[a][1] * q[c];
        }
    }
    (p, [a1, a2], n)
}

/// The cell's mass rule on the parent face (tri6: the 16-point collapsed
/// rule; quads: 3 x 3 Gauss points).
fn face_rule(nn: usize) -> &'static [([f64; 2], f64)] {
    if is_triangle(nn) {
        &COLLAPSED_TRI16
    } else {
        &GAUSS3X3
    }
}

/// The coefficients `A` of the dual functions `psi_j = sum_m A_jm N~_m`
/// of the curved slave face `x` (see the module): `A = D_e M_e^-1` over
/// the face by its mass rule; `None` for a singular `M_e`.
pub fn dual_coefficients<const N: usize>(x: &[P3<N>]) -> Option<[[Ad<N>; 9]; 9]> {
    let nn = x.len();
    let z = Ad::<N>::cst(0.0);
    let mut me = [[z; 9]; 9];
    for (q, w) in face_rule(nn) {
        let (_, [a1, a2], n) = face_point(x, q.map(Ad::cst));
        let m = cross(a1, a2);
        let da = dot(m, m).sqrt() * *w;
        let nt = modified(nn, &n);
        for j in 0..nn {
            let f = nt[j] * da;
            for k in 0..nn {
                me[j][k] += f * nt[k];
            }
        }
    }
    let de: [Ad<N>; 9] = std::array::from_fn(|j| (0..nn).fold(z, |s, k| s + me[j][k]));
    // M_e^-1 by Gauss-Jordan (symmetric positive definite: no pivoting)
    let mut inv = [[z; 9]; 9];
    for (j, row) in inv.iter_mut().enumerate().take(nn) {
        row[j] = Ad::cst(1.0);
    }
    let scale = me[0][0].v.abs().max(f64::MIN_POSITIVE);
    for c in 0..nn {
        let pivot = me[c][c];
        if pivot.v.is_nan() || pivot.v <= 1e-12 * scale {
            return None;
        }
        for k in 0..nn {
            me[c][k] = me[c][k] / pivot;
            inv[c][k] = inv[c][k] / pivot;
        }
        for r in 0..nn {
            if r == c {
                continue;
            }
            let f = me[r][c];
            for k in 0..nn {
                me[r][k] = me[r][k] - f * me[c][k];
                inv[r][k] = inv[r][k] - f * inv[c][k];
            }
        }
    }
    let mut a = [[z; 9]; 9];
    for j in 0..nn {
        for k in 0..nn {
            a[j][k] = de[j] * inv[j][k];
        }
    }
    Some(a)
}

/// The reference weights `int N~_j dA` of the nodes `nodes` (sorted) over
/// the quadratic faces `faces` of the coordinates `x` (the slave nodes'
/// tributary areas of quadratic 3D mortar: positive at every node).
pub fn supports(x: &[[f64; 3]], faces: &[&[usize]], nodes: &[usize]) -> Vec<f64> {
    let mut out = vec![0.0; nodes.len()];
    for face in faces {
        let nn = face.len();
        if !is_mortar_face(nn) {
            continue;
        }
        let Some(pts) = face
            .iter()
            .map(|&n| x.get(n).map(|p| p.map(Ad::<0>::cst)))
            .collect::<Option<Vec<_>>>()
        else {
            continue;
        };
        for (q, w) in face_rule(nn) {
            let (_, [a1, a2], n) = face_point(&pts, q.map(Ad::cst));
            let m = cross(a1, a2);
            let da = dot(m, m).sqrt().v * w;
            let nt = modified(nn, &n);
            for (a, node) in face.iter().enumerate() {
                if let Ok(i) = nodes.binary_search(node) {
                    out[i] += nt[a].v * da;
                }
            }
        }
    }
    out
}

/// The mortar integrals of a quadratic slave face against a quadratic
/// master face (module doc); rows `j < ns`.
#[derive(Debug, Clone)]
pub struct QuadSegment {
    /// Slave face nodes (6, 8 or 9).
    pub ns: usize,
    /// Master face nodes (6, 8 or 9).
    pub nm: usize,
    /// `A_j = int psi_j dA` over the covered part of the slave face.
    pub area: Vec<Ad54>,
    /// Weighted gaps `g~_j`.
    pub gap: Vec<Ad54>,
    /// `B_j` per row: slave node `k` at `k`, master node `l` at
    /// [`MAX_NODES`] `+ l` (vectors).
    pub b: Vec<Vec<[Ad54; 3]>>,
    /// Area of the overlap (the clip polygons in their planes).
    pub overlap: f64,
    /// Smallest and largest gap over the integration points.
    pub gap_range: [f64; 2],
    /// Friction ([`face_pair_frictional`]; empty otherwise): the scalar
    /// mortar integrals per row, `D_jk = int psi_j N_k dA` at `k` and `M_jl
    /// = int psi_j N^_l dA` at [`MAX_NODES`] `+ l`.
    pub d: Vec<Vec<Ad54>>,
    /// Friction: the integration points (values), where the weighted
    /// tangential slip is measured ([`super::friction_quadratic`]).
    pub points: Vec<QuadPoint>,
}

/// One integration point of a quadratic face pair (values): the slave
/// parameters `xi`, the master parameters `eta` of the point facing it,
/// and per row `j` the weight `psi_j dA`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct QuadPoint {
    /// Slave parameters.
    pub xi: [f64; 2],
    /// Master parameters.
    pub eta: [f64; 2],
    /// Per row (slave node `j < ns`): `psi_j dA`.
    pub weight: [f64; MAX_NODES],
}

/// The master parameters where the line through `xs` along the slave
/// tangents' normal meets the face `xm` (`(x_m(eta) - xs) . a_k = 0`):
/// Newton on the values from `eta0`, then one step in dual numbers;
/// `None` if Newton fails or the point lies farther than
/// [`OUTSIDE_PARENT`] outside the face.
fn project_master<const N: usize>(
    xm: &[P3<N>],
    xs: P3<N>,
    a: [P3<N>; 2],
    eta0: [f64; 2],
) -> Option<[Ad<N>; 2]> {
    let residual = |pts: &[P3<N>], eta: [Ad<N>; 2]| {
        let (x, t, _) = face_point(pts, eta);
        let d = sub(x, xs);
        let r = [dot(d, a[0]), dot(d, a[1])];
        let j = [
            [dot(t[0], a[0]), dot(t[1], a[0])],
            [dot(t[0], a[1]), dot(t[1], a[1])],
        ];
        (r, j)
    };
    let values = |q: P3<N>| q.map(|v| Ad::<0>::cst(v.v));
    let pv: Vec<P3<0>> = xm.iter().map(|&q| values(q)).collect();
    let (xv, av) = (values(xs), a.map(values));
    let mut eta = eta0;
    let mut converged = false;
    for _ in 0..MAX_PROJECTION_ITERATIONS {
        let (x, t, _) = face_point(&pv, eta.map(Ad::cst));
        let d = sub(x, xv);
        let r = [dot(d, av[0]), dot(d, av[1])];
        let j = [
            [dot(t[0], av[0]), dot(t[1], av[0])],
            [dot(t[0], av[1]), dot(t[1], av[1])],
        ];
        let step = newton_step(r, j)?;
        eta = [eta[0] + step[0].v, eta[1] + step[1].v];
        if eta.iter().any(|v| v.is_nan() || v.abs() > 1e3) {
            return None;
        }
        if step[0].v.abs().max(step[1].v.abs()) <= 1e-14 {
            converged = true;
            break;
        }
    }
    if !converged || outside(xm.len(), eta) > OUTSIDE_PARENT {
        return None;
    }
    let e = eta.map(Ad::cst);
    let (r, j) = residual(xm, e);
    let step = newton_step(r, j)?;
    Some([e[0] + step[0], e[1] + step[1]])
}

/// How far parameters `eta` lie outside the parent domain of a face of
/// `nn` nodes (0 inside).
fn outside(nn: usize, eta: [f64; 2]) -> f64 {
    if is_triangle(nn) {
        (-eta[0]).max(-eta[1]).max(eta[0] + eta[1] - 1.0).max(0.0)
    } else {
        (eta[0].abs() - 1.0).max(eta[1].abs() - 1.0).max(0.0)
    }
}

/// The sub-triangles of a face of `nn` nodes: the physical corners (the
/// face's nodes, a quad8's centre `x(0, 0)`) and their parent coordinates.
#[allow(clippy::type_complexity)]
fn sub_triangles<const N: usize>(x: &[P3<N>]) -> Vec<([P3<N>; 3], [[f64; 2]; 3])> {
    let nn = x.len();
    let centre = if matches!(nn, 4 | 8) {
        face_point(x, [Ad::cst(0.0), Ad::cst(0.0)]).0
    } else {
        x[nn - 1]
    };
    let at = |a: usize| if a < nn { x[a] } else { centre };
    let list: &[[usize; 3]] = match nn {
        3 => &[[0, 1, 2]],
        4 => &QUAD4_SUB,
        6 => &TRI6_SUB,
        _ => &QUAD_SUB,
    };
    list.iter()
        .map(|t| (t.map(at), t.map(|a| parent(nn, a))))
        .collect()
}

/// Barycentric coordinates `(l_1, l_2)` of `p` in the plane triangle `t`.
fn barycentric<const N: usize>(t: &[P2<N>; 3], p: P2<N>) -> [Ad<N>; 2] {
    let (e1, e2, d) = (sub2(t[1], t[0]), sub2(t[2], t[0]), sub2(p, t[0]));
    let det = cross2(e1, e2);
    [cross2(d, e2) / det, cross2(e1, d) / det]
}

/// The integrals of [`face_pair`] in dual numbers of `N` directions (`N =
/// 0`: values only).
struct Integrals<const N: usize> {
    area: Vec<Ad<N>>,
    gap: Vec<Ad<N>>,
    b: Vec<Vec<[Ad<N>; 3]>>,
    overlap: f64,
    gap_range: [f64; 2],
    d: Vec<Vec<Ad<N>>>,
    points: Vec<QuadPoint>,
}

/// Point `p` as variables `base..base + 3` (constants past `N`).
fn var<const N: usize>(p: [f64; 3], base: usize) -> P3<N> {
    std::array::from_fn(|c| {
        if base + c < N {
            Ad::var(p[c], base + c)
        } else {
            Ad::cst(p[c])
        }
    })
}

/// [`face_pair`] in dual numbers of `N` directions; `vectors`: also the
/// force coefficients `B`; `friction`: also the scalar integrals `d` and
/// the points.
fn integrate<const N: usize>(
    slave: &[[f64; 3]],
    master: &[[f64; 3]],
    vectors: bool,
    friction: bool,
) -> Option<Integrals<N>> {
    let (ns, nm) = (slave.len(), master.len());
    let xs: Vec<P3<N>> = slave
        .iter()
        .enumerate()
        .map(|(a, &p)| var(p, 3 * a))
        .collect();
    let xm: Vec<P3<N>> = master
        .iter()
        .enumerate()
        .map(|(b, &p)| var(p, MASTER_BASE + 3 * b))
        .collect();
    let coef = dual_coefficients(&xs)?;
    let z = Ad::<N>::cst(0.0);
    let mut out = Integrals {
        area: vec![z; ns],
        gap: vec![z; ns],
        b: if vectors {
            vec![vec![[z; 3]; MAX_NODES + nm]; ns]
        } else {
            Vec::new()
        },
        overlap: 0.0,
        gap_range: [f64::INFINITY, f64::NEG_INFINITY],
        d: if friction {
            vec![vec![z; MAX_NODES + nm]; ns]
        } else {
            Vec::new()
        },
        points: Vec::new(),
    };
    let masters = sub_triangles(&xm);
    for (ps, xi_s) in sub_triangles(&xs) {
        let raw = cross(sub(ps[1], ps[0]), sub(ps[2], ps[0]));
        let len = dot(raw, raw).sqrt();
        if len.v.is_nan() || len.v <= 0.0 {
            return None;
        }
        let n_s = raw.map(|v| v / len);
        let x0: P3<N> = std::array::from_fn(|c| (ps[0][c] + ps[1][c] + ps[2][c]) * (1.0 / 3.0));
        let e = sub(ps[1], ps[0]);
        let en = dot(e, n_s);
        let et: P3<N> = std::array::from_fn(|c| e[c] - n_s[c] * en);
        let el = dot(et, et).sqrt();
        if el.v.is_nan() || el.v <= 0.0 {
            return None;
        }
        let t1 = et.map(|v| v / el);
        let t2 = cross(n_s, t1);
        let project = |p: P3<N>| {
            let d = sub(p, x0);
            [dot(d, t1), dot(d, t2)]
        };
        let sp: [P2<N>; 3] = ps.map(project);
        let plane_area = twice_area(&sp);
        if plane_area.v.is_nan() || plane_area.v <= 0.0 {
            return None;
        }
        // |dxi / dp|: twice the parent area over twice the plane area
        let parent_area = (xi_s[1][0] - xi_s[0][0]) * (xi_s[2][1] - xi_s[0][1])
            - (xi_s[1][1] - xi_s[0][1]) * (xi_s[2][0] - xi_s[0][0]);
        let ratio = Ad::cst(parent_area) / plane_area;
        for (pm, eta_m) in &masters {
            let mq: [P2<N>; 3] = pm.map(project);
            let mp: Vec<P2<N>> = mq.iter().rev().copied().collect();
            let mraw = cross(sub(pm[1], pm[0]), sub(pm[2], pm[0]));
            let own = 0.5 * dot(mraw, mraw).sqrt().v;
            let projected = 0.5 * twice_area(&mp).v;
            if projected.is_nan() || projected <= MIN_FACING * own {
                continue;
            }
            let poly = clip(mp, &sp);
            if poly.len() < 3 {
                continue;
            }
            let area = 0.5 * twice_area(&poly).v;
            if area.is_nan() || area <= MIN_OVERLAP * 0.5 * plane_area.v {
                continue;
            }
            out.overlap += area;
            // the clip polygon is convex: a fan from its first vertex (n - 2
            // triangles, against n from its centre)
            let centre = poly[0];
            for i in 1..poly.len() - 1 {
                let (a, b) = (poly[i], poly[i + 1]);
                let at = cross2(sub2(a, centre), sub2(b, centre)) * 0.5;
                for (l, w) in RULE {
                    let p: P2<N> =
                        std::array::from_fn(|c| centre[c] * l[0] + a[c] * l[1] + b[c] * l[2]);
                    let lam = barycentric(&sp, p);
                    let xi: [Ad<N>; 2] = std::array::from_fn(|c| {
                        lam[0] * (xi_s[1][c] - xi_s[0][c])
                            + lam[1] * (xi_s[2][c] - xi_s[0][c])
                            + xi_s[0][c]
                    });
                    let (x_s, [a1, a2], n_sh) = face_point(&xs, xi);
                    let nv = cross(a1, a2);
                    let jac = dot(nv, nv).sqrt();
                    let n = nv.map(|v| v / jac);
                    // the master sub-triangle's barycentric guess
                    let lm = barycentric(&mq, p);
                    let guess: [f64; 2] = std::array::from_fn(|c| {
                        eta_m[0][c]
                            + lm[0].v * (eta_m[1][c] - eta_m[0][c])
                            + lm[1].v * (eta_m[2][c] - eta_m[0][c])
                    });
                    let eta = project_master(&xm, x_s, [a1, a2], guess)?;
                    let (x_m, _, n_ma) = face_point(&xm, eta);
                    let g = dot(n, sub(x_m, x_s));
                    out.gap_range = [out.gap_range[0].min(g.v), out.gap_range[1].max(g.v)];
                    let jw = at * w * jac * ratio;
                    let nt = modified(ns, &n_sh);
                    let mut point = QuadPoint {
                        xi: xi.map(|v| v.v),
                        eta: eta.map(|v| v.v),
                        weight: [0.0; MAX_NODES],
                    };
                    for (j, cj) in coef.iter().enumerate().take(ns) {
                        let mut psi = z;
                        for q in 0..ns {
                            psi += cj[q] * nt[q];
                        }
                        let pw = psi * jw;
                        point.weight[j] = pw.v;
                        if let Some(row) = out.d.get_mut(j) {
                            for q in 0..ns {
                                row[q] += pw * n_sh[q];
                            }
                            for q in 0..nm {
                                row[MAX_NODES + q] += pw * n_ma[q];
                            }
                        }
                        out.area[j] += pw;
                        out.gap[j] += pw * g;
                        if !vectors {
                            continue;
                        }
                        let pn = n.map(|c| pw * c);
                        let row = &mut out.b[j];
                        for q in 0..ns {
                            for c in 0..3 {
                                row[q][c] = row[q][c] - pn[c] * n_sh[q];
                            }
                        }
                        for q in 0..nm {
                            for c in 0..3 {
                                row[MAX_NODES + q][c] += pn[c] * n_ma[q];
                            }
                        }
                    }
                    if friction {
                        out.points.push(point);
                    }
                }
            }
        }
    }
    (out.overlap > 0.0).then_some(out)
}

/// The mortar integrals of quadratic slave face `slave` (6, 8 or 9 nodes,
/// counter-clockwise seen from outside) against quadratic master face
/// `master`; `None` when they do not overlap or a face is degenerate.
pub fn face_pair(slave: &[[f64; 3]], master: &[[f64; 3]]) -> Option<QuadSegment> {
    face_pair_within(slave, master, f64::INFINITY, f64::INFINITY)
}

/// [`face_pair`], `None` also when the gaps at the integration points all
/// exceed `max_gap` or all lie below `-max_depth` (decided on values,
/// before the dual numbers).
pub fn face_pair_within(
    slave: &[[f64; 3]],
    master: &[[f64; 3]],
    max_gap: f64,
    max_depth: f64,
) -> Option<QuadSegment> {
    face_pair_with(slave, master, max_gap, max_depth, false)
}

/// [`face_pair_within`] with the friction integrals (`d` and the points).
pub fn face_pair_frictional(
    slave: &[[f64; 3]],
    master: &[[f64; 3]],
    max_gap: f64,
    max_depth: f64,
) -> Option<QuadSegment> {
    face_pair_with(slave, master, max_gap, max_depth, true)
}

fn face_pair_with(
    slave: &[[f64; 3]],
    master: &[[f64; 3]],
    max_gap: f64,
    max_depth: f64,
    friction: bool,
) -> Option<QuadSegment> {
    let (ns, nm) = (slave.len(), master.len());
    if !is_mortar_face(ns) || !is_mortar_face(nm) {
        return None;
    }
    let values = integrate::<0>(slave, master, false, false)?;
    let [lo, hi] = values.gap_range;
    if lo > max_gap || hi < -max_depth {
        return None;
    }
    let i = integrate::<NVAR>(slave, master, true, friction)?;
    Some(QuadSegment {
        ns,
        nm,
        area: i.area,
        gap: i.gap,
        b: i.b,
        overlap: i.overlap,
        gap_range: i.gap_range,
        d: i.d,
        points: i.points,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::reference::{Quad8, Quad9, ReferenceCell, Tri6};

    /// The nodes of a face of `nn` nodes placed by `map` from their parent
    /// coordinates.
    fn face(nn: usize, map: &dyn Fn([f64; 2]) -> [f64; 3]) -> Vec<[f64; 3]> {
        (0..nn).map(|a| map(parent(nn, a))).collect()
    }

    /// A slave face over `[0, 1]^2` (the unit triangle for tri6) at `z =
    /// bend (x^2 + y^2)`, outward `+z`.
    fn slave(nn: usize, bend: f64) -> Vec<[f64; 3]> {
        face(nn, &|[r, s]| {
            let (x, y) = if is_triangle(nn) {
                (r, s)
            } else {
                (0.5 * (1.0 + r), 0.5 * (1.0 + s))
            };
            [x, y, bend * (x * x + y * y)]
        })
    }

    /// A master face of size `size` at `(ox, oy)` turned by `rot`, at `z =
    /// gap + bend (x^2 + y^2)`, facing down (its parent axes swapped).
    fn master(
        nn: usize,
        ox: f64,
        oy: f64,
        size: f64,
        rot: f64,
        gap: f64,
        bend: f64,
    ) -> Vec<[f64; 3]> {
        face(nn, &|[r, s]| {
            let (u, v) = if is_triangle(nn) {
                (s, r)
            } else {
                (0.5 * (1.0 + s), 0.5 * (1.0 + r))
            };
            let (c, sn) = (rot.cos(), rot.sin());
            let (x, y) = (ox + size * (c * u - sn * v), oy + size * (sn * u + c * v));
            [x, y, gap + bend * (x * x + y * y)]
        })
    }

    #[test]
    fn shapes_match_the_reference_cells() {
        let pts = [[0.2, 0.3], [0.05, 0.7], [-0.4, 0.6], [0.9, -0.8]];
        let mut worst = 0.0f64;
        for p in pts {
            let (n, g) = shapes::<0>(9, p.map(Ad::cst));
            let (rn, rg) = (Quad9::shape(&p), Quad9::gradients(&p));
            let (n8, g8) = shapes::<0>(8, p.map(Ad::cst));
            let (rn8, rg8) = (Quad8::shape(&p), Quad8::gradients(&p));
            for a in 0..9 {
                worst = worst.max((n[a].v - rn[a]).abs());
                for k in 0..2 {
                    worst = worst.max((g[a][k].v - rg[a][k]).abs());
                }
            }
            for a in 0..8 {
                worst = worst.max((n8[a].v - rn8[a]).abs());
                for k in 0..2 {
                    worst = worst.max((g8[a][k].v - rg8[a][k]).abs());
                }
            }
            if p[0] >= 0.0 && p[1] >= 0.0 && p[0] + p[1] <= 1.0 {
                let (n6, g6) = shapes::<0>(6, p.map(Ad::cst));
                let (rn6, rg6) = (Tri6::shape(&p), Tri6::gradients(&p));
                for a in 0..6 {
                    worst = worst.max((n6[a].v - rn6[a]).abs());
                    for k in 0..2 {
                        worst = worst.max((g6[a][k].v - rg6[a][k]).abs());
                    }
                }
            }
        }
        assert!(worst < 1e-14, "{worst:e}");
        // the gradients' own derivatives (the tangents' in dual numbers)
        // against central differences of the gradients
        let h = 1e-6;
        for nn in [6, 8, 9] {
            let p = [0.21, 0.33];
            let (_, g) = shapes::<2>(nn, [Ad::var(p[0], 0), Ad::var(p[1], 1)]);
            for k in 0..2 {
                let mut q = p;
                q[k] += h;
                let (_, gp) = shapes::<0>(nn, q.map(Ad::cst));
                q[k] -= 2.0 * h;
                let (_, gm) = shapes::<0>(nn, q.map(Ad::cst));
                for a in 0..nn {
                    for c in 0..2 {
                        let fd = (gp[a][c].v - gm[a][c].v) / (2.0 * h);
                        assert!((fd - g[a][c].d[k]).abs() < 1e-8, "{nn} {a} {c} {k}");
                    }
                }
            }
        }
    }

    #[test]
    fn weights_are_positive_and_a_covered_flat_face_has_its_areas() {
        // tri6 corners 2/15 of the area, midsides (1 - 2/5) / 3; quad8
        // corners -1/12 + 2/5 / 3 = 1/20, midsides 3/5 / 3; quad9 by the
        // tensor rule: corners 1/36 + 2/5 / 9, midsides 3/5 / 9, centre 4/9
        let expected = |nn: usize, a: usize| -> f64 {
            match (nn, a) {
                (6, 0..=2) => 2.0 / 15.0 * 0.5,
                (6, _) => 0.6 / 3.0 * 0.5,
                (8, 0..=3) => 1.0 / 20.0,
                (8, _) => 0.6 / 3.0,
                (9, 0..=3) => 1.0 / 36.0 + 0.4 / 9.0,
                (9, 8) => 4.0 / 9.0,
                _ => 0.6 / 9.0,
            }
        };
        for nn in [6, 8, 9] {
            let s = slave(nn, 0.0);
            let nodes: Vec<usize> = (0..nn).collect();
            let w = supports(&s, &[&nodes], &nodes);
            for (a, v) in w.iter().enumerate() {
                assert!((v - expected(nn, a)).abs() < 1e-14, "{nn} {a}: {v}");
            }
            // a master covering the slave at a uniform gap 0.05: A_j = int
            // N~_j, g~_j = 0.05 A_j, each row's forces in balance
            let m = master(nn, -0.7, -0.6, 3.0, 0.3, 0.05, 0.0);
            let seg = face_pair(&s, &m).unwrap();
            for (j, wj) in w.iter().enumerate() {
                assert!((seg.area[j].v - wj).abs() < 1e-13, "{nn} {j}");
                assert!((seg.gap[j].v - 0.05 * wj).abs() < 1e-14, "{nn} {j}");
                for c in 0..3 {
                    let sum: f64 = seg.b[j].iter().map(|b| b[c].v).sum();
                    assert!(sum.abs() < 1e-14, "{nn} {j} {c}: {sum:e}");
                }
            }
        }
    }

    #[test]
    fn a_partly_covering_master_gives_a_uniform_nodal_gap() {
        // flat faces, master turned and shifted over part of the slave: the
        // nodal gap g~_j / A_j of every node the master covers is the gap,
        // and the covered areas add up to the overlap
        for (ns, nm) in [(6, 6), (6, 8), (8, 9), (9, 6), (8, 8)] {
            let s = slave(ns, 0.0);
            let m = master(nm, 0.35, -0.2, 0.9, 0.4, -0.02, 0.0);
            let seg = face_pair(&s, &m).unwrap();
            let total: f64 = seg.area.iter().map(|a| a.v).sum();
            assert!((total - seg.overlap).abs() < 1e-13, "{ns} {nm}");
            for j in 0..ns {
                assert!((seg.gap[j].v + 0.02 * seg.area[j].v).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn concentric_spheres_give_their_radial_gap() {
        // slave: a patch of the unit sphere at the pole (nodes on the
        // sphere), master: the sphere of radius 1 + g over it, facing
        // down, turned and shifted: the gap along the slave normal is g
        // everywhere; the nodal gaps of the nodes the master covers must
        // be g up to the quadratic faces' geometric error (the quad8's
        // missing r^4 term: 2e-3 on a master of half-width 0.3, 1e-4 on
        // these)
        let g = 0.05;
        let cap = |radius: f64, x: f64, y: f64| [x, y, (radius * radius - x * x - y * y).sqrt()];
        for (ns, nm) in [(8, 8), (6, 9), (9, 6)] {
            let s = face(ns, &|[r, t]| {
                let (x, y) = if ns == 6 {
                    (0.1 * r, 0.1 * t)
                } else {
                    (0.05 * (1.0 + r), 0.05 * (1.0 + t))
                };
                cap(1.0, x, y)
            });
            let m = face(nm, &|[r, t]| {
                let (u, v) = if nm == 6 {
                    (0.5 * t, 0.5 * r)
                } else {
                    (0.15 * (1.0 + t), 0.15 * (1.0 + r))
                };
                let (c, sn) = (0.3f64.cos(), 0.3f64.sin());
                cap(1.0 + g, -0.08 + c * u - sn * v, -0.1 + sn * u + c * v)
            });
            let seg = face_pair(&s, &m).unwrap();
            let w = supports(
                &s,
                &[&(0..ns).collect::<Vec<_>>()],
                &(0..ns).collect::<Vec<_>>(),
            );
            let (mut worst, mut coverage) = (0.0f64, 0.0f64);
            for (j, wj) in w.iter().enumerate() {
                worst = worst.max((seg.gap[j].v / seg.area[j].v - g).abs() / g);
                coverage = coverage.max((seg.area[j].v / wj - 1.0).abs());
            }
            println!(
                "slave {ns}, master {nm}: nodal gap vs g: {worst:.2e}, A_j / T_j - 1: {coverage:.1e}"
            );
            assert!(coverage < 1e-2, "{ns} {nm}: covered {coverage:e}");
            // measured 3.1e-3 (quad8 | quad8), 9.3e-4 (tri6 | quad9), 1.6e-2
            // (quad9 | tri6: the tri6 master of side 0.5)
            assert!(worst < 2e-2, "{ns} {nm}: {worst:e}");
        }
    }

    /// The values of a face pair's integrals (`g~`, `A`, `B`) flattened.
    fn values(slave: &[[f64; 3]], master: &[[f64; 3]]) -> Option<Vec<f64>> {
        let i = integrate::<0>(slave, master, true, false)?;
        let mut v: Vec<f64> = i.gap.iter().chain(&i.area).map(|x| x.v).collect();
        for row in &i.b {
            v.extend(row.iter().flatten().map(|x| x.v));
        }
        Some(v)
    }

    /// The largest relative error `|fd - ad| / (1 + |fd|)` of the
    /// derivatives of every integral against central differences, and the
    /// largest moment imbalance of a row (`sum x x B`).
    fn fd_error(slave: &[[f64; 3]], master: &[[f64; 3]]) -> Option<(f64, f64)> {
        let seg = face_pair(slave, master)?;
        let mut derivs: Vec<[f64; NVAR]> = seg.gap.iter().chain(&seg.area).map(|x| x.d).collect();
        for row in &seg.b {
            derivs.extend(row.iter().flatten().map(|x| x.d));
        }
        let mut moment = 0.0f64;
        for row in &seg.b {
            let mut m = [0.0; 3];
            let mut scale = 0.0f64;
            let pts = slave
                .iter()
                .enumerate()
                .chain(master.iter().enumerate().map(|(l, p)| (MAX_NODES + l, p)));
            for (k, p) in pts {
                let b = row[k].map(|v| v.v);
                scale = scale.max(b.iter().map(|v| v.abs()).fold(0.0, f64::max));
                m[0] += p[1] * b[2] - p[2] * b[1];
                m[1] += p[2] * b[0] - p[0] * b[2];
                m[2] += p[0] * b[1] - p[1] * b[0];
            }
            moment = moment.max(m.iter().map(|v| v.abs()).fold(0.0, f64::max) / scale.max(1e-300));
        }
        let h = 1e-6;
        let mut worst = 0.0f64;
        for k in 0..NVAR {
            let (side, a, c) = if k < MASTER_BASE {
                (0, k / 3, k % 3)
            } else {
                (1, (k - MASTER_BASE) / 3, k % 3)
            };
            if (side == 0 && a >= slave.len()) || (side == 1 && a >= master.len()) {
                continue;
            }
            let shifted = |dx: f64| {
                let (mut sl, mut ma) = (slave.to_vec(), master.to_vec());
                if side == 0 {
                    sl[a][c] += dx;
                } else {
                    ma[a][c] += dx;
                }
                values(&sl, &ma)
            };
            let (p, m) = (shifted(h)?, shifted(-h)?);
            for ((vp, vm), dv) in p.iter().zip(&m).zip(&derivs) {
                let fd = (vp - vm) / (2.0 * h);
                worst = worst.max((fd - dv[k]).abs() / (1.0 + fd.abs()));
            }
        }
        Some((worst, moment))
    }

    #[test]
    fn derivatives_match_finite_differences_on_curved_jittered_pairs() {
        let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
        let mut rnd = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for (ns, nm) in [(6, 8), (8, 8), (9, 6), (8, 9)] {
            let (mut worst, mut moment, mut count) = (0.0f64, 0.0f64, 0);
            for _ in 0..3 {
                let mut s = slave(ns, 0.3 * rnd());
                let mut m = master(
                    nm,
                    0.3 + 0.2 * rnd(),
                    -0.1 + 0.2 * rnd(),
                    0.8 + 0.2 * rnd(),
                    0.5 * rnd(),
                    0.05 * rnd(),
                    0.2 * rnd(),
                );
                for p in s.iter_mut().chain(m.iter_mut()) {
                    for v in p.iter_mut() {
                        *v += 0.02 * rnd();
                    }
                }
                if let Some((e, mo)) = fd_error(&s, &m) {
                    worst = worst.max(e);
                    moment = moment.max(mo);
                    count += 1;
                }
            }
            println!(
                "slave {ns}, master {nm}: {count} pairs, FD error {worst:.1e}, moment {moment:.1e}"
            );
            assert!(count >= 2 && worst < 1e-6, "{ns} {nm}: {count} {worst:e}");
            assert!(moment < 1e-10, "{ns} {nm}: moment {moment:e}");
        }
    }
    /// Mixed orders (issue 23): tri3 / quad4 faces are faces of 3 / 4
    /// nodes with their own (bi)linear functions: the shapes are the
    /// reference cells', the weights `int N_j dA` (a quarter of a flat
    /// quad4, a third of a tri3), a partly covering master gives a
    /// uniform nodal gap (either side linear), and every integral's
    /// derivative matches central differences on curved jittered pairs,
    /// each row in moment balance.
    #[test]
    fn linear_faces_against_quadratic_ones() {
        use crate::element::reference::{Quad4, Tri3};
        let mut worst = 0.0f64;
        for p in [[0.2, 0.3], [0.05, 0.7], [-0.4, 0.6], [0.9, -0.8]] {
            let (n, g) = shapes::<0>(4, p.map(Ad::cst));
            let (rn, rg) = (Quad4::shape(&p), Quad4::gradients(&p));
            for a in 0..4 {
                worst = worst.max((n[a].v - rn[a]).abs());
                for k in 0..2 {
                    worst = worst.max((g[a][k].v - rg[a][k]).abs());
                }
            }
            let (n, g) = shapes::<0>(3, p.map(Ad::cst));
            let (rn, rg) = (Tri3::shape(&p), Tri3::gradients(&p));
            for a in 0..3 {
                worst = worst.max((n[a].v - rn[a]).abs());
                for k in 0..2 {
                    worst = worst.max((g[a][k].v - rg[a][k]).abs());
                }
            }
        }
        assert!(worst < 1e-15, "{worst:e}");
        for nn in [3, 4] {
            let s = slave(nn, 0.0);
            let nodes: Vec<usize> = (0..nn).collect();
            let w = supports(&s, &[&nodes], &nodes);
            let share = if nn == 3 { 0.5 / 3.0 } else { 0.25 };
            for v in &w {
                assert!((v - share).abs() < 1e-14, "{nn}: {v}");
            }
        }
        for (ns, nm) in [
            (3, 6),
            (4, 8),
            (4, 9),
            (3, 8),
            (6, 3),
            (8, 4),
            (9, 4),
            (8, 3),
        ] {
            let s = slave(ns, 0.0);
            let m = master(nm, 0.35, -0.2, 0.9, 0.4, -0.02, 0.0);
            let seg = face_pair(&s, &m).unwrap();
            let total: f64 = seg.area.iter().map(|a| a.v).sum();
            assert!((total - seg.overlap).abs() < 1e-13, "{ns} {nm}");
            for j in 0..ns {
                assert!(
                    (seg.gap[j].v + 0.02 * seg.area[j].v).abs() < 1e-14,
                    "{ns} {nm} {j}"
                );
            }
        }
        let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut rnd = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for (ns, nm) in [(3, 8), (4, 6), (4, 9), (6, 4), (8, 3), (9, 4)] {
            let (mut worst, mut moment, mut count) = (0.0f64, 0.0f64, 0);
            for _ in 0..3 {
                let mut s = slave(ns, 0.3 * rnd());
                let mut m = master(
                    nm,
                    0.3 + 0.2 * rnd(),
                    -0.1 + 0.2 * rnd(),
                    0.8 + 0.2 * rnd(),
                    0.5 * rnd(),
                    0.05 * rnd(),
                    0.2 * rnd(),
                );
                for p in s.iter_mut().chain(m.iter_mut()) {
                    for v in p.iter_mut() {
                        *v += 0.02 * rnd();
                    }
                }
                if let Some((e, mo)) = fd_error(&s, &m) {
                    worst = worst.max(e);
                    moment = moment.max(mo);
                    count += 1;
                }
            }
            println!(
                "mixed: slave {ns}, master {nm}: {count} pairs, FD error {worst:.1e}, moment {moment:.1e}"
            );
            assert!(count >= 2 && worst < 1e-6, "{ns} {nm}: {count} {worst:e}");
            assert!(moment < 1e-10, "{ns} {nm}: moment {moment:e}");
        }
    }
}
