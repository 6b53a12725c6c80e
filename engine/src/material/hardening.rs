//! Isotropic hardening laws: flow stress `sigma_y(ep)` and its slope; the
//! rate factor of Johnson-Cook (`rate_factor`).

use crate::model::Hardening;

impl Hardening {
    /// Flow stress at equivalent plastic strain `ep >= 0`.
    pub fn flow_stress(&self, ep: f64) -> f64 {
        match *self {
            Hardening::Linear {
                yield_stress,
                modulus,
            } => yield_stress + modulus * ep,
            Hardening::Swift { k, eps0, n } => k * (eps0 + ep).powf(n),
            Hardening::Voce {
                yield_stress,
                sigma_inf,
                delta,
            } => yield_stress + (sigma_inf - yield_stress) * (1.0 - (-delta * ep).exp()),
            Hardening::JohnsonCook { a, b, n, .. } => {
                (a + b * ep.max(0.0).powf(n)) * self.thermal_factor()
            }
        }
    }

    /// Johnson-Cook's thermal factor `1 - T*^m` (1 for the other laws).
    pub fn thermal_factor(&self) -> f64 {
        match *self {
            Hardening::JohnsonCook {
                m,
                t_ref,
                t_melt,
                temperature,
                ..
            } => {
                let t = ((temperature - t_ref) / (t_melt - t_ref)).clamp(0.0, 1.0);
                1.0 - t.powf(m)
            }
            _ => 1.0,
        }
    }

    /// The rate factor `R` of a plastic increment `dgamma` over `dt` and
    /// `dR / d dgamma`: Johnson-Cook `1 + C ln(dgamma / (dt rate0))` above
    /// the reference rate, `(1, 0)` below it, for `dt <= 0` and for the
    /// rate-independent laws.
    pub fn rate_factor(&self, dgamma: f64, dt: f64) -> (f64, f64) {
        match *self {
            Hardening::JohnsonCook { c, rate0, .. } if c > 0.0 && dt > 0.0 => {
                let rate = dgamma / (dt * rate0);
                if rate > 1.0 {
                    (1.0 + c * rate.ln(), c / dgamma)
                } else {
                    (1.0, 0.0)
                }
            }
            _ => (1.0, 0.0),
        }
    }

    /// `d sigma_y / d ep` at `ep >= 0`.
    pub fn slope(&self, ep: f64) -> f64 {
        match *self {
            Hardening::Linear { modulus, .. } => modulus,
            Hardening::Swift { k, eps0, n } => n * k * (eps0 + ep).powf(n - 1.0),
            Hardening::Voce {
                yield_stress,
                sigma_inf,
                delta,
            } => (sigma_inf - yield_stress) * delta * (-delta * ep).exp(),
            // infinite at ep = 0 when n < 1: the return mapping brackets
            Hardening::JohnsonCook { b, n, .. } => {
                n * b * ep.max(0.0).powf(n - 1.0) * self.thermal_factor()
            }
        }
    }

    /// Checks the parameters; explains what is wrong.
    pub fn check(&self) -> Result<(), String> {
        let pos = positive;
        match *self {
            Hardening::Linear {
                yield_stress,
                modulus,
            } => {
                pos(yield_stress, "the yield stress")?;
                if !(modulus.is_finite() && modulus >= 0.0) {
                    return Err(format!(
                        "the hardening modulus H must be >= 0 (got {modulus})"
                    ));
                }
                Ok(())
            }
            Hardening::Swift { k, eps0, n } => {
                pos(k, "Swift K")?;
                pos(eps0, "Swift eps0")?;
                if !(n.is_finite() && (0.0..=1.0).contains(&n)) {
                    return Err(format!("Swift n must be in [0, 1] (got {n})"));
                }
                Ok(())
            }
            Hardening::Voce {
                yield_stress,
                sigma_inf,
                delta,
            } => {
                pos(yield_stress, "the yield stress")?;
                pos(delta, "Voce delta")?;
                if !(sigma_inf.is_finite() && sigma_inf >= yield_stress) {
                    return Err(format!(
                        "Voce sigma_inf must be >= the yield stress {yield_stress} (got {sigma_inf})"
                    ));
                }
                Ok(())
            }
            Hardening::JohnsonCook {
                a,
                b,
                n,
                c,
                rate0,
                m,
                t_ref,
                t_melt,
                temperature,
            } => {
                pos(a, "Johnson-Cook A")?;
                pos(rate0, "the Johnson-Cook reference rate")?;
                pos(m, "Johnson-Cook m")?;
                if !(b.is_finite() && b >= 0.0) {
                    return Err(format!("Johnson-Cook B must be >= 0 (got {b})"));
                }
                if !(c.is_finite() && c >= 0.0) {
                    return Err(format!("Johnson-Cook C must be >= 0 (got {c})"));
                }
                if !(n.is_finite() && n > 0.0 && n <= 1.0) {
                    return Err(format!("Johnson-Cook n must be in (0, 1] (got {n})"));
                }
                if !(t_ref.is_finite() && t_melt.is_finite() && t_melt > t_ref) {
                    return Err(format!(
                        "the Johnson-Cook melting temperature {t_melt} must exceed the reference \
                         temperature {t_ref}"
                    ));
                }
                if !temperature.is_finite() {
                    return Err(format!("temperature {temperature} is not finite"));
                }
                Ok(())
            }
        }
    }
}

/// `Ok` when `v` is finite and > 0; otherwise explains that `what` must
/// be (a material parameter check).
pub fn positive(v: f64, what: &str) -> Result<(), String> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(format!("{what} must be > 0 (got {v})"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hardening_slopes_match_finite_differences() {
        let laws = [
            Hardening::Linear {
                yield_stress: 250.0,
                modulus: 1000.0,
            },
            Hardening::Swift {
                k: 500.0,
                eps0: 0.01,
                n: 0.2,
            },
            Hardening::Voce {
                yield_stress: 200.0,
                sigma_inf: 350.0,
                delta: 12.0,
            },
        ];
        for h in laws {
            h.check().unwrap();
            for ep in [0.0, 0.03, 0.4] {
                let e = 1e-6;
                let fd = (h.flow_stress(ep + e) - h.flow_stress((ep - e).max(0.0)))
                    / (ep + e - (ep - e).max(0.0));
                assert!(
                    (fd - h.slope(ep)).abs() < 1e-4 * h.slope(ep).abs().max(1.0),
                    "{h:?}"
                );
            }
        }
        assert!(
            (Hardening::Swift {
                k: 500.0,
                eps0: 0.01,
                n: 0.2
            }
            .flow_stress(0.0)
                - 500.0 * 0.01f64.powf(0.2))
            .abs()
                < 1e-12
        );
        assert!(Hardening::Voce {
            yield_stress: 200.0,
            sigma_inf: 100.0,
            delta: 1.0
        }
        .check()
        .is_err());
    }

    /// Johnson & Cook (1983), OFHC copper: the closed form, its strain
    /// slope and the rate factor's derivative against finite differences.
    #[test]
    fn johnson_cook_closed_form_and_derivatives() {
        let jc = |temperature| Hardening::JohnsonCook {
            a: 90.0,
            b: 292.0,
            n: 0.31,
            c: 0.025,
            rate0: 1.0,
            m: 1.09,
            t_ref: 298.0,
            t_melt: 1356.0,
            temperature,
        };
        let h = jc(600.0);
        h.check().unwrap();
        let t_star: f64 = (600.0 - 298.0) / (1356.0 - 298.0);
        let ep: f64 = 0.2;
        let closed = (90.0 + 292.0 * ep.powf(0.31)) * (1.0 - t_star.powf(1.09));
        assert!((h.flow_stress(ep) - closed).abs() < 1e-12 * closed);
        // below room temperature and above melting: clamped
        assert_eq!(jc(200.0).thermal_factor(), 1.0);
        assert_eq!(jc(2000.0).thermal_factor(), 0.0);
        let e = 1e-7;
        let fd = (h.flow_stress(ep + e) - h.flow_stress(ep - e)) / (2.0 * e);
        assert!((fd - h.slope(ep)).abs() < 1e-6 * h.slope(ep));
        // rate 1e3 / s over dt = 1e-4: dgamma = 0.1
        let (dt, dg) = (1e-4, 0.1);
        let (r, dr) = h.rate_factor(dg, dt);
        assert!((r - (1.0 + 0.025 * 1e3f64.ln())).abs() < 1e-12);
        let fd = (h.rate_factor(dg + e, dt).0 - h.rate_factor(dg - e, dt).0) / (2.0 * e);
        assert!((fd - dr).abs() < 1e-6 * dr);
        // below the reference rate, and the other laws: no rate effect
        assert_eq!(h.rate_factor(1e-5, dt), (1.0, 0.0));
        assert_eq!(
            Hardening::Linear {
                yield_stress: 1.0,
                modulus: 0.0
            }
            .rate_factor(dg, dt),
            (1.0, 0.0)
        );
        assert!(jc(0.0).check().is_ok());
        let mut bad = jc(300.0);
        if let Hardening::JohnsonCook { t_melt, .. } = &mut bad {
            *t_melt = 100.0;
        }
        assert!(bad.check().is_err());
    }
}
