//! The file's content before assembly: nodes and elements by gmsh tag,
//! physical groups and names, each with the line it came from.

use std::collections::BTreeMap;

/// Element types read (first and second order); anything else is an
/// error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElementType {
    /// gmsh type 15, 1-node point.
    Point,
    /// gmsh type 1, 2-node line.
    Line,
    /// gmsh type 2, 3-node triangle.
    Triangle,
    /// gmsh type 3, 4-node quadrangle.
    Quadrangle,
    /// gmsh type 4, 4-node tetrahedron (solid meshes only).
    Tetrahedron,
    /// gmsh type 5, 8-node hexahedron (solid meshes only).
    Hexahedron,
    /// gmsh type 8, 3-node line (planar meshes: edge and node sets of
    /// quadratic cells; solid meshes: node sets).
    Line3,
    /// gmsh type 9, 6-node triangle (planar meshes: tri6 cells; solid
    /// meshes: face sets).
    Triangle6,
    /// gmsh type 16, 8-node quadrangle (planar: quad8 cells; solid: face
    /// sets).
    Quadrangle8,
    /// gmsh type 10, 9-node quadrangle (planar: quad9 cells; solid: face
    /// sets).
    Quadrangle9,
    /// gmsh type 11, 10-node tetrahedron (solid meshes only).
    Tetrahedron10,
    /// gmsh type 17, 20-node hexahedron (solid meshes only).
    Hexahedron20,
    /// gmsh type 12, 27-node hexahedron (solid meshes only).
    Hexahedron27,
}

impl ElementType {
    /// The supported type of gmsh type number `t` in a planar (`solid =
    /// false`) or solid mesh, or why it is not.
    pub fn from_gmsh(t: i64, solid: bool) -> Result<Self, String> {
        Ok(match t {
            15 => ElementType::Point,
            1 => ElementType::Line,
            2 => ElementType::Triangle,
            3 => ElementType::Quadrangle,
            4 if solid => ElementType::Tetrahedron,
            5 if solid => ElementType::Hexahedron,
            8 => ElementType::Line3,
            9 => ElementType::Triangle6,
            16 => ElementType::Quadrangle8,
            10 => ElementType::Quadrangle9,
            11 if solid => ElementType::Tetrahedron10,
            17 if solid => ElementType::Hexahedron20,
            12 if solid => ElementType::Hexahedron27,
            29..=35 | 92 | 93 if solid => return Err(higher_order(t, "solid")),
            26..=28 | 20..=25 | 36 | 37 if solid => return Err(higher_order(t, "facet")),
            6 | 7 | 13 | 14 | 18 | 19 if solid => {
                return Err(format!(
                    "element type {t} (prism or pyramid) is not supported: ctc reads tetrahedra (4) and hexahedra (5)"
                ))
            }
            26..=28 => return Err(higher_order(t, "line")),
            20..=25 => return Err(higher_order(t, "triangle")),
            36 | 37 => return Err(higher_order(t, "quadrangle")),
            4..=7 | 11..=14 | 17..=19 | 29..=35 | 92 | 93 => {
                return Err(format!(
                    "element type {t} is a 3D element: ctc reads 2D meshes only (triangles and quadrangles in a plane)"
                ))
            }
            _ => {
                return Err(format!(
                    "unsupported element type {t}: ctc reads points (15), lines (1), triangles (2) and quadrangles (3)"
                ))
            }
        })
    }

    /// Nodes per element.
    pub fn nodes(self) -> usize {
        match self {
            ElementType::Point => 1,
            ElementType::Line => 2,
            ElementType::Triangle => 3,
            ElementType::Quadrangle | ElementType::Tetrahedron => 4,
            ElementType::Hexahedron => 8,
            ElementType::Line3 => 3,
            ElementType::Triangle6 => 6,
            ElementType::Quadrangle8 => 8,
            ElementType::Quadrangle9 => 9,
            ElementType::Tetrahedron10 => 10,
            ElementType::Hexahedron20 => 20,
            ElementType::Hexahedron27 => 27,
        }
    }

    /// Topological dimension.
    pub fn dim(self) -> usize {
        match self {
            ElementType::Point => 0,
            ElementType::Line | ElementType::Line3 => 1,
            ElementType::Triangle
            | ElementType::Quadrangle
            | ElementType::Triangle6
            | ElementType::Quadrangle8
            | ElementType::Quadrangle9 => 2,
            ElementType::Tetrahedron
            | ElementType::Hexahedron
            | ElementType::Tetrahedron10
            | ElementType::Hexahedron20
            | ElementType::Hexahedron27 => 3,
        }
    }
}

fn higher_order(t: i64, shape: &str) -> String {
    format!(
        "element type {t} is a higher-order {shape}: ctc reads first- and second-order meshes \
         (planar: tri6 9, quad8 16, quad9 10 with 3-node lines 8; solid: tet10 11, hex20 17, \
         hex27 12 with their 8, 9, 10, 16 facets); mesh with order 2 or less (gmsh: \
         Mesh.ElementOrder = 2, or -order 2)"
    )
}

/// One node as read.
#[derive(Debug, Clone, Copy)]
pub struct RawNode {
    /// gmsh node tag.
    pub tag: u64,
    /// x, y, z (planar meshes ignore z).
    pub xyz: [f64; 3],
    /// Line of its coordinates.
    pub line: usize,
}

/// One element as read; its node tags and physical groups are ranges of
/// [`RawMesh::element_nodes`] and [`RawMesh::element_physicals`] (issue
/// 20: one flat array instead of a 27-tag array and a vector per element,
/// 256 bytes and an allocation for each of the 80,000 triangles of the
/// tutorial mesh).
#[derive(Debug, Clone)]
pub struct RawElement {
    /// Topology.
    pub kind: ElementType,
    /// Start of its `kind.nodes()` gmsh node tags in
    /// [`RawMesh::element_nodes`].
    pub first_node: usize,
    /// Its physical group tags (of dimension `kind.dim()`) in
    /// [`RawMesh::element_physicals`].
    pub physicals: std::ops::Range<usize>,
    /// Line of the element.
    pub line: usize,
}

/// Everything the sections yield.
#[derive(Debug, Default)]
pub struct RawMesh {
    /// Nodes in file order.
    pub nodes: Vec<RawNode>,
    /// Elements in file order.
    pub elements: Vec<RawElement>,
    /// The node tags of the elements, in file order.
    pub element_nodes: Vec<u64>,
    /// The physical group tags of the elements, in file order.
    pub element_physicals: Vec<i64>,
    /// `(dim, tag)` -> name, from `$PhysicalNames`.
    pub names: BTreeMap<(usize, i64), String>,
    /// Whether a `$Nodes` section was read.
    pub has_nodes: bool,
    /// Whether an `$Elements` section was read.
    pub has_elements: bool,
    /// Whether the mesh is read as a solid (3D) one: tetrahedra and
    /// hexahedra are its cells.
    pub solid: bool,
}

impl RawMesh {
    /// The gmsh node tags of element `e`.
    pub fn nodes_of(&self, e: &RawElement) -> &[u64] {
        &self.element_nodes[e.first_node..e.first_node + e.kind.nodes()]
    }

    /// The physical group tags of element `e`.
    pub fn physicals_of(&self, e: &RawElement) -> &[i64] {
        &self.element_physicals[e.physicals.clone()]
    }
}
