//! `extrude` and `revolve` in decks: a planar generator (or gmsh file)
//! nested as the input of a solid generator, its sets carried over, and
//! the mistakes a user makes diagnosed at the right place.

use ctc_engine::model::AnyModel;
use ctc_lang::{check, compile_any, Source};

fn deck(mesh: &str) -> Source {
    Source::new(
        "sweep.ctc",
        format!(
            "analysis {{ dimension = 3d }}\n\
             material m {{ elastic {{ E = 1000  nu = 0.3 }} }}\n\
             body part {{\n  mesh = {mesh}\n  material = m\n}}\n\
             fix part.zmin {{ ux uy uz }}\n\
             step s {{ time = 0 .. 1  increments = 1 }}\n"
        ),
    )
}

#[test]
fn extruded_rectangle_lowers_with_its_swept_sets() {
    let src = deck(
        "extrude { base = rectangle { size = (2, 1)  divisions = (4, 2)  element = tri3 }  \
         length = 0.5  layers = 3  grading = geometric(2) }",
    );
    let m = match compile_any(&src) {
        Ok(AnyModel::D3(m)) => m,
        Ok(_) => panic!("not 3d"),
        Err(d) => panic!("{}", d.render(&src)),
    };
    assert_eq!(m.mesh.nodes.len(), 5 * 3 * 4);
    // 4 x 2 quads in 2 triangles each, 3 tetrahedra per prism, 3 layers
    assert_eq!(m.mesh.cells.len(), 4 * 2 * 2 * 3 * 3);
    for set in [
        "part.zmin",
        "part.zmax",
        "part.left",
        "part.top",
        "part.corner_tr",
    ] {
        assert!(m.mesh.node_sets.contains_key(set), "{set}");
    }
    assert_eq!(m.mesh.face_sets["part.top"].len(), 4 * 3 * 2);
}

#[test]
fn revolved_section_lowers_and_a_full_turn_has_no_ends() {
    let src = Source::new(
        "rev.ctc",
        "analysis { dimension = 3d }\n\
         material m { elastic { E = 1000  nu = 0.3 } }\n\
         body ring {\n  mesh = revolve { section = rectangle { origin = (1, 0)  size = (1, 0.5)  \
         divisions = (2, 2) }  segments = 16 }\n  material = m\n}\n\
         fix ring.bottom { uz }\n\
         pressure ring.left { p = 1 }\n\
         step s { time = 0 .. 1  increments = 1 }\n",
    );
    let m = match compile_any(&src) {
        Ok(AnyModel::D3(m)) => m,
        Ok(_) => panic!("not 3d"),
        Err(d) => panic!("{}", d.render(&src)),
    };
    assert_eq!(m.mesh.nodes.len(), 9 * 16);
    assert!(!m.mesh.face_sets.contains_key("ring.start"));
    assert_eq!(m.mesh.face_sets["ring.left"].len(), 2 * 16);
}

fn errors(src: &Source) -> String {
    let c = check(src);
    assert!(c.model.is_none(), "accepted");
    c.diagnostics.render(src)
}

#[test]
fn a_solid_base_is_refused_at_the_inner_generator() {
    let text = errors(&deck(
        "extrude { base = box { size = (1, 1, 1)  divisions = (1, 1, 1) }  length = 1  layers = 1 }",
    ));
    assert!(
        text.contains("must be a planar mesh, but `box` makes a solid one"),
        "{text}"
    );
}

#[test]
fn the_inner_generator_settings_are_validated() {
    let text = errors(&deck(
        "extrude { base = rectangle { size = (1, -1)  divisions = (2, 2) }  length = 1  layers = 1 }",
    ));
    assert!(text.contains("size"), "{text}");
}

#[test]
fn a_tri3_section_on_the_axis_revolves_into_a_solid_of_revolution() {
    // the rod 0 <= r <= 1, 0 <= z <= 2: one copy of each axis node, also
    // with quadratic cells (midside nodes of axis edges stay on the axis)
    for order in [1, 2] {
        let src = Source::new(
            "rod.ctc",
            format!(
                "analysis {{ dimension = 3d }}\n\
                 material m {{ elastic {{ E = 1000  nu = 0.3 }} }}\n\
                 body rod {{\n  mesh = revolve {{ section = rectangle {{ size = (1, 2)  \
                 divisions = (3, 4)  element = tri3 }}  segments = 12  order = {order} }}\n  \
                 material = m\n}}\n\
                 fix rod.bottom {{ uz }}\n\
                 fix rod.left {{ ux uy }}\n\
                 pressure rod.top {{ p = 1 }}\n\
                 step s {{ time = 0 .. 1  increments = 1 }}\n"
            ),
        );
        let m = match compile_any(&src) {
            Ok(AnyModel::D3(m)) => m,
            Ok(_) => panic!("not 3d"),
            Err(d) => panic!("{}", d.render(&src)),
        };
        let axis = m.mesh.node_sets["rod.left"].len();
        assert_eq!(axis, 4 * order + 1, "order {order}");
        assert!(m.mesh.node_sets["rod.left"]
            .iter()
            .all(|&v| m.mesh.nodes[v][0] == 0.0 && m.mesh.nodes[v][1] == 0.0));
        if order == 1 {
            assert_eq!(m.mesh.nodes.len(), 5 + 3 * 5 * 12);
        }
    }
}

#[test]
fn a_quad4_section_on_the_axis_is_a_clear_mesh_error() {
    let text = errors(&deck(
        "revolve { section = rectangle { size = (1, 1)  divisions = (2, 2) }  angle = 90  segments = 4 }",
    ));
    assert!(text.contains("reaches the axis"), "{text}");
    assert!(text.contains("element = tri3"), "{text}");
    let text = errors(&deck(
        "revolve { section = rectangle { origin = (1, 0)  size = (1, 1)  divisions = (2, 2) }  \
         angle = 400  segments = 4 }",
    ));
    assert!(text.contains("at most 360 degrees"), "{text}");
}

#[test]
fn an_unknown_swept_set_is_diagnosed_against_the_built_mesh() {
    let src = Source::new(
        "sets.ctc",
        "analysis { dimension = 3d }\n\
         material m { elastic { E = 1000  nu = 0.3 } }\n\
         body part {\n  mesh = extrude { base = rectangle { size = (1, 1)  divisions = (2, 2) }  \
         length = 1  layers = 2 }\n  material = m\n}\n\
         fix part.lefft { ux }\n\
         step s { time = 0 .. 1  increments = 1 }\n",
    );
    let text = compile_any(&src).unwrap_err().render(&src);
    assert!(text.contains("lefft"), "{text}");
    assert!(text.contains("left"), "{text}");
}

/// A `set` naming the boundary less the extruded ends is a face set: the
/// sides of a slice, taken by contact and pressure (the blades of
/// `examples/blade_loss_3d.ctc`, whose end faces must not be masters).
#[test]
fn the_sides_of_an_extruded_slice_are_a_face_set() {
    let src = Source::new(
        "sides.ctc",
        "analysis { dimension = 3d }\n\
         material m { elastic { E = 1000  nu = 0.3 } }\n\
         body a {\n  mesh = extrude { base = rectangle { size = (2, 1)  divisions = (4, 2) }  \
         length = 0.5  layers = 1 }\n  material = m\n}\n\
         body b {\n  mesh = extrude { base = rectangle { origin = (0, 1)  size = (2, 1)  \
         divisions = (4, 2) }  length = 0.5  layers = 1 }\n  material = m\n}\n\
         set sides = a.boundary - a.zmin - a.zmax\n\
         set sides = b.boundary - b.zmin - b.zmax\n\
         fix a.zmin { ux uy uz }\n\
         fix b.zmin { ux uy uz }\n\
         pressure b.sides { p = 1 }\n\
         contact a.sides -> b.sides { method = penalty { kind = area  stiffness = 1e3 } }\n\
         step s { time = 0 .. 1  increments = 1 }\n",
    );
    let m = match compile_any(&src) {
        Ok(AnyModel::D3(m)) => m,
        Ok(_) => panic!("not 3d"),
        Err(d) => panic!("{}", d.render(&src)),
    };
    // the four sides of a 4 x 2 x 1 block: 2 (4 + 2) faces, no end face
    for body in ["a", "b"] {
        let sides = &m.mesh.face_sets[&format!("{body}.sides")];
        assert_eq!(sides.len(), 12, "{body}");
        let boundary = &m.mesh.face_sets[&format!("{body}.boundary")];
        assert_eq!(boundary.len(), 12 + 2 * 8, "{body}");
        for f in sides {
            assert!(boundary.contains(f), "{body}: a side is a boundary face");
        }
    }
    // the slave nodes: those on a side (not the 3 in-plane interior ones
    // of either layer)
    assert_eq!(m.contacts[0].nodes.len(), 5 * 3 * 2 - 3 * 2);
}
