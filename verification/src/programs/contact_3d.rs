//! Contact of solid (3D) bodies with rigid surface tools (tag `3d`,
//! `contact`): the node-to-surface laws of `ctc_engine::contact::surface`
//! in the full solver (deck-free models through the test kit).
//!
//! `contact_patch_3d` — the contact patch test (Taylor & Papadopoulos 1991,
//! "On a patch test for contact problems in two dimensions", in 3D): a unit
//! block on rollers (`u_x = 0` on `x = 0`, `u_y = 0` on `y = 0`, `u_z = 0` on
//! `z = 0`) pressed by a rigid frictionless plane lowered by `d = 0.01`.
//! The exact state is uniform uniaxial stress: Lagrange multipliers give
//! `sigma_zz = E d / H`; the area penalty `k` gives `sigma_zz = k g` with
//! the penetration `g = sigma / k`, so `sigma = E d / (H + E / k)`; the
//! augmented Lagrangian tends to the Lagrange value within its gap
//! tolerance. Every slave node must carry the same pressure (hex8 and
//! tet4, whose slave faces are triangles of different areas). A last run
//! brings the plane to the same final position by a rigid rotation of
//! 0.02 rad about the x axis through `(0.5, 0.5, 1 - d)` (the plane starts
//! tilted): elastic frictionless contact is path independent, so the final
//! state must be the same.
//!
//! ```text
//!     rigid plane, u_z = -d t      (or tilted, rotated back by the motion)
//!   ======================
//!   |                    |  H = 1, E = 1000, nu = 0.3
//!   |      block         |  rollers on x = 0, y = 0, z = 0
//!   |____________________|
//! ```
//!
//! `hertz_sphere_3d` — Hertz point contact (K. L. Johnson, Contact
//! Mechanics, 1985, §4.2): a rigid sphere of radius `R = 1` pressed into an
//! elastic block (quarter model, `E* = E / (1 - nu^2)`), approach `d = 0.01`.
//! From the total force `P` (4x the quarter's contact force), Hertz gives the
//! contact radius `a = (3 P R / (4 E*))^(1/3)` and the pressure
//! `p(r) = p0 sqrt(1 - r^2 / a^2)`, `p0 = 3 P / (2 pi a^2)`. The local
//! quantities are judged against the force the model carries: the peak
//! pressure (the node on the axis) and the pressure profile inside `0.7 a`.
//! The force against Hertz's `P = 4/3 E* sqrt(R) d^(3/2)` of a half-space
//! is reported with the finite block's share: a block of depth 1 = 10 a on
//! a fixed base is stiffer than a half-space (about +9 %), so that check
//! has a loose tolerance and shows the model limit, not the discretization.
//!
//! ```text
//!          rigid sphere R = 1, centre (0, 0, 2 - d)
//!              .-"""-.
//!   __________/_______\___   z = 1 (slave face zmax)
//!   |  quarter block 1 x 1 x 1, graded towards (0, 0, 1)
//!   |  symmetry x = 0, y = 0; u_z = 0 at z = 0
//! ```

//!
//! `cad_patch_3d` and `cad_sphere_3d` — the same scenes with CAD tools:
//! NURBS faces written to IGES by `ctc_geom::iges::Writer`, read back by
//! the reader and projected by Newton on the foot-point equations
//! (`ctc_geom::brep`). A flat bicubic patch must give the patch test's
//! uniform pressure; the same plate trimmed by a circular hole of radius
//! 0.25 over the block's centre must leave exactly the four slave nodes
//! under the hole open (distance 0.014 from its edge, a cylinder of radius
//! 0) and close the twelve others; the exact rational NURBS sphere
//! (`build::sphere`, the contact at its south pole, a degenerate point of
//! the parametrization) must reproduce the analytical sphere's Hertz run
//! to the projection tolerance.
//!
//! `stl_sphere_3d` — the Hertz scene with the sphere triangulated and read
//! from an STL file (`ctc_geom::trimesh`): the difference from the
//! analytical sphere against the facet size (see [`stl_sphere_level`]).

use super::{error, value};
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::contact::{ContactStatus, NodeContact};
use ctc_engine::mesh::generate::{solid, Grading};
use ctc_engine::mesh::CellKind;
use ctc_engine::model::SurfaceShape;
use ctc_engine::model::{
    ContactMethod, LagrangeFormulation, Model, MultiplierUpdate, PenaltyKind, SurfaceMotion,
    TimeFunction,
};
use ctc_engine::solve::{run, IncrementView, Observer, RunSummary};
use ctc_engine::testkit::{ramp, ModelBuilder};
use ctc_geom::analytic::{Analytic, Plane, Sphere};
use ctc_geom::brep::{BrepOptions, BrepTool};
use ctc_geom::nurbs::{build, NurbsSurface};
use ctc_geom::trim::TrimCurve;
use ctc_geom::{Side, Vec2, Vec3};
use std::f64::consts::PI;
use std::sync::Arc;

const E: f64 = 1000.0;
const NU: f64 = 0.3;
/// Approach of the tool.
const D: f64 = 0.01;

/// The registry entries.
pub fn cases() -> Vec<VerifyCase> {
    vec![
        VerifyCase {
            name: "contact_patch_3d",
            title: "3D contact patch test: block pressed by a rigid plane, uniform pressure",
            source: "Taylor & Papadopoulos 1991 (contact patch test), in 3D; uniaxial stress",
            tags: &["3d", "contact", "patch", "penalty", "lagrange", "augmented"],
            levels: 1,
            checks: vec![
                Check::new(Quantity::Named("sigma penalty hex8"), &[1e-10]),
                Check::new(Quantity::Named("sigma penalty tet4"), &[1e-10]),
                Check::new(Quantity::Named("sigma lagrange hex8"), &[1e-10]),
                Check::new(Quantity::Named("sigma augmented hex8"), &[1e-6]),
                Check::new(Quantity::Named("sigma rotated plane"), &[1e-10]),
                Check::new(Quantity::Named("pressure spread"), &[1e-10]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: patch_level,
            }),
        },
        VerifyCase {
            name: "hertz_sphere_3d",
            title: "Hertz: rigid sphere into an elastic block (3D quarter model): area penalty, \
                    Lagrange multipliers, augmented Lagrangian",
            source: "K. L. Johnson, Contact Mechanics (1985) §4.2; Hertz 1882",
            tags: &[
                "3d",
                "contact",
                "hertz",
                "penalty",
                "lagrange",
                "augmented",
                "closed_form",
            ],
            levels: 2,
            checks: vec![
                Check::new(Quantity::Named("p0 vs Hertz(P)"), &[3e-2, 2e-2, 1e-2]),
                Check::new(
                    Quantity::Named("p(r < 0.7a) vs Hertz(P)"),
                    &[0.1, 4e-2, 3e-2],
                ),
                Check::new(Quantity::Named("P vs half-space (finite block)"), &[0.15]),
                Check::new(Quantity::Named("p0 vs Hertz(P) lagrange"), &[3e-2, 2e-2, 1e-2]),
                Check::new(Quantity::Named("p0 vs Hertz(P) augmented"), &[3e-2, 2e-2, 1e-2]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 3,
                run: hertz_level,
            }),
        },
        VerifyCase {
            name: "cad_patch_3d",
            title: "3D contact patch test against IGES NURBS faces, and a plate with a hole",
            source: "Taylor & Papadopoulos 1991 (contact patch test); IGES 5.3 entities 128/144",
            tags: &["3d", "contact", "cad", "nurbs", "iges", "patch", "penalty"],
            levels: 1,
            checks: vec![
                Check::new(Quantity::Named("sigma flat NURBS face"), &[1e-9]),
                Check::new(Quantity::Named("pressure spread"), &[1e-9]),
                Check::new(Quantity::Named("open nodes under the hole"), &[1e-12]),
                Check::new(Quantity::Named("closed nodes around the hole"), &[1e-12]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: cad_patch_level,
            }),
        },
        VerifyCase {
            name: "cad_sphere_3d",
            title: "Hertz block against the IGES rational NURBS sphere vs the analytical sphere",
            source: "exact rational sphere (Piegl & Tiller, The NURBS Book, 8.5); hertz_sphere_3d",
            tags: &[
                "3d",
                "contact",
                "cad",
                "nurbs",
                "iges",
                "hertz",
                "cross_check",
            ],
            levels: 1,
            checks: vec![
                Check::new(Quantity::Named("P NURBS vs analytical"), &[1e-8]),
                Check::new(Quantity::Named("p0 NURBS vs analytical"), &[1e-8]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: cad_sphere_level,
            }),
        },
        VerifyCase {
            name: "stl_sphere_3d",
            title: "Hertz block against a triangulated (STL) sphere vs the analytical sphere, by facet size",
            source: "hertz_sphere_3d with the tool read from an ASCII STL file; faceting (chord) error O(h^2 / R)",
            tags: &["3d", "contact", "stl", "hertz", "cross_check"],
            levels: 3,
            checks: vec![
                // measured: P 0.224, 0.061, 0.0154 at h = 0.139, 0.069,
                // 0.035 (rates 1.88, 1.98); p0 0.53, 0.15, 0.027
                Check::new(
                    Quantity::Named("P STL vs analytical"),
                    &[0.3, 8e-2, 2e-2, 6e-3],
                )
                .with_min_rate(1.7),
                Check::new(
                    Quantity::Named("p0 STL vs analytical"),
                    &[0.7, 0.2, 4e-2, 1.5e-2],
                )
                .with_min_rate(1.7),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 4,
                run: stl_sphere_level,
            }),
        },
    ]
}

/// The sphere of centre `center` and radius `r` triangulated by an
/// octahedron whose triangles are split in four `levels` times, every new
/// vertex pushed onto the sphere (counter-clockwise seen from outside; a
/// vertex at each pole).
pub fn octahedron_sphere(center: Vec3, r: f64, levels: usize) -> Vec<[Vec3; 3]> {
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
        let mut next = Vec::with_capacity(4 * t.len());
        let mut m = |a: usize, b: usize, v: &mut Vec<Vec3>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                v.push(((v[a] + v[b]) * 0.5).normalize());
                v.len() - 1
            })
        };
        for [a, b, c] in t {
            let (ab, bc, ca) = (m(a, b, &mut v), m(b, c, &mut v), m(c, a, &mut v));
            next.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
        }
        t = next;
    }
    t.iter().map(|tri| tri.map(|k| center + v[k] * r)).collect()
}

/// Subdivisions of the octahedron sphere of `stl_sphere_3d` at each level.
const STL_LEVELS: [usize; 4] = [4, 5, 6, 7];

/// `stl_sphere_3d` — the Hertz block of `hertz_sphere_3d` (10 cells per
/// edge, area penalty) pressed by the unit sphere given as triangles: the
/// octahedron sphere ([`octahedron_sphere`]) written to an ASCII STL file
/// (`ctc_geom::trimesh::stl`, every `f64` written exactly), read back and
/// merged into a `TriMesh` (flat triangles, edges and vertices of radius 0,
/// pseudonormal sign), against the same run with the analytical sphere.
/// The triangles are chords of the sphere, inside it by up to the sagitta
/// `s = h^2 / (8 R)` (`h` the longest edge near the pole), so the tool
/// reaches `s` less deep: the force `P ~ d^(3/2)` differs by about `1.5 s
/// / d`, second order in the facet size `h` (rate >= 1.7 judged); the
/// peak pressure at the pole vertex also feels the kinks between facets.
/// The level's `h` is the facet size.
fn stl_sphere_level(level: usize) -> Result<ProgramLevel, String> {
    use ctc_geom::trimesh::{stl, TriMesh};
    let k = *STL_LEVELS
        .get(level)
        .ok_or_else(|| format!("stl_sphere_3d has no level {level}"))?;
    let n = HERTZ_DIVISIONS[0];
    let center = Vec3::new(0.0, 0.0, 2.0);
    let model = sphere_block(n, center)?;
    let triangles = octahedron_sphere(center, 1.0, k);
    let text = stl::write_ascii("sphere", &triangles);
    let corners = stl::read(text.as_bytes()).map_err(|e| e.to_string())?;
    let mesh = TriMesh::from_soup(&corners, 1e-12, Side::Outside)?;
    // facet size: the longest edge of the triangles within 0.3 of the pole
    let pole = center - Vec3::z();
    let h = triangles
        .iter()
        .filter(|t| t.iter().all(|p| (p - pole).norm() < 0.3))
        .flat_map(|t| (0..3).map(move |i| (t[i] - t[(i + 1) % 3]).norm()))
        .fold(0.0, f64::max);
    let mut faceted = model.clone();
    faceted.surfaces[0].geometry = SurfaceShape::Mesh(Arc::new(mesh));
    let measure = |m: &Model<3>| -> Result<(f64, f64, RunSummary), String> {
        let (last, s) = solve(m)?;
        let p = -last.0.iter().map(|c| c.force[2]).sum::<f64>();
        let p0 = last.0.iter().map(|c| c.pressure).fold(0.0, f64::max);
        Ok((p, p0, s))
    };
    let (pa, p0a, sa) = measure(&model)?;
    let (pf, p0f, sf) = measure(&faceted)?;
    Ok(ProgramLevel {
        figures: Vec::new(),
        values: vec![
            value("P STL vs analytical", pf, pa),
            value("p0 STL vs analytical", p0f, p0a),
        ],
        h,
        nodes: model.mesh.nodes.len(),
        free_dofs: sa.free_dofs,
        increments: sa.increments.len() + sf.increments.len(),
        newton_total: sa.newton_iterations + sf.newton_iterations,
        newton_max: sf
            .increments
            .iter()
            .map(|i| i.iterations)
            .max()
            .unwrap_or(0),
        cutbacks: sa.cutbacks + sf.cutbacks,
    })
}

/// A CAD tool from NURBS faces: written to IGES, read back, oriented from
/// the first face (`orientation` +1: `S_u x S_v` into free space).
fn iges_tool(
    faces: &[(NurbsSurface, Option<Vec<Vec<TrimCurve>>>)],
    orientation: f64,
) -> Result<SurfaceShape, String> {
    iges_tool_with(faces, orientation, BrepOptions::default())
}

/// [`iges_tool`] with the BREP options `options`.
fn iges_tool_with(
    faces: &[(NurbsSurface, Option<Vec<Vec<TrimCurve>>>)],
    orientation: f64,
    options: BrepOptions,
) -> Result<SurfaceShape, String> {
    let mut w = ctc_geom::iges::Writer::new("ctc verification: contact_3d");
    for (s, loops) in faces {
        let si = w.add_surface(s);
        if let Some(loops) = loops {
            let ids: Vec<usize> = loops.iter().map(|l| w.add_loop(si, l)).collect();
            w.add_trimmed(si, Some(ids[0]), &ids[1..]);
        }
    }
    let text = w.finish();
    let file = ctc_geom::iges::read(&text).map_err(|e| e.to_string())?;
    let faces: Vec<_> = file
        .faces()
        .map_err(|e| e.to_string())?
        .into_iter()
        .map(|f| f.face)
        .collect();
    let mut tool = BrepTool::new(faces, options)?;
    tool.orient(0, orientation)?;
    Ok(SurfaceShape::Brep(Arc::new(tool)))
}

/// The contact evaluation of the last converged increment.
#[derive(Default)]
struct LastContact(Vec<NodeContact<3>>, Vec<[f64; 3]>);

impl Observer<3> for LastContact {
    fn converged(&mut self, v: &IncrementView<'_, 3>) -> Result<(), String> {
        self.0 = v.contact.first().cloned().unwrap_or_default();
        self.1 = v.displacement.to_vec();
        Ok(())
    }
}

fn solve(model: &Model<3>) -> Result<(LastContact, RunSummary), String> {
    let mut last = LastContact::default();
    let s = run(model, &mut last).map_err(|e| e.message)?;
    if !s.completed {
        return Err("the run did not complete".into());
    }
    Ok((last, s))
}

/// The rigid block on rollers with `divisions` cells per edge (graded by
/// `grading`), slave face `zmax`, and `tool` as its master.
fn block(
    kind: CellKind,
    divisions: usize,
    grading: [Grading; 3],
    tool: Analytic,
    motion: SurfaceMotion,
    method: ContactMethod,
    increments: usize,
) -> Result<Model<3>, String> {
    let mesh = solid::brick([0.0; 3], [1.0; 3], [divisions; 3], grading, kind.linear())
        .map_err(|e| e.message)?;
    block_on(kind, mesh, tool, motion, method, increments)
}

/// [`block`] on the linear mesh `mesh` of the unit cube (sets `xmin` ..
/// `zmax`), elevated to `kind`.
fn block_on(
    kind: CellKind,
    mut mesh: ctc_engine::mesh::Mesh<3>,
    tool: Analytic,
    motion: SurfaceMotion,
    method: ContactMethod,
    increments: usize,
) -> Result<Model<3>, String> {
    // quadratic kinds: the linear brick elevated (straight midpoints)
    if kind.order() == 2 {
        mesh = ctc_engine::mesh::elevate::elevate(&mesh, kind).map_err(|e| e.message)?;
    }
    let mut b = ModelBuilder::solid()
        .elastic("m", E, NU)
        .body("block", mesh, "m")
        .surface("tool", tool, motion);
    for (set, c) in [("xmin", 0), ("ymin", 1), ("zmin", 2)] {
        let nodes = b.node_set(&format!("block.{set}"));
        b = b.fix(nodes, c);
    }
    let faces = b.face_set("block.zmax");
    Ok(
        b.contact_faces("block.zmax -> tool", "block", faces, "tool", method)
            .step("press", 1.0, increments)
            .tol(1e-11)
            .build(),
    )
}

fn lowered(d: f64) -> SurfaceMotion {
    let mut m = SurfaceMotion::fixed();
    m.translation[2] = ramp(0.0, 1.0, -d);
    m
}

/// Mean pressure of the closed nodes and their largest relative spread.
fn pressures(c: &[NodeContact<3>], slaves: usize) -> Result<(f64, f64), String> {
    let closed: Vec<f64> = c
        .iter()
        .filter(|n| n.status == ContactStatus::Closed)
        .map(|n| n.pressure)
        .collect();
    if closed.len() != slaves {
        return Err(format!(
            "{} of {slaves} slave nodes are closed in the patch test",
            closed.len()
        ));
    }
    let mean = closed.iter().sum::<f64>() / closed.len() as f64;
    let spread = closed
        .iter()
        .map(|p| ((p - mean) / mean).abs())
        .fold(0.0, f64::max);
    Ok((mean, spread))
}

fn patch_level(_level: usize) -> Result<ProgramLevel, String> {
    let k = 1e5;
    let flat = || {
        Analytic::Plane(Plane::new(Vec3::new(0.0, 0.0, 1.0), -Vec3::z(), Side::Outside).unwrap())
    };
    let penalty = ContactMethod::Penalty {
        kind: PenaltyKind::Area,
        stiffness: k,
    };
    let sigma_penalty = E * D / (1.0 + E / k);
    let sigma_exact = E * D;
    let uniform = [Grading::Uniform; 3];
    let mut values = Vec::new();
    let mut spread = 0.0f64;
    let (mut newton, mut increments, mut nodes, mut dofs) = (0, 0, 0, 0);
    let mut record = |name: &'static str, model: Model<3>, exact: f64| -> Result<(), String> {
        let (last, s) = solve(&model)?;
        let (p, sp) = pressures(&last.0, model.contacts[0].nodes.len())
            .map_err(|e| format!("{name}: {e}"))?;
        spread = spread.max(sp);
        newton += s.newton_iterations;
        increments += s.increments.len();
        nodes = nodes.max(model.mesh.nodes.len());
        dofs = dofs.max(s.free_dofs);
        values.push(value(name, p, exact));
        Ok(())
    };
    record(
        "sigma penalty hex8",
        block(
            CellKind::Hex8,
            3,
            uniform,
            flat(),
            lowered(D),
            penalty.clone(),
            2,
        )?,
        sigma_penalty,
    )?;
    record(
        "sigma penalty tet4",
        block(
            CellKind::Tet4,
            3,
            uniform,
            flat(),
            lowered(D),
            penalty.clone(),
            2,
        )?,
        sigma_penalty,
    )?;
    record(
        "sigma lagrange hex8",
        block(
            CellKind::Hex8,
            3,
            uniform,
            flat(),
            lowered(D),
            ContactMethod::Lagrange {
                formulation: LagrangeFormulation::Single,
            },
            2,
        )?,
        sigma_exact,
    )?;
    record(
        "sigma augmented hex8",
        block(
            CellKind::Hex8,
            3,
            uniform,
            flat(),
            lowered(D),
            ContactMethod::AugmentedLagrange {
                kind: PenaltyKind::Area,
                penalty: 1e4,
                tolerance: 1e-9,
                update: MultiplierUpdate::Converged,
            },
            2,
        )?,
        sigma_exact,
    )?;
    // the plane starts tilted by 0.02 rad about x and the motion rotates it
    // back about the axis through (0.5, 0.5, 1 - d)
    let theta: f64 = 0.02;
    let tilted = -Vec3::new(0.0, theta.sin(), theta.cos());
    let center = Vec3::new(0.5, 0.5, 1.0 - D);
    let plane = Analytic::Plane(Plane::new(center, tilted, Side::Outside).unwrap());
    let motion = SurfaceMotion {
        translation: std::array::from_fn(|_| TimeFunction::Constant(0.0)),
        rotation: ramp(0.0, 1.0, theta),
        axis: [1.0, 0.0, 0.0],
        center: center.into(),
    };
    record(
        "sigma rotated plane",
        block(CellKind::Hex8, 3, uniform, plane, motion, penalty, 4)?,
        sigma_penalty,
    )?;
    values.push(error("pressure spread", spread));
    Ok(ProgramLevel {
        figures: Vec::new(),
        values,
        h: 1.0 / 3.0,
        nodes,
        free_dofs: dofs,
        increments,
        newton_total: newton,
        newton_max: 0,
        cutbacks: 0,
    })
}

/// Divisions per edge of the Hertz block at each level.
const HERTZ_DIVISIONS: [usize; 3] = [10, 16, 24];

/// The Hertz enforcement methods: (method, names of its four quantities:
/// p0, profile, force, contact radius). Penalty keeps the case's original
/// names; Lagrange multipliers and the augmented Lagrangian (area penalty
/// 1e5, multipliers updated to a gap of 1e-9) run the same mesh and load.
fn hertz_methods() -> [(ContactMethod, [&'static str; 4]); 3] {
    [
        (
            ContactMethod::Penalty {
                kind: PenaltyKind::Area,
                stiffness: 1e7,
            },
            [
                "p0 vs Hertz(P)",
                "p(r < 0.7a) vs Hertz(P)",
                "P vs half-space (finite block)",
                "a from P",
            ],
        ),
        (
            ContactMethod::Lagrange {
                formulation: LagrangeFormulation::Single,
            },
            [
                "p0 vs Hertz(P) lagrange",
                "p(r < 0.7a) vs Hertz(P) lagrange",
                "P vs half-space (finite block) lagrange",
                "a from P lagrange",
            ],
        ),
        (
            ContactMethod::AugmentedLagrange {
                kind: PenaltyKind::Area,
                penalty: 1e5,
                tolerance: 1e-9,
                update: MultiplierUpdate::Converged,
            },
            [
                "p0 vs Hertz(P) augmented",
                "p(r < 0.7a) vs Hertz(P) augmented",
                "P vs half-space (finite block) augmented",
                "a from P augmented",
            ],
        ),
    ]
}

/// One Hertz run: the model at `n` divisions with `method`; (values under
/// `names`, summary, nodes, wall seconds).
fn hertz_run(
    n: usize,
    names: [&'static str; 4],
    method: ContactMethod,
) -> Result<(Vec<crate::measure::Value>, RunSummary, usize, f64), String> {
    hertz_run_on(CellKind::Hex8, n, names, method)
}

/// [`hertz_run`] on cells of `kind` (hex8, or hex20 / hex27: the graded
/// brick elevated; `quadratic_contact.rs`).
pub(crate) fn hertz_run_on(
    kind: CellKind,
    n: usize,
    names: [&'static str; 4],
    method: ContactMethod,
) -> Result<(Vec<crate::measure::Value>, RunSummary, usize, f64), String> {
    let f = hertz_figures_on(kind, n, method)?;
    let values = vec![
        value(names[0], f.p0, f.p0_hertz),
        error(names[1], f.profile),
        value(names[2], f.force, f.force_half_space),
        super::value(names[3], f.a_hertz, (HERTZ_R * D).sqrt()),
    ];
    Ok((values, f.summary, f.nodes, f.seconds))
}

/// Radius of the rigid sphere of the 3D Hertz runs.
const HERTZ_R: f64 = 1.0;

/// What one 3D Hertz run measured (the rigid sphere of radius
/// [`HERTZ_R`] lowered by `D` into the graded block, quarter model).
pub(crate) struct HertzFigures {
    /// The carried force (4 x the quarter's contact forces).
    pub force: f64,
    /// The half-space's force at the approach `D` (the finite block is
    /// about 9 % stiffer).
    pub force_half_space: f64,
    /// Hertz's contact radius at the carried force.
    pub a_hertz: f64,
    /// The contact radius from the first moment of the nodal contact
    /// forces, `16 / (3 pi) sum f r / sum f` (the ratio of Hertz's
    /// pressure over the disc).
    pub a_moment: f64,
    /// Hertz's peak pressure at the carried force.
    pub p0_hertz: f64,
    /// The reported pressure of the slave node nearest the axis.
    pub p0: f64,
    /// Largest `|p - p_H(r)| / p0` of a slave node inside `0.7 a`.
    pub profile: f64,
    /// L2 error of the reported pressure field over the quarter disc `r <
    /// 1.5 a` ([`pressure_l2`]), relative to `p0` and the disc of radius
    /// `a`.
    pub l2: f64,
    /// The run's summary.
    pub summary: RunSummary,
    /// Mesh nodes.
    pub nodes: usize,
    /// Solve wall time, seconds.
    pub seconds: f64,
}

/// The rigid sphere into the block of `kind` on `n` graded divisions
/// (the scene of `hertz_sphere_3d`), measured against Hertz at the
/// carried force.
pub(crate) fn hertz_figures_on(
    kind: CellKind,
    n: usize,
    method: ContactMethod,
) -> Result<HertzFigures, String> {
    let grading = [
        Grading::Geometric { ratio: 8.0 },
        Grading::Geometric { ratio: 8.0 },
        Grading::Geometric { ratio: 0.125 },
    ];
    let mesh =
        solid::brick([0.0; 3], [1.0; 3], [n; 3], grading, kind.linear()).map_err(|e| e.message)?;
    hertz_figures_on_mesh(kind, mesh, method, 4)
}

/// [`hertz_figures_on`] on the linear mesh `mesh` of the unit cube (sets
/// `xmin` .. `zmax`; the contact at its corner `(0, 0, 1)`), elevated to
/// `kind`, the approach applied in `increments` equal increments.
pub(crate) fn hertz_figures_on_mesh(
    kind: CellKind,
    mesh: ctc_engine::mesh::Mesh<3>,
    method: ContactMethod,
    increments: usize,
) -> Result<HertzFigures, String> {
    let ball = Analytic::Sphere(
        Sphere::new(Vec3::new(0.0, 0.0, 1.0 + HERTZ_R), HERTZ_R, Side::Outside).unwrap(),
    );
    let model = block_on(kind, mesh, ball, lowered(D), method, increments)?;
    let start = std::time::Instant::now();
    let (last, s) = solve(&model)?;
    let seconds = start.elapsed().as_secs_f64();
    let e_star = E / (1.0 - NU * NU);
    let p_total = -4.0 * last.0.iter().map(|c| c.force[2]).sum::<f64>();
    let a = (3.0 * p_total * HERTZ_R / (4.0 * e_star)).cbrt();
    let p0 = 3.0 * p_total / (2.0 * PI * a * a);
    let hertz = |r: f64| p0 * (1.0 - (r / a).powi(2)).max(0.0).sqrt();
    let x = |c: &NodeContact<3>| {
        let x0 = model.mesh.nodes[c.node];
        let u = last.1[c.node];
        [x0[0] + u[0], x0[1] + u[1]]
    };
    let radius = |c: &NodeContact<3>| {
        let p = x(c);
        p[0].hypot(p[1])
    };
    let axis = last
        .0
        .iter()
        .min_by(|a, b| radius(a).total_cmp(&radius(b)))
        .ok_or("no slave node was evaluated")?;
    let profile = last
        .0
        .iter()
        .filter(|c| radius(c) < 0.7 * a)
        .map(|c| ((c.pressure - hertz(radius(c))) / p0).abs())
        .fold(0.0, f64::max);
    let (moment, fz) = last.0.iter().fold((0.0, 0.0), |(m, f), c| {
        (m - c.force[2] * radius(c), f - c.force[2])
    });
    let mut pressure = vec![0.0; model.mesh.nodes.len()];
    for c in &last.0 {
        pressure[c.node] = c.pressure;
    }
    let l2 = pressure_l2(&model, &pressure, &hertz, 1.5 * a) / (0.25 * PI * a * a).sqrt() / p0;
    Ok(HertzFigures {
        force: p_total,
        force_half_space: 4.0 / 3.0 * e_star * HERTZ_R.sqrt() * D.powf(1.5),
        a_hertz: a,
        a_moment: 16.0 / (3.0 * PI) * moment / fz,
        p0_hertz: p0,
        p0: axis.pressure,
        profile,
        l2,
        summary: s,
        nodes: model.mesh.nodes.len(),
        seconds,
    })
}

/// `sqrt(int (p_h - p_H(r))^2 dA)` over the part `r < extent` (reference
/// radius from the z axis) of the first pair's slave faces, `p_h` the
/// nodal pressures `pressure` interpolated by each face's shape functions
/// (quad4, quad8, quad9; the field the nodal output describes), by 6 x 6
/// Gauss points per face (the pressure's square-root edge is not
/// polynomial).
fn pressure_l2(
    model: &Model<3>,
    pressure: &[f64],
    reference: &dyn Fn(f64) -> f64,
    extent: f64,
) -> f64 {
    use ctc_engine::element::reference::{Quad4, Quad8, Quad9, ReferenceCell};
    const G: [(f64, f64); 6] = [
        (-0.932_469_514_203_152, 0.171_324_492_379_170_3),
        (-0.661_209_386_466_264_5, 0.360_761_573_048_138_6),
        (-0.238_619_186_083_196_9, 0.467_913_934_572_691),
        (0.238_619_186_083_196_9, 0.467_913_934_572_691),
        (0.661_209_386_466_264_5, 0.360_761_573_048_138_6),
        (0.932_469_514_203_152, 0.171_324_492_379_170_3),
    ];
    let mut sum = 0.0;
    for face in model.contacts.first().map_or(&[][..], |c| &c.faces[..]) {
        let nodes = face.nodes();
        for (xi, wx) in G {
            for (eta, wy) in G {
                let q = [xi, eta];
                let (n, g): (Vec<f64>, Vec<[f64; 2]>) = match nodes.len() {
                    4 => (Quad4::shape(&q).to_vec(), Quad4::gradients(&q).to_vec()),
                    8 => (Quad8::shape(&q).to_vec(), Quad8::gradients(&q).to_vec()),
                    9 => (Quad9::shape(&q).to_vec(), Quad9::gradients(&q).to_vec()),
                    _ => continue,
                };
                let (mut x, mut t, mut p) = ([0.0; 3], [[0.0; 3]; 2], 0.0);
                for (a, &node) in nodes.iter().enumerate() {
                    let xa = model.mesh.nodes[node];
                    for c in 0..3 {
                        x[c] += n[a] * xa[c];
                        t[0][c] += g[a][0] * xa[c];
                        t[1][c] += g[a][1] * xa[c];
                    }
                    p += n[a] * pressure[node];
                }
                let r = x[0].hypot(x[1]);
                if r >= extent {
                    continue;
                }
                let [t1, t2] = t;
                let area = Vec3::from(t1).cross(&Vec3::from(t2)).norm();
                sum += wx * wy * area * (p - reference(r)).powi(2);
            }
        }
    }
    sum.sqrt()
}

/// The work-precision table of `hertz_sphere_3d` at `level`: per method,
/// the p0 error against Hertz at the carried force, Newton iterations and
/// wall seconds of the solve (`cargo test -p ctc-verification --test
/// contact_3d hertz_methods -- --nocapture` prints it).
pub fn hertz_work_precision(level: usize) -> Result<Vec<(String, f64, usize, f64)>, String> {
    let n = *HERTZ_DIVISIONS
        .get(level)
        .ok_or_else(|| format!("hertz_sphere_3d has no level {level}"))?;
    hertz_methods()
        .into_iter()
        .map(|(method, names)| {
            let label = match method {
                ContactMethod::Lagrange { .. } => "lagrange",
                ContactMethod::AugmentedLagrange { .. } => "augmented",
                _ => "penalty",
            };
            let (values, s, _, seconds) = hertz_run(n, names, method)?;
            Ok((
                label.to_string(),
                values[0].error,
                s.newton_iterations,
                seconds,
            ))
        })
        .collect()
}

fn hertz_level(level: usize) -> Result<ProgramLevel, String> {
    let n = *HERTZ_DIVISIONS
        .get(level)
        .ok_or_else(|| format!("hertz_sphere_3d has no level {level}"))?;
    let mut out: Option<ProgramLevel> = None;
    for (method, names) in hertz_methods() {
        let (values, s, nodes, _) = hertz_run(n, names, method)?;
        match out.as_mut() {
            None => {
                out = Some(ProgramLevel {
                    figures: Vec::new(),
                    values,
                    h: 1.0 / n as f64,
                    nodes,
                    free_dofs: s.free_dofs,
                    increments: s.increments.len(),
                    newton_total: s.newton_iterations,
                    newton_max: s.increments.iter().map(|i| i.iterations).max().unwrap_or(0),
                    cutbacks: s.cutbacks,
                })
            }
            Some(o) => o.values.extend(values),
        }
    }
    out.ok_or_else(|| "no method ran".to_string())
}

/// A flat bicubic patch over `[-0.5, 1.5]^2` at `z = 1` whose control
/// points are spaced unevenly along each direction (a non-affine
/// parametrization of the plane: the foot needs Newton iterations).
fn flat_bicubic() -> Result<NurbsSurface, String> {
    let t = [0.0, 0.1, 0.6, 1.0];
    let mut points = Vec::new();
    // u runs fastest in the control net: S_u along x, S_v along y, S_u x S_v = +z
    for &b in &t {
        for &a in &t {
            points.push(Vec3::new(-0.5 + 2.0 * a, -0.5 + 2.0 * b, 1.0));
        }
    }
    let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    NurbsSurface::new(
        [3, 3],
        [4, 4],
        [knots.clone(), knots],
        points,
        vec![1.0; 16],
    )
}

fn cad_patch_level(_level: usize) -> Result<ProgramLevel, String> {
    let k = 1e5;
    let penalty = ContactMethod::Penalty {
        kind: PenaltyKind::Area,
        stiffness: k,
    };
    let sigma_penalty = E * D / (1.0 + E / k);
    let uniform = [Grading::Uniform; 3];
    // S_u x S_v = +z: the free side (the block, below) is the other one
    let flat = iges_tool(&[(flat_bicubic()?, None)], -1.0)?;
    let model = block(
        CellKind::Hex8,
        3,
        uniform,
        Analytic::Plane(Plane::new(Vec3::zeros(), Vec3::z(), Side::Outside).unwrap()),
        lowered(D),
        penalty.clone(),
        2,
    )?;
    let with = |m: &Model<3>, tool: &SurfaceShape| {
        let mut m = m.clone();
        m.surfaces[0].geometry = tool.clone();
        m
    };
    let m = with(&model, &flat);
    let (last, s1) = solve(&m)?;
    let (p, spread) = pressures(&last.0, m.contacts[0].nodes.len())?;
    // the same plate trimmed by a hole of radius 0.25 (0.125 in the
    // parameter square) around (0.5, 0.5)
    let v = Vec2::new;
    let outer = vec![
        TrimCurve::line(v(0.0, 0.0), v(1.0, 0.0))?,
        TrimCurve::line(v(1.0, 0.0), v(1.0, 1.0))?,
        TrimCurve::line(v(1.0, 1.0), v(0.0, 1.0))?,
        TrimCurve::line(v(0.0, 1.0), v(0.0, 0.0))?,
    ];
    let hole = vec![TrimCurve::arc(
        v(0.5, 0.5),
        0.125,
        0.0,
        -std::f64::consts::TAU,
    )?];
    let plate = build::plane_patch(
        Vec3::new(-0.5, -0.5, 1.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 2.0, 0.0),
    );
    let holed = iges_tool(&[(plate, Some(vec![outer, hole]))], -1.0)?;
    let m2 = with(&model, &holed);
    let (last2, s2) = solve(&m2)?;
    let (mut open_in, mut closed_out, mut under) = (0usize, 0usize, 0usize);
    for &n in &m2.contacts[0].nodes {
        let x = m2.mesh.nodes[n];
        let r = (x[0] - 0.5).hypot(x[1] - 0.5);
        let closed = last2
            .0
            .iter()
            .any(|c| c.node == n && c.status == ContactStatus::Closed);
        if r < 0.25 {
            under += 1;
            open_in += usize::from(!closed);
        } else {
            closed_out += usize::from(closed);
        }
    }
    let around = m2.contacts[0].nodes.len() - under;
    Ok(ProgramLevel {
        figures: Vec::new(),
        values: vec![
            value("sigma flat NURBS face", p, sigma_penalty),
            error("pressure spread", spread),
            value("open nodes under the hole", open_in as f64, under as f64),
            value(
                "closed nodes around the hole",
                closed_out as f64,
                around as f64,
            ),
        ],
        h: 1.0 / 3.0,
        nodes: m.mesh.nodes.len(),
        free_dofs: s1.free_dofs,
        increments: s1.increments.len() + s2.increments.len(),
        newton_total: s1.newton_iterations + s2.newton_iterations,
        newton_max: 0,
        cutbacks: s1.cutbacks + s2.cutbacks,
    })
}

/// The Hertz block of `cad_sphere_3d` (10 cells per edge) against the
/// IGES rational NURBS sphere whose surface projections use `projection`
/// (the health figures of `summary.json`: with too few Newton iterations
/// the projections do not converge, the nodes are left out and the run
/// warns).
pub fn nurbs_sphere_block(projection: ctc_geom::nurbs::ProjectOptions) -> Result<Model<3>, String> {
    let center = Vec3::new(0.0, 0.0, 2.0);
    let grading = [
        Grading::Geometric { ratio: 8.0 },
        Grading::Geometric { ratio: 8.0 },
        Grading::Geometric { ratio: 0.125 },
    ];
    let method = ContactMethod::Penalty {
        kind: PenaltyKind::Area,
        stiffness: 1e7,
    };
    let exact = Analytic::Sphere(Sphere::new(center, 1.0, Side::Outside).unwrap());
    let mut model = block(
        CellKind::Hex8,
        HERTZ_DIVISIONS[0],
        grading,
        exact,
        lowered(D),
        method,
        4,
    )?;
    let options = BrepOptions {
        projection,
        ..BrepOptions::default()
    };
    model.surfaces[0].geometry =
        iges_tool_with(&[(build::sphere(center, 1.0), None)], 1.0, options)?;
    Ok(model)
}

/// The coarsest Hertz block (`n` divisions, graded towards the contact)
/// pressed by the analytical unit sphere centred at `center` (area penalty
/// 1e7): the reference of the CAD and STL sphere cases, which swap the tool.
fn sphere_block(n: usize, center: Vec3) -> Result<Model<3>, String> {
    let grading = [
        Grading::Geometric { ratio: 8.0 },
        Grading::Geometric { ratio: 8.0 },
        Grading::Geometric { ratio: 0.125 },
    ];
    let method = ContactMethod::Penalty {
        kind: PenaltyKind::Area,
        stiffness: 1e7,
    };
    let exact = Analytic::Sphere(Sphere::new(center, 1.0, Side::Outside).unwrap());
    block(CellKind::Hex8, n, grading, exact, lowered(D), method, 4)
}

fn cad_sphere_level(_level: usize) -> Result<ProgramLevel, String> {
    let n = HERTZ_DIVISIONS[0];
    let center = Vec3::new(0.0, 0.0, 2.0);
    let model = sphere_block(n, center)?;
    let mut cad = model.clone();
    cad.surfaces[0].geometry = iges_tool(&[(build::sphere(center, 1.0), None)], 1.0)?;
    let measure = |m: &Model<3>| -> Result<(f64, f64, RunSummary), String> {
        let (last, s) = solve(m)?;
        let p = -last.0.iter().map(|c| c.force[2]).sum::<f64>();
        let p0 = last.0.iter().map(|c| c.pressure).fold(0.0, f64::max);
        Ok((p, p0, s))
    };
    let (pa, p0a, sa) = measure(&model)?;
    let (pc, p0c, sc) = measure(&cad)?;
    Ok(ProgramLevel {
        figures: Vec::new(),
        values: vec![
            value("P NURBS vs analytical", pc, pa),
            value("p0 NURBS vs analytical", p0c, p0a),
        ],
        h: 1.0 / n as f64,
        nodes: model.mesh.nodes.len(),
        free_dofs: sa.free_dofs,
        increments: sa.increments.len() + sc.increments.len(),
        newton_total: sa.newton_iterations + sc.newton_iterations,
        newton_max: sc
            .increments
            .iter()
            .map(|i| i.iterations)
            .max()
            .unwrap_or(0),
        cutbacks: sa.cutbacks + sc.cutbacks,
    })
}
