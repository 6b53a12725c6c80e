//! VERIFICATION-CASES case 4 as `ctc verify` cases (NAFEMS CGS-4 as used
//! by other codes; Wriggers, Computational Contact Mechanics §5.2), on the
//! block of [`super::friction_block`]:
//!
//! - `friction_inclined_plane`: a block on a rigid plane inclined at
//!   tan(alpha) = 0.1, loaded normally, then pushed horizontally up the
//!   slope. Once every contact node slides, `F / G = (tan a + mu) / (1 - mu
//!   tan a)` (0.412371 for mu = 0.3), for mu = 0, 0.1, 0.2, 0.3 and every
//!   normal method (penalty under the weight or a squeeze, augmented
//!   Lagrangian, Lagrange multipliers).
//! - `friction_stick_slip`: a block pressed with `N` and pulled with `Q`
//!   sticks for `Q < mu N` (the friction forces hold `Q`, no work), has no
//!   static equilibrium for `Q > mu N` (the run stops with a diagnosis),
//!   and under a displacement pull the force plateaus at `mu N` with the
//!   friction work `mu N x slip`.
//! - `friction_alpha_t`: the regularized (penalty) stick lets the base
//!   creep by exactly `R_T / alpha_T` (area penalty: `Q / (alpha_T
//!   width)`) for `alpha_T / alpha_N` = 1e-3 .. 10, the slip threshold of
//!   the inclined plane stays exact at every `alpha_T`, and Lagrange
//!   multipliers stick exactly.
//! - `friction_impact_cut`: a block moved down rigidly at constant velocity
//!   onto a plane 0.013 below the base touches it at t = 0.325; with
//!   `cut_at_impact` the increment is cut there (closed form of the
//!   constant-velocity intersection).
//!
//! ```text
//!          N (weight or squeeze)
//!        +-----------+
//!  Q  -> |   block   |
//!        +-----------+
//!   ////// plane, tan(alpha) = 0.1 (or 0) //////
//! ```

use super::error;
use super::friction_block::{count, solve, Block, Drive, Row};
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::contact::friction::FrictionStatus;
use ctc_engine::model::{
    ContactMethod, Dirichlet, LagrangeFormulation, MultiplierUpdate, PenaltyKind, TimeFunction,
};
use ctc_engine::solve::{run, IncrementView, Observer, RunSummary};

/// `F / G` at slip on the plane inclined at tan(alpha) = 0.1.
pub fn inclined_reference(mu: f64) -> f64 {
    (0.1 + mu) / (1.0 - mu * 0.1)
}

/// Accumulates the counts of several runs into a level.
#[derive(Default)]
struct Counts(ProgramLevel);

impl Counts {
    fn add(&mut self, b: &Block, s: &RunSummary) {
        let l = &mut self.0;
        l.nodes = l.nodes.max((b.divisions[0] + 1) * (b.divisions[1] + 1));
        l.free_dofs = l.free_dofs.max(s.free_dofs);
        l.increments += s.increments.len();
        l.newton_total += s.newton_iterations;
        l.newton_max = l
            .newton_max
            .max(s.increments.iter().map(|i| i.iterations).max().unwrap_or(0));
        l.cutbacks += s.cutbacks;
    }

    fn level(mut self, values: Vec<crate::measure::Value>) -> ProgramLevel {
        self.0.values = values;
        self.0.h = f64::NAN;
        self.0
    }
}

/// Runs `block`; an error when it fails.
fn solved(block: &Block, counts: &mut Counts) -> Result<Vec<Row>, String> {
    let (rows, summary) = solve(block).map_err(|e| format!("{block:?}: {e}"))?;
    counts.add(block, &summary);
    if rows.rows.is_empty() {
        return Err(format!("{block:?}: no converged increment"));
    }
    Ok(rows.rows)
}

/// The normal methods of the inclined-plane case: (quantity, method,
/// squeeze, tangential penalty).
fn inclined_methods() -> [(&'static str, ContactMethod, Option<f64>, Option<f64>); 4] {
    let penalty = ContactMethod::Penalty {
        kind: PenaltyKind::Area,
        stiffness: 1e7,
    };
    [
        ("F/G penalty (weight)", penalty.clone(), None, None),
        ("F/G penalty (squeeze)", penalty, Some(1e-3), None),
        (
            "F/G augmented Lagrangian",
            ContactMethod::AugmentedLagrange {
                kind: PenaltyKind::Area,
                penalty: 1e6,
                tolerance: 1e-8,
                update: MultiplierUpdate::Converged,
            },
            Some(1e-3),
            // Uzawa contracts the stick gaps at about K / (K + alpha_T):
            // alpha_T = alpha_N keeps the number of updates small
            Some(1e6),
        ),
        (
            "F/G Lagrange",
            ContactMethod::Lagrange {
                formulation: LagrangeFormulation::Single,
            },
            Some(1e-3),
            None,
        ),
    ]
}

/// F/G at the end of the push of `block` (every node must slide).
fn threshold(block: &Block, counts: &mut Counts) -> Result<f64, String> {
    let rows = solved(block, counts)?;
    let last = rows.last().expect("rows");
    let n = last.contact.len();
    let slipping = count(&last.contact, FrictionStatus::Slip);
    if slipping != n {
        return Err(format!(
            "mu = {}: {slipping} of {n} nodes slide at the end of the push",
            block.mu
        ));
    }
    let g = match block.squeeze {
        Some(_) => -last.lift,
        None => block.weight,
    };
    Ok(last.push / g)
}

fn inclined_plane() -> Result<ProgramLevel, String> {
    let alpha = 0.1f64.atan();
    let mut counts = Counts::default();
    let mut values = Vec::new();
    let mut at_03 = f64::NAN;
    for (name, method, squeeze, stiffness) in inclined_methods() {
        let mut worst = 0.0f64;
        for mu in [0.0, 0.1, 0.2, 0.3] {
            let mut b = Block::new(alpha, mu, Drive::LeftSide(0.01));
            b.method = method.clone();
            b.squeeze = squeeze;
            b.friction_stiffness = stiffness;
            let ratio = threshold(&b, &mut counts)?;
            worst = worst.max((ratio - inclined_reference(mu)).abs() / inclined_reference(mu));
            if mu == 0.3 && at_03.is_nan() {
                at_03 = ratio;
            }
        }
        values.push(error(name, worst));
    }
    // the published threshold (6 digits)
    values.push(super::value("F/G at mu = 0.3 vs 0.412371", at_03, 0.412371));
    Ok(counts.level(values))
}

const MU: f64 = 0.3;
const N: f64 = 100.0;

/// Displacement-driven pull: (plateau error, sliding-phase work error,
/// whole-run work error against `mu N (u_base - u_elastic)`).
fn pulled_block_energy(
    method: ContactMethod,
    squeeze: Option<f64>,
    drive: Drive,
    counts: &mut Counts,
) -> Result<(f64, f64, f64), String> {
    let mut b = Block::new(0.0, MU, drive);
    b.method = method;
    b.squeeze = squeeze;
    b.increments = 10;
    b.poisson = 0.0;
    let rows = solved(&b, counts)?;
    let last = rows.last().expect("rows");
    let all_slip = |r: &Row| count(&r.contact, FrictionStatus::Slip) == r.contact.len();
    if !all_slip(last) {
        return Err(format!("{drive:?}: not every node slides at the end"));
    }
    let n = match squeeze {
        Some(_) => -last.lift,
        None => N,
    };
    let plateau = (last.push - MU * n).abs() / (MU * n);
    // steady sliding: from the first increment after which every one slides
    let k0 = (0..rows.len())
        .rev()
        .take_while(|&k| all_slip(&rows[k]))
        .last()
        .expect("the last increment slides");
    let slip = last.bottom_ux - rows[k0].bottom_ux;
    let sliding: f64 = rows[k0 + 1..].iter().map(|r| r.dissipation).sum();
    let sliding_err = (sliding - MU * n * slip).abs() / (MU * n * slip);
    // whole run: slip = base displacement minus the elastic tangential gap
    let c = &last.contact[0];
    let total_slip = last.bottom_ux - (c.friction.tangential_gap - c.friction.slip);
    let dissipated: f64 = rows.iter().map(|r| r.dissipation).sum();
    let total_err = (dissipated - MU * n * total_slip).abs() / (MU * n * total_slip);
    Ok((plateau, sliding_err, total_err))
}

fn stick_slip() -> Result<ProgramLevel, String> {
    let mut counts = Counts::default();
    let mut values = Vec::new();
    // below mu N: every node sticks, the friction forces hold the pull
    let q = 0.9 * MU * N;
    let mut b = Block::new(0.0, MU, Drive::Force(q));
    // nu = 0: pressing does not spread the base (no slip at the edges)
    b.poisson = 0.0;
    let rows = solved(&b, &mut counts)?;
    let last = rows.last().expect("rows");
    let not_stuck = last.contact.len() - count(&last.contact, FrictionStatus::Stick);
    values.push(error("Q < mu N: nodes not sticking", not_stuck as f64));
    // t = (n_y, -n_x) = (1, 0): the friction force holds the pull
    let rt: f64 = last
        .contact
        .iter()
        .map(|c| c.friction.tangential_force)
        .sum();
    values.push(error("Q < mu N: |sum R_T + Q| / Q", (rt + q).abs() / q));
    let dissipated: f64 = rows.iter().map(|r| r.dissipation).sum();
    values.push(error("Q < mu N: friction work", dissipated.abs()));
    // above mu N: no static equilibrium, the run stops with a diagnosis
    let b = Block::new(0.0, MU, Drive::Force(1.1 * MU * N));
    let refused = match solve(&b) {
        Err(e) if e.contains("push") => 0.0,
        _ => 1.0,
    };
    values.push(error("Q > mu N: run refused with a diagnosis", refused));
    let penalty = ContactMethod::Penalty {
        kind: PenaltyKind::Area,
        stiffness: 1e7,
    };
    // rigid translation of the block: every base node slips at once
    let (p, e, t) = pulled_block_energy(penalty.clone(), None, Drive::AllNodes(0.01), &mut counts)?;
    values.push(error("rigid pull: Q / (mu N) - 1", p));
    values.push(error("rigid pull: sliding work / (mu N slip) - 1", e));
    values.push(error("rigid pull: run work / (mu N slip) - 1", t));
    // the base nodes free (Lagrange needs free tangential dofs at the contact)
    let (p, e, _) = pulled_block_energy(penalty, None, Drive::AboveBase(0.01), &mut counts)?;
    values.push(error("shear pull, penalty: Q / (mu N) - 1", p));
    values.push(error("shear pull, penalty: work / (mu N slip) - 1", e));
    let (p, e, _) = pulled_block_energy(
        ContactMethod::Lagrange {
            formulation: LagrangeFormulation::Single,
        },
        Some(1e-3),
        Drive::AboveBase(0.01),
        &mut counts,
    )?;
    values.push(error("shear pull, Lagrange: Q / (mu N) - 1", p));
    values.push(error("shear pull, Lagrange: work / (mu N slip) - 1", e));
    Ok(counts.level(values))
}

/// Largest |u_T| of the base under `Q = 0.9 mu N` (a sticking block) and `Q`.
fn creep(
    method: ContactMethod,
    stiffness: Option<f64>,
    squeeze: Option<f64>,
    counts: &mut Counts,
) -> Result<(f64, f64), String> {
    let q = 0.9 * MU * N;
    let mut b = Block::new(0.0, MU, Drive::Force(q));
    b.method = method;
    b.friction_stiffness = stiffness;
    b.squeeze = squeeze;
    b.poisson = 0.0;
    let rows = solved(&b, counts)?;
    let u = rows
        .last()
        .expect("rows")
        .contact
        .iter()
        .map(|c| c.friction.tangential_gap.abs())
        .fold(0.0, f64::max);
    Ok((u, q))
}

/// One row of the tangential-penalty study.
#[derive(Debug, Clone, PartialEq)]
pub struct AlphaTRow {
    /// alpha_T / alpha_N.
    pub ratio: f64,
    /// Largest tangential creep of the sticking base.
    pub creep: f64,
    /// Expected creep `Q / alpha_T`.
    pub expected: f64,
    /// Relative error of the inclined-plane F/G (mu = 0.3).
    pub threshold_error: f64,
    /// Newton iterations of the inclined-plane run.
    pub newton: usize,
}

const ALPHA_N: f64 = 1e7;

/// The tangential-penalty study (`alpha_T / alpha_N = 1e-3 .. 10`).
pub fn alpha_t_rows() -> Result<Vec<AlphaTRow>, String> {
    alpha_t_rows_counted(&mut Counts::default())
}

fn alpha_t_rows_counted(counts: &mut Counts) -> Result<Vec<AlphaTRow>, String> {
    let alpha = 0.1f64.atan();
    let reference = inclined_reference(MU);
    let mut rows = Vec::new();
    for ratio in [1e-3, 1e-2, 1e-1, 1.0, 1e1] {
        let at = ratio * ALPHA_N;
        let penalty = ContactMethod::Penalty {
            kind: PenaltyKind::Area,
            stiffness: ALPHA_N,
        };
        let (creep, q) = creep(penalty, Some(at), None, counts)?;
        let mut b = Block::new(alpha, MU, Drive::LeftSide(0.01));
        b.friction_stiffness = Some(at);
        let (r, summary) = solve(&b).map_err(|e| format!("alpha_T = {at}: {e}"))?;
        counts.add(&b, &summary);
        let last = r.rows.last().ok_or("no converged increment")?;
        rows.push(AlphaTRow {
            ratio,
            creep,
            // uniform shear traction q / width over alpha_T
            expected: q / at,
            threshold_error: (last.push / b.weight - reference).abs() / reference,
            newton: summary.newton_iterations,
        });
    }
    Ok(rows)
}

fn alpha_t() -> Result<ProgramLevel, String> {
    let mut counts = Counts::default();
    let rows = alpha_t_rows_counted(&mut counts)?;
    let creep_err = rows
        .iter()
        .map(|r| (r.creep - r.expected).abs() / r.expected)
        .fold(0.0, f64::max);
    let threshold = rows.iter().map(|r| r.threshold_error).fold(0.0, f64::max);
    // the creep is exactly inversely proportional to alpha_T
    let p0 = rows[0].creep * rows[0].ratio;
    let product = rows
        .iter()
        .map(|r| (r.creep * r.ratio - p0).abs() / p0)
        .fold(0.0, f64::max);
    let (lagrange, _) = creep(
        ContactMethod::Lagrange {
            formulation: LagrangeFormulation::Single,
        },
        None,
        Some(1e-3),
        &mut counts,
    )?;
    Ok(counts.level(vec![
        error("creep vs Q / alpha_T", creep_err),
        error("creep x alpha_T constant", product),
        error("F/G at every alpha_T", threshold),
        error("Lagrange stick creep", lagrange),
    ]))
}

#[derive(Default)]
struct Times(Vec<f64>);

impl Observer for Times {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        self.0.push(v.time);
        Ok(())
    }
}

/// The block moves down rigidly (every node's uy prescribed, so its path
/// is exactly at constant velocity) by 0.04 over the first step (one
/// increment) onto a plane 0.013 below: the base meets it at t = 0.325.
/// The accepted times and the cutbacks.
fn falling_block(cut: bool, counts: &mut Counts) -> Result<Vec<f64>, String> {
    let b = Block::new(0.0, 0.3, Drive::LeftSide(0.0));
    let mut m = b.model();
    // (the weight stays: it gives the residual a force scale)
    m.tools[0].geometry = ctc_engine::model::ToolGeometry::Plane {
        point: [0.0, -0.013],
        normal: [0.0, 1.0],
    };
    m.constraints.push(Dirichlet {
        label: "fall".into(),
        nodes: (0..m.mesh.nodes.len()).collect(),
        component: 1,
        value: TimeFunction::Ramp {
            t0: 0.0,
            t1: 1.0,
            v0: 0.0,
            v1: -0.04,
        },
    });
    if let Some(f) = m.contacts[0].friction.as_mut() {
        f.cut_at_impact = cut;
    }
    let mut times = Times::default();
    let s = run(&m, &mut times).map_err(|e| e.message)?;
    counts.add(&b, &s);
    let mut t = times.0;
    t.push(s.cutbacks as f64);
    Ok(t)
}

fn impact_cut() -> Result<ProgramLevel, String> {
    let mut counts = Counts::default();
    let mut cut = falling_block(true, &mut counts)?;
    let cutbacks = cut.pop().unwrap_or(0.0);
    let mut uncut = falling_block(false, &mut counts)?;
    let uncut_cutbacks = uncut.pop().unwrap_or(0.0);
    let flag = |ok: bool| if ok { 0.0 } else { 1.0 };
    Ok(counts.level(vec![
        super::value(
            "first accepted time vs impact 0.325",
            cut.first().copied().unwrap_or(f64::NAN),
            0.325,
        ),
        error("cut: at least one cutback", flag(cutbacks >= 1.0)),
        error("cut: run ends at t = 2", flag(cut.last() == Some(&2.0))),
        error(
            "no cut: first increment whole, no cutback",
            flag(uncut.first() == Some(&1.0) && uncut_cutbacks == 0.0),
        ),
    ]))
}

const TAGS: &[&str] = &[
    "friction",
    "contact",
    "penalty",
    "lagrange",
    "plane_strain",
    "closed_form",
];

// ------------------------------------------------------------ quadratic

/// `friction_quadratic` (tags `quadratic`, `friction`): the inclined-plane
/// and stick/slip benchmarks of this file on quadratic cells, friction
/// face-integrated (`ctc_engine::contact::face_integrated`: a stick point
/// per integration point of the 3-node edges / quadratic faces, the
/// nodes' return map there). Plane strain, the block of
/// [`super::friction_block`] elevated to quad8 and quad9 (4 x 2 cells):
///
/// - pushed up the plane inclined at `tan a = 0.1` (weight 100, penalty;
///   squeeze, penalty and augmented Lagrangian) with mu = 0.3: `F / G`
///   against `(tan a + mu) / (1 - mu tan a)` once every point slides, and
///   `|sum R_T| / (mu sum R_N) - 1` from the nodes' forces (Coulomb at
///   every integration point sums exactly);
/// - pulled by `Q = 0.5 mu N` on the flat plane (nu = 0): no node slides,
///   `|sum R_T + Q| / Q`, no frictional work;
///
/// and in 3D the block of `friction_inclined_3d` (3 x 3 x 2 cells) on
/// hex20, hex27 and tet10 pushed up its slope (penalty): `F / G` against
/// the same closed form.
///
/// ```text
///          G (or squeeze)
///        +-----------+
///  push->|   quad8   |  1 x 0.5, 3-node slave edges
///        +-----------+
///   ////// plane inclined at tan a = 0.1, mu = 0.3 //////
/// ```
fn quadratic_level() -> Result<ProgramLevel, String> {
    use ctc_engine::mesh::CellKind;
    let alpha = 0.1f64.atan();
    let mut counts = Counts::default();
    let mut values = Vec::new();
    let (mut ratio, mut coulomb) = (0.0f64, 0.0f64);
    let (mut not_stuck, mut hold, mut work) = (0.0f64, 0.0f64, 0.0f64);
    for cell in [CellKind::Quad8, CellKind::Quad9] {
        for (name, mut method, squeeze, stiffness) in inclined_methods().into_iter().take(3) {
            // the points' Uzawa loop contracts the stick gaps slowly (about
            // 20 % per update on the corner points): a looser gap
            // tolerance, the slip ratio is exact by equilibrium at any
            if let ContactMethod::AugmentedLagrange { tolerance, .. } = &mut method {
                *tolerance = 1e-6;
            }
            let mut b = Block::new(alpha, MU, Drive::LeftSide(0.01));
            b.method = method;
            b.squeeze = squeeze;
            b.friction_stiffness = stiffness;
            b.cell = cell;
            let r = threshold(&b, &mut counts).map_err(|e| format!("{cell:?} {name}: {e}"))?;
            ratio = ratio.max((r - inclined_reference(MU)).abs() / inclined_reference(MU));
            let rows = solved(&b, &mut counts)?;
            let last = rows.last().expect("rows");
            let n = [-alpha.sin(), alpha.cos()];
            let f = ctc_engine::contact::pair_total_force(&last.contact);
            let (rn, rt) = (f[0] * n[0] + f[1] * n[1], f[0] * n[1] - f[1] * n[0]);
            coulomb = coulomb.max((rt.abs() / (MU * rn) - 1.0).abs());
        }
        let q = 0.5 * MU * N;
        let mut b = Block::new(0.0, MU, Drive::Force(q));
        b.poisson = 0.0;
        b.cell = cell;
        let rows = solved(&b, &mut counts)?;
        let last = rows.last().expect("rows");
        not_stuck += (last.contact.len() - count(&last.contact, FrictionStatus::Stick)) as f64;
        let rt: f64 = ctc_engine::contact::pair_total_force(&last.contact)[0];
        hold = hold.max((rt + q).abs() / q);
        work += rows.iter().map(|r| r.dissipation.abs()).sum::<f64>();
    }
    values.push(error("quad8/quad9 F/G vs closed form", ratio));
    values.push(error(
        "quad8/quad9 slip: |sum R_T| / (mu sum R_N) - 1",
        coulomb,
    ));
    values.push(error("quad8/quad9 Q < mu N: nodes not sticking", not_stuck));
    values.push(error("quad8/quad9 Q < mu N: |sum R_T + Q| / Q", hold));
    values.push(error("quad8/quad9 Q < mu N: friction work", work));
    for (cell, name) in [
        (CellKind::Hex20, "hex20 F/G vs closed form"),
        (CellKind::Hex27, "hex27 F/G vs closed form"),
        (CellKind::Tet10, "tet10 F/G vs closed form"),
    ] {
        // penalty (the augmented Lagrangian's point Uzawa loop does not
        // reach the 1e-8 stick tolerance in 50 updates on hex20 / tet10)
        let push = super::friction_3d::inclined_push_on(cell, 0, &mut counts.0)
            .map_err(|e| format!("{cell:?}: {e}"))?;
        values.push(error(
            name,
            (push.ratio - inclined_reference(MU)).abs() / inclined_reference(MU),
        ));
    }
    Ok(counts.level(values))
}

fn checks(list: &[(&'static str, f64)]) -> Vec<Check> {
    list.iter()
        .map(|(q, t)| Check::new(Quantity::Named(q), &[*t]))
        .collect()
}

fn program(
    name: &'static str,
    title: &'static str,
    tags: &'static [&'static str],
    checks: Vec<Check>,
    run: fn(usize) -> Result<ProgramLevel, String>,
) -> VerifyCase {
    VerifyCase {
        name,
        title,
        source: "VERIFICATION-CASES.md case 4 (NAFEMS CGS-4); Wriggers, Computational Contact Mechanics §5.2",
        tags,
        levels: 1,
        checks,
        kind: CaseKind::Program(ProgramCase { max_levels: 1, run }),
    }
}

/// The registry entries.
pub fn cases() -> Vec<VerifyCase> {
    vec![
        program(
            "friction_inclined_plane",
            "Friction: block pushed up a plane inclined at tan a = 0.1, F/G = (tan a + mu)/(1 - mu tan a), 4 methods x 4 mu",
            &[
                "friction",
                "contact",
                "penalty",
                "lagrange",
                "augmented_lagrange",
                "plane_strain",
                "closed_form",
            ],
            checks(&[
                ("F/G penalty (weight)", 1e-6),
                ("F/G penalty (squeeze)", 1e-6),
                ("F/G augmented Lagrangian", 1e-6),
                ("F/G Lagrange", 1e-6),
                ("F/G at mu = 0.3 vs 0.412371", 2e-6),
            ]),
            |_| inclined_plane(),
        ),
        program(
            "friction_stick_slip",
            "Friction: pulled block sticks below mu N, slides above, work = mu N slip",
            &[
                "friction",
                "contact",
                "penalty",
                "lagrange",
                "plane_strain",
                "energy",
                "exact",
            ],
            checks(&[
                ("Q < mu N: nodes not sticking", 0.0),
                ("Q < mu N: |sum R_T + Q| / Q", 1e-8),
                ("Q < mu N: friction work", 0.0),
                ("Q > mu N: run refused with a diagnosis", 0.0),
                ("rigid pull: Q / (mu N) - 1", 1e-8),
                ("rigid pull: sliding work / (mu N slip) - 1", 1e-8),
                ("rigid pull: run work / (mu N slip) - 1", 1e-8),
                ("shear pull, penalty: Q / (mu N) - 1", 1e-8),
                ("shear pull, penalty: work / (mu N slip) - 1", 1e-8),
                ("shear pull, Lagrange: Q / (mu N) - 1", 1e-8),
                ("shear pull, Lagrange: work / (mu N slip) - 1", 1e-8),
            ]),
            |_| stick_slip(),
        ),
        program(
            "friction_alpha_t",
            "Friction: tangential penalty alpha_T, stick creep = Q / alpha_T, threshold exact at every alpha_T",
            TAGS,
            checks(&[
                ("creep vs Q / alpha_T", 1e-6),
                ("creep x alpha_T constant", 1e-6),
                ("F/G at every alpha_T", 1e-8),
                ("Lagrange stick creep", 1e-12),
            ]),
            |_| alpha_t(),
        ),
        program(
            "friction_impact_cut",
            "Friction: first impact at constant velocity, increment cut at t = 0.325",
            &["friction", "contact", "penalty", "plane_strain", "exact"],
            checks(&[
                ("first accepted time vs impact 0.325", 3e-9),
                ("cut: at least one cutback", 0.0),
                ("cut: run ends at t = 2", 0.0),
                ("no cut: first increment whole, no cutback", 0.0),
            ]),
            |_| impact_cut(),
        ),
        program(
            "friction_quadratic",
            "Friction on quadratic faces (face-integrated): quad8/quad9 block up a plane at tan a = 0.1 and held below mu N; hex20/hex27/tet10 block up a slope",
            &[
                "quadratic",
                "friction",
                "contact",
                "penalty",
                "augmented_lagrange",
                "plane_strain",
                "3d",
                "closed_form",
            ],
            checks(&[
                ("quad8/quad9 F/G vs closed form", 1e-6),
                ("quad8/quad9 slip: |sum R_T| / (mu sum R_N) - 1", 1e-8),
                ("quad8/quad9 Q < mu N: nodes not sticking", 0.0),
                ("quad8/quad9 Q < mu N: |sum R_T + Q| / Q", 1e-8),
                ("quad8/quad9 Q < mu N: friction work", 1e-12),
                ("hex20 F/G vs closed form", 1e-6),
                ("hex27 F/G vs closed form", 1e-6),
                ("tet10 F/G vs closed form", 1e-6),
            ]),
            |_| quadratic_level(),
        ),
    ]
}
