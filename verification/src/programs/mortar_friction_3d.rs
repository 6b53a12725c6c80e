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
//! Measured per run: see [`CHECKS`]. Figures (`ctc verify
//! contact_patch_friction_3d`, 8 runs, 171 Newton iterations, 27 s dev):
//! stick, augmented Lagrangian: q deviation 2.2e-11 (hex8, x) / 1.7e-11
//! (hex8, 30 degrees) / 6.3e-11 (tet4, 30 degrees), p deviation <= 8.8e-12,
//! `|q| / tau - 1` <= 3.9e-12; stick, penalty (hex8, 30 degrees): q
//! deviation 3.7e-5, p deviation 3.4e-5, `|q| / tau - 1` 1.5e-5 — the
//! penalty's elastic slip `g_T = tau / k_T = 2.9e-6` moves the slave's rim
//! past the master's on the sides the shear points to: the rim nodes lose
//! the coverage of a strip `g_T` of their support (about `4 g_T / h` =
//! 3.5e-5 of their force, as in 2D), an end effect of the regularization
//! that the augmented Lagrangian closes; slip, penalty: `| |q| - mu p |`
//! 4.6e-16 / 3.1e-16 / 3.1e-16 of `mu p` (every node on the cone), `T /
//! (mu N) - 1` 5.1e-12 / 9.8e-9 / 3.4e-9, the direction of `T` off the
//! shear by 4e-14 / 1.6e-6 / 1.5e-5 rad (the slide of 5 % past the limit
//! overhangs the rim on two sides at 30 degrees: the pressure deviates by
//! 2.5e-3 / 3.5e-3 / 2.6e-3 from uniform, the nodes' slip directions
//! spread by that non-uniformity); slip, augmented Lagrangian (hex8, 30
//! degrees): the Uzawa loop leaves nodes sticking on the cone, `| |q| - mu
//! p |` 1.6e-7, `T / (mu N) - 1` 1.1e-7.
//!
//! [`NodeFriction::traction`]: ctc_engine::contact::friction::NodeFriction

use super::error;
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

/// The area penalty method of the runs.
pub const PENALTY: &str = "penalty { kind = area  stiffness = 1e8 }";
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

/// Names and tolerances of every value, in run order: per stick run the
/// largest deviation of the traction vectors from their mean, the
/// pressure's deviation from uniform and `|q_mean| / tau - 1`; per slip
/// run the largest `| |q_i| - mu p_i | / (mu p_mean)`, the total
/// tangential force over `mu` times the total normal one minus 1 (both
/// summed over the nodes' laws: `sum t_i A_i / T_i` against `mu sum R_i
/// A_i / T_i`), the angle between the total tangential force (in the
/// plane) and minus the shear, and the pressure's deviation from uniform.
/// The stick runs with the augmented Lagrangian and every `|q| = mu p`
/// are issue 18's 1e-8; the penalty's figures are guards (the measured
/// figure rounded up; see the module doc).
pub const CHECKS: [(&str, f64); 28] = [
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
    ("hex8 stick penalty 30deg: |q| / tau - 1", 3e-5),
    ("hex8 slip penalty x: max ||q| - mu p| / (mu p)", 1e-12),
    ("hex8 slip penalty x: T / (mu N) - 1", 1e-10),
    ("hex8 slip penalty x: T direction error (rad)", 1e-12),
    ("hex8 slip penalty x: p deviation", 1e-2),
    ("hex8 slip penalty 30deg: max ||q| - mu p| / (mu p)", 1e-12),
    ("hex8 slip penalty 30deg: T / (mu N) - 1", 3e-8),
    ("hex8 slip penalty 30deg: T direction error (rad)", 1e-5),
    ("hex8 slip penalty 30deg: p deviation", 1e-2),
    ("tet4 slip penalty 30deg: max ||q| - mu p| / (mu p)", 1e-12),
    ("tet4 slip penalty 30deg: T / (mu N) - 1", 1e-8),
    ("tet4 slip penalty 30deg: T direction error (rad)", 5e-5),
    ("tet4 slip penalty 30deg: p deviation", 1e-2),
    ("hex8 slip augmented 30deg: max ||q| - mu p| / (mu p)", 1e-6),
    ("hex8 slip augmented 30deg: T / (mu N) - 1", 1e-6),
    ("hex8 slip augmented 30deg: T direction error (rad)", 1e-5),
    ("hex8 slip augmented 30deg: p deviation", 1e-2),
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
    /// The pair's evaluation at the last converged increment.
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
    /// `(name suffix, value)` of each of the run's [`CHECKS`].
    pub values: Vec<(&'static str, f64)>,
    /// Closed slave nodes at the end.
    pub closed: usize,
    /// Newton iterations of the run.
    pub iterations: usize,
    /// Per closed slave node: the node, its traction vector `q` and its
    /// pressure.
    pub nodes: Vec<(usize, [f64; 3], f64)>,
}

/// Runs one of [`RUNS`].
pub fn run_one(r: &Run) -> Result<(Outcome, ProgramLevel), String> {
    run_edited(r, &|deck| deck)
}

/// Runs one of [`RUNS`] on its deck changed by `edit` (another
/// formulation, other meshes: `super::nagata_3d`'s node-to-facet runs).
pub fn run_edited(
    r: &Run,
    edit: &dyn Fn(String) -> String,
) -> Result<(Outcome, ProgramLevel), String> {
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
    let text = edit(deck(cell, method, k_t, delta, tau, t_lim, theta));
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
    // per node: the traction vector q (3D: in the node's tangent plane),
    // the pressure and the reference area
    let mut q: Vec<[f64; 3]> = Vec::new();
    let mut pr = Vec::new();
    let mut area = Vec::new();
    for c in &closed {
        let t = areas
            .iter()
            .find(|e| e.0 == c.node)
            .map(|e| e.1)
            .ok_or_else(|| format!("{name}: node {} is no slave", c.node))?;
        q.push(c.friction.traction.map(|v| v / t));
        pr.push(c.pressure);
        area.push(t);
    }
    let n = q.len() as f64;
    let mean_q: [f64; 3] = std::array::from_fn(|k| q.iter().map(|v| v[k]).sum::<f64>() / n);
    let mean_p = pr.iter().sum::<f64>() / n;
    let len = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let dp = pr.iter().map(|v| (v - mean_p).abs()).fold(0.0, f64::max) / mean_p;
    let values = if slip {
        let cone = q
            .iter()
            .zip(&pr)
            .map(|(v, p)| (len(*v) - MU * p).abs())
            .fold(0.0, f64::max)
            / (MU * mean_p);
        // the totals of the laws: T = sum q_i T_i, N = sum p_i T_i
        let t: [f64; 3] =
            std::array::from_fn(|k| q.iter().zip(&area).map(|(v, a)| v[k] * a).sum::<f64>());
        let normal: f64 = pr.iter().zip(&area).map(|(p, a)| p * a).sum();
        let angle = (t[1] * theta.cos() - t[0] * theta.sin())
            .atan2(-(t[0] * theta.cos() + t[1] * theta.sin()));
        vec![
            ("max ||q| - mu p| / (mu p)", cone),
            ("T / (mu N) - 1", len(t) / (MU * normal) - 1.0),
            ("T direction error (rad)", angle),
            ("p deviation", dp),
        ]
    } else {
        let dq = q
            .iter()
            .map(|v| len([v[0] - mean_q[0], v[1] - mean_q[1], v[2] - mean_q[2]]))
            .fold(0.0, f64::max)
            / len(mean_q);
        vec![
            ("q deviation", dq),
            ("p deviation", dp),
            ("|q| / tau - 1", len(mean_q) / tau - 1.0),
        ]
    };
    Ok((
        Outcome {
            values,
            closed: closed.len(),
            iterations: s.newton_iterations,
            nodes: closed
                .iter()
                .zip(q.iter().zip(&pr))
                .map(|(c, (v, p))| (c.node, *v, *p))
                .collect(),
        },
        level,
    ))
}

/// The [`CHECKS`] name of `suffix` of run `run`.
fn check_name(run: &str, suffix: &str) -> Result<&'static str, String> {
    CHECKS
        .iter()
        .find(|(n, _)| n.strip_prefix(run).and_then(|r| r.strip_prefix(": ")) == Some(suffix))
        .map(|c| c.0)
        .ok_or_else(|| format!("no check `{run}: {suffix}`"))
}

fn level(_level: usize) -> Result<ProgramLevel, String> {
    let mut out = ProgramLevel {
        h: 1.0 / 3.0,
        ..ProgramLevel::default()
    };
    for r in &RUNS {
        let (o, l) = run_one(r)?;
        super::contact_ntf_3d::add_level(&mut out, &l);
        for (suffix, v) in o.values {
            out.values.push(error(check_name(r.0, suffix)?, v.abs()));
        }
    }
    Ok(out)
}
