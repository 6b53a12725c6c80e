//! First impact: with `cut_at_impact = true` the increment in which a node
//! first touches is cut at the fraction found by the constant-velocity
//! intersection, so the accepted increment ends at the impact.

mod support;

use ctc_engine::model::{Dirichlet, TimeFunction};
use ctc_engine::solve::{run, IncrementView, Observer};
use support::friction::{Block, Drive};

#[derive(Default)]
struct Times(Vec<f64>);

impl Observer for Times {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        self.0.push(v.time);
        Ok(())
    }
}

/// The block moves down rigidly (every node's uy prescribed, so its path
/// is exactly at constant velocity) by 0.04 over the first step (one
/// increment) onto a plane 0.013 below: the base meets it at t = 0.325.
fn falling_block(cut: bool) -> (Vec<f64>, usize) {
    let b = Block::new(0.0, 0.3, Drive::LeftSide(0.0));
    let mut m = b.model();
    // (the weight stays: it gives the residual a force scale)
    m.tools[0].geometry = ctc_engine::model::ToolGeometry::Plane {
        point: [0.0, -0.013],
        normal: [0.0, 1.0],
    };
    m.constraints.push(Dirichlet {
        label: "fall".into(),
        nodes: (0..m.mesh.nodes.len()).collect(),
        component: 1,
        value: TimeFunction::Ramp {
            t0: 0.0,
            t1: 1.0,
            v0: 0.0,
            v1: -0.04,
        },
    });
    if let Some(f) = m.contacts[0].friction.as_mut() {
        f.cut_at_impact = cut;
    }
    let mut times = Times::default();
    let s = run(&m, &mut times).unwrap_or_else(|e| panic!("{}", e.message));
    (times.0, s.cutbacks)
}

#[test]
fn increment_is_cut_at_the_first_impact() {
    let (times, cutbacks) = falling_block(true);
    assert!((times[0] - 0.325).abs() < 1e-9, "{times:?}");
    assert!(cutbacks >= 1, "{times:?}");
    assert_eq!(times.last(), Some(&2.0));
    let (times, cutbacks) = falling_block(false);
    assert_eq!((times[0], cutbacks), (1.0, 0));
}
