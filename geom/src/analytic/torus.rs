//! Ring torus (a bead, a die radius revolved about an axis).
//!
//! The closest point of the centre circle (radius `R` in the plane through
//! `center` normal to `axis`) to `x` is `c = center + R q / |q|`, `q` the
//! projection of `x - center` on that plane; the torus foot is at distance
//! `r` from `c` towards `x`. With `rho = |x - c|` and `m = (x - c) / rho`:
//! `dn/dx = s [(I - m m) / rho - R / (|q| rho) e_t e_t]`, `e_t` the
//! circumferential direction (principal curvatures `1/r` and
//! `cos(phi) / (R + r cos(phi))`, offset by the gap).

use super::{finite, frame, positive, unit};
use crate::{Aabb, Mat3, Projection, ProjectionError, Side, Vec2, Vec3};

/// A torus of major radius `major` and minor radius `minor < major`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Torus {
    /// Centre.
    pub center: Vec3,
    /// Unit axis of revolution.
    pub axis: Vec3,
    /// Radius of the centre circle.
    pub major: f64,
    /// Radius of the tube, `< major`.
    pub minor: f64,
    /// Free side: outside or inside the tube.
    pub side: Side,
}

impl Torus {
    /// Checks and builds the torus.
    pub fn new(
        center: Vec3,
        axis: Vec3,
        major: f64,
        minor: f64,
        side: Side,
    ) -> Result<Self, String> {
        let major = positive(major, "torus: major radius")?;
        let minor = positive(minor, "torus: minor radius")?;
        if minor >= major {
            return Err(format!(
                "torus: the minor radius ({minor}) must be smaller than the major radius ({major})"
            ));
        }
        Ok(Torus {
            center: finite(center, "torus: centre")?,
            axis: unit(axis, "torus: axis")?,
            major,
            minor,
            side,
        })
    }

    /// Bounding box.
    pub fn bounding_box(&self) -> Aabb {
        // Extent along each coordinate: that of the tube's centre circle plus the tube.
        let big = self.major;
        let ext = Vec3::new(
            big * (1.0 - self.axis.x * self.axis.x).max(0.0).sqrt() + self.minor,
            big * (1.0 - self.axis.y * self.axis.y).max(0.0).sqrt() + self.minor,
            big * (1.0 - self.axis.z * self.axis.z).max(0.0).sqrt() + self.minor,
        );
        Aabb {
            min: self.center - ext,
            max: self.center + ext,
        }
    }

    /// Exact projection; singular on the axis and on the centre circle.
    /// Parameter: (angle about the axis, angle around the tube).
    pub fn project(&self, x: &Vec3) -> Result<Projection, ProjectionError> {
        let rel = x - self.center;
        let h = rel.dot(&self.axis);
        let q = rel - self.axis * h;
        let qn = q.norm();
        if qn <= 1e-14 * self.major {
            return Err(ProjectionError::Singular { at: *x });
        }
        let er = q / qn;
        let c = self.center + er * self.major;
        let d = x - c;
        let rho = d.norm();
        if rho <= 1e-14 * self.minor {
            return Err(ProjectionError::Singular { at: *x });
        }
        let m = d / rho;
        let s = self.side.sign();
        let et = self.axis.cross(&er);
        let w = ((Mat3::identity() - m * m.transpose()) / rho
            - et * et.transpose() * (self.major / (qn * rho)))
            * s;
        let mut p = Projection::closed_form(c + m * self.minor, s * (rho - self.minor), m * s, w);
        let (e1, e2) = frame(&self.axis);
        p.param = Vec2::new(er.dot(&e2).atan2(er.dot(&e1)), h.atan2(qn - self.major));
        Ok(p)
    }
}
