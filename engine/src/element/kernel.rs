//! [`CellKernel`]: everything the assembly, the recovery and the heat
//! solver need from one cell kind, behind one object-safe trait, and the
//! registry that maps a mesh cell kind to its kernel in dimension `D`.
//!
//! [`Kernel`] implements the trait once for every reference cell:
//! monomorphized inside (node arrays of length `NN`, dual numbers with
//! `ND = D NN` directions), slices at the interface. A new element type is
//! a file in [`super::reference`] and one line in the registry
//! (`crate::geom::Dimension::kernel`).

use super::finite::FiniteElement;
use super::geometry::{centre_point, quadrature_points, shape_point};
use super::reference::{
    Hex20, Hex20R, Hex27, Hex8, Quad4, Quad8, Quad8R, Quad9, ReferenceCell, Tet10, Tet4, Tri3, Tri6,
};
use super::small::{inelastic_response, linear_response, linear_states, strain_points};
use super::{ElementError, ElementMatrix, MaterialPoint, PointState, Section};
use crate::geom::{Dimension, Point};
use crate::material::{History, LinearElastic, NonlinearLaw, Strain};
use crate::mesh::CellKind;
use crate::model::{Formulation, Kinematics, MassMatrix};
use nalgebra::Const;
use std::marker::PhantomData;

/// Shape data of one integration point, for the heat solver.
#[derive(Debug, Clone, PartialEq)]
pub struct ShapeData<const D: usize> {
    /// Shape function values.
    pub n: Vec<f64>,
    /// Cartesian gradients per node.
    pub dndx: Vec<Point<D>>,
    /// Position.
    pub position: Point<D>,
    /// Volume weight.
    pub volume: f64,
}

/// Inputs of a nonlinear (history-dependent or finite-strain) evaluation.
#[derive(Debug, Clone, Copy)]
pub struct NonlinearInput<'a, const D: usize> {
    /// Reference coordinates of the nodes.
    pub x: &'a [Point<D>],
    /// Nodal displacements.
    pub u: &'a [Point<D>],
    /// Section (analysis kind, thickness).
    pub section: &'a Section,
    /// Full or selective reduced (B-bar / F-bar).
    pub formulation: Formulation,
    /// Small or finite strain.
    pub kinematics: Kinematics,
    /// The law.
    pub law: &'a NonlinearLaw,
    /// Internal variables at the start of the increment, one per point.
    pub history: &'a [History],
    /// Time increment.
    pub dt: f64,
    /// Isotropic thermal strain of the cell.
    pub thermal_strain: f64,
    /// Whether the tangent is wanted.
    pub with_tangent: bool,
}

/// The kernel of one cell kind in dimension `D`.
pub trait CellKernel<const D: usize>: Sync + std::fmt::Debug {
    /// The cell kind.
    fn kind(&self) -> CellKind;

    /// Number of nodes.
    fn node_count(&self) -> usize;

    /// Number of integration points (the same for every kinematics and
    /// formulation).
    fn point_count(&self) -> usize;

    /// Shape data at the integration points (reference configuration).
    fn shape_points(
        &self,
        x: &[Point<D>],
        section: &Section,
    ) -> Result<Vec<ShapeData<D>>, ElementError>;

    /// Small-strain linear elasticity: internal force at `u` and, if
    /// `with_tangent`, the (constant) stiffness.
    #[allow(clippy::too_many_arguments)]
    fn linear(
        &self,
        x: &[Point<D>],
        u: &[Point<D>],
        section: &Section,
        formulation: Formulation,
        law: &LinearElastic,
        with_tangent: bool,
        out: &mut ElementMatrix<D>,
    ) -> Result<(), ElementError>;

    /// Small-strain linear elasticity: stress and strain at the points.
    fn linear_states(
        &self,
        x: &[Point<D>],
        u: &[Point<D>],
        section: &Section,
        formulation: Formulation,
        law: &LinearElastic,
    ) -> Result<Vec<PointState>, ElementError>;

    /// `sum B_a^T D [1, 1, 1, 0, 0, 0] dV`: the nodal force of a unit
    /// isotropic thermal strain of a linear elastic cell.
    fn thermal_unit_force(
        &self,
        x: &[Point<D>],
        section: &Section,
        formulation: Formulation,
        law: &LinearElastic,
    ) -> Result<Vec<Point<D>>, ElementError>;

    /// Nonlinear law: internal force, tangent (if requested) and the
    /// updated integration points (`states`, one per point).
    fn nonlinear(
        &self,
        input: &NonlinearInput<'_, D>,
        out: &mut ElementMatrix<D>,
        states: &mut [MaterialPoint],
    ) -> Result<(), ElementError>;

    /// Nodal values from integration-point values: `at_points` holds
    /// `width` values per point; the result `width` values per node.
    fn extrapolate(&self, at_points: &[f64], width: usize) -> Vec<f64>;

    /// Mass matrix of density `rho` in the reference configuration:
    /// `M_ab = int rho N_a N_b dV` (`dV` with the thickness or `2 pi r`)
    /// by the cell's mass rule, `NN x NN` row-major; the node block is
    /// `M_ab I`. [`MassMatrix::Lumped`]: the row sums on the diagonal, or
    /// the HRZ diagonal (`M_aa` scaled to the total mass) when a row sum is
    /// not positive.
    fn mass(
        &self,
        x: &[Point<D>],
        section: &Section,
        rho: f64,
        kind: MassMatrix,
    ) -> Result<Vec<f64>, ElementError>;
}

/// The consistent `NN x NN` mass `m` (row-major) lumped onto its diagonal:
/// row sums, or HRZ (Hinton, Rock & Zienkiewicz 1976: the consistent
/// diagonal scaled to the total mass) when a row sum is not positive.
pub fn lump(m: &mut [f64], nn: usize) {
    let rows: Vec<f64> = (0..nn)
        .map(|a| m[a * nn..(a + 1) * nn].iter().sum())
        .collect();
    let total: f64 = rows.iter().sum();
    let diag: Vec<f64> = if rows.iter().all(|r| *r > 0.0) {
        rows
    } else {
        let d: f64 = (0..nn).map(|a| m[a * nn + a]).sum();
        (0..nn).map(|a| m[a * nn + a] * total / d).collect()
    };
    m.fill(0.0);
    for (a, v) in diag.into_iter().enumerate() {
        m[a * nn + a] = v;
    }
}

/// The kernel of reference cell `C` (`NN` nodes, `ND = D NN` dofs).
pub struct Kernel<C, const D: usize, const NN: usize, const ND: usize>(PhantomData<fn() -> C>);

impl<C, const D: usize, const NN: usize, const ND: usize> std::fmt::Debug for Kernel<C, D, NN, ND>
where
    C: ReferenceCell<D, NN>,
{
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Kernel({})", C::KIND.name())
    }
}

impl<C, const D: usize, const NN: usize, const ND: usize> Kernel<C, D, NN, ND>
where
    C: ReferenceCell<D, NN>,
{
    /// Rejects a kernel instantiated with `ND != D NN` at compile time.
    const DOFS: () = assert!(ND == D * NN, "a kernel has D NN dofs");

    /// The kernel (a constant: kernels hold no data).
    pub const fn new() -> Self {
        let () = Self::DOFS;
        Kernel(PhantomData)
    }

    fn nodes(x: &[Point<D>]) -> Result<[Point<D>; NN], ElementError> {
        x.try_into().map_err(|_| {
            ElementError::new(format!(
                "{} has {NN} nodes, got {}",
                C::KIND.name(),
                x.len()
            ))
        })
    }
}

impl<C, const D: usize, const NN: usize, const ND: usize> Default for Kernel<C, D, NN, ND>
where
    C: ReferenceCell<D, NN>,
{
    fn default() -> Self {
        Self::new()
    }
}

impl<C, const D: usize, const NN: usize, const ND: usize> CellKernel<D> for Kernel<C, D, NN, ND>
where
    C: ReferenceCell<D, NN>,
    Const<D>: Dimension<D>,
{
    fn kind(&self) -> CellKind {
        C::KIND
    }

    fn node_count(&self) -> usize {
        NN
    }

    fn point_count(&self) -> usize {
        C::QUADRATURE.len()
    }

    fn shape_points(
        &self,
        x: &[Point<D>],
        section: &Section,
    ) -> Result<Vec<ShapeData<D>>, ElementError> {
        let x = Self::nodes(x)?;
        Ok(quadrature_points::<D, NN, C>(&x, section)?
            .into_iter()
            .map(|p| ShapeData {
                n: p.n.to_vec(),
                dndx: p.dndx.to_vec(),
                position: p.position,
                volume: p.volume,
            })
            .collect())
    }

    fn linear(
        &self,
        x: &[Point<D>],
        u: &[Point<D>],
        section: &Section,
        formulation: Formulation,
        law: &LinearElastic,
        with_tangent: bool,
        out: &mut ElementMatrix<D>,
    ) -> Result<(), ElementError> {
        let (x, u) = (Self::nodes(x)?, Self::nodes(u)?);
        let points = strain_points::<D, NN, C>(&x, section, formulation)?;
        out.resize(NN);
        linear_response(
            &points,
            &u,
            law,
            with_tangent,
            &mut out.force,
            &mut out.stiffness,
        );
        Ok(())
    }

    fn linear_states(
        &self,
        x: &[Point<D>],
        u: &[Point<D>],
        section: &Section,
        formulation: Formulation,
        law: &LinearElastic,
    ) -> Result<Vec<PointState>, ElementError> {
        let (x, u) = (Self::nodes(x)?, Self::nodes(u)?);
        let points = strain_points::<D, NN, C>(&x, section, formulation)?;
        Ok(linear_states(&points, &u, law))
    }

    fn thermal_unit_force(
        &self,
        x: &[Point<D>],
        section: &Section,
        formulation: Formulation,
        law: &LinearElastic,
    ) -> Result<Vec<Point<D>>, ElementError> {
        let x = Self::nodes(x)?;
        let points = strain_points::<D, NN, C>(&x, section, formulation)?;
        let sigma = law.d * Strain::from([1.0, 1.0, 1.0, 0.0, 0.0, 0.0]);
        let mut f = vec![Point::<D>::zeros(); NN];
        for p in &points {
            for (fa, b) in f.iter_mut().zip(&p.b) {
                *fa += b.tr_mul(&sigma) * p.volume;
            }
        }
        Ok(f)
    }

    fn nonlinear(
        &self,
        input: &NonlinearInput<'_, D>,
        out: &mut ElementMatrix<D>,
        states: &mut [MaterialPoint],
    ) -> Result<(), ElementError> {
        let (x, u) = (Self::nodes(input.x)?, Self::nodes(input.u)?);
        match input.kinematics {
            Kinematics::Small => {
                let points = strain_points::<D, NN, C>(&x, input.section, input.formulation)?;
                inelastic_response::<D, NN, ND>(
                    &points,
                    &u,
                    input.law,
                    input.history,
                    input.dt,
                    input.thermal_strain,
                    input.with_tangent,
                    out,
                    states,
                )
            }
            Kinematics::Finite => {
                let points = quadrature_points::<D, NN, C>(&x, input.section)?;
                for p in &points {
                    super::planar::check_radius(input.section, p.position[0])?;
                }
                let fbar = input.formulation == Formulation::SelectiveReduced
                    && C::QUADRATURE.len() > 1
                    && C::SELECTIVE_REDUCED;
                let centre = if fbar {
                    let c = centre_point::<D, NN, C>(&x, input.section)?;
                    super::planar::check_radius(input.section, c.position[0])?;
                    Some(c)
                } else {
                    None
                };
                let el = FiniteElement {
                    points: &points,
                    centre: centre.as_ref(),
                    section: input.section,
                    law: input.law,
                    history: input.history,
                    dt: input.dt,
                    thermal_strain: input.thermal_strain,
                };
                el.response::<ND>(&u, input.with_tangent, out, states)
            }
        }
    }

    fn extrapolate(&self, at_points: &[f64], width: usize) -> Vec<f64> {
        let mut out = vec![0.0; NN * width];
        for node in 0..NN {
            for (p, vals) in at_points.chunks(width).enumerate() {
                let w = C::extrapolation(node, p);
                for (o, v) in out[node * width..(node + 1) * width].iter_mut().zip(vals) {
                    *o += w * v;
                }
            }
        }
        out
    }

    fn mass(
        &self,
        x: &[Point<D>],
        section: &Section,
        rho: f64,
        kind: MassMatrix,
    ) -> Result<Vec<f64>, ElementError> {
        let x = Self::nodes(x)?;
        let mut m = vec![0.0; NN * NN];
        for (xi, w) in C::MASS_QUADRATURE {
            let p = shape_point::<D, NN, C>(&x, xi, *w, section)?;
            for a in 0..NN {
                for b in 0..NN {
                    m[a * NN + b] += rho * p.n[a] * p.n[b] * p.volume;
                }
            }
        }
        if kind == MassMatrix::Lumped {
            lump(&mut m, NN);
        }
        Ok(m)
    }
}

/// Linear triangle.
pub static TRI3: Kernel<Tri3, 2, 3, 6> = Kernel::new();
/// Bilinear quadrilateral.
pub static QUAD4: Kernel<Quad4, 2, 4, 8> = Kernel::new();
/// Linear tetrahedron.
pub static TET4: Kernel<Tet4, 3, 4, 12> = Kernel::new();
/// Trilinear hexahedron.
pub static HEX8: Kernel<Hex8, 3, 8, 24> = Kernel::new();
/// Quadratic triangle.
pub static TRI6: Kernel<Tri6, 2, 6, 12> = Kernel::new();
/// Serendipity quadrilateral.
pub static QUAD8: Kernel<Quad8, 2, 8, 16> = Kernel::new();
/// Serendipity quadrilateral, reduced integration.
pub static QUAD8R: Kernel<Quad8R, 2, 8, 16> = Kernel::new();
/// Biquadratic quadrilateral.
pub static QUAD9: Kernel<Quad9, 2, 9, 18> = Kernel::new();
/// Quadratic tetrahedron.
pub static TET10: Kernel<Tet10, 3, 10, 30> = Kernel::new();
/// Serendipity hexahedron.
pub static HEX20: Kernel<Hex20, 3, 20, 60> = Kernel::new();
/// Serendipity hexahedron, reduced integration.
pub static HEX20R: Kernel<Hex20R, 3, 20, 60> = Kernel::new();
/// Triquadratic hexahedron.
pub static HEX27: Kernel<Hex27, 3, 27, 81> = Kernel::new();

/// The kernel of cell kind `kind` in dimension `D`, or why there is none
/// (a 3D cell in a planar analysis, or the reverse).
pub fn kernel_of<const D: usize>(kind: CellKind) -> Result<&'static dyn CellKernel<D>, ElementError>
where
    Const<D>: Dimension<D>,
{
    <Const<D> as Dimension<D>>::kernel(kind).ok_or_else(|| {
        ElementError::new(format!(
            "{} cells are not {} cells (the mesh does not match the analysis dimension)",
            kind.name(),
            <Const<D> as Dimension<D>>::NAME
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::testing::{check_element, dense, Shape};
    use crate::model::AnalysisKind;
    use proptest::prelude::*;

    fn section(kind: AnalysisKind, thickness: f64) -> Section {
        Section { kind, thickness }
    }

    fn p2(v: [[f64; 2]; 3]) -> Vec<Point<2>> {
        v.iter().map(|&p| Point::<2>::from(p)).collect()
    }

    #[test]
    fn tri3_hand_stiffness_unit_right_triangle() {
        // E = 1, nu = 0, plane stress, t = 1, nodes (0,0) (1,0) (0,1):
        // dN0/dx = -1, dN0/dy = -1, area 1/2, D = diag(1, 1, 0, 1/2):
        // K_00 = A (dN0/dx^2 + dN0/dy^2 / 2) = 0.75, K_01 = A (1/2) dN0/dy dN0/dx = 0.25.
        let law = LinearElastic::new(1.0, 0.0, AnalysisKind::PlaneStress).unwrap();
        let x = p2([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        let mut r = ElementMatrix::default();
        TRI3.linear(
            &x,
            &[Point::<2>::zeros(); 3],
            &section(AnalysisKind::PlaneStress, 1.0),
            Formulation::Full,
            &law,
            true,
            &mut r,
        )
        .unwrap();
        let k = dense(&r);
        assert!((k[(0, 0)] - 0.75).abs() < 1e-15);
        assert!((k[(0, 1)] - 0.25).abs() < 1e-15);
        assert!((k[(2, 2)] - 0.5).abs() < 1e-15); // node 1: A dN1/dx^2 = 0.5
        assert!((k[(3, 3)] - 0.25).abs() < 1e-15); // node 1: A dN1/dx^2 / 2
        assert!((k[(2, 5)] - 0.0).abs() < 1e-15); // dN1/dy = 0, dN2/dx = 0
    }

    #[test]
    fn clockwise_and_inverted_cells_are_rejected() {
        let law = LinearElastic::new(1.0, 0.3, AnalysisKind::PlaneStrain).unwrap();
        let x = p2([[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]]);
        let mut r = ElementMatrix::default();
        let sec = section(AnalysisKind::PlaneStrain, 1.0);
        let e = TRI3
            .linear(
                &x,
                &[Point::<2>::zeros(); 3],
                &sec,
                Formulation::Full,
                &law,
                true,
                &mut r,
            )
            .unwrap_err();
        assert!(e.message.contains("counter-clockwise"), "{}", e.message);
        let law3 = LinearElastic::new(1.0, 0.3, AnalysisKind::Solid).unwrap();
        let t: Vec<Point<3>> = [
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
        ]
        .iter()
        .map(|&p| Point::<3>::from(p))
        .collect();
        let mut r3 = ElementMatrix::default();
        let e = TET4
            .linear(
                &t,
                &[Point::<3>::zeros(); 4],
                &section(AnalysisKind::Solid, 1.0),
                Formulation::Full,
                &law3,
                true,
                &mut r3,
            )
            .unwrap_err();
        assert!(e.message.contains("gmsh ordering"), "{}", e.message);
    }

    #[test]
    fn volumes_of_rectangle_ring_and_box() {
        let x: Vec<Point<2>> = [[1.0, 0.0], [3.0, 0.0], [3.0, 1.0], [1.0, 1.0]]
            .iter()
            .map(|&p| Point::<2>::from(p))
            .collect();
        let v = |kind| -> f64 {
            QUAD4
                .shape_points(&x, &section(kind, 2.5))
                .unwrap()
                .iter()
                .map(|p| p.volume)
                .sum()
        };
        assert!((v(AnalysisKind::PlaneStrain) - 2.0 * 2.5).abs() < 1e-13);
        // ring volume pi (r_o^2 - r_i^2) h
        assert!((v(AnalysisKind::Axisymmetric) - std::f64::consts::PI * 8.0).abs() < 1e-12);
        // a triangle of area 1/2 with centroid radius r_c sweeps 2 pi r_c / 2
        let t = p2([[2.0, 0.0], [3.0, 0.0], [2.0, 1.0]]);
        let p = TRI3
            .shape_points(&t, &section(AnalysisKind::Axisymmetric, 1.0))
            .unwrap();
        assert!((p[0].volume - std::f64::consts::PI * 7.0 / 3.0).abs() < 1e-14);
        // a 1 x 2 x 3 box and a tetrahedron of volume 1/6
        let b: Vec<Point<3>> = crate::element::reference::Hex8::NODES
            .iter()
            .map(|c| Point::<3>::new(0.5 * (c[0] + 1.0), c[1] + 1.0, 1.5 * (c[2] + 1.0)))
            .collect();
        let vb: f64 = HEX8
            .shape_points(&b, &section(AnalysisKind::Solid, 1.0))
            .unwrap()
            .iter()
            .map(|p| p.volume)
            .sum();
        assert!((vb - 6.0).abs() < 1e-13);
        let tt: Vec<Point<3>> = Tet4::NODES.iter().map(|&c| Point::<3>::from(c)).collect();
        let vt = TET4
            .shape_points(&tt, &section(AnalysisKind::Solid, 1.0))
            .unwrap()[0]
            .volume;
        assert!((vt - 1.0 / 6.0).abs() < 1e-15);
    }

    #[test]
    fn quad4_node_on_axis_is_allowed_and_off_axis_cells_are_not() {
        let x: Vec<Point<2>> = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
            .iter()
            .map(|&p| Point::<2>::from(p))
            .collect();
        let law = LinearElastic::new(1.0, 0.3, AnalysisKind::Axisymmetric).unwrap();
        let sec = section(AnalysisKind::Axisymmetric, 1.0);
        let mut r = ElementMatrix::default();
        for f in [Formulation::Full, Formulation::SelectiveReduced] {
            QUAD4
                .linear(&x, &[Point::<2>::zeros(); 4], &sec, f, &law, true, &mut r)
                .unwrap();
            assert!(r.stiffness.iter().all(|b| b.iter().all(|v| v.is_finite())));
        }
        let neg: Vec<Point<2>> = x
            .iter()
            .map(|p| Point::<2>::new(p[0] - 2.0, p[1]))
            .collect();
        let e = QUAD4
            .linear(
                &neg,
                &[Point::<2>::zeros(); 4],
                &sec,
                Formulation::Full,
                &law,
                true,
                &mut r,
            )
            .unwrap_err();
        assert!(e.message.contains("r >= 0"), "{}", e.message);
    }

    /// Bending energy ratio nu = 0.4999 / nu = 0.3 of the mode `u_x = xi eta`
    /// (`xi eta zeta` in 3D): large for full integration (volumetric
    /// locking), about 1 with B-bar / F-bar.
    fn locking_ratio<const D: usize>(
        kernel: &dyn CellKernel<D>,
        x: &[Point<D>],
        u: &[Point<D>],
        kind: AnalysisKind,
        formulation: Formulation,
        finite: bool,
    ) -> f64 {
        let sec = section(kind, 1.0);
        let energy = |nu: f64| {
            let mut r = ElementMatrix::default();
            let zero = vec![Point::<D>::zeros(); x.len()];
            if finite {
                let law = NonlinearLaw::Hencky {
                    elastic: crate::material::j2::Elastic::from_young(1.0, nu),
                };
                let hist = vec![History::initial(Kinematics::Finite); kernel.point_count()];
                let mut states = vec![
                    crate::element::recovery::virgin(Kinematics::Finite);
                    kernel.point_count()
                ];
                kernel
                    .nonlinear(
                        &NonlinearInput {
                            x,
                            u: &zero,
                            section: &sec,
                            formulation,
                            kinematics: Kinematics::Finite,
                            law: &law,
                            history: &hist,
                            dt: 0.0,
                            thermal_strain: 0.0,
                            with_tangent: true,
                        },
                        &mut r,
                        &mut states,
                    )
                    .unwrap();
            } else {
                let law = LinearElastic::new(1.0, nu, kind).unwrap();
                kernel
                    .linear(x, &zero, &sec, formulation, &law, true, &mut r)
                    .unwrap();
            }
            let k = dense(&r);
            let uv = nalgebra::DVector::from_iterator(
                k.nrows(),
                u.iter().flat_map(|p| p.iter().copied()),
            );
            (uv.transpose() * k * &uv)[(0, 0)]
        };
        energy(0.4999) / energy(0.3)
    }

    #[test]
    fn bbar_and_fbar_remove_volumetric_locking_in_bending() {
        let sq: Vec<Point<2>> = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
            .iter()
            .map(|&p| Point::<2>::from(p))
            .collect();
        let u2: Vec<Point<2>> = [1.0, -1.0, 1.0, -1.0]
            .iter()
            .map(|&v| Point::<2>::new(v, 0.0))
            .collect();
        for kind in [AnalysisKind::PlaneStrain, AnalysisKind::Axisymmetric] {
            let x: Vec<Point<2>> = if kind == AnalysisKind::Axisymmetric {
                sq.iter().map(|p| p + Point::<2>::new(1.0, 0.0)).collect()
            } else {
                sq.clone()
            };
            for finite in [false, true] {
                let full = locking_ratio(&QUAD4, &x, &u2, kind, Formulation::Full, finite);
                let reduced =
                    locking_ratio(&QUAD4, &x, &u2, kind, Formulation::SelectiveReduced, finite);
                assert!(full > 100.0, "{kind:?} finite={finite} full: {full}");
                assert!(reduced < 2.0, "{kind:?} finite={finite} reduced: {reduced}");
            }
        }
        let cube: Vec<Point<3>> = Hex8::NODES.iter().map(|&c| Point::<3>::from(c)).collect();
        let u3: Vec<Point<3>> = Hex8::NODES
            .iter()
            .map(|c| Point::<3>::new(c[0] * c[1], 0.0, 0.0))
            .collect();
        for finite in [false, true] {
            let full = locking_ratio(
                &HEX8,
                &cube,
                &u3,
                AnalysisKind::Solid,
                Formulation::Full,
                finite,
            );
            let reduced = locking_ratio(
                &HEX8,
                &cube,
                &u3,
                AnalysisKind::Solid,
                Formulation::SelectiveReduced,
                finite,
            );
            assert!(full > 100.0, "hex8 finite={finite} full: {full}");
            assert!(reduced < 2.0, "hex8 finite={finite} reduced: {reduced}");
        }
    }

    /// The mass properties every kernel must have (consistent and lumped):
    /// total mass `rho V` (`V` the cell's volume by its stiffness rule: the
    /// measure `t` or `2 pi r` included), the kinetic energy of a rigid
    /// translation `1/2 rho V |v|^2`, symmetry, positive definiteness of the
    /// consistent mass and a positive lumped diagonal.
    fn check_mass<const D: usize>(
        kernel: &dyn CellKernel<D>,
        x: &[Point<D>],
        sec: &Section,
        rho: f64,
    ) -> Result<(), String> {
        let nn = kernel.node_count();
        let volume: f64 = kernel
            .shape_points(x, sec)
            .map_err(|e| e.message)?
            .iter()
            .map(|p| p.volume)
            .sum();
        let total = rho * volume;
        let v = Point::<D>::from_fn(|c, _| 0.3 + c as f64);
        for kind in [MassMatrix::Consistent, MassMatrix::Lumped] {
            let m = kernel.mass(x, sec, rho, kind).map_err(|e| e.message)?;
            let sum: f64 = m.iter().sum();
            if (sum - total).abs() > 1e-12 * total {
                return Err(format!("{kind:?}: total mass {sum} != rho V = {total}"));
            }
            // kinetic energy of the rigid translation v (node blocks M_ab I)
            let ke: f64 = 0.5 * m.iter().sum::<f64>() * v.norm_squared();
            let mut ke_blocks = 0.0;
            for a in 0..nn {
                for b in 0..nn {
                    ke_blocks += 0.5 * m[a * nn + b] * v.dot(&v);
                }
            }
            let want = 0.5 * total * v.norm_squared();
            if (ke - want).abs() > 1e-12 * want || (ke_blocks - want).abs() > 1e-12 * want {
                return Err(format!(
                    "{kind:?}: rigid kinetic energy {ke_blocks} != {want}"
                ));
            }
            let dm = nalgebra::DMatrix::from_row_slice(nn, nn, &m);
            if (&dm - dm.transpose()).amax() > 1e-14 * dm.amax() {
                return Err(format!("{kind:?}: not symmetric"));
            }
            let eig = dm.symmetric_eigen().eigenvalues;
            let min = eig.min();
            if min.is_nan() || min <= 1e-8 * eig.max() {
                return Err(format!(
                    "{kind:?}: not positive definite, eigenvalues {eig:?}"
                ));
            }
            if kind == MassMatrix::Lumped {
                let off = (0..nn * nn)
                    .filter(|i| i / nn != i % nn)
                    .map(|i| m[i].abs())
                    .sum::<f64>();
                if off != 0.0 {
                    return Err("lumped mass has off-diagonal terms".into());
                }
            }
        }
        Ok(())
    }

    /// The quadratic cells with their own mass rules (tri6 and tet10 by the
    /// collapsed Gauss rules, quad8R and hex20R by the full rule of quad8 and
    /// hex20): total mass, rigid kinetic energy, symmetry, positive definite
    /// consistent and positive lumped (HRZ) mass, on affinely mapped cells
    /// (plane strain, plane stress and axisymmetric in 2D).
    #[test]
    fn quadratic_cells_have_a_regular_mass() {
        fn nodes<const D: usize, const NN: usize, C: ReferenceCell<D, NN>>() -> Vec<Point<D>> {
            C::NODES
                .iter()
                .map(|xi| {
                    Point::<D>::from_fn(|c, _| {
                        // x = A xi + b with a skewed A and x > 0 (radius)
                        let mut v = if c == 0 { 2.0 } else { 0.0 };
                        for (k, x) in xi.iter().enumerate() {
                            v += x * if k == c { 1.2 + 0.1 * c as f64 } else { 0.15 };
                        }
                        v
                    })
                })
                .collect()
        }
        let planar: [(&dyn CellKernel<2>, Vec<Point<2>>); 4] = [
            (&TRI6, nodes::<2, 6, Tri6>()),
            (&QUAD8, nodes::<2, 8, Quad8>()),
            (&QUAD8R, nodes::<2, 8, Quad8R>()),
            (&QUAD9, nodes::<2, 9, Quad9>()),
        ];
        for (kernel, x) in &planar {
            for kind in [
                AnalysisKind::PlaneStrain,
                AnalysisKind::PlaneStress,
                AnalysisKind::Axisymmetric,
            ] {
                check_mass(*kernel, x, &section(kind, 2.5), 7.8)
                    .unwrap_or_else(|e| panic!("{:?} {kind:?}: {e}", kernel.node_count()));
            }
        }
        let solid: [(&dyn CellKernel<3>, Vec<Point<3>>); 4] = [
            (&TET10, nodes::<3, 10, Tet10>()),
            (&HEX20, nodes::<3, 20, Hex20>()),
            (&HEX20R, nodes::<3, 20, Hex20R>()),
            (&HEX27, nodes::<3, 27, Hex27>()),
        ];
        for (kernel, x) in &solid {
            check_mass(*kernel, x, &section(AnalysisKind::Solid, 1.0), 7.8)
                .unwrap_or_else(|e| panic!("{}: {e}", kernel.node_count()));
        }
    }

    #[test]
    fn consistent_mass_of_the_unit_triangle_and_tetrahedron() {
        // int N_a N_b dA = A / 12 (1 + delta_ab), int N_a N_b dV = V / 20 (1 + delta_ab)
        let t = p2([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        let m = TRI3
            .mass(
                &t,
                &section(AnalysisKind::PlaneStrain, 1.0),
                1.0,
                MassMatrix::Consistent,
            )
            .unwrap();
        assert!((m[0] - 1.0 / 12.0).abs() < 1e-15 && (m[1] - 1.0 / 24.0).abs() < 1e-15);
        let tt: Vec<Point<3>> = Tet4::NODES.iter().map(|&c| Point::<3>::from(c)).collect();
        let m = TET4
            .mass(
                &tt,
                &section(AnalysisKind::Solid, 1.0),
                1.0,
                MassMatrix::Consistent,
            )
            .unwrap();
        assert!((m[0] - 1.0 / 60.0).abs() < 1e-15 && (m[1] - 1.0 / 120.0).abs() < 1e-15);
    }

    #[test]
    fn hrz_lumping_where_row_sums_are_not_positive() {
        // a 3-node mass with a negative row sum (the corner rows of serendipity cells)
        let mut m = vec![2.0, 0.5, -3.0, 0.5, 2.0, 0.5, -3.0, 0.5, 3.0];
        let total: f64 = m.iter().sum();
        lump(&mut m, 3);
        assert_eq!([m[1], m[2], m[3], m[5], m[6], m[7]], [0.0; 6]);
        let d = [m[0], m[4], m[8]];
        assert!(d.iter().all(|v| *v > 0.0));
        assert!((d.iter().sum::<f64>() - total).abs() < 1e-14);
        assert!((d[0] / d[2] - 2.0 / 3.0).abs() < 1e-14);
    }

    fn kinds2() -> impl Strategy<Value = AnalysisKind> {
        prop_oneof![
            Just(AnalysisKind::PlaneStrain),
            Just(AnalysisKind::PlaneStress),
            Just(AnalysisKind::Axisymmetric)
        ]
    }

    fn formulations() -> impl Strategy<Value = Formulation> {
        prop_oneof![Just(Formulation::Full), Just(Formulation::SelectiveReduced)]
    }

    fn points<const D: usize>(v: &[f64]) -> Vec<Point<D>> {
        v.chunks(D).map(Point::<D>::from_column_slice).collect()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        #[test]
        fn tri3_stiffness_properties(
            shape in Shape::triangle(),
            young in 1.0f64..1e6,
            poisson in -0.9f64..0.49,
            kind in kinds2(),
            u in proptest::collection::vec(-1.0f64..1.0, 6),
        ) {
            let law = LinearElastic::new(young, poisson, kind).unwrap();
            let u = points::<2>(&u);
            let mut r = ElementMatrix::default();
            TRI3.linear(&shape.x, &u, &section(kind, 1.0), Formulation::Full, &law, true, &mut r).unwrap();
            // the 1-point axisymmetric triangle has rank 4: z-translation plus one
            // (mesh-communicated, well-known) zero-energy mode
            let zero_modes = if kind == AnalysisKind::Axisymmetric { 2 } else { 3 };
            check_element(&shape.x, &r, &u, kind, zero_modes).map_err(TestCaseError::fail)?;
        }

        #[test]
        fn quad4_stiffness_properties(
            shape in Shape::quad(),
            young in 1.0f64..1e6,
            poisson in -0.9f64..0.49,
            kind in kinds2(),
            formulation in formulations(),
            u in proptest::collection::vec(-1.0f64..1.0, 8),
        ) {
            let law = LinearElastic::new(young, poisson, kind).unwrap();
            let u = points::<2>(&u);
            let mut r = ElementMatrix::default();
            QUAD4.linear(&shape.x, &u, &section(kind, 2.5), formulation, &law, true, &mut r).unwrap();
            let zero_modes = if kind == AnalysisKind::Axisymmetric { 1 } else { 3 };
            check_element(&shape.x, &r, &u, kind, zero_modes).map_err(TestCaseError::fail)?;
        }

        #[test]
        fn tet4_stiffness_properties(
            shape in Shape::tet(),
            young in 1.0f64..1e6,
            poisson in -0.9f64..0.49,
            u in proptest::collection::vec(-1.0f64..1.0, 12),
        ) {
            let law = LinearElastic::new(young, poisson, AnalysisKind::Solid).unwrap();
            let u = points::<3>(&u);
            let mut r = ElementMatrix::default();
            TET4.linear(&shape.x, &u, &section(AnalysisKind::Solid, 1.0), Formulation::Full, &law, true, &mut r).unwrap();
            check_element(&shape.x, &r, &u, AnalysisKind::Solid, 6).map_err(TestCaseError::fail)?;
        }

        #[test]
        fn tri3_mass_properties(shape in Shape::triangle(), rho in 0.1f64..1e4, kind in kinds2()) {
            check_mass(&TRI3, &shape.x, &section(kind, 2.5), rho).map_err(TestCaseError::fail)?;
        }

        #[test]
        fn quad4_mass_properties(shape in Shape::quad(), rho in 0.1f64..1e4, kind in kinds2()) {
            check_mass(&QUAD4, &shape.x, &section(kind, 2.5), rho).map_err(TestCaseError::fail)?;
        }

        #[test]
        fn tet4_mass_properties(shape in Shape::tet(), rho in 0.1f64..1e4) {
            check_mass(&TET4, &shape.x, &section(AnalysisKind::Solid, 1.0), rho).map_err(TestCaseError::fail)?;
        }

        #[test]
        fn hex8_mass_properties(shape in Shape::hex(), rho in 0.1f64..1e4) {
            check_mass(&HEX8, &shape.x, &section(AnalysisKind::Solid, 1.0), rho).map_err(TestCaseError::fail)?;
        }

        #[test]
        fn hex8_stiffness_properties(
            shape in Shape::hex(),
            young in 1.0f64..1e6,
            poisson in -0.9f64..0.49,
            formulation in formulations(),
            u in proptest::collection::vec(-1.0f64..1.0, 24),
        ) {
            let law = LinearElastic::new(young, poisson, AnalysisKind::Solid).unwrap();
            let u = points::<3>(&u);
            let mut r = ElementMatrix::default();
            HEX8.linear(&shape.x, &u, &section(AnalysisKind::Solid, 1.0), formulation, &law, true, &mut r).unwrap();
            check_element(&shape.x, &r, &u, AnalysisKind::Solid, 6).map_err(TestCaseError::fail)?;
        }
    }
}
