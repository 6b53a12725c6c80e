//! Projection robustness benchmark: random points against a revolved NURBS
//! surface with a pole and a periodic seam (the dome punch of
//! [`crate::nurbs::build::dome`]: a quarter circle of radius 1 from the pole
//! `(0, 0, 2)` down to `(1, 0, 1)`, then a straight flank down to the free
//! edge at `z = 0`, revolved about `z`), checked against the exact distance
//! to the profile in the point's meridian plane. Run by `ctc bench
//! --projection`; speed figures belong here, never in timed tests.

use crate::nurbs::{build, NurbsSurface, ProjectOptions, SurfaceFoot};
use crate::{ProjectionError, Vec2, Vec3};
use std::time::Instant;

/// Figures of one run (cold: no hint; warm: the foot of the previous point
/// of a path as the hint).
#[derive(Debug, Clone, PartialEq)]
pub struct ProjectionFigures {
    /// "cold" or "warm".
    pub mode: &'static str,
    /// Points projected.
    pub points: usize,
    /// Accepted projections.
    pub converged: usize,
    /// Accepted projections whose distance differs from the exact one by
    /// more than 1e-9 (a wrong local minimum).
    pub wrong_minimum: usize,
    /// Largest |distance - exact| over accepted projections.
    pub max_distance_error: f64,
    /// Mean Newton iterations per projection (all seeds).
    pub mean_iterations: f64,
    /// Largest Newton iterations of one projection.
    pub max_iterations: u32,
    /// Wall time per projection, nanoseconds.
    pub ns_per_projection: f64,
}

/// Exact distance from `x` to the dome of radius `r` and height `h`.
pub fn dome_distance(x: &Vec3, r: f64, h: f64) -> f64 {
    let rho = (x.x * x.x + x.y * x.y).sqrt();
    let z = x.z;
    // Quarter circle: centre (0, h - r), angle from the axis in [0, pi/2].
    let (dr, dz) = (rho, z - (h - r));
    let arc = if dz >= 0.0 {
        ((dr * dr + dz * dz).sqrt() - r).abs()
    } else {
        // Closest arc point is its lower end (r, h - r).
        ((rho - r).powi(2) + dz * dz).sqrt()
    };
    let zc = z.clamp(0.0, h - r);
    let flank = ((rho - r).powi(2) + (z - zc).powi(2)).sqrt();
    arc.min(flank)
}

/// Runs `n` random points (a fixed seed: the same points every run) in the
/// box `[-1.5, 1.5]^2 x [-0.5, 2.5]` around the dome.
pub fn run(n: usize) -> Vec<ProjectionFigures> {
    let (r, h) = (1.0, 2.0);
    let dome = build::dome(r, h).expect("the dome is valid");
    let opts = ProjectOptions::default();
    let mut seed = 0x853c49e6748fea9bu64;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let points: Vec<Vec3> = (0..n)
        .map(|_| Vec3::new(3.0 * rnd() - 1.5, 3.0 * rnd() - 1.5, 3.0 * rnd() - 0.5))
        .collect();
    // A path for the warm runs: consecutive points 1e-3 apart along random
    // directions, restarting at each cold point every 100 steps.
    let mut path = Vec::with_capacity(n);
    let mut p = points[0];
    for (i, q) in points.iter().enumerate() {
        if i % 100 == 0 {
            p = *q;
        } else {
            let d = Vec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize() * 1e-3;
            p += d;
        }
        path.push(p);
    }
    vec![
        measure("cold", &dome, &points, &opts, false, r, h),
        measure("warm", &dome, &path, &opts, true, r, h),
    ]
}

fn measure(
    mode: &'static str,
    s: &NurbsSurface,
    pts: &[Vec3],
    opts: &ProjectOptions,
    warm: bool,
    r: f64,
    h: f64,
) -> ProjectionFigures {
    let start = Instant::now();
    let mut results: Vec<Result<SurfaceFoot, ProjectionError>> = Vec::with_capacity(pts.len());
    let mut hint: Option<Vec2> = None;
    for (i, x) in pts.iter().enumerate() {
        if i % 100 == 0 {
            hint = None;
        }
        let f = s.project(x, if warm { hint } else { None }, opts);
        hint = f.as_ref().ok().map(|f| f.uv);
        results.push(f);
    }
    let secs = start.elapsed().as_secs_f64();
    let mut fig = ProjectionFigures {
        mode,
        points: pts.len(),
        converged: 0,
        wrong_minimum: 0,
        max_distance_error: 0.0,
        mean_iterations: 0.0,
        max_iterations: 0,
        ns_per_projection: secs * 1e9 / pts.len().max(1) as f64,
    };
    let mut its = 0u64;
    for (x, f) in pts.iter().zip(&results) {
        let i = match f {
            Ok(f) => {
                fig.converged += 1;
                let e = (f.distance - dome_distance(x, r, h)).abs();
                fig.max_distance_error = fig.max_distance_error.max(e);
                if e > 1e-9 {
                    fig.wrong_minimum += 1;
                }
                f.iterations
            }
            Err(ProjectionError::NotConverged { iterations, .. }) => *iterations,
            Err(_) => 0,
        };
        its += u64::from(i);
        fig.max_iterations = fig.max_iterations.max(i);
    }
    fig.mean_iterations = its as f64 / pts.len().max(1) as f64;
    fig
}

impl std::fmt::Display for ProjectionFigures {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "| {} | {} | {:.6} | {} | {:.1e} | {:.2} | {} | {:.0} |",
            self.mode,
            self.points,
            self.converged as f64 / self.points.max(1) as f64,
            self.wrong_minimum,
            self.max_distance_error,
            self.mean_iterations,
            self.max_iterations,
            self.ns_per_projection
        )
    }
}

/// The table header matching [`ProjectionFigures`]'s `Display`.
pub const HEADER: &str = "| seeds | points | converged fraction | wrong minimum (> 1e-9) | max distance error | mean Newton its | max Newton its | ns / projection |\n|---|---|---|---|---|---|---|---|";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_small_run_converges_to_the_exact_distance() {
        for f in run(2000) {
            assert_eq!(f.converged, f.points, "{f}");
            assert_eq!(f.wrong_minimum, 0, "{f}");
            assert!(f.max_iterations <= 60, "{f}");
        }
        assert!((dome_distance(&Vec3::new(0.0, 0.0, 3.0), 1.0, 2.0) - 1.0).abs() < 1e-15);
        assert!((dome_distance(&Vec3::new(3.0, 0.0, 0.5), 1.0, 2.0) - 2.0).abs() < 1e-15);
    }
}
