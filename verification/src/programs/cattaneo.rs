//! VERIFICATION-CASES.md §5 (Johnson, Contact Mechanics §7.1), Cattaneo
//! partial slip: two identical elastic cylinders (R = 8, E = 200, nu = 0.3,
//! plane strain; node-to-segment contact with penalty-regularized Coulomb
//! friction, mu = 0.3) pressed by P, then sheared by Q < mu P
//! (examples/cattaneo_cylinders.ctc). The stick zone half-width is
//! `c / a = (1 - Q / (mu P))^(1/2)`.
//!
//! ```text
//!        ( upper )   Q ->
//!   ------- a -------        stick |x| < c, slip c < |x| < a
//!        ( lower )
//! ```
//!
//! Measured from the engine's own friction status of the slave nodes at
//! the end: `c` is the mid-point between the outermost sticking node and
//! the next (slipping) node on each side, `a` the mid-point between the
//! outermost closed node and the next open one (resolution: half an
//! element). `P` and `Q` are the contact force components. The traction
//! `q = R_T / area` is compared with Cattaneo's profile (RMS over the
//! contact zone, relative to mu p0). Levels: 64 x 12, 128 x 16, 256 x 24
//! cells per body (level 0 by default; `--max-level 2` in release).

use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::contact::friction::FrictionStatus;
use ctc_engine::contact::{ContactStatus, NodeContact};
use ctc_engine::model::Model;
use ctc_engine::solve::{self, IncrementView, Observer};

/// Mesh per body at each level: (circumferential, radial).
const LEVELS: [(usize, usize); 3] = [(64, 12), (128, 16), (256, 24)];

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    vec![VerifyCase {
        name: "cattaneo_cylinders",
        title: "Cattaneo: partial slip of two elastic cylinders, c/a = (1 - Q/(mu P))^(1/2)",
        source: "VERIFICATION-CASES.md §5; Johnson, Contact Mechanics §7.1",
        tags: &[
            "friction",
            "contact",
            "node_to_segment",
            "penalty",
            "plane_strain",
            "closed_form",
        ],
        levels: 1,
        // measured (levels 0-2): c/a 1.8e-1 6.4e-2 6.9e-4 (c is resolved to
        // half an element); traction RMS / (mu p0) 0.084 0.055 0.055
        checks: vec![
            Check::new(Quantity::Named("c/a"), &[0.3, 0.1, 0.01]),
            Check::new(Quantity::Named("q RMS / (mu p0)"), &[0.12, 0.08, 0.08]),
        ],
        kind: CaseKind::Program(ProgramCase {
            max_levels: LEVELS.len(),
            run,
        }),
    }]
}

fn run(level: usize) -> Result<ProgramLevel, String> {
    let (circ, radial) = *LEVELS.get(level).ok_or("no such level")?;
    let (ca, theory, _ratio, rms, closed, summary, nodes) = measure(circ, radial)?;
    if !(ca > 0.3 && ca < 0.999) {
        return Err(format!("partial slip expected, found c/a = {ca}"));
    }
    if closed < 3 {
        return Err(format!("only {closed} closed nodes"));
    }
    Ok(ProgramLevel {
        figures: Vec::new(),
        values: vec![
            super::value("c/a", ca, theory),
            super::error("q RMS / (mu p0)", rms),
        ],
        // arc length of a division at the pole
        h: 8.0 * std::f64::consts::PI / circ as f64,
        nodes,
        free_dofs: summary.free_dofs,
        increments: summary.increments.len(),
        newton_total: summary.newton_iterations,
        newton_max: summary
            .increments
            .iter()
            .map(|i| i.iterations)
            .max()
            .unwrap_or(0),
        cutbacks: summary.cutbacks,
    })
}

const MU: f64 = 0.3;

fn model(circumferential: usize, radial: usize) -> Result<Model, String> {
    let path = super::examples_dir().join("cattaneo_cylinders.ctc");
    let text = std::fs::read_to_string(&path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?
        .replace(
            "circumferential = 64",
            &format!("circumferential = {circumferential}"),
        )
        .replace("radial = 12", &format!("radial = {radial}"));
    super::compile(&path, &text)
}

/// The contact state of pair 0 and the current coordinates at the last
/// converged increment.
#[derive(Default)]
pub(crate) struct Last {
    pub(crate) contact: Vec<NodeContact>,
    pub(crate) x: Vec<[f64; 2]>,
}

impl Observer for Last {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        self.contact = v.contact.first().ok_or("no contact pair")?.clone();
        self.x = v.positions();
        Ok(())
    }
}

/// Half-width of the zone where `inside` holds: mid-point between the
/// outermost node inside and the next node outside, averaged over both sides.
pub(crate) fn half_width(nodes: &[(f64, bool)]) -> f64 {
    let mut sides = [0.0f64; 2];
    for (k, dir) in [(0usize, 1.0f64), (1, -1.0)] {
        // walk outwards from the centre
        let mut v: Vec<(f64, bool)> = nodes
            .iter()
            .filter(|(x, _)| dir * x >= 0.0)
            .map(|&(x, b)| (x.abs(), b))
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        if v.is_empty() {
            continue;
        }
        let last = v.iter().rposition(|n| n.1).unwrap_or(0);
        let next = v.get(last + 1).map_or(v[last].0, |n| n.0);
        sides[k] = 0.5 * (v[last].0 + next);
    }
    0.5 * (sides[0] + sides[1])
}

/// (c/a measured, c/a Cattaneo, Q/(mu P), traction RMS error / (mu p0), closed nodes, run)
type Measured = (
    f64,
    f64,
    f64,
    f64,
    usize,
    ctc_engine::solve::RunSummary,
    usize,
);

fn measure(circumferential: usize, radial: usize) -> Result<Measured, String> {
    let m = model(circumferential, radial)?;
    let mut last = Last::default();
    let summary = solve::run(&m, &mut last).map_err(|e| e.message)?;
    // slave nodes along x (current position), the contact centred near x = 0
    let closed: Vec<&NodeContact> = last
        .contact
        .iter()
        .filter(|c| c.status == ContactStatus::Closed)
        .collect();
    // force of the lower cylinder on the upper one's nodes: P up, Q along x
    let p: f64 = closed.iter().map(|c| c.force[1]).sum();
    let q: f64 = closed.iter().map(|c| c.force[0]).sum::<f64>().abs();
    let centre = closed
        .iter()
        .map(|c| last.x[c.node][0] * c.force[1])
        .sum::<f64>()
        / p;
    let pts = |f: &dyn Fn(&NodeContact) -> bool| -> Vec<(f64, bool)> {
        last.contact
            .iter()
            .map(|c| (last.x[c.node][0] - centre, f(c)))
            .collect()
    };
    let a = half_width(&pts(&|c| c.status == ContactStatus::Closed));
    let c = half_width(&pts(&|c| {
        c.status == ContactStatus::Closed && c.friction.status == FrictionStatus::Stick
    }));
    let ratio = q / (MU * p);
    let theory = (1.0 - ratio).sqrt();
    // traction profile against Cattaneo with the Hertz a of this load
    let e_star = 200.0 / (2.0 * (1.0 - 0.09));
    let a_h = (4.0 * p * 4.0 / (std::f64::consts::PI * e_star)).sqrt();
    let p0 = 2.0 * p / (std::f64::consts::PI * a_h);
    let c_h = theory * a_h;
    let mut err2 = 0.0;
    let mut n = 0;
    for nc in &closed {
        let x = last.x[nc.node][0] - centre;
        if x.abs() >= a_h {
            continue;
        }
        // R_N = force . n; tributary area = R_N / pressure
        let rn = nc.force[0] * nc.normal[0] + nc.force[1] * nc.normal[1];
        let traction = nc.friction.tangential_force.abs() * nc.pressure / rn.max(1e-300);
        let mut exact = MU * p0 * (1.0 - x * x / (a_h * a_h)).sqrt();
        if x.abs() < c_h {
            exact -= theory * MU * p0 * (1.0 - x * x / (c_h * c_h)).sqrt();
        }
        err2 += (traction - exact).powi(2);
        n += 1;
    }
    let rms = (err2 / n.max(1) as f64).sqrt() / (MU * p0);
    Ok((
        c / a,
        theory,
        ratio,
        rms,
        closed.len(),
        summary,
        m.mesh.nodes.len(),
    ))
}
