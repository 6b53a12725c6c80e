//! Small-strain kernel for history-dependent laws (J2 elasto-plasticity,
//! Perzyna visco-plasticity): `eps = B u` (B-bar for selective reduced
//! quads), stress from the law and the committed internal variables,
//! `f_int = sum B^T sigma dV`. The tangent `K = d f_int / d u` is obtained
//! by forward automatic differentiation through the return mapping: the
//! consistent (algorithmic) tangent, exactly.

use super::{ElementError, ElementResponse, IntegrationPoint, MaterialPoint, PointState};
use crate::material::dual::{Dual, Scalar};
use crate::material::{History, NonlinearLaw};
use nalgebra::SVector;

fn forces<T: Scalar, const ND: usize>(
    points: &[IntegrationPoint<ND>],
    u: &[T],
    law: &NonlinearLaw,
    history: &[History],
    dt: f64,
    thermal_strain: f64,
) -> Result<(Vec<T>, Vec<MaterialPoint>), ElementError> {
    let mut force = vec![T::cst(0.0); ND];
    let mut out = Vec::with_capacity(points.len());
    for (p, h) in points.iter().zip(history) {
        let mut eps = [T::cst(0.0); 4];
        for (k, e) in eps.iter_mut().enumerate() {
            for (j, uj) in u.iter().enumerate() {
                let b = p.b[(k, j)];
                if b != 0.0 {
                    *e = *e + *uj * b;
                }
            }
        }
        let tensor = [
            eps[0] - thermal_strain,
            eps[1] - thermal_strain,
            eps[2] - thermal_strain,
            eps[3] * 0.5,
        ];
        let up = law.small(&tensor, h, dt).map_err(ElementError::new)?;
        for (j, f) in force.iter_mut().enumerate() {
            let mut acc = T::cst(0.0);
            for k in 0..4 {
                let b = p.b[(k, j)];
                if b != 0.0 {
                    acc = acc + up.stress[k] * b;
                }
            }
            *f = *f + acc * p.volume;
        }
        out.push(MaterialPoint {
            state: PointState {
                position: p.position,
                volume: p.volume,
                strain: [eps[0].re(), eps[1].re(), eps[2].re(), eps[3].re()].into(),
                stress: [
                    up.stress[0].re(),
                    up.stress[1].re(),
                    up.stress[2].re(),
                    up.stress[3].re(),
                ]
                .into(),
            },
            history: up.history,
        });
    }
    Ok((force, out))
}

/// Internal force, consistent tangent (if `with_tangent`) and updated
/// points at displacement `u` from the internal variables `history`.
pub fn response<const ND: usize>(
    points: &[IntegrationPoint<ND>],
    u: &SVector<f64, ND>,
    law: &NonlinearLaw,
    history: &[History],
    dt: f64,
    with_tangent: bool,
) -> Result<(ElementResponse<ND>, Vec<MaterialPoint>), ElementError> {
    response_with_thermal_strain(points, u, law, history, dt, with_tangent, 0.0)
}

/// Like [`response`], with the isotropic thermal strain `thermal_strain`
/// taken out of the strain seen by the law (`crate::thermal::expansion`).
pub fn response_with_thermal_strain<const ND: usize>(
    points: &[IntegrationPoint<ND>],
    u: &SVector<f64, ND>,
    law: &NonlinearLaw,
    history: &[History],
    dt: f64,
    with_tangent: bool,
    thermal_strain: f64,
) -> Result<(ElementResponse<ND>, Vec<MaterialPoint>), ElementError> {
    let mut r = ElementResponse {
        stiffness: nalgebra::SMatrix::<f64, ND, ND>::zeros(),
        force: SVector::<f64, ND>::zeros(),
    };
    if with_tangent {
        let ud: Vec<Dual<ND>> = (0..ND).map(|k| Dual::var(u[k], k)).collect();
        let (f, pts) = forces(points, &ud, law, history, dt, thermal_strain)?;
        for (i, fi) in f.iter().enumerate() {
            r.force[i] = fi.v;
            for j in 0..ND {
                r.stiffness[(i, j)] = fi.d[j];
            }
        }
        Ok((r, pts))
    } else {
        let (f, pts) = forces(points, u.as_slice(), law, history, dt, thermal_strain)?;
        for (i, fi) in f.iter().enumerate() {
            r.force[i] = *fi;
        }
        Ok((r, pts))
    }
}
