//! Load stepping: equal increments over each step, automatic cutback and
//! grow-back.
//!
//! Each step starts with `(t_end - t_start) / increments`. A failed
//! increment is retried from the last converged state with half the size;
//! below `min_fraction` of the initial size the run stops with a diagnosis.
//! An iterative linear solver that stopped before its tolerance
//! ([`FailureKind::LinearSolver`]: a Krylov method at `-ksp_max_it`, a
//! breakdown) is cut back once: if the attempt at half the size fails the
//! same way (the same words: the solver's reason and iteration count), the
//! run stops there instead of halving down to `min_fraction` — the matrix
//! hardly changes with the increment size, so neither does the linear
//! solve (issue 21: `-ksp_max_it 2` took 10 cutbacks, each a preconditioner
//! set-up, to say the same thing). Those words come from the solver's
//! collective result (PETSc's converged reason and iteration count are
//! the same on every rank), so every rank stops at the same attempt.
//! After two consecutive easy increments (first attempt, at most half of
//! `max_iter` iterations) the size grows by 1.5, never above the initial one.
//! The last increment of a step ends exactly at `t_end`. Times on the
//! step's grid (multiples of 2^-20 of the initial size, which cutbacks and
//! grow-backs stay on for 20 levels) are computed as
//! `t_start + (t_end - t_start) * n / increments`, not by summing the
//! increments: `0.3`, not `0.30000000000000004`.
//!
//! Adaptive dynamic steps (`dynamic { adaptive = true }`,
//! [`crate::model::Adaptive`]): the size stays within `[dt_min, dt_max]`
//! (`dt_max` may exceed the initial size); after each converged attempt
//! the local error estimate `eta` of the integrator
//! ([`IncrementSolver::local_error`]) is compared with `error_tol`: above
//! `2 error_tol` the increment is redone with `dt (error_tol / eta)^(1/3)
//! 0.9` (at least a quarter of it, at least `dt_min`); accepted, the next
//! size is `0.9 dt (error_tol / eta)^(1/3)` within `[dt / 2, 1.5 dt]`, the
//! growth only after an easy increment (first attempt, at most half of
//! `max_iter`). A contact event — the number of active contact nodes
//! changed since the last accepted increment (a first contact, a release)
//! — halves the next size. The first increment after a restart sees no
//! contact event (the count is not in the restart point).
//!
//! Rotation control of dynamic steps (`dynamic { max_rotation }`,
//! adaptive or not): after each converged attempt the largest rotation of
//! a cell over the increment `theta` ([`IncrementSolver::rotation`],
//! `solve::cell_rotation`) is compared with `max_rotation`: above it the
//! increment is redone with `0.9 dt max_rotation / theta` (at least a
//! quarter of it, at least the smallest size; [`FailureKind::Rotation`]);
//! accepted, the next size is at most `0.9 dt max_rotation / theta`, and
//! grows back by the rules above. The scheme's trapezoidal work follows
//! the strain energy only while increments turn the bodies by small
//! angles (see `solve::cell_rotation`).
//!
//! Energy control of dynamic steps (`dynamic { energy_tol }`, absent
//! [`crate::model::DEFAULT_ENERGY_TOL`], adaptive or not): after each
//! converged attempt in which contact forces act (at its start or end)
//! the energy the increment would
//! create ([`IncrementSolver::energy_created`]: the growth of the kinetic
//! energy, internal and damping work and stored penalty energy beyond the
//! work of the loads and supports, `dynamics::Energy::created_since`) is
//! compared with `energy_tol` times the largest energy of the run: above
//! it the increment is redone with `0.9 dt sqrt(energy_tol scale /
//! created)` (at least a quarter of it, at least the smallest size;
//! [`FailureKind::Energy`]); accepted, the next size is at most the same.
//! A penalty node that ends an increment open after beginning it closed
//! gets the start's force over the whole separating motion: the energy it
//! creates grows with `dt^2`.
//!
//! A restart point is continued by [`drive_from`] through [`resumable`]:
//! a point without a next size (a completed run's) takes the step's
//! planned size.

use super::newton::{Converged, Failure, FailureKind};
use super::restart::Resume;
use crate::model::Step;

/// Cutback factor.
const CUT: f64 = 0.5;
/// Grow-back factor.
const GROW: f64 = 1.5;
/// Easy increments needed before growing back.
const EASY_BEFORE_GROW: usize = 2;

/// What the stepper drives: one increment attempt, its acceptance or its
/// rejection.
pub trait IncrementSolver {
    /// Tries to reach equilibrium at time `t` of step `step`, starting from
    /// the last accepted state.
    fn attempt(&mut self, step: usize, t: f64) -> Result<Converged, Failure>;
    /// Accepts the state reached by the last attempt (time `t`, size `dt`,
    /// after `cutbacks` failed attempts). An error aborts the run.
    fn accept(
        &mut self,
        step: usize,
        t: f64,
        dt: f64,
        cutbacks: usize,
        converged: Converged,
    ) -> Result<(), String>;
    /// Discards the last attempt (restores the last accepted state); the
    /// next attempt will use `new_dt`.
    fn reject(&mut self, step: usize, failure: &Failure, new_dt: f64);
    /// After an accepted increment, once the stepping state is updated:
    /// `resume` is where a restart from this state continues. An error
    /// aborts the run.
    fn checkpoint(&mut self, _resume: &Resume) -> Result<(), String> {
        Ok(())
    }
    /// After a converged attempt: the fraction of the increment at which
    /// a node first touched its master, when the deck asks to cut the
    /// increment there (`None`: no cut).
    fn impact_fraction(&self) -> Option<f64> {
        None
    }
    /// After a converged attempt of a dynamic increment: the relative
    /// local error estimate of the integrator (`None`: none).
    fn local_error(&self) -> Option<f64> {
        None
    }
    /// After a converged attempt: the largest rotation of a cell over the
    /// increment, in radians, and where (words), for the rotation control
    /// of dynamic steps (`dynamic { max_rotation }`; `None`: none).
    fn rotation(&self) -> Option<(f64, String)> {
        None
    }
    /// After a converged attempt of a dynamic increment: the energy it
    /// would create if accepted, the largest energy of the run it is
    /// weighed against and where (words), for the energy control of
    /// dynamic steps (`dynamic { energy_tol }`; `None`: none).
    fn energy_created(&self) -> Option<(f64, f64, String)> {
        None
    }
}

/// Safety factor of the error-controlled size.
const ERROR_SAFETY: f64 = 0.9;
/// An increment whose error estimate exceeds this many tolerances is
/// redone.
const ERROR_REJECT: f64 = 2.0;

/// The size the error estimate `eta` of an increment of size `dt` asks
/// for against `tol` (`tol == 0` or no estimate: no limit, `GROW dt`).
fn error_controlled(dt: f64, eta: Option<f64>, tol: f64) -> f64 {
    match eta {
        Some(e) if tol > 0.0 && e > 0.0 => dt * ERROR_SAFETY * (tol / e).cbrt(),
        _ => dt * GROW,
    }
}

/// The size whose rotation is [`ERROR_SAFETY`] of `limit`, after an
/// increment of size `dt` turned a cell by `theta` (the rotation of an
/// increment grows with its size; `theta == 0`: no limit).
fn rotation_controlled(dt: f64, theta: f64, limit: f64) -> f64 {
    if theta > 0.0 && limit.is_finite() {
        dt * ERROR_SAFETY * limit / theta
    } else {
        f64::INFINITY
    }
}

/// The size whose created energy is [`ERROR_SAFETY`]^2 of `limit` after
/// an increment of size `dt` created `created` (a penalty node released
/// from a depth `v dt` past the surface by `v dt`: the energy grows with
/// `dt^2`; `created <= 0`: no limit).
fn energy_controlled(dt: f64, created: f64, limit: f64) -> f64 {
    if created > 0.0 && limit > 0.0 {
        dt * ERROR_SAFETY * (limit / created).sqrt()
    } else {
        f64::INFINITY
    }
}

/// Impact fractions outside `(IMPACT_MIN, IMPACT_MAX)` do not cut: an
/// initial overlap (0) or an impact at the end of the increment.
const IMPACT_MIN: f64 = 1e-6;
/// See [`IMPACT_MIN`].
const IMPACT_MAX: f64 = 0.99;

/// Why stepping stopped.
#[derive(Debug, Clone)]
pub enum StepError {
    /// An increment could not converge even at the smallest size.
    Cutbacks {
        /// Step index.
        step: usize,
        /// Time of the last converged state.
        time: f64,
        /// Size of the last failed attempt.
        dt: f64,
        /// Smallest allowed size.
        min_dt: f64,
        /// The last failure.
        failure: Failure,
        /// Stopped above `min_dt`: the iterative linear solver failed the
        /// same way at this size and at twice it (see the module notes).
        linear_repeat: bool,
    },
    /// Accepting an increment failed (e.g. writing results).
    Aborted(String),
}

/// True when `failure` repeats `previous`, the failure of the attempt just
/// before it (at twice the size) within the same increment, as a linear
/// solver failure with the same words: a smaller increment did not help
/// the linear solver and will not (see the module notes).
fn repeats_linear_failure(previous: Option<&Failure>, failure: &Failure) -> bool {
    failure.kind == FailureKind::LinearSolver
        && previous
            .is_some_and(|p| p.kind == FailureKind::LinearSolver && p.detail == failure.detail)
}

/// Runs all `steps` with `solver`.
pub fn drive(steps: &[Step], solver: &mut dyn IncrementSolver) -> Result<(), StepError> {
    drive_from(steps, solver, None)
}

/// Runs `steps` with `solver` from the beginning, or from `from` (a
/// restart point reported by [`IncrementSolver::checkpoint`]): the same
/// sequence of attempts as the uninterrupted run.
pub fn drive_from(
    steps: &[Step],
    solver: &mut dyn IncrementSolver,
    from: Option<Resume>,
) -> Result<(), StepError> {
    let from = from.map(|r| resumable(steps, r));
    let first = from.map_or(0, |r| r.step);
    for (si, step) in steps.iter().enumerate().skip(first) {
        let dt0 = (step.t_end - step.t_start) / step.increments as f64;
        let adaptive = step.dynamic.and_then(|d| d.adaptive);
        let min_dt = adaptive.map_or(dt0 * step.min_fraction, |a| a.dt_min.min(dt0));
        let max_dt = adaptive.map_or(dt0, |a| a.dt_max.max(min_dt));
        let error_tol = adaptive.map_or(0.0, |a| a.error_tol);
        let max_rotation = step.dynamic.and_then(|d| d.max_rotation);
        let energy_tol = step.dynamic.and_then(|d| d.energy_tol);
        // active contact nodes at the last accepted increment (contact
        // events of adaptive stepping)
        let mut last_active: Option<usize> = None;
        let easy_iterations = (step.newton.max_iter / 2).max(1);
        let (mut t, mut dt, mut easy) = match from {
            Some(r) if r.step == si => (r.time, r.dt, r.easy),
            _ => (step.t_start, dt0, 0),
        };
        while step.t_end - t > 1e-9 * dt0 {
            let mut cutbacks = 0;
            let mut impact_cut = false;
            // the failure of the attempt just before, in this increment
            let mut previous: Option<Failure> = None;
            loop {
                let remaining = step.t_end - t;
                let (this_dt, t_new) = if dt >= remaining - 1e-6 * dt0 {
                    (remaining, step.t_end)
                } else {
                    (dt, grid_time(step, t + dt))
                };
                let attempt = solver.attempt(si, t_new);
                // the energy the converged attempt would create (once:
                // the audit is a pass over every dof)
                let created = match (&attempt, energy_tol) {
                    (Ok(_), Some(_)) => solver.energy_created(),
                    _ => None,
                };
                match attempt {
                    Ok(conv)
                        if !impact_cut
                            && solver.impact_fraction().is_some_and(|tau| {
                                tau > IMPACT_MIN && tau < IMPACT_MAX && this_dt * tau >= min_dt
                            }) =>
                    {
                        // first impact inside the increment: redo it up to
                        // the impact (once; the retry ends at the impact)
                        let tau = solver.impact_fraction().unwrap_or(1.0);
                        let new_dt = this_dt * tau;
                        let failure = Failure {
                            kind: FailureKind::ImpactCut,
                            residuals: conv.residuals,
                            detail: format!("first impact at {tau:.4} of the increment"),
                        };
                        solver.reject(si, &failure, new_dt);
                        dt = new_dt;
                        impact_cut = true;
                        previous = None;
                    }
                    Ok(conv)
                        if adaptive.is_some()
                            && error_tol > 0.0
                            && this_dt > min_dt * (1.0 + 1e-9)
                            && solver
                                .local_error()
                                .is_some_and(|e| e > ERROR_REJECT * error_tol) =>
                    {
                        // the local error is too large: redo it smaller
                        let eta = solver.local_error().unwrap_or(0.0);
                        let new_dt = error_controlled(this_dt, Some(eta), error_tol)
                            .max(this_dt / 4.0)
                            .max(min_dt);
                        let failure = Failure {
                            kind: FailureKind::ErrorEstimate,
                            residuals: conv.residuals,
                            detail: format!(
                                "local error estimate {eta:.2e} above {ERROR_REJECT} x error_tol \
                                 = {error_tol:.2e}"
                            ),
                        };
                        solver.reject(si, &failure, new_dt);
                        dt = new_dt;
                        easy = 0;
                        previous = None;
                    }
                    Ok(conv)
                        if max_rotation.is_some_and(|m| {
                            this_dt > min_dt * (1.0 + 1e-9)
                                && solver.rotation().is_some_and(|(r, _)| r > m)
                        }) =>
                    {
                        // a cell turned too far: redo it smaller
                        let limit = max_rotation.unwrap_or(f64::INFINITY);
                        let (theta, at) = solver.rotation().unwrap_or((0.0, String::new()));
                        let new_dt = rotation_controlled(this_dt, theta, limit)
                            .max(this_dt / 4.0)
                            .max(min_dt);
                        let failure = Failure {
                            kind: FailureKind::Rotation,
                            residuals: conv.residuals,
                            detail: format!(
                                "{at} turned by {theta:.3e} rad in the increment, above \
                                 max_rotation = {limit:.3e}"
                            ),
                        };
                        solver.reject(si, &failure, new_dt);
                        dt = new_dt;
                        easy = 0;
                        previous = None;
                    }
                    Ok(conv)
                        if energy_tol.is_some_and(|tol| {
                            this_dt > min_dt * (1.0 + 1e-9)
                                && created
                                    .as_ref()
                                    .is_some_and(|(e, scale, _)| *e > tol * scale)
                        }) =>
                    {
                        // the increment created too much energy: redo it
                        // smaller
                        let tol = energy_tol.unwrap_or(f64::INFINITY);
                        let (created, scale, at) = created.unwrap_or((0.0, 0.0, String::new()));
                        let new_dt = energy_controlled(this_dt, created, tol * scale)
                            .max(this_dt / 4.0)
                            .max(min_dt);
                        let failure = Failure {
                            kind: FailureKind::Energy,
                            residuals: conv.residuals,
                            detail: format!(
                                "the increment created {created:.3e} of energy, above \
                                 energy_tol = {tol:.3e} of {scale:.3e}; {at}"
                            ),
                        };
                        solver.reject(si, &failure, new_dt);
                        dt = new_dt;
                        easy = 0;
                        previous = None;
                    }
                    Ok(conv) => {
                        let is_easy = cutbacks == 0 && conv.iterations <= easy_iterations;
                        let eta = if adaptive.is_some() {
                            solver.local_error()
                        } else {
                            None
                        };
                        let active = conv.active_contacts;
                        // the size the rotation of this increment allows
                        // the next one
                        let rotation_cap = max_rotation
                            .and_then(|m| solver.rotation().map(|(r, _)| (r, m)))
                            .map_or(f64::INFINITY, |(r, m)| rotation_controlled(this_dt, r, m));
                        // and the size its created energy allows
                        let energy_cap = energy_tol
                            .zip(created.as_ref())
                            .map_or(f64::INFINITY, |(tol, (e, scale, _))| {
                                energy_controlled(this_dt, *e, tol * scale)
                            });
                        solver
                            .accept(si, t_new, this_dt, cutbacks, conv)
                            .map_err(StepError::Aborted)?;
                        t = t_new;
                        easy = if is_easy { easy + 1 } else { 0 };
                        if adaptive.is_some() {
                            // the size of the accepted increment, not the
                            // remainder of the step it may have been cut to
                            let base = if this_dt < dt { dt } else { this_dt };
                            let mut next = error_controlled(base, eta, error_tol)
                                .clamp(base * CUT, base * GROW);
                            // growth after EASY_BEFORE_GROW easy increments
                            if easy < EASY_BEFORE_GROW {
                                next = next.min(base);
                            } else if next > base {
                                easy = 0;
                            }
                            if last_active.is_some_and(|n| n != active) {
                                next = next.min(this_dt * CUT);
                                easy = 0;
                            }
                            last_active = Some(active);
                            dt = next.clamp(min_dt, max_dt);
                        } else if easy >= EASY_BEFORE_GROW && dt < dt0 {
                            dt = (dt * GROW).min(dt0);
                            easy = 0;
                        }
                        if rotation_cap < dt {
                            dt = rotation_cap.max(min_dt);
                        }
                        if energy_cap < dt {
                            dt = energy_cap.max(min_dt);
                        }
                        let resume = if step.t_end - t > 1e-9 * dt0 {
                            Resume {
                                step: si,
                                time: t,
                                dt,
                                easy,
                            }
                        } else {
                            // the step is done: the next one starts afresh
                            let next = steps.get(si + 1);
                            Resume {
                                step: si + 1,
                                time: next.map_or(t, |s| s.t_start),
                                dt: next
                                    .map_or(0.0, |s| (s.t_end - s.t_start) / s.increments as f64),
                                easy: 0,
                            }
                        };
                        solver.checkpoint(&resume).map_err(StepError::Aborted)?;
                        break;
                    }
                    Err(failure) => {
                        let new_dt = this_dt * CUT;
                        let linear_repeat = repeats_linear_failure(previous.as_ref(), &failure);
                        if linear_repeat || new_dt < min_dt * (1.0 - 1e-9) {
                            return Err(StepError::Cutbacks {
                                step: si,
                                time: t,
                                dt: this_dt,
                                min_dt,
                                failure,
                                linear_repeat,
                            });
                        }
                        solver.reject(si, &failure, new_dt);
                        dt = new_dt;
                        cutbacks += 1;
                        easy = 0;
                        previous = Some(failure);
                    }
                }
            }
        }
    }
    Ok(())
}

/// Where a run continues from the restart point `r` among `steps`: the
/// point itself, but for a size that is not a positive number (the restart
/// point of a completed run carries 0: there was no next increment), which
/// becomes the step's planned size, and for a point inside a step it had
/// completed (`r` past step `s - 1`, whose end now lies beyond `r.time`: a
/// longer step), which continues that step from `r.time` at its planned
/// size. Without it a continued step would attempt zero-length increments
/// forever.
pub fn resumable(steps: &[Step], r: Resume) -> Resume {
    let planned = |s: &Step| (s.t_end - s.t_start) / s.increments.max(1) as f64;
    if let Some(prev) = r.step.checked_sub(1).and_then(|s| steps.get(s)) {
        let dt0 = planned(prev);
        if prev.t_end - r.time > 1e-9 * dt0 && r.time >= prev.t_start {
            return Resume {
                step: r.step - 1,
                time: r.time,
                dt: dt0,
                easy: 0,
            };
        }
    }
    match steps.get(r.step) {
        Some(s) if !(r.dt > 0.0 && r.dt.is_finite()) => Resume {
            dt: planned(s),
            easy: 0,
            ..r
        },
        _ => r,
    }
}

/// The position of `t` on the grid of step `step` in units of its
/// initial increment, when `t` is within round-off of a grid point.
fn grid_units(step: &Step, t: f64) -> Option<f64> {
    const FINE: f64 = (1u64 << 20) as f64;
    let n = step.increments.max(1) as f64;
    let span = step.t_end - step.t_start;
    if span.is_nan() || span <= 0.0 {
        return None;
    }
    let u = (t - step.t_start) * n / span;
    let q = (u * FINE).round() / FINE;
    ((u - q).abs() <= 1e-11 * u.abs().max(1.0)).then_some(q)
}

/// `t` of step `step`, snapped to the step's grid when it is within
/// round-off of it (see the module notes); other times unchanged.
pub fn grid_time(step: &Step, t: f64) -> f64 {
    let n = step.increments.max(1) as f64;
    grid_units(step, t).map_or(t, |q| step.t_start + (step.t_end - step.t_start) * q / n)
}

/// The time since the start of step `step` at analysis time `t`, computed
/// on the grid like [`grid_time`] (`0.3`, not `1.3 - 1.0`).
pub fn step_time(step: &Step, t: f64) -> f64 {
    let n = step.increments.max(1) as f64;
    grid_units(step, t).map_or(t - step.t_start, |q| (step.t_end - step.t_start) * q / n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::NewtonSettings;
    use crate::solve::newton::FailureKind;

    /// Converges whenever the increment is at most `max_dt`.
    struct Mock {
        max_dt: f64,
        t: f64,
        attempts: Vec<f64>,
        accepted: Vec<(f64, usize)>,
        rejected: Vec<f64>,
    }

    impl IncrementSolver for Mock {
        fn attempt(&mut self, _step: usize, t: f64) -> Result<Converged, Failure> {
            self.attempts.push(t);
            if t - self.t <= self.max_dt + 1e-12 {
                Ok(Converged {
                    iterations: 1,
                    residuals: vec![1e-16],
                    active_contacts: 0,
                    contact_iterations: 0,
                    max_penetration: 0.0,
                })
            } else {
                Err(Failure {
                    kind: FailureKind::MaxIterations,
                    residuals: vec![1.0, 0.5],
                    detail: "mock".into(),
                })
            }
        }
        fn accept(
            &mut self,
            _: usize,
            t: f64,
            _: f64,
            cutbacks: usize,
            _: Converged,
        ) -> Result<(), String> {
            self.t = t;
            self.accepted.push((t, cutbacks));
            Ok(())
        }
        fn reject(&mut self, _: usize, _: &Failure, new_dt: f64) {
            self.rejected.push(new_dt);
        }
    }

    fn step(t_end: f64, increments: usize, min_fraction: f64) -> Step {
        Step {
            name: "s".into(),
            t_start: 0.0,
            t_end,
            increments,
            min_fraction,
            newton: NewtonSettings::default(),
            dynamic: None,
        }
    }

    #[test]
    fn times_are_on_the_grid_not_sums_of_increments() {
        // 10 increments of 0.1: 0.1 + 0.1 + 0.1 is 0.30000000000000004
        let mut m = mock(1.0);
        drive(&[step(1.0, 10, 1e-3)], &mut m).unwrap();
        let times: Vec<String> = m.accepted.iter().map(|a| a.0.to_string()).collect();
        let expected: Vec<String> = (1..=10).map(|k| (k as f64 / 10.0).to_string()).collect();
        assert_eq!(times, expected);
        // cutbacks and grow-backs (0.05, 0.075, 0.0375, ..): every time is
        // exactly k / (10 * 2^20), the correctly rounded grid value
        let mut m = mock(0.06);
        drive(&[step(1.0, 10, 1e-3)], &mut m).unwrap();
        assert!(m.accepted.len() > 10);
        let grid = 10.0 * (1u64 << 20) as f64;
        for a in &m.accepted {
            let k = (a.0 * grid).round();
            assert_eq!(a.0, k / grid, "{:?}", m.accepted);
        }
        assert!(m.accepted.iter().any(|a| a.0 == 0.15), "{:?}", m.accepted);
        // a second step from 1 to 2 in thirds
        let mut s2 = step(2.0, 3, 1e-3);
        s2.t_start = 1.0;
        assert_eq!(grid_time(&s2, 1.0 + 1.0 / 3.0 + 1.0 / 3.0), 1.0 + 2.0 / 3.0);
        assert_eq!(step_time(&s2, 1.0 + 1.0 / 3.0 + 1.0 / 3.0), 2.0 / 3.0);
        // off-grid times (an impact cut) are kept
        assert_eq!(grid_time(&s2, 1.123456789), 1.123456789);
    }

    fn mock(max_dt: f64) -> Mock {
        Mock {
            max_dt,
            t: 0.0,
            attempts: vec![],
            accepted: vec![],
            rejected: vec![],
        }
    }

    #[test]
    fn cutback_then_grow_back_sequence() {
        let mut m = mock(0.3);
        drive(&[step(2.0, 2, 1e-3)], &mut m).unwrap();
        let times: Vec<f64> = m.accepted.iter().map(|a| a.0).collect();
        // dt 1 and 0.5 fail -> 0.25 (after 2 cutbacks, not easy), 0.5, 0.75
        // (two easy: grow to 0.375) -> 1.125 fails -> 0.1875: 0.9375 (not easy),
        // 1.125, 1.3125 (grow to 0.28125), 1.59375, 1.875 (grow), 2.0 (0.125 left)
        let expect = [0.25, 0.5, 0.75, 0.9375, 1.125, 1.3125, 1.59375, 1.875, 2.0];
        assert_eq!(times.len(), expect.len(), "{times:?}");
        for (a, b) in times.iter().zip(expect) {
            assert!((a - b).abs() < 1e-12, "{times:?}");
        }
        assert_eq!(m.rejected, vec![0.5, 0.25, 0.1875]);
        assert_eq!(m.accepted[0].1, 2);
        assert_eq!(m.accepted[3].1, 1);
        assert_eq!(m.accepted[4].1, 0);
        assert_eq!(*m.attempts.last().unwrap(), 2.0);
    }

    #[test]
    fn failure_below_min_increment_names_the_state() {
        let mut m = mock(0.0);
        let e = drive(&[step(1.0, 2, 1.0 / 8.0)], &mut m).unwrap_err();
        match e {
            StepError::Cutbacks {
                step,
                time,
                dt,
                min_dt,
                ..
            } => {
                assert_eq!((step, time), (0, 0.0));
                assert_eq!(dt, 0.0625);
                assert_eq!(min_dt, 0.0625);
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(m.attempts.len(), 4);
        assert_eq!(m.rejected, vec![0.25, 0.125, 0.0625]);
    }

    /// Converges always; the local error is `c dt^3` of the attempt and
    /// the active contact count switches from 1 to 0 at `release`.
    struct Smooth {
        mock: Mock,
        c: f64,
        release: f64,
        last_dt: f64,
    }

    impl IncrementSolver for Smooth {
        fn attempt(&mut self, step: usize, t: f64) -> Result<Converged, Failure> {
            self.last_dt = t - self.mock.t;
            let mut conv = self.mock.attempt(step, t)?;
            conv.active_contacts = usize::from(t <= self.release);
            Ok(conv)
        }
        fn accept(
            &mut self,
            s: usize,
            t: f64,
            dt: f64,
            cutbacks: usize,
            c: Converged,
        ) -> Result<(), String> {
            self.mock.accept(s, t, dt, cutbacks, c)
        }
        fn reject(&mut self, s: usize, f: &Failure, new_dt: f64) {
            self.mock.t = self.mock.accepted.last().map_or(0.0, |a| a.0);
            self.mock.reject(s, f, new_dt);
        }
        fn local_error(&self) -> Option<f64> {
            Some(self.c * self.last_dt.powi(3))
        }
    }

    fn adaptive_step(dt_max: f64, error_tol: f64) -> Step {
        let mut s = step(10.0, 100, 1e-3);
        s.dynamic = Some(crate::model::Dynamic {
            scheme: crate::model::Scheme::Newmark {
                beta: 0.25,
                gamma: 0.5,
            },
            mass: crate::model::MassMatrix::Consistent,
            contact_mass: crate::model::ContactMass::Redistributed,
            rayleigh: crate::model::Rayleigh::default(),
            adaptive: Some(crate::model::Adaptive {
                dt_min: 1e-3,
                dt_max,
                error_tol,
            }),
            max_rotation: None,
            energy_tol: None,
        });
        s
    }

    #[test]
    fn adaptive_steps_follow_the_error_estimate_and_contact_events() {
        // without an error estimate: growth by 1.5 after two easy
        // increments, up to dt_max (above the initial 0.1)
        let mut m = Smooth {
            mock: mock(10.0),
            c: 0.0,
            release: -1.0,
            last_dt: 0.0,
        };
        drive(&[adaptive_step(1.0, 0.0)], &mut m).unwrap();
        let dts: Vec<f64> = m
            .mock
            .accepted
            .windows(2)
            .map(|w| w[1].0 - w[0].0)
            .collect();
        assert!(dts.iter().all(|d| *d <= 1.0 + 1e-12), "{dts:?}");
        assert!(dts.iter().any(|d| (*d - 1.0).abs() < 1e-12), "{dts:?}");
        assert!(m.mock.accepted.len() < 30, "{}", m.mock.accepted.len());
        assert_eq!(m.mock.accepted.last().unwrap().0, 10.0);
        // error eta = c dt^3 against tol: the size settles where eta is
        // 0.9^3 tol .. tol, (tol / c)^(1/3) = 0.2 here; an attempt above
        // 2 tol is redone
        let (c, tol) = (1.0, 8e-3);
        let mut m = Smooth {
            mock: mock(10.0),
            c,
            release: -1.0,
            last_dt: 0.0,
        };
        drive(&[adaptive_step(5.0, tol)], &mut m).unwrap();
        let acc = &m.mock.accepted;
        let last: Vec<f64> = acc.windows(2).map(|w| w[1].0 - w[0].0).collect();
        for d in &last[last.len() / 2..last.len() - 1] {
            assert!(*d <= 0.2 * 2f64.cbrt() && *d >= 0.2 * 0.9 * 0.5, "{last:?}");
        }
        for d in &last {
            assert!(c * d.powi(3) <= 2.0 * tol * (1.0 + 1e-12), "{last:?}");
        }
        // a release halves the next size
        let mut m = Smooth {
            mock: mock(10.0),
            c: 0.0,
            release: 5.0,
            last_dt: 0.0,
        };
        drive(&[adaptive_step(1.0, 0.0)], &mut m).unwrap();
        let acc = &m.mock.accepted;
        let i = acc.iter().position(|a| a.0 > 5.0).unwrap();
        let before = acc[i].0 - acc[i - 1].0;
        let after = acc[i + 1].0 - acc[i].0;
        assert!((after - 0.5 * before).abs() < 1e-12, "{before} {after}");
    }

    /// Converges always; `amount(t0, t1)` of the increment from `t0` to
    /// `t1` is what a dynamic limit weighs: the rotation of cell 7 (`kind`
    /// Rotation) or the energy created at node 3 against a scale of 1
    /// (`kind` Energy); a rejection must name that kind and place.
    struct Watched {
        mock: Mock,
        kind: FailureKind,
        amount: Box<dyn Fn(f64, f64) -> f64>,
        last: (f64, f64),
    }

    impl Watched {
        /// A cell turning by `rate` times the increment's size until
        /// `stop`, then by nothing.
        fn spinning(rate: f64, stop: f64) -> Watched {
            Watched {
                mock: mock(10.0),
                kind: FailureKind::Rotation,
                amount: Box::new(move |t0: f64, t1: f64| {
                    rate * (t1.min(stop) - t0.min(stop)).max(0.0)
                }),
                last: (0.0, 0.0),
            }
        }

        /// An increment creating `rate (t1 - t0)^2` of energy inside
        /// `window`, nothing elsewhere.
        fn creating(rate: f64, window: (f64, f64)) -> Watched {
            Watched {
                mock: mock(10.0),
                kind: FailureKind::Energy,
                amount: Box::new(move |t0: f64, t1: f64| {
                    if t1 > window.0 && t0 < window.1 {
                        rate * (t1 - t0).powi(2)
                    } else {
                        0.0
                    }
                }),
                last: (0.0, 0.0),
            }
        }
    }

    impl IncrementSolver for Watched {
        fn attempt(&mut self, step: usize, t: f64) -> Result<Converged, Failure> {
            self.last = (self.mock.t, t);
            self.mock.attempt(step, t)
        }
        fn accept(
            &mut self,
            s: usize,
            t: f64,
            dt: f64,
            cutbacks: usize,
            c: Converged,
        ) -> Result<(), String> {
            self.mock.accept(s, t, dt, cutbacks, c)
        }
        fn reject(&mut self, s: usize, f: &Failure, new_dt: f64) {
            assert_eq!(f.kind, self.kind, "{f:?}");
            if self.kind == FailureKind::Rotation {
                assert!(f.detail.starts_with("cell 7 turned by"), "{}", f.detail);
            } else {
                assert!(f.detail.contains("node 3"), "{}", f.detail);
            }
            self.mock.t = self.mock.accepted.last().map_or(0.0, |a| a.0);
            self.mock.reject(s, f, new_dt);
        }
        fn rotation(&self) -> Option<(f64, String)> {
            (self.kind == FailureKind::Rotation)
                .then(|| ((self.amount)(self.last.0, self.last.1), "cell 7".into()))
        }
        fn energy_created(&self) -> Option<(f64, f64, String)> {
            (self.kind == FailureKind::Energy).then(|| {
                (
                    (self.amount)(self.last.0, self.last.1),
                    1.0,
                    "node 3".into(),
                )
            })
        }
    }

    #[test]
    fn a_rotation_limit_redoes_and_caps_the_increments_that_turn_a_cell_too_far() {
        // fixed increments of 0.1 over 10, a cell turning 1.5 rad per unit
        // time to t = 5 (0.15 rad per increment), the limit 0.05: the first
        // increment is redone at 0.9 x 0.05 / 0.15 of it, then every
        // increment stays at that size (never above the limit); once the
        // spin stops the size grows back to the initial one
        let mut s = step(10.0, 100, 1e-3);
        s.dynamic = adaptive_step(1.0, 0.0)
            .dynamic
            .map(|d| crate::model::Dynamic {
                adaptive: None,
                max_rotation: Some(0.05),
                ..d
            });
        let mut m = Watched::spinning(1.5, 5.0);
        drive(&[s.clone()], &mut m).unwrap();
        let acc = &m.mock.accepted;
        assert_eq!(m.mock.rejected.len(), 1, "{:?}", m.mock.rejected);
        assert!((m.mock.rejected[0] - 0.03).abs() < 1e-12);
        let dts: Vec<(f64, f64)> = std::iter::once((0.0, acc[0].0))
            .chain(acc.windows(2).map(|w| (w[0].0, w[1].0)))
            .collect();
        for &(t0, t1) in &dts {
            let spun = 1.5 * (t1.min(5.0) - t0.min(5.0));
            assert!(spun <= 0.05 * (1.0 + 1e-9), "{t0} {t1}: {spun}");
            if t1 < 5.0 {
                assert!((t1 - t0 - 0.03).abs() < 1e-9, "{t0} {t1}");
            }
        }
        assert!(
            dts.iter()
                .any(|&(t0, t1)| t0 > 6.0 && (t1 - t0 - 0.1).abs() < 1e-9),
            "{dts:?}"
        );
        assert_eq!(acc.last().unwrap().0, 10.0);
        // without the limit: the 100 increments, none redone
        s.dynamic = s.dynamic.map(|d| crate::model::Dynamic {
            max_rotation: None,
            energy_tol: None,
            ..d
        });
        let mut m = Watched::spinning(1.5, 5.0);
        drive(&[s], &mut m).unwrap();
        assert_eq!(m.mock.accepted.len(), 100);
        assert!(m.mock.rejected.is_empty());
    }

    /// Records the restart points reported by the stepper.
    struct Recorder {
        mock: Mock,
        resumes: Vec<Resume>,
    }

    impl IncrementSolver for Recorder {
        fn attempt(&mut self, step: usize, t: f64) -> Result<Converged, Failure> {
            self.mock.attempt(step, t)
        }
        fn accept(
            &mut self,
            s: usize,
            t: f64,
            dt: f64,
            cutbacks: usize,
            c: Converged,
        ) -> Result<(), String> {
            self.mock.accept(s, t, dt, cutbacks, c)
        }
        fn reject(&mut self, s: usize, f: &Failure, new_dt: f64) {
            self.mock.reject(s, f, new_dt);
        }
        fn checkpoint(&mut self, resume: &Resume) -> Result<(), String> {
            self.resumes.push(*resume);
            Ok(())
        }
    }

    #[test]
    fn resume_from_every_checkpoint_repeats_the_remaining_sequence() {
        let second = Step {
            t_start: 2.0,
            t_end: 3.0,
            ..step(1.0, 2, 1e-3)
        };
        let steps = [step(2.0, 2, 1e-3), second];
        let mut full = Recorder {
            mock: mock(0.3),
            resumes: vec![],
        };
        drive(&steps, &mut full).unwrap();
        assert_eq!(full.resumes.len(), full.mock.accepted.len());
        assert_eq!(full.resumes.last().unwrap().step, 2);
        for (k, r) in full.resumes.iter().enumerate() {
            let mut m = mock(0.3);
            m.t = r.time;
            let mut rest = Recorder {
                mock: m,
                resumes: vec![],
            };
            drive_from(&steps, &mut rest, Some(*r)).unwrap();
            assert_eq!(rest.mock.accepted, full.mock.accepted[k + 1..], "from {k}");
            assert_eq!(rest.resumes, full.resumes[k + 1..], "from {k}");
        }
    }

    #[test]
    fn a_restart_point_without_a_next_size_continues_at_the_planned_size() {
        // the restart point of a completed run carries dt = 0 (there was
        // no next increment): continued into a step added after it, or
        // into its own last step made longer, the run takes the step's
        // planned size instead of zero-length increments (which never
        // reach the step's end)
        let first = step(2.0, 2, 1e-3);
        let done = Resume {
            step: 1,
            time: 2.0,
            dt: 0.0,
            easy: 0,
        };
        // a new step 2 -> 3 in 4 increments
        let added = Step {
            t_start: 2.0,
            t_end: 3.0,
            ..step(1.0, 4, 1e-3)
        };
        let mut m = mock(1.0);
        m.t = 2.0;
        drive_from(&[first.clone(), added], &mut m, Some(done)).unwrap();
        let times: Vec<f64> = m.accepted.iter().map(|a| a.0).collect();
        assert_eq!(times, [2.25, 2.5, 2.75, 3.0]);
        // the first step made longer: 0 -> 3 in 3 increments, continued
        // from t = 2 at its planned size 1
        let longer = step(3.0, 3, 1e-3);
        let mut m = mock(1.0);
        m.t = 2.0;
        drive_from(std::slice::from_ref(&longer), &mut m, Some(done)).unwrap();
        assert_eq!(m.accepted.iter().map(|a| a.0).collect::<Vec<_>>(), [3.0]);
        // a point with a size, and a completed run, are left as they are
        let mid = Resume {
            step: 0,
            time: 1.0,
            dt: 0.5,
            easy: 1,
        };
        assert_eq!(resumable(std::slice::from_ref(&longer), mid), mid);
        let end = Resume {
            step: 1,
            time: 3.0,
            dt: 0.0,
            easy: 0,
        };
        assert_eq!(resumable(&[longer], end), end);
    }

    #[test]
    fn an_energy_limit_redoes_and_caps_the_increments_that_create_energy() {
        // increments of 0.1 over 10; between t = 4 and 6 an increment
        // creates 10 dt^2 (0.1 at the planned size), the limit 1e-3: the
        // first increment there is redone at 0.9 sqrt(1e-3 / 0.1) dt
        // (0.009, at least dt / 4 = 0.025), and every accepted one creates
        // at most the limit; past t = 6 the size grows back
        let mut s = step(10.0, 100, 1e-4);
        s.dynamic = adaptive_step(1.0, 0.0)
            .dynamic
            .map(|d| crate::model::Dynamic {
                adaptive: None,
                energy_tol: Some(1e-3),
                ..d
            });
        let mut m = Watched::creating(10.0, (4.0, 6.0));
        drive(&[s.clone()], &mut m).unwrap();
        let acc = &m.mock.accepted;
        assert!(!m.mock.rejected.is_empty());
        assert!(
            (m.mock.rejected[0] - 0.025).abs() < 1e-12,
            "{:?}",
            m.mock.rejected
        );
        let dts: Vec<(f64, f64)> = std::iter::once((0.0, acc[0].0))
            .chain(acc.windows(2).map(|w| (w[0].0, w[1].0)))
            .collect();
        for &(t0, t1) in &dts {
            if t1 > 4.0 && t0 < 6.0 {
                assert!(10.0 * (t1 - t0).powi(2) <= 1e-3 * (1.0 + 1e-9), "{t0} {t1}");
            }
        }
        assert!(
            dts.iter()
                .any(|&(t0, t1)| t0 > 7.0 && (t1 - t0 - 0.1).abs() < 1e-9),
            "{dts:?}"
        );
        assert_eq!(acc.last().unwrap().0, 10.0);
    }

    #[test]
    fn equal_increments_without_failures_end_exactly_at_t_end() {
        let mut m = mock(1.0);
        drive(&[step(1.0, 3, 0.5)], &mut m).unwrap();
        assert_eq!(m.accepted.len(), 3);
        assert_eq!(m.accepted[2].0, 1.0);
        assert!((m.accepted[0].0 - 1.0 / 3.0).abs() < 1e-15);
    }

    /// Fails every attempt larger than `max_dt` with what `failure` says
    /// for the attempt's size; converges otherwise.
    struct Scripted {
        mock: Mock,
        failure: fn(f64) -> Failure,
    }

    impl IncrementSolver for Scripted {
        fn attempt(&mut self, step: usize, t: f64) -> Result<Converged, Failure> {
            let dt = t - self.mock.t;
            self.mock.attempt(step, t).map_err(|_| (self.failure)(dt))
        }
        fn accept(
            &mut self,
            s: usize,
            t: f64,
            dt: f64,
            cutbacks: usize,
            c: Converged,
        ) -> Result<(), String> {
            self.mock.accept(s, t, dt, cutbacks, c)
        }
        fn reject(&mut self, s: usize, f: &Failure, new_dt: f64) {
            self.mock.reject(s, f, new_dt);
        }
    }

    /// A Krylov solve capped at its iteration limit, at any size.
    fn capped(_dt: f64) -> Failure {
        Failure::new(
            FailureKind::LinearSolver,
            "PETSc: the Krylov solver did not converge: DIVERGED_ITS (-3) after 2 iterations",
        )
    }

    #[test]
    fn a_linear_solver_failing_the_same_way_at_half_the_size_stops_the_run() {
        // issue 21: every attempt's Krylov solve stops at its cap; the old
        // rule halved 1 -> 1/1024 (10 cutbacks) before stopping
        let mut m = Scripted {
            mock: mock(0.0),
            failure: capped,
        };
        let e = drive(&[step(1.0, 1, 1.0 / 1024.0)], &mut m).unwrap_err();
        let StepError::Cutbacks {
            dt,
            min_dt,
            linear_repeat,
            failure,
            ..
        } = e
        else {
            panic!("{e:?}")
        };
        assert!(linear_repeat);
        assert_eq!((dt, min_dt), (0.5, 1.0 / 1024.0));
        assert_eq!(failure.kind, FailureKind::LinearSolver);
        assert_eq!(m.mock.attempts, vec![1.0, 0.5]);
        assert_eq!(m.mock.rejected, vec![0.5], "one cutback");

        // the same failure cured by the cutback: the run goes on
        let mut m = Scripted {
            mock: mock(0.5),
            failure: capped,
        };
        drive(&[step(1.0, 1, 1.0 / 1024.0)], &mut m).unwrap();
        assert_eq!(m.mock.accepted[0], (0.5, 1));

        // different words at each size (a breakdown after a number of
        // iterations that changes with the size): cut back as before, down
        // to the attempt that converges
        let mut m = Scripted {
            mock: mock(0.1),
            failure: |dt| {
                Failure::new(
                    FailureKind::LinearSolver,
                    format!(
                        "DIVERGED_BREAKDOWN after {} iterations",
                        (dt * 64.0) as usize
                    ),
                )
            },
        };
        drive(&[step(1.0, 1, 1.0 / 1024.0)], &mut m).unwrap();
        assert_eq!(m.mock.rejected[..4], [0.5, 0.25, 0.125, 0.0625]);
        assert_eq!(m.mock.accepted[0], (0.0625, 4));

        // a Newton failure between two equal linear failures: not
        // consecutive, no stop
        let mut m = Scripted {
            mock: mock(0.0),
            failure: |dt| {
                if dt == 0.5 {
                    Failure::new(FailureKind::MaxIterations, "no convergence")
                } else {
                    capped(dt)
                }
            },
        };
        let e = drive(&[step(1.0, 1, 1.0 / 1024.0)], &mut m).unwrap_err();
        let StepError::Cutbacks { dt, .. } = e else {
            panic!("{e:?}")
        };
        assert_eq!(
            dt, 0.125,
            "1 and 0.25 are not consecutive: 0.125 repeats 0.25"
        );
        assert_eq!(m.mock.rejected, vec![0.5, 0.25, 0.125]);
    }
}
