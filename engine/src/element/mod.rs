//! Element kernels, generic over the spatial dimension `D` and the
//! reference cell: tri3 and quad4 (planar: plane strain, plane stress,
//! axisymmetric), tet4 and hex8 (solid).
//!
//! Every element follows the same structure: shape data at the
//! integration points ([`geometry`]), the kinematics ([`small`]: strain
//! `eps = sum B_a u_a`, B-bar; [`finite`]: total Lagrangian `F`, F-bar), the
//! 3D law ([`crate::material`]) through the planar embedding of 2D
//! analyses ([`planar`]), `f_int = sum B^T sigma dV` (or `P : Grad N`) and
//! `K`, where `dV = w det(J) t` (plane, thickness `t`), `w det(J) 2 pi r`
//! (axisymmetric: element totals are over the full 2*pi) or `w det(J)`
//! (solid). Element matrices are node blocks (`K_ab` is a `D x D`
//! [`Block`]); nonlinear tangents are exact derivatives by dual numbers.
//!
//! - [`reference`]: the [`reference::ReferenceCell`] trait and the cells;
//! - [`kernel`]: [`CellKernel`], the object-safe kernel of one cell kind,
//!   and the registry [`kernel_of`];
//! - [`recovery`]: nodal averages of stress and strain for output.

pub mod finite;
pub mod geometry;
pub mod kernel;
pub mod planar;
pub mod recovery;
pub mod reference;
pub mod small;
#[cfg(test)]
pub(crate) mod testing;

pub use kernel::{kernel_of, CellKernel, NonlinearInput, ShapeData};

use crate::geom::{Block, Point};
use crate::material::{Strain, Stress};
use crate::model::{Analysis, AnalysisKind};

/// Cross-section of an analysis: how a reference measure becomes a volume.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Plane strain, plane stress, axisymmetric or solid.
    pub kind: AnalysisKind,
    /// Out-of-plane thickness (plane kinds only).
    pub thickness: f64,
}

impl Section {
    /// The section of an analysis.
    pub fn new(analysis: &Analysis) -> Self {
        Section {
            kind: analysis.kind,
            thickness: analysis.thickness,
        }
    }

    /// Volume per unit area (2D) or volume (3D) at radius `r`
    /// ([`planar::measure`]).
    pub fn measure(&self, r: f64) -> f64 {
        planar::measure(self, r)
    }
}

/// An element that cannot be evaluated (inverted, degenerate, off-axis).
#[derive(Debug, Clone, PartialEq)]
pub struct ElementError {
    /// What is wrong, in words a user understands.
    pub message: String,
}

impl ElementError {
    /// An error with a message.
    pub fn new(message: impl Into<String>) -> Self {
        ElementError {
            message: message.into(),
        }
    }
}

impl std::fmt::Display for ElementError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for ElementError {}

/// `[x, y, z]` of a point of any dimension (z = 0 in 2D).
pub fn position3<const D: usize>(p: &Point<D>) -> [f64; 3] {
    std::array::from_fn(|k| if k < D { p[k] } else { 0.0 })
}

/// Stress and strain at one integration point (always 3D components).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointState {
    /// Position `[x, y, z]` (`z = 0` for planar analyses).
    pub position: [f64; 3],
    /// Volume weight of the point.
    pub volume: f64,
    /// Full strain `[xx, yy, zz, xy, xz, yz]` (engineering shear; plane
    /// stress `zz` completed by the law).
    pub strain: Strain,
    /// Stress `[xx, yy, zz, xy, xz, yz]`.
    pub stress: Stress,
}

/// State of one integration point of a nonlinear kernel: output values and
/// the updated internal variables.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaterialPoint {
    /// Stress (Cauchy) and strain (small strain, or the logarithmic strain
    /// `1/2 ln(F F^T)` for finite strain; engineering shear).
    pub state: PointState,
    /// Internal variables after the update.
    pub history: crate::material::History,
}

/// Internal force and tangent of one element as node blocks.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ElementMatrix<const D: usize> {
    /// Number of nodes.
    pub nodes: usize,
    /// Internal force on each node.
    pub force: Vec<Point<D>>,
    /// Tangent blocks `K_ab = d f_a / d u_b`, block `(a, b)` at
    /// `a * nodes + b` (zero when not requested).
    pub stiffness: Vec<Block<D>>,
}

impl<const D: usize> ElementMatrix<D> {
    /// Zeroed storage for `nodes` nodes.
    pub fn resize(&mut self, nodes: usize) {
        self.nodes = nodes;
        self.force.clear();
        self.force.resize(nodes, Point::<D>::zeros());
        self.stiffness.clear();
        self.stiffness.resize(nodes * nodes, Block::<D>::zeros());
    }

    /// Entry `(i, j)` in element dof numbering (`a D + c`).
    #[inline]
    pub fn entry(&self, i: usize, j: usize) -> f64 {
        self.stiffness[(i / D) * self.nodes + j / D][(i % D, j % D)]
    }

    /// Force component `i` in element dof numbering.
    #[inline]
    pub fn force_entry(&self, i: usize) -> f64 {
        self.force[i / D][i % D]
    }

    /// Force (values) and tangent (derivatives) from dual numbers in
    /// element dof numbering.
    pub fn set_from_duals<const N: usize>(
        &mut self,
        nodes: usize,
        f: &[crate::material::dual::Dual<N>],
    ) {
        self.resize(nodes);
        for (i, fi) in f.iter().enumerate() {
            self.force[i / D][i % D] = fi.v;
            for (j, dj) in fi.d.iter().enumerate() {
                self.stiffness[(i / D) * nodes + j / D][(i % D, j % D)] = *dj;
            }
        }
    }

    /// Force from values in element dof numbering (tangent zeroed).
    pub fn set_force(&mut self, nodes: usize, f: &[f64]) {
        self.resize(nodes);
        for (i, fi) in f.iter().enumerate() {
            self.force[i / D][i % D] = *fi;
        }
    }
}
