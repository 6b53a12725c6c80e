//! J2 (von Mises) radial return with isotropic hardening, shared by the
//! small-strain (additive split, strains) and finite-strain (multiplicative
//! split, Hencky logarithmic elastic strains, exponential map) models.
//!
//! Given the trial elastic strain `e_tr` (small strain tensor, or
//! `1/2 ln b_e,tr`), the elastic predictor is
//! `s_tr = 2 G dev e_tr`, `q_tr = sqrt(3/2 s_tr : s_tr)`. If
//! `q_tr > sigma_y(ep_n)` the plastic multiplier solves
//! `q_tr - 3 G dgamma - sigma_y(ep_n + dgamma) = 0` (scalar Newton in `f64`,
//! then one Newton correction in the caller's scalar type so that
//! derivatives are exact), and `s = (1 - 3 G dgamma / q_tr) s_tr`,
//! `ep = ep_n + dgamma`. Stress (Cauchy for small strain, Kirchhoff for
//! finite strain): `K tr(e) I + s`.

use super::dual::Scalar;
use super::tensor::{deviator, norm2, trace, Sym};
use crate::model::{Hardening, Viscosity};

/// Elastic constants of the return mapping.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastic {
    /// Bulk modulus `K`.
    pub bulk: f64,
    /// Shear modulus `G`.
    pub shear: f64,
}

impl Elastic {
    /// From Young's modulus and Poisson's ratio.
    pub fn from_young(young: f64, poisson: f64) -> Self {
        Elastic {
            bulk: young / (3.0 * (1.0 - 2.0 * poisson)),
            shear: young / (2.0 * (1.0 + poisson)),
        }
    }

    /// Isotropic linear stress `K tr(e) I + 2 G dev(e)`.
    pub fn stress<T: Scalar>(&self, e: &Sym<T>) -> Sym<T> {
        let p = trace(e) * self.bulk;
        let s = deviator(e);
        let g2 = 2.0 * self.shear;
        [
            p + s[0] * g2,
            p + s[1] * g2,
            p + s[2] * g2,
            s[3] * g2,
            s[4] * g2,
            s[5] * g2,
        ]
    }
}

/// Result of a return mapping.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Returned<T> {
    /// Stress `K tr(e) I + s`.
    pub stress: Sym<T>,
    /// Elastic strain after the return.
    pub elastic_strain: Sym<T>,
    /// Equivalent plastic strain after the return.
    pub ep: f64,
    /// Plastic multiplier increment (0 when elastic).
    pub dgamma: f64,
}

/// Local iterations of the return mapping (Newton, bisection where Newton
/// leaves the bracket).
const MAX_LOCAL: usize = 200;

/// Radial return from the trial elastic strain `e_tr` with equivalent
/// plastic strain `ep_n` at the start of the increment. `viscosity =
/// Some((law, dt))` makes the flow rate dependent ([`Viscosity`]): the
/// von Mises stress during flow is `q = sigma_y(ep) + over(ep, r)` at the
/// rate `r = dgamma / dt`, integrated by backward Euler over the time
/// increment `dt` (consistency becomes `q_trial - 3 G dgamma -
/// sigma_y(ep_n + dgamma) - over(ep_n + dgamma, dgamma / dt) = 0`); `None`
/// is rate independent. The consistency equation is solved by Newton kept
/// inside the bracket `0 < dgamma < q_trial / 3G` (bisection where Newton
/// leaves it: a rate sensitivity below 1 has an infinite slope at 0).
/// A rate-dependent flow stress (Johnson-Cook) takes the plastic rate
/// `dgamma / dt` of the increment `dt` (`Hardening::rate_factor`): the
/// flow stress is `sigma_y(ep_n + dgamma) R(dgamma / dt)`, whose derivative
/// (the consistent tangent) includes the rate term.
pub fn radial_return<T: Scalar>(
    elastic: &Elastic,
    hardening: &Hardening,
    e_tr: &Sym<T>,
    ep_n: f64,
    viscosity: Option<(Viscosity, f64)>,
    dt: f64,
) -> Result<Returned<T>, String> {
    let g = elastic.shear;
    let tr = trace(e_tr);
    let dev = deviator(e_tr);
    let q = (norm2(&dev) * 1.5).sqrt() * (2.0 * g);
    let sy0 = hardening.flow_stress(ep_n);
    if q.re() <= sy0 * (1.0 + 1e-12) {
        return Ok(Returned {
            stress: elastic.stress(e_tr),
            elastic_strain: *e_tr,
            ep: ep_n,
            dgamma: 0.0,
        });
    }
    if viscosity.is_some_and(|(_, dt)| dt.is_nan() || dt <= 0.0) {
        // no time elapsed: a viscous material responds elastically
        return Ok(Returned {
            stress: elastic.stress(e_tr),
            elastic_strain: *e_tr,
            ep: ep_n,
            dgamma: 0.0,
        });
    }
    let qv = q.re();
    // the flow stress (with a Johnson-Cook rate factor) and its slope
    let flow = |dg: f64| hardening.flow_stress(ep_n + dg) * hardening.rate_factor(dg, dt).0;
    let flow_slope = |dg: f64| {
        let (r, dr) = hardening.rate_factor(dg, dt);
        hardening.slope(ep_n + dg) * r + hardening.flow_stress(ep_n + dg) * dr
    };
    // over-stress and its derivative in dgamma
    let over = |dg: f64| -> (f64, f64) {
        match viscosity {
            None => (0.0, 0.0),
            Some((Viscosity::Perzyna { eta }, dt)) => (eta * dg / dt, eta / dt),
            Some((Viscosity::PerzynaPower { rate, exponent }, dt)) => {
                let x = dg / (dt * rate);
                let a = 1.0 / exponent;
                let (sy, h) = (flow(dg), flow_slope(dg));
                let xa = x.powf(a);
                (sy * xa, h * xa + sy * a * x.powf(a - 1.0) / (dt * rate))
            }
            Some((Viscosity::NortonHoff { stress, rate, m }, dt)) => {
                let x = dg / (dt * rate);
                (
                    stress * x.powf(m),
                    stress * m * x.powf(m - 1.0) / (dt * rate),
                )
            }
        }
    };
    let resid = |dg: f64| qv - 3.0 * g * dg - flow(dg) - over(dg).0;
    let slope = |dg: f64| 3.0 * g + flow_slope(dg) + over(dg).1;
    // the residual's scale: the static flow stress, or the trial stress of
    // a law without one (pure Norton-Hoff)
    let scale = if sy0 > 0.0 { sy0 } else { qv };
    // r(lo) > 0 > r(hi) (the flow stress is not negative): a Newton step
    // leaving the bracket (or stalled by an infinite slope) bisects
    let (mut lo, mut hi): (f64, f64) = (0.0, qv / (3.0 * g));
    let mut dg: f64 = 0.0;
    let mut converged = false;
    for _ in 0..MAX_LOCAL {
        let r = resid(dg);
        if r > 0.0 {
            lo = lo.max(dg);
        } else {
            hi = hi.min(dg);
        }
        let newton = dg + r / slope(dg);
        let next = if newton.is_finite() && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        let step = (next - dg).abs();
        dg = next;
        if step <= 1e-14 * dg.max(1e-300) || resid(dg).abs() <= 1e-13 * scale {
            converged = true;
            break;
        }
    }
    if !converged || !dg.is_finite() {
        return Err(format!(
            "the plastic return mapping did not converge (trial von Mises stress {qv:e}, flow \
             stress {sy0:e})"
        ));
    }
    let visc_total = |dg: f64| over(dg).0;
    // one Newton correction in T: exact derivatives (implicit function theorem)
    let dg_t = (q - (3.0 * g * dg + flow(dg) + visc_total(dg))) / slope(dg) + dg;
    let factor = -(dg_t * (3.0 * g)) / q + 1.0;
    let p = tr * elastic.bulk;
    let g2 = 2.0 * g;
    let s = dev.map(|d| d * factor * g2);
    let m = tr / 3.0;
    let elastic_strain = [
        m + s[0] / g2,
        m + s[1] / g2,
        m + s[2] / g2,
        s[3] / g2,
        s[4] / g2,
        s[5] / g2,
    ];
    Ok(Returned {
        stress: [p + s[0], p + s[1], p + s[2], s[3], s[4], s[5]],
        elastic_strain,
        ep: ep_n + dg,
        dgamma: dg,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radial_return_lands_on_the_yield_surface() {
        let el = Elastic::from_young(200e3, 0.3);
        let h = Hardening::Swift {
            k: 500.0,
            eps0: 0.01,
            n: 0.2,
        };
        let e = [0.01, -0.004, -0.003, 0.002, -0.001, 0.003];
        let r = radial_return(&el, &h, &e, 0.02, None, 1.0).unwrap();
        assert!(r.dgamma > 0.0);
        let q = (1.5 * norm2(&deviator(&r.stress))).sqrt();
        assert!((q - h.flow_stress(r.ep)).abs() < 1e-9 * q, "{q}");
        // pressure unchanged by the (isochoric) return
        assert!((trace(&r.stress) - 3.0 * el.bulk * trace(&e)).abs() < 1e-9);
    }

    /// Johnson-Cook from a virgin point (infinite slope at ep = 0): the
    /// return lands on `(A + B ep^n)(1 + C ln(rate*))(1 - T*^m)` at the
    /// increment's plastic rate `dgamma / dt`.
    #[test]
    fn johnson_cook_return_lands_on_the_rate_dependent_surface() {
        let el = Elastic::from_young(124e3, 0.34);
        let h = Hardening::JohnsonCook {
            a: 90.0,
            b: 292.0,
            n: 0.31,
            c: 0.025,
            rate0: 1.0,
            m: 1.09,
            t_ref: 298.0,
            t_melt: 1356.0,
            temperature: 400.0,
        };
        let e = [0.02, -0.01, -0.01, 0.0, 0.0, 0.0];
        for dt in [1e-5, 1.0] {
            let r = radial_return(&el, &h, &e, 0.0, None, dt).unwrap();
            assert!(r.dgamma > 0.0);
            let q = (1.5 * norm2(&deviator(&r.stress))).sqrt();
            let rate = (r.dgamma / dt).max(1.0);
            let t_star: f64 = (400.0 - 298.0) / (1356.0 - 298.0);
            let closed = (90.0 + 292.0 * r.ep.powf(0.31))
                * (1.0 + 0.025 * rate.ln())
                * (1.0 - t_star.powf(1.09));
            assert!((q - closed).abs() < 1e-9 * q, "dt {dt}: {q} vs {closed}");
        }
    }
}
