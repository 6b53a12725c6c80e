//! Lamé quantities: inner-surface radial displacement, hoop stress at the
//! integration points, axial strain.
//!
//! Stresses are those of the engine's own element kernels
//! (`ctc_engine::element::recovery::cell_states`) at the integration
//! points, compared with the closed form at the same (reference) radius.

use super::{max_cell_edge, relative_error, Measured, Value};
use crate::analytical::lame::ThickCylinder;
use crate::capture::FinalState;
use crate::case::Quantity;
use ctc_engine::element::recovery::{blocks_of, cell_states};
use ctc_engine::element::Section;
use ctc_engine::model::Model;

/// Measures u_r on the inner surface, the hoop stress and (axisymmetric)
/// the axial strain.
pub fn measure(
    model: &Model,
    state: &FinalState,
    cyl: &ThickCylinder,
    center: [f64; 2],
    axisymmetric: bool,
) -> Result<Measured, String> {
    let radius_of = |p: [f64; 2]| {
        if axisymmetric {
            p[0]
        } else {
            ((p[0] - center[0]).powi(2) + (p[1] - center[1]).powi(2)).sqrt()
        }
    };
    let tol = 1e-8 * cyl.outer;
    let u = &state.displacement;

    // Radial displacement of the inner surface.
    let ur_a = cyl.u_r(cyl.inner);
    let mut worst: Option<(f64, f64)> = None; // (error, computed)
    for (n, &p) in model.mesh.nodes.iter().enumerate() {
        let r = radius_of(p);
        if (r - cyl.inner).abs() > tol {
            continue;
        }
        let ur = if axisymmetric {
            u[n][0]
        } else {
            (u[n][0] * (p[0] - center[0]) + u[n][1] * (p[1] - center[1])) / r
        };
        let e = (ur - ur_a).abs() / ur_a.abs();
        if worst.is_none_or(|w| e > w.0) {
            worst = Some((e, ur));
        }
    }
    let (ur_err, ur_h) =
        worst.ok_or_else(|| format!("no node on the inner surface r = {}", cyl.inner))?;

    // Hoop stress at the integration points.
    let section = Section::new(&model.analysis);
    let blocks = blocks_of(model)?;
    let stt_a = cyl.sigma_tt(cyl.inner);
    let mut worst_s: Option<(f64, f64, f64)> = None; // (error, computed, exact)
    for block in &blocks {
        for c in block.cells.clone() {
            let states =
                cell_states(&model.mesh, c, u, &section, block).map_err(|e| e.to_string())?;
            for s in states {
                let p = [s.position[0], s.position[1]];
                let hoop = if axisymmetric {
                    s.stress[2]
                } else {
                    let r = radius_of(p);
                    let (cs, sn) = ((p[0] - center[0]) / r, (p[1] - center[1]) / r);
                    s.stress[0] * sn * sn + s.stress[1] * cs * cs - 2.0 * s.stress[3] * sn * cs
                };
                let exact = cyl.sigma_tt(radius_of(p));
                let e = (hoop - exact).abs() / stt_a.abs();
                if worst_s.is_none_or(|w| e > w.0) {
                    worst_s = Some((e, hoop, exact));
                }
            }
        }
    }
    let (s_err, s_h, s_exact) = worst_s.ok_or("the model has no integration point")?;
    let mut values = vec![
        Value {
            quantity: Quantity::InnerDisplacement,
            reference: Some(ur_a),
            computed: ur_h,
            error: ur_err,
        },
        Value {
            quantity: Quantity::HoopStress,
            reference: Some(s_exact),
            computed: s_h,
            error: s_err,
        },
    ];
    if axisymmetric {
        let eps = axial_strain(model, u);
        values.push(Value {
            quantity: Quantity::AxialStrain,
            reference: Some(cyl.eps_zz()),
            computed: eps,
            error: relative_error(eps, cyl.eps_zz()),
        });
    }
    Ok(Measured {
        values,
        h: max_cell_edge(model),
        profile: None,
    })
}

/// Least-squares slope of u_y against y over all nodes.
fn axial_strain(model: &Model, u: &[[f64; 2]]) -> f64 {
    let n = model.mesh.nodes.len() as f64;
    let my = model.mesh.nodes.iter().map(|p| p[1]).sum::<f64>() / n;
    let mu = u.iter().map(|d| d[1]).sum::<f64>() / n;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (p, d) in model.mesh.nodes.iter().zip(u) {
        sxy += (p[1] - my) * (d[1] - mu);
        sxx += (p[1] - my).powi(2);
    }
    sxy / sxx
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytical::lame::EndCondition;
    use crate::measure::test_model::one_body;
    use ctc_engine::mesh::generate::{generate, Grading, MeshSpec};
    use ctc_engine::mesh::CellKind;
    use ctc_engine::model::AnalysisKind;

    fn pipe() -> ThickCylinder {
        ThickCylinder {
            inner: 1.0,
            outer: 2.0,
            pressure: 100.0,
            young: 210e3,
            poisson: 0.3,
            ends: EndCondition::PlaneStrain,
        }
    }

    /// Error of the Lamé quantities for the exact field interpolated on an
    /// n x 2n quarter ring.
    fn interpolated_errors(n: usize) -> (f64, f64, f64) {
        let cyl = pipe();
        let mesh = generate(&MeshSpec::Annulus {
            center: [0.0, 0.0],
            inner: 1.0,
            outer: 2.0,
            start_angle: 0.0,
            end_angle: 90.0,
            radial: n,
            circumferential: 2 * n,
            radial_grading: Grading::Uniform,
            kind: CellKind::Quad4,
        })
        .unwrap();
        let model = one_body(mesh, AnalysisKind::PlaneStrain, cyl.young, cyl.poisson);
        let displacement = model
            .mesh
            .nodes
            .iter()
            .map(|p| {
                let r = (p[0] * p[0] + p[1] * p[1]).sqrt();
                let ur = cyl.u_r(r);
                [ur * p[0] / r, ur * p[1] / r]
            })
            .collect();
        let state = FinalState {
            displacement,
            ..FinalState::default()
        };
        let m = measure(&model, &state, &cyl, [0.0, 0.0], false).unwrap();
        let e = |q| m.values.iter().find(|v| v.quantity == q).unwrap().error;
        (e(Quantity::InnerDisplacement), e(Quantity::HoopStress), m.h)
    }

    /// The exact nodal field has no nodal error, and the hoop stress of its
    /// interpolant converges (checks the polar transformation of stress).
    #[test]
    fn lame_plane_strain_exact_field_measures_zero_displacement_error() {
        let (u1, s1, h1) = interpolated_errors(8);
        let (u2, s2, h2) = interpolated_errors(16);
        assert!(u1 < 1e-13 && u2 < 1e-13, "{u1} {u2}");
        assert!(s1 < 0.1 && s2 < s1, "hoop stress errors {s1} {s2}");
        let rate = (s1 / s2).ln() / (h1 / h2).ln();
        assert!(rate > 0.9, "hoop stress {s1} {s2} rate {rate}");
    }
}
