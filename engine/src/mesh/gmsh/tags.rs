//! gmsh node tag -> position in the file's node list.
//!
//! gmsh numbers nodes 1..n in nearly every file: then the index is a
//! vector over the tags (one load per lookup); tags spread over a range
//! much wider than the node count (a file cut out of a larger model) go to
//! a hash map. Lookups only (no iteration), so the choice cannot change
//! the mesh. Issue 20: the SipHash map of every tag was ~3 % of a whole
//! `ctc run` of an 80,000-dof gmsh mesh.

use crate::mesh::MeshError;
use rustc_hash::FxHashMap;

use super::raw::RawNode;

/// Dense tags: the largest tag at most this many times the node count
/// (plus [`DENSE_SLACK`]) takes the vector.
const DENSE_FACTOR: u64 = 4;

/// Tags below this always take the vector (small files with sparse tags).
const DENSE_SLACK: u64 = 1 << 16;

/// Where each tag's node is in the file's node list.
#[derive(Debug)]
pub enum TagIndex {
    /// Position of tag `t` at `t` (`usize::MAX`: no such node).
    Dense(Vec<usize>),
    /// Position of each tag (tags far apart).
    Sparse(FxHashMap<u64, usize>),
}

impl TagIndex {
    /// The index of `nodes` (file order). Errors: a tag defined twice,
    /// at the line of its second definition.
    pub fn new(nodes: &[RawNode]) -> Result<Self, MeshError> {
        let max = nodes.iter().map(|n| n.tag).max().unwrap_or(0);
        let twice = |n: &RawNode, j: usize| {
            MeshError::at_line(
                n.line,
                format!(
                    "node tag {} is defined twice (first at line {})",
                    n.tag, nodes[j].line
                ),
            )
        };
        if max <= DENSE_FACTOR * nodes.len() as u64 + DENSE_SLACK {
            let mut at = vec![usize::MAX; max as usize + 1];
            for (i, n) in nodes.iter().enumerate() {
                let slot = &mut at[n.tag as usize];
                if *slot != usize::MAX {
                    return Err(twice(n, *slot));
                }
                *slot = i;
            }
            return Ok(TagIndex::Dense(at));
        }
        let mut at = FxHashMap::default();
        at.reserve(nodes.len());
        for (i, n) in nodes.iter().enumerate() {
            if let Some(&j) = at.get(&n.tag) {
                return Err(twice(n, j));
            }
            at.insert(n.tag, i);
        }
        Ok(TagIndex::Sparse(at))
    }

    /// The position of tag `t`, if a node has it.
    pub fn get(&self, t: u64) -> Option<usize> {
        match self {
            TagIndex::Dense(at) => usize::try_from(t)
                .ok()
                .and_then(|t| at.get(t))
                .copied()
                .filter(|&i| i != usize::MAX),
            TagIndex::Sparse(at) => at.get(&t).copied(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn node(tag: u64, line: usize) -> RawNode {
        RawNode {
            tag,
            xyz: [0.0; 3],
            line,
        }
    }

    #[test]
    fn dense_and_sparse_tags_give_the_same_positions() {
        let dense = [node(3, 10), node(1, 11), node(7, 12)];
        let idx = TagIndex::new(&dense).unwrap();
        assert!(matches!(idx, TagIndex::Dense(_)));
        assert_eq!(
            [1, 3, 7, 2, 0, 8].map(|t| idx.get(t)),
            [Some(1), Some(0), Some(2), None, None, None]
        );
        let sparse = [node(3, 10), node(1 << 40, 11), node(7, 12)];
        let idx = TagIndex::new(&sparse).unwrap();
        assert!(matches!(idx, TagIndex::Sparse(_)));
        assert_eq!(
            [3, 1 << 40, 7, 2].map(|t| idx.get(t)),
            [Some(0), Some(1), Some(2), None]
        );
    }

    #[test]
    fn a_tag_defined_twice_is_an_error_at_its_second_line() {
        for nodes in [
            vec![node(2, 5), node(4, 6), node(2, 7)],
            vec![node(1 << 40, 5), node(4, 6), node(1 << 40, 7)],
        ] {
            let e = TagIndex::new(&nodes).unwrap_err().to_string();
            assert!(e.contains("line 7") || e.contains('7'), "{e}");
            assert!(e.contains("defined twice (first at line 5)"), "{e}");
        }
    }
}
