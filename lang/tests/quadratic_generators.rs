//! `order = 2` on the mesh generators (issue 23): the linear mesh lifted by
//! `mesh::elevate`, its sets carried to the midside nodes, loads on the
//! 3-node edges / quadratic faces, and the midside nodes of the arcs on
//! the true circle.

use ctc_engine::mesh::CellKind;
use ctc_engine::model::{AnyModel, Load, Model};
use ctc_lang::{check, compile_any, Source};

fn planar(analysis: &str, mesh: &str, rest: &str) -> Model {
    let src = Source::new(
        "quad.ctc",
        format!(
            "analysis {{ dimension = {analysis} }}\n\
             material m {{ elastic {{ E = 1000  nu = 0.3 }} }}\n\
             body b {{\n  mesh = {mesh}\n  material = m\n}}\n\
             {rest}\n\
             step s {{ time = 0 .. 1  increments = 1 }}\n"
        ),
    );
    match compile_any(&src) {
        Ok(AnyModel::D2(m)) => m,
        Ok(_) => panic!("not planar"),
        Err(d) => panic!("{}", d.render(&src)),
    }
}

fn solid(mesh: &str, rest: &str) -> Model<3> {
    let src = Source::new(
        "quad3.ctc",
        format!(
            "analysis {{ dimension = 3d }}\n\
             material m {{ elastic {{ E = 1000  nu = 0.3 }} }}\n\
             body b {{\n  mesh = {mesh}\n  material = m\n}}\n\
             {rest}\n\
             step s {{ time = 0 .. 1  increments = 1 }}\n"
        ),
    );
    match compile_any(&src) {
        Ok(AnyModel::D3(m)) => m,
        Ok(_) => panic!("not 3d"),
        Err(d) => panic!("{}", d.render(&src)),
    }
}

#[test]
fn rectangle_of_order_two_is_quad8_with_midside_nodes_in_its_edge_sets() {
    let m = planar(
        "plane_strain",
        "rectangle { size = (2, 1)  divisions = (4, 2)  order = 2 }",
        "fix b.left { ux uy }\npressure b.right { p = 1 }",
    );
    // 5 x 3 corners, 4 x 3 + 5 x 2 midside nodes
    assert_eq!(m.mesh.nodes.len(), 15 + 12 + 10);
    assert!((0..m.mesh.cells.len()).all(|c| m.mesh.cells.kind(c) == CellKind::Quad8));
    // the left edge: 3 corners and 2 midside nodes, all at x = 0
    let left = &m.mesh.node_sets["b.left"];
    assert_eq!(left.len(), 5);
    assert!(left.iter().all(|&n| m.mesh.nodes[n][0] == 0.0));
    assert_eq!(m.constraints[0].nodes.len(), 5);
    // the pressure acts on the two 3-node edges of the right side; its
    // total is p * height (consistent 1/6, 4/6, 1/6 shares)
    let Load::FacetPressure { facets, .. } = &m.loads[0] else {
        panic!("{:?}", m.loads[0]);
    };
    assert_eq!(facets.len(), 2);
    assert!(facets.iter().all(|f| f.nodes().len() == 3));
    let mut f = vec![0.0; 2 * m.mesh.nodes.len()];
    ctc_engine::solve::loads::external_forces(&m, 1.0, &mut f);
    let fx: f64 = f.iter().step_by(2).sum();
    assert!((fx + 1.0).abs() < 1e-12, "{fx}");
}

#[test]
fn reduced_integration_gives_quad8r_and_triangles_give_tri6() {
    let m = planar(
        "axisymmetric",
        "rectangle { origin = (1, 0)  size = (1, 1)  divisions = (2, 2)  order = 2  \
         integration = reduced }",
        "fix b.bottom { uy }",
    );
    assert_eq!(m.mesh.cells.kind(0), CellKind::Quad8R);
    let m = planar(
        "plane_strain",
        "rectangle { size = (1, 1)  divisions = (2, 2)  element = tri3  order = 2 }",
        "fix b.bottom { uy }",
    );
    assert_eq!(m.mesh.cells.kind(0), CellKind::Tri6);
}

#[test]
fn annulus_of_order_two_puts_its_arc_midpoints_on_the_circles() {
    let m = planar(
        "plane_strain",
        "annulus { center = (1, 2)  inner = 1  outer = 2  end = 90  radial = 2  \
         circumferential = 3  order = 2 }",
        "fix b.start { uy }",
    );
    let radius = |n: usize| {
        let p = m.mesh.nodes[n];
        (p[0] - 1.0).hypot(p[1] - 2.0)
    };
    // every node of the inner and outer arcs on its circle (midpoints too)
    for (set, r) in [("b.inner", 1.0), ("b.outer", 2.0)] {
        let nodes = &m.mesh.node_sets[set];
        assert_eq!(nodes.len(), 7, "{set}");
        for &n in nodes {
            assert!((radius(n) - r).abs() < 1e-12, "{set}: {}", radius(n));
        }
    }
}

#[test]
fn tube_of_order_two_is_hex20_with_its_faces_on_the_cylinders() {
    let m = solid(
        "tube { inner = 1  outer = 2  angle = 90  height = 0.5  divisions = (2, 3, 1)  \
         order = 2 }",
        "fix b.zmin { uz }\npressure b.inner { p = 1 }",
    );
    assert!((0..m.mesh.cells.len()).all(|c| m.mesh.cells.kind(c) == CellKind::Hex20));
    for &n in &m.mesh.node_sets["b.inner"] {
        let p = m.mesh.nodes[n];
        assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-12);
    }
    let Load::FacetPressure { facets, .. } = &m.loads[0] else {
        panic!("{:?}", m.loads[0]);
    };
    assert!(facets.iter().all(|f| f.nodes().len() == 8));
    let m = solid(
        "box { size = (1, 1, 1)  divisions = (1, 1, 1)  element = tet4  order = 2 }",
        "fix b.zmin { uz }",
    );
    assert_eq!(m.mesh.cells.kind(0), CellKind::Tet10);
    let m = solid(
        "extrude { base = rectangle { size = (1, 1)  divisions = (2, 2) }  length = 1  \
         layers = 1  order = 2  integration = reduced }",
        "fix b.zmin { uz }",
    );
    assert_eq!(m.mesh.cells.kind(0), CellKind::Hex20R);
}

#[test]
fn explain_names_the_quadratic_cell_kinds() {
    let src = Source::new(
        "explain.ctc",
        "analysis { dimension = plane_strain }\n\
         material m { elastic { E = 1000  nu = 0.3 } }\n\
         body b { mesh = rectangle { size = (1, 1)  divisions = (2, 2)  order = 2 }  material = m }\n\
         fix b.bottom { uy }\n\
         step s { time = 0 .. 1 }\n",
    );
    let r = check(&src);
    let model = r.model.expect("valid deck");
    let text = ctc_lang::explain::explain(&model);
    assert!(
        text.contains("4 cells (4 quad8), full integration (quad8: 3x3 Gauss)"),
        "{text}"
    );
}

/// A gmsh file of second-order quadrangles (type 16) with 3-node boundary
/// lines (type 8): quad8 cells, the midside nodes in the node sets, the
/// pressure on the 3-node edges (total p x width).
#[test]
fn gmsh_quad8_strip_lowers_with_its_three_node_edges() {
    let src = Source::new(
        "tests/decks/strip_quad8.ctc",
        "analysis { dimension = plane_strain }\n\
         material m { elastic { E = 1000  nu = 0.3 } }\n\
         body b { mesh = file \"strip_quad8.msh\"  material = m }\n\
         fix b.bottom { ux uy }\n\
         pressure b.top { p = 2 }\n\
         step s { time = 0 .. 1 }\n",
    );
    let m = match compile_any(&src) {
        Ok(AnyModel::D2(m)) => m,
        Ok(_) => panic!("not planar"),
        Err(d) => panic!("{}", d.render(&src)),
    };
    assert_eq!(m.mesh.cells.len(), 2);
    assert_eq!(m.mesh.cells.kind(1), CellKind::Quad8);
    assert_eq!(m.mesh.node_sets["b.bottom"].len(), 5);
    assert_eq!(m.constraints[0].nodes.len(), 5);
    let Load::FacetPressure { facets, .. } = &m.loads[0] else {
        panic!("{:?}", m.loads[0]);
    };
    assert_eq!(facets.len(), 2);
    let mut f = vec![0.0; 2 * m.mesh.nodes.len()];
    ctc_engine::solve::loads::external_forces(&m, 1.0, &mut f);
    let fy: f64 = f.iter().skip(1).step_by(2).sum();
    assert!((fy + 4.0).abs() < 1e-12, "{fy}");
    let summary =
        ctc_engine::solve::run(&m, &mut ctc_engine::testkit::Recorder::default()).unwrap();
    assert!(summary.completed);
}

/// The discs mix a triangle hub with quadrilateral rings: `order = 2`
/// lifts each (tri6 + quad8), the arc's midside nodes on the circle.
#[test]
fn quarter_disc_of_order_two_is_tri6_and_quad8_with_its_arc_on_the_circle() {
    let m = planar(
        "axisymmetric",
        "quarter_disc { center = (0, 0)  radius = 1  radial = 4  circumferential = 4  order = 2 }",
        "fix b.flat { uy }",
    );
    let kinds: std::collections::BTreeSet<&str> = (0..m.mesh.cells.len())
        .map(|c| m.mesh.cells.kind(c).name())
        .collect();
    assert_eq!(kinds.into_iter().collect::<Vec<_>>(), ["quad8", "tri6"]);
    let arc = &m.mesh.node_sets["b.arc"];
    assert_eq!(arc.len(), 9);
    for &n in arc {
        let p = m.mesh.nodes[n];
        assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-12);
    }
}

/// Two deformable blocks of quad8 cells in contact (issues 23 and 18):
/// mortar lowers (the slave midside nodes are contact nodes), with or
/// without friction, also with one side linear (mixed orders, frictionless);
/// node-to-segment, friction with mixed orders and friction with Lagrange
/// multipliers are refused with a caret.
#[test]
fn deformable_quadratic_pair_lowers_with_mortar_only() {
    let penalty = "penalty { kind = area  stiffness = 1e6 }";
    let deck_with = |top_order: usize, method: &str, contact_extra: &str| {
        format!(
            "analysis {{ dimension = plane_strain }}\n\
             material m {{ elastic {{ E = 1000  nu = 0.3 }} }}\n\
             body base {{\n  mesh = rectangle {{ origin = (0, 0)  size = (1, 1)  divisions = (4, 2)  order = 2 }}\n  material = m\n}}\n\
             body top {{\n  mesh = rectangle {{ origin = (0, 1)  size = (1, 1)  divisions = (3, 2)  order = {top_order} }}\n  material = m\n}}\n\
             contact top.bottom -> base.top {{\n  method = {method}\n  {contact_extra}\n}}\n\
             fix base.bottom {{ uy }}\nfix base.left {{ ux }}\nfix top.left {{ ux }}\n\
             displace top.top {{ uy = ramp(0, -0.01) }}\n\
             step s {{ time = 0 .. 1  increments = 1 }}\n"
        )
    };
    let deck = |top_order: usize, contact_extra: &str| deck_with(top_order, penalty, contact_extra);
    for extra in [
        "formulation = mortar",
        "formulation = mortar\n  friction = coulomb { mu = 0.2 }",
    ] {
        let src = Source::new("pair.ctc", deck(2, extra));
        let m = match compile_any(&src) {
            Ok(AnyModel::D2(m)) => m,
            Ok(_) => panic!("not planar"),
            Err(d) => panic!("{}", d.render(&src)),
        };
        // 3 edges: 4 corners and 3 midside nodes
        assert_eq!(m.contacts[0].nodes.len(), 7);
        assert!(ctc_engine::solve::check::check_model(&m).is_empty());
    }
    // mixed orders (a quad4 slave on the quad8 base) lower: 4 corners
    let src = Source::new("pair.ctc", deck(1, "formulation = mortar"));
    let m = match compile_any(&src) {
        Ok(AnyModel::D2(m)) => m,
        Ok(_) => panic!("not planar"),
        Err(d) => panic!("{}", d.render(&src)),
    };
    assert_eq!(m.contacts[0].nodes.len(), 4);
    assert!(ctc_engine::solve::check::check_model(&m).is_empty());
    for (order, method, extra, expected) in [
        (2, penalty, "", "add `formulation = mortar`"),
        (
            1,
            penalty,
            "formulation = mortar\n  friction = coulomb { mu = 0.2 }",
            "friction with mortar between a linear and a quadratic side",
        ),
        (
            2,
            "lagrange { }",
            "formulation = mortar\n  friction = coulomb { mu = 0.2 }",
            "Lagrange-multiplier friction against a deformable master",
        ),
    ] {
        let src = Source::new("pair.ctc", deck_with(order, method, extra));
        let out = check(&src).diagnostics.render(&src);
        assert!(out.contains(expected), "{out}");
    }
}

/// Two deformable blocks of hex20 cells in contact (issues 23 and 18): 3D
/// mortar on quad8 faces lowers (every face node is a contact node), with
/// or without friction, with Lagrange multipliers, also with one side
/// linear (mixed orders, with or without friction); node-to-facet and
/// Lagrange-multiplier friction are refused with a located error.
#[test]
fn deformable_quadratic_3d_pair_lowers_with_mortar_only() {
    let deck = |top_order: usize, method: &str, contact_extra: &str| {
        format!(
            "analysis {{ dimension = 3d }}\n\
             material m {{ elastic {{ E = 1000  nu = 0.3 }} }}\n\
             body base {{\n  mesh = box {{ size = (1, 1, 0.5)  divisions = (3, 3, 1)  order = 2 }}\n  material = m\n}}\n\
             body top {{\n  mesh = box {{ origin = (0, 0, 0.5)  size = (1, 1, 0.5)  divisions = (2, 2, 1)  order = {top_order} }}\n  material = m\n}}\n\
             contact top.zmin -> base.zmax {{\n  method = {method}\n  {contact_extra}\n}}\n\
             fix base.zmin {{ uz }}\nfix base.xmin {{ ux }}\nfix base.ymin {{ uy }}\n\
             fix top.xmin {{ ux }}\nfix top.ymin {{ uy }}\n\
             displace top.zmax {{ uz = ramp(0, -0.01) }}\n\
             step s {{ time = 0 .. 1  increments = 1 }}\n"
        )
    };
    let penalty = "penalty { kind = area  stiffness = 1e6 }";
    for extra in [
        "formulation = mortar",
        "formulation = mortar\n  friction = coulomb { mu = 0.2 }",
    ] {
        let src = Source::new("pair3d.ctc", deck(2, penalty, extra));
        let m = match compile_any(&src) {
            Ok(AnyModel::D3(m)) => m,
            Ok(_) => panic!("not 3d"),
            Err(d) => panic!("{}", d.render(&src)),
        };
        // 2 x 2 quad8 faces: 9 corners and 12 midside nodes
        assert_eq!(m.contacts[0].nodes.len(), 21);
        assert!(ctc_engine::solve::check::check_model(&m).is_empty());
    }
    // mixed orders (hex8 slave faces on the hex20 base) lower, with or
    // without friction: 9 corners
    for extra in [
        "formulation = mortar",
        "formulation = mortar\n  friction = coulomb { mu = 0.2 }",
    ] {
        let src = Source::new("pair3d.ctc", deck(1, penalty, extra));
        let m = match compile_any(&src) {
            Ok(AnyModel::D3(m)) => m,
            Ok(_) => panic!("not 3d"),
            Err(d) => panic!("{}", d.render(&src)),
        };
        assert_eq!(m.contacts[0].nodes.len(), 9);
        assert!(ctc_engine::solve::check::check_model(&m).is_empty());
    }
    // Lagrange multipliers (one per slave node, corners and midside nodes)
    let src = Source::new(
        "pair3d.ctc",
        deck(2, "lagrange { }", "formulation = mortar"),
    );
    match compile_any(&src) {
        Ok(AnyModel::D3(m)) => {
            let errors = ctc_engine::solve::check::check_model(&m);
            assert!(errors.is_empty(), "{errors:?}");
        }
        Ok(_) => panic!("not 3d"),
        Err(d) => panic!("{}", d.render(&src)),
    }
    for (order, method, extra, expected) in [
        (2, penalty, "", "formulation = mortar"),
        (
            2,
            "lagrange { }",
            "formulation = mortar\n  friction = coulomb { mu = 0.2 }",
            "lagrange-multiplier friction against a deformable master",
        ),
    ] {
        let src = Source::new("pair3d.ctc", deck(order, method, extra));
        let out = check(&src).diagnostics.render(&src);
        println!("{out}");
        assert!(out.to_lowercase().contains(expected), "{out}");
        assert!(out.contains("pair3d.ctc:"), "located: {out}");
    }
}

/// `imperfection` on `tube`: every node, the hex20 midside nodes too,
/// sits at its perfect radius plus `a cos(n theta) sin(m pi z / h)`; an
/// amplitude of the inner radius is a diagnostic, not a panic.
#[test]
fn tube_imperfection_moves_every_node_of_a_quadratic_tube() {
    let (a, n, m_half, h) = (0.05, 2.0, 1.0, 0.5);
    let m = solid(
        "tube { inner = 1  outer = 2  angle = 90  height = 0.5  divisions = (2, 3, 2)  \
         order = 2  imperfection = 0.05  imperfection_waves = 2 }",
        "fix b.zmin { uz }",
    );
    let perfect = solid(
        "tube { inner = 1  outer = 2  angle = 90  height = 0.5  divisions = (2, 3, 2)  \
         order = 2 }",
        "fix b.zmin { uz }",
    );
    assert_eq!(m.mesh.nodes.len(), perfect.mesh.nodes.len());
    let mut moved = 0;
    for (p, q) in perfect.mesh.nodes.iter().zip(&m.mesh.nodes) {
        let theta = p[1].atan2(p[0]);
        let want = a * (n * theta).cos() * (m_half * std::f64::consts::PI * p[2] / h).sin();
        let dr = q[0].hypot(q[1]) - p[0].hypot(p[1]);
        assert!((dr - want).abs() < 1e-12, "{p:?}: {dr} against {want}");
        moved += usize::from(want.abs() > 1e-3);
    }
    assert!(moved > 10, "{moved}");
    // the sets are the perfect tube's
    assert_eq!(
        m.mesh.node_sets["b.inner"],
        perfect.mesh.node_sets["b.inner"]
    );
    let src = Source::new(
        "bad.ctc",
        "analysis { dimension = 3d }\n\
         material m { elastic { E = 1000  nu = 0.3 } }\n\
         body b {\n  mesh = tube { inner = 1  outer = 2  height = 1  divisions = (1, 8, 2)  \
         imperfection = 1 }\n  material = m\n}\n\
         fix b.zmin { uz }\n\
         step s { time = 0 .. 1 }\n",
    );
    let Err(e) = compile_any(&src) else {
        panic!("an amplitude of the inner radius compiled")
    };
    let text = e.render(&src);
    assert!(text.contains("imperfection amplitude 1"), "{text}");
}
