//! Isotropic hardening laws: flow stress `sigma_y(ep)` and its slope.

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
}
