//! Program cases of the registry ([`crate::registry::CaseKind::Program`]):
//! verification problems that are not a single refinable deck against a
//! closed form — several runs per level, load histories, energy balances,
//! comparisons with other codes. Each file opens with its reference and
//! registers its cases in [`all`]; the cargo tests run the same entries.

pub mod blade_loss;
pub mod blade_loss_3d;
pub mod blankholder;
pub mod cattaneo;
pub mod contact_3d;
pub mod contact_ntf_3d;
pub mod discrete;
pub mod dynamic_buckling;
pub mod dynamic_buckling_3d;
pub mod dynamics;
pub mod energy_audit;
pub mod fenicsx;
pub mod follower;
pub mod free_bulge;
pub mod friction;
pub mod friction_3d;
pub mod friction_block;
pub mod friction_ntf_3d;
pub mod gravity;
pub mod hertz_3d_axi;
pub mod hertz_two_spheres_3d;
pub mod impact;
pub mod ironing_3d;
pub mod johnson_cook;
pub mod lame_sphere_quadratic;
pub mod mortar;
pub mod mortar_condensed;
pub mod mortar_friction;
pub mod mortar_friction_3d;
pub mod mortar_lagrange_3d;
pub mod mortar_mixed;
pub mod mortar_quadratic;
pub mod mortar_quadratic_3d;
pub mod mortar_quadratic_friction;
pub mod nagata_3d;
pub mod norton_hoff;
pub mod objectivity;
pub mod penalty_scaling;
pub mod pressure_control;
pub mod quadratic;
pub mod quadratic_contact;
pub mod quadratic_thermal;
pub mod rigid_body;
pub mod rigid_body_3d;
pub mod self_contact_3d;
pub mod self_contact_patch;
pub mod skin_pass;
pub mod sliding_cylinder;
pub mod solid;
pub mod solid_patch;
pub mod superplastic_3d;
pub mod taylor_bar;
pub mod taylor_bar_jc;
pub mod thermal_3d;
pub mod thermal_contact;
pub mod thermal_contact_quadratic;
pub mod thermal_coupling;
pub mod traction_3d;
pub mod tube_bulge;
pub mod upsetting;
pub mod upsetting_3d;
pub mod viscoplastic;

use crate::case::Quantity;
use crate::measure::Value;
use crate::registry::VerifyCase;
use ctc_engine::model::Model;
use std::path::{Path, PathBuf};

/// Every program case, in report order.
pub fn all() -> Vec<VerifyCase> {
    let mut v = thermal_contact::cases();
    v.extend(thermal_coupling::cases());
    v.extend(friction::cases());
    v.extend(cattaneo::cases());
    v.extend(upsetting::cases());
    v.extend(objectivity::cases());
    v.extend(viscoplastic::cases());
    v.extend(norton_hoff::cases());
    v.extend(pressure_control::cases());
    v.extend(free_bulge::cases());
    v.extend(penalty_scaling::cases());
    v.extend(fenicsx::cases());
    v.extend(mortar::cases());
    v.extend(mortar_quadratic::cases());
    v.extend(mortar_friction::cases());
    v.extend(solid::cases());
    v.extend(solid_patch::cases());
    v.extend(quadratic::cases());
    v.extend(lame_sphere_quadratic::cases());
    v.extend(quadratic_contact::cases());
    v.extend(quadratic_thermal::cases());
    v.extend(thermal_contact_quadratic::cases());
    v.extend(upsetting_3d::cases());
    v.extend(contact_3d::cases());
    v.extend(contact_ntf_3d::cases());
    v.extend(mortar_quadratic_3d::cases());
    v.extend(mortar_mixed::cases());
    v.extend(mortar_friction_3d::cases());
    v.extend(mortar_quadratic_friction::cases());
    v.extend(mortar_lagrange_3d::cases());
    v.extend(mortar_condensed::cases());
    v.extend(hertz_3d_axi::cases());
    v.extend(hertz_two_spheres_3d::cases());
    v.extend(friction_3d::cases());
    v.extend(friction_ntf_3d::cases());
    v.extend(nagata_3d::cases());
    v.extend(ironing_3d::cases());
    v.extend(sliding_cylinder::cases());
    v.extend(self_contact_3d::cases());
    v.extend(self_contact_patch::cases());
    v.extend(traction_3d::cases());
    v.extend(follower::cases());
    v.extend(dynamics::cases());
    v.extend(impact::cases());
    v.extend(energy_audit::cases());
    v.extend(taylor_bar::cases());
    v.extend(taylor_bar_jc::cases());
    v.extend(dynamic_buckling::cases());
    v.extend(dynamic_buckling_3d::cases());
    v.extend(thermal_3d::cases());
    v.extend(discrete::cases());
    v.extend(rigid_body::cases());
    v.extend(rigid_body_3d::cases());
    v.extend(gravity::cases());
    v.extend(johnson_cook::cases());
    v.extend(blankholder::cases());
    v.extend(skin_pass::cases());
    v.extend(tube_bulge::cases());
    v.extend(superplastic_3d::cases());
    v.extend(blade_loss::cases());
    v.extend(blade_loss_3d::cases());
    v
}

/// The example decks' directory (`examples/` of the repository).
pub fn examples_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples")
}

/// The verification decks' directory (`cases/` of this crate).
pub fn cases_dir() -> PathBuf {
    crate::default_cases_dir()
}

/// Reads `cases/<name>`.
pub fn read_case_deck(name: &str) -> Result<(PathBuf, String), String> {
    let path = cases_dir().join(name);
    let text = std::fs::read_to_string(&path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    Ok((path, text))
}

/// Compiles deck text (diagnostics rendered into the error).
pub fn compile(path: &Path, text: &str) -> Result<Model, String> {
    crate::deck::compile_text(path, text)
}

/// A measured value with its relative error against `reference`.
pub fn value(name: &'static str, computed: f64, reference: f64) -> Value {
    Value {
        quantity: Quantity::Named(name),
        reference: Some(reference),
        computed,
        error: crate::measure::relative_error(computed, reference),
    }
}

/// A value that is an error itself (no reference).
pub fn error(name: &'static str, error: f64) -> Value {
    Value {
        quantity: Quantity::Named(name),
        reference: None,
        computed: error,
        error,
    }
}
