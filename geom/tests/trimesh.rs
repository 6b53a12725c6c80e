//! Triangulated rigid surfaces: the signed closest point against brute
//! force, the angle-weighted pseudonormal sign against the winding number,
//! derivatives by finite differences, and the STL reader.
//!
//! Reference: J. A. Baerentzen and H. Aanaes, "Signed distance computation
//! using the angle weighted pseudonormal", IEEE TVCG 11(3), 2005: for a
//! closed, consistently oriented mesh the sign of `(x - p) . N` (N the
//! pseudonormal of the closest feature) is the inside/outside sign. The
//! brute-force inside test is the generalised winding number (sum of the
//! triangles' solid angles, Van Oosterom & Strackee 1983): 4 pi inside, 0
//! outside.
//!
//! ```text
//!        *            a subdivided octahedron pushed onto a "bumpy"
//!      /   \          sphere: r = 1 + 0.25 (+-1) at alternate vertices,
//!    *-------*        so the mesh has convex and concave edges and
//!      \   /          saddle vertices
//!        *
//! ```

use ctc_geom::trimesh::{stl, TriMesh};
use ctc_geom::{FootKind, Side, Vec3};
use proptest::prelude::*;

/// The octahedron subdivided `levels` times, vertices pushed to radius
/// `1 + bump * (+-1)`.
fn bumpy_sphere(levels: usize, bump: f64) -> (Vec<Vec3>, Vec<[usize; 3]>) {
    let mut v = vec![
        Vec3::x(),
        -Vec3::x(),
        Vec3::y(),
        -Vec3::y(),
        Vec3::z(),
        -Vec3::z(),
    ];
    let mut t = vec![
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    for _ in 0..levels {
        let mut mid = std::collections::HashMap::new();
        let mut nt = Vec::new();
        let mut m = |a: usize, b: usize, v: &mut Vec<Vec3>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                v.push(((v[a] + v[b]) * 0.5).normalize());
                v.len() - 1
            })
        };
        for [a, b, c] in t {
            let (ab, bc, ca) = (m(a, b, &mut v), m(b, c, &mut v), m(c, a, &mut v));
            nt.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
        }
        t = nt;
    }
    let v = v
        .iter()
        .enumerate()
        .map(|(i, p)| p * (1.0 + bump * if i % 2 == 0 { 1.0 } else { -1.0 }))
        .collect();
    (v, t)
}

fn solid_angle(x: &Vec3, [a, b, c]: [Vec3; 3]) -> f64 {
    let (a, b, c) = (a - x, b - x, c - x);
    let (la, lb, lc) = (a.norm(), b.norm(), c.norm());
    let num = a.dot(&b.cross(&c));
    let den = la * lb * lc + a.dot(&b) * lc + a.dot(&c) * lb + b.dot(&c) * la;
    2.0 * num.atan2(den)
}

fn winding(mesh: &TriMesh, x: &Vec3) -> f64 {
    mesh.triangles
        .iter()
        .map(|t| solid_angle(x, t.map(|v| mesh.vertices[v])))
        .sum::<f64>()
        / (4.0 * std::f64::consts::PI)
}

fn mesh() -> TriMesh {
    let (v, t) = bumpy_sphere(2, 0.08);
    TriMesh::new(v, t, Side::Outside).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1500))]

    #[test]
    fn sign_matches_the_winding_number_and_distance_the_brute_force(x in -1.6f64..1.6, y in -1.6f64..1.6, z in -1.6f64..1.6) {
        let m = mesh();
        let p = Vec3::new(x, y, z);
        let r = m.project(&p).unwrap();
        let w = winding(&m, &p);
        prop_assert!((w - 1.0).abs() < 1e-6 || w.abs() < 1e-6, "winding {}", w);
        let inside = w > 0.5;
        let brute = m.triangles.iter().map(|t| ctc_geom::trimesh::closest_on_triangle(&p, t.map(|v| m.vertices[v])).0.distance2).fold(f64::INFINITY, f64::min).sqrt();
        prop_assert!((r.gap.abs() - brute).abs() <= 1e-12, "{} vs {}", r.gap, brute);
        if brute > 1e-9 {
            prop_assert_eq!(r.gap < 0.0, inside, "{:?}: {:?}", p, r);
        }
        // Derivatives away from a switch of the closest feature.
        let h = 1e-6;
        let mut ok = true;
        let mut dg = Vec3::zeros();
        let mut dn = ctc_geom::Mat3::zeros();
        for k in 0..3 {
            let mut e = Vec3::zeros();
            e[k] = h;
            let (a, b) = (m.project(&(p + e)).unwrap(), m.project(&(p - e)).unwrap());
            ok &= a.kind == r.kind && b.kind == r.kind && a.entity == r.entity && b.entity == r.entity;
            dg[k] = (a.gap - b.gap) / (2.0 * h);
            dn.set_column(k, &((a.normal - b.normal) / (2.0 * h)));
        }
        if ok && brute > 1e-3 {
            prop_assert!((dg - r.normal).norm() <= 1e-6);
            prop_assert!((dn - r.curvature).norm() <= 1e-6 * r.curvature.norm().max(1.0), "{:?}", r.kind);
        }
    }

    #[test]
    fn mutated_stl_files_never_panic(cut in 0usize..2000, byte in any::<u8>(), at in 0usize..2000, binary in any::<bool>()) {
        let m = mesh();
        let tris: Vec<[Vec3; 3]> = m.triangles.iter().take(20).map(|t| t.map(|v| m.vertices[v])).collect();
        let mut bytes = if binary { stl::write_binary(&tris) } else { stl::write_ascii("part", &tris).into_bytes() };
        if at < bytes.len() {
            bytes[at] = byte;
        }
        bytes.truncate(cut.max(1));
        if let Ok(t) = stl::read(&bytes) {
            let _ = TriMesh::from_soup(&t, 0.0, Side::Outside);
        }
    }
}

#[test]
fn every_foot_kind_is_reached_and_counted() {
    let m = mesh();
    let mut counts = [0usize; 3];
    let mut seed = 12345u64;
    for _ in 0..3000 {
        let mut r = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 3.2 - 1.6
        };
        let p = Vec3::new(r(), r(), r());
        counts[m.project(&p).unwrap().kind as usize] += 1;
    }
    println!(
        "interior {} edge {} vertex {}",
        counts[0], counts[1], counts[2]
    );
    assert!(counts.iter().all(|&c| c > 50), "{counts:?}");
    let _ = FootKind::Interior;
}

#[test]
fn stl_ascii_and_binary_round_trip_and_errors_name_the_line() {
    let m = mesh();
    let tris: Vec<[Vec3; 3]> = m
        .triangles
        .iter()
        .map(|t| t.map(|v| m.vertices[v]))
        .collect();
    let a = stl::read(stl::write_ascii("bumpy", &tris).as_bytes()).unwrap();
    let ma = TriMesh::from_soup(&a, 0.0, Side::Outside).unwrap();
    assert_eq!(
        (ma.vertices.len(), ma.triangles.len()),
        (m.vertices.len(), m.triangles.len())
    );
    let b = stl::read(&stl::write_binary(&tris)).unwrap();
    let mb = TriMesh::from_soup(&b, 1e-6, Side::Outside).unwrap();
    assert_eq!(mb.triangles.len(), m.triangles.len());
    assert_eq!(mb.vertices.len(), m.vertices.len());
    let x = Vec3::new(0.3, 0.2, 1.4);
    assert!((mb.project(&x).unwrap().gap - m.project(&x).unwrap().gap).abs() < 1e-6);

    let bad = "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0\n";
    let e = stl::read(bad.as_bytes()).unwrap_err();
    assert_eq!(e.line, 5, "{e}");
    let e = stl::read(b"solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n  endloop\n").unwrap_err();
    assert!(e.to_string().contains("endfacet"), "{e}");
    let e = stl::read(b"hello").unwrap_err();
    assert!(e.to_string().contains("expected `solid`"), "{e}");
    // An inconsistent orientation is refused.
    let e = TriMesh::new(
        vec![
            Vec3::zeros(),
            Vec3::x(),
            Vec3::y(),
            Vec3::new(1.0, 1.0, 0.0),
        ],
        vec![[0, 1, 2], [1, 2, 3]],
        Side::Outside,
    )
    .unwrap_err();
    assert!(e.contains("inconsistently"), "{e}");
}
