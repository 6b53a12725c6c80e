//! Kinematics of the node-to-segment contact element (seed slides,
//! "Contact between two deformable bodies", "Part I - Geometrical
//! aspects"): a slave node `x_s` against a straight master segment
//! `x_1 -> x_2` whose body lies on its left (outward normal to the right).
//!
//! With `a = x_2 - x_1`, `L = |a|`, `t = a / L`, `n = (t_y, -t_x)` and
//! `d = x_s - x_1`:
//!
//! - gap `g = d . n` (negative = penetration), projection parameter
//!   `xi = d . t / L` (0 at `x_1`, 1 at `x_2`);
//! - first variation (the projection point moves with the segment, its
//!   change cancels in `g` because `d - xi a` is normal to the segment):
//!   `dg = G . dx`, `G = [n, -(1 - xi) n, -xi n]` over `[x_s, x_1, x_2]`;
//! - second variation, with `T = [t, -(1 - xi) t, -xi t]` and
//!   `N0 = [0, -n, n]` (`N0 . dx = n . da`):
//!   `H = d2g/dx2 = -(N0 T^T + T N0^T) / L - g N0 N0^T / L^2`
//!   (symmetric; it carries the change of the projection point `d xi` and
//!   the rotation of the normal).
//!
//! A normal force `R >= 0` on the slave node (`R n`) derives from the gap,
//! so the element forces over the six dofs are `f = R G`: the master ends
//! receive `-(1 - xi) R n` and `-xi R n`. They sum to zero and so does
//! their moment (`x_s - (1 - xi) x_1 - xi x_2 = g n` is parallel to the
//! force). The tangent is `K = -df/dx = -(dR/dg) G G^T - R H`; for the
//! frictionless penalty `R = -alpha g` it is `alpha (G G^T + g H)`, the
//! Hessian of the potential `alpha g^2 / 2`, hence symmetric.
//!
//! `xi` outside `[0, 1]` is allowed here (the segment line extended): the
//! caller decides which projection to keep (see
//! [`super::node_to_segment`]).

use super::vec2::{dot, sub};

/// Projection of a slave node on the line of a master segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentProjection {
    /// Signed gap `g = (x_s - x_1) . n` (negative = penetration).
    pub gap: f64,
    /// Parameter of the projection, 0 at `x_1`, 1 at `x_2` (may lie
    /// outside `[0, 1]`).
    pub xi: f64,
    /// Unit outward normal of the segment (right of `x_1 -> x_2`).
    pub normal: [f64; 2],
    /// Unit tangent `(x_2 - x_1) / L`.
    pub tangent: [f64; 2],
    /// Current length `L` of the segment.
    pub length: f64,
    /// The projection is the segment's end at `xi` (0 or 1), a master
    /// vertex seen as a circle of radius 0: `g = s |x_s - x_v|`, `n =
    /// s (x_s - x_v) / |x_s - x_v|` (see [`SegmentProjection::corner`]).
    pub corner: bool,
}

impl SegmentProjection {
    /// Projects `xs` on the segment `x1 -> x2`; `None` for a degenerate
    /// (zero-length or non-finite) segment.
    pub fn new(xs: [f64; 2], x1: [f64; 2], x2: [f64; 2]) -> Option<Self> {
        let a = sub(x2, x1);
        let length = a[0].hypot(a[1]);
        if !(length.is_finite() && length > 0.0) {
            return None;
        }
        let t = [a[0] / length, a[1] / length];
        let n = [t[1], -t[0]];
        let d = sub(xs, x1);
        Some(SegmentProjection {
            gap: dot(d, n),
            xi: dot(d, t) / length,
            normal: n,
            tangent: t,
            length,
            corner: false,
        })
    }

    /// The end `x_v` of segment `x1 -> x2` at `xi_end` (0: `x1`, 1: `x2`)
    /// as the closest point of `xs`: a master vertex (kink) treated as a
    /// circle of radius 0, the distance function of the polyline in the
    /// wedge of a kink where no projection falls inside a segment. The gap
    /// is `g = s r`, `r = |x_s - x_v|`, `s` the side of the segment's line
    /// the node is on; the normal `n = s (x_s - x_v) / r` turns
    /// continuously from one segment's normal to the other's across the
    /// wedge, so gap and normal are continuous at the vertex (no jump of
    /// the force direction between the two segments). `G = [n, -n]` on
    /// `[x_s, x_v]` and `H = s t t^T / r` (`t` perpendicular to `n`) on the
    /// slave-slave and vertex-vertex blocks, minus that on the cross blocks.
    /// `None` when the node is on the vertex (within round-off of the
    /// segment length) or the segment is degenerate.
    pub fn corner(xs: [f64; 2], x1: [f64; 2], x2: [f64; 2], xi_end: f64) -> Option<Self> {
        Self::corner_on_side(xs, x1, x2, xi_end, None)
    }

    /// [`SegmentProjection::corner`] with the side `s` of the node given
    /// (`Some(1.0)`: outside the body, `Some(-1.0)`: inside) instead of
    /// read from the segment's line. In the wedge of a kink the side is
    /// the kink's: outside at a convex vertex, inside at a concave one
    /// (`node_to_segment::closest`). The line's side differs from it in a
    /// sliver of the wedge when the corner is not a right angle (a convex
    /// 88 degree corner: the node in front of one face and behind the
    /// other face's extension), and the two segments of the vertex then
    /// gave the same distance with opposite signs.
    pub fn corner_on_side(
        xs: [f64; 2],
        x1: [f64; 2],
        x2: [f64; 2],
        xi_end: f64,
        side: Option<f64>,
    ) -> Option<Self> {
        let line = SegmentProjection::new(xs, x1, x2)?;
        let xv = if xi_end < 0.5 { x1 } else { x2 };
        let d = sub(xs, xv);
        let r = d[0].hypot(d[1]);
        if r.is_nan() || r <= 1e-12 * line.length {
            return None;
        }
        let s = side.unwrap_or(if line.gap < 0.0 { -1.0 } else { 1.0 });
        let n = [s * d[0] / r, s * d[1] / r];
        Some(SegmentProjection {
            gap: s * r,
            xi: if xi_end < 0.5 { 0.0 } else { 1.0 },
            normal: n,
            tangent: [-n[1], n[0]],
            length: line.length,
            corner: true,
        })
    }

    /// Point of the segment line at `xi`.
    pub fn point(&self, x1: [f64; 2]) -> [f64; 2] {
        let s = self.xi * self.length;
        [x1[0] + s * self.tangent[0], x1[1] + s * self.tangent[1]]
    }

    /// `G = dg/dx` over `[x_s, x_1, x_2]` (6 dofs).
    pub fn gap_gradient(&self) -> [f64; 6] {
        let n = self.normal;
        let (w1, w2) = (1.0 - self.xi, self.xi);
        [n[0], n[1], -w1 * n[0], -w1 * n[1], -w2 * n[0], -w2 * n[1]]
    }

    /// `H = d2g/dx2` (6x6, symmetric), see the module documentation.
    pub fn gap_hessian(&self) -> [[f64; 6]; 6] {
        let (n, t) = (self.normal, self.tangent);
        if self.corner {
            // g = s r: d2g/dxs2 = s (I - e e^T) / r = t t^T / g
            let v = if self.xi < 0.5 { 1 } else { 2 };
            let mut h = [[0.0; 6]; 6];
            for (bi, si) in [(0, 1.0), (v, -1.0)] {
                for (bj, sj) in [(0, 1.0), (v, -1.0)] {
                    for a in 0..2 {
                        for b in 0..2 {
                            h[2 * bi + a][2 * bj + b] = si * sj * t[a] * t[b] / self.gap;
                        }
                    }
                }
            }
            return h;
        }
        let (w1, w2) = (1.0 - self.xi, self.xi);
        let tv = [t[0], t[1], -w1 * t[0], -w1 * t[1], -w2 * t[0], -w2 * t[1]];
        let n0 = [0.0, 0.0, -n[0], -n[1], n[0], n[1]];
        let l = self.length;
        let c = self.gap / (l * l);
        let mut h = [[0.0; 6]; 6];
        for i in 0..6 {
            for j in 0..6 {
                h[i][j] = -(n0[i] * tv[j] + tv[i] * n0[j]) / l - c * n0[i] * n0[j];
            }
        }
        h
    }

    /// Element forces `f = R G` and tangent `K = -df/dx = -dR/dg G G^T - R H`
    /// of a normal force `r` (>= 0, on the slave node along `n`) whose
    /// derivative with respect to the gap is `dr_dg`.
    pub fn element(&self, r: f64, dr_dg: f64) -> ([f64; 6], [[f64; 6]; 6]) {
        let g = self.gap_gradient();
        let mut f = [0.0; 6];
        for (fi, gi) in f.iter_mut().zip(&g) {
            *fi = r * gi;
        }
        let mut k = [[0.0; 6]; 6];
        if r == 0.0 && dr_dg == 0.0 {
            return (f, k);
        }
        let h = self.gap_hessian();
        for i in 0..6 {
            for j in 0..6 {
                k[i][j] = -dr_dg * g[i] * g[j] - r * h[i][j];
            }
        }
        (f, k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn split(x: &[f64; 6]) -> ([f64; 2], [f64; 2], [f64; 2]) {
        ([x[0], x[1]], [x[2], x[3]], [x[4], x[5]])
    }

    fn gap(x: &[f64; 6]) -> f64 {
        let (s, a, b) = split(x);
        SegmentProjection::new(s, a, b).unwrap().gap
    }

    /// Penalty element forces at `x` (`R = -alpha g` when closed).
    fn penalty_forces(x: &[f64; 6], alpha: f64) -> ([f64; 6], [[f64; 6]; 6]) {
        let (s, a, b) = split(x);
        let p = SegmentProjection::new(s, a, b).unwrap();
        p.element(
            (-alpha * p.gap).max(0.0),
            if p.gap < 0.0 { -alpha } else { 0.0 },
        )
    }

    fn element_coords() -> impl Strategy<Value = [f64; 6]> {
        (
            -0.3f64..1.3,
            -0.2f64..0.2,
            -0.2f64..0.2,
            -0.2f64..0.2,
            0.6f64..1.5,
            -0.4f64..0.4,
        )
            .prop_map(|(xi, g, ax, ay, bx, by)| {
                // slave near the segment (a, b), whatever the rotation
                let (a, b) = ([ax, ay], [bx, by]);
                let l = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
                let t = [(b[0] - a[0]) / l, (b[1] - a[1]) / l];
                let n = [t[1], -t[0]];
                let s = [
                    a[0] + xi * l * t[0] + g * n[0],
                    a[1] + xi * l * t[1] + g * n[1],
                ];
                [s[0], s[1], a[0], a[1], b[0], b[1]]
            })
    }

    #[test]
    fn flat_segment_gap_xi_normal() {
        let p = SegmentProjection::new([0.25, -0.1], [1.0, 0.0], [0.0, 0.0]).unwrap();
        // walking -x, body on the left (below): outward normal +y
        assert_eq!(p.normal, [0.0, 1.0]);
        assert!((p.gap + 0.1).abs() < 1e-15);
        assert!((p.xi - 0.75).abs() < 1e-15);
        assert!(SegmentProjection::new([0.0; 2], [1.0, 1.0], [1.0, 1.0]).is_none());
    }

    proptest! {
        #[test]
        fn gap_gradient_and_hessian_match_finite_differences(x in element_coords()) {
            let (s, a, b) = split(&x);
            let p = SegmentProjection::new(s, a, b).unwrap();
            let g = p.gap_gradient();
            let h = p.gap_hessian();
            let e = 1e-6;
            for j in 0..6 {
                let (mut xp, mut xm) = (x, x);
                xp[j] += e;
                xm[j] -= e;
                let fd = (gap(&xp) - gap(&xm)) / (2.0 * e);
                prop_assert!((fd - g[j]).abs() < 1e-7, "dg/dx{j}: {fd} vs {}", g[j]);
                let (sp, ap, bp) = split(&xp);
                let (sm, am, bm) = split(&xm);
                let gp = SegmentProjection::new(sp, ap, bp).unwrap().gap_gradient();
                let gm = SegmentProjection::new(sm, am, bm).unwrap().gap_gradient();
                for i in 0..6 {
                    let fd = (gp[i] - gm[i]) / (2.0 * e);
                    prop_assert!((fd - h[i][j]).abs() < 1e-6, "H{i}{j}: {fd} vs {}", h[i][j]);
                }
            }
        }

        #[test]
        fn corner_gap_gradient_and_hessian_match_finite_differences(
            x in element_coords(), end in 0usize..2
        ) {
            let corner = |x: &[f64; 6]| {
                let (s, a, b) = split(x);
                SegmentProjection::corner(s, a, b, end as f64)
            };
            let Some(p) = corner(&x) else { return Ok(()); };
            // away from the vertex (the distance is smooth there)
            prop_assume!(p.gap.abs() > 1e-3);
            let g = p.gap_gradient();
            let h = p.gap_hessian();
            let e = 1e-7;
            for j in 0..6 {
                let (mut xp, mut xm) = (x, x);
                xp[j] += e;
                xm[j] -= e;
                let (Some(cp), Some(cm)) = (corner(&xp), corner(&xm)) else { continue; };
                if cp.gap.signum() != cm.gap.signum() {
                    continue;
                }
                let fd = (cp.gap - cm.gap) / (2.0 * e);
                prop_assert!((fd - g[j]).abs() < 1e-6, "dg/dx{j}: {fd} vs {}", g[j]);
                let (gp, gm) = (cp.gap_gradient(), cm.gap_gradient());
                for i in 0..6 {
                    let fd = (gp[i] - gm[i]) / (2.0 * e);
                    prop_assert!((fd - h[i][j]).abs() < 1e-4 * (1.0 + h[i][j].abs()),
                        "H{i}{j}: {fd} vs {}", h[i][j]);
                }
            }
        }

        #[test]
        fn penalty_tangent_is_symmetric_and_minus_force_derivative(x in element_coords()) {
            let alpha = 7.0;
            let (_, k) = penalty_forces(&x, alpha);
            let e = 1e-7;
            for j in 0..6 {
                let (mut xp, mut xm) = (x, x);
                xp[j] += e;
                xm[j] -= e;
                // skip points where the status changes inside the stencil
                if gap(&xp).signum() != gap(&xm).signum() {
                    continue;
                }
                let (fp, _) = penalty_forces(&xp, alpha);
                let (fm, _) = penalty_forces(&xm, alpha);
                for i in 0..6 {
                    let fd = -(fp[i] - fm[i]) / (2.0 * e);
                    prop_assert!((fd - k[i][j]).abs() < 1e-5 * (1.0 + k[i][j].abs()),
                        "K{i}{j}: {fd} vs {}", k[i][j]);
                    prop_assert!((k[i][j] - k[j][i]).abs() < 1e-12 * (1.0 + k[i][j].abs()));
                }
            }
        }

        #[test]
        fn element_forces_are_in_force_and_moment_equilibrium(
            x in element_coords(), r in 0.0f64..10.0
        ) {
            let (s, a, b) = split(&x);
            let p = SegmentProjection::new(s, a, b).unwrap();
            let (f, _) = p.element(r, -1.0);
            let sum = [f[0] + f[2] + f[4], f[1] + f[3] + f[5]];
            prop_assert!(sum[0].abs() < 1e-12 && sum[1].abs() < 1e-12);
            let moment: f64 = [s, a, b]
                .iter()
                .enumerate()
                .map(|(k, p)| p[0] * f[2 * k + 1] - p[1] * f[2 * k])
                .sum();
            prop_assert!(moment.abs() < 1e-11, "moment {moment}");
            // the slave force is R n
            prop_assert!((f[0] - r * p.normal[0]).abs() < 1e-14);
        }
    }
}
