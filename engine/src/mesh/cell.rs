//! Cell kinds and the cell storage: connectivity in compressed rows (one
//! node list per cell, any length), so cells of any order fit.

use serde::Serialize;

/// Cell topology.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CellKind {
    /// 3-node linear triangle.
    Tri3,
    /// 4-node bilinear quadrilateral.
    Quad4,
    /// 4-node linear tetrahedron.
    Tet4,
    /// 8-node trilinear hexahedron.
    Hex8,
    /// 6-node quadratic triangle.
    Tri6,
    /// 8-node serendipity quadrilateral, 3x3 Gauss points.
    Quad8,
    /// 8-node serendipity quadrilateral, reduced 2x2 Gauss points.
    Quad8R,
    /// 9-node biquadratic quadrilateral.
    Quad9,
    /// 10-node quadratic tetrahedron.
    Tet10,
    /// 20-node serendipity hexahedron, 3x3x3 Gauss points.
    Hex20,
    /// 20-node serendipity hexahedron, reduced 2x2x2 Gauss points.
    Hex20R,
    /// 27-node triquadratic hexahedron.
    Hex27,
}

impl CellKind {
    /// Number of nodes of the cell.
    pub fn node_count(self) -> usize {
        match self {
            CellKind::Tri3 => 3,
            CellKind::Quad4 | CellKind::Tet4 => 4,
            CellKind::Hex8 | CellKind::Quad8 | CellKind::Quad8R => 8,
            CellKind::Tri6 => 6,
            CellKind::Quad9 => 9,
            CellKind::Tet10 => 10,
            CellKind::Hex20 | CellKind::Hex20R => 20,
            CellKind::Hex27 => 27,
        }
    }

    /// Dimension of the cell (2 or 3).
    pub fn dimension(self) -> usize {
        match self {
            CellKind::Tri3
            | CellKind::Quad4
            | CellKind::Tri6
            | CellKind::Quad8
            | CellKind::Quad8R
            | CellKind::Quad9 => 2,
            CellKind::Tet4
            | CellKind::Hex8
            | CellKind::Tet10
            | CellKind::Hex20
            | CellKind::Hex20R
            | CellKind::Hex27 => 3,
        }
    }

    /// Polynomial order of the shape functions (1 or 2).
    pub fn order(self) -> usize {
        match self {
            CellKind::Tri3 | CellKind::Quad4 | CellKind::Tet4 | CellKind::Hex8 => 1,
            _ => 2,
        }
    }

    /// The linear cell of the same shape (its corners are the first
    /// nodes of this cell).
    pub fn linear(self) -> CellKind {
        match self {
            CellKind::Tri3 | CellKind::Tri6 => CellKind::Tri3,
            CellKind::Quad4 | CellKind::Quad8 | CellKind::Quad8R | CellKind::Quad9 => {
                CellKind::Quad4
            }
            CellKind::Tet4 | CellKind::Tet10 => CellKind::Tet4,
            CellKind::Hex8 | CellKind::Hex20 | CellKind::Hex20R | CellKind::Hex27 => CellKind::Hex8,
        }
    }

    /// Number of corner nodes (the nodes of [`CellKind::linear`]).
    pub fn corner_count(self) -> usize {
        self.linear().node_count()
    }

    /// Short name (`tri3`, `quad4`, `tet4`, `hex8`, `tri6`, `quad8`,
    /// `quad8r`, `quad9`, `tet10`, `hex20`, `hex20r`, `hex27`).
    pub fn name(self) -> &'static str {
        match self {
            CellKind::Tri3 => "tri3",
            CellKind::Quad4 => "quad4",
            CellKind::Tet4 => "tet4",
            CellKind::Hex8 => "hex8",
            CellKind::Tri6 => "tri6",
            CellKind::Quad8 => "quad8",
            CellKind::Quad8R => "quad8r",
            CellKind::Quad9 => "quad9",
            CellKind::Tet10 => "tet10",
            CellKind::Hex20 => "hex20",
            CellKind::Hex20R => "hex20r",
            CellKind::Hex27 => "hex27",
        }
    }

    /// Local node lists of the faces (edges in 2D), ordered so that their
    /// normal points out of the cell (`crate::element::reference`).
    pub fn faces(self) -> &'static [&'static [usize]] {
        use crate::element::reference::{
            Hex20, Hex27, Hex8, Quad4, Quad8, Quad9, ReferenceCell, Tet10, Tet4, Tri3, Tri6,
        };
        match self {
            CellKind::Tri3 => <Tri3 as ReferenceCell<2, 3>>::FACES,
            CellKind::Quad4 => <Quad4 as ReferenceCell<2, 4>>::FACES,
            CellKind::Tet4 => <Tet4 as ReferenceCell<3, 4>>::FACES,
            CellKind::Hex8 => <Hex8 as ReferenceCell<3, 8>>::FACES,
            CellKind::Tri6 => <Tri6 as ReferenceCell<2, 6>>::FACES,
            CellKind::Quad8 | CellKind::Quad8R => <Quad8 as ReferenceCell<2, 8>>::FACES,
            CellKind::Quad9 => <Quad9 as ReferenceCell<2, 9>>::FACES,
            CellKind::Tet10 => <Tet10 as ReferenceCell<3, 10>>::FACES,
            CellKind::Hex20 | CellKind::Hex20R => <Hex20 as ReferenceCell<3, 20>>::FACES,
            CellKind::Hex27 => <Hex27 as ReferenceCell<3, 27>>::FACES,
        }
    }
}

/// One cell to add to a mesh: its kind and node numbers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Cell {
    /// Topology.
    pub kind: CellKind,
    /// Node numbers (counter-clockwise in 2D, gmsh order in 3D).
    pub nodes: Vec<usize>,
}

impl Cell {
    /// A counter-clockwise triangle.
    pub fn tri(a: usize, b: usize, c: usize) -> Self {
        Cell {
            kind: CellKind::Tri3,
            nodes: vec![a, b, c],
        }
    }

    /// A counter-clockwise quadrilateral.
    pub fn quad(a: usize, b: usize, c: usize, d: usize) -> Self {
        Cell {
            kind: CellKind::Quad4,
            nodes: vec![a, b, c, d],
        }
    }

    /// A positively oriented tetrahedron (gmsh order).
    pub fn tet(n: [usize; 4]) -> Self {
        Cell {
            kind: CellKind::Tet4,
            nodes: n.to_vec(),
        }
    }

    /// A positively oriented hexahedron (gmsh order: bottom face
    /// counter-clockwise seen from the top, then the top face).
    pub fn hex(n: [usize; 8]) -> Self {
        Cell {
            kind: CellKind::Hex8,
            nodes: n.to_vec(),
        }
    }
}

/// A cell of a mesh, borrowed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CellRef<'a> {
    /// Topology.
    pub kind: CellKind,
    /// Node numbers.
    pub nodes: &'a [usize],
}

/// The cells of a mesh in compressed rows.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Cells {
    /// Kind of each cell.
    kinds: Vec<CellKind>,
    /// Start of each cell's nodes in `nodes` (`len + 1` entries, or empty).
    offsets: Vec<usize>,
    /// Node numbers of all cells, concatenated.
    nodes: Vec<usize>,
}

impl Cells {
    /// No cells.
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.kinds.len()
    }

    /// Whether there is no cell.
    pub fn is_empty(&self) -> bool {
        self.kinds.is_empty()
    }

    /// Appends a cell of kind `kind` with nodes `nodes` (`kind.node_count()`
    /// of them).
    pub fn push_nodes(&mut self, kind: CellKind, nodes: &[usize]) {
        debug_assert_eq!(nodes.len(), kind.node_count());
        if self.offsets.is_empty() {
            self.offsets.push(0);
        }
        self.kinds.push(kind);
        self.nodes.extend_from_slice(nodes);
        self.offsets.push(self.nodes.len());
    }

    /// Appends `cell`.
    pub fn push(&mut self, cell: Cell) {
        self.push_nodes(cell.kind, &cell.nodes);
    }

    /// Kind of cell `c`.
    #[inline]
    pub fn kind(&self, c: usize) -> CellKind {
        self.kinds[c]
    }

    /// Nodes of cell `c`.
    #[inline]
    pub fn nodes(&self, c: usize) -> &[usize] {
        &self.nodes[self.offsets[c]..self.offsets[c + 1]]
    }

    /// Nodes of cell `c`, mutable.
    pub fn nodes_mut(&mut self, c: usize) -> &mut [usize] {
        &mut self.nodes[self.offsets[c]..self.offsets[c + 1]]
    }

    /// Cell `c`.
    #[inline]
    pub fn get(&self, c: usize) -> CellRef<'_> {
        CellRef {
            kind: self.kinds[c],
            nodes: self.nodes(c),
        }
    }

    /// The cells in order.
    pub fn iter(&self) -> CellIter<'_> {
        CellIter {
            cells: self,
            next: 0,
        }
    }

    /// Appends the cells of `other` with node numbers shifted by `shift`.
    pub fn extend_shifted(&mut self, other: &Cells, shift: usize) {
        for c in other.iter() {
            let shifted: Vec<usize> = c.nodes.iter().map(|n| n + shift).collect();
            self.push_nodes(c.kind, &shifted);
        }
    }

    /// Every node number of every cell (with repetitions).
    pub fn all_nodes(&self) -> &[usize] {
        &self.nodes
    }

    /// The distinct cell kinds present, sorted.
    pub fn kinds(&self) -> Vec<CellKind> {
        let mut k = self.kinds.clone();
        k.sort_unstable();
        k.dedup();
        k
    }
}

impl FromIterator<Cell> for Cells {
    fn from_iter<I: IntoIterator<Item = Cell>>(iter: I) -> Self {
        let mut cells = Cells::new();
        for c in iter {
            cells.push(c);
        }
        cells
    }
}

/// Iterator over the cells of a mesh.
#[derive(Debug, Clone)]
pub struct CellIter<'a> {
    cells: &'a Cells,
    next: usize,
}

impl<'a> Iterator for CellIter<'a> {
    type Item = CellRef<'a>;

    fn next(&mut self) -> Option<CellRef<'a>> {
        if self.next < self.cells.len() {
            self.next += 1;
            Some(self.cells.get(self.next - 1))
        } else {
            None
        }
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.cells.len() - self.next;
        (n, Some(n))
    }
}

impl ExactSizeIterator for CellIter<'_> {}

impl<'a> IntoIterator for &'a Cells {
    type Item = CellRef<'a>;
    type IntoIter = CellIter<'a>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compressed_rows_hold_cells_of_any_size() {
        let mut cells: Cells = [Cell::tri(0, 1, 2), Cell::hex([0, 1, 2, 3, 4, 5, 6, 7])]
            .into_iter()
            .collect();
        cells.push(Cell::quad(3, 4, 5, 6));
        assert_eq!(cells.len(), 3);
        assert_eq!(cells.nodes(1), &[0, 1, 2, 3, 4, 5, 6, 7]);
        assert_eq!(cells.get(2).kind, CellKind::Quad4);
        let mut more = Cells::new();
        more.extend_shifted(&cells, 10);
        assert_eq!(more.nodes(0), &[10, 11, 12]);
        assert_eq!(
            cells.kinds(),
            vec![CellKind::Tri3, CellKind::Quad4, CellKind::Hex8]
        );
        assert_eq!(cells.iter().map(|c| c.nodes.len()).sum::<usize>(), 15);
        assert_eq!(CellKind::Hex8.faces().len(), 6);
    }
}
