//! The energy control of dynamic steps (`dynamic { energy_tol }`, issue 19):
//! an increment whose penalty contact gives the bodies more energy than
//! its springs stored is redone smaller.
//!
//! Reference: a penalty contact force is a spring `f = k (-g)`; over an
//! increment in which a node stays closed the scheme's work of it is the
//! change of the spring's energy `1/2 k g^2`, but an increment that
//! begins closed at a depth `d` and ends open at a gap `g1` applies the
//! start's force `k d` (weighted `alpha_f` in generalized-alpha, 1/2 in
//! the trapezoidal audit) over the whole of its motion `d + g1`: it gives
//! the body about `1/2 k d g1` more than the spring held (Laursen &
//! Chawla, IJNME 40, 1997; Armero & Petocz, CMAME 158, 1998, on energy
//! created by penalty and persistency at release). The 3D blade loss
//! (examples/blade_loss_3d.ctc) gained up to 9e4 mJ per increment this
//! way, where a blade's node left another blade's side, and blew up later.
//!
//! ```text
//!         vx = -1
//!    |<-- [ 1 x 1 block, 2 x 2 quads ]   E = 100, rho = 1, plane strain
//!    |    penalty wall k = 1e4 (area), 0.05 away
//!   wall  0 .. 1 in 20 increments (rho_inf 0.9): contact lasts ~4
//!         increments, the release increment (0.25 -> 0.3) creates 4.2e-2
//!         (8 % of the kinetic energy 0.5): the audit's alarm
//! ```
//!
//! With `energy_tol = 1e-3` (the default: `energy_tol = 0` turns it off)
//! the release is redone smaller and the block leaves with at most the
//! energy it came with.

use ctc_engine::model::Model;
use ctc_engine::solve::{self, Observer, RunSummary};

struct Quiet;
impl Observer<2> for Quiet {}

fn deck(extra: &str) -> String {
    format!(
        "analysis {{ dimension = plane_strain }}
material m {{ elastic {{ E = 100  nu = 0.3 }}  density = 1 }}
body b {{
  mesh = rectangle {{ origin = (0.05, 0)  size = (1, 1)  divisions = (2, 2) }}
  material = m
}}
tool wall = plane {{ point = (0, 0)  normal = (1, 0) }}
contact b.left -> wall {{ method = penalty {{ stiffness = 1e4 }} }}
initial_velocity b.all {{ vx = -1 }}
step fly {{ time = 0 .. 1  increments = 20  dynamic {{ {extra} }}  newton {{ tol = 1e-10 }} }}
"
    )
}

fn run(extra: &str) -> RunSummary {
    let source = ctc_lang::Source::new(std::path::Path::new("bounce.ctc"), deck(extra));
    let model: Model =
        ctc_lang::compile(&source).unwrap_or_else(|d| panic!("{}", d.render(&source)));
    solve::run(&model, &mut Quiet).unwrap_or_else(|e| panic!("{}", e.message))
}

#[test]
fn a_penalty_release_that_creates_energy_is_redone_smaller() {
    let k0 = 0.5;
    // without the control: the release increment creates energy, the
    // block leaves faster than it came, the audit warns
    let plain = run("energy_tol = 0");
    let e = plain.energy.expect("the run's audit");
    assert!(e.gain > 0.05 * k0, "{e:?}");
    assert!(e.kinetic > k0, "{e:?}");
    assert!(
        plain
            .warnings
            .iter()
            .any(|w| w.starts_with("energy audit") && w.contains("grew beyond the work")),
        "{:?}",
        plain.warnings
    );
    // with it: the increments that create more than 1e-3 of the largest
    // energy are redone smaller; no increment creates more (the record's
    // audit: gain plus stored penalty energy), the block keeps at most its
    // energy, no warning
    let controlled = run("energy_tol = 1e-3");
    assert!(controlled.completed);
    assert!(controlled.cutbacks > 0, "nothing redone");
    assert!(
        controlled
            .cutback_log
            .iter()
            .all(|c| c.reason.contains("of energy, above energy_tol")),
        "{:?}",
        controlled.cutback_log
    );
    let mut before = ctc_engine::solve::dynamics::Energy {
        kinetic: k0,
        ..Default::default()
    };
    before.close(k0);
    for r in &controlled.increments {
        let x = r.energy.expect("a dynamic increment has its audit");
        let created = x.created_since(&before);
        assert!(
            created <= 1e-3 * x.scale,
            "{}: {created:e} {x:?}",
            r.increment
        );
        before = x;
    }
    let e = controlled.energy.expect("the run's audit");
    assert!(e.gain < 1e-3 * k0 && e.kinetic < k0, "{e:?}");
    assert!(controlled.warnings.is_empty(), "{:?}", controlled.warnings);
}

#[test]
fn the_energy_control_is_on_by_default_and_off_at_zero() {
    // absent: the same run as `energy_tol = 1e-3`, bit for bit
    let default = run("");
    let explicit = run("energy_tol = 1e-3");
    assert!(default.cutbacks > 0, "the default redid nothing");
    assert_eq!(default.cutbacks, explicit.cutbacks);
    let x = |s: &RunSummary| -> Vec<u64> {
        s.increments
            .iter()
            .map(|r| r.energy.expect("audit").kinetic.to_bits())
            .collect()
    };
    assert_eq!(x(&default), x(&explicit));
    // 0: no control, the release creates energy
    let off = run("energy_tol = 0");
    assert_eq!(off.cutbacks, 0);
    assert!(off.energy.expect("audit").kinetic > 0.5);
}
