//! The consistent start of a dynamic step (issue 19): the massless free
//! dofs carry no inertia, so their equation `r_q(u) = 0` is static at every
//! instant, the start included. A load present at the start on such a dof
//! (a moment on a 3D rigid body's spin node, a force on a spring's end
//! node, gravity on the contact nodes of `contact_mass = redistributed`)
//! is balanced there by the bodies it is attached to, whose masses it
//! accelerates from the first instant. The start solves, linearized at
//! the initial state `u0` (the tangent `K` of the static forces):
//!
//! ```text
//! K_qq du_q = -r_q(u0)                       (the massless dofs' equilibrium)
//! M_mm a0_m = -(r_m(u0) + K_mq du_q)         (the massy dofs' acceleration)
//! ```
//!
//! (Abaqus likewise solves the initial equilibrium before the first
//! increment; generalized-alpha is second order only from a consistent
//! `a0`.) The displacements stay `u0`: the first increment's equation
//! puts the massless dofs at their equilibrium, and the committed residual
//! `r0 = r(u0) + K du` is zero on them, so its `alpha_f r0` share does not
//! carry the start's imbalance into the next increments.

use super::{Failure, Newton};
use crate::geom::Dimension;
use crate::solve::dynamics::Dynamics;
use crate::solve::scene::ContactScene;
use nalgebra::Const;

/// The massless dofs' residual below this fraction of the largest force
/// of the start (internal, external, contact) is round-off: the start
/// solves nothing then (measured: the initial residual of the unloaded
/// massless dofs of the dynamics cases is exactly 0 or ~1e-16 of it).
const MASSLESS_TOL: f64 = 1e-12;

/// The start of a dynamic step ([`Newton::consistent_start`]).
pub(super) struct Start {
    /// The residual per dof the initial acceleration is solved with.
    pub residual: Vec<f64>,
    /// The change of the contact forces per dof in the condensation
    /// (`-K_c du`; the rest of `K du` is the internal forces').
    pub contact: Vec<f64>,
}

impl<const D: usize> Newton<'_, D>
where
    Const<D>: Dimension<D>,
{
    /// The residual per dof the initial acceleration is solved with
    /// ([`Dynamics::start`]): `r(u0)` plus the forces of the static
    /// condensation of the massless free dofs (module docs), evaluated at
    /// time `t0` (`dy`: the dynamics, taken out of `self` by the caller, so
    /// the tangent is the static one). `r(u0)` unchanged when no massless
    /// dof is loaded, under a distributed assembly split over ranks, with
    /// active Lagrange constraints, or when `K_qq` cannot be factorized
    /// (the former start: those dofs' acceleration 0).
    pub(super) fn consistent_start(&mut self, dy: &Dynamics, t0: f64) -> Result<Start, Failure> {
        let mut r = self.r_static.clone();
        let massless = dy.massless_free(self.model, &self.dofs);
        let loaded: f64 = r
            .iter()
            .zip(&massless)
            .filter(|(_, q)| **q)
            .map(|(r, _)| r * r)
            .sum::<f64>()
            .sqrt();
        let scale = [&self.f_int, &self.f_ext, &self.f_follow, &self.f_c]
            .iter()
            .map(|f| f.iter().map(|x| x * x).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        let split = self.share.as_ref().is_some_and(|s| s.split());
        let unchanged = |r: Vec<f64>| Start {
            contact: vec![0.0; r.len()],
            residual: r,
        };
        if loaded <= MASSLESS_TOL * scale || split {
            return Ok(unchanged(r));
        }
        self.evaluate(t0, true)?;
        r.copy_from_slice(&self.r_static);
        if self.saddle.is_some() && !self.contacts.constraints().is_empty() {
            return Ok(unchanged(r));
        }
        let pattern = &self.scatter.pattern;
        let free = &self.dofs.free;
        let q: Vec<bool> = free.iter().map(|&g| massless[g]).collect();
        // K_qq, and the identity on the massy dofs (rows and columns cut:
        // symmetric when K is)
        let mut values = self.values[..pattern.nnz()].to_vec();
        for j in 0..pattern.n {
            let range = pattern.col_ptr[j]..pattern.col_ptr[j + 1];
            for (v, &i) in values[range.clone()]
                .iter_mut()
                .zip(&pattern.row_idx[range])
            {
                if !(q[i] && q[j]) {
                    *v = if i == j { 1.0 } else { 0.0 };
                }
            }
        }
        let mut du: Vec<f64> = free
            .iter()
            .zip(&q)
            .map(|(&g, q)| if *q { -r[g] } else { 0.0 })
            .collect();
        if self.linear.factorize(pattern, &values).is_err() || self.linear.solve(&mut du).is_err() {
            return Ok(unchanged(r));
        }
        // r + K du on the free rows (0 on the massless ones), and the
        // contact forces' share `-K_c du` of it
        let mut kc = vec![0.0; self.values.len()];
        self.contacts
            .add_tangent(&self.scatter, &self.dofs, &mut kc);
        let mut contact = vec![0.0; r.len()];
        for (j, d) in du.iter().enumerate() {
            if *d == 0.0 {
                continue;
            }
            for k in pattern.col_ptr[j]..pattern.col_ptr[j + 1] {
                let g = free[pattern.row_idx[k]];
                r[g] += self.values[k] * d;
                contact[g] -= kc[k] * d;
            }
        }
        Ok(Start {
            residual: r,
            contact,
        })
    }
}
