//! Verification case 8 (thermal contact and frictional heating) as
//! `ctc verify` runs it: the registry entries `thermal_contact_tool`,
//! `thermal_contact_blocks` and `frictional_heating`
//! (`verification/src/programs/thermal_contact.rs`, with the references and
//! sketches), judged against their tolerances.

use ctc_verification::registry;

/// Runs the registry case `name` (every level) and asserts it passes.
fn passes(name: &str) {
    registry::run_passing(name);
}

#[test]
fn case8_thermal_contact_block_on_tool_matches_the_closed_form_at_two_pressures() {
    passes("thermal_contact_tool");
}

#[test]
fn case8_frictional_heating_of_a_sliding_block_equals_mu_rn_slip() {
    passes("frictional_heating");
}

#[test]
fn case8_thermal_contact_two_blocks_node_to_segment_matches_the_closed_form() {
    passes("thermal_contact_blocks");
}
