//! The verification suite in one test binary: every module below was its
//! own binary. One binary links once, and the cases run on their default
//! levels are shared between the catalogue run and the tests that inspect
//! a case (`ctc_verification::registry::run_default`), so each runs once.

mod bench_small;
mod cases_coarse;
mod contact_3d;
mod contact_mortar_3d;
mod contact_ntf_3d;
mod dynamic_buckling;
mod dynamics;
mod fenicsx;
mod fenicsx_snapshots;
mod friction;
mod friction_3d;
mod friction_ntf_3d;
mod hertz_two_spheres_3d;
mod ironing_mortar_3d;
mod johnson_cook;
mod methods;
mod mortar_lagrange;
mod mortar_mixed;
mod mortar_quadratic;
mod mortar_quadratic_3d;
mod objectivity;
mod penalty_scaling;
mod quadratic;
mod quadratic_contact;
mod skin_pass;
mod stress_reduced;
mod superplastic_3d;
mod traction_3d;
mod tube_bulge;
mod upsetting;
mod viscoplastic;
