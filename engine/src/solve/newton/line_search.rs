//! Line search along the Newton direction.
//!
//! Energy test along the step: `phi'(s) = du . r(u + s du)`, with
//! `phi'(0) = -du . K du < 0`. The full step is kept when
//! `phi'(1) < |phi'(0)|` (the energy still decreases along the step: a
//! contact closing under a full step raises `||r||` without making the step
//! bad). Only with a potential (symmetric tangent: no friction), or a
//! tangent non-symmetric only by a follower pressure's load stiffness or by
//! F-bar (the test along the step still measures descent there).
//!
//! Otherwise, when the full step increases the residual (and has not
//! already reached the tolerance: no backtracking on round-off noise, and
//! not with Lagrange constraints: the multipliers are already updated), the
//! step is halved up to [`LINE_SEARCH_HALVINGS`] times until the residual
//! is below the one at the start of the step; the best trial is kept.
//!
//! Before both: a full step that inverts an element (finite strain, a
//! trial iterate overshooting under a punch) is halved along the Newton
//! direction until every element is valid (`Newton::backtrack_to_valid`,
//! at most `VALID_HALVINGS` times), and the search above continues from
//! there (invalid trials are never kept). Only when no valid step exists
//! does the increment fail and get cut back.

use super::convergence::Eval;
use super::failure::Failure;

/// Line-search halvings before giving up on decreasing the residual.
pub const LINE_SEARCH_HALVINGS: i32 = 6;

/// The energy test: `du` the step, `rhs0 = -r(u)` at its start, `r1 =
/// r(u + du)` at its end.
pub fn energy_decreases(potential: bool, du: &[f64], rhs0: &[f64], r1: &[f64]) -> bool {
    let slope0: f64 = du.iter().zip(rhs0).map(|(d, r)| -d * r).sum();
    let slope1: f64 = du.iter().zip(r1).map(|(d, r)| d * r).sum();
    potential && slope0 < 0.0 && slope1.is_finite() && slope1 < -slope0
}

/// Result of a backtracking search.
#[derive(Debug, Clone, Copy)]
pub struct Backtracked {
    /// Step length kept.
    pub s: f64,
    /// Residual at that step length.
    pub eval: Eval,
    /// Step length of the last trial evaluated (the state the problem is
    /// left in).
    pub last_trial: f64,
}

/// Halves the step from the full step (residual `full`) while the residual
/// is not below `ref_norm` (its value at the start of the step);
/// `trial(s)` sets the state `u + s du` and evaluates its residual.
pub fn backtrack(
    ref_norm: f64,
    full: Eval,
    mut trial: impl FnMut(f64) -> Result<Eval, Failure>,
) -> Result<Backtracked, Failure> {
    let mut best = (1.0, full);
    let mut last_s = 1.0;
    for h in 1..=LINE_SEARCH_HALVINGS {
        let s = 0.5f64.powi(h);
        let e = trial(s)?;
        last_s = s;
        if e.abs < best.1.abs {
            best = (s, e);
        }
        if e.abs < ref_norm {
            break;
        }
    }
    Ok(Backtracked {
        s: best.0,
        eval: best.1,
        last_trial: last_s,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn backtracking_keeps_the_best_trial_and_stops_below_the_start() {
        // residual |1 - 2 s| * 4 + 1: best at s = 1/2
        let f = |s: f64| Eval {
            abs: (1.0 - 2.0 * s).abs() * 4.0 + 1.0,
            rel: 0.0,
            floor: 0.0,
            scale: 1.0,
        };
        let mut trials = Vec::new();
        let b = backtrack(2.0, f(1.0), |s| {
            trials.push(s);
            Ok(f(s))
        })
        .unwrap();
        assert_eq!(trials, vec![0.5]);
        assert_eq!((b.s, b.last_trial), (0.5, 0.5));
        // never below the start: every halving tried, the best kept
        let b = backtrack(0.0, f(1.0), |s| Ok(f(s))).unwrap();
        assert_eq!(b.s, 0.5);
        assert_eq!(b.last_trial, 0.5f64.powi(LINE_SEARCH_HALVINGS));
    }

    #[test]
    fn energy_test_needs_a_potential_and_a_descent_direction() {
        let du = [1.0, 0.0];
        let rhs0 = [2.0, 0.0]; // phi'(0) = -2
        assert!(energy_decreases(true, &du, &rhs0, &[1.0, 5.0]));
        assert!(!energy_decreases(false, &du, &rhs0, &[1.0, 5.0]));
        assert!(!energy_decreases(true, &du, &rhs0, &[3.0, 0.0]));
        assert!(!energy_decreases(true, &du, &rhs0, &[f64::NAN, 0.0]));
    }
}
