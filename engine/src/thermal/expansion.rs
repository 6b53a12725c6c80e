//! Thermal expansion: the isotropic thermal strain
//! `eps_th = alpha (T - T_ref)` of each cell (nodal temperatures averaged
//! over the cell), taken out of the mechanical strain.
//!
//! - small strain, nonlinear laws: the law sees `eps - eps_th [1, 1, 1, 0, 0, 0]`;
//! - finite strain: multiplicative split `F = F_m (1 + eps_th)`: the law sees
//!   `F_m = F / (1 + eps_th)` and the Kirchhoff stress scales by
//!   `(1 + eps_th)^3` (`element::finite`);
//! - small-strain linear elastic cells: `sigma = D (B u - eps_th)`, so
//!   `f_int = K u - f_th` with `f_th = sum B^T D eps_th dV`, computed per
//!   unit thermal strain once ([`unit_thermal_force`]).
//!
//! Plane strain keeps `eps_zz = 0` in total, so a heated constrained plane
//! strain body carries `sigma_zz = -E alpha dT` when also held in-plane. A
//! solid (3D) cell takes the same route with its six strain components: a
//! fully constrained heated brick carries `sigma = -E alpha dT / (1 - 2 nu)`
//! in every direction.

use crate::element::{kernel_of, ElementError, Section};
use crate::geom::{Dimension, Point};
use crate::material::LinearElastic;
use crate::mesh::Mesh;
use crate::model::thermal::ThermalScene;
use crate::model::{Formulation, Model};
use nalgebra::Const;

/// Thermal strain of every cell for nodal temperatures `temperature`
/// (0 in cells whose material has no thermal block).
pub fn cell_thermal_strains<const D: usize>(
    model: &Model<D>,
    scene: &ThermalScene,
    temperature: &[f64],
) -> Vec<f64> {
    let mut out = vec![0.0; model.mesh.cells.len()];
    for body in &model.bodies {
        let Some(Some(m)) = scene.materials.get(body.material) else {
            continue;
        };
        if m.expansion == 0.0 {
            continue;
        }
        for c in body.cells.clone() {
            let nodes = model.mesh.cells.nodes(c);
            let mean = nodes.iter().map(|&n| temperature[n]).sum::<f64>() / nodes.len() as f64;
            out[c] = m.expansion * (mean - m.reference);
        }
    }
    out
}

/// Mean temperature of every cell (0 in cells without temperature).
pub fn cell_temperatures<const D: usize>(
    model: &Model<D>,
    scene: &ThermalScene,
    temperature: &[f64],
) -> Vec<f64> {
    let mut out = vec![0.0; model.mesh.cells.len()];
    for body in &model.bodies {
        if !matches!(scene.materials.get(body.material), Some(Some(_))) {
            continue;
        }
        for c in body.cells.clone() {
            let nodes = model.mesh.cells.nodes(c);
            out[c] = nodes.iter().map(|&n| temperature[n]).sum::<f64>() / nodes.len() as f64;
        }
    }
    out
}

/// `sum B^T D [1, 1, 1, 0, 0, 0] dV` of a small-strain linear elastic
/// cell: the nodal force of a unit thermal strain.
pub fn unit_thermal_force<const D: usize>(
    mesh: &Mesh<D>,
    c: usize,
    section: &Section,
    formulation: Formulation,
    law: &LinearElastic,
) -> Result<Vec<Point<D>>, ElementError>
where
    Const<D>: Dimension<D>,
{
    kernel_of::<D>(mesh.cells.kind(c))?.thermal_unit_force(
        &mesh.cell_points(c),
        section,
        formulation,
        law,
    )
}
