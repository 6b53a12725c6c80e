//! Vanishing stabilization of bodies held only by contact
//! (`newton { stabilize }` / `stabilize = c`): a body pushed by a load onto
//! another with no `fix`/`displace` holding it is free until its contact
//! closes, so the tangent of the first iteration is singular (issue 14,
//! item 8). Like Abaqus's `*CONTACT STABILIZATION` / `STABILIZE`, a
//! viscous-like term on the increment displacement is added to the free
//! dofs of those bodies ([`super::check::held_only_by_contact`]):
//!
//! `f_s = k_i (u_i - u_i^committed)`, `k_i = c(t) d_b`,
//!
//! `d_b` the mean diagonal of the element stiffness over the free dofs of
//! body `b` (reference configuration), `c(t) = c (t_end - t) / (t_end -
//! t_start)` ramped down linearly over the step to exactly 0 at its end:
//! the converged end-of-step state is unstabilized equilibrium. Its work
//! `sum k_i (du_i)^2` per increment is reported with the internal work
//! (trapezoidal `sum (f_int^n + f_int^(n+1)) / 2 du`) and a warning is
//! given when it exceeds [`ENERGY_WARNING_FRACTION`] of it (Abaqus's ALLSD
//! / ALLIE check).

use super::dofs::DofMap;
use super::linalg::SparsePattern;
use crate::model::{Model, Step};

/// The factor of a bare `stabilize`.
pub const DEFAULT_FACTOR: f64 = 1e-5;

/// Stabilization energy over internal work above which a run warns.
pub const ENERGY_WARNING_FRACTION: f64 = 0.05;

/// Stabilization of one run: the spring scale per free dof and the energy
/// bookkeeping.
#[derive(Debug, Clone, Default)]
pub struct Stabilization {
    /// Per free dof: the mean diagonal `d_b` of its body (0: not
    /// stabilized).
    pub scale: Vec<f64>,
    /// Names of the stabilized bodies.
    pub bodies: Vec<String>,
    /// Ramped factor `c(t)` of the current increment (0: off).
    pub factor: f64,
    /// Work of the stabilization forces over the converged increments of
    /// the current step.
    pub step_energy: f64,
    /// Work of the last converged increment.
    pub increment_energy: f64,
    /// Internal work (strain energy plus dissipation) over the run.
    pub internal_energy: f64,
    /// Euclidean norm of the stabilization forces at the last converged
    /// state.
    pub force: f64,
    /// Internal forces at the last converged state (all dofs).
    f_int_committed: Vec<f64>,
    /// Step of the current increment.
    step: Option<usize>,
}

impl Stabilization {
    /// The stabilization of `model`: empty (no stabilized dof) unless a
    /// step asks for it; `diagonal(j)` is the element stiffness `K_jj` of
    /// free dof `j` in the reference configuration.
    pub fn new<const D: usize>(
        model: &Model<D>,
        dofs: &DofMap<D>,
        diagonal: impl Fn(usize) -> f64,
    ) -> Self
    where
        nalgebra::Const<D>: crate::geom::Dimension<D>,
    {
        let mut s = Stabilization {
            scale: vec![0.0; dofs.n_free()],
            f_int_committed: vec![0.0; dofs.dofs.len()],
            ..Default::default()
        };
        if !model.steps.iter().any(|st| st.newton.stabilize.is_some()) {
            return s;
        }
        let nc = dofs.components();
        let held = super::check::held_only_by_contact(model);
        for (b, body) in model.bodies.iter().enumerate() {
            if !held.get(b).copied().unwrap_or(false) {
                continue;
            }
            let free: Vec<usize> = dofs
                .free
                .iter()
                .enumerate()
                .filter(|(_, &g)| body.nodes.contains(&(g / nc)))
                .map(|(j, _)| j)
                .collect();
            let sum: f64 = free.iter().map(|&j| diagonal(j).abs()).sum();
            let mean = sum / free.len().max(1) as f64;
            if !(mean.is_finite() && mean > 0.0) {
                continue;
            }
            for j in free {
                s.scale[j] = mean;
            }
            s.bodies.push(body.name.clone());
        }
        s
    }

    /// Whether any dof is stabilized.
    pub fn any(&self) -> bool {
        !self.bodies.is_empty()
    }

    /// Sets the factor of an increment of step `index` (`step`) ending at
    /// `t`; the step's energy starts at 0 in its first increment.
    pub fn begin_increment(&mut self, index: usize, step: &Step, t: f64) {
        if self.step != Some(index) {
            self.step = Some(index);
            self.step_energy = 0.0;
        }
        self.factor = match step.newton.stabilize {
            Some(c) if self.any() => ramp(c, step, t),
            _ => 0.0,
        };
    }

    /// Adds the stabilization forces at displacements `u` (relative to
    /// the `committed` ones) to the free residual `r_free`.
    pub fn add_forces(
        &self,
        dofs_free: &[usize],
        u: &[f64],
        committed: &[f64],
        r_free: &mut [f64],
    ) {
        if self.factor <= 0.0 {
            return;
        }
        for ((r, &g), &d) in r_free.iter_mut().zip(dofs_free).zip(&self.scale) {
            if d > 0.0 {
                *r += self.factor * d * (u[g] - committed[g]);
            }
        }
    }

    /// Adds the springs `c(t) d_b` to the diagonal of the free-free
    /// tangent `values` (pattern `pattern`).
    pub fn add_springs(&self, pattern: &SparsePattern, values: &mut [f64]) {
        if self.factor <= 0.0 {
            return;
        }
        for (j, &d) in self.scale.iter().enumerate() {
            if d > 0.0 && j < pattern.n {
                if let Some(k) = pattern.find(j, j) {
                    values[k] += self.factor * d;
                }
            }
        }
    }

    /// Carries the committed internal force of a free 3D body's rotation
    /// vector (dofs `dofs`) over to another chart
    /// ([`super::rotation_chart`]).
    pub fn rechart(&mut self, dofs: [usize; 3], chart: &super::rotation_chart::Chart) {
        if self.f_int_committed.is_empty() {
            return;
        }
        let f = chart.force(dofs.map(|g| self.f_int_committed[g]));
        for (g, f) in dofs.iter().zip(f) {
            self.f_int_committed[*g] = f;
        }
    }

    /// Books the converged increment from `committed` to `u` with internal
    /// forces `f_int` (all dofs): stabilization and internal work, and the
    /// stabilization force at the converged state.
    pub fn commit(&mut self, dofs_free: &[usize], u: &[f64], committed: &[f64], f_int: &[f64]) {
        let mut work = 0.0;
        let mut f2 = 0.0;
        if self.factor > 0.0 {
            for (&g, &d) in dofs_free.iter().zip(&self.scale) {
                if d > 0.0 {
                    let du = u[g] - committed[g];
                    let f = self.factor * d * du;
                    work += f * du;
                    f2 += f * f;
                }
            }
        }
        self.increment_energy = work;
        self.step_energy += work;
        self.force = f2.sqrt();
        if self.f_int_committed.len() == f_int.len() {
            let internal: f64 = f_int
                .iter()
                .zip(&self.f_int_committed)
                .zip(u.iter().zip(committed))
                .map(|((a, b), (x, y))| 0.5 * (a + b) * (x - y))
                .sum();
            self.internal_energy += internal;
            self.f_int_committed.copy_from_slice(f_int);
        }
    }
}

/// `c (t_end - t) / (t_end - t_start)`, 0 at (and within round-off of) the
/// step's end.
pub fn ramp(c: f64, step: &Step, t: f64) -> f64 {
    let span = step.t_end - step.t_start;
    if !(span > 0.0 && c > 0.0) {
        return 0.0;
    }
    let left = (step.t_end - t) / span;
    if left <= 1e-12 {
        0.0
    } else {
        c * left.min(1.0)
    }
}

/// The stabilization of one converged increment in the run summary.
#[derive(Debug, Clone, serde::Serialize)]
pub struct IncrementRecord {
    /// The ramped factor `c(t)` of the increment.
    pub factor: f64,
    /// Work of the stabilization forces over the increment.
    pub energy: f64,
    /// Norm of the stabilization forces at convergence.
    pub force: f64,
}

/// The stabilization of one step in the run summary.
#[derive(Debug, Clone, serde::Serialize)]
pub struct StepRecord {
    /// Step name.
    pub step: String,
    /// The factor `c` at the start of the step (ramped to 0 at its end).
    pub factor: f64,
    /// The stabilized bodies (held only by contact).
    pub bodies: Vec<String>,
    /// Work of the stabilization forces over the step.
    pub energy: f64,
    /// Internal work (strain energy plus dissipation) at the end of the
    /// step, over the run.
    pub internal_energy: f64,
    /// `energy / internal_energy` (0 without internal work).
    pub ratio: f64,
    /// Norm of the stabilization forces at the last converged state of the
    /// step (0 when the step reached its end: the factor is 0 there).
    pub end_force: f64,
    /// Whether the step reached its end.
    pub completed: bool,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::NewtonSettings;

    #[test]
    fn the_factor_ramps_to_zero_at_the_step_end() {
        let step = Step {
            name: "s".into(),
            t_start: 1.0,
            t_end: 3.0,
            increments: 4,
            min_fraction: 1e-3,
            newton: NewtonSettings::default(),
            dynamic: None,
        };
        assert_eq!(ramp(1e-4, &step, 1.0), 1e-4);
        assert!((ramp(1e-4, &step, 2.0) - 5e-5).abs() < 1e-18);
        assert_eq!(ramp(1e-4, &step, 3.0), 0.0);
        assert_eq!(ramp(1e-4, &step, 3.0 - 1e-15), 0.0);
        assert_eq!(ramp(0.0, &step, 2.0), 0.0);
        assert_eq!(ramp(f64::NAN, &step, 2.0), 0.0);
    }
}
