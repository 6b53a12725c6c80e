//! Constraint rows of the Lagrange-multiplier contact laws, in node terms.
//!
//! A law states `d g / d x` for each (node, component) its constraint
//! touches; it never sees the dof numbering (free / prescribed / inactive,
//! owned / ghost): `crate::solve::constraints` maps the rows to dofs. Rows
//! have any number of terms (a node on a rigid curve: 2; node-to-segment in
//! 2D: 6; a node on a quad facet in 3D: 15).

/// What a constraint row enforces.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RowKind {
    /// Normal contact `g = 0` of an active node; multiplier
    /// `PairState::multiplier`.
    Normal,
    /// Tangential stick `g_T = 0` (Lagrange friction); multiplier
    /// `PairState::friction.multiplier`.
    Stick,
}

/// One term `d g / d x[node][component]` of a row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeTerm {
    /// Global node number.
    pub node: usize,
    /// Component (0 = x or r, 1 = y or z, 2 = z).
    pub component: usize,
    /// `d g / d x` of that coordinate.
    pub coefficient: f64,
}

/// A view of one row.
#[derive(Debug, Clone, Copy)]
pub struct NodeRow<'a> {
    /// Terms, in the order the law produced them.
    pub terms: &'a [NodeTerm],
    /// The constrained gap (normal or tangential).
    pub gap: f64,
    /// `(pair, slave index)` owning the multiplier.
    pub owner: (usize, usize),
    /// Normal or stick.
    pub kind: RowKind,
    /// The force per unit multiplier where it is not the row itself (the
    /// saddle point's column; mortar: `D`, `M` and the normal held fixed
    /// while `terms` is the full derivative of the gap); empty: `terms`.
    pub force: &'a [NodeTerm],
    /// The node of the multiplier (the slave node), whose equilibrium
    /// equations the condensed solver eliminates the multiplier from
    /// (`crate::solve::linalg::condensed`); `usize::MAX` for a row
    /// without terms.
    pub node: usize,
}

/// Rows of every Lagrange pair at one evaluation (contiguous storage).
#[derive(Debug, Clone, Default)]
pub struct NodeRows {
    start: Vec<usize>,
    terms: Vec<NodeTerm>,
    gap: Vec<f64>,
    owner: Vec<(usize, usize)>,
    kind: Vec<RowKind>,
    /// Start of each row's force terms in `force` (empty: the row's own).
    force_start: Vec<usize>,
    force: Vec<NodeTerm>,
    /// The multiplier's node of each row.
    node: Vec<usize>,
}

impl NodeRows {
    /// Removes every row (keeps the storage).
    pub fn clear(&mut self) {
        self.start.clear();
        self.terms.clear();
        self.gap.clear();
        self.owner.clear();
        self.kind.clear();
        self.force_start.clear();
        self.force.clear();
        self.node.clear();
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.gap.len()
    }

    /// Whether there is no row.
    pub fn is_empty(&self) -> bool {
        self.gap.is_empty()
    }

    /// Appends a row with `terms` (`(node, component, d g / d x)`); the
    /// multiplier's node is the first term's (the slave node: rigid tools,
    /// node-to-segment, stick rows list it first).
    pub fn push(
        &mut self,
        kind: RowKind,
        owner: (usize, usize),
        gap: f64,
        terms: impl IntoIterator<Item = NodeTerm>,
    ) {
        let begin = self.terms.len();
        self.start.push(begin);
        self.terms.extend(terms);
        self.gap.push(gap);
        self.owner.push(owner);
        self.kind.push(kind);
        self.force_start.push(self.force.len());
        self.node
            .push(self.terms.get(begin).map_or(usize::MAX, |t| t.node));
    }

    /// Appends a row whose force per unit multiplier `force` (the saddle
    /// point's column) differs from its terms `d g / d x` (the row); the
    /// multiplier lives on `node` (mortar: the slave node).
    pub fn push_split(
        &mut self,
        kind: RowKind,
        owner: (usize, usize),
        node: usize,
        gap: f64,
        terms: impl IntoIterator<Item = NodeTerm>,
        force: impl IntoIterator<Item = NodeTerm>,
    ) {
        self.push(kind, owner, gap, terms);
        self.force.extend(force);
        if let Some(last) = self.node.last_mut() {
            *last = node;
        }
    }

    /// Every row, in the order pushed.
    pub fn iter(&self) -> impl Iterator<Item = NodeRow<'_>> + '_ {
        (0..self.len()).map(move |k| {
            let end = self.start.get(k + 1).copied().unwrap_or(self.terms.len());
            let force_end = self
                .force_start
                .get(k + 1)
                .copied()
                .unwrap_or(self.force.len());
            NodeRow {
                terms: &self.terms[self.start[k]..end],
                force: &self.force[self.force_start[k]..force_end],
                gap: self.gap[k],
                owner: self.owner[k],
                kind: self.kind[k],
                node: self.node[k],
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_keep_their_terms_and_order() {
        let mut r = NodeRows::default();
        let t = |node, component, coefficient| NodeTerm {
            node,
            component,
            coefficient,
        };
        r.push(RowKind::Normal, (0, 3), -0.1, [t(7, 0, 0.6), t(7, 1, 0.8)]);
        r.push(RowKind::Stick, (1, 0), 0.0, []);
        r.push(
            RowKind::Normal,
            (0, 4),
            0.2,
            (0..15).map(|k| t(k / 3, k % 3, 1.0)),
        );
        let rows: Vec<_> = r.iter().collect();
        assert_eq!(rows.len(), 3);
        assert_eq!(rows[0].terms, &[t(7, 0, 0.6), t(7, 1, 0.8)]);
        assert_eq!((rows[0].gap, rows[0].owner), (-0.1, (0, 3)));
        assert!(rows[1].terms.is_empty() && rows[1].kind == RowKind::Stick);
        assert_eq!(rows[2].terms.len(), 15);
        assert!(rows.iter().all(|r| r.force.is_empty()));
        r.push_split(
            RowKind::Normal,
            (0, 5),
            2,
            0.0,
            [t(1, 0, 0.5)],
            [t(1, 0, 1.0), t(2, 1, -1.0)],
        );
        r.push(RowKind::Normal, (0, 6), 0.0, [t(3, 0, 1.0)]);
        let rows: Vec<_> = r.iter().collect();
        assert_eq!(rows[3].terms, &[t(1, 0, 0.5)]);
        assert_eq!(rows[3].force, &[t(1, 0, 1.0), t(2, 1, -1.0)]);
        assert_eq!((rows[3].node, rows[4].node, rows[0].node), (2, 3, 7));
        assert_eq!(rows[1].node, usize::MAX);
        assert!(rows[4].force.is_empty() && rows[2].force.is_empty());
        r.clear();
        assert!(r.is_empty());
    }
}
