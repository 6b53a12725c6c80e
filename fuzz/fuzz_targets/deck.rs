//! The deck compiler on arbitrary text: parse, validate, lower (meshes
//! built, absurd sizes refused by diagnostics), then what `ctc check`
//! does with a model (the solver's model checks, the start-inside
//! warnings) and `--explain`. Nothing may panic, hang or exhaust memory.
#![no_main]

use libfuzzer_sys::fuzz_target;

/// Cells per generated mesh the harness allows (the compiler's own limit
/// is 4 000 000): a mutated seed asking for millions of cells is refused
/// by the same "too many cells" diagnostic, in microseconds instead of
/// the seconds it takes to build and check such a mesh (fuzz/README.md).
const FUZZ_CELLS: i64 = 2_000;

fuzz_target!(|data: &[u8]| {
    ctc_lang::validate::set_cell_limit(FUZZ_CELLS);
    let text = String::from_utf8_lossy(data);
    let src = ctc_lang::Source::new("fuzz.ctc", text.into_owned());
    let compiled = ctc_lang::check(&src);
    let _ = compiled.diagnostics.render(&src);
    if let Some(model) = compiled.model {
        let _ = ctc_engine::solve::check::check_model(&model);
        let _ = ctc_engine::solve::health::start_inside(&model);
        let _ = ctc_lang::explain(&model);
    }
});
