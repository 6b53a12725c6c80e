//! Lagrange-multiplier constraint rows in dof terms.
//!
//! A contact law states its constraints in node terms
//! ([`crate::contact::rows::NodeRows`]: `d g / d x` per (node, component),
//! any number of terms: 2 for a node on a rigid curve, 6 for node-to-segment
//! in 2D, 15 for a node on a quad facet in 3D). This module alone maps them
//! to the dof numbering: free dofs become the rows `G = -d g / d u_free` of
//! the saddle-point system, prescribed dofs the coupling `d g / d u_p` that
//! carries the prescribed increment into the constraint right-hand side,
//! inactive dofs are dropped. Under MPI this is where owned / ghost dofs
//! will be told apart; the contact laws do not change.

use super::dofs::{Dof, DofMap};
use crate::contact::rows::{NodeRows, RowKind};

/// Variable-length sparse rows `(column, coefficient)`, stored
/// contiguously (CSR); entries of each row sorted by column.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstraintRows {
    /// Start of each row in `entries` (`rows + 1` values).
    start: Vec<usize>,
    /// `(column, coefficient)` of every row, row after row.
    entries: Vec<(usize, f64)>,
}

impl Default for ConstraintRows {
    fn default() -> Self {
        ConstraintRows {
            start: vec![0],
            entries: Vec::new(),
        }
    }
}

impl ConstraintRows {
    /// Number of rows.
    pub fn len(&self) -> usize {
        self.start.len() - 1
    }

    /// Whether there is no row.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Removes every row (keeps the storage).
    pub fn clear(&mut self) {
        self.start.truncate(1);
        self.entries.clear();
    }

    /// Entries of row `k`, sorted by column.
    pub fn row(&self, k: usize) -> &[(usize, f64)] {
        &self.entries[self.start[k]..self.start[k + 1]]
    }

    /// Every row in order.
    pub fn iter(&self) -> impl Iterator<Item = &[(usize, f64)]> + '_ {
        self.start.windows(2).map(|w| &self.entries[w[0]..w[1]])
    }

    /// Appends a row as given (entries in the given order).
    fn push_unsorted(&mut self, entries: impl IntoIterator<Item = (usize, f64)>) {
        self.entries.extend(entries);
        self.start.push(self.entries.len());
    }

    /// Appends a row; its entries are sorted by column (stable: equal
    /// columns keep their order).
    pub fn push(&mut self, entries: impl IntoIterator<Item = (usize, f64)>) {
        let begin = self.entries.len();
        self.entries.extend(entries);
        self.entries[begin..].sort_by_key(|e| e.0);
        self.start.push(self.entries.len());
    }
}

/// The Lagrange constraints of the last contact evaluation, in dof terms.
#[derive(Debug, Clone, Default)]
pub struct Constraints {
    /// Rows `G = -d g / d u_free`, one per constraint.
    pub rows: ConstraintRows,
    /// Columns `-d f / d lambda` on the free dofs (the force per unit
    /// multiplier), one per constraint: equal to `rows` unless the law
    /// gives a separate force ([`crate::contact::rows::NodeRow::force`]).
    pub columns: ConstraintRows,
    /// Whether every column equals its row (a symmetric saddle point).
    pub symmetric: bool,
    /// Per constraint: its column restricted to the free dofs of the
    /// multiplier's node ([`crate::contact::rows::NodeRow::node`]), the
    /// equations the condensed solver eliminates the multiplier from
    /// ([`super::linalg::condensed`]).
    pub pivots: ConstraintRows,
    /// Gap of each constraint (normal gap, or tangential gap of a stick row).
    pub gap: Vec<f64>,
    /// `(pair, slave index)` of each constraint.
    pub owner: Vec<(usize, usize)>,
    /// Per constraint: `(prescribed dof index into DofMap::prescribed,
    /// d g / d u_p)`.
    pub prescribed: ConstraintRows,
    /// Per constraint: normal row or tangential stick row (whose multiplier
    /// is `PairState::friction.multiplier`).
    pub kind: Vec<RowKind>,
}

impl Constraints {
    /// Number of constraints.
    pub fn len(&self) -> usize {
        self.gap.len()
    }

    /// Whether there is no constraint.
    pub fn is_empty(&self) -> bool {
        self.gap.is_empty()
    }

    /// Maps the node-term rows of the contact laws to dof terms.
    pub fn build<const D: usize>(&mut self, rows: &NodeRows, dofs: &DofMap<D>) {
        self.rows.clear();
        self.columns.clear();
        self.pivots.clear();
        self.symmetric = true;
        self.prescribed.clear();
        self.gap.clear();
        self.owner.clear();
        self.kind.clear();
        let mut free = Vec::new();
        let mut presc = Vec::new();
        let mut column = Vec::new();
        let mut pivot = Vec::new();
        for row in rows.iter() {
            free.clear();
            presc.clear();
            pivot.clear();
            for t in row.terms {
                match dofs.dofs[dofs.dof(t.node, t.component)] {
                    Dof::Free(f) => {
                        free.push((f, -t.coefficient));
                        if row.force.is_empty() && t.node == row.node {
                            pivot.push((f, -t.coefficient));
                        }
                    }
                    Dof::Prescribed(p) => presc.push((p, t.coefficient)),
                    Dof::Inactive => {}
                }
            }
            self.rows.push(free.iter().copied());
            if row.force.is_empty() {
                self.columns.push(free.iter().copied());
            } else {
                self.symmetric = false;
                column.clear();
                for t in row.force {
                    if let Dof::Free(f) = dofs.dofs[dofs.dof(t.node, t.component)] {
                        column.push((f, -t.coefficient));
                        if t.node == row.node {
                            pivot.push((f, -t.coefficient));
                        }
                    }
                }
                self.columns.push(column.iter().copied());
            }
            self.pivots.push(pivot.iter().copied());
            // prescribed terms keep their order: they only enter sums, in
            // this order
            self.prescribed.push_unsorted(presc.iter().copied());
            self.gap.push(row.gap);
            self.owner.push(row.owner);
            self.kind.push(row.kind);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_of_any_length_are_stored_sorted_and_in_order() {
        let mut r = ConstraintRows::default();
        assert!(r.is_empty());
        r.push([(5, 1.0), (2, -1.0)]);
        // a quad-facet row in 3D: 5 nodes x 3 components
        r.push((0..15).rev().map(|c| (c, c as f64)));
        r.push([]);
        assert_eq!(r.len(), 3);
        assert_eq!(r.row(0), &[(2, -1.0), (5, 1.0)]);
        assert_eq!(r.row(1).len(), 15);
        assert!(r.row(1).windows(2).all(|w| w[0].0 < w[1].0));
        assert!(r.row(2).is_empty());
        assert_eq!(r.iter().count(), 3);
        r.clear();
        assert!(r.is_empty());
    }
}
