//! Gravity (`gravity { gx gy gz }`, `model::Load::Gravity`), tags
//! `dynamics` / `gravity`:
//!
//! - `self_weight_column`: a column of height `L` held at its base, under
//!   its own weight (`nu = 0`, so the stress is uniaxial), quasi-static, in
//!   plane strain, axisymmetric (a solid cylinder) and 3D: the top moves
//!   by `rho g L^2 / (2 E)` (Timoshenko & Gere, Mechanics of Materials,
//!   1997, section 2.3, example 2-5). The consistent nodal loads of linear
//!   elements make the 1D nodal displacements exact, so the error is
//!   round-off; the total gravity force is `rho g V` (the reaction).
//!
//! ```text
//!    +--+  top: u = -rho g L^2 / (2 E)
//!    |  |
//!    |  |  | g
//!    |  |  v
//!    +--+
//!   /////  fixed
//! ```
//!
//! - `mass_spring_bounce_gravity`: a mass `M = 1` on a spring `k = 1000`
//!   (a massless one-cell block, `E = 1000`, `nu = 0`, 1 x 1, carrying a
//!   point mass `M/2` at each top node, `ux` held), dropped from `h0 =
//!   0.05` above a rigid floor under `g = 10`, the block's base on the
//!   floor by Lagrange multipliers (exact: the spring is the block's
//!   elasticity `k = E A / H`, no penalty), average-acceleration Newmark
//!   at `dt = 0.005, 0.0025, 0.00125`. Closed form (e.g. Chopra, Dynamics
//!   of Structures, 2012, section 3.1 for the free vibration with a
//!   constant force): free fall `u = -g t^2 / 2` until `t_f = sqrt(2 h0 /
//!   g)` at the impact speed `v_i = g t_f`; in contact `z'' = -w^2 z - g`
//!   (`w = sqrt(k/M)`, `z` the compression coordinate from the touching
//!   position, `z(0) = 0`, `z'(0) = -v_i`): `z = -d_s + d_s cos(w t) -
//!   (v_i / w) sin(w t)`, `d_s = M g / k`, contact for `t_c = (2 pi - 2
//!   phi) / w`, `phi = atan(v_i / (w d_s))`, the largest compression `d_s
//!   + R` with `R = sqrt(d_s^2 + (v_i / w)^2)`; then the rebound at `v_i`
//!   and a parabola again. Measured: the trajectory of the top node
//!   against it (max error over the run / h0), the largest compression
//!   (the sampled peak refined by the parabola through three samples),
//!   the rebound speed (from the energy of the flight after the release:
//!   `v_r^2 = v^2 + 2 g (u + h0)`), and the energy balance over `M g h0`.
//!
//! ```text
//!        [ M ]   point masses on the top nodes
//!        |/\/|   the block (k = E A / H), massless
//!        +---+   | g    h0 = 0.05 gap
//!   ==============  rigid floor (Lagrange)
//! ```

use super::value;
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::model::AnyModel;
use ctc_engine::solve::{run, IncrementView, Observer, RunSummary};

const G: f64 = 10.0;
const K: f64 = 1000.0;
const M: f64 = 1.0;
const H0: f64 = 0.05;
const T_END: f64 = 0.35;

const TRAJECTORY: &str = "trajectory: max |u - u_exact| / h0";
const COMPRESSION: &str = "largest compression vs M g / k + R";
const REBOUND: &str = "rebound speed vs impact speed sqrt(2 g h0)";
const BALANCE: &str = "energy balance: max |K + W_int - W_ext - W_c - K0| / (M g h0)";

const COLUMN_NAMES: [&str; 3] = [
    "plane strain column: top displacement vs rho g L^2 / (2 E)",
    "axisymmetric column: top displacement vs rho g L^2 / (2 E)",
    "3d column: top displacement vs rho g L^2 / (2 E)",
];
const WEIGHT_NAMES: [&str; 3] = [
    "plane strain column: base reaction vs rho g V",
    "axisymmetric column: base reaction vs rho g V",
    "3d column: base reaction vs rho g V",
];

/// The closed-form displacement of the top node at `t`.
fn exact(t: f64) -> f64 {
    let t_f = (2.0 * H0 / G).sqrt();
    let v_i = G * t_f;
    let w = (K / M).sqrt();
    let d_s = M * G / K;
    let phi = (v_i / (w * d_s)).atan();
    let t_c = (2.0 * std::f64::consts::PI - 2.0 * phi) / w;
    if t <= t_f {
        -0.5 * G * t * t
    } else if t <= t_f + t_c {
        let s = t - t_f;
        -H0 - d_s + d_s * (w * s).cos() - v_i / w * (w * s).sin()
    } else {
        let s = t - t_f - t_c;
        -H0 + v_i * s - 0.5 * G * s * s
    }
}

/// The bounce deck at `n` increments.
fn bounce_deck(n: usize) -> String {
    format!(
        "analysis {{ dimension = plane_strain }}\n\
         material spring {{ elastic {{ E = {K}  nu = 0 }}  density = 0 }}\n\
         body block {{\n  mesh = rectangle {{ origin = (0, {H0})  size = (1, 1)  divisions = (1, 1) }}\n  material = spring\n}}\n\
         tool floor = plane {{ point = (0, 0)  normal = (0, 1) }}\n\
         contact block.bottom -> floor {{ method = lagrange {{ }} }}\n\
         fix block.all {{ ux }}\n\
         point_mass block.top {{ mass = {} }}\n\
         gravity {{ gy = -{G} }}\n\
         step bounce {{\n  time = 0 .. {T_END}\n  increments = {n}\n  \
         dynamic {{ scheme = newmark }}\n  newton {{ tol = 1e-12 }}\n}}\n",
        M / 2.0
    )
}

/// Per converged increment of the bounce: the top node's displacement
/// and velocity, whether the floor pushes, the energy balance.
#[derive(Default)]
struct Bounce {
    rows: Vec<(f64, f64, f64, bool)>,
    balance: f64,
}

impl Observer<2> for Bounce {
    fn converged(&mut self, view: &IncrementView<'_, 2>) -> Result<(), String> {
        let nodes = &view.model.mesh.nodes;
        let top = (0..nodes.len())
            .max_by(|&a, &b| nodes[a][1].total_cmp(&nodes[b][1]).then(b.cmp(&a)))
            .ok_or("no node")?;
        let v = view.velocity.ok_or("no velocity in a dynamic run")?[2 * top + 1];
        let pushes = view
            .contact
            .iter()
            .flatten()
            .any(|n| n.force.iter().any(|f| *f != 0.0));
        self.rows
            .push((view.time, view.displacement[top][1], v, pushes));
        if let Some(e) = view.energy {
            self.balance = self.balance.max(e.balance.abs());
        }
        Ok(())
    }
}

fn compile_run<O: Observer<2> + Observer<3>>(
    name: &str,
    text: String,
    observer: &mut O,
) -> Result<RunSummary, String> {
    let src = ctc_lang::Source::new(name, text);
    let summary = match ctc_lang::compile_any(&src).map_err(|d| d.render(&src))? {
        AnyModel::D2(m) => run(&m, observer),
        AnyModel::D3(m) => run(&m, observer),
    }
    .map_err(|e| e.message)?;
    if !summary.completed {
        return Err(format!("{name}: the run did not complete"));
    }
    Ok(summary)
}

impl Observer<3> for Bounce {
    fn converged(&mut self, _view: &IncrementView<'_, 3>) -> Result<(), String> {
        Err("the bounce is planar".into())
    }
}

fn bounce(level: usize) -> Result<ProgramLevel, String> {
    let n = 70 << level;
    let dt = T_END / n as f64;
    let mut trace = Bounce::default();
    let summary = compile_run("bounce.ctc", bounce_deck(n), &mut trace)?;
    let trajectory = trace
        .rows
        .iter()
        .map(|(t, u, _, _)| (u - exact(*t)).abs())
        .fold(0.0, f64::max)
        / H0;
    let first = trace
        .rows
        .iter()
        .position(|r| r.3)
        .ok_or("the block never touched the floor")?;
    let release = first
        + trace.rows[first..]
            .iter()
            .position(|r| !r.3)
            .ok_or("the block never left the floor")?;
    // the sampled peak refined by the parabola through it and its
    // neighbours (the samples alone are off by up to w^2 c dt^2 / 8)
    let c: Vec<f64> = trace.rows.iter().map(|r| -(r.1 + H0)).collect();
    let i = (first..release)
        .max_by(|&a, &b| c[a].total_cmp(&c[b]))
        .ok_or("no contact increment")?;
    let compression = if i > 0 && i + 1 < c.len() {
        let (a, b, d) = (c[i - 1], c[i], c[i + 1]);
        let curvature = 2.0 * b - a - d;
        if curvature > 0.0 {
            b + (d - a).powi(2) / (8.0 * curvature)
        } else {
            b
        }
    } else {
        c[i]
    };
    let &(_, u, v, _) = trace.rows.last().ok_or("no increment")?;
    if release + 2 > trace.rows.len() {
        return Err("no flight after the rebound".into());
    }
    let v_r = (v * v + 2.0 * G * (u + H0)).sqrt();
    let v_i = (2.0 * G * H0).sqrt();
    let w = (K / M).sqrt();
    let d_s = M * G / K;
    let r = d_s.hypot(v_i / w);
    let mut out = ProgramLevel {
        h: dt,
        values: vec![
            super::error(TRAJECTORY, trajectory),
            value(COMPRESSION, compression, d_s + r),
            value(REBOUND, v_r, v_i),
            super::error(BALANCE, trace.balance / (M * G * H0)),
        ],
        ..ProgramLevel::default()
    };
    out.add_run(&summary);
    Ok(out)
}

/// The column under its own weight: `(deck, L, base area or volume
/// factor)`: E = 1000, rho = 2, g = 10, L = 4, nu = 0.
fn column_deck(s: usize) -> String {
    let common = "material m { elastic { E = 1000  nu = 0 }  density = 2 }\n\
                  step weigh { time = 0 .. 1  increments = 1  newton { tol = 1e-12 } }\n";
    match s {
        0 => format!(
            "analysis {{ dimension = plane_strain }}\n{common}\
             body col {{\n  mesh = rectangle {{ origin = (0, 0)  size = (1, 4)  divisions = (2, 8) }}\n  material = m\n}}\n\
             fix col.bottom {{ ux uy }}\nfix col.all {{ ux }}\ngravity {{ gy = -10 }}\n"
        ),
        1 => format!(
            "analysis {{ dimension = axisymmetric }}\n{common}\
             body col {{\n  mesh = rectangle {{ origin = (0, 0)  size = (1, 4)  divisions = (2, 8) }}\n  material = m\n}}\n\
             fix col.bottom {{ ux uy }}\nfix col.all {{ ux }}\ngravity {{ gy = -10 }}\n"
        ),
        _ => format!(
            "analysis {{ dimension = 3d }}\n{common}\
             body col {{\n  mesh = box {{ size = (1, 1, 4)  divisions = (2, 2, 8) }}\n  material = m\n}}\n\
             fix col.zmin {{ ux uy uz }}\nfix col.all {{ ux uy }}\ngravity {{ gz = -10 }}\n"
        ),
    }
}

/// The top displacement (largest along the vertical axis `axis`) and the
/// total vertical reaction.
#[derive(Default)]
struct Column {
    top: f64,
    reaction: f64,
}

fn column_at<const D: usize>(c: &mut Column, view: &IncrementView<'_, D>) {
    let axis = D - 1;
    let nodes = &view.model.mesh.nodes;
    let high = nodes.iter().map(|x| x[axis]).fold(f64::MIN, f64::max);
    let tops: Vec<usize> = (0..nodes.len())
        .filter(|&n| nodes[n][axis] == high)
        .collect();
    c.top = tops
        .iter()
        .map(|&n| view.displacement[n][axis])
        .sum::<f64>()
        / tops.len().max(1) as f64;
    c.reaction = view.reaction.iter().map(|r| r[axis]).sum();
}

impl Observer<2> for Column {
    fn converged(&mut self, view: &IncrementView<'_, 2>) -> Result<(), String> {
        column_at(self, view);
        Ok(())
    }
}

impl Observer<3> for Column {
    fn converged(&mut self, view: &IncrementView<'_, 3>) -> Result<(), String> {
        column_at(self, view);
        Ok(())
    }
}

fn columns(_level: usize) -> Result<ProgramLevel, String> {
    let (e, rho, g, l) = (1000.0, 2.0, 10.0, 4.0);
    let mut out = ProgramLevel {
        h: f64::NAN,
        ..ProgramLevel::default()
    };
    for s in 0..3 {
        let mut c = Column::default();
        let summary = compile_run("column.ctc", column_deck(s), &mut c)?;
        // plane strain: thickness 1; axisymmetric: a solid cylinder of
        // radius 1 (totals over 2 pi); 3d: a 1 x 1 section
        let volume = match s {
            1 => std::f64::consts::PI * l,
            _ => l,
        };
        out.values
            .push(value(COLUMN_NAMES[s], c.top, -rho * g * l * l / (2.0 * e)));
        out.values
            .push(value(WEIGHT_NAMES[s], c.reaction, rho * g * volume));
        out.add_run(&summary);
    }
    Ok(out)
}

/// The registry entries.
pub fn cases() -> Vec<VerifyCase> {
    let mut column_checks = Vec::new();
    for (a, b) in COLUMN_NAMES.iter().zip(WEIGHT_NAMES) {
        column_checks.push(Check::new(Quantity::Named(a), &[1e-9]));
        column_checks.push(Check::new(Quantity::Named(b), &[1e-9]));
    }
    vec![
        VerifyCase {
            name: "self_weight_column",
            title: "Column under its own weight (gravity, nu = 0), quasi-static, plane strain / axisymmetric / 3d: top displacement vs rho g L^2 / (2 E), base reaction vs rho g V",
            source: "Timoshenko & Gere, Mechanics of Materials (4th ed. 1997), section 2.3 (bar hanging under its own weight)",
            tags: &["gravity", "plane_strain", "axisymmetric", "3d"],
            levels: 1,
            // measured: top displacement 2.2e-15, 1.1e-15, 2.9e-15;
            // reaction 2.2e-15, 4.4e-16, 8.9e-16 (plane strain,
            // axisymmetric, 3d)
            checks: column_checks,
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: columns,
            }),
        },
        VerifyCase {
            name: "mass_spring_bounce_gravity",
            title: "Mass on a spring dropped onto a rigid floor under gravity (M = 1, k = 1000, g = 10, h0 = 0.05; Lagrange contact, average-acceleration Newmark at dt = 0.005, 0.0025, 0.00125): trajectory vs the closed form (parabola, shifted half sine, parabola), largest compression, rebound speed = impact speed, energy balance",
            source: "Chopra, Dynamics of Structures (4th ed. 2012), sections 2.1 and 3.1 (free vibration, constant force); closed form of the drop in the module's documentation",
            tags: &["dynamics", "gravity", "contact", "plane_strain"],
            levels: 3,
            // measured (levels 0, 1, 2): trajectory 7.0e-3, 2.4e-3,
            // 3.1e-4 of h0; compression 6.3e-7, 2.1e-7, 4.3e-8; rebound
            // speed 2.1e-3, 7.8e-4, 1.1e-5; balance 2.0e-14, 2.6e-14,
            // 1.7e-13
            checks: vec![
                Check::new(Quantity::Named(TRAJECTORY), &[1e-2, 4e-3, 5e-4]),
                Check::new(Quantity::Named(COMPRESSION), &[2e-6, 5e-7, 1e-7]),
                Check::new(Quantity::Named(REBOUND), &[3e-3, 1.2e-3, 5e-5]),
                Check::new(Quantity::Named(BALANCE), &[1e-10]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 3,
                run: bounce,
            }),
        },
    ]
}
