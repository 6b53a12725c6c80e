//! End-to-end compilation of valid decks: the lowered model's contents and
//! the `explain` plan (snapshot).

use ctc_engine::mesh::CellKind;
use ctc_engine::model::{
    AnalysisKind, ContactMethod, Formulation, HistoryRequest, Load, MaterialLaw, OutputRequest,
    PenaltyKind, TimeFunction, ToolGeometry, ToolSide,
};
use ctc_lang::{check, compile, explain, Source};

fn deck(name: &str) -> Source {
    Source::read(format!("tests/decks/{name}.ctc")).expect("deck")
}

#[test]
fn brief_deck_lowers_every_construct() {
    let src = deck("brief");
    let c = check(&src);
    let m = c
        .model
        .as_ref()
        .unwrap_or_else(|| panic!("{}", c.diagnostics.render(&src)));
    // One warning: fix block.clamp and displace block.left share a corner node.
    assert_eq!(c.diagnostics.warning_count(), 1);
    assert_eq!(m.analysis.kind, AnalysisKind::PlaneStrain);
    assert_eq!(m.analysis.thickness, 1.0);
    // 40 x 20 quads.
    assert_eq!(m.mesh.nodes.len(), 41 * 21);
    assert_eq!(m.mesh.cells.len(), 800);
    assert!(m.mesh.cells.iter().all(|c| c.kind == CellKind::Quad4));
    assert_eq!(m.bodies[0].nodes, 0..861);
    assert_eq!(m.bodies[0].formulation, Formulation::Full);
    assert_eq!(
        m.materials[0].law,
        MaterialLaw::LinearElastic {
            young: 210e3,
            poisson: 0.3
        }
    );
    // Qualified sets, built-in sets, deck sets.
    for s in ["block.top", "block.bottom", "block.boundary", "block.load"] {
        assert!(m.mesh.edge_sets.contains_key(s), "{s}");
        assert!(m.mesh.node_sets.contains_key(s), "{s}");
    }
    assert_eq!(m.mesh.node_sets["block.all"].len(), 861);
    assert_eq!(m.mesh.node_sets["block.clamp"].len(), 41);
    assert!(!m.mesh.edge_sets.contains_key("block.clamp"));
    // Dirichlet: one entry per component.
    let comps: Vec<(String, usize)> = m
        .constraints
        .iter()
        .map(|d| (d.label.clone(), d.component))
        .collect();
    assert_eq!(
        comps,
        [
            ("fix block.clamp".to_string(), 0),
            ("fix block.clamp".to_string(), 1),
            ("displace block.left".to_string(), 0)
        ]
    );
    assert!(m.mesh.node_sets["block.clamp"]
        .iter()
        .all(|&n| m.mesh.nodes[n][1] == -4.0));
    // ramp(v0, v1) spans the whole analysis: first step start .. last step end.
    assert_eq!(
        m.constraints[2].value,
        TimeFunction::Ramp {
            t0: 0.0,
            t1: 1.5,
            v0: 0.0,
            v1: -0.05
        }
    );
    assert_eq!(m.constraints[0].value, TimeFunction::Constant(0.0));
    match &m.loads[1] {
        Load::NodalForce {
            nodes,
            component,
            value,
            ..
        } => {
            assert_eq!(nodes.len(), 1);
            assert_eq!(m.mesh.nodes[nodes[0]], [0.0, 0.0]);
            assert_eq!(*component, 1);
            assert_eq!(*value, TimeFunction::Constant(-1.0));
        }
        l => panic!("{l:?}"),
    }
    match &m.loads[2] {
        Load::Pressure { edges, value, .. } => {
            assert!(!edges.is_empty());
            assert!(edges
                .iter()
                .flatten()
                .all(|&n| m.mesh.nodes[n][0].abs() <= 1.0 + 1e-12));
            assert_eq!(
                *value,
                TimeFunction::Table(vec![(0.0, 0.0), (0.5, 1.0), (1.0, 0.0)])
            );
        }
        l => panic!("{l:?}"),
    }
    // Tools.
    assert_eq!(
        m.tools[0].geometry,
        ToolGeometry::Circle {
            center: [0.0, 1.0],
            radius: 1.0,
            side: ToolSide::Outside
        }
    );
    assert_eq!(m.tools[0].motion.center, [0.0, 1.0]);
    assert_eq!(m.tools[0].motion.uy.eval(1.5), -0.02);
    // Contact pairs: nodes = sorted distinct nodes of the edges.
    let top = &m.contacts[0];
    assert_eq!(top.name, "block.top -> punch");
    assert_eq!(top.edges.len(), 40);
    let mut expect: Vec<usize> = top.edges.iter().flatten().copied().collect();
    expect.sort_unstable();
    expect.dedup();
    assert_eq!(top.nodes, expect);
    assert_eq!(top.prof, Some(0.5));
    assert_eq!(
        top.method,
        ContactMethod::Penalty {
            kind: PenaltyKind::Area,
            stiffness: 1e4
        }
    );
    assert_eq!(m.contacts[1].prof, None);
    assert_eq!(m.contacts[1].master.tool(), Some(1));
    // Steps: contiguous, defaults filled in.
    assert_eq!((m.steps[0].t_start, m.steps[0].t_end), (0.0, 1.0));
    assert_eq!((m.steps[1].t_start, m.steps[1].t_end), (1.0, 1.5));
    assert_eq!(m.steps[0].min_fraction, 1e-3);
    assert_eq!(m.steps[1].min_fraction, 1.0 / 1024.0);
    assert_eq!(m.steps[0].newton.tol, 1e-9);
    assert_eq!(m.steps[0].newton.max_iter, 20);
    assert_eq!(m.steps[1].newton.max_iter, 25);
    // Output.
    assert_eq!(m.output.fields.len(), 6);
    assert!(
        matches!(&m.output.history[2], HistoryRequest::ContactForce { pair: 0, label } if label == "contact_force(block.top -> punch)")
    );
}

#[test]
fn generators_tools_and_mesh_files_lower() {
    let src = deck("axisymmetric_tools");
    let m = compile(&src).unwrap_or_else(|d| panic!("{}", d.render(&src)));
    assert_eq!(m.analysis.kind, AnalysisKind::Axisymmetric);
    assert_eq!(m.bodies.len(), 4);
    // Bodies are contiguous, in deck order.
    for w in m.bodies.windows(2) {
        assert_eq!(w[0].nodes.end, w[1].nodes.start);
        assert_eq!(w[0].cells.end, w[1].cells.start);
    }
    assert_eq!(m.bodies[0].formulation, Formulation::SelectiveReduced);
    // Only used materials, in order of first use.
    let names: Vec<&str> = m.materials.iter().map(|x| x.name.as_str()).collect();
    assert_eq!(names, ["rubber", "steel"]);
    assert_eq!(m.bodies[1].material, 1);
    assert!(m.bodies[1]
        .cells
        .clone()
        .all(|c| m.mesh.cells.kind(c) == CellKind::Tri3));
    // The gmsh body: 6 nodes, 2 quads, physical groups as qualified sets.
    let strip = &m.bodies[3];
    assert_eq!(strip.nodes.len(), 6);
    assert_eq!(strip.cells.len(), 2);
    assert_eq!(m.mesh.edge_sets["strip.bottom"].len(), 2);
    assert!(m.mesh.node_sets.contains_key("strip.domain"));
    assert!(m.mesh.edge_sets["strip.bottom"]
        .iter()
        .flatten()
        .all(|n| strip.nodes.contains(n)));
    // Tools: unit plane normal, arc in radians, open uniform knots, unit weights.
    assert_eq!(
        m.tools[0].geometry,
        ToolGeometry::Plane {
            point: [0.0, 0.0],
            normal: [0.0, 1.0]
        }
    );
    match &m.tools[2].geometry {
        ToolGeometry::Arc {
            start_angle,
            end_angle,
            ..
        } => {
            assert_eq!(*start_angle, 0.0);
            assert!((end_angle - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        }
        g => panic!("{g:?}"),
    }
    // Rotation is in radians as written, about the arc's centre by default.
    assert_eq!(m.tools[2].motion.rotation.eval(2.0), 0.1);
    assert_eq!(m.tools[2].motion.center, [10.0, 0.0]);
    match &m.tools[3].geometry {
        ToolGeometry::Nurbs { knots, weights, .. } => {
            assert_eq!(knots, &vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
            assert_eq!(weights, &vec![1.0, 0.8, 1.0]);
        }
        g => panic!("{g:?}"),
    }
    match &m.tools[4].geometry {
        ToolGeometry::Nurbs { knots, weights, .. } => {
            assert_eq!(knots, &vec![0.0, 0.0, 0.5, 1.0, 1.0]);
            assert_eq!(weights, &vec![1.0; 3]);
        }
        g => panic!("{g:?}"),
    }
    // No output block: the default request.
    assert_eq!(m.output, OutputRequest::default());
    assert_eq!(m.contacts.len(), 5);
    assert_eq!(
        m.contacts[1].method,
        ContactMethod::Penalty {
            kind: PenaltyKind::Nodal,
            stiffness: 1e3
        }
    );
}

#[test]
fn explain_brief_deck() {
    let m = compile(&deck("brief")).expect("compiles");
    insta::assert_snapshot!("explain_brief", explain(&m));
}

#[test]
fn explain_axisymmetric_deck() {
    let m = compile(&deck("axisymmetric_tools")).expect("compiles");
    insta::assert_snapshot!("explain_axisymmetric_tools", explain(&m));
}

#[test]
fn explain_leaves_out_what_a_scene_does_not_need() {
    let src = Source::new(
        "min.ctc",
        "analysis { dimension = plane_stress  thickness = 0.1 }\n\
         material m { elastic { E = 1  nu = 0 } }\n\
         body b { mesh = rectangle { size = (1, 1)  divisions = (1, 1) }  material = m }\n\
         step s { time = 0 .. 1 }\n",
    );
    let m = compile(&src).expect("compiles");
    let text = explain(&m);
    assert!(text.contains("not in this scene: contact search (no contact pairs), rigid tools, external loads, prescribed displacements,"));
    assert!(!text.contains("rigid tools:"));
    assert!(!text.contains("loads:"));
    assert!(text.contains("unknowns: 8 displacement dofs (2 per node): 8 free, 0 prescribed"));
}

#[test]
fn deformable_contact_lowers_to_a_surface_master_with_oriented_edges() {
    use ctc_engine::model::{ContactMaster, ContactStrategy, LocalSearch};
    let text = "analysis { dimension = plane_strain }\n\
        material m { elastic { E = 1  nu = 0 } }\n\
        body top { mesh = rectangle { origin = (0, 1)  size = (1, 1)  divisions = (3, 2) }  material = m }\n\
        body base { mesh = rectangle { origin = (0, 0)  size = (1, 1)  divisions = (4, 2) }  material = m }\n\
        contact top.bottom -> base.top { method = penalty { stiffness = 1 }  strategy = double_pass  search = circle }\n\
        fix base.bottom { ux uy }\n\
        displace top.top { uy = ramp(0, -0.1) }\n\
        step s { time = 0 .. 1 }\n";
    let src = ctc_lang::Source::new("deformable.ctc", text);
    let model = ctc_lang::compile(&src).unwrap_or_else(|d| panic!("{}", d.render(&src)));
    let cp = &model.contacts[0];
    assert_eq!(cp.name, "top.bottom -> base.top");
    assert_eq!(cp.strategy, ContactStrategy::DoublePass);
    assert_eq!(cp.search, LocalSearch::Circle);
    let ContactMaster::Surface {
        body, edges, nodes, ..
    } = &cp.master
    else {
        panic!("surface master expected");
    };
    assert_eq!(model.bodies[*body].name, "base");
    assert_eq!((edges.len(), nodes.len()), (4, 5));
    // body on the left: the base's top edges walk towards -x (normal +y)
    for &[a, b] in edges {
        let (pa, pb) = (model.mesh.nodes[a], model.mesh.nodes[b]);
        assert!(pb[0] < pa[0] && pa[1] == 1.0 && pb[1] == 1.0);
    }
}

/// Parameters, arithmetic, units (mm_N_s), an include, a set union and
/// quoted gmsh group names, lowered to the same numbers a user would type.
#[test]
fn parametric_deck_with_units_include_and_unions() {
    let src = deck("parametric");
    assert!(src.include_errors.is_empty(), "{:?}", src.include_errors);
    let c = check(&src);
    let m = c
        .model
        .as_ref()
        .unwrap_or_else(|| panic!("{}", c.diagnostics.render(&src)));
    // E = 210 GPa in MPa (the stress unit of mm_N_s)
    let MaterialLaw::LinearElastic { young, poisson } = m.materials[0].law else {
        panic!("{:?}", m.materials[0].law)
    };
    assert!((young - 210e3).abs() < 1e-9 * 210e3, "{young}");
    assert_eq!(poisson, 0.3);
    // radius R = 8 mm, n = 8 radial divisions: the disc's lowest node at y = 0
    let disc = &m.bodies[0];
    let ymin = m.mesh.nodes[disc.nodes.clone()]
        .iter()
        .map(|p| p[1])
        .fold(f64::INFINITY, f64::min);
    assert!(ymin.abs() < 1e-12, "{ymin}");
    // stiffness = 10 E / (R / n) = 10 x 210e3 / 1 mm
    match &m.contacts[0].method {
        ContactMethod::Penalty { stiffness, .. } => {
            assert!((stiffness - 2.1e6).abs() < 1e-6 * 2.1e6, "{stiffness}")
        }
        other => panic!("{other:?}"),
    }
    // the union of the two quoted gmsh groups: all 6 nodes of the strip
    assert_eq!(m.mesh.node_sets["lug.clamp"].len(), 6);
    assert_eq!(m.mesh.edge_sets["lug.clamp"].len(), 4);
    // ramp(0, -d), d = R / 100 = 0.08 mm
    let uy = m
        .constraints
        .iter()
        .find(|d| d.label == "displace disc.flat")
        .unwrap();
    let TimeFunction::Ramp { t0, t1, v0, v1 } = uy.value else {
        panic!("{:?}", uy.value)
    };
    assert_eq!((t0, t1, v0), (0.0, 1.0, 0.0));
    assert!((v1 + 0.08).abs() < 1e-15, "{v1}");
}

/// The `cylinder` generator from a deck: a 90 degree O-grid sector lowers
/// to the solid mesh of `solid::cylinder` with its face sets, and an angle
/// that is not whole quarters is a located error naming the rule.
#[test]
fn cylinder_generator_lowers_a_quarter_o_grid_with_its_face_sets() {
    let text = |angle: &str| {
        format!(
            "analysis {{ dimension = 3d }}\n\
             material m {{ elastic {{ E = 1  nu = 0.3 }} }}\n\
             body c {{ mesh = cylinder {{ radius = 1  angle = {angle}  height = 0.5  divisions = (3, 2, 2) }}  material = m }}\n\
             fix c.zmin {{ uz }}\n\
             fix c.start {{ uy }}\n\
             fix c.end {{ ux }}\n\
             pressure c.outer {{ p = ramp(0, 1) }}\n\
             step s {{ time = 0 .. 1 }}\n"
        )
    };
    let src = Source::new("cylinder.ctc", text("90"));
    let model = match ctc_lang::compile_any(&src) {
        Ok(ctc_engine::model::AnyModel::D3(m)) => m,
        Ok(_) => panic!("a 3d deck lowers to D3"),
        Err(d) => panic!("{}", d.render(&src)),
    };
    let expected =
        ctc_engine::mesh::generate::solid::cylinder(1.0, 90.0, 0.5, [3, 2, 2], CellKind::Hex8)
            .unwrap();
    assert_eq!(model.mesh.nodes, expected.nodes);
    assert_eq!(model.mesh.cells.len(), 3 * (3 + 2 * 2) * 2);
    for set in ["outer", "zmin", "zmax", "start", "end"] {
        assert_eq!(
            model.mesh.node_sets[&format!("c.{set}")],
            expected.node_sets[set],
            "{set}"
        );
    }
    let bad = Source::new("cylinder.ctc", text("45"));
    let Err(err) = ctc_lang::compile_any(&bad) else {
        panic!("45 degrees is refused");
    };
    let rendered = err.render(&bad);
    assert!(rendered.contains("90, 180, 270 or 360"), "{rendered}");
}

#[test]
fn follower_pressure_lowers_on_edges_and_faces() {
    // planar: 2-node edges of the sheet's bottom; 3d: the box's top faces
    for (analysis, mesh, held, set, facet_nodes, count) in [
        (
            "plane_strain",
            "rectangle { size = (4, 0.2)  divisions = (8, 1) }",
            "left { ux uy }",
            "bottom",
            2,
            8,
        ),
        (
            "3d",
            "box { size = (1, 1, 0.2)  divisions = (2, 3, 1) }",
            "xmin { ux uy uz }",
            "zmax",
            4,
            6,
        ),
    ] {
        let text = format!(
            "analysis {{ dimension = {analysis} }}\n\
             material rubber {{ neo_hookean {{ E = 10  nu = 0.45 }} }}\n\
             body sheet {{\n  mesh = {mesh}\n  material = rubber\n  kinematics = finite\n}}\n\
             fix sheet.{held}\n\
             pressure sheet.{set} {{ p = ramp(0, 0.01)  follower = true }}\n\
             step blow {{ time = 0 .. 1  increments = 2 }}\n"
        );
        let src = Source::new("follower.ctc", text);
        let loads: Vec<(usize, usize)> = match ctc_lang::compile_any(&src) {
            Ok(ctc_engine::model::AnyModel::D2(m)) => m
                .loads
                .iter()
                .filter_map(|l| match l {
                    Load::FollowerPressure { facets, .. } => {
                        Some((facets.len(), facets[0].nodes().len()))
                    }
                    _ => None,
                })
                .collect(),
            Ok(ctc_engine::model::AnyModel::D3(m)) => m
                .loads
                .iter()
                .filter_map(|l| match l {
                    Load::FollowerPressure { facets, .. } => {
                        Some((facets.len(), facets[0].nodes().len()))
                    }
                    _ => None,
                })
                .collect(),
            Err(d) => panic!("{}", d.render(&src)),
        };
        assert_eq!(loads, [(count, facet_nodes)], "{analysis}");
    }
}
