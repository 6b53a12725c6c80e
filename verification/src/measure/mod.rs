//! Extraction of the verification quantities from a converged state.
//!
//! One file per family of closed forms: [`hertz`], [`lame`], [`patch`].
//! Every function returns all the quantities of its family; the case's
//! checks decide which ones are judged.

pub mod hertz;
pub mod lame;
pub mod patch;

use crate::capture::FinalState;
use crate::case::{Quantity, Reference};
use ctc_engine::model::{AnalysisKind, MaterialLaw, Model};

/// One measured quantity.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Value {
    /// What was measured.
    pub quantity: Quantity,
    /// The reference value (`None` for quantities that are errors
    /// themselves, such as the L2 error of a profile).
    pub reference: Option<f64>,
    /// The computed value.
    pub computed: f64,
    /// Relative error (normalisation documented on [`Quantity`]).
    pub error: f64,
}

/// A contact pressure profile prepared for plotting, in physical units.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ProfileData {
    /// Computed (abscissa from the axis, pressure) of each slave node.
    pub points: Vec<[f64; 2]>,
    /// Reference contact half-width (Hertz, computed load).
    pub a: f64,
    /// Reference peak pressure.
    pub p0: f64,
    /// Estimated half-width.
    pub a_computed: f64,
}

/// Everything measured on one converged run.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Measured {
    /// The quantities.
    pub values: Vec<Value>,
    /// Characteristic mesh size used for convergence rates.
    pub h: f64,
    /// Pressure profile (contact cases).
    pub profile: Option<ProfileData>,
}

/// Measures the quantities of `reference` on the final state of a run.
pub fn measure(
    reference: &Reference,
    model: &Model,
    state: &FinalState,
) -> Result<Measured, String> {
    match reference {
        Reference::HertzCylinder {
            young,
            poisson,
            radius,
            pair,
            axis,
            half_model,
            abscissa,
        } => {
            expect_kind(model, &[AnalysisKind::PlaneStrain])?;
            expect_material(model, *young, *poisson)?;
            let setup = hertz::HertzSetup::cylinder(
                *young,
                *poisson,
                *radius,
                *pair,
                *axis,
                *half_model,
                *abscissa,
            );
            hertz::measure(model, state, &setup)
        }
        Reference::HertzSphere {
            young,
            poisson,
            radius,
            pair,
        } => {
            expect_kind(model, &[AnalysisKind::Axisymmetric])?;
            expect_material(model, *young, *poisson)?;
            hertz::measure(
                model,
                state,
                &hertz::HertzSetup::sphere(*young, *poisson, *radius, *pair),
            )
        }
        Reference::Lame {
            cylinder,
            center,
            axisymmetric,
        } => {
            let kind = if *axisymmetric {
                AnalysisKind::Axisymmetric
            } else {
                AnalysisKind::PlaneStrain
            };
            expect_kind(model, &[kind])?;
            expect_material(model, cylinder.young, cylinder.poisson)?;
            lame::measure(model, state, cylinder, *center, *axisymmetric)
        }
        Reference::Patch { patch, pair } => {
            expect_material(model, patch.young, patch.poisson)?;
            patch::measure(model, state, patch, *pair)
        }
    }
}

/// Fails unless the analysis kind is one of `kinds`.
fn expect_kind(model: &Model, kinds: &[AnalysisKind]) -> Result<(), String> {
    if kinds.contains(&model.analysis.kind) {
        Ok(())
    } else {
        Err(format!(
            "the deck's analysis is {:?} but the reference is for {:?}",
            model.analysis.kind, kinds
        ))
    }
}

/// Fails unless every material of the model is linear elastic with the
/// constants the reference was computed with (deck and case must agree).
fn expect_material(model: &Model, young: f64, poisson: f64) -> Result<(), String> {
    for m in &model.materials {
        match m.law {
            MaterialLaw::LinearElastic {
                young: e,
                poisson: nu,
            } => {
                if (e - young).abs() > 1e-12 * young.abs() || (nu - poisson).abs() > 1e-12 {
                    return Err(format!(
                        "material `{}` has E = {e}, nu = {nu} but the reference uses E = {young}, nu = {poisson}: \
                         the deck and the case disagree",
                        m.name
                    ));
                }
            }
            _ => {
                return Err(format!(
                    "material `{}` is not linear elastic but the reference is",
                    m.name
                ))
            }
        }
    }
    Ok(())
}

/// Sum of the reaction forces of all nodes.
pub fn total_reaction(state: &FinalState) -> [f64; 2] {
    state
        .reaction
        .iter()
        .fold([0.0, 0.0], |s, r| [s[0] + r[0], s[1] + r[1]])
}

/// Largest edge length of all cells (reference configuration).
pub fn max_cell_edge(model: &Model) -> f64 {
    let nodes = &model.mesh.nodes;
    let mut h: f64 = 0.0;
    for c in &model.mesh.cells {
        let n = c.nodes;
        for i in 0..n.len() {
            let (a, b) = (nodes[n[i]], nodes[n[(i + 1) % n.len()]]);
            h = h.max(((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt());
        }
    }
    h
}

/// Relative error `|computed - reference| / |reference|` (absolute error
/// when the reference is 0).
pub fn relative_error(computed: f64, reference: f64) -> f64 {
    let d = (computed - reference).abs();
    if reference == 0.0 {
        d
    } else {
        d / reference.abs()
    }
}

/// Hand-built models for the unit tests of the measurement modules.
#[cfg(test)]
pub(crate) mod test_model {
    use ctc_engine::mesh::Mesh;
    use ctc_engine::model::*;

    /// A one-body linear-elastic model on `mesh`, no loads, one step.
    pub fn one_body(mesh: Mesh, kind: AnalysisKind, young: f64, poisson: f64) -> Model {
        ctc_engine::testkit::ModelBuilder::new(kind)
            .elastic("m", young, poisson)
            .body("b", mesh, "m")
            .step("s", 1.0, 1)
            .build()
    }
}
