//! Finite-strain kinematics: **total Lagrangian** formulation with the
//! deformation gradient `F = I + Grad u` (3x3; planar analyses:
//! `F_33 = 1` in plane strain, `1 + u_r / R` axisymmetric, see
//! [`super::planar`]), integrated over the reference configuration:
//! `f_int = int_Omega0 P : Grad(dN) dV0`, `P = tau F^-T` (first
//! Piola-Kirchhoff stress from the law's Kirchhoff stress `tau`).
//!
//! The tangent `K = d f_int / d u` is computed by forward automatic
//! differentiation of the whole kernel ([`crate::material::dual`]): it is
//! the exact linearisation — material tangent (return mapping included),
//! geometric (initial stress) stiffness, hoop terms and F-bar terms.
//!
//! `formulation = selective_reduced` uses **F-bar** (de Souza Neto et al.
//! 1996): the volumetric part of `F` is taken from the cell centre,
//! `F_bar = (J_0 / J)^(1/2) F` on the in-plane block (plane strain,
//! `F_33 = 1`) or `(J_0 / J)^(1/3) F` (axisymmetric and solid), and
//! `f_int = int (J / J_0) tau(F_bar) F^-T : Grad(dN) dV0`, whose tangent is
//! unsymmetric (used as computed).
//!
//! Plane stress is not supported by this kernel (validation rejects it).

use super::geometry::ShapePoint;
use super::{planar, ElementError, ElementMatrix, MaterialPoint, PointState, Section};
use crate::geom::Point;
use crate::material::dual::{Dual, Scalar};
use crate::material::tensor::{log, Deformation};
use crate::material::{History, NonlinearLaw, Strain, Stress};

/// Inputs of the finite-strain kernel of one cell.
#[derive(Debug, Clone, Copy)]
pub struct FiniteElement<'a, const D: usize, const NN: usize> {
    /// Integration points in the reference configuration.
    pub points: &'a [ShapePoint<D, NN>],
    /// Cell centre, for F-bar (`None`: plain `F`).
    pub centre: Option<&'a ShapePoint<D, NN>>,
    /// Analysis kind (planar embedding) and thickness.
    pub section: &'a Section,
    /// The law.
    pub law: &'a NonlinearLaw,
    /// Internal variables at the start of the increment, one per point.
    pub history: &'a [History],
    /// Time increment (rate-dependent laws).
    pub dt: f64,
    /// Isotropic thermal strain (multiplicative split,
    /// `crate::thermal::expansion`).
    pub thermal_strain: f64,
}

/// `F = I + sum_a u_a (x) dN_a/dX` (+ the hoop stretch) at point `p`.
fn deformation<T: Scalar, const D: usize, const NN: usize>(
    p: &ShapePoint<D, NN>,
    u: &[T],
    hoop: bool,
) -> Deformation<T> {
    let mut f = Deformation::<T>::identity();
    for a in 0..NN {
        for i in 0..D {
            for j in 0..D {
                f.f[i][j] = f.f[i][j] + u[a * D + i] * p.dndx[a][j];
            }
        }
        if hoop {
            f.f[2][2] = f.f[2][2] + u[a * D] * (p.n[a] / p.position[0]);
        }
    }
    f
}

fn at<const D: usize>(p: &Point<D>) -> String {
    let c: Vec<String> = p.iter().map(|v| format!("{v:.4e}")).collect();
    format!("({})", c.join(", "))
}

impl<const D: usize, const NN: usize> FiniteElement<'_, D, NN> {
    /// Internal force at displacement `u` (`D NN` entries, scalar `T`) and
    /// the updated points.
    fn forces<T: Scalar>(
        &self,
        u: &[T],
        out: &mut [MaterialPoint],
    ) -> Result<Vec<T>, ElementError> {
        // multiplicative thermal split F = F_m theta: the law sees F / theta
        // and tau = theta^3 tau_m (`crate::thermal::expansion`)
        let theta = 1.0 + self.thermal_strain;
        let hoop = planar::has_hoop(self.section);
        let (exponent, block) = (
            planar::fbar_exponent(self.section),
            planar::fbar_block(self.section),
        );
        let mut force = vec![T::cst(0.0); D * NN];
        let j0 = match self.centre {
            Some(c) => {
                let j0 = deformation(c, u, hoop).det();
                if j0.re() <= 0.0 || !j0.re().is_finite() {
                    return Err(ElementError::new(format!(
                        "inverted element (det F = {:.2e} at the centre)",
                        j0.re()
                    )));
                }
                Some(j0)
            }
            None => None,
        };
        for ((p, h), mp) in self.points.iter().zip(self.history).zip(out.iter_mut()) {
            let f = deformation(p, u, hoop);
            let j = f.det();
            if j.re() <= 0.0 || !j.re().is_finite() {
                return Err(ElementError::new(format!(
                    "inverted element (det F = {:.2e} at {})",
                    j.re(),
                    at(&p.position)
                )));
            }
            let (mut fbar, mut scale) = (f, T::cst(1.0));
            if let Some(j0) = j0 {
                let c = (j0 / j).powf(exponent);
                for row in fbar.f.iter_mut().take(block) {
                    for v in row.iter_mut().take(block) {
                        *v = *v * c;
                    }
                }
                scale = j / j0;
            }
            if self.thermal_strain != 0.0 {
                fbar = fbar.scaled(T::cst(1.0 / theta));
                scale = scale * (theta * theta * theta);
            }
            let up = self
                .law
                .finite(&fbar, h, self.dt)
                .map_err(ElementError::new)?;
            let tau = up.stress.map(|s| s * scale);
            let pk = f.piola(&tau);
            for a in 0..NN {
                let d = &p.dndx[a];
                for i in 0..D {
                    let mut fi = T::cst(0.0);
                    for j in 0..D {
                        fi = fi + pk[i][j] * d[j];
                    }
                    if hoop && i == 0 {
                        fi = fi + pk[2][2] * (p.n[a] / p.position[0]);
                    }
                    force[a * D + i] = force[a * D + i] + fi * p.volume;
                }
            }
            // output: Cauchy stress sigma = tau / J, log strain of F
            let jv = j.re();
            let e = log(&f.re().left_cauchy_green());
            *mp = MaterialPoint {
                state: PointState {
                    position: super::position3(&p.position),
                    volume: p.volume,
                    strain: Strain::from([0.5 * e[0], 0.5 * e[1], 0.5 * e[2], e[3], e[4], e[5]]),
                    stress: Stress::from(tau.map(|t| t.re() / jv)),
                },
                history: up.history,
            };
        }
        Ok(force)
    }

    /// Internal force, tangent (if `with_tangent`, exact by automatic
    /// differentiation, `ND = D NN` directions) and updated points at
    /// displacement `u`.
    pub fn response<const ND: usize>(
        &self,
        u: &[Point<D>; NN],
        with_tangent: bool,
        out: &mut ElementMatrix<D>,
        states: &mut [MaterialPoint],
    ) -> Result<(), ElementError> {
        debug_assert_eq!(ND, D * NN);
        if with_tangent {
            let ud: Vec<Dual<ND>> = (0..ND).map(|k| Dual::var(u[k / D][k % D], k)).collect();
            let f = self.forces(&ud, states)?;
            out.set_from_duals(NN, &f);
        } else {
            let uf: Vec<f64> = (0..ND).map(|k| u[k / D][k % D]).collect();
            let f = self.forces(&uf, states)?;
            out.set_force(NN, &f);
        }
        Ok(())
    }
}
