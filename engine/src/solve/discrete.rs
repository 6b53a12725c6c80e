//! Springs and dashpots of `model::Discrete` in the residual and the
//! tangent: to the ground (`Ground`: `k u` on the node's diagonal) and
//! between two nodes (`Link`: `k (u_a - u_b)` on `a`, its opposite on
//! `b`, with the 2 x 2 node block `[k, -k; -k, k]` per component). The
//! springs are part of `f_int` (their energy is internal work of the
//! audit); the dashpots' forces are the same operator on velocities,
//! applied by `dynamics::Dynamics` with the Rayleigh damping.
//!
//! A link couples two nodes that may share no cell: their pairs join the
//! sparsity pattern ([`couplings`], [`scatter_for`]) at every place it is
//! built (start, contact growth, restart); so do the pilot nodes of free
//! tools with their pairs' slave nodes (`free_tool::couplings`).

use super::dofs::{Dof, DofMap};
use super::linalg::Scatter;
use crate::model::{Discrete, Model};

/// The node pairs of the links (smaller node first, sorted, unique).
pub fn couplings<const D: usize>(model: &Model<D>) -> Vec<(usize, usize)> {
    let mut out: Vec<(usize, usize)> = model
        .discrete
        .iter()
        .flat_map(|d| match d {
            Discrete::Link { pairs, .. } => pairs.clone(),
            Discrete::Rigid {
                nodes, pilot, spin, ..
            } => super::rigid_body::couplings(nodes, *pilot, *spin),
            _ => Vec::new(),
        })
        .filter(|(a, b)| a != b)
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// The scatter of `model` with the links' couplings and `extra` (contact
/// couplings) in its pattern.
pub fn scatter_for<const D: usize>(
    model: &Model<D>,
    dofs: &DofMap<D>,
    extra: &[(usize, usize)],
    share: Option<&std::sync::Arc<crate::solve::share::AssemblyShare>>,
) -> Result<Scatter, String> {
    let mut all = couplings(model);
    all.extend(super::free_tool::couplings(model));
    if all.is_empty() {
        return Scatter::with_share(&model.mesh, dofs, extra, share.cloned());
    }
    all.extend_from_slice(extra);
    Scatter::with_share(&model.mesh, dofs, &all, share.cloned())
}

/// Whether the model has a link or a ground element whose `pick(k, c)`
/// coefficient is not zero.
pub fn any<const D: usize>(model: &Model<D>, pick: impl Fn(f64, f64) -> f64) -> bool {
    model.discrete.iter().any(|d| match d {
        Discrete::Ground {
            stiffness, damping, ..
        }
        | Discrete::Link {
            stiffness, damping, ..
        } => pick(*stiffness, *damping) != 0.0,
        Discrete::Mass { .. } | Discrete::Rigid { .. } => false,
    })
}

/// Whether a link released at `release_at` still acts at time `t`.
pub fn linked(release_at: Option<f64>, t: f64) -> bool {
    release_at.is_none_or(|r| t < r)
}

/// `out += A x` over all dofs (`x`, `out` per dof `node D + c`), `A` the
/// operator of the ground elements and links with the coefficient
/// `pick(k, c)` (springs: `|k, _| k`, dashpots: `|_, c| c`) at time `t`
/// (a link released at or before `t` is gone). The rigid bodies are not
/// linear: `rigid_body::add_forces`.
pub fn times<const D: usize>(
    model: &Model<D>,
    x: &[f64],
    out: &mut [f64],
    t: f64,
    pick: impl Fn(f64, f64) -> f64,
) {
    for d in &model.discrete {
        match d {
            Discrete::Ground {
                nodes,
                stiffness,
                damping,
                ..
            } => {
                let k = pick(*stiffness, *damping);
                if k == 0.0 {
                    continue;
                }
                for &n in nodes {
                    for c in 0..D {
                        out[n * D + c] += k * x[n * D + c];
                    }
                }
            }
            Discrete::Link {
                pairs,
                stiffness,
                damping,
                release_at,
                ..
            } => {
                let k = pick(*stiffness, *damping);
                if k == 0.0 || !linked(*release_at, t) {
                    continue;
                }
                for &(a, b) in pairs {
                    for c in 0..D {
                        let f = k * (x[a * D + c] - x[b * D + c]);
                        out[a * D + c] += f;
                        out[b * D + c] -= f;
                    }
                }
            }
            Discrete::Mass { .. } | Discrete::Rigid { .. } => {}
        }
    }
}

/// Adds `scale` times the operator of [`times`] (coefficient `pick(k,
/// c)`, time `t`) to the free-free tangent `values`. Under a distributed
/// assembly split over ranks a node's rows are added by its owner only
/// (`Scatter::adds_rows_of`; the links' couplings are in every rank's
/// pattern, [`scatter_for`]); the forces ([`times`]) are whole on every
/// rank.
pub fn add_tangent<const D: usize>(
    model: &Model<D>,
    dofs: &DofMap<D>,
    scatter: &Scatter,
    values: &mut [f64],
    t: f64,
    pick: impl Fn(f64, f64) -> f64,
) {
    let mut add = |r: usize, c: usize, x: f64| {
        if !scatter.adds_rows_of(r / D) {
            return;
        }
        if let (Some(Dof::Free(i)), Some(Dof::Free(j))) = (dofs.dofs.get(r), dofs.dofs.get(c)) {
            if let Some(s) = scatter.pattern.find(*i, *j) {
                values[s] += x;
            }
        }
    };
    for d in &model.discrete {
        match d {
            Discrete::Ground {
                nodes,
                stiffness,
                damping,
                ..
            } => {
                let k = pick(*stiffness, *damping);
                if k == 0.0 {
                    continue;
                }
                for &n in nodes {
                    for c in 0..D {
                        add(n * D + c, n * D + c, k);
                    }
                }
            }
            Discrete::Link {
                pairs,
                stiffness,
                damping,
                release_at,
                ..
            } => {
                let k = pick(*stiffness, *damping);
                if k == 0.0 || !linked(*release_at, t) {
                    continue;
                }
                for &(a, b) in pairs {
                    for c in 0..D {
                        let (ra, rb) = (a * D + c, b * D + c);
                        add(ra, ra, k);
                        add(rb, rb, k);
                        add(ra, rb, -k);
                        add(rb, ra, -k);
                    }
                }
            }
            Discrete::Mass { .. } | Discrete::Rigid { .. } => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::grid::grid;
    use crate::testkit::ModelBuilder;

    /// A link between two nodes of separate cells: the forces balance,
    /// the tangent is their exact derivative, and the pattern has the
    /// coupling.
    #[test]
    fn link_forces_balance_and_the_tangent_is_their_derivative() {
        let mut model = ModelBuilder::plane_strain()
            .elastic("m", 1.0, 0.0)
            .body("a", grid(1, 1, [0.0, 0.0], [1.0, 1.0], 0.0, 1, false), "m")
            .body("b", grid(1, 1, [2.0, 0.0], [1.0, 1.0], 0.0, 1, false), "m")
            .step("s", 1.0, 1)
            .build();
        model.discrete.push(Discrete::Link {
            label: "l".into(),
            pairs: vec![(1, 4)],
            stiffness: 3.0,
            damping: 0.5,
            release_at: None,
        });
        let n = model.mesh.nodes.len() * 2;
        let u: Vec<f64> = (0..n).map(|i| 0.1 * i as f64 - 0.3).collect();
        let mut f = vec![0.0; n];
        times(&model, &u, &mut f, 0.0, |k, _| k);
        assert!(f.iter().sum::<f64>().abs() < 1e-15, "{f:?}");
        for c in 0..2 {
            assert_eq!(f[2 + c], 3.0 * (u[2 + c] - u[8 + c]));
        }
        let dofs = DofMap::new(&model);
        assert!(Scatter::new(&model.mesh, &dofs)
            .unwrap()
            .pair_slots(&dofs, 1, 4)
            .is_none());
        let scatter = scatter_for(&model, &dofs, &[], None).unwrap();
        assert!(scatter.pair_slots(&dofs, 1, 4).is_some());
        let mut values = vec![0.0; scatter.n_values()];
        add_tangent(&model, &dofs, &scatter, &mut values, 0.0, |_, c| c);
        let (Dof::Free(i), Dof::Free(j)) = (dofs.dofs[2], dofs.dofs[8]) else {
            panic!("free dofs")
        };
        assert_eq!(values[scatter.pattern.find(i, j).unwrap()], -0.5);
        assert_eq!(values[scatter.pattern.find(i, i).unwrap()], 0.5);
        // released at t = 1: acting before, gone from then on (force and
        // tangent)
        if let Discrete::Link { release_at, .. } = &mut model.discrete[0] {
            *release_at = Some(1.0);
        }
        for (t, acting) in [(0.5, true), (1.0, false), (2.0, false)] {
            let mut f = vec![0.0; n];
            times(&model, &u, &mut f, t, |k, _| k);
            assert_eq!(f[2] != 0.0, acting, "t = {t}");
            let mut values = vec![0.0; scatter.n_values()];
            add_tangent(&model, &dofs, &scatter, &mut values, t, |k, _| k);
            assert_eq!(values.iter().any(|v| *v != 0.0), acting, "t = {t}");
        }
    }
}
