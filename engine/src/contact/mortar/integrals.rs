//! Mortar integrals of one slave segment against one master segment (2D,
//! seg2 on both sides).
//!
//! The slave segment `a -> b` (length `L`, unit tangent `t`, outward unit
//! normal `n = (t_y, -t_x)`: the body is on the left) is the integration
//! side. The master segment `c -> d` is projected on the slave segment's
//! line along `n`: its ends land at `xi_c = (x_c - x_a) . t / L` and
//! `xi_d`. A master segment faces the slave one when `xi_d < xi_c` (the
//! two bodies walk their boundaries in opposite directions); the **mortar
//! segment** is the overlap `[lo, hi] = [max(0, xi_d), min(1, xi_c)]` of
//! the projection with `[0, 1]` (the segmentation). On it the master point
//! facing slave point `xi` has the parameter
//! `eta = (xi - xi_c) / (xi_d - xi_c)` (an affine map), and the gap along
//! `n` is `g(xi) = n . (x_m(eta) - x_s(xi))`, linear in `xi`.
//!
//! With the slave shape functions `N_j = (1 - xi, xi)`, the master ones
//! `N^_l = (1 - eta, eta)` and the weight `w` (thickness, or `2 pi r` in
//! axisymmetry):
//!
//! `D_jk = int N_j N_k w ds`, `M_jl = int N_j N^_l w ds`,
//! `g~_j = n . (sum_l M_jl x_l - sum_k D_jk x_k) = int N_j g w ds`.
//!
//! **Dual multipliers** ([`Basis::Dual`], Wohlmuth 2000; Popp, Gee & Wall,
//! IJNME 79 (2009) 1354): the rows are weighted with the dual functions
//! `psi_j = sum_k A_jk N_k` instead of `N_j`, `A = D_e M_e^-1` from the
//! slave segment's mass matrix `M_e = int_e N N^T w ds` and its lumped
//! diagonal `D_e = diag(int_e N_j w ds)`, so that `int_e psi_j N_k w ds =
//! delta_jk int_e N_j w ds` (biorthogonality): on a slave segment the
//! master covers, `D` is diagonal and the nodal gap `g~_j / D_jj` is the
//! value at node `j` of the gap's linear interpolation (with the standard
//! functions it is the gap averaged over `j`'s support). With a constant
//! weight `psi_a = 2 N_a - N_b`; in axisymmetry `A` depends on the radii of
//! the slave ends. The dual basis is the full segment's (the variant of
//! Popp et al. 2009, not the consistent one of Cichosz & Bischoff 2011
//! that recomputes `A` on the covered part of a partially projected
//! segment): it depends on the slave segment's coordinates only, so the
//! derivatives stay within the pair's 8 variables; on a segment only
//! partly covered, `D` keeps a small off-diagonal term (`int_cov psi_j
//! N_k`), used as it is (the forces stay in equilibrium).
//!
//! The integrands are polynomials of degree <= 3 in `xi` on the mortar
//! segment, so the 2-point Gauss rule on `[lo, hi]` is exact (a uniform
//! pressure is transmitted exactly: the patch test). Every quantity is an
//! [`Ad<8>`] over the coordinates `[x_a, y_a, x_b, y_b, x_c, y_c, x_d,
//! y_d]`: its exact derivative, including the change of the segmentation
//! with the geometry (the ends `lo`, `hi` move with the nodes).

use super::ad::Ad;
use std::f64::consts::PI;

/// Dual numbers over the 8 coordinates of a segment pair.
pub type Ad8 = Ad<8>;

/// Integration weight across the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Weight {
    /// Plane strain / stress: the thickness.
    Thickness(f64),
    /// Axisymmetric: `2 pi r` at the slave point.
    Axisymmetric,
}

/// Shape functions of the multiplier (the row weights).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Basis {
    /// The slave's own shape functions `N_j`.
    Standard,
    /// Their biorthogonal duals `psi_j` (`D` diagonal).
    #[default]
    Dual,
}

/// The 2-point Gauss rule on `[0, 1]` (abscissae; the weights are 1/2).
const GAUSS: [f64; 2] = [
    0.5 - 0.5 / 1.732_050_807_568_877_2,
    0.5 + 0.5 / 1.732_050_807_568_877_2,
];

/// The integration weight at slave parameter `xi` (`ra`, `rb` the radii of
/// the slave ends).
fn weight_at(weight: Weight, ra: Ad8, rb: Ad8, xi: Ad8) -> Ad8 {
    match weight {
        Weight::Thickness(th) => Ad8::cst(th),
        Weight::Axisymmetric => (ra * (-xi + 1.0) + rb * xi) * (2.0 * PI),
    }
}

/// The coefficients `A` of the dual functions `psi_j = sum_k A_jk N_k` of
/// a slave segment whose ends lie at radii `ra`, `rb` (`A = D_e M_e^-1`,
/// module doc); the identity for [`Basis::Standard`].
pub fn dual_coefficients(basis: Basis, weight: Weight, ra: Ad8, rb: Ad8) -> [[Ad8; 2]; 2] {
    let one = Ad8::cst(1.0);
    let zero = Ad8::cst(0.0);
    if basis == Basis::Standard {
        return [[one, zero], [zero, one]];
    }
    if let Weight::Thickness(_) = weight {
        // constant weight: A = [[2, -1], [-1, 2]] exactly
        return [[one * 2.0, -one], [-one, one * 2.0]];
    }
    // the length and the thickness factor cancel in D_e M_e^-1
    let mut me = [[zero; 2]; 2];
    for s in GAUSS {
        let xi = Ad8::cst(s);
        let w = weight_at(weight, ra, rb, xi) * 0.5;
        let n = [-xi + 1.0, xi];
        for j in 0..2 {
            for k in 0..2 {
                me[j][k] += n[j] * n[k] * w;
            }
        }
    }
    let de = [me[0][0] + me[0][1], me[1][0] + me[1][1]];
    let det = me[0][0] * me[1][1] - me[0][1] * me[1][0];
    let inv = [
        [me[1][1] / det, -me[0][1] / det],
        [-me[1][0] / det, me[0][0] / det],
    ];
    std::array::from_fn(|j| std::array::from_fn(|k| de[j] * inv[j][k]))
}

/// Mortar integrals of one slave segment against one master segment
/// (`D_jk = int psi_j N_k w ds` and `M_jl = int psi_j N^_l w ds` with the
/// row functions `psi_j` of the [`Basis`]).
#[derive(Debug, Clone, Copy)]
pub struct MortarSegment {
    /// Mortar segment on the slave segment, `0 <= lo < hi <= 1`.
    pub lo: f64,
    /// Upper end of the mortar segment.
    pub hi: f64,
    /// `D_jk` (slave `j`, slave `k`), `j, k` in `{a, b}`.
    pub d: [[Ad8; 2]; 2],
    /// `M_jl` (slave `j`, master `l`), `l` in `{c, d}`.
    pub m: [[Ad8; 2]; 2],
    /// Outward unit normal of the slave segment.
    pub normal: [Ad8; 2],
    /// Weighted gap contributions `g~_j`.
    pub gap: [Ad8; 2],
    /// Gap `g` at `lo` and at `hi` (values).
    pub end_gaps: [f64; 2],
}

type V = [Ad8; 2];

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot(a: V, b: V) -> Ad8 {
    a[0] * b[0] + a[1] * b[1]
}

/// Smallest `|xi_c - xi_d| L / L_m` accepted: a master segment (nearly)
/// perpendicular to the slave one projects on a point.
const MIN_PROJECTED: f64 = 1e-6;

/// The mortar integrals of slave segment `[x_a, x_b]` against master
/// segment `[x_c, x_d]` (`x = [x_a, x_b, x_c, x_d]`), rows weighted by the
/// functions of `basis`; `None` when the master segment does not face the
/// slave one or its projection misses it.
pub fn segment_pair(x: [[f64; 2]; 4], weight: Weight, basis: Basis) -> Option<MortarSegment> {
    let p: [V; 4] =
        std::array::from_fn(|k| [Ad8::var(x[k][0], 2 * k), Ad8::var(x[k][1], 2 * k + 1)]);
    let [xa, xb, xc, xd] = p;
    let e = sub(xb, xa);
    let len = dot(e, e).sqrt();
    if len.v.is_nan() || len.v <= 0.0 {
        return None;
    }
    let t = [e[0] / len, e[1] / len];
    let n = [t[1], -t[0]];
    let xi_c = dot(sub(xc, xa), t) / len;
    let xi_d = dot(sub(xd, xa), t) / len;
    let em = sub(xd, xc);
    let len_m = dot(em, em).sqrt().v;
    let projected = (xi_c.v - xi_d.v) * len.v;
    if projected.is_nan() || projected <= MIN_PROJECTED * len_m {
        return None;
    }
    let lo = xi_d.max(Ad8::cst(0.0));
    let hi = xi_c.min(Ad8::cst(1.0));
    if hi.v.is_nan() || hi.v <= lo.v {
        return None;
    }
    let dc = dot(sub(xc, xa), n);
    let dd = dot(sub(xd, xa), n);
    let span = hi - lo;
    let mut d = [[Ad8::cst(0.0); 2]; 2];
    let mut m = [[Ad8::cst(0.0); 2]; 2];
    let g_at = |xi: Ad8| {
        let eta = (xi - xi_c) / (xi_d - xi_c);
        (dc * (-eta + 1.0) + dd * eta, eta)
    };
    let coef = dual_coefficients(basis, weight, xa[0], xb[0]);
    for s in GAUSS {
        let xi = lo + span * s;
        let (_, eta) = g_at(xi);
        let w = weight_at(weight, xa[0], xb[0], xi);
        // Gauss weight 1/2 on [0, 1] of the mortar segment, ds = L dxi
        let jw = span * len * w * 0.5;
        let ns = [-xi + 1.0, xi];
        let psi: [Ad8; 2] = std::array::from_fn(|j| coef[j][0] * ns[0] + coef[j][1] * ns[1]);
        let nm = [-eta + 1.0, eta];
        for j in 0..2 {
            for k in 0..2 {
                d[j][k] += psi[j] * ns[k] * jw;
                m[j][k] += psi[j] * nm[k] * jw;
            }
        }
    }
    let gap = std::array::from_fn(|j| {
        let mut v = V::default();
        for c in 0..2 {
            v[c] = m[j][0] * xc[c] + m[j][1] * xd[c] - d[j][0] * xa[c] - d[j][1] * xb[c];
        }
        dot(v, n)
    });
    Some(MortarSegment {
        lo: lo.v,
        hi: hi.v,
        d,
        m,
        normal: n,
        gap,
        end_gaps: [g_at(lo).0.v, g_at(hi).0.v],
    })
}

impl Default for Ad8 {
    fn default() -> Self {
        Ad8::cst(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Slave on y = 0 walking -x (body below), master above walking +x.
    fn flat(offset: f64, gap: f64) -> [[f64; 2]; 4] {
        [[1.0, 0.0], [0.0, 0.0], [offset, gap], [offset + 0.7, gap]]
    }

    #[test]
    fn flat_overlap_gives_the_overlap_integrals() {
        // slave [0, 1] (xi runs from x = 1 to x = 0), master [0.2, 0.9]
        // at gap 0.1: mortar segment xi in [0.1, 0.8]
        let s = segment_pair(flat(0.2, 0.1), Weight::Thickness(2.0), Basis::Standard).unwrap();
        assert!((s.lo - 0.1).abs() < 1e-14 && (s.hi - 0.8).abs() < 1e-14);
        let total: f64 = s.d.iter().flatten().map(|v| v.v).sum();
        assert!((total - 2.0 * 0.7).abs() < 1e-14);
        let total_m: f64 = s.m.iter().flatten().map(|v| v.v).sum();
        assert!((total_m - 2.0 * 0.7).abs() < 1e-14);
        // uniform gap: g~_j = 0.1 * sum_k D_jk
        for j in 0..2 {
            let dj = s.d[j][0].v + s.d[j][1].v;
            assert!((s.gap[j].v - 0.1 * dj).abs() < 1e-14);
        }
        assert_eq!(s.normal[0].v, 0.0);
        assert_eq!(s.normal[1].v, 1.0);
        // a master walking the same way as the slave does not face it
        let mut back = flat(0.2, 0.1);
        back.swap(2, 3);
        assert!(segment_pair(back, Weight::Thickness(1.0), Basis::Standard).is_none());
        // a master beside the slave misses it
        assert!(segment_pair(flat(1.5, 0.1), Weight::Thickness(1.0), Basis::Dual).is_none());
    }

    #[test]
    fn axisymmetric_weight_integrates_the_ring() {
        // slave from r = 2 to r = 1 on z = 0, master covering it
        let x = [[2.0, 0.0], [1.0, 0.0], [0.5, 0.0], [3.0, 0.0]];
        let s = segment_pair(x, Weight::Axisymmetric, Basis::Standard).unwrap();
        let total: f64 = s.d.iter().flatten().map(|v| v.v).sum();
        assert!((total - PI * (4.0 - 1.0)).abs() < 1e-13);
        // D is the consistent ring mass matrix: row sums are the
        // tributary areas 2 pi L (2 r_a + r_b) / 6
        let da = s.d[0][0].v + s.d[0][1].v;
        assert!((da - 2.0 * PI * (4.0 + 1.0) / 6.0).abs() < 1e-13);
    }

    fn pair_coords() -> impl Strategy<Value = [[f64; 2]; 4]> {
        (
            -0.5f64..0.5,
            -0.3f64..0.3,
            0.0f64..std::f64::consts::TAU,
            -0.3f64..0.3,
            0.3f64..1.4,
            -0.2f64..0.2,
            0.5f64..1.5,
        )
            .prop_map(|(_, tilt, rot, g, lm, shift, ls)| {
                let (c, s) = (rot.cos(), rot.sin());
                let r = |p: [f64; 2]| [c * p[0] - s * p[1], s * p[0] + c * p[1]];
                let xa = r([ls, 0.0]);
                let xb = r([0.0, 0.0]);
                let mc = [shift, g];
                let md = [shift + lm * tilt.cos(), g + lm * tilt.sin()];
                [xa, xb, r(mc), r(md)]
            })
    }

    /// Slave segment from `(ra, 0)` to `(rb, 0)`, `ra > rb` (walking -x:
    /// body below), under a master walking +x that covers it, whose gap is
    /// `g0 + g1 x`.
    fn covered(ra: f64, rb: f64, g0: f64, g1: f64) -> [[f64; 2]; 4] {
        assert!(ra > rb);
        let (lo, hi) = (rb - 0.5, ra + 0.5);
        [[ra, 0.0], [rb, 0.0], [lo, g0 + g1 * lo], [hi, g0 + g1 * hi]]
    }

    #[test]
    fn dual_functions_are_biorthogonal_and_d_is_diagonal() {
        for (weight, ra, rb) in [
            (Weight::Thickness(1.5), 2.0, 1.0),
            (Weight::Axisymmetric, 2.0, 1.0),
            (Weight::Axisymmetric, 1.0, 0.0),
            (Weight::Axisymmetric, 3.0, 2.9),
        ] {
            let a = dual_coefficients(Basis::Dual, weight, Ad8::cst(ra), Ad8::cst(rb));
            let w = |xi: f64| match weight {
                Weight::Thickness(t) => t,
                Weight::Axisymmetric => 2.0 * PI * (ra * (1.0 - xi) + rb * xi),
            };
            // int psi_j N_k w dxi by a 3-point Gauss rule (independent of
            // the 2-point rule of the code)
            let g3 = [
                (0.5 - 0.5 * 0.6f64.sqrt(), 5.0 / 18.0),
                (0.5, 8.0 / 18.0),
                (0.5 + 0.5 * 0.6f64.sqrt(), 5.0 / 18.0),
            ];
            for j in 0..2 {
                for k in 0..2 {
                    let (mut bi, mut nn) = (0.0, 0.0);
                    for (xi, gw) in g3 {
                        let n = [1.0 - xi, xi];
                        let psi = a[j][0].v * n[0] + a[j][1].v * n[1];
                        bi += psi * n[k] * w(xi) * gw;
                        nn += n[j] * w(xi) * gw;
                    }
                    let expected = if j == k { nn } else { 0.0 };
                    assert!(
                        (bi - expected).abs() < 1e-14 * nn.abs().max(1.0),
                        "{weight:?} {j}{k}: {bi} vs {expected}"
                    );
                }
            }
            // through segment_pair: D diagonal, its diagonal the lumped
            // (row-sum) mass, M rows summing to D's
            let x = covered(ra, rb, 0.1, 0.0);
            let s = segment_pair(x, weight, Basis::Dual).unwrap();
            let std = segment_pair(x, weight, Basis::Standard).unwrap();
            for j in 0..2 {
                let k = 1 - j;
                let scale = std.d[j][j].v;
                assert!(
                    s.d[j][k].v.abs() < 1e-14 * scale,
                    "{weight:?}: D_{j}{k} = {}",
                    s.d[j][k].v
                );
                let lumped = std.d[j][0].v + std.d[j][1].v;
                assert!((s.d[j][j].v - lumped).abs() < 1e-14 * lumped);
                assert!((s.m[j][0].v + s.m[j][1].v - lumped).abs() < 1e-13 * lumped);
            }
        }
        // the constant-weight duals: psi_a = 2 N_a - N_b
        let a = dual_coefficients(
            Basis::Dual,
            Weight::Thickness(1.0),
            Ad8::cst(0.0),
            Ad8::cst(0.0),
        );
        assert_eq!(
            [[a[0][0].v, a[0][1].v], [a[1][0].v, a[1][1].v]],
            [[2.0, -1.0], [-1.0, 2.0]]
        );
    }

    #[test]
    fn dual_nodal_gap_is_the_nodal_value_of_a_linear_gap() {
        // gap 0.1 + 0.05 x under a covered slave segment: g~_j / D_jj is
        // the gap at node j (dual); the standard average is not
        for weight in [Weight::Thickness(1.0), Weight::Axisymmetric] {
            let (ra, rb) = (2.0, 1.0);
            let x = covered(ra, rb, 0.1, 0.05);
            let s = segment_pair(x, weight, Basis::Dual).unwrap();
            for (j, r) in [(0, ra), (1, rb)] {
                let g = s.gap[j].v / s.d[j][j].v;
                assert!(
                    (g - (0.1 + 0.05 * r)).abs() < 1e-13,
                    "{weight:?} node {j}: {g}"
                );
            }
            let st = segment_pair(x, weight, Basis::Standard).unwrap();
            let g = st.gap[0].v / (st.d[0][0].v + st.d[0][1].v);
            assert!((g - (0.1 + 0.05 * ra)).abs() > 1e-3);
        }
    }

    proptest! {
        #[test]
        fn integrals_match_finite_differences(x in pair_coords(), dual in proptest::bool::ANY) {
            let w = Weight::Axisymmetric;
            let basis = if dual { Basis::Dual } else { Basis::Standard };
            let x = x.map(|p| [p[0] + 2.0, p[1]]);
            let Some(s) = segment_pair(x, w, basis) else { return Ok(()) };
            // stay away from the kinks of the segmentation
            prop_assume!(s.lo > 1e-4 || s.lo == 0.0);
            prop_assume!(s.hi < 1.0 - 1e-4 || s.hi == 1.0);
            let h = 1e-7;
            for k in 0..8 {
                let mut xp = x;
                let mut xm = x;
                xp[k / 2][k % 2] += h;
                xm[k / 2][k % 2] -= h;
                let (Some(p), Some(m)) = (segment_pair(xp, w, basis), segment_pair(xm, w, basis)) else {
                    continue;
                };
                prop_assume!((p.lo == 0.0) == (s.lo == 0.0) && (m.lo == 0.0) == (s.lo == 0.0));
                prop_assume!((p.hi == 1.0) == (s.hi == 1.0) && (m.hi == 1.0) == (s.hi == 1.0));
                for j in 0..2 {
                    let fd = (p.gap[j].v - m.gap[j].v) / (2.0 * h);
                    prop_assert!((fd - s.gap[j].d[k]).abs() < 1e-6 * (1.0 + fd.abs()), "gap {j} var {k}: {fd} vs {}", s.gap[j].d[k]);
                    for l in 0..2 {
                        let fd = (p.d[j][l].v - m.d[j][l].v) / (2.0 * h);
                        prop_assert!((fd - s.d[j][l].d[k]).abs() < 1e-6 * (1.0 + fd.abs()));
                        let fd = (p.m[j][l].v - m.m[j][l].v) / (2.0 * h);
                        prop_assert!((fd - s.m[j][l].d[k]).abs() < 1e-6 * (1.0 + fd.abs()));
                    }
                }
            }
        }
    }
}
