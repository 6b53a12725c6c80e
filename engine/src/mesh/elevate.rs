//! Order elevation: a linear mesh (tri3, quad4, tet4, hex8) becomes a
//! quadratic one of the same shape, with the new nodes (edge midpoints,
//! face and body centres) where the linear map puts them (straight edges),
//! shared between the cells that share the entity, the face sets carried
//! over to the quadratic faces, and every node set closed over its
//! entities (a new node joins a set holding all the corners it depends on:
//! the midside nodes of a boundary edge join the edge's node set). Planar
//! edge sets keep their corner pairs (`Mesh::edge_midsides` finds the
//! midside node). The generators use it for
//! `order = 2`; tests use it to build distorted quadratic patches.

use super::{Facet, Mesh, MeshError};
use crate::element::reference::{linear_shape, node_coordinates};
use crate::mesh::CellKind;
use std::collections::{BTreeMap, HashMap};

/// `mesh` with every cell of kind `target.linear()` turned into a cell of
/// kind `target` (the other cells, and quadratic ones, are an error).
pub fn elevate<const D: usize>(mesh: &Mesh<D>, target: CellKind) -> Result<Mesh<D>, MeshError> {
    elevate_each(mesh, &[target])
}

/// `mesh` with every cell turned into the cell of `targets` of its linear
/// kind (a mixed tri3 + quad4 mesh becomes tri6 + quad8 with
/// `[Tri6, Quad8]`); a cell whose kind no target lifts is an error.
pub fn elevate_each<const D: usize>(
    mesh: &Mesh<D>,
    targets: &[CellKind],
) -> Result<Mesh<D>, MeshError> {
    if let Some(t) = targets
        .iter()
        .find(|t| t.order() != 2 || t.dimension() != D)
    {
        return Err(MeshError::new(format!(
            "{} is not a quadratic {D}D cell kind",
            t.name()
        )));
    }
    // for each target and new node: the corners it depends on and their
    // weights
    let weights: Vec<Vec<Vec<(usize, f64)>>> = targets
        .iter()
        .map(|&target| {
            let linear = target.linear();
            node_coordinates(target)[linear.node_count()..]
                .iter()
                .map(|xi| {
                    linear_shape(linear, xi)
                        .unwrap_or_default()
                        .into_iter()
                        .enumerate()
                        .filter(|(_, w)| w.abs() > 1e-12)
                        .collect()
                })
                .collect()
        })
        .collect();
    let mut out = Mesh {
        nodes: mesh.nodes.clone(),
        node_sets: mesh.node_sets.clone(),
        edge_sets: mesh.edge_sets.clone(),
        ..Default::default()
    };
    let mut shared: HashMap<Vec<usize>, usize> = HashMap::new();
    // the sorted corners each new node depends on, by new node
    let mut parents: Vec<Vec<usize>> = Vec::new();
    for (c, cell) in mesh.cells.iter().enumerate() {
        let Some(t) = targets.iter().position(|t| t.linear() == cell.kind) else {
            let names: Vec<&str> = targets.iter().map(|t| t.linear().name()).collect();
            return Err(MeshError::new(format!(
                "cell {c} is a {}: only {} cells are lifted",
                cell.kind.name(),
                names.join(" / ")
            )));
        };
        let (target, weights) = (targets[t], &weights[t]);
        let mut nodes = cell.nodes.to_vec();
        for w in weights {
            let mut key: Vec<usize> = w.iter().map(|&(a, _)| cell.nodes[a]).collect();
            key.sort_unstable();
            let n = *shared.entry(key.clone()).or_insert_with(|| {
                let mut x = [0.0; D];
                for &(a, wa) in w {
                    for (xk, pk) in x.iter_mut().zip(&mesh.nodes[cell.nodes[a]]) {
                        *xk += wa * pk;
                    }
                }
                out.nodes.push(x);
                out.nodes.len() - 1
            });
            if n >= mesh.nodes.len() + parents.len() {
                parents.push(key);
            }
            nodes.push(n);
        }
        out.cells.push_nodes(target, &nodes);
    }
    for set in out.node_sets.values_mut() {
        let members: std::collections::HashSet<usize> = set.iter().copied().collect();
        for (i, p) in parents.iter().enumerate() {
            if p.iter().all(|c| members.contains(c)) {
                set.push(mesh.nodes.len() + i);
            }
        }
    }
    // face sets: each linear face becomes the quadratic face with its corners
    let mut faces: BTreeMap<Vec<usize>, Facet> = BTreeMap::new();
    for cell in out.cells.iter() {
        for face in cell.kind.faces() {
            let nodes: Vec<usize> = face.iter().map(|&a| cell.nodes[a]).collect();
            let corners = match face.len() {
                3 => 2,
                6 => 3,
                _ => 4,
            };
            let mut key = nodes[..corners].to_vec();
            key.sort_unstable();
            faces.entry(key).or_insert_with(|| Facet::new(&nodes));
        }
    }
    for (name, set) in &mesh.face_sets {
        let mut mapped = Vec::with_capacity(set.len());
        for f in set {
            let mut key = f.nodes().to_vec();
            key.sort_unstable();
            let q = faces.get(&key).ok_or_else(|| {
                MeshError::new(format!(
                    "face set `{name}`: face {:?} is no cell face",
                    f.nodes()
                ))
            })?;
            mapped.push(*q);
        }
        out.face_sets.insert(name.clone(), mapped);
    }
    Ok(out)
}

/// For every node of a cell of kind `kind`, the sorted local corners of
/// the smallest entity it belongs to (a corner: itself; an edge midpoint:
/// the edge's two corners; a face centre: the face's corners; the body
/// centre: all corners).
pub fn corner_sets(kind: CellKind) -> Vec<Vec<usize>> {
    let linear = kind.linear();
    node_coordinates(kind)
        .iter()
        .map(|xi| {
            linear_shape(linear, xi)
                .unwrap_or_default()
                .into_iter()
                .enumerate()
                .filter(|(_, w)| w.abs() > 1e-12)
                .map(|(a, _)| a)
                .collect()
        })
        .collect()
}

/// The node list of a cell of kind `kind` whose corners are renumbered by
/// `corners` (new corner `i` is old corner `corners[i]`, e.g. a reflection
/// that fixes an inverted cell), the other nodes following their entity.
pub fn permute_corners(kind: CellKind, nodes: &[usize], corners: &[usize]) -> Vec<usize> {
    let sets = corner_sets(kind);
    sets.iter()
        .map(|set| {
            let mut image: Vec<usize> = set.iter().map(|&i| corners[i]).collect();
            image.sort_unstable();
            let old = sets.iter().position(|s| *s == image).unwrap_or(0);
            nodes[old]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Cell;

    #[test]
    fn two_quads_share_their_midside_node_and_keep_positive_jacobians() {
        let m = Mesh::<2>::new(
            vec![
                [0.0, 0.0],
                [1.0, 0.0],
                [2.0, 0.0],
                [0.0, 1.0],
                [1.0, 1.2],
                [2.0, 1.0],
            ],
            vec![Cell::quad(0, 1, 4, 3), Cell::quad(1, 2, 5, 4)],
        );
        for (target, extra) in [
            (CellKind::Quad8, 7),
            (CellKind::Quad9, 9),
            (CellKind::Quad8R, 7),
        ] {
            let q = elevate(&m, target).unwrap();
            assert_eq!(q.nodes.len(), 6 + extra, "{target:?}");
            // the shared edge 1-4 has one midpoint, at its middle
            let (a, b) = (q.cells.nodes(0)[5], q.cells.nodes(1)[7]);
            assert_eq!(a, b);
            assert_eq!(q.nodes[a], [1.0, 0.6]);
            assert!(crate::mesh::validate::check(&q).is_ok(), "{target:?}");
            assert_eq!(q.boundary_facets(0..2).len(), 6);
            assert!(q.boundary_facets(0..2).iter().all(|f| f.nodes().len() == 3));
        }
        assert!(elevate(&m, CellKind::Tet10).is_err());
    }

    #[test]
    fn node_sets_gain_the_midside_nodes_of_their_edges_and_planar_edges_find_theirs() {
        let mut m = crate::mesh::generate::generate(&crate::mesh::generate::MeshSpec::Rectangle {
            origin: [0.0, 0.0],
            size: [2.0, 1.0],
            divisions: [2, 1],
            grading: [crate::mesh::generate::Grading::Uniform; 2],
            kind: CellKind::Quad4,
        })
        .unwrap();
        m.node_sets.insert("bottom".into(), vec![0, 1, 2]);
        let q = elevate(&m, CellKind::Quad8).unwrap();
        // the bottom set: its 3 corners and the 2 midpoints between them
        let bottom = &q.node_sets["bottom"];
        assert_eq!(bottom.len(), 5);
        assert!(bottom.iter().all(|&n| q.nodes[n][1] == 0.0));
        let midsides = q.edge_midsides();
        let facets: Vec<Facet> = q.edge_sets["bottom"]
            .iter()
            .map(|&e| Mesh::edge_facet(&midsides, e))
            .collect();
        assert!(facets.iter().all(|f| f.nodes().len() == 3));
        assert_eq!(q.facet_set("bottom").unwrap(), facets);
        assert_eq!(q.boundary_edges(0..2).len(), 6);
        assert!(m.edge_midsides().is_empty());
    }

    #[test]
    fn reflecting_an_inverted_quadratic_cell_keeps_midpoints_on_their_edges() {
        // tet10: swapping corners 1 and 2 swaps the midpoints of (0,1) and
        // (0,2), of (1,3) and (2,3), and keeps that of (1,2)
        let n: Vec<usize> = (10..20).collect();
        assert_eq!(
            permute_corners(CellKind::Tet10, &n, &[0, 2, 1, 3]),
            vec![10, 12, 11, 13, 16, 15, 14, 17, 19, 18]
        );
        let n: Vec<usize> = (0..27).collect();
        let p = permute_corners(CellKind::Hex27, &n, &[0, 3, 2, 1, 4, 7, 6, 5]);
        // (0,1) <-> (0,3), x = -1 face <-> y = -1 face, the centre stays
        assert_eq!((p[8], p[11], p[20], p[22], p[26]), (11, 8, 22, 20, 26));
    }
}
