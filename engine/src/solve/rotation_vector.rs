//! The total rotation vector of a 3D rigid body (issue 19): the rotation
//! `R(psi) = exp([psi]x)` of a vector `r`, with its first and second
//! derivatives in `psi`, exact to round-off at any angle.
//!
//! Rodrigues' formula written with coefficients that are smooth functions
//! of `s = psi . psi` (no `1 / |psi|` anywhere):
//!
//! `R r = c1(s) r + c2(s) psi x r + c3(s) (psi . r) psi`,
//! `c1 = cos t`, `c2 = sin t / t`, `c3 = (1 - cos t) / t^2`, `t = sqrt s`.
//!
//! Their `s`-derivatives `c'`, `c''` come from power series below `s = 1`
//! (`c_k = sum (-1)^n s^n / (2n + k)!`) and from the closed forms above
//! (`c1' = -c2 / 2`, `c2' = (c1 - c2) / (2s)`, `c3' = (c2 / 2 - c3) / s`,
//! and their derivatives). With `A = c1' r + c2' psi x r + c3' (psi . r)
//! psi` and `B` the same with `c''`:
//!
//! - `G_j = d(R r)/d psi_j = 2 psi_j A + c2 e_j x r + c3 (r_j psi + (psi .
//!   r) e_j)`;
//! - `H_ij = d2(R r)/d psi_i d psi_j = 2 delta_ij A + 4 psi_i psi_j B + 2
//!   psi_j (c2' e_i x r + c3' (r_i psi + (psi . r) e_i)) + 2 psi_i (c2' e_j
//!   x r + c3' (r_j psi + (psi . r) e_j)) + c3 (r_j e_i + r_i e_j)`.
//!
//! The map is smooth everywhere; its differential `G` loses rank where
//! `|psi|` is a non-zero multiple of `2 pi` (the total rotation vector's
//! known singularity), which a prescribed rotation never meets (its three
//! components are prescribed) and a free body avoids by its change of
//! chart past `|psi| = pi` (`rotation_chart.rs`).

/// `R(psi) r` and its derivatives in `psi`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rotated {
    /// `R(psi) r`.
    pub p: [f64; 3],
    /// `g[l][j] = d p_l / d psi_j`.
    pub g: [[f64; 3]; 3],
    /// `h[l][i][j] = d2 p_l / d psi_i d psi_j` (symmetric in `i`, `j`).
    pub h: [[[f64; 3]; 3]; 3],
}

/// `c[k] = [c_k, c_k', c_k'']` (`k` = 1, 2, 3 of the module doc) at `s =
/// |psi|^2`.
fn coefficients(s: f64) -> [[f64; 3]; 3] {
    if s < 1.0 {
        // c_k = sum_n a_n s^n, a_n = (-1)^n / (2n + k)!: 20 terms leave
        // 1 / 40! behind
        let mut c = [[0.0; 3]; 3];
        for (k, ck) in c.iter_mut().enumerate() {
            let mut fact: f64 = (1..=k).map(|i| i as f64).product();
            for n in 0..20 {
                if n > 0 {
                    fact *= ((2 * n + k - 1) * (2 * n + k)) as f64;
                }
                let a = if n % 2 == 0 { 1.0 } else { -1.0 } / fact;
                let nf = n as f64;
                ck[0] += a * s.powi(n as i32);
                if n >= 1 {
                    ck[1] += a * nf * s.powi(n as i32 - 1);
                }
                if n >= 2 {
                    ck[2] += a * nf * (nf - 1.0) * s.powi(n as i32 - 2);
                }
            }
        }
        return c;
    }
    let t = s.sqrt();
    let (sn, cs) = t.sin_cos();
    let (c1, c2, c3) = (cs, sn / t, (1.0 - cs) / s);
    let d1 = -0.5 * c2;
    let d2 = (c1 - c2) / (2.0 * s);
    let d3 = (0.5 * c2 - c3) / s;
    let e1 = -0.5 * d2;
    let e2 = (d1 - d2) / (2.0 * s) - d2 / s;
    let e3 = (0.5 * d2 - 2.0 * d3) / s;
    [[c1, d1, e1], [c2, d2, e2], [c3, d3, e3]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit(j: usize) -> [f64; 3] {
    let mut e = [0.0; 3];
    e[j] = 1.0;
    e
}

/// `R(psi) r` with its first and second derivatives in `psi`.
pub fn rotate(psi: [f64; 3], r: [f64; 3]) -> Rotated {
    let s = dot(psi, psi);
    let [[c1, d1, e1], [c2, d2, e2], [c3, d3, e3]] = coefficients(s);
    let w = cross(psi, r);
    let q = dot(psi, r);
    let comb = |a: f64, b: f64, c: f64| -> [f64; 3] {
        std::array::from_fn(|l| a * r[l] + b * w[l] + c * q * psi[l])
    };
    let p = comb(c1, c2, c3);
    let a = comb(d1, d2, d3);
    let b = comb(e1, e2, e3);
    let ex: [[f64; 3]; 3] = std::array::from_fn(|j| cross(unit(j), r));
    let mut g = [[0.0; 3]; 3];
    let mut h = [[[0.0; 3]; 3]; 3];
    for l in 0..3 {
        for j in 0..3 {
            let dj = if l == j { 1.0 } else { 0.0 };
            g[l][j] = 2.0 * psi[j] * a[l] + c2 * ex[j][l] + c3 * (r[j] * psi[l] + q * dj);
            for i in 0..3 {
                let di = if l == i { 1.0 } else { 0.0 };
                let dij = if i == j { 1.0 } else { 0.0 };
                h[l][i][j] = 2.0 * dij * a[l]
                    + 4.0 * psi[i] * psi[j] * b[l]
                    + 2.0 * psi[j] * (d2 * ex[i][l] + d3 * (r[i] * psi[l] + q * di))
                    + 2.0 * psi[i] * (d2 * ex[j][l] + d3 * (r[j] * psi[l] + q * dj))
                    + c3 * (r[j] * di + r[i] * dj);
            }
        }
    }
    Rotated { p, g, h }
}

/// `c4 = (t - sin t) / t^3` and its `s`-derivative at `s = |psi|^2`
/// (`c4 = sum (-1)^n s^n / (2n + 3)!` below `s = 1`, `(1 - c2) / s` and
/// `-(c2' + c4) / s` above).
fn c4(s: f64) -> [f64; 2] {
    if s < 1.0 {
        let (mut c, mut d) = (0.0, 0.0);
        let mut fact = 6.0;
        for n in 0..20 {
            if n > 0 {
                fact *= ((2 * n + 2) * (2 * n + 3)) as f64;
            }
            let a = if n % 2 == 0 { 1.0 } else { -1.0 } / fact;
            c += a * s.powi(n);
            if n >= 1 {
                d += a * n as f64 * s.powi(n - 1);
            }
        }
        return [c, d];
    }
    let [_, [c2, d2, _], _] = coefficients(s);
    let c = (1.0 - c2) / s;
    [c, -(d2 + c) / s]
}

/// The generalized force on the total rotation vector `psi` of a spatial
/// moment `m` (fixed in space) and its derivative: `f = T(psi)^T m`,
/// `T = I + c3 [psi]x + c4 [psi]x^2` the differential of `exp` in the
/// spatial frame (`dR R^T = [T dpsi]x`), so that `f . dpsi = m . dphi`
/// for every virtual rotation `dphi = T dpsi` (the moment's virtual work);
/// `f = m - c3 psi x m + c4 (psi (psi . m) - s m)`, `df[i][j] = d f_i / d
/// psi_j`. At `psi` parallel to `m`, `f = m`.
pub fn moment_force(psi: [f64; 3], m: [f64; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    let s = dot(psi, psi);
    let [_, _, [c3, d3, _]] = coefficients(s);
    let [k4, d4] = c4(s);
    let w = cross(psi, m);
    let pm = dot(psi, m);
    let f: [f64; 3] = std::array::from_fn(|i| m[i] - c3 * w[i] + k4 * (psi[i] * pm - s * m[i]));
    let mut df = [[0.0; 3]; 3];
    for (j, col) in (0..3).map(|j| (j, cross(unit(j), m))) {
        for i in 0..3 {
            let delta = if i == j { 1.0 } else { 0.0 };
            df[i][j] = -2.0 * psi[j] * d3 * w[i] - c3 * col[i]
                + 2.0 * psi[j] * d4 * (psi[i] * pm - s * m[i])
                + k4 * (delta * pm + psi[i] * m[j] - 2.0 * psi[j] * m[i]);
        }
    }
    (f, df)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// `R(psi) r` by nalgebra's axis-angle rotation (an independent formula).
    fn reference(psi: [f64; 3], r: [f64; 3]) -> [f64; 3] {
        let rot = nalgebra::Rotation3::from_scaled_axis(nalgebra::Vector3::from(psi));
        let x = rot * nalgebra::Vector3::from(r);
        [x[0], x[1], x[2]]
    }

    /// Largest error of `rotate` against the reference rotation and of its
    /// derivatives against central differences of the lower one.
    fn errors(psi: [f64; 3], r: [f64; 3]) -> (f64, f64, f64) {
        let x = rotate(psi, r);
        let e0 = (0..3)
            .map(|l| (x.p[l] - reference(psi, r)[l]).abs())
            .fold(0.0, f64::max);
        let step = 1e-6;
        let (mut e1, mut e2): (f64, f64) = (0.0, 0.0);
        for j in 0..3 {
            let (mut a, mut b) = (psi, psi);
            a[j] += step;
            b[j] -= step;
            let (xa, xb) = (rotate(a, r), rotate(b, r));
            for l in 0..3 {
                let fd = (xa.p[l] - xb.p[l]) / (2.0 * step);
                e1 = e1.max((fd - x.g[l][j]).abs());
                for i in 0..3 {
                    let fd = (xa.g[l][i] - xb.g[l][i]) / (2.0 * step);
                    e2 = e2.max((fd - x.h[l][i][j]).abs());
                }
            }
        }
        (e0, e1, e2)
    }

    /// The moment's generalized force is work-conjugate: with `dR R^T =
    /// [dphi]x` measured from `rotate`'s own derivative (`G_j r = dphi_j x
    /// R r` for the three body vectors `r = e_k`, solved for `dphi_j`),
    /// `f . dpsi = m . dphi`; its derivative matches central differences;
    /// at `psi` parallel to `m`, `f = m`. Either side of the series' limit
    /// and at large angles.
    #[test]
    fn moment_force_is_work_conjugate_and_its_derivative_matches_differences() {
        let m = [0.7, -0.4, 1.3];
        for psi in [
            [0.0, 0.0, 0.0],
            [0.2, 0.1, -0.3],
            [0.6, 0.0, 0.8 - 1e-12],
            [0.6, 0.0, 0.8 + 1e-12],
            [1.5, -2.0, 1.1],
            [-2.5, 3.0, 1.0],
        ] {
            let (f, df) = moment_force(psi, m);
            // dphi_j from G: the columns R e_k turn by dphi_j x R e_k; with
            // a = R e_0, b = R e_1: dphi = a x da + b x db + c x dc over 2
            // (for an orthonormal frame, sum_k e'_k x (w x e'_k) = 2 w)
            let frame: Vec<Rotated> = (0..3).map(|k| rotate(psi, unit(k))).collect();
            for (j, fj) in f.iter().enumerate() {
                let mut dphi = [0.0; 3];
                for x in &frame {
                    let d = [x.g[0][j], x.g[1][j], x.g[2][j]];
                    let c = cross(x.p, d);
                    for (o, ci) in dphi.iter_mut().zip(c) {
                        *o += 0.5 * ci;
                    }
                }
                let work = dot(m, dphi);
                assert!((fj - work).abs() < 1e-13, "{psi:?} {j}: {fj} vs {work}");
            }
            let step = 1e-6;
            for j in 0..3 {
                let (mut a, mut b) = (psi, psi);
                a[j] += step;
                b[j] -= step;
                let (fa, fb) = (moment_force(a, m).0, moment_force(b, m).0);
                for i in 0..3 {
                    let fd = (fa[i] - fb[i]) / (2.0 * step);
                    assert!(
                        (fd - df[i][j]).abs() < 1e-8,
                        "{psi:?} {i} {j}: {fd} vs {}",
                        df[i][j]
                    );
                }
            }
        }
        let along: [f64; 3] = std::array::from_fn(|i| 2.1 * m[i]);
        let (f, _) = moment_force(along, m);
        for i in 0..3 {
            assert!((f[i] - m[i]).abs() < 1e-14);
        }
    }

    /// At zero, a small angle, either side of the series' limit `|psi| =
    /// 1`, and large angles (near pi and beyond).
    #[test]
    fn rotation_and_derivatives_match_the_reference_and_differences() {
        let r = [0.3, -1.2, 0.7];
        for psi in [
            [0.0, 0.0, 0.0],
            [1e-9, -2e-9, 5e-10],
            [0.2, 0.1, -0.3],
            [0.6, 0.0, 0.8 - 1e-12],
            [0.6, 0.0, 0.8 + 1e-12],
            [1.5, -2.0, 1.1],
            [0.0, 0.0, 3.1],
            [-2.5, 3.0, 1.0],
        ] {
            let (e0, e1, e2) = errors(psi, r);
            assert!(e0 < 1e-14, "{psi:?}: R r {e0:e}");
            assert!(e1 < 1e-8, "{psi:?}: G {e1:e}");
            assert!(e2 < 1e-8, "{psi:?}: H {e2:e}");
        }
        // at zero: G = -[r]x, the infinitesimal rotation
        let x = rotate([0.0; 3], r);
        assert_eq!(x.g[0], [0.0, r[2], -r[1]]);
    }

    proptest! {
        #[test]
        fn derivatives_are_exact_at_any_rotation(
            psi in proptest::array::uniform3(-4.0f64..4.0),
            r in proptest::array::uniform3(-2.0f64..2.0),
        ) {
            let (e0, e1, e2) = errors(psi, r);
            prop_assert!(e0 < 1e-13, "R r {e0:e}");
            prop_assert!(e1 < 1e-7, "G {e1:e}");
            prop_assert!(e2 < 1e-7, "H {e2:e}");
        }
    }
}
