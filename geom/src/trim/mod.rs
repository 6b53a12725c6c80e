//! Trimming: curves in the parameter plane, loops, and the parity test
//! deciding whether a foot point belongs to a face.

pub mod curve;
pub mod parity;

pub use curve::TrimCurve;
pub use parity::{classify, Containment, ParityTolerance};

use crate::Vec2;

/// A closed loop of trimming curves, each starting where the previous ends.
#[derive(Debug, Clone, PartialEq)]
pub struct Loop {
    /// The curves in walking order.
    pub curves: Vec<TrimCurve>,
}

impl Loop {
    /// Checks that the curves join end to start within `gap` (and the last
    /// back to the first).
    pub fn new(curves: Vec<TrimCurve>, gap: f64) -> Result<Self, String> {
        if curves.is_empty() {
            return Err("trimming loop: no curve".into());
        }
        let n = curves.len();
        for i in 0..n {
            let (e, s) = (curves[i].end(), curves[(i + 1) % n].start());
            let d = (e - s).norm();
            if d.is_nan() || d > gap {
                return Err(format!(
                    "trimming loop: curve {} ends at ({}, {}) but curve {} starts at ({}, {}) \
                     ({d:.3e} apart, more than the tolerance {gap:.1e})",
                    i + 1,
                    e.x,
                    e.y,
                    (i + 1) % n + 1,
                    s.x,
                    s.y
                ));
            }
        }
        Ok(Loop { curves })
    }

    /// The rectangle `[u0, u1] x [v0, v1]` walked counter-clockwise.
    pub fn rectangle(u: [f64; 2], v: [f64; 2]) -> Self {
        let c = [
            Vec2::new(u[0], v[0]),
            Vec2::new(u[1], v[0]),
            Vec2::new(u[1], v[1]),
            Vec2::new(u[0], v[1]),
        ];
        Loop {
            curves: (0..4)
                .map(|i| TrimCurve::Line {
                    a: c[i],
                    b: c[(i + 1) % 4],
                })
                .collect(),
        }
    }

    /// Box `[min, max]` of a fine polyline of the loop, grown by 1 %.
    pub fn bounds(&self) -> [Vec2; 2] {
        let mut lo = Vec2::repeat(f64::INFINITY);
        let mut hi = Vec2::repeat(f64::NEG_INFINITY);
        for c in &self.curves {
            for p in c.polyline(8) {
                lo = lo.inf(&p);
                hi = hi.sup(&p);
            }
        }
        let m = (hi - lo).norm() * 0.01;
        [lo.add_scalar(-m), hi.add_scalar(m)]
    }
}

/// The boundary of a face: an outer loop and holes, with the box and
/// tolerances of the parity test.
#[derive(Debug, Clone, PartialEq)]
pub struct Boundary {
    /// Outer loop.
    pub outer: Loop,
    /// Holes.
    pub holes: Vec<Loop>,
    /// Box of every loop.
    pub bounds: [Vec2; 2],
    /// Parity tolerances (relative to the box).
    pub tolerance: ParityTolerance,
}

impl Boundary {
    /// A boundary from its loops.
    pub fn new(outer: Loop, holes: Vec<Loop>) -> Self {
        let mut b = outer.bounds();
        for h in &holes {
            let hb = h.bounds();
            b = [b[0].inf(&hb[0]), b[1].sup(&hb[1])];
        }
        let size = (b[1] - b[0]).norm();
        Boundary {
            outer,
            holes,
            bounds: b,
            tolerance: ParityTolerance::relative(size),
        }
    }

    /// Every curve, outer loop first.
    pub fn curves(&self) -> impl Iterator<Item = &TrimCurve> + Clone {
        self.outer
            .curves
            .iter()
            .chain(self.holes.iter().flat_map(|h| h.curves.iter()))
    }

    /// Containment of `p` by the parity test, and the number of rays drawn.
    pub fn classify(&self, p: Vec2) -> (Containment, usize) {
        let [lo, hi] = self.bounds;
        if p.x < lo.x || p.y < lo.y || p.x > hi.x || p.y > hi.y {
            return (Containment::Outside, 0);
        }
        let corners = [lo, hi, Vec2::new(lo.x, hi.y), Vec2::new(hi.x, lo.y)];
        let reach = corners.iter().map(|c| (c - p).norm()).fold(0.0, f64::max) * 1.5 + 1e-300;
        classify(self.curves(), p, reach, &self.tolerance)
    }
}
