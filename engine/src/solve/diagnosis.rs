//! Why a run failed, in words: the likely cause and the remedy printed with
//! the final error. First the contact health of the failed increment
//! ([`contact_cause`]): nodes whose contact status flipped between Newton
//! iterations (chattering) and the ratio of the penalty stiffness to the
//! element stiffness at the contact nodes (a ratio far above ~1e4 makes the
//! tangent ill-conditioned and the open/closed decision of a node flip on
//! round-off-sized gaps); otherwise the failure's kind and residual history
//! ([`failure_cause`]).

use super::contact_assembly::ContactAssembly;
use super::linalg::{Scatter, NO_SLOT};
use super::newton::{Failure, FailureKind};
use crate::contact::{ContactStatus, NodeContact};
use crate::model::{ContactMethod, Model, NewtonSettings};
use std::collections::{BTreeMap, BTreeSet};

/// Floor of norms used as denominators.
const TINY: f64 = 1e-300;

/// Penalty-to-element stiffness ratio above which the penalty is named as
/// the likely cause.
pub const RATIO_TOO_HIGH: f64 = 1e5;
/// Ratio suggested as the remedy (penetration ~1e-3 of the local elastic
/// deflection, well-conditioned tangent).
pub const RATIO_SUGGESTED: f64 = 1e3;
/// Nodes listed in a message.
const LISTED: usize = 8;

/// Counts contact status flips per node between consecutive Newton
/// iterations, over the failed attempts since the last converged increment,
/// and the switches of a closed node from one master entity (segment) to
/// another with its status unchanged (the normal of a faceted master jumps
/// at a vertex: a 2-cycle without any status change).
#[derive(Debug, Clone, Default)]
pub struct FlipTracker {
    /// Closed nodes at the previous iteration of the current attempt.
    prev: Option<BTreeSet<usize>>,
    /// Flips per node.
    flips: BTreeMap<usize, usize>,
    /// Master entity of each closed node (deformable masters) at the
    /// previous iteration: node -> (pair, entity).
    prev_entity: BTreeMap<usize, (usize, usize)>,
    /// Entity switches per node: (pair, count, entities met).
    switches: BTreeMap<usize, (usize, usize, BTreeSet<usize>)>,
}

/// A closed node that changed master entity between iterations.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EntitySwitch {
    /// Global node number.
    pub node: usize,
    /// Contact pair index.
    pub pair: usize,
    /// Switches counted.
    pub count: usize,
    /// Master entities (segments) the node went to and fro between.
    pub entities: Vec<usize>,
}

impl FlipTracker {
    /// A new attempt starts (from the converged state).
    pub fn start_attempt(&mut self) {
        self.prev = None;
        self.prev_entity.clear();
    }

    /// An increment converged: forget everything.
    pub fn clear(&mut self) {
        self.prev = None;
        self.flips.clear();
        self.prev_entity.clear();
        self.switches.clear();
    }

    /// Closed nodes that switched master entity at least twice with their
    /// status unchanged, most switches first.
    pub fn entity_switches(&self) -> Vec<EntitySwitch> {
        let mut v: Vec<EntitySwitch> = self
            .switches
            .iter()
            .filter(|(_, (_, c, _))| *c >= 2)
            .map(|(n, (p, c, e))| EntitySwitch {
                node: *n,
                pair: *p,
                count: *c,
                entities: e.iter().copied().collect(),
            })
            .collect();
        v.sort_by(|a, b| b.count.cmp(&a.count).then(a.node.cmp(&b.node)));
        v
    }

    /// Records the statuses of one iteration.
    pub fn record<const D: usize>(&mut self, contact: &[Vec<NodeContact<D>>]) {
        let closed: BTreeSet<usize> = contact
            .iter()
            .flatten()
            .filter(|c| c.status == ContactStatus::Closed)
            .map(|c| c.node)
            .collect();
        if let Some(prev) = &self.prev {
            for n in prev.symmetric_difference(&closed) {
                *self.flips.entry(*n).or_default() += 1;
            }
        }
        self.prev = Some(closed);
        let mut now = BTreeMap::new();
        for (p, list) in contact.iter().enumerate() {
            for c in list {
                if c.status == ContactStatus::Closed && c.master.is_some() {
                    now.insert(c.node, (p, c.entity));
                }
            }
        }
        for (n, &(p, e)) in &now {
            if let Some(&(q, f)) = self.prev_entity.get(n) {
                if q == p && f != e {
                    let s = self.switches.entry(*n).or_insert((p, 0, BTreeSet::new()));
                    s.1 += 1;
                    s.2.insert(e);
                    s.2.insert(f);
                }
            }
        }
        self.prev_entity = now;
    }

    /// Nodes that flipped at least twice (node, flips), most flips first.
    pub fn chattering(&self) -> Vec<(usize, usize)> {
        let mut v: Vec<(usize, usize)> = self
            .flips
            .iter()
            .filter(|(_, f)| **f >= 2)
            .map(|(n, f)| (*n, *f))
            .collect();
        v.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
        v
    }
}

/// The stiffest penalty relative to the element stiffness.
#[derive(Debug, Clone, PartialEq)]
pub struct PenaltyRatio {
    /// `alpha_eff / K_elem`: nodal penalty coefficient over the element
    /// stiffness diagonal at the node.
    pub ratio: f64,
    /// Node where the ratio is largest.
    pub node: usize,
    /// Contact pair name.
    pub pair: String,
    /// The pair's penalty value as given in the deck.
    pub stiffness: f64,
}

/// The largest ratio of a penalty coefficient `alpha_eff` to the element
/// stiffness diagonal at its node, over the penalty and augmented
/// Lagrangian pairs of `contacts` at its last evaluated state, with the
/// tangent `values` of the last iteration (slots of `scatter`).
pub fn penalty_ratio(
    model: &Model,
    contacts: &ContactAssembly,
    scatter: &Scatter,
    values: &[f64],
) -> Option<PenaltyRatio> {
    let mut best: Option<PenaltyRatio> = None;
    for (p, list) in contacts.contact.iter().enumerate() {
        let cp = &model.contacts[p];
        let stiffness = match cp.method {
            ContactMethod::Penalty { stiffness, .. } => stiffness,
            ContactMethod::AugmentedLagrange { penalty, .. } => penalty,
            ContactMethod::Lagrange { .. } => continue,
        };
        for nc in list {
            let Some(i) = contacts.pairs[p].slave_index(nc.node) else {
                continue;
            };
            let trib = contacts.pairs[p].tributary.get(i).copied().unwrap_or(0.0);
            let alpha = crate::contact::penalty::effective_stiffness(&cp.method_at(nc.node), trib);
            let slots = scatter.node_slots(nc.node);
            let k_elem = [0, 3]
                .iter()
                .zip([nc.stiffness[0][0], nc.stiffness[1][1]])
                .filter(|(s, _)| slots[**s] != NO_SLOT)
                .map(|(s, kc)| values[slots[*s] as usize] - kc)
                .fold(0.0, f64::max);
            if k_elem <= 0.0 || !alpha.is_finite() {
                continue;
            }
            let ratio = alpha / k_elem;
            if best.as_ref().is_none_or(|b| ratio > b.ratio) {
                best = Some(PenaltyRatio {
                    ratio,
                    node: nc.node,
                    pair: cp.name.clone(),
                    stiffness,
                });
            }
        }
    }
    best
}

/// Likely cause and remedy from the contact health, or `None` when the
/// contact does not explain the failure. `pair_name` names pair `i`;
/// `smoothed` says whether pair `i` already smooths its master's normal.
pub fn contact_cause(
    ratio: Option<&PenaltyRatio>,
    flips: &FlipTracker,
    pair_name: &dyn Fn(usize) -> String,
    smoothed: &dyn Fn(usize) -> bool,
) -> Option<(String, String)> {
    let chatter = flips.chattering();
    let switches = flips.entity_switches();
    let nodes = |v: &[(usize, usize)]| {
        let list: Vec<String> = v
            .iter()
            .take(LISTED)
            .map(|(n, f)| format!("{n} ({f}x)"))
            .collect();
        let more = v.len().saturating_sub(LISTED);
        if more > 0 {
            format!("[{}, and {more} more]", list.join(", "))
        } else {
            format!("[{}]", list.join(", "))
        }
    };
    let chatter_text = if chatter.is_empty() {
        "no node changed contact status back and forth".to_string()
    } else {
        format!(
            "contact status chattering on nodes {} (status flips in the failed iterations)",
            nodes(&chatter)
        )
    };
    match ratio {
        Some(r) if r.ratio > RATIO_TOO_HIGH => {
            let suggested = r.stiffness * RATIO_SUGGESTED / r.ratio;
            Some((
                format!(
                    "penalty too high for this mesh: alpha_eff / element stiffness ~ {:.0e} \
                     (pair `{}`, node {}); {chatter_text}",
                    r.ratio, r.pair, r.node
                ),
                format!(
                    "try stiffness <= {suggested:.1e} for pair `{}` (alpha_eff / element \
                     stiffness ~ {RATIO_SUGGESTED:.0e}), or `method = augmented_lagrange {{ penalty \
                     = {suggested:.1e} }}` / `method = lagrange` for an exact contact condition",
                    r.pair
                ),
            ))
        }
        _ if !chatter.is_empty() => Some((
            format!(
                "{chatter_text}: the contact zone does not settle within the increment{}",
                ratio.map_or(String::new(), |r| format!(
                    " (alpha_eff / element stiffness ~ {:.0e}, pair `{}`)",
                    r.ratio, r.pair
                ))
            ),
            "use more `increments` (smaller contact changes per increment), or \
             `method = augmented_lagrange` for this pair"
                .into(),
        )),
        _ if !switches.is_empty() => {
            let first = &switches[0];
            let list: Vec<String> = switches
                .iter()
                .take(LISTED)
                .map(|s| format!("{} ({}x, segments {:?})", s.node, s.count, s.entities))
                .collect();
            let more = switches.len().saturating_sub(LISTED);
            let more = if more > 0 {
                format!(", and {more} more")
            } else {
                String::new()
            };
            Some((
                format!(
                    "no contact status changes, but closed slave nodes go back and forth between \
                     master segments (pair `{}`): nodes [{}{more}]; the normal of a faceted \
                     master surface jumps at the vertex between two segments (a slave node \
                     over a master node), so the contact force changes direction from one \
                     iteration to the next",
                    pair_name(first.pair),
                    list.join(", ")
                ),
                if smoothed(first.pair) {
                    // issue 18: the smoothed normal, its gap and friction
                    // basis are continuous across the master nodes, and a
                    // node on a vertex to round-off keeps its segment
                    // (`node_to_segment::VERTEX_TIE`): what switches here
                    // goes to and fro across a vertex by more than that
                    format!(
                        "pair `{}` already smooths its normal (continuous normal, gap and \
                         friction across the master nodes; a node on a vertex to round-off \
                         keeps its segment): the nodes cross master vertices back and forth; \
                         use more `increments`, refine the master surface, or use \
                         `formulation = mortar`",
                        pair_name(first.pair)
                    )
                } else {
                    format!(
                        "set `smoothing = nodal` in the contact block of pair `{}` (a normal \
                         continuous across the master nodes), or refine the master surface",
                        pair_name(first.pair)
                    )
                },
            ))
        }
        _ => None,
    }
}

/// The remedy of a singular failure at the start of step `step` (time
/// `time`) when a body's own `fix`/`displace` conditions leave it free,
/// only contact can hold it and none of its pairs had a closed node at the
/// start of the analysis (`start_closed`: closed nodes per pair, the
/// touching start included), and the step has no stabilization: `newton {
/// stabilize }`, naming the bodies; `None` otherwise (a body free along a
/// direction its closed contact cannot hold needs a `fix`).
pub fn stabilize_hint<const D: usize>(
    model: &crate::model::Model<D>,
    failure: &Failure,
    step: &crate::model::Step,
    time: f64,
    start_closed: &[usize],
) -> Option<String> {
    let at_start = (time - step.t_start).abs() <= 1e-12 * (step.t_end - step.t_start).abs();
    if failure.kind != FailureKind::Singular || !at_start || step.newton.stabilize.is_some() {
        return None;
    }
    let held = super::check::held_only_by_contact(model);
    let open_at_start = |b: usize| {
        model.contacts.iter().enumerate().all(|(i, c)| {
            let involved = c.body == b
                || matches!(&c.master, crate::model::ContactMaster::Surface { body, .. } if *body == b);
            !involved || start_closed.get(i).copied().unwrap_or(0) == 0
        })
    };
    let bodies: Vec<String> = model
        .bodies
        .iter()
        .zip(&held)
        .enumerate()
        .filter(|(i, (_, h))| **h && open_at_start(*i))
        .map(|(_, (b, _))| format!("`{}`", b.name))
        .collect();
    if bodies.is_empty() || model.contacts.is_empty() {
        return None;
    }
    Some(format!(
        "{} {} held only by contact, which is still open at t = {time}: add `newton {{ \
         stabilize }}` to step `{}` (springs on the increment displacement of these bodies, \
         ramped to 0 at the step's end, their energy reported), or start the bodies touching \
         (a gap within {} x the smallest slave edge counts as closed at the start)",
        bodies.join(", "),
        if bodies.len() == 1 { "is" } else { "are" },
        step.name,
        crate::contact::penalty::TOUCH_FRACTION
    ))
}

/// Likely cause and remedy of a failed increment when the contact health
/// does not explain it (see [`contact_cause`]), from the failure's kind and
/// residual history, for the final error message. `floor` is the round-off
/// floor of the relative residual at the last evaluation
/// (`newton::convergence`; 0: unknown).
pub fn failure_cause(failure: &Failure, settings: &NewtonSettings, floor: f64) -> (String, String) {
    let last = failure.residuals.last().copied().unwrap_or(f64::NAN);
    match failure.kind {
        FailureKind::MaxIterations | FailureKind::Diverged if stagnates(&failure.residuals) => {
            let floor_text = if floor > 0.0 {
                format!(
                    " ({:.1}x the round-off floor {floor:.1e} = 4 eps |K| |x| / force scale: the \
                     residual cannot be computed more accurately)",
                    last / floor
                )
            } else {
                String::new()
            };
            (
                format!(
                    "the residual stagnates at {last:.1e}{floor_text}: tol = {:.0e} (or \
                     tol_displacement = {:.0e}) is below what round-off allows for this problem; \
                     more increments do not lower it",
                    settings.tol, settings.tol_displacement
                ),
                format!(
                    "raise `newton {{ tol = .. }}` to {:.0e} or more (1e-8 is usual), or lower a \
                     very stiff penalty (the floor grows with it)",
                    (10.0 * last).max(settings.tol)
                ),
            )
        }
        FailureKind::MaxIterations | FailureKind::Diverged if plateau(&failure.residuals) => {
            let n = failure.residuals.len();
            let flat = failure
                .residuals
                .iter()
                .rev()
                .take_while(|r| (*r / last - 1.0).abs() <= PLATEAU)
                .count();
            (
                format!(
                    "the residual stalls at {last:.2e} for its last {flat} of {n} iterations, \
                     far above round-off: the Newton steps no longer lower it, so the tangent does not describe the residual there \
                     -- a force that is not differentiable at the solution, typically a \
                     contact or friction node sitting on its switching point (the gap at 0, \
                     the tangential force on the Coulomb cone); a smaller increment did not \
                     move it off"
                ),
                "try another contact method for the pair (`augmented_lagrange` or `penalty` \
                 with another stiffness), change the friction coefficient or the increment \
                 size of the step so the node does not land on the switching point, or accept \
                 the stalled value: `newton { tol = .. }` above it"
                    .into(),
            )
        }
        FailureKind::MaxIterations => (
            "the increment is too large for the nonlinearity (no contact node changed \
             status back and forth; a large load or contact change, a stiff penalty)"
                .into(),
            "use more `increments`, keep `line_search = true`, raise `max_iter`, or \
             lower the penalty stiffness"
                .into(),
        ),
        FailureKind::Diverged => (
            "the residual grows from iteration to iteration: the load or contact \
             increment is too large, or the penalty stiffness is too high for the mesh"
                .into(),
            "use more `increments`, a smaller penalty stiffness, `line_search = true`".into(),
        ),
        FailureKind::NotFinite | FailureKind::Singular => (
            "the stiffness matrix is singular or nearly so: a body (or part of one) can \
             move rigidly (not enough `fix`/`displace`, or a body held only by a contact \
             that is still open)"
                .into(),
            "constrain every rigid-body motion (e.g. `fix` one node in x), or start the \
             contact closed"
                .into(),
        ),
        FailureKind::LinearSolver => (
            "the iterative linear solver did not converge (not the Newton loop: each \
             linear solve stopped before its tolerance, and a smaller increment did not \
             help)"
                .into(),
            "allow more Krylov iterations (`-ksp_max_it`), a looser `-ksp_rtol`, a stronger \
             preconditioner, or the direct solver (`--solver petsc` without `-ksp_type`: \
             MUMPS LU)"
                .into(),
        ),
        FailureKind::ActiveSetCycling => (
            "the contact active set cycles: nodes are introduced and released in turn \
             (a node close to the contact boundary, or an increment too large for the \
             change of contact zone)"
                .into(),
            "use more `increments`; if it persists, use `augmented_lagrange` or \
             `penalty` for this pair"
                .into(),
        ),
        FailureKind::ErrorEstimate => (
            "the local error estimate of adaptive stepping stays above `error_tol` down to \
             `dt_min`"
                .into(),
            "raise `error_tol` or lower `dt_min`".into(),
        ),
        FailureKind::Rotation => (
            "a cell turns by more than `max_rotation` per increment down to the smallest \
             increment"
                .into(),
            "raise `max_rotation` or lower `dt_min` / `min_increment`".into(),
        ),
        FailureKind::Energy => (
            "increments create more energy than `energy_tol` allows down to the smallest \
             increment"
                .into(),
            "raise `energy_tol` or lower `dt_min` / `min_increment`".into(),
        ),
        FailureKind::ImpactCut => (
            "increments are cut at each first impact (`cut_at_impact = true`)".into(),
            "set `cut_at_impact = false` or use more `increments`".into(),
        ),
        FailureKind::Element => (
            "an element is inverted or degenerate (mesh or deformation)".into(),
            "check the mesh orientation and quality, or use smaller increments".into(),
        ),
    }
}

/// Relative spread under which residuals are "the same" for [`plateau`].
const PLATEAU: f64 = 1e-2;

/// Whether a residual history stalls above round-off: its last five
/// residuals within [`PLATEAU`] of the last one, that one at or above 1e-9
/// (below, [`stagnates`] names the round-off floor). Newton's divergence
/// test counts growths of the last bits of such a plateau as growth
/// (`examples/blankholder.ctc` at mu 0.05 with a cone tie in 2D rigid
/// friction: 23 iterations at 1.952e-7, reported as "the residual grows").
pub fn plateau(residuals: &[f64]) -> bool {
    let n = residuals.len();
    let last = residuals.last().copied().unwrap_or(f64::NAN);
    n >= 5
        && last >= 1e-9
        && residuals[n - 5..]
            .iter()
            .all(|r| (*r / last - 1.0).abs() <= PLATEAU)
}

/// Whether a residual history stagnates at round-off level: the last
/// three within a factor 1e3 of the last one, below 1e-9.
pub fn stagnates(residuals: &[f64]) -> bool {
    let n = residuals.len();
    let last = residuals.last().copied().unwrap_or(f64::NAN);
    n >= 3 && last < 1e-9 && residuals[n - 3..].iter().all(|r| *r < 1e3 * last.max(TINY))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nc(node: usize, closed: bool) -> NodeContact {
        NodeContact {
            node,
            gap: if closed { -1e-9 } else { 1e-9 },
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

    #[test]
    fn chattering_nodes_are_counted_per_attempt_and_ranked() {
        let mut t = FlipTracker::default();
        t.start_attempt();
        t.record(&[vec![nc(1, true), nc(2, false)]]);
        t.record(&[vec![nc(1, true), nc(2, true)]]);
        t.record(&[vec![nc(1, true), nc(2, false)]]);
        t.record(&[vec![nc(1, false), nc(2, true)]]);
        // a new attempt does not count a flip against the last iteration
        t.start_attempt();
        t.record(&[vec![nc(1, true)]]);
        assert_eq!(t.chattering(), vec![(2, 3)]);
        t.clear();
        assert!(t.chattering().is_empty());
    }

    #[test]
    fn a_node_switching_master_segments_without_status_change_is_named() {
        // issue 14 item 5: node 158 over master node 144 alternates between
        // segments 7 and 8, closed throughout
        let on = |entity| NodeContact {
            entity,
            master: Some(crate::contact::MasterSegment {
                nodes: [144, 145],
                xi: 1.0,
                forces: [[0.0; 2]; 2],
                tangent: [[0.0; 6]; 6],
                gap_gradient: [0.0; 6],
            }),
            ..nc(158, true)
        };
        let mut t = FlipTracker::default();
        t.start_attempt();
        for e in [7, 8, 7, 8] {
            t.record(&[vec![on(e), nc(3, true)]]);
        }
        assert!(t.chattering().is_empty());
        let s = t.entity_switches();
        assert_eq!(s.len(), 1);
        assert_eq!(
            (s[0].node, s[0].count, s[0].entities.clone()),
            (158, 3, vec![7, 8])
        );
        let (cause, remedy) =
            contact_cause(None, &t, &|_| "punch -> block".into(), &|_| false).unwrap();
        assert!(cause.starts_with("no contact status changes"), "{cause}");
        assert!(cause.contains("158 (3x, segments [7, 8])"), "{cause}");
        assert!(!cause.contains("chattering"), "{cause}");
        assert!(remedy.contains("smoothing = nodal"), "{remedy}");
        // a pair that already smooths is not told to smooth
        let (_, remedy) = contact_cause(None, &t, &|_| "punch -> block".into(), &|_| true).unwrap();
        assert!(!remedy.contains("set `smoothing"), "{remedy}");
        assert!(remedy.contains("already smooths"), "{remedy}");
        // a new attempt does not count a switch against the last iteration
        t.start_attempt();
        t.record(&[vec![on(9)]]);
        assert_eq!(t.entity_switches()[0].count, 3);
    }

    #[test]
    fn penalty_1e6_times_element_stiffness_is_named_with_a_remedy() {
        let mut t = FlipTracker::default();
        t.record(&[vec![nc(7, true)]]);
        t.record(&[vec![nc(7, false)]]);
        t.record(&[vec![nc(7, true)]]);
        let r = PenaltyRatio {
            ratio: 2e6,
            node: 7,
            pair: "top-punch".into(),
            stiffness: 2.5e10,
        };
        let (cause, remedy) = contact_cause(Some(&r), &t, &|_| "p".into(), &|_| false).unwrap();
        assert!(
            cause.starts_with("penalty too high for this mesh"),
            "{cause}"
        );
        assert!(
            cause.contains("~ 2e6") && cause.contains("7 (2x)"),
            "{cause}"
        );
        assert!(remedy.contains("stiffness <= 1.2e7"), "{remedy}");
        assert!(remedy.contains("augmented_lagrange"));
        // a moderate penalty without chattering does not explain a failure
        let soft = PenaltyRatio { ratio: 10.0, ..r };
        assert!(contact_cause(
            Some(&soft),
            &FlipTracker::default(),
            &|_| "p".into(),
            &|_| false
        )
        .is_none());
    }

    #[test]
    fn a_residual_stalled_at_round_off_names_the_floor_not_more_increments() {
        let f = Failure::new(FailureKind::MaxIterations, "no convergence")
            .with_residuals(&[1e-3, 2e-10, 3e-10, 2.5e-10]);
        let settings = NewtonSettings {
            tol: 1e-12,
            ..NewtonSettings::default()
        };
        let (cause, remedy) = failure_cause(&f, &settings, 1e-10);
        assert!(cause.contains("stagnates at 2.5e-10"), "{cause}");
        assert!(
            cause.contains("2.5x the round-off floor 1.0e-10"),
            "{cause}"
        );
        assert!(cause.contains("more increments do not lower it"), "{cause}");
        assert!(
            remedy.contains("tol = .. }` to ") && remedy.contains("e-9 or more"),
            "{remedy}"
        );
        assert!(!remedy.contains("increments"), "{remedy}");
        // growth at round-off level is stagnation too (not "diverging")
        let grew =
            Failure::new(FailureKind::Diverged, "grew").with_residuals(&[1e-14, 2e-14, 4e-14]);
        assert!(failure_cause(&grew, &settings, 0.0).0.contains("stagnates"));
    }

    /// The final diagnosis of `examples/blankholder.ctc` at mu 0.05 with
    /// a cone tie tried in 2D rigid friction: the relative residual sat at
    /// 1.952e-7 from its third iteration to its 25th, and the divergence
    /// test fired on growths of its last bits; it was reported as "the
    /// residual grows ... the increment is too large". A plateau far
    /// above round-off is a stall: named as such, with the switching
    /// point as the likely cause. A residual that really grows, or falls,
    /// is not one.
    #[test]
    fn a_residual_stalled_far_above_round_off_is_named_a_stall_not_a_divergence() {
        let settings = NewtonSettings::default();
        let mut stalled = vec![1.68e-3, 9.66e-7];
        stalled.extend((0..23).map(|k| 1.952e-7 * (1.0 + 1e-12 * f64::from(k % 3))));
        let f = Failure::new(FailureKind::Diverged, "grew").with_residuals(&stalled);
        let (cause, remedy) = failure_cause(&f, &settings, 1e-12);
        assert!(cause.contains("stalls at 1.95e-7"), "{cause}");
        assert!(cause.contains("last 23 of 25 iterations"), "{cause}");
        assert!(cause.contains("switching point"), "{cause}");
        assert!(!cause.contains("grows"), "{cause}");
        assert!(remedy.contains("another contact method"), "{remedy}");
        // growing, falling or round-off histories are not plateaus
        let grows = [1e-3, 2e-3, 4e-3, 8e-3, 1.6e-2, 3.2e-2];
        assert!(!plateau(&grows));
        let g = Failure::new(FailureKind::Diverged, "grew").with_residuals(&grows);
        assert!(failure_cause(&g, &settings, 0.0).0.contains("grows"));
        assert!(!plateau(&[1e-3, 5e-4, 2.5e-4, 1.2e-4, 6e-5, 3e-5]));
        assert!(!plateau(&[2e-12; 6]));
        assert!(!plateau(&[1e-7; 4]));
    }

    #[test]
    fn a_krylov_solve_that_stopped_is_named_as_such_not_as_a_singular_matrix() {
        // `--solver petsc -- -ksp_max_it 2`: PETSc's DIVERGED_ITS reaches the
        // Newton loop as FailureKind::LinearSolver (issue 21)
        let settings = NewtonSettings::default();
        let f = Failure::new(
            FailureKind::LinearSolver,
            "PETSc: the Krylov solver did not converge: DIVERGED_ITS (-3) after 2 iterations",
        );
        let (cause, remedy) = failure_cause(&f, &settings, 0.0);
        assert!(
            cause.contains("the iterative linear solver did not converge"),
            "{cause}"
        );
        assert!(!cause.contains("singular"), "{cause}");
        assert!(remedy.contains("-ksp_max_it"), "{remedy}");
        let (cause, _) = failure_cause(&Failure::new(FailureKind::Singular, ""), &settings, 0.0);
        assert!(cause.contains("singular"), "{cause}");
    }
}
