//! Follower pressure at finite strain (`pressure .. { follower = true }`,
//! `ctc_engine::solve::follower`): the hydrostatic patch test. A
//! neo-Hookean block loaded by the pressure `p` on every face that is not
//! a symmetry plane is compressed homogeneously; a pressure that follows
//! the deformed surface gives the Cauchy stress `sigma = -p I` exactly,
//! whatever the law and the stretch (equilibrium of the deformed block:
//! the force on a face is `p` times its current area). A dead pressure
//! (on the reference surface) gives the nominal stress `-p` instead, i.e.
//! `sigma = -p / lambda` per stretched face: its error is reported (not
//! judged) to show the test tells them apart. Planar variants: plane
//! strain (`sigma_xx = sigma_yy = -p`, `sigma_xy = 0`), axisymmetric
//! (`sigma_rr = sigma_zz = sigma_tt = -p`: the outer radius and the top
//! loaded, the axis and the base held). Newton must converge
//! quadratically: the load stiffness is exact (its finite-difference check
//! is a unit test of `solve::follower`).
//! Source: Bonet & Wood, Nonlinear Continuum Mechanics for Finite Element
//! Analysis, 2nd ed., §8.4.2 (follower pressure and its linearization);
//! the patch test of Zienkiewicz & Taylor vol. 1 §9.
//!
//! ```text
//!          p (follows the face)
//!      +---------+
//!      |         |  <- p         x = 0, y = 0 (z = 0): symmetry planes
//!      |  block  |               graded mesh, p = E / 4
//!      +---------+
//!   ///////////////
//! ```

use super::error;
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::geom::Dimension;
use ctc_engine::mesh::generate::{generate, solid, Grading, MeshSpec};
use ctc_engine::mesh::{CellKind, Facet, Mesh};
use ctc_engine::model::{Kinematics, Load, MaterialLaw, Model, TimeFunction};
use ctc_engine::solve::{run, IncrementView, Observer, RunSummary};
use ctc_engine::testkit::ModelBuilder;
use nalgebra::Const;

/// Young's modulus and Poisson's ratio of the block.
const E: f64 = 1000.0;
const NU: f64 = 0.3;
/// The pressure: a large compression (stretches about 0.85 in 3D).
const P: f64 = 0.25 * E;

/// Quantities: (follower error, dead-load error (not judged)) per scene.
const SCENES: [(&str, &str); 3] = [
    (
        "hex8: max |sigma + p I| / p, follower",
        "hex8: max |sigma + p I| / p, dead pressure (not judged)",
    ),
    (
        "quad4 plane strain: max |sigma_in-plane + p I| / p, follower",
        "quad4 plane strain: max |sigma_in-plane + p I| / p, dead pressure (not judged)",
    ),
    (
        "quad4 axisymmetric: max |sigma + p I| / p, follower",
        "quad4 axisymmetric: max |sigma + p I| / p, dead pressure (not judged)",
    ),
];

/// The catalogue entry.
pub fn cases() -> Vec<VerifyCase> {
    // the dead-pressure errors and the iterations are reported, not judged
    let checks = SCENES
        .iter()
        .map(|(follower, _)| Check::new(Quantity::Named(follower), &[1e-10]))
        .collect();
    vec![VerifyCase {
        name: "follower_pressure_patch",
        title: "Follower pressure at finite strain: hydrostatic patch test, sigma = -p I \
                exactly on the deformed block (hex8, plane strain, axisymmetric); the dead \
                pressure differs by the stretch",
        source: "Bonet & Wood, Nonlinear Continuum Mechanics for FE Analysis, §8.4.2",
        tags: &[
            "finite_strain",
            "loads",
            "follower",
            "patch",
            "exact",
            "3d",
            "plane_strain",
            "axisymmetric",
        ],
        levels: 1,
        checks,
        kind: CaseKind::Program(ProgramCase {
            max_levels: 1,
            run: level,
        }),
    }]
}

/// The Cauchy stress of every integration point of the last increment.
#[derive(Default)]
struct Stresses(Vec<[f64; 6]>);

impl<const D: usize> Observer<D> for Stresses
where
    Const<D>: Dimension<D>,
{
    fn converged(&mut self, v: &IncrementView<'_, D>) -> Result<(), String> {
        self.0 = v
            .points
            .iter()
            .flatten()
            .map(|p| std::array::from_fn(|k| p.state.stress[k]))
            .collect();
        Ok(())
    }
}

/// `max |sigma_ij + p delta_ij| / p` over the points and the components
/// `components` (Voigt `[xx, yy, zz, xy, xz, yz]`).
fn hydrostatic_error(stresses: &[[f64; 6]], components: &[usize]) -> f64 {
    stresses
        .iter()
        .flat_map(|s| {
            components
                .iter()
                .map(move |&k| (s[k] + if k < 3 { P } else { 0.0 }).abs())
        })
        .fold(0.0, f64::max)
        / P
}

/// Runs `model` and returns its summary and stresses.
fn solve<const D: usize>(model: &Model<D>) -> Result<(RunSummary, Vec<[f64; 6]>), String>
where
    Const<D>: Dimension<D>,
{
    let mut s = Stresses::default();
    let summary = run(model, &mut s).map_err(|e| e.message)?;
    Ok((summary, s.0))
}

/// The block `mesh` of `builder`'s kind, held on the symmetry sets
/// `(set, component)`, under the pressure on `loaded` (follower or dead).
fn block<const D: usize>(
    builder: ModelBuilder<D>,
    mesh: Mesh<D>,
    held: &[(&str, usize)],
    loaded: Vec<Facet>,
    follower: bool,
) -> Model<D>
where
    Const<D>: Dimension<D>,
{
    let mut b = builder
        .material(
            "rubber",
            MaterialLaw::NeoHookean {
                young: E,
                poisson: NU,
            },
        )
        .body("block", mesh, "rubber")
        .kinematics(Kinematics::Finite);
    for &(set, c) in held {
        let nodes = b.node_set(&format!("block.{set}"));
        b = b.fix(nodes, c);
    }
    let value = TimeFunction::Ramp {
        t0: 0.0,
        t1: 1.0,
        v0: 0.0,
        v1: P,
    };
    let label = "pressure block".to_string();
    let load = if follower {
        Load::FollowerPressure {
            label,
            facets: loaded,
            value,
            control: None,
        }
    } else if D == 3 {
        Load::FacetPressure {
            label,
            facets: loaded,
            value,
        }
    } else {
        Load::Pressure {
            label,
            edges: loaded.iter().map(Facet::edge).collect(),
            value,
        }
    };
    b.load(load).step("press", 1.0, 4).build()
}

fn level(_level: usize) -> Result<ProgramLevel, String> {
    let mut values = Vec::new();
    let mut newton_max = 0;
    let mut out: Option<ProgramLevel> = None;
    let mut record = |summary: &RunSummary, nodes: usize| {
        let m = summary
            .increments
            .iter()
            .map(|i| i.iterations)
            .max()
            .unwrap_or(0);
        newton_max = newton_max.max(m);
        let level = out.get_or_insert(ProgramLevel {
            figures: Vec::new(),
            values: Vec::new(),
            h: 0.0,
            nodes: 0,
            free_dofs: 0,
            increments: 0,
            newton_total: 0,
            newton_max: 0,
            cutbacks: 0,
        });
        level.nodes += nodes;
        level.free_dofs += summary.free_dofs;
        level.increments += summary.increments.len();
        level.newton_total += summary.newton_iterations;
        level.newton_max = level.newton_max.max(m);
        level.cutbacks += summary.cutbacks;
    };
    // 3D: a graded 3 x 2 x 2 hex8 brick, pressure on x, y, z = max
    let brick = solid::brick(
        [0.0; 3],
        [1.0, 0.8, 0.6],
        [3, 2, 2],
        [
            Grading::Geometric { ratio: 2.0 },
            Grading::Uniform,
            Grading::Center { ratio: 2.0 },
        ],
        CellKind::Hex8,
    )
    .map_err(|e| e.message)?;
    for follower in [true, false] {
        let builder = ModelBuilder::solid();
        let mut faces = Vec::new();
        for set in ["xmax", "ymax", "zmax"] {
            faces.extend(
                brick
                    .face_sets
                    .get(set)
                    .ok_or(format!("brick has no `{set}`"))?
                    .iter()
                    .copied(),
            );
        }
        let model = block(
            builder,
            brick.clone(),
            &[("xmin", 0), ("ymin", 1), ("zmin", 2)],
            faces.clone(),
            follower,
        );
        let (summary, stresses) = solve(&model)?;
        record(&summary, model.mesh.nodes.len());
        let name = if follower { SCENES[0].0 } else { SCENES[0].1 };
        values.push(error(
            name,
            hydrostatic_error(&stresses, &[0, 1, 2, 3, 4, 5]),
        ));
    }
    // planar: a graded 3 x 2 quad4 rectangle, pressure on `right` and `top`
    let planar = generate(&MeshSpec::Rectangle {
        origin: [0.0, 0.0],
        size: [1.0, 0.7],
        divisions: [3, 2],
        grading: [Grading::Geometric { ratio: 2.0 }, Grading::Uniform],
        kind: CellKind::Quad4,
    })
    .map_err(|e| e.message)?;
    let mut edges = Vec::new();
    for set in ["right", "top"] {
        edges.extend(
            planar
                .edge_sets
                .get(set)
                .ok_or(format!("rectangle has no `{set}`"))?
                .iter()
                .map(|&e| Facet::new(&e)),
        );
    }
    for (scene, components) in [(1, &[0usize, 1, 3][..]), (2, &[0, 1, 2, 3][..])] {
        for follower in [true, false] {
            let builder = if scene == 1 {
                ModelBuilder::plane_strain()
            } else {
                ModelBuilder::axisymmetric()
            };
            let model = block(
                builder,
                planar.clone(),
                &[("left", 0), ("bottom", 1)],
                edges.clone(),
                follower,
            );
            let (summary, stresses) = solve(&model)?;
            record(&summary, model.mesh.nodes.len());
            let name = if follower {
                SCENES[scene].0
            } else {
                SCENES[scene].1
            };
            values.push(error(name, hydrostatic_error(&stresses, components)));
        }
    }
    values.push(error(
        "Newton iterations per increment (max)",
        newton_max as f64,
    ));
    let mut out = out.ok_or("no run")?;
    out.values = values;
    Ok(out)
}
