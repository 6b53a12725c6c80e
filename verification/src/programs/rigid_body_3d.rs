//! 3D rigid bodies (6 dofs: the pilot's translation and the total
//! rotation vector, issue 19; deck `rigid_body NODES { center = (x, y, z)
//! .. }`, `engine/src/solve/rigid_body.rs`); tags `dynamics rigid_body
//! 3d`.
//!
//! - `rigid_body_bearing_frequency_3d`: a hex8 cube (density 1) made
//!   rigid with a mass `M` and an isotropic rotary inertia (six inertia
//!   points) on an isotropic bearing spring `k`, given a velocity along the
//!   skew direction `(0.48, 0.6, 0.64)`: the centre vibrates along it at
//!   `omega = sqrt(k / m_total)`, `m_total = M + rho V` (Thomson & Dahleh,
//!   Theory of Vibration with Applications, 1998, section 2.1);
//!   average-acceleration Newmark at `dt = T/20, T/40`: the period, the
//!   energy balance, the ties' gap.
//! - `jeffcott_rotor_whirl_3d`: the planar case's Jeffcott rotor as a
//!   massless hex8 cube with point masses `m0` at its eight corners and an
//!   eccentric `m_e` at the corner `(h, h, h)`, rigid about its centre
//!   (mass `M`), spun about z (`axis = (0, 0, 1)`) up to `omega` on an
//!   isotropic damped bearing (`zeta = 0.2`, 10 natural periods): the
//!   steady whirl radius in
//!   the xy plane against `e r^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2)`, `e =
//!   m_e sqrt(2) h / m_total` (Genta, Dynamics of Rotating Systems, 2005,
//!   section 4.2), at `r = 0.5` and `2`, Newmark at `dt = T_n/40, T_n/80`.
//! - `rigid_hub_spins_a_disc_3d`: a finite-strain (neo-Hookean) hex8
//!   ring whose inner face is a rigid hub turned quasi-statically by 3
//!   rad about the skew axis `(1, 1, 1)` in 10 increments, nothing else
//!   holding it: every node follows the rigid rotation.
//! - `free_symmetric_top_3d`: a torque-free symmetric body (mass 1,
//!   inertia `diag(1, 1, 1.5)` about its centre, carried by the six
//!   inertia points; a massless hex8 cube tied to it), free (no bearing),
//!   spun at `omega0 = (0.4, 0, 1)`: the angular momentum `L = sum m x x
//!   v` is conserved, and the symmetry axis precesses about `L` at the
//!   rate `|L| / J_1` on a cone of constant half-angle (Goldstein,
//!   Classical Mechanics, 3rd ed. 2002, section 5.6; Landau & Lifshitz,
//!   Mechanics, section 33); average-acceleration Newmark to t = 2 at `dt
//!   = 0.02, 0.01`.
//! - `free_top_several_turns_3d`: the same top spun ten times faster
//!   (`10 omega0`, about 3.4 turns of the body by `t = 2`): its total
//!   rotation vector is carried over to `psi (1 - 2 pi / |psi|)` each
//!   time `|psi|` passes `pi` (`solve/rotation_chart.rs`); the same
//!   measures and the body's turns (the sum of the increments' rotation
//!   angles) against the closed form `R(t) = exp(t [L / J1]x) exp(t [w3
//!   (J1 - J3) / J1 e3]x)`; Newmark at `dt = 0.005, 0.0025`.
//!
//! - `torqued_body_3d`: a free rigid body with isotropic inertia `J`
//!   (mass 1, `inertia = 1`: `L = J omega` whatever its orientation),
//!   spun at `omega0 = (0.4, 0, 1)` and driven by a moment `m(t) = 0.6 t
//!   a`, `a = (1, -2, 2) / 3` fixed in space (`moment = ramp(0, 1.2, 0,
//!   2)  axis = (1, -2, 2)`, applied work-conjugately on the total
//!   rotation vector: `T(psi)^T m`). Euler's equations reduce to `J
//!   omega' = m`: `L(t) = J omega0 + 0.3 t^2 a` and `K(t) = |L(t)|^2 / (2
//!   J)`, at any rotation (the body turns about 2 rad about a moving axis
//!   by `t = 2`). Average-acceleration Newmark at `dt = 0.02, 0.01`.
//!   Measured (`ctc verify torqued_body_3d --max-level 1`, 0.4 / 0.6 s
//!   debug): `L` 8.3e-4 / 2.3e-4, `K` 9.3e-4 / 2.6e-4 (rate 1.85), energy
//!   balance 5.6e-13 / 8.6e-12; the same run with the moment put on psi
//!   as a dead load (`f_psi = m`, not conjugate): `L` 0.49 / 0.49, `K`
//!   3.6e-2 / 3.7e-2, no convergence in dt.
//!   Then a constant moment `m = 0.6 a` from `t = 0` (`L(t) = J omega0 +
//!   m t`): the spin node carries no mass, so the moment reaches the
//!   inertia points through the ties' static condensation at the start
//!   (`Newton::consistent_start`): `L` 8.5e-4 / 2.4e-4, `K` 9.6e-4 /
//!   2.7e-4 (rate 1.83). Without the condensation (the start left the
//!   massless dofs' residual out: a zero initial acceleration) 5.8e-3 /
//!   2.7e-3 and 6.2e-3 / 2.9e-3, first order (rate 1.10).
//!
//! ```text
//!        L (fixed)
//!        |   e3 (symmetry axis)
//!        |  /          e3 turns about L at |L| / J1,
//!        | /           the cone's half-angle constant
//!        |/
//!   -----o-----  six inertia points at +-a q_k (equimomental system)
//! ```

use super::rigid_body::crossings;
use super::{error, value};
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::model::AnyModel;
use ctc_engine::model::{Discrete, InitialVelocity, Model};
use ctc_engine::solve::{IncrementView, Observer, RunSummary};

const PERIOD: &str = "bearing 3d: period vs 2 pi sqrt(m_total / k)";
const BALANCE: &str = "bearing 3d: energy balance max |K + W_int - K0| / K0";
const OFF_LINE: &str = "bearing 3d: max distance of the centre from its line / amplitude";
const TIE_GAP: &str = "bearing 3d: max tie gap / amplitude";
const WHIRL_SUB: &str =
    "Jeffcott 3d r = 0.5: whirl radius vs e r^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2)";
const WHIRL_SUPER: &str =
    "Jeffcott 3d r = 2: whirl radius vs e r^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2)";
const WHIRL_Z: &str =
    "Jeffcott 3d: max |u_z| of the centre / whirl radius (the elastic cube's nodal motion through the ties)";
const WHIRL_BALANCE: &str = "Jeffcott 3d: energy balance max |balance| / max energy";
const SPIN_ERROR: &str = "hub 3d spun 3 rad about (1, 1, 1): max |u - u_rigid| / outer radius";
const MOMENTUM: &str = "free top: max |L(t) - L(0)| / |L(0)|";
const PRECESSION: &str = "free top: precession angle of the axis about L vs |L| t / J1";
const NUTATION: &str = "free top: max change of the angle between the axis and L (rad)";
const TOP_ENERGY: &str =
    "free top: max |K(t) - K0| / K0 (the kinetic energy of the inertia points)";
const TURNS_MOMENTUM: &str = "free top spun 10x (several turns): max |L(t) - L(0)| / |L(0)|";
const TURNS_PRECESSION: &str =
    "free top spun 10x: precession angle of the axis about L vs |L| t / J1";
const TURNS_NUTATION: &str =
    "free top spun 10x: max change of the angle between the axis and L (rad)";
const TURNS_ENERGY: &str = "free top spun 10x: max |K(t) - K0| / K0";
const TURNS_ANGLE: &str =
    "free top spun 10x: turns of the body (sum of the increments' rotation angles / 2 pi) vs the closed form's";

/// Compiles a 3D deck; the pilot and spin nodes of its (only) rigid body.
fn compile(name: &str, deck: String) -> Result<(Model<3>, usize, usize), String> {
    let src = ctc_lang::Source::new(name, deck);
    let model = match ctc_lang::compile_any(&src).map_err(|d| d.render(&src))? {
        AnyModel::D3(m) => m,
        AnyModel::D2(_) => return Err("not a 3d model".into()),
    };
    let (pilot, spin) = ctc_engine::solve::rigid_body::bodies(&model)
        .next()
        .ok_or("no rigid body")?;
    Ok((model, pilot, spin))
}

/// Every converged increment: the time, every node's displacement and
/// velocity, the energy audit's worst balance and largest energy, the
/// ties' largest gap.
#[derive(Default)]
struct Trace {
    time: Vec<f64>,
    u: Vec<Vec<[f64; 3]>>,
    v: Vec<Vec<f64>>,
    balance: f64,
    scale: f64,
    gap: f64,
}

impl Observer<3> for Trace {
    fn converged(&mut self, view: &IncrementView<'_, 3>) -> Result<(), String> {
        self.time.push(view.time);
        self.u.push(view.displacement.to_vec());
        self.v
            .push(view.velocity.map(<[f64]>::to_vec).unwrap_or_default());
        if let Some(e) = view.energy {
            self.balance = self.balance.max(e.balance.abs());
            self.scale = self
                .scale
                .max(e.kinetic.abs())
                .max(e.internal.abs())
                .max(e.external.abs());
        }
        self.gap = self.gap.max(ctc_engine::solve::rigid_body::max_tie_gap(
            view.model,
            view.displacement.as_flattened(),
        ));
        Ok(())
    }
}

fn run(model: &Model<3>) -> Result<(Trace, RunSummary), String> {
    let mut trace = Trace::default();
    let summary = ctc_engine::solve::run(model, &mut trace).map_err(|e| e.message)?;
    if !summary.completed {
        return Err("the run did not complete".into());
    }
    Ok((trace, summary))
}

/// Gives the rigid body of `model` (pilot, spin) the rigid velocity `v +
/// omega x (X - X_c)` at every node tied to it (its inertia points too),
/// `v` at the pilot and `omega` as the rotation vector's rate (`psi = 0`).
fn rigid_velocity(model: &mut Model<3>, pilot: usize, spin: usize, v: [f64; 3], w: [f64; 3]) {
    let nodes: Vec<usize> = model
        .discrete
        .iter()
        .find_map(|d| match d {
            Discrete::Rigid {
                nodes, pilot: p, ..
            } if *p == pilot => Some(nodes.clone()),
            _ => None,
        })
        .unwrap_or_default();
    let xc = model.mesh.nodes[pilot];
    let mut push = |n: usize, value: [f64; 3]| {
        for (c, x) in value.iter().enumerate() {
            model.initial_velocities.push(InitialVelocity {
                label: format!("rigid velocity of node {n}"),
                nodes: vec![n],
                component: c,
                value: *x,
            });
        }
    };
    for n in nodes {
        let x = model.mesh.nodes[n];
        let r = [x[0] - xc[0], x[1] - xc[1], x[2] - xc[2]];
        let wr = cross(w, r);
        push(n, [v[0] + wr[0], v[1] + wr[1], v[2] + wr[2]]);
    }
    push(pilot, v);
    push(spin, w);
}

/// The point masses of `model` per node (the inertia points of its rigid
/// bodies; the cubes of these cases are massless).
fn node_masses(model: &Model<3>) -> Vec<f64> {
    let mut mass = vec![0.0; model.mesh.nodes.len()];
    for d in &model.discrete {
        if let Discrete::Mass { nodes, mass: m, .. } = d {
            for &a in nodes {
                mass[a] += m;
            }
        }
    }
    mass
}

/// The angular momentum about the origin `sum m x x v` and the kinetic
/// energy of the point masses `mass` at displacements `u`, velocities `v`.
fn momentum_and_kinetic(
    model: &Model<3>,
    mass: &[f64],
    u: &[[f64; 3]],
    v: &[f64],
) -> ([f64; 3], f64) {
    let (mut l, mut k) = ([0.0; 3], 0.0);
    for (a, m) in mass.iter().enumerate().filter(|(_, m)| **m > 0.0) {
        let x = model.mesh.nodes[a];
        let x = [x[0] + u[a][0], x[1] + u[a][1], x[2] + u[a][2]];
        let va = [v[3 * a], v[3 * a + 1], v[3 * a + 2]];
        let c = cross(x, va);
        for i in 0..3 {
            l[i] += m * c[i];
        }
        k += 0.5 * m * dot(va, va);
    }
    (l, k)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

const BEARING_K: f64 = 4.0;
const BEARING_M: f64 = 0.5;
const RHO: f64 = 1.0;
const DIRECTION: [f64; 3] = [0.48, 0.6, 0.64];

fn bearing(level: usize) -> Result<ProgramLevel, String> {
    let m_total = BEARING_M + RHO;
    let omega = (BEARING_K / m_total).sqrt();
    let t = std::f64::consts::TAU / omega;
    let n = 20 << level;
    let deck = format!(
        "analysis {{ dimension = 3d }}\n\
         material m {{ elastic {{ E = 1e3  nu = 0.3 }}  density = {RHO} }}\n\
         body cube {{ mesh = box {{ origin = (-0.5, -0.5, -0.5)  size = (1, 1, 1)  divisions = (1, 1, 1) }}  material = m  kinematics = finite }}\n\
         rigid_body cube.all {{ center = (0, 0, 0)  mass = {BEARING_M}  inertia = 0.1  stiffness = {BEARING_K}  tie_stiffness = 1e4 }}\n\
         initial_velocity cube.all {{ vx = {}  vy = {}  vz = {} }}\n\
         step vibrate {{\n  time = 0 .. {}\n  increments = {}\n  dynamic {{ scheme = newmark }}\n  newton {{ tol = 1e-10 }}\n}}\n",
        DIRECTION[0],
        DIRECTION[1],
        DIRECTION[2],
        3.0 * t,
        3 * n
    );
    let (mut model, pilot, spin) = compile("bearing_3d.ctc", deck)?;
    // the pilot and the inertia points move with the cube from the start
    rigid_velocity(&mut model, pilot, spin, DIRECTION, [0.0; 3]);
    let (trace, summary) = run(&model)?;
    let along: Vec<f64> = trace.u.iter().map(|u| dot(u[pilot], DIRECTION)).collect();
    let off = trace
        .u
        .iter()
        .zip(&along)
        .map(|(u, a)| {
            let p = u[pilot];
            let d = [
                p[0] - a * DIRECTION[0],
                p[1] - a * DIRECTION[1],
                p[2] - a * DIRECTION[2],
            ];
            dot(d, d).sqrt()
        })
        .fold(0.0, f64::max);
    let c = crossings(&along, &trace.time);
    if c.len() < 3 {
        return Err(format!("too few cycles: {} crossings", c.len()));
    }
    if summary.cutbacks > 0 {
        return Err(format!("{} cutbacks", summary.cutbacks));
    }
    let m = c.len() - 1;
    let t_h = 2.0 * (c[m] - c[0]) / m as f64;
    let k0 = 0.5 * m_total;
    let amplitude = 1.0 / omega;
    let mut out = ProgramLevel {
        h: t / n as f64,
        values: vec![
            value(PERIOD, t_h, t),
            error(BALANCE, trace.balance / k0),
            error(OFF_LINE, off / amplitude),
            error(TIE_GAP, trace.gap / amplitude),
        ],
        ..ProgramLevel::default()
    };
    out.add_run(&summary);
    Ok(out)
}

const J_M: f64 = 0.8;
const J_M0: f64 = 0.025;
const J_ME: f64 = 0.1;
const J_K: f64 = 1.0;
const J_ZETA: f64 = 0.2;
const J_HALF: f64 = 0.1;

/// The 3D Jeffcott rotor at `omega = ratio omega_n`, `n` increments per
/// natural period: the mean whirl radius over the last natural period,
/// its closed form, the largest axial displacement over the whirl radius,
/// the energy balance.
fn jeffcott(ratio: f64, n: usize) -> Result<(f64, f64, f64, f64, RunSummary), String> {
    let m_total = J_M + 8.0 * J_M0 + J_ME;
    let omega_n = (J_K / m_total).sqrt();
    let c = 2.0 * J_ZETA * (J_K * m_total).sqrt();
    let t_n = std::f64::consts::TAU / omega_n;
    let omega = ratio * omega_n;
    let (spin_up, total) = (2.0 * t_n, 10.0 * t_n);
    let h = J_HALF;
    let deck = format!(
        "analysis {{ dimension = 3d }}\n\
         material m {{ elastic {{ E = 1e3  nu = 0.3 }}  density = 0 }}\n\
         body rotor {{ mesh = box {{ origin = ({}, {}, {})  size = ({}, {}, {})  divisions = (1, 1, 1) }}  material = m  kinematics = finite }}\n\
         point_mass rotor.all {{ mass = {J_M0} }}\n\
         point_mass rotor.node(near({h}, {h}, {h})) {{ mass = {J_ME} }}\n\
         rigid_body rotor.all {{ center = (0, 0, 0)  axis = (0, 0, 1)  mass = {J_M}  stiffness = {J_K}  damping = {c}  \
         angular_velocity = ramp(0, {omega}, 0, {spin_up})  tie_stiffness = 1e3 }}\n\
         step whirl {{\n  time = 0 .. {total}\n  increments = {}\n  dynamic {{ scheme = newmark }}\n  newton {{ tol = 1e-10 }}\n}}\n",
        -h,
        -h,
        -h,
        2.0 * h,
        2.0 * h,
        2.0 * h,
        10 * n
    );
    let (model, pilot, _) = compile("jeffcott_3d.ctc", deck)?;
    let (trace, summary) = run(&model)?;
    let e = J_ME * h * std::f64::consts::SQRT_2 / m_total;
    let r2 = ratio * ratio;
    let exact = e * r2 / ((1.0 - r2).powi(2) + (2.0 * J_ZETA * ratio).powi(2)).sqrt();
    let last: Vec<f64> = trace
        .u
        .iter()
        .zip(&trace.time)
        .filter(|(_, &t)| t > total - t_n * (1.0 + 1e-9))
        .map(|(u, _)| u[pilot][0].hypot(u[pilot][1]))
        .collect();
    if last.is_empty() {
        return Err("no increment in the last period".into());
    }
    let mean = last.iter().sum::<f64>() / last.len() as f64;
    let axial = trace
        .u
        .iter()
        .map(|u| u[pilot][2].abs())
        .fold(0.0, f64::max);
    Ok((
        mean,
        exact,
        axial / mean,
        trace.balance / trace.scale.max(f64::MIN_POSITIVE),
        summary,
    ))
}

fn whirl(level: usize) -> Result<ProgramLevel, String> {
    let n = 40 << level;
    let (sub, sub_exact, z_sub, balance_sub, s1) = jeffcott(0.5, n)?;
    let (sup, sup_exact, z_sup, balance_sup, s2) = jeffcott(2.0, n)?;
    let m_total = J_M + 8.0 * J_M0 + J_ME;
    let t_n = std::f64::consts::TAU * (m_total / J_K).sqrt();
    let mut out = ProgramLevel {
        h: t_n / n as f64,
        values: vec![
            value(WHIRL_SUB, sub, sub_exact),
            value(WHIRL_SUPER, sup, sup_exact),
            error(WHIRL_Z, z_sub.max(z_sup)),
            error(WHIRL_BALANCE, balance_sub.max(balance_sup)),
        ],
        ..ProgramLevel::default()
    };
    out.add_run(&s1);
    out.add_run(&s2);
    Ok(out)
}

fn spin(_level: usize) -> Result<ProgramLevel, String> {
    let (inner, outer, angle, zc) = (0.3_f64, 1.0_f64, 3.0_f64, 0.1);
    let deck = format!(
        "analysis {{ dimension = 3d }}\n\
         material m {{ neo_hookean {{ E = 1e3  nu = 0.3 }} }}\n\
         body disc {{ mesh = tube {{ inner = {inner}  outer = {outer}  height = 0.2  divisions = (2, 12, 1) }}  material = m  kinematics = finite }}\n\
         rigid_body disc.inner {{ center = (0, 0, {zc})  axis = (1, 1, 1)  rotation = ramp(0, {angle})  stiffness = 1  tie_stiffness = 1e6 }}\n\
         step spin {{ time = 0 .. 1  increments = 10 }}\n"
    );
    let (model, pilot, _) = compile("spin_3d.ctc", deck)?;
    let (trace, summary) = run(&model)?;
    let last = trace.u.last().ok_or("no increment")?;
    let axis = nalgebra::Vector3::new(1.0, 1.0, 1.0).normalize();
    let rot = nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle);
    let xc = nalgebra::Vector3::new(0.0, 0.0, zc);
    let mut worst: f64 = 0.0;
    for (n, x) in model.mesh.nodes.iter().enumerate().take(pilot) {
        let x = nalgebra::Vector3::from(*x);
        let rigid = rot * (x - xc) + xc - x;
        let u = nalgebra::Vector3::from(last[n]);
        worst = worst.max((u - rigid).norm());
    }
    let mut out = ProgramLevel {
        h: 0.1,
        values: vec![error(SPIN_ERROR, worst / outer)],
        ..ProgramLevel::default()
    };
    out.add_run(&summary);
    Ok(out)
}

const TORQUE_MOMENTUM: &str =
    "torqued body: max |L(t) - J omega0 - int m dt| / |int m dt| at the end";
const TORQUE_ENERGY: &str = "torqued body: max |K(t) - |L(t)|^2 / (2 J)| / K(t_end)";
const TORQUE_BALANCE: &str = "torqued body: energy balance max |balance| / max energy";
/// The torqued body's moment rate (`m(t) = 0.6 t (1, -2, 2) / 3`).
const TORQUE: f64 = 0.6;
const TORQUE_AXIS: [f64; 3] = [1.0, -2.0, 2.0];

/// The constant moment's checks (`torqued_body_3d`, `m = 0.6 a` from
/// `t = 0`).
const CONSTANT_MOMENTUM: &str =
    "torqued body, constant moment: max |L(t) - J omega0 - m t| / |m t| at the end";
const CONSTANT_ENERGY: &str =
    "torqued body, constant moment: max |K(t) - |L(t)|^2 / (2 J)| / K(t_end)";

/// `torqued_body_3d`: the free body with isotropic inertia `J = 1` under
/// the fixed moment `m`, spun at `TOP_OMEGA`, `20 << level` Newmark
/// increments per unit time to `TOP_END`: the ramped moment, then the
/// constant one.
fn torqued(level: usize) -> Result<ProgramLevel, String> {
    let n = (TOP_END * 50.0) as usize * (1 << level);
    let mut out = ProgramLevel {
        h: 1.0 / n as f64,
        ..ProgramLevel::default()
    };
    for constant in [false, true] {
        let (dl, dk, balance, summary) = torqued_run(n, constant)?;
        out.add_run(&summary);
        if constant {
            out.values.push(error(CONSTANT_MOMENTUM, dl));
            out.values.push(error(CONSTANT_ENERGY, dk));
        } else {
            out.values.push(error(TORQUE_MOMENTUM, dl));
            out.values.push(error(TORQUE_ENERGY, dk));
            out.values.push(error(TORQUE_BALANCE, balance));
        }
    }
    Ok(out)
}

/// One run of `torqued_body_3d` in `n` increments: `m(t) = 0.6 t a`
/// (`constant = false`) or `0.6 a` from the start; the largest errors of
/// `L` and `K` against the closed form and the energy balance.
fn torqued_run(n: usize, constant: bool) -> Result<(f64, f64, f64, RunSummary), String> {
    let moment = if constant {
        format!("{TORQUE}")
    } else {
        format!("ramp(0, {}, 0, {TOP_END})", TORQUE * TOP_END)
    };
    let deck = format!(
        "analysis {{ dimension = 3d }}\n\
         material m {{ elastic {{ E = 1e3  nu = 0.3 }}  density = 0 }}\n\
         body b {{ mesh = box {{ origin = (-0.1, -0.1, -0.1)  size = (0.2, 0.2, 0.2)  divisions = (1, 1, 1) }}  material = m  kinematics = finite }}\n\
         rigid_body b.all {{ center = (0, 0, 0)  mass = 1  inertia = 1  moment = {moment}  axis = ({}, {}, {})  tie_stiffness = 1e6 }}\n\
         step spin {{\n  time = 0 .. {TOP_END}\n  increments = {n}\n  dynamic {{ scheme = newmark }}\n  newton {{ tol = 1e-11 }}\n}}\n",
        TORQUE_AXIS[0],
        TORQUE_AXIS[1],
        TORQUE_AXIS[2]
    );
    let (mut model, pilot, spin) = compile("torqued_body.ctc", deck)?;
    rigid_velocity(&mut model, pilot, spin, [0.0; 3], TOP_OMEGA);
    let (trace, summary) = run(&model)?;
    let mass = node_masses(&model);
    let norm = dot(TORQUE_AXIS, TORQUE_AXIS).sqrt();
    let axis = TORQUE_AXIS.map(|a| a / norm);
    let j = 1.0;
    // L(t) = J omega0 + int_0^t m: TORQUE t^2 / 2 a (ramp), TORQUE t a
    let impulse = |t: f64| {
        if constant {
            TORQUE * t
        } else {
            0.5 * TORQUE * t * t
        }
    };
    let l_exact =
        |t: f64| -> [f64; 3] { std::array::from_fn(|i| j * TOP_OMEGA[i] + impulse(t) * axis[i]) };
    let t_end = *trace.time.last().ok_or("no increment")?;
    let l_end = l_exact(t_end);
    let k_end = dot(l_end, l_end) / (2.0 * j);
    let (mut dl, mut dk): (f64, f64) = (0.0, 0.0);
    for ((u, v), &t) in trace.u.iter().zip(&trace.v).zip(&trace.time) {
        if v.is_empty() {
            return Err("no velocity in the increment view".into());
        }
        let (l, k) = momentum_and_kinetic(&model, &mass, u, v);
        let le = l_exact(t);
        let d: [f64; 3] = std::array::from_fn(|i| l[i] - le[i]);
        dl = dl.max(dot(d, d).sqrt() / impulse(t_end));
        dk = dk.max((k - dot(le, le) / (2.0 * j)).abs() / k_end);
    }
    let balance = trace.balance / trace.scale.max(f64::MIN_POSITIVE);
    Ok((dl, dk, balance, summary))
}

const TOP_J1: f64 = 1.0;
const TOP_J3: f64 = 1.5;
const TOP_OMEGA: [f64; 3] = [0.4, 0.0, 1.0];
const TOP_END: f64 = 2.0;

fn top(level: usize) -> Result<ProgramLevel, String> {
    let n = 100 << level;
    let (top, summary) = spun_top(TOP_OMEGA, n)?;
    let mut out = ProgramLevel {
        h: TOP_END / n as f64,
        values: vec![
            error(MOMENTUM, top.momentum),
            value(PRECESSION, top.precession, top.precession_exact),
            error(NUTATION, top.nutation),
            error(TOP_ENERGY, top.energy),
        ],
        ..ProgramLevel::default()
    };
    out.add_run(&summary);
    Ok(out)
}

/// The top spun ten times faster (`10 omega0`, to `t = 2` at `dt = 0.005,
/// 0.0025`): the body turns about 3.4 times and its axis about 4.9 times
/// about `L`, its rotation vector passing `|psi| = pi` again and again,
/// each time carried over to the equivalent `psi (1 - 2 pi / |psi|)`
/// (`solve/rotation_chart.rs`; without it the run stopped at the singular
/// `|psi| = 2 pi`).
fn top_turns(level: usize) -> Result<ProgramLevel, String> {
    let n = 400 << level;
    let (top, summary) = spun_top(TOP_OMEGA.map(|w| 10.0 * w), n)?;
    let mut out = ProgramLevel {
        h: TOP_END / n as f64,
        values: vec![
            error(TURNS_MOMENTUM, top.momentum),
            value(TURNS_PRECESSION, top.precession, top.precession_exact),
            error(TURNS_NUTATION, top.nutation),
            error(TURNS_ENERGY, top.energy),
            value(TURNS_ANGLE, top.turns, top.turns_exact),
        ],
        ..ProgramLevel::default()
    };
    out.add_run(&summary);
    Ok(out)
}

/// The measures of a free top's run.
struct Top {
    /// Max `|L(t) - L(0)| / |L(0)|`.
    momentum: f64,
    /// The axis' precession angle about `L` at the end (unwrapped).
    precession: f64,
    /// `|L| t / J1`.
    precession_exact: f64,
    /// Max change of the angle between the axis and `L`.
    nutation: f64,
    /// Max `|K(t) - K0| / K0`.
    energy: f64,
    /// The body's total rotation in turns: the sum of the increments'
    /// rotation angles (each the angle of `R_n^T R_{n+1}`).
    turns: f64,
    /// The same for the closed-form motion sampled at the increments'
    /// times (`R(t) = exp(t [L / J1]x) exp(t [w3 (J1 - J3) / J1 e3]x)`).
    turns_exact: f64,
}

/// The torque-free symmetric top (`J = diag(TOP_J1, TOP_J1, TOP_J3)`)
/// spun at `omega` from its reference orientation to `TOP_END` in `n`
/// Newmark increments.
fn spun_top(omega: [f64; 3], n: usize) -> Result<(Top, RunSummary), String> {
    let deck = format!(
        "analysis {{ dimension = 3d }}\n\
         material m {{ elastic {{ E = 1e3  nu = 0.3 }}  density = 0 }}\n\
         body top {{ mesh = box {{ origin = (-0.1, -0.1, -0.1)  size = (0.2, 0.2, 0.2)  divisions = (1, 1, 1) }}  material = m  kinematics = finite }}\n\
         rigid_body top.all {{ center = (0, 0, 0)  mass = 1  inertia_diagonal = ({TOP_J1}, {TOP_J1}, {TOP_J3})  tie_stiffness = 1e6 }}\n\
         step spin {{\n  time = 0 .. {TOP_END}\n  increments = {n}\n  dynamic {{ scheme = newmark }}\n  newton {{ tol = 1e-11 }}\n}}\n"
    );
    let (mut model, pilot, spin) = compile("free_top.ctc", deck)?;
    rigid_velocity(&mut model, pilot, spin, [0.0; 3], omega);
    let (trace, summary) = run(&model)?;
    let mass = node_masses(&model);
    // the closed form's momentum J omega0 (the body starts unrotated)
    let l0 = [TOP_J1 * omega[0], TOP_J1 * omega[1], TOP_J3 * omega[2]];
    let l0n = dot(l0, l0).sqrt();
    let lhat = l0.map(|x| x / l0n);
    let k0 = 0.5 * dot(omega, l0);
    let (mut dl, mut dk): (f64, f64) = (0.0, 0.0);
    for (u, v) in trace.u.iter().zip(&trace.v) {
        if v.is_empty() {
            return Err("no velocity in the increment view".into());
        }
        let (l, k) = momentum_and_kinetic(&model, &mass, u, v);
        let d = [l[0] - l0[0], l[1] - l0[1], l[2] - l0[2]];
        dl = dl.max(dot(d, d).sqrt() / l0n);
        dk = dk.max((k - k0).abs() / k0);
    }
    // the symmetry axis e3 = R(psi) e_z: its angle to L and its azimuth
    // about L (unwrapped)
    let p = {
        let e = [0.0, 0.0, 1.0];
        let c = dot(e, lhat);
        let x = [e[0] - c * lhat[0], e[1] - c * lhat[1], e[2] - c * lhat[2]];
        let nx = dot(x, x).sqrt();
        x.map(|y| y / nx)
    };
    let q = cross(lhat, p);
    let cone0 = lhat[2].acos();
    let (mut phi, mut last, mut cone) = (0.0_f64, 0.0_f64, 0.0_f64);
    for u in &trace.u {
        let psi = nalgebra::Vector3::from(u[spin]);
        let e3 = nalgebra::Rotation3::from_scaled_axis(psi) * nalgebra::Vector3::z();
        let e3 = [e3[0], e3[1], e3[2]];
        cone = cone.max((dot(e3, lhat).clamp(-1.0, 1.0).acos() - cone0).abs());
        let az = dot(e3, q).atan2(dot(e3, p));
        let mut step = az - last;
        while step > std::f64::consts::PI {
            step -= std::f64::consts::TAU;
        }
        while step < -std::f64::consts::PI {
            step += std::f64::consts::TAU;
        }
        phi += step;
        last = az;
    }
    let t_end = *trace.time.last().ok_or("no increment")?;
    // the total rotation, run and closed form: in the body frame the
    // angular velocity turns about e3 at w3 (J1 - J3) / J1, so R(t) =
    // exp(t [L / J1]x) exp(t [w3 (J1 - J3) / J1 e3]x)
    use nalgebra::{Rotation3, Vector3};
    let body_rate = Vector3::z() * (omega[2] * (TOP_J1 - TOP_J3) / TOP_J1);
    let exact = |t: f64| {
        Rotation3::from_scaled_axis(Vector3::from(l0) * (t / TOP_J1))
            * Rotation3::from_scaled_axis(body_rate * t)
    };
    let (mut turns, mut turns_exact) = (0.0, 0.0);
    let (mut r_last, mut e_last) = (Rotation3::identity(), Rotation3::identity());
    for (u, &t) in trace.u.iter().zip(&trace.time) {
        let r = Rotation3::from_scaled_axis(Vector3::from(u[spin]));
        let e = exact(t);
        turns += (r_last.inverse() * r).angle();
        turns_exact += (e_last.inverse() * e).angle();
        (r_last, e_last) = (r, e);
    }
    let top = Top {
        momentum: dl,
        precession: phi,
        precession_exact: l0n / TOP_J1 * t_end,
        nutation: cone,
        energy: dk,
        turns: turns / std::f64::consts::TAU,
        turns_exact: turns_exact / std::f64::consts::TAU,
    };
    Ok((top, summary))
}

/// The registry entries.
pub fn cases() -> Vec<VerifyCase> {
    vec![
        VerifyCase {
            name: "rigid_body_bearing_frequency_3d",
            title: "A hex8 cube made rigid (rigid_body cube.all, 6 dofs, mass M and isotropic inertia by six inertia points) on an isotropic bearing spring k, given v0 along (0.48, 0.6, 0.64): period vs 2 pi sqrt(m_total / k), Newmark at dt = T/20, T/40; the centre stays on its line; energy balance; the ties' gap",
            source: "Thomson & Dahleh, Theory of Vibration with Applications (5th ed. 1998), section 2.1",
            tags: &["dynamics", "rigid_body", "3d"],
            levels: 2,
            checks: vec![
                Check::new(Quantity::Named(PERIOD), &[1e-2, 3e-3]),
                Check::new(Quantity::Named(BALANCE), &[1e-8]),
                Check::new(Quantity::Named(OFF_LINE), &[1e-10]),
                Check::new(Quantity::Named(TIE_GAP), &[1e-4]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 2,
                run: bearing,
            }),
        },
        VerifyCase {
            name: "jeffcott_rotor_whirl_3d",
            title: "Jeffcott rotor in 3d: a rigid hex8 cube with an eccentric point mass spun about z up to omega = 0.5 and 2 omega_n on an isotropic damped bearing (zeta = 0.2), Newmark at dt = T_n/40, T_n/80: steady whirl radius vs e r^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2), the axial motion of the centre, energy balance",
            source: "Genta, Dynamics of Rotating Systems (2005), section 4.2 (the Jeffcott rotor); Den Hartog, Mechanical Vibrations (1956), section 7.4",
            tags: &["dynamics", "rigid_body", "3d"],
            // level 1 (13 s debug) by `--max-level 1`
            levels: 1,
            checks: vec![
                Check::new(Quantity::Named(WHIRL_SUB), &[1e-2, 5e-3]),
                Check::new(Quantity::Named(WHIRL_SUPER), &[1e-2, 5e-3]),
                Check::new(Quantity::Named(WHIRL_Z), &[1e-3]),
                Check::new(Quantity::Named(WHIRL_BALANCE), &[1e-6]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 2,
                run: whirl,
            }),
        },
        VerifyCase {
            name: "rigid_hub_spins_a_disc_3d",
            title: "A finite-strain hex8 ring whose inner face is a rigid hub (rigid_body disc.inner, 6 dofs) turned by 3 rad about the skew axis (1, 1, 1) in 10 quasi-static increments: every node follows the rigid rotation",
            source: "objectivity of the finite-strain kinematics (Belytschko, Liu & Moran, Nonlinear Finite Elements, 2000, section 3.7): a rigid rotation leaves no strain",
            tags: &["rigid_body", "finite_strain", "3d"],
            levels: 1,
            checks: vec![Check::new(Quantity::Named(SPIN_ERROR), &[1e-8])],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: spin,
            }),
        },
        VerifyCase {
            name: "free_symmetric_top_3d",
            title: "A torque-free symmetric rigid body (J = diag(1, 1, 1.5), six inertia points, total rotation vector) spun at omega0 = (0.4, 0, 1): angular momentum conserved, the symmetry axis precessing about L at |L| / J1 on a cone of constant angle, energy; Newmark at dt = 0.02, 0.01 to t = 2",
            source: "Goldstein, Poole & Safko, Classical Mechanics (3rd ed. 2002), section 5.6 (the force-free symmetric top); Landau & Lifshitz, Mechanics (1976), section 33",
            tags: &["dynamics", "rigid_body", "3d"],
            levels: 2,
            checks: vec![
                Check::new(Quantity::Named(MOMENTUM), &[1e-3, 3e-4]),
                Check::new(Quantity::Named(PRECESSION), &[1e-3, 3e-4]),
                Check::new(Quantity::Named(NUTATION), &[1e-6]),
                Check::new(Quantity::Named(TOP_ENERGY), &[1e-3, 3e-4]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 2,
                run: top,
            }),
        },
        VerifyCase {
            name: "free_top_several_turns_3d",
            title: "The torque-free symmetric top spun ten times faster (omega0 = (4, 0, 10)) to t = 2: the body turns about 3.4 times, its total rotation vector carried over to psi (1 - 2 pi / |psi|) each time |psi| passes pi; angular momentum, precession, nutation, energy and the body's turns vs the closed form; Newmark at dt = 0.005, 0.0025",
            source: "Goldstein, Poole & Safko, Classical Mechanics (3rd ed. 2002), section 5.6 (the force-free symmetric top); Cardona & Geradin, Flexible Multibody Dynamics (2001), section 4.7 (the complement rotation vector)",
            tags: &["dynamics", "rigid_body", "3d"],
            levels: 1,
            checks: vec![
                Check::new(Quantity::Named(TURNS_MOMENTUM), &[1e-2, 3e-3]),
                Check::new(Quantity::Named(TURNS_PRECESSION), &[1e-2, 3e-3]),
                // the ties' penalty floor (|f| / k with 100 times the
                // centripetal load of `free_symmetric_top_3d`'s 3.9e-8):
                // 4.1e-6 at both levels
                Check::new(Quantity::Named(TURNS_NUTATION), &[1e-5, 1e-5]),
                Check::new(Quantity::Named(TURNS_ENERGY), &[1e-2, 3e-3]),
                Check::new(Quantity::Named(TURNS_ANGLE), &[1e-2, 3e-3]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 2,
                run: top_turns,
            }),
        },
        VerifyCase {
            name: "torqued_body_3d",
            title: "A free rigid body with isotropic inertia (J = 1) spun at omega0 = (0.4, 0, 1) and driven by a moment m(t) = 0.6 t (1, -2, 2) / 3 fixed in space, applied work-conjugately on its total rotation vector (T(psi)^T m): L(t) = J omega0 + int m dt and K = |L|^2 / (2 J) at finite rotation; Newmark at dt = 0.02, 0.01 to t = 2",
            source: "Euler's equations of a rigid body with isotropic inertia, J omega' = m (Goldstein, Poole & Safko, Classical Mechanics (3rd ed. 2002), section 5.5); the work-conjugate moment on the rotation vector: Cardona & Geradin, Flexible Multibody Dynamics (2001), section 4.6",
            tags: &["dynamics", "rigid_body", "3d"],
            levels: 2,
            checks: vec![
                Check::new(Quantity::Named(TORQUE_MOMENTUM), &[1e-3, 3e-4]),
                Check::new(Quantity::Named(TORQUE_ENERGY), &[1e-3, 3e-4]),
                // measured 5.6e-13 / 8.6e-12: the moment's work is in the
                // audit's external work (it is assembled with the follower
                // loads)
                Check::new(Quantity::Named(TORQUE_BALANCE), &[1e-10]),
                // the constant moment from t = 0 (the start solves the
                // spin node's condensation): measured L 8.5e-4 / 2.4e-4, K
                // 9.6e-4 / 2.7e-4; 5.8e-3 / 2.7e-3 and 6.2e-3 / 2.9e-3
                // without it
                Check::new(Quantity::Named(CONSTANT_MOMENTUM), &[1e-3, 3e-4]),
                Check::new(Quantity::Named(CONSTANT_ENERGY), &[1e-3, 3e-4]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 2,
                run: torqued,
            }),
        },
    ]
}
