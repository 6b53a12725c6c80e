//! The stiffness of a linear model, assembled once (issue 20: cheaper
//! Newton iterations for linear-elastic bodies).
//!
//! When every cell is small-strain linear elastic (no integration points:
//! [`super::assembly::Assembler::has_points`] is false), the element
//! stiffness depends neither on the displacements nor on the time or a
//! thermal strain. Then
//!
//! - the element part of the tangent is the same matrix at every
//!   evaluation. It is assembled by the element loop itself, once per
//!   scatter map (a contact pattern growth makes a new map, and the bulk is
//!   assembled again), into zeroed values; every later tangent starts as a
//!   copy of it. The Newton evaluation puts the element part first and adds
//!   the contact, follower, spring and inertia terms after it
//!   (`newton::Newton::evaluate`), so the copy has the bits of the loop;
//! - the internal force is `f_int = K u` with `K` the stiffness over all
//!   dofs ([`DofMatrix`], free and prescribed, rows compressed: the
//!   reactions need the prescribed rows), assembled once per run from the
//!   cached element matrices in cell order: one pass over `K` instead of
//!   the element loop over the (larger) element matrices. Its sums run in
//!   another order than the loop's `sum_e K_e u_e`: the forces agree to
//!   round-off, not bit for bit (`newton::bulk_tests`). A thermal strain
//!   adds its element forces after the product.
//!
//! Every evaluation of a linear model takes this path (the first one
//! included), so a run is one function of its deck: deterministic.

use crate::mesh::Mesh;

/// The assembled element tangent of the scatter map it was built for and
/// the stiffness over all dofs.
#[derive(Debug, Clone, Default)]
pub struct BulkTangent {
    /// [`super::linalg::Scatter::id`] of the map the values belong to
    /// (`None`: nothing assembled yet).
    scatter: Option<u64>,
    /// The element entries in the map's value layout (free-free entries,
    /// then the `K_fp` slots), summed from zero in the element loop's
    /// order.
    values: Vec<f64>,
    /// The stiffness over all dofs (built at the first force evaluation).
    stiffness: Option<DofMatrix>,
    /// Times the bulk was assembled (once per scatter map).
    pub builds: usize,
    /// Tangents that were a copy of the bulk.
    pub reuses: usize,
    /// Whether the cache is off: the element loop assembles every tangent
    /// and every force (the reference of the tests).
    pub disabled: bool,
}

impl BulkTangent {
    /// The assembled values for the scatter map `id`, if held (and the
    /// cache is on).
    pub fn get(&self, id: u64) -> Option<&[f64]> {
        (self.scatter == Some(id) && !self.disabled).then_some(&self.values[..])
    }

    /// Keeps `values` (the element loop's tangent, assembled from zero)
    /// as the bulk of the scatter map `id`.
    pub fn store(&mut self, id: u64, values: Vec<f64>) {
        self.scatter = Some(id);
        self.values = values;
        self.builds += 1;
    }

    /// Forgets the bulk and the stiffness.
    pub fn clear(&mut self) {
        self.scatter = None;
        self.values = Vec::new();
        self.stiffness = None;
    }

    /// Overwrites `values` (of the layout of scatter map `id`) with the
    /// bulk; false (`values` untouched) when no bulk of that map is held.
    pub fn copy_to(&mut self, id: u64, values: &mut [f64]) -> bool {
        let Some(bulk) = self.get(id) else {
            return false;
        };
        values.copy_from_slice(bulk);
        self.reuses += 1;
        true
    }

    /// `f = K u` over all dofs (`u`, `f`: `D` per node), the stiffness
    /// built by `build` at the first call, the rows shared among
    /// `threads` threads (the same bits on any count).
    pub fn forces(
        &mut self,
        u: &[f64],
        f: &mut [f64],
        threads: usize,
        build: impl FnOnce() -> DofMatrix,
    ) {
        self.stiffness
            .get_or_insert_with(build)
            .times(u, f, (threads, PARALLEL_MIN_ROWS));
    }
}

/// A matrix over all dofs of a mesh (`D` per node), rows compressed, each
/// node row holding the `D x D` blocks of the nodes it shares a cell with,
/// in increasing node order.
#[derive(Debug, Clone, Default)]
pub struct DofMatrix {
    /// Start of each row in `cols` and `vals` (`dofs + 1` entries).
    row_ptr: Vec<usize>,
    /// Column (dof) of each entry.
    cols: Vec<u32>,
    /// Value of each entry.
    vals: Vec<f64>,
}

/// Rows below which the product stays on one thread.
const PARALLEL_MIN_ROWS: usize = 20_000;

impl DofMatrix {
    /// The sum of the element matrices `matrix(c)` (column-major, local
    /// dof `D a + i` of the cell's node `a`) of `cells` of `mesh`, added
    /// in the order of `cells`. Errors: more than `u32::MAX` dofs.
    pub fn assemble<'k, const D: usize>(
        mesh: &Mesh<D>,
        cells: &[usize],
        matrix: impl Fn(usize) -> &'k [f64],
    ) -> Result<Self, String> {
        let nn = mesh.nodes.len();
        u32::try_from(D * nn).map_err(|_| "the model has more than 4e9 dofs".to_string())?;
        let adj = super::linalg::pattern::NodeGraph::new(
            nn,
            cells.iter().map(|&c| mesh.cells.nodes(c)),
            &[],
        );
        // row `D a + i`: the blocks of a's neighbours, `D` columns each
        let mut row_ptr = Vec::with_capacity(D * nn + 1);
        row_ptr.push(0);
        let mut cols = Vec::with_capacity(D * D * adj.idx.len());
        for a in (0..nn).map(|a| adj.row(a)) {
            for _ in 0..D {
                cols.extend(
                    a.iter()
                        .flat_map(|&b| (0..D).map(move |j| D as u32 * b + j as u32)),
                );
                row_ptr.push(cols.len());
            }
        }
        let mut vals = vec![0.0; cols.len()];
        let mut at = Vec::new();
        for &c in cells {
            let nodes = mesh.cells.nodes(c);
            let nd = D * nodes.len();
            let k = matrix(c);
            // position of each node's block in each node's rows
            at.clear();
            for &a in nodes {
                for &b in nodes {
                    let p = adj.row(a).binary_search(&(b as u32)).expect("built above");
                    at.push(D * p);
                }
            }
            for (lb, _) in nodes.iter().enumerate() {
                for j in 0..D {
                    let col = D * lb + j;
                    for (la, &a) in nodes.iter().enumerate() {
                        let block = at[la * nodes.len() + lb];
                        for i in 0..D {
                            let slot = row_ptr[D * a + i] + block + j;
                            vals[slot] += k[col * nd + D * la + i];
                        }
                    }
                }
            }
        }
        Ok(DofMatrix {
            row_ptr,
            cols,
            vals,
        })
    }

    /// Number of rows.
    pub fn rows(&self) -> usize {
        self.row_ptr.len() - 1
    }

    /// `out = self u` (overwritten), the rows cut among `threads` threads
    /// when there are at least `min_rows` ([`PARALLEL_MIN_ROWS`] in the
    /// solver): each row is the same sum on any count.
    pub fn times(&self, u: &[f64], out: &mut [f64], (threads, min_rows): (usize, usize)) {
        let rows = |range: std::ops::Range<usize>, out: &mut [f64]| {
            for (r, o) in range.zip(out.iter_mut()) {
                let (s, e) = (self.row_ptr[r], self.row_ptr[r + 1]);
                *o = self.vals[s..e]
                    .iter()
                    .zip(&self.cols[s..e])
                    .map(|(v, &c)| v * u[c as usize])
                    .sum();
            }
        };
        let n = self.rows().min(out.len());
        if threads < 2 || n < min_rows.max(2) {
            rows(0..n, &mut out[..n]);
            return;
        }
        let parts = super::parallel::split(n, threads);
        std::thread::scope(|scope| {
            let mut rest = &mut out[..n];
            let mut first = None;
            for range in parts {
                let (head, tail) = rest.split_at_mut(range.len());
                rest = tail;
                if first.is_none() {
                    first = Some((range, head));
                    continue;
                }
                let rows = &rows;
                scope.spawn(move || rows(range, head));
            }
            if let Some((range, head)) = first {
                rows(range, head);
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Cell, Mesh};

    #[test]
    fn the_bulk_belongs_to_one_scatter_map() {
        let mut b = BulkTangent::default();
        let mut v = vec![1.0, 2.0];
        assert!(!b.copy_to(3, &mut v));
        b.store(3, vec![0.5, -1.0]);
        assert!(!b.copy_to(4, &mut v), "another map's values are not used");
        assert_eq!(v, [1.0, 2.0]);
        assert!(b.copy_to(3, &mut v));
        assert_eq!(v, [0.5, -1.0]);
        assert_eq!((b.builds, b.reuses), (1, 1));
        b.disabled = true;
        assert!(!b.copy_to(3, &mut v), "off: not used");
        b.clear();
        assert!(b.get(3).is_none());
    }

    /// Two triangles sharing an edge, arbitrary element matrices: the
    /// product equals the element-by-element sum, on 1 and 3 threads.
    #[test]
    fn the_dof_matrix_product_is_the_sum_of_the_element_products() {
        let mesh = Mesh::new(
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [2.0, 2.0]],
            vec![Cell::tri(0, 1, 2), Cell::tri(0, 2, 3)],
        );
        let k: Vec<Vec<f64>> = (0..2)
            .map(|c| {
                (0..36)
                    .map(|e| ((e * 7 + c * 3) % 11) as f64 - 4.5)
                    .collect()
            })
            .collect();
        let m = DofMatrix::assemble(&mesh, &[0, 1], |c| &k[c][..]).unwrap();
        assert_eq!(m.rows(), 10);
        let u: Vec<f64> = (0..10).map(|i| 0.1 * i as f64 - 0.3).collect();
        let mut want = vec![0.0; 10];
        for (c, ke) in k.iter().enumerate() {
            let nodes = mesh.cells.nodes(c);
            for j in 0..6 {
                for i in 0..6 {
                    want[2 * nodes[i / 2] + i % 2] += ke[j * 6 + i] * u[2 * nodes[j / 2] + j % 2];
                }
            }
        }
        let mut one = vec![f64::NAN; 10];
        m.times(&u, &mut one, (1, 0));
        for threads in [1, 3] {
            let mut f = vec![f64::NAN; 10];
            m.times(&u, &mut f, (threads, 0));
            assert!(f.iter().zip(&one).all(|(a, b)| a.to_bits() == b.to_bits()));
            for (a, b) in f.iter().zip(&want) {
                assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "{a} vs {b}");
            }
            // node 4 belongs to no cell: no force
            assert_eq!(&f[8..], &[0.0, 0.0]);
        }
    }
}
