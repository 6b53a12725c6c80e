//! Rigid motion of a tool at a given time.
//!
//! A point `X` of the tool's reference geometry is at
//! `x = Q(theta) (X - c) + c + u` at time `t`, with `theta = rotation(t)`,
//! `u = (ux(t), uy(t))` and `c` the centre of rotation. Nodes are brought
//! into the reference frame (`X = Q^T (x - c - u) + c`), projected there, and
//! the normal is rotated back with `Q`; gaps and curvatures are invariant.

use crate::model::ToolMotion;

/// The tool's rigid placement at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// `cos(theta)`.
    pub cos: f64,
    /// `sin(theta)`.
    pub sin: f64,
    /// Centre of rotation (reference configuration).
    pub center: [f64; 2],
    /// Translation `(ux, uy)`.
    pub translation: [f64; 2],
}

impl Placement {
    /// Placement of `motion` at time `t`.
    pub fn at(motion: &ToolMotion, t: f64) -> Self {
        let theta = motion.rotation.eval(t);
        Placement {
            cos: theta.cos(),
            sin: theta.sin(),
            center: motion.center,
            translation: [motion.ux.eval(t), motion.uy.eval(t)],
        }
    }

    /// The same centre and translation turned to angle `theta` (a free
    /// rotation, whose angle is an unknown rather than a time function).
    pub fn with_angle(self, theta: f64) -> Self {
        Placement {
            cos: theta.cos(),
            sin: theta.sin(),
            ..self
        }
    }

    /// The identity placement.
    pub fn identity() -> Self {
        Placement {
            cos: 1.0,
            sin: 0.0,
            center: [0.0, 0.0],
            translation: [0.0, 0.0],
        }
    }

    /// `Q v`: a vector of the reference frame in the current frame.
    pub fn rotate(&self, v: [f64; 2]) -> [f64; 2] {
        [
            self.cos * v[0] - self.sin * v[1],
            self.sin * v[0] + self.cos * v[1],
        ]
    }

    /// `Q^T v`: a vector of the current frame in the reference frame.
    pub fn rotate_back(&self, v: [f64; 2]) -> [f64; 2] {
        [
            self.cos * v[0] + self.sin * v[1],
            -self.sin * v[0] + self.cos * v[1],
        ]
    }

    /// Current position of the reference point `p`.
    pub fn to_current(&self, p: [f64; 2]) -> [f64; 2] {
        let r = self.rotate([p[0] - self.center[0], p[1] - self.center[1]]);
        [
            r[0] + self.center[0] + self.translation[0],
            r[1] + self.center[1] + self.translation[1],
        ]
    }

    /// Reference-frame position of the current point `x`.
    pub fn to_reference(&self, x: [f64; 2]) -> [f64; 2] {
        let r = self.rotate_back([
            x[0] - self.center[0] - self.translation[0],
            x[1] - self.center[1] - self.translation[1],
        ]);
        [r[0] + self.center[0], r[1] + self.center[1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::TimeFunction;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn rotation_about_centre_then_translation() {
        let motion = ToolMotion {
            ux: TimeFunction::Constant(1.0),
            uy: TimeFunction::Ramp {
                t0: 0.0,
                t1: 1.0,
                v0: 0.0,
                v1: -2.0,
            },
            rotation: TimeFunction::Constant(FRAC_PI_2),
            center: [1.0, 0.0],
        };
        let p = Placement::at(&motion, 0.5);
        // (2, 0): relative (1, 0) -> rotated (0, 1) -> (1, 1) -> + (1, -1).
        let x = p.to_current([2.0, 0.0]);
        assert!((x[0] - 2.0).abs() < 1e-15 && x[1].abs() < 1e-15);
        let back = p.to_reference(x);
        assert!((back[0] - 2.0).abs() < 1e-15 && back[1].abs() < 1e-15);
        let v = p.rotate([1.0, 0.0]);
        assert!(v[0].abs() < 1e-15 && (v[1] - 1.0).abs() < 1e-15);
        assert_eq!(Placement::identity().to_current([3.0, 4.0]), [3.0, 4.0]);
    }
}
