//! Strain-displacement matrices shared by the 2D elements.
//!
//! Rows follow the Voigt order `[xx, yy, zz, xy]` of [`crate::material`];
//! columns are the element dofs `[u_0x, u_0y, u_1x, u_1y, ...]`.

use super::ElementError;
use crate::model::AnalysisKind;
use nalgebra::SMatrix;

/// Volumetric projector used by B-bar: `m = [1, 1, 1, 0]`.
const M: [f64; 4] = [1.0, 1.0, 1.0, 0.0];

/// `B` at a point with shape values `n`, Cartesian shape derivatives `dndx`
/// (`[dN/dx, dN/dy]` per node) and radius `r` (used only by axisymmetric
/// analyses, where row `zz` is the hoop strain `u_r / r`; `r <= 0` is an
/// error because the hoop strain is undefined on the axis).
pub fn strain_displacement<const ND: usize>(
    n: &[f64],
    dndx: &[[f64; 2]],
    r: f64,
    kind: AnalysisKind,
) -> Result<SMatrix<f64, 4, ND>, ElementError> {
    debug_assert_eq!(n.len() * 2, ND);
    debug_assert_eq!(dndx.len() * 2, ND);
    let mut b = SMatrix::<f64, 4, ND>::zeros();
    for (i, d) in dndx.iter().enumerate() {
        b[(0, 2 * i)] = d[0];
        b[(1, 2 * i + 1)] = d[1];
        b[(3, 2 * i)] = d[1];
        b[(3, 2 * i + 1)] = d[0];
    }
    if kind == AnalysisKind::Axisymmetric {
        if r.is_nan() || r <= 0.0 {
            return Err(ElementError::new(format!(
                "axisymmetric integration point at radius r = {r:e} <= 0: the body must lie \
                 in x = r >= 0"
            )));
        }
        for (i, ni) in n.iter().enumerate() {
            b[(2, 2 * i)] = ni / r;
        }
    }
    Ok(b)
}

/// Replaces the volumetric part of `b` by that of `b_center` (B-bar):
/// `B_bar = B + m (m^T (B_c - B)) / 3`, `m = [1, 1, 1, 0]`. The dilatation
/// `eps_xx + eps_yy + eps_zz` is then the one at the element centre, while
/// the deviatoric part keeps full integration.
pub fn apply_bbar<const ND: usize>(b: &mut SMatrix<f64, 4, ND>, b_center: &SMatrix<f64, 4, ND>) {
    for j in 0..ND {
        let mut dvol = 0.0;
        for (i, m) in M.iter().enumerate() {
            dvol += m * (b_center[(i, j)] - b[(i, j)]);
        }
        for (i, m) in M.iter().enumerate() {
            b[(i, j)] += m * dvol / 3.0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axisymmetric_hoop_row_is_n_over_r() {
        let b = strain_displacement::<4>(
            &[0.25, 0.75],
            &[[1.0, 2.0], [3.0, 4.0]],
            2.0,
            AnalysisKind::Axisymmetric,
        )
        .unwrap();
        assert_eq!(b[(2, 0)], 0.125);
        assert_eq!(b[(2, 2)], 0.375);
        assert_eq!(b[(2, 1)], 0.0);
        assert_eq!(b[(0, 2)], 3.0);
        assert_eq!(b[(3, 3)], 3.0);
    }

    #[test]
    fn axisymmetric_point_on_axis_is_an_error() {
        let e = strain_displacement::<2>(&[1.0], &[[0.0, 0.0]], 0.0, AnalysisKind::Axisymmetric)
            .unwrap_err();
        assert!(e.message.contains("r = 0"), "{}", e.message);
    }

    #[test]
    fn bbar_keeps_deviatoric_part_and_takes_centre_dilatation() {
        let mut b = SMatrix::<f64, 4, 2>::new(1.0, 0.0, 0.0, 2.0, 0.5, 0.0, 3.0, 0.0);
        let bc = SMatrix::<f64, 4, 2>::new(4.0, 0.0, 0.0, 1.0, 0.0, 0.0, 7.0, 0.0);
        let before = b;
        apply_bbar(&mut b, &bc);
        for j in 0..2 {
            let vol = |m: &SMatrix<f64, 4, 2>| m[(0, j)] + m[(1, j)] + m[(2, j)];
            assert!((vol(&b) - vol(&bc)).abs() < 1e-14);
            for i in 0..3 {
                let dev = |m: &SMatrix<f64, 4, 2>| m[(i, j)] - vol(m) / 3.0;
                assert!((dev(&b) - dev(&before)).abs() < 1e-14);
            }
            assert_eq!(b[(3, j)], before[(3, j)]);
        }
    }
}
