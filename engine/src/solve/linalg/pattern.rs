//! Sparsity pattern of the free-free stiffness block and the scatter map
//! from element (and contact node) matrices to its value slots.
//!
//! Built once per run from the cell connectivity: assembly then only adds
//! numbers into a flat value array (`values[slot] += k`), with no search,
//! no hash map and no allocation. The pattern stores **both triangles**
//! (sorted rows in each column), so the same values feed a Cholesky
//! factorization (lower triangle read) and, if the tangent turns
//! indefinite, an LU factorization.
//!
//! The value array also holds, after the `nnz` free-free entries, the
//! free-prescribed coupling `K_fp` (one slot per element entry, duplicates
//! summed by [`Scatter::add_fp_product`]), used to apply the increment of
//! prescribed displacements in the Newton predictor.

use crate::mesh::Mesh;
use crate::solve::dofs::{Dof, DofMap};
use crate::solve::share::AssemblyShare;
use std::sync::Arc;

/// Marks an element entry that has no slot (a prescribed row).
pub const NO_SLOT: u32 = u32::MAX;

/// Entries of the largest node block (3 x 3).
pub const MAX_BLOCK: usize = 9;

/// Compressed sparse column pattern of a square matrix.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SparsePattern {
    /// Number of rows and columns.
    pub n: usize,
    /// Column pointers (`n + 1` entries).
    pub col_ptr: Vec<usize>,
    /// Row index of each stored entry, sorted within each column.
    pub row_idx: Vec<usize>,
}

impl SparsePattern {
    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Slot of entry `(row, col)`, if stored.
    pub fn find(&self, row: usize, col: usize) -> Option<usize> {
        let range = self.col_ptr[col]..self.col_ptr[col + 1];
        self.row_idx[range.clone()]
            .binary_search(&row)
            .ok()
            .map(|k| range.start + k)
    }
}

/// The node adjacency of a set of cells: per node, the sorted distinct
/// nodes it shares a cell (or an extra coupling) with, itself included,
/// in compressed rows (two flat arrays instead of a vector per node;
/// issue 20).
#[derive(Debug, Clone, Default)]
pub struct NodeGraph {
    /// Start of each node's row in `idx` (`nodes + 1` entries).
    pub ptr: Vec<usize>,
    /// Neighbours, row by row.
    pub idx: Vec<u32>,
}

impl NodeGraph {
    /// The adjacency over `nn` nodes of `cells` (each cell's node list:
    /// every pair of its nodes) and of the `extra` node pairs (both ways;
    /// pairs with a node out of range are left out). Node numbers must fit
    /// in `u32`.
    pub fn new<'c>(
        nn: usize,
        cells: impl Iterator<Item = &'c [usize]> + Clone,
        extra: &[(usize, usize)],
    ) -> Self {
        let extra = || extra.iter().filter(|&&(a, b)| a < nn && b < nn);
        // room per node: every entry before removing the repetitions
        let mut start = vec![0usize; nn + 1];
        for ns in cells.clone() {
            for &a in ns {
                start[a + 1] += ns.len();
            }
        }
        for &(a, b) in extra() {
            start[a + 1] += 2;
            start[b + 1] += 2;
        }
        for i in 0..nn {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut idx = vec![0u32; start[nn]];
        for ns in cells {
            for &a in ns {
                let at = fill[a];
                for (slot, &b) in idx[at..at + ns.len()].iter_mut().zip(ns) {
                    *slot = b as u32;
                }
                fill[a] += ns.len();
            }
        }
        for &(a, b) in extra() {
            for n in [a, b] {
                idx[fill[n]] = a as u32;
                idx[fill[n] + 1] = b as u32;
                fill[n] += 2;
            }
        }
        // each row sorted, repetitions removed, rows moved down in place
        let mut ptr = Vec::with_capacity(nn + 1);
        ptr.push(0);
        let mut w = 0;
        for a in 0..nn {
            let row = start[a]..start[a + 1];
            idx[row.clone()].sort_unstable();
            let mut last = None;
            for k in row {
                let v = idx[k];
                if last != Some(v) {
                    idx[w] = v;
                    w += 1;
                    last = Some(v);
                }
            }
            ptr.push(w);
        }
        idx.truncate(w);
        NodeGraph { ptr, idx }
    }

    /// The neighbours of node `a` (sorted, itself included if it is in a
    /// cell).
    #[inline]
    pub fn row(&self, a: usize) -> &[u32] {
        &self.idx[self.ptr[a]..self.ptr[a + 1]]
    }
}

/// Where each element matrix entry goes.
#[derive(Debug, Clone)]
pub struct Scatter {
    /// Pattern of the free-free block.
    pub pattern: SparsePattern,
    /// Start of each cell's slots in `slots` (`cells + 1` entries).
    cell_offset: Vec<usize>,
    /// Per cell, per local entry `i + j * ndof` (column-major): value slot.
    slots: Vec<u32>,
    /// Components per node (the dimension of the dof map).
    dim: usize,
    /// Per node, slots of its `dim x dim` self block (column-major,
    /// `dim * dim` entries per node), for contact.
    node_block: Vec<u32>,
    /// Free row of each `K_fp` slot.
    fp_row: Vec<u32>,
    /// Prescribed column (index into `DofMap::prescribed`) of each `K_fp` slot.
    fp_col: Vec<u32>,
    /// The cells and nodes of this rank under a distributed assembly
    /// (`crate::solve::share`): only their couplings are in the pattern,
    /// only their slots exist; `None`: the whole mesh.
    share: Option<Arc<AssemblyShare>>,
    /// Number of this scatter map (a new one for every pattern built):
    /// the key of the parallel assembly's partition
    /// (`crate::solve::assembly`).
    id: u64,
}

/// Scatter maps built so far (their [`Scatter::id`]).
static SCATTERS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

impl Scatter {
    /// Builds the pattern and the scatter maps of `mesh` numbered by `dofs`.
    pub fn new<const D: usize>(mesh: &Mesh<D>, dofs: &DofMap<D>) -> Result<Self, String> {
        Self::with_couplings(mesh, dofs, &[])
    }

    /// Like [`Scatter::new`], with the extra node couplings `extra` (pairs
    /// of nodes not sharing a cell, coupled by contact elements; both
    /// orders are added).
    pub fn with_couplings<const D: usize>(
        mesh: &Mesh<D>,
        dofs: &DofMap<D>,
        extra: &[(usize, usize)],
    ) -> Result<Self, String> {
        Self::with_share(mesh, dofs, extra, None)
    }

    /// Like [`Scatter::with_couplings`], restricted to a rank's `share`
    /// (distributed assembly): the couplings of its cells (and `extra`),
    /// slots for its cells only, node blocks for its nodes only.
    pub fn with_share<const D: usize>(
        mesh: &Mesh<D>,
        dofs: &DofMap<D>,
        extra: &[(usize, usize)],
        share: Option<Arc<AssemblyShare>>,
    ) -> Result<Self, String> {
        let nn = mesh.nodes.len();
        let owns_cell = |c: usize| share.as_ref().is_none_or(|s| s.owns_cell(c));
        // node adjacency (sorted, unique, including the node itself)
        let adj = NodeGraph::new(
            nn,
            mesh.cells
                .iter()
                .enumerate()
                .filter(|&(ci, _)| owns_cell(ci))
                .map(|(_, c)| c.nodes),
            extra,
        );
        let n = dofs.n_free();
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0usize);
        let mut row_idx =
            Vec::with_capacity(dofs.free.iter().map(|&g| D * adj.row(g / D).len()).sum());
        for &g in &dofs.free {
            for &m in adj.row(g / D) {
                for c in 0..D {
                    if let Dof::Free(i) = dofs.dofs[D * m as usize + c] {
                        row_idx.push(i);
                    }
                }
            }
            col_ptr.push(row_idx.len());
        }
        let pattern = SparsePattern {
            n,
            col_ptr,
            row_idx,
        };
        let nnz = pattern.nnz();
        let mut fp_row = Vec::new();
        let mut fp_col = Vec::new();
        let mut slot_of = |ga: usize, gb: usize| -> Result<u32, String> {
            let slot = match (dofs.dofs[ga], dofs.dofs[gb]) {
                (Dof::Free(i), Dof::Free(j)) => pattern
                    .find(i, j)
                    .ok_or("internal error: entry missing from the sparsity pattern")?,
                (Dof::Free(i), Dof::Prescribed(p)) => {
                    fp_row.push(i as u32);
                    fp_col.push(p as u32);
                    nnz + fp_row.len() - 1
                }
                _ => return Ok(NO_SLOT),
            };
            u32::try_from(slot)
                .ok()
                .filter(|&s| s != NO_SLOT)
                .ok_or_else(|| "the model is too large (more than 4e9 matrix entries)".into())
        };
        // the free-free slots of a cell without a search per entry: the
        // column of a free dof of node `b` lists the free dofs of `adj[b]`
        // in order, so the entry of node `a`'s free dof `i` sits at
        // `col_ptr[col] + before[b][position of a in adj[b]] + (free dofs
        // of a below i)`: one search per node pair (the slots of
        // `pattern.find`, tested)
        let free = |g: usize| matches!(dofs.dofs[g], Dof::Free(_));
        // `before[b][k]` at `adj`'s entry `k` of node `b`
        let free_of: Vec<u32> = (0..nn)
            .map(|m| (0..D).filter(|&c| free(D * m + c)).count() as u32)
            .collect();
        let mut before: Vec<u32> = Vec::with_capacity(adj.idx.len());
        for b in 0..nn {
            let mut k = 0u32;
            for &m in adj.row(b) {
                before.push(k);
                k += free_of[m as usize];
            }
        }
        let before = |b: usize| &before[adj.ptr[b]..adj.ptr[b + 1]];
        let below = |g: usize| (g - g % D..g).filter(|&h| free(h)).count();
        let mut cell_offset = Vec::with_capacity(mesh.cells.len() + 1);
        cell_offset.push(0);
        let mut slots = Vec::new();
        let mut at = Vec::new();
        for (ci, c) in mesh.cells.iter().enumerate() {
            if !owns_cell(ci) {
                cell_offset.push(slots.len());
                continue;
            }
            let ns = c.nodes;
            let nd = D * ns.len();
            // position of each row node in each column node's adjacency
            at.clear();
            for &b in ns {
                for &a in ns {
                    at.push(
                        before(b)[adj
                            .row(b)
                            .binary_search(&(a as u32))
                            .map_err(|_| "internal error: a cell's node pair is not adjacent")?],
                    );
                }
            }
            for j in 0..nd {
                let gb = D * ns[j / D] + j % D;
                for i in 0..nd {
                    let ga = D * ns[i / D] + i % D;
                    let slot = match (dofs.dofs[ga], dofs.dofs[gb]) {
                        (Dof::Free(_), Dof::Free(col)) => {
                            let k = pattern.col_ptr[col]
                                + at[(j / D) * ns.len() + i / D] as usize
                                + below(ga);
                            u32::try_from(k)
                                .ok()
                                .filter(|&s| s != NO_SLOT)
                                .ok_or_else(|| {
                                    "the model is too large (more than 4e9 matrix entries)"
                                        .to_string()
                                })?
                        }
                        _ => slot_of(ga, gb)?,
                    };
                    slots.push(slot);
                }
            }
            cell_offset.push(slots.len());
        }
        let mut node_block = vec![NO_SLOT; D * D * nn];
        for (node, block) in node_block.chunks_exact_mut(D * D).enumerate() {
            if adj.row(node).is_empty() || share.as_ref().is_some_and(|s| !s.owns_node(node)) {
                continue;
            }
            for j in 0..D {
                for i in 0..D {
                    block[i + D * j] = slot_of(D * node + i, D * node + j)?;
                }
            }
        }
        Ok(Scatter {
            pattern,
            cell_offset,
            slots,
            dim: D,
            node_block,
            fp_row,
            fp_col,
            share,
            id: SCATTERS.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
        })
    }

    /// Number of this scatter map (distinct for every pattern built; a
    /// clone keeps it).
    pub fn id(&self) -> u64 {
        self.id
    }

    /// The rank's share of a distributed assembly (`None`: the whole mesh).
    pub fn share(&self) -> Option<&Arc<AssemblyShare>> {
        self.share.as_ref()
    }

    /// Length of the value array: free-free entries, then `K_fp` slots.
    pub fn n_values(&self) -> usize {
        self.pattern.nnz() + self.fp_row.len()
    }

    /// Slots of cell `c`'s local entries, column-major.
    #[inline]
    pub fn cell_slots(&self, c: usize) -> &[u32] {
        &self.slots[self.cell_offset[c]..self.cell_offset[c + 1]]
    }

    /// Slots of node `n`'s `D x D` self block, column-major (`a + D b`).
    #[inline]
    pub fn node_slots(&self, n: usize) -> &[u32] {
        let dd = self.dim * self.dim;
        &self.node_block[n * dd..(n + 1) * dd]
    }

    /// Free-free slots of the `D x D` block coupling node `a` (rows) and
    /// node `b` (columns), column-major (`i + D j`, the first `D * D`
    /// entries); `NO_SLOT` for a prescribed or inactive dof; `None` if a
    /// free-free entry is missing from the pattern.
    pub fn pair_slots<const D: usize>(
        &self,
        dofs: &DofMap<D>,
        a: usize,
        b: usize,
    ) -> Option<[u32; MAX_BLOCK]> {
        let mut out = [NO_SLOT; MAX_BLOCK];
        if a == b {
            out[..D * D].copy_from_slice(self.node_slots(a));
            return Some(out);
        }
        for j in 0..D {
            for i in 0..D {
                if let (Dof::Free(r), Dof::Free(c)) = (dofs.dofs[D * a + i], dofs.dofs[D * b + j]) {
                    out[i + D * j] = self.pattern.find(r, c)? as u32;
                }
            }
        }
        Some(out)
    }

    /// Whether nodes `a` and `b` are coupled for a contact element, as far
    /// as [`crate::solve::contact_assembly`]'s pattern growth is concerned.
    /// Alone (no share split over ranks): their entries are in the
    /// pattern. Under a distributed assembly the ranks' patterns differ
    /// (each holds its own cells), so the answer is taken from the
    /// replicated, sorted list of contact `couplings` instead (`a == b` is
    /// always coupled): the same on every rank, so every rank grows its
    /// pattern (and rebuilds its PETSc matrix, a collective call) at the
    /// same evaluation, and every rank's pattern holds every coupling of
    /// every contact element (the owner of a node adds that node's rows).
    pub fn contact_coupled<const D: usize>(
        &self,
        dofs: &DofMap<D>,
        couplings: &[(usize, usize)],
        a: usize,
        b: usize,
    ) -> bool {
        if self.share.as_ref().is_some_and(|s| s.split()) {
            a == b || couplings.binary_search(&(a.min(b), a.max(b))).is_ok()
        } else {
            self.pair_slots(dofs, a, b).is_some()
        }
    }

    /// Whether this rank adds the rows of node `a` of a contact element:
    /// always, except under a distributed assembly split over ranks, where
    /// only `a`'s owner does (the element is evaluated by every rank).
    #[inline]
    pub fn adds_rows_of(&self, a: usize) -> bool {
        self.share
            .as_ref()
            .is_none_or(|s| !s.split() || s.owns_node(a))
    }

    /// `out[i] += sum_p K_fp[i, p] dp[p]` for the `K_fp` part of `values`.
    pub fn add_fp_product(&self, values: &[f64], dp: &[f64], out: &mut [f64]) {
        let kfp = &values[self.pattern.nnz()..];
        for ((v, &i), &p) in kfp.iter().zip(&self.fp_row).zip(&self.fp_col) {
            out[i as usize] += v * dp[p as usize];
        }
    }
}

/// Test helper: CSC pattern and values of a small dense matrix; entries that
/// are zero are left out, except on the diagonal when `keep_diagonal`.
#[cfg(test)]
pub(crate) fn dense_to_csc<const N: usize>(
    a: &[[f64; N]; N],
    keep_diagonal: bool,
) -> (SparsePattern, Vec<f64>) {
    let mut col_ptr = vec![0];
    let mut row_idx = vec![];
    let mut vals = vec![];
    for j in 0..N {
        for (i, row) in a.iter().enumerate() {
            if row[j] != 0.0 || (keep_diagonal && i == j) {
                row_idx.push(i);
                vals.push(row[j]);
            }
        }
        col_ptr.push(row_idx.len());
    }
    (
        SparsePattern {
            n: N,
            col_ptr,
            row_idx,
        },
        vals,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Cell;
    use crate::model::*;

    fn model() -> Model {
        // two quads side by side: 0-1-2 bottom, 3-4-5 top; node 0 fixed in x and y
        crate::testkit::ModelBuilder::plane_strain()
            .mesh(Mesh::new(
                vec![
                    [0.0, 0.0],
                    [1.0, 0.0],
                    [2.0, 0.0],
                    [0.0, 1.0],
                    [1.0, 1.0],
                    [2.0, 1.0],
                ],
                vec![Cell::quad(0, 1, 4, 3), Cell::quad(1, 2, 5, 4)],
            ))
            .fix([0], 0)
            .fix([0], 1)
            .build()
    }

    #[test]
    fn cell_slots_are_the_patterns_entries_with_partly_held_nodes() {
        // node 0 held in x only, node 5 in y only: free and prescribed
        // dofs mixed inside a node
        let m = crate::testkit::ModelBuilder::plane_strain()
            .mesh(model().mesh.clone())
            .fix([0], 0)
            .fix([5], 1)
            .build();
        let d = DofMap::new(&m);
        let s = Scatter::new(&m.mesh, &d).unwrap();
        let mut checked = 0;
        for c in 0..m.mesh.cells.len() {
            let ns = m.mesh.cells.nodes(c);
            let nd = 2 * ns.len();
            for j in 0..nd {
                for i in 0..nd {
                    let slot = s.slots[s.cell_offset[c] + i + j * nd];
                    let (ga, gb) = (2 * ns[i / 2] + i % 2, 2 * ns[j / 2] + j % 2);
                    if let (Dof::Free(r), Dof::Free(col)) = (d.dofs[ga], d.dofs[gb]) {
                        assert_eq!(Some(slot as usize), s.pattern.find(r, col), "{c} {i} {j}");
                        checked += 1;
                    }
                }
            }
        }
        assert_eq!(checked, 2 * 49);
    }

    #[test]
    fn pattern_of_two_quads_matches_dense_assembly() {
        let m = model();
        let d = DofMap::new(&m);
        let s = Scatter::new(&m.mesh, &d).unwrap();
        assert_eq!(s.pattern.n, 10);
        // node 2 (free dofs 2,3) does not touch node 3 (free dofs 4,5)
        assert!(s.pattern.find(2, 4).is_none());
        assert!(s.pattern.find(0, 9).is_some());
        // columns sorted, symmetric pattern
        for j in 0..s.pattern.n {
            let rows = &s.pattern.row_idx[s.pattern.col_ptr[j]..s.pattern.col_ptr[j + 1]];
            assert!(rows.windows(2).all(|w| w[0] < w[1]));
            for &i in rows {
                assert!(s.pattern.find(j, i).is_some());
            }
        }
        // scatter a dense "element matrix" k_ij = 1 for every cell and compare
        // with a dense assembly
        let mut values = vec![0.0; s.n_values()];
        let mut dense = vec![vec![0.0; 12]; 12];
        for (c, cell) in m.mesh.cells.iter().enumerate() {
            let ns = cell.nodes;
            for (e, &slot) in s.cell_slots(c).iter().enumerate() {
                let (i, j) = (e % 8, e / 8);
                let v = (i * 8 + j) as f64 + 1.0;
                dense[2 * ns[i / 2] + i % 2][2 * ns[j / 2] + j % 2] += v;
                if slot != NO_SLOT {
                    values[slot as usize] += v;
                }
            }
        }
        for (jf, &gj) in d.free.iter().enumerate() {
            for (if_, &gi) in d.free.iter().enumerate() {
                let stored = s.pattern.find(if_, jf).map_or(0.0, |k| values[k]);
                assert_eq!(stored, dense[gi][gj]);
            }
        }
        // K_fp times a prescribed increment equals the dense product
        let dp = [0.5, -2.0];
        let mut out = vec![0.0; 10];
        s.add_fp_product(&values, &dp, &mut out);
        for (if_, &gi) in d.free.iter().enumerate() {
            let expect = dense[gi][0] * dp[0] + dense[gi][1] * dp[1];
            assert!((out[if_] - expect).abs() < 1e-12);
        }
        // node self blocks: node 0 is fully prescribed, node 4 free
        assert_eq!(s.node_slots(0), &[NO_SLOT; 4]);
        assert!(s
            .node_slots(4)
            .iter()
            .all(|&k| (k as usize) < s.pattern.nnz()));
    }
}
