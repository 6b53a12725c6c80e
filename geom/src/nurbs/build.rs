//! Exact NURBS constructions: planar patches, surfaces of revolution (the
//! nine-point rational circle), the sphere, and the profiles used by the
//! tests and the benchmark.

use super::curve::NurbsCurve;
use super::surface::NurbsSurface;
use crate::Vec3;
use std::f64::consts::FRAC_1_SQRT_2;

/// The bilinear patch `origin + u eu + v ev`, `(u, v)` in `[0, 1]^2`.
pub fn plane_patch(origin: Vec3, eu: Vec3, ev: Vec3) -> NurbsSurface {
    NurbsSurface::new(
        [1, 1],
        [2, 2],
        [vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]],
        vec![origin, origin + eu, origin + ev, origin + eu + ev],
        vec![1.0; 4],
    )
    .expect("a bilinear patch is valid")
}

/// The surface swept by `profile` (in the plane `y = 0`: `x` is the radius,
/// `z` the height) in a full turn about the `z` axis. `u` follows the
/// profile, `v` goes around (`v = 0` on the `x` axis; closed in `v`). A
/// profile point on the axis gives a pole (a degenerate edge).
pub fn revolve(profile: &NurbsCurve<3>) -> Result<NurbsSurface, String> {
    if let Some(i) = profile
        .points
        .iter()
        .position(|p| p.y.abs() > 0.0 || p.x < 0.0)
    {
        return Err(format!(
            "revolve: profile control point {} must lie in the half-plane y = 0, x >= 0",
            i + 1
        ));
    }
    let circle = [
        (1.0, 0.0, 1.0),
        (1.0, 1.0, FRAC_1_SQRT_2),
        (0.0, 1.0, 1.0),
        (-1.0, 1.0, FRAC_1_SQRT_2),
        (-1.0, 0.0, 1.0),
        (-1.0, -1.0, FRAC_1_SQRT_2),
        (0.0, -1.0, 1.0),
        (1.0, -1.0, FRAC_1_SQRT_2),
        (1.0, 0.0, 1.0),
    ];
    let nu = profile.points.len();
    let mut points = Vec::with_capacity(nu * 9);
    let mut weights = Vec::with_capacity(nu * 9);
    for &(cx, cy, cw) in &circle {
        for (p, w) in profile.points.iter().zip(&profile.weights) {
            points.push(Vec3::new(p.x * cx, p.x * cy, p.z));
            weights.push(w * cw);
        }
    }
    let kv = vec![
        0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
    ];
    NurbsSurface::new(
        [profile.degree, 2],
        [nu, 9],
        [profile.knots.clone(), kv],
        points,
        weights,
    )
}

/// The exact sphere of centre `center` and radius `r`: a half circle from
/// the south pole to the north pole revolved (poles at `u = 0` and `u = 1`,
/// seam at `v = 0`), normal `S_u x S_v` pointing outwards.
pub fn sphere(center: Vec3, r: f64) -> NurbsSurface {
    let h = FRAC_1_SQRT_2;
    let half = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0],
        vec![
            Vec3::new(0.0, 0.0, -r),
            Vec3::new(r, 0.0, -r),
            Vec3::new(r, 0.0, 0.0),
            Vec3::new(r, 0.0, r),
            Vec3::new(0.0, 0.0, r),
        ],
        vec![1.0, h, 1.0, h, 1.0],
    )
    .expect("a half circle is valid");
    // Walking up from the south pole, S_u x S_v points inwards: reverse v.
    let s = reverse_v(&revolve(&half).expect("the half circle lies in y = 0"));
    let points = s.points.iter().map(|p| p + center).collect();
    NurbsSurface::new(s.degree, s.counts, s.knots, points, s.weights).expect("a sphere is valid")
}

/// A dome punch: a quarter circle of radius `r` from the pole `(0, 0, h)`
/// down to `(r, 0, h - r)`, then the straight flank down to `(r, 0, 0)`,
/// revolved about `z` (pole at `u = 0`, free edge at `u = 1`, seam at
/// `v = 0`); normal `S_u x S_v` pointing outwards. Needs `h > r > 0`.
pub fn dome(r: f64, h: f64) -> Result<NurbsSurface, String> {
    if !(r > 0.0 && h > r && h.is_finite()) {
        return Err(format!("dome: needs h > r > 0 (got r = {r}, h = {h})"));
    }
    let profile = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0],
        vec![
            Vec3::new(0.0, 0.0, h),
            Vec3::new(r, 0.0, h),
            Vec3::new(r, 0.0, h - r),
            Vec3::new(r, 0.0, 0.5 * (h - r)),
            Vec3::new(r, 0.0, 0.0),
        ],
        vec![1.0, FRAC_1_SQRT_2, 1.0, 1.0, 1.0],
    )?;
    // The profile walks down from the pole: S_u x S_v points outwards.
    revolve(&profile)
}

/// The same surface with the `v` parameter reversed (normal flipped).
pub fn reverse_v(s: &NurbsSurface) -> NurbsSurface {
    let [nu, nv] = s.counts;
    let [a, b] = s.domain()[1];
    let mut kv: Vec<f64> = s.knots[1].iter().rev().map(|k| a + b - k).collect();
    for i in 1..kv.len() {
        if kv[i] < kv[i - 1] {
            kv[i] = kv[i - 1];
        }
    }
    let mut points = Vec::with_capacity(nu * nv);
    let mut weights = Vec::with_capacity(nu * nv);
    for j in (0..nv).rev() {
        for i in 0..nu {
            points.push(s.points[j * nu + i]);
            weights.push(s.weights[j * nu + i]);
        }
    }
    NurbsSurface::new(
        s.degree,
        s.counts,
        [s.knots[0].clone(), kv],
        points,
        weights,
    )
    .expect("reversing a valid surface keeps it valid")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Vec2;

    #[test]
    fn dome_normal_points_outwards_and_pole_is_degenerate() {
        let s = dome(1.0, 2.0).unwrap();
        let d = s.eval(Vec2::new(0.75, 0.3));
        let n = d.su.cross(&d.sv);
        let radial = Vec3::new(d.p.x, d.p.y, 0.0);
        assert!(n.dot(&radial) > 0.0);
        assert!((radial.norm() - 1.0).abs() < 1e-14);
        assert!(s.degenerate[0][0] && !s.degenerate[0][1] && s.closed[1]);
        let sp = sphere(Vec3::zeros(), 2.0);
        let d = sp.eval(Vec2::new(0.3, 0.6));
        assert!(d.su.cross(&d.sv).dot(&d.p) > 0.0, "sphere normal outwards");
    }
}
