//! Circular arc. Walked from `start` to `end` angle: counter-clockwise
//! (`end > start`) puts the free side inside (a bowl, a die radius seen from
//! inside), clockwise puts it outside (a roller). Beyond its ends an arc
//! behaves like a polyline end (rounded end, positive gap behind it).

use super::circle::radial_projection;
use super::corner::end_cap;
use super::{finite, Projection};
use crate::contact::vec2::add;
use crate::geom::Aabb;
use std::f64::consts::{FRAC_PI_2, TAU};

/// A circular arc prepared for projection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arc {
    /// Centre.
    pub center: [f64; 2],
    /// Radius > 0.
    pub radius: f64,
    /// Angle of the first end, radians.
    pub start: f64,
    /// Signed sweep `end - start`, radians, `0 < |sweep| <= 2 pi`.
    pub sweep: f64,
    /// +1 when the free side is outside (clockwise arc), -1 inside.
    pub orientation: f64,
}

impl Arc {
    /// Builds the arc from its end angles (radians).
    pub fn new(center: [f64; 2], radius: f64, start: f64, end: f64) -> Result<Self, String> {
        if !finite(center) || !start.is_finite() || !end.is_finite() {
            return Err("arc tool: centre and angles must be finite".into());
        }
        if !(radius > 0.0 && radius.is_finite()) {
            return Err(format!("arc tool: radius must be > 0 (got {radius})"));
        }
        let sweep = end - start;
        if sweep == 0.0 {
            return Err("arc tool: start and end angles are equal; the arc is empty".into());
        }
        if sweep.abs() > TAU * (1.0 + 1e-12) {
            return Err(format!(
                "arc tool: the arc sweeps {:.3} degrees, more than a full turn; use a circle tool",
                sweep.abs().to_degrees()
            ));
        }
        Ok(Arc {
            center,
            radius,
            start,
            sweep: sweep.clamp(-TAU, TAU),
            orientation: if sweep > 0.0 { -1.0 } else { 1.0 },
        })
    }

    /// Point of the arc at angle `theta`.
    fn point_at(&self, theta: f64) -> [f64; 2] {
        add(
            self.center,
            [self.radius * theta.cos(), self.radius * theta.sin()],
        )
    }

    /// Exact bounding box (end points and the axis extremes inside the sweep).
    pub fn bounding_box(&self) -> Aabb<2> {
        let end = self.start + self.sweep;
        let mut b = Aabb::around(&[self.point_at(self.start), self.point_at(end)]);
        for k in 0..4 {
            let theta = k as f64 * FRAC_PI_2;
            if self.angular_offset(theta) <= self.sweep.abs() {
                b.include(self.point_at(theta));
            }
        }
        b
    }

    /// Angle travelled from the start, in the walking direction, to reach
    /// `theta` (in `[0, 2 pi)`).
    fn angular_offset(&self, theta: f64) -> f64 {
        ((theta - self.start) * self.sweep.signum()).rem_euclid(TAU)
    }

    /// Exact projection. Inside the angular sector: `|x-c| - R` (free
    /// outside) or `R - |x-c|` (free inside). Outside the sector the closest
    /// point is the nearer end, handled as a free end.
    pub fn project(&self, x: [f64; 2]) -> Option<Projection> {
        let p = radial_projection(self.center, self.radius, self.orientation, x)?;
        let offset = self.angular_offset(p.param);
        let span = self.sweep.abs();
        if offset <= span {
            return Some(Projection {
                param: self.start + self.sweep.signum() * offset,
                ..p
            });
        }
        // Outside the sector: the nearer end in angle is the nearer in distance.
        let theta = if offset - span <= TAU - offset {
            self.start + self.sweep
        } else {
            self.start
        };
        let n_end = [
            self.orientation * theta.cos(),
            self.orientation * theta.sin(),
        ];
        Some(end_cap(x, self.point_at(theta), n_end, theta))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::geometry::Foot;
    use std::f64::consts::PI;

    #[test]
    fn lower_half_arc_ccw_is_a_bowl() {
        // start 180, end 360 degrees: counter-clockwise, free side inside.
        let a = Arc::new([0.0, 0.0], 1.0, PI, 2.0 * PI).unwrap();
        let p = a.project([0.0, -0.75]).unwrap();
        assert!((p.gap - 0.25).abs() < 1e-15);
        assert!((p.normal[0]).abs() < 1e-15 && (p.normal[1] - 1.0).abs() < 1e-15);
        assert!((p.normal_rate + 1.0 / 0.75).abs() < 1e-14);
        let q = a.project([0.6, -1.2]).unwrap();
        let d = (0.36f64 + 1.44).sqrt();
        assert!((q.gap - (1.0 - d)).abs() < 1e-15);
        let b = a.bounding_box();
        assert!((b.min[0] + 1.0).abs() < 1e-15 && (b.min[1] + 1.0).abs() < 1e-15);
        assert!((b.max[0] - 1.0).abs() < 1e-15 && b.max[1].abs() < 1e-15);
    }

    #[test]
    fn arc_ends_rounded_on_free_side_nothing_behind() {
        // Quarter arc from 0 to 90 degrees, counter-clockwise: free inside.
        let a = Arc::new([0.0, 0.0], 1.0, 0.0, FRAC_PI_2).unwrap();
        // Below the start end (1, 0), inside the circle: free side of the end.
        let p = a.project([0.7, -0.4]).unwrap();
        assert_eq!(p.foot, Foot::End);
        assert!((p.gap - (0.09f64 + 0.16).sqrt()).abs() < 1e-15);
        // Below the start end, outside the circle: behind the tool's end,
        // past the tool: positive distance.
        let b = a.project([1.3, -0.4]).unwrap();
        assert_eq!(b.foot, Foot::End);
        assert!((b.gap - 0.5).abs() < 1e-15);
        // Clockwise arc from 90 to 0 degrees: a roller, free outside.
        let r = Arc::new([0.0, 0.0], 1.0, FRAC_PI_2, 0.0).unwrap();
        let q = r.project([1.0, 1.0]).unwrap();
        assert!((q.gap - (2f64.sqrt() - 1.0)).abs() < 1e-15);
        assert!((q.normal_rate - 1.0 / 2f64.sqrt()).abs() < 1e-15);
        assert!(Arc::new([0.0, 0.0], 1.0, 0.0, 7.0).is_err());
    }
}
