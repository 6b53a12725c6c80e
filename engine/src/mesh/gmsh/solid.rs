//! Turns the raw file content into a solid [`Mesh<3>`]: tetrahedra and
//! hexahedra as cells (positive volume), dense node numbering in file
//! order, physical surfaces as face sets in outward order, physical volumes
//! (and points, lines) as node sets.

use super::raw::{ElementType, RawMesh};
use super::tags::TagIndex;
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

/// The engine's (VTK) node `k` of a 10-node tetrahedron is gmsh's node
/// `GMSH_TET10[k]` (gmsh numbers the midpoints of (1,3) and (2,3) the other
/// way round).
const GMSH_TET10: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8];

/// The engine's node `k` of a 20-node hexahedron is gmsh's node
/// `GMSH_HEX20[k]` (gmsh numbers the edges (0,1), (0,3), (0,4), (1,2),
/// (1,5), (2,3), (2,6), (3,7), (4,5), (4,7), (5,6), (6,7)).
const GMSH_HEX20: [usize; 20] = [
    0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15,
];

/// The engine's node `k` of a 27-node hexahedron is gmsh's node
/// `GMSH_HEX27[k]` (gmsh's face centres: z = -1, y = -1, x = -1, x = 1,
/// y = 1, z = 1; the engine's: x = -1, x = 1, y = -1, y = 1, z = -1, z = 1).
const GMSH_HEX27: [usize; 27] = [
    0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15, 22, 23, 21, 24, 20, 25,
    26,
];

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
    let by_tag = TagIndex::new(&raw.nodes)?;
    let mut positions: Vec<Vec<usize>> = Vec::with_capacity(raw.elements.len());
    for e in &raw.elements {
        let mut pos = Vec::with_capacity(e.kind.nodes());
        for &t in raw.nodes_of(e) {
            pos.push(by_tag.get(t).ok_or_else(|| {
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
        let (kind, order): (_, &[usize]) = match e.kind {
            ElementType::Tetrahedron => (CellKind::Tet4, &[]),
            ElementType::Hexahedron => (CellKind::Hex8, &[]),
            ElementType::Tetrahedron10 => (CellKind::Tet10, &GMSH_TET10),
            ElementType::Hexahedron20 => (CellKind::Hex20, &GMSH_HEX20),
            ElementType::Hexahedron27 => (CellKind::Hex27, &GMSH_HEX27),
            _ => continue,
        };
        let mut key = pos.clone();
        key.sort_unstable();
        if keys.insert(key) {
            let pos = if order.is_empty() {
                pos.clone()
            } else {
                order.iter().map(|&g| pos[g]).collect()
            };
            cells.push((kind, pos));
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
            CellKind::Tet4 | CellKind::Tet10 => tet_volume([x(0), x(1), x(2), x(3)]) < 0.0,
            // the corner tetrahedron at node 0 gives the orientation
            _ => tet_volume([x(0), x(1), x(3), x(4)]) < 0.0,
        };
        if inverted {
            let corners: &[usize] = match kind {
                CellKind::Tet4 | CellKind::Tet10 => &[0, 2, 1, 3],
                _ => &[0, 3, 2, 1, 4, 7, 6, 5],
            };
            n = crate::mesh::elevate::permute_corners(*kind, &n, corners);
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
        for &tag in raw.physicals_of(e) {
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
        let e = gmsh::parse_solid(&CUBE_V2.replace("2 5 2 2 1", "2 29 2 2 1")).unwrap_err();
        assert!(e.message.contains("order"), "{}", e.message);
    }

    /// One second-order cell written in gmsh's node order (corners, then
    /// gmsh's edge midpoints, face centres and body centre computed from
    /// them), with the corners optionally listed mirrored (an inverted
    /// cell), and its first face as a physical surface of the matching
    /// second-order type.
    fn second_order(gmsh_type: usize, corners: &[[f64; 3]], mirror: bool) -> String {
        let tet = corners.len() == 4;
        let order: Vec<usize> = match (tet, mirror) {
            (true, true) => vec![0, 2, 1, 3],
            (false, true) => vec![0, 3, 2, 1, 4, 7, 6, 5],
            _ => (0..corners.len()).collect(),
        };
        let c: Vec<[f64; 3]> = order.iter().map(|&k| corners[k]).collect();
        let avg = |ids: &[usize]| -> [f64; 3] {
            std::array::from_fn(|k| ids.iter().map(|&i| c[i][k]).sum::<f64>() / ids.len() as f64)
        };
        let edges: &[[usize; 2]] = if tet {
            &[[0, 1], [1, 2], [0, 2], [0, 3], [2, 3], [1, 3]]
        } else {
            &[
                [0, 1],
                [0, 3],
                [0, 4],
                [1, 2],
                [1, 5],
                [2, 3],
                [2, 6],
                [3, 7],
                [4, 5],
                [4, 7],
                [5, 6],
                [6, 7],
            ]
        };
        let mut x = c.clone();
        x.extend(edges.iter().map(|e| avg(e)));
        if gmsh_type == 12 {
            for f in [
                [0, 1, 2, 3],
                [0, 1, 5, 4],
                [0, 3, 7, 4],
                [1, 2, 6, 5],
                [2, 3, 7, 6],
                [4, 5, 6, 7],
            ] {
                x.push(avg(&f));
            }
            x.push(avg(&[0, 1, 2, 3, 4, 5, 6, 7]));
        }
        // the face of corners 0, 1, 2 (tet) or 0..3 (hex) with its gmsh facet
        let (face_type, face): (usize, Vec<usize>) = match gmsh_type {
            11 => (9, vec![0, 1, 2, 4, 5, 6]),
            17 => (16, vec![0, 1, 2, 3, 8, 11, 13, 9]),
            _ => (10, vec![0, 1, 2, 3, 8, 11, 13, 9, 20]),
        };
        let mut t = String::from("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 1 \"face\"\n$EndPhysicalNames\n");
        t += &format!("$Nodes\n{}\n", x.len());
        for (i, p) in x.iter().enumerate() {
            t += &format!("{} {} {} {}\n", i + 1, p[0], p[1], p[2]);
        }
        t += "$EndNodes\n$Elements\n2\n";
        let list = |ids: &mut dyn Iterator<Item = usize>| -> String {
            ids.map(|i| (i + 1).to_string())
                .collect::<Vec<_>>()
                .join(" ")
        };
        t += &format!("1 {gmsh_type} 2 2 1 {}\n", list(&mut (0..x.len())));
        t += &format!("2 {face_type} 2 1 1 {}\n", list(&mut face.iter().copied()));
        t + "$EndElements\n"
    }

    #[test]
    fn second_order_tet10_hex20_hex27_mapped_to_the_engine_order_and_reoriented() {
        // a sheared, stretched brick and tetrahedron (no symmetry hides a
        // wrong permutation)
        let m = |p: [f64; 3]| {
            [
                2.0 * p[0] + 0.3 * p[1],
                1.5 * p[1] + 0.2 * p[2],
                0.8 * p[2] + 0.1 * p[0],
            ]
        };
        let hex: Vec<[f64; 3]> = crate::element::reference::node_coordinates(CellKind::Hex8)
            .iter()
            .map(|p| m([p[0], p[1], p[2]]))
            .collect();
        let tet: Vec<[f64; 3]> = crate::element::reference::node_coordinates(CellKind::Tet4)
            .iter()
            .map(|p| m([p[0], p[1], p[2]]))
            .collect();
        for (t, kind, corners) in [
            (11, CellKind::Tet10, &tet),
            (17, CellKind::Hex20, &hex),
            (12, CellKind::Hex27, &hex),
        ] {
            for mirror in [false, true] {
                let mesh = gmsh::parse_solid(&second_order(t, corners, mirror)).unwrap();
                assert_eq!(mesh.cells.kind(0), kind);
                // positive Jacobian at every node and integration point
                assert!(
                    validate::check(&mesh).is_ok(),
                    "{kind:?} {mirror}: {:?}",
                    validate::check(&mesh)
                );
                // every engine node where the linear map of its corners puts it
                let n = mesh.cells.nodes(0);
                for (set, &node) in crate::mesh::elevate::corner_sets(kind).iter().zip(n) {
                    let want: [f64; 3] = std::array::from_fn(|k| {
                        set.iter().map(|&a| mesh.nodes[n[a]][k]).sum::<f64>() / set.len() as f64
                    });
                    let d: f64 = (0..3).map(|k| (mesh.nodes[node][k] - want[k]).abs()).sum();
                    assert!(
                        d < 1e-12,
                        "{kind:?} mirror {mirror}: node {node} at {:?}, want {want:?}",
                        mesh.nodes[node]
                    );
                }
                let faces = &mesh.face_sets["face"];
                assert_eq!(faces.len(), 1, "{kind:?}");
                assert_eq!(
                    faces[0].nodes().len(),
                    if t == 11 {
                        6
                    } else if t == 17 {
                        8
                    } else {
                        9
                    }
                );
            }
        }
    }
}
