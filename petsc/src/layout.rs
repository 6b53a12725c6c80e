//! Who owns what under MPI, and the PETSc numbering of the dofs.
//!
//! Input: the cells (node lists, natural numbering of the whole mesh, held
//! by every rank) and a partition `cell → rank`. Rules, all deterministic:
//! - a rank *computes* its own cells (`part == rank`);
//! - a node is *owned* by the lowest rank among the cells that contain it
//!   (a node in no cell belongs to rank 0);
//! - the PETSc block index of a node: the nodes of rank 0 first, then rank
//!   1, ..., each rank's nodes in increasing natural number; dof `c` of a
//!   node is `dim * block + c` (block size `dim`);
//! - a rank's *ghosts* are the nodes of its cells that it does not own, in
//!   increasing PETSc index.
//!
//! So for a given partition the numbering is unique, and [`DofLayout::to_natural`]
//! maps a result back to the natural order: output is the same file whatever
//! the rank count.

use crate::error::PetscError;
use std::ops::Range;

/// Ownership and numbering of one rank (see the module doc for the rules).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DofLayout {
    /// Dofs per node (the matrix block size).
    pub dim: usize,
    /// Number of ranks of the partition.
    pub n_ranks: usize,
    /// The rank this layout is for.
    pub rank: usize,
    /// Owning rank of each node (natural numbering).
    pub node_owner: Vec<usize>,
    /// PETSc block index of each node (natural numbering).
    pub node_block: Vec<usize>,
    /// First PETSc block index of each rank, and the total at the end.
    pub rank_offsets: Vec<usize>,
    /// This rank's cells (indices into the cell list), increasing.
    pub cells: Vec<usize>,
    /// Natural numbers of this rank's owned nodes, increasing (= in PETSc order).
    pub owned_nodes: Vec<usize>,
    /// Natural numbers of this rank's ghost nodes, in increasing PETSc index.
    pub ghost_nodes: Vec<usize>,
}

impl DofLayout {
    /// Builds the layout of `rank` from the cells, their partition and the
    /// node count. Errors on a partition of the wrong length, a rank out of
    /// range or a cell naming a node that does not exist.
    pub fn new<C: AsRef<[usize]>>(
        cells: &[C],
        cell_rank: &[usize],
        n_nodes: usize,
        n_ranks: usize,
        rank: usize,
        dim: usize,
    ) -> Result<DofLayout, PetscError> {
        if cell_rank.len() != cells.len() {
            return Err(PetscError::Layout(format!(
                "the partition has {} entries for {} cells",
                cell_rank.len(),
                cells.len()
            )));
        }
        if n_ranks == 0 || rank >= n_ranks || dim == 0 {
            return Err(PetscError::Layout(format!(
                "rank {rank} of {n_ranks} with {dim} dofs per node"
            )));
        }
        let mut node_owner = vec![usize::MAX; n_nodes];
        for (c, (cell, &r)) in cells.iter().zip(cell_rank).enumerate() {
            if r >= n_ranks {
                return Err(PetscError::Layout(format!(
                    "cell {c} is given to rank {r} of {n_ranks}"
                )));
            }
            for &n in cell.as_ref() {
                let owner = node_owner.get_mut(n).ok_or_else(|| {
                    PetscError::Layout(format!("cell {c} names node {n} of {n_nodes}"))
                })?;
                *owner = (*owner).min(r);
            }
        }
        for o in &mut node_owner {
            if *o == usize::MAX {
                *o = 0;
            }
        }
        let mut counts = vec![0usize; n_ranks];
        for &o in &node_owner {
            counts[o] += 1;
        }
        let mut rank_offsets = vec![0usize; n_ranks + 1];
        for r in 0..n_ranks {
            rank_offsets[r + 1] = rank_offsets[r] + counts[r];
        }
        let mut next = rank_offsets.clone();
        let mut node_block = vec![0usize; n_nodes];
        for (n, &o) in node_owner.iter().enumerate() {
            node_block[n] = next[o];
            next[o] += 1;
        }
        let owned_nodes: Vec<usize> = (0..n_nodes).filter(|&n| node_owner[n] == rank).collect();
        let my_cells: Vec<usize> = (0..cells.len()).filter(|&c| cell_rank[c] == rank).collect();
        let mut ghost_nodes: Vec<usize> = my_cells
            .iter()
            .flat_map(|&c| cells[c].as_ref().iter().copied())
            .filter(|&n| node_owner[n] != rank)
            .collect();
        ghost_nodes.sort_unstable_by_key(|&n| node_block[n]);
        ghost_nodes.dedup();
        Ok(DofLayout {
            dim,
            n_ranks,
            rank,
            node_owner,
            node_block,
            rank_offsets,
            cells: my_cells,
            owned_nodes,
            ghost_nodes,
        })
    }

    /// Number of nodes of the whole mesh.
    pub fn n_nodes(&self) -> usize {
        self.node_block.len()
    }

    /// Global number of dofs.
    pub fn n_global_dofs(&self) -> usize {
        self.dim * self.n_nodes()
    }

    /// This rank's rows (PETSc dof indices).
    pub fn owned_dofs(&self) -> Range<usize> {
        self.dim * self.rank_offsets[self.rank]..self.dim * self.rank_offsets[self.rank + 1]
    }

    /// PETSc index of component `c` of natural node `node`.
    pub fn dof(&self, node: usize, c: usize) -> usize {
        self.dim * self.node_block[node] + c
    }

    /// PETSc dof indices of the nodes of a cell, node by node
    /// (`dim` per node): the rows and columns of its element matrix.
    pub fn cell_dofs(&self, nodes: &[usize]) -> Vec<usize> {
        nodes
            .iter()
            .flat_map(|&n| (0..self.dim).map(move |c| self.dof(n, c)))
            .collect()
    }

    /// PETSc dof indices of the ghost nodes, in the order of the ghosted
    /// vector's local form (after the owned values).
    pub fn ghost_dofs(&self) -> Vec<usize> {
        self.cell_dofs(&self.ghost_nodes)
    }

    /// Position of natural node `node` in the ghosted vector's local form
    /// (owned nodes first, then ghosts), in blocks of `dim`; `None` if the
    /// node is neither owned nor a ghost of this rank.
    pub fn local_block(&self, node: usize) -> Option<usize> {
        if self.node_owner[node] == self.rank {
            return Some(self.node_block[node] - self.rank_offsets[self.rank]);
        }
        let key = self.node_block[node];
        self.ghost_nodes
            .binary_search_by_key(&key, |&g| self.node_block[g])
            .ok()
            .map(|i| self.owned_nodes.len() + i)
    }

    /// Reorders a whole vector in PETSc order (all ranks' blocks
    /// concatenated) into the natural order `dim * node + c`.
    pub fn to_natural(&self, petsc_order: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.n_global_dofs()];
        for (n, &b) in self.node_block.iter().enumerate() {
            for c in 0..self.dim {
                out[self.dim * n + c] = petsc_order[self.dim * b + c];
            }
        }
        out
    }
}

/// Exact preallocation of this rank's rows: for each owned node, the
/// sorted PETSc block indices of the nodes it couples to. Built from *all*
/// cells containing an owned node (the mesh is replicated), so rows that
/// receive contributions from another rank's cells are counted exactly too;
/// contact or constraint couplings are added with [`Preallocation::couple`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Preallocation {
    /// Per owned node (in PETSc order), the coupled block indices, sorted.
    pub neighbours: Vec<Vec<usize>>,
    first_block: usize,
    end_block: usize,
    dim: usize,
}

impl Preallocation {
    /// The element couplings of `layout`'s owned rows.
    pub fn from_cells<C: AsRef<[usize]>>(layout: &DofLayout, cells: &[C]) -> Preallocation {
        let first_block = layout.rank_offsets[layout.rank];
        let end_block = layout.rank_offsets[layout.rank + 1];
        let mut neighbours = vec![Vec::new(); end_block - first_block];
        for cell in cells {
            let nodes = cell.as_ref();
            for &a in nodes {
                if layout.node_owner[a] != layout.rank {
                    continue;
                }
                let row = &mut neighbours[layout.node_block[a] - first_block];
                row.extend(nodes.iter().map(|&b| layout.node_block[b]));
            }
        }
        for row in &mut neighbours {
            row.sort_unstable();
            row.dedup();
        }
        Preallocation {
            neighbours,
            first_block,
            end_block,
            dim: layout.dim,
        }
    }

    /// Adds the coupling of natural nodes `a` and `b` (both directions, for
    /// the rows this rank owns).
    pub fn couple(&mut self, layout: &DofLayout, a: usize, b: usize) {
        for (r, c) in [(a, b), (b, a)] {
            let rb = layout.node_block[r];
            if (self.first_block..self.end_block).contains(&rb) {
                let row = &mut self.neighbours[rb - self.first_block];
                let cb = layout.node_block[c];
                if let Err(i) = row.binary_search(&cb) {
                    row.insert(i, cb);
                }
            }
        }
    }

    /// Adds column block `col` to row block `row` (PETSc block indices),
    /// when this rank owns `row`: an entry of a rank's partial pattern
    /// (contact couplings, added to every rank's pattern alike).
    pub fn couple_blocks(&mut self, row: usize, col: usize) {
        if (self.first_block..self.end_block).contains(&row) {
            let r = &mut self.neighbours[row - self.first_block];
            if let Err(i) = r.binary_search(&col) {
                r.insert(i, col);
            }
        }
    }

    /// `(d_nnz, o_nnz)` per owned dof row: entries in the diagonal block
    /// (columns owned by this rank) and outside it.
    pub fn nnz(&self) -> (Vec<usize>, Vec<usize>) {
        let mut d = Vec::with_capacity(self.neighbours.len() * self.dim);
        let mut o = Vec::with_capacity(self.neighbours.len() * self.dim);
        for row in &self.neighbours {
            let diag = row
                .iter()
                .filter(|&&b| (self.first_block..self.end_block).contains(&b))
                .count();
            for _ in 0..self.dim {
                d.push(self.dim * diag);
                o.push(self.dim * (row.len() - diag));
            }
        }
        (d, o)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3 x 1 strip of quads: nodes 0..8, bottom row 0..4, top row 4..8.
    /// ```text
    ///  4---5---6---7
    ///  | 0 | 1 | 2 |
    ///  0---1---2---3
    /// ```
    fn strip() -> Vec<[usize; 4]> {
        vec![[0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6]]
    }

    #[test]
    fn one_rank_is_the_natural_numbering() {
        let l = DofLayout::new(&strip(), &[0, 0, 0], 8, 1, 0, 2).unwrap();
        assert_eq!(l.node_block, (0..8).collect::<Vec<_>>());
        assert!(l.ghost_nodes.is_empty());
        assert_eq!(l.owned_dofs(), 0..16);
        let v: Vec<f64> = (0..16).map(f64::from).collect();
        assert_eq!(l.to_natural(&v), v);
    }

    #[test]
    fn interface_nodes_go_to_the_lowest_rank() {
        // cells 0 on rank 1, cells 1, 2 on rank 0: nodes 1, 5 touch both
        let part = [1, 0, 0];
        let l0 = DofLayout::new(&strip(), &part, 8, 2, 0, 2).unwrap();
        let l1 = DofLayout::new(&strip(), &part, 8, 2, 1, 2).unwrap();
        assert_eq!(l0.owned_nodes, vec![1, 2, 3, 5, 6, 7]);
        assert_eq!(l1.owned_nodes, vec![0, 4]);
        assert_eq!(l1.ghost_nodes, vec![1, 5]);
        assert!(l0.ghost_nodes.is_empty());
        assert_eq!(l0.node_block, l1.node_block);
        assert_eq!(l0.node_block, vec![6, 0, 1, 2, 7, 3, 4, 5]);
        assert_eq!(l1.owned_dofs(), 12..16);
        assert_eq!(l1.local_block(4), Some(1));
        assert_eq!(l1.local_block(5), Some(3));
        assert_eq!(l1.local_block(3), None);
        // PETSc order -> natural order is a permutation
        let petsc: Vec<f64> = (0..16).map(f64::from).collect();
        let mut nat = l0.to_natural(&petsc);
        assert_eq!(nat[2], 0.0);
        nat.sort_by(f64::total_cmp);
        assert_eq!(nat, petsc);
    }

    #[test]
    fn preallocation_counts_rows_fed_by_other_ranks() {
        let part = [1, 0, 0];
        let l0 = DofLayout::new(&strip(), &part, 8, 2, 0, 2).unwrap();
        let p = Preallocation::from_cells(&l0, &strip());
        let (d, o) = p.nnz();
        // node 1 (first owned block of rank 0) couples to 0, 1, 2, 4, 5, 6:
        // 0 and 4 are rank 1's
        assert_eq!((d[0], o[0]), (8, 4));
        assert_eq!((d[1], o[1]), (8, 4));
        // node 3 couples to 2, 3, 6, 7 only
        assert_eq!((d[4], o[4]), (8, 0));
        let l1 = DofLayout::new(&strip(), &part, 8, 2, 1, 2).unwrap();
        let mut p1 = Preallocation::from_cells(&l1, &strip());
        assert_eq!(p1.nnz().0[0], 4); // node 0 with 0 and 4
        p1.couple(&l1, 0, 7);
        assert_eq!(p1.nnz(), (vec![4, 4, 4, 4], vec![6, 6, 4, 4]));
        // by blocks: node 4 (block 7, owned) with node 3 (block 2); a row
        // of another rank is not this rank's
        let before = p1.clone();
        p1.couple_blocks(7, 2);
        p1.couple_blocks(7, 2);
        p1.couple_blocks(0, 7);
        assert_eq!(p1.nnz().1, vec![6, 6, 6, 6]);
        assert_eq!(p1.neighbours[1], vec![0, 2, 3, 6, 7]);
        assert_ne!(p1, before);
    }

    #[test]
    fn bad_partitions_are_errors() {
        assert!(DofLayout::new(&strip(), &[0, 0], 8, 1, 0, 2).is_err());
        assert!(DofLayout::new(&strip(), &[0, 2, 0], 8, 2, 0, 2).is_err());
        assert!(DofLayout::new(&strip(), &[0, 0, 0], 7, 1, 0, 2).is_err());
        assert!(DofLayout::new(&strip(), &[0, 0, 0], 8, 1, 1, 2).is_err());
    }
}
