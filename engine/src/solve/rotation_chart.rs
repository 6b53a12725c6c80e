//! Re-charting the total rotation vector of a free 3D rigid body (issue
//! 19), so that it turns any number of times.
//!
//! The spin node of a 3D rigid body carries the total rotation vector
//! `psi` (`R = exp([psi]x)`, `rotation_vector.rs`), whose differential is
//! singular at `|psi| = 2 pi`. The rotation vectors `psi` and `psi' = psi
//! (1 - 2 pi / |psi|)` (the same axis, the angle `|psi| - 2 pi`) give the
//! same rotation, and `psi -> psi'` is smooth where `psi != 0`: it is
//! another chart of the rotation group. When a converged increment ends
//! with `|psi| > pi` on a free body, the committed state is carried over
//! to that chart (`|psi'| = 2 pi - |psi| < pi`), so the next increments
//! stay at least `pi` away from the singular sphere however many turns
//! the body makes (Cardona & Geradin, Flexible Multibody Dynamics, 2001,
//! section 4.7: the "complement rotation"; Ibrahimbegovic, Frey & Kozar,
//! IJNME 38, 1995, the same update of the total rotation vector).
//!
//! Everything of the committed state that is expressed in `psi` is carried
//! over, the rotation itself unchanged:
//!
//! - the rates: with `v_k = R e_k` and `G_k = d(R e_k)/d psi`, `H_k` its
//!   second derivative, the velocities `d(R e_k)/dt = G_k psi_dot` and the
//!   accelerations `d2(R e_k)/dt2 = G_k psi_ddot + H_k[psi_dot, psi_dot]`
//!   of the body-fixed triad do not depend on the chart; `G_k = -[v_k]x T`
//!   with `T` the tangent map (`omega = T psi_dot`), so `T = 1/2 sum_k
//!   [v_k]x G_k` (`sum_k [v_k]x^2 = -2 I`), and the new rates solve `T'
//!   psi_dot' = T psi_dot` and `T' psi_ddot' = 1/2 sum_k [v_k]x (G_k
//!   psi_ddot + H_k[psi_dot, psi_dot] - H'_k[psi_dot', psi_dot'])`;
//! - the generalized forces conjugate to `psi` (virtual work `f . d psi = m
//!   . d theta`, `d theta = T d psi`): `f' = T'^T T^-T f`, so the work
//!   integrals of the energy audit see the same power.
//!
//! A prescribed rotation (its three components prescribed) is never
//! re-charted: it has no singularity to avoid.

use super::rotation_vector::rotate;
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::{PI, TAU};

/// The equivalent rotation vector `psi (1 - 2 pi / |psi|)` of `psi` when
/// `|psi| > pi` (`None`: `psi` is already in the ball of radius `pi`).
pub fn equivalent(psi: [f64; 3]) -> Option<[f64; 3]> {
    let n = norm(psi);
    (n > PI).then(|| complement(psi))
}

/// `psi (1 - 2 pi / |psi|)` (`psi` itself at 0): the chart map, also
/// applied to other committed values of the same body (the predictor's
/// `u_{n-1}`) so that their difference stays a small rotation.
pub fn complement(psi: [f64; 3]) -> [f64; 3] {
    let n = norm(psi);
    if n == 0.0 {
        return psi;
    }
    psi.map(|x| x * (1.0 - TAU / n))
}

fn norm(psi: [f64; 3]) -> f64 {
    (psi[0] * psi[0] + psi[1] * psi[1] + psi[2] * psi[2]).sqrt()
}

/// The triad `v_k = R e_k`, `G_k` and `H_k` at `psi`.
struct Triad {
    /// `v_k = R(psi) e_k`.
    v: [Vector3<f64>; 3],
    /// `G_k = d v_k / d psi`.
    g: [Matrix3<f64>; 3],
    /// `H_k[l][i][j] = d2 (v_k)_l / d psi_i d psi_j`.
    h: [[[[f64; 3]; 3]; 3]; 3],
    /// The tangent map `T` (`omega = T psi_dot`).
    t: Matrix3<f64>,
}

impl Triad {
    fn at(psi: [f64; 3]) -> Self {
        let r: [_; 3] = std::array::from_fn(|k| {
            let mut e = [0.0; 3];
            e[k] = 1.0;
            rotate(psi, e)
        });
        let v = r.map(|x| Vector3::from(x.p));
        let g = r.map(|x| Matrix3::from_fn(|l, j| x.g[l][j]));
        let h = r.map(|x| x.h);
        let mut t = Matrix3::zeros();
        for k in 0..3 {
            t += v[k].cross_matrix() * g[k];
        }
        Triad {
            v,
            g,
            h,
            t: 0.5 * t,
        }
    }

    /// `H_k[a, b]`.
    fn second(&self, k: usize, a: &Vector3<f64>, b: &Vector3<f64>) -> Vector3<f64> {
        Vector3::from_fn(|l, _| {
            let mut s = 0.0;
            for i in 0..3 {
                for j in 0..3 {
                    s += self.h[k][l][i][j] * a[i] * b[j];
                }
            }
            s
        })
    }
}

/// The change from the chart of `psi` to that of `psi'` (the same
/// rotation) for the committed rates and forces.
pub struct Chart {
    old: Triad,
    new: Triad,
    /// `T'^-1`.
    new_inverse: Matrix3<f64>,
    /// `T^-T`.
    old_inverse_t: Matrix3<f64>,
}

impl Chart {
    /// The change of chart `psi -> new`; `None` where a tangent map is
    /// singular (`|psi|` or `|new|` a non-zero multiple of `2 pi`).
    pub fn new(psi: [f64; 3], new: [f64; 3]) -> Option<Self> {
        let old = Triad::at(psi);
        let new = Triad::at(new);
        let new_inverse = new.t.try_inverse()?;
        let old_inverse_t = old.t.try_inverse()?.transpose();
        Some(Chart {
            old,
            new,
            new_inverse,
            old_inverse_t,
        })
    }

    /// The rate `psi_dot'` of the new chart.
    pub fn velocity(&self, psi_dot: [f64; 3]) -> [f64; 3] {
        let w = self.old.t * Vector3::from(psi_dot);
        (self.new_inverse * w).into()
    }

    /// The second rate `psi_ddot'` of the new chart, given the old rates.
    pub fn acceleration(&self, psi_dot: [f64; 3], psi_ddot: [f64; 3]) -> [f64; 3] {
        let (v, a) = (Vector3::from(psi_dot), Vector3::from(psi_ddot));
        let vn = Vector3::from(self.velocity(psi_dot));
        let mut s = Vector3::zeros();
        for k in 0..3 {
            let w = self.old.g[k] * a + self.old.second(k, &v, &v) - self.new.second(k, &vn, &vn);
            // the same triad in both charts: v_k from the old one
            s += self.old.v[k].cross(&w);
        }
        (self.new_inverse * (0.5 * s)).into()
    }

    /// The generalized force `f'` conjugate to the new chart's `psi'`.
    pub fn force(&self, f: [f64; 3]) -> [f64; 3] {
        let m = self.old_inverse_t * Vector3::from(f);
        (self.new.t.transpose() * m).into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A smooth path `psi(t)` just past `|psi| = pi` (3.19 at `t = 0.3`).
    fn path(t: f64) -> [f64; 3] {
        [
            0.8 + 0.3 * t + 0.1 * t * t,
            -1.2 + 0.5 * t,
            2.9 - 0.2 * t + 0.4 * t * t,
        ]
    }

    #[test]
    fn same_rotation_smaller_angle() {
        let psi = path(0.3);
        let n = equivalent(psi).expect("past pi");
        assert!(norm(n) < PI && (norm(psi) + norm(n) - TAU).abs() < 1e-14);
        for k in 0..3 {
            let mut e = [0.0; 3];
            e[k] = 1.0;
            let (a, b) = (rotate(psi, e).p, rotate(n, e).p);
            for l in 0..3 {
                assert!((a[l] - b[l]).abs() < 1e-14, "R e_{k}: {a:?} vs {b:?}");
            }
        }
        assert_eq!(equivalent([0.0, 3.0, 0.0]), None);
        assert_eq!(complement([0.0; 3]), [0.0; 3]);
    }

    /// The chart's rates against central differences of the re-charted
    /// path `psi'(t) = complement(psi(t))`, and the power of a force.
    #[test]
    fn rates_and_forces_match_the_recharted_path() {
        let t0 = 0.3;
        let h = 1e-4;
        let d1 = |f: &dyn Fn(f64) -> [f64; 3]| -> [f64; 3] {
            std::array::from_fn(|i| (f(t0 + h)[i] - f(t0 - h)[i]) / (2.0 * h))
        };
        let d2 = |f: &dyn Fn(f64) -> [f64; 3]| -> [f64; 3] {
            std::array::from_fn(|i| (f(t0 + h)[i] - 2.0 * f(t0)[i] + f(t0 - h)[i]) / (h * h))
        };
        let recharted = |t: f64| complement(path(t));
        let (v, a) = (d1(&path), d2(&path));
        let (vn, an) = (d1(&recharted), d2(&recharted));
        let chart = Chart::new(path(t0), recharted(t0)).expect("regular");
        let (cv, ca) = (chart.velocity(v), chart.acceleration(v, a));
        for i in 0..3 {
            assert!((cv[i] - vn[i]).abs() < 1e-7, "velocity {cv:?} vs {vn:?}");
            assert!(
                (ca[i] - an[i]).abs() < 1e-5,
                "acceleration {ca:?} vs {an:?}"
            );
        }
        // the same power f . psi_dot = f' . psi_dot'
        let f = [0.7, -0.4, 1.3];
        let fnew = chart.force(f);
        let p0: f64 = (0..3).map(|i| f[i] * v[i]).sum();
        let p1: f64 = (0..3).map(|i| fnew[i] * cv[i]).sum();
        assert!((p0 - p1).abs() < 1e-12 * p0.abs().max(1.0), "{p0} vs {p1}");
    }
}
