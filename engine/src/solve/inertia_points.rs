//! The mass and rotary inertia of a 3D rigid body as point masses at
//! body-fixed points (issue 19): the equimomental system of six points.
//!
//! With the principal moments `J_k` and axes `q_k` of the inertia tensor
//! `J` about the centre, a pair of equal masses `mu_k` at `+-a q_k` adds
//! `2 mu_k a^2 (I - q_k q_k^T)` to `J`; the three pairs give `J` when `2
//! mu_k a^2 = S - J_k`, `S = (J_1 + J_2 + J_3) / 2` (non-negative by the
//! triangle inequality of a body's principal moments, `J_k <= J_i + J_j`).
//! Their total mass is `S / a^2`: `a = sqrt(S / m)` makes it the body's
//! mass `m`, centred at the centre (the pairs are symmetric). Tied to the
//! body like its nodes, the points carry its kinetic energy
//! `m |v_c|^2 / 2 + omega . J omega / 2` exactly for any rigid motion, and the
//! translational time integration of the points gives the rotational
//! dynamics, gyroscopic terms included (Euler's equations are not written:
//! `d/dt (sum m_i x_i x v_i) = moment` is what the points' Newton laws sum
//! to).

/// The points `(offset from the centre, mass)` with mass `mass` and
/// inertia tensor `j` about the centre; empty when `j` is zero (the mass
/// then sits at the centre). Pairs of zero mass are left out.
pub fn inertia_points(mass: f64, j: [[f64; 3]; 3]) -> Result<Vec<([f64; 3], f64)>, String> {
    let scale = j.iter().flatten().fold(0.0_f64, |a, x| a.max(x.abs()));
    if !j.iter().flatten().all(|x| x.is_finite()) || !mass.is_finite() {
        return Err("the mass and inertia must be finite".into());
    }
    if scale == 0.0 {
        return Ok(Vec::new());
    }
    for (a, b) in [(0, 1), (1, 2), (0, 2)] {
        if (j[a][b] - j[b][a]).abs() > 1e-12 * scale {
            return Err("the inertia tensor is not symmetric".into());
        }
    }
    if mass <= 0.0 {
        return Err(
            "a body with rotary inertia needs its mass (`mass = ..`): the inertia is carried by \
             point masses at body-fixed points"
                .into(),
        );
    }
    let m = nalgebra::Matrix3::from_fn(|r, c| j[r][c]);
    let eig = m.symmetric_eigen();
    let moments: [f64; 3] = std::array::from_fn(|k| eig.eigenvalues[k]);
    let sum = 0.5 * (moments[0] + moments[1] + moments[2]);
    let tol = 1e-12 * scale;
    if moments.iter().any(|&jk| jk < -tol) {
        return Err(format!(
            "the inertia tensor is not positive: principal moments {moments:?}"
        ));
    }
    if moments.iter().any(|&jk| sum - jk < -tol) {
        return Err(format!(
            "no body has these principal moments {moments:?}: each must be at most the sum of \
             the other two"
        ));
    }
    let a2 = sum / mass;
    let a = a2.sqrt();
    let mut out = Vec::new();
    for (k, &jk) in moments.iter().enumerate() {
        let mu = ((sum - jk).max(0.0)) / (2.0 * a2);
        if mu <= 0.0 {
            continue;
        }
        let q: [f64; 3] = std::array::from_fn(|l| eig.eigenvectors[(l, k)]);
        out.push((q.map(|x| a * x), mu));
        out.push((q.map(|x| -a * x), mu));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The points' mass, first moment and inertia tensor are the body's.
    fn check(mass: f64, j: [[f64; 3]; 3]) {
        let pts = inertia_points(mass, j).unwrap();
        let m: f64 = pts.iter().map(|p| p.1).sum();
        assert!((m - mass).abs() < 1e-13 * mass, "{m} vs {mass}");
        for l in 0..3 {
            let first: f64 = pts.iter().map(|p| p.1 * p.0[l]).sum();
            assert!(first.abs() < 1e-13, "first moment {first}");
        }
        let scale = j.iter().flatten().fold(0.0_f64, |a, x| a.max(x.abs()));
        for r in 0..3 {
            for c in 0..3 {
                let x: f64 = pts
                    .iter()
                    .map(|(o, mu)| {
                        let o2 = o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
                        mu * (if r == c { o2 } else { 0.0 } - o[r] * o[c])
                    })
                    .sum();
                assert!((x - j[r][c]).abs() < 1e-12 * scale, "J[{r}][{c}] {x}");
            }
        }
    }

    #[test]
    fn the_points_have_the_body_mass_and_inertia() {
        // a general tensor, a symmetric top, a thin rod (one pair only)
        check(2.5, [[3.0, -0.4, 0.2], [-0.4, 2.0, 0.3], [0.2, 0.3, 4.0]]);
        check(1.0, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.6]]);
        let rod = inertia_points(3.0, [[0.0; 3], [0.0, 2.0, 0.0], [0.0, 0.0, 2.0]]).unwrap();
        assert_eq!(rod.len(), 2);
        check(3.0, [[0.0; 3], [0.0, 2.0, 0.0], [0.0, 0.0, 2.0]]);
        assert!(inertia_points(1.0, [[0.0; 3]; 3]).unwrap().is_empty());
        // refused: no mass, not a body's moments, not symmetric
        assert!(inertia_points(0.0, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).is_err());
        assert!(inertia_points(1.0, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 3.0]]).is_err());
        assert!(inertia_points(1.0, [[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).is_err());
    }
}
