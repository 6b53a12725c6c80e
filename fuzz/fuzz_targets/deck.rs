//! The deck compiler on arbitrary text: parse, validate, lower (meshes
//! built, absurd sizes refused by diagnostics), then what `ctc check`
//! does with a model (the solver's model checks, the start-inside
//! warnings) and `--explain`. Nothing may panic, hang or exhaust memory.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
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
