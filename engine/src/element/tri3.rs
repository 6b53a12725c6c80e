//! 3-node linear triangle (constant strain in plane; one integration point
//! at the centroid, also for the axisymmetric hoop strain).

use super::bmatrix::strain_displacement;
use super::{
    check_jacobian, integrate, point_states, ElementError, ElementResponse, IntegrationPoint,
    PointState, RefPoint, Section,
};
use crate::material::Constitutive;
use nalgebra::SVector;

/// Element dofs: `[u_0x, u_0y, u_1x, u_1y, u_2x, u_2y]`.
pub const DOFS: usize = 6;

/// The centroid integration point of the triangle with counter-clockwise
/// nodes `x` (weight = area x thickness, or area x 2 pi r_centroid).
pub fn integration_points(
    x: &[[f64; 2]; 3],
    section: &Section,
) -> Result<[IntegrationPoint<DOFS>; 1], ElementError> {
    let [p0, p1, p2] = *x;
    let two_area = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1]);
    check_jacobian(two_area, "tri3")?;
    let dndx = [
        [(p1[1] - p2[1]) / two_area, (p2[0] - p1[0]) / two_area],
        [(p2[1] - p0[1]) / two_area, (p0[0] - p2[0]) / two_area],
        [(p0[1] - p1[1]) / two_area, (p1[0] - p0[0]) / two_area],
    ];
    let n = [1.0 / 3.0; 3];
    let centroid = [(p0[0] + p1[0] + p2[0]) / 3.0, (p0[1] + p1[1] + p2[1]) / 3.0];
    let b = strain_displacement::<DOFS>(&n, &dndx, centroid[0], section.kind)?;
    Ok([IntegrationPoint {
        b,
        volume: 0.5 * two_area * section.measure(centroid[0]),
        position: centroid,
    }])
}

/// Reference shape data at the centroid (the single integration point).
pub fn reference_points(
    x: &[[f64; 2]; 3],
    section: &Section,
) -> Result<[RefPoint<3>; 1], ElementError> {
    let [p0, p1, p2] = *x;
    let two_area = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1]);
    check_jacobian(two_area, "tri3")?;
    let dndx = [
        [(p1[1] - p2[1]) / two_area, (p2[0] - p1[0]) / two_area],
        [(p2[1] - p0[1]) / two_area, (p0[0] - p2[0]) / two_area],
        [(p0[1] - p1[1]) / two_area, (p1[0] - p0[0]) / two_area],
    ];
    let centroid = [(p0[0] + p1[0] + p2[0]) / 3.0, (p0[1] + p1[1] + p2[1]) / 3.0];
    if section.kind == crate::model::AnalysisKind::Axisymmetric && centroid[0] <= 0.0 {
        return Err(ElementError::new(format!(
            "axisymmetric integration point at radius r = {:e} <= 0: the body must lie in x = r >= 0",
            centroid[0]
        )));
    }
    Ok([RefPoint {
        n: [1.0 / 3.0; 3],
        dndx,
        position: centroid,
        volume: 0.5 * two_area * section.measure(centroid[0]),
    }])
}

/// Stiffness (if `with_tangent`) and internal force for displacement `u`.
pub fn response(
    x: &[[f64; 2]; 3],
    u: &SVector<f64, DOFS>,
    section: &Section,
    law: &impl Constitutive,
    with_tangent: bool,
) -> Result<ElementResponse<DOFS>, ElementError> {
    let points = integration_points(x, section)?;
    Ok(integrate(&points, u, law, with_tangent))
}

/// Stress and strain at the integration point.
pub fn states(
    x: &[[f64; 2]; 3],
    u: &SVector<f64, DOFS>,
    section: &Section,
    law: &impl Constitutive,
) -> Result<Vec<PointState>, ElementError> {
    Ok(point_states(&integration_points(x, section)?, u, law))
}

/// Nodal values recovered from the integration point values (constant).
pub fn extrapolate<T: Copy>(at_points: &[T]) -> [T; 3] {
    [at_points[0]; 3]
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
            thickness: 1.0,
        }
    }

    #[test]
    fn tri3_hand_stiffness_unit_right_triangle() {
        // E = 1, nu = 0, plane stress, t = 1, nodes (0,0) (1,0) (0,1):
        // dN0/dx = -1, dN0/dy = -1, area 1/2, D = diag(1, 1, 0, 1/2):
        // K_00 = A (dN0/dx^2 + dN0/dy^2 / 2) = 0.75, K_01 = A (1/2) dN0/dy dN0/dx = 0.25.
        let law = LinearElastic::new(1.0, 0.0, AnalysisKind::PlaneStress).unwrap();
        let x = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let r = response(
            &x,
            &SVector::zeros(),
            &section(AnalysisKind::PlaneStress),
            &law,
            true,
        )
        .unwrap();
        let k = r.stiffness;
        assert!((k[(0, 0)] - 0.75).abs() < 1e-15);
        assert!((k[(0, 1)] - 0.25).abs() < 1e-15);
        assert!((k[(2, 2)] - 0.5).abs() < 1e-15); // node 1: A dN1/dx^2 = 0.5
        assert!((k[(3, 3)] - 0.25).abs() < 1e-15); // node 1: A dN1/dx^2 / 2
        assert!((k[(2, 5)] - 0.0).abs() < 1e-15); // dN1/dy = 0, dN2/dx = 0
    }

    #[test]
    fn tri3_clockwise_nodes_are_rejected() {
        let law = LinearElastic::new(1.0, 0.3, AnalysisKind::PlaneStrain).unwrap();
        let x = [[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]];
        let e = response(
            &x,
            &SVector::zeros(),
            &section(AnalysisKind::PlaneStrain),
            &law,
            true,
        )
        .unwrap_err();
        assert!(e.message.contains("counter-clockwise"), "{}", e.message);
    }

    #[test]
    fn tri3_axisymmetric_volume_is_pappus_ring() {
        // A triangle of area 1/2 with centroid radius r_c sweeps 2 pi r_c / 2.
        let x = [[2.0, 0.0], [3.0, 0.0], [2.0, 1.0]];
        let p = integration_points(&x, &section(AnalysisKind::Axisymmetric)).unwrap();
        let rc = 7.0 / 3.0;
        assert!((p[0].volume - std::f64::consts::PI * rc).abs() < 1e-14);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn tri3_stiffness_properties(
            shape in Shape::triangle(),
            young in 1.0f64..1e6,
            poisson in -0.9f64..0.49,
            kind in prop_oneof![
                Just(AnalysisKind::PlaneStrain),
                Just(AnalysisKind::PlaneStress),
                Just(AnalysisKind::Axisymmetric)
            ],
            u in proptest::array::uniform6(-1.0f64..1.0),
        ) {
            let x = [shape.x[0], shape.x[1], shape.x[2]];
            let law = LinearElastic::new(young, poisson, kind).unwrap();
            let sec = section(kind);
            let u = SVector::<f64, 6>::from_row_slice(&u);
            let r = response(&x, &u, &sec, &law, true).unwrap();
            // the 1-point axisymmetric triangle has rank 4: z-translation plus one
            // (mesh-communicated, well-known) zero-energy mode
            let zero_modes = if kind == AnalysisKind::Axisymmetric { 2 } else { 3 };
            check_element(&x, &r, &u, kind, zero_modes).map_err(TestCaseError::fail)?;
        }
    }
}
