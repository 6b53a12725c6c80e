//! VERIFICATION-CASES.md §8, adiabatic heating: a small-strain J2 cylinder
//! (axisymmetric, r = 1, h = 1, E = 1000, sigma_y = 2, H = 100) compressed
//! homogeneously by 5 % in 10 increments, frictionless and insulated; the
//! heat is `beta W` with the backward-Euler plastic work
//! `W = sum q_{n+1} (ep_{n+1} - ep_n) V`, `q = sigma_y + H ep`,
//! `ep = (eps - sigma_y / E) / (1 + H / E)` (uniaxial stress), and every
//! node warms by `beta W / (rho c V)` (Simo & Hughes, Computational
//! Inelasticity §2.3).
//!
//! ```text
//!    uy = -0.05 (top)
//!   +-------+
//!   |  J2   |  insulated, ux = 0 on the axis
//!   +-------+
//!    uy = 0
//! ```

use super::{compile, error, read_case_deck};
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::solve::{IncrementView, Observer};

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    vec![VerifyCase {
        name: "adiabatic_heating",
        title: "Adiabatic heating: J2 cylinder compressed, heat = beta x plastic work",
        source: "VERIFICATION-CASES.md §8; Simo & Hughes, Computational Inelasticity §2.3",
        tags: &[
            "thermal",
            "plasticity",
            "axisymmetric",
            "energy",
            "closed_form",
            "exact",
        ],
        levels: 1,
        checks: vec![
            Check::new(Quantity::Named("heat / beta W"), &[1e-9]),
            Check::new(Quantity::Named("T rise"), &[1e-9]),
        ],
        kind: CaseKind::Program(ProgramCase {
            max_levels: 1,
            run: |_| adiabatic(),
        }),
    }]
}

#[derive(Default)]
struct Temperatures {
    last: Vec<f64>,
    plastic: f64,
}

impl Observer for Temperatures {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        self.last = v.temperature.ok_or("no thermal scene")?.to_vec();
        self.plastic += v.thermal.ok_or("no heat report")?.plastic;
        Ok(())
    }
}

fn adiabatic() -> Result<ProgramLevel, String> {
    let (path, text) = read_case_deck("adiabatic_heating.ctc")?;
    let model = compile(&path, &text)?;
    let mut probe = Temperatures::default();
    let s = ctc_engine::solve::run(&model, &mut probe).map_err(|e| e.message)?;
    let (e, sy, h, beta, rho_c) = (1000.0, 2.0, 100.0, 0.9, 1.0);
    let volume = std::f64::consts::PI;
    let mut ep_old: f64 = 0.0;
    let mut work = 0.0;
    for n in 1..=10 {
        let eps = 0.05 * n as f64 / 10.0;
        let ep = ((eps - sy / e) / (1.0 + h / e)).max(0.0);
        work += (sy + h * ep) * (ep - ep_old);
        ep_old = ep;
    }
    let heat = beta * work * volume;
    let dt = heat / (rho_c * volume);
    let worst = probe
        .last
        .iter()
        .map(|t| (t - 20.0 - dt).abs() / dt)
        .fold(0.0, f64::max);
    Ok(ProgramLevel {
        figures: Vec::new(),
        values: vec![
            super::value("heat / beta W", probe.plastic, heat),
            error("T rise", worst),
        ],
        h: f64::NAN,
        nodes: model.mesh.nodes.len(),
        free_dofs: s.free_dofs,
        increments: s.increments.len(),
        newton_total: s.newton_iterations,
        newton_max: s.increments.iter().map(|i| i.iterations).max().unwrap_or(0),
        cutbacks: s.cutbacks,
    })
}
