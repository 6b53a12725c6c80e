//! Edges of a BREP tool: each face's boundary curves mapped onto its surface
//! (`E(t) = S(c(t))`, a *coedge*), and their closest points.
//!
//! With `c(t) = (u, v)`: `E' = S_u u' + S_v v'` and
//! `E'' = S_uu u'^2 + 2 S_uv u' v' + S_vv v'^2 + S_u u'' + S_v v''`.

use crate::nurbs::NurbsSurface;
use crate::trim::TrimCurve;
use crate::{Aabb, Vec3};

/// A face boundary curve seen in 3D.
#[derive(Debug, Clone, PartialEq)]
pub struct Coedge {
    /// Face holding the curve.
    pub face: usize,
    /// The curve in the face's parameter plane.
    pub curve: TrimCurve,
    /// The coedge of a neighbouring face along the same 3D curve, if any.
    pub partner: Option<usize>,
    /// A seam: the partner is on the same face (the two sides of a closed
    /// surface's parameter seam); not an edge of the tool.
    pub seam: bool,
    /// Zero length in 3D (a pole of the surface); not an edge of the tool.
    pub degenerate: bool,
    /// Vertex indices at the start and end.
    pub vertices: [usize; 2],
    /// Samples `(t, E(t))`, seeds of the projection.
    pub samples: Vec<(f64, Vec3)>,
    /// Box of the samples, grown by the chord error bound.
    pub bbox: Aabb,
    /// Length of the sample polyline.
    pub length: f64,
}

/// Point and derivatives of a coedge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeDerivs {
    /// `E(t)`.
    pub p: Vec3,
    /// `E'(t)`.
    pub d1: Vec3,
    /// `E''(t)`.
    pub d2: Vec3,
}

/// Closest point of a coedge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeFoot {
    /// Curve parameter.
    pub t: f64,
    /// Point and derivatives.
    pub derivs: EdgeDerivs,
    /// `|x - E|`.
    pub distance: f64,
    /// `Some(0)` / `Some(1)`: clamped at the start / end with the closest
    /// point beyond it (a vertex); `None`: an orthogonal foot.
    pub end: Option<usize>,
    /// Newton iterations.
    pub iterations: u32,
}

/// `E(t) = S(c(t))` with its derivatives.
pub fn eval(surface: &NurbsSurface, curve: &TrimCurve, t: f64) -> EdgeDerivs {
    let c = curve.eval(t);
    let s = surface.eval(c.p);
    let (u1, v1) = (c.d1.x, c.d1.y);
    EdgeDerivs {
        p: s.p,
        d1: s.su * u1 + s.sv * v1,
        d2: s.suu * (u1 * u1)
            + s.suv * (2.0 * u1 * v1)
            + s.svv * (v1 * v1)
            + s.su * c.d2.x
            + s.sv * c.d2.y,
    }
}

impl Coedge {
    /// The coedge of `curve` on face `face` of surface `surface`.
    pub fn new(face: usize, surface: &NurbsSurface, curve: TrimCurve) -> Self {
        let pieces = curve.pieces();
        let mut samples = Vec::new();
        for w in pieces.windows(2) {
            for i in 0..4 {
                let t = w[0] + (w[1] - w[0]) * i as f64 / 4.0;
                samples.push((t, eval(surface, &curve, t).p));
            }
        }
        let tl = *pieces.last().unwrap();
        samples.push((tl, eval(surface, &curve, tl).p));
        let length: f64 = samples.windows(2).map(|w| (w[1].1 - w[0].1).norm()).sum();
        // The curve between two samples stays within the chord's box grown
        // by the chord length (a generous bound for smooth pieces).
        let mut bbox = Aabb::empty();
        for w in samples.windows(2) {
            let l = (w[1].1 - w[0].1).norm();
            bbox = bbox.union(&Aabb::around(&[w[0].1, w[1].1]).inflated(0.5 * l));
        }
        Coedge {
            face,
            curve,
            partner: None,
            seam: false,
            degenerate: false,
            vertices: [0, 0],
            samples,
            bbox,
            length,
        }
    }

    /// Whether this coedge is an edge of the tool (not a seam, not a pole).
    pub fn is_edge(&self) -> bool {
        !self.seam && !self.degenerate
    }

    /// Closest point of the coedge to `x`: nearest sample, then Newton on
    /// `(E - x) . E' = 0` clamped to the parameter range.
    pub fn project(&self, surface: &NurbsSurface, x: &Vec3) -> EdgeFoot {
        let [t0, t1] = self.curve.domain();
        let mut best = 0;
        let mut bd = f64::INFINITY;
        for (i, (_, p)) in self.samples.iter().enumerate() {
            let d = (p - x).norm_squared();
            if d < bd {
                bd = d;
                best = i;
            }
        }
        let mut t = self.samples[best].0;
        let mut iterations = 0;
        let mut d = eval(surface, &self.curve, t);
        let mut r = d.p - x;
        let mut f = r.norm_squared();
        let span = t1 - t0;
        for _ in 0..50 {
            let g = r.dot(&d.d1);
            let h = d.d1.norm_squared() + r.dot(&d.d2);
            // At an end with the gradient pushing out: clamped.
            if (t <= t0 && g > 0.0) || (t >= t1 && g < 0.0) {
                break;
            }
            let sine = if f > 0.0 {
                g.abs() / (d.d1.norm() * f.sqrt())
            } else {
                0.0
            };
            if sine <= 1e-15 {
                break;
            }
            iterations += 1;
            let mut step = if h > 0.0 {
                -g / h
            } else {
                -g.signum() * 0.1 * span
            };
            let mut accepted = false;
            for _ in 0..60 {
                let tt = (t + step).clamp(t0, t1);
                let dt = eval(surface, &self.curve, tt);
                let rt = dt.p - x;
                let ft = rt.norm_squared();
                let gt = rt.dot(&dt.d1);
                if ft < f || (ft <= f * (1.0 + 1e-12) && gt.abs() < g.abs()) {
                    accepted = tt != t;
                    t = tt;
                    d = dt;
                    r = rt;
                    f = ft;
                    break;
                }
                step *= 0.5;
            }
            if !accepted {
                break;
            }
        }
        let g = r.dot(&d.d1);
        let push = 1e-12 * d.d1.norm() * f.sqrt();
        let end = if t <= t0 && g > push {
            Some(0)
        } else if t >= t1 && g < -push {
            Some(1)
        } else {
            None
        };
        EdgeFoot {
            t,
            derivs: d,
            distance: f.sqrt(),
            end,
            iterations,
        }
    }
}
