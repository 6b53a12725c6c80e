//! Recovery of nodal stress and strain for output.
//!
//! Integration point values are extrapolated to the element's nodes (quad4:
//! bilinear through the 2x2 Gauss points; tri3: the constant value), then
//! averaged over the elements sharing each node (unweighted, as Abaqus
//! does). Von Mises is computed from the averaged stress.

use super::finite::FiniteElement;
use super::{
    inelastic, quad4, tri3, ElementError, ElementResponse, MaterialPoint, PointState, Section,
};
use crate::material::{self, History, LinearElastic, NonlinearLaw};
use crate::mesh::{CellKind, Mesh};
use crate::model::{Formulation, Kinematics, Model};
use nalgebra::SVector;
use std::ops::Range;

/// Nodal fields for output; nodes not attached to any cell get zeros.
#[derive(Debug, Clone, PartialEq)]
pub struct NodalFields {
    /// Stress `[xx, yy, zz, xy]` per node (`zz` is the hoop stress for
    /// axisymmetric analyses).
    pub stress: Vec<[f64; 4]>,
    /// Strain `[xx, yy, zz, xy]` per node (engineering shear).
    pub strain: Vec<[f64; 4]>,
    /// Von Mises stress per node (of the averaged stress).
    pub von_mises: Vec<f64>,
    /// Equivalent plastic strain per node (nodal average of the
    /// integration points; zero for elastic bodies). Empty when no body of
    /// the model is plastic.
    pub equivalent_plastic_strain: Vec<f64>,
}

/// The cells of one body with their law and formulation.
#[derive(Debug, Clone)]
pub struct CellBlock {
    /// Global cell numbers.
    pub cells: Range<usize>,
    /// Constitutive law of the block.
    pub law: LinearElastic,
    /// Quadrilateral integration.
    pub formulation: Formulation,
    /// Small or finite strain.
    pub kinematics: Kinematics,
    /// The full law when it is not small-strain linear elasticity (then
    /// `law` is only its initial elastic response).
    pub nonlinear: Option<NonlinearLaw>,
}

/// One block per body of `model`.
pub fn blocks_of(model: &Model) -> Result<Vec<CellBlock>, String> {
    model
        .bodies
        .iter()
        .map(|b| {
            let m = model.materials.get(b.material).ok_or_else(|| {
                format!(
                    "body `{}` refers to missing material {}",
                    b.name, b.material
                )
            })?;
            Ok(CellBlock {
                cells: b.cells.clone(),
                law: material::build(m, model.analysis.kind)?,
                formulation: b.formulation,
                kinematics: b.kinematics,
                nonlinear: NonlinearLaw::build(m, b.kinematics, model.analysis.kind)?,
            })
        })
        .collect()
}

/// Integration point states of cell `c` for nodal displacements `u`.
/// History-dependent laws are evaluated from the virgin state (exact for
/// elastic and hyperelastic laws; for plasticity use the points stored by
/// the solver, [`nodal_fields_from_points`]).
pub fn cell_states(
    mesh: &Mesh,
    c: usize,
    u: &[[f64; 2]],
    section: &Section,
    block: &CellBlock,
) -> Result<Vec<PointState>, ElementError> {
    if let Some(law) = &block.nonlinear {
        let history = vec![History::initial(block.kinematics); 4];
        return Ok(
            nonlinear_points(mesh, c, u, section, block, law, &history, 0.0, false)?
                .1
                .iter()
                .map(|p| p.state)
                .collect(),
        );
    }
    let cell = &mesh.cells[c];
    let wrap = |e: ElementError| ElementError::new(format!("cell {c}: {}", e.message));
    match cell.kind {
        CellKind::Tri3 => {
            let (x, ue) = gather::<3, 6>(mesh, &cell.nodes, u);
            tri3::states(&x, &ue, section, &block.law).map_err(wrap)
        }
        CellKind::Quad4 => {
            let (x, ue) = gather::<4, 8>(mesh, &cell.nodes, u);
            quad4::states(&x, &ue, section, block.formulation, &block.law).map_err(wrap)
        }
    }
}

/// Element forces (and tangent if `with_tangent`) of cell `c` of a block
/// with a nonlinear law: the element's dofs in order, the response as a
/// dense row-major `nd x nd` matrix and the updated points.
#[allow(clippy::too_many_arguments)]
pub fn nonlinear_points(
    mesh: &Mesh,
    c: usize,
    u: &[[f64; 2]],
    section: &Section,
    block: &CellBlock,
    law: &NonlinearLaw,
    history: &[History],
    dt: f64,
    with_tangent: bool,
) -> Result<(NonlinearResponse, Vec<MaterialPoint>), ElementError> {
    nonlinear_points_thermal(
        mesh,
        c,
        u,
        section,
        block,
        law,
        history,
        dt,
        with_tangent,
        0.0,
    )
}

/// Like [`nonlinear_points`], with the isotropic thermal strain
/// `thermal_strain` of the cell (`crate::thermal::expansion`).
#[allow(clippy::too_many_arguments)]
pub fn nonlinear_points_thermal(
    mesh: &Mesh,
    c: usize,
    u: &[[f64; 2]],
    section: &Section,
    block: &CellBlock,
    law: &NonlinearLaw,
    history: &[History],
    dt: f64,
    with_tangent: bool,
    thermal_strain: f64,
) -> Result<(NonlinearResponse, Vec<MaterialPoint>), ElementError> {
    let cell = &mesh.cells[c];
    let wrap = |e: ElementError| ElementError::new(format!("cell {c}: {}", e.message));
    let reduced = block.formulation == Formulation::SelectiveReduced;
    match (cell.kind, block.kinematics) {
        (CellKind::Tri3, Kinematics::Small) => {
            let (x, ue) = gather::<3, 6>(mesh, &cell.nodes, u);
            let pts = tri3::integration_points(&x, section).map_err(wrap)?;
            let (r, p) = inelastic::response_with_thermal_strain(
                &pts,
                &ue,
                law,
                history,
                dt,
                with_tangent,
                thermal_strain,
            )
            .map_err(wrap)?;
            Ok((NonlinearResponse::Tri3(Box::new(r)), p))
        }
        (CellKind::Quad4, Kinematics::Small) => {
            let (x, ue) = gather::<4, 8>(mesh, &cell.nodes, u);
            let pts = quad4::integration_points(&x, section, block.formulation).map_err(wrap)?;
            let (r, p) = inelastic::response_with_thermal_strain(
                &pts,
                &ue,
                law,
                history,
                dt,
                with_tangent,
                thermal_strain,
            )
            .map_err(wrap)?;
            Ok((NonlinearResponse::Quad4(Box::new(r)), p))
        }
        (CellKind::Tri3, Kinematics::Finite) => {
            let (x, ue) = gather::<3, 6>(mesh, &cell.nodes, u);
            let pts = tri3::reference_points(&x, section).map_err(wrap)?;
            let el = FiniteElement {
                points: &pts,
                center: None,
                kind: section.kind,
                law,
                history,
                dt,
            };
            let (r, p) = el
                .response_with_thermal_strain(&ue, with_tangent, thermal_strain)
                .map_err(wrap)?;
            Ok((NonlinearResponse::Tri3(Box::new(r)), p))
        }
        (CellKind::Quad4, Kinematics::Finite) => {
            let (x, ue) = gather::<4, 8>(mesh, &cell.nodes, u);
            let (pts, center) = quad4::reference_points(&x, section).map_err(wrap)?;
            let el = FiniteElement {
                points: &pts,
                center: reduced.then_some(&center),
                kind: section.kind,
                law,
                history,
                dt,
            };
            let (r, p) = el
                .response_with_thermal_strain(&ue, with_tangent, thermal_strain)
                .map_err(wrap)?;
            Ok((NonlinearResponse::Quad4(Box::new(r)), p))
        }
    }
}

/// Element response of a nonlinear kernel, by element type.
#[derive(Debug, Clone)]
pub enum NonlinearResponse {
    /// A triangle.
    Tri3(Box<ElementResponse<6>>),
    /// A quadrilateral.
    Quad4(Box<ElementResponse<8>>),
}

/// Coordinates and displacements of a cell's nodes.
pub fn gather<const NN: usize, const ND: usize>(
    mesh: &Mesh,
    nodes: &[usize; 4],
    u: &[[f64; 2]],
) -> ([[f64; 2]; NN], SVector<f64, ND>) {
    let mut x = [[0.0; 2]; NN];
    let mut ue = SVector::<f64, ND>::zeros();
    for i in 0..NN {
        x[i] = mesh.nodes[nodes[i]];
        ue[2 * i] = u[nodes[i]][0];
        ue[2 * i + 1] = u[nodes[i]][1];
    }
    (x, ue)
}

/// Nodal-averaged stress, strain and von Mises for displacements `u`.
pub fn nodal_fields(
    mesh: &Mesh,
    blocks: &[CellBlock],
    section: &Section,
    u: &[[f64; 2]],
) -> Result<NodalFields, ElementError> {
    nodal_fields_from_points(mesh, blocks, section, u, &[])
}

/// Nodal-averaged stress, strain, von Mises and equivalent plastic strain:
/// cells with stored integration points (`points[c]` non-empty, the
/// solver's converged state of history-dependent laws) use them; the others
/// are evaluated from `u`.
pub fn nodal_fields_from_points(
    mesh: &Mesh,
    blocks: &[CellBlock],
    section: &Section,
    u: &[[f64; 2]],
    points: &[Vec<MaterialPoint>],
) -> Result<NodalFields, ElementError> {
    let nn = mesh.nodes.len();
    let mut sum = vec![[0.0f64; 9]; nn];
    let mut count = vec![0u32; nn];
    for block in blocks {
        for c in block.cells.clone() {
            let packed: Vec<[f64; 9]> = match points.get(c).filter(|p| !p.is_empty()) {
                Some(stored) => stored
                    .iter()
                    .map(|p| {
                        let mut v = [0.0; 9];
                        v[..4].copy_from_slice(p.state.stress.as_slice());
                        v[4..8].copy_from_slice(p.state.strain.as_slice());
                        v[8] = p.history.ep;
                        v
                    })
                    .collect(),
                None => cell_states(mesh, c, u, section, block)?
                    .iter()
                    .map(|s| {
                        let mut v = [0.0; 9];
                        v[..4].copy_from_slice(s.stress.as_slice());
                        v[4..8].copy_from_slice(s.strain.as_slice());
                        v
                    })
                    .collect(),
            };
            let cell = &mesh.cells[c];
            let nodal: Vec<[f64; 9]> = match cell.kind {
                CellKind::Tri3 => tri3::extrapolate(&packed).to_vec(),
                CellKind::Quad4 => quad4::extrapolate(&packed).to_vec(),
            };
            for (node, v) in cell.node_slice().iter().zip(nodal) {
                for k in 0..9 {
                    sum[*node][k] += v[k];
                }
                count[*node] += 1;
            }
        }
    }
    let plastic = blocks
        .iter()
        .any(|b| matches!(b.nonlinear, Some(NonlinearLaw::J2 { .. })));
    let mut out = NodalFields {
        stress: vec![[0.0; 4]; nn],
        strain: vec![[0.0; 4]; nn],
        von_mises: vec![0.0; nn],
        equivalent_plastic_strain: if plastic { vec![0.0; nn] } else { Vec::new() },
    };
    for n in 0..nn {
        if count[n] == 0 {
            continue;
        }
        let w = 1.0 / count[n] as f64;
        for k in 0..4 {
            out.stress[n][k] = sum[n][k] * w;
            out.strain[n][k] = sum[n][k + 4] * w;
        }
        if plastic {
            // bilinear extrapolation can undershoot: ep is never negative
            out.equivalent_plastic_strain[n] = (sum[n][8] * w).max(0.0);
        }
        out.von_mises[n] = material::von_mises(&SVector::from(out.stress[n]));
    }
    Ok(out)
}

/// [`nodal_fields`] for a whole model.
pub fn nodal_fields_of_model(model: &Model, u: &[[f64; 2]]) -> Result<NodalFields, String> {
    let blocks = blocks_of(model)?;
    nodal_fields(&model.mesh, &blocks, &Section::new(&model.analysis), u).map_err(|e| e.message)
}

/// [`nodal_fields_from_points`] for a whole model and the solver's
/// converged integration points ([`crate::solve::IncrementView::points`]).
pub fn nodal_fields_of_model_with_points(
    model: &Model,
    u: &[[f64; 2]],
    points: &[Vec<MaterialPoint>],
) -> Result<NodalFields, String> {
    let blocks = blocks_of(model)?;
    nodal_fields_from_points(
        &model.mesh,
        &blocks,
        &Section::new(&model.analysis),
        u,
        points,
    )
    .map_err(|e| e.message)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Cell;
    use crate::model::AnalysisKind;

    #[test]
    fn recovery_of_uniform_strain_on_mixed_mesh() {
        // a quad and a triangle; u = (0.01 x, -0.02 y): uniform strain everywhere
        let mesh = Mesh::new(
            vec![[0.0, 0.0], [1.0, 0.0], [1.2, 1.0], [0.0, 1.0], [2.0, 0.5]],
            vec![Cell::quad(0, 1, 2, 3), Cell::tri(1, 4, 2)],
        );
        let u: Vec<[f64; 2]> = mesh
            .nodes
            .iter()
            .map(|p| [0.01 * p[0], -0.02 * p[1]])
            .collect();
        let law = LinearElastic::new(100.0, 0.25, AnalysisKind::PlaneStress).unwrap();
        let blocks = [CellBlock {
            cells: 0..2,
            law,
            formulation: Formulation::Full,
            kinematics: Kinematics::Small,
            nonlinear: None,
        }];
        let sec = Section {
            kind: AnalysisKind::PlaneStress,
            thickness: 1.0,
        };
        let f = nodal_fields(&mesh, &blocks, &sec, &u).unwrap();
        let c = 100.0 / (1.0 - 0.0625);
        let sxx = c * (0.01 - 0.25 * 0.02);
        let syy = c * (-0.02 + 0.25 * 0.01);
        let ezz = -0.25 / 0.75 * (0.01 - 0.02);
        for n in 0..5 {
            assert!((f.stress[n][0] - sxx).abs() < 1e-12, "{:?}", f.stress[n]);
            assert!((f.stress[n][1] - syy).abs() < 1e-12);
            assert!(f.stress[n][2].abs() < 1e-12 && f.stress[n][3].abs() < 1e-12);
            assert!((f.strain[n][2] - ezz).abs() < 1e-14);
            let vm = (sxx * sxx - sxx * syy + syy * syy).sqrt();
            assert!((f.von_mises[n] - vm).abs() < 1e-12);
        }
    }
}
