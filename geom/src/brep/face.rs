//! A face: a NURBS surface, optionally trimmed by an outer loop and holes in
//! its parameter plane, with the side of free space.

use crate::nurbs::{NurbsSurface, ProjectOptions, SurfaceFoot};
use crate::trim::{Boundary, Containment, Loop};
use crate::{offset, Aabb, FootKind, Projection, ProjectionError, Vec2, Vec3};

/// One face of a BREP tool.
#[derive(Debug, Clone, PartialEq)]
pub struct Face {
    /// The underlying surface.
    pub surface: NurbsSurface,
    /// The trimming boundary; `None`: the whole parameter rectangle.
    pub boundary: Option<Boundary>,
    /// `+1` when `S_u x S_v` points into free space, `-1` otherwise.
    pub orientation: f64,
    /// Bounding box (of the control net).
    pub bbox: Aabb,
}

impl Face {
    /// A face; `orientation` `+1` puts free space on the side of `S_u x S_v`.
    pub fn new(surface: NurbsSurface, boundary: Option<Boundary>, orientation: f64) -> Self {
        let bbox = surface.bounding_box();
        Face {
            surface,
            boundary,
            orientation: if orientation < 0.0 { -1.0 } else { 1.0 },
            bbox,
        }
    }

    /// Whether the parameter `uv` belongs to the face (parity test), and the
    /// number of rays drawn.
    pub fn contains(&self, uv: Vec2) -> (Containment, usize) {
        match &self.boundary {
            Some(b) => b.classify(uv),
            None => (Containment::Inside, 0),
        }
    }

    /// The boundary loops (the parameter rectangle when untrimmed).
    pub fn loops(&self) -> Vec<Loop> {
        match &self.boundary {
            Some(b) => std::iter::once(b.outer.clone())
                .chain(b.holes.iter().cloned())
                .collect(),
            None => {
                let [u, v] = self.surface.domain();
                vec![Loop::rectangle(u, v)]
            }
        }
    }

    /// Whether `uv` is near a singular point of the parameterisation (a
    /// pole): `|S_u x S_v| < 1e-4 (|S_u|^2 + |S_v|^2)`. There the normal and
    /// curvature computed from the derivatives lose digits (as `1e-16 /
    /// theta^2` at an angle `theta` from the pole), so they come from a ring
    /// around the pole instead.
    fn near_pole(&self, uv: Vec2) -> bool {
        let d = self.surface.eval_order(uv, 1);
        d.su.cross(&d.sv).norm() <= 1e-4 * (d.su.norm_squared() + d.sv.norm_squared())
    }

    /// Eight parameters at `delta` (fraction of the domain) from the pole
    /// near `uv`, spread over the other direction (around the pole when that
    /// direction is closed), and whether they surround it symmetrically.
    fn ring(&self, uv: Vec2, delta: f64) -> (Vec<Vec2>, bool) {
        let dom = self.surface.domain();
        for k in 0..2 {
            let len = dom[k][1] - dom[k][0];
            for e in 0..2 {
                if self.surface.degenerate[k][e] && (uv[k] - dom[k][e]).abs() <= 1e-2 * len {
                    let t = dom[k][e] + if e == 0 { delta } else { -delta } * len;
                    let o = 1 - k;
                    let [a, b] = dom[o];
                    let closed = self.surface.closed[o];
                    let ring = (0..8)
                        .map(|i| {
                            let mut q = uv;
                            q[k] = t;
                            q[o] = if closed {
                                a + (b - a) * i as f64 / 8.0
                            } else {
                                a + (b - a) * (i as f64 + 0.5) / 8.0
                            };
                            q
                        })
                        .collect();
                    return (ring, closed);
                }
            }
        }
        // A singular point that is not a known pole: one point towards the middle.
        let mut q = uv;
        for k in 0..2 {
            let len = dom[k][1] - dom[k][0];
            q[k] += (0.5 * (dom[k][0] + dom[k][1]) - uv[k]).signum() * delta * len;
        }
        (vec![q], false)
    }

    /// Average unit normal (unoriented) and `dn/dx` at gap `g` over a ring.
    fn ring_average(&self, ring: &[Vec2], g: f64) -> Option<(Vec3, crate::Mat3)> {
        let mut n = Vec3::zeros();
        let mut w = crate::Mat3::zeros();
        for q in ring {
            let d = self.surface.eval(*q);
            let nq = d.su.cross(&d.sv).normalize();
            n += nq;
            w += offset::surface(d.su, d.sv, d.suu, d.suv, d.svv, nq * self.orientation, g)?;
        }
        let k = ring.len() as f64;
        Some((n.normalize(), w / k))
    }

    /// Oriented unit normal at `uv` (free side); near a pole the average of
    /// the normals around it.
    pub fn normal(&self, uv: Vec2) -> Vec3 {
        if !self.near_pole(uv) {
            let d = self.surface.eval_order(uv, 1);
            return d.su.cross(&d.sv).normalize() * self.orientation;
        }
        let (ring, _) = self.ring(uv, 1e-3);
        let n: Vec3 = ring
            .iter()
            .map(|q| {
                let d = self.surface.eval_order(*q, 1);
                d.su.cross(&d.sv).normalize()
            })
            .sum();
        n.normalize() * self.orientation
    }

    /// The projection on the face's surface at an orthogonal foot `foot` of
    /// `x`: gap `n . (x - S)`, the oriented normal, `dn/dx` of the offset
    /// surface. Near a pole: the normal is `±(x - S) / |x - S|` (exact at an
    /// orthogonal foot) signed by the ring normal, and `dn/dx` the ring
    /// average extrapolated to the pole (Richardson on rings at 1e-3 and
    /// 2e-3 of the domain: O(1e-10) around the pole of a surface of
    /// revolution, where `dn/dx` is even in the distance to the axis; O(1e-6)
    /// at a collapsed edge that is not a pole of a closed direction).
    pub fn interior(
        &self,
        x: &Vec3,
        foot: &SurfaceFoot,
        entity: usize,
    ) -> Result<Projection, ProjectionError> {
        let p = foot.derivs.p;
        let singular = ProjectionError::Singular { at: *x };
        let (n, w) = if !self.near_pole(foot.uv) {
            let d = &foot.derivs;
            let n = d.su.cross(&d.sv).normalize() * self.orientation;
            let g = n.dot(&(x - p));
            (
                n,
                offset::surface(d.su, d.sv, d.suu, d.suv, d.svv, n, g).ok_or(singular)?,
            )
        } else {
            let (r1, symmetric) = self.ring(foot.uv, 1e-3);
            let (r2, _) = self.ring(foot.uv, 2e-3);
            let (nr, _) = self.ring_average(&r1, 0.0).ok_or(singular)?;
            let nr = nr * self.orientation;
            let dx = x - p;
            let dist = dx.norm();
            let n = if dist > 1e-9 * self.bbox.diagonal() {
                dx / dist * dx.dot(&nr).signum()
            } else {
                nr
            };
            let g = n.dot(&dx);
            let (_, w1) = self.ring_average(&r1, g).ok_or(singular)?;
            let (_, w2) = self.ring_average(&r2, g).ok_or(singular)?;
            let w = if symmetric {
                (w1 * 4.0 - w2) / 3.0
            } else {
                w1 * 2.0 - w2
            };
            let proj = crate::Mat3::identity() - n * n.transpose();
            (n, proj * w * proj)
        };
        Ok(Projection {
            point: p,
            gap: n.dot(&(x - p)),
            normal: n,
            curvature: w,
            kind: FootKind::Interior,
            param: foot.uv,
            entity,
            iterations: foot.iterations,
            residual: foot.residual,
        })
    }

    /// Closest point of the untrimmed surface.
    pub fn project_surface(
        &self,
        x: &Vec3,
        hint: Option<Vec2>,
        opts: &ProjectOptions,
    ) -> Result<SurfaceFoot, ProjectionError> {
        self.surface.project(x, hint, opts)
    }
}
