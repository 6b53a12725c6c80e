//! Normal smoothing of a deformable master surface (2D, `smoothing =
//! nodal`; issue 18, seed "the normal vector is smoothed using various
//! equations involving the gaps, the angle and the projections of the
//! node").
//!
//! The faceted master has a normal that jumps at every master node: a
//! slave node over a master node switches segment from one iteration to the
//! next, the force changes direction, Newton cycles. Here one continuous
//! normal field replaces it:
//!
//! - nodal normal `nu_k` of master node `k`: the unit mean of the unit
//!   normals of its two segments (the segment normal at a free end);
//! - at a free end on a symmetry line of its body or on the axis `r = 0`
//!   of an axisymmetric model ([`super::symmetry`]: the mirrored half's
//!   segment is not in the model) the end segment's normal is tilted by
//!   half a segment angle off the whole's mean normal, which lies in the
//!   line by symmetry: `nu_k = P n / |P n|`, `P` the constant projection
//!   that removes the coordinate across the line (the radial one at `r =
//!   0`), i.e. the unit vector along the line pointing out of the body
//!   (the whole's nodal normal there). `P` is constant, so the
//!   derivatives below go through it unchanged;
//! - along segment `x_1 -> x_2`: `m(xi) = (1 - xi) nu_1 + xi nu_2`,
//!   `n(xi) = m / |m|`, the point `x(xi) = (1 - xi) x_1 + xi x_2`;
//! - projection of the slave node `x_s`: the `xi` where `x_s - x(xi)` is
//!   along `n(xi)`, `c(xi) = (x_s - x(xi)) x m(xi) = 0` (quadratic in
//!   `xi`, solved by Newton from the faceted projection);
//! - gap `g = (x_s - x(xi)) . n(xi)`.
//!
//! At a master node both segments give `n = nu_k` and the same point: gap
//! and normal are continuous along the surface. The normal force `R` acts
//! along the smoothed normal: `R n` on the slave, `-(1 - xi) R n` and `-xi
//! R n` on the segment ends (`f = R B`, `B = [n, 0, -(1 - xi) n, -xi n,
//! 0]` over `[x_s, x_0, x_1, x_2, x_3]`, `x_0`, `x_3` the far nodes of the
//! neighbouring segments, which `nu_1`, `nu_2` depend on). The forces sum
//! to zero and so does their moment (`x_s - x(xi) = g n` is along the
//! force), and they are continuous where the slave passes a master node.
//! (The gradient of `g` itself is not: the zero level set of `g` is still
//! the faceted polyline, so a force `R dg/dx` would jump like the faceted
//! normal.) The tangent `K = -dR/dg B (dg/dx)^T - R dB/dx` is exact (not
//! symmetric: the solver factorizes with LU), from dual numbers carried
//! through one Newton step of the projection at its solution (which makes
//! `d xi / d x` exact). The same gap decides contact, gives the force and
//! the reported pressure, and the same normal gives the friction basis:
//! the friction force acts along `tau = (-n_y, n_x)` of `n(xi)`
//! ([`super::friction_segment::respond_smoothed`], over the same 10
//! coordinates, [`dual`]).

use super::mortar::ad::Ad;

/// Variables: `[x_s, x_0, x_1, x_2, x_3]`, two coordinates each.
pub const N: usize = 10;

/// A value with its gradient over the [`N`] coordinates.
pub type Ad10 = Ad<N>;

/// Scalar operations of the projection, for `f64` and [`Ad10`].
pub trait Scalar:
    Copy
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::Mul<Output = Self>
    + std::ops::Div<Output = Self>
{
    /// A constant.
    fn of(v: f64) -> Self;
    /// Square root.
    fn root(self) -> Self;
    /// The value.
    fn val(&self) -> f64;
}

impl Scalar for f64 {
    fn of(v: f64) -> Self {
        v
    }
    fn root(self) -> Self {
        self.sqrt()
    }
    fn val(&self) -> f64 {
        *self
    }
}

impl Scalar for Ad10 {
    fn of(v: f64) -> Self {
        Ad::cst(v)
    }
    fn root(self) -> Self {
        self.sqrt()
    }
    fn val(&self) -> f64 {
        self.v
    }
}

type V<T> = [T; 2];

fn sub<T: Scalar>(a: V<T>, b: V<T>) -> V<T> {
    [a[0] - b[0], a[1] - b[1]]
}

fn cross<T: Scalar>(a: V<T>, b: V<T>) -> T {
    a[0] * b[1] - a[1] * b[0]
}

fn dot<T: Scalar>(a: V<T>, b: V<T>) -> T {
    a[0] * b[0] + a[1] * b[1]
}

fn unit<T: Scalar>(a: V<T>) -> V<T> {
    let l = dot(a, a).root();
    [a[0] / l, a[1] / l]
}

/// Unit outward normal of segment `a -> b` (right of the walk).
fn seg_normal<T: Scalar>(a: V<T>, b: V<T>) -> V<T> {
    let d = sub(b, a);
    unit([d[1], T::of(0.0) - d[0]])
}

/// Coordinates removed from the nodal normals at the two ends of a
/// segment, `[at x_1, at x_2]` (a node on a symmetry line or the axis,
/// [`super::symmetry`]); [`NO_SYMMETRY`] elsewhere.
pub type Symmetry = [[bool; 2]; 2];

/// No coordinate removed at either end.
pub const NO_SYMMETRY: Symmetry = [[false; 2]; 2];

/// Nodal normal at `x` between segments `p -> x` and `x -> q` (either may
/// be missing: the other's normal), with the coordinates `sym` removed and
/// renormalized (kept whole where that leaves nothing: a segment lying in
/// its symmetry line).
fn nodal<T: Scalar>(p: Option<V<T>>, x: V<T>, q: Option<V<T>>, sym: [bool; 2]) -> Option<V<T>> {
    let n = match (p, q) {
        (Some(p), Some(q)) => {
            let (a, b) = (seg_normal(p, x), seg_normal(x, q));
            let s = [a[0] + b[0], a[1] + b[1]];
            // a surface folded back onto itself has no mean normal
            (dot(s, s).val() > 1e-12).then(|| unit(s))
        }
        (Some(p), None) => Some(seg_normal(p, x)),
        (None, Some(q)) => Some(seg_normal(x, q)),
        (None, None) => None,
    }?;
    if sym == [false; 2] {
        return Some(n);
    }
    let z = T::of(0.0);
    let m = [if sym[0] { z } else { n[0] }, if sym[1] { z } else { n[1] }];
    Some(if dot(m, m).val() > 1e-12 { unit(m) } else { n })
}

/// One smoothed segment `x_1 -> x_2` with the slave node and the nodal
/// normals at its ends.
#[derive(Debug, Clone, Copy)]
pub struct Patch<T> {
    /// Slave node.
    pub xs: V<T>,
    /// First end.
    pub x1: V<T>,
    /// Second end.
    pub x2: V<T>,
    /// Nodal normals at `x_1`, `x_2`.
    pub nu: [V<T>; 2],
}

impl<T: Scalar> Patch<T> {
    /// The patch of coordinates `[x_s, x_0, x_1, x_2, x_3]` (`x_0` unused
    /// unless `has0`, `x_3` unless `has3`), the nodal normals at `x_1`,
    /// `x_2` without the coordinates `sym`; `None` for a degenerate
    /// segment or a surface folded onto itself.
    pub fn new(x: [V<T>; 5], has0: bool, has3: bool, sym: Symmetry) -> Option<Self> {
        let [xs, x0, x1, x2, x3] = x;
        let d = sub(x2, x1);
        if dot(d, d).val().is_nan() || dot(d, d).val() <= 0.0 {
            return None;
        }
        let nu1 = nodal(has0.then_some(x0), x1, Some(x2), sym[0])?;
        let nu2 = nodal(Some(x1), x2, has3.then_some(x3), sym[1])?;
        Some(Patch {
            xs,
            x1,
            x2,
            nu: [nu1, nu2],
        })
    }

    /// The point `x(xi)` and the unnormalized normal `m(xi)`.
    fn at(&self, xi: T) -> (V<T>, V<T>) {
        let w = T::of(1.0) - xi;
        let x = [
            w * self.x1[0] + xi * self.x2[0],
            w * self.x1[1] + xi * self.x2[1],
        ];
        let m = [
            w * self.nu[0][0] + xi * self.nu[1][0],
            w * self.nu[0][1] + xi * self.nu[1][1],
        ];
        (x, m)
    }

    /// `c(xi)` and `c'(xi)`.
    fn residual(&self, xi: T) -> (T, T) {
        let (x, m) = self.at(xi);
        let d = sub(self.xs, x);
        let c = cross(d, m);
        let dc = cross(sub(self.x1, self.x2), m) + cross(d, sub(self.nu[1], self.nu[0]));
        (c, dc)
    }

    /// One Newton step of the projection from `xi`.
    fn step(&self, xi: T) -> Option<T> {
        let (c, dc) = self.residual(xi);
        (dc.val().abs() > 0.0 && dc.val().is_finite()).then(|| xi - c / dc)
    }

    /// Gap and unit normal at `xi`.
    pub fn gap(&self, xi: T) -> (T, V<T>) {
        let (x, m) = self.at(xi);
        let n = unit(m);
        (dot(sub(self.xs, x), n), n)
    }
}

/// Solves the projection in `f64` from `xi0` (the faceted projection).
pub fn project(p: &Patch<f64>, xi0: f64) -> Option<f64> {
    let mut xi = xi0;
    for _ in 0..30 {
        let next = p.step(xi)?;
        if !next.is_finite() || next.abs() > 1e3 {
            return None;
        }
        let done = (next - xi).abs() <= 1e-15 * (1.0 + xi.abs());
        xi = next;
        if done {
            return Some(xi);
        }
    }
    // round-off may keep the last bits moving: accept a zero residual
    let (c, dc) = p.residual(xi);
    (c.abs() <= 1e-13 * dc.abs()).then_some(xi)
}

/// A smoothed projection with its derivatives over `[x_s, x_0, x_1, x_2,
/// x_3]`.
#[derive(Debug, Clone, Copy)]
pub struct Smoothed {
    /// Parameter on the segment (0 at `x_1`).
    pub xi: f64,
    /// Unit normal `n(xi)`.
    pub normal: [f64; 2],
    /// The gap and `dg/dx`.
    pub gap: Ad10,
    /// `B = [n, 0, -(1 - xi) n, -xi n, 0]` and `dB/dx`: the force per unit
    /// normal force.
    pub b: [Ad10; N],
}

/// The smoothed projection in dual numbers over `[x_s, x_0, x_1, x_2,
/// x_3]` (the friction of [`super::friction_segment::respond_smoothed`]
/// carries them through its return map).
#[derive(Debug, Clone, Copy)]
pub struct DualProjection {
    /// The coordinates, seeded.
    pub x: [[Ad10; 2]; 5],
    /// `xi(x)`.
    pub xi: Ad10,
    /// The point `x(xi)` of the segment.
    pub point: [Ad10; 2],
    /// The unit normal `n(xi)`.
    pub normal: [Ad10; 2],
    /// The gap `(x_s - x(xi)) . n(xi)`.
    pub gap: Ad10,
}

/// The projection of `x[0]` (slave) on segment `x[2] -> x[3]` with
/// neighbours `x[1]` (if `has0`) and `x[4]` (if `has3`), the nodal normals
/// without the coordinates `sym`, in dual numbers, at the solved parameter
/// `xi` (from [`project`]): one Newton step in dual numbers from the
/// solution gives the exact `d xi / d x`.
pub fn dual(
    x: [[f64; 2]; 5],
    has0: bool,
    has3: bool,
    sym: Symmetry,
    xi: f64,
) -> Option<DualProjection> {
    let mut v = [[Ad10::cst(0.0); 2]; 5];
    for (k, p) in x.iter().enumerate() {
        for c in 0..2 {
            v[k][c] = Ad10::var(p[c], 2 * k + c);
        }
    }
    let p = Patch::new(v, has0, has3, sym)?;
    let t = p.step(Ad10::cst(xi))?;
    let (point, _) = p.at(t);
    let (gap, normal) = p.gap(t);
    Some(DualProjection {
        x: v,
        xi: t,
        point,
        normal,
        gap,
    })
}

/// The smoothed gap of `x[0]` (slave) against segment `x[2] -> x[3]` with
/// neighbours `x[1]` (if `has0`) and `x[4]` (if `has3`), the nodal normals
/// without the coordinates `sym`, at the solved parameter `xi` (from
/// [`project`]), with its exact derivatives ([`dual`]).
pub fn differentiate(
    x: [[f64; 2]; 5],
    has0: bool,
    has3: bool,
    sym: Symmetry,
    xi: f64,
) -> Option<Smoothed> {
    let DualProjection {
        xi: t,
        normal: n,
        gap: g,
        ..
    } = dual(x, has0, has3, sym, xi)?;
    let w1 = Ad10::cst(1.0) - t;
    let z = Ad10::cst(0.0);
    let b = [
        n[0],
        n[1],
        z,
        z,
        z - w1 * n[0],
        z - w1 * n[1],
        z - t * n[0],
        z - t * n[1],
        z,
        z,
    ];
    Some(Smoothed {
        xi: t.v,
        normal: [n[0].v, n[1].v],
        gap: g,
        b,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn pts(x: &[f64; 10]) -> [[f64; 2]; 5] {
        let c = |k: usize| [x[2 * k], x[2 * k + 1]];
        [c(0), c(1), c(2), c(3), c(4)]
    }

    fn solve(x: &[f64; 10], has0: bool, has3: bool, sym: Symmetry) -> Option<Smoothed> {
        let p = Patch::new(pts(x), has0, has3, sym)?;
        let xi = project(&p, 0.5)?;
        differentiate(pts(x), has0, has3, sym, xi)
    }

    #[test]
    fn flat_surface_gives_the_segment_gap_and_a_kink_a_continuous_one() {
        // flat: nodal normals = segment normal (walk -x, body below: +y)
        let x = [0.3, 0.2, 2.0, 0.0, 1.0, 0.0, 0.0, 0.0, -1.0, 0.0];
        let s = solve(&x, true, true, NO_SYMMETRY).unwrap();
        assert!((s.gap.v - 0.2).abs() < 1e-15 && (s.xi - 0.7).abs() < 1e-15);
        // a kink at (0, 0): a node on the vertex's nodal normal projects
        // on the vertex from both segments, with the same gap and normal
        let (a, v, b) = ([1.0, 0.0], [0.0, 0.0], [-1.0, 0.2]);
        let nv = Patch::new([v, [2.0, 0.0], a, v, b], true, true, NO_SYMMETRY)
            .unwrap()
            .nu[1];
        let xs = [0.05 * nv[0], 0.05 * nv[1]];
        let p1 = Patch::new([xs, [2.0, 0.0], a, v, b], true, true, NO_SYMMETRY).unwrap();
        let p2 = Patch::new([xs, a, v, b, [-2.0, 0.4]], true, true, NO_SYMMETRY).unwrap();
        let xi1 = project(&p1, 0.5).unwrap();
        let xi2 = project(&p2, 0.5).unwrap();
        assert!(
            (xi1 - 1.0).abs() < 1e-12 && xi2.abs() < 1e-12,
            "{xi1} {xi2}"
        );
        let (g1, n1) = p1.gap(xi1);
        let (g2, n2) = p2.gap(xi2);
        assert!((g1 - 0.05).abs() < 1e-12 && (g2 - 0.05).abs() < 1e-12);
        assert!((n1[0] - n2[0]).abs() < 1e-12 && (n1[1] - n2[1]).abs() < 1e-12);
    }

    /// A quarter circle of radius 1 about `(0, 1)` from the axis node
    /// `(0, 0)` (body above, walked +x): the end segment's normal is tilted
    /// by half its angle; with the axis coordinate removed the nodal normal
    /// at the axis node is `-y`, so a node on the axis below it projects on
    /// it at the gap of its distance, as on the mirrored whole.
    #[test]
    fn a_free_end_on_a_symmetry_line_gets_the_mirrored_normal() {
        let arc = |k: f64| {
            let t = k * std::f64::consts::PI / 32.0;
            [t.sin(), 1.0 - t.cos()]
        };
        let xs = [0.0, -0.01];
        let x = [xs, arc(0.0), arc(0.0), arc(1.0), arc(2.0)];
        let plain = Patch::new(x, false, true, NO_SYMMETRY).unwrap();
        let half = std::f64::consts::PI / 64.0;
        // tilted by half the segment angle off -y
        assert!(
            (plain.nu[0][0] - half.sin()).abs() < 1e-15,
            "{:?}",
            plain.nu[0]
        );
        let sym = [[true, false], [false, false]];
        let p = Patch::new(x, false, true, sym).unwrap();
        assert_eq!(p.nu[0], [0.0, -1.0]);
        // the interior node's normal is untouched
        assert_eq!(p.nu[1], plain.nu[1]);
        let xi = project(&p, 0.5).unwrap();
        let (g, n) = p.gap(xi);
        assert!(xi.abs() < 1e-15 && (g - 0.01).abs() < 1e-15, "{xi} {g}");
        assert!(n[0].abs() < 1e-15 && (n[1] + 1.0).abs() < 1e-15);
        // faceted end normal: the foot is off the axis node, the gap off
        let xi = project(&plain, 0.5).unwrap();
        let (g, _) = plain.gap(xi);
        assert!(xi < -1e-3 && (g - 0.01).abs() > 1e-6, "{xi} {g}");
        // the derivatives: the axis node's normal is constant
        let d = differentiate(x, false, true, sym, 0.0).unwrap();
        assert!((d.gap.v - 0.01).abs() < 1e-15);
        // a segment lying in its symmetry line keeps its own normal
        let flat = [xs, [0.0, 0.0], [0.0, 0.0], [0.0, 1.0], [0.0, 2.0]];
        let f = Patch::new(flat, false, true, [[false, true], [false, false]]).unwrap();
        assert_eq!(f.nu[0], [1.0, 0.0]);
    }

    fn coords() -> impl Strategy<Value = ([f64; 10], bool, bool, Symmetry)> {
        (
            proptest::collection::vec(-0.15f64..0.15, 10),
            -0.2f64..1.2,
            -0.3f64..0.3,
            any::<bool>(),
            any::<bool>(),
            any::<bool>(),
            any::<bool>(),
        )
            .prop_map(|(w, xi, g, h0, h3, s1, s2)| {
                // a wavy master walked -x (body below), the slave near it
                let base = [2.0, 1.0, 0.0, -1.0];
                let mut x = [0.0; 10];
                for k in 1..5 {
                    x[2 * k] = base[k - 1] + w[2 * k];
                    x[2 * k + 1] = w[2 * k + 1];
                }
                x[0] = 1.0 - xi + w[0];
                x[1] = g + w[1];
                // x removed at either end or not: a symmetry line x =
                // const across the surface (y would be along it)
                let mask = |k: bool| [k, false];
                (x, h0, h3, [mask(s1), mask(s2)])
            })
    }

    proptest! {
        #[test]
        fn gap_and_force_derivatives_match_finite_differences((x, h0, h3, sym) in coords()) {
            let Some(s) = solve(&x, h0, h3, sym) else { return Ok(()); };
            prop_assume!((-0.5..1.5).contains(&s.xi));
            let e = 1e-6;
            for j in 0..N {
                let (mut xp, mut xm) = (x, x);
                xp[j] += e;
                xm[j] -= e;
                let (Some(sp), Some(sm)) = (solve(&xp, h0, h3, sym), solve(&xm, h0, h3, sym)) else {
                    continue;
                };
                let fd = (sp.gap.v - sm.gap.v) / (2.0 * e);
                prop_assert!((fd - s.gap.d[j]).abs() < 1e-6 * (1.0 + fd.abs()),
                    "dg/dx{j}: {fd} vs {}", s.gap.d[j]);
                for i in 0..N {
                    let fd = (sp.b[i].v - sm.b[i].v) / (2.0 * e);
                    prop_assert!((fd - s.b[i].d[j]).abs() < 1e-6 * (1.0 + fd.abs()),
                        "dB{i}/dx{j}: {fd} vs {}", s.b[i].d[j]);
                }
            }
            // a translation leaves the gap unchanged
            let sum: f64 = (0..5).map(|k| s.gap.d[2 * k]).sum();
            prop_assert!(sum.abs() < 1e-10, "sum {sum}");
            // the forces R B: sum and moment zero
            for comp in 0..2 {
                let f: f64 = (0..5).map(|k| s.b[2 * k + comp].v).sum();
                prop_assert!(f.abs() < 1e-12, "force sum {f}");
            }
            let moment: f64 = (0..5)
                .map(|k| x[2 * k] * s.b[2 * k + 1].v - x[2 * k + 1] * s.b[2 * k].v)
                .sum();
            prop_assert!(moment.abs() < 1e-10, "moment {moment}");
        }
    }
}
