//! Increment predictor: the first iterate of an increment extrapolated from
//! the converged history (Abaqus' `*STEP, EXTRAPOLATION = LINEAR`).
//!
//! Within a step, an increment `t_n -> t` whose previous increment
//! `t_{n-1} -> t_n` converged in the same step starts from
//!
//! ```text
//! u_pred = u_n + (t - t_n) / (t_n - t_{n-1}) (u_n - u_{n-1})   (free dofs)
//! u_pred = u(t)                                               (prescribed dofs)
//! ```
//!
//! with the contact state evaluated there (the contact search runs at the
//! predicted positions, so the nodes the tool is about to reach are closed
//! in the first tangent). The plain start (the converged state with the
//! prescribed increment applied through the tangent, `-(r_f + K_fp dp)`)
//! is kept whenever the predicted start has the larger right-hand side:
//! a change of load path (a new direction of the tool, a pressure
//! controller, an unloading) then costs one residual evaluation and no
//! iteration. The convergence criteria are unchanged; the predictor only
//! moves the first iterate. Deterministic (no thresholds on timings), it
//! survives cutbacks (the ratio follows the attempted `dt`) and restarts
//! (the history is part of the restart point, `restart.rs`).
//!
//! A closing contact (a penalty pair against a rigid tool): the
//! extrapolation closes the nodes near the contact edge too early (near
//! the edge of a smooth elastic contact the gap closes as the edge
//! distance to the power 3/2, ever more slowly as the edge arrives), and
//! each extra closed node costs Newton iterations opening again, ring by
//! ring. [`edge_moves`] moves the nodes the extrapolated edge does not
//! reach back out of the tool (the edge extrapolated through `g^(2/3)`,
//! [`edge_gap`]): on the 3D Hertz sphere of
//! `verification/fenicsx/sphere3d.py` 15 -> 13 iterations at N = 20,
//! 18 -> 14 at N = 30 (see [`EDGE_MARGIN`]); the 2D tutorial 18 -> 15
//! (SPEED.md, 2026-12-06). The analysis' first increment has no history:
//! its plain start closes every node of the undeformed intersection with
//! the tool, more than the contact holds; [`first_touch_moves`] opens the
//! shallow ones (3D sphere 13 -> 12 at N = 20, 14 -> 12 at N = 30; 2D
//! tutorial 15 -> 14; SPEED.md, 2026-12-06, "first touch"). A moved start
//! whose first Newton step has to be shortened (a node opened that
//! belongs closed) is retaken from the unmoved start, the abandoned
//! iteration counted (`predictor_retakes` in summary.json;
//! `tests/suite/predictor_retake.rs`).
//!
//! Dynamic steps keep their integrator's own predictor (the first iterate
//! is the converged state); `newton { predictor = false }` turns it off.
//! Models with a material other than linear elasticity (Hencky at finite
//! strain) or Neo-Hooke (plasticity, viscoplasticity), friction, a free
//! tool or a follower pressure keep the plain start too
//! ([`applies`]): an extrapolated slip or tool rotation can start the
//! increment on another stick / slip branch, where the plain start's
//! residual test cannot see it (a free-roller strip bending,
//! `tests/robust_restart.rs`, stalled at a cutback limit with it).
//!
//! Finite strain ([`guarded`]): a predicted start whose first Newton step
//! has to be shortened (an element would invert, or the residual grows
//! along it) is abandoned, and the increment goes on from the plain start
//! (the abandoned iteration counts). An extrapolation of a large
//! deformation can land where the residual is small but the Newton
//! direction leads out of the valid region: the Neo-Hooke indentation of
//! `tests/suite/run_trust.rs` (circle pushed to 1.6 R in 4 increments)
//! stalled there for 25 iterations at step lengths 1/64..1/8 and cut back
//! twice without the guard (80 iterations, against 29 without the
//! predictor); with it 26 iterations [7, 5, 5, 9], no cutback (the last
//! increment abandons its predicted start after one iteration). Issue 20's
//! Neo-Hooke indentation against DOLFINx (`verification/fenicsx/
//! neo_indent.sh`, circle to R/2 in 10 increments) takes full first steps
//! in every predicted increment: 31 / 35 / 37 iterations on 24 x 12 /
//! 48 x 24 / 96 x 48 cells against 70 / 57 / 79 without the predictor
//! (`ctc run -v` of the decks `neo_indent.py --export-only` writes).

use crate::model::Model;

/// Whether the predictor is used for `model`: only with path-independent
/// elastic materials (linear elastic, Hencky at finite strain, Neo-Hooke)
/// — with plasticity or viscoplasticity the
/// extrapolated start can lead the increment onto another loading path
/// (skin pass: one more cutback and a 15 % different final roll force;
/// rivet forming: one more increment, 3 % in a reaction); at finite
/// strain with the guard of [`guarded`] (without it the Neo-Hooke
/// indentation of `tests/suite/run_trust.rs` cut back twice); not with friction (a
/// path-dependent stick / slip state), free tools (a rotation unknown
/// driven by friction) or follower pressures (the follower patch's
/// homogeneous stress, checked to 1e-10, ended at 2.3e-10 with it).
///
/// Neo-Hooke models only when every contact pair's master is a rigid tool:
/// between deformable bodies (and in self contact) the predicted positions
/// move the node-to-facet search, and the 3D self-contact ring
/// (`examples/self_contact_3d.ctc`) ended with its pair forces summing to
/// 1.1e-3 instead of 1e-14 (fewer iterations, 32 against 47, but the
/// pair's balance lost).
pub fn applies<const D: usize>(model: &Model<D>) -> bool {
    use crate::model::MaterialLaw;
    let rigid_masters = model.contacts.iter().all(|c| c.master.tool().is_some());
    model.materials.iter().all(|m| match m.law {
        MaterialLaw::LinearElastic { .. } => true,
        MaterialLaw::NeoHookean { .. } => rigid_masters,
        _ => false,
    }) && model.contacts.iter().all(|c| c.friction.is_none())
        && model.tools.iter().all(|t| t.free_rotation.is_none())
        && !crate::solve::follower::has_follower(model)
}

/// Whether a predicted start of `model` is abandoned for the plain start
/// when its first Newton step is shortened: models with a finite-strain
/// body (module doc).
pub fn guarded<const D: usize>(model: &Model<D>) -> bool {
    model
        .bodies
        .iter()
        .any(|b| b.kinematics == crate::model::Kinematics::Finite)
}

/// The last converged increment, as far as the predictor needs it.
#[derive(Debug, Clone, PartialEq)]
pub struct PredictorHistory<const D: usize = 2> {
    /// Step of the last converged increment.
    pub step: usize,
    /// Its start and end times `(t_{n-1}, t_n)`.
    pub times: (f64, f64),
    /// Nodal displacements at its start, `u_{n-1}`.
    pub start: Vec<[f64; D]>,
}

/// The converged history kept by the Newton solver.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct History<const D: usize> {
    /// The last converged increment (`None` before the first one).
    pub last: Option<PredictorHistory<D>>,
}

impl<const D: usize> History<D> {
    /// Records a converged increment of `step` from `t0` (displacements
    /// `start`) to `t1`.
    pub fn record(&mut self, step: usize, t0: f64, t1: f64, start: &[[f64; D]]) {
        match &mut self.last {
            Some(h) if h.start.len() == start.len() => {
                h.step = step;
                h.times = (t0, t1);
                h.start.copy_from_slice(start);
            }
            _ => {
                self.last = Some(PredictorHistory {
                    step,
                    times: (t0, t1),
                    start: start.to_vec(),
                })
            }
        }
    }

    /// The extrapolation factor `(t - t_n) / (t_n - t_{n-1})` of an
    /// increment of `step` ending at `t`, or `None` when the last converged
    /// increment belongs to another step (a new load path) or the times
    /// are degenerate.
    pub fn ratio(&self, step: usize, t: f64) -> Option<f64> {
        let h = self.last.as_ref()?;
        let (t0, t1) = h.times;
        let ratio = (t - t1) / (t1 - t0);
        (h.step == step && t1 > t0 && t > t1 && ratio.is_finite() && ratio > 0.0).then_some(ratio)
    }
}

/// `u[g] += ratio (u[g] - start[g])` on the free dofs `free` (flattened
/// node-major arrays), `u` holding the converged state `u_n`.
pub fn extrapolate(u: &mut [f64], start: &[f64], free: &[usize], ratio: f64) {
    for &g in free {
        u[g] += ratio * (u[g] - start[g]);
    }
}

/// The gaps of the nodes of every rigid-tool pair in `contact` (one list
/// per pair, sorted by node; empty for the other pairs): the converged
/// gaps the edge rule of [`edge_moves`] starts from.
pub fn gaps<const D: usize>(
    model: &Model<D>,
    contact: &[Vec<crate::contact::NodeContact<D>>],
) -> Vec<Vec<(usize, f64)>> {
    contact
        .iter()
        .zip(&model.contacts)
        .map(|(pair, cp)| {
            if cp.master.tool().is_none() {
                return Vec::new();
            }
            let mut g: Vec<(usize, f64)> = pair.iter().map(|c| (c.node, c.gap)).collect();
            g.sort_by_key(|x| x.0);
            g
        })
        .collect()
}

/// `h(g) = g^(2/3)`: near the edge of a smooth frictionless elastic
/// contact the gap opens as the distance to the edge to the power 3/2, so
/// `h` is linear in that distance.
fn edge_distance(g: f64) -> f64 {
    g.max(0.0).powf(2.0 / 3.0)
}

/// The edge rule for one node open at the converged state (gap `g_n > 0`)
/// that the extrapolation by `ratio` closes (gap `g < 0`): the gap the
/// extrapolation implies at the previous converged state is
/// `g_{n-1} = g_n + (g_n - g) / ratio`; extrapolating `h = g^(2/3)`
/// (linear in the distance to the contact edge) instead of `g` gives
/// `h = (1 + ratio) h(g_n) - ratio h(g_{n-1})`, the edge's advance over
/// the increment `ratio (h(g_{n-1}) - h(g_n))`. `Some(gap)`, the gap
/// `h^(3/2)` (at least `1e-3 |g|`, clear of round-off), where the edge
/// stops short of the node by [`EDGE_MARGIN`] times its advance; `None`
/// where it does not (or the node is not such a node).
pub fn edge_gap(g_n: f64, g: f64, ratio: f64) -> Option<f64> {
    let closing = g_n > 0.0 && g < 0.0 && ratio > 0.0;
    if !closing {
        return None;
    }
    let g_prev = g_n + (g_n - g) / ratio;
    let advance = ratio * (edge_distance(g_prev) - edge_distance(g_n));
    let h = edge_distance(g_n) - advance;
    (h >= EDGE_MARGIN * advance).then(|| h.powf(1.5).max(1e-3 * -g))
}

/// How far short of a node the extrapolated edge must stop, in units of
/// its advance over the increment, for [`edge_gap`] to open the node: 0,
/// anywhere short of it. A node wrongly opened costs more than one left
/// closed (its first step penetrates deeply and the line search shortens
/// it: 5 iterations at step lengths 1/4..1/64 in the last increment of
/// `verification/cases/rigid_cylinder_block.ctc` without the bound of
/// [`EDGE_MIN_CLOSED`]); such a start is retaken from the unmoved
/// extrapolation (`Newton::newton_iterations`). Measured with the bound
/// and the retake (`ctc verify --tag contact --max-level 0 -j 1`, release,
/// `CTC_X_MARGIN` of a temporary switch, SPEED.md 2026-12-06): margin 0
/// against 0.5, the 82 contact cases keep their iterations but
/// hertz_sphere_3d_vs_axi (26 -> 25); the 3D sphere of `sphere3d.py` at
/// N = 30 18 -> 14, N = 20 13 (unchanged), the 2D tutorial 16 -> 15.
const EDGE_MARGIN: f64 = 0.0;

/// The fewest closed nodes of a pair at `t_n` for [`edge_moves`] to move
/// any: the 3/2 law is that of a resolved edge. Measured with a margin
/// of 0.5: the fenicsx hertz_sphere_tri3 deck (5 closed
/// nodes) went from 7 to 12 iterations with the rule, the 3D sphere at
/// N = 10 (8 to 15 closed nodes) kept its 12; the gains came at 22 or
/// more (3D sphere N = 20, 30; 2D tutorial 31).
const EDGE_MIN_CLOSED: usize = 16;

/// The moves of a closing increment's predicted state (`contact`,
/// evaluated there; `g_n` the converged gaps of [`gaps`]): every closed
/// node of a penalty pair against a rigid tool with at least
/// [`EDGE_MIN_CLOSED`] nodes closed at `t_n` that [`edge_gap`] opens is moved along the
/// tool's normal to that gap. The extrapolation closes the nodes near the
/// edge too early (their gap closes ever more slowly as the edge
/// arrives): on the 3D Hertz sphere of `verification/fenicsx/sphere3d.py`
/// (N = 20) it closed 44, 52 and 59 nodes where 33, 44 and 56 are closed
/// at convergence, and each extra node cost Newton iterations opening
/// again ring by ring; with the rule 33, 44 and 54. Returns `(node,
/// displacement)`, in pair and node order.
pub fn edge_moves<const D: usize>(
    model: &Model<D>,
    contact: &[Vec<crate::contact::NodeContact<D>>],
    g_n: &[Vec<(usize, f64)>],
    ratio: f64,
) -> Vec<(usize, [f64; D])> {
    let mut moves = Vec::new();
    for ((pair, cp), converged) in contact.iter().zip(&model.contacts).zip(g_n) {
        let closed = converged.iter().filter(|x| x.1 <= 0.0).count();
        if cp.master.tool().is_none()
            || !matches!(cp.method, crate::model::ContactMethod::Penalty { .. })
            || closed < EDGE_MIN_CLOSED
        {
            continue;
        }
        for c in pair {
            if c.status != crate::contact::ContactStatus::Closed {
                continue;
            }
            let Ok(k) = converged.binary_search_by_key(&c.node, |x| x.0) else {
                continue;
            };
            if let Some(target) = edge_gap(converged[k].1, c.gap, ratio) {
                let d = target - c.gap;
                moves.push((c.node, std::array::from_fn(|i| d * c.normal[i])));
            }
        }
    }
    moves
}

/// The fraction of the deepest penetration below which
/// [`first_touch_moves`] opens a node of a first touch: 1/2, Hertz's
/// sphere (contact radius `sqrt(R d)` where the undeformed intersection
/// has `sqrt(2 R d)`: the nodes in contact are those whose undeformed
/// penetration exceeds `d / 2`). Measured (`ctc run sphere3d.ctc -v
/// --threads 1` of `sphere3d.py OUT --n 20 --export-only`, a temporary
/// switch, SPEED.md 2026-12-06): the first increment takes 3 iterations
/// with 0.3, 0.4, 0.5 and 0.6 (4 without the rule; its 22 closed nodes
/// reached in the first iteration with each), the residual after the
/// first iteration 0.14, 0.029, 0.31, 0.87; the 2D tutorial's first
/// increment 5 with 0.4 and 0.5 (6 without). In plane strain the
/// contact is narrower still (the approach `d` grows with the log of the
/// body's size over the half-width `a`: `d ~ a^2 / (4 R) (2 ln(2 h / a) -
/// 1)`, so the edge penetrates about 3/4 of the deepest node for `h / a
/// ~ 80`; an estimate, not measured), and 1/2 leaves closed more nodes
/// than belong: the safe side (a node wrongly opened costs a shortened
/// step and a retake).
const FIRST_TOUCH_FRACTION: f64 = 0.5;

/// The first-touch rule for one node closed at the plain start of a first
/// touch (undeformed penetration `-g > 0`, the pair's deepest `deepest`):
/// `Some(gap)`, a small positive gap (`1e-3 |g|`, clear of round-off) to
/// move it to, when it penetrates less than [`FIRST_TOUCH_FRACTION`] of
/// the deepest node; `None` otherwise.
pub fn first_touch_gap(g: f64, deepest: f64) -> Option<f64> {
    (g < 0.0 && -g < FIRST_TOUCH_FRACTION * deepest).then(|| 1e-3 * -g)
}

/// The moves of the plain start of a first touch (`contact` evaluated at
/// the plain start, the tool at `t`; `g_n` the gaps of the same state
/// against the tool at `t_n`, [`gaps`]): with a penalty pair against a
/// rigid tool that no node penetrates at `t_n` and that closes at least
/// [`EDGE_MIN_CLOSED`] nodes at the start, the closed nodes
/// [`first_touch_gap`] opens are moved along the tool's normal out of it.
///
/// Why it is general: a frictionless elastic body pressed by a convex
/// rigid tool sinks everywhere around the contact (the surface
/// displacement under a compressive load is into the body), so its
/// contact set is inside the undeformed intersection of body and tool,
/// the set the plain start closes; the nodes near the intersection's rim
/// (the shallowest ones) are the ones outside. The fraction 1/2 is
/// exact for a sphere (or any paraboloid) on a half-space; where the
/// contact is wider than that (a cone: radius `2 / pi` of the
/// intersection's, the nodes between 1/2 and 0.64 of it open wrongly) or
/// the tool is flat (every node penetrates alike: nothing opens) the rule
/// is wrong or idle; a wrong opening makes the first step penetrate,
/// the line search shortens it and the start is retaken without the rule
/// (`Newton::newton_iterations`, as for [`edge_moves`]). Returns `(node,
/// displacement)`, in pair and node order.
pub fn first_touch_moves<const D: usize>(
    model: &Model<D>,
    contact: &[Vec<crate::contact::NodeContact<D>>],
    g_n: &[Vec<(usize, f64)>],
) -> Vec<(usize, [f64; D])> {
    let mut moves = Vec::new();
    for ((pair, cp), converged) in contact.iter().zip(&model.contacts).zip(g_n) {
        let closed = || {
            pair.iter()
                .filter(|c| c.status == crate::contact::ContactStatus::Closed && c.gap < 0.0)
        };
        if cp.master.tool().is_none()
            || !matches!(cp.method, crate::model::ContactMethod::Penalty { .. })
            || converged.iter().any(|x| x.1 < 0.0)
            || closed().count() < EDGE_MIN_CLOSED
        {
            continue;
        }
        let deepest = closed().fold(0.0, |m: f64, c| m.max(-c.gap));
        for c in closed() {
            if let Some(target) = first_touch_gap(c.gap, deepest) {
                let d = target - c.gap;
                moves.push((c.node, std::array::from_fn(|i| d * c.normal[i])));
            }
        }
    }
    moves
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ratio_follows_the_attempted_increment_within_a_step() {
        let mut h = History::<2>::default();
        assert_eq!(h.ratio(0, 0.5), None, "no history yet");
        h.record(0, 0.25, 0.5, &[[0.0; 2]; 3]);
        assert_eq!(h.ratio(0, 0.75), Some(1.0));
        // a cutback halves the attempted increment: half the extrapolation
        assert_eq!(h.ratio(0, 0.625), Some(0.5));
        // a grown increment
        assert_eq!(h.ratio(0, 0.875), Some(1.5));
        // another step: a new load path, no extrapolation
        assert_eq!(h.ratio(1, 0.75), None);
        // degenerate times
        assert_eq!(h.ratio(0, 0.5), None);
        h.record(0, 0.5, 0.5, &[[0.0; 2]; 3]);
        assert_eq!(h.ratio(0, 0.75), None);
    }

    #[test]
    fn linear_path_is_extrapolated_exactly_on_free_dofs_only() {
        // u(t) = a t along a path: u_{n-1} at 0.2, u_n at 0.4, predicted 0.7
        let a = [1.0, -2.0, 3.0, 0.5];
        let start: Vec<f64> = a.iter().map(|x| x * 0.2).collect();
        let mut u: Vec<f64> = a.iter().map(|x| x * 0.4).collect();
        let mut h = History::<2>::default();
        h.record(3, 0.2, 0.4, &[[start[0], start[1]], [start[2], start[3]]]);
        let ratio = h.ratio(3, 0.7).unwrap();
        extrapolate(&mut u, &start, &[0, 1, 3], ratio);
        for g in [0, 1, 3] {
            assert!((u[g] - a[g] * 0.7).abs() < 1e-15, "dof {g}: {}", u[g]);
        }
        // a prescribed dof is not touched
        assert_eq!(u[2], a[2] * 0.4);
    }

    #[test]
    fn edge_rule_follows_a_gap_closing_as_the_edge_distance_to_the_three_halves() {
        // g = c s^(3/2), s the distance to the edge, shrinking by 1 per
        // increment: s = 2.6 at t_{n-1}, 1.6 at t_n, 0.6 at t
        let c = 2e-4;
        let g = |s: f64| c * s.max(0.0).powf(1.5);
        let (g_prev, g_n) = (g(2.6), g(1.6));
        // the linear extrapolation of the gap closes the node ...
        let g_lin = g_n + (g_n - g_prev);
        assert!(g_lin < 0.0, "{g_lin}");
        // ... the edge stops 0.6 short of it (>= 0.5 of its advance of
        // 1): open, at its gap
        let open = edge_gap(g_n, g_lin, 1.0).expect("the edge does not reach it");
        assert!((open - g(0.6)).abs() < 1e-12 * c, "{open} vs {}", g(0.6));
        // the edge stops 0.2 short (anywhere short of the node: margin
        // 0): open too, at its gap
        let (g_prev, g_n) = (g(2.2), g(1.2));
        let g_lin = g_n + (g_n - g_prev);
        assert!(g_lin < 0.0);
        let open = edge_gap(g_n, g_lin, 1.0).expect("the edge does not reach it");
        assert!((open - g(0.2)).abs() < 1e-12 * c, "{open} vs {}", g(0.2));
        // the edge passes the node (s = 1.0 -> -0.5 at a ratio of 1.5)
        let (g_prev, g_n) = (g(2.0), g(1.0));
        let g_lin = g_n + 1.5 * (g_n - g_prev);
        assert!(g_lin < 0.0);
        assert_eq!(edge_gap(g_n, g_lin, 1.5), None);
        // a node closed at t_n, or left open by the extrapolation: untouched
        assert_eq!(edge_gap(-1e-6, -2e-6, 1.0), None);
        assert_eq!(edge_gap(1e-6, 5e-7, 1.0), None);
    }

    #[test]
    fn first_touch_opens_the_nodes_outside_a_paraboloid_contact() {
        // a paraboloid z = r^2 / (2 R) pressed d into a half-space: the
        // undeformed penetration at r is d - r^2 / (2 R); Hertz's contact
        // radius sqrt(R d) is where it is d / 2
        let (r_tool, d) = (1.0, 0.01);
        let pen = |r: f64| d - r * r / (2.0 * r_tool);
        let a = (r_tool * d).sqrt();
        // inside the contact radius: kept closed
        assert_eq!(first_touch_gap(-pen(0.9 * a), d), None);
        assert_eq!(first_touch_gap(-pen(0.0), d), None);
        // between it and the intersection's sqrt(2 R d): opened, just out
        let g = -pen(1.1 * a);
        let open = first_touch_gap(g, d).expect("outside the contact radius");
        assert!(open > 0.0 && open < 1e-3 * d, "{open}");
        // an open node is not touched
        assert_eq!(first_touch_gap(1e-6, d), None);
    }
}
