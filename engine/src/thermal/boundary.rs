//! Boundary terms of heat conduction on a straight edge `[a, b]` with linear
//! shape functions, integrated exactly: a heat flux `q` gives nodal heat
//! `int N_a q dA`; a convection film `h` gives the matrix
//! `int h N_a N_b dA` and the load `int h T_ambient N_a dA`.
//!
//! Plane: `dA = t ds`. Axisymmetric: `dA = 2 pi r ds` with `r` linear along
//! the edge (the same consistent rule as the contact tributary areas,
//! `contact::tributary`), totals over the full ring.

use crate::model::AnalysisKind;
use std::f64::consts::PI;

/// `int N_a dA` for the two nodes of edge `pa -> pb`.
pub fn edge_weights(pa: [f64; 2], pb: [f64; 2], kind: AnalysisKind, thickness: f64) -> [f64; 2] {
    let len = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
    match kind {
        AnalysisKind::PlaneStrain | AnalysisKind::PlaneStress | AnalysisKind::Solid => {
            let w = 0.5 * len * thickness;
            [w, w]
        }
        AnalysisKind::Axisymmetric => {
            let (ra, rb) = (pa[0].max(0.0), pb[0].max(0.0));
            [
                2.0 * PI * len * (2.0 * ra + rb) / 6.0,
                2.0 * PI * len * (ra + 2.0 * rb) / 6.0,
            ]
        }
    }
}

/// `int N_a N_b dA` for the two nodes of edge `pa -> pb` (row-major 2x2).
pub fn edge_mass(pa: [f64; 2], pb: [f64; 2], kind: AnalysisKind, thickness: f64) -> [[f64; 2]; 2] {
    let len = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
    match kind {
        AnalysisKind::PlaneStrain | AnalysisKind::PlaneStress | AnalysisKind::Solid => {
            let d = len * thickness / 3.0;
            let o = len * thickness / 6.0;
            [[d, o], [o, d]]
        }
        AnalysisKind::Axisymmetric => {
            let (ra, rb) = (pa[0].max(0.0), pb[0].max(0.0));
            let c = 2.0 * PI * len / 12.0;
            [
                [c * (3.0 * ra + rb), c * (ra + rb)],
                [c * (ra + rb), c * (ra + 3.0 * rb)],
            ]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edge_mass_rows_sum_to_the_weights_and_weights_to_the_area() {
        let (pa, pb) = ([1.0, 0.0], [3.0, 1.0]);
        for kind in [AnalysisKind::PlaneStrain, AnalysisKind::Axisymmetric] {
            let w = edge_weights(pa, pb, kind, 2.0);
            let m = edge_mass(pa, pb, kind, 2.0);
            for a in 0..2 {
                assert!((m[a][0] + m[a][1] - w[a]).abs() < 1e-12);
            }
            let len = 5f64.sqrt();
            let area = match kind {
                AnalysisKind::Axisymmetric => 2.0 * PI * 2.0 * len,
                _ => 2.0 * len,
            };
            assert!((w[0] + w[1] - area).abs() < 1e-12);
        }
    }
}
