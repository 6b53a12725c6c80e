//! When a Newton loop has converged, and when it is diverging.
//!
//! Convergence (after each update, on the updated state):
//! `||r|| / max(||f_ext + f_c|| + ||reactions||, ||f_int||, tiny) <= tol`
//! and `||du|| / max(||u||, tiny) <= tol_displacement`, where `du` is the
//! correction just applied or, when it is large but the residual is
//! already within tolerance (a linear or nearly linear increment), the
//! next correction `K^-1 r` estimated with the factorization already at
//! hand (one triangular solve, no factorization). With Lagrange
//! constraints the gaps of the active nodes must vanish too.
//!
//! Round-off floor: the residual cannot be computed more accurately than
//! `FLOOR_FACTOR * eps * || |K| |x| ||` (`|K|` the entrywise absolute
//! tangent; `|x|` the current coordinates `X + u` at contact nodes — a
//! penalty force `k g` with `g` computed from coordinates of size `|x|`
//! carries an error `k eps |x|` — and the displacements elsewhere — an
//! element force `K u` carries `eps |K| |u|`). A residual at or below its
//! floor is equilibrium to machine precision: the loop converges there
//! whatever `tol` and `tol_displacement` ask once the iterate has settled
//! (correction below [`FLOOR_SETTLED`]; the next correction is then the
//! response to round-off; [`Criteria::residual_small`]), and the
//! residual's wanderings below ten times the floor are not divergence
//! ([`DivergenceMonitor::diverges`]). The floor of each converged
//! increment is in `summary.json` (`residual_floor`, `at_floor`).
//! A stiff penalty (`k = 1e10` against a plane) raises the floor to
//! `1e-10..1e-9` of the load: without it the loop stalled there and the
//! increment was cut back to the minimum ("could not advance from t = 0").
//!
//! Divergence: the residual grew in [`DIVERGENCE_GROWTHS`] consecutive
//! iterations (not counted across an augmented-Lagrangian multiplier
//! update, which changes the problem).

use crate::model::NewtonSettings;

/// Floor of norms used as denominators.
pub(crate) const TINY: f64 = 1e-300;
/// Round-off floor of the residual, in units of `eps || |K| |x| ||`.
pub const FLOOR_FACTOR: f64 = 4.0;

/// Largest relative correction of an iteration that may converge on the
/// round-off floor without meeting `tol_displacement`: the iterate must
/// have settled (a body running away along a zero-energy mode has a
/// residual "at the floor" of its huge displacements, and corrections as
/// large as they are).
pub const FLOOR_SETTLED: f64 = 1e-3;

/// Consecutive residual increases that mean divergence.
pub const DIVERGENCE_GROWTHS: usize = 3;

/// A converged increment.
#[derive(Debug, Clone, PartialEq)]
pub struct Converged {
    /// Newton iterations (factorizations) used.
    pub iterations: usize,
    /// Relative residual after each iteration.
    pub residuals: Vec<f64>,
    /// Closed contact nodes at convergence.
    pub active_contacts: usize,
    /// Contact iterations: Lagrange active-set changes plus
    /// augmented-Lagrangian multiplier updates (0 for penalty).
    pub contact_iterations: usize,
    /// Largest penetration `max(0, -g)` over all pairs at convergence.
    pub max_penetration: f64,
}

/// Norms of one evaluation of the residual.
#[derive(Debug, Clone, Copy)]
pub struct Eval {
    /// `||r||` on the free dofs.
    pub abs: f64,
    /// Relative residual.
    pub rel: f64,
    /// Round-off floor of `abs` (0: unknown).
    pub floor: f64,
    /// The force scale `rel` is relative to (`abs / rel`).
    pub scale: f64,
}

impl Eval {
    /// The floor relative to the same force scale as `rel`.
    pub fn rel_floor(&self) -> f64 {
        self.floor / self.scale.max(TINY)
    }

    /// Whether the residual is at its round-off floor.
    pub fn at_floor(&self) -> bool {
        self.abs <= self.floor
    }
}

/// The convergence test of one Newton loop.
#[derive(Debug, Clone, Copy)]
pub struct Criteria {
    /// Relative residual tolerance.
    pub tol: f64,
    /// Relative displacement-correction tolerance.
    pub tol_displacement: f64,
    /// Also accept a residual small against the loop's initial
    /// out-of-balance force (`first_ref`): with Lagrange pairs a Newton loop
    /// may carry no force at all (a body moved rigidly towards a tool whose
    /// constraints are not introduced yet), the relative residual being
    /// round-off over round-off.
    pub force_free: bool,
    /// Norm of the first right-hand side of the loop.
    pub first_ref: f64,
}

impl Criteria {
    /// The test of `settings`.
    pub fn new(settings: &NewtonSettings, force_free: bool) -> Self {
        Criteria {
            tol: settings.tol,
            tol_displacement: settings.tol_displacement,
            force_free,
            first_ref: 0.0,
        }
    }

    /// Whether the residual `ev` is within tolerance, or at its round-off
    /// floor (nothing more accurate can be computed).
    pub fn residual_small(&self, ev: Eval) -> bool {
        ev.rel.is_finite()
            && (ev.rel <= self.tol
                || ev.at_floor()
                || (self.force_free && ev.abs <= self.tol * self.first_ref))
    }

    /// Whether the Lagrange gaps (norm `gap_norm`) vanish relative to the
    /// displacement norm `u_norm`.
    pub fn gaps_small(&self, gap_norm: f64, u_norm: f64) -> bool {
        gap_norm / u_norm <= self.tol_displacement
    }

    /// Whether a relative displacement correction is within tolerance.
    pub fn correction_small(&self, rel_du: f64) -> bool {
        rel_du <= self.tol_displacement
    }
}

/// Relative size of the update of one iteration: the free correction
/// `du` scaled by the step length `s`, with the prescribed increment
/// `dp` (first iteration only), over `max(||u||, tiny)`.
pub fn relative_correction(s: f64, du_norm: f64, dp_norm: f64, u_norm: f64) -> f64 {
    ((s * du_norm).powi(2) + dp_norm * dp_norm).sqrt() / u_norm
}

/// Counts consecutive residual growths.
#[derive(Debug, Clone, Copy, Default)]
pub struct DivergenceMonitor {
    growths: usize,
    updated_last: bool,
}

impl DivergenceMonitor {
    /// Records the residual history after an iteration (`updated`: the
    /// problem changed in this iteration, e.g. a multiplier update;
    /// `floor`: the relative round-off floor of the last residual, whose
    /// growth below ten times the floor is noise, not divergence); returns
    /// whether the loop diverges.
    pub fn diverges(&mut self, residuals: &[f64], updated: bool, floor: f64) -> bool {
        let n = residuals.len();
        if updated || self.updated_last {
            self.growths = 0;
        } else if n >= 2 && residuals[n - 1] > residuals[n - 2] && residuals[n - 1] > 10.0 * floor {
            self.growths += 1;
        } else {
            self.growths = 0;
        }
        self.updated_last = updated;
        self.growths >= DIVERGENCE_GROWTHS
    }
}

/// Euclidean norm.
pub fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn divergence_needs_consecutive_growths_and_resets_on_updates() {
        let mut m = DivergenceMonitor::default();
        let r = [1.0, 2.0, 3.0, 4.0, 5.0];
        assert!(!m.diverges(&r[..1], false, 0.0));
        assert!(!m.diverges(&r[..2], false, 0.0));
        assert!(!m.diverges(&r[..3], false, 0.0));
        assert!(m.diverges(&r[..4], false, 0.0));
        let mut m = DivergenceMonitor::default();
        assert!(!m.diverges(&r[..2], false, 0.0));
        assert!(!m.diverges(&r[..3], true, 0.0));
        assert!(!m.diverges(&r[..4], false, 0.0));
        assert!(!m.diverges(&r[..5], false, 0.0));
        // growth of round-off noise (below 10 x the floor) is not divergence
        let mut m = DivergenceMonitor::default();
        let noise = [1e-14, 2e-14, 3e-14, 4e-14, 5e-14];
        for k in 1..=5 {
            assert!(!m.diverges(&noise[..k], false, 1e-14));
        }
    }

    #[test]
    fn a_residual_at_its_round_off_floor_converges_whatever_the_tolerance() {
        let settings = NewtonSettings {
            tol: 1e-12,
            ..NewtonSettings::default()
        };
        let c = Criteria::new(&settings, false);
        let stalled = Eval {
            abs: 3e-6,
            rel: 1e-9,
            floor: 4e-6,
            scale: 3e3,
        };
        assert!(c.residual_small(stalled));
        assert!((stalled.rel_floor() - 4e-9 / 3.0).abs() < 1e-20);
        assert!(!c.residual_small(Eval {
            floor: 1e-7,
            ..stalled
        }));
    }
}
