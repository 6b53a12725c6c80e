//! Infinite circular cone, one nappe, with its apex (a conical punch from
//! outside, a conical die from inside).
//!
//! In the meridian half-plane of the query point (radius `r` from the axis,
//! height `z` along it from the apex) the cone is the ray of direction
//! `m = (sin a, cos a)` from the apex. The foot is on that ray when
//! `t = r sin a + z cos a > 0`, with the signed distance `r cos a - z sin a`
//! (positive outside the solid cone) and `dn/dx = s cos a e_t e_t / r`
//! (`e_t` the circumferential direction); otherwise it is the apex, a vertex
//! (sphere of radius 0).

use super::{finite, frame, unit};
use crate::{offset, FootKind, Projection, ProjectionError, Side, Vec2, Vec3};

/// A cone of apex `apex`, axis `axis` (pointing into the opening) and
/// half-angle `half_angle`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cone {
    /// Apex.
    pub apex: Vec3,
    /// Unit axis, from the apex into the cone.
    pub axis: Vec3,
    /// Half-angle in (0, pi/2), radians.
    pub half_angle: f64,
    /// Free side.
    pub side: Side,
}

impl Cone {
    /// Checks and builds the cone.
    pub fn new(apex: Vec3, axis: Vec3, half_angle: f64, side: Side) -> Result<Self, String> {
        if !(half_angle > 0.0 && half_angle < std::f64::consts::FRAC_PI_2) {
            return Err(format!(
                "cone: the half-angle must be in (0, pi/2) radians (got {half_angle})"
            ));
        }
        Ok(Cone {
            apex: finite(apex, "cone: apex")?,
            axis: unit(axis, "cone: axis")?,
            half_angle,
            side,
        })
    }

    /// Exact projection; singular on the axis inside the cone.
    /// Parameter: (distance from the apex along the generator, angle).
    pub fn project(&self, x: &Vec3) -> Result<Projection, ProjectionError> {
        let rel = x - self.apex;
        let z = rel.dot(&self.axis);
        let q = rel - self.axis * z;
        let r = q.norm();
        let (sa, ca) = self.half_angle.sin_cos();
        let s = self.side.sign();
        let scale = rel.norm();
        if r * sa + z * ca <= 0.0 {
            // Behind the apex: the apex is the closest point.
            let dist = scale;
            if dist == 0.0 {
                return Err(ProjectionError::Singular { at: *x });
            }
            let m = rel / dist;
            let w = offset::point(*x, self.apex, s).ok_or(ProjectionError::Singular { at: *x })?;
            return Ok(
                Projection::closed_form(self.apex, s * dist, m * s, w).with_kind(FootKind::Vertex)
            );
        }
        if r <= 1e-14 * scale {
            return Err(ProjectionError::Singular { at: *x });
        }
        let er = q / r;
        let t = r * sa + z * ca;
        let nu = er * ca - self.axis * sa;
        let dist = r * ca - z * sa;
        let et = self.axis.cross(&er);
        let mut p = Projection::closed_form(
            self.apex + (er * sa + self.axis * ca) * t,
            s * dist,
            nu * s,
            et * et.transpose() * (s * ca / r),
        );
        let (e1, e2) = frame(&self.axis);
        p.param = Vec2::new(t, er.dot(&e2).atan2(er.dot(&e1)));
        Ok(p)
    }
}
