//! Triangulated rigid surfaces (STL files, or the triangles of a gmsh
//! surface mesh given by the caller).
//!
//! The closest point of the mesh is found through a bounding-volume
//! hierarchy over the triangles; the region of the closest triangle where
//! it falls (inside, on an edge, at a vertex: Ericson, *Real-Time Collision
//! Detection*, 5.1.5) gives the foot kind, and the inside/outside sign is
//! that of `(x - p) . N` with `N` the **angle-weighted pseudonormal** of the
//! feature (Baerentzen & Aanaes, "Signed distance computation using the
//! angle weighted pseudonormal", IEEE TVCG 11(3), 2005): the face normal on
//! a face, the sum of the two face normals on an edge, the sum of the
//! incident face normals weighted by their angles at a vertex. That sign is
//! exact for a closed, consistently oriented mesh. On an open mesh a free
//! edge or vertex gives a positive gap (a node past the tool's extent is
//! not inside it). Faces are flat (`dn/dx = 0`); edges are cylinders and
//! vertices spheres of radius 0 ([`crate::offset`]).

pub mod bvh;
pub mod stl;

use crate::{offset, Aabb, FootKind, Mat3, Projection, ProjectionError, Side, Vec2, Vec3};
use std::collections::HashMap;

/// A triangle mesh prepared for signed closest-point queries.
#[derive(Debug, Clone, PartialEq)]
pub struct TriMesh {
    /// Vertex positions.
    pub vertices: Vec<Vec3>,
    /// Triangles (counter-clockwise seen from free space for
    /// [`Side::Outside`]).
    pub triangles: Vec<[usize; 3]>,
    /// Unit normal of each triangle, pointing into free space.
    pub face_normals: Vec<Vec3>,
    /// Edges as vertex pairs `(a, b)`, `a < b`.
    pub edges: Vec<[usize; 2]>,
    /// Edge index of the three edges of each triangle (`[ab, bc, ca]`).
    pub triangle_edges: Vec<[usize; 3]>,
    /// Pseudonormal of each edge (unit).
    pub edge_normals: Vec<Vec3>,
    /// Whether an edge belongs to one triangle only.
    pub edge_free: Vec<bool>,
    /// Angle-weighted pseudonormal of each vertex (unit).
    pub vertex_normals: Vec<Vec3>,
    /// Whether a free edge ends at the vertex.
    pub vertex_free: Vec<bool>,
    /// Hierarchy of triangle boxes.
    pub bvh: bvh::Bvh,
}

impl TriMesh {
    /// Builds the mesh; errors on bad indices, zero-area triangles, edges
    /// shared by more than two triangles and inconsistent orientation.
    pub fn new(
        vertices: Vec<Vec3>,
        triangles: Vec<[usize; 3]>,
        side: Side,
    ) -> Result<Self, String> {
        if triangles.is_empty() {
            return Err("triangle mesh: no triangle".into());
        }
        if let Some(i) = vertices
            .iter()
            .position(|p| !p.iter().all(|c| c.is_finite()))
        {
            return Err(format!("triangle mesh: vertex {} is not finite", i + 1));
        }
        let s = side.sign();
        let mut face_normals = Vec::with_capacity(triangles.len());
        for (t, tri) in triangles.iter().enumerate() {
            if let Some(&v) = tri.iter().find(|&&v| v >= vertices.len()) {
                return Err(format!(
                    "triangle mesh: triangle {} uses vertex {} but there are {} vertices",
                    t + 1,
                    v + 1,
                    vertices.len()
                ));
            }
            let [a, b, c] = tri.map(|v| vertices[v]);
            let n = (b - a).cross(&(c - a));
            let scale = (b - a).norm() * (c - a).norm();
            if !(n.norm() > 1e-14 * scale && scale > 0.0) {
                return Err(format!("triangle mesh: triangle {} has zero area", t + 1));
            }
            face_normals.push(n.normalize() * s);
        }
        let mut map: HashMap<[usize; 2], usize> = HashMap::new();
        let mut edges = Vec::new();
        let mut edge_tris: Vec<Vec<(usize, bool)>> = Vec::new();
        let mut triangle_edges = Vec::with_capacity(triangles.len());
        for (t, tri) in triangles.iter().enumerate() {
            let mut te = [0; 3];
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let key = [a.min(b), a.max(b)];
                let e = *map.entry(key).or_insert_with(|| {
                    edges.push(key);
                    edge_tris.push(Vec::new());
                    edges.len() - 1
                });
                edge_tris[e].push((t, a < b));
                te[k] = e;
            }
            triangle_edges.push(te);
        }
        let mut edge_normals = Vec::with_capacity(edges.len());
        let mut edge_free = Vec::with_capacity(edges.len());
        for (e, ts) in edge_tris.iter().enumerate() {
            match ts.as_slice() {
                [(t, _)] => {
                    edge_normals.push(face_normals[*t]);
                    edge_free.push(true);
                }
                [(t1, d1), (t2, d2)] => {
                    if d1 == d2 {
                        let [a, b] = edges[e];
                        return Err(format!(
                            "triangle mesh: triangles {} and {} are oriented inconsistently across the edge ({}, {})",
                            t1 + 1,
                            t2 + 1,
                            a + 1,
                            b + 1
                        ));
                    }
                    let n = face_normals[*t1] + face_normals[*t2];
                    edge_normals.push(n.try_normalize(0.0).unwrap_or(face_normals[*t1]));
                    edge_free.push(false);
                }
                _ => {
                    let [a, b] = edges[e];
                    return Err(format!(
                        "triangle mesh: the edge ({}, {}) is shared by {} triangles (non-manifold)",
                        a + 1,
                        b + 1,
                        ts.len()
                    ));
                }
            }
        }
        let mut vn = vec![Vec3::zeros(); vertices.len()];
        let mut vertex_free = vec![false; vertices.len()];
        for (t, tri) in triangles.iter().enumerate() {
            for k in 0..3 {
                let (p, q, r) = (
                    vertices[tri[k]],
                    vertices[tri[(k + 1) % 3]],
                    vertices[tri[(k + 2) % 3]],
                );
                let (u, w) = ((q - p).normalize(), (r - p).normalize());
                vn[tri[k]] += face_normals[t] * u.dot(&w).clamp(-1.0, 1.0).acos();
            }
        }
        for (e, &free) in edge_free.iter().enumerate() {
            if free {
                vertex_free[edges[e][0]] = true;
                vertex_free[edges[e][1]] = true;
            }
        }
        let vertex_normals = vn
            .iter()
            .map(|n| n.try_normalize(0.0).unwrap_or_else(Vec3::z))
            .collect();
        let boxes: Vec<Aabb> = triangles
            .iter()
            .map(|t| Aabb::around(&t.map(|v| vertices[v])))
            .collect();
        let bvh = bvh::Bvh::new(&boxes);
        Ok(TriMesh {
            vertices,
            triangles,
            face_normals,
            edges,
            triangle_edges,
            edge_normals,
            edge_free,
            vertex_normals,
            vertex_free,
            bvh,
        })
    }

    /// Builds a mesh from a triangle soup (three corners per triangle, as in
    /// STL), merging corners closer than `merge` (exactly equal for 0).
    pub fn from_soup(corners: &[[Vec3; 3]], merge: f64, side: Side) -> Result<Self, String> {
        let mut vertices: Vec<Vec3> = Vec::new();
        let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
        let cell = if merge > 0.0 { merge * 2.0 } else { 1.0 };
        let mut triangles = Vec::with_capacity(corners.len());
        for tri in corners {
            let mut t = [0; 3];
            for (k, p) in tri.iter().enumerate() {
                let key = [0, 1, 2].map(|i| (p[i] / cell).floor() as i64);
                let mut found = None;
                'search: for dx in -1..=1 {
                    for dy in -1..=1 {
                        for dz in -1..=1 {
                            if let Some(list) = grid.get(&[
                                key[0].saturating_add(dx),
                                key[1].saturating_add(dy),
                                key[2].saturating_add(dz),
                            ]) {
                                if let Some(&v) =
                                    list.iter().find(|&&v| (vertices[v] - p).norm() <= merge)
                                {
                                    found = Some(v);
                                    break 'search;
                                }
                            }
                        }
                    }
                }
                t[k] = found.unwrap_or_else(|| {
                    vertices.push(*p);
                    grid.entry(key).or_default().push(vertices.len() - 1);
                    vertices.len() - 1
                });
            }
            triangles.push(t);
        }
        TriMesh::new(vertices, triangles, side)
    }

    /// Box of the mesh.
    pub fn bounding_box(&self) -> Aabb {
        self.bvh.bounds()
    }

    /// Signed closest point of the mesh to `x` (see the module doc).
    /// Parameter: barycentric `(v, w)` of the foot in its triangle.
    pub fn project(&self, x: &Vec3) -> Result<Projection, ProjectionError> {
        let (t, q, region) = self
            .bvh
            .nearest(x, |t| {
                closest_on_triangle(x, self.triangles[t].map(|v| self.vertices[v]))
            })
            .ok_or(ProjectionError::OutOfReach)?;
        let tri = self.triangles[t];
        let d = x - q.point;
        let dist = d.norm();
        let (kind, entity, pseudo, free) = match region {
            Region::Face => (FootKind::Interior, t, self.face_normals[t], false),
            Region::Edge(k) => {
                let e = self.triangle_edges[t][k];
                (FootKind::Edge, e, self.edge_normals[e], self.edge_free[e])
            }
            Region::Vertex(k) => {
                let v = tri[k];
                (
                    FootKind::Vertex,
                    v,
                    self.vertex_normals[v],
                    self.vertex_free[v],
                )
            }
        };
        let s = if free || d.dot(&pseudo) >= 0.0 {
            1.0
        } else {
            -1.0
        };
        let (normal, curvature) = match kind {
            FootKind::Interior => (pseudo, Mat3::zeros()),
            _ if dist == 0.0 => (pseudo, Mat3::zeros()),
            FootKind::Edge => {
                let [a, b] = self.edges[entity].map(|v| self.vertices[v]);
                (
                    d * (s / dist),
                    offset::curve(*x, q.point, b - a, Vec3::zeros(), s).unwrap_or_else(Mat3::zeros),
                )
            }
            FootKind::Vertex => (
                d * (s / dist),
                offset::point(*x, q.point, s).unwrap_or_else(Mat3::zeros),
            ),
        };
        let gap = if kind == FootKind::Interior {
            pseudo.dot(&d)
        } else {
            s * dist
        };
        Ok(Projection {
            point: q.point,
            gap,
            normal,
            curvature,
            kind,
            param: Vec2::new(q.bary[1], q.bary[2]),
            entity,
            iterations: 0,
            residual: 0.0,
        })
    }
}

/// Where on a triangle the closest point lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Region {
    /// Inside the triangle.
    Face,
    /// On edge `k` (0: ab, 1: bc, 2: ca).
    Edge(usize),
    /// At vertex `k`.
    Vertex(usize),
}

/// Closest point of a triangle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriangleFoot {
    /// The point.
    pub point: Vec3,
    /// Its barycentric coordinates.
    pub bary: [f64; 3],
    /// `|x - point|^2`.
    pub distance2: f64,
}

/// Closest point of the triangle `[a, b, c]` to `x` and the region holding
/// it (Voronoi regions of the vertices, then edges, then the face).
pub fn closest_on_triangle(x: &Vec3, [a, b, c]: [Vec3; 3]) -> (TriangleFoot, Region) {
    let foot = |bary: [f64; 3], region: Region| {
        let point = a * bary[0] + b * bary[1] + c * bary[2];
        let point = match region {
            Region::Vertex(0) => a,
            Region::Vertex(1) => b,
            Region::Vertex(_) => c,
            _ => point,
        };
        (
            TriangleFoot {
                point,
                bary,
                distance2: (x - point).norm_squared(),
            },
            region,
        )
    };
    let (ab, ac, ap) = (b - a, c - a, x - a);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return foot([1.0, 0.0, 0.0], Region::Vertex(0));
    }
    let bp = x - b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    if d3 >= 0.0 && d4 <= d3 {
        return foot([0.0, 1.0, 0.0], Region::Vertex(1));
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return foot([1.0 - v, v, 0.0], Region::Edge(0));
    }
    let cp = x - c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    if d6 >= 0.0 && d5 <= d6 {
        return foot([0.0, 0.0, 1.0], Region::Vertex(2));
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return foot([1.0 - w, 0.0, w], Region::Edge(2));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return foot([0.0, 1.0 - w, w], Region::Edge(1));
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    foot([1.0 - v - w, v, w], Region::Face)
}
