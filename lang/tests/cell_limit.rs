//! The per-mesh cell limit can be lowered by an embedding program (the
//! cargo-fuzz `deck` target): a deck above it gets the "too many cells"
//! diagnostic, not a mesh. Its own test binary: the limit is process-wide.

use ctc_lang::{check, Source};

const DECK: &str = "analysis { dimension = plane_strain }
material m { elastic { E = 1000  nu = 0.3 } }
body b {
  mesh = rectangle { origin = (0, 0)  size = (1, 1)  divisions = (8, 4)  element = quad4 }
  material = m
}
fix b.bottom { ux uy }
step s { time = 0 .. 1  increments = 1 }
";

#[test]
fn a_lowered_cell_limit_refuses_larger_meshes_with_a_diagnostic() {
    let src = Source::new("limit.ctc", DECK.to_string());
    assert!(check(&src).model.is_some());
    ctc_lang::validate::set_cell_limit(31);
    let c = check(&src);
    let text = c.diagnostics.render(&src);
    assert!(c.model.is_none());
    assert!(
        text.contains("the `rectangle` mesh would have 32 cells")
            && text.contains("at most 31 cells per generated mesh"),
        "{text}"
    );
    ctc_lang::validate::set_cell_limit(32);
    assert!(check(&src).model.is_some());
    // clamped: never above the compiler's own limit
    ctc_lang::validate::set_cell_limit(i64::MAX);
    assert_eq!(
        ctc_lang::validate::cell_limit(),
        ctc_lang::validate::MAX_CELLS
    );
}
