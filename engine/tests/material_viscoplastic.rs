//! Perzyna visco-plasticity (linear over-stress, `d ep/dt = <q - sigma_y>/eta`)
//! at a material point in pure shear, against closed forms:
//!
//! - loading at a constant equivalent strain rate `r` from the yield point,
//!   perfect plasticity: the over-stress `s = q - sigma_y` obeys
//!   `ds/dt = 3 G (r - s/eta)`, so `s(t) = eta r (1 - exp(-3 G t / eta))`
//!   (rate dependent: two rates, steady over-stress `eta r`);
//! - relaxation at fixed strain with linear hardening `H`:
//!   `s(t) = s0 exp(-(3 G + H) t / eta)`.
//!
//! Backward Euler in time: first-order convergence to the closed form is
//! checked (halving `dt` halves the error).

use ctc_engine::material::j2::Elastic;
use ctc_engine::material::tensor::{deviator, norm2};
use ctc_engine::material::{History, NonlinearLaw};
use ctc_engine::model::{Hardening, Kinematics};

const E: f64 = 200e3;
const NU: f64 = 0.3;
const ETA: f64 = 5e3;

fn q_of(s: &[f64; 6]) -> f64 {
    (1.5 * norm2(&deviator(s))).sqrt()
}

/// Pure shear with equivalent strain `eb`: tensor shear `sqrt(3) eb / 2`.
fn shear(eb: f64) -> [f64; 6] {
    [0.0, 0.0, 0.0, 3f64.sqrt() * eb / 2.0, 0.0, 0.0]
}

fn law(h: f64) -> NonlinearLaw {
    NonlinearLaw::J2 {
        elastic: Elastic::from_young(E, NU),
        hardening: Hardening::Linear {
            yield_stress: 250.0,
            modulus: h,
        },
        viscosity: Some(ETA),
    }
}

/// Max relative error of the over-stress during loading at rate `r` over
/// `t_end`, with `n` increments.
fn loading_error(r: f64, t_end: f64, n: usize) -> (f64, f64) {
    let g = Elastic::from_young(E, NU).shear;
    let law = law(0.0);
    let e_yield = 250.0 / (3.0 * g);
    let dt = t_end / n as f64;
    let mut h = History::initial(Kinematics::Small);
    let mut worst = 0.0f64;
    let mut last = 0.0;
    for k in 1..=n {
        let t = k as f64 * dt;
        let up = law.small(&shear(e_yield + r * t), &h, dt).unwrap();
        h = up.history;
        let s = q_of(&up.stress) - 250.0;
        let exact = ETA * r * (1.0 - (-3.0 * g * t / ETA).exp());
        worst = worst.max((s - exact).abs() / (ETA * r));
        last = s;
    }
    (worst, last)
}

#[test]
fn perzyna_constant_rate_loading_two_rates_matches_closed_form() {
    let g = Elastic::from_young(E, NU).shear;
    let tau = ETA / (3.0 * g); // relaxation time
    for r in [1e-3 / tau * 0.01, 1e-3 / tau * 1.0] {
        let t_end = 5.0 * tau;
        let (e1, s1) = loading_error(r, t_end, 400);
        let (e2, _) = loading_error(r, t_end, 800);
        println!(
            "rate {r:.3e}/time: over-stress at 5 tau {s1:.4e} (closed form {:.4e}), max error \
             {e1:.2e} (400 incr.), {e2:.2e} (800 incr.), ratio {:.2}",
            ETA * r * (1.0 - (-5f64).exp()),
            e1 / e2
        );
        assert!(e1 < 2e-2, "{e1}");
        assert!(
            (e1 / e2 - 2.0).abs() < 0.1,
            "first order in dt: {}",
            e1 / e2
        );
    }
}

#[test]
fn perzyna_relaxation_with_hardening_matches_closed_form() {
    let g = Elastic::from_young(E, NU).shear;
    let hmod = 2e4;
    let law = law(hmod);
    let tau = ETA / (3.0 * g + hmod);
    let eb = 2.0 * 250.0 / (3.0 * g); // twice the yield strain, applied at once
    for n in [200usize, 400] {
        let dt = 5.0 * tau / n as f64;
        let mut h = History::initial(Kinematics::Small);
        // instantaneous loading over a tiny time: elastic trial, no flow
        let up = law.small(&shear(eb), &h, 1e-12 * tau).unwrap();
        h = up.history;
        let s0 = q_of(&up.stress) - 250.0 - hmod * h.ep;
        let mut worst = 0.0f64;
        for k in 1..=n {
            let up = law.small(&shear(eb), &h, dt).unwrap();
            h = up.history;
            let s = q_of(&up.stress) - 250.0 - hmod * h.ep;
            let exact = s0 * (-(k as f64) * dt / tau).exp();
            worst = worst.max((s - exact).abs() / s0);
        }
        println!("relaxation, {n} increments over 5 tau: s0 = {s0:.4e}, max error {worst:.2e}");
        assert!(s0 > 240.0 && worst < 1e-2, "{s0} {worst}");
    }
}

mod through_the_solver {
    //! The same Perzyna law through the full solver: one axisymmetric quad
    //! (r0 = 1, h0 = 1, small strain) compressed at a constant rate by a
    //! prescribed top displacement, at two rates. Uniaxial stress, perfect
    //! plasticity: after yield at `t_y` the over-stress is
    //! `s = eta rate (1 - exp(-E (t - t_y) / eta))`; the axial force is
    //! `(sigma_y + s) pi`. Checks the time increment reaching the law.
    use super::{E, ETA, NU};
    use ctc_engine::mesh::{Cell, Mesh};
    use ctc_engine::model::{Hardening, MaterialLaw, Model, NewtonSettings};
    use ctc_engine::solve::{run, IncrementView, Observer};
    use ctc_engine::testkit::{ramp, ModelBuilder};
    use std::f64::consts::PI;

    struct Force(Vec<(f64, f64)>);

    impl Observer for Force {
        fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
            let fy: f64 = [0usize, 1].iter().map(|&n| v.reaction[n][1]).sum();
            self.0.push((v.time, fy));
            Ok(())
        }
    }

    fn model(rate: f64, t_end: f64, increments: usize) -> Model {
        ModelBuilder::axisymmetric()
            .material(
                "m",
                MaterialLaw::ElastoPlastic {
                    young: E,
                    poisson: NU,
                    hardening: Hardening::Linear {
                        yield_stress: 250.0,
                        modulus: 0.0,
                    },
                    viscosity: Some(ETA),
                },
            )
            .body(
                "b",
                Mesh::new(
                    vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
                    vec![Cell::quad(0, 1, 2, 3)],
                ),
                "m",
            )
            .fix([0, 1], 1)
            .fix([0, 3], 0)
            .displace([2, 3], 1, ramp(0.0, t_end, -rate * t_end))
            .step("s", t_end, increments)
            .min_fraction(1.0 / 64.0)
            .newton(NewtonSettings {
                tol: 1e-11,
                tol_displacement: 1e-11,
                max_iter: 20,
                line_search: true,
            })
            .build()
    }

    #[test]
    fn perzyna_uniaxial_compression_at_two_rates_through_the_solver() {
        let tau = ETA / E;
        for rate in [1e-4 / tau, 1e-2 / tau] {
            let t_y = 250.0 / (E * rate);
            let t_end = t_y + 5.0 * tau;
            let mut f = Force(Vec::new());
            run(&model(rate, t_end, 400), &mut f).unwrap_or_else(|e| panic!("{}", e.message));
            let mut worst = 0.0f64;
            for &(t, fy) in &f.0 {
                let s = if t <= t_y {
                    E * rate * t - 250.0
                } else {
                    ETA * rate * (1.0 - (-(t - t_y) / tau).exp())
                };
                let exact = (250.0 + s) * PI;
                worst = worst.max((fy - exact).abs() / (ETA * rate * PI));
            }
            let (t, fy) = *f.0.last().unwrap();
            println!(
                "rate {rate:.3e}: force at t = {t:.3e}: {fy:.6e} (closed form {:.6e}), max \
                 over-stress error {worst:.2e} of eta*rate",
                (250.0 + ETA * rate * (1.0 - (-(t - t_y) / tau).exp())) * PI
            );
            assert!(worst < 3e-2, "{worst}");
        }
    }
}
