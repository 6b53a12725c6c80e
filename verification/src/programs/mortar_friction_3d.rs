//! `contact_patch_friction_3d` — the frictional contact patch test in 3D
//! with mortar contact (issue 18; Taylor & Papadopoulos, IJNME 31 (1991)
//! 2205 for the patch test, here in 3D; Gitterle, Popp, Gee & Wall, IJNME
//! 84 (2010) 543 for mortar friction; `ctc_engine::contact::mortar::friction3d`).
//!
//! ```text
//!              u = (delta cos th, delta sin th, -d) on top.zmax
//!   +-------------------------+
//!   | top [0,1]^2 x [0.5,1]   |  on the sides: t_z = -+tau cos th (x faces),
//!   | 3 x 3 cells across      |               -+tau sin th (y faces)
//!   +-------------------------+  slave = top.zmin (3 x 3 facets), mortar, mu = 0.3
//!   +-------------------------+  master = base.zmax (4 x 4 facets)
//!   | base [0,1]^2 x [0,0.5]  |  same side tractions
//!   | 4 x 4 cells across      |
//!   +-------------------------+  fixed (ux, uy, uz)
//!   E = 2e6, nu = 0 (G = 1e6); hex8, or tet4 (6 per hex); area penalty k_N = 1e8
//! ```
//!
//! Pressed by `d = 1e-2` (2 increments), then sheared (2 increments) along
//! the direction `th` (0, or 30 degrees: both tangent components act) by
//! a top displacement `delta` with the side tractions of the uniform state
//! (`sigma_zz = -p`, `(sigma_xz, sigma_yz) = tau (cos th, sin th)` in
//! both blocks, `p = d / (H / E + 1 / k_N)`, `H = 1`, without the `1 /
//! k_N` for the augmented Lagrangian): below the cone (`tau = mu p / 2`,
//! `delta = tau (H / G + 1 / k_T)`) every node sticks and the tangential
//! traction is uniform; past it (`delta` 1.05 times the stick limit, `tau
//! = mu p`) every node slips with `q = mu p`. Penalty (`k_T = 1e9` per
//! area) and augmented Lagrangian (`k_T = 1e8`, Uzawa on the normal and
//! stick gaps to 1e-13). `q` is the slave node's tangential traction
//! vector (`t A / T`, [`NodeFriction::traction`]) over its reference
//! tributary area `T` (the convention of the reported pressure).
//!
//! Measured per run: stick, the largest `|q_i - q_mean| / |q_mean|` (the
//! vectors: magnitude and direction), the pressure's deviation from
//! uniform and `|q_mean| / tau - 1`; slip, the largest `| |q_i| - mu p_i
//! | / (mu p_mean)`, the total tangential contact force over `mu` times
//! the total normal one minus 1, and the angle between the total
//! tangential force and minus the shear direction. See the figures in the
//! test `verification/tests/suite/contact_mortar_3d.rs`.
//!
//! [`NodeFriction::traction`]: ctc_engine::contact::friction::NodeFriction

use super::{error, value};
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::contact::friction::FrictionStatus;
use ctc_engine::contact::{ContactStatus, NodeContact};
use ctc_engine::model::{AnyModel, Model};
use ctc_engine::solve::{run, IncrementView, Observer};

const YOUNG: f64 = 2e6;
const SHEAR: f64 = 1e6;
const K_N: f64 = 1e8;
const MU: f64 = 0.3;
const PRESS: f64 = 1e-2;
/// Total height of the stack.
const HEIGHT: f64 = 1.0;
/// The slip runs' top displacement over the stick limit's.
const SLIP: f64 = 1.05;

const PENALTY: &str = "penalty { kind = area  stiffness = 1e8 }";
const AUGMENTED: &str = "augmented_lagrange { kind = area  penalty = 1e8  tolerance = 1e-13 }";

/// One run: name, cell, method, tangential penalty per area, slip, shear
/// direction (degrees).
pub type Run = (&'static str, &'static str, &'static str, f64, bool, f64);

/// The runs.
pub const RUNS: [Run; 8] = [
    ("hex8 stick augmented x", "hex8", AUGMENTED, 1e8, false, 0.0),
    (
        "hex8 stick augmented 30deg",
        "hex8",
        AUGMENTED,
        1e8,
        false,
        30.0,
    ),
    (
        "tet4 stick augmented 30deg",
        "tet4",
        AUGMENTED,
        1e8,
        false,
        30.0,
    ),
    (
        "hex8 stick penalty 30deg",
        "hex8",
        PENALTY,
        1e9,
        false,
        30.0,
    ),
    ("hex8 slip penalty x", "hex8", PENALTY, 1e9, true, 0.0),
    ("hex8 slip penalty 30deg", "hex8", PENALTY, 1e9, true, 30.0),
    ("tet4 slip penalty 30deg", "tet4", PENALTY, 1e9, true, 30.0),
    (
        "hex8 slip augmented 30deg",
        "hex8",
        AUGMENTED,
        1e8,
        true,
        30.0,
    ),
];

/// The quantities of a stick run and of a slip run (suffixes of the run's
/// name).
const STICK: [&str; 3] = ["q deviation", "p deviation", "|q| / tau - 1"];
const SLIPPING: [&str; 3] = [
    "max ||q| - mu p| / (mu p)",
    "T / (mu N) - 1",
    "T direction error (rad)",
];

/// Names and tolerances of every value, in run order.
pub const CHECKS: [(&str, f64); 24] = [
    ("hex8 stick augmented x: q deviation", 1e-8),
    ("hex8 stick augmented x: p deviation", 1e-8),
    ("hex8 stick augmented x: |q| / tau - 1", 1e-8),
    ("hex8 stick augmented 30deg: q deviation", 1e-8),
    ("hex8 stick augmented 30deg: p deviation", 1e-8),
    ("hex8 stick augmented 30deg: |q| / tau - 1", 1e-8),
    ("tet4 stick augmented 30deg: q deviation", 1e-8),
    ("tet4 stick augmented 30deg: p deviation", 1e-8),
    ("tet4 stick augmented 30deg: |q| / tau - 1", 1e-8),
    ("hex8 stick penalty 30deg: q deviation", 1e-4),
    ("hex8 stick penalty 30deg: p deviation", 1e-4),
    ("hex8 stick penalty 30deg: |q| / tau - 1", 2e-5),
    ("hex8 slip penalty x: max ||q| - mu p| / (mu p)", 1e-10),
    ("hex8 slip penalty x: T / (mu N) - 1", 1e-10),
    ("hex8 slip penalty x: T direction error (rad)", 1e-10),
    ("hex8 slip penalty 30deg: max ||q| - mu p| / (mu p)", 1e-10),
    ("hex8 slip penalty 30deg: T / (mu N) - 1", 1e-10),
    ("hex8 slip penalty 30deg: T direction error (rad)", 1e-10),
    ("tet4 slip penalty 30deg: max ||q| - mu p| / (mu p)", 1e-10),
    ("tet4 slip penalty 30deg: T / (mu N) - 1", 1e-10),
    ("tet4 slip penalty 30deg: T direction error (rad)", 1e-10),
    ("hex8 slip augmented 30deg: max ||q| - mu p| / (mu p)", 1e-6),
    ("hex8 slip augmented 30deg: T / (mu N) - 1", 1e-6),
    ("hex8 slip augmented 30deg: T direction error (rad)", 1e-6),
];

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    vec![VerifyCase {
        name: "contact_patch_friction_3d",
        title: "3D frictional contact patch test, two blocks 3x3 | 4x4 facets (hex8, tet4), \
                mortar: stick (uniform q) and slip (q = mu p), along x and at 30 degrees, \
                penalty and augmented Lagrangian",
        source: "Taylor & Papadopoulos IJNME 31 (1991), in 3D; Gitterle, Popp, Gee & Wall \
                 IJNME 84 (2010)",
        tags: &[
            "contact",
            "patch",
            "mortar",
            "friction",
            "two_bodies",
            "3d",
            "penalty",
            "augmented_lagrange",
            "exact",
        ],
        levels: 1,
        checks: CHECKS
            .iter()
            .map(|(n, t)| Check::new(Quantity::Named(n), &[*t]))
            .collect(),
        kind: CaseKind::Program(ProgramCase {
            max_levels: 1,
            run: level,
        }),
    }]
}

/// The exact pressure of the press (the augmented Lagrangian: no
/// penetration).
pub fn pressure(augmented: bool) -> f64 {
    PRESS / (HEIGHT / YOUNG + if augmented { 0.0 } else { 1.0 / K_N })
}

/// The deck of one run: `tau` the final shear traction, reached at `t_lim`
/// (then held), `delta` the final top displacement, along `theta`
/// (radians).
#[allow(clippy::too_many_arguments)]
pub fn deck(
    cell: &str,
    method: &str,
    k_t: f64,
    delta: f64,
    tau: f64,
    t_lim: f64,
    theta: f64,
) -> String {
    let (c, s) = (theta.cos(), theta.sin());
    let table = |v: f64| {
        if t_lim < 2.0 {
            format!("table((0, 0), (1, 0), ({t_lim:e}, {v:e}), (2, {v:e}))")
        } else {
            format!("table((0, 0), (1, 0), (2, {v:e}))")
        }
    };
    let mut sides = String::new();
    for body in ["top", "base"] {
        for (face, v) in [
            ("xmin", -tau * c),
            ("xmax", tau * c),
            ("ymin", -tau * s),
            ("ymax", tau * s),
        ] {
            if v != 0.0 {
                sides += &format!("traction {body}.{face} {{ tz = {} }}\n", table(v));
            }
        }
    }
    let ramp = |v: f64| format!("table((0, 0), (1, 0), (2, {v:e}))");
    format!(
        "# 3D frictional contact patch test, generated by verification/src/programs/mortar_friction_3d.rs\n\
         analysis {{ dimension = 3d }}\n\
         material soft {{ elastic {{ E = {YOUNG:e}  nu = 0 }} }}\n\
         body base {{\n  mesh = box {{ size = (1, 1, 0.5)  divisions = (4, 4, 2)  element = {cell} }}\n  material = soft\n}}\n\
         body top {{\n  mesh = box {{ origin = (0, 0, 0.5)  size = (1, 1, 0.5)  divisions = (3, 3, 2)  element = {cell} }}\n  material = soft\n}}\n\
         contact top.zmin -> base.zmax {{\n  method = {method}\n  friction = coulomb {{ mu = {MU}  stiffness = {k_t:e} }}\n  formulation = mortar\n}}\n\
         fix base.zmin {{ ux uy uz }}\n\
         displace top.zmax {{ uz = ramp(0, {:e}, 0, 1)  ux = {}  uy = {} }}\n\
         {sides}\
         step press {{\n  time = 0 .. 1\n  increments = 2\n  newton {{ tol = 1e-10  max_iter = 30 }}\n}}\n\
         step shear {{\n  time = 1 .. 2\n  increments = 2\n  newton {{ tol = 1e-10  max_iter = 30 }}\n}}\n",
        -PRESS,
        ramp(delta * c),
        ramp(delta * s),
    )
}

/// The contact of the last converged increment.
#[derive(Default)]
struct Last {
    contact: Vec<NodeContact<3>>,
}

impl Observer<3> for Last {
    fn converged(&mut self, v: &IncrementView<'_, 3>) -> Result<(), String> {
        self.contact = v.contact.first().cloned().unwrap_or_default();
        Ok(())
    }
}

/// Reference tributary area of every slave node of pair 0.
fn tributary(model: &Model<3>) -> Vec<(usize, f64)> {
    let nodes = model
        .contacts
        .first()
        .map_or_else(Vec::new, |c| c.nodes.clone());
    let faces = model
        .contacts
        .first()
        .map_or_else(Vec::new, |c| c.faces.clone());
    let areas = ctc_engine::contact::surface::tributary_areas(&model.mesh, &faces, &nodes);
    nodes.into_iter().zip(areas).collect()
}

/// The measures of one run.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The three values (see [`STICK`], [`SLIPPING`]).
    pub values: [f64; 3],
    /// Closed slave nodes at the end.
    pub closed: usize,
    /// Newton iterations of the run.
    pub iterations: usize,
    /// Mean `|q|` over `tau` (stick) or over `mu p_exact` (slip).
    pub ratio: f64,
}

/// Runs one of [`RUNS`].
pub fn run_one(r: &Run) -> Result<(Outcome, ProgramLevel), String> {
    let &(name, cell, method, k_t, slip, degrees) = r;
    let augmented = method.starts_with("augmented");
    let p = pressure(augmented);
    let compliance = HEIGHT / SHEAR + if augmented { 0.0 } else { 1.0 / k_t };
    let limit = MU * p * compliance;
    let (delta, tau, t_lim) = if slip {
        (SLIP * limit, MU * p, 1.0 + 1.0 / SLIP)
    } else {
        (0.5 * limit, 0.5 * MU * p, 2.0)
    };
    let theta = degrees.to_radians();
    let text = deck(cell, method, k_t, delta, tau, t_lim, theta);
    let path = std::path::Path::new("contact_patch_friction_3d.ctc");
    let src = ctc_lang::Source::new(path, &text);
    let AnyModel::D3(model) = ctc_lang::compile_any(&src).map_err(|d| d.render(&src))? else {
        return Err("the patch deck is not a 3d deck".into());
    };
    let mut last = Last::default();
    let s = run(&model, &mut last).map_err(|e| format!("{name}: {}", e.message))?;
    if !s.completed {
        return Err(format!("{name}: the run did not complete"));
    }
    let mut level = ProgramLevel {
        h: 1.0 / 3.0,
        ..ProgramLevel::default()
    };
    level.add_run(&s);
    level.nodes = model.mesh.nodes.len();
    let areas = tributary(&model);
    let closed: Vec<&NodeContact<3>> = last
        .contact
        .iter()
        .filter(|c| c.status == ContactStatus::Closed)
        .collect();
    if closed.len() != 16 {
        return Err(format!("{name}: {} closed nodes of 16", closed.len()));
    }
    let want = if slip {
        FrictionStatus::Slip
    } else {
        FrictionStatus::Stick
    };
    // the augmented Lagrangian's slip ends on the cone with its stick gap
    // closed by the Uzawa loop: stick or slip, `|q| = mu p` judges it
    let judged = !(slip && augmented);
    if let Some(c) = closed.iter().find(|c| judged && c.friction.status != want) {
        return Err(format!(
            "{name}: node {} is {:?}",
            c.node, c.friction.status
        ));
    }
    let mut q: Vec<[f64; 2]> = Vec::new();
    let mut pr = Vec::new();
    for c in &closed {
        let t = areas
            .iter()
            .find(|e| e.0 == c.node)
            .map(|e| e.1)
            .ok_or_else(|| format!("{name}: node {} is no slave", c.node))?;
        q.push([c.friction.traction[0] / t, c.friction.traction[1] / t]);
        pr.push(c.pressure);
    }
    let n = q.len() as f64;
    let mean_q = [
        q.iter().map(|v| v[0]).sum::<f64>() / n,
        q.iter().map(|v| v[1]).sum::<f64>() / n,
    ];
    let mean_p = pr.iter().sum::<f64>() / n;
    let len = |v: [f64; 2]| v[0].hypot(v[1]);
    let values = if slip {
        let cone = q
            .iter()
            .zip(&pr)
            .map(|(v, p)| (len(*v) - MU * p).abs())
            .fold(0.0, f64::max)
            / (MU * mean_p);
        // totals on the slave (top) block: N up, T against the shear
        let fz: f64 = closed.iter().map(|c| c.force[2]).sum();
        let t = [
            closed.iter().map(|c| c.force[0]).sum::<f64>(),
            closed.iter().map(|c| c.force[1]).sum::<f64>(),
        ];
        let angle = (t[1] * theta.cos() - t[0] * theta.sin())
            .atan2(-(t[0] * theta.cos() + t[1] * theta.sin()));
        [cone, len(t) / (MU * fz) - 1.0, angle.abs()]
    } else {
        let dq = q
            .iter()
            .map(|v| len([v[0] - mean_q[0], v[1] - mean_q[1]]))
            .fold(0.0, f64::max)
            / len(mean_q);
        let dp = pr.iter().map(|v| (v - mean_p).abs()).fold(0.0, f64::max) / mean_p;
        [dq, dp, len(mean_q) / tau - 1.0]
    };
    Ok((
        Outcome {
            values,
            closed: closed.len(),
            iterations: s.newton_iterations,
            ratio: len(mean_q) / if slip { MU * p } else { tau },
        },
        level,
    ))
}

fn level(_level: usize) -> Result<ProgramLevel, String> {
    let mut out = ProgramLevel {
        h: 1.0 / 3.0,
        ..ProgramLevel::default()
    };
    for (k, r) in RUNS.iter().enumerate() {
        let (o, l) = run_one(r)?;
        super::contact_ntf_3d::add_level(&mut out, &l);
        for (m, v) in o.values.iter().enumerate() {
            let name = CHECKS[3 * k + m].0;
            debug_assert!(name.ends_with(if r.4 { SLIPPING[m] } else { STICK[m] }));
            if m == 2 && !r.4 {
                out.values.push(value(name, o.ratio * 1.0, 1.0));
            } else {
                out.values.push(error(name, v.abs()));
            }
        }
    }
    Ok(out)
}
