//! Rigid-body modes from nodal coordinates: the near-null space of linear
//! elasticity that smoothed-aggregation AMG (GAMG) needs to build good
//! coarse spaces. 2D: two translations and the rotation about z; 3D: three
//! translations and three rotations. Vectors are node-blocked
//! (`dim * node + c`), like the matrix; they are not orthonormalised here
//! (that needs the distributed dot products, see `krylov::near_null_space`).

/// The rigid-body modes of the nodes `coords` (`dim` values per node,
/// `dim` = 2 or 3): 3 vectors in 2D, 6 in 3D, each of length
/// `coords.len()`. Rotations are about `centre`, which keeps the vectors
/// well conditioned (pass the centroid of the whole mesh so that every rank
/// uses the same one). Any other `dim` gives no mode.
pub fn rigid_body_modes(coords: &[f64], dim: usize, centre: &[f64]) -> Vec<Vec<f64>> {
    if !(dim == 2 || dim == 3) || centre.len() != dim {
        return Vec::new();
    }
    let n = coords.len() / dim;
    let n_modes = if dim == 2 { 3 } else { 6 };
    let mut modes = vec![vec![0.0; coords.len()]; n_modes];
    for i in 0..n {
        let x: Vec<f64> = (0..dim).map(|c| coords[dim * i + c] - centre[c]).collect();
        for c in 0..dim {
            modes[c][dim * i + c] = 1.0;
        }
        if dim == 2 {
            // rotation about z: (-y, x)
            modes[2][2 * i] = -x[1];
            modes[2][2 * i + 1] = x[0];
        } else {
            // rotations about x, y, z: e_k x (x - centre)
            modes[3][3 * i + 1] = -x[2];
            modes[3][3 * i + 2] = x[1];
            modes[4][3 * i] = x[2];
            modes[4][3 * i + 2] = -x[0];
            modes[5][3 * i] = -x[1];
            modes[5][3 * i + 1] = x[0];
        }
    }
    modes
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Small-strain tensor of the linear field `u` sampled at the 4 nodes of
    /// the unit tetrahedron (exact for a linear field): zero for a rigid mode.
    fn tet_strain(u: &[f64]) -> [[f64; 3]; 3] {
        // grad u = [u1 - u0, u2 - u0, u3 - u0] for nodes 0, e_x, e_y, e_z
        let mut g = [[0.0; 3]; 3];
        for (k, row) in g.iter_mut().enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                *v = u[3 * (k + 1) + c] - u[c]; // d u_c / d x_k
            }
        }
        let mut e = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                e[i][j] = 0.5 * (g[i][j] + g[j][i]);
            }
        }
        e
    }

    proptest! {
        #[test]
        fn rigid_modes_3d_are_strain_free(cx in -5.0..5.0f64, cy in -5.0..5.0f64, cz in -5.0..5.0f64) {
            let coords = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
            let modes = rigid_body_modes(&coords, 3, &[cx, cy, cz]);
            prop_assert_eq!(modes.len(), 6);
            for m in &modes {
                for row in tet_strain(m) {
                    for v in row {
                        prop_assert!(v.abs() < 1e-12);
                    }
                }
            }
        }

        #[test]
        fn rigid_modes_2d_are_strain_free(cx in -5.0..5.0f64, cy in -5.0..5.0f64) {
            // unit triangle: grad u from nodes 0, e_x, e_y
            let coords = [0.0, 0.0, 1.0, 0.0, 0.0, 1.0];
            for m in rigid_body_modes(&coords, 2, &[cx, cy]) {
                let dux_dx = m[2] - m[0];
                let duy_dy = m[5] - m[1];
                let shear = (m[4] - m[0]) + (m[3] - m[1]);
                prop_assert!(dux_dx.abs() < 1e-12 && duy_dy.abs() < 1e-12 && shear.abs() < 1e-12);
            }
        }
    }

    #[test]
    fn modes_are_independent() {
        // 3D rotation modes of 4 non-coplanar nodes plus translations: rank 6
        let coords = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
        let modes = rigid_body_modes(&coords, 3, &[0.25, 0.25, 0.25]);
        let m = faer::Mat::<f64>::from_fn(12, 6, |i, j| modes[j][i]);
        let s = m.singular_values().unwrap();
        assert!(s.iter().all(|&v| v > 1e-3), "{s:?}");
        assert!(rigid_body_modes(&coords, 1, &[0.0]).is_empty());
    }
}
