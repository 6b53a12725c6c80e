//! Implicit dynamics: the time integrator beside `stepping.rs` and the
//! inertia terms of `Newton::evaluate` (the loop, line search and
//! convergence are those of quasi-static steps).
//!
//! One formulation, generalized-alpha (Chung & Hulbert 1993, J. Appl.
//! Mech. 60:371), with the forces weighted like Abaqus' HHT and MOOSE
//! (the internal, external and contact forces at the end of the increment
//! and the committed ones, not the forces at an intermediate
//! displacement, so history-dependent laws are evaluated at the end of the
//! increment only):
//!
//! ```text
//! M [(1 - am) a1 + am a0] + (1 - af) r(u1) + af r(u0) = 0,   r = f_int - f_ext - f_c + C v
//! a1 = (u1 - u0 - dt v0) / (beta dt^2) - (1 / (2 beta) - 1) a0
//! v1 = v0 + dt ((1 - gamma) a0 + gamma a1)
//! ```
//!
//! divided by `1 - af` so the static part keeps its scale: the residual is
//! `r(u1) + M [(1 - am) a1 + am a0] / (1 - af) + af / (1 - af) r(u0)` and
//! the tangent `K + (1 - am) / ((1 - af) beta dt^2) M`. Newmark (`am = af
//! = 0`) and HHT-alpha (`am = 0`) are the special cases
//! ([`Coefficients::of`]). Velocities and accelerations are state
//! committed with converged increments (a cutback recomputes `a1` from the
//! committed state with the new `dt`).
//!
//! Rayleigh damping (`dynamic { rayleigh_alpha  rayleigh_beta }`): `C =
//! alpha M + beta K_0` per cell, `K_0` the cell's stiffness in the
//! reference configuration ([`super::assembly::Assembler::reference_stiffness`]);
//! the damping force `C v1` (`v1` of the scheme, a function of `u1`) is
//! weighted like the other forces (Chung & Hulbert 1993, eq. 2), its
//! tangent is `gamma / (beta dt) C`.
//!
//! Energy audit ([`Energy`]): kinetic `1/2 v M v`, internal work
//! (trapezoidal `f_int . du`, the strain energy of elastic bodies),
//! external work (loads and reactions), contact work, damping dissipation
//! (trapezoidal `C v . du`), and the balance error `K + W_int + W_d -
//! W_ext - W_c - K_0` (the integrator's: negative is numerical
//! dissipation), and the gain `K + W_int + W_d - W_ext - K_0` (energy
//! created, e.g. by contact chatter). A run is warned about at the first
//! increment where the gain, the balance or minus the internal work
//! exceeds [`ENERGY_GROWTH_TOL`] of the largest energy ([`EnergyAlarm`]:
//! a negative internal work is a kinetic energy beyond the work put in,
//! which the balance does not see when the trapezoidal internal work
//! follows the blow-up).

use super::dofs::{Dof, DofMap};
use super::linalg::{Scatter, NO_SLOT};
use crate::contact::friction::FrictionStatus;
use crate::contact::NodeContact;
use crate::element::kernel::kernel_of;
use crate::element::Section;
use crate::geom::Dimension;
use crate::model::{
    ContactMass, ContactMaster, Dynamic, MassMatrix, Model, Rayleigh, Scheme, Step,
};
use nalgebra::Const;

/// Default spectral radius at infinite frequency of the dissipative
/// schemes.
pub const DEFAULT_RHO_INF: f64 = 0.9;

/// The forces of the work integrals: internal, external + reactions,
/// contact, damping.
pub const FORCES: usize = 4;

/// Relative growth of the total energy above which a run is warned about.
pub const ENERGY_GROWTH_TOL: f64 = 1e-2;

/// The generalized-alpha parameters of a scheme.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coefficients {
    /// Weight of the committed acceleration in the inertia term.
    pub alpha_m: f64,
    /// Weight of the committed forces.
    pub alpha_f: f64,
    /// Newmark `beta`.
    pub beta: f64,
    /// Newmark `gamma`.
    pub gamma: f64,
}

impl Coefficients {
    /// The parameters of `scheme` (Chung & Hulbert 1993, eqs. 25 and 17;
    /// HHT: Hilber, Hughes & Taylor 1977 with `alpha = (1 - rho_inf) / (1 +
    /// rho_inf)`).
    pub fn of(scheme: Scheme) -> Self {
        match scheme {
            Scheme::Newmark { beta, gamma } => Coefficients {
                alpha_m: 0.0,
                alpha_f: 0.0,
                beta,
                gamma,
            },
            Scheme::Hht { rho_inf } => {
                let a = (1.0 - rho_inf) / (1.0 + rho_inf);
                Coefficients {
                    alpha_m: 0.0,
                    alpha_f: a,
                    beta: 0.25 * (1.0 + a) * (1.0 + a),
                    gamma: 0.5 + a,
                }
            }
            Scheme::GeneralizedAlpha { rho_inf } => {
                let am = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
                let af = rho_inf / (rho_inf + 1.0);
                let g = 0.5 - am + af;
                Coefficients {
                    alpha_m: am,
                    alpha_f: af,
                    beta: 0.25 * (1.0 - am + af) * (1.0 - am + af),
                    gamma: g,
                }
            }
        }
    }
}

impl Coefficients {
    /// `(period ratio T_h / T - 1, damping ratio)` of a linear one-mode system
    /// `omega dt = w` by the eigenvalues of the generalized-alpha amplification
    /// matrix (Chung & Hulbert 1993, eq. 16 with xi = 0): the principal root
    /// `lambda = exp(w_h (-xi_h +- i))`.
    pub fn spectral(&self, w: f64) -> (f64, f64) {
        let (am, af, b, g) = (self.alpha_m, self.alpha_f, self.beta, self.gamma);
        // X_{n+1} = A X_n, X = (d, dt v, dt^2 a), from
        // (1-am) a1 + am a0 + w^2 ((1-af) d1 + af d0) = 0 (unit mass, dt = 1),
        // d1 = d0 + v0 + (1/2 - b) a0 + b a1, v1 = v0 + (1 - g) a0 + g a1
        let w2 = w * w;
        let lhs = nalgebra::Matrix3::new(
            1.0,
            0.0,
            -b, //
            0.0,
            1.0,
            -g, //
            w2 * (1.0 - af),
            0.0,
            1.0 - am,
        );
        let rhs = nalgebra::Matrix3::new(
            1.0,
            1.0,
            0.5 - b, //
            0.0,
            1.0,
            1.0 - g, //
            -w2 * af,
            0.0,
            -am,
        );
        let a = lhs.try_inverse().unwrap() * rhs;
        let l = a
            .complex_eigenvalues()
            .iter()
            .copied()
            .max_by(|x, y| x.im.abs().total_cmp(&y.im.abs()))
            .unwrap();
        let phase = l.im.abs().atan2(l.re);
        ((w / phase) - 1.0, -l.norm().ln() / phase)
    }
}

/// Energies of the run at the last converged increment (all totals since
/// the start of the analysis).
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct Energy {
    /// Kinetic energy `1/2 v M v`.
    pub kinetic: f64,
    /// Internal work `sum 1/2 (f_int_0 + f_int_1) . du` (strain energy of
    /// elastic bodies, plus plastic dissipation).
    pub internal: f64,
    /// Work of the loads and of the reactions at prescribed dofs.
    pub external: f64,
    /// Work of the contact forces on the bodies (minus the energy stored in
    /// penalty springs, plus friction dissipation).
    pub contact: f64,
    /// Energy dissipated by Rayleigh damping `sum 1/2 (f_d0 + f_d1) . du`,
    /// `f_d = C v` (`>= 0`).
    pub damping: f64,
    /// `kinetic + internal + damping - external - contact - kinetic_0`:
    /// the integrator's own energy error (0 for average-acceleration Newmark,
    /// negative: numerical dissipation), `error - numerical`.
    pub balance: f64,
    /// `kinetic + internal + damping - external - kinetic_0`: the energy
    /// gained
    /// beyond the work of the loads and supports (0 in a conservative
    /// system; contact against fixed rigid tools must not make it
    /// positive: the contact work is part of it).
    pub gain: f64,
    /// The largest of the energies so far (the scale of `balance`).
    pub scale: f64,
    /// The energy the time discretization removed (negative: created),
    /// summed over the increments ([`numerical_dissipation`]): what
    /// `balance` is when every increment's equation holds exactly.
    pub numerical: f64,
    /// `balance + numerical`: the energy the audit does not explain, the
    /// work `sum (M a_m + f_m) . du` of the residual the Newton loops left
    /// (their tolerance) and of any force the scheme uses but the audit
    /// does not (0 to round-off when both are consistent and converged).
    pub error: f64,
    /// The energy stored in the penalty springs of the closed contact
    /// nodes, `sum 1/2 f_n (-g)` ([`penalty_energy`]; 0 under Lagrange
    /// multipliers, whose gap is closed): with the contact work, what the
    /// energy control of dynamic steps weighs (`dynamic { energy_tol }`,
    /// [`Energy::created_since`]).
    pub penalty: f64,
}

/// The committed state of the integrator in a restart point
/// (`crate::solve::restart`): everything [`Dynamics`] carries from one
/// increment to the next but the mass, which the model determines.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicState {
    /// Whether the initial acceleration was computed.
    pub started: bool,
    /// Velocity per dof.
    pub v: Vec<f64>,
    /// Acceleration per dof.
    pub a: Vec<f64>,
    /// `f_int - f_ext - f_c` per dof (the `alpha_f` term).
    pub r0: Vec<f64>,
    /// Internal, external + reactions, contact, damping forces per dof
    /// (the work integrals), then each contact pair's friction forces on
    /// its slave nodes (per dof, empty: none; the friction work's
    /// trapezoidal rule, [`Dynamics::friction_work`]).
    pub forces0: Vec<Vec<f64>>,
    /// Kinetic energy at the start.
    pub kinetic0: f64,
    /// [`Energy::values`].
    pub energy: Vec<f64>,
}

impl Energy {
    /// The fields in declaration order (restart points).
    pub fn values(&self) -> Vec<f64> {
        vec![
            self.kinetic,
            self.internal,
            self.external,
            self.contact,
            self.damping,
            self.balance,
            self.gain,
            self.scale,
            self.numerical,
            self.error,
            self.penalty,
        ]
    }

    /// The energy created from the committed audit `before` to this one:
    /// the growth of the kinetic energy, the internal and damping work and
    /// the stored penalty energy beyond the work of the loads and supports
    /// (`gain + penalty`). Positive: the contact forces gave the bodies
    /// more than their springs stored (a penalty released from a deeper
    /// penetration than it was loaded through) or the integrator created
    /// energy; a consistent increment keeps it at or below 0 (the scheme's
    /// numerical dissipation).
    ///
    /// The scheme's numerical dissipation of `K + U` is in it, and per
    /// increment it takes either sign (generalized-alpha is monotone in
    /// its own energy): the planar blade loss's spin-up from rest without
    /// contact gives +2.9e-4, -1.5e-4, +7.7e-4 mJ in successive
    /// increments, so at `energy_tol = 1e-4` it redid 597 of 1098
    /// increments (`CTC_LOG=debug`: each "created" the balance, equal to
    /// minus the numerical dissipation to 1e-12). Measured and reverted:
    /// `d(error + contact + penalty)` minus the contact forces' share of
    /// the dissipation (`(af - 1/2)(f_c1 - f_c0) . du`), i.e. without
    /// the scheme's dissipation of the other forces, ends that crawl (68
    /// increments) but stopped the 3D blade loss flown to 20 ms at 13.60
    /// ms: at 10.4 ms it counted 2.8e5-3.6e5 mJ created whatever the
    /// increment's size, the contact's creation that the scheme's
    /// dissipation of the same increment offsets here (this measure:
    /// 648 increments to 20 ms).
    pub fn created_since(&self, before: &Energy) -> f64 {
        (self.gain + self.penalty) - (before.gain + before.penalty)
    }

    /// Closes an increment's audit once its totals (kinetic, internal,
    /// external, contact, damping, numerical) are set: the balance
    /// `K + W_int + W_damp - W_ext - W_contact - K_0`, the gain (the
    /// balance without the contact work), the error (the balance plus the
    /// scheme's numerical dissipation) and the running scale (the largest
    /// magnitude so far).
    pub fn close(&mut self, kinetic0: f64) {
        self.balance =
            self.kinetic + self.internal + self.damping - self.external - self.contact - kinetic0;
        self.gain = self.kinetic + self.internal + self.damping - self.external - kinetic0;
        self.error = self.balance + self.numerical;
        self.scale = self
            .scale
            .max(self.kinetic)
            .max(self.internal.abs())
            .max(self.external.abs())
            .max(self.contact.abs())
            .max(self.damping.abs())
            .max(self.numerical.abs());
    }

    /// The inverse of [`Energy::values`] (`None`: a wrong count; the ten
    /// values of restart points written before the penalty energy was
    /// kept read with a penalty energy of 0).
    pub fn from_values(v: &[f64]) -> Option<Self> {
        let (
            &[kinetic, internal, external, contact, damping, balance, gain, scale, numerical, error],
            penalty,
        ) = (v.get(..10)?, v.get(10).copied().unwrap_or(0.0))
        else {
            return None;
        };
        if v.len() > 11 {
            return None;
        }
        Some(Energy {
            kinetic,
            internal,
            external,
            contact,
            damping,
            balance,
            gain,
            scale,
            numerical,
            error,
            penalty,
        })
    }
}

/// The energy stored in the penalty springs of the closed contact nodes
/// of `contact` (per pair, an evaluation's lists): `sum 1/2 f_n (-g)`, `f_n
/// = force . normal` the normal force on a node and `g < 0` its gap (the
/// spring's energy for a penalty linear in the gap; Lagrange multipliers
/// keep the gap at 0 and add nothing).
pub fn penalty_energy<const D: usize>(contact: &[Vec<NodeContact<D>>]) -> f64 {
    contact
        .iter()
        .flatten()
        .filter(|c| c.status == crate::contact::ContactStatus::Closed && c.gap < 0.0)
        .map(|c| {
            let normal: f64 = c.force.iter().zip(&c.normal).map(|(f, n)| f * n).sum();
            0.5 * normal.max(0.0) * (-c.gap)
        })
        .sum()
}

/// What committing an increment makes of the dynamic state
/// ([`Dynamics::audit`]).
#[derive(Debug, Clone)]
pub struct Audit {
    /// Velocities and accelerations at the end (`None`: quasi-static, at
    /// rest).
    pub rates: Option<(Vec<f64>, Vec<f64>)>,
    /// External forces plus the reactions and the inertia of the
    /// prescribed dofs (the start of the next increment's external work).
    pub external: Vec<f64>,
    /// The energies at the end.
    pub energy: Energy,
}

/// Mass, velocities, accelerations and energies of a model with dynamic
/// steps.
#[derive(Debug, Clone)]
pub struct Dynamics {
    /// Scalar mass matrix of each global cell, `NN x NN` row-major (node
    /// block `M_ab I`).
    cell_mass: Vec<Vec<f64>>,
    /// The kind the cell masses were built as.
    mass_kind: Option<(MassMatrix, ContactMass)>,
    /// Committed velocity per dof (`node D + c`).
    pub v: Vec<f64>,
    /// Committed acceleration per dof.
    pub a: Vec<f64>,
    /// Committed `f_int - f_ext - f_c` per dof (at prescribed dofs too).
    r0: Vec<f64>,
    /// Whether `a` and `r0` belong to the committed state (false before
    /// the first dynamic increment: [`Dynamics::start`]).
    pub started: bool,
    /// Parameters and `dt` of the current increment (`None`: quasi-static).
    active: Option<(Coefficients, f64)>,
    /// Committed forces for the work integrals: internal, external +
    /// reactions, contact, damping ([`FORCES`] of them).
    forces0: Vec<Vec<f64>>,
    /// Point mass at each node (`Discrete::Mass`; empty: none).
    node_mass: Vec<f64>,
    /// `contact_mass = normal`: a `D x D` block per node (row-major,
    /// `node D D + p D + q`) added to the redistributed mass: the
    /// tangential mass `m_a (I - n n^T)` of contact nodes on axis-aligned
    /// rigid planes, minus its share moved to the other nodes of their
    /// cells (empty: none).
    node_tensor: Vec<f64>,
    /// Whether a dashpot (`Discrete::Ground` or `Link` with a damping)
    /// exists (`super::discrete` applies them).
    dashpots: bool,
    /// Rayleigh damping matrix of each global cell, column-major `D NN x
    /// D NN` (empty: no damping).
    cell_damping: Vec<Vec<f64>>,
    /// The coefficients the damping matrices were built with.
    damping_kind: Option<Rayleigh>,
    /// Kinetic energy at the start.
    kinetic0: f64,
    /// Energies at the last converged increment.
    pub energy: Energy,
    /// Cells with every node on a contact surface, whose lumped mass was
    /// kept (no other node to move it to).
    pub contact_cells_kept: usize,
    /// What the contact-mass redistribution could not do (cells kept
    /// lumped, centres of mass it moved), for the run's notes.
    pub mass_notes: Vec<String>,
    /// Committed friction force on each slave node per contact pair, per
    /// dof (the start of the friction work's trapezoidal rule,
    /// [`Dynamics::friction_work`]; empty until a pair has friction).
    friction0: Vec<Vec<f64>>,
}

impl Dynamics {
    /// The state of `model` at rest but for its initial velocities; the
    /// mass is built when a dynamic step begins.
    pub fn new<const D: usize>(model: &Model<D>) -> Self
    where
        Const<D>: Dimension<D>,
    {
        let n = model.mesh.nodes.len() * D;
        let mut v = vec![0.0; n];
        for iv in &model.initial_velocities {
            for &node in &iv.nodes {
                if iv.component < D {
                    v[node * D + iv.component] = iv.value;
                }
            }
        }
        Dynamics {
            cell_mass: Vec::new(),
            mass_kind: None,
            v,
            a: vec![0.0; n],
            r0: vec![0.0; n],
            started: false,
            active: None,
            forces0: vec![vec![0.0; n]; FORCES],
            cell_damping: Vec::new(),
            node_mass: Vec::new(),
            node_tensor: Vec::new(),
            dashpots: false,
            damping_kind: None,
            kinetic0: 0.0,
            energy: Energy::default(),
            contact_cells_kept: 0,
            mass_notes: Vec::new(),
            friction0: Vec::new(),
        }
    }

    /// Builds the cell masses of the step's `dynamic` (once per mass kind):
    /// `d.mass` everywhere, but for the cells with contact-surface nodes
    /// when `d.contact_mass` redistributes their mass
    /// ([`super::contact_mass`]).
    pub fn build_mass<const D: usize>(
        &mut self,
        model: &Model<D>,
        d: &Dynamic,
    ) -> Result<(), String>
    where
        Const<D>: Dimension<D>,
    {
        let kind = (d.mass, d.contact_mass);
        if self.mass_kind == Some(kind) {
            return Ok(());
        }
        let massless = match d.contact_mass {
            ContactMass::Full => vec![false; model.mesh.nodes.len()],
            ContactMass::Redistributed | ContactMass::Normal => super::contact_mass::contact_nodes(
                model.mesh.nodes.len(),
                model.contacts.iter().flat_map(|p| {
                    let master: &[usize] = match &p.master {
                        ContactMaster::Surface { nodes, .. } => nodes,
                        ContactMaster::Tool(_) => &[],
                    };
                    [&p.nodes[..], master]
                }),
            ),
        };
        // contact_mass = normal: the unit normal of the axis-aligned rigid
        // plane each contact node touches (its tangential mass is kept)
        let mut normal: Vec<Option<[f64; D]>> = vec![None; model.mesh.nodes.len()];
        if d.contact_mass == ContactMass::Normal {
            for p in &model.contacts {
                let Some(n) = super::contact_mass::axis_plane_normal::<D>(model, &p.master) else {
                    continue;
                };
                for &node in &p.nodes {
                    if let Some(x) = normal.get_mut(node) {
                        *x = Some(n);
                    }
                }
            }
        }
        let mut tensor = vec![
            0.0;
            if normal.iter().any(Option::is_some) {
                model.mesh.nodes.len() * D * D
            } else {
                0
            }
        ];
        let section = Section::new(&model.analysis);
        let mut masses = vec![Vec::new(); model.mesh.cells.len()];
        let mut kept = 0;
        let mut notes = Vec::new();
        let mut held: Option<Vec<[bool; D]>> = None;
        for b in &model.bodies {
            let rho = model.materials.get(b.material).map_or(0.0, |m| m.density);
            // the body's mass, its first moment before minus after the
            // redistribution, the mass each (cell, local node) received,
            // its cells that kept their lumped mass
            let mut body_mass = 0.0;
            let mut missing = [0.0; D];
            let mut received: Vec<(usize, usize, f64)> = Vec::new();
            let kept_before = kept;
            for c in b.cells.clone() {
                let nodes = model.mesh.cells.nodes(c);
                if rho == 0.0 {
                    // a massless body (its nodes may carry point masses):
                    // no lumping of a zero matrix (HRZ would divide 0 by 0)
                    masses[c] = vec![0.0; nodes.len() * nodes.len()];
                    continue;
                }
                let kernel = kernel_of::<D>(model.mesh.cells.kind(c))
                    .map_err(|e| format!("cell {c}: {}", e.message))?;
                let x: Vec<crate::geom::Point<D>> = nodes
                    .iter()
                    .map(|&n| crate::geom::Point::<D>::from(model.mesh.nodes[n]))
                    .collect();
                let flags: Vec<bool> = nodes.iter().map(|&n| massless[n]).collect();
                let touches = flags.iter().any(|f| *f);
                let mut m = kernel
                    .mass(
                        &x,
                        &section,
                        rho,
                        if touches {
                            MassMatrix::Consistent
                        } else {
                            d.mass
                        },
                    )
                    .map_err(|e| format!("cell {c}: {}", e.message))?;
                let moved = if touches && !tensor.is_empty() {
                    super::contact_mass::moved_mass(&m, nodes.len(), &flags)
                } else {
                    Vec::new()
                };
                let nn = nodes.len();
                body_mass += m.iter().sum::<f64>();
                // the first moment sum M_ab X_b and the lumped diagonal
                // before the redistribution
                let lumped = if touches {
                    for a in 0..nn {
                        for (bb, &nb) in nodes.iter().enumerate() {
                            for (k, mk) in missing.iter_mut().enumerate() {
                                *mk += m[a * nn + bb] * model.mesh.nodes[nb][k];
                            }
                        }
                    }
                    let mut l = m.clone();
                    crate::element::kernel::lump(&mut l, nn);
                    l
                } else {
                    Vec::new()
                };
                if touches && !super::contact_mass::redistribute(&mut m, nodes.len(), &flags) {
                    kept += 1;
                } else if !moved.is_empty() {
                    // the tangential share stays where it was
                    let nn = nodes.len();
                    for (a, &na) in nodes.iter().enumerate() {
                        let Some(n) = normal[na] else { continue };
                        for (b, &nb) in nodes.iter().enumerate() {
                            let w = moved[a * nn + b];
                            if w == 0.0 {
                                continue;
                            }
                            for p in 0..D {
                                for q in 0..D {
                                    let t = f64::from(u8::from(p == q)) - n[p] * n[q];
                                    tensor[na * D * D + p * D + q] += w * t;
                                    tensor[nb * D * D + p * D + q] -= w * t;
                                }
                            }
                        }
                    }
                }
                if touches {
                    for (a, &na) in nodes.iter().enumerate() {
                        let maa = m[a * nn + a];
                        for (k, mk) in missing.iter_mut().enumerate() {
                            *mk -= maa * model.mesh.nodes[na][k];
                        }
                        let got = maa - lumped[a * nn + a];
                        if !flags[a] && got > 0.0 {
                            received.push((c, a, got));
                        }
                    }
                }
                masses[c] = m;
            }
            if kept > kept_before {
                notes.push(format!(
                    "body `{}`: {} cells have every node on a contact surface and keep their \
                     lumped mass (`contact_mass = redistributed` has no other node of theirs to \
                     move it to)",
                    b.name,
                    kept - kept_before
                ));
            }
            // the body's centre of mass put back by the receivers (not
            // under `contact_mass = normal`, whose tangential share stays
            // on the contact nodes)
            if d.contact_mass == ContactMass::Redistributed && !received.is_empty() {
                let mut by_node: Vec<(usize, f64)> = received
                    .iter()
                    .map(|&(c, a, w)| (model.mesh.cells.nodes(c)[a], w))
                    .collect();
                by_node.sort_by_key(|r| r.0);
                let mut receivers: Vec<(usize, f64)> = Vec::new();
                for (n, w) in by_node {
                    match receivers.last_mut() {
                        Some(last) if last.0 == n => last.1 += w,
                        _ => receivers.push((n, w)),
                    }
                }
                let mut lo = [f64::INFINITY; D];
                let mut hi = [f64::NEG_INFINITY; D];
                for n in b.nodes.clone() {
                    let x = model.mesh.nodes[n];
                    for ((l, h), v) in lo.iter_mut().zip(hi.iter_mut()).zip(x) {
                        *l = l.min(v);
                        *h = h.max(v);
                    }
                }
                let size = lo
                    .iter()
                    .zip(&hi)
                    .map(|(l, h)| (h - l).powi(2))
                    .sum::<f64>()
                    .sqrt();
                // along the body's symmetry planes only (the mirrored
                // whole's centre stays on them)
                let held = held.get_or_insert_with(|| super::contact_mass::held_at_zero(model));
                let free = super::contact_mass::free_directions(
                    &model.mesh.nodes,
                    b.nodes.clone(),
                    held,
                    size,
                );
                let along = |x: &[f64]| -> Vec<f64> {
                    x.iter()
                        .zip(&free)
                        .filter(|(_, f)| **f)
                        .map(|(x, _)| *x)
                        .collect()
                };
                let input: Vec<(f64, Vec<f64>)> = receivers
                    .iter()
                    .map(|&(n, w)| (w, along(&model.mesh.nodes[n])))
                    .collect();
                let missing = along(&missing);
                match super::contact_mass::restore_centre(&input, &missing, body_mass, size) {
                    super::contact_mass::Centre::Restored(f) => {
                        for &(c, a, w) in &received {
                            let n = model.mesh.cells.nodes(c)[a];
                            let Ok(k) = receivers.binary_search_by_key(&n, |r| r.0) else {
                                continue;
                            };
                            let nn = model.mesh.cells.nodes(c).len();
                            masses[c][a * nn + a] += w * f[k];
                        }
                    }
                    super::contact_mass::Centre::Moved(shift) => {
                        notes.push(format!(
                            "body `{}`: the redistributed contact mass moves its centre of \
                             mass by {shift:.3e} (the nodes that take the contact nodes' mass \
                             cannot carry the first moment back)",
                            b.name
                        ));
                    }
                    _ => {}
                }
            }
        }
        self.mass_notes = notes;
        self.contact_cells_kept = kept;
        self.cell_mass = masses;
        self.node_tensor = tensor;
        self.node_mass.clear();
        self.dashpots = super::discrete::any(model, |_, c| c);
        let nn = model.mesh.nodes.len();
        for d in &model.discrete {
            let crate::model::Discrete::Mass { nodes, mass, .. } = d else {
                continue;
            };
            if *mass == 0.0 {
                continue;
            }
            self.node_mass.resize(nn, 0.0);
            for &n in nodes {
                if let Some(x) = self.node_mass.get_mut(n) {
                    *x += mass;
                }
            }
        }
        self.mass_kind = Some(kind);
        // the reference of the energy audit: the kinetic energy of the
        // initial velocities (once: a restarted run carries it over)
        if !self.started {
            self.kinetic0 = self.kinetic(model);
            self.energy.kinetic = self.kinetic0;
            self.energy.scale = self.kinetic0;
        }
        Ok(())
    }

    /// `out += M x` over all dofs (`x`, `out` per dof `node D + c`; point
    /// masses included).
    pub fn mass_times<const D: usize>(&self, model: &Model<D>, x: &[f64], out: &mut [f64]) {
        for (n, t) in self.node_tensor.chunks_exact(D * D).enumerate() {
            for p in 0..D {
                for q in 0..D {
                    out[n * D + p] += t[p * D + q] * x[n * D + q];
                }
            }
        }
        for (n, m) in self.node_mass.iter().enumerate() {
            for k in 0..D {
                out[n * D + k] += m * x[n * D + k];
            }
        }
        for (c, m) in self.cell_mass.iter().enumerate() {
            let nodes = model.mesh.cells.nodes(c);
            let nn = nodes.len();
            for (a, &na) in nodes.iter().enumerate() {
                for (b, &nb) in nodes.iter().enumerate() {
                    let mab = m[a * nn + b];
                    if mab == 0.0 {
                        continue;
                    }
                    for k in 0..D {
                        out[na * D + k] += mab * x[nb * D + k];
                    }
                }
            }
        }
    }

    /// Builds the Rayleigh damping matrices `alpha M + beta K_0` of every
    /// cell (once per coefficients; `stiffness` gives the cells' reference
    /// stiffness, called only when `beta != 0`). Call after
    /// [`Dynamics::build_mass`].
    pub fn build_damping<const D: usize>(
        &mut self,
        model: &Model<D>,
        d: &Dynamic,
        stiffness: impl FnOnce() -> Result<Vec<Vec<f64>>, String>,
    ) -> Result<(), String> {
        let r = d.rayleigh;
        if self.damping_kind == Some(r) {
            return Ok(());
        }
        self.damping_kind = Some(r);
        self.cell_damping.clear();
        if !r.any() {
            return Ok(());
        }
        let k0 = if r.beta != 0.0 {
            stiffness()?
        } else {
            Vec::new()
        };
        self.cell_damping = (0..model.mesh.cells.len())
            .map(|c| {
                let nn = model.mesh.cells.nodes(c).len();
                let nd = nn * D;
                let mut m = match k0.get(c).filter(|k| k.len() == nd * nd) {
                    Some(k) => k.iter().map(|x| r.beta * x).collect(),
                    None => vec![0.0; nd * nd],
                };
                if let Some(mass) = self.cell_mass.get(c).filter(|m| m.len() == nn * nn) {
                    for a in 0..nn {
                        for b in 0..nn {
                            for q in 0..D {
                                m[(a * D + q) + nd * (b * D + q)] += r.alpha * mass[a * nn + b];
                            }
                        }
                    }
                }
                m
            })
            .collect();
        Ok(())
    }

    /// `out += C x` over all dofs (`C` the Rayleigh damping and the
    /// dashpots to the ground and between nodes).
    fn damping_times<const D: usize>(&self, model: &Model<D>, x: &[f64], out: &mut [f64]) {
        if self.dashpots {
            // a released link carries no dashpot (`check`): any time will do
            super::discrete::times(model, x, out, f64::NEG_INFINITY, |_, c| c);
        }
        for (c, m) in self.cell_damping.iter().enumerate() {
            let nodes = model.mesh.cells.nodes(c);
            let nd = nodes.len() * D;
            if m.len() != nd * nd {
                continue;
            }
            for j in 0..nd {
                let xj = x[nodes[j / D] * D + j % D];
                if xj == 0.0 {
                    continue;
                }
                for i in 0..nd {
                    out[nodes[i / D] * D + i % D] += m[i + nd * j] * xj;
                }
            }
        }
    }

    /// Whether the model has Rayleigh damping or dashpots.
    fn damped(&self) -> bool {
        !self.cell_damping.is_empty() || self.dashpots
    }

    /// The damping force `C v1` at `u` (committed `u0`), `v1` the
    /// velocity of the scheme at the end of the increment, per dof (zero
    /// without damping or in a quasi-static increment); returns its norm.
    pub fn damping_force<const D: usize>(
        &self,
        model: &Model<D>,
        u: &[f64],
        u0: &[f64],
        out: &mut [f64],
    ) -> f64 {
        out.fill(0.0);
        let Some((k, dt)) = self.active.filter(|_| self.damped()) else {
            return 0.0;
        };
        let a1 = self.acceleration(&k, dt, u, u0);
        let v1: Vec<f64> = self
            .v
            .iter()
            .zip(&self.a)
            .zip(&a1)
            .map(|((v0, a0), a1)| v0 + dt * ((1.0 - k.gamma) * a0 + k.gamma * a1))
            .collect();
        self.damping_times(model, &v1, out);
        out.iter().map(|x| x * x).sum::<f64>().sqrt()
    }

    /// Kinetic energy `1/2 v M v` of the committed velocities.
    pub fn kinetic<const D: usize>(&self, model: &Model<D>) -> f64 {
        let mut mv = vec![0.0; self.v.len()];
        self.mass_times(model, &self.v, &mut mv);
        0.5 * mv.iter().zip(&self.v).map(|(a, b)| a * b).sum::<f64>()
    }

    /// Sets the parameters of an increment ending at `t` of `step` from the
    /// committed time `t0` (quasi-static steps: none).
    pub fn begin_increment(&mut self, step: Option<&Step>, dt: f64) {
        self.active = step
            .and_then(|s| s.dynamic)
            .filter(|_| dt > 0.0)
            .map(|d| (Coefficients::of(d.scheme), dt));
    }

    /// The parameters of the current increment, if it is dynamic.
    pub fn active(&self) -> Option<(Coefficients, f64)> {
        self.active
    }

    /// The acceleration at the end of the increment for displacements `u`
    /// (committed `u0`), per dof.
    fn acceleration(&self, k: &Coefficients, dt: f64, u: &[f64], u0: &[f64]) -> Vec<f64> {
        let (b, h) = (k.beta, dt);
        u.iter()
            .zip(u0)
            .zip(self.v.iter().zip(&self.a))
            .map(|((u1, u0), (v0, a0))| (u1 - u0 - h * v0) / (b * h * h) - (0.5 / b - 1.0) * a0)
            .collect()
    }

    /// The local error estimate of Zienkiewicz & Xie (1991, Earthquake
    /// Eng. Struct. Dyn. 20:871) of the increment ending at `u` (committed
    /// `u0`): `e = (beta - 1/6) dt^2 (a1 - a0)`, the difference between the
    /// scheme's displacement and a third-order Taylor step, in the mass
    /// norm relative to the increment's displacement, `|e|_M / |u1 -
    /// u0|_M` (massless dofs, e.g. the contact nodes of `contact_mass =
    /// redistributed`, do not count). `None` when the increment is
    /// quasi-static or nothing moved.
    pub fn local_error<const D: usize>(
        &self,
        model: &Model<D>,
        u: &[f64],
        u0: &[f64],
    ) -> Option<f64> {
        let (k, dt) = self.active?;
        let a1 = self.acceleration(&k, dt, u, u0);
        let c = (k.beta - 1.0 / 6.0) * dt * dt;
        let e: Vec<f64> = a1
            .iter()
            .zip(&self.a)
            .map(|(a1, a0)| c * (a1 - a0))
            .collect();
        let du: Vec<f64> = u.iter().zip(u0).map(|(u1, u0)| u1 - u0).collect();
        let norm = |x: &[f64]| {
            let mut mx = vec![0.0; x.len()];
            self.mass_times(model, x, &mut mx);
            mx.iter()
                .zip(x)
                .map(|(a, b)| a * b)
                .sum::<f64>()
                .max(0.0)
                .sqrt()
        };
        let (ne, nu) = (norm(&e), norm(&du));
        (nu > 0.0).then(|| ne / nu)
    }

    /// The inertia part of the residual at `u` (added to `f_int - f_ext -
    /// f_c` at every dof) and its force scale (the norm of the mass times
    /// the magnitudes of the terms of `a1`, which cancel in a rigid
    /// motion). Zero when the increment is quasi-static.
    pub fn inertia<const D: usize>(
        &self,
        model: &Model<D>,
        u: &[f64],
        u0: &[f64],
        out: &mut [f64],
    ) -> f64 {
        out.fill(0.0);
        let Some((k, dt)) = self.active else {
            return 0.0;
        };
        let a1 = self.acceleration(&k, dt, u, u0);
        let w = 1.0 / (1.0 - k.alpha_f);
        let mix: Vec<f64> = a1
            .iter()
            .zip(&self.a)
            .map(|(a1, a0)| w * ((1.0 - k.alpha_m) * a1 + k.alpha_m * a0))
            .collect();
        self.mass_times(model, &mix, out);
        let (b, h) = (k.beta, dt);
        let mag: Vec<f64> = (0..u.len())
            .map(|g| {
                w * (((u[g] - u0[g]).abs() + h * self.v[g].abs()) / (b * h * h)
                    + (0.5 / b).abs() * self.a[g].abs())
            })
            .collect();
        let mut scale = vec![0.0; u.len()];
        self.mass_times(model, &mag, &mut scale);
        let c = k.alpha_f * w;
        for (o, r) in out.iter_mut().zip(&self.r0) {
            *o += c * r;
        }
        scale.iter().map(|s| s * s).sum::<f64>().sqrt()
    }

    /// Adds `(1 - am) / ((1 - af) beta dt^2) M` to the tangent values
    /// (free-free and free-prescribed slots of every cell). Under a
    /// distributed assembly split over ranks: the cells of the rank's
    /// share (the others have no slots) and the point masses and nodal
    /// blocks of its nodes (`Scatter::adds_rows_of`).
    pub fn add_tangent<const D: usize>(
        &self,
        model: &Model<D>,
        dofs: &DofMap<D>,
        scatter: &Scatter,
        values: &mut [f64],
    ) {
        let Some((k, dt)) = self.active else {
            return;
        };
        let coef = (1.0 - k.alpha_m) / ((1.0 - k.alpha_f) * k.beta * dt * dt);
        // d (C v1) / d u1 = gamma / (beta dt) C
        let cdamp = k.gamma / (k.beta * dt);
        // point masses: the diagonal of their free dofs
        for (n, m) in self.node_mass.iter().enumerate() {
            if *m == 0.0 || !scatter.adds_rows_of(n) {
                continue;
            }
            for q in 0..D {
                if let Some(Dof::Free(j)) = dofs.dofs.get(n * D + q) {
                    if let Some(s) = scatter.pattern.find(*j, *j) {
                        values[s] += coef * m;
                    }
                }
            }
        }
        // the nodal blocks of contact_mass = normal
        for (n, t) in self.node_tensor.chunks_exact(D * D).enumerate() {
            if !scatter.adds_rows_of(n) {
                continue;
            }
            for p in 0..D {
                for q in 0..D {
                    let (Some(Dof::Free(i)), Some(Dof::Free(j))) =
                        (dofs.dofs.get(n * D + p), dofs.dofs.get(n * D + q))
                    else {
                        continue;
                    };
                    if t[p * D + q] != 0.0 {
                        if let Some(s) = scatter.pattern.find(*i, *j) {
                            values[s] += coef * t[p * D + q];
                        }
                    }
                }
            }
        }
        if self.dashpots {
            super::discrete::add_tangent(
                model,
                dofs,
                scatter,
                values,
                f64::NEG_INFINITY,
                |_, c| cdamp * c,
            );
        }
        for (c, m) in self.cell_damping.iter().enumerate() {
            let nd = model.mesh.cells.nodes(c).len() * D;
            if m.len() != nd * nd {
                continue;
            }
            let slots = scatter.cell_slots(c);
            for (e, &s) in slots.iter().enumerate().take(nd * nd) {
                if s != NO_SLOT {
                    values[s as usize] += cdamp * m[e];
                }
            }
        }
        for (c, m) in self.cell_mass.iter().enumerate() {
            let nn = model.mesh.cells.nodes(c).len();
            let nd = nn * D;
            let slots = scatter.cell_slots(c);
            if slots.len() < nd * nd {
                // another rank's cell
                continue;
            }
            for a in 0..nn {
                for b in 0..nn {
                    let mab = m[a * nn + b];
                    if mab == 0.0 {
                        continue;
                    }
                    for q in 0..D {
                        // column-major: row a D + q, column b D + q
                        let s = slots[(a * D + q) + nd * (b * D + q)];
                        if s != NO_SLOT {
                            values[s as usize] += coef * mab;
                        }
                    }
                }
            }
        }
    }

    /// The diagonal of the mass matrix per dof (`n` dofs; point masses
    /// included).
    fn mass_diagonal<const D: usize>(&self, model: &Model<D>, n: usize) -> Vec<f64> {
        let mut diag = vec![0.0; n];
        for (node, m) in self.node_mass.iter().enumerate() {
            for k in 0..D {
                diag[node * D + k] += m;
            }
        }
        for (node, t) in self.node_tensor.chunks_exact(D * D).enumerate() {
            for k in 0..D {
                diag[node * D + k] += t[k * D + k];
            }
        }
        for (c, m) in self.cell_mass.iter().enumerate() {
            let nodes = model.mesh.cells.nodes(c);
            let nn = nodes.len();
            for (a, &na) in nodes.iter().enumerate() {
                for k in 0..D {
                    diag[na * D + k] += m.get(a * nn + a).copied().unwrap_or(0.0);
                }
            }
        }
        diag
    }

    /// Per dof: whether it is free and carries no mass (the spin node of
    /// a 3D rigid body, a spring's end node, the contact nodes of
    /// `contact_mass = redistributed`): the dofs whose equation is static
    /// ([`Dynamics::start`]).
    pub fn massless_free<const D: usize>(&self, model: &Model<D>, dofs: &DofMap<D>) -> Vec<bool> {
        let diag = self.mass_diagonal(model, dofs.dofs.len());
        dofs.dofs
            .iter()
            .zip(&diag)
            .map(|(d, m)| matches!(d, Dof::Free(_)) && *m <= 0.0)
            .collect()
    }

    /// The initial acceleration `M_ff a_f = -r_f` (prescribed dofs: 0) of
    /// the state with residual `r` (`f_int - f_ext - f_c` per dof), by
    /// Jacobi-preconditioned conjugate gradients; `r` becomes the
    /// committed residual. The massless free dofs ([`Dynamics::massless_free`])
    /// get no acceleration: their equation is static, so `r` must hold it
    /// (`r = 0` there): the caller solves their static condensation first
    /// (`Newton::consistent_start`), else a load on them at the start (a
    /// moment on a 3D rigid body's spin node) would reach the masses one
    /// increment late (a first-order error) and its share `alpha_f r0` would
    /// stay in the next increment's equation.
    pub fn start<const D: usize>(&mut self, model: &Model<D>, dofs: &DofMap<D>, r: &[f64]) {
        // the damping force of the initial velocities is part of it, and
        // the start of the damping work integral
        let mut d0 = vec![0.0; r.len()];
        self.damping_times(model, &self.v, &mut d0);
        let r: Vec<f64> = r.iter().zip(&d0).map(|(r, d)| r + d).collect();
        let r = &r[..];
        self.forces0[3] = d0;
        // free dofs that carry mass (contact nodes may not: their
        // acceleration is left 0, they follow the constraint statically)
        let mut free: Vec<bool> = dofs
            .dofs
            .iter()
            .map(|d| matches!(d, Dof::Free(_)))
            .collect();
        let n = r.len();
        // the diagonal of M: the Jacobi preconditioner
        let mut diag = self.mass_diagonal(model, n);
        for (f, d) in free.iter_mut().zip(&mut diag) {
            *f = *f && *d > 0.0;
            if !*f {
                *d = 1.0;
            }
        }
        let apply = |x: &[f64], out: &mut [f64]| {
            out.fill(0.0);
            self.mass_times(model, x, out);
            for (o, f) in out.iter_mut().zip(&free) {
                if !f {
                    *o = 0.0;
                }
            }
        };
        let b: Vec<f64> = r
            .iter()
            .zip(&free)
            .map(|(r, f)| if *f { -r } else { 0.0 })
            .collect();
        let bnorm = b.iter().map(|x| x * x).sum::<f64>().sqrt();
        let mut x = vec![0.0; n];
        if bnorm > 0.0 {
            let mut res = b.clone();
            let mut z: Vec<f64> = res.iter().zip(&diag).map(|(r, d)| r / d).collect();
            let mut p = z.clone();
            let mut rz: f64 = res.iter().zip(&z).map(|(a, b)| a * b).sum();
            let mut ap = vec![0.0; n];
            for _ in 0..10 * n.max(10) {
                apply(&p, &mut ap);
                let pap: f64 = p.iter().zip(&ap).map(|(a, b)| a * b).sum();
                if pap <= 0.0 {
                    break;
                }
                let alpha = rz / pap;
                for i in 0..n {
                    x[i] += alpha * p[i];
                    res[i] -= alpha * ap[i];
                }
                if res.iter().map(|x| x * x).sum::<f64>().sqrt() <= 1e-14 * bnorm {
                    break;
                }
                z = res.iter().zip(&diag).map(|(r, d)| r / d).collect();
                let rz1: f64 = res.iter().zip(&z).map(|(a, b)| a * b).sum();
                let beta = rz1 / rz;
                rz = rz1;
                for i in 0..n {
                    p[i] = z[i] + beta * p[i];
                }
            }
        }
        self.a = x;
        self.r0.copy_from_slice(r);
        self.started = true;
    }

    /// The internal, external (+ reactions) and contact forces of the
    /// initial state, where the trapezoidal work integrals start (call
    /// after [`Dynamics::start`] when no increment was committed before).
    pub fn start_forces(&mut self, forces: [&[f64]; 3]) {
        for (f0, f) in self.forces0.iter_mut().zip(forces) {
            f0.copy_from_slice(f);
        }
    }

    /// Adds `internal` and `contact` (per dof) to the start of the internal
    /// and contact work integrals: the forces `K du` of the massless dofs'
    /// static condensation at the start (`Newton::consistent_start`), so
    /// that the audit's net force at the start is the committed residual
    /// the scheme uses.
    pub fn add_start_forces(&mut self, internal: &[f64], contact: &[f64]) {
        for (k, forces) in [(0, internal), (2, contact)] {
            for (f0, f) in self.forces0[k].iter_mut().zip(forces) {
                *f0 += f;
            }
        }
    }

    /// Commits the converged increment: velocities and accelerations (a
    /// dynamic increment), the committed residual `r` and the energies
    /// from the forces (`f_int`, `f_ext` + static reactions, `f_c`,
    /// damping `C v`, per dof; the inertia `M a1` of the `prescribed` dofs
    /// is added to their reactions here) and the displacements `u`
    /// (committed `u0`).
    pub fn commit<const D: usize>(
        &mut self,
        model: &Model<D>,
        u: &[f64],
        u0: &[f64],
        r: &[f64],
        forces: [&[f64]; FORCES],
        prescribed: &[usize],
    ) {
        let audit = self.audit(model, u, u0, forces, prescribed);
        match audit.rates {
            Some((v, a)) => {
                self.v = v;
                self.a = a;
            }
            None => {
                // a quasi-static increment ends at rest
                self.v.fill(0.0);
                self.a.fill(0.0);
            }
        }
        self.r0.copy_from_slice(r);
        for (k, (f0, f1)) in self.forces0.iter_mut().zip(forces).enumerate() {
            f0.copy_from_slice(if k == 1 { &audit.external } else { f1 });
        }
        self.energy = audit.energy;
    }

    /// What committing the increment ending at `u` (committed `u0`) would
    /// make of the state, without committing it ([`Dynamics::commit`]; the
    /// energy control of dynamic steps weighs an attempt by it): the
    /// velocities and accelerations (`None`: a quasi-static increment, which
    /// ends at rest), the external forces with the inertia of the
    /// `prescribed` dofs, and the energies (`penalty` kept from the last
    /// commit: the caller sets it).
    pub fn audit<const D: usize>(
        &self,
        model: &Model<D>,
        u: &[f64],
        u0: &[f64],
        forces: [&[f64]; FORCES],
        prescribed: &[usize],
    ) -> Audit {
        let mut external = forces[1].to_vec();
        let mut forces = forces;
        let mut numerical = 0.0;
        let mut rates = None;
        if let Some((k, dt)) = self.active {
            let a1 = self.acceleration(&k, dt, u, u0);
            if !prescribed.is_empty() {
                let mut ma = vec![0.0; a1.len()];
                self.mass_times(model, &a1, &mut ma);
                for &g in prescribed {
                    external[g] += ma[g];
                }
            }
            forces[1] = &external;
            // the net force f_int - f_ext - f_c + C v the audit integrates
            let net = |f: &[&[f64]]| -> Vec<f64> {
                (0..u.len())
                    .map(|g| f[0][g] - f[1][g] - f[2][g] + f[3][g])
                    .collect()
            };
            let mut v1 = self.v.clone();
            for ((v, a0), a1) in v1.iter_mut().zip(&self.a).zip(&a1) {
                *v += dt * ((1.0 - k.gamma) * a0 + k.gamma * a1);
            }
            numerical = numerical_dissipation(
                &k,
                [&self.v, &v1],
                [&self.a, &a1],
                [
                    &net(&self.forces0.iter().map(Vec::as_slice).collect::<Vec<_>>()),
                    &net(&forces),
                ],
                u,
                u0,
                |x, out| self.mass_times(model, x, out),
            );
            rates = Some((v1, a1));
        }
        let mut work = [0.0; FORCES];
        for (w, (f1, f0)) in work.iter_mut().zip(forces.iter().zip(&self.forces0)) {
            *w = f1
                .iter()
                .zip(f0)
                .zip(u.iter().zip(u0))
                .map(|((f1, f0), (u1, u0))| 0.5 * (f1 + f0) * (u1 - u0))
                .sum();
        }
        let mut e = self.energy;
        e.internal += work[0];
        e.external += work[1];
        e.contact += work[2];
        e.damping += work[3];
        e.kinetic = match &rates {
            Some((v1, _)) => {
                let mut mv = vec![0.0; v1.len()];
                self.mass_times(model, v1, &mut mv);
                0.5 * mv.iter().zip(v1).map(|(a, b)| a * b).sum::<f64>()
            }
            None => self.kinetic_of_rest(model),
        };
        e.numerical += numerical;
        e.close(self.kinetic0);
        Audit {
            rates,
            external,
            energy: e,
        }
    }

    /// The kinetic energy of the bodies at rest (0; the same operations as
    /// [`Dynamics::kinetic`] on zero velocities).
    fn kinetic_of_rest<const D: usize>(&self, model: &Model<D>) -> f64 {
        let zero = vec![0.0; self.v.len()];
        let mut mv = vec![0.0; zero.len()];
        self.mass_times(model, &zero, &mut mv);
        0.5 * mv.iter().zip(&zero).map(|(a, b)| a * b).sum::<f64>()
    }

    /// The friction work of the converged increment as the time scheme
    /// does it, written over each node's `friction.dissipation` of
    /// `contact` (per pair, the lists of the increment's end): the
    /// trapezoidal rule of the audit's other work terms, `-(T_0 + T_1) / 2
    /// . s` with `T_0`, `T_1` the node's friction force at the ends of the
    /// increment and `s` its slip increment vector, that is the return
    /// map's `-T_1 . s` plus `-(T_0 - T_1) . s / 2`. The friction forces
    /// are part of the contact force whose work the audit integrates by
    /// the same rule, so the pair's friction work and the normal forces'
    /// work add up to `contact` (but for the energy stored in the
    /// regularized tangential springs of closed nodes); what the scheme's
    /// `alpha_f` weighting does beyond it is in [`numerical_dissipation`],
    /// for every force alike. A node that opens also dissipates its
    /// tangential spring's energy `|R_T| |g_e| / 2` (the stick point is
    /// dropped with it): a block hopping as it slides loses it at every
    /// lift-off. (The force at the end alone, the return map's, is
    /// backward Euler.) A quasi-static increment keeps the return map's
    /// value and only records `T_1`. Mortar pairs in 2D, which report no
    /// slip vector, keep the return map's value but for the spring's
    /// energy.
    pub fn friction_work<const D: usize>(&mut self, contact: &mut [Vec<NodeContact<D>>]) {
        let n = self.v.len();
        let dynamic = self.active.is_some();
        // per pair: the friction forces and the elastic energies (at the
        // node's first dof) of the increment's start
        self.friction0.resize(2 * contact.len(), Vec::new());
        for (p, pair) in contact.iter_mut().enumerate() {
            let [f0, e0] = &mut self.friction0[2 * p..2 * p + 2] else {
                continue;
            };
            let any = pair
                .iter()
                .any(|c| c.friction.traction.iter().any(|t| *t != 0.0));
            if !any && f0.is_empty() {
                continue;
            }
            for v in [&mut *f0, &mut *e0] {
                if v.len() != n {
                    *v = vec![0.0; n];
                }
            }
            let (mut f1, mut e1) = (vec![0.0; n], vec![0.0; n]);
            for c in pair.iter_mut() {
                let at = c.node * D;
                if at + D > n {
                    continue;
                }
                let fr = &mut c.friction;
                // no friction force at the end: open, or a zero cone
                let open = fr.status == FrictionStatus::Frictionless
                    || fr.traction.iter().all(|t| *t == 0.0);
                if dynamic {
                    let change: f64 = (0..D)
                        .map(|k| (f0[at + k] - fr.traction[k]) * fr.slip_vector[k])
                        .sum();
                    fr.dissipation -= 0.5 * change;
                    if open {
                        // the tangential spring's energy, lost with the
                        // stick point
                        fr.dissipation += e0[at];
                    }
                }
                for k in 0..D {
                    f1[at + k] += fr.traction[k];
                }
                if !open {
                    e1[at] += elastic_energy(fr);
                }
            }
            *f0 = f1;
            *e0 = e1;
        }
    }

    /// Carries the committed rates and forces of the three dofs `dofs` of
    /// a free 3D body's rotation vector over to another chart
    /// ([`super::rotation_chart`]).
    pub fn rechart(&mut self, dofs: [usize; 3], chart: &super::rotation_chart::Chart) {
        let get = |x: &[f64]| -> [f64; 3] { dofs.map(|g| x[g]) };
        let put = |x: &mut [f64], y: [f64; 3]| {
            for (g, y) in dofs.iter().zip(y) {
                x[*g] = y;
            }
        };
        let (v, a) = (get(&self.v), get(&self.a));
        put(&mut self.v, chart.velocity(v));
        put(&mut self.a, chart.acceleration(v, a));
        let r0 = chart.force(get(&self.r0));
        put(&mut self.r0, r0);
        for f in &mut self.forces0 {
            let y = chart.force(get(f));
            put(f, y);
        }
    }

    /// The committed contact forces per dof (the start of the contact
    /// work integral).
    pub fn contact_force0(&self) -> &[f64] {
        &self.forces0[2]
    }

    /// The committed state carried by restart points (the mass is rebuilt
    /// from the model when the next dynamic increment begins).
    pub fn saved(&self) -> DynamicState {
        DynamicState {
            started: self.started,
            v: self.v.clone(),
            a: self.a.clone(),
            r0: self.r0.clone(),
            // the pairs' committed friction forces follow the work integrals'
            forces0: self
                .forces0
                .iter()
                .chain(&self.friction0)
                .cloned()
                .collect(),
            kinetic0: self.kinetic0,
            energy: self.energy.values(),
        }
    }

    /// Makes `s` the committed state (a restart).
    pub fn restore(&mut self, s: &DynamicState) -> Result<(), String> {
        let n = self.v.len();
        let lens = [s.v.len(), s.a.len(), s.r0.len()]
            .into_iter()
            .chain(s.forces0.iter().take(FORCES).map(Vec::len));
        // past the work integrals' forces: each pair's friction forces
        // (empty: none yet)
        let friction = s.forces0.iter().skip(FORCES).map(Vec::len);
        if s.forces0.len() < FORCES
            || lens.into_iter().any(|l| l != n)
            || friction.into_iter().any(|l| l != n && l != 0)
        {
            return Err(format!(
                "the restart point's velocities do not match the model ({n} dofs)"
            ));
        }
        self.started = s.started;
        self.v.clone_from(&s.v);
        self.a.clone_from(&s.a);
        self.r0.clone_from(&s.r0);
        self.forces0 = s.forces0[..FORCES].to_vec();
        // restart points written before the friction work's trapezoidal
        // rule carry no friction forces: from none
        // (two per pair: forces and elastic energies)
        let friction = &s.forces0[FORCES..];
        self.friction0 = if friction.len().is_multiple_of(2) {
            friction.to_vec()
        } else {
            Vec::new()
        };
        self.kinetic0 = s.kinetic0;
        self.energy = Energy::from_values(&s.energy)
            .ok_or("the restart point's energy audit does not match this version")?;
        Ok(())
    }
}

/// What the energy audit of a committed increment shows the physics
/// cannot do, each beyond [`ENERGY_GROWTH_TOL`] of the largest energy
/// ([`Energy::alarms`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EnergyAlarm {
    /// The internal work is negative: the bodies' strain energy plus
    /// their plastic dissipation cannot be, so the kinetic energy exceeds
    /// the work put in (an integrator whose trapezoidal work no longer
    /// follows a stiff nonlinear response: `kinetic + internal` balances
    /// while both blow up).
    NegativeInternal,
    /// `Energy::gain`: kinetic + internal energy beyond the work of the
    /// loads and supports (energy created, e.g. by contact chatter).
    Gain,
    /// `Energy::balance`: kinetic + internal energy beyond the work of the
    /// loads, supports and contact forces (energy created by the
    /// integrator).
    Created,
}

impl EnergyAlarm {
    /// Every alarm, in the order [`Energy::alarms`] gives them.
    pub const ALL: [EnergyAlarm; 3] = [
        EnergyAlarm::NegativeInternal,
        EnergyAlarm::Gain,
        EnergyAlarm::Created,
    ];
}

impl Energy {
    /// The alarms the energies raise (in [`EnergyAlarm::ALL`] order), each
    /// against [`ENERGY_GROWTH_TOL`] of [`Energy::scale`]; with
    /// `thermal_strain` the internal work may go negative (a body heated
    /// against a constraint does work on it) and is not checked.
    pub fn alarms(&self, thermal_strain: bool) -> Vec<EnergyAlarm> {
        let tol = ENERGY_GROWTH_TOL * self.scale;
        EnergyAlarm::ALL
            .into_iter()
            .filter(|a| match a {
                EnergyAlarm::NegativeInternal => !thermal_strain && self.internal < -tol,
                EnergyAlarm::Gain => self.gain > tol,
                EnergyAlarm::Created => self.balance > tol,
            })
            .collect()
    }

    /// The warning for `alarm` raised at increment `increment` ending at
    /// time `t`.
    pub fn warning(&self, alarm: EnergyAlarm, increment: usize, t: f64) -> String {
        let (what, value, remedy) = match alarm {
            EnergyAlarm::NegativeInternal => (
                "the internal work went negative (strain energy and plastic dissipation \
                 cannot: the kinetic energy exceeds the work put in)",
                self.internal,
                "the response is no longer resolved in time (a stiff or distorted cell, a \
                 node driven through a surface): smaller increments (`dynamic { adaptive = \
                 true }`), and look at the cells and contact nodes of the largest velocities",
            ),
            EnergyAlarm::Gain => (
                "the total energy grew beyond the work of the loads and supports",
                self.gain,
                "a smaller time increment, or a dissipative scheme (`dynamic { scheme = \
                 generalized_alpha  rho_inf = 0.8 }`) against contact chatter",
            ),
            EnergyAlarm::Created => (
                "the integrator created energy: kinetic + internal energy beyond the work of \
                 the loads, supports and contact forces",
                self.balance,
                "a smaller time increment, or a dissipative scheme (`dynamic { scheme = \
                 generalized_alpha  rho_inf = 0.8 }`)",
            ),
        };
        format!(
            "energy audit, increment {increment} (t = {t:.6e}): {what}: {value:.3e} ({:.2} % of \
             the largest energy {:.3e}, tolerance {} %); kinetic {:.4e}, internal work {:.4e}, \
             external work {:.4e}, contact work {:.4e}, balance {:.4e}; {remedy}",
            100.0 * value.abs() / self.scale,
            self.scale,
            100.0 * ENERGY_GROWTH_TOL,
            self.kinetic,
            self.internal,
            self.external,
            self.contact,
            self.balance,
        )
    }
}

/// The energy the generalized-alpha scheme removes in one increment
/// (negative: creates), from its own quantities: velocities `v = [v0, v1]`,
/// accelerations `a = [a0, a1]`, the net forces the audit integrates `f
/// = [f0, f1]` (`f_int - f_ext - f_c + C v`, reactions in `f_ext`),
/// displacements `u` (committed `u0`), the mass product `mass(x, out)`.
///
/// The audit integrates the net force `f = f_int - f_ext - f_c + C v` by
/// the trapezoidal rule, but the scheme holds `M a_m + f_m = 0` at the
/// alpha levels, `a_m = (1 - am) a1 + am a0`, `f_m = (1 - af) f1 + af f0`.
/// With `(f0 + f1) / 2 = f_m + (af - 1/2) (f1 - f0)`, the audited energy
/// change of an increment is
///
/// ```text
/// dK + (f0 + f1) / 2 . du = [M a_m + f_m] . du  -  D,
/// D = -(dK - M a_m . du) - (af - 1/2) (f1 - f0) . du
/// ```
///
/// the first term the residual's work (0 when the increment's equation
/// holds), `D` the scheme's numerical dissipation. `D = 0` for the
/// average-acceleration rule (`am = af = 0`, `beta = 1/4`, `gamma = 1/2`:
/// `M a = -f` at both ends and `du = dt (v0 + v1) / 2`), and for a linear
/// system under generalized-alpha it is the loss of the amplification
/// matrix (Chung & Hulbert 1993: `rho_inf < 1` damps the high modes).
/// Under contact it is of either sign: a penalty force switched on or off
/// within an increment makes `(af - 1/2) (f1 - f0) . du` large.
pub fn numerical_dissipation(
    k: &Coefficients,
    v: [&[f64]; 2],
    a: [&[f64]; 2],
    f: [&[f64]; 2],
    u: &[f64],
    u0: &[f64],
    mass: impl Fn(&[f64], &mut [f64]),
) -> f64 {
    let n = u.len();
    // dK = (v1 - v0) . M (v1 + v0) / 2 and M a_m . du with one product:
    // M [(v1 + v0) / 2] . (v1 - v0) - M a_m . du (M symmetric)
    let vbar: Vec<f64> = (0..n).map(|g| 0.5 * (v[0][g] + v[1][g])).collect();
    let am: Vec<f64> = (0..n)
        .map(|g| (1.0 - k.alpha_m) * a[1][g] + k.alpha_m * a[0][g])
        .collect();
    let (mut mv, mut ma) = (vec![0.0; n], vec![0.0; n]);
    mass(&vbar, &mut mv);
    mass(&am, &mut ma);
    let mut kinematic = 0.0;
    let mut force = 0.0;
    for g in 0..n {
        let du = u[g] - u0[g];
        kinematic += mv[g] * (v[1][g] - v[0][g]) - ma[g] * du;
        force += (f[1][g] - f[0][g]) * du;
    }
    -kinematic - (k.alpha_f - 0.5) * force
}

/// The energy `|R_T| |g_e| / 2` of a node's regularized tangential spring,
/// `g_e` the elastic part of its tangential gap (`g_T - slip`: planar,
/// signed components; 3D, magnitudes along the same direction); 0 under
/// Lagrange multipliers (no elastic part).
fn elastic_energy<const D: usize>(f: &crate::contact::friction::NodeFriction<D>) -> f64 {
    let elastic = if D == 2 {
        f.tangential_gap - f.slip
    } else {
        f.tangential_gap.abs() - f.slip.abs()
    };
    0.5 * f.tangential_force.abs() * elastic.abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One mode `u'' + w^2 u = 0` stepped by the scheme's own recursion:
    /// the energy `v^2 / 2 + w^2 u^2 / 2` lost per step (the trapezoidal
    /// work of a linear spring is its exact energy) is
    /// [`numerical_dissipation`] to round-off, positive for `rho_inf < 1`
    /// and 0 for the average-acceleration rule.
    #[test]
    fn numerical_dissipation_is_the_energy_lost_by_one_mode() {
        let (w, dt) = (2.0 * std::f64::consts::PI, 0.05);
        let k2 = w * w;
        for (scheme, lossy) in [
            (Scheme::GeneralizedAlpha { rho_inf: 0.9 }, true),
            (Scheme::GeneralizedAlpha { rho_inf: 0.5 }, true),
            (Scheme::Hht { rho_inf: 0.7 }, true),
            (
                Scheme::Newmark {
                    beta: 0.25,
                    gamma: 0.5,
                },
                false,
            ),
        ] {
            let k = Coefficients::of(scheme);
            let (b, g) = (k.beta, k.gamma);
            let (mut u, mut v) = (1.0f64, 0.3f64);
            let mut a = -k2 * u;
            let energy = |u: f64, v: f64| 0.5 * v * v + 0.5 * k2 * u * u;
            let e_start = energy(u, v);
            let mut total = 0.0;
            for _ in 0..200 {
                // (1 - am) a1 + am a + (1 - af) w^2 u1 + af w^2 u = 0
                let pred = u + dt * v + dt * dt * (0.5 - b) * a;
                let a1 = -(k.alpha_m * a + k.alpha_f * k2 * u + (1.0 - k.alpha_f) * k2 * pred)
                    / ((1.0 - k.alpha_m) + (1.0 - k.alpha_f) * k2 * b * dt * dt);
                let u1 = pred + dt * dt * b * a1;
                let v1 = v + dt * ((1.0 - g) * a + g * a1);
                let d = numerical_dissipation(
                    &k,
                    [&[v], &[v1]],
                    [&[a], &[a1]],
                    [&[k2 * u], &[k2 * u1]],
                    &[u1],
                    &[u],
                    |x, out| out.copy_from_slice(x),
                );
                let lost = energy(u, v) - energy(u1, v1);
                assert!(
                    (d - lost).abs() <= 1e-13 * e_start,
                    "{scheme:?}: D {d:e} vs lost {lost:e}"
                );
                total += d;
                (u, v, a) = (u1, v1, a1);
            }
            if lossy {
                // 10 periods at omega dt = 0.31: 3.0e-4 of the energy lost
                // at rho_inf = 0.9, more at the others
                assert!(total > 1e-4 * e_start, "{scheme:?}: {total:e}");
            } else {
                assert!(total.abs() <= 1e-13 * e_start, "{scheme:?}: {total:e}");
            }
        }
    }

    /// The audit of the 3D blade loss flown to 20 ms (issue 19; debug
    /// `ctc run` of examples/blade_loss_3d.ctc with `flight_end = 20e-3`,
    /// history.csv at 13.475 and 13.5 ms): the kinetic energy jumped 5.3e6
    /// -> 1.6e7 mJ while the trapezoidal internal work went -1.0e7, so the
    /// gain and the balance stayed negative and no warning was given. The
    /// negative internal work is the alarm (not under thermal strains);
    /// the gain and the balance raise theirs when positive.
    #[test]
    fn a_negative_internal_work_raises_an_alarm_the_balance_does_not() {
        let energy = |kinetic: f64, internal: f64, external: f64, contact: f64, damping: f64| {
            let mut e = Energy {
                kinetic,
                internal,
                external,
                contact,
                damping,
                ..Energy::default()
            };
            e.close(0.0);
            e
        };
        // 13.475 ms (increment 361): sound
        let before = energy(5.261e6, 3.702e5, 2.331e7, -1.643e7, 1.088e6);
        assert!(before.alarms(false).is_empty(), "{before:?}");
        // 13.5 ms: the blow-up's first increment
        let after = energy(1.603e7, -1.013e7, 2.415e7, -1.673e7, 1.104e6);
        assert!(after.gain < 0.0 && after.balance < 0.0, "{after:?}");
        assert_eq!(after.alarms(false), vec![EnergyAlarm::NegativeInternal]);
        assert!(after.alarms(true).is_empty());
        let w = after.warning(EnergyAlarm::NegativeInternal, 362, 0.013500000000000002);
        assert!(
            w.contains("increment 362 (t = 1.350000e-2)")
                && w.contains("internal work went negative"),
            "{w}"
        );
        // energy created by contact (gain) and by the integrator (balance)
        let chatter = energy(2.0, 1.0, 1.0, 2.0, 0.0);
        assert_eq!(chatter.alarms(false), vec![EnergyAlarm::Gain]);
        let created = energy(2.0, 1.0, 1.0, 0.0, 0.0);
        assert_eq!(
            created.alarms(false),
            vec![EnergyAlarm::Gain, EnergyAlarm::Created]
        );
    }

    #[test]
    fn special_cases_of_generalized_alpha() {
        // rho_inf = 1: every scheme is the average acceleration rule
        for s in [
            Scheme::Hht { rho_inf: 1.0 },
            Scheme::GeneralizedAlpha { rho_inf: 1.0 },
        ] {
            let k = Coefficients::of(s);
            assert!(
                (k.beta - 0.25).abs() < 1e-15 && (k.gamma - 0.5).abs() < 1e-15,
                "{s:?}"
            );
            // the same weights on accelerations and forces: trapezoidal
            assert!((k.alpha_m - k.alpha_f).abs() < 1e-15, "{s:?}");
        }
        // Chung & Hulbert eq. 25 at rho_inf = 0: am = -1, af = 0, gamma = 3/2, beta = 1
        let k = Coefficients::of(Scheme::GeneralizedAlpha { rho_inf: 0.0 });
        assert_eq!(
            (k.alpha_m, k.alpha_f, k.gamma, k.beta),
            (-1.0, 0.0, 1.5, 1.0)
        );
        // HHT at rho_inf = 1/2: alpha = 1/3
        let k = Coefficients::of(Scheme::Hht { rho_inf: 0.5 });
        assert!((k.alpha_f - 1.0 / 3.0).abs() < 1e-15 && k.alpha_m == 0.0);
    }
}
