//! Coulomb friction of solid (3D) bodies against rigid surface tools (tags
//! `3d`, `contact`, `friction`): the return map on the Coulomb disc of
//! `ctc_engine::contact::friction_surface` in the full solver, penalty and
//! augmented Lagrangian (deck-free models through the test kit).
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
    ContactMethod, Dirichlet, FirstImpact, Friction, Load, Model, MultiplierUpdate, NewtonSettings,
    PenaltyKind, SurfaceMotion, TimeFunction,
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
            tags: &["3d", "contact", "friction", "penalty", "augmented", "closed_form"],
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
            tags: &["3d", "contact", "friction", "penalty", "augmented", "closed_form"],
            levels: 1,
            checks: vec![
                Check::new(Quantity::Named("F/G penalty vs 0.412371"), &[1e-5]),
                Check::new(Quantity::Named("F/G augmented vs 0.412371"), &[1e-5]),
                Check::new(Quantity::Named("lateral / F"), &[1e-6]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: inclined_level,
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
    direction: f64,
    drive: TimeFunction,
    back: bool,
    increments: [usize; 2],
    poisson: f64,
}

impl Scene {
    fn model(&self) -> Result<Model<3>, String> {
        let (a, phi) = (self.slope.atan(), self.azimuth);
        // local frame: e1 up the slope, e2 across, e3 = the plane's normal
        let e1 = Vec3::new(a.cos() * phi.cos(), a.cos() * phi.sin(), a.sin());
        let e2 = Vec3::new(-phi.sin(), phi.cos(), 0.0);
        let e3 = e1.cross(&e2);
        let mut mesh = solid::brick(
            [0.0; 3],
            [1.0, 1.0, 0.5],
            [3, 3, 2],
            [Grading::Uniform; 3],
            CellKind::Hex8,
        )
        .map_err(|e| e.message)?;
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
        let (c, s) = (self.direction.cos(), self.direction.sin());
        for (component, k) in [(0, c), (1, s)] {
            let value = match &self.drive {
                TimeFunction::Table(t) => {
                    TimeFunction::Table(t.iter().map(|&(t, v)| (t, k * v)).collect())
                }
                _ => return Err("the drive is a table".into()),
            };
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
        match &self.drive {
            TimeFunction::Table(t) => t.last().map_or(3.0, |p| p.0),
            _ => 3.0,
        }
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

/// The model of `friction_block_3d` with the penalty (`augmented =
/// false`) or the augmented Lagrangian: press (t = 0..1, 1 increment),
/// stick (1..2, 1 increment), pull (2..3, 8 increments). For the restart
/// and convergence tests.
pub fn pulled_block(augmented: bool) -> Result<Model<3>, String> {
    let (_, method, stiffness) = methods()[usize::from(augmented)].clone();
    Scene {
        slope: 0.0,
        azimuth: 0.0,
        method,
        stiffness,
        direction: 30f64.to_radians(),
        drive: TimeFunction::Table(vec![(0.0, 0.0), (1.0, 0.0), (2.0, 2e-5), (3.0, 1e-2)]),
        back: false,
        increments: [1, 8],
        poisson: 0.0,
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

fn methods() -> [(&'static str, ContactMethod, Option<f64>); 2] {
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
    let labels: [[&'static str; 5]; 2] = [
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
    ];
    let increments = 8;
    for (k, (name, method, stiffness)) in methods().into_iter().enumerate() {
        let scene = Scene {
            slope: 0.0,
            azimuth: 0.0,
            method,
            stiffness,
            direction,
            drive: TimeFunction::Table(vec![(0.0, 0.0), (1.0, 0.0), (2.0, d_s), (3.0, d)]),
            back: false,
            increments: [1, increments],
            // no Poisson expansion under the press: no tangential force
            // before the pull, and a uniform shear of the base under it
            poisson: 0.0,
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

fn inclined_level(_: usize) -> Result<ProgramLevel, String> {
    let azimuth = 40f64.to_radians();
    let h = [azimuth.cos(), azimuth.sin(), 0.0];
    let mut level = ProgramLevel {
        h: f64::NAN,
        ..Default::default()
    };
    let reference = (0.1 + MU) / (1.0 - MU * 0.1);
    let mut values = Vec::new();
    let mut lateral = 0.0f64;
    for (name, method, stiffness) in methods() {
        let scene = Scene {
            slope: 0.1,
            azimuth,
            method,
            stiffness,
            direction: azimuth,
            drive: TimeFunction::Table(vec![(0.0, 0.0), (1.0, 0.0), (2.0, 1e-3), (3.0, 1e-2)]),
            back: true,
            increments: [1, 4],
            poisson: NU,
        };
        let rows = scene
            .solve(&mut level)
            .map_err(|e| format!("{name}: {e}"))?;
        let last = rows.last().ok_or("no increment")?;
        all_in(
            last,
            FrictionStatus::Slip,
            &format!("{name} end of the push"),
        )?;
        let r = last.reaction;
        let f = r[0] * h[0] + r[1] * h[1];
        lateral = lateral.max((r[1] * h[0] - r[0] * h[1]).abs() / f.abs());
        let label = if name == "penalty" {
            "F/G penalty vs 0.412371"
        } else {
            "F/G augmented vs 0.412371"
        };
        values.push(value(label, f / LOAD, reference));
    }
    values.push(error("lateral / F", lateral));
    level.values = values;
    Ok(level)
}
