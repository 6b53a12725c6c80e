//! A face: a NURBS surface, optionally trimmed by an outer loop and holes in
//! its parameter plane, with the side of free space.

use crate::nurbs::{NurbsSurface, ProjectOptions, SurfaceDerivs, SurfaceFoot};
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

    /// Derivatives used for the normal and curvature at `uv`: at a point
    /// where `S_u x S_v` vanishes (a pole) they are taken a little inside
    /// the domain (1e-7 of its size), where the surface is regular.
    pub fn regular_derivs(&self, uv: Vec2) -> SurfaceDerivs {
        let d = self.surface.eval(uv);
        let n = d.su.cross(&d.sv).norm();
        if n > 1e-10 * d.su.norm() * d.sv.norm() && n > 0.0 {
            return d;
        }
        let dom = self.surface.domain();
        let mut q = uv;
        for k in 0..2 {
            let len = dom[k][1] - dom[k][0];
            let mid = 0.5 * (dom[k][0] + dom[k][1]);
            // Step off a degenerate edge of this direction, towards the middle.
            let degenerate_here = self.surface.degenerate[k]
                .iter()
                .enumerate()
                .any(|(e, &g)| g && (uv[k] - dom[k][e]).abs() <= 1e-6 * len);
            if degenerate_here {
                q[k] += if uv[k] < mid { 1e-7 * len } else { -1e-7 * len };
            }
        }
        if q == uv {
            // A singular point that is not a known pole: step towards the centre.
            for k in 0..2 {
                let len = dom[k][1] - dom[k][0];
                let mid = 0.5 * (dom[k][0] + dom[k][1]);
                q[k] += (mid - uv[k]).signum() * 1e-7 * len;
            }
        }
        self.surface.eval(q)
    }

    /// Oriented unit normal at `uv` (free side).
    pub fn normal(&self, uv: Vec2) -> Vec3 {
        let d = self.regular_derivs(uv);
        d.su.cross(&d.sv).normalize() * self.orientation
    }

    /// The projection on the face's surface at an orthogonal foot `foot` of
    /// `x`: gap `n . (x - S)`, the oriented normal, `dn/dx` of the offset
    /// surface.
    pub fn interior(
        &self,
        x: &Vec3,
        foot: &SurfaceFoot,
        entity: usize,
    ) -> Result<Projection, ProjectionError> {
        let d = self.regular_derivs(foot.uv);
        let n = d.su.cross(&d.sv).normalize() * self.orientation;
        let p = foot.derivs.p;
        let g = n.dot(&(x - p));
        let w = offset::surface(d.su, d.sv, d.suu, d.suv, d.svv, n, g)
            .ok_or(ProjectionError::Singular { at: *x })?;
        Ok(Projection {
            point: p,
            gap: g,
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
