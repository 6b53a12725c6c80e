//! The rotation of a cell over an increment: the rigid rotation that best
//! maps the cell's nodes at the start of the increment onto their places at
//! its end (least squares about the nodes' centroid: Kabsch 1976, Acta
//! Cryst. A32:922; in 2D the angle of `sum p0 x p1`, `sum p0 . p1`), and the
//! largest over the model.
//!
//! Used by the rotation control of dynamic steps (`dynamic { max_rotation
//! }`, [`crate::solve::stepping`]): generalized-alpha, like every
//! Newmark-family scheme, is energy-stable for linear problems only; on a
//! body turned by a large angle per increment the trapezoidal work of the
//! internal forces is no longer the change of the strain energy and the
//! kinetic energy can run away (Simo & Tarnow 1992, ZAMP 43:757; Kuhl &
//! Crisfield 1999, IJNME 45:569). The angle is that of the nodes, so it
//! does not depend on the element or the material law, and it is the rigid
//! part of the motion only (a cell stretched without turning has 0).

use crate::model::Model;
use nalgebra::Matrix3;

/// The largest rotation of a cell between the displacements `u0` and `u`
/// (flattened, `D` per node), in radians, and the global cell turning by
/// it (`None`: no cell).
pub fn largest<const D: usize>(model: &Model<D>, u: &[f64], u0: &[f64]) -> Option<(f64, usize)> {
    let mesh = &model.mesh;
    let mut best: Option<(f64, usize)> = None;
    let mut p0 = Vec::new();
    let mut p1 = Vec::new();
    for c in 0..mesh.cells.len() {
        let nodes = mesh.cells.nodes(c);
        p0.clear();
        p1.clear();
        for &n in nodes {
            let mut a = [0.0; 3];
            let mut b = [0.0; 3];
            for k in 0..D {
                let x = mesh.nodes[n][k];
                a[k] = x + u0.get(n * D + k).copied().unwrap_or(0.0);
                b[k] = x + u.get(n * D + k).copied().unwrap_or(0.0);
            }
            p0.push(a);
            p1.push(b);
        }
        let angle = rotation(&p0, &p1, D == 2);
        if angle.is_finite() && best.is_none_or(|(b, _)| angle > b) {
            best = Some((angle, c));
        }
    }
    best
}

/// The angle of the rotation that best maps the points `p0` onto `p1`
/// about their centroids (radians, in `[0, pi]`); `planar`: the points lie
/// in the xy plane (the third component ignored).
pub fn rotation(p0: &[[f64; 3]], p1: &[[f64; 3]], planar: bool) -> f64 {
    let n = p0.len().min(p1.len());
    if n < 2 {
        return 0.0;
    }
    let centroid = |p: &[[f64; 3]]| {
        let mut c = [0.0; 3];
        for x in &p[..n] {
            for k in 0..3 {
                c[k] += x[k] / n as f64;
            }
        }
        c
    };
    let (c0, c1) = (centroid(p0), centroid(p1));
    // H = sum (p0 - c0) (p1 - c1)^T
    let mut h = Matrix3::<f64>::zeros();
    for (a, b) in p0[..n].iter().zip(&p1[..n]) {
        for i in 0..3 {
            for j in 0..3 {
                h[(i, j)] += (a[i] - c0[i]) * (b[j] - c1[j]);
            }
        }
    }
    if planar {
        // the angle maximizing sum p1 . R p0
        let cross = h[(0, 1)] - h[(1, 0)];
        let dot = h[(0, 0)] + h[(1, 1)];
        return cross.atan2(dot).abs();
    }
    // R = V diag(1, 1, d) U^T from H = U S V^T maximizes tr(R H)
    let svd = h.svd(true, true);
    let (Some(uu), Some(vt)) = (svd.u, svd.v_t) else {
        return 0.0;
    };
    let v = vt.transpose();
    let d = (v * uu.transpose()).determinant().signum();
    let r = v * Matrix3::from_diagonal(&nalgebra::Vector3::new(1.0, 1.0, d)) * uu.transpose();
    // the angle from the axial vector and the trace: accurate near 0
    let s = 0.5
        * ((r[(2, 1)] - r[(1, 2)]).powi(2)
            + (r[(0, 2)] - r[(2, 0)]).powi(2)
            + (r[(1, 0)] - r[(0, 1)]).powi(2))
        .sqrt();
    let c = 0.5 * (r.trace() - 1.0);
    s.atan2(c)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The corners of a unit cube, turned by `angle` about the unit `axis`
    /// (Rodrigues), stretched by `stretch` along x first and shifted.
    fn cube(angle: f64, axis: [f64; 3], stretch: f64) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
        let mut p0 = Vec::new();
        let mut p1 = Vec::new();
        let k = nalgebra::Vector3::from(axis).normalize();
        let r = nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(k), angle);
        for i in 0..8 {
            let x = [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64];
            p0.push(x);
            let y = r * nalgebra::Vector3::new(stretch * x[0], x[1], x[2]);
            p1.push([y[0] + 3.0, y[1] - 1.0, y[2] + 0.5]);
        }
        (p0, p1)
    }

    #[test]
    fn the_angle_of_a_turned_cube_is_the_angle_it_was_turned_by() {
        for &(angle, axis) in &[
            (0.0, [0.0, 0.0, 1.0]),
            (1e-6, [1.0, 0.0, 0.0]),
            (0.05, [1.0, 1.0, 1.0]),
            (0.3, [0.2, -1.0, 0.4]),
            (2.5, [0.0, 1.0, 0.0]),
        ] {
            let (p0, p1) = cube(angle, axis, 1.0);
            let got = rotation(&p0, &p1, false);
            assert!((got - angle).abs() < 1e-12, "{angle} {axis:?}: {got}");
        }
        // a stretch along a principal axis of the cube does not turn it
        let (p0, p1) = cube(0.0, [0.0, 0.0, 1.0], 1.3);
        assert!(rotation(&p0, &p1, false) < 1e-14);
        // nor changes the rotation that follows it
        let (p0, p1) = cube(0.2, [0.0, 0.0, 1.0], 1.3);
        assert!((rotation(&p0, &p1, false) - 0.2).abs() < 1e-12);
    }

    #[test]
    fn the_planar_angle_is_the_angle_in_the_plane() {
        let (p0, p1) = cube(0.4, [0.0, 0.0, 1.0], 1.0);
        let p0: Vec<[f64; 3]> = p0.into_iter().take(4).collect();
        let p1: Vec<[f64; 3]> = p1.into_iter().take(4).collect();
        assert!((rotation(&p0, &p1, true) - 0.4).abs() < 1e-12);
        let (q0, q1) = cube(-0.7, [0.0, 0.0, 1.0], 1.0);
        assert!((rotation(&q0[..4], &q1[..4], true) - 0.7).abs() < 1e-12);
    }
}
