//! The thickness map of a sheet or tube (`output { thickness = (a.top,
//! a.bottom) }`, 3D): at every node of the body, the sum of its distances
//! to the two named boundary faces in the current configuration,
//! `t(x) = dist(x, A) + dist(x, B)` (closest points on the deformed faces,
//! each face cut into triangles: tri3 as they are, quadrilaterals along
//! their first diagonal, quadratic faces by their corners). On a node of
//! `A` it is the distance to `B`: the wall thickness measured along `B`'s
//! normal, what a thickness gauge reads; through the thickness it is the
//! same for a sheet of slowly varying thickness. Written as the VTU point
//! field `thickness` (0 outside the body), `thickness.csv` (the nodes of
//! `A` at the written increment: reference and current coordinates,
//! reference distance from the origin, thickness) and the `history.csv`
//! columns `thickness_min`, `thickness_min_x`, `_y`, `_z` (the thinnest
//! node of `A` and its reference position).

use crate::mesh::Mesh;
use crate::model::ThicknessRequest;
use ctc_geom::trimesh::bvh::Bvh;
use ctc_geom::trimesh::closest_on_triangle;
use ctc_geom::{Aabb, Vec3};

/// The triangles of `faces` at the current coordinates `x`.
fn triangles(faces: &[crate::mesh::Facet], x: &[Vec3]) -> Vec<[Vec3; 3]> {
    let mut out = Vec::with_capacity(2 * faces.len());
    for f in faces {
        let n = f.nodes();
        match n.len() {
            3 | 6 => out.push([x[n[0]], x[n[1]], x[n[2]]]),
            4 | 8 | 9 => {
                out.push([x[n[0]], x[n[1]], x[n[2]]]);
                out.push([x[n[0]], x[n[2]], x[n[3]]]);
            }
            _ => {}
        }
    }
    out
}

/// Closest-point distances to a set of triangles.
struct Surface {
    tris: Vec<[Vec3; 3]>,
    bvh: Bvh,
}

impl Surface {
    fn new(tris: Vec<[Vec3; 3]>) -> Self {
        let boxes: Vec<Aabb> = tris.iter().map(|t| Aabb::around(t.iter())).collect();
        Surface {
            bvh: Bvh::new(&boxes),
            tris,
        }
    }

    fn distance(&self, p: &Vec3) -> f64 {
        self.bvh
            .nearest(p, |t| closest_on_triangle(p, self.tris[t]))
            .map_or(f64::NAN, |(_, foot, _)| foot.distance2.sqrt())
    }
}

/// The thickness at every node of the mesh (0 at nodes outside the
/// request's body; NaN where a face set is empty) for the displacements
/// `u`.
pub fn nodal<const D: usize>(
    mesh: &Mesh<D>,
    request: &ThicknessRequest,
    u: &[[f64; D]],
) -> Vec<f64> {
    let nn = mesh.nodes.len();
    let mut out = vec![0.0; nn];
    if D != 3 {
        return out;
    }
    let x: Vec<Vec3> = (0..nn)
        .map(|n| {
            let (x0, un) = (&mesh.nodes[n], u.get(n));
            Vec3::from_fn(|k, _| {
                if k < D {
                    x0[k] + un.map_or(0.0, |v| v[k])
                } else {
                    0.0
                }
            })
        })
        .collect();
    let a = Surface::new(triangles(&request.faces[0], &x));
    let b = Surface::new(triangles(&request.faces[1], &x));
    for &n in &request.nodes {
        if let Some(p) = x.get(n) {
            out[n] = a.distance(p) + b.distance(p);
        }
    }
    out
}

/// The nodes of the first face set (sorted, distinct).
pub fn face_nodes(request: &ThicknessRequest) -> Vec<usize> {
    let mut v: Vec<usize> = request.faces[0]
        .iter()
        .flat_map(|f| f.nodes().iter().copied())
        .collect();
    v.sort_unstable();
    v.dedup();
    v
}

/// Thicknesses within this fraction of the minimum tie (see [`minimum`]).
const TIE: f64 = 1e-9;

/// The thinnest node of the first face set: `(thickness, reference
/// position)` (NaN without nodes): the smallest thickness, at the
/// lowest-numbered node within [`TIE`] of it. Nodes that symmetry makes
/// equally thin (a ring of a tube) differ by round-off, which the thread
/// count or the MPI ranks' summation order changes: the strict minimum's
/// node jumped between them (issue 21: the tube hydroforming example's
/// thinnest point at (7.85, 18.94, 0) serial and (20.5, 0, 0) on 2 ranks,
/// thicknesses equal to 3e-13); the lowest-numbered tied node does not.
pub fn minimum<const D: usize>(
    mesh: &Mesh<D>,
    request: &ThicknessRequest,
    thickness: &[f64],
) -> (f64, [f64; 3]) {
    let nodes = face_nodes(request);
    // f64::min skips NaN; all NaN (or none) stays NaN and finds no node
    let min = nodes.iter().map(|&n| thickness[n]).fold(f64::NAN, f64::min);
    match nodes
        .iter()
        .find(|&&n| thickness[n] <= min + TIE * min.abs())
    {
        Some(&n) => {
            let x0 = &mesh.nodes[n];
            (
                min,
                std::array::from_fn(|k| if k < D { x0[k] } else { 0.0 }),
            )
        }
        None => (f64::NAN, [f64::NAN; 3]),
    }
}

/// `thickness.csv`: the nodes of the first face set, sorted by their
/// reference distance from the origin.
pub fn csv<const D: usize>(
    mesh: &Mesh<D>,
    request: &ThicknessRequest,
    thickness: &[f64],
    u: &[[f64; D]],
) -> String {
    use crate::output::encode::fmt_f64;
    let mut rows: Vec<(f64, usize)> = face_nodes(request)
        .into_iter()
        .map(|n| {
            let r = mesh.nodes[n].iter().map(|c| c * c).sum::<f64>().sqrt();
            (r, n)
        })
        .collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut s = String::from("node,x0,y0,z0,x,y,z,distance0,thickness\n");
    for (r, n) in rows {
        let x0: [f64; 3] = std::array::from_fn(|k| mesh.nodes[n].get(k).copied().unwrap_or(0.0));
        let x: [f64; 3] = std::array::from_fn(|k| x0[k] + u[n].get(k).copied().unwrap_or(0.0));
        let cells: Vec<String> = x0
            .iter()
            .chain(&x)
            .chain([r, thickness[n]].iter())
            .map(|v| fmt_f64(*v))
            .collect();
        s.push_str(&format!("{n},{}\n", cells.join(",")));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::solid::brick;
    use crate::mesh::generate::Grading;
    use crate::mesh::CellKind;

    /// A 4 x 3 x 2 hex8 plate `[0, 4] x [0, 3] x [0, 0.5]`.
    fn plate() -> (Mesh<3>, ThicknessRequest) {
        let mesh = brick(
            [0.0; 3],
            [4.0, 3.0, 0.5],
            [4, 3, 2],
            [Grading::Uniform; 3],
            CellKind::Hex8,
        )
        .unwrap();
        let request = ThicknessRequest {
            label: "p.zmax, p.zmin".into(),
            faces: [
                mesh.face_sets["zmax"].clone(),
                mesh.face_sets["zmin"].clone(),
            ],
            nodes: (0..mesh.nodes.len()).collect(),
        };
        (mesh, request)
    }

    #[test]
    fn a_stretched_and_bent_plate_has_its_thickness_at_every_node() {
        let (mesh, request) = plate();
        // in-plane stretch 1.25 x 1.25 at constant volume: t = 0.5 / 1.5625;
        // then a rigid rotation about (1, 2, 3) and a translation
        let l = 1.25f64;
        let axis = Vec3::new(1.0, 2.0, 3.0).normalize();
        let rot = nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), 0.7);
        let u: Vec<[f64; 3]> = mesh
            .nodes
            .iter()
            .map(|x0| {
                let y = Vec3::new(l * x0[0], l * x0[1], x0[2] / (l * l));
                let z = rot * y + Vec3::new(0.3, -2.0, 5.0);
                [z.x - x0[0], z.y - x0[1], z.z - x0[2]]
            })
            .collect();
        let t = nodal(&mesh, &request, &u);
        for (n, tn) in t.iter().enumerate() {
            assert!((tn - 0.5 / (l * l)).abs() < 1e-12, "node {n}: {tn}");
        }
        let (tmin, _) = minimum(&mesh, &request, &t);
        assert!((tmin - 0.32).abs() < 1e-12);
        let csv = csv(&mesh, &request, &t, &u);
        assert_eq!(csv.lines().count(), 1 + 5 * 4);
        assert!(csv.starts_with("node,x0,y0,z0,x,y,z,distance0,thickness\n"));
    }

    #[test]
    fn a_thinned_spot_is_found_with_its_reference_position() {
        let (mesh, request) = plate();
        // push the top face's node at (2, 1) down by 0.2
        let spot = (0..mesh.nodes.len())
            .find(|&n| {
                let x = mesh.nodes[n];
                (x[0] - 2.0).abs() < 1e-12
                    && (x[1] - 1.0).abs() < 1e-12
                    && (x[2] - 0.5).abs() < 1e-12
            })
            .unwrap();
        let mut u = vec![[0.0; 3]; mesh.nodes.len()];
        u[spot][2] = -0.2;
        let t = nodal(&mesh, &request, &u);
        assert!((t[spot] - 0.3).abs() < 1e-12, "{}", t[spot]);
        let (tmin, at) = minimum(&mesh, &request, &t);
        assert!((tmin - 0.3).abs() < 1e-12);
        assert_eq!(at, [2.0, 1.0, 0.5]);
        // the bottom node below it: its distance to the dented top face is
        // the depth under the dent's vertex
        let below = (0..mesh.nodes.len())
            .find(|&n| {
                let x = mesh.nodes[n];
                (x[0] - 2.0).abs() < 1e-12 && (x[1] - 1.0).abs() < 1e-12 && x[2].abs() < 1e-12
            })
            .unwrap();
        assert!((t[below] - 0.3).abs() < 1e-12, "{}", t[below]);
    }

    #[test]
    fn nodes_thin_to_round_off_alike_give_the_lowest_numbered_place() {
        let (mesh, request) = plate();
        let top = |x: f64, y: f64| {
            (0..mesh.nodes.len())
                .find(|&n| mesh.nodes[n] == [x, y, 0.5])
                .unwrap()
        };
        let (a, b) = (top(1.0, 1.0), top(3.0, 2.0));
        assert!(a < b);
        let place = |dent_b: f64| {
            let mut u = vec![[0.0; 3]; mesh.nodes.len()];
            u[a][2] = -0.2;
            u[b][2] = -dent_b;
            let t = nodal(&mesh, &request, &u);
            let (tmin, at) = minimum(&mesh, &request, &t);
            assert_eq!(tmin, t[a].min(t[b]), "the value is the minimum");
            at
        };
        // b thinner by round-off: a's place (the strict minimum gave b's)
        assert_eq!(place(0.2 + 1e-14), [1.0, 1.0, 0.5]);
        assert_eq!(place(0.2 - 1e-14), [1.0, 1.0, 0.5]);
        // b thinner by more than the tie: b's place
        assert_eq!(place(0.2 + 1e-6), [3.0, 2.0, 0.5]);
    }
}
