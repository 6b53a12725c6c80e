//! Thermo-mechanical coupling through decks: adiabatic heating by plastic
//! dissipation against the closed form (the registry case
//! `adiabatic_heating`, `verification/src/programs/thermal_coupling.rs`),
//! and the clear refusal to restart a thermal run.

use ctc_engine::model::Model;

fn compile_text(name: &str, text: &str) -> Model {
    let src = ctc_lang::Source::new(name, text);
    match ctc_lang::compile(&src) {
        Ok(m) => m,
        Err(d) => panic!("{}", d.render(&src)),
    }
}

/// Small-strain J2 cylinder (r = 1, h = 1) compressed homogeneously, no
/// friction, insulated: all the plastic work times beta stays in it.
/// The deck of the registry case (`verification/cases/adiabatic_heating.ctc`).
fn compressed() -> String {
    let path = ctc_verification::default_cases_dir().join("adiabatic_heating.ctc");
    std::fs::read_to_string(path).expect("the adiabatic heating deck")
}

#[test]
fn adiabatic_plastic_heating_of_a_compressed_cylinder_matches_the_closed_form() {
    let case = ctc_verification::registry::find("adiabatic_heating").expect("registered");
    let report = case.run(&ctc_verification::default_cases_dir(), None, &mut |l| {
        eprintln!("{l}")
    });
    assert!(report.passed(), "{report:#?}");
}

#[test]
fn a_thermal_run_refuses_to_restart_with_a_clear_message() {
    let model = compile_text("compressed.ctc", &compressed());
    let dir = tempfile::tempdir().unwrap();
    let mut writer = ctc_engine::output::ResultWriter::create(dir.path(), &model).unwrap();
    let summary = ctc_engine::solve::run(&model, &mut writer).unwrap();
    writer.finish(&summary).unwrap();
    assert!(summary.temperature_dofs > 0);
    let message = match ctc_engine::output::ResultWriter::resume(dir.path(), &model) {
        Err(e) => e,
        Ok((mut w, cp)) => {
            ctc_engine::solve::run_from(&model, &mut w, Some(&cp))
                .unwrap_err()
                .message
        }
    };
    assert!(
        message.contains("cannot restart a thermo-mechanical run"),
        "{message}"
    );
}
