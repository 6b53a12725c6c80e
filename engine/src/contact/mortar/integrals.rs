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

/// Mortar integrals of one slave segment against one master segment.
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
/// segment `[x_c, x_d]` (`x = [x_a, x_b, x_c, x_d]`); `None` when the
/// master segment does not face the slave one or its projection misses it.
pub fn segment_pair(x: [[f64; 2]; 4], weight: Weight) -> Option<MortarSegment> {
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
    let r = 0.5 / 3f64.sqrt();
    for s in [0.5 - r, 0.5 + r] {
        let xi = lo + span * s;
        let (_, eta) = g_at(xi);
        let w = match weight {
            Weight::Thickness(th) => Ad8::cst(th),
            Weight::Axisymmetric => (xa[0] * (-xi + 1.0) + xb[0] * xi) * (2.0 * PI),
        };
        // Gauss weight 1/2 on [0, 1] of the mortar segment, ds = L dxi
        let jw = span * len * w * 0.5;
        let ns = [-xi + 1.0, xi];
        let nm = [-eta + 1.0, eta];
        for j in 0..2 {
            for k in 0..2 {
                d[j][k] += ns[j] * ns[k] * jw;
                m[j][k] += ns[j] * nm[k] * jw;
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
        let s = segment_pair(flat(0.2, 0.1), Weight::Thickness(2.0)).unwrap();
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
        assert!(segment_pair(back, Weight::Thickness(1.0)).is_none());
        // a master beside the slave misses it
        assert!(segment_pair(flat(1.5, 0.1), Weight::Thickness(1.0)).is_none());
    }

    #[test]
    fn axisymmetric_weight_integrates_the_ring() {
        // slave from r = 2 to r = 1 on z = 0, master covering it
        let x = [[2.0, 0.0], [1.0, 0.0], [0.5, 0.0], [3.0, 0.0]];
        let s = segment_pair(x, Weight::Axisymmetric).unwrap();
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

    proptest! {
        #[test]
        fn integrals_match_finite_differences(x in pair_coords()) {
            let w = Weight::Axisymmetric;
            let x = x.map(|p| [p[0] + 2.0, p[1]]);
            let Some(s) = segment_pair(x, w) else { return Ok(()) };
            // stay away from the kinks of the segmentation
            prop_assume!(s.lo > 1e-4 || s.lo == 0.0);
            prop_assume!(s.hi < 1.0 - 1e-4 || s.hi == 1.0);
            let h = 1e-7;
            for k in 0..8 {
                let mut xp = x;
                let mut xm = x;
                xp[k / 2][k % 2] += h;
                xm[k / 2][k % 2] -= h;
                let (Some(p), Some(m)) = (segment_pair(xp, w), segment_pair(xm, w)) else {
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
