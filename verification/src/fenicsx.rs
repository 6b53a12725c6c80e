//! Comparison of ctc with FEniCSx (DOLFINx) reference solutions computed on
//! the **same** mesh with the same discretization (issue 9).
//!
//! Each [`FenicsxCase`] is a verification deck at a given refinement level.
//! Its problem is exported with [`crate::fenicsx_export`] to
//! `verification/reference/<case>.problem.json`; the script
//! `verification/fenicsx/solve.py` solves it with DOLFINx (P1 triangles /
//! Q1 quadrilaterals, small-strain elasticity, the same penalty law, gap
//! function and tributary areas, contact assembled at the slave nodes) and
//! writes `verification/reference/<case>.json` ([`Reference`]).
//! [`compare_case`] re-exports the problem (it must be identical to the
//! committed one, or the reference is stale), solves it with ctc and
//! measures the differences ([`Comparison`]). Since the discretizations are
//! identical, the differences must be at the level of the Newton tolerance.

use crate::capture::Capture;
use crate::deck::DeckFile;
use crate::fenicsx_export::{export, ProblemExport};
use ctc_engine::contact::pair_total_force;
use ctc_engine::solve::run;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// A deck solved by both ctc and FEniCSx.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FenicsxCase {
    /// Case name, also the stem of the reference files.
    pub name: &'static str,
    /// Deck file, relative to the `verification/` crate directory.
    pub deck: &'static str,
    /// Refinement level of the deck.
    pub level: usize,
}

/// The cases with committed FEniCSx references.
pub fn cases() -> Vec<FenicsxCase> {
    vec![
        FenicsxCase {
            name: "fenicsx_rigid_cylinder",
            deck: "cases/rigid_cylinder_block.ctc",
            level: 0,
        },
        FenicsxCase {
            name: "fenicsx_rigid_cylinder_level1",
            deck: "cases/rigid_cylinder_block.ctc",
            level: 1,
        },
        FenicsxCase {
            name: "fenicsx_lame_plane_strain",
            deck: "cases/lame_plane_strain.ctc",
            level: 0,
        },
        FenicsxCase {
            name: "fenicsx_hertz_sphere_tri3",
            deck: "fenicsx/cases/hertz_sphere_tri3.ctc",
            level: 0,
        },
        FenicsxCase {
            name: "fenicsx_patch_plane_strain_tri3",
            deck: "cases/patch_plane_strain.ctc",
            level: 0,
        },
        FenicsxCase {
            name: "fenicsx_rigid_sphere_block",
            deck: "fenicsx/cases/rigid_sphere_block.ctc",
            level: 0,
        },
    ]
}

/// Relative agreement required between ctc and FEniCSx (issue 9).
pub const TOLERANCE: f64 = 1e-6;

/// The `verification/` crate directory (decks of [`FenicsxCase::deck`]).
pub fn crate_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

/// The directory of the committed reference files.
pub fn reference_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("reference")
}

/// What a FEniCSx reference script writes (`<case>.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Reference {
    /// Case name.
    pub case: String,
    /// DOLFINx version used.
    pub dolfinx_version: String,
    /// Nodal displacements at the final time, ctc node numbering.
    pub displacement: Vec<[f64; 2]>,
    /// Per contact pair: the force of the tool on each slave node
    /// (`ContactExport::nodes` order) at the final time.
    pub contact_forces: Vec<Vec<[f64; 2]>>,
    /// Per contact pair: the total contact force (sum of the nodal ones).
    pub total_contact_force: Vec<[f64; 2]>,
    /// Newton iterations of each increment.
    pub newton_iterations: Vec<usize>,
    /// Relative residual after each Newton iteration, per increment (same
    /// measure as ctc's).
    #[serde(default)]
    pub residuals: Vec<Vec<f64>>,
    /// Wall time of the solve (Newton loops, assembly included), seconds.
    pub wall_time: f64,
    /// Largest relative difference between the tributary areas assembled
    /// by DOLFINx and the ones ctc exported.
    pub tributary_max_rel_diff: f64,
}

/// ctc against FEniCSx on one case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Comparison {
    /// Case name.
    pub case: String,
    /// Nodes of the mesh.
    pub nodes: usize,
    /// `max_i |u_ctc,i - u_ref,i| / max_i |u_ref,i|` (Euclidean norms of
    /// nodal vectors): relative to the largest displacement, so nodes that
    /// barely move do not inflate it.
    pub max_rel_displacement: f64,
    /// `|F_ctc - F_ref| / |F_ref|` of the total contact force (summed over
    /// pairs; `None` without contact).
    pub rel_total_force: Option<f64>,
    /// `max_i |f_ctc,i - f_ref,i| / max_i |f_ref,i|` over the nodal contact
    /// forces (`None` without contact).
    pub max_rel_nodal_force: Option<f64>,
    /// Total contact force of ctc (y component, summed over pairs).
    pub ctc_force_y: Option<f64>,
    /// Total contact force of FEniCSx (y component, summed over pairs).
    pub ref_force_y: Option<f64>,
    /// Newton iterations of ctc (all increments).
    pub ctc_iterations: usize,
    /// Newton iterations of FEniCSx (all increments).
    pub ref_iterations: usize,
    /// Wall time of ctc's solve, seconds.
    pub ctc_time: f64,
    /// Wall time of the FEniCSx solve (when the reference was generated),
    /// seconds.
    pub ref_time: f64,
    /// Largest relative difference between the tributary areas DOLFINx
    /// assembled and ctc's.
    pub tributary_rel_diff: f64,
}

impl Comparison {
    /// Whether every difference is within `tol`.
    pub fn within(&self, tol: f64) -> bool {
        self.max_rel_displacement <= tol
            && self.tributary_rel_diff <= tol
            && self.rel_total_force.is_none_or(|e| e <= tol)
            && self.max_rel_nodal_force.is_none_or(|e| e <= tol)
    }
}

fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{}: invalid JSON: {e}", path.display()))
}

/// Writes the problem export of `case` (decks relative to `crate_dir`) to
/// `out_dir/<case>.problem.json`; returns the path.
pub fn write_problem(
    case: &FenicsxCase,
    cases_dir: &Path,
    out_dir: &Path,
) -> Result<PathBuf, String> {
    let deck = DeckFile::read(&cases_dir.join(case.deck))?;
    let model = deck.compile(case.level)?;
    let problem = export(&model, case.name)?;
    let path = out_dir.join(format!("{}.problem.json", case.name));
    let text = serde_json::to_string(&problem).map_err(|e| e.to_string())?;
    std::fs::write(&path, text + "\n")
        .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    Ok(path)
}

fn norm(v: [f64; 2]) -> f64 {
    v[0].hypot(v[1])
}

fn diff(a: [f64; 2], b: [f64; 2]) -> f64 {
    norm([a[0] - b[0], a[1] - b[1]])
}

/// Largest nodal difference relative to the largest reference vector.
fn max_rel(computed: &[[f64; 2]], reference: &[[f64; 2]]) -> Result<f64, String> {
    if computed.len() != reference.len() {
        return Err(format!(
            "{} computed vectors against {} reference ones",
            computed.len(),
            reference.len()
        ));
    }
    let scale = reference.iter().map(|&v| norm(v)).fold(0.0, f64::max);
    let worst = computed
        .iter()
        .zip(reference)
        .map(|(&a, &b)| diff(a, b))
        .fold(0.0, f64::max);
    Ok(if scale > 0.0 { worst / scale } else { worst })
}

/// Solves `case` (deck relative to `crate_dir`) with ctc and compares it
/// with the committed reference in
/// `reference_dir`. Fails when the committed problem export differs from
/// the current one (mesh, loads or contact changed: regenerate).
pub fn compare_case(
    case: &FenicsxCase,
    crate_dir: &Path,
    reference_dir: &Path,
) -> Result<Comparison, String> {
    let deck = DeckFile::read(&crate_dir.join(case.deck))?;
    let model = deck.compile(case.level)?;
    let problem = export(&model, case.name)?;
    let committed: ProblemExport =
        read_json(&reference_dir.join(format!("{}.problem.json", case.name)))?;
    // Compared through the same JSON text round trip (serde_json's float
    // parsing is not always correctly rounded): equal iff the text is.
    let current: ProblemExport = serde_json::to_string(&problem)
        .and_then(|t| serde_json::from_str(&t))
        .map_err(|e| e.to_string())?;
    if committed != current {
        return Err(format!(
            "{}: the committed problem export differs from the deck's (mesh, loads or contact \
             changed): regenerate the references with verification/fenicsx/regenerate.sh",
            case.name
        ));
    }
    let reference: Reference = read_json(&reference_dir.join(format!("{}.json", case.name)))?;
    let mut capture = Capture::default();
    let start = Instant::now();
    let summary =
        run(&model, &mut capture).map_err(|e| format!("{}: ctc: {}", case.name, e.message))?;
    let ctc_time = start.elapsed().as_secs_f64();
    let state = capture
        .last
        .as_ref()
        .ok_or_else(|| format!("{}: ctc converged no increment", case.name))?;
    let max_rel_displacement = max_rel(&state.displacement, &reference.displacement)
        .map_err(|e| format!("{}: displacements: {e}", case.name))?;
    let (mut rel_total_force, mut max_rel_nodal_force) = (None, None);
    let (mut ctc_force_y, mut ref_force_y) = (None, None);
    if !problem.contacts.is_empty() {
        let mut ctc_total = [0.0; 2];
        let mut ref_total = [0.0; 2];
        let mut ctc_nodal = Vec::new();
        let mut ref_nodal = Vec::new();
        for (p, cp) in problem.contacts.iter().enumerate() {
            let contacts = state.contact.get(p).map(Vec::as_slice).unwrap_or(&[]);
            let f = pair_total_force(contacts);
            ctc_total = [ctc_total[0] + f[0], ctc_total[1] + f[1]];
            let r = reference
                .total_contact_force
                .get(p)
                .ok_or_else(|| format!("{}: reference lacks pair {p}", case.name))?;
            ref_total = [ref_total[0] + r[0], ref_total[1] + r[1]];
            let refs = reference
                .contact_forces
                .get(p)
                .ok_or_else(|| format!("{}: reference lacks pair {p}", case.name))?;
            for (i, &node) in cp.nodes.iter().enumerate() {
                let c = contacts
                    .iter()
                    .find(|c| c.node == node)
                    .map_or([0.0; 2], |c| c.force);
                ctc_nodal.push(c);
                ref_nodal.push(*refs.get(i).ok_or_else(|| {
                    format!("{}: reference lacks slave node {i} of pair {p}", case.name)
                })?);
            }
        }
        let scale = norm(ref_total);
        rel_total_force = Some(diff(ctc_total, ref_total) / scale.max(f64::MIN_POSITIVE));
        max_rel_nodal_force = Some(max_rel(&ctc_nodal, &ref_nodal)?);
        ctc_force_y = Some(ctc_total[1]);
        ref_force_y = Some(ref_total[1]);
    }
    Ok(Comparison {
        case: case.name.into(),
        nodes: model.mesh.nodes.len(),
        max_rel_displacement,
        rel_total_force,
        max_rel_nodal_force,
        ctc_force_y,
        ref_force_y,
        ctc_iterations: summary.newton_iterations,
        ref_iterations: reference.newton_iterations.iter().sum(),
        ctc_time,
        ref_time: reference.wall_time,
        tributary_rel_diff: reference.tributary_max_rel_diff,
    })
}

/// Markdown table of comparisons (the issue-9 "ctc vs FEniCSx" table).
pub fn table(rows: &[Comparison]) -> String {
    let opt = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{x:.1e}"));
    let mut s = String::from(
        "| case | nodes | max rel. du | rel. dF total | max rel. dF nodal | F_y ctc | F_y FEniCSx | Newton ctc | Newton FEniCSx | time ctc (s) | time FEniCSx (s) |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        s.push_str(&format!(
            "| {} | {} | {:.1e} | {} | {} | {} | {} | {} | {} | {:.3} | {:.3} |\n",
            r.case,
            r.nodes,
            r.max_rel_displacement,
            opt(r.rel_total_force),
            opt(r.max_rel_nodal_force),
            r.ctc_force_y.map_or("-".into(), |f| format!("{f:.6e}")),
            r.ref_force_y.map_or("-".into(), |f| format!("{f:.6e}")),
            r.ctc_iterations,
            r.ref_iterations,
            r.ctc_time,
            r.ref_time
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn max_rel_is_relative_to_the_largest_reference_vector() {
        let r = [[0.0, 2.0], [0.0, 0.0]];
        let c = [[0.0, 2.0], [0.0, 1e-3]];
        assert!((max_rel(&c, &r).unwrap() - 5e-4).abs() < 1e-15);
        assert!(max_rel(&c[..1], &r).is_err());
    }

    #[test]
    fn every_case_deck_exists() {
        let dir = crate_dir();
        for c in cases() {
            assert!(dir.join(c.deck).is_file(), "{}", c.deck);
        }
    }
}
