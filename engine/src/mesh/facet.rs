//! Boundary facets: edges of planar cells and faces of solid cells, as
//! node lists in outward order (a planar edge has the body on its left; a
//! face is counter-clockwise seen from outside).

/// Most nodes a facet may have (a 9-node quadrilateral face).
pub const MAX_FACET_NODES: usize = 9;

/// A boundary facet: its nodes in outward order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Facet {
    /// Number of nodes.
    len: u8,
    /// Node numbers (the first `len` are used).
    nodes: [usize; MAX_FACET_NODES],
}

impl Facet {
    /// The facet with nodes `nodes` (2 to [`MAX_FACET_NODES`] of them).
    pub fn new(nodes: &[usize]) -> Self {
        assert!(
            (2..=MAX_FACET_NODES).contains(&nodes.len()),
            "a facet has 2 to {MAX_FACET_NODES} nodes"
        );
        let mut n = [usize::MAX; MAX_FACET_NODES];
        n[..nodes.len()].copy_from_slice(nodes);
        Facet {
            len: nodes.len() as u8,
            nodes: n,
        }
    }

    /// The node numbers.
    #[inline]
    pub fn nodes(&self) -> &[usize] {
        &self.nodes[..self.len as usize]
    }

    /// The same facet with node numbers shifted by `shift`.
    pub fn shifted(&self, shift: usize) -> Self {
        let n: Vec<usize> = self.nodes().iter().map(|n| n + shift).collect();
        Facet::new(&n)
    }

    /// The two nodes of an edge (the first two nodes).
    pub fn edge(&self) -> [usize; 2] {
        [self.nodes[0], self.nodes[1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn facets_keep_their_node_order() {
        let f = Facet::new(&[4, 1, 7]);
        assert_eq!(f.nodes(), &[4, 1, 7]);
        assert_eq!(f.shifted(10).nodes(), &[14, 11, 17]);
        assert_eq!(Facet::new(&[3, 2]).edge(), [3, 2]);
    }
}
