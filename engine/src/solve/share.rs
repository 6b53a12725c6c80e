//! Distributed assembly: the part of the model one MPI rank assembles
//! (`ctc run --solver petsc` under `mpirun`, crate `ctc-petsc`).
//!
//! ```text
//!   rank r: cells of its METIS part ──element loop──▶ f_int (partial), K (partial CSC)
//!           contact nodes it owns   ──node blocks──▶ K (partial CSC)
//!   f_int: summed over the ranks (reduce to rank 0 + broadcast: the same
//!          bits on every rank) ──▶ residual, norms, reactions: identical
//!   K: each rank's entries added into the distributed matrix (ADD_VALUES)
//! ```
//!
//! The share is given by the linear system ([`super::linalg::LinearSystem::
//! share`]); the sparsity pattern ([`super::linalg::Scatter`]) then holds
//! only the couplings of the rank's cells, and the element matrices only
//! its cells, so the memory of the assembly falls with the rank count.
//! Integration points (plastic strain, hardening, finite-strain history)
//! are evaluated by the rank of their cell only; at each commit the ranks
//! exchange them (`Assembler::exchange_points`), so every rank holds the
//! committed points of every cell for the output, the pressure controls
//! and restart files, and a rollback (cutback) is the same on every rank.
//! Contact is evaluated by every rank for every slave node (the rigid
//! tools and the deformable master surfaces are replicated with the mesh
//! and displacements; the search is a small part of a run), so every
//! contact decision is identical on all ranks; the rows of a node of a
//! contact element (a slave node against a tool; slave and master nodes
//! of a node-to-segment, node-to-facet or mortar element) are added by
//! the rank owning the node (`Scatter::adds_rows_of`), and every rank
//! grows its pattern at the same evaluation with the same couplings
//! (`Scatter::contact_coupled`).
//!
//! A follower pressure's facet is evaluated by the rank of its cell, like
//! an element; its forces are summed over the ranks
//! ([`super::follower::FollowerShare`]). Springs, dashpots and the
//! inertia of a dynamic step are computed whole by every rank from the
//! replicated model (the serial bits); their tangent rows are added by
//! the node's owner, a cell's mass by the cell's rank.
//!
//! Only models whose every contribution is split this way are assembled
//! distributed ([`replicated_reason`] says why another one is not): the
//! others are assembled whole by every rank, as before.

use crate::model::{ContactMethod, Model};

/// The cells and nodes one rank assembles.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct AssemblyShare {
    /// Ranks of the run.
    pub ranks: usize,
    /// Whether this rank assembles each global cell.
    pub cells: Vec<bool>,
    /// Whether this rank owns each global node (adds its contact block).
    pub nodes: Vec<bool>,
    /// Whether each global cell's committed integration points are held
    /// by every rank (the same on all ranks): the cells with a node that
    /// cells of several ranks share, whose points the output's nodal
    /// averages on either side of a border read. The points of the other
    /// cells stay with their rank (`Assembler::exchange_points`); empty:
    /// no cell.
    pub exchanged: Vec<bool>,
}

impl AssemblyShare {
    /// Whether this rank assembles cell `c`.
    #[inline]
    pub fn owns_cell(&self, c: usize) -> bool {
        self.cells.get(c).copied().unwrap_or(false)
    }

    /// Whether this rank owns node `n`.
    #[inline]
    pub fn owns_node(&self, n: usize) -> bool {
        self.nodes.get(n).copied().unwrap_or(false)
    }

    /// Whether every rank holds cell `c`'s integration points.
    #[inline]
    pub fn exchanged(&self, c: usize) -> bool {
        self.exchanged.get(c).copied().unwrap_or(false)
    }

    /// The cells whose points are exchanged, from every cell's rank
    /// `part`: those with a node that cells of two ranks or more share.
    pub fn exchanged_cells<C: AsRef<[usize]>>(
        cells: &[C],
        part: &[usize],
        n_nodes: usize,
    ) -> Vec<bool> {
        // per node: the first rank seen, and whether another one touches it
        let mut first = vec![usize::MAX; n_nodes];
        let mut border = vec![false; n_nodes];
        for (cell, &r) in cells.iter().zip(part) {
            for &n in cell.as_ref() {
                if first[n] == usize::MAX {
                    first[n] = r;
                } else if first[n] != r {
                    border[n] = true;
                }
            }
        }
        cells
            .iter()
            .map(|cell| cell.as_ref().iter().any(|&n| border[n]))
            .collect()
    }

    /// Number of cells this rank assembles.
    pub fn owned_cells(&self) -> usize {
        self.cells.iter().filter(|&&o| o).count()
    }

    /// Whether the partial vectors need summing over ranks (more than one).
    pub fn split(&self) -> bool {
        self.ranks > 1
    }
}

/// Why `model` cannot be assembled distributed (each rank its cells and
/// contact nodes), or `None` when it can: any cell kind, linear or
/// quadratic, any material law and kinematics (the integration points
/// of a rank's cells are evaluated by it alone and exchanged at each
/// commit, `crate::solve::assembly::Assembler::exchange_points`), every
/// contact by penalty or augmented Lagrangian, against a rigid tool or a
/// deformable surface (the contact elements are evaluated by every rank,
/// the rows of a node added by its owner, `Scatter::adds_rows_of`), a
/// follower pressure (each facet evaluated by the rank of its cell, its
/// forces summed over the ranks, [`super::follower::FollowerShare`]),
/// springs, point masses and dashpots and dynamic steps (their forces and
/// the inertia forces computed whole by every rank from the replicated
/// masses, their tangent rows added by the node's owner, the cell masses
/// by the cell's rank: `discrete::add_tangent`, `Dynamics::add_tangent`);
/// thermal coupling (the mechanical part: the element thermal forces of
/// a rank's cells; the staggered heat step, its assembly, contact
/// conductance and faer solve, is computed whole by every rank on the
/// replicated contact and exchanged integration points: not distributed);
/// no rigid body, no stiffness-proportional Rayleigh damping (it needs
/// the reference stiffness of every cell, which a rank has of its own
/// cells only), no stabilization, no free tool.
pub fn replicated_reason<const D: usize>(model: &Model<D>) -> Option<&'static str> {
    for c in &model.contacts {
        if matches!(c.method, ContactMethod::Lagrange { .. }) {
            return Some("Lagrange-multiplier contact");
        }
    }
    if model.tools.iter().any(|t| t.free_rotation.is_some()) {
        return Some("a free tool");
    }
    if model
        .discrete
        .iter()
        .any(|d| matches!(d, crate::model::Discrete::Rigid { .. }))
    {
        return Some("a rigid body");
    }
    if model
        .steps
        .iter()
        .filter_map(|s| s.dynamic.as_ref())
        .any(|d| d.rayleigh.beta != 0.0)
    {
        return Some("stiffness-proportional Rayleigh damping");
    }
    if model.steps.iter().any(|s| s.newton.stabilize.is_some()) {
        return Some("stabilization");
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Cell, CellKind, Mesh};
    use crate::model::{Hardening, MaterialLaw};

    fn square(law: MaterialLaw) -> Model {
        crate::testkit::ModelBuilder::plane_strain()
            .material("m", law)
            .body(
                "sq",
                Mesh::new(
                    vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
                    vec![Cell::quad(0, 1, 2, 3)],
                ),
                "m",
            )
            .build()
    }

    #[test]
    fn plastic_and_quadratic_cells_are_distributed() {
        let elastic = square(MaterialLaw::LinearElastic {
            young: 1.0,
            poisson: 0.3,
        });
        assert_eq!(replicated_reason(&elastic), None);
        let plastic = square(MaterialLaw::ElastoPlastic {
            young: 200e3,
            poisson: 0.3,
            hardening: Hardening::Linear {
                yield_stress: 250.0,
                modulus: 1000.0,
            },
            viscosity: None,
        });
        // its integration points are exchanged at each commit
        // (`Assembler::exchange_points`)
        assert_eq!(replicated_reason(&plastic), None);
        // quadratic cells too (their face rows are added by node owners)
        let mut quadratic = plastic.clone();
        quadratic.mesh = Mesh::new(
            vec![
                [0.0, 0.0],
                [1.0, 0.0],
                [0.0, 1.0],
                [0.5, 0.0],
                [0.5, 0.5],
                [0.0, 0.5],
            ],
            vec![Cell {
                kind: CellKind::Tri6,
                nodes: vec![0, 1, 2, 3, 4, 5],
            }],
        );
        assert_eq!(replicated_reason(&quadratic), None);
    }

    #[test]
    fn follower_pressures_springs_dynamics_and_thermal_are_distributed() {
        let elastic = square(MaterialLaw::LinearElastic {
            young: 1.0,
            poisson: 0.3,
        });
        let mut follower = elastic.clone();
        follower.loads.push(crate::model::Load::FollowerPressure {
            label: "p".into(),
            facets: vec![crate::mesh::Facet::new(&[1, 0])],
            value: crate::model::TimeFunction::Constant(1.0),
            control: None,
        });
        assert!(super::super::follower::has_follower(&follower));
        // each facet evaluated by the rank of its cell
        // (`follower::FollowerShare`)
        assert_eq!(replicated_reason(&follower), None);
        let spring = crate::testkit::ModelBuilder::plane_strain()
            .material(
                "m",
                MaterialLaw::LinearElastic {
                    young: 1.0,
                    poisson: 0.3,
                },
            )
            .body(
                "sq",
                Mesh::new(
                    vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
                    vec![Cell::quad(0, 1, 2, 3)],
                ),
                "m",
            )
            .ground_spring([2], 1.0, 0.5)
            .point_mass([3], 2.0)
            .step("s", 1.0, 1)
            .build();
        // their rows added by the node's owner (`discrete::add_tangent`)
        assert_eq!(replicated_reason(&spring), None);
        let mut dynamic = spring.clone();
        let mut d = crate::model::Dynamic {
            scheme: crate::model::Scheme::Newmark {
                beta: 0.25,
                gamma: 0.5,
            },
            mass: crate::model::MassMatrix::Consistent,
            contact_mass: crate::model::ContactMass::Full,
            rayleigh: crate::model::Rayleigh {
                alpha: 0.1,
                beta: 0.0,
            },
            adaptive: None,
            max_rotation: None,
            energy_tol: None,
        };
        dynamic.steps[0].dynamic = Some(d);
        assert_eq!(replicated_reason(&dynamic), None);
        d.rayleigh.beta = 0.01;
        dynamic.steps[0].dynamic = Some(d);
        assert_eq!(
            replicated_reason(&dynamic),
            Some("stiffness-proportional Rayleigh damping")
        );
        // thermal coupling: the mechanical part distributed, the
        // staggered heat step computed whole by every rank
        let mut thermal = spring.clone();
        thermal.thermal = Some(crate::model::thermal::ThermalScene {
            materials: vec![None],
            initial: vec![20.0],
            temperatures: Vec::new(),
            fluxes: Vec::new(),
            convection: Vec::new(),
            contacts: Vec::new(),
            scheme: crate::model::thermal::CouplingScheme::Staggered,
        });
        assert_eq!(replicated_reason(&thermal), None);
    }

    #[test]
    fn a_share_counts_its_cells() {
        let s = AssemblyShare {
            ranks: 2,
            cells: vec![true, false, true],
            nodes: vec![false, true],
            exchanged: vec![false, true],
        };
        assert_eq!(s.owned_cells(), 2);
        assert!(s.owns_cell(2) && !s.owns_cell(1) && !s.owns_cell(7));
        assert!(s.owns_node(1) && !s.owns_node(0));
        assert!(s.split());
        assert!(s.exchanged(1) && !s.exchanged(0) && !s.exchanged(7));
    }

    #[test]
    fn the_cells_at_a_border_between_ranks_are_exchanged() {
        // a strip of four quads 0-1-2-3 (nodes 0..5 below, 5..10 above),
        // cells 0, 1 on rank 0 and 2, 3 on rank 1: the border is the
        // line of nodes 2 and 7, shared by cells 1 and 2
        let cells: Vec<[usize; 4]> = (0..4).map(|c| [c, c + 1, c + 6, c + 5]).collect();
        let exchanged = AssemblyShare::exchanged_cells(&cells, &[0, 0, 1, 1], 10);
        assert_eq!(exchanged, [false, true, true, false]);
        // one rank: no border
        let one = AssemblyShare::exchanged_cells(&cells, &[0; 4], 10);
        assert_eq!(one, [false; 4]);
        // a part in the middle: its neighbours on both sides are exchanged
        let corner = AssemblyShare::exchanged_cells(&cells, &[0, 1, 0, 0], 10);
        assert_eq!(corner, [true, true, true, false]);
    }
}
