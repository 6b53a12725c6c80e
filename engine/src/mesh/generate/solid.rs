//! Solid (3D) structured generators: a graded brick, a sector of a tube,
//! a solid cylinder (O-grid) and an octant of a spherical shell, in hex8 (or tet4: each hexahedron
//! split into six tetrahedra around its main diagonal, the Kuhn split,
//! conforming between neighbours).
//!
//! Sets: the boundary faces of the mesh are classified by the surface they
//! lie on (a face belongs to a set when all its nodes do); each face set
//! comes with the node set of the same name.

use super::common::{divisions, node_budget, positive};
use super::Grading;
use crate::mesh::{Cell, CellKind, Facet, Mesh, MeshError};
use std::collections::BTreeMap;

/// The six Kuhn tetrahedra of a hexahedron (gmsh order `0..8`), each a
/// path 0 -> 6 along the axes in one order, positively oriented.
const KUHN: [[usize; 4]; 6] = [
    [0, 1, 2, 6],
    [0, 2, 3, 6],
    [0, 3, 7, 6],
    [0, 7, 4, 6],
    [0, 4, 5, 6],
    [0, 5, 1, 6],
];

/// A structured block of `n[0] x n[1] x n[2]` hexahedra whose node `(i, j,
/// k)` is at `place(i, j, k)`; nodes at the same position (a collapsed or
/// closed block) are merged. Returns the mesh without sets.
fn block(
    generator: &str,
    n: [usize; 3],
    kind: CellKind,
    place: impl Fn(usize, usize, usize) -> [f64; 3],
) -> Result<Mesh<3>, MeshError> {
    let count = (n[0] + 1)
        .checked_mul(n[1] + 1)
        .and_then(|v| v.checked_mul(n[2] + 1));
    node_budget(generator, count)?;
    if !matches!(kind, CellKind::Hex8 | CellKind::Tet4) {
        return Err(MeshError::new(format!(
            "{generator}: cells must be hex8 or tet4, got {}",
            kind.name()
        )));
    }
    let mut mesh = Mesh::<3>::default();
    let mut index = vec![0usize; count.unwrap_or(0)];
    let mut seen: BTreeMap<[u64; 3], usize> = BTreeMap::new();
    let id = |i: usize, j: usize, k: usize| (k * (n[1] + 1) + j) * (n[0] + 1) + i;
    for k in 0..=n[2] {
        for j in 0..=n[1] {
            for i in 0..=n[0] {
                let p = place(i, j, k);
                if !p.iter().all(|v| v.is_finite()) {
                    return Err(MeshError::new(format!(
                        "{generator}: a node position is not finite; check the sizes"
                    )));
                }
                // -0.0 and 0.0 are the same point
                let key = p.map(|v| (v + 0.0).to_bits());
                let next = mesh.nodes.len();
                let node = *seen.entry(key).or_insert(next);
                if node == next {
                    mesh.nodes.push(p);
                }
                index[id(i, j, k)] = node;
            }
        }
    }
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                let h = [
                    index[id(i, j, k)],
                    index[id(i + 1, j, k)],
                    index[id(i + 1, j + 1, k)],
                    index[id(i, j + 1, k)],
                    index[id(i, j, k + 1)],
                    index[id(i + 1, j, k + 1)],
                    index[id(i + 1, j + 1, k + 1)],
                    index[id(i, j + 1, k + 1)],
                ];
                match kind {
                    CellKind::Tet4 => {
                        for t in KUHN {
                            mesh.cells.push(Cell::tet(t.map(|a| h[a])));
                        }
                    }
                    _ => mesh.cells.push(Cell::hex(h)),
                }
            }
        }
    }
    Ok(mesh)
}

/// Adds the face set `name` (and its node set): the boundary faces all of
/// whose nodes satisfy `on`.
fn add_face_set(
    mesh: &mut Mesh<3>,
    boundary: &[Facet],
    name: &str,
    on: impl Fn(&[f64; 3]) -> bool,
) {
    let faces: Vec<Facet> = boundary
        .iter()
        .filter(|f| f.nodes().iter().all(|&n| on(&mesh.nodes[n])))
        .copied()
        .collect();
    let mut nodes: Vec<usize> = faces.iter().flat_map(|f| f.nodes().to_vec()).collect();
    nodes.sort_unstable();
    nodes.dedup();
    mesh.node_sets.insert(name.to_string(), nodes);
    mesh.face_sets.insert(name.to_string(), faces);
}

/// Tolerance for classifying boundary nodes on a surface of a body of size
/// `size`.
fn tol(size: f64) -> f64 {
    1e-9 * size
}

/// The brick `[x0, x0 + a] x [y0, y0 + b] x [z0, z0 + c]` with `divisions`
/// along x, y, z and a grading per axis. Sets (faces and nodes): `xmin`,
/// `xmax`, `ymin`, `ymax`, `zmin`, `zmax`; node set `origin` (the corner at
/// `origin`).
pub fn brick(
    origin: [f64; 3],
    size: [f64; 3],
    n: [usize; 3],
    grading: [Grading; 3],
    kind: CellKind,
) -> Result<Mesh<3>, MeshError> {
    const G: &str = "box";
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        positive(G, &format!("size along {axis}"), size[k])?;
        divisions(G, axis, n[k], 1)?;
        grading[k].check(&format!("{G}: grading along {axis}"))?;
        if !origin[k].is_finite() {
            return Err(MeshError::new(format!("{G}: the origin must be finite")));
        }
    }
    let t: Vec<Vec<f64>> = (0..3).map(|k| grading[k].points(n[k])).collect();
    let coord = |k: usize, i: usize| {
        if i == n[k] {
            origin[k] + size[k]
        } else {
            origin[k] + size[k] * t[k][i]
        }
    };
    let mut mesh = block(G, n, kind, |i, j, k| {
        [coord(0, i), coord(1, j), coord(2, k)]
    })?;
    let lo = origin;
    let hi = [0, 1, 2].map(|k| origin[k] + size[k]);
    brick_sets(&mut mesh, lo, hi, size);
    Ok(mesh)
}

/// The sets of a brick spanning `lo` .. `hi` (edge lengths `extent`):
/// faces and nodes `xmin` .. `zmax` (boundary facets within round-off of
/// each bounding plane), node set `origin` (node 0).
fn brick_sets(mesh: &mut Mesh<3>, lo: [f64; 3], hi: [f64; 3], extent: [f64; 3]) {
    let boundary = mesh.boundary_facets(0..mesh.cells.len());
    let e = tol(extent.iter().copied().fold(0.0, f64::max));
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        add_face_set(mesh, &boundary, &format!("{axis}min"), |p| {
            (p[k] - lo[k]).abs() <= e
        });
        add_face_set(mesh, &boundary, &format!("{axis}max"), |p| {
            (p[k] - hi[k]).abs() <= e
        });
    }
    mesh.node_sets.insert("origin".into(), vec![0]);
}

/// The brick spanned by three lines of node coordinates (strictly
/// increasing, finite, at least two points each): node `(i, j, k)` at
/// `(x[i], y[j], z[k])` — any grading, e.g. a uniform fine core next to a
/// geometric outer region (the resolved 3D Hertz block of
/// `hertz_sphere_3d_quadratic`). Sets as for [`brick`]: faces and nodes
/// `xmin` .. `zmax`, node set `origin` (the node `(x[0], y[0], z[0])`).
pub fn brick_on_lines(lines: [&[f64]; 3], kind: CellKind) -> Result<Mesh<3>, MeshError> {
    const G: &str = "box";
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        let l = lines[k];
        if l.len() < 2 {
            return Err(MeshError::new(format!(
                "{G}: the {axis} line needs at least 2 points, got {}",
                l.len()
            )));
        }
        if let Some(i) = (0..l.len()).find(|&i| !l[i].is_finite()) {
            return Err(MeshError::new(format!(
                "{G}: point {i} of the {axis} line is not finite"
            )));
        }
        if let Some(i) = (1..l.len()).find(|&i| l[i] <= l[i - 1]) {
            return Err(MeshError::new(format!(
                "{G}: the {axis} line must increase strictly: point {i} ({}) after {}",
                l[i],
                l[i - 1]
            )));
        }
    }
    let n = lines.map(|l| l.len() - 1);
    let mut mesh = block(G, n, kind, |i, j, k| {
        [lines[0][i], lines[1][j], lines[2][k]]
    })?;
    brick_sets(
        &mut mesh,
        [0, 1, 2].map(|k| lines[k][0]),
        [0, 1, 2].map(|k| lines[k][n[k]]),
        lines.map(|l| l[l.len() - 1] - l[0]),
    );
    Ok(mesh)
}

/// A sector of the tube `inner <= r <= outer` about the z axis, from angle
/// 0 to `angle` degrees (in (0, 360]; 360 closes the ring), `0 <= z <=
/// height`; `n` = (radial, circumferential, axial) divisions. Sets: `inner`,
/// `outer`, `zmin`, `zmax`, and for an open sector `start` (the plane
/// through the x axis) and `end`.
pub fn tube(
    inner: f64,
    outer: f64,
    angle: f64,
    height: f64,
    n: [usize; 3],
    radial_grading: Grading,
    kind: CellKind,
) -> Result<Mesh<3>, MeshError> {
    const G: &str = "tube";
    positive(G, "inner radius", inner)?;
    positive(G, "height", height)?;
    if !(outer.is_finite() && outer > inner) {
        return Err(MeshError::new(format!(
            "{G}: outer radius {outer} must be larger than the inner radius {inner}"
        )));
    }
    if !(angle > 0.0 && angle <= 360.0) {
        return Err(MeshError::new(format!(
            "{G}: angle {angle} must be in (0, 360] degrees"
        )));
    }
    divisions(G, "radial", n[0], 1)?;
    divisions(
        G,
        "circumferential",
        n[1],
        if angle == 360.0 { 3 } else { 1 },
    )?;
    divisions(G, "axial", n[2], 1)?;
    radial_grading.check(&format!("{G}: radial grading"))?;
    let t = radial_grading.points(n[0]);
    let closed = angle == 360.0;
    let mut mesh = block(G, n, kind, |i, j, k| {
        let r = if i == n[0] {
            outer
        } else {
            inner + (outer - inner) * t[i]
        };
        let j = if closed && j == n[1] { 0 } else { j };
        let (c, s) = super::common::cos_sin_deg(angle * j as f64 / n[1] as f64);
        let z = if k == n[2] {
            height
        } else {
            height * k as f64 / n[2] as f64
        };
        [r * c, r * s, z]
    })?;
    let boundary = mesh.boundary_facets(0..mesh.cells.len());
    let e = tol(outer.max(height));
    let radius = |p: &[f64; 3]| p[0].hypot(p[1]);
    add_face_set(&mut mesh, &boundary, "inner", |p| {
        (radius(p) - inner).abs() <= e
    });
    add_face_set(&mut mesh, &boundary, "outer", |p| {
        (radius(p) - outer).abs() <= e
    });
    add_face_set(&mut mesh, &boundary, "zmin", |p| p[2].abs() <= e);
    add_face_set(&mut mesh, &boundary, "zmax", |p| (p[2] - height).abs() <= e);
    if !closed {
        let (c, s) = super::common::cos_sin_deg(angle);
        add_face_set(&mut mesh, &boundary, "start", |p| {
            p[1].abs() <= e && p[0] >= -e
        });
        // the end is the half-plane on the side of the angle's direction:
        // at 180 degrees the full plane y = 0 also holds the start
        add_face_set(&mut mesh, &boundary, "end", |p| {
            (p[0] * s - p[1] * c).abs() <= e && p[0] * c + p[1] * s >= -e
        });
    }
    Ok(mesh)
}

/// A seeded geometric imperfection of a tube about the z axis (the shape
/// a buckling analysis starts from): every node moves radially, the whole
/// wall alike, by `amplitude cos(waves theta) f(z)`, with `f(z) =
/// sin(half_waves pi z / height)` (the ends stay circular), or `f = 1`
/// when `half_waves` is 0; `waves = 0` is an axisymmetric bulge. A node
/// on a plane through the axis stays on it (symmetry planes of a sector
/// keep their normal); the face and node sets are unchanged. The
/// amplitude must be smaller than the tube's inner radius.
pub fn tube_imperfection(
    mesh: &mut Mesh<3>,
    amplitude: f64,
    waves: usize,
    half_waves: usize,
    height: f64,
    inner: f64,
) -> Result<(), MeshError> {
    const G: &str = "tube";
    if !(amplitude.is_finite() && amplitude.abs() < inner) {
        return Err(MeshError::new(format!(
            "{G}: imperfection amplitude {amplitude} must be smaller than the inner radius {inner}"
        )));
    }
    positive(G, "height", height)?;
    if amplitude == 0.0 {
        return Ok(());
    }
    for p in &mut mesh.nodes {
        let r = p[0].hypot(p[1]);
        if r == 0.0 {
            continue;
        }
        let theta = p[1].atan2(p[0]);
        let along = if half_waves == 0 {
            1.0
        } else {
            (half_waves as f64 * std::f64::consts::PI * p[2] / height).sin()
        };
        let scale = 1.0 + amplitude * (waves as f64 * theta).cos() * along / r;
        p[0] *= scale;
        p[1] *= scale;
    }
    Ok(())
}

/// The octant `x, y, z >= 0` of the spherical shell `inner <= r <= outer`,
/// hex-structured as a cubed sphere: the three faces `x = 1`, `y = 1`,
/// `z = 1` of the unit cube, each with `tangential x tangential` divisions,
/// projected radially (no degenerate cell at the poles), and `radial`
/// layers. Sets: `inner`, `outer`, and the symmetry planes `xmin` (x = 0),
/// `ymin`, `zmin`.
pub fn sphere_octant(
    inner: f64,
    outer: f64,
    radial: usize,
    tangential: usize,
    radial_grading: Grading,
    kind: CellKind,
) -> Result<Mesh<3>, MeshError> {
    const G: &str = "sphere_octant";
    positive(G, "inner radius", inner)?;
    if !(outer.is_finite() && outer > inner) {
        return Err(MeshError::new(format!(
            "{G}: outer radius {outer} must be larger than the inner radius {inner}"
        )));
    }
    divisions(G, "radial", radial, 1)?;
    divisions(G, "tangential", tangential, 1)?;
    radial_grading.check(&format!("{G}: radial grading"))?;
    let t = radial_grading.points(radial);
    let m = tangential;
    // patch p: the cube face where axis p is 1; (u, v) along the next two
    // axes, ordered so that (u, v, r) is right-handed for every patch
    let mut mesh = Mesh::<3>::default();
    let mut seen: BTreeMap<[u64; 3], usize> = BTreeMap::new();
    for p in 0..3 {
        let (a, b) = ((p + 1) % 3, (p + 2) % 3);
        let patch = block(G, [m, m, radial], kind, |i, j, k| {
            // equiangular parameters keep the cells even
            let angle = |i: usize| (std::f64::consts::FRAC_PI_4 * i as f64 / m as f64).tan();
            let mut q = [0.0; 3];
            q[p] = 1.0;
            q[a] = if i == m { 1.0 } else { angle(i) };
            q[b] = if j == m { 1.0 } else { angle(j) };
            let len = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
            let r = if k == radial {
                outer
            } else {
                inner + (outer - inner) * t[k]
            };
            // exact zeros stay zeros: the symmetry planes are exact
            q.map(|c| r * c / len)
        })?;
        // merge the patch into the octant (shared seams)
        let mut map = Vec::with_capacity(patch.nodes.len());
        for x in &patch.nodes {
            let key = x.map(|v| (v + 0.0).to_bits());
            let next = mesh.nodes.len();
            let node = *seen.entry(key).or_insert(next);
            if node == next {
                mesh.nodes.push(*x);
            }
            map.push(node);
        }
        for c in patch.cells.iter() {
            let nodes: Vec<usize> = c.nodes.iter().map(|&n| map[n]).collect();
            mesh.cells.push_nodes(c.kind, &nodes);
        }
    }
    // seams computed by different formulas: merge nodes that coincide to
    // round-off (the seam x = y of patch z meets patch x's edge)
    merge_close_nodes(&mut mesh, tol(outer));
    let boundary = mesh.boundary_facets(0..mesh.cells.len());
    let e = tol(outer);
    let radius = |p: &[f64; 3]| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    add_face_set(&mut mesh, &boundary, "inner", |p| {
        (radius(p) - inner).abs() <= e * 10.0
    });
    add_face_set(&mut mesh, &boundary, "outer", |p| {
        (radius(p) - outer).abs() <= e * 10.0
    });
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        add_face_set(&mut mesh, &boundary, &format!("{axis}min"), |p| {
            p[k].abs() <= e
        });
    }
    Ok(mesh)
}

/// A solid cylinder `r <= radius` about the z axis, `0 <= z <= height`,
/// hex-structured with an O-grid: in each quarter a square core `[0, c]^2`
/// (`c = radius / 2`) of `n[0] x n[0]` cells and a ring of `n[0] x n[1]`
/// cells on each of the core's two outer edges, blended linearly from the
/// edge to the arc (no degenerate cell on the axis); `n[2]` axial
/// divisions. `angle` (degrees) is 90, 180, 270 or 360: that many quarters
/// from the x axis. Sets: `outer`, `zmin`, `zmax`, and for an open sector
/// `start` (the plane through the positive x axis) and `end`.
pub fn cylinder(
    radius: f64,
    angle: f64,
    height: f64,
    n: [usize; 3],
    kind: CellKind,
) -> Result<Mesh<3>, MeshError> {
    const G: &str = "cylinder";
    positive(G, "radius", radius)?;
    positive(G, "height", height)?;
    let quarters = angle / 90.0;
    if !(quarters == quarters.round() && (1.0..=4.0).contains(&quarters)) {
        return Err(MeshError::new(format!(
            "{G}: angle {angle} must be 90, 180, 270 or 360 degrees (whole quarters of the O-grid)"
        )));
    }
    divisions(G, "core", n[0], 1)?;
    divisions(G, "ring", n[1], 1)?;
    divisions(G, "axial", n[2], 1)?;
    let quarters = quarters as usize;
    let (m, nr) = (n[0], n[1]);
    let c = 0.5 * radius;
    let z = |k: usize| {
        if k == n[2] {
            height
        } else {
            height * k as f64 / n[2] as f64
        }
    };
    let frac = |i: usize, m: usize| if i == m { 1.0 } else { i as f64 / m as f64 };
    // one quarter: core, ring on x = c, ring on y = c; (i, j, k) right-handed
    let core = block(G, [m, m, n[2]], kind, |i, j, k| {
        [c * frac(i, m), c * frac(j, m), z(k)]
    })?;
    let ring_x = block(G, [nr, m, n[2]], kind, |i, j, k| {
        let t = frac(i, nr);
        let (co, si) = super::common::cos_sin_deg(45.0 * frac(j, m));
        let edge = [c, c * frac(j, m)];
        [
            (1.0 - t) * edge[0] + t * radius * co,
            (1.0 - t) * edge[1] + t * radius * si,
            z(k),
        ]
    })?;
    // i along x and j outwards, like the core: the Kuhn split of tet4
    // conforms across every seam (each face diagonal runs from the corner
    // nearest the axis and z = 0 to the opposite one on both sides)
    let ring_y = block(G, [m, nr, n[2]], kind, |i, j, k| {
        let t = frac(j, nr);
        let (co, si) = super::common::cos_sin_deg(90.0 - 45.0 * frac(i, m));
        let edge = [c * frac(i, m), c];
        [
            (1.0 - t) * edge[0] + t * radius * co,
            (1.0 - t) * edge[1] + t * radius * si,
            z(k),
        ]
    })?;
    let mut mesh = Mesh::<3>::default();
    for q in 0..quarters {
        // rotation by q quarter turns: (x, y) -> (-y, x), exact
        let turn = |p: [f64; 3]| {
            let mut p = p;
            for _ in 0..q {
                p = [-p[1], p[0], p[2]];
            }
            p
        };
        for part in [&core, &ring_x, &ring_y] {
            let base = mesh.nodes.len();
            mesh.nodes.extend(part.nodes.iter().map(|&p| turn(p)));
            for cell in part.cells.iter() {
                let nodes: Vec<usize> = cell.nodes.iter().map(|&v| base + v).collect();
                mesh.cells.push_nodes(cell.kind, &nodes);
            }
        }
    }
    node_budget(G, Some(mesh.nodes.len()))?;
    merge_close_nodes(&mut mesh, tol(radius.max(height)));
    let boundary = mesh.boundary_facets(0..mesh.cells.len());
    let e = tol(radius.max(height));
    let r = |p: &[f64; 3]| p[0].hypot(p[1]);
    add_face_set(&mut mesh, &boundary, "outer", |p| {
        (r(p) - radius).abs() <= e
    });
    add_face_set(&mut mesh, &boundary, "zmin", |p| p[2].abs() <= e);
    add_face_set(&mut mesh, &boundary, "zmax", |p| (p[2] - height).abs() <= e);
    if quarters < 4 {
        let (co, si) = super::common::cos_sin_deg(angle);
        add_face_set(&mut mesh, &boundary, "start", |p| {
            p[1].abs() <= e && p[0] >= -e
        });
        add_face_set(&mut mesh, &boundary, "end", |p| {
            (p[0] * si - p[1] * co).abs() <= e && p[0] * co + p[1] * si >= -e
        });
    }
    Ok(mesh)
}

/// Merges nodes closer than `tol` (grid hashing; the first node of a group
/// is kept, the cells renumbered, unused nodes dropped in order).
fn merge_close_nodes(mesh: &mut Mesh<3>, tol: f64) {
    let h = 4.0 * tol;
    let cell = |p: &[f64; 3]| p.map(|v| (v / h).floor() as i64);
    let mut grid: BTreeMap<[i64; 3], Vec<usize>> = BTreeMap::new();
    let mut target: Vec<usize> = (0..mesh.nodes.len()).collect();
    for (n, p) in mesh.nodes.iter().enumerate() {
        let c = cell(p);
        let mut found = None;
        'search: for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(list) = grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) {
                        for &m in list {
                            let q = &mesh.nodes[m];
                            let d2: f64 = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum();
                            if d2 <= tol * tol {
                                found = Some(m);
                                break 'search;
                            }
                        }
                    }
                }
            }
        }
        match found {
            Some(m) => target[n] = m,
            None => grid.entry(c).or_default().push(n),
        }
    }
    let mut new_index = vec![usize::MAX; mesh.nodes.len()];
    let mut nodes = Vec::new();
    for n in 0..mesh.nodes.len() {
        if target[n] == n {
            new_index[n] = nodes.len();
            nodes.push(mesh.nodes[n]);
        }
    }
    for c in 0..mesh.cells.len() {
        for v in mesh.cells.nodes_mut(c) {
            *v = new_index[target[*v]];
        }
    }
    mesh.nodes = nodes;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::validate;

    fn volume(m: &Mesh<3>) -> f64 {
        m.cells
            .iter()
            .map(|c| crate::mesh::quality::cell_measure(m, c))
            .sum()
    }

    #[test]
    fn brick_hex_and_tet_fill_the_box_with_valid_cells_and_six_face_sets() {
        for kind in [CellKind::Hex8, CellKind::Tet4] {
            let g = [
                Grading::Uniform,
                Grading::Geometric { ratio: 2.0 },
                Grading::Uniform,
            ];
            let m = brick([1.0, 0.0, -1.0], [2.0, 1.0, 3.0], [2, 3, 2], g, kind).unwrap();
            assert_eq!(m.nodes.len(), 3 * 4 * 3);
            let per = if kind == CellKind::Hex8 { 1 } else { 6 };
            assert_eq!(m.cells.len(), 12 * per);
            validate::check(&m).unwrap();
            assert!((volume(&m) - 6.0).abs() < 1e-12);
            // every boundary face is in exactly one of the six sets
            let total: usize = m.face_sets.values().map(Vec::len).sum();
            assert_eq!(total, m.boundary_facets(0..m.cells.len()).len());
            let quads = 2 * (2 * 3 + 3 * 2 + 2 * 2);
            let faces_per_quad = if kind == CellKind::Hex8 { 1 } else { 2 };
            assert_eq!(total, quads * faces_per_quad);
            assert_eq!(m.node_sets["xmin"].len(), 4 * 3);
            assert_eq!(m.nodes[m.node_sets["origin"][0]], [1.0, 0.0, -1.0]);
        }
    }

    #[test]
    fn brick_on_lines_places_the_nodes_on_the_lines_and_refuses_bad_lines() {
        let x = [0.0, 0.1, 0.2, 0.5, 1.0];
        let y = [0.0, 0.25, 1.0];
        let z = [-1.0, 0.0];
        for kind in [CellKind::Hex8, CellKind::Tet4] {
            let m = brick_on_lines([&x, &y, &z], kind).unwrap();
            assert_eq!(m.nodes.len(), 5 * 3 * 2);
            validate::check(&m).unwrap();
            assert!((volume(&m) - 1.0).abs() < 1e-12);
            let total: usize = m.face_sets.values().map(Vec::len).sum();
            assert_eq!(total, m.boundary_facets(0..m.cells.len()).len());
            // node (i, j, k) at (x[i], y[j], z[k]): every coordinate is a
            // line point, and zmax holds the 15 nodes at z = 0
            for p in &m.nodes {
                assert!(x.contains(&p[0]) && y.contains(&p[1]) && z.contains(&p[2]));
            }
            assert_eq!(m.node_sets["zmax"].len(), 15);
            assert!(m.node_sets["xmax"].iter().all(|&n| m.nodes[n][0] == 1.0));
            assert_eq!(m.nodes[m.node_sets["origin"][0]], [0.0, 0.0, -1.0]);
        }
        // the same nodes as `brick` on uniform divisions
        let u = [0.0, 0.5, 1.0];
        let a = brick_on_lines([&u, &u, &u], CellKind::Hex8).unwrap();
        let b = brick(
            [0.0; 3],
            [1.0; 3],
            [2; 3],
            [Grading::Uniform; 3],
            CellKind::Hex8,
        )
        .unwrap();
        assert_eq!(a.nodes, b.nodes);
        assert_eq!(a.face_sets, b.face_sets);
        for (lines, what) in [
            ([&x[..], &y[..], &[0.0][..]], "at least 2 points"),
            (
                [&x[..], &[0.0, 0.5, 0.5][..], &z[..]],
                "increase strictly: point 2",
            ),
            (
                [&[0.0, f64::NAN][..], &y[..], &z[..]],
                "point 1 of the x line is not finite",
            ),
        ] {
            let e = brick_on_lines(lines, CellKind::Hex8).unwrap_err();
            assert!(e.message.contains(what), "{}", e.message);
        }
    }

    #[test]
    fn tube_sector_and_sphere_octant_are_valid_with_their_volumes() {
        use std::f64::consts::PI;
        let m = tube(
            1.0,
            2.0,
            90.0,
            0.5,
            [3, 8, 1],
            Grading::Uniform,
            CellKind::Hex8,
        )
        .unwrap();
        validate::check(&m).unwrap();
        // chords: the polygonal sector is slightly smaller than the exact one
        let exact = PI / 4.0 * 3.0 * 0.5;
        assert!((volume(&m) - exact).abs() / exact < 0.01, "{}", volume(&m));
        assert!(m.face_sets.contains_key("start") && m.face_sets.contains_key("end"));
        let ring = tube(
            1.0,
            2.0,
            360.0,
            0.5,
            [1, 6, 1],
            Grading::Uniform,
            CellKind::Tet4,
        )
        .unwrap();
        validate::check(&ring).unwrap();
        assert_eq!(ring.nodes.len(), 2 * 6 * 2);
        for kind in [CellKind::Hex8, CellKind::Tet4] {
            let s = sphere_octant(1.0, 2.0, 2, 3, Grading::Uniform, kind).unwrap();
            validate::check(&s).unwrap();
            let exact = PI / 6.0 * (8.0 - 1.0);
            assert!((volume(&s) - exact).abs() / exact < 0.05, "{}", volume(&s));
            // nodes: 3 patches of 4 x 4 per layer, seams shared (3 edges of
            // 4, the corner once): 3 * 16 - 3 * 4 + 1 = 37 per layer
            assert_eq!(s.nodes.len(), 37 * 3);
            let inner = &s.node_sets["inner"];
            assert_eq!(inner.len(), 37);
            for &n in inner {
                let p = s.nodes[n];
                let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                assert!((r - 1.0).abs() < 1e-12);
            }
            for axis in ["xmin", "ymin", "zmin"] {
                assert!(!s.face_sets[axis].is_empty());
            }
        }
    }

    /// A seeded imperfection `a cos(n theta) sin(m pi z / h)`: each node
    /// moves radially by exactly that (hand values at theta = 0 and 45
    /// degrees, z = h / 2), the ends stay circular, the symmetry planes'
    /// nodes stay on them, the cells stay valid, and an amplitude of the
    /// inner radius is refused.
    #[test]
    fn tube_imperfection_moves_nodes_radially_by_the_seeded_shape() {
        let (inner, outer, h) = (19.0, 21.0, 40.0);
        let base = tube(
            inner,
            outer,
            90.0,
            h,
            [2, 8, 4],
            Grading::Uniform,
            CellKind::Hex8,
        )
        .unwrap();
        let mut m = base.clone();
        tube_imperfection(&mut m, 0.05, 2, 1, h, inner).unwrap();
        validate::check(&m).unwrap();
        let radius = |p: [f64; 3]| p[0].hypot(p[1]);
        let mut checked = 0;
        for (p, q) in base.nodes.iter().zip(&m.nodes) {
            let theta = p[1].atan2(p[0]);
            // the node moved along its radius
            assert!((theta - q[1].atan2(q[0])).abs() < 1e-12, "{p:?} -> {q:?}");
            assert_eq!(p[2], q[2]);
            let dr = radius(*q) - radius(*p);
            if p[2] == 0.0 || p[2] == h {
                assert!(dr.abs() < 1e-15, "end node {p:?}: {dr}");
            }
            if (p[2] - h / 2.0).abs() < 1e-12 {
                // cos(2 * 0) = 1, cos(2 * 45 deg) = 0, cos(2 * 90 deg) = -1
                let want = if p[1].abs() < 1e-12 {
                    0.05
                } else if p[0].abs() < 1e-12 {
                    -0.05
                } else if (p[0] - p[1]).abs() < 1e-9 {
                    0.0
                } else {
                    continue;
                };
                assert!((dr - want).abs() < 1e-12, "{p:?}: {dr} against {want}");
                checked += 1;
            }
        }
        // 3 nodes through the wall at each of the three angles
        assert_eq!(checked, 9);
        for n in &m.node_sets["start"] {
            assert!(m.nodes[*n][1].abs() < 1e-12);
        }
        for n in &m.node_sets["end"] {
            assert!(m.nodes[*n][0].abs() < 1e-12);
        }
        // waves = 0, half_waves = 0: a uniform radial shift
        let mut u = base.clone();
        tube_imperfection(&mut u, 0.1, 0, 0, h, inner).unwrap();
        for (p, q) in base.nodes.iter().zip(&u.nodes) {
            assert!((radius(*q) - radius(*p) - 0.1).abs() < 1e-12);
        }
        let e = tube_imperfection(&mut u, inner, 2, 1, h, inner).unwrap_err();
        assert!(e.message.contains("imperfection"), "{}", e.message);
        assert!(tube_imperfection(&mut u, f64::NAN, 2, 1, h, inner).is_err());
    }

    /// Regression: with angle 180 the end plane is the plane of the start
    /// (y = 0), so the end set took the start faces too. Start and end must
    /// be disjoint half-planes for every open angle, and every boundary
    /// face must be in exactly one set.
    #[test]
    fn tube_start_and_end_sets_are_disjoint_half_planes_for_every_open_angle() {
        for angle in [90.0, 180.0, 270.0, 350.0] {
            for kind in [CellKind::Hex8, CellKind::Tet4] {
                let m = tube(1.0, 2.0, angle, 0.5, [2, 6, 1], Grading::Uniform, kind).unwrap();
                let (start, end) = (&m.face_sets["start"], &m.face_sets["end"]);
                let per = if kind == CellKind::Hex8 { 1 } else { 2 };
                assert_eq!(start.len(), 2 * per, "{angle} {kind:?}");
                assert_eq!(end.len(), 2 * per, "{angle} {kind:?}");
                let (c, s) = super::super::common::cos_sin_deg(angle);
                for &n in &m.node_sets["start"] {
                    assert!(m.nodes[n][0] > 0.5, "{angle}: start node {:?}", m.nodes[n]);
                }
                for &n in &m.node_sets["end"] {
                    let p = m.nodes[n];
                    assert!(p[0] * c + p[1] * s > 0.5, "{angle}: end node {p:?}");
                }
                let total: usize = m.face_sets.values().map(Vec::len).sum();
                assert_eq!(total, m.boundary_facets(0..m.cells.len()).len(), "{angle}");
            }
        }
    }

    #[test]
    fn cylinder_o_grid_quarters_are_valid_conforming_and_fill_the_disc() {
        use std::f64::consts::PI;
        let (m, nr, nz) = (3, 2, 2);
        // nodes per layer of one quarter: core + two rings, minus the shared
        // core edges, the shared ring edge, plus the corner counted thrice
        let quarter = (m + 1) * (m + 1) + 2 * (nr + 1) * (m + 1) - 2 * (m + 1) - (nr + 1) + 1;
        for kind in [CellKind::Hex8, CellKind::Tet4] {
            for (angle, quarters) in [(90.0, 1), (180.0, 2), (360.0, 4)] {
                let c = cylinder(2.0, angle, 1.5, [m, nr, nz], kind).unwrap();
                validate::check(&c).unwrap();
                let per_layer = if quarters == 4 {
                    4 * quarter - 4 * (m + nr + 1) + 1
                } else {
                    quarters * quarter - (quarters - 1) * (m + nr + 1)
                };
                assert_eq!(c.nodes.len(), per_layer * (nz + 1), "{angle} {kind:?}");
                // chords of 2 m segments per quarter: inscribed polygon area
                let segments = (2 * m * quarters) as f64;
                let theta = angle.to_radians() / segments;
                let exact = 0.5 * segments * 4.0 * theta.sin() * 1.5;
                let v = volume(&c);
                assert!(
                    (v - exact).abs() / exact < 1e-12,
                    "{angle} {kind:?}: {v} vs {exact}"
                );
                assert!(v < PI * 4.0 * 1.5 * quarters as f64 / 4.0);
                // every outer node on the radius; the face sets cover the boundary
                for &n in &c.node_sets["outer"] {
                    assert!((c.nodes[n][0].hypot(c.nodes[n][1]) - 2.0).abs() < 1e-12);
                }
                let faces: usize = c.face_sets.values().map(Vec::len).sum();
                assert_eq!(faces, c.boundary_facets(0..c.cells.len()).len(), "{angle}");
                assert_eq!(c.face_sets.contains_key("start"), quarters < 4);
                if quarters == 2 {
                    // the end of a half cylinder is the plane y = 0, x <= 0
                    for &n in &c.node_sets["end"] {
                        assert!(c.nodes[n][1] == 0.0 && c.nodes[n][0] <= 0.0);
                    }
                }
            }
        }
        assert!(cylinder(1.0, 45.0, 1.0, [2, 2, 2], CellKind::Hex8).is_err());
        assert!(cylinder(1.0, 90.0, 1.0, [0, 2, 2], CellKind::Hex8).is_err());
    }

    #[test]
    fn bad_solid_specs_are_errors() {
        let g = [Grading::Uniform; 3];
        assert!(brick([0.0; 3], [1.0, 0.0, 1.0], [1, 1, 1], g, CellKind::Hex8).is_err());
        assert!(brick([0.0; 3], [1.0; 3], [1, 0, 1], g, CellKind::Hex8).is_err());
        assert!(brick([0.0; 3], [1.0; 3], [1, 1, 1], g, CellKind::Quad4).is_err());
        assert!(brick(
            [0.0; 3],
            [1.0; 3],
            [100_000, 100_000, 10],
            g,
            CellKind::Hex8
        )
        .is_err());
        assert!(tube(
            2.0,
            1.0,
            90.0,
            1.0,
            [1, 1, 1],
            Grading::Uniform,
            CellKind::Hex8
        )
        .is_err());
        assert!(sphere_octant(1.0, 2.0, 0, 1, Grading::Uniform, CellKind::Hex8).is_err());
    }
}
