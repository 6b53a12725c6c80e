//! Small-strain kinematics: strain-displacement node blocks `B_a`
//! (`eps = sum_a B_a u_a`, rows `[xx, yy, zz, xy, xz, yz]`, engineering
//! shear; the hoop row `u_r / r` of axisymmetric analyses), the B-bar
//! projection, and the small-strain kernels: linear elasticity
//! (`f_int = sum B^T sigma dV`, `K_ab = sum B_a^T D B_b dV`) and
//! history-dependent laws (J2, Perzyna) whose consistent tangent is the
//! exact derivative of the internal force by forward automatic
//! differentiation through the return mapping.
//!
//! B-bar (`formulation = selective_reduced`): the dilatation of `B` is
//! replaced by its value at the cell centre in planar analyses (for a
//! bilinear quad that is its cell average) and by its volume average
//! (mean dilatation) in solids; the deviatoric part keeps full
//! integration, so no hourglass mode.

use super::geometry::{centre_point, quadrature_points, ShapePoint};
use super::reference::ReferenceCell;
use super::{planar, ElementError, MaterialPoint, PointState, Section};
use crate::geom::{Dimension, Point};
use crate::material::dual::{Dual, Scalar};
use crate::material::{Constitutive, History, NonlinearLaw, Strain, Tangent};
use crate::model::Formulation;
use nalgebra::{Const, SMatrix};

/// Strain per unit displacement of one node (6 x D).
pub type BBlock<const D: usize> = SMatrix<f64, 6, D>;

/// Voigt row and the two directions of each shear strain.
const SHEARS: [(usize, usize, usize); 3] = [(3, 0, 1), (4, 0, 2), (5, 1, 2)];

/// One integration point of a small-strain kernel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrainPoint<const D: usize, const NN: usize> {
    /// Strain-displacement block of each node (B-bar when selective
    /// reduced).
    pub b: [BBlock<D>; NN],
    /// Volume weight.
    pub volume: f64,
    /// Position.
    pub position: Point<D>,
}

/// The `B_a` blocks at a point with shape data `p` (the hoop row of
/// axisymmetric analyses needs `r > 0` there).
pub fn strain_displacement<const D: usize, const NN: usize>(
    p: &ShapePoint<D, NN>,
    section: &Section,
) -> Result<[BBlock<D>; NN], ElementError> {
    planar::check_radius(section, p.position[0])?;
    let hoop = planar::has_hoop(section);
    let mut out = [BBlock::<D>::zeros(); NN];
    for (a, b) in out.iter_mut().enumerate() {
        let d = &p.dndx[a];
        for i in 0..D {
            b[(i, i)] = d[i];
        }
        for &(row, i, j) in &SHEARS {
            if j < D {
                b[(row, i)] = d[j];
                b[(row, j)] = d[i];
            }
        }
        if hoop {
            b[(2, 0)] = p.n[a] / p.position[0];
        }
    }
    Ok(out)
}

/// Replaces the volumetric part of `b` by that of `b_centre` (B-bar):
/// `B_bar = B + m (m^T (B_c - B)) / 3`, `m = [1, 1, 1, 0, 0, 0]`.
pub fn apply_bbar<const D: usize, const NN: usize>(
    b: &mut [BBlock<D>; NN],
    b_centre: &[BBlock<D>; NN],
) {
    for (ba, bc) in b.iter_mut().zip(b_centre) {
        for j in 0..D {
            let mut dvol = 0.0;
            for i in 0..3 {
                dvol += bc[(i, j)] - ba[(i, j)];
            }
            for i in 0..3 {
                ba[(i, j)] += dvol / 3.0;
            }
        }
    }
}

/// The small-strain integration points of cell `C` with nodes `x`.
pub fn strain_points<const D: usize, const NN: usize, C: ReferenceCell<D, NN>>(
    x: &[Point<D>; NN],
    section: &Section,
    formulation: Formulation,
) -> Result<Vec<StrainPoint<D, NN>>, ElementError>
where
    Const<D>: Dimension<D>,
{
    let points = quadrature_points::<D, NN, C>(x, section)?;
    let centre = match formulation {
        Formulation::SelectiveReduced
            if C::QUADRATURE.len() > 1 && C::SELECTIVE_REDUCED && (D == 3 || NN > 4) =>
        {
            // solid and quadratic planar cells: the mean dilatation (volume
            // average of B over the cell), which passes the patch test on
            // distorted hexahedra (their centre value does not: the adjugate
            // of J is quadratic)
            let mut mean = [BBlock::<D>::zeros(); NN];
            let mut volume = 0.0;
            for p in &points {
                let b = strain_displacement(p, section)?;
                for (m, ba) in mean.iter_mut().zip(&b) {
                    *m += ba * p.volume;
                }
                volume += p.volume;
            }
            for m in &mut mean {
                *m /= volume;
            }
            Some(mean)
        }
        Formulation::SelectiveReduced if C::QUADRATURE.len() > 1 && C::SELECTIVE_REDUCED => {
            // planar quads: the centre value equals the cell average
            let c = centre_point::<D, NN, C>(x, section)?;
            Some(strain_displacement(&c, section)?)
        }
        _ => None,
    };
    points
        .iter()
        .map(|p| {
            let mut b = strain_displacement(p, section)?;
            if let Some(bc) = &centre {
                apply_bbar(&mut b, bc);
            }
            Ok(StrainPoint {
                b,
                volume: p.volume,
                position: p.position,
            })
        })
        .collect()
}

/// `eps = sum_a B_a u_a`.
pub fn strain<const D: usize, const NN: usize>(
    p: &StrainPoint<D, NN>,
    u: &[Point<D>; NN],
) -> Strain {
    let mut e = Strain::zeros();
    for (b, ua) in p.b.iter().zip(u) {
        e += b * ua;
    }
    e
}

/// Internal force `f_a = sum B_a^T sigma dV` and, if `with_tangent`, the
/// stiffness `K_ab = sum B_a^T D B_b dV` (node blocks, `k[a][b]`), made
/// exactly symmetric.
pub fn linear_response<const D: usize, const NN: usize>(
    points: &[StrainPoint<D, NN>],
    u: &[Point<D>; NN],
    law: &impl Constitutive,
    with_tangent: bool,
    force: &mut [Point<D>],
    stiffness: &mut [crate::geom::Block<D>],
) {
    force.fill(Point::<D>::zeros());
    if with_tangent {
        stiffness.fill(crate::geom::Block::<D>::zeros());
    }
    for p in points {
        let eps = strain(p, u);
        let sigma = law.stress(&eps) * p.volume;
        for (f, b) in force.iter_mut().zip(&p.b) {
            *f += b.tr_mul(&sigma);
        }
        if with_tangent {
            let d: Tangent = law.tangent(&eps);
            let db: [SMatrix<f64, 6, D>; NN] = std::array::from_fn(|b| (d * p.b[b]) * p.volume);
            for a in 0..NN {
                for b in 0..NN {
                    stiffness[a * NN + b] += p.b[a].tr_mul(&db[b]);
                }
            }
        }
    }
    if with_tangent {
        // B^T D B is symmetric in exact arithmetic: make it so in floating
        // point (keeps Cholesky happy and the assembled matrix symmetric)
        for a in 0..NN {
            for b in 0..=a {
                for r in 0..D {
                    for c in 0..D {
                        if a == b && c >= r {
                            continue;
                        }
                        let s =
                            0.5 * (stiffness[a * NN + b][(r, c)] + stiffness[b * NN + a][(c, r)]);
                        stiffness[a * NN + b][(r, c)] = s;
                        stiffness[b * NN + a][(c, r)] = s;
                    }
                }
            }
        }
    }
}

/// Stress and strain at each point for displacement `u` (linear law).
pub fn linear_states<const D: usize, const NN: usize>(
    points: &[StrainPoint<D, NN>],
    u: &[Point<D>; NN],
    law: &impl Constitutive,
) -> Vec<PointState> {
    points
        .iter()
        .map(|p| {
            let eps = strain(p, u);
            PointState {
                position: super::position3(&p.position),
                volume: p.volume,
                strain: law.complete_strain(&eps),
                stress: law.stress(&eps),
            }
        })
        .collect()
}

/// Internal force (element dof order `a D + c`) and updated points of a
/// history-dependent law at displacement `u` (`D NN` entries of scalar `T`).
fn inelastic_forces<T: Scalar, const D: usize, const NN: usize>(
    points: &[StrainPoint<D, NN>],
    u: &[T],
    law: &NonlinearLaw,
    history: &[History],
    dt: f64,
    thermal_strain: f64,
    out: &mut [MaterialPoint],
) -> Result<Vec<T>, ElementError> {
    let mut force = vec![T::cst(0.0); D * NN];
    for ((p, h), mp) in points.iter().zip(history).zip(out.iter_mut()) {
        let mut eps = [T::cst(0.0); 6];
        for (k, e) in eps.iter_mut().enumerate() {
            for (a, b) in p.b.iter().enumerate() {
                for c in 0..D {
                    let bk = b[(k, c)];
                    if bk != 0.0 {
                        *e = *e + u[a * D + c] * bk;
                    }
                }
            }
        }
        let tensor = [
            eps[0] - thermal_strain,
            eps[1] - thermal_strain,
            eps[2] - thermal_strain,
            eps[3] * 0.5,
            eps[4] * 0.5,
            eps[5] * 0.5,
        ];
        let up = law.small(&tensor, h, dt).map_err(ElementError::new)?;
        for (a, b) in p.b.iter().enumerate() {
            for c in 0..D {
                let mut acc = T::cst(0.0);
                for k in 0..6 {
                    let bk = b[(k, c)];
                    if bk != 0.0 {
                        acc = acc + up.stress[k] * bk;
                    }
                }
                force[a * D + c] = force[a * D + c] + acc * p.volume;
            }
        }
        *mp = MaterialPoint {
            state: PointState {
                position: super::position3(&p.position),
                volume: p.volume,
                strain: Strain::from(eps.map(|e| e.re())),
                stress: crate::material::Stress::from(up.stress.map(|s| s.re())),
            },
            history: up.history,
        };
    }
    Ok(force)
}

/// Internal force, consistent tangent (if `with_tangent`) and updated
/// points of a history-dependent law, `ND = D NN` dual directions.
#[allow(clippy::too_many_arguments)]
pub fn inelastic_response<const D: usize, const NN: usize, const ND: usize>(
    points: &[StrainPoint<D, NN>],
    u: &[Point<D>; NN],
    law: &NonlinearLaw,
    history: &[History],
    dt: f64,
    thermal_strain: f64,
    with_tangent: bool,
    out: &mut super::ElementMatrix<D>,
    states: &mut [MaterialPoint],
) -> Result<(), ElementError> {
    debug_assert_eq!(ND, D * NN);
    if with_tangent {
        let ud: Vec<Dual<ND>> = (0..ND).map(|k| Dual::var(u[k / D][k % D], k)).collect();
        let f = inelastic_forces(points, &ud, law, history, dt, thermal_strain, states)?;
        out.set_from_duals(NN, &f);
    } else {
        let uf: Vec<f64> = (0..ND).map(|k| u[k / D][k % D]).collect();
        let f = inelastic_forces(points, &uf, law, history, dt, thermal_strain, states)?;
        out.set_force(NN, &f);
    }
    Ok(())
}
