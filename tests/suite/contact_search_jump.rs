//! A rigid blade that jumps past the block's surface in one increment
//! (farther than the search window `prof`) misses the contact: the run
//! says so in a warning naming the nodes instead of staying silent. The
//! same motion in small increments finds the contact and gives no warning.

use ctc_engine::solve::{Observer, RunSummary};

fn deck(increments: usize) -> String {
    format!(
        r#"
analysis {{ dimension = plane_strain }}
material soft {{ elastic {{ E = 1e3  nu = 0.3 }} }}
body block {{
  mesh = rectangle {{ origin = (-1, -1)  size = (2, 1)  divisions = (4, 2)  element = quad4 }}
  material = soft
}}
# free side below the blade: walked from right to left
tool blade = polyline {{ points = [(2, 0.05), (-2, 0.05)]
                        motion {{ uy = ramp(0, -0.1) }} }}
contact block.top -> blade {{
  method = penalty {{ stiffness = 1e3 }}
  prof = 0.02
}}
fix block.bottom {{ ux uy }}
step push {{ time = 0 .. 1  increments = {increments} }}
"#
    )
}

#[derive(Default)]
struct Warnings(Vec<String>);

impl Observer for Warnings {
    fn warning(&mut self, message: &str) {
        self.0.push(message.to_string());
    }
}

fn run(increments: usize) -> (RunSummary, Vec<String>, f64) {
    let src = ctc_lang::Source::new("jump.ctc", deck(increments));
    let model = ctc_lang::compile(&src).unwrap_or_else(|d| panic!("{}", d.render(&src)));
    let mut seen = Warnings::default();
    let summary = ctc_engine::solve::run(&model, &mut seen).unwrap();
    let max_penetration = summary
        .increments
        .iter()
        .map(|i| i.max_penetration)
        .fold(0.0, f64::max);
    (summary, seen.0, max_penetration)
}

#[test]
fn contact_search_warns_when_the_tool_jumps_past_the_surface() {
    let (summary, seen, _) = run(1);
    assert!(summary.completed);
    // the blade ended 0.05 inside the block, deeper than prof: missed
    assert_eq!(summary.increments[0].active_contacts, 0);
    // the jump, then (after the run) the pair that never closed
    assert_eq!(summary.warnings.len(), 2, "{:?}", summary.warnings);
    assert_eq!(seen, summary.warnings);
    assert!(
        summary.warnings[1].starts_with("contact pair `block.top -> blade` never closed"),
        "{:?}",
        summary.warnings
    );
    let w = &summary.warnings[0];
    // the 5 top nodes (y = 0) of the 5 x 3 node grid: 10..=14
    assert!(
        w.contains("5 slave node(s) of contact `block.top -> blade`"),
        "{w}"
    );
    assert!(w.contains("nodes 10, 11, 12, 13, 14"), "{w}");
    assert!(w.contains("prof = 2.000e-2"), "{w}");
}

#[test]
fn contact_search_small_increments_find_the_contact_without_warning() {
    let (summary, seen, max_penetration) = run(10);
    assert!(summary.completed);
    assert!(summary.warnings.is_empty(), "{:?}", summary.warnings);
    assert!(seen.is_empty());
    assert!(summary.increments.last().unwrap().active_contacts > 0);
    assert!(max_penetration > 0.0);
}
