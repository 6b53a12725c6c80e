//! An inverted cell stops the run with a message naming its body and cell
//! (issue 19: the 3D blade loss's blow-up was first suspected to be an
//! inverted cell; the failure now says which).
//!
//! Reference: a finite-strain cell whose height is crushed past zero
//! cannot have `det F > 0` (the kinematics, no closed form needed): the
//! top of a neo-Hookean pad 1 high is driven down by 1.5, so past t = 2/3
//! every state the supports allow is inverted; the increments are cut
//! back to the smallest and the run stops there.
//!
//! ```text
//!   top: ux = 0, uy = ramp(0, -1.5)      +-----+-----+
//!                                        | 2   | 3   |   pad 2 x 1,
//!                                        +-----+-----+   2 x 2 quad4
//!                                        | 0   | 1   |
//!   bottom: fixed                        +-----+-----+
//! ```

use ctc_engine::model::{AnyModel, Model};
use ctc_engine::solve::{self, Observer};

struct Quiet;
impl Observer<2> for Quiet {}

const DECK: &str = "analysis { dimension = plane_strain }
material rubber { neo_hookean { E = 10  nu = 0.3 } }
body other {
  mesh = rectangle { origin = (5, 0)  size = (1, 1)  divisions = (1, 1) }
  material = rubber
  kinematics = finite
}
fix other.bottom { ux uy }
body pad {
  mesh = rectangle { origin = (0, 0)  size = (2, 1)  divisions = (2, 2) }
  material = rubber
  kinematics = finite
}
fix pad.bottom { ux uy }
fix pad.top { ux }
displace pad.top { uy = ramp(0, -1.5) }
step crush { time = 0 .. 1  increments = 3 }
";

#[test]
fn a_cell_crushed_inside_out_stops_the_run_naming_its_body_and_cell() {
    let source = ctc_lang::Source::new(std::path::Path::new("crush.ctc"), DECK.to_string());
    let model: Model<2> = match ctc_lang::compile_any(&source) {
        Ok(AnyModel::D2(m)) => m,
        Ok(_) => panic!("a 2d deck"),
        Err(d) => panic!("{}", d.render(&source)),
    };
    let err = match solve::run(&model, &mut Quiet) {
        Ok(_) => panic!("the pad cannot be crushed past its height"),
        Err(e) => e,
    };
    let m = &err.message;
    // the body and its cell (local and global numbers: `other` comes
    // first, so the pad's cells are global 1..5)
    let at = m.find("body `pad` cell ").unwrap_or_else(|| panic!("{m}"));
    let rest = &m[at + "body `pad` cell ".len()..];
    let local: usize = rest
        .split(' ')
        .next()
        .and_then(|c| c.parse().ok())
        .unwrap_or_else(|| panic!("{m}"));
    assert!(local < 4, "{m}");
    assert!(
        rest.contains(&format!(
            "(global {}): inverted element (det F = ",
            local + 1
        )),
        "{m}"
    );
    assert!(m.contains("likely cause: an element is inverted"), "{m}");
    assert!(!m.contains("body `other`"), "{m}");
    // it stopped where the pad is crushed flat
    let t = err.summary.increments.last().map_or(0.0, |r| r.time);
    assert!(t > 0.6 && t < 2.0 / 3.0, "{t}");
}
