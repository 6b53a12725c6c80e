//! Degree-of-freedom numbering: `D` dofs per node (`D n + c`, c = 0 for x
//! (or r), 1 for y (or z), 2 for z in 3D), split into free dofs (the unknowns, numbered in
//! node order), prescribed dofs (Dirichlet data, eliminated from the
//! matrix) and inactive dofs (nodes attached to no cell, e.g. unused points
//! of a gmsh file: no unknown, no reaction — except the pilot nodes of free
//! tools, `free_tool.rs`).

use crate::model::Model;

/// Role of one global dof.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dof {
    /// Unknown number `i` (row/column of the free-free matrix).
    Free(usize),
    /// Prescribed dof number `p` (index into [`DofMap::prescribed`]).
    Prescribed(usize),
    /// Node attached to no cell.
    Inactive,
}

/// A prescribed dof and the constraint that sets it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PrescribedDof {
    /// Global dof `D node + component`.
    pub dof: usize,
    /// Index into `Model::constraints` (the last one in deck order wins
    /// when several prescribe the same dof).
    pub constraint: usize,
}

/// The dof numbering of a model of dimension `D` (`DofMap` without a
/// parameter is the planar one).
#[derive(Debug, Clone)]
pub struct DofMap<const D: usize = 2> {
    /// Role of each global dof (`D * nodes` entries).
    pub dofs: Vec<Dof>,
    /// Global dof of each free unknown.
    pub free: Vec<usize>,
    /// Prescribed dofs in ascending global dof order.
    pub prescribed: Vec<PrescribedDof>,
}

impl<const D: usize> DofMap<D> {
    /// Numbers the dofs of `model`; nodes and components of constraints must
    /// be valid (see `check::check_model`).
    pub fn new(model: &Model<D>) -> Self {
        let nn = model.mesh.nodes.len();
        let mut active = vec![false; nn];
        for c in &model.mesh.cells {
            for &n in c.nodes {
                active[n] = true;
            }
        }
        // the pilot nodes of free tools carry their angle (`free_tool.rs`),
        // those of rigid bodies their motion (`rigid_body.rs`)
        for n in super::free_tool::pilot_nodes(model).chain(super::rigid_body::pilot_nodes(model)) {
            if let Some(a) = active.get_mut(n) {
                *a = true;
            }
        }
        let mut constraint_of: Vec<Option<usize>> = vec![None; D * nn];
        for (k, d) in model.constraints.iter().enumerate() {
            for &n in &d.nodes {
                constraint_of[D * n + d.component] = Some(k);
            }
        }
        let mut dofs = vec![Dof::Inactive; D * nn];
        let mut free = Vec::new();
        let mut prescribed = Vec::new();
        for (g, role) in dofs.iter_mut().enumerate() {
            if !active[g / D] {
                continue;
            }
            *role = match constraint_of[g] {
                Some(constraint) => {
                    prescribed.push(PrescribedDof { dof: g, constraint });
                    Dof::Prescribed(prescribed.len() - 1)
                }
                None => {
                    free.push(g);
                    Dof::Free(free.len() - 1)
                }
            };
        }
        DofMap {
            dofs,
            free,
            prescribed,
        }
    }

    /// Displacement components per node (the dimension `D`). New code
    /// takes it from here rather than writing the literal.
    pub fn components(&self) -> usize {
        D
    }

    /// Global dof of component `component` of node `node`.
    #[inline]
    pub fn dof(&self, node: usize, component: usize) -> usize {
        node * self.components() + component
    }

    /// Number of free unknowns.
    pub fn n_free(&self) -> usize {
        self.free.len()
    }

    /// Prescribed values at time `t` (one per prescribed dof).
    pub fn prescribed_values(&self, model: &Model<D>, t: f64, out: &mut [f64]) {
        for (o, p) in out.iter_mut().zip(&self.prescribed) {
            *o = model.constraints[p.constraint].value.eval(t);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Cell, Mesh};
    use crate::model::*;

    pub(crate) fn tiny_model() -> Model {
        crate::testkit::ModelBuilder::plane_strain()
            .mesh(Mesh::new(
                vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [5.0, 5.0]],
                vec![Cell::quad(0, 1, 2, 3)],
            ))
            .fix([0, 1], 1)
            .displace([1], 1, TimeFunction::Constant(2.0))
            .build()
    }

    #[test]
    fn numbering_free_prescribed_inactive_and_last_constraint_wins() {
        let m = tiny_model();
        let d = DofMap::new(&m);
        assert_eq!(d.n_free(), 6);
        assert_eq!(d.free, vec![0, 2, 4, 5, 6, 7]);
        assert_eq!(d.dofs[1], Dof::Prescribed(0));
        assert_eq!(d.dofs[3], Dof::Prescribed(1));
        assert_eq!(d.dofs[8], Dof::Inactive);
        assert_eq!(d.dofs[9], Dof::Inactive);
        let mut v = [0.0; 2];
        d.prescribed_values(&m, 0.5, &mut v);
        assert_eq!(v, [0.0, 2.0]);
    }
}
