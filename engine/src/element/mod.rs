//! Element kernels: linear triangles and bilinear quadrilaterals for plane
//! strain, plane stress and axisymmetric analyses.
//!
//! Every element follows the same small-strain structure, so that nonlinear
//! laws fit later without touching the elements:
//! strain `eps = B u` at each integration point, stress from the
//! [`Constitutive`] law, `f_int = sum B^T sigma dV` and
//! `K = sum B^T D B dV`, where `dV = w det(J) t` (plane, thickness `t`) or
//! `w det(J) 2 pi r` (axisymmetric: element totals are over the full 2*pi).
//!
//! - [`tri3`]: 1-point constant-strain triangle;
//! - [`quad4`]: 2x2 Gauss, full or selective reduced (B-bar) integration;
//! - [`bmatrix`]: strain-displacement matrices and the B-bar projection;
//! - [`recovery`]: nodal averages of stress and strain for output;
//! - [`inelastic`]: small-strain history-dependent laws (J2 plasticity);
//! - [`finite`]: finite-strain total Lagrangian kernel (Neo-Hookean, Hencky,
//!   finite J2 plasticity, F-bar).

pub mod bmatrix;
pub mod finite;
pub mod inelastic;
pub mod quad4;
pub mod recovery;
pub mod tri3;

use crate::material::{Constitutive, Strain, Stress};
use crate::model::{Analysis, AnalysisKind};
use nalgebra::{SMatrix, SVector};

/// Cross-section of a 2D analysis: how an area becomes a volume.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Plane strain, plane stress or axisymmetric.
    pub kind: AnalysisKind,
    /// Out-of-plane thickness (plane kinds only).
    pub thickness: f64,
}

impl Section {
    /// The section of an analysis.
    pub fn new(analysis: &Analysis) -> Self {
        Section {
            kind: analysis.kind,
            thickness: analysis.thickness,
        }
    }

    /// Volume per unit area at radius `r`: the thickness (plane) or
    /// `2 pi r` (axisymmetric, totals over the full ring).
    pub fn measure(&self, r: f64) -> f64 {
        match self.kind {
            AnalysisKind::Axisymmetric => 2.0 * std::f64::consts::PI * r,
            AnalysisKind::PlaneStrain | AnalysisKind::PlaneStress => self.thickness,
        }
    }
}

/// An element that cannot be evaluated (inverted, degenerate, off-axis).
#[derive(Debug, Clone, PartialEq)]
pub struct ElementError {
    /// What is wrong, in words a user understands.
    pub message: String,
}

impl ElementError {
    /// An error with a message.
    pub fn new(message: impl Into<String>) -> Self {
        ElementError {
            message: message.into(),
        }
    }
}

impl std::fmt::Display for ElementError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for ElementError {}

/// One integration point of an element with `ND` dofs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IntegrationPoint<const ND: usize> {
    /// Strain-displacement matrix (B-bar for selective reduced quads).
    pub b: SMatrix<f64, 4, ND>,
    /// Volume weight `w det(J) t` or `w det(J) 2 pi r`.
    pub volume: f64,
    /// Position (x, y) — (r, z) for axisymmetric analyses.
    pub position: [f64; 2],
}

/// Reference-configuration shape data of one integration point, for the
/// nonlinear kernels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefPoint<const NN: usize> {
    /// Shape function values.
    pub n: [f64; NN],
    /// Shape function derivatives `[dN/dX, dN/dY]` per node.
    pub dndx: [[f64; 2]; NN],
    /// Position (x, y) — (r, z) for axisymmetric analyses.
    pub position: [f64; 2],
    /// Volume weight `w det(J) t` or `w det(J) 2 pi r`.
    pub volume: f64,
}

/// Stress and strain at one integration point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointState {
    /// Position (x, y).
    pub position: [f64; 2],
    /// Volume weight of the point.
    pub volume: f64,
    /// Full strain `[xx, yy, zz, xy]` (engineering shear; plane stress
    /// `zz` completed by the law).
    pub strain: Strain,
    /// Stress `[xx, yy, zz, xy]`.
    pub stress: Stress,
}

/// State of one integration point of a nonlinear kernel: output values and
/// the updated internal variables.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaterialPoint {
    /// Stress (Cauchy) and strain (small strain, or the logarithmic strain
    /// `1/2 ln(F F^T)` for finite strain; engineering shear).
    pub state: PointState,
    /// Internal variables after the update.
    pub history: crate::material::History,
}

/// Element stiffness and internal force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElementResponse<const ND: usize> {
    /// Tangent stiffness `sum B^T D B dV` (zero when not requested).
    pub stiffness: SMatrix<f64, ND, ND>,
    /// Internal force `sum B^T sigma dV`.
    pub force: SVector<f64, ND>,
}

/// Integrates the internal force (and the tangent if `with_tangent`) of an
/// element with displacement `u` over `points`.
pub fn integrate<const ND: usize>(
    points: &[IntegrationPoint<ND>],
    u: &SVector<f64, ND>,
    law: &impl Constitutive,
    with_tangent: bool,
) -> ElementResponse<ND> {
    let mut stiffness = SMatrix::<f64, ND, ND>::zeros();
    let mut force = SVector::<f64, ND>::zeros();
    for p in points {
        let strain = p.b * u;
        let stress = law.stress(&strain);
        force += p.b.transpose() * (stress * p.volume);
        if with_tangent {
            let db = law.tangent(&strain) * p.b;
            stiffness += p.b.transpose() * (db * p.volume);
        }
    }
    if with_tangent {
        // B^T D B is symmetric in exact arithmetic: make it so in floating point
        // (keeps Cholesky happy and the assembled matrix exactly symmetric).
        for i in 0..ND {
            for j in 0..i {
                let s = 0.5 * (stiffness[(i, j)] + stiffness[(j, i)]);
                stiffness[(i, j)] = s;
                stiffness[(j, i)] = s;
            }
        }
    }
    ElementResponse { stiffness, force }
}

/// Stress and strain at each of `points` for displacement `u`.
pub fn point_states<const ND: usize>(
    points: &[IntegrationPoint<ND>],
    u: &SVector<f64, ND>,
    law: &impl Constitutive,
) -> Vec<PointState> {
    points
        .iter()
        .map(|p| {
            let strain = p.b * u;
            PointState {
                position: p.position,
                volume: p.volume,
                strain: law.complete_strain(&strain),
                stress: law.stress(&strain),
            }
        })
        .collect()
}

/// Checks that a Jacobian determinant is positive (cells must be
/// counter-clockwise and not degenerate).
pub(crate) fn check_jacobian(det: f64, what: &str) -> Result<(), ElementError> {
    if det > 0.0 && det.is_finite() {
        Ok(())
    } else {
        Err(ElementError::new(format!(
            "{what}: non-positive Jacobian determinant {det:e} (nodes must be counter-clockwise \
             and the cell must not be degenerate or inverted)"
        )))
    }
}

/// Shared property checks and random shapes for element unit tests.
#[cfg(test)]
pub(crate) mod testing {
    use super::ElementResponse;
    use crate::model::AnalysisKind;
    use nalgebra::{DMatrix, SVector};
    use proptest::prelude::*;

    /// A random valid element shape (counter-clockwise, convex).
    #[derive(Debug, Clone)]
    pub struct Shape {
        /// Node coordinates.
        pub x: Vec<[f64; 2]>,
    }

    fn polygon(n: usize, start: f64, angle_jitter: f64) -> impl Strategy<Value = Shape> {
        (
            proptest::collection::vec((-angle_jitter..angle_jitter, 0.6f64..1.4), n),
            0.05f64..20.0,
            0.0f64..4.0,
            -10.0f64..10.0,
        )
            .prop_map(move |(pts, scale, r_min, y0)| {
                let mut x: Vec<[f64; 2]> = pts
                    .iter()
                    .enumerate()
                    .map(|(i, (da, rad))| {
                        let a = start + i as f64 * std::f64::consts::TAU / n as f64 + da;
                        [scale * rad * a.cos(), scale * rad * a.sin()]
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
                    let la = (b[0] - a[0]).hypot(b[1] - a[1]);
                    let lb = (c[0] - b[0]).hypot(c[1] - b[1]);
                    cross > 0.2 * la * lb
                })
            })
    }

    impl Shape {
        /// Random triangles.
        pub fn triangle() -> impl Strategy<Value = Shape> {
            polygon(3, 0.3, 0.5)
        }
        /// Random convex quadrilaterals.
        pub fn quad() -> impl Strategy<Value = Shape> {
            polygon(4, std::f64::consts::FRAC_PI_4, 0.35)
        }
    }

    /// Checks symmetry, rigid-body modes in the null space, positive
    /// semi-definiteness with exactly `zero_modes` zero eigenvalues, and
    /// `f_int = K u` (linear elasticity).
    pub fn check_element<const ND: usize>(
        x: &[[f64; 2]],
        r: &ElementResponse<ND>,
        u: &SVector<f64, ND>,
        kind: AnalysisKind,
        zero_modes: usize,
    ) -> Result<(), String> {
        let k = &r.stiffness;
        let knorm = k.norm();
        for i in 0..ND {
            for j in 0..ND {
                if (k[(i, j)] - k[(j, i)]).abs() > 1e-13 * knorm {
                    return Err(format!("K not symmetric at ({i},{j})"));
                }
            }
        }
        let mut modes: Vec<SVector<f64, ND>> = Vec::new();
        let mut tz = SVector::<f64, ND>::zeros();
        for i in 0..ND / 2 {
            tz[2 * i + 1] = 1.0;
        }
        modes.push(tz);
        if kind != AnalysisKind::Axisymmetric {
            let mut tx = SVector::<f64, ND>::zeros();
            let mut rot = SVector::<f64, ND>::zeros();
            for (i, p) in x.iter().enumerate() {
                tx[2 * i] = 1.0;
                rot[2 * i] = -p[1];
                rot[2 * i + 1] = p[0];
            }
            modes.push(tx);
            modes.push(rot);
        }
        for (m, v) in modes.iter().enumerate() {
            let kv = k * v;
            if kv.norm() > 1e-10 * knorm * v.norm() {
                return Err(format!(
                    "rigid mode {m}: |K v| / (|K| |v|) = {:e}",
                    kv.norm() / (knorm * v.norm())
                ));
            }
        }
        let eig = DMatrix::from_fn(ND, ND, |i, j| k[(i, j)]).symmetric_eigenvalues();
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
        let resid = r.force - k * u;
        if resid.norm() > 1e-12 * knorm * u.norm().max(1e-300) {
            return Err(format!("f_int != K u: {:e}", resid.norm()));
        }
        Ok(())
    }
}
