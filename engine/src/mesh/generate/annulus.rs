//! Annular sector (or full ring), polar structured.

use super::common::{
    add_boundary, chain, divisions, finite_point, node_budget, polar_point, positive, push_quad,
};
use super::Grading;
use crate::mesh::{CellKind, Mesh, MeshError};

const NAME: &str = "annulus";

/// Builds the annular sector; see [`super::MeshSpec::Annulus`]. Nodes ring by
/// ring from the inner radius out, each ring by increasing angle;
/// circumferential divisions are uniform.
#[allow(clippy::too_many_arguments)]
pub fn annulus(
    center: [f64; 2],
    inner: f64,
    outer: f64,
    start_angle: f64,
    end_angle: f64,
    radial: usize,
    circumferential: usize,
    radial_grading: Grading,
    kind: CellKind,
) -> Result<Mesh, MeshError> {
    finite_point(NAME, "center", center)?;
    positive(NAME, "inner radius", inner)?;
    positive(NAME, "outer radius", outer)?;
    if outer <= inner {
        return Err(MeshError::new(format!(
            "{NAME}: outer radius {outer} must be larger than inner radius {inner}"
        )));
    }
    if !start_angle.is_finite() || !end_angle.is_finite() {
        return Err(MeshError::new(format!(
            "{NAME}: start and end angles must be finite, got {start_angle} and {end_angle}"
        )));
    }
    let span = end_angle - start_angle;
    if span <= 0.0 || span > 360.0 * (1.0 + 1e-12) {
        return Err(MeshError::new(format!(
            "{NAME}: end angle {end_angle} must be above start angle {start_angle} by at most 360 degrees"
        )));
    }
    let full = (span - 360.0).abs() <= 360.0 * 1e-12;
    divisions(NAME, "radial", radial, 1)?;
    divisions(
        NAME,
        "circumferential",
        circumferential,
        if full { 3 } else { 1 },
    )?;
    if span / circumferential as f64 >= 180.0 {
        return Err(MeshError::new(format!(
            "{NAME}: {circumferential} circumferential division(s) over {span} degrees: each must span less than 180 degrees"
        )));
    }
    radial_grading.check("annulus radial grading")?;
    let per_ring = if full {
        circumferential
    } else {
        circumferential + 1
    };
    node_budget(
        NAME,
        radial.checked_add(1).and_then(|r| r.checked_mul(per_ring)),
    )?;

    let radii: Vec<f64> = radial_grading
        .points(radial)
        .iter()
        .map(|t| inner + (outer - inner) * t)
        .collect();
    let radii_exact = {
        let mut r = radii;
        r[radial] = outer;
        r
    };
    let angle = |k: usize| {
        if k == circumferential {
            end_angle
        } else {
            start_angle + span * k as f64 / circumferential as f64
        }
    };
    let mid_angle = start_angle + 0.5 * span;
    let id = |i: usize, k: usize| i * per_ring + k % per_ring;

    let mut mesh = Mesh::default();
    for &r in &radii_exact {
        for k in 0..per_ring {
            mesh.nodes.push(polar_point(center, r, angle(k)));
        }
    }
    for i in 0..radial {
        for k in 0..circumferential {
            // mirrored diagonals about the middle angle of a sector
            let low_side = full || angle(k) + 0.5 * span / (circumferential as f64) < mid_angle;
            push_quad(
                &mut mesh.cells,
                kind,
                [id(i, k), id(i + 1, k), id(i + 1, k + 1), id(i, k + 1)],
                low_side,
            );
        }
    }
    let outer_walk: Vec<usize> = (0..=circumferential).map(|k| id(radial, k)).collect();
    let inner_walk: Vec<usize> = (0..=circumferential).rev().map(|k| id(0, k)).collect();
    add_boundary(&mut mesh, "outer", chain(&outer_walk));
    add_boundary(&mut mesh, "inner", chain(&inner_walk));
    if !full {
        let start: Vec<usize> = (0..=radial).map(|i| id(i, 0)).collect();
        let end: Vec<usize> = (0..=radial).rev().map(|i| id(i, circumferential)).collect();
        add_boundary(&mut mesh, "start", chain(&start));
        add_boundary(&mut mesh, "end", chain(&end));
    }
    Ok(mesh)
}
