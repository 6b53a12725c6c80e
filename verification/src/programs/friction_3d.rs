//! Coulomb friction of solid (3D) bodies against rigid surface tools (tags
//! `3d`, `contact`, `friction`): the return map on the Coulomb disc of
//! `ctc_engine::contact::friction_surface` in the full solver, penalty,
//! augmented Lagrangian and Lagrange multipliers (two tangential rows per
//! sticking node and the stick/slip loop of
//! `ctc_engine::contact::friction_lagrange`), deck-free models through the
//! test kit. Every case runs the three methods on the same model.
//!
//! `friction_block_3d` — a hex8 block `1 x 1 x 0.5` (E = 1e5, nu = 0: no
//! Poisson expansion under the press, so the base is free of tangential
//! force before the pull and uniformly sheared by it) on a
//! rigid plane `z = 0`, pressed by a uniform traction `p = 100` on its top
//! (`F_n = 100`), then every node above the contact face is displaced
//! horizontally along `e = (cos 30°, sin 30°, 0)` (`u_z` free): first by
//! `d_s = 2e-5`, a tenth of the sliding limit (stage "stick": every
//! contact node sticks, its slip is zero), then to `d = 1e-2`, about fifty
//! times the displacement at which the base starts to slide (`1.8e-4`: the
//! shear of the first cell row, `G A / h = 2e5`, in series with the
//! tangential penalty `k_T A = 1e6`). In full slip
//! Coulomb's law gives, per node, `|T_i| = mu R_N,i` with `T_i` opposite to
//! the slip, so `sum |T_i| = mu sum R_N,i`, the total tangential force
//! `|F_t| = mu F_n` (mu = 0.3), every slip direction along `e`, and in the
//! steady slide the frictional work of an increment `mu F_n Δd` (the base
//! moves with the rest); the slip direction is judged on the mean slip of
//! the contact nodes and on the resultant friction force (single nodes
//! turn by the elastic shear under a non-uniform pressure, and that
//! transient decays as the block slides); equilibrium: `sum R_N = F_n` and the tangential
//! reactions of the driven nodes balance `sum T_i`.
//!
//! ```text
//!     p = 100 (traction on the top face)
//!   +------------+  --> nodes above the base displaced along e
//!   |   block    |      (30° from x in the plane z = 0)
//!   +------------+  contact face zmin
//!  ================  rigid plane z = 0, mu = 0.3
//! ```
//!
//! `friction_inclined_3d` — the inclined-plane benchmark of the 2D case
//! `friction_inclined_plane` (a block pushed horizontally up a plane
//! inclined at `tan a = 0.1`; at slip `F / G = (tan a + mu) / (1 - mu tan a)`
//! = 0.412371 for mu = 0.3, the statics of a block on a slope: e.g.
//! Meriam & Kraige, Engineering Mechanics: Statics, ch. 6, the wedge /
//! inclined-plane problems), in 3D with the slope rising along the
//! horizontal direction `h = (cos 40°, sin 40°, 0)`, not along an axis:
//! the block `1 x 1 x 0.5` lies on the tilted rigid plane, its weight `G =
//! 100` is a vertical traction on its top face, and the nodes of its back
//! face above the contact are pushed horizontally along `h` (`u_z` free).
//! `F` is the reaction of the driven nodes along `h` once every contact
//! node slides; the lateral reaction must vanish.
//!
//! ```text
//!           G (vertical)
//!         +------+
//!   F --> | block|      slope rising along h (40° from x)
//!         +------+
//!   ////// rigid plane, tan a = 0.1 //////
//! ```

use super::{error, value};
use crate::case::{Check, Quantity};
use crate::measure::Value;
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::contact::friction::{pair_dissipation, FrictionStatus};
use ctc_engine::contact::NodeContact;
use ctc_engine::mesh::generate::{solid, Grading};
use ctc_engine::mesh::CellKind;
use ctc_engine::model::{
    ContactMethod, Dirichlet, FirstImpact, Friction, LagrangeFormulation, Load, Model,
    MultiplierUpdate, NewtonSettings, PenaltyKind, SurfaceMotion, TimeFunction,
};
use ctc_engine::solve::{run, IncrementView, Observer, RunSummary};
use ctc_geom::analytic::{Analytic, Plane};
use ctc_geom::{Side, Vec3};

const E: f64 = 1e5;
const NU: f64 = 0.3;
const MU: f64 = 0.3;
/// Normal load (total; traction on the unit top face).
const LOAD: f64 = 100.0;

/// The registry entries.
pub fn cases() -> Vec<VerifyCase> {
    vec![
        VerifyCase {
            name: "friction_block_3d",
            title: "3D friction: hex8 block pressed on a rigid plane, pulled at 30° (stick, then full slip)",
            source: "Coulomb's law on the tangent plane (return map on the disc |t| <= mu R_N); statics",
            tags: &["3d", "contact", "friction", "penalty", "augmented", "lagrange", "closed_form"],
            levels: 1,
            checks: vec![
                Check::new(Quantity::Named("stick: slip / d_s"), &[1e-12]),
                Check::new(Quantity::Named("sum|T| vs mu sum R_N penalty"), &[1e-9]),
                Check::new(Quantity::Named("|F_t| / (mu F_n) penalty"), &[1e-6]),
                Check::new(Quantity::Named("slip direction vs pull penalty"), &[1e-6]),
                Check::new(Quantity::Named("force balance penalty"), &[1e-6]),
                Check::new(Quantity::Named("work of last increment penalty"), &[1e-6]),
                Check::new(Quantity::Named("sum|T| vs mu sum R_N augmented"), &[1e-9]),
                Check::new(Quantity::Named("|F_t| / (mu F_n) augmented"), &[1e-6]),
                Check::new(Quantity::Named("slip direction vs pull augmented"), &[1e-6]),
                Check::new(Quantity::Named("force balance augmented"), &[1e-6]),
                Check::new(Quantity::Named("sum|T| vs mu sum R_N lagrange"), &[1e-9]),
                Check::new(Quantity::Named("|F_t| / (mu F_n) lagrange"), &[1e-6]),
                Check::new(Quantity::Named("slip direction vs pull lagrange"), &[1e-6]),
                Check::new(Quantity::Named("force balance lagrange"), &[1e-6]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: block_level,
            }),
        },
        VerifyCase {
            name: "friction_inclined_3d",
            title: "3D friction: block pushed up a plane inclined at tan a = 0.1 along 40°, F/G = (tan a + mu)/(1 - mu tan a)",
            source: "statics of a block on a slope (Meriam & Kraige, Statics, ch. 6); 2D friction_inclined_plane",
            tags: &["3d", "contact", "friction", "penalty", "augmented", "lagrange", "closed_form"],
            levels: 1,
            checks: vec![
                Check::new(Quantity::Named("F/G penalty vs 0.412371"), &[1e-5]),
                Check::new(Quantity::Named("F/G augmented vs 0.412371"), &[1e-5]),
                Check::new(Quantity::Named("F/G lagrange vs 0.412371"), &[1e-5]),
                Check::new(Quantity::Named("lateral / F"), &[1e-6]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: inclined_level,
            }),
        },
        VerifyCase {
            name: "friction_curved_path_3d",
            title: "3D friction: block dragged along a quarter circle on a rigid plane (stick, then slip that turns), W = mu F_n L",
            source: "Coulomb's law on the tangent plane: dissipation of a sliding block = mu N x slip length; the slip direction follows the path",
            tags: &["3d", "contact", "friction", "penalty", "augmented", "lagrange", "closed_form"],
            levels: 1,
            checks: vec![
                Check::new(Quantity::Named("stick: slip / d_s"), &[1e-12]),
                Check::new(Quantity::Named("W / (mu F_n L_slip) penalty"), &[2e-5]),
                Check::new(Quantity::Named("W / (mu F_n R Theta) penalty"), &[1e-3]),
                Check::new(Quantity::Named("slip direction vs path penalty"), &[1e-3]),
                Check::new(Quantity::Named("W / (mu F_n L_slip) augmented"), &[5e-4]),
                Check::new(Quantity::Named("W / (mu F_n R Theta) augmented"), &[1e-3]),
                Check::new(Quantity::Named("slip direction vs path augmented"), &[2e-2]),
                Check::new(Quantity::Named("W / (mu F_n L_slip) lagrange"), &[2e-5]),
                Check::new(Quantity::Named("W / (mu F_n R Theta) lagrange"), &[1e-3]),
                Check::new(Quantity::Named("slip direction vs path lagrange"), &[1e-3]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: curved_level,
            }),
        },
    ]
}

/// One converged increment.
struct Row {
    time: f64,
    reaction: [f64; 3],
    contact: Vec<NodeContact<3>>,
}

#[derive(Default)]
struct Rows(Vec<Row>);

impl Observer<3> for Rows {
    fn converged(&mut self, v: &IncrementView<'_, 3>) -> Result<(), String> {
        let mut r = [0.0; 3];
        for n in v.reaction {
            for (rc, nc) in r.iter_mut().zip(n) {
                *rc += nc;
            }
        }
        self.0.push(Row {
            time: v.time,
            reaction: r,
            contact: v.contact.first().cloned().unwrap_or_default(),
        });
        Ok(())
    }
}

/// The block on a rigid plane of slope `tan a` rising along the horizontal
/// direction at `azimuth` (0: flat), with `method`, loaded by `LOAD`
/// vertically on its top face (step 1), then driven by the horizontal
/// displacement `drive(t)` along `direction` of the nodes `driven`
/// (`"above"`: every node off the contact face; `"back"`: the back face
/// above the contact).
struct Scene {
    slope: f64,
    azimuth: f64,
    method: ContactMethod,
    stiffness: Option<f64>,
    /// The horizontal drive: `(time, [u_x, u_y])`, piecewise linear.
    drive: Vec<(f64, [f64; 2])>,
    back: bool,
    increments: [usize; 2],
    poisson: f64,
    /// Cell kind: hex8, or tet4 (Kuhn split), both elevated when
    /// quadratic (hex20, hex27, tet10: face-integrated friction).
    cell: CellKind,
}

/// A straight drive along the horizontal direction at `direction`
/// (radians from x) of the magnitudes `table` (`(time, d)`).
fn straight(direction: f64, table: &[(f64, f64)]) -> Vec<(f64, [f64; 2])> {
    let (c, s) = (direction.cos(), direction.sin());
    table.iter().map(|&(t, d)| (t, [c * d, s * d])).collect()
}

impl Scene {
    fn model(&self) -> Result<Model<3>, String> {
        let (a, phi) = (self.slope.atan(), self.azimuth);
        // local frame: e1 up the slope, e2 across, e3 = the plane's normal
        let e1 = Vec3::new(a.cos() * phi.cos(), a.cos() * phi.sin(), a.sin());
        let e2 = Vec3::new(-phi.sin(), phi.cos(), 0.0);
        let e3 = e1.cross(&e2);
        let linear = match self.cell {
            CellKind::Tet4 | CellKind::Tet10 => CellKind::Tet4,
            _ => CellKind::Hex8,
        };
        let mut mesh = solid::brick(
            [0.0; 3],
            [1.0, 1.0, 0.5],
            [3, 3, 2],
            [Grading::Uniform; 3],
            linear,
        )
        .map_err(|e| e.message)?;
        if self.cell != linear {
            mesh = ctc_engine::mesh::elevate::elevate(&mesh, self.cell).map_err(|e| e.message)?;
        }
        let bottom: Vec<usize> = {
            let mut v: Vec<usize> = (0..mesh.nodes.len())
                .filter(|&k| mesh.nodes[k][2].abs() < 1e-12)
                .collect();
            v.sort_unstable();
            v
        };
        let back_face: Vec<usize> = (0..mesh.nodes.len())
            .filter(|&k| mesh.nodes[k][0].abs() < 1e-12 && mesh.nodes[k][2] > 1e-12)
            .collect();
        for p in &mut mesh.nodes {
            let x = e1 * p[0] + e2 * p[1] + e3 * p[2];
            *p = [x[0], x[1], x[2]];
        }
        let mut b = ctc_engine::testkit::ModelBuilder::solid()
            .elastic("m", E, self.poisson)
            .body("block", mesh, "m");
        let driven: Vec<usize> = if self.back {
            back_face
        } else {
            (0..b.model().mesh.nodes.len())
                .filter(|k| bottom.binary_search(k).is_err())
                .collect()
        };
        let top = b.face_set("block.zmax");
        let faces = b.face_set("block.zmin");
        for component in 0..2 {
            let value =
                TimeFunction::Table(self.drive.iter().map(|&(t, u)| (t, u[component])).collect());
            b = b.constraint(Dirichlet {
                label: "drive".into(),
                nodes: driven.clone(),
                component,
                value,
            });
        }
        // the plane overlaps the block by 1e-6 so that contact is closed
        // from the first iteration on (nothing else holds the block in z)
        let plane = Plane::new(e3 * 1e-6, e3, Side::Outside).map_err(|e| e.to_string())?;
        let newton = NewtonSettings {
            tol: 1e-10,
            tol_displacement: 1e-10,
            max_iter: 30,
            line_search: true,
            predictor: true,
            stabilize: None,
        };
        let last = self.drive_end();
        Ok(b.load(Load::FacetTraction {
            label: "weight".into(),
            facets: top,
            component: 2,
            value: ctc_engine::testkit::ramp(0.0, 1.0, -LOAD),
        })
        .surface("plane", Analytic::Plane(plane), SurfaceMotion::fixed())
        .contact_faces(
            "block.zmin -> plane",
            "block",
            faces,
            "plane",
            self.method.clone(),
        )
        .prof(0.1)
        .friction(Friction {
            mu: MU,
            stiffness: self.stiffness,
            first_impact: FirstImpact::Intersect,
            cut_at_impact: false,
        })
        .step("press", 1.0, 1)
        .newton(newton)
        .step("stick", 2.0, self.increments[0])
        .newton(newton)
        .step("pull", last, self.increments[1])
        .min_fraction(1.0 / 64.0)
        .newton(newton)
        .build())
    }

    fn drive_end(&self) -> f64 {
        self.drive.last().map_or(3.0, |p| p.0)
    }

    fn solve(&self, counts: &mut ProgramLevel) -> Result<Vec<Row>, String> {
        let model = self.model()?;
        let mut rows = Rows::default();
        let s = run(&model, &mut rows).map_err(|e| e.message)?;
        if !s.completed {
            return Err("the run did not complete".into());
        }
        add(counts, &model, &s);
        Ok(rows.0)
    }
}

/// The model of `friction_block_3d` with method `method` (0 penalty, 1
/// augmented Lagrangian, 2 Lagrange multipliers): press (t = 0..1, 1
/// increment), stick (1..2, 1 increment), pull (2..3, 8 increments). For
/// the restart and convergence tests.
pub fn pulled_block(method: usize) -> Result<Model<3>, String> {
    pulled_block_on(CellKind::Hex8, method)
}

/// [`pulled_block`] on cells of `cell` (hex8, tet4, or elevated to hex20,
/// hex27, tet10: friction face-integrated).
pub fn pulled_block_on(cell: CellKind, method: usize) -> Result<Model<3>, String> {
    let (_, method, stiffness) = methods().get(method).ok_or("method 0, 1 or 2")?.clone();
    Scene {
        slope: 0.0,
        azimuth: 0.0,
        method,
        stiffness,
        drive: straight(
            30f64.to_radians(),
            &[(0.0, 0.0), (1.0, 0.0), (2.0, 2e-5), (3.0, 1e-2)],
        ),
        back: false,
        increments: [1, 8],
        poisson: 0.0,
        cell,
    }
    .model()
}

fn add(l: &mut ProgramLevel, model: &Model<3>, s: &RunSummary) {
    l.nodes = l.nodes.max(model.mesh.nodes.len());
    l.free_dofs = l.free_dofs.max(s.free_dofs);
    l.increments += s.increments.len();
    l.newton_total += s.newton_iterations;
    l.newton_max = l
        .newton_max
        .max(s.increments.iter().map(|i| i.iterations).max().unwrap_or(0));
    l.cutbacks += s.cutbacks;
}

/// The three methods: penalty, augmented Lagrangian, Lagrange multipliers
/// (normal and tangential rows, the stick/slip status loop of
/// `ctc_engine::contact::friction_lagrange`).
fn methods() -> [(&'static str, ContactMethod, Option<f64>); 3] {
    [
        (
            "penalty",
            ContactMethod::Penalty {
                kind: PenaltyKind::Area,
                stiffness: 1e7,
            },
            None,
        ),
        (
            "augmented",
            ContactMethod::AugmentedLagrange {
                kind: PenaltyKind::Area,
                penalty: 1e6,
                tolerance: 1e-8,
                update: MultiplierUpdate::Converged,
            },
            // Uzawa contracts the stick gaps at about K / (K + alpha_T)
            Some(1e6),
        ),
        (
            "lagrange",
            ContactMethod::Lagrange {
                formulation: LagrangeFormulation::Single,
            },
            None,
        ),
    ]
}

fn normal_force(c: &NodeContact<3>) -> f64 {
    (0..3)
        .map(|k| (c.force[k] - c.friction.traction[k]) * c.normal[k])
        .sum()
}

fn norm(v: [f64; 3]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Every contact node in `status`, or the error naming the stage.
fn all_in(row: &Row, status: FrictionStatus, stage: &str) -> Result<(), String> {
    let n = row
        .contact
        .iter()
        .filter(|c| c.friction.status == status)
        .count();
    if n != row.contact.len() || n == 0 {
        return Err(format!(
            "{stage} (t = {}): {n} of {} contact nodes in {status:?}",
            row.time,
            row.contact.len()
        ));
    }
    Ok(())
}

fn block_level(_: usize) -> Result<ProgramLevel, String> {
    let (d_s, d) = (2e-5, 1e-2);
    let direction = 30f64.to_radians();
    let e = [direction.cos(), direction.sin(), 0.0];
    let mut level = ProgramLevel {
        h: f64::NAN,
        ..Default::default()
    };
    let mut values: Vec<Value> = Vec::new();
    let mut stick_slip = 0.0f64;
    let labels: [[&'static str; 5]; 3] = [
        [
            "sum|T| vs mu sum R_N penalty",
            "|F_t| / (mu F_n) penalty",
            "slip direction vs pull penalty",
            "force balance penalty",
            "work of last increment penalty",
        ],
        [
            "sum|T| vs mu sum R_N augmented",
            "|F_t| / (mu F_n) augmented",
            "slip direction vs pull augmented",
            "force balance augmented",
            "",
        ],
        [
            "sum|T| vs mu sum R_N lagrange",
            "|F_t| / (mu F_n) lagrange",
            "slip direction vs pull lagrange",
            "force balance lagrange",
            "",
        ],
    ];
    let increments = 8;
    for (k, (name, method, stiffness)) in methods().into_iter().enumerate() {
        let scene = Scene {
            slope: 0.0,
            azimuth: 0.0,
            method,
            stiffness,
            drive: straight(direction, &[(0.0, 0.0), (1.0, 0.0), (2.0, d_s), (3.0, d)]),
            back: false,
            increments: [1, increments],
            // no Poisson expansion under the press: no tangential force
            // before the pull, and a uniform shear of the base under it
            poisson: 0.0,
            cell: CellKind::Hex8,
        };
        let rows = scene
            .solve(&mut level)
            .map_err(|e| format!("{name}: {e}"))?;
        let stick = rows
            .iter()
            .find(|r| (r.time - 2.0).abs() < 1e-12)
            .ok_or("no increment at the end of the stick stage")?;
        all_in(stick, FrictionStatus::Stick, &format!("{name} stick stage"))?;
        stick_slip = stick_slip.max(
            stick
                .contact
                .iter()
                .map(|c| c.friction.slip)
                .fold(0.0, f64::max)
                / d_s,
        );
        let last = rows.last().ok_or("no increment")?;
        all_in(
            last,
            FrictionStatus::Slip,
            &format!("{name} end of the pull"),
        )?;
        let rn: f64 = last.contact.iter().map(normal_force).sum();
        let sum_t: f64 = last.contact.iter().map(|c| norm(c.friction.traction)).sum();
        let mut ft = [0.0; 3];
        for c in &last.contact {
            for (f, t) in ft.iter_mut().zip(c.friction.traction) {
                *f += t;
            }
        }
        // slip direction: the sine of the angle between the pull and the
        // mean slip of the contact nodes, and between the pull and minus
        // the resultant friction force; each node slips forward
        let mut mean = [0.0; 3];
        for c in &last.contact {
            let s = c.friction.slip_vector;
            let along: f64 = (0..3).map(|j| s[j] * e[j]).sum();
            if along <= 0.0 {
                return Err(format!("{name}: node {} slips against the pull", c.node));
            }
            for (m, sj) in mean.iter_mut().zip(s) {
                *m += sj;
            }
        }
        let sine = |v: [f64; 3]| {
            let cross = [
                v[1] * e[2] - v[2] * e[1],
                v[2] * e[0] - v[0] * e[2],
                v[0] * e[1] - v[1] * e[0],
            ];
            norm(cross) / norm(v)
        };
        let angle = sine(mean).max(sine(ft));
        // balance: the normal forces carry the load; the tangential
        // reactions of the driven nodes balance the friction forces
        let reaction_t = [last.reaction[0], last.reaction[1], 0.0];
        let balance_t = norm([
            reaction_t[0] + ft[0],
            reaction_t[1] + ft[1],
            reaction_t[2] + ft[2],
        ]) / norm(ft);
        let balance_n = ((rn - LOAD) / LOAD).abs();
        values.push(value(labels[k][0], sum_t, MU * rn));
        values.push(value(labels[k][1], norm(ft) / (MU * LOAD), 1.0));
        values.push(error(labels[k][2], angle));
        values.push(error(labels[k][3], balance_t.max(balance_n)));
        if k == 0 {
            // steady slide: the base moves with the driven nodes
            let dd = (d - d_s) / increments as f64;
            values.push(value(
                labels[k][4],
                pair_dissipation(&last.contact),
                MU * LOAD * dd,
            ));
        }
    }
    values.insert(0, error("stick: slip / d_s", stick_slip));
    level.values = values;
    Ok(level)
}

/// One method's push of `friction_inclined_3d`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InclinedPush {
    /// `F / G` at the end of the push.
    pub ratio: f64,
    /// Lateral reaction over `F`.
    pub lateral: f64,
    /// Wall time of the run (seconds).
    pub seconds: f64,
    /// Newton iterations of the run.
    pub newton: usize,
}

/// The block of `friction_inclined_3d` pushed up the slope with method
/// `method` (0 penalty, 1 augmented Lagrangian, 2 Lagrange multipliers);
/// `counts` gathers the run's sizes.
pub fn inclined_push(method: usize, counts: &mut ProgramLevel) -> Result<InclinedPush, String> {
    inclined_push_on(CellKind::Hex8, method, counts)
}

/// [`inclined_push`] on cells of `cell` (hex8, tet4, or the quadratic
/// hex20, hex27, tet10: the brick elevated, face-integrated friction).
pub fn inclined_push_on(
    cell: CellKind,
    method: usize,
    counts: &mut ProgramLevel,
) -> Result<InclinedPush, String> {
    let azimuth = 40f64.to_radians();
    let h = [azimuth.cos(), azimuth.sin(), 0.0];
    let (name, method, stiffness) = methods().get(method).ok_or("method 0, 1 or 2")?.clone();
    let scene = Scene {
        slope: 0.1,
        azimuth,
        method,
        stiffness,
        drive: straight(azimuth, &[(0.0, 0.0), (1.0, 0.0), (2.0, 1e-3), (3.0, 1e-2)]),
        back: true,
        increments: [1, 4],
        poisson: NU,
        cell,
    };
    let newton = counts.newton_total;
    let start = std::time::Instant::now();
    let rows = scene.solve(counts).map_err(|e| format!("{name}: {e}"))?;
    let seconds = start.elapsed().as_secs_f64();
    let last = rows.last().ok_or("no increment")?;
    all_in(
        last,
        FrictionStatus::Slip,
        &format!("{name} end of the push"),
    )?;
    let r = last.reaction;
    let f = r[0] * h[0] + r[1] * h[1];
    Ok(InclinedPush {
        ratio: f / LOAD,
        lateral: (r[1] * h[0] - r[0] * h[1]).abs() / f.abs(),
        seconds,
        newton: counts.newton_total - newton,
    })
}

fn inclined_level(_: usize) -> Result<ProgramLevel, String> {
    let mut level = ProgramLevel {
        h: f64::NAN,
        ..Default::default()
    };
    let reference = (0.1 + MU) / (1.0 - MU * 0.1);
    let mut values = Vec::new();
    let mut lateral = 0.0f64;
    let labels = [
        "F/G penalty vs 0.412371",
        "F/G augmented vs 0.412371",
        "F/G lagrange vs 0.412371",
    ];
    for (k, label) in labels.into_iter().enumerate() {
        let push = inclined_push(k, &mut level)?;
        lateral = lateral.max(push.lateral);
        values.push(value(label, push.ratio, reference));
    }
    values.push(error("lateral / F", lateral));
    level.values = values;
    Ok(level)
}

/// Radius of the path of `friction_curved_path_3d`.
const PATH_RADIUS: f64 = 0.5;
/// Angle of that path (a quarter circle).
const PATH_ANGLE: f64 = std::f64::consts::FRAC_PI_2;
/// Increments of its pull.
const PATH_INCREMENTS: usize = 32;

/// The drive of `friction_curved_path_3d`: press (t = 0..1), stick stage
/// (1..2) to the arc length `d_s`, then along the quarter circle of radius
/// `R` centred at `(0, R)` to the angle `Theta` (2..3), the points on the
/// circle at every increment (piecewise linear in between: the driven
/// nodes move along its chords).
fn circle_drive(d_s: f64) -> Vec<(f64, [f64; 2])> {
    let at = |theta: f64| [PATH_RADIUS * theta.sin(), PATH_RADIUS * (1.0 - theta.cos())];
    let theta_s = d_s / PATH_RADIUS;
    let mut drive = vec![(0.0, [0.0; 2]), (1.0, [0.0; 2]), (2.0, at(theta_s))];
    for k in 1..=PATH_INCREMENTS {
        let f = k as f64 / PATH_INCREMENTS as f64;
        drive.push((2.0 + f, at(theta_s + f * (PATH_ANGLE - theta_s))));
    }
    drive
}

/// The scene of `friction_curved_path_3d` with method `method` (0
/// penalty, 1 augmented Lagrangian, 2 Lagrange multipliers), stick stage
/// to the arc `d_s`.
fn curved_scene(method: usize, d_s: f64) -> Result<Scene, String> {
    let (_, method, stiffness) = methods().get(method).ok_or("method 0, 1 or 2")?.clone();
    Ok(Scene {
        slope: 0.0,
        azimuth: 0.0,
        method,
        stiffness,
        drive: circle_drive(d_s),
        back: false,
        increments: [1, PATH_INCREMENTS],
        poisson: 0.0,
        cell: CellKind::Hex8,
    })
}

/// The model of `friction_curved_path_3d` with method `method` (0
/// penalty, 1 augmented Lagrangian, 2 Lagrange multipliers): press, stick
/// stage, the drag along the quarter circle in 32 increments. For the
/// convergence tests.
pub fn curved_path_block(method: usize) -> Result<Model<3>, String> {
    curved_scene(method, 2e-5)?.model()
}

/// `friction_curved_path_3d` — the block of `friction_block_3d` (hex8 `1
/// x 1 x 0.5`, E = 1e5, nu = 0, pressed by `F_n = 100`, mu = 0.3) on the
/// rigid plane `z = 0`, every node above its base dragged along a quarter
/// circle of radius `R = 0.5` (arc length `R Theta = 0.785`, 32
/// increments): first by the arc `d_s = 2e-5` (every contact node
/// sticks), then along the whole arc, where the base slides and its slip
/// direction turns by 90°. Coulomb: the friction force of a sliding node
/// is `mu R_N` against its slip, so the work dissipated is `W = mu F_n
/// L_slip`, `L_slip` the length of the base's slip path (the sum over
/// increments of the mean slip vector's length), and `W = mu F_n R Theta`
/// up to the slip missing at the start (the elastic shear before sliding,
/// about 2e-4, 3e-4 of `R Theta`) and the chords of the increments (1 -
/// (dTheta)^2 / 24 = 1 - 1e-4); the slip of the last increment is along
/// the chord the driven nodes moved on (the base trails them by a shear
/// that turns with the path: an angle of about its size over `R`).
/// Measured (tolerances in brackets): `W / (mu F_n L_slip)` 6.6e-6
/// penalty, 5.3e-6 Lagrange [2e-5: the nodes' slips differ by the elastic
/// shear, `L_slip` is the length of their mean], 1.6e-4 augmented [5e-4];
/// `W / (mu F_n R Theta)` 3.7e-4, 5.7e-4, 4.8e-4 [1e-3]; slip direction
/// 4.0e-4 penalty, 3.4e-4 Lagrange [1e-3], 7.7e-3 augmented [2e-2: the
/// Uzawa loop stops on the gaps, and a node it slides by moving the base
/// of its trial force keeps a force direction that lags the turning slip].
///
/// ```text
///          y
///          |   . '  quarter circle, radius R = 0.5, centred (0, R)
///          | .'
///          |.    the block, pressed by F_n, dragged along the arc
///   [block]+-------- x      rigid plane z = 0, mu = 0.3
/// ```
fn curved_level(_: usize) -> Result<ProgramLevel, String> {
    let d_s = 2e-5;
    let mut level = ProgramLevel {
        h: f64::NAN,
        ..Default::default()
    };
    let labels: [[&'static str; 3]; 3] = [
        [
            "W / (mu F_n L_slip) penalty",
            "W / (mu F_n R Theta) penalty",
            "slip direction vs path penalty",
        ],
        [
            "W / (mu F_n L_slip) augmented",
            "W / (mu F_n R Theta) augmented",
            "slip direction vs path augmented",
        ],
        [
            "W / (mu F_n L_slip) lagrange",
            "W / (mu F_n R Theta) lagrange",
            "slip direction vs path lagrange",
        ],
    ];
    let mut values = Vec::new();
    let mut stick_slip = 0.0f64;
    for (k, (name, _, _)) in methods().into_iter().enumerate() {
        let rows = curved_scene(k, d_s)?
            .solve(&mut level)
            .map_err(|e| format!("{name}: {e}"))?;
        let stick = rows
            .iter()
            .find(|r| (r.time - 2.0).abs() < 1e-12)
            .ok_or("no increment at the end of the stick stage")?;
        all_in(stick, FrictionStatus::Stick, &format!("{name} stick stage"))?;
        stick_slip = stick_slip.max(
            stick
                .contact
                .iter()
                .map(|c| c.friction.slip)
                .fold(0.0, f64::max)
                / d_s,
        );
        let last = rows.last().ok_or("no increment")?;
        // every contact node slides (the augmented Lagrangian slides a node
        // by moving the base of its trial force: it may end a hair inside
        // the disc, reported as stick, while it slips with the rest)
        for c in &last.contact {
            let rim = norm(c.friction.traction) >= (1.0 - 1e-3) * MU * normal_force(c);
            let sliding = c.friction.status == FrictionStatus::Slip
                || (k == 1
                    && rim
                    && c.friction.slip > 0.5 * PATH_RADIUS * PATH_ANGLE / PATH_INCREMENTS as f64);
            if !sliding {
                return Err(format!(
                    "{name}: node {} is not sliding at the end of the drag ({:?})",
                    c.node, c.friction.status
                ));
            }
        }
        // dissipated work and slip path of the base over the run
        let mut work = 0.0;
        let mut path = 0.0;
        for r in &rows {
            work += pair_dissipation(&r.contact);
            let mut mean = [0.0; 3];
            for c in &r.contact {
                for (m, s) in mean.iter_mut().zip(c.friction.slip_vector) {
                    *m += s / r.contact.len() as f64;
                }
            }
            path += norm(mean);
        }
        values.push(value(labels[k][0], work, MU * LOAD * path));
        values.push(value(
            labels[k][1],
            work,
            MU * LOAD * PATH_RADIUS * PATH_ANGLE,
        ));
        // the chord of the last increment, against the mean slip and minus
        // the resultant friction force of that increment
        let (t0, t1) = (
            2.0 + (PATH_INCREMENTS - 1) as f64 / PATH_INCREMENTS as f64,
            3.0,
        );
        let drive = circle_drive(d_s);
        let at = |t: f64| {
            drive
                .iter()
                .find(|p| (p.0 - t).abs() < 1e-12)
                .map(|p| p.1)
                .ok_or("no drive point")
        };
        let (a, b) = (at(t0)?, at(t1)?);
        let chord = [b[0] - a[0], b[1] - a[1], 0.0];
        let mut mean = [0.0; 3];
        let mut ft = [0.0; 3];
        for c in &last.contact {
            for j in 0..3 {
                mean[j] += c.friction.slip_vector[j];
                ft[j] -= c.friction.traction[j];
            }
        }
        let sine = |v: [f64; 3]| {
            let cross = [
                v[1] * chord[2] - v[2] * chord[1],
                v[2] * chord[0] - v[0] * chord[2],
                v[0] * chord[1] - v[1] * chord[0],
            ];
            let dot: f64 = (0..3).map(|j| v[j] * chord[j]).sum();
            if dot <= 0.0 {
                1.0
            } else {
                norm(cross) / (norm(v) * norm(chord))
            }
        };
        values.push(error(labels[k][2], sine(mean).max(sine(ft))));
    }
    values.insert(0, error("stick: slip / d_s", stick_slip));
    level.values = values;
    Ok(level)
}
