//! Shared property checks and random shapes for the element unit tests.

use super::ElementMatrix;
use crate::geom::Point;
use crate::model::AnalysisKind;
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

/// A random valid element shape.
#[derive(Debug, Clone)]
pub struct Shape<const D: usize> {
    /// Node coordinates.
    pub x: Vec<Point<D>>,
}

fn polygon(n: usize, start: f64, angle_jitter: f64) -> impl Strategy<Value = Shape<2>> {
    (
        proptest::collection::vec((-angle_jitter..angle_jitter, 0.6f64..1.4), n),
        0.05f64..20.0,
        0.0f64..4.0,
        -10.0f64..10.0,
    )
        .prop_map(move |(pts, scale, r_min, y0)| {
            let mut x: Vec<Point<2>> = pts
                .iter()
                .enumerate()
                .map(|(i, (da, rad))| {
                    let a = start + i as f64 * std::f64::consts::TAU / n as f64 + da;
                    Point::<2>::new(scale * rad * a.cos(), scale * rad * a.sin())
                })
                .collect();
            // shift so that min x = r_min * scale (0: a node on the axis)
            let xmin = x.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
            for p in &mut x {
                p[0] += scale * r_min - xmin;
                p[1] += y0;
            }
            Shape { x }
        })
        .prop_filter("convex, not too flat", |s| {
            let n = s.x.len();
            (0..n).all(|i| {
                let (a, b, c) = (s.x[i], s.x[(i + 1) % n], s.x[(i + 2) % n]);
                let cross = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
                cross > 0.2 * (b - a).norm() * (c - b).norm()
            })
        })
}

/// The nodes of a reference cell (`corners`) mapped by a random affine
/// map `A` (well conditioned, positive determinant) plus a random
/// perturbation of each node by up to `jitter` of the size.
fn solid(corners: Vec<[f64; 3]>, jitter: f64) -> impl Strategy<Value = Shape<3>> {
    let n = corners.len();
    (
        proptest::collection::vec(-0.3f64..0.3, 9),
        0.05f64..20.0,
        proptest::collection::vec(-1.0f64..1.0, 3 * n),
        proptest::collection::vec(-10.0f64..10.0, 3),
    )
        .prop_map(move |(a, scale, dx, shift)| {
            let m = nalgebra::Matrix3::from_row_slice(&a) + nalgebra::Matrix3::identity();
            let x = corners
                .iter()
                .enumerate()
                .map(|(i, c)| {
                    let p = m * Point::<3>::from(*c)
                        + Point::<3>::new(dx[3 * i], dx[3 * i + 1], dx[3 * i + 2]) * jitter;
                    p * scale + Point::<3>::new(shift[0], shift[1], shift[2])
                })
                .collect();
            Shape { x }
        })
}

impl Shape<2> {
    /// Random triangles.
    pub fn triangle() -> impl Strategy<Value = Shape<2>> {
        polygon(3, 0.3, 0.5)
    }
    /// Random convex quadrilaterals.
    pub fn quad() -> impl Strategy<Value = Shape<2>> {
        polygon(4, std::f64::consts::FRAC_PI_4, 0.35)
    }
}

impl Shape<3> {
    /// Random tetrahedra.
    pub fn tet() -> impl Strategy<Value = Shape<3>> {
        solid(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
            ],
            0.12,
        )
    }
    /// Random distorted hexahedra.
    pub fn hex() -> impl Strategy<Value = Shape<3>> {
        solid(
            vec![
                [-0.5, -0.5, -0.5],
                [0.5, -0.5, -0.5],
                [0.5, 0.5, -0.5],
                [-0.5, 0.5, -0.5],
                [-0.5, -0.5, 0.5],
                [0.5, -0.5, 0.5],
                [0.5, 0.5, 0.5],
                [-0.5, 0.5, 0.5],
            ],
            0.08,
        )
    }
}

/// The element stiffness as a dense matrix in element dof order.
pub fn dense<const D: usize>(r: &ElementMatrix<D>) -> DMatrix<f64> {
    let nd = D * r.nodes;
    DMatrix::from_fn(nd, nd, |i, j| r.entry(i, j))
}

/// Rigid-body modes of nodes `x`: translations and rotations (only the
/// axial translation for axisymmetric analyses).
pub fn rigid_modes<const D: usize>(x: &[Point<D>], kind: AnalysisKind) -> Vec<DVector<f64>> {
    let nd = D * x.len();
    let mut modes = Vec::new();
    for c in 0..D {
        if kind == AnalysisKind::Axisymmetric && c == 0 {
            continue;
        }
        modes.push(DVector::from_fn(nd, |i, _| f64::from(i % D == c)));
    }
    if kind != AnalysisKind::Axisymmetric {
        // rotation in the (i, j) plane: u_i = -x_j, u_j = x_i
        for (i, j) in [(0, 1), (0, 2), (1, 2)] {
            if j < D {
                let mut v = DVector::zeros(nd);
                for (a, p) in x.iter().enumerate() {
                    v[D * a + i] = -p[j];
                    v[D * a + j] = p[i];
                }
                modes.push(v);
            }
        }
    }
    modes
}

/// Checks symmetry, rigid-body modes in the null space, positive
/// semi-definiteness with exactly `zero_modes` zero eigenvalues, and
/// `f_int = K u` (linear elasticity).
pub fn check_element<const D: usize>(
    x: &[Point<D>],
    r: &ElementMatrix<D>,
    u: &[Point<D>],
    kind: AnalysisKind,
    zero_modes: usize,
) -> Result<(), String> {
    let k = dense(r);
    let nd = k.nrows();
    let knorm = k.norm();
    for i in 0..nd {
        for j in 0..nd {
            if (k[(i, j)] - k[(j, i)]).abs() > 1e-13 * knorm {
                return Err(format!("K not symmetric at ({i},{j})"));
            }
        }
    }
    for (m, v) in rigid_modes(x, kind).iter().enumerate() {
        let kv = &k * v;
        if kv.norm() > 1e-10 * knorm * v.norm() {
            return Err(format!(
                "rigid mode {m}: |K v| / (|K| |v|) = {:e}",
                kv.norm() / (knorm * v.norm())
            ));
        }
    }
    let eig = k.clone().symmetric_eigenvalues();
    let lmax = eig.iter().cloned().fold(0.0, f64::max);
    let lmin = eig.iter().cloned().fold(f64::INFINITY, f64::min);
    if lmin < -1e-10 * lmax {
        return Err(format!("negative eigenvalue {lmin:e} (max {lmax:e})"));
    }
    let zeros = eig.iter().filter(|&&l| l.abs() <= 1e-9 * lmax).count();
    if zeros != zero_modes {
        return Err(format!(
            "{zeros} zero eigenvalues, expected {zero_modes}: {:?}",
            eig.as_slice()
        ));
    }
    let uv = DVector::from_iterator(nd, u.iter().flat_map(|p| p.iter().copied()));
    let f = DVector::from_iterator(nd, r.force.iter().flat_map(|p| p.iter().copied()));
    let resid = f - &k * &uv;
    if resid.norm() > 1e-12 * knorm * uv.norm().max(1e-300) {
        return Err(format!("f_int != K u: {:e}", resid.norm()));
    }
    Ok(())
}
