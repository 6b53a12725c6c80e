//! `motion { rotation = free  moment = .. }` (issue 22): a tool whose
//! angle is an unknown of the global system (a pilot node,
//! `ctc_engine::solve::free_tool`). The deck lowers to the pilot node,
//! its held y component and the applied moment; a converged run balances
//! the moment to round-off; misuse is a located error.
//!
//! ```text
//!        uy = -0.05 (top)
//!     +-----------+
//!     |   block   |  2 x 1, E = 1000, mu = 0.5 (sticks)
//!     +-----------+
//!          (o)  roller R = 1, free, moment M(t) = 0.2 t
//! ```

use ctc_engine::model::{Load, TimeFunction};
use ctc_engine::solve::{run, IncrementView, Observer};
use ctc_lang::Source;

fn deck(motion: &str, method: &str, dimension: &str) -> String {
    format!(
        "analysis {{ dimension = {dimension} }}\n\
         material m {{ elastic {{ E = 1000  nu = 0.3 }} }}\n\
         body block {{ mesh = rectangle {{ origin = (-1, 0)  size = (2, 1)  divisions = (8, 4) }}  material = m }}\n\
         tool roller = circle {{ center = (0.1, -1)  radius = 1  side = outside\n  motion {{ {motion} }} }}\n\
         contact block.bottom -> roller {{ method = {method}  friction = coulomb {{ mu = 0.5 }} }}\n\
         displace block.top {{ uy = ramp(0, -0.05) }}\n\
         fix block.top {{ ux }}\n\
         step s {{ time = 0 .. 1  increments = 4  newton {{ tol = 1e-12 }} }}\n"
    )
}

const PENALTY: &str = "penalty { kind = nodal  stiffness = 1e4 }";

#[derive(Default)]
struct Records(Vec<ctc_engine::solve::free_tool::ToolRecord>);

impl Observer for Records {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        self.0.extend_from_slice(v.tools);
        Ok(())
    }
}

#[test]
fn a_free_roller_lowers_to_a_pilot_node_and_balances_its_moment() {
    let src = Source::new(
        "t.ctc",
        deck(
            "rotation = free  moment = ramp(0, 0.2)",
            PENALTY,
            "plane_strain",
        ),
    );
    let model = ctc_lang::compile(&src).unwrap_or_else(|d| panic!("{}", d.render(&src)));
    let free = model.tools[0].free_rotation.clone().expect("free rotation");
    // the pilot node is the last node, at the centre, attached to no cell
    assert_eq!(free.node, model.mesh.nodes.len() - 1);
    assert_eq!(model.mesh.nodes[free.node], [0.1, -1.0]);
    assert!(model
        .mesh
        .cells
        .iter()
        .all(|c| !c.nodes.contains(&free.node)));
    assert!(model
        .constraints
        .iter()
        .any(|d| d.nodes == [free.node] && d.component == 1));
    assert!(model.loads.iter().any(|l| matches!(l,
        Load::NodalForce { nodes, component: 0, value: TimeFunction::Ramp { v1, .. }, .. }
            if nodes == &[free.node] && *v1 == 0.2)));
    let mut rec = Records::default();
    let summary = run(&model, &mut rec).unwrap_or_else(|e| panic!("{}", e.message));
    assert!(summary.completed);
    assert_eq!(rec.0.len(), 4);
    for (k, r) in rec.0.iter().enumerate() {
        let applied = 0.2 * (k + 1) as f64 / 4.0;
        assert_eq!(r.applied, applied);
        // the contact moment on the roller balances the applied one
        assert!(
            r.balance.abs() <= 1e-10 * applied,
            "increment {}: moment {} applied {} balance {:e}",
            k + 1,
            r.moment,
            r.applied,
            r.balance
        );
    }
    // a counter-clockwise moment turns the roller counter-clockwise
    // against the stuck block, relative to the same run without it (the
    // block's lateral expansion turns it too)
    let src0 = Source::new("t.ctc", deck("rotation = free", PENALTY, "plane_strain"));
    let model0 = ctc_lang::compile(&src0).unwrap_or_else(|d| panic!("{}", d.render(&src0)));
    let mut rec0 = Records::default();
    run(&model0, &mut rec0).unwrap_or_else(|e| panic!("{}", e.message));
    for (r, r0) in rec.0.iter().zip(&rec0.0) {
        assert!(r.angle > r0.angle, "{r:?} vs {r0:?}");
        assert!(r0.balance.abs() <= 1e-12 * r.applied, "{r0:?}");
    }
    eprintln!(
        "free roller: worst |moment + applied| / applied = {:.2e}",
        rec.0
            .iter()
            .map(|r| r.balance.abs() / r.applied)
            .fold(0.0, f64::max)
    );
}

fn error_of(text: &str) -> String {
    let src = Source::new("t.ctc", text);
    match ctc_lang::compile(&src) {
        Ok(_) => panic!("compiled:\n{text}"),
        Err(d) => d.render(&src),
    }
}

#[test]
fn misuse_of_a_free_rotation_is_a_located_error() {
    let e = error_of(&deck("moment = 1", PENALTY, "plane_strain"));
    assert!(e.contains("`moment` acts on a tool free to rotate"), "{e}");
    assert!(e.contains("t.ctc:5:"), "{e}");
    let e = error_of(&deck("rotation = free", PENALTY, "axisymmetric"));
    assert!(
        e.contains("a free rotation needs a plane strain or plane stress analysis"),
        "{e}"
    );
    assert!(e.contains("t.ctc:5:"), "{e}");
    let e = error_of(&deck("rotation = free", "lagrange { }", "plane_strain"));
    assert!(
        e.contains("Lagrange multipliers are not available against a tool free to rotate"),
        "{e}"
    );
    assert!(e.contains("t.ctc:6:"), "{e}");
    let dynamic = deck("rotation = free", PENALTY, "plane_strain")
        .replace("increments = 4 ", "increments = 4  dynamic ");
    let e = error_of(&dynamic);
    assert!(e.contains("quasi-static steps only"), "{e}");
}
