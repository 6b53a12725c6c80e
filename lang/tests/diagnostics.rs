//! Snapshots of the rendered diagnostics of decks with mistakes
//! (`tests/bad_decks/*.ctc`, one mistake per deck unless the name says
//! otherwise). Review changes with `cargo insta review` or rerun with
//! `INSTA_UPDATE=always` and read the diff of `tests/snapshots/`.

use ctc_lang::{check, Source};

/// The rendered diagnostics of `tests/bad_decks/<name>.ctc`.
fn rendered(name: &str) -> String {
    let path = format!("tests/bad_decks/{name}.ctc");
    let src = Source::read(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    check(&src).diagnostics.render(&src)
}

macro_rules! decks {
    ($($name:ident),* $(,)?) => {
        const DECKS: &[&str] = &[$(stringify!($name)),*];
        $(
            #[test]
            fn $name() {
                let out = rendered(stringify!($name));
                insta::with_settings!({ omit_expression => true }, {
                    insta::assert_snapshot!(stringify!($name), out);
                });
            }
        )*
    };
}

decks!(
    syntax_missing_equals,
    unclosed_block,
    misspelled_key,
    misspelled_material,
    unknown_body_in_set,
    young_not_positive,
    poisson_half,
    rate_laws,
    pressure_control_errors,
    negative_thickness,
    energy_tol_negative,
    zero_divisions,
    empty_time_range,
    unknown_tool,
    unknown_enum_value,
    duplicate_material,
    missing_material,
    three_d,
    plastic_block,
    empty_selection,
    bad_knots,
    overlapping_steps,
    several_errors,
    mesh_file_not_found,
    mesh_file_bad_line,
    unknown_item,
    pressure_on_nodes,
    stray_brace,
    wrong_value_types,
    unknown_set_name,
    missing_analysis,
    unknown_history,
    augmented_lagrange_bad_update,
    table_not_increasing,
    unknown_time_function,
    warnings_only,
    axisymmetric_negative_radius,
    unterminated_string,
    comma_in_block,
    contact_master_unknown_body,
    contact_master_unknown_set,
    contact_bad_strategy,
    contact_mortar_unsupported,
    contact_smoothing_unsupported,
    friction_bad_coulomb,
    several_thermal_errors,
    expr_division_by_zero,
    expr_not_whole,
    expr_parameter_twice,
    expr_sqrt_negative,
    expr_syntax_operator,
    expr_unknown_function,
    expr_unknown_parameter,
    include_cycle,
    include_error_inside,
    contact_misspelled_gmsh_group,
    contact_quadratic_faces,
    contact_quadratic_generator,
    contact_thermal_deformable_3d,
    quadratic_order_three,
    quadratic_reduced_triangles,
    quadratic_reduced_without_order,
    quadratic_sweep_input,
    include_missing,
    quoted_set_unknown,
    union_nodes_as_edges,
    union_two_bodies,
    union_unknown_set,
    units_mixed_sum,
    units_power_of_length,
    units_unknown_system,
    units_unknown_unit,
    units_without_system,
    units_wrong_dimension,
    selection_3d_empty,
    selection_3d_coordinates,
    selection_z_in_planar,
    follower_on_small_strain_body,
);

#[test]
fn every_bad_deck_has_a_snapshot_test() {
    let mut on_disk: Vec<String> = std::fs::read_dir("tests/bad_decks")
        .expect("tests/bad_decks")
        .filter_map(|e| e.ok())
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().to_string();
            name.strip_suffix(".ctc").map(str::to_string)
        })
        .collect();
    on_disk.sort();
    let mut tested: Vec<String> = DECKS.iter().map(|s| s.to_string()).collect();
    tested.sort();
    assert_eq!(on_disk, tested);
}

#[test]
fn every_bad_deck_fails_except_the_warning_one() {
    for name in DECKS {
        let src = Source::read(format!("tests/bad_decks/{name}.ctc")).expect("deck");
        let result = check(&src);
        if *name == "warnings_only" {
            assert!(result.model.is_some());
            assert_eq!(result.diagnostics.error_count(), 0);
            assert!(result.diagnostics.warning_count() > 0);
        } else {
            assert!(result.model.is_none(), "{name} compiled");
            assert!(result.diagnostics.error_count() > 0, "{name}");
        }
    }
}
