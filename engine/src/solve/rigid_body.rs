//! Rigid bodies with mass and rotary inertia (issue 19; `model::Discrete::
//! Rigid`): a set of nodes moving as one rigid body, driven by a
//! prescribed rotation or free, on spring bearings; planar (3 dofs) and
//! 3D (6 dofs).
//!
//! The body's motion is carried by two nodes appended at its centre
//! `X_c` and attached to no cell ([`make_rigid`]), so the dof map, the
//! Newton state, line search, cutbacks, commits and restart points carry
//! it like any displacement (the scheme of `free_tool.rs`, Abaqus'
//! reference node): the **pilot** node's displacement is the translation
//! `u_c`, the **spin** node's displacement the rotation: planar, its x
//! the angle `theta` (its y held); 3D, its three components the **total
//! rotation vector** `psi` (`R = exp([psi]x)`, `rotation_vector.rs`). The
//! body's mass is a point mass on the pilot; the bearings ground springs
//! and dashpots on the pilot; a prescribed rotation a `Dirichlet` on the
//! spin node (3D: `theta(t) a` on its three components, `a` the unit
//! axis), a planar applied moment a nodal force on it. `history.csv` gets
//! the columns `centre[NAME]_x`, `_y` (`_z`) (the orbit) and
//! `rotation[NAME]_x` (the angle; `_y` the held 0), 3D `_x _y _z` the
//! rotation vector.
//!
//! Rotary inertia: planar, `J` is a point mass on the spin node (its x
//! component is `theta`: kinetic energy `J theta'^2 / 2`, in the dynamics
//! and the energy audit like any point mass). 3D, the mass and the
//! inertia tensor are carried by six point masses at body-fixed points
//! tied to the body like its nodes (`inertia_points.rs`, the equimomental
//! system): their translational time integration is the rotational
//! dynamics of the body (gyroscopic coupling included; no Euler equation
//! is written, the spin node carries no mass).
//!
//! Why the total rotation vector: the engine's state is the total
//! displacement with additive updates (Newton, line search, cutback,
//! restart all add to or scale `u`), which an additive parameterization
//! fits as it is; an incremental rotation composed multiplicatively would
//! need a committed rotation outside `u`. Its limit: the differential of
//! `exp` is singular at `|psi| = 2 pi k` (`k >= 1`); a **free** 3D body
//! whose `|psi|` ends a converged increment past `pi` is carried over to
//! the equivalent `psi (1 - 2 pi / |psi|)` with its rates and forces
//! (`rotation_chart.rs`, from `Newton::commit`), so it turns any number
//! of times as long as one increment turns it by less than `pi` (a
//! prescribed rotation about an axis has its three components
//! prescribed: any angle, never re-charted).
//!
//! Each node `a` of the body is tied to its place on the rigid body at
//! finite rotation, `p_a = X_c + u_c + R r_a` (`r_a = X_a - X_c`), by a
//! stiff spring `k` (a penalty: the energy `k/2 |d_a|^2`, `d_a = x_a - p_a
//! = u_a - u_c + r_a - R r_a`, part of the internal work). Planar, with
//! `R' = J R` (`J` the rotation by +90 degrees) and `R'' = -R`:
//!
//! - forces: `f_a = k d_a`, `f_c = -k d_a`, `f_theta = -k d_a . (J R r_a)`
//!   (the moment of the ties about the current centre);
//! - tangent (symmetric, exact): `K_aa = K_cc = k I`, `K_ac = -k I`,
//!   `K_a theta = -k J R r_a`, `K_c theta = k J R r_a`, `K_theta theta =
//!   k |r_a|^2 + k d_a . (R r_a)` (the last term the rotation's second
//!   derivative); FD-checked below.
//!
//! 3D, with `G = d(R r_a)/d psi` and `H` its derivative
//! (`rotation_vector::rotate`): `f_psi = -k G^T d_a`, `K_a psi = -k G`,
//! `K_c psi = k G`, `K_psi psi = k G^T G - k sum_l d_l H_l`.
//!
//! A body moving rigidly leaves `d_a = 0` at any angle: the rigid motion
//! is exact at large rotation; under load the ties stretch by `|f| / k`
//! (the penalty's error, reported by [`max_tie_gap`]).

use super::dofs::{Dof, DofMap};
use super::linalg::Scatter;
use super::rotation_vector::rotate;
use crate::model::{AnalysisKind, Dirichlet, Discrete, HistoryRequest, Load, Model, TimeFunction};

/// What [`make_rigid`] needs.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidSpec {
    /// Label (the deck's `rigid_body` item).
    pub label: String,
    /// The nodes moving with the body.
    pub nodes: Vec<usize>,
    /// The centre `X_c` (reference position of the pilot; planar: `z`
    /// unused).
    pub centre: [f64; 3],
    /// Mass of the body (`0`: none besides its nodes').
    pub mass: f64,
    /// Rotary inertia tensor about the centre (`0`: none); planar: only
    /// `inertia[2][2]`, the inertia about the normal to the plane.
    pub inertia: [[f64; 3]; 3],
    /// The axis of a prescribed 3D rotation, or the direction of a free
    /// 3D body's moment (fixed in space; planar: unused).
    pub axis: [f64; 3],
    /// The prescribed rotation `theta(t)` (radians, counter-clockwise
    /// about the axis); `None`: free, under `moment`.
    pub rotation: Option<TimeFunction>,
    /// The applied moment of a free rotation (3D: its magnitude along
    /// `axis`, a [`Load::RigidMoment`]).
    pub moment: TimeFunction,
    /// Bearing: a spring from the pilot to the ground (every direction).
    pub bearing_stiffness: f64,
    /// Bearing: a dashpot from the pilot to the ground.
    pub bearing_damping: f64,
    /// The tie stiffness per node (penalty).
    pub stiffness: f64,
}

/// Points per linear segment of [`angle_of`].
pub const SAMPLES: usize = 64;

/// The rotation `theta(t) = int_{t0}^{t} omega` of a prescribed angular
/// velocity over the analysis `window = (t0, t1)` (`theta(t0) = 0`): a
/// table through [`SAMPLES`] points per linear piece of `omega` (its
/// breakpoints kept), exact at the points (the trapezoidal rule is exact
/// on a linear piece); constant `omega` gives an exact ramp.
pub fn angle_of(omega: &TimeFunction, window: (f64, f64)) -> TimeFunction {
    let (t0, t1) = window;
    if let TimeFunction::Constant(w) = omega {
        return TimeFunction::Ramp {
            t0,
            t1,
            v0: 0.0,
            v1: w * (t1 - t0),
        };
    }
    let mut breaks = vec![t0, t1];
    match omega {
        TimeFunction::Ramp { t0: a, t1: b, .. } => breaks.extend([*a, *b]),
        TimeFunction::Table(points) => breaks.extend(points.iter().map(|p| p.0)),
        TimeFunction::Constant(_) => {}
    }
    breaks.retain(|t| t.is_finite() && *t >= t0 && *t <= t1);
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let mut points = vec![(t0, 0.0)];
    let mut theta = 0.0;
    for w in breaks.windows(2) {
        let (a, b) = (w[0], w[1]);
        for i in 1..=SAMPLES {
            let (s0, s1) = (
                a + (b - a) * (i - 1) as f64 / SAMPLES as f64,
                a + (b - a) * i as f64 / SAMPLES as f64,
            );
            theta += 0.5 * (omega.eval(s0) + omega.eval(s1)) * (s1 - s0);
            points.push((s1, theta));
        }
    }
    if points.len() < 2 {
        return TimeFunction::Constant(0.0);
    }
    TimeFunction::Table(points)
}

/// The nodes `(pilot, spin)` of the rigid bodies of `model`.
pub fn bodies<const D: usize>(model: &Model<D>) -> impl Iterator<Item = (usize, usize)> + '_ {
    model.discrete.iter().filter_map(|d| match d {
        Discrete::Rigid { pilot, spin, .. } => Some((*pilot, *spin)),
        _ => None,
    })
}

/// The pilot and spin nodes of every rigid body and the nodes tied to it
/// (active dofs although attached to no cell: the pilot, the spin node,
/// the inertia points of a 3D body).
pub fn pilot_nodes<const D: usize>(model: &Model<D>) -> impl Iterator<Item = usize> + '_ {
    model.discrete.iter().flat_map(|d| match d {
        Discrete::Rigid {
            nodes, pilot, spin, ..
        } => [*pilot, *spin]
            .into_iter()
            .chain(nodes.iter().copied())
            .collect::<Vec<_>>(),
        _ => Vec::new(),
    })
}

/// Node couplings of one rigid body for the sparsity pattern: every node
/// with the pilot and the spin node, and the two together.
pub fn couplings(nodes: &[usize], pilot: usize, spin: usize) -> Vec<(usize, usize)> {
    let pair = |a: usize, b: usize| (a.min(b), a.max(b));
    let mut out = vec![pair(pilot, spin)];
    for &a in nodes {
        out.push(pair(a, pilot));
        out.push(pair(a, spin));
    }
    out
}

/// `s f(t)`.
fn scaled(f: &TimeFunction, s: f64) -> TimeFunction {
    match f {
        TimeFunction::Constant(v) => TimeFunction::Constant(s * v),
        TimeFunction::Ramp { t0, t1, v0, v1 } => TimeFunction::Ramp {
            t0: *t0,
            t1: *t1,
            v0: s * v0,
            v1: s * v1,
        },
        TimeFunction::Table(p) => TimeFunction::Table(p.iter().map(|&(t, v)| (t, s * v)).collect()),
    }
}

/// Makes the nodes of `spec` one rigid body: appends the pilot and spin
/// nodes at the centre; planar: holds the spin node's y, prescribes its x
/// (rotation) or loads it (moment), puts the mass and inertia on them as
/// point masses; 3D: prescribes the rotation vector `theta(t) axis` or
/// leaves it free, and carries the mass and inertia tensor by six tied
/// point masses ([`super::inertia_points`]; the mass alone on the pilot);
/// the bearing on the pilot as a ground spring and dashpot. Returns
/// `(pilot, spin)`. Refused in axisymmetric models.
pub fn make_rigid<const D: usize>(
    model: &mut Model<D>,
    spec: RigidSpec,
) -> Result<(usize, usize), String> {
    if model.analysis.kind == AnalysisKind::Axisymmetric || !(D == 2 || D == 3) {
        return Err(
            "a rigid body needs a plane strain, plane stress or 3d analysis: in an axisymmetric \
             model a cross-section does not turn as a rigid body"
                .into(),
        );
    }
    let nn = model.mesh.nodes.len();
    if spec.nodes.is_empty() {
        return Err(format!("{}: a rigid body needs nodes", spec.label));
    }
    if let Some(n) = spec.nodes.iter().find(|&&n| n >= nn) {
        return Err(format!(
            "{}: node {n} is not in the mesh ({nn} nodes)",
            spec.label
        ));
    }
    if !(spec.stiffness.is_finite() && spec.stiffness > 0.0) {
        return Err(format!(
            "{}: the tie stiffness must be finite and > 0 (got {})",
            spec.label, spec.stiffness
        ));
    }
    let label = spec.label;
    let mut nodes = spec.nodes;
    // 3D: the mass and inertia as tied point masses (checked before the
    // model changes)
    let points = if D == 3 {
        super::inertia_points::inertia_points(spec.mass, spec.inertia)
            .map_err(|e| format!("{label}: {e}"))?
    } else {
        Vec::new()
    };
    let moment_3d = D == 3 && spec.rotation.is_none() && spec.moment != TimeFunction::Constant(0.0);
    if D == 3 {
        if spec.rotation.is_some() && spec.moment != TimeFunction::Constant(0.0) {
            return Err(format!(
                "{label}: a moment on a rigid body whose rotation is prescribed (give one of \
                 them)"
            ));
        }
        let n = spec.axis.iter().map(|x| x * x).sum::<f64>().sqrt();
        if (spec.rotation.is_some() || moment_3d) && !(n.is_finite() && n > 0.0) {
            return Err(format!("{label}: the rotation axis is zero"));
        }
    }
    let centre: [f64; D] = std::array::from_fn(|i| spec.centre[i]);
    let pilot = nn;
    let spin = nn + 1;
    model.mesh.nodes.push(centre);
    model.mesh.nodes.push(centre);
    if D == 2 {
        model.constraints.push(Dirichlet {
            label: format!("{label}: spin node (y held)"),
            nodes: vec![spin],
            component: 1,
            value: TimeFunction::Constant(0.0),
        });
        match spec.rotation {
            Some(theta) => model.constraints.push(Dirichlet {
                label: format!("{label}: rotation"),
                nodes: vec![spin],
                component: 0,
                value: theta,
            }),
            None => model.loads.push(Load::NodalForce {
                label: format!("{label}: moment"),
                nodes: vec![spin],
                component: 0,
                value: spec.moment,
            }),
        }
        if spec.mass > 0.0 {
            model.discrete.push(Discrete::Mass {
                label: format!("{label}: mass"),
                nodes: vec![pilot],
                mass: spec.mass,
            });
        }
        if spec.inertia[2][2] > 0.0 {
            model.discrete.push(Discrete::Mass {
                label: format!("{label}: rotary inertia"),
                nodes: vec![spin],
                mass: spec.inertia[2][2],
            });
        }
    } else {
        if moment_3d {
            let n = spec.axis.iter().map(|x| x * x).sum::<f64>().sqrt();
            model.loads.push(Load::RigidMoment {
                label: format!("{label}: moment"),
                spin,
                axis: spec.axis.map(|a| a / n),
                value: spec.moment.clone(),
            });
        }
        if let Some(theta) = &spec.rotation {
            let n = spec.axis.iter().map(|x| x * x).sum::<f64>().sqrt();
            for c in 0..3 {
                model.constraints.push(Dirichlet {
                    label: format!("{label}: rotation"),
                    nodes: vec![spin],
                    component: c,
                    value: scaled(theta, spec.axis[c] / n),
                });
            }
        }
        if points.is_empty() {
            if spec.mass > 0.0 {
                model.discrete.push(Discrete::Mass {
                    label: format!("{label}: mass"),
                    nodes: vec![pilot],
                    mass: spec.mass,
                });
            }
        } else {
            for (k, (offset, mu)) in points.iter().enumerate() {
                let n = model.mesh.nodes.len();
                model
                    .mesh
                    .nodes
                    .push(std::array::from_fn(|i| centre[i] + offset[i]));
                nodes.push(n);
                model.discrete.push(Discrete::Mass {
                    label: format!("{label}: mass and inertia (point {k})"),
                    nodes: vec![n],
                    mass: *mu,
                });
            }
        }
    }
    if spec.bearing_stiffness > 0.0 || spec.bearing_damping > 0.0 {
        model.discrete.push(Discrete::Ground {
            label: format!("{label}: bearing"),
            nodes: vec![pilot],
            stiffness: spec.bearing_stiffness,
            damping: spec.bearing_damping,
        });
    }
    // history.csv: the centre's displacement (the shaft's orbit) and the
    // rotation (`rotation[..]_x`; planar: its `_y` is the held 0)
    let name = label.strip_prefix("rigid_body ").unwrap_or(&label);
    model.output.history.push(HistoryRequest::Displacement {
        label: format!("centre[{name}]"),
        nodes: vec![pilot],
    });
    model.output.history.push(HistoryRequest::Displacement {
        label: format!("rotation[{name}]"),
        nodes: vec![spin],
    });
    model.discrete.push(Discrete::Rigid {
        label,
        nodes,
        pilot,
        spin,
        stiffness: spec.stiffness,
    });
    Ok((pilot, spin))
}

/// Why the rigid bodies of `model` cannot be solved, if they cannot: not
/// planar, a pilot or spin node out of range or attached to a cell, a
/// body node that is its own pilot, a tie stiffness not positive.
pub fn refusals<const D: usize>(model: &Model<D>) -> Vec<String> {
    let mut out = Vec::new();
    let nn = model.mesh.nodes.len();
    for d in &model.discrete {
        let Discrete::Rigid {
            label,
            nodes,
            pilot,
            spin,
            stiffness,
        } = d
        else {
            continue;
        };
        if !(D == 2 || D == 3) || model.analysis.kind == AnalysisKind::Axisymmetric {
            out.push(format!(
                "{label}: a rigid body needs a plane strain, plane stress or 3d analysis"
            ));
        }
        for n in [*pilot, *spin] {
            if n >= nn || model.mesh.cells.iter().any(|c| c.nodes.contains(&n)) {
                out.push(format!("{label}: node {n} is not a free node of the mesh"));
            }
        }
        if let Some(n) = nodes
            .iter()
            .find(|&&n| n >= nn || n == *pilot || n == *spin)
        {
            out.push(format!("{label}: node {n} cannot move with the body"));
        }
        if !(stiffness.is_finite() && *stiffness > 0.0) {
            out.push(format!(
                "{label}: the tie stiffness must be finite and > 0 (got {stiffness})"
            ));
        }
    }
    out
}

/// One tie: the arm `r`, `R r`, `J R r` and the gap `d` of node `a` (2D).
struct Tie {
    r: [f64; 2],
    rr: [f64; 2],
    jrr: [f64; 2],
    d: [f64; 2],
}

fn tie<const D: usize>(model: &Model<D>, u: &[f64], a: usize, pilot: usize, spin: usize) -> Tie {
    let (xa, xc) = (&model.mesh.nodes[a], &model.mesh.nodes[pilot]);
    let r = [xa[0] - xc[0], xa[1] - xc[1]];
    let (s, c) = u[spin * D].sin_cos();
    let rr = [c * r[0] - s * r[1], s * r[0] + c * r[1]];
    let jrr = [-rr[1], rr[0]];
    let d = [
        u[a * D] - u[pilot * D] + r[0] - rr[0],
        u[a * D + 1] - u[pilot * D + 1] + r[1] - rr[1],
    ];
    Tie { r, rr, jrr, d }
}

/// One 3D tie: the gap `d` of node `a` and the derivatives `g`, `h` of
/// `R(psi) r_a` in the rotation vector `psi`.
struct Tie3 {
    d: [f64; 3],
    g: [[f64; 3]; 3],
    h: [[[f64; 3]; 3]; 3],
}

fn tie3<const D: usize>(model: &Model<D>, u: &[f64], a: usize, pilot: usize, spin: usize) -> Tie3 {
    let (xa, xc) = (&model.mesh.nodes[a], &model.mesh.nodes[pilot]);
    let r: [f64; 3] = std::array::from_fn(|i| xa[i] - xc[i]);
    let psi: [f64; 3] = std::array::from_fn(|i| u[spin * D + i]);
    let x = rotate(psi, r);
    let d = std::array::from_fn(|i| u[a * D + i] - u[pilot * D + i] + r[i] - x.p[i]);
    Tie3 { d, g: x.g, h: x.h }
}

/// The rigid bodies of `model`: `(nodes, pilot, spin, k)`.
fn rigid<const D: usize>(model: &Model<D>) -> impl Iterator<Item = (&[usize], usize, usize, f64)> {
    model.discrete.iter().filter_map(|d| match d {
        Discrete::Rigid {
            nodes,
            pilot,
            spin,
            stiffness,
            ..
        } => Some((nodes.as_slice(), *pilot, *spin, *stiffness)),
        _ => None,
    })
}

/// The 3D tie forces: `f_a = k d`, `f_c = -k d`, `f_psi = -k G^T d`.
fn add_forces_3d<const D: usize>(model: &Model<D>, u: &[f64], f: &mut [f64]) {
    for (nodes, pilot, spin, k) in rigid(model) {
        for &a in nodes {
            let t = tie3(model, u, a, pilot, spin);
            for c in 0..3 {
                f[a * D + c] += k * t.d[c];
                f[pilot * D + c] -= k * t.d[c];
            }
            for j in 0..3 {
                f[spin * D + j] -= k * (0..3).map(|l| t.d[l] * t.g[l][j]).sum::<f64>();
            }
        }
    }
}

/// The exact tangent of [`add_forces_3d`]: `K_aa = K_cc = k I`, `K_ac =
/// -k I`, `K_a psi = -k G`, `K_c psi = k G`, `K_psi psi = k G^T G - k
/// sum_l d_l H_l`.
fn add_tangent_3d<const D: usize>(
    model: &Model<D>,
    u: &[f64],
    add: &mut impl FnMut(usize, usize, f64),
) {
    for (nodes, pilot, spin, k) in rigid(model) {
        for &a in nodes {
            let t = tie3(model, u, a, pilot, spin);
            for c in 0..3 {
                let (ra, rc) = (a * D + c, pilot * D + c);
                add(ra, ra, k);
                add(rc, rc, k);
                add(ra, rc, -k);
                add(rc, ra, -k);
                for j in 0..3 {
                    let th = spin * D + j;
                    add(ra, th, -k * t.g[c][j]);
                    add(th, ra, -k * t.g[c][j]);
                    add(rc, th, k * t.g[c][j]);
                    add(th, rc, k * t.g[c][j]);
                }
            }
            for i in 0..3 {
                for j in 0..3 {
                    let x: f64 = (0..3)
                        .map(|l| t.g[l][i] * t.g[l][j] - t.d[l] * t.h[l][i][j])
                        .sum();
                    add(spin * D + i, spin * D + j, k * x);
                }
            }
        }
    }
}

/// `f += ` the tie forces of every rigid body at the displacements `u`
/// (per dof `node D + c`).
pub fn add_forces<const D: usize>(model: &Model<D>, u: &[f64], f: &mut [f64]) {
    if D == 3 {
        return add_forces_3d(model, u, f);
    }
    if D != 2 {
        return;
    }
    for d in &model.discrete {
        let Discrete::Rigid {
            nodes,
            pilot,
            spin,
            stiffness: k,
            ..
        } = d
        else {
            continue;
        };
        for &a in nodes {
            let t = tie(model, u, a, *pilot, *spin);
            for c in 0..2 {
                f[a * D + c] += k * t.d[c];
                f[pilot * D + c] -= k * t.d[c];
            }
            f[spin * D] -= k * (t.d[0] * t.jrr[0] + t.d[1] * t.jrr[1]);
        }
    }
}

/// Adds the exact tangent of [`add_forces`] at `u` to the free-free
/// tangent `values`.
pub fn add_tangent<const D: usize>(
    model: &Model<D>,
    u: &[f64],
    dofs: &DofMap<D>,
    scatter: &Scatter,
    values: &mut [f64],
) {
    let mut add = |r: usize, c: usize, x: f64| {
        if let (Some(Dof::Free(i)), Some(Dof::Free(j))) = (dofs.dofs.get(r), dofs.dofs.get(c)) {
            if let Some(s) = scatter.pattern.find(*i, *j) {
                values[s] += x;
            }
        }
    };
    if D == 3 {
        return add_tangent_3d(model, u, &mut add);
    }
    if D != 2 {
        return;
    }
    for d in &model.discrete {
        let Discrete::Rigid {
            nodes,
            pilot,
            spin,
            stiffness: k,
            ..
        } = d
        else {
            continue;
        };
        let th = spin * D;
        for &a in nodes {
            let t = tie(model, u, a, *pilot, *spin);
            for c in 0..2 {
                let (ra, rc) = (a * D + c, pilot * D + c);
                add(ra, ra, *k);
                add(rc, rc, *k);
                add(ra, rc, -k);
                add(rc, ra, -k);
                add(ra, th, -k * t.jrr[c]);
                add(th, ra, -k * t.jrr[c]);
                add(rc, th, k * t.jrr[c]);
                add(th, rc, k * t.jrr[c]);
            }
            let r2 = t.r[0] * t.r[0] + t.r[1] * t.r[1];
            add(th, th, k * r2 + k * (t.d[0] * t.rr[0] + t.d[1] * t.rr[1]));
        }
    }
}

/// Whether `model` has a moment on a 3D rigid body ([`Load::RigidMoment`]).
pub fn has_moments<const D: usize>(model: &Model<D>) -> bool {
    model
        .loads
        .iter()
        .any(|l| matches!(l, Load::RigidMoment { .. }))
}

/// Adds to `f` (`D` per node) the generalized forces of the 3D rigid
/// bodies' moments at time `t` and displacements `u` (`f_psi = T(psi)^T
/// m` on the spin node, [`super::rotation_vector::moment_force`]) and,
/// with `tangent`, subtracts their derivative from the free-free entries
/// of the tangent (the residual is `f_int - f_ext - f_follow - ..`: the
/// load stiffness `-d f / d psi`, not symmetric).
pub fn add_moments<const D: usize>(
    model: &Model<D>,
    t: f64,
    u: &[[f64; D]],
    f: &mut [f64],
    mut tangent: Option<(&Scatter, &DofMap<D>, &mut [f64])>,
) {
    if D != 3 {
        return;
    }
    for load in &model.loads {
        let Load::RigidMoment {
            spin, axis, value, ..
        } = load
        else {
            continue;
        };
        let v = value.eval(t);
        let Some(us) = u.get(*spin) else { continue };
        let m = axis.map(|a| a * v);
        let psi = [us[0], us[1], us[2]];
        let (force, df) = super::rotation_vector::moment_force(psi, m);
        for (i, fi) in force.iter().enumerate() {
            f[spin * D + i] += fi;
        }
        if let Some((scatter, dofs, values)) = tangent.as_mut() {
            for (i, row) in df.iter().enumerate() {
                for (j, dij) in row.iter().enumerate() {
                    let (r, c) = (spin * D + i, spin * D + j);
                    if let (Some(Dof::Free(a)), Some(Dof::Free(b))) =
                        (dofs.dofs.get(r), dofs.dofs.get(c))
                    {
                        if let Some(slot) = scatter.pattern.find(*a, *b) {
                            values[slot] -= dij;
                        }
                    }
                }
            }
        }
    }
}

/// The largest tie gap `|x_a - p_a|` over every rigid body at `u` (the
/// penalty's violation of the rigid motion).
pub fn max_tie_gap<const D: usize>(model: &Model<D>, u: &[f64]) -> f64 {
    if D == 3 {
        let mut worst: f64 = 0.0;
        for (nodes, pilot, spin, _) in rigid(model) {
            for &a in nodes {
                let d = tie3(model, u, a, pilot, spin).d;
                worst = worst.max((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt());
            }
        }
        return worst;
    }
    if D != 2 {
        return 0.0;
    }
    let mut worst: f64 = 0.0;
    for d in &model.discrete {
        if let Discrete::Rigid {
            nodes, pilot, spin, ..
        } = d
        {
            for &a in nodes {
                let t = tie(model, u, a, *pilot, *spin);
                worst = worst.max(t.d[0].hypot(t.d[1]));
            }
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::grid::grid;
    use crate::testkit::ModelBuilder;

    fn model_with_body() -> (Model, usize, usize) {
        let mut model = ModelBuilder::plane_strain()
            .elastic("m", 1.0, 0.0)
            .body("a", grid(2, 1, [0.0, 0.0], [2.0, 1.0], 0.0, 1, false), "m")
            .step("s", 1.0, 1)
            .build();
        let (p, s) = make_rigid(
            &mut model,
            RigidSpec {
                label: "rigid_body a".into(),
                nodes: vec![0, 1, 4],
                centre: [0.7, 0.3, 0.0],
                mass: 2.0,
                inertia: [[0.0; 3], [0.0; 3], [0.0, 0.0, 0.5]],
                axis: [0.0, 0.0, 1.0],
                rotation: None,
                moment: TimeFunction::Constant(0.0),
                bearing_stiffness: 3.0,
                bearing_damping: 0.1,
                stiffness: 7.0,
            },
        )
        .unwrap();
        (model, p, s)
    }

    /// The tangent is the exact derivative of the forces (central
    /// differences, every free dof, at a large angle and stretched ties).
    #[test]
    fn the_tangent_is_the_derivative_of_the_tie_forces() {
        let (model, _, spin) = model_with_body();
        assert!(refusals(&model).is_empty(), "{:?}", refusals(&model));
        let mut u = scattered_state(model.mesh.nodes.len() * 2);
        u[spin * 2] = 1.3;
        let worst = tangent_fd_error(&model, &u);
        assert!(worst < 1e-7, "worst relative error {worst:e}");
    }

    /// A state with every component set, `0.05 (7 i mod 11) - 0.2`.
    fn scattered_state(n: usize) -> Vec<f64> {
        (0..n).map(|i| 0.05 * ((i * 7 % 11) as f64) - 0.2).collect()
    }

    /// The largest relative error, over the free dofs, of the ties'
    /// tangent at `u` against central differences of their forces.
    fn tangent_fd_error<const D: usize>(model: &Model<D>, u: &[f64]) -> f64 {
        let dofs = DofMap::new(model);
        let scatter = super::super::discrete::scatter_for(model, &dofs, &[], None).unwrap();
        let n = u.len();
        let mut values = vec![0.0; scatter.n_values()];
        add_tangent(model, u, &dofs, &scatter, &mut values);
        let h = 1e-6;
        let mut worst: f64 = 0.0;
        for (j, &gj) in dofs.free.iter().enumerate() {
            let (mut up, mut um) = (u.to_vec(), u.to_vec());
            up[gj] += h;
            um[gj] -= h;
            let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
            add_forces(model, &up, &mut fp);
            add_forces(model, &um, &mut fm);
            for (i, &gi) in dofs.free.iter().enumerate() {
                let fd = (fp[gi] - fm[gi]) / (2.0 * h);
                let k = scatter.pattern.find(i, j).map_or(0.0, |s| values[s]);
                worst = worst.max((fd - k).abs() / (1.0 + k.abs()));
            }
        }
        worst
    }

    /// A rigid motion (translation and a large rotation) leaves the ties
    /// unstretched and forceless; the forces balance and have no moment
    /// about the current centre beyond the spin's own.
    #[test]
    fn a_rigid_motion_is_exact_at_large_angle() {
        let (model, pilot, spin) = model_with_body();
        let n = model.mesh.nodes.len() * 2;
        let mut u = vec![0.0; n];
        let (uc, theta) = ([0.4, -1.1], 2.5);
        u[pilot * 2] = uc[0];
        u[pilot * 2 + 1] = uc[1];
        u[spin * 2] = theta;
        let (s, c) = f64::sin_cos(theta);
        for &a in &[0, 1, 4] {
            let x = model.mesh.nodes[a];
            let r = [x[0] - 0.7, x[1] - 0.3];
            u[a * 2] = uc[0] + c * r[0] - s * r[1] - r[0];
            u[a * 2 + 1] = uc[1] + s * r[0] + c * r[1] - r[1];
        }
        assert!(max_tie_gap(&model, &u) < 1e-15);
        let mut f = vec![0.0; n];
        add_forces(&model, &u, &mut f);
        assert!(f.iter().all(|x| x.abs() < 1e-14), "{f:?}");
        // a stretched tie: the pilot takes the opposite force
        u[2] += 0.1;
        let mut f = vec![0.0; n];
        add_forces(&model, &u, &mut f);
        assert!((f[2] - 0.7).abs() < 1e-14 && (f[pilot * 2] + 0.7).abs() < 1e-14);
        assert!((f.iter().step_by(2).take(pilot).sum::<f64>() - 0.7).abs() < 1e-14);
        // the moment about the current centre: r x f with r = R r_1
        let x1 = model.mesh.nodes[1];
        let arm = [
            c * (x1[0] - 0.7) - s * (x1[1] - 0.3),
            s * (x1[0] - 0.7) + c * (x1[1] - 0.3),
        ];
        assert!((f[spin * 2] - (-(arm[0] * 0.0 - arm[1] * 0.7))).abs() < 1e-14);
    }

    /// An angular velocity ramped then held integrates to the exact
    /// angle at the samples (quadratic, then linear).
    #[test]
    fn a_ramped_angular_velocity_integrates_to_its_angle() {
        let omega = TimeFunction::Ramp {
            t0: 0.0,
            t1: 2.0,
            v0: 0.0,
            v1: 10.0,
        };
        let theta = angle_of(&omega, (0.0, 5.0));
        for t in [0.0, 0.5, 1.0, 2.0, 3.0, 5.0] {
            let exact = if t <= 2.0 {
                2.5 * t * t
            } else {
                10.0 + 10.0 * (t - 2.0)
            };
            assert!((theta.eval(t) - exact).abs() < 1e-12, "{t}");
        }
        assert_eq!(
            angle_of(&TimeFunction::Constant(3.0), (1.0, 2.0)).eval(2.0),
            3.0
        );
    }

    /// `make_rigid` appends the pilot and spin nodes with their masses,
    /// bearing and held y; the dofs are active and the pattern couples
    /// them to the body's nodes.
    #[test]
    fn make_rigid_appends_a_pilot_and_a_spin_node() {
        let (model, pilot, spin) = model_with_body();
        assert_eq!((pilot, spin), (6, 7));
        let dofs = DofMap::new(&model);
        assert!(matches!(dofs.dofs[pilot * 2], Dof::Free(_)));
        assert!(matches!(dofs.dofs[spin * 2], Dof::Free(_)));
        assert!(matches!(dofs.dofs[spin * 2 + 1], Dof::Prescribed(_)));
        let scatter = super::super::discrete::scatter_for(&model, &dofs, &[], None).unwrap();
        assert!(scatter.pair_slots(&dofs, 4, spin).is_some());
        assert!(scatter.pair_slots(&dofs, pilot, spin).is_some());
        let masses: Vec<f64> = model
            .discrete
            .iter()
            .filter_map(|d| match d {
                Discrete::Mass { mass, .. } => Some(*mass),
                _ => None,
            })
            .collect();
        assert_eq!(masses, [2.0, 0.5]);
        let mut axi = model.clone();
        axi.analysis.kind = AnalysisKind::Axisymmetric;
        assert_eq!(refusals(&axi).len(), 1);
    }

    /// A 3D body: a 2 x 1 x 1 hex8 block, three of its nodes tied, with
    /// mass and a general inertia tensor (six inertia points).
    fn model_3d(rotation: Option<TimeFunction>) -> (Model<3>, usize, usize) {
        use crate::mesh::generate::solid::brick;
        use crate::mesh::generate::Grading;
        let mesh = brick(
            [0.0; 3],
            [2.0, 1.0, 1.0],
            [2, 1, 1],
            [Grading::Uniform; 3],
            crate::mesh::CellKind::Hex8,
        )
        .unwrap();
        let mut model = ModelBuilder::solid()
            .elastic("m", 1.0, 0.0)
            .body("a", mesh, "m")
            .step("s", 1.0, 1)
            .build();
        let (p, s) = make_rigid(
            &mut model,
            RigidSpec {
                label: "rigid_body a".into(),
                nodes: vec![0, 1, 4, 7],
                centre: [0.7, 0.3, 0.4],
                mass: 2.0,
                inertia: [[0.9, 0.1, -0.2], [0.1, 0.7, 0.05], [-0.2, 0.05, 1.1]],
                axis: [1.0, 2.0, 2.0],
                rotation,
                moment: TimeFunction::Constant(0.0),
                bearing_stiffness: 3.0,
                bearing_damping: 0.1,
                stiffness: 7.0,
            },
        )
        .unwrap();
        (model, p, s)
    }

    /// 3D: the tangent is the exact derivative of the forces (central
    /// differences over every free dof, at a rotation of 2.9 rad and
    /// stretched ties).
    #[test]
    fn the_3d_tangent_is_the_derivative_of_the_tie_forces() {
        let (model, _, spin) = model_3d(None);
        assert!(refusals(&model).is_empty(), "{:?}", refusals(&model));
        let mut u = scattered_state(model.mesh.nodes.len() * 3);
        u[spin * 3..spin * 3 + 3].copy_from_slice(&[1.2, -2.1, 1.6]);
        let worst = tangent_fd_error(&model, &u);
        assert!(worst < 1e-7, "worst relative error {worst:e}");
    }

    /// 3D: a rigid motion (translation and a rotation of 2.9 rad about a
    /// skew axis) leaves every tie, the inertia points' too, unstretched.
    #[test]
    fn a_3d_rigid_motion_is_exact_at_large_angle() {
        let (model, pilot, spin) = model_3d(None);
        let n = model.mesh.nodes.len();
        let mut u = vec![0.0; n * 3];
        let psi = [1.2, -2.1, 1.6];
        let uc = [0.4, -1.1, 0.3];
        u[pilot * 3..pilot * 3 + 3].copy_from_slice(&uc);
        u[spin * 3..spin * 3 + 3].copy_from_slice(&psi);
        let rot = nalgebra::Rotation3::from_scaled_axis(nalgebra::Vector3::from(psi));
        let xc = nalgebra::Vector3::from(model.mesh.nodes[pilot]);
        for a in 0..n {
            if a == pilot || a == spin {
                continue;
            }
            let x = nalgebra::Vector3::from(model.mesh.nodes[a]);
            let moved = rot * (x - xc) + xc - x;
            for c in 0..3 {
                u[a * 3 + c] = uc[c] + moved[c];
            }
        }
        assert!(
            max_tie_gap(&model, &u) < 1e-14,
            "{}",
            max_tie_gap(&model, &u)
        );
        let mut f = vec![0.0; n * 3];
        add_forces(&model, &u, &mut f);
        assert!(f.iter().all(|x| x.abs() < 1e-13), "{f:?}");
    }

    /// 3D: six inertia points (a general tensor) are appended, tied and
    /// active; a prescribed rotation fixes the three components of the
    /// rotation vector along the unit axis; a moment on a free body and
    /// rotary inertia without mass are refused.
    #[test]
    fn make_rigid_in_3d_appends_inertia_points_and_prescribes_the_axis() {
        let (model, pilot, spin) = model_3d(Some(TimeFunction::Constant(3.0)));
        assert_eq!((pilot, spin), (12, 13));
        assert_eq!(model.mesh.nodes.len(), 20);
        let dofs = DofMap::new(&model);
        for c in 0..3 {
            assert!(matches!(dofs.dofs[19 * 3 + c], Dof::Free(_)));
            assert!(matches!(dofs.dofs[spin * 3 + c], Dof::Prescribed(_)));
        }
        let values: Vec<f64> = model
            .constraints
            .iter()
            .map(|d| d.value.eval(0.5))
            .collect();
        assert_eq!(values, [1.0, 2.0, 2.0]);
        let Some(Discrete::Rigid { nodes, .. }) = model.discrete.last() else {
            panic!("no rigid body")
        };
        assert_eq!(nodes.len(), 10);
        let mut bad = model_3d(None).0;
        bad.mesh.nodes.truncate(12);
        let spec = |mass: f64, moment: f64| RigidSpec {
            label: "b".into(),
            nodes: vec![0],
            centre: [0.0; 3],
            mass,
            inertia: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            axis: [0.0, 0.0, 1.0],
            rotation: None,
            moment: TimeFunction::Constant(moment),
            bearing_stiffness: 0.0,
            bearing_damping: 0.0,
            stiffness: 1.0,
        };
        assert!(make_rigid(&mut bad, spec(0.0, 0.0))
            .unwrap_err()
            .contains("mass"));
        // a free body's moment: a `RigidMoment` load along the unit axis
        let mut free = bad.clone();
        let (_, spin) = make_rigid(&mut free, spec(1.0, 2.0)).unwrap();
        assert!(matches!(
            free.loads.last(),
            Some(Load::RigidMoment { spin: s, axis, value, .. })
                if *s == spin && *axis == [0.0, 0.0, 1.0] && *value == TimeFunction::Constant(2.0)
        ));
        // with a prescribed rotation, a moment is refused
        let mut turned = spec(1.0, 2.0);
        turned.rotation = Some(TimeFunction::Constant(1.0));
        assert!(make_rigid(&mut bad, turned).unwrap_err().contains("moment"));
    }
}
