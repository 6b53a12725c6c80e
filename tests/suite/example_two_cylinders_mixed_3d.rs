//! `examples/two_cylinders_mixed_3d.ctc` (issue 23, mortar between a
//! quadratic and a linear body in 3D): two identical elastic cylinders as
//! one layer of solid cells in plane strain, the upper one hex20 (slave
//! arc of quad8 faces), the lower one hex8 (master arc of quad4 faces).
//!
//! Reference: the plane-strain Hertz deck
//! `verification/cases/hertz_two_cylinders_mortar.ctc` (Johnson, Contact
//! Mechanics §4.3) at the same approach: its 2D seg3 mortar run at 4,464
//! dofs (quad8 | quad8) carries P = 2.489 per unit length (`ctc verify
//! hertz_two_cylinders_mortar_mixed --max-level 2`, where the quad4 |
//! quad4 run is within 2e-3 of it), 0.2489 over the thickness 0.1.
//!
//! ```text
//!          |  top: quarter cylinder, hex20 (tet10 hub), radial 3, circ. 6
//!          | .-'     flat pushed down 0.02
//!   -------+---- slave top.arc (quad8) -> master bottom.arc (quad4), mortar
//!          | '-.
//!          |  bottom: hex8 (tet4 hub), radial 6, circ. 12, flat held
//!   x = 0 symmetry; uz = 0 on z = 0 and z = 0.1 (plane strain)
//! ```

use crate::examples::{run_example_with, SharedRun};
use ctc_engine::model::{AnyModel, Model};
use ctc_engine::solve::{IncrementView, Observer};
use std::path::Path;
use std::sync::OnceLock;

/// The 2D reference force per unit length (module doc) times the thickness.
const P_REF: f64 = 2.489 * 0.1;

/// The force on the pushed flat (`-` its reaction `y`) at the last increment.
#[derive(Default)]
pub(crate) struct Force {
    nodes: Vec<usize>,
    p: f64,
}

impl Observer<3> for Force {
    fn converged(&mut self, v: &IncrementView<'_, 3>) -> Result<(), String> {
        self.p = -self.nodes.iter().map(|&n| v.reaction[n][1]).sum::<f64>();
        Ok(())
    }
}

/// The deck `text` compiled, and its probe.
fn model_and_probe(text: &str) -> (Model<3>, Force) {
    let src = ctc_lang::Source::new(Path::new("two_cylinders_mixed_3d.ctc"), text);
    let model: Model<3> = match ctc_lang::compile_any(&src) {
        Ok(AnyModel::D3(m)) => m,
        Ok(_) => panic!("not a 3d deck"),
        Err(d) => panic!("{}", d.render(&src)),
    };
    let mut nodes: Vec<usize> = model.mesh.face_sets["top.flat"]
        .iter()
        .flat_map(|f| f.nodes().to_vec())
        .collect();
    nodes.sort_unstable();
    nodes.dedup();
    let probe = Force {
        nodes,
        ..Force::default()
    };
    (model, probe)
}

fn force(text: &str) -> (f64, usize) {
    let (model, mut probe) = model_and_probe(text);
    let s = ctc_engine::solve::run(&model, &mut probe).expect("the run");
    assert!(s.completed);
    (probe.p, s.free_dofs)
}

fn deck_path() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/two_cylinders_mixed_3d.ctc")
}

/// The example as written, run once for this file's test and the examples
/// test ([`crate::examples::SharedRun`]).
pub(crate) fn shared() -> &'static SharedRun<Force> {
    static RUN: OnceLock<SharedRun<Force>> = OnceLock::new();
    RUN.get_or_init(|| {
        let text = std::fs::read_to_string(deck_path()).expect("the example deck");
        let (model, probe) = model_and_probe(&text);
        run_example_with(&deck_path(), &model, probe)
    })
}

/// The mixed-order run against the 2D reference and against the same
/// deck all hex8 (the upper cylinder's divisions doubled, no `order`).
/// Measured (this test, `--nocapture`): mixed 0.24751 (-5.6e-3), all hex8
/// 0.25674 (+3.2e-2); tolerances: 1e-2 and the mixed run closer to the
/// reference than the linear one.
#[test]
fn two_cylinders_mixed_3d_carries_the_plane_strain_hertz_force() {
    let text = std::fs::read_to_string(deck_path()).expect("the example deck");
    // the example's run, shared with the examples test (its snapshot)
    let run = shared();
    let (mixed, dofs) = (run.probe.p, run.summary.free_dofs);
    let linear_text = text
        .replace(
            "radial = 3  circumferential = 6",
            "radial = 6  circumferential = 12",
        )
        .replace("    order = 2\n", "");
    assert_ne!(linear_text, text);
    assert!(!linear_text.contains("order = 2"));
    let (linear, linear_dofs) = force(&linear_text);
    let (e_mixed, e_linear) = (mixed / P_REF - 1.0, linear / P_REF - 1.0);
    println!(
        "P mixed {mixed:.5} ({dofs} dofs) {e_mixed:+.2e}, all hex8 {linear:.5} \
         ({linear_dofs} dofs) {e_linear:+.2e} against {P_REF:.5}"
    );
    assert!(e_mixed.abs() < 1e-2, "{e_mixed:e}");
    assert!(e_mixed.abs() < e_linear.abs(), "{e_mixed:e} {e_linear:e}");
}
