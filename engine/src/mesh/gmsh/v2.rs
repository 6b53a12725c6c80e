//! `$Nodes` and `$Elements` of the MSH 2.x format.
//!
//! ```text
//! $Nodes
//! n
//! tag x y z            (n lines)
//! $EndNodes
//! $Elements
//! n
//! tag type ntags tag_1 .. tag_ntags node_1 .. node_k   (n lines)
//! $EndElements
//! ```
//! The first element tag is the physical group (0: none), the second the
//! elementary entity.

use super::cursor::Cursor;
use super::raw::{ElementType, RawElement, RawMesh, RawNode};
use crate::mesh::MeshError;

/// Reads the body of `$Nodes` (after the header token) and `$EndNodes`.
pub fn nodes(c: &mut Cursor, raw: &mut RawMesh) -> Result<(), MeshError> {
    let n = c.usize("the number of nodes")?;
    for _ in 0..n {
        let tag = c.tag("a node tag")?;
        let line = c.line();
        let x = c.f64("the node's x")?;
        let y = c.f64("the node's y")?;
        let z = c.f64("the node's z")?;
        raw.nodes.push(RawNode {
            tag,
            xyz: [x, y, z],
            line,
        });
    }
    c.end("Nodes")
}

/// Reads the body of `$Elements` and `$EndElements`.
pub fn elements(c: &mut Cursor, raw: &mut RawMesh) -> Result<(), MeshError> {
    let n = c.usize("the number of elements")?;
    raw.elements.reserve(n.min(c.remaining_bytes() / 8));
    for _ in 0..n {
        c.tag("an element tag")?;
        let line = c.line();
        let t = c.i64("the element type")?;
        let kind = ElementType::from_gmsh(t, raw.solid).map_err(|m| MeshError::at_line(line, m))?;
        let ntags = c.usize("the number of element tags")?;
        let physicals_start = raw.element_physicals.len();
        for k in 0..ntags {
            let v = c.i64("an element tag value")?;
            if k == 0 && v != 0 {
                raw.element_physicals.push(v);
            }
        }
        let first_node = raw.element_nodes.len();
        for _ in 0..kind.nodes() {
            let tag = c.tag("a node tag of the element")?;
            raw.element_nodes.push(tag);
        }
        raw.elements.push(RawElement {
            kind,
            first_node,
            physicals: physicals_start..raw.element_physicals.len(),
            line,
        });
    }
    c.end("Elements")
}
