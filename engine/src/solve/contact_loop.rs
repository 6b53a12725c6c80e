//! Contact iterations around the Newton loop of an increment: the
//! Lagrange-multiplier active set and the augmented-Lagrangian (Uzawa)
//! multiplier updates (seed flowcharts, "Part II – Lagrange multipliers" and
//! "Flowcharts for the penalty & Augmented Lagrangian methods").
//!
//! ```text
//! repeat
//!     Newton loop with the active set and the multipliers lambda* fixed
//!     introduce the constraint where g < 0, release it where lambda < 0
//!     if the active set changed: (cycling guard) repeat
//!     if max |g| (closed nodes) or penetration > gmax*:
//!         lambda* <- max(0, lambda* - alpha g), repeat
//! until nothing changes
//! ```
//!
//! Cycling guard: the active sets met in the increment are remembered; if a
//! set comes back, the increment fails naming the nodes that flip, and the
//! stepper cuts it back. With `update = newton` the augmented-Lagrangian
//! multipliers are instead updated inside the Newton loop
//! ([`crate::contact::augmented::uzawa_update`] called at every iteration).
//!
//! Every Lagrange pair's active set is decided inside the Newton loop, by
//! the semi-smooth Newton of [`crate::contact::semismooth`]: a converged
//! Newton loop has a set this loop leaves as it is, but for the nodes the
//! semi-smooth decision froze (its cycle guard) and a round-off tensile
//! multiplier; this loop decides those, and the friction statuses.
//!
//! The loop drives a [`NewtonLoop`] (the solver of one Newton loop) and
//! changes only the contact state it exposes: it never reaches into the
//! Newton solver, and the Newton solver never calls back into it. The
//! contact laws give their constraint rows in node terms
//! ([`crate::contact::rows`]); only `contact_assembly` maps them to dofs.
//!
//! Sign convention: `lambda >= 0` is a compressive normal force; the force
//! of the tool on a node is `lambda n`.

use super::newton::{Converged, Failure, FailureKind};
use super::Observer;
use crate::contact::augmented::uzawa_update;
use crate::contact::{NodeContact, PairState};
use crate::model::{ContactMethod, Model, MultiplierUpdate, NewtonSettings};

/// The solver of one Newton loop, as the contact loop sees it.
pub trait NewtonLoop {
    /// One Newton loop at time `t` with the Lagrange active sets and the
    /// multipliers `lambda*` of `update = converged` pairs fixed.
    fn newton_loop(
        &mut self,
        settings: &NewtonSettings,
        t: f64,
        step: usize,
        increment: usize,
        observer: &mut dyn Observer,
    ) -> Result<Converged, Failure>;
    /// The model, the contact state of every pair and its evaluation at
    /// the state the last Newton loop converged to.
    fn contact_state(&mut self) -> (&Model, &mut [PairState], &[Vec<NodeContact>]);
}

/// Newton loops allowed per increment attempt (active-set changes plus
/// Uzawa updates) before the attempt fails.
pub const MAX_CONTACT_ITERATIONS: usize = 50;

/// Gap below which an inactive Lagrange node is introduced, relative to the
/// size of the mesh (round-off level: a released node sitting exactly on
/// the tool is not re-introduced by a gap of -1e-17).
const INTRODUCE_GAP: f64 = 1e-14;

/// What an active-set update changed: global nodes introduced and released.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SetChange {
    /// Nodes introduced (`g < 0`).
    pub introduced: Vec<usize>,
    /// Nodes released (`lambda < 0`, or out of the search window).
    pub released: Vec<usize>,
}

impl SetChange {
    /// Whether the set changed.
    pub fn is_empty(&self) -> bool {
        self.introduced.is_empty() && self.released.is_empty()
    }
}

/// Size of the model (bounding-box diagonal of the mesh), the length scale
/// of the introduction threshold.
fn model_size(model: &Model) -> f64 {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in &model.mesh.nodes {
        for c in 0..2 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    let d = ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2)).sqrt();
    if d.is_finite() && d > 0.0 {
        d
    } else {
        1.0
    }
}

/// The gap below which an inactive Lagrange node of `model` is introduced
/// (round-off of the model's size).
pub fn introduce_threshold(model: &Model) -> f64 {
    INTRODUCE_GAP * model_size(model)
}

/// Introduces the inactive Lagrange nodes that penetrate, releases the
/// active ones in tension (`lambda < 0`) or no longer found by the search.
pub fn update_active_sets(
    model: &Model,
    pairs: &mut [PairState],
    contact: &[Vec<NodeContact>],
) -> SetChange {
    let mut change = SetChange::default();
    let lagrange =
        |c: &crate::model::ContactPair| matches!(c.method, ContactMethod::Lagrange { .. });
    if !model.contacts.iter().any(lagrange) {
        return change;
    }
    let threshold = INTRODUCE_GAP * model_size(model);
    for (pi, cp) in model.contacts.iter().enumerate() {
        if !matches!(cp.method, ContactMethod::Lagrange { .. }) {
            continue;
        }
        let state = &mut pairs[pi];
        let mut seen = vec![false; state.slaves.len()];
        for nc in &contact[pi] {
            let Some(i) = state.slave_index(nc.node) else {
                continue;
            };
            seen[i] = true;
            if state.active[i] {
                if state.multiplier[i] < 0.0 {
                    state.active[i] = false;
                    state.multiplier[i] = 0.0;
                    change.released.push(nc.node);
                }
            } else if nc.gap < -threshold {
                state.active[i] = true;
                state.multiplier[i] = 0.0;
                change.introduced.push(nc.node);
            }
        }
        for (i, s) in seen.iter().enumerate() {
            if !s && state.active[i] {
                state.active[i] = false;
                state.multiplier[i] = 0.0;
                change.released.push(state.slaves[i]);
            }
        }
    }
    change
}

/// Cycling guard: the active sets met during one increment attempt.
#[derive(Debug, Clone)]
pub struct CyclingGuard {
    seen: Vec<Vec<bool>>,
}

impl CyclingGuard {
    /// Starts with the set the increment begins with.
    pub fn new(initial: Vec<bool>) -> Self {
        CyclingGuard {
            seen: vec![initial],
        }
    }

    /// Records the set `key` reached by `change`; a set already met is an
    /// error naming the nodes that flip.
    pub fn visit(&mut self, key: Vec<bool>, change: &SetChange) -> Result<(), String> {
        if self.seen.contains(&key) {
            let mut flip = change.introduced.clone();
            flip.extend(&change.released);
            flip.sort_unstable();
            return Err(format!(
                "the contact active set cycles (a set already met in this increment came back \
                 after {} active-set changes): nodes {:?} are introduced and released in turn",
                self.seen.len(),
                flip
            ));
        }
        self.seen.push(key);
        Ok(())
    }
}

/// The active sets of all pairs, concatenated (for the cycling guard),
/// then the friction stick/slip statuses.
pub fn active_key(pairs: &[PairState]) -> Vec<bool> {
    pairs
        .iter()
        .flat_map(|p| p.active.iter().copied())
        .chain(crate::contact::friction_lagrange::status_key(
            pairs.iter().map(|p| &p.friction),
        ))
        .collect()
}

/// Solves one increment attempt: Newton loops until the Lagrange active
/// sets are stable and the augmented-Lagrangian penetrations are below
/// their tolerances (a single Newton loop for penalty-only models).
pub fn attempt(
    solver: &mut dyn NewtonLoop,
    settings: &NewtonSettings,
    t: f64,
    step: usize,
    increment: usize,
    observer: &mut dyn Observer,
) -> Result<Converged, Failure> {
    let mut residuals: Vec<f64> = Vec::new();
    let mut iterations = 0;
    let mut updates = 0;
    let mut guard = CyclingGuard::new(active_key(solver.contact_state().1));
    for _ in 0..MAX_CONTACT_ITERATIONS {
        let conv = solver
            .newton_loop(settings, t, step, increment, observer)
            .map_err(|mut f| {
                let mut r = residuals.clone();
                r.append(&mut f.residuals);
                f.residuals = r;
                f
            })?;
        iterations += conv.iterations;
        updates += conv.contact_iterations;
        residuals.extend_from_slice(&conv.residuals);
        let (model, pairs, contact) = solver.contact_state();
        // the contact and friction loops in one pass: the stick/slip
        // statuses of the nodes that stay closed are decided on the same
        // solution as the active set (see `friction_lagrange`)
        let mut change = update_active_sets(model, pairs, contact);
        change
            .introduced
            .extend(crate::contact::friction_lagrange::update_status(
                model,
                pairs,
                contact,
                INTRODUCE_GAP * model_size(model),
            ));
        if !change.is_empty() {
            updates += 1;
            if let Err(detail) = guard.visit(active_key(pairs), &change) {
                return Err(Failure {
                    kind: FailureKind::ActiveSetCycling,
                    residuals,
                    detail,
                });
            }
            continue;
        }
        if uzawa_update(model, pairs, contact, MultiplierUpdate::Converged) {
            updates += 1;
            continue;
        }
        return Ok(Converged {
            iterations,
            residuals,
            active_contacts: conv.active_contacts,
            contact_iterations: updates,
            max_penetration: conv.max_penetration,
        });
    }
    Err(Failure {
        kind: FailureKind::MaxIterations,
        residuals,
        detail: format!(
            "the contact iterations (active set / Uzawa updates) did not settle in \
             {MAX_CONTACT_ITERATIONS} Newton loops"
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::augmented::{constraint_violation, max_penetration};
    use crate::contact::ContactStatus;
    use crate::contact::NodeContact;
    use crate::mesh::Mesh;
    use crate::model::*;

    fn nc(node: usize, gap: f64, closed: bool) -> NodeContact {
        NodeContact {
            node,
            gap,
            normal: [0.0, 1.0],
            force: [0.0; 2],
            stiffness: [[0.0; 2]; 2],
            pressure: 0.0,
            status: if closed {
                ContactStatus::Closed
            } else {
                ContactStatus::Open
            },
            entity: 0,
            master: None,
            friction: Default::default(),
        }
    }

    /// Three slave nodes on y = 0 against a floor, with `method`.
    fn model(method: ContactMethod) -> Model {
        crate::testkit::ModelBuilder::plane_strain()
            .elastic("m", 1.0, 0.3)
            .body(
                "s",
                Mesh::new(vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], vec![]),
                "m",
            )
            .tool(
                "floor",
                ToolGeometry::Plane {
                    point: [0.0, 0.0],
                    normal: [0.0, 1.0],
                },
                ToolMotion::fixed(),
            )
            .contact_tool("s -> floor", "s", vec![[0, 1], [1, 2]], "floor", method)
            .build()
    }

    #[test]
    fn active_set_introduces_penetrating_and_releases_tensile_nodes() {
        let m = model(ContactMethod::Lagrange {
            formulation: LagrangeFormulation::Single,
        });
        let mut pairs = vec![PairState::new(&m, 0)];
        pairs[0].active = vec![true, true, false];
        pairs[0].multiplier = vec![2.0, -0.5, 0.0];
        // node 1 in tension -> released; node 2 penetrating -> introduced;
        // node 0 stays; a round-off gap does not introduce
        let contact = vec![vec![
            nc(0, 0.0, true),
            nc(1, 0.0, true),
            nc(2, -1e-3, false),
        ]];
        let change = update_active_sets(&m, &mut pairs, &contact);
        assert_eq!(change.introduced, vec![2]);
        assert_eq!(change.released, vec![1]);
        assert_eq!(pairs[0].active, vec![true, false, true]);
        assert_eq!(pairs[0].multiplier, vec![2.0, 0.0, 0.0]);
        let contact = vec![vec![
            nc(0, 0.0, true),
            nc(1, -1e-17, false),
            nc(2, 0.0, true),
        ]];
        assert!(update_active_sets(&m, &mut pairs, &contact).is_empty());
        // an active node the search no longer finds is released
        let contact = vec![vec![nc(0, 0.0, true), nc(1, 0.1, false)]];
        let change = update_active_sets(&m, &mut pairs, &contact);
        assert_eq!(change.released, vec![2]);
    }

    #[test]
    fn cycling_guard_reports_the_flipping_nodes() {
        let mut g = CyclingGuard::new(vec![false, false]);
        let add = SetChange {
            introduced: vec![7],
            released: vec![],
        };
        let swap = SetChange {
            introduced: vec![3],
            released: vec![7],
        };
        g.visit(vec![true, false], &add).unwrap();
        g.visit(vec![false, true], &swap).unwrap();
        let back = SetChange {
            introduced: vec![7],
            released: vec![3],
        };
        let e = g.visit(vec![true, false], &back).unwrap_err();
        assert!(e.contains("nodes [3, 7]"), "{e}");
    }

    #[test]
    fn uzawa_update_shifts_multipliers_until_within_tolerance() {
        let m = model(ContactMethod::AugmentedLagrange {
            kind: PenaltyKind::Nodal,
            penalty: 100.0,
            tolerance: 1e-3,
            update: MultiplierUpdate::Converged,
        });
        let mut pairs = vec![PairState::new(&m, 0)];
        pairs[0].multiplier = vec![1.0, 0.0, 0.5];
        let contact = vec![vec![
            nc(0, -0.01, true),
            nc(1, 0.2, false),
            nc(2, 0.001, true),
        ]];
        // the other mode does nothing
        assert!(!uzawa_update(
            &m,
            &mut pairs,
            &contact,
            MultiplierUpdate::Newton
        ));
        assert!(uzawa_update(
            &m,
            &mut pairs,
            &contact,
            MultiplierUpdate::Converged
        ));
        // lambda* <- max(0, lambda* - alpha g): 1 + 1, 0, 0.5 - 0.1
        let l = &pairs[0].multiplier;
        assert!((l[0] - 2.0).abs() < 1e-14 && l[1] == 0.0 && (l[2] - 0.4).abs() < 1e-14);
        // within tolerance: no update
        let ok = vec![vec![nc(0, -1e-4, true), nc(2, 5e-4, true)]];
        assert!(!uzawa_update(
            &m,
            &mut pairs,
            &ok,
            MultiplierUpdate::Converged
        ));
        assert_eq!(constraint_violation(&contact[0]), 0.01);
        assert_eq!(max_penetration(&contact[0]), 0.01);
    }

    #[test]
    fn multipliers_and_active_set_roll_back_with_the_increment() {
        let m = model(ContactMethod::Lagrange {
            formulation: LagrangeFormulation::Doubled,
        });
        let mut s = PairState::new(&m, 0);
        s.active[1] = true;
        s.multiplier[1] = 3.0;
        s.commit();
        s.active[2] = true;
        s.multiplier[1] = 5.0;
        s.rollback();
        assert_eq!(s.active, vec![false, true, false]);
        assert_eq!(s.multiplier, vec![0.0, 3.0, 0.0]);
    }
}
