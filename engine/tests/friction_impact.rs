//! First impact: with `cut_at_impact = true` the increment in which a node
//! first touches is cut at the fraction found by the constant-velocity
//! intersection, so the accepted increment ends at the impact.

mod friction_support;

use ctc_engine::model::{TimeFunction, ToolMotion};
use ctc_engine::solve::{run, IncrementView, Observer};
use friction_support::{Block, Drive};

#[derive(Default)]
struct Times(Vec<f64>);

impl Observer for Times {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        self.0.push(v.time);
        Ok(())
    }
}

/// The plane starts 0.01 below the block (top held) and rises by 0.04 over
/// the first step (one increment): the base meets it at t = 0.25.
fn rising_plane(cut: bool) -> (Vec<f64>, usize) {
    let mut b = Block::new(0.0, 0.3, Drive::LeftSide(0.0));
    b.squeeze = Some(0.0);
    let mut m = b.model();
    m.tools[0].geometry = ctc_engine::model::ToolGeometry::Plane {
        point: [0.0, -0.01],
        normal: [0.0, 1.0],
    };
    m.tools[0].motion = ToolMotion {
        uy: TimeFunction::Ramp {
            t0: 0.0,
            t1: 1.0,
            v0: 0.0,
            v1: 0.04,
        },
        ..ToolMotion::fixed()
    };
    if let Some(f) = m.contacts[0].friction.as_mut() {
        f.cut_at_impact = cut;
    }
    let mut times = Times::default();
    let s = run(&m, &mut times).unwrap_or_else(|e| panic!("{}", e.message));
    (times.0, s.cutbacks)
}

#[test]
fn increment_is_cut_at_the_first_impact() {
    let (times, cutbacks) = rising_plane(true);
    assert!((times[0] - 0.25).abs() < 1e-9, "{times:?}");
    assert!(cutbacks >= 1, "{times:?}");
    assert_eq!(times.last(), Some(&2.0));
    let (times, _) = rising_plane(false);
    assert!((times[0] - 0.25).abs() > 1e-3, "{times:?}");
}
