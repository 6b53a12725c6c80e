//! `$Entities`, `$Nodes` and `$Elements` of the MSH 4.1 format.
//!
//! ```text
//! $Entities
//! numPoints numCurves numSurfaces numVolumes
//! pointTag x y z numPhysicalTags physicalTag ...
//! curveTag minX minY minZ maxX maxY maxZ numPhysicalTags physicalTag ... numBoundingPoints pointTag ...
//! (surfaces, volumes alike)
//! $EndEntities
//! $Nodes
//! numEntityBlocks numNodes minNodeTag maxNodeTag
//! entityDim entityTag parametric numNodesInBlock
//! nodeTag                      (numNodesInBlock lines)
//! x y z [u [v [w]]]            (numNodesInBlock lines)
//! ...
//! $EndNodes
//! $Elements
//! numEntityBlocks numElements minElementTag maxElementTag
//! entityDim entityTag elementType numElementsInBlock
//! elementTag nodeTag ...       (numElementsInBlock lines)
//! ...
//! $EndElements
//! ```
//! Physical groups are attached to entities; elements inherit those of
//! their block's entity.

use super::cursor::Cursor;
use super::raw::{ElementType, RawElement, RawMesh, RawNode};
use crate::mesh::MeshError;
use std::collections::HashMap;

/// Physical tags of each `(dim, entity tag)`.
pub type EntityPhysicals = HashMap<(usize, i64), Vec<i64>>;

/// Reads the body of `$Entities` and `$EndEntities`.
pub fn entities(c: &mut Cursor) -> Result<EntityPhysicals, MeshError> {
    let mut map = EntityPhysicals::new();
    let counts = [
        c.usize("the number of points")?,
        c.usize("the number of curves")?,
        c.usize("the number of surfaces")?,
        c.usize("the number of volumes")?,
    ];
    for (dim, &count) in counts.iter().enumerate() {
        for _ in 0..count {
            let tag = c.i64("an entity tag")?;
            // a point has x y z, the others a bounding box
            let reals = if dim == 0 { 3 } else { 6 };
            for _ in 0..reals {
                let (tok, line) = c.token("a coordinate")?;
                if tok.parse::<f64>().is_err() {
                    return Err(MeshError::at_line(
                        line,
                        format!("in $Entities: expected a coordinate, found '{tok}'"),
                    ));
                }
            }
            let np = c.usize("the number of physical tags")?;
            let mut phys = Vec::new();
            for _ in 0..np {
                phys.push(c.i64("a physical tag")?);
            }
            if dim > 0 {
                let nb = c.usize("the number of bounding entities")?;
                for _ in 0..nb {
                    c.i64("a bounding entity tag")?;
                }
            }
            if !phys.is_empty() {
                map.insert((dim, tag), phys);
            }
        }
    }
    c.end("Entities")?;
    Ok(map)
}

/// Reads the body of `$Nodes` and `$EndNodes`.
pub fn nodes(c: &mut Cursor, raw: &mut RawMesh) -> Result<(), MeshError> {
    let blocks = c.usize("the number of entity blocks")?;
    let header = c.line();
    let total = c.usize("the number of nodes")?;
    c.usize("the smallest node tag")?;
    c.usize("the largest node tag")?;
    let mut read = 0usize;
    for _ in 0..blocks {
        let dim = c.usize("the entity dimension")?;
        let block_line = c.line();
        if dim > 3 {
            return Err(MeshError::at_line(
                block_line,
                format!("in $Nodes: entity dimension {dim} is not 0, 1, 2 or 3"),
            ));
        }
        c.i64("the entity tag")?;
        let parametric = c.usize("the parametric flag")?;
        let n = c.usize("the number of nodes in the block")?;
        let mut tags = Vec::new();
        for _ in 0..n {
            tags.push(c.tag("a node tag")?);
        }
        let extra = if parametric == 0 { 0 } else { dim };
        for tag in tags {
            let x = c.f64("the node's x")?;
            let line = c.line();
            let y = c.f64("the node's y")?;
            let z = c.f64("the node's z")?;
            for _ in 0..extra {
                c.f64("a parametric coordinate")?;
            }
            raw.nodes.push(RawNode {
                tag,
                xyz: [x, y, z],
                line,
            });
        }
        read = read.saturating_add(n);
    }
    if read != total {
        return Err(MeshError::at_line(
            header,
            format!("in $Nodes: the header announces {total} nodes but the blocks hold {read}"),
        ));
    }
    c.end("Nodes")
}

/// Reads the body of `$Elements` and `$EndElements`.
pub fn elements(
    c: &mut Cursor,
    raw: &mut RawMesh,
    entities: &EntityPhysicals,
) -> Result<(), MeshError> {
    let blocks = c.usize("the number of entity blocks")?;
    let header = c.line();
    let total = c.usize("the number of elements")?;
    c.usize("the smallest element tag")?;
    c.usize("the largest element tag")?;
    let mut read = 0usize;
    for _ in 0..blocks {
        let dim = c.usize("the entity dimension")?;
        let block_line = c.line();
        let entity = c.i64("the entity tag")?;
        let t = c.i64("the element type")?;
        let kind =
            ElementType::from_gmsh(t, raw.solid).map_err(|m| MeshError::at_line(block_line, m))?;
        if kind.dim() != dim {
            return Err(MeshError::at_line(
                block_line,
                format!(
                    "in $Elements: a block of element type {t} (dimension {}) in an entity of dimension {dim}",
                    kind.dim()
                ),
            ));
        }
        let physicals = entities.get(&(dim, entity)).cloned().unwrap_or_default();
        let n = c.usize("the number of elements in the block")?;
        for _ in 0..n {
            c.tag("an element tag")?;
            let line = c.line();
            let first_node = raw.element_nodes.len();
            for _ in 0..kind.nodes() {
                let tag = c.tag("a node tag of the element")?;
                raw.element_nodes.push(tag);
            }
            let start = raw.element_physicals.len();
            raw.element_physicals.extend_from_slice(&physicals);
            raw.elements.push(RawElement {
                kind,
                first_node,
                physicals: start..raw.element_physicals.len(),
                line,
            });
        }
        read = read.saturating_add(n);
    }
    if read != total {
        return Err(MeshError::at_line(
            header,
            format!(
                "in $Elements: the header announces {total} elements but the blocks hold {read}"
            ),
        ));
    }
    c.end("Elements")
}
