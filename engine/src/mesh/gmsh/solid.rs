//! Turns the raw file content into a solid [`Mesh<3>`]: tetrahedra and
//! hexahedra as cells (positive volume), dense node numbering in file
//! order, physical surfaces as face sets in outward order, physical volumes
//! (and points, lines) as node sets.

use super::raw::{ElementType, RawMesh};
use crate::mesh::{Cell, CellKind, Facet, Mesh, MeshError};
use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};

/// What one physical group collects.
#[derive(Default)]
struct Group {
    /// Nodes (new numbers).
    nodes: BTreeSet<usize>,
    /// Boundary faces in outward order, file order, distinct.
    faces: Vec<Facet>,
    /// Sorted keys of the faces already taken.
    seen: HashSet<Vec<usize>>,
    /// Line of the first surface element that is not a boundary face.
    interior: Option<usize>,
}

/// Signed volume of a tetrahedron.
fn tet_volume(p: [[f64; 3]; 4]) -> f64 {
    let d = |a: usize| [p[a][0] - p[0][0], p[a][1] - p[0][1], p[a][2] - p[0][2]];
    let (a, b, c) = (d(1), d(2), d(3));
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

/// Assembles the solid mesh. `eof_line` is the last line of the file.
pub fn assemble(raw: RawMesh, eof_line: usize) -> Result<Mesh<3>, MeshError> {
    if !raw.has_nodes {
        return Err(MeshError::at_line(
            eof_line,
            "the file has no $Nodes section",
        ));
    }
    if !raw.has_elements {
        return Err(MeshError::at_line(
            eof_line,
            "the file has no $Elements section",
        ));
    }
    let mut by_tag: HashMap<u64, usize> = HashMap::with_capacity(raw.nodes.len());
    for (i, n) in raw.nodes.iter().enumerate() {
        if let Some(&j) = by_tag.get(&n.tag) {
            return Err(MeshError::at_line(
                n.line,
                format!(
                    "node tag {} is defined twice (first at line {})",
                    n.tag, raw.nodes[j].line
                ),
            ));
        }
        by_tag.insert(n.tag, i);
    }
    let mut positions: Vec<Vec<usize>> = Vec::with_capacity(raw.elements.len());
    for e in &raw.elements {
        let mut pos = Vec::with_capacity(8);
        for &t in &e.nodes[..e.kind.nodes()] {
            pos.push(*by_tag.get(&t).ok_or_else(|| {
                MeshError::at_line(
                    e.line,
                    format!("the element refers to node tag {t}, which is not in $Nodes"),
                )
            })?);
        }
        positions.push(pos);
    }
    // cells, deduplicated (MSH 2 repeats an element once per physical group)
    let mut cells: Vec<(CellKind, Vec<usize>)> = Vec::new();
    let mut keys: HashSet<Vec<usize>> = HashSet::new();
    for (e, pos) in raw.elements.iter().zip(&positions) {
        let kind = match e.kind {
            ElementType::Tetrahedron => CellKind::Tet4,
            ElementType::Hexahedron => CellKind::Hex8,
            _ => continue,
        };
        let mut key = pos.clone();
        key.sort_unstable();
        if keys.insert(key) {
            cells.push((kind, pos.clone()));
        }
    }
    if cells.is_empty() {
        return Err(MeshError::at_line(
            eof_line,
            "the file has no tetrahedra or hexahedra (type 4 or 5). If physical groups are \
             defined, gmsh saves only their elements: add a Physical Volume, or set \
             Mesh.SaveAll = 1",
        ));
    }
    let mut new_of: Vec<Option<usize>> = vec![None; raw.nodes.len()];
    for (_, c) in &cells {
        for &p in c {
            new_of[p] = Some(0);
        }
    }
    let mut mesh = Mesh::<3>::default();
    for (i, n) in raw.nodes.iter().enumerate() {
        if new_of[i].is_some() {
            new_of[i] = Some(mesh.nodes.len());
            mesh.nodes.push(n.xyz);
        }
    }
    for (kind, c) in &cells {
        let mut n: Vec<usize> = c.iter().filter_map(|&p| new_of[p]).collect();
        let x = |k: usize| mesh.nodes[n[k]];
        let inverted = match kind {
            CellKind::Tet4 => tet_volume([x(0), x(1), x(2), x(3)]) < 0.0,
            // the corner tetrahedron at node 0 gives the orientation
            _ => tet_volume([x(0), x(1), x(3), x(4)]) < 0.0,
        };
        if inverted {
            match kind {
                CellKind::Tet4 => n.swap(1, 2),
                _ => n = [0, 3, 2, 1, 4, 7, 6, 5].iter().map(|&k| n[k]).collect(),
            }
        }
        mesh.cells.push(Cell {
            kind: *kind,
            nodes: n,
        });
    }
    // boundary faces: sorted key -> outward facet
    let boundary: HashMap<Vec<usize>, Facet> = mesh
        .boundary_facets(0..mesh.cells.len())
        .into_iter()
        .map(|f| {
            let mut k = f.nodes().to_vec();
            k.sort_unstable();
            (k, f)
        })
        .collect();
    let mut groups: BTreeMap<String, Group> = BTreeMap::new();
    for (e, pos) in raw.elements.iter().zip(&positions) {
        let dim = e.kind.dim();
        for &tag in &e.physicals {
            let name = raw
                .names
                .get(&(dim, tag))
                .cloned()
                .unwrap_or_else(|| format!("physical_{tag}"));
            let g = groups.entry(name).or_default();
            let nodes: Vec<usize> = pos.iter().filter_map(|&p| new_of[p]).collect();
            g.nodes.extend(nodes.iter().copied());
            if dim == 2 && nodes.len() == pos.len() {
                let mut key = nodes.clone();
                key.sort_unstable();
                match boundary.get(&key) {
                    Some(f) => {
                        if g.seen.insert(key) {
                            g.faces.push(*f);
                        }
                    }
                    None => {
                        g.interior.get_or_insert(e.line);
                    }
                }
            }
        }
    }
    for (name, g) in groups {
        if let (Some(line), false) = (g.interior, g.faces.is_empty()) {
            return Err(MeshError::at_line(
                line,
                format!(
                    "physical surface `{name}` mixes boundary faces and faces inside the mesh: \
                     split it into two groups"
                ),
            ));
        }
        if !g.faces.is_empty() {
            mesh.face_sets.insert(name.clone(), g.faces);
        }
        mesh.node_sets.insert(name, g.nodes.into_iter().collect());
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use crate::mesh::{gmsh, validate, CellKind};

    /// A unit cube of one hexahedron (both faces given clockwise seen from +z: the cell is
    /// inverted in the file) and its bottom face as a physical surface.
    const CUBE_V2: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n\
$PhysicalNames\n2\n2 1 \"bottom\"\n3 2 \"solid\"\n$EndPhysicalNames\n\
$Nodes\n8\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0 0 1\n6 1 0 1\n7 1 1 1\n8 0 1 1\n$EndNodes\n\
$Elements\n2\n1 3 2 1 1 1 2 3 4\n2 5 2 2 1 1 4 3 2 5 8 7 6\n$EndElements\n";

    #[test]
    fn hexahedron_reoriented_with_an_outward_face_set() {
        let m = gmsh::parse_solid(CUBE_V2).unwrap();
        assert_eq!(m.nodes.len(), 8);
        assert_eq!(m.cells.kind(0), CellKind::Hex8);
        validate::check(&m).unwrap();
        let bottom = &m.face_sets["bottom"];
        assert_eq!(bottom.len(), 1);
        // outward: the normal of the bottom face points to -z
        let f = bottom[0].nodes();
        let p = |k: usize| m.nodes[f[k]];
        let (a, b) = (
            [p(1)[0] - p(0)[0], p(1)[1] - p(0)[1]],
            [p(2)[0] - p(0)[0], p(2)[1] - p(0)[1]],
        );
        assert!(a[0] * b[1] - a[1] * b[0] < 0.0);
        assert_eq!(m.node_sets["bottom"], vec![0, 1, 2, 3]);
        assert_eq!(m.node_sets["solid"].len(), 8);
        // the planar reader refuses the same file
        let e = gmsh::parse(CUBE_V2).unwrap_err();
        assert!(e.message.contains("3D element"), "{}", e.message);
    }

    #[test]
    fn tetrahedra_v41_inverted_ones_fixed_and_no_cells_is_an_error() {
        let text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n\
$Nodes\n1 5 1 5\n3 1 0 5\n1\n2\n3\n4\n5\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n$EndNodes\n\
$Elements\n1 2 1 2\n3 1 4 2\n1 1 2 3 4\n2 2 4 3 5\n$EndElements\n";
        let m = gmsh::parse_solid(text).unwrap();
        assert_eq!(m.cells.len(), 2);
        validate::check(&m).unwrap();
        let e = gmsh::parse_solid(
            "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n\
             $EndNodes\n$Elements\n1\n1 2 2 0 1 1 2 3\n$EndElements\n",
        )
        .unwrap_err();
        assert!(e.message.contains("no tetrahedra"), "{}", e.message);
        let e = gmsh::parse_solid(&CUBE_V2.replace("2 5 2 2 1", "2 11 2 2 1")).unwrap_err();
        assert!(e.message.contains("order"), "{}", e.message);
    }
}
