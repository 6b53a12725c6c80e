//! The file's content before assembly: nodes and elements by gmsh tag,
//! physical groups and names, each with the line it came from.

use std::collections::BTreeMap;

/// Element types read (all first order); anything else is an error.
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
            11 | 12 | 17 | 29..=35 | 92 | 93 if solid => return Err(higher_order(t, "solid")),
            6 | 7 | 13 | 14 | 18 | 19 if solid => {
                return Err(format!(
                    "element type {t} (prism or pyramid) is not supported: ctc reads tetrahedra (4) and hexahedra (5)"
                ))
            }
            8 | 26..=28 => return Err(higher_order(t, "line")),
            9 | 20..=25 => return Err(higher_order(t, "triangle")),
            10 | 16 | 36 | 37 => return Err(higher_order(t, "quadrangle")),
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
        }
    }

    /// Topological dimension.
    pub fn dim(self) -> usize {
        match self {
            ElementType::Point => 0,
            ElementType::Line => 1,
            ElementType::Triangle | ElementType::Quadrangle => 2,
            ElementType::Tetrahedron | ElementType::Hexahedron => 3,
        }
    }
}

fn higher_order(t: i64, shape: &str) -> String {
    format!(
        "element type {t} is a second- or higher-order {shape}: ctc uses linear elements; \
         mesh with order 1 (gmsh: Mesh.ElementOrder = 1, or -order 1)"
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

/// One element as read.
#[derive(Debug, Clone)]
pub struct RawElement {
    /// Topology.
    pub kind: ElementType,
    /// gmsh node tags (first `kind.nodes()` used).
    pub nodes: [u64; 8],
    /// Physical group tags it belongs to (of dimension `kind.dim()`).
    pub physicals: Vec<i64>,
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
