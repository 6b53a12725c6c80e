//! 4-node bilinear quadrilateral with 2x2 Gauss integration, full or
//! selective reduced (B-bar: the dilatation of `B` is replaced by its value
//! at the element centre, for plane strain, plane stress and axisymmetric
//! alike; the deviatoric part keeps full integration, so no hourglass mode).

use super::bmatrix::{apply_bbar, strain_displacement};
use super::{
    check_jacobian, integrate, point_states, ElementError, ElementResponse, IntegrationPoint,
    PointState, RefPoint, Section,
};
use crate::material::Constitutive;
use crate::model::Formulation;
use nalgebra::SVector;

/// Element dofs: `[u_0x, u_0y, .., u_3x, u_3y]`.
pub const DOFS: usize = 8;

/// Natural coordinates of the nodes (counter-clockwise).
const CORNERS: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// Shape values, Cartesian derivatives, position and `det J` at natural
/// point `(xi, eta)`.
struct ShapeAt {
    n: [f64; 4],
    dndx: [[f64; 2]; 4],
    position: [f64; 2],
    det: f64,
}

fn shape_at(x: &[[f64; 2]; 4], xi: f64, eta: f64) -> Result<ShapeAt, ElementError> {
    let mut n = [0.0; 4];
    let mut dn = [[0.0; 2]; 4];
    for (i, c) in CORNERS.iter().enumerate() {
        n[i] = 0.25 * (1.0 + c[0] * xi) * (1.0 + c[1] * eta);
        dn[i] = [
            0.25 * c[0] * (1.0 + c[1] * eta),
            0.25 * c[1] * (1.0 + c[0] * xi),
        ];
    }
    // J = [[dx/dxi, dy/dxi], [dx/deta, dy/deta]]
    let mut j = [[0.0; 2]; 2];
    let mut position = [0.0; 2];
    for i in 0..4 {
        for a in 0..2 {
            j[0][a] += dn[i][0] * x[i][a];
            j[1][a] += dn[i][1] * x[i][a];
            position[a] += n[i] * x[i][a];
        }
    }
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    check_jacobian(det, "quad4")?;
    let mut dndx = [[0.0; 2]; 4];
    for i in 0..4 {
        // [dN/dx, dN/dy] = J^-1 [dN/dxi, dN/deta]
        dndx[i][0] = (j[1][1] * dn[i][0] - j[0][1] * dn[i][1]) / det;
        dndx[i][1] = (-j[1][0] * dn[i][0] + j[0][0] * dn[i][1]) / det;
    }
    Ok(ShapeAt {
        n,
        dndx,
        position,
        det,
    })
}

/// The 2x2 Gauss points (ordered like the nodes: point `g` is nearest
/// node `g`), with B-bar matrices when `formulation` is selective reduced.
pub fn integration_points(
    x: &[[f64; 2]; 4],
    section: &Section,
    formulation: Formulation,
) -> Result<[IntegrationPoint<DOFS>; 4], ElementError> {
    let g = 1.0 / 3f64.sqrt();
    let center = match formulation {
        Formulation::Full => None,
        Formulation::SelectiveReduced => {
            let s = shape_at(x, 0.0, 0.0)?;
            Some(strain_displacement::<DOFS>(
                &s.n,
                &s.dndx,
                s.position[0],
                section.kind,
            )?)
        }
    };
    let mut points = [IntegrationPoint {
        b: Default::default(),
        volume: 0.0,
        position: [0.0; 2],
    }; 4];
    for (p, c) in points.iter_mut().zip(CORNERS.iter()) {
        let s = shape_at(x, g * c[0], g * c[1])?;
        let mut b = strain_displacement::<DOFS>(&s.n, &s.dndx, s.position[0], section.kind)?;
        if let Some(bc) = &center {
            apply_bbar(&mut b, bc);
        }
        *p = IntegrationPoint {
            b,
            volume: s.det * section.measure(s.position[0]),
            position: s.position,
        };
    }
    Ok(points)
}

/// Reference shape data at the 2x2 Gauss points (ordered like the nodes)
/// and at the element centre (whose volume weight is the element's).
pub fn reference_points(
    x: &[[f64; 2]; 4],
    section: &Section,
) -> Result<([RefPoint<4>; 4], RefPoint<4>), ElementError> {
    let g = 1.0 / 3f64.sqrt();
    let at = |xi: f64, eta: f64, w: f64| -> Result<RefPoint<4>, ElementError> {
        let s = shape_at(x, xi, eta)?;
        if section.kind == crate::model::AnalysisKind::Axisymmetric && s.position[0] <= 0.0 {
            return Err(ElementError::new(format!(
                "axisymmetric integration point at radius r = {:e} <= 0: the body must lie in x = r >= 0",
                s.position[0]
            )));
        }
        Ok(RefPoint {
            n: s.n,
            dndx: s.dndx,
            position: s.position,
            volume: w * s.det * section.measure(s.position[0]),
        })
    };
    let points = [
        at(-g, -g, 1.0)?,
        at(g, -g, 1.0)?,
        at(g, g, 1.0)?,
        at(-g, g, 1.0)?,
    ];
    Ok((points, at(0.0, 0.0, 4.0)?))
}

/// Stiffness (if `with_tangent`) and internal force for displacement `u`.
pub fn response(
    x: &[[f64; 2]; 4],
    u: &SVector<f64, DOFS>,
    section: &Section,
    formulation: Formulation,
    law: &impl Constitutive,
    with_tangent: bool,
) -> Result<ElementResponse<DOFS>, ElementError> {
    let points = integration_points(x, section, formulation)?;
    Ok(integrate(&points, u, law, with_tangent))
}

/// Stress and strain at the four Gauss points.
pub fn states(
    x: &[[f64; 2]; 4],
    u: &SVector<f64, DOFS>,
    section: &Section,
    formulation: Formulation,
    law: &impl Constitutive,
) -> Result<Vec<PointState>, ElementError> {
    Ok(point_states(
        &integration_points(x, section, formulation)?,
        u,
        law,
    ))
}

/// Nodal values extrapolated from the 2x2 Gauss point values (bilinear
/// through the Gauss points, evaluated at the corners).
pub fn extrapolate<const C: usize>(at_points: &[[f64; C]]) -> [[f64; C]; 4] {
    let s3 = 3f64.sqrt();
    let mut out = [[0.0; C]; 4];
    for (node, c) in CORNERS.iter().enumerate() {
        for (gp, cg) in CORNERS.iter().enumerate() {
            let w = 0.25 * (1.0 + s3 * c[0] * cg[0]) * (1.0 + s3 * c[1] * cg[1]);
            for k in 0..C {
                out[node][k] += w * at_points[gp][k];
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::testing::{check_element, Shape};
    use crate::material::LinearElastic;
    use crate::model::AnalysisKind;
    use proptest::prelude::*;

    fn section(kind: AnalysisKind) -> Section {
        Section {
            kind,
            thickness: 2.5,
        }
    }

    #[test]
    fn quad4_extrapolation_reproduces_bilinear_fields() {
        // a bilinear field f = 1 + 2 xi - 3 eta + 4 xi eta sampled at the Gauss points
        let g = 1.0 / 3f64.sqrt();
        let f = |xi: f64, eta: f64| 1.0 + 2.0 * xi - 3.0 * eta + 4.0 * xi * eta;
        let at: Vec<[f64; 1]> = CORNERS.iter().map(|c| [f(g * c[0], g * c[1])]).collect();
        let nodal = extrapolate(&at);
        for (i, c) in CORNERS.iter().enumerate() {
            assert!((nodal[i][0] - f(c[0], c[1])).abs() < 1e-13);
        }
    }

    #[test]
    fn quad4_volume_of_rectangle_and_axisymmetric_ring() {
        let x = [[1.0, 0.0], [3.0, 0.0], [3.0, 1.0], [1.0, 1.0]];
        let plane =
            integration_points(&x, &section(AnalysisKind::PlaneStrain), Formulation::Full).unwrap();
        let v: f64 = plane.iter().map(|p| p.volume).sum();
        assert!((v - 2.0 * 2.5).abs() < 1e-13);
        let axi = integration_points(&x, &section(AnalysisKind::Axisymmetric), Formulation::Full)
            .unwrap();
        let v: f64 = axi.iter().map(|p| p.volume).sum();
        // ring volume pi (r_o^2 - r_i^2) h
        assert!((v - std::f64::consts::PI * 8.0).abs() < 1e-12);
    }

    #[test]
    fn quad4_node_on_axis_is_allowed() {
        let x = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let law = LinearElastic::new(1.0, 0.3, AnalysisKind::Axisymmetric).unwrap();
        for f in [Formulation::Full, Formulation::SelectiveReduced] {
            let r = response(
                &x,
                &SVector::zeros(),
                &section(AnalysisKind::Axisymmetric),
                f,
                &law,
                true,
            )
            .unwrap();
            assert!(r.stiffness.iter().all(|v| v.is_finite()));
        }
    }

    #[test]
    fn quad4_inverted_or_off_axis_is_an_error() {
        let law = LinearElastic::new(1.0, 0.3, AnalysisKind::Axisymmetric).unwrap();
        let cw = [[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]];
        let sec = section(AnalysisKind::Axisymmetric);
        assert!(response(&cw, &SVector::zeros(), &sec, Formulation::Full, &law, true).is_err());
        let neg = [[-2.0, 0.0], [-1.0, 0.0], [-1.0, 1.0], [-2.0, 1.0]];
        let e = response(&neg, &SVector::zeros(), &sec, Formulation::Full, &law, true).unwrap_err();
        assert!(e.message.contains("r >= 0"), "{}", e.message);
    }

    #[test]
    fn selective_reduced_removes_volumetric_locking_in_bending() {
        // A single square in pure bending, nu -> 0.5: the fully integrated
        // element's bending energy blows up with the bulk modulus, B-bar's does not.
        let x = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        // bending mode u_x = xi eta: nodes (-1,-1) +1, (1,-1) -1, (1,1) +1, (-1,1) -1
        let u = SVector::<f64, 8>::from_row_slice(&[1.0, 0.0, -1.0, 0.0, 1.0, 0.0, -1.0, 0.0]);
        let sec = section(AnalysisKind::PlaneStrain);
        let energy = |nu: f64, f: Formulation| {
            let law = LinearElastic::new(1.0, nu, AnalysisKind::PlaneStrain).unwrap();
            let k = response(&x, &u, &sec, f, &law, true).unwrap().stiffness;
            (u.transpose() * k * u)[(0, 0)]
        };
        let full_ratio = energy(0.4999, Formulation::Full) / energy(0.3, Formulation::Full);
        let bbar_ratio = energy(0.4999, Formulation::SelectiveReduced)
            / energy(0.3, Formulation::SelectiveReduced);
        assert!(full_ratio > 100.0, "full: {full_ratio}");
        assert!(bbar_ratio < 2.0, "B-bar: {bbar_ratio}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn quad4_stiffness_properties(
            shape in Shape::quad(),
            young in 1.0f64..1e6,
            poisson in -0.9f64..0.49,
            kind in prop_oneof![
                Just(AnalysisKind::PlaneStrain),
                Just(AnalysisKind::PlaneStress),
                Just(AnalysisKind::Axisymmetric)
            ],
            formulation in prop_oneof![Just(Formulation::Full), Just(Formulation::SelectiveReduced)],
            u in proptest::collection::vec(-1.0f64..1.0, 8),
        ) {
            let x = [shape.x[0], shape.x[1], shape.x[2], shape.x[3]];
            let law = LinearElastic::new(young, poisson, kind).unwrap();
            let sec = section(kind);
            let u = SVector::<f64, 8>::from_row_slice(&u);
            let r = response(&x, &u, &sec, formulation, &law, true).unwrap();
            let zero_modes = if kind == AnalysisKind::Axisymmetric { 1 } else { 3 };
            check_element(&x, &r, &u, kind, zero_modes).map_err(TestCaseError::fail)?;
        }
    }
}
