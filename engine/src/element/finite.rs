//! Finite-strain element kernel: **total Lagrangian** formulation with the
//! deformation gradient `F = I + Grad u` (in-plane) and
//! `F33 = 1` (plane strain) or `1 + u_r / R` (axisymmetric hoop stretch),
//! integrated over the reference configuration:
//! `f_int = int_Omega0 P : Grad(dN) dV0`, `P = tau F^-T` (first
//! Piola-Kirchhoff stress from the law's Kirchhoff stress `tau`).
//!
//! The tangent `K = d f_int / d u` is computed by forward automatic
//! differentiation of the whole kernel ([`crate::material::dual`]): it is
//! the exact linearisation — material tangent (return mapping included),
//! geometric (initial stress) stiffness, hoop terms and F-bar terms.
//!
//! `formulation = selective_reduced` on quad4 uses **F-bar** (de Souza Neto
//! et al. 1996): the volumetric part of `F` is taken from the element centre,
//! `F_bar = (J_0 / J)^(1/2) F` on the in-plane block (plane strain, `F33 = 1`)
//! or `(J_0 / J)^(1/3) F` (axisymmetric), and
//! `f_int = int (J / J_0) tau(F_bar) F^-T : Grad(dN) dV0`, whose tangent is
//! unsymmetric (used as computed).
//!
//! Plane stress is not supported by this kernel (validation rejects it).

use super::{ElementError, ElementResponse, MaterialPoint, PointState, RefPoint};
use crate::material::dual::{Dual, Scalar};
use crate::material::tensor::{log, Deformation};
use crate::material::{History, NonlinearLaw};
use crate::model::AnalysisKind;
use nalgebra::SVector;

/// Inputs of the kernel of one element.
#[derive(Debug, Clone, Copy)]
pub struct FiniteElement<'a, const NN: usize> {
    /// Integration points in the reference configuration.
    pub points: &'a [RefPoint<NN>],
    /// Element centre, for F-bar (`None`: plain `F`).
    pub center: Option<&'a RefPoint<NN>>,
    /// Plane strain or axisymmetric.
    pub kind: AnalysisKind,
    /// The law.
    pub law: &'a NonlinearLaw,
    /// Internal variables at the start of the increment, one per point.
    pub history: &'a [History],
    /// Time increment (rate-dependent laws).
    pub dt: f64,
}

fn deformation<T: Scalar, const NN: usize>(
    p: &RefPoint<NN>,
    u: &[T],
    kind: AnalysisKind,
) -> Deformation<T> {
    let mut f = Deformation::<T>::identity();
    for a in 0..NN {
        for i in 0..2 {
            for j in 0..2 {
                f.f[i][j] = f.f[i][j] + u[2 * a + i] * p.dndx[a][j];
            }
        }
        if kind == AnalysisKind::Axisymmetric {
            f.f33 = f.f33 + u[2 * a] * (p.n[a] / p.position[0]);
        }
    }
    f
}

impl<const NN: usize> FiniteElement<'_, NN> {
    /// Internal force at displacement `u` (`2 NN` entries, scalar `T`) and
    /// the updated points.
    fn forces<T: Scalar>(
        &self,
        u: &[T],
        thermal_strain: f64,
    ) -> Result<(Vec<T>, Vec<MaterialPoint>), ElementError> {
        // multiplicative thermal split F = F_m theta: the law sees F / theta
        // and tau = theta^3 tau_m (`crate::thermal::expansion`)
        let theta = 1.0 + thermal_strain;
        let mut force = vec![T::cst(0.0); 2 * NN];
        let mut out = Vec::with_capacity(self.points.len());
        let axi = self.kind == AnalysisKind::Axisymmetric;
        let j0 = match self.center {
            Some(c) => {
                let j0 = deformation(c, u, self.kind).det();
                if j0.re() <= 0.0 || !j0.re().is_finite() {
                    return Err(ElementError::new(format!(
                        "inverted element (det F = {:e} at the centre)",
                        j0.re()
                    )));
                }
                Some(j0)
            }
            None => None,
        };
        for (p, h) in self.points.iter().zip(self.history) {
            let f = deformation(p, u, self.kind);
            let j = f.det();
            if j.re() <= 0.0 || !j.re().is_finite() {
                return Err(ElementError::new(format!(
                    "inverted element (det F = {:e} at ({:.4e}, {:.4e}))",
                    j.re(),
                    p.position[0],
                    p.position[1]
                )));
            }
            let (fbar, scale) = match j0 {
                None => (f, T::cst(1.0)),
                Some(j0) => {
                    let ratio = j0 / j;
                    let mut fb = f;
                    let c = if axi {
                        ratio.powf(1.0 / 3.0)
                    } else {
                        ratio.powf(0.5)
                    };
                    for row in &mut fb.f {
                        for v in row {
                            *v = *v * c;
                        }
                    }
                    if axi {
                        fb.f33 = fb.f33 * c;
                    }
                    (fb, j / j0)
                }
            };
            let (fbar, scale) = if thermal_strain != 0.0 {
                let mut fm = fbar;
                for row in &mut fm.f {
                    for v in row {
                        *v = *v * (1.0 / theta);
                    }
                }
                fm.f33 = fm.f33 * (1.0 / theta);
                (fm, scale * (theta * theta * theta))
            } else {
                (fbar, scale)
            };
            let up = self
                .law
                .finite(&fbar, h, self.dt)
                .map_err(ElementError::new)?;
            let tau = [
                up.stress[0] * scale,
                up.stress[1] * scale,
                up.stress[2] * scale,
                up.stress[3] * scale,
            ];
            let (pk, p33) = f.piola(&tau);
            for a in 0..NN {
                let d = p.dndx[a];
                let mut fx = pk[0][0] * d[0] + pk[0][1] * d[1];
                if axi {
                    fx = fx + p33 * (p.n[a] / p.position[0]);
                }
                let fy = pk[1][0] * d[0] + pk[1][1] * d[1];
                force[2 * a] = force[2 * a] + fx * p.volume;
                force[2 * a + 1] = force[2 * a + 1] + fy * p.volume;
            }
            // output: Cauchy stress sigma = tau / J, log strain of F
            let fv = f.re();
            let jv = j.re();
            let b = fv.push(&[1.0, 1.0, 1.0, 0.0]);
            let e = log(&b);
            out.push(MaterialPoint {
                state: PointState {
                    position: p.position,
                    volume: p.volume,
                    strain: [0.5 * e[0], 0.5 * e[1], 0.5 * e[2], e[3]].into(),
                    stress: [
                        tau[0].re() / jv,
                        tau[1].re() / jv,
                        tau[2].re() / jv,
                        tau[3].re() / jv,
                    ]
                    .into(),
                },
                history: up.history,
            });
        }
        Ok((force, out))
    }

    /// Internal force, tangent (if `with_tangent`, exact by automatic
    /// differentiation) and updated points at displacement `u`.
    pub fn response<const ND: usize>(
        &self,
        u: &SVector<f64, ND>,
        with_tangent: bool,
    ) -> Result<(ElementResponse<ND>, Vec<MaterialPoint>), ElementError> {
        self.response_with_thermal_strain(u, with_tangent, 0.0)
    }

    /// Like [`FiniteElement::response`], with the isotropic thermal strain
    /// `thermal_strain` (multiplicative split, `crate::thermal::expansion`).
    pub fn response_with_thermal_strain<const ND: usize>(
        &self,
        u: &SVector<f64, ND>,
        with_tangent: bool,
        thermal_strain: f64,
    ) -> Result<(ElementResponse<ND>, Vec<MaterialPoint>), ElementError> {
        debug_assert_eq!(ND, 2 * NN);
        let mut r = ElementResponse {
            stiffness: nalgebra::SMatrix::<f64, ND, ND>::zeros(),
            force: SVector::<f64, ND>::zeros(),
        };
        if with_tangent {
            let ud: Vec<Dual<ND>> = (0..ND).map(|k| Dual::var(u[k], k)).collect();
            let (f, pts) = self.forces(&ud, thermal_strain)?;
            for (i, fi) in f.iter().enumerate() {
                r.force[i] = fi.v;
                for j in 0..ND {
                    r.stiffness[(i, j)] = fi.d[j];
                }
            }
            Ok((r, pts))
        } else {
            let (f, pts) = self.forces(u.as_slice(), thermal_strain)?;
            for (i, fi) in f.iter().enumerate() {
                r.force[i] = *fi;
            }
            Ok((r, pts))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::{quad4, Section};
    use crate::material::j2::Elastic;
    use crate::model::Kinematics;

    #[test]
    fn fbar_removes_volumetric_locking_in_bending_near_incompressibility() {
        // single square, bending mode u_x = xi eta; tangent at the reference state
        let x = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let u = SVector::<f64, 8>::from_row_slice(&[1.0, 0.0, -1.0, 0.0, 1.0, 0.0, -1.0, 0.0]);
        for kind in [AnalysisKind::PlaneStrain, AnalysisKind::Axisymmetric] {
            let sec = Section {
                kind,
                thickness: 1.0,
            };
            let x = if kind == AnalysisKind::Axisymmetric {
                x.map(|p| [p[0] + 1.0, p[1]])
            } else {
                x
            };
            let (pts, center) = quad4::reference_points(&x, &sec).unwrap();
            let hist = [History::initial(Kinematics::Finite); 4];
            let energy = |nu: f64, fbar: bool| {
                let law = NonlinearLaw::Hencky {
                    elastic: Elastic::from_young(1.0, nu),
                };
                let el = FiniteElement {
                    points: &pts,
                    center: fbar.then_some(&center),
                    kind,
                    law: &law,
                    history: &hist,
                    dt: 0.0,
                };
                let k = el.response(&SVector::zeros(), true).unwrap().0.stiffness;
                (u.transpose() * k * u)[(0, 0)]
            };
            let full = energy(0.4999, false) / energy(0.3, false);
            let fbar = energy(0.4999, true) / energy(0.3, true);
            assert!(full > 100.0, "{kind:?} full: {full}");
            assert!(fbar < 2.0, "{kind:?} F-bar: {fbar}");
        }
    }
}
