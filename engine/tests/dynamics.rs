//! Implicit dynamics without contact (`ctc_engine::solve::dynamics`).
//!
//! - Free vibration of an elastic cantilever (plane strain, clamped at
//!   x = 0, released with a uniform transverse velocity): average-
//!   acceleration Newmark conserves `K + W_int` to round-off per step
//!   (Hughes, The Finite Element Method, 2000, section 9.3.2: the scheme is
//!   energy conserving for linear systems).
//!
//!   ```text
//!   |>=========================  v0 = 0.1 (uy) on every free node
//!   |>=========================
//!   ```
//! - One-mode oscillator (one quad, nu = 0, the free end moving along x,
//!   lumped mass: omega^2 = (E h / L) / (rho h L / 2) = 2): period
//!   elongation and algorithmic damping ratio of generalized-alpha at three
//!   `dt` against the eigenvalues of its amplification matrix (Chung &
//!   Hulbert 1993, J. Appl. Mech. 60:371, eqs. 16-20).

use ctc_engine::model::{Dynamic, MassMatrix, NewtonSettings, Scheme};
use ctc_engine::solve::dynamics::Coefficients;
use ctc_engine::testkit::grid::{grid, grid_node};
use ctc_engine::testkit::{solve, ModelBuilder};

fn newton() -> NewtonSettings {
    NewtonSettings {
        tol: 1e-12,
        tol_displacement: 1e-12,
        ..NewtonSettings::default()
    }
}

#[test]
fn newmark_average_acceleration_conserves_the_energy_of_a_free_cantilever() {
    let (nx, ny) = (20, 2);
    for mass in [MassMatrix::Consistent, MassMatrix::Lumped] {
        let left: Vec<usize> = (0..=ny).map(|j| grid_node(nx, 0, j)).collect();
        let free: Vec<usize> = (0..=ny)
            .flat_map(|j| (1..=nx).map(move |i| grid_node(nx, i, j)))
            .collect();
        let model = ModelBuilder::plane_strain()
            .elastic("m", 1000.0, 0.3)
            .density(1.0)
            .body(
                "beam",
                grid(nx, ny, [0.0, 0.0], [10.0, 1.0], 0.0, 1, false),
                "m",
            )
            .fix(left.clone(), 0)
            .fix(left, 1)
            .initial_velocity(free, 1, 0.1)
            .step("vibrate", 40.0, 80)
            .dynamic(Dynamic {
                scheme: Scheme::Newmark {
                    beta: 0.25,
                    gamma: 0.5,
                },
                mass,
            })
            .newton(newton())
            .build();
        let (summary, _) = solve(&model).unwrap();
        let e: Vec<_> = summary
            .increments
            .iter()
            .map(|i| i.energy.unwrap())
            .collect();
        let e0 = e[0].kinetic + e[0].internal;
        let drift = e
            .windows(2)
            .map(|w| ((w[1].kinetic + w[1].internal) - (w[0].kinetic + w[0].internal)).abs() / e0)
            .fold(0.0, f64::max);
        let min_kinetic = e.iter().map(|x| x.kinetic).fold(f64::INFINITY, f64::min);
        println!(
            "{mass:?}: max relative energy drift per step {drift:.2e}, min K / E = {:.3}",
            min_kinetic / e0
        );
        // it vibrates: the kinetic energy goes (almost) through zero
        assert!(
            min_kinetic < 0.2 * e0,
            "{mass:?}: min K {min_kinetic} of {e0}"
        );
        assert!(drift < 1e-11, "{mass:?}: drift {drift:e}");
        // the balance error accumulates the round-off of every step
        let balance = e.iter().map(|x| x.balance.abs()).fold(0.0, f64::max) / e0;
        println!("{mass:?}: max |balance error| / E = {balance:.2e}");
        assert!(balance < 1e-9, "{mass:?}: balance {balance:e}");
    }
}

#[test]
fn generalized_alpha_period_and_damping_match_chung_hulbert() {
    let omega = 2f64.sqrt();
    let period = std::f64::consts::TAU / omega;
    let rho_inf = 0.5;
    let k = Coefficients::of(Scheme::GeneralizedAlpha { rho_inf });
    for steps_per_period in [10usize, 20, 40] {
        let dt = period / steps_per_period as f64;
        let cycles = 6.0;
        let increments = (cycles * steps_per_period as f64) as usize;
        let x = grid(1, 1, [0.0, 0.0], [1.0, 1.0], 0.0, 1, false);
        let model = ModelBuilder::plane_strain()
            .elastic("m", 1.0, 0.0)
            .density(1.0)
            .body("cell", x, "m")
            .fix(vec![0, 2], 0)
            .fix(vec![0, 1, 2, 3], 1)
            .initial_velocity(vec![1, 3], 0, 1.0)
            .step("vibrate", dt * increments as f64, increments)
            .dynamic(Dynamic {
                scheme: Scheme::GeneralizedAlpha { rho_inf },
                mass: MassMatrix::Lumped,
            })
            .newton(newton())
            .build();
        let (_, rec) = solve(&model).unwrap();
        let mut u = vec![0.0];
        u.extend(rec.increments.iter().map(|i| i.displacement[1][0]));
        // upward zero crossings (linear interpolation) give the period, the
        // ratio of successive positive peaks (parabola through three
        // samples) the decay per period
        let mut crossings = Vec::new();
        for n in 1..u.len() {
            if u[n - 1] < 0.0 && u[n] >= 0.0 {
                crossings.push((n - 1) as f64 + u[n - 1] / (u[n - 1] - u[n]));
            }
        }
        let mut peaks = Vec::new();
        for n in 1..u.len() - 1 {
            if u[n] > u[n - 1] && u[n] >= u[n + 1] {
                let (a, b, c) = (u[n - 1], u[n], u[n + 1]);
                let s = 0.5 * (a - c) / (a - 2.0 * b + c);
                peaks.push(b - 0.25 * (a - c) * s);
            }
        }
        let m = crossings.len() - 1;
        let t_h = (crossings[m] - crossings[0]) / m as f64 * dt;
        let decay = (peaks[peaks.len() - 1] / peaks[1]).ln() / (peaks.len() - 2) as f64;
        let xi_h = -decay / std::f64::consts::TAU * (period / t_h);
        let (dt_ref, xi_ref) = k.spectral(omega * dt);
        println!(
            "dt = T/{steps_per_period}: period error {:.4e} (closed form {:.4e}), damping ratio \
             {:.4e} (closed form {:.4e})",
            t_h / period - 1.0,
            dt_ref,
            xi_h,
            xi_ref
        );
        assert!(((t_h / period - 1.0) - dt_ref).abs() < 0.05 * dt_ref.abs() + 1e-4);
        assert!((xi_h - xi_ref).abs() < 0.1 * xi_ref.abs() + 1e-4);
    }
}
