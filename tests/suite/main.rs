//! The integration tests of the `ctc` program in one test binary (one link,
//! and the modules run side by side on the test threads); each module was
//! its own binary. `petsc_run.rs` stays apart: it needs the `petsc` feature.

mod blade_loss;
mod blade_loss_3d;
mod cli;
mod cli_bench_search;
mod common;
mod contact_deformable;
mod contact_search_jump;
mod determinism;
mod dynamic_fields;
mod energy_alarm;
mod energy_control;
mod example_files;
mod example_iges_punch;
mod example_superplastic_forming;
mod example_tube_hydroforming;
mod example_two_cylinders_mixed_3d;
mod examples;
mod follower_plate;
mod friction_cattaneo;
mod inverted_cell;
mod pattern_growth_3d;
mod predictor_retake;
mod pressure_cap;

mod relative_penalty;
mod robust_fuzz;
mod robust_kill;
mod robust_restart;
mod robust_stress_report;
mod run_trust;
mod sweep;
mod thermal_3d;
mod thermal_contact;
mod thermal_coupling;
