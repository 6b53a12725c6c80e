//! Implicit dynamics without contact (tag `dynamics`), the solver of
//! `ctc_engine::solve::dynamics`:
//!
//! - `newmark_energy_cantilever`: free vibration of an elastic cantilever
//!   (plane strain, 10 x 1, 20 x 2 quad4, E = 1000, nu = 0.3, rho = 1,
//!   clamped at x = 0, released with vy = 0.1 on every free node), 80
//!   increments of 0.5 (about two periods of the first bending mode).
//!   Average-acceleration Newmark conserves `K + W_int` of a linear system
//!   exactly (Hughes, The Finite Element Method, 2000, section 9.3.2):
//!   measured, the largest change per step over `K0` (consistent and
//!   lumped mass) — round-off.
//! - `generalized_alpha_period_damping`: a one-mode oscillator (one quad,
//!   nu = 0, the free end moving along x, lumped mass: `omega^2 = 2`),
//!   generalized-alpha with `rho_inf = 0.5` at `dt = T/10, T/20, T/40`
//!   (levels 0, 1, 2), released with `vx = 1`: the period (zero crossings)
//!   and the damping ratio (decay of the peaks) over six cycles against
//!   the eigenvalues of the amplification matrix (Chung & Hulbert 1993, J.
//!   Appl. Mech. 60:371, eqs. 16-20; `Coefficients::spectral`).
//!
//! - `rayleigh_damping_decrement`: the same oscillator with Rayleigh
//!   damping `C = alpha M + beta K_0` (`alpha / (2 omega) = 0.02`, `beta
//!   omega / 2 = 0.03`: zeta = 0.05), average-acceleration Newmark at `dt =
//!   T/25, T/50, T/100`: the damping ratio from the logarithmic decrement
//!   of the peaks `delta = ln(x_n / x_{n+1})`, `zeta = delta / sqrt(4 pi^2
//!   + delta^2)`, and the damped period against `T / sqrt(1 - zeta^2)`
//!   (Chopra, Dynamics of Structures, 2012, sections 2.2 and 11.4); the
//!   energy balance with the damping dissipation (`Energy::damping`).
//!
//! ```text
//!   |>=========================  v0 (uy)        |>[ ]--> vx = 1
//!   |>=========================                 |>[ ]-->
//! ```
//! `verification/tests/suite/dynamics.rs` runs both entries.

use super::error;
use crate::case::{Check, Quantity};
use crate::measure::Value;
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::model::{ContactMass, Dynamic, MassMatrix, NewtonSettings, Rayleigh, Scheme};
use ctc_engine::solve::dynamics::Coefficients;
use ctc_engine::solve::RunSummary;
use ctc_engine::testkit::grid::{grid, grid_node};
use ctc_engine::testkit::{solve, ModelBuilder, Recorder};

const DRIFT: [&str; 2] = [
    "Newmark AA, consistent mass: max |dE| per step / E",
    "Newmark AA, lumped mass: max |dE| per step / E",
];
const BALANCE: [&str; 2] = [
    "Newmark AA, consistent mass: max |balance error| / E",
    "Newmark AA, lumped mass: max |balance error| / E",
];
const PERIOD: &str = "generalized-alpha period error T_h/T - 1";
const DAMPING: &str = "generalized-alpha damping ratio";
const RHO_INF: f64 = 0.5;

fn newton() -> NewtonSettings {
    NewtonSettings {
        tol: 1e-12,
        tol_displacement: 1e-12,
        ..NewtonSettings::default()
    }
}

fn cantilever(_level: usize) -> Result<ProgramLevel, String> {
    let (nx, ny) = (20, 2);
    let mut out = ProgramLevel {
        h: f64::NAN,
        ..ProgramLevel::default()
    };
    for ((name, balance_name), mass) in DRIFT
        .iter()
        .zip(BALANCE)
        .zip([MassMatrix::Consistent, MassMatrix::Lumped])
    {
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
                contact_mass: ContactMass::Redistributed,
                rayleigh: Rayleigh::default(),
                adaptive: None,
                max_rotation: None,
                energy_tol: None,
            })
            .newton(newton())
            .build();
        let (summary, _) = solve(&model)?;
        let e: Vec<_> = summary
            .increments
            .iter()
            .filter_map(|i| i.energy)
            .map(|e| e.kinetic + e.internal)
            .collect();
        let kinetic_min = summary
            .increments
            .iter()
            .filter_map(|i| i.energy)
            .map(|e| e.kinetic)
            .fold(f64::INFINITY, f64::min);
        let e0 = *e.first().ok_or("no increment")?;
        if kinetic_min > 0.2 * e0 {
            return Err(format!(
                "the beam did not vibrate (min K = {kinetic_min:e} of {e0:e})"
            ));
        }
        let drift = e
            .windows(2)
            .map(|w| (w[1] - w[0]).abs() / e0)
            .fold(0.0, f64::max);
        out.values.push(error(name, drift));
        // the balance error accumulates the round-off of every step
        let balance = summary
            .increments
            .iter()
            .filter_map(|i| i.energy)
            .map(|e| e.balance.abs())
            .fold(0.0, f64::max)
            / e0;
        out.values.push(error(balance_name, balance));
        out.add_run(&summary);
    }
    Ok(out)
}

/// The one-mode oscillator (one quad, the free end moving along x, lumped
/// mass: `omega^2 = 2`) released with `vx = 1`, `steps_per_period`
/// increments per undamped period, six periods: the free end's
/// displacement after every increment (0 first) and the run.
fn one_mode(
    steps_per_period: usize,
    scheme: Scheme,
    rayleigh: Rayleigh,
) -> Result<(Vec<f64>, f64, RunSummary), String> {
    let omega = 2f64.sqrt();
    let period = std::f64::consts::TAU / omega;
    let dt = period / steps_per_period as f64;
    let increments = 6 * steps_per_period;
    let model = ModelBuilder::plane_strain()
        .elastic("m", 1.0, 0.0)
        .density(1.0)
        .body(
            "cell",
            grid(1, 1, [0.0, 0.0], [1.0, 1.0], 0.0, 1, false),
            "m",
        )
        .fix(vec![0, 2], 0)
        .fix(vec![0, 1, 2, 3], 1)
        .initial_velocity(vec![1, 3], 0, 1.0)
        .step("vibrate", dt * increments as f64, increments)
        .dynamic(Dynamic {
            scheme,
            mass: MassMatrix::Lumped,
            contact_mass: ContactMass::Redistributed,
            rayleigh,
            adaptive: None,
            max_rotation: None,
            energy_tol: None,
        })
        .newton(newton())
        .build();
    let (summary, rec): (RunSummary, Recorder) = solve(&model)?;
    let mut u = vec![0.0];
    u.extend(rec.increments.iter().map(|i| i.displacement[1][0]));
    Ok((u, dt, summary))
}

/// Zero crossings upward (fractional increment numbers) and the maxima
/// (parabola through the three points around each) of `u`.
pub(crate) fn crossings_and_peaks(u: &[f64]) -> (Vec<f64>, Vec<f64>) {
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
    (crossings, peaks)
}

fn oscillator(level: usize) -> Result<ProgramLevel, String> {
    let omega = 2f64.sqrt();
    let period = std::f64::consts::TAU / omega;
    let (u, dt, summary) = one_mode(
        10usize << level,
        Scheme::GeneralizedAlpha { rho_inf: RHO_INF },
        Rayleigh::default(),
    )?;
    let (crossings, peaks) = crossings_and_peaks(&u);
    if crossings.len() < 3 || peaks.len() < 3 {
        return Err(format!(
            "too few cycles: {} crossings, {} peaks",
            crossings.len(),
            peaks.len()
        ));
    }
    let m = crossings.len() - 1;
    let t_h = (crossings[m] - crossings[0]) / m as f64 * dt;
    let decay = (peaks[peaks.len() - 1] / peaks[1]).ln() / (peaks.len() - 2) as f64;
    let xi_h = -decay / std::f64::consts::TAU * (period / t_h);
    let k = Coefficients::of(Scheme::GeneralizedAlpha { rho_inf: RHO_INF });
    let (dt_ref, xi_ref) = k.spectral(omega * dt);
    let value = |name, computed: f64, reference: f64| Value {
        quantity: Quantity::Named(name),
        reference: Some(reference),
        computed,
        error: (computed - reference).abs() / reference.abs(),
    };
    let mut out = ProgramLevel {
        h: dt,
        values: vec![
            value(PERIOD, t_h / period - 1.0, dt_ref),
            value(DAMPING, xi_h, xi_ref),
        ],
        ..ProgramLevel::default()
    };
    out.add_run(&summary);
    Ok(out)
}

/// Modal damping ratio of the damped oscillator: `alpha / (2 omega)` =
/// 0.02 and `beta omega / 2` = 0.03.
const ZETA: f64 = 0.05;
const DAMPED: &str = "Rayleigh damping ratio from the logarithmic decrement";
const DAMPED_PERIOD: &str = "damped period T_d = T / sqrt(1 - zeta^2)";
const DAMPED_BALANCE: &str = "energy balance with damping: max |K + W_int + W_d - K0| / K0";

fn damped(level: usize) -> Result<ProgramLevel, String> {
    let omega = 2f64.sqrt();
    let rayleigh = Rayleigh {
        alpha: 2.0 * omega * 0.02,
        beta: 2.0 * 0.03 / omega,
    };
    let (u, dt, summary) = one_mode(
        25usize << level,
        Scheme::Newmark {
            beta: 0.25,
            gamma: 0.5,
        },
        rayleigh,
    )?;
    let (crossings, peaks) = crossings_and_peaks(&u);
    if crossings.len() < 3 || peaks.len() < 4 {
        return Err(format!(
            "too few cycles: {} crossings, {} peaks",
            crossings.len(),
            peaks.len()
        ));
    }
    // logarithmic decrement over the cycles (peaks one damped period apart)
    let n = peaks.len() - 1;
    let delta = (peaks[0] / peaks[n]).ln() / n as f64;
    let zeta_h = delta / (4.0 * std::f64::consts::PI.powi(2) + delta * delta).sqrt();
    let m = crossings.len() - 1;
    let t_d = (crossings[m] - crossings[0]) / m as f64 * dt;
    let t_ref = std::f64::consts::TAU / omega / (1.0 - ZETA * ZETA).sqrt();
    let energies: Vec<_> = summary.increments.iter().filter_map(|i| i.energy).collect();
    // the initial kinetic energy (no external work: balance = K + W_int +
    // W_d - K0)
    let first = energies.first().ok_or("no increment")?;
    let k_start = first.kinetic + first.internal + first.damping - first.balance;
    let balance = energies.iter().map(|e| e.balance.abs()).fold(0.0, f64::max) / k_start;
    let dissipated = energies.last().map_or(0.0, |e| e.damping) / k_start;
    if dissipated < 0.5 {
        return Err(format!(
            "the damping dissipated only {dissipated:.3} of the initial energy"
        ));
    }
    let value = |name, computed: f64, reference: f64| Value {
        quantity: Quantity::Named(name),
        reference: Some(reference),
        computed,
        error: (computed - reference).abs() / reference.abs(),
    };
    let mut out = ProgramLevel {
        h: dt,
        values: vec![
            value(DAMPED, zeta_h, ZETA),
            value(DAMPED_PERIOD, t_d, t_ref),
            error(DAMPED_BALANCE, balance),
        ],
        ..ProgramLevel::default()
    };
    out.add_run(&summary);
    Ok(out)
}

/// The registry entries.
pub fn cases() -> Vec<VerifyCase> {
    vec![
        VerifyCase {
            name: "newmark_energy_cantilever",
            title: "Free vibration of an elastic cantilever: average-acceleration Newmark conserves K + W_int to round-off per step (consistent and lumped mass)",
            source: "Hughes, The Finite Element Method (2000), section 9.3.2: energy conservation of the trapezoidal rule",
            tags: &["dynamics", "plane_strain"],
            levels: 1,
            // measured 9.8e-13 (consistent), 2.5e-13 (lumped)
            // balance measured 3.6e-11 (consistent), 4.1e-12 (lumped)
            checks: DRIFT
                .iter()
                .map(|n| Check::new(Quantity::Named(n), &[1e-11]))
                .chain(BALANCE.iter().map(|n| Check::new(Quantity::Named(n), &[1e-9])))
                .collect(),
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: cantilever,
            }),
        },
        VerifyCase {
            name: "rayleigh_damping_decrement",
            title: "Damped free vibration of one mode with Rayleigh damping (alpha M + beta K, zeta = alpha/(2 w) + beta w/2 = 0.05), average-acceleration Newmark at dt = T/25, T/50, T/100: logarithmic decrement, damped period and energy balance with the damping dissipation",
            source: "Chopra, Dynamics of Structures (4th ed. 2012), sections 2.2 (logarithmic decrement, T_D = T / sqrt(1 - zeta^2)) and 11.4 (Rayleigh damping)",
            tags: &["dynamics", "plane_strain"],
            levels: 3,
            // measured (levels 0, 1, 2): zeta 1.03e-2, 2.61e-3, 6.55e-4;
            // period 5.17e-3, 1.30e-3, 3.26e-4 (both rate 2.0); balance
            // 6e-15, 1.1e-14, 7.3e-14
            checks: vec![
                Check::new(Quantity::Named(DAMPED), &[2e-2, 5e-3, 1.5e-3]),
                Check::new(Quantity::Named(DAMPED_PERIOD), &[1e-2, 3e-3, 1e-3]),
                Check::new(Quantity::Named(DAMPED_BALANCE), &[1e-10]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 3,
                run: damped,
            }),
        },
        VerifyCase {
            name: "generalized_alpha_period_damping",
            title: "Generalized-alpha (rho_inf = 0.5) on one mode at dt = T/10, T/20, T/40: period elongation and algorithmic damping vs the amplification matrix",
            source: "Chung & Hulbert 1993, J. Appl. Mech. 60:371, eqs. 16-20",
            tags: &["dynamics", "plane_strain"],
            levels: 3,
            // measured (level 0, 1, 2): period 1.8e-3, 2e-5, 1.1e-3;
            // damping 4.4e-2, 1.3e-2, 6.6e-4 (the peak fit over 6 cycles)
            checks: vec![
                Check::new(Quantity::Named(PERIOD), &[1e-2]),
                Check::new(Quantity::Named(DAMPING), &[1e-1, 5e-2, 1e-2]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 3,
                run: oscillator,
            }),
        },
    ]
}
