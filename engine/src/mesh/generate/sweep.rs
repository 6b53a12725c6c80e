//! Solid meshes swept from a planar mesh: an **extrusion** along z and a
//! **revolution** about the z axis (the section's x is the radius, its y
//! the axial coordinate, as in an axisymmetric deck).
//!
//! Each planar cell becomes one layer of cells per division of the sweep:
//! a quad4 a hexahedron, a tri3 a prism split into three tetrahedra by the
//! rule of Dompierre et al. (1999, "How to subdivide pyramids, prisms and
//! hexahedra into tetrahedra", 8th International Meshing Roundtable): each
//! quadrilateral side is cut along the diagonal from its smallest global
//! node number, so two prisms sharing a side cut it the same way and the
//! tetrahedra conform. Cells are oriented positively (a sweep that turns
//! the section's orientation over swaps the layers).
//!
//! Sets: each edge set of the section becomes the face set (and node set)
//! of the same name, made of the swept faces of its edges; each node set
//! becomes the node set of all copies of its nodes; the two ends are the
//! face sets `zmin` / `zmax` (extrusion) or `start` / `end` (revolution by
//! less than a full turn; a full turn closes the ring and has no ends).
//!
//! A revolved section may reach the axis (x = 0): its nodes there are kept
//! once (every layer shares them). A tri3 prism with one node on the axis
//! collapses into a pyramid, with two into a tetrahedron: of its three
//! tetrahedra those holding a collapsed vertical edge have no volume and
//! are left out (the others keep the smallest-number cut, so they still
//! conform). A quad4 cell on the axis would collapse into a wedge, for
//! which there is no element: such a section is refused with its remedy.

use super::common::{divisions, node_budget, positive};
use super::Grading;
use crate::mesh::{Cell, CellKind, Facet, Mesh, MeshError};
use std::collections::BTreeSet;

/// Prism vertex permutations bringing vertex `k` (row `k`) to position 0
/// while keeping the prism's structure (bottom `0 1 2`, top `3 4 5`, `i + 3`
/// above `i`): Dompierre et al., table 2.
const PRISM_ROTATION: [[usize; 6]; 6] = [
    [0, 1, 2, 3, 4, 5],
    [1, 2, 0, 4, 5, 3],
    [2, 0, 1, 5, 3, 4],
    [3, 5, 4, 0, 2, 1],
    [4, 3, 5, 1, 0, 2],
    [5, 4, 3, 2, 1, 0],
];

/// The extrusion of `base` along +z by `length` in `layers` divisions
/// (graded by `grading`). Sets: those of `base`, swept, and `zmin`
/// (z = 0), `zmax` (z = length).
pub fn extrude(
    base: &Mesh,
    length: f64,
    layers: usize,
    grading: Grading,
) -> Result<Mesh<3>, MeshError> {
    const G: &str = "extrude";
    positive(G, "length", length)?;
    divisions(G, "layers", layers, 1)?;
    grading.check(&format!("{G}: grading"))?;
    let t = grading.points(layers);
    let z = |k: usize| {
        if k == layers {
            length
        } else {
            length * t[k]
        }
    };
    let shared = vec![false; base.nodes.len()];
    sweep(G, base, layers, false, ["zmin", "zmax"], &shared, |p, k| {
        [p[0], p[1], z(k)]
    })
}

/// The revolution of `section` (x = radius >= 0, y = axial coordinate)
/// about the z axis by `angle` degrees (in (0, 360]) in `segments`
/// divisions: the point `(r, y)` at angle `phi` is `(r cos phi, r sin phi,
/// y)`. Sets: those of `section`, swept, and for an open sector `start`
/// (phi = 0) and `end` (phi = angle). Nodes on the axis (x within 1e-9 of
/// the section's size of 0) are kept once; only tri3 cells may touch it
/// (see the module doc); a section crossing it (x < 0) is refused.
pub fn revolve(section: &Mesh, angle: f64, segments: usize) -> Result<Mesh<3>, MeshError> {
    const G: &str = "revolve";
    if !(angle > 0.0 && angle <= 360.0) {
        return Err(MeshError::new(format!(
            "{G}: the angle must be in (0, 360] degrees, got {angle}"
        )));
    }
    divisions(G, "segments", segments, 1)?;
    let closed = angle == 360.0;
    if closed && segments < 3 {
        return Err(MeshError::new(format!(
            "{G}: a full turn needs at least 3 segments, got {segments}"
        )));
    }
    let size = extent(section);
    let tol = 1e-9 * size;
    if let Some((i, p)) = section.nodes.iter().enumerate().find(|(_, p)| p[0] < -tol) {
        return Err(MeshError::new(format!(
            "{G}: the section crosses the axis (node {i} at x = {:e}; x is the radius and must \
             be >= 0)",
            p[0]
        )));
    }
    let shared: Vec<bool> = section.nodes.iter().map(|p| p[0] <= tol).collect();
    for c in 0..section.cells.len() {
        let cell = section.cells.get(c);
        if cell.kind != CellKind::Tri3 && cell.nodes.iter().any(|&a| shared[a]) {
            return Err(MeshError::new(format!(
                "{G}: the section reaches the axis with {} cell {c} (x = 0 at node {}): revolved, \
                 it would collapse into a wedge, for which there is no element; mesh the section \
                 with triangles (`element = tri3`: their prisms become tetrahedra at the axis), \
                 start it at x > 0, or mesh a solid of revolution with `cylinder`",
                cell.kind.name(),
                cell.nodes
                    .iter()
                    .find(|&&a| shared[a])
                    .copied()
                    .unwrap_or(0)
            )));
        }
    }
    let step = angle.to_radians() / segments as f64;
    sweep(
        G,
        section,
        segments,
        closed,
        ["start", "end"],
        &shared,
        |p, k| {
            if p[0] <= tol {
                return [0.0, 0.0, p[1]];
            }
            let phi = if k == segments && !closed {
                angle.to_radians()
            } else {
                step * k as f64
            };
            [p[0] * phi.cos(), p[0] * phi.sin(), p[1]]
        },
    )
}

/// The largest coordinate extent of a planar mesh.
fn extent(m: &Mesh) -> f64 {
    (0..2)
        .map(|c| {
            let lo = m.nodes.iter().map(|p| p[c]).fold(f64::INFINITY, f64::min);
            let hi = m
                .nodes
                .iter()
                .map(|p| p[c])
                .fold(f64::NEG_INFINITY, f64::max);
            hi - lo
        })
        .fold(0.0, f64::max)
}

/// Sweeps `base` through `layers` divisions, node `(p, k)` of layer `k`
/// at `place(p, k)`; `closed`: layer `layers` is layer 0 (a full turn);
/// `ends`: the names of the face sets of the first and last layers;
/// `shared[a]`: base node `a` stays where it is and is one node of every
/// layer (on the axis of a revolution).
#[allow(clippy::too_many_arguments)]
fn sweep(
    generator: &str,
    base: &Mesh,
    layers: usize,
    closed: bool,
    ends: [&str; 2],
    shared: &[bool],
    place: impl Fn(&[f64; 2], usize) -> [f64; 3],
) -> Result<Mesh<3>, MeshError> {
    let n = base.nodes.len();
    if base.cells.is_empty() {
        return Err(MeshError::new(format!(
            "{generator}: the planar mesh has no cells"
        )));
    }
    let copies = if closed { layers } else { layers + 1 };
    node_budget(generator, n.checked_mul(copies))?;
    let mut mesh = Mesh::<3>::default();
    // index[k * n + a]: the node of base node `a` in layer `k`;
    // origin[v]: the base node and the layer of node `v` (layer 0 for a
    // shared node, which is in every layer)
    let mut index = Vec::with_capacity(n * copies);
    let mut origin = Vec::with_capacity(n * copies);
    for k in 0..copies {
        for (a, p) in base.nodes.iter().enumerate() {
            if shared[a] && k > 0 {
                index.push(index[a]);
                continue;
            }
            let q = place(p, k);
            if !q.iter().all(|v| v.is_finite()) {
                return Err(MeshError::new(format!(
                    "{generator}: a node position is not finite; check the sizes"
                )));
            }
            index.push(mesh.nodes.len());
            origin.push((a, k));
            mesh.nodes.push(q);
        }
    }
    // node `a` of the base in layer `k`
    let id = |a: usize, k: usize| index[(k % copies) * n + a];
    for c in 0..base.cells.len() {
        let cell = base.cells.get(c);
        for k in 0..layers {
            match cell.kind {
                CellKind::Quad4 => {
                    let b: Vec<usize> = cell.nodes.iter().map(|&a| id(a, k)).collect();
                    let t: Vec<usize> = cell.nodes.iter().map(|&a| id(a, k + 1)).collect();
                    let mut h = [b[0], b[1], b[2], b[3], t[0], t[1], t[2], t[3]];
                    if hex_volume_sign(&mesh.nodes, &h) < 0.0 {
                        h = [t[0], t[1], t[2], t[3], b[0], b[1], b[2], b[3]];
                    }
                    mesh.cells.push(Cell::hex(h));
                }
                CellKind::Tri3 => {
                    let v = [
                        id(cell.nodes[0], k),
                        id(cell.nodes[1], k),
                        id(cell.nodes[2], k),
                        id(cell.nodes[0], k + 1),
                        id(cell.nodes[1], k + 1),
                        id(cell.nodes[2], k + 1),
                    ];
                    for mut t in prism_tets(v) {
                        // a collapsed vertical edge (both ends on the axis)
                        if (0..4).any(|i| t[i + 1..].contains(&t[i])) {
                            continue;
                        }
                        if tet_volume(&mesh.nodes, &t) < 0.0 {
                            t.swap(2, 3);
                        }
                        mesh.cells.push(Cell::tet(t));
                    }
                }
                other => {
                    return Err(MeshError::new(format!(
                        "{generator}: the planar mesh must have tri3 or quad4 cells, got {}",
                        other.name()
                    )))
                }
            }
        }
    }
    let boundary = mesh.boundary_facets(0..mesh.cells.len());
    let origin = |v: usize| origin[v];
    // swept edge sets
    for (name, edges) in &base.edge_sets {
        let keys: BTreeSet<[usize; 2]> = edges
            .iter()
            .map(|&[a, b]| if a < b { [a, b] } else { [b, a] })
            .collect();
        let faces: Vec<Facet> = boundary
            .iter()
            .filter(|f| {
                let base_nodes: BTreeSet<usize> = f.nodes().iter().map(|&v| origin(v).0).collect();
                let mut it = base_nodes.iter();
                // two base nodes: a face swept from an edge (a face within
                // a layer has three or four)
                match (it.next(), it.next(), it.next()) {
                    (Some(&a), Some(&b), None) => keys.contains(&[a, b]),
                    _ => false,
                }
            })
            .copied()
            .collect();
        // an edge set on the axis sweeps no face: its nodes stay a node set
        if !faces.is_empty() {
            add_faces(&mut mesh, name, faces);
        }
    }
    // swept node sets (those of edge sets are already there)
    for (name, nodes) in &base.node_sets {
        if mesh.node_sets.contains_key(name) {
            continue;
        }
        let mut all: Vec<usize> = (0..copies)
            .flat_map(|k| nodes.iter().map(move |&a| (a, k)))
            .map(|(a, k)| id(a, k))
            .collect();
        all.sort_unstable();
        all.dedup();
        mesh.node_sets.insert(name.clone(), all);
    }
    if !closed {
        for (name, k) in [(ends[0], 0), (ends[1], layers)] {
            let faces: Vec<Facet> = boundary
                .iter()
                .filter(|f| {
                    f.nodes()
                        .iter()
                        .all(|&v| origin(v).1 == k || shared[origin(v).0])
                })
                .copied()
                .collect();
            add_faces(&mut mesh, name, faces);
        }
    }
    Ok(mesh)
}

/// Adds the face set `name` and the node set of its nodes.
fn add_faces(mesh: &mut Mesh<3>, name: &str, faces: Vec<Facet>) {
    let mut nodes: Vec<usize> = faces.iter().flat_map(|f| f.nodes().to_vec()).collect();
    nodes.sort_unstable();
    nodes.dedup();
    mesh.node_sets.insert(name.to_string(), nodes);
    mesh.face_sets.insert(name.to_string(), faces);
}

/// The three tetrahedra of the prism `v` (bottom `v0 v1 v2`, top `v3 v4
/// v5`), cut by the smallest-global-number rule on its sides.
fn prism_tets(v: [usize; 6]) -> [[usize; 4]; 3] {
    let m = (0..6).min_by_key(|&i| v[i]).unwrap_or(0);
    let w = PRISM_ROTATION[m].map(|i| v[i]);
    if w[1].min(w[5]) < w[2].min(w[4]) {
        [
            [w[0], w[1], w[2], w[5]],
            [w[0], w[1], w[5], w[4]],
            [w[0], w[4], w[5], w[3]],
        ]
    } else {
        [
            [w[0], w[1], w[2], w[4]],
            [w[0], w[4], w[2], w[5]],
            [w[0], w[4], w[5], w[3]],
        ]
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn triple(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

/// Six times the signed volume of the tetrahedron `t`.
fn tet_volume(x: &[[f64; 3]], t: &[usize; 4]) -> f64 {
    let o = x[t[0]];
    triple(sub(x[t[1]], o), sub(x[t[2]], o), sub(x[t[3]], o))
}

/// The sign of the Jacobian of the hexahedron `h` (gmsh order) at its
/// centre.
fn hex_volume_sign(x: &[[f64; 3]], h: &[usize; 8]) -> f64 {
    let avg = |idx: [usize; 4]| {
        let mut s = [0.0; 3];
        for i in idx {
            for c in 0..3 {
                s[c] += 0.25 * x[h[i]][c];
            }
        }
        s
    };
    // centre differences of the opposite faces
    let dx = sub(avg([1, 2, 6, 5]), avg([0, 3, 7, 4]));
    let dy = sub(avg([3, 2, 6, 7]), avg([0, 1, 5, 4]));
    let dz = sub(avg([4, 5, 6, 7]), avg([0, 1, 2, 3]));
    triple(dx, dy, dz)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::{generate, MeshSpec};
    use crate::mesh::validate;
    use std::collections::BTreeMap;
    use std::f64::consts::PI;

    fn volume(m: &Mesh<3>) -> f64 {
        m.cells
            .iter()
            .map(|c| crate::mesh::quality::cell_measure(m, c))
            .sum()
    }

    fn rectangle(origin: [f64; 2], size: [f64; 2], n: [usize; 2], kind: CellKind) -> Mesh {
        generate(&MeshSpec::Rectangle {
            origin,
            size,
            divisions: n,
            grading: [Grading::Geometric { ratio: 3.0 }, Grading::Uniform],
            kind,
        })
        .unwrap()
    }

    /// Every boundary face of `m` is in exactly one of `sets`, and the
    /// others are interior: the swept cells conform (a non-conforming
    /// tetrahedral split would leave unmatched faces inside).
    fn sets_cover_the_boundary(m: &Mesh<3>, sets: &[&str]) {
        let boundary = m.boundary_facets(0..m.cells.len());
        let mut seen = BTreeMap::new();
        for s in sets {
            for f in &m.face_sets[*s] {
                let mut k = f.nodes().to_vec();
                k.sort_unstable();
                *seen.entry(k).or_insert(0) += 1;
            }
        }
        assert_eq!(seen.len(), boundary.len(), "sets {sets:?}");
        assert!(seen.values().all(|&c| c == 1));
    }

    #[test]
    fn extruded_rectangle_is_the_box_in_hex8_and_conforming_tet4() {
        for (kind, per) in [(CellKind::Quad4, 1), (CellKind::Tri3, 6)] {
            let base = rectangle([1.0, -1.0], [2.0, 1.5], [3, 2], kind);
            let m = extrude(&base, 0.5, 3, Grading::Geometric { ratio: 0.5 }).unwrap();
            assert_eq!(m.nodes.len(), 4 * 3 * 4);
            assert_eq!(m.cells.len(), 3 * 2 * 3 * per);
            validate::check(&m).unwrap();
            assert!((volume(&m) - 1.5).abs() < 1e-13, "{}", volume(&m));
            sets_cover_the_boundary(&m, &["bottom", "right", "top", "left", "zmin", "zmax"]);
            // swept edge set: 3 edges x 3 layers quads (x2 triangles)
            assert_eq!(m.face_sets["bottom"].len(), 9 * per.min(2));
            assert!(m.node_sets["bottom"].iter().all(|&v| m.nodes[v][1] == -1.0));
            assert!(m.face_sets["zmax"]
                .iter()
                .all(|f| f.nodes().iter().all(|&v| m.nodes[v][2] == 0.5)));
            // corner node sets: one copy per layer
            assert_eq!(m.node_sets["corner_bl"].len(), 4);
            // graded: the first layer is the thickest (ratio 0.5)
            let mut z: Vec<f64> = m.nodes.iter().map(|p| p[2]).collect();
            z.sort_by(f64::total_cmp);
            z.dedup();
            assert!(z[1] - z[0] > z[3] - z[2]);
        }
    }

    #[test]
    fn boundary_faces_point_out_of_the_swept_solid() {
        // the outward normal of a face on `right` (x = 3) has n_x > 0
        for kind in [CellKind::Quad4, CellKind::Tri3] {
            let base = rectangle([1.0, 0.0], [2.0, 1.0], [2, 2], kind);
            for m in [
                extrude(&base, 1.0, 2, Grading::Uniform).unwrap(),
                revolve(&base, 90.0, 4).unwrap(),
            ] {
                // extrusion: the section's top (y = 1) faces +y, zmin -z;
                // revolution: the section's top (axial y = 1) faces +z,
                // start (the plane phi = 0, y = 0) faces -y
                let checks = if m.face_sets.contains_key("zmin") {
                    [("top", [0.0, 1.0, 0.0]), ("zmin", [0.0, 0.0, -1.0])]
                } else {
                    [("top", [0.0, 0.0, 1.0]), ("start", [0.0, -1.0, 0.0])]
                };
                for (set, dir) in checks {
                    for f in &m.face_sets[set] {
                        let n = f.nodes();
                        let a = sub(m.nodes[n[1]], m.nodes[n[0]]);
                        let b = sub(m.nodes[n[2]], m.nodes[n[0]]);
                        let c = [
                            a[1] * b[2] - a[2] * b[1],
                            a[2] * b[0] - a[0] * b[2],
                            a[0] * b[1] - a[1] * b[0],
                        ];
                        let dot: f64 = (0..3).map(|i| c[i] * dir[i]).sum();
                        assert!(dot > 0.0, "{set}: {c:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn revolved_rectangle_is_a_tube_sector_and_a_full_turn_closes_the_ring() {
        // section 1 <= r <= 2, 0 <= y <= 0.5: a tube of volume
        // angle / 2 * (2^2 - 1^2) * 0.5, approached by the chords (second
        // order in the segment angle) - checked against the polygon area.
        for (kind, per) in [(CellKind::Quad4, 1), (CellKind::Tri3, 6)] {
            let base = rectangle([1.0, 0.0], [1.0, 0.5], [2, 1], kind);
            let quarter = revolve(&base, 90.0, 8).unwrap();
            validate::check(&quarter).unwrap();
            // the swept solid of straight chords: sum over segments of
            // (r2^2 - r1^2) / 2 sin(dphi) * height
            let dphi = (PI / 2.0) / 8.0;
            let exact = 8.0 * 0.5 * dphi.sin() * (4.0 - 1.0) * 0.5;
            assert!(
                (volume(&quarter) - exact).abs() < 1e-12,
                "{}",
                volume(&quarter)
            );
            assert_eq!(quarter.cells.len(), 2 * 8 * per);
            sets_cover_the_boundary(
                &quarter,
                &["bottom", "right", "top", "left", "start", "end"],
            );
            // `end` lies in the plane phi = 90 degrees (x = 0)
            assert!(quarter.node_sets["end"]
                .iter()
                .all(|&v| quarter.nodes[v][0].abs() < 1e-15));
            assert!(quarter.node_sets["start"]
                .iter()
                .all(|&v| quarter.nodes[v][1] == 0.0));
            let full = revolve(&base, 360.0, 12).unwrap();
            validate::check(&full).unwrap();
            assert_eq!(full.nodes.len(), base.nodes.len() * 12);
            assert!(!full.face_sets.contains_key("start"));
            sets_cover_the_boundary(&full, &["bottom", "right", "top", "left"]);
            let exact = 12.0 * 0.5 * (2.0 * PI / 12.0).sin() * 3.0 * 0.5;
            assert!((volume(&full) - exact).abs() < 1e-12);
        }
    }

    #[test]
    fn tri3_section_on_the_axis_revolves_into_a_conforming_solid() {
        // section 0 <= r <= 1, 0 <= y <= 0.5 (tri3): the axis nodes are
        // kept once, the prisms at the axis collapse into pyramids and
        // tetrahedra; volume of the chord solid sum sin(dphi) int r dA
        let base = rectangle([0.0, 0.0], [1.0, 0.5], [3, 2], CellKind::Tri3);
        let on_axis = base.nodes.iter().filter(|p| p[0] == 0.0).count();
        assert_eq!(on_axis, 3);
        for (angle, segments) in [(90.0, 6), (360.0, 12)] {
            let m = revolve(&base, angle, segments).unwrap();
            validate::check(&m).unwrap();
            let copies = if angle == 360.0 {
                segments
            } else {
                segments + 1
            };
            assert_eq!(
                m.nodes.len(),
                on_axis + (base.nodes.len() - on_axis) * copies
            );
            let dphi = f64::to_radians(angle) / segments as f64;
            let exact = segments as f64 * dphi.sin() * 0.5 * 0.5;
            assert!((volume(&m) - exact).abs() < 1e-12, "{}", volume(&m));
            // 2 x 2 triangles at the axis: one with an edge on it (1 tet),
            // one with a node on it (2 tets); 3 tets elsewhere
            let cells_at_axis = 2 * (1 + 2);
            let elsewhere = (base.cells.len() - 4) * 3;
            assert_eq!(m.cells.len(), segments * (cells_at_axis + elsewhere));
            // `left` (the axis) sweeps no face; its nodes are the axis nodes
            assert!(!m.face_sets.contains_key("left"));
            assert_eq!(m.node_sets["left"].len(), on_axis);
            let sets: &[&str] = if angle == 360.0 {
                &["bottom", "right", "top"]
            } else {
                &["bottom", "right", "top", "start", "end"]
            };
            sets_cover_the_boundary(&m, sets);
        }
    }

    #[test]
    fn prism_split_conforms_for_every_numbering() {
        // two prisms sharing the side (1, 2, 4, 5) numbered in every order
        // cut it along the same diagonal
        let side = |tets: &[[usize; 4]; 3], quad: [usize; 4]| {
            let mut cut = BTreeSet::new();
            for t in tets {
                let on: Vec<usize> = t.iter().copied().filter(|v| quad.contains(v)).collect();
                if on.len() == 3 {
                    let mut k = on.clone();
                    k.sort_unstable();
                    cut.insert(k);
                }
            }
            cut
        };
        for perm in 0..720usize {
            // a permutation of 10..16 from the factorial number system
            let mut pool: Vec<usize> = (10..16).collect();
            let mut code = perm;
            let mut p = Vec::new();
            for k in (1..=6).rev() {
                p.push(pool.remove(code % k));
                code /= k;
            }
            let a = prism_tets([p[0], p[1], p[2], p[3], p[4], p[5]]);
            // the side v1 v2 v5 v4 of prism a, shared with a second prism
            // that has it as its side v0 v1 v4 v3
            // (its other nodes numbered above and below the shared ones)
            let q = [p[1], p[2], p[5], p[4]];
            for (u, w) in [(99, 98), (0, 1)] {
                let b = prism_tets([p[1], p[2], u, p[4], p[5], w]);
                assert_eq!(side(&a, q), side(&b, q), "{p:?}");
            }
            assert_eq!(side(&a, q).len(), 2);
        }
    }

    #[test]
    fn bad_sweeps_are_errors() {
        let base = rectangle([0.0, 0.0], [1.0, 1.0], [2, 2], CellKind::Quad4);
        let e = revolve(&base, 90.0, 4).unwrap_err();
        assert!(e.message.contains("reaches the axis"), "{}", e.message);
        assert!(e.message.contains("element = tri3"), "{}", e.message);
        let across = rectangle([-0.5, 0.0], [1.0, 1.0], [2, 2], CellKind::Tri3);
        let e = revolve(&across, 90.0, 4).unwrap_err();
        assert!(e.message.contains("crosses the axis"), "{}", e.message);
        let off = rectangle([1.0, 0.0], [1.0, 1.0], [2, 2], CellKind::Quad4);
        assert!(revolve(&off, 0.0, 4).is_err());
        assert!(revolve(&off, 400.0, 4).is_err());
        assert!(revolve(&off, 360.0, 2).is_err());
        assert!(extrude(&off, -1.0, 2, Grading::Uniform).is_err());
        assert!(extrude(&off, 1.0, 0, Grading::Uniform).is_err());
        assert!(extrude(&off, f64::NAN, 2, Grading::Uniform).is_err());
    }
}
