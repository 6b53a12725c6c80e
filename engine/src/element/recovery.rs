//! Recovery of nodal stress and strain for output, and the per-body view of
//! the element kernels (law, formulation, kinematics of each block of
//! cells).
//!
//! Integration point values are extrapolated to the element's nodes
//! (multilinear through the Gauss points of quad4 and hex8; the constant
//! value of tri3 and tet4), then averaged over the elements sharing each
//! node (unweighted, as Abaqus does). Von Mises is computed from the
//! averaged stress. Besides, each cell gets the volume-weighted mean of its
//! integration points ([`CellFields`]: element values, not smoothed).

use super::kernel::{kernel_of, NonlinearInput};
use super::{ElementError, ElementMatrix, MaterialPoint, PointState, Section};
use crate::geom::{Dimension, Point};
use crate::material::{self, Constitutive, History, LinearElastic, NonlinearLaw};
use crate::mesh::Mesh;
use crate::model::{Formulation, Kinematics, Model};
use nalgebra::{Const, SVector};
use std::ops::Range;

/// Nodal fields for output; nodes not attached to any cell get zeros.
#[derive(Debug, Clone, PartialEq)]
pub struct NodalFields {
    /// Stress `[xx, yy, zz, xy, xz, yz]` per node (`zz` is the hoop stress
    /// for axisymmetric analyses).
    pub stress: Vec<[f64; 6]>,
    /// Strain `[xx, yy, zz, xy, xz, yz]` per node (engineering shear).
    pub strain: Vec<[f64; 6]>,
    /// Von Mises stress per node (of the averaged stress).
    pub von_mises: Vec<f64>,
    /// Equivalent plastic strain per node (nodal average of the
    /// integration points; zero for elastic bodies). Empty when no body of
    /// the model is plastic.
    pub equivalent_plastic_strain: Vec<f64>,
    /// Per cell: the mean of its integration points weighted by their
    /// volumes (no extrapolation, no averaging across cells: the element
    /// values, discontinuous between cells). Cells of no body get zeros.
    pub cells: CellFields,
}

/// Integration-point averages per cell (see [`NodalFields::cells`]).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CellFields {
    /// Stress `[xx, yy, zz, xy, xz, yz]` per cell.
    pub stress: Vec<[f64; 6]>,
    /// Strain per cell (engineering shear).
    pub strain: Vec<[f64; 6]>,
    /// Von Mises stress of each integration point, averaged like the
    /// stress (not the von Mises of the mean stress).
    pub von_mises: Vec<f64>,
    /// Equivalent plastic strain per cell; empty when no body is plastic.
    pub equivalent_plastic_strain: Vec<f64>,
}

/// The cells of one body with their law and formulation.
#[derive(Debug, Clone)]
pub struct CellBlock {
    /// The body's name (`body NAME { .. }`): failures name it.
    pub body: String,
    /// Global cell numbers.
    pub cells: Range<usize>,
    /// Small-strain linear elastic law of the block (for nonlinear
    /// materials, their initial elastic response).
    pub law: LinearElastic,
    /// Full or selective reduced integration (B-bar / F-bar).
    pub formulation: Formulation,
    /// Small or finite strain.
    pub kinematics: Kinematics,
    /// The full law when it is not small-strain linear elasticity.
    pub nonlinear: Option<NonlinearLaw>,
}

/// One block per body of `model`.
pub fn blocks_of<const D: usize>(model: &Model<D>) -> Result<Vec<CellBlock>, String> {
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
                body: b.name.clone(),
                cells: b.cells.clone(),
                law: material::build(m, model.analysis.kind)?,
                formulation: b.formulation,
                kinematics: b.kinematics,
                nonlinear: NonlinearLaw::build(m, b.kinematics, model.analysis.kind)?,
            })
        })
        .collect()
}

/// Reference coordinates and displacements of the nodes of cell `c`.
pub fn cell_input<const D: usize>(
    mesh: &Mesh<D>,
    c: usize,
    u: &[[f64; D]],
) -> (Vec<Point<D>>, Vec<Point<D>>) {
    let nodes = mesh.cells.nodes(c);
    (
        nodes
            .iter()
            .map(|&n| Point::<D>::from(mesh.nodes[n]))
            .collect(),
        nodes.iter().map(|&n| Point::<D>::from(u[n])).collect(),
    )
}

fn wrap(c: usize) -> impl Fn(ElementError) -> ElementError {
    move |e| ElementError::new(format!("cell {c}: {}", e.message))
}

/// Integration point states of cell `c` for nodal displacements `u`.
/// History-dependent laws are evaluated from the virgin state (exact for
/// elastic and hyperelastic laws; for plasticity use the points stored by
/// the solver, [`nodal_fields_from_points`]).
pub fn cell_states<const D: usize>(
    mesh: &Mesh<D>,
    c: usize,
    u: &[[f64; D]],
    section: &Section,
    block: &CellBlock,
) -> Result<Vec<PointState>, ElementError>
where
    Const<D>: Dimension<D>,
{
    heated_cell_states(mesh, c, u, section, block, 0.0)
}

/// [`cell_states`] of a cell carrying the isotropic thermal strain
/// `thermal_strain` (the one the solver used for the increment): the stress
/// is `D (eps - eps_th I)`, the strain reported is the total strain.
pub fn heated_cell_states<const D: usize>(
    mesh: &Mesh<D>,
    c: usize,
    u: &[[f64; D]],
    section: &Section,
    block: &CellBlock,
    thermal_strain: f64,
) -> Result<Vec<PointState>, ElementError>
where
    Const<D>: Dimension<D>,
{
    let kernel = kernel_of::<D>(mesh.cells.kind(c)).map_err(wrap(c))?;
    let (x, ue) = cell_input(mesh, c, u);
    if let Some(law) = &block.nonlinear {
        let history = vec![History::initial(block.kinematics); kernel.point_count()];
        let mut states = vec![virgin(block.kinematics); kernel.point_count()];
        let mut out = ElementMatrix::default();
        kernel
            .nonlinear(
                &NonlinearInput {
                    x: &x,
                    u: &ue,
                    section,
                    formulation: block.formulation,
                    kinematics: block.kinematics,
                    law,
                    history: &history,
                    dt: 0.0,
                    thermal_strain,
                    with_tangent: false,
                },
                &mut out,
                &mut states,
            )
            .map_err(wrap(c))?;
        return Ok(states.iter().map(|p| p.state).collect());
    }
    let mut states = kernel
        .linear_states(&x, &ue, section, block.formulation, &block.law)
        .map_err(wrap(c))?;
    if thermal_strain != 0.0 {
        let e = thermal_strain;
        let thermal_stress = block.law.stress(&SVector::from([e, e, e, 0.0, 0.0, 0.0]));
        for s in &mut states {
            s.stress -= thermal_stress;
        }
    }
    Ok(states)
}

/// A material point in the virgin state of `kinematics` (zero stress).
pub fn virgin(kinematics: Kinematics) -> MaterialPoint {
    MaterialPoint {
        state: PointState {
            position: [0.0; 3],
            volume: 0.0,
            strain: Default::default(),
            stress: Default::default(),
        },
        history: History::initial(kinematics),
    }
}

/// Nodal-averaged stress, strain and von Mises for displacements `u`.
pub fn nodal_fields<const D: usize>(
    mesh: &Mesh<D>,
    blocks: &[CellBlock],
    section: &Section,
    u: &[[f64; D]],
) -> Result<NodalFields, ElementError>
where
    Const<D>: Dimension<D>,
{
    nodal_fields_from_points(mesh, blocks, section, u, &[], &[], None)
}

/// Values packed per point for the recovery: stress, strain, `ep`.
const WIDTH: usize = 13;

/// Nodal-averaged stress, strain, von Mises and equivalent plastic strain:
/// cells with stored integration points (`points[c]` non-empty, the
/// solver's converged state of history-dependent laws) use them; the others
/// are evaluated from `u`. `only`: the cells to recover (the others add
/// nothing: the nodes around them and their cell values are only right
/// where every cell around a node is recovered); `None`: every cell.
pub fn nodal_fields_from_points<const D: usize>(
    mesh: &Mesh<D>,
    blocks: &[CellBlock],
    section: &Section,
    u: &[[f64; D]],
    points: &[Vec<MaterialPoint>],
    thermal_strain: &[f64],
    only: Option<&[bool]>,
) -> Result<NodalFields, ElementError>
where
    Const<D>: Dimension<D>,
{
    let only = |c: usize| only.is_none_or(|o| o.get(c).copied().unwrap_or(false));
    let nn = mesh.nodes.len();
    let nc = mesh.cells.len();
    let mut sum = vec![[0.0f64; WIDTH]; nn];
    let mut count = vec![0u32; nn];
    let mut packed = Vec::new();
    let mut weights = Vec::new();
    let mut cell_sum = vec![[0.0f64; WIDTH + 1]; nc];
    for block in blocks {
        for c in block.cells.clone().filter(|&c| only(c)) {
            packed.clear();
            weights.clear();
            let mut pack = |s: &PointState, ep: f64| {
                packed.extend_from_slice(s.stress.as_slice());
                packed.extend_from_slice(s.strain.as_slice());
                packed.push(ep);
                weights.push(s.volume);
            };
            match points.get(c).filter(|p| !p.is_empty()) {
                Some(stored) => stored.iter().for_each(|p| pack(&p.state, p.history.ep)),
                None => heated_cell_states(
                    mesh,
                    c,
                    u,
                    section,
                    block,
                    thermal_strain.get(c).copied().unwrap_or(0.0),
                )?
                .iter()
                .for_each(|s| pack(s, 0.0)),
            }
            if let Some(acc) = cell_sum.get_mut(c) {
                // volume weights; equal weights if the volumes are not known
                let total: f64 = weights.iter().sum();
                let equal = total.is_nan() || total <= 0.0;
                let n = weights.len().max(1) as f64;
                for (p, &wp) in packed.chunks(WIDTH).zip(&weights) {
                    let w = if equal { 1.0 / n } else { wp / total };
                    for k in 0..WIDTH {
                        acc[k] += w * p[k];
                    }
                    let stress: [f64; 6] = std::array::from_fn(|k| p[k]);
                    acc[WIDTH] += w * material::von_mises(&SVector::from(stress));
                }
            }
            let kernel = kernel_of::<D>(mesh.cells.kind(c)).map_err(wrap(c))?;
            let nodal = kernel.extrapolate(&packed, WIDTH);
            for (node, v) in mesh.cells.nodes(c).iter().zip(nodal.chunks(WIDTH)) {
                for k in 0..WIDTH {
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
        stress: vec![[0.0; 6]; nn],
        strain: vec![[0.0; 6]; nn],
        von_mises: vec![0.0; nn],
        equivalent_plastic_strain: if plastic { vec![0.0; nn] } else { Vec::new() },
        cells: CellFields {
            stress: cell_sum
                .iter()
                .map(|a| std::array::from_fn(|k| a[k]))
                .collect(),
            strain: cell_sum
                .iter()
                .map(|a| std::array::from_fn(|k| a[k + 6]))
                .collect(),
            von_mises: cell_sum.iter().map(|a| a[WIDTH]).collect(),
            equivalent_plastic_strain: if plastic {
                cell_sum.iter().map(|a| a[12]).collect()
            } else {
                Vec::new()
            },
        },
    };
    for n in 0..nn {
        if count[n] == 0 {
            continue;
        }
        let w = 1.0 / count[n] as f64;
        for k in 0..6 {
            out.stress[n][k] = sum[n][k] * w;
            out.strain[n][k] = sum[n][k + 6] * w;
        }
        if plastic {
            // multilinear extrapolation can undershoot: ep is never negative
            out.equivalent_plastic_strain[n] = (sum[n][12] * w).max(0.0);
        }
        out.von_mises[n] = material::von_mises(&SVector::from(out.stress[n]));
    }
    Ok(out)
}

/// [`nodal_fields`] for a whole model.
pub fn nodal_fields_of_model<const D: usize>(
    model: &Model<D>,
    u: &[[f64; D]],
) -> Result<NodalFields, String>
where
    Const<D>: Dimension<D>,
{
    let blocks = blocks_of(model)?;
    nodal_fields(&model.mesh, &blocks, &Section::new(&model.analysis), u).map_err(|e| e.message)
}

/// [`nodal_fields_from_points`] for a whole model, the solver's converged
/// integration points ([`crate::solve::IncrementView::points`]) and the
/// cells' thermal strains of the increment
/// ([`crate::solve::IncrementView::thermal_strain`], empty without heat).
/// `piece`: the cells of one rank's piece of a parallel output (the
/// points of the cells around its nodes are enough, and only they are
/// recovered: the piece's values are those of the whole recovery, bit for
/// bit); `None`: the whole mesh.
pub fn nodal_fields_of_model_with_points<const D: usize>(
    model: &Model<D>,
    u: &[[f64; D]],
    points: &[Vec<MaterialPoint>],
    thermal_strain: &[f64],
    piece: Option<&[usize]>,
) -> Result<NodalFields, String>
where
    Const<D>: Dimension<D>,
{
    let blocks = blocks_of(model)?;
    let only = piece.map(|cells| piece_and_ring(&model.mesh, cells));
    nodal_fields_from_points(
        &model.mesh,
        &blocks,
        &Section::new(&model.analysis),
        u,
        points,
        thermal_strain,
        only.as_deref(),
    )
    .map_err(|e| e.message)
}

/// The cells of `piece` and those sharing a node with them: every cell
/// around a node of the piece, whose extrapolated values its nodal
/// average sums (in the order of the whole mesh's cells, so the piece's
/// nodes get the whole recovery's bits).
fn piece_and_ring<const D: usize>(mesh: &Mesh<D>, piece: &[usize]) -> Vec<bool> {
    let mut node = vec![false; mesh.nodes.len()];
    for &c in piece {
        for &n in mesh.cells.nodes(c) {
            node[n] = true;
        }
    }
    (0..mesh.cells.len())
        .map(|c| mesh.cells.nodes(c).iter().any(|&n| node[n]))
        .collect()
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
            body: "b".into(),
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
        // the cell values are the same uniform state
        let vm = (sxx * sxx - sxx * syy + syy * syy).sqrt();
        for c in 0..2 {
            assert!((f.cells.stress[c][0] - sxx).abs() < 1e-12);
            assert!((f.cells.stress[c][1] - syy).abs() < 1e-12);
            assert!((f.cells.strain[c][2] - ezz).abs() < 1e-14);
            assert!((f.cells.von_mises[c] - vm).abs() < 1e-12);
        }
        assert!(f.cells.equivalent_plastic_strain.is_empty());
    }

    #[test]
    fn a_piece_recovers_its_cells_and_ring_with_the_whole_bits() {
        // a strip of four quads with a non-uniform displacement: the
        // piece of cells 2, 3 recovers them and cell 1 (sharing nodes 2
        // and 7); its nodes and cells get the whole recovery's bits
        let nodes: Vec<[f64; 2]> = (0..10)
            .map(|n| [(n % 5) as f64 + 0.1 * (n / 5) as f64, (n / 5) as f64])
            .collect();
        let cells = (0..4).map(|c| Cell::quad(c, c + 1, c + 6, c + 5)).collect();
        let mesh = Mesh::new(nodes, cells);
        let u: Vec<[f64; 2]> = mesh
            .nodes
            .iter()
            .map(|p| {
                [
                    0.01 * p[0] * p[1] + 0.003 * p[0] * p[0],
                    -0.02 * p[1] * p[0],
                ]
            })
            .collect();
        let law = LinearElastic::new(100.0, 0.25, AnalysisKind::PlaneStrain).unwrap();
        let blocks = [CellBlock {
            body: "b".into(),
            cells: 0..4,
            law,
            formulation: Formulation::Full,
            kinematics: Kinematics::Small,
            nonlinear: None,
        }];
        let sec = Section {
            kind: AnalysisKind::PlaneStrain,
            thickness: 1.0,
        };
        let whole = nodal_fields(&mesh, &blocks, &sec, &u).unwrap();
        let only = piece_and_ring(&mesh, &[2, 3]);
        assert_eq!(only, [false, true, true, true]);
        let piece =
            nodal_fields_from_points(&mesh, &blocks, &sec, &u, &[], &[], Some(&only)).unwrap();
        for n in [2, 3, 4, 7, 8, 9] {
            assert_eq!(piece.stress[n], whole.stress[n], "node {n}");
            assert_eq!(piece.strain[n], whole.strain[n]);
            assert_eq!(piece.von_mises[n], whole.von_mises[n]);
        }
        for c in [2, 3] {
            assert_eq!(piece.cells.stress[c], whole.cells.stress[c], "cell {c}");
        }
        // node 1 lacks cell 0: not the whole value (the piece does not
        // write it)
        assert_ne!(piece.stress[1], whole.stress[1]);
        assert_eq!(piece.cells.stress[0], [0.0; 6]);
    }

    #[test]
    fn cell_values_are_integration_point_means_not_nodal_averages() {
        // unit square, u_x = 0.01 x y: eps_xx = 0.01 y varies across the
        // cell; the cell mean is its centre value, the top nodes get the
        // value extrapolated to y = 1
        let mesh = Mesh::new(
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            vec![Cell::quad(0, 1, 2, 3)],
        );
        let u: Vec<[f64; 2]> = mesh
            .nodes
            .iter()
            .map(|p| [0.01 * p[0] * p[1], 0.0])
            .collect();
        let law = LinearElastic::new(100.0, 0.0, AnalysisKind::PlaneStress).unwrap();
        let blocks = [CellBlock {
            body: "b".into(),
            cells: 0..1,
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
        assert!(
            (f.cells.strain[0][0] - 0.005).abs() < 1e-15,
            "{:?}",
            f.cells.strain[0]
        );
        assert!((f.cells.stress[0][0] - 0.5).abs() < 1e-12);
        assert!((f.strain[2][0] - 0.01).abs() < 1e-14, "{:?}", f.strain[2]);
        assert!(f.strain[0][0].abs() < 1e-14);
    }
}
