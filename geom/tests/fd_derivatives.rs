//! Finite-difference checks of the geometric derivatives every contact
//! tangent rests on: the gradient of the gap is the normal (`dg/dx = n`) and
//! the derivative of the normal is the returned curvature (`dn/dx = W`, the
//! Weingarten map of the offset surface in ambient 3x3 form), for every
//! surface type: the five analytical shapes (both sides), a rational NURBS
//! surface, a trimmed NURBS face with holes (interior and hole edges), a
//! revolved surface with a pole, and a closed box of six faces (edges and
//! vertices, convex from outside and concave from inside).
//!
//! Reference: the closest-point map is smooth away from the medial axis,
//! so central differences with step h agree to O(h^2); h = 1e-6 of the
//! tool size, relative error <= 1e-6 required. A stencil whose six
//! projections do not all land on the same entity and kind (it straddles a
//! switch between face, edge and vertex) is skipped, as are points near a
//! focal set (where `dn/dx` blows up).

use ctc_geom::analytic::{Analytic, Cone, Cylinder, Plane, Sphere, Torus};
use ctc_geom::brep::{BrepOptions, BrepTool, Counters, Face, SearchState};
use ctc_geom::nurbs::{build, NurbsCurve, NurbsSurface};
use ctc_geom::trim::{Boundary, Loop, TrimCurve};
use ctc_geom::{FootKind, Placement, Projection, ProjectionError, Side, Vec2, Vec3};
use proptest::prelude::*;

/// Worst relative errors of the gap gradient and the normal derivative.
#[derive(Debug)]
struct Errors {
    gap: f64,
    normal: f64,
}

/// Central differences of `project` at `x` with step `h`; `None` when the
/// stencil straddles a switch or a projection fails.
fn fd(
    project: &dyn Fn(&Vec3) -> Result<Projection, ProjectionError>,
    x: Vec3,
    h: f64,
    size: f64,
) -> Option<(Projection, Errors)> {
    let p0 = project(&x).ok()?;
    let mut gap: f64 = 0.0;
    let mut normal: f64 = 0.0;
    let scale = p0.curvature.norm().max(1.0 / size);
    for k in 0..3 {
        let mut e = Vec3::zeros();
        e[k] = h;
        let pp = project(&(x + e)).ok()?;
        let pm = project(&(x - e)).ok()?;
        if pp.kind != p0.kind
            || pm.kind != p0.kind
            || pp.entity != p0.entity
            || pm.entity != p0.entity
        {
            return None;
        }
        let dg = (pp.gap - pm.gap) / (2.0 * h);
        gap = gap.max((dg - p0.normal[k]).abs());
        let dn = (pp.normal - pm.normal) / (2.0 * h);
        normal = normal.max((dn - p0.curvature.column(k)).norm() / scale);
    }
    // Symmetric, and zero along the normal.
    assert!((p0.curvature - p0.curvature.transpose()).norm() <= 1e-12 * scale);
    assert!(
        (p0.curvature * p0.normal).norm() <= 1e-9 * scale,
        "{:?}",
        p0
    );
    Some((p0, Errors { gap, normal }))
}

fn check(
    project: &dyn Fn(&Vec3) -> Result<Projection, ProjectionError>,
    x: Vec3,
    size: f64,
) -> Result<Option<Projection>, TestCaseError> {
    match fd(project, x, 1e-6 * size, size) {
        None => Ok(None),
        Some((p, e)) => {
            prop_assert!(
                e.gap <= 1e-6,
                "gap gradient error {:.2e} at {:?}: {:?}",
                e.gap,
                x,
                p
            );
            prop_assert!(
                e.normal <= 1e-6,
                "normal derivative error {:.2e} at {:?}: {:?}",
                e.normal,
                x,
                p
            );
            // The query point is foot + gap * normal.
            prop_assert!((p.point + p.normal * p.gap - x).norm() <= 1e-9 * size);
            Ok(Some(p))
        }
    }
}

fn side(b: bool) -> Side {
    if b {
        Side::Outside
    } else {
        Side::Inside
    }
}

fn unit(a: f64, b: f64) -> Vec3 {
    Vec3::new(a.sin() * b.cos(), a.sin() * b.sin(), a.cos())
}

/// A bicubic rational patch over [-1, 1]^2 with a bump, 5 x 4 control points.
fn bumpy() -> NurbsSurface {
    let (nu, nv) = (5, 4);
    let mut pts = Vec::new();
    let mut w = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let (x, y) = (-1.0 + 2.0 * i as f64 / 4.0, -1.0 + 2.0 * j as f64 / 3.0);
            pts.push(Vec3::new(
                x,
                y,
                0.4 * (1.0 - x * x) * (1.0 - 0.5 * y * y) + 0.1 * x * y,
            ));
            w.push(1.0 + 0.3 * ((i + 2 * j) % 3) as f64);
        }
    }
    NurbsSurface::new(
        [3, 2],
        [nu, nv],
        [
            vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0],
            vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        ],
        pts,
        w,
    )
    .unwrap()
}

/// The bumpy patch trimmed by a rectangle-ish outer loop and two holes (a
/// circle and a NURBS-sided triangle).
fn trimmed() -> BrepTool {
    let v = Vec2::new;
    let outer = Loop::new(
        vec![
            TrimCurve::line(v(0.1, 0.1), v(0.9, 0.1)).unwrap(),
            TrimCurve::line(v(0.9, 0.1), v(0.9, 0.9)).unwrap(),
            TrimCurve::line(v(0.9, 0.9), v(0.1, 0.9)).unwrap(),
            TrimCurve::line(v(0.1, 0.9), v(0.1, 0.1)).unwrap(),
        ],
        1e-12,
    )
    .unwrap();
    let hole1 = Loop::new(
        vec![TrimCurve::arc(v(0.3, 0.3), 0.1, 0.0, std::f64::consts::TAU).unwrap()],
        1e-12,
    )
    .unwrap();
    let side = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![v(0.75, 0.55), v(0.75, 0.75), v(0.55, 0.75)],
        vec![1.0, 0.6, 1.0],
    )
    .unwrap();
    let hole2 = Loop::new(
        vec![
            TrimCurve::line(v(0.55, 0.55), v(0.75, 0.55)).unwrap(),
            TrimCurve::Nurbs(side),
            TrimCurve::line(v(0.55, 0.75), v(0.55, 0.55)).unwrap(),
        ],
        1e-12,
    )
    .unwrap();
    let face = Face::new(bumpy(), Some(Boundary::new(outer, vec![hole1, hole2])), 1.0);
    BrepTool::new(vec![face], BrepOptions::default()).unwrap()
}

/// The cube [0, 1]^3 as six bilinear faces, normals outwards (free space
/// outside) or inwards.
fn cube(outside: bool) -> BrepTool {
    let o = Vec3::zeros;
    let (x, y, z) = (Vec3::x(), Vec3::y(), Vec3::z());
    let faces = [
        (o(), y, x), // z = 0, normal -z
        (z, x, y),   // z = 1, normal +z
        (o(), x, z), // y = 0, normal -y
        (y, z, x),   // y = 1, normal +y
        (o(), z, y), // x = 0, normal -x
        (x, y, z),   // x = 1, normal +x
    ];
    let faces: Vec<Face> = faces
        .iter()
        .map(|(p, a, b)| {
            Face::new(
                build::plane_patch(*p, *a, *b),
                None,
                if outside { 1.0 } else { -1.0 },
            )
        })
        .collect();
    let mut t = BrepTool::new(faces, BrepOptions::default()).unwrap();
    t.orient(1, if outside { 1.0 } else { -1.0 }).unwrap();
    t
}

/// A cylinder of radius 1 and height 2 (a revolved vertical line: `u`
/// along the axis, `v` around, closed in `v`) trimmed to `u` in [0.2, 0.8]
/// by a loop that runs along the parameter seam `v = 0` and back along
/// `v = 1`: those two coedges are one seam, not edges of the tool.
fn seamed_cylinder() -> BrepTool {
    let line = NurbsCurve::new(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Vec3::new(1.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 2.0)],
        vec![1.0, 1.0],
    )
    .unwrap();
    let s = build::revolve(&line).unwrap();
    let v = Vec2::new;
    let outer = Loop::new(
        vec![
            TrimCurve::line(v(0.2, 0.0), v(0.8, 0.0)).unwrap(),
            TrimCurve::line(v(0.8, 0.0), v(0.8, 1.0)).unwrap(),
            TrimCurve::line(v(0.8, 1.0), v(0.2, 1.0)).unwrap(),
            TrimCurve::line(v(0.2, 1.0), v(0.2, 0.0)).unwrap(),
        ],
        1e-12,
    )
    .unwrap();
    // S_u x S_v points inwards: free space outside is orientation -1.
    let face = Face::new(s, Some(Boundary::new(outer, Vec::new())), -1.0);
    BrepTool::new(vec![face], BrepOptions::default()).unwrap()
}

fn brep(tool: &BrepTool) -> impl Fn(&Vec3) -> Result<Projection, ProjectionError> + '_ {
    move |x| tool.project(x, &mut SearchState::new(), &mut Counters::default())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn analytical_surfaces(kind in 0usize..5, out in any::<bool>(), a in 0.1f64..3.0, b in -3.0f64..3.0,
                           r in 0.05f64..3.0, angle in 0.2f64..1.3, rot in 0.0f64..6.0) {
        let c = Vec3::new(0.3, -0.2, 0.5);
        let axis = unit(0.7, 0.4);
        let shape = match kind {
            0 => Analytic::Plane(Plane::new(c, axis, side(out)).unwrap()),
            1 => Analytic::Sphere(Sphere::new(c, 1.0, side(out)).unwrap()),
            2 => Analytic::Cylinder(Cylinder::new(c, axis, 1.0, side(out)).unwrap()),
            3 => Analytic::Cone(Cone::new(c, axis, angle, side(out)).unwrap()),
            _ => Analytic::Torus(Torus::new(c, axis, 1.5, 0.5, side(out)).unwrap()),
        };
        // A moved tool: rotate about an axis through a point, translate.
        let placement = Placement::about_axis(Vec3::new(0.2, 1.0, -0.3), rot, Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.1, 0.2, -0.4)).unwrap();
        let x = c + unit(a, b) * r;
        let project = |x: &Vec3| shape.project(&placement.to_reference(x)).map(|p| placement.to_current(&p));
        let x = placement.apply(&x);
        check(&project, x, 1.0)?;
    }

    #[test]
    fn nurbs_surface_interior_edges_and_corners(u in -0.5f64..1.5, v in -0.5f64..1.5, h in -0.8f64..0.8) {
        let tool = BrepTool::new(vec![Face::new(bumpy(), None, 1.0)], BrepOptions::default()).unwrap();
        let x = Vec3::new(-1.0 + 2.0 * u, -1.0 + 2.0 * v, h);
        check(&brep(&tool), x, 2.0)?;
    }

    #[test]
    fn trimmed_face_with_holes(u in 0.0f64..1.0, v in 0.0f64..1.0, h in -0.3f64..0.5) {
        let tool = trimmed();
        let x = Vec3::new(-1.0 + 2.0 * u, -1.0 + 2.0 * v, h);
        check(&brep(&tool), x, 2.0)?;
    }

    #[test]
    fn revolved_surface_with_a_pole(a in 0.0f64..1.6, b in -3.2f64..3.2, r in 0.2f64..3.0) {
        let dome = build::dome(1.0, 2.0).unwrap();
        let tool = BrepTool::new(vec![Face::new(dome, None, 1.0)], BrepOptions::default()).unwrap();
        let x = Vec3::new(0.0, 0.0, 1.0) + unit(a, b) * r;
        check(&brep(&tool), x, 3.0)?;
    }

    #[test]
    fn box_edges_and_vertices(x in -0.6f64..1.6, y in -0.6f64..1.6, z in -0.6f64..1.6, out in any::<bool>()) {
        let tool = cube(out);
        let p = Vec3::new(x, y, z);
        let project = brep(&tool);
        let checked = check(&project, p, 1.0)?;
        if let Some(proj) = checked {
            // Inside the cube is inside the tool (negative gap) when free
            // space is outside, and free space when it is inside.
            let inside = (0.0..=1.0).contains(&x) && (0.0..=1.0).contains(&y) && (0.0..=1.0).contains(&z);
            let expect = if out == inside { -1.0 } else { 1.0 };
            prop_assert!(proj.gap * expect >= 0.0, "{:?}: {:?}", p, proj);
        }
    }
}

#[test]
fn box_feet_have_the_right_kind() {
    let tool = cube(true);
    let p = brep(&tool);
    let r = p(&Vec3::new(0.5, 0.5, 2.0)).unwrap();
    assert_eq!((r.kind, r.gap), (FootKind::Interior, 1.0));
    let r = p(&Vec3::new(0.5, -1.0, 2.0)).unwrap();
    assert_eq!(r.kind, FootKind::Edge);
    assert!((r.gap - 2f64.sqrt()).abs() < 1e-12);
    let r = p(&Vec3::new(-1.0, -1.0, 2.0)).unwrap();
    assert_eq!(r.kind, FootKind::Vertex);
    assert!((r.gap - 3f64.sqrt()).abs() < 1e-12);
    let r = p(&Vec3::new(0.5, 0.4, 0.45)).unwrap();
    assert_eq!(r.kind, FootKind::Interior);
    assert!((r.gap + 0.4).abs() < 1e-12);
    assert_eq!(tool.vertices.len(), 8);
    assert!(
        tool.neighbours.iter().all(|n| n.len() == 4),
        "{:?}",
        tool.neighbours
    );
}

/// A deterministic sweep over every tool: how many points were checked per
/// foot kind and the worst relative errors (printed with `--nocapture`);
/// every kind a tool has must be reached.
#[test]
fn coverage_and_worst_errors() {
    let mut seed: u64 = 0x9e3779b97f4a7c15;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let untrimmed =
        BrepTool::new(vec![Face::new(bumpy(), None, 1.0)], BrepOptions::default()).unwrap();
    let holes = trimmed();
    let dome = BrepTool::new(
        vec![Face::new(build::dome(1.0, 2.0).unwrap(), None, 1.0)],
        BrepOptions::default(),
    )
    .unwrap();
    let (cube_out, cube_in) = (cube(true), cube(false));
    let seamed = seamed_cylinder();
    let seams = seamed.coedges.iter().filter(|c| c.seam).count();
    assert_eq!(
        seams, 2,
        "the loop's two sides of the parameter seam are one seam"
    );
    let sphere = Analytic::Sphere(Sphere::new(Vec3::zeros(), 1.0, Side::Outside).unwrap());
    let cone = Analytic::Cone(Cone::new(Vec3::zeros(), Vec3::z(), 0.5, Side::Inside).unwrap());
    let torus =
        Analytic::Torus(Torus::new(Vec3::zeros(), Vec3::z(), 1.5, 0.5, Side::Outside).unwrap());
    let cyl =
        Analytic::Cylinder(Cylinder::new(Vec3::zeros(), Vec3::x(), 1.0, Side::Inside).unwrap());
    let plane = Analytic::Plane(
        Plane::new(Vec3::zeros(), Vec3::new(1.0, 1.0, 1.0), Side::Outside).unwrap(),
    );
    type Tool<'a> = (
        &'a str,
        Box<dyn Fn(&Vec3) -> Result<Projection, ProjectionError> + 'a>,
        [f64; 6],
        &'a [FootKind],
    );
    let all = [FootKind::Interior, FootKind::Edge, FootKind::Vertex];
    let tools: Vec<Tool> = vec![
        (
            "plane",
            Box::new(move |x: &Vec3| plane.project(x)),
            [-2.0, 2.0, -2.0, 2.0, -2.0, 2.0],
            &[FootKind::Interior],
        ),
        (
            "sphere",
            Box::new(move |x: &Vec3| sphere.project(x)),
            [-2.0, 2.0, -2.0, 2.0, -2.0, 2.0],
            &[FootKind::Interior],
        ),
        (
            "cylinder",
            Box::new(move |x: &Vec3| cyl.project(x)),
            [-2.0, 2.0, -2.0, 2.0, -2.0, 2.0],
            &[FootKind::Interior],
        ),
        (
            "cone",
            Box::new(move |x: &Vec3| cone.project(x)),
            [-2.0, 2.0, -2.0, 2.0, -2.0, 2.0],
            &[FootKind::Interior, FootKind::Vertex],
        ),
        (
            "torus",
            Box::new(move |x: &Vec3| torus.project(x)),
            [-2.5, 2.5, -2.5, 2.5, -1.0, 1.0],
            &[FootKind::Interior],
        ),
        (
            "nurbs patch",
            Box::new(brep(&untrimmed)),
            [-2.0, 2.0, -2.0, 2.0, -0.8, 0.8],
            &all,
        ),
        (
            "trimmed face, 2 holes",
            Box::new(brep(&holes)),
            [-1.0, 1.0, -1.0, 1.0, -0.3, 0.5],
            &all,
        ),
        (
            "revolved, pole + seam",
            Box::new(brep(&dome)),
            [-2.0, 2.0, -2.0, 2.0, -1.0, 3.0],
            &[FootKind::Interior, FootKind::Edge],
        ),
        (
            "trimmed cylinder, seam in the loop",
            Box::new(brep(&seamed)),
            [-2.0, 2.0, -2.0, 2.0, -0.5, 2.5],
            &[FootKind::Interior, FootKind::Edge],
        ),
        (
            "box, free outside",
            Box::new(brep(&cube_out)),
            [-0.6, 1.6, -0.6, 1.6, -0.6, 1.6],
            &all,
        ),
        (
            "box, free inside",
            Box::new(brep(&cube_in)),
            [-0.6, 1.6, -0.6, 1.6, -0.6, 1.6],
            &all,
        ),
    ];
    println!(
        "| tool | interior | edge | vertex | skipped | max rel. err dg/dx | max rel. err dn/dx |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (name, project, b, kinds) in &tools {
        let mut counts = [0usize; 3];
        let mut skipped = 0;
        let (mut eg, mut en): (f64, f64) = (0.0, 0.0);
        for _ in 0..1500 {
            let x = Vec3::new(
                b[0] + (b[1] - b[0]) * rnd(),
                b[2] + (b[3] - b[2]) * rnd(),
                b[4] + (b[5] - b[4]) * rnd(),
            );
            match fd(project.as_ref(), x, 1e-6 * 2.0, 2.0) {
                None => skipped += 1,
                Some((p, e)) => {
                    counts[p.kind as usize] += 1;
                    eg = eg.max(e.gap);
                    en = en.max(e.normal);
                }
            }
        }
        println!(
            "| {name} | {} | {} | {} | {skipped} | {eg:.1e} | {en:.1e} |",
            counts[0], counts[1], counts[2]
        );
        assert!(eg <= 1e-6 && en <= 1e-6, "{name}: {eg:e} {en:e}");
        for k in kinds.iter() {
            assert!(
                counts[*k as usize] >= 5,
                "{name}: too few {k:?} feet: {counts:?}"
            );
        }
        assert!(skipped < 300, "{name}: {skipped} stencils skipped");
    }
}
