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
}
