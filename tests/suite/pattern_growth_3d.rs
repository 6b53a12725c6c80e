//! The 3D contact scene's sparsity-pattern growth keeps every coupling of
//! the model: a spring link between two nodes that share no cell must keep
//! its off-diagonal tangent slots when contact (node-to-facet between two
//! deformable blocks) adds new couplings during the step.
//!
//! Regression of 3c874bc: the growth rebuilt the pattern from the contact
//! couplings alone, the link's off-diagonal terms were silently skipped
//! from then on and Newton converged linearly (the 3D dynamic buckling
//! tube: 14 iterations per increment). On this deck the code before the
//! fix cut back to the minimum increment and stopped at t = 0.167 with a
//! residual contraction of 0.90 per iteration; with the fix it runs 4
//! increments in 16 iterations.
//!
//! ```text
//!      uz = -0.012 on top.zmax            spring link (k = 1e3) between
//!   +----------------+                    (1, 1/3) and (1/3, 1) of the
//!   |   top 3x3x2    |  gap 0.002         top face: no shared cell
//!   +----------------+
//!   +----------------+  node-to-facet, penalty
//!   |  base 4x4x2    |
//!   +----------------+  rollers on zmin, xmin, ymin
//! ```

use ctc_engine::model::AnyModel;
use ctc_engine::solve::{IncrementView, Observer};

const DECK: &str = "analysis { dimension = 3d }
material soft { elastic { E = 1000  nu = 0.3 } }
body base { mesh = box { size = (1, 1, 0.5)  divisions = (4, 4, 2) }  material = soft }
body top {
  mesh = box { origin = (0, 0, 0.502)  size = (1, 1, 0.5)  divisions = (3, 3, 2) }
  material = soft
}
contact top.zmin -> base.zmax { method = penalty { stiffness = 1e6 } }
fix base.zmin { uz }
fix base.xmin { ux }
fix base.ymin { uy }
fix top.xmin { ux }
fix top.ymin { uy }
spring top.node(near(1, 0.3333, 1.002)) -> top.node(near(0.3333, 1, 1.002)) { stiffness = 1e3 }
displace top.zmax { uz = ramp(0, -0.012) }
step press {
  time = 0 .. 1
  increments = 4
  newton { tol = 1e-10 }
}
";

/// The relative residuals of every converged increment.
#[derive(Default)]
struct Residuals(Vec<Vec<f64>>);

impl Observer<3> for Residuals {
    fn converged(&mut self, v: &IncrementView<'_, 3>) -> Result<(), String> {
        self.0.push(v.residuals.to_vec());
        Ok(())
    }
}

#[test]
fn a_spring_link_keeps_its_tangent_when_contact_grows_the_pattern() {
    let src = ctc_lang::Source::new(std::path::Path::new("pattern_growth.ctc"), DECK.to_string());
    let AnyModel::D3(model) = ctc_lang::compile_any(&src)
        .map_err(|d| d.render(&src))
        .unwrap()
    else {
        panic!("not a 3D deck");
    };
    let mut seen = Residuals::default();
    let summary = ctc_engine::solve::run(&model, &mut seen).unwrap_or_else(|e| panic!("{e:?}"));
    assert!(summary.completed);
    assert_eq!(summary.cutbacks, 0, "{:?}", seen.0);
    assert_eq!(seen.0.len(), 4);
    for (i, r) in seen.0.iter().enumerate() {
        // Newton's finish is quadratic: the last step divides the residual
        // by more than 100 (a tangent without the link's coupling: 0.90)
        let n = r.len();
        assert!(n >= 2, "increment {}: {r:?}", i + 1);
        assert!(
            r[n - 1] < 1e-2 * r[n - 2],
            "increment {}: linear finish {r:?}",
            i + 1
        );
    }
    // contact closes in the first increment (status changes first), then
    // at most 3 iterations each
    assert!(seen.0[0].len() <= 10, "{:?}", seen.0[0]);
    for r in &seen.0[1..] {
        assert!(r.len() <= 3, "{r:?}");
    }
}
