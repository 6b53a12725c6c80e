//! The lowered scene: everything the engine needs to run a deck, and nothing
//! the deck did not ask for.
//!
//! `ctc-lang` parses and validates a `.ctc` deck and lowers it into a [`Model`].
//! All node and element numbers here are **global** (all bodies share one
//! [`Mesh`]); each [`Body`] owns a contiguous range of nodes and cells.
//! Sign and unit conventions are stated on each field; there are no units in
//! the engine (consistent units are the user's business, as in Abaqus).

pub mod thermal;

use crate::mesh::Mesh;
use std::ops::Range;

/// A complete, validated problem ready to be solved, in dimension `D`
/// (2: planar analyses, 3: solid). `Model` without a parameter is the
/// planar model.
#[derive(Debug, Clone)]
pub struct Model<const D: usize = 2> {
    /// Kinematic assumption of the 2D analysis and out-of-plane thickness.
    pub analysis: Analysis,
    /// Nodes, cells and named sets of every body, globally numbered.
    pub mesh: Mesh<D>,
    /// The deformable bodies, in deck order.
    pub bodies: Vec<Body>,
    /// Materials referenced by bodies (index = `Body::material`).
    pub materials: Vec<Material>,
    /// Prescribed displacement components (fixed = constant 0).
    pub constraints: Vec<Dirichlet>,
    /// External loads (pressures, nodal forces).
    pub loads: Vec<Load>,
    /// Rigid analytical curve tools of a planar model (no mesh, no
    /// unknowns); empty in 3D.
    pub tools: Vec<RigidTool>,
    /// Rigid surface tools of a solid (3D) model; empty in 2D. A 3D pair's
    /// `ContactMaster::Tool(i)` indexes this list.
    pub surfaces: Vec<SurfaceTool>,
    /// Contact pairs between a body surface and a rigid tool.
    pub contacts: Vec<ContactPair>,
    /// Load steps, run in order; their time ranges are contiguous.
    pub steps: Vec<Step>,
    /// What to write, and how often.
    pub output: OutputRequest,
    /// Heat conduction and thermo-mechanical coupling; `None` when the deck
    /// has no `thermal` block (then there are no temperature unknowns).
    pub thermal: Option<thermal::ThermalScene>,
    /// Initial velocities (dynamic steps; nodes not listed start at rest).
    pub initial_velocities: Vec<InitialVelocity>,
    /// Discrete elements at nodes: springs and dashpots to the ground or
    /// between two nodes, point masses (`crate::solve::discrete`,
    /// `crate::solve::dynamics`, `Newton::evaluate`).
    pub discrete: Vec<Discrete>,
}

/// A discrete element on each node of a set. Values are totals per node
/// (planar: for the model's thickness; axisymmetric: over the full 2 pi).
#[derive(Debug, Clone, PartialEq)]
pub enum Discrete {
    /// A linear spring and a linear dashpot from each node to the ground,
    /// isotropic (every component): force `-(k u + c v)`; the dashpot acts
    /// in dynamic increments only.
    Ground {
        /// Label.
        label: String,
        /// Global node numbers.
        nodes: Vec<usize>,
        /// Spring stiffness `k` (force / length), `>= 0`.
        stiffness: f64,
        /// Dashpot coefficient `c` (force time / length), `>= 0`.
        damping: f64,
    },
    /// A linear spring and a linear dashpot between two nodes, isotropic
    /// (every component): on `a` the force `-(k (u_a - u_b) + c (v_a -
    /// v_b))`, its opposite on `b` (`solve/discrete.rs`); the dashpot acts
    /// in dynamic increments only.
    Link {
        /// Label.
        label: String,
        /// Global node pairs `(a, b)`.
        pairs: Vec<(usize, usize)>,
        /// Spring stiffness `k` (force / length), `>= 0`.
        stiffness: f64,
        /// Dashpot coefficient `c` (force time / length), `>= 0`.
        damping: f64,
        /// The time from which the links are gone (a released part: a
        /// blade off its disc; `None`: never). The spring acts while `t <
        /// release_at`; a released link carries no dashpot (refused).
        release_at: Option<f64>,
    },
    /// A rigid body (`solve/rigid_body.rs`): its nodes follow the motion
    /// of a **pilot node** (translation `u_c`) and a **spin node** (planar:
    /// its x displacement is the rotation `theta`, y held; 3D: its
    /// displacement is the total rotation vector `psi`), `x_a = X_c + u_c +
    /// R (X_a - X_c)` at finite rotation, `X_c` the pilot's position; tied
    /// by a stiff spring `stiffness` per node to that position (a penalty:
    /// the energy `k/2 |x_a - p_a(u_c, R)|^2`, in `f_int` with its exact
    /// tangent). Planar and 3D models (not axisymmetric).
    Rigid {
        /// Label.
        label: String,
        /// The nodes moving with the body (global numbers; 3D: with the
        /// inertia points appended by `make_rigid`).
        nodes: Vec<usize>,
        /// The pilot node (translation), appended at the centre.
        pilot: usize,
        /// The spin node (planar: angle on x, y held; 3D: the rotation
        /// vector), appended at the centre.
        spin: usize,
        /// The tie stiffness per node (force / length), `> 0`.
        stiffness: f64,
    },
    /// A point mass at each node (every component; dynamic steps).
    Mass {
        /// Label.
        label: String,
        /// Global node numbers.
        nodes: Vec<usize>,
        /// The mass, `>= 0`.
        mass: f64,
    },
}

/// A model of either dimension: what lowering a deck gives (the dimension
/// is chosen once, at the top, and every caller matches once).
#[derive(Debug, Clone)]
pub enum AnyModel {
    /// A planar model (plane strain, plane stress, axisymmetric).
    D2(Model<2>),
    /// A solid (3D) model.
    D3(Model<3>),
}

/// Kinematic assumption: a planar embedding (2D) or the solid (3D).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum AnalysisKind {
    /// eps_zz = 0; sigma_zz = lambda (eps_xx + eps_yy).
    PlaneStrain,
    /// sigma_zz = 0.
    PlaneStress,
    /// x is the radius r >= 0, y is the axis z; hoop strain u_r / r.
    /// Forces, reactions and contact forces are totals over the full 2*pi.
    Axisymmetric,
    /// Three-dimensional solid (x, y, z): no embedding.
    Solid,
}

/// Analysis settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Analysis {
    /// Plane strain, plane stress or axisymmetric.
    pub kind: AnalysisKind,
    /// Out-of-plane thickness for plane strain/stress (ignored for axisymmetric).
    pub thickness: f64,
}

/// One deformable body: a contiguous block of the global mesh.
#[derive(Debug, Clone)]
pub struct Body {
    /// Name from the deck (`body disc { .. }`).
    pub name: String,
    /// Global node numbers of this body.
    pub nodes: Range<usize>,
    /// Global cell numbers of this body.
    pub cells: Range<usize>,
    /// Index into `Model::materials`.
    pub material: usize,
    /// How quadrilaterals are integrated (triangles are always 1-point tri3).
    pub formulation: Formulation,
    /// Small strain (linear kinematics) or finite strain (total Lagrangian).
    pub kinematics: Kinematics,
}

/// Kinematic assumption of a body.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Kinematics {
    /// Small displacements and strains: `eps = sym grad u` (the cheaper path).
    #[default]
    Small,
    /// Finite strains and rotations: total Lagrangian with the deformation
    /// gradient `F = I + Grad u` (see `crate::element::finite`).
    Finite,
}

/// Element technology of a body.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Formulation {
    /// quad4 with 2x2 Gauss; tri3 with 1 point.
    Full,
    /// quad4 with 2x2 Gauss on the deviatoric part and 1 point on the
    /// volumetric part (B-bar style selective reduced integration).
    SelectiveReduced,
}

/// A named material.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Name from the deck.
    pub name: String,
    /// The constitutive law.
    pub law: MaterialLaw,
    /// Mass density (mass per volume; 0: no inertia, quasi-static steps
    /// only).
    pub density: f64,
}

/// Constitutive laws. Only what decks can ask for exists here.
#[derive(Debug, Clone, PartialEq)]
pub enum MaterialLaw {
    /// Small-strain isotropic linear elasticity.
    LinearElastic {
        /// Young's modulus, > 0.
        young: f64,
        /// Poisson's ratio, in (-1, 0.5).
        poisson: f64,
    },
    /// Compressible Neo-Hookean hyperelasticity (finite kinematics only):
    /// `W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2`, with the Lame
    /// constants of `young` and `poisson`.
    NeoHookean {
        /// Small-strain Young's modulus, > 0.
        young: f64,
        /// Small-strain Poisson's ratio, in (-1, 0.5).
        poisson: f64,
    },
    /// Isotropic elasticity with von Mises (J2) plasticity and isotropic
    /// hardening; small strain (additive split) or finite strain
    /// (multiplicative split, Hencky elastic strains) by the body's
    /// kinematics.
    ElastoPlastic {
        /// Young's modulus, > 0.
        young: f64,
        /// Poisson's ratio, in (-1, 0.5).
        poisson: f64,
        /// Flow stress as a function of the equivalent plastic strain.
        hardening: Hardening,
        /// Rate dependence of the flow (Perzyna or Norton-Hoff); `None` is
        /// rate-independent plasticity.
        viscosity: Option<Viscosity>,
    },
}

/// A pressure-cycle controller (superplastic forming): after every
/// converged increment the factor `c` applied to a follower pressure is
/// multiplied by `(target / rate)^exponent`, bounded to `[1 / max_factor,
/// max_factor]`, where `rate` is the largest equivalent plastic strain rate
/// of `body` over that increment (`max_factor` when nothing flowed), or of
/// the cells touching the nodes `at` when given (the pole of a bulge). With
/// a Norton-Hoff body (`q ~ rate^m`) and `exponent = m` the pressure that
/// holds the target rate is reached in a few increments. The applied
/// pressure and the measured rate are written to `history.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct RateControl {
    /// The monitored body (the body of the pressure's surface).
    pub body: usize,
    /// The monitored region: the cells of `body` touching these nodes
    /// (sorted); empty: the whole body.
    pub at: Vec<usize>,
    /// Target largest equivalent plastic strain rate (1 / time), > 0.
    pub target: f64,
    /// Exponent of the update `(target / rate)^exponent`, in (0, 1].
    pub exponent: f64,
    /// Largest change of the factor in one increment, > 1.
    pub max_factor: f64,
    /// Cap of the applied pressure (factor x the deck's value), > 0;
    /// infinite: no cap.
    pub max_pressure: f64,
}

/// Rate dependence of J2 flow: the von Mises stress during plastic flow at
/// the equivalent plastic strain rate `r = d ep / dt` is
/// `q = sigma_y(ep) + over(ep, r)`, integrated by backward Euler
/// (`crate::material::j2::radial_return`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Viscosity {
    /// Perzyna with a linear over-stress: `q - sigma_y(ep) = eta r`
    /// (`r = <q - sigma_y> / eta`).
    Perzyna {
        /// Viscosity `eta` (stress x time), > 0.
        eta: f64,
    },
    /// Perzyna with a power over-stress relative to the flow stress:
    /// `r = rate <q / sigma_y(ep) - 1>^exponent`, i.e.
    /// `q = sigma_y(ep) (1 + (r / rate)^(1 / exponent))`.
    PerzynaPower {
        /// Reference rate `rate` (1 / time), > 0.
        rate: f64,
        /// Rate exponent `N`, > 0 (1: over-stress linear in the rate).
        exponent: f64,
    },
    /// Norton-Hoff (the superplastic law): `q = sigma_y(ep) + stress (r /
    /// rate)^m`; with no static yield (`sigma_y = 0`) this is `q = sqrt(3) K
    /// (sqrt(3) r)^m` with `K = stress / (sqrt(3) (sqrt(3) rate)^m)`.
    NortonHoff {
        /// Flow stress `stress` at the reference rate, > 0.
        stress: f64,
        /// Reference rate `rate` (1 / time), > 0.
        rate: f64,
        /// Strain-rate sensitivity `m`, in (0, 1].
        m: f64,
    },
}

impl Viscosity {
    /// Checks the parameters; explains what is wrong.
    pub fn check(&self) -> Result<(), String> {
        let pos = crate::material::hardening::positive;
        match *self {
            Viscosity::Perzyna { eta } => pos(eta, "the viscosity eta"),
            Viscosity::PerzynaPower { rate, exponent } => {
                pos(rate, "the Perzyna reference rate")?;
                pos(exponent, "the Perzyna exponent")
            }
            Viscosity::NortonHoff { stress, rate, m } => {
                pos(stress, "the Norton-Hoff stress")?;
                pos(rate, "the Norton-Hoff reference rate")?;
                if !(m.is_finite() && m > 0.0 && m <= 1.0) {
                    return Err(format!(
                        "the Norton-Hoff rate sensitivity m must be in (0, 1] (got {m})"
                    ));
                }
                Ok(())
            }
        }
    }
}

impl MaterialLaw {
    /// The (small-strain) Young's modulus of the law.
    pub fn young(&self) -> f64 {
        match self {
            MaterialLaw::LinearElastic { young, .. }
            | MaterialLaw::NeoHookean { young, .. }
            | MaterialLaw::ElastoPlastic { young, .. } => *young,
        }
    }
}

/// Isotropic hardening: flow stress `sigma_y(ep)` for the equivalent plastic
/// strain `ep >= 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Hardening {
    /// `sigma_y = yield + modulus * ep`.
    Linear {
        /// Initial yield stress, > 0.
        yield_stress: f64,
        /// Plastic modulus `H` (>= 0; 0 is perfect plasticity).
        modulus: f64,
    },
    /// Swift/Krupkowski: `sigma_y = k (eps0 + ep)^n`.
    Swift {
        /// Strength coefficient `K`, > 0.
        k: f64,
        /// Pre-strain `eps0`, > 0.
        eps0: f64,
        /// Hardening exponent `n`, in [0, 1].
        n: f64,
    },
    /// Voce: `sigma_y = yield + (sigma_inf - yield) (1 - exp(-delta ep))`.
    Voce {
        /// Initial yield stress, > 0.
        yield_stress: f64,
        /// Saturation stress, >= yield.
        sigma_inf: f64,
        /// Saturation rate, > 0.
        delta: f64,
    },
    /// Johnson & Cook (1983): `sigma_y = (A + B ep^n) (1 + C ln(rate*))
    /// (1 - T*^m)`, `rate* = max(d ep / dt / rate0, 1)` (no rate effect
    /// below the reference rate, as Abaqus), `T* = (T - T_ref) / (T_melt -
    /// T_ref)` clamped to [0, 1]; the plastic rate of an increment is `d
    /// gamma / dt` (backward Euler, `material::j2::radial_return`).
    JohnsonCook {
        /// `A` (> 0): the yield stress at the reference rate and
        /// temperature.
        a: f64,
        /// `B` (>= 0).
        b: f64,
        /// `n` in (0, 1].
        n: f64,
        /// `C` (>= 0): rate sensitivity.
        c: f64,
        /// Reference plastic strain rate (> 0, 1 / time).
        rate0: f64,
        /// Thermal softening exponent `m` (> 0).
        m: f64,
        /// Reference (room) temperature.
        t_ref: f64,
        /// Melting temperature (> `t_ref`).
        t_melt: f64,
        /// The temperature the law is evaluated at (`t_ref` without a
        /// thermal scene; set per cell by `thermal::properties::law_at`).
        temperature: f64,
    },
}

/// A scalar function of the analysis time.
#[derive(Debug, Clone, PartialEq)]
pub enum TimeFunction {
    /// The same value at all times.
    Constant(f64),
    /// Linear from `v0` at `t0` to `v1` at `t1`, constant outside.
    Ramp {
        /// Start time.
        t0: f64,
        /// End time (> t0).
        t1: f64,
        /// Value at and before t0.
        v0: f64,
        /// Value at and after t1.
        v1: f64,
    },
    /// Piecewise-linear through (time, value) points with strictly
    /// increasing times; constant beyond the first and last points.
    Table(Vec<(f64, f64)>),
}

impl TimeFunction {
    /// Value at time `t`.
    pub fn eval(&self, t: f64) -> f64 {
        match self {
            TimeFunction::Constant(v) => *v,
            TimeFunction::Ramp { t0, t1, v0, v1 } => {
                if t <= *t0 {
                    *v0
                } else if t >= *t1 {
                    *v1
                } else {
                    v0 + (v1 - v0) * (t - t0) / (t1 - t0)
                }
            }
            TimeFunction::Table(points) => {
                let Some(first) = points.first() else {
                    return 0.0;
                };
                if t <= first.0 {
                    return first.1;
                }
                for w in points.windows(2) {
                    let ((ta, va), (tb, vb)) = (w[0], w[1]);
                    if t <= tb {
                        return va + (vb - va) * (t - ta) / (tb - ta);
                    }
                }
                points[points.len() - 1].1
            }
        }
    }
}

/// Prescribed value of one displacement component on a set of nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct Dirichlet {
    /// Human-readable origin, e.g. `fix disc.bottom`.
    pub label: String,
    /// Global node numbers.
    pub nodes: Vec<usize>,
    /// 0 = x (or r), 1 = y (or z).
    pub component: usize,
    /// Prescribed displacement as a function of time.
    pub value: TimeFunction,
}

/// External loads.
#[derive(Debug, Clone, PartialEq)]
pub enum Load {
    /// Follower-free pressure on boundary edges (positive pushes into the
    /// body, i.e. along the inward normal), in the reference configuration.
    Pressure {
        /// Human-readable origin.
        label: String,
        /// Boundary edges `[a, b]` oriented with the body on their left.
        edges: Vec<[usize; 2]>,
        /// Pressure as a function of time.
        value: TimeFunction,
    },
    /// Follower-free pressure on boundary faces of a solid (3D) mesh
    /// (positive pushes into the body, against the outward normal), in the
    /// reference configuration: consistent nodal forces
    /// `f_a = -p int N_a n dA` (tri3 faces: 1-point exact, quad4 faces: 2x2
    /// Gauss).
    FacetPressure {
        /// Human-readable origin.
        label: String,
        /// Boundary faces, counter-clockwise seen from outside.
        facets: Vec<crate::mesh::Facet>,
        /// Pressure as a function of time.
        value: TimeFunction,
    },
    /// Pressure on the deformed surface (a follower load; positive pushes
    /// into the body): consistent nodal forces on the current
    /// configuration with their load stiffness (`solve/follower.rs`).
    /// Bodies under it have finite kinematics (`check_model`).
    FollowerPressure {
        /// Human-readable origin.
        label: String,
        /// Boundary facets: edges `[a, b]` / `[a, b, m]` of a planar mesh
        /// (body on the left), or faces of a solid, counter-clockwise seen
        /// from outside.
        facets: Vec<crate::mesh::Facet>,
        /// Pressure as a function of time (times the controller's factor
        /// when `control` is set).
        value: TimeFunction,
        /// Pressure-cycle controller, if any ([`RateControl`]).
        control: Option<RateControl>,
    },
    /// Follower-free (dead) traction on boundary facets: force per unit
    /// reference area along the global axis `component`, in the reference
    /// configuration (Abaqus `TRVEC` on `*DSLOAD`, not following the
    /// surface). Consistent nodal forces `f_a = t int N_a dA`: solid faces
    /// with the face quadrature of [`Load::FacetPressure`] (tri3 faces: the
    /// area over 3 on each node; quad4 faces: 2x2 Gauss, exact on flat
    /// faces); planar edges (2-node facets) with `dA = thickness ds`, or
    /// `2 pi r ds` (axisymmetric: totals over the ring).
    FacetTraction {
        /// Human-readable origin.
        label: String,
        /// Boundary facets: faces of a solid, or edges `[a, b]` of a planar
        /// mesh.
        facets: Vec<crate::mesh::Facet>,
        /// 0 = x (or r), 1 = y (or z), 2 = z.
        component: usize,
        /// Traction (force per unit reference area) as a function of time.
        value: TimeFunction,
    },
    /// Gravity (a body force per unit mass, Abaqus `GRAV`): the
    /// acceleration component `value(t)` along `component` acting on every
    /// body of non-zero density and every point mass; consistent nodal
    /// forces `f_a = g int rho N_a dV` (the row sums of the consistent
    /// mass, `solve/loads.rs`; axisymmetric: totals over the ring) plus
    /// `m g` at point masses, in the reference configuration.
    Gravity {
        /// Human-readable origin.
        label: String,
        /// 0 = x (or r), 1 = y (or z), 2 = z.
        component: usize,
        /// The acceleration (length / time^2) as a function of time.
        value: TimeFunction,
    },
    /// A force applied at each listed node (Abaqus CLOAD semantics: the value
    /// is per node; axisymmetric: total over the ring).
    NodalForce {
        /// Human-readable origin.
        label: String,
        /// Global node numbers.
        nodes: Vec<usize>,
        /// 0 = x (or r), 1 = y (or z).
        component: usize,
        /// Force per node as a function of time.
        value: TimeFunction,
    },
    /// A moment on a free 3D rigid body (deck: `rigid_body .. { moment =
    /// M  axis = (..) }`): the spatial moment `m(t) = value(t) axis`, its
    /// direction fixed in space, applied work-conjugately on the body's
    /// total rotation vector `psi` (the spin node's displacement): `f_psi
    /// = T(psi)^T m`, `T` the differential of `exp` in the spatial frame
    /// (`solve::rigid_body::add_moments`). Configuration dependent: it is
    /// assembled with the follower loads (non-symmetric tangent).
    RigidMoment {
        /// Human-readable origin.
        label: String,
        /// The body's spin node.
        spin: usize,
        /// Unit direction of the moment (fixed in space).
        axis: [f64; 3],
        /// Magnitude of the moment as a function of time.
        value: TimeFunction,
    },
}

/// A rigid tool described analytically (exact CAD-like geometry, no mesh).
#[derive(Debug, Clone, PartialEq)]
pub struct RigidTool {
    /// Name from the deck.
    pub name: String,
    /// Geometry in the tool's reference position (time 0 of its motion).
    pub geometry: ToolGeometry,
    /// Prescribed rigid motion (with a free rotation, `motion.rotation` is
    /// unused: the angle is the unknown of [`FreeRotation`]).
    pub motion: ToolMotion,
    /// The rotation about `motion.center` as an unknown (a free roller), or
    /// `None`: prescribed by `motion.rotation`.
    pub free_rotation: Option<FreeRotation>,
}

/// A tool's rotation about its centre as an unknown of the global system
/// (`solve/free_tool.rs`): the angle is the x displacement of the pilot
/// node `node` (a node attached to no cell, its y component held at 0),
/// and its equation is the tool's moment balance about the current centre
/// `c + u(t)`: net contact moment on the tool + `moment(t)` = 0 (the
/// applied moment is a nodal force on the pilot node's x component).
/// Planar (plane strain / plane stress) models; 3D rotation about an axis
/// can use the same pilot-node scheme with one component.
#[derive(Debug, Clone, PartialEq)]
pub struct FreeRotation {
    /// The pilot node (global number) carrying the angle.
    pub node: usize,
    /// Applied moment about the centre (counter-clockwise positive;
    /// force x length per unit thickness as the contact forces are).
    pub moment: TimeFunction,
}

/// Which side of a closed curve (circle) is free space for the body.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ToolSide {
    /// The body lives outside the circle (a punch, a roller).
    Outside,
    /// The body lives inside the circle (a die, a container).
    Inside,
}

/// Analytical tool geometry. For open curves (segment polylines, arcs,
/// splines) the free side — where the body may be — is on the **left** when
/// walking along the curve in its given direction (outward normal =
/// tangent rotated by +90 degrees).
#[derive(Debug, Clone, PartialEq)]
pub enum ToolGeometry {
    /// Infinite straight line through `point`; `normal` (unit) points to the
    /// free side.
    Plane {
        /// A point of the line.
        point: [f64; 2],
        /// Unit normal pointing into free space.
        normal: [f64; 2],
    },
    /// Connected straight segments through the points (at least 2).
    Polyline {
        /// Vertices in walking order.
        points: Vec<[f64; 2]>,
    },
    /// Circular arc from `start_angle` to `end_angle` (radians,
    /// counter-clockwise when `end_angle > start_angle`).
    Arc {
        /// Centre.
        center: [f64; 2],
        /// Radius > 0.
        radius: f64,
        /// Angle of the first end, radians.
        start_angle: f64,
        /// Angle of the second end, radians.
        end_angle: f64,
    },
    /// Full circle.
    Circle {
        /// Centre.
        center: [f64; 2],
        /// Radius > 0.
        radius: f64,
        /// Whether the body is outside or inside the circle.
        side: ToolSide,
    },
    /// Rational B-spline (NURBS) curve; a B-spline when all weights are 1.
    Nurbs {
        /// Polynomial degree >= 1.
        degree: usize,
        /// Control points.
        control_points: Vec<[f64; 2]>,
        /// Positive weights, one per control point.
        weights: Vec<f64>,
        /// Non-decreasing knot vector of length `control_points.len() + degree + 1`.
        knots: Vec<f64>,
    },
}

/// Rigid motion of a tool: its reference geometry is rotated by `rotation(t)`
/// (radians, counter-clockwise) about `center`, then translated by
/// `(ux(t), uy(t))`.
#[derive(Debug, Clone, PartialEq)]
pub struct ToolMotion {
    /// Translation along x.
    pub ux: TimeFunction,
    /// Translation along y.
    pub uy: TimeFunction,
    /// Rotation angle about `center`, radians.
    pub rotation: TimeFunction,
    /// Centre of rotation in the reference configuration.
    pub center: [f64; 2],
}

impl ToolMotion {
    /// A tool that does not move.
    pub fn fixed() -> Self {
        ToolMotion {
            ux: TimeFunction::Constant(0.0),
            uy: TimeFunction::Constant(0.0),
            rotation: TimeFunction::Constant(0.0),
            center: [0.0, 0.0],
        }
    }
}

/// A rigid surface tool of a solid model: exact analytical geometry (no
/// mesh, no unknowns) and a rigid motion.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceTool {
    /// Name from the deck.
    pub name: String,
    /// Geometry in the tool's reference position (time 0 of its motion).
    pub geometry: SurfaceShape,
    /// Prescribed rigid motion.
    pub motion: SurfaceMotion,
}

/// The exact geometry of a rigid surface tool.
#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceShape {
    /// A closed-form surface (plane, sphere, cylinder, cone, torus).
    Analytic(ctc_geom::analytic::Analytic),
    /// CAD faces: trimmed NURBS surfaces (with holes) read from an IGES
    /// file, their shared edges and vertices (a foot on an edge or a
    /// vertex is a cylinder or a sphere of radius 0).
    Brep(std::sync::Arc<ctc_geom::brep::BrepTool>),
    /// A triangulated surface (an STL file): flat triangles, their edges
    /// and vertices as cylinders and spheres of radius 0, the inside /
    /// outside sign by angle-weighted pseudonormals
    /// (`ctc_geom::trimesh::TriMesh`).
    Mesh(std::sync::Arc<ctc_geom::trimesh::TriMesh>),
}

impl From<ctc_geom::analytic::Analytic> for SurfaceShape {
    fn from(a: ctc_geom::analytic::Analytic) -> Self {
        SurfaceShape::Analytic(a)
    }
}

/// Rigid motion of a surface tool: its reference geometry is rotated by
/// `rotation(t)` (radians, right-handed about `axis`) about the axis
/// through `center`, then translated by `(ux(t), uy(t), uz(t))`.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceMotion {
    /// Translation along x, y and z.
    pub translation: [TimeFunction; 3],
    /// Rotation angle about `axis`, radians.
    pub rotation: TimeFunction,
    /// Unit rotation axis.
    pub axis: [f64; 3],
    /// A point of the rotation axis in the reference configuration.
    pub center: [f64; 3],
}

impl SurfaceMotion {
    /// A tool that does not move.
    pub fn fixed() -> Self {
        SurfaceMotion {
            translation: std::array::from_fn(|_| TimeFunction::Constant(0.0)),
            rotation: TimeFunction::Constant(0.0),
            axis: [0.0, 0.0, 1.0],
            center: [0.0; 3],
        }
    }
}

/// How the penalty coefficient is scaled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PenaltyKind {
    /// Force per unit gap at each node (Metafor style; halve it when the mesh
    /// size is halved to keep the same gaps).
    Nodal,
    /// Pressure per unit gap, times the node's tributary length x thickness
    /// (plane) or tributary length x 2*pi*r (axisymmetric): mesh independent.
    Area,
}

/// Normal contact enforcement.
#[derive(Debug, Clone, PartialEq)]
pub enum ContactMethod {
    /// R_N = -alpha g for g < 0.
    Penalty {
        /// Nodal or area-weighted.
        kind: PenaltyKind,
        /// alpha (force/length for nodal, pressure/length for area), > 0.
        stiffness: f64,
    },
    /// Lagrange multipliers: one multiplier (the normal contact force,
    /// non-negative in compression) per active slave node, `g = 0` enforced
    /// exactly on the active set, which is found by an active-set loop.
    Lagrange {
        /// How the saddle-point system is written and factorized.
        formulation: LagrangeFormulation,
    },
    /// Augmented Lagrangian (Uzawa): `R_N = max(0, lambda* - alpha g)`, the
    /// multiplier `lambda*` updated until the max penetration is below
    /// `tolerance`.
    AugmentedLagrange {
        /// Nodal or area-weighted penalty (default area).
        kind: PenaltyKind,
        /// alpha (force/length for nodal, pressure/length for area), > 0.
        penalty: f64,
        /// Largest accepted penetration `gmax*` (length), > 0.
        tolerance: f64,
        /// When `lambda*` is updated.
        update: MultiplierUpdate,
    },
}

/// Formulation of the Lagrange-multiplier saddle-point system.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LagrangeFormulation {
    /// `[K G^T; G 0]`, sparse LU with pivoting.
    Single,
    /// Doubled multipliers `lambda1, q, lambda2` (seed, "Main difficulties
    /// (1)"), symmetric `L D L^T` without pivoting.
    Doubled,
    /// The multipliers eliminated at their slave nodes (dual mortar: `D`
    /// diagonal), the displacements alone by sparse LU
    /// (`crate::solve::linalg::condensed`); the multipliers recovered
    /// after each solve.
    Condensed,
}

/// When the augmented-Lagrangian multipliers are updated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MultiplierUpdate {
    /// After each converged Newton loop (Uzawa), until the penetration is
    /// below the tolerance.
    Converged,
    /// At every Newton iteration (inside the loop).
    Newton,
}

/// Master side of a contact pair.
#[derive(Debug, Clone, PartialEq)]
pub enum ContactMaster {
    /// A rigid analytical tool: index into `Model::tools`.
    Tool(usize),
    /// A boundary of a deformable body (node-to-segment contact). The slave
    /// and master surfaces may be the same (self contact).
    Surface {
        /// Index into `Model::bodies`.
        body: usize,
        /// Master segments `[a, b]` (body on the left, outward normal to the
        /// right of `a -> b`).
        edges: Vec<[usize; 2]>,
        /// Master facets (3D: tri3 / quad4 boundary faces, outward normal
        /// by the right-hand rule; empty in 2D).
        faces: Vec<crate::mesh::Facet>,
        /// The distinct nodes of `edges` (3D: of `faces`), sorted.
        nodes: Vec<usize>,
    },
}

impl ContactMaster {
    /// The tool index if the master is a rigid tool.
    pub fn tool(&self) -> Option<usize> {
        match self {
            ContactMaster::Tool(t) => Some(*t),
            ContactMaster::Surface { .. } => None,
        }
    }
}

/// Which surface plays master and which slave (seed, "Three usual
/// strategies").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ContactStrategy {
    /// One pass: slave nodes against master segments only.
    #[default]
    SinglePass,
    /// Master and slave swapped from one increment to the next.
    DoublePass,
    /// Each surface master and slave at the same time.
    ModifiedDoublePass,
}

impl ContactStrategy {
    /// Which sides of a deformable pair act as slave after `increments`
    /// converged increments: `[side 0 is slave, side 1 is slave]` (double
    /// pass swaps them every increment).
    pub fn slave_sides(self, increments: usize) -> [bool; 2] {
        match self {
            ContactStrategy::SinglePass => [true, false],
            ContactStrategy::DoublePass => {
                let even = increments.is_multiple_of(2);
                [even, !even]
            }
            ContactStrategy::ModifiedDoublePass => [true, true],
        }
    }
}

/// Discretization of the contact between deformable bodies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ContactFormulation {
    /// One constraint per slave node against the master point under it.
    #[default]
    NodeToSegment,
    /// Mortar segment-to-segment: the gap integrated against the slave
    /// shape functions (weighted gaps, `D` and `M` matrices), see
    /// `crate::contact::mortar`.
    Mortar,
}

/// Master normal of node-to-segment contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NormalSmoothing {
    /// The faceted surface: each segment's own normal (kinks are circles
    /// of radius 0).
    #[default]
    None,
    /// Nodal normals (the unit mean of the adjacent segment normals)
    /// interpolated along each segment, normalized: one continuous normal
    /// field (`crate::contact::smoothing`).
    Nodal,
    /// 3D node-to-facet: Nagata's quadratic patches through the master
    /// facets' nodes and their area-weighted nodal normals
    /// (`crate::contact::nagata`).
    Nagata,
}

/// Local contact search test (seed, "Part I - Geometrical aspects").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LocalSearch {
    /// Metafor: the entity found at the last increment first, then its
    /// neighbours, then the others (within the window `prof`).
    #[default]
    Memory,
    /// Cast3M: a segment is a candidate only if the node lies in the circle
    /// centred on the segment's midpoint through its ends.
    Circle,
}

/// A body surface (slave nodes) against a rigid tool or a deformable
/// surface (master).
#[derive(Debug, Clone, PartialEq)]
pub struct ContactPair {
    /// Human-readable name, e.g. `disc.arc -> floor`.
    pub name: String,
    /// Index into `Model::bodies`.
    pub body: usize,
    /// Slave boundary edges `[a, b]` (body on the left); they define the slave
    /// nodes and their tributary lengths.
    pub edges: Vec<[usize; 2]>,
    /// Slave boundary faces of a solid (3D) model, outward (empty in 2D);
    /// they define the slave nodes and their tributary areas.
    pub faces: Vec<crate::mesh::Facet>,
    /// Slave nodes: the distinct nodes of `edges` (2D) or `faces` (3D),
    /// sorted.
    pub nodes: Vec<usize>,
    /// What the slave nodes contact: a rigid tool or a deformable surface.
    pub master: ContactMaster,
    /// Single, double or modified double pass (deformable masters only;
    /// rigid tools are always single pass, the tool being the master).
    pub strategy: ContactStrategy,
    /// Local search test used to pick the candidate master entities.
    pub search: LocalSearch,
    /// Node-to-segment or mortar segment-to-segment (deformable masters).
    pub formulation: ContactFormulation,
    /// Master normal of node-to-segment pairs (deformable masters).
    pub smoothing: NormalSmoothing,
    /// Normal enforcement.
    pub method: ContactMethod,
    /// Maximum gap `prof`: nodes farther than this from the tool create no
    /// contact element. `None`: automatic (a multiple of the slave edge size).
    pub prof: Option<f64>,
    /// Coulomb friction (`None`: frictionless).
    pub friction: Option<Friction>,
    /// Per-node penalty coefficients `(node, alpha)` sorted by node, of a
    /// penalty given relative to the mesh (`stiffness = 10 * E / h`): they
    /// replace the method's value at those nodes. Empty: the method's value
    /// everywhere.
    pub local_penalty: Vec<(usize, f64)>,
}

impl ContactPair {
    /// The enforcement method at slave node `node`: the pair's method, with
    /// the node's own coefficient when the penalty is relative.
    pub fn method_at(&self, node: usize) -> ContactMethod {
        let mut m = self.method.clone();
        if let Ok(k) = self.local_penalty.binary_search_by_key(&node, |&(n, _)| n) {
            let alpha = self.local_penalty[k].1;
            match &mut m {
                ContactMethod::Penalty { stiffness, .. } => *stiffness = alpha,
                ContactMethod::AugmentedLagrange { penalty, .. } => *penalty = alpha,
                ContactMethod::Lagrange { .. } => {}
            }
        }
        m
    }
}

/// Coulomb friction of a contact pair (seed, "Part III - Friction"). The
/// tangential enforcement follows the pair's normal method: penalty
/// (regularized Coulomb law, return map), Lagrange multipliers (stick/slip
/// status loop) or augmented Lagrangian (tangential multiplier shift).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Friction {
    /// Coulomb coefficient `mu >= 0`.
    pub mu: f64,
    /// Tangential penalty `alpha_T`, same units and kind (nodal or area) as
    /// the normal penalty; `None`: `alpha_N / 10`. Unused by Lagrange
    /// multipliers.
    pub stiffness: Option<f64>,
    /// Friction in the increment in which a node first touches.
    pub first_impact: FirstImpact,
    /// Cut an increment in which a node first touches at the fraction of
    /// the increment where it meets the master (constant-velocity
    /// intersection).
    pub cut_at_impact: bool,
}

/// How friction treats the increment in which a node first touches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FirstImpact {
    /// No tangential force in that increment; the stick point is where the
    /// node is at the end of it.
    Frictionless,
    /// The stick point is where the node met the master, found by the
    /// constant-velocity intersection; friction acts from there on.
    #[default]
    Intersect,
}

/// Newton-Raphson settings of a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonSettings {
    /// Converged when ||r|| <= tol * max(||f_ext + f_reaction||, tiny).
    pub tol: f64,
    /// And ||du|| <= tol_displacement * max(||u||, tiny).
    pub tol_displacement: f64,
    /// Maximum Newton iterations per increment before a cutback.
    pub max_iter: usize,
    /// Backtracking line search on the residual norm.
    pub line_search: bool,
    /// Increment predictor: the first iterate of an increment extrapolated
    /// from the last two converged states of the step
    /// (`crate::solve::newton::predictor`).
    pub predictor: bool,
    /// Vanishing stabilization of the bodies held only by contact: the
    /// factor `c` of springs `c d_b` on the increment displacement (`d_b`
    /// the mean stiffness diagonal of body `b`), ramped down to 0 at the
    /// step's end (`crate::solve::stabilize`); `None`: off.
    pub stabilize: Option<f64>,
}

impl Default for NewtonSettings {
    fn default() -> Self {
        NewtonSettings {
            tol: 1e-8,
            tol_displacement: 1e-8,
            max_iter: 25,
            line_search: true,
            predictor: true,
            stabilize: None,
        }
    }
}

/// How the mass matrix of a dynamic step is formed
/// (`crate::element::CellKernel::mass`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MassMatrix {
    /// `int rho N_a N_b dV`.
    #[default]
    Consistent,
    /// Row-sum (HRZ where a row sum is not positive) diagonal.
    Lumped,
}

/// The time integrator of a dynamic step: one generalized-alpha
/// formulation (Chung & Hulbert 1993) of which Newmark and HHT-alpha are
/// special cases (`crate::solve::dynamics::Coefficients`).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case", tag = "scheme")]
pub enum Scheme {
    /// Newmark: `alpha_m = alpha_f = 0`; average acceleration is
    /// `beta = 1/4`, `gamma = 1/2` (no numerical dissipation).
    Newmark {
        /// `beta`, in (0, 1/2].
        beta: f64,
        /// `gamma`, in [1/2, 1].
        gamma: f64,
    },
    /// Hilber-Hughes-Taylor: `alpha_m = 0`, `alpha_f = (1 - rho_inf) / (1
    /// + rho_inf)`, `gamma = 1/2 + alpha_f`, `beta = (1 + alpha_f)^2 / 4`.
    Hht {
        /// Spectral radius at infinite frequency, in [1/2, 1].
        rho_inf: f64,
    },
    /// Chung-Hulbert generalized-alpha: `alpha_m = (2 rho_inf - 1) /
    /// (rho_inf + 1)`, `alpha_f = rho_inf / (rho_inf + 1)`, `gamma = 1/2 -
    /// alpha_m + alpha_f`, `beta = (1 - alpha_m + alpha_f)^2 / 4`.
    GeneralizedAlpha {
        /// Spectral radius at infinite frequency, in [0, 1].
        rho_inf: f64,
    },
}

/// What makes a step dynamic: the integrator and the mass matrix.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Dynamic {
    /// The time integrator.
    pub scheme: Scheme,
    /// Consistent or lumped mass.
    pub mass: MassMatrix,
    /// The mass of the nodes of contact surfaces.
    pub contact_mass: ContactMass,
    /// Rayleigh damping `C = alpha M + beta K_0`.
    pub rayleigh: Rayleigh,
    /// Adaptive time stepping (`None`: the step's increments, cut back
    /// and grown back to at most the initial size).
    pub adaptive: Option<Adaptive>,
    /// The largest rotation of a cell in one increment, in radians
    /// (`dynamic { max_rotation }`; `None`: no limit): an increment that
    /// turns a cell by more is redone smaller, and the next size is kept
    /// below it (`solve::stepping`, `solve::cell_rotation`).
    pub max_rotation: Option<f64>,
    /// The largest energy one increment may create, relative to the
    /// largest energy of the run (`dynamic { energy_tol }`, absent:
    /// [`DEFAULT_ENERGY_TOL`]; `None`: no control, `energy_tol = 0`): an
    /// increment in which contact forces act and whose kinetic energy,
    /// internal and damping work and stored penalty energy grow by more
    /// than the work of the loads and supports plus this share is redone
    /// smaller, and the next size is kept below it (`solve::stepping`,
    /// `solve::dynamics::Energy::created_since`).
    pub energy_tol: Option<f64>,
}

/// The energy control of a dynamic step whose deck does not set
/// `energy_tol` (issue 19): an increment in which contact forces act may
/// create at most this share of the largest energy of the run. Penalty
/// contact that releases a node from deeper than it closed through gives
/// the bodies more than its springs stored (Laursen & Chawla 1997): the
/// planar blade loss without it created 2-18 % of its kinetic energy per
/// increment from 9.4 ms and stopped at 16.1 ms; with it, it flies to
/// 20 ms with an energy error below 1e-4 of the kinetic energy. Runs
/// without contact are not touched (the control weighs only increments in
/// which contact forces act).
pub const DEFAULT_ENERGY_TOL: f64 = 1e-3;

/// Adaptive time stepping of a dynamic step (`dynamic { adaptive = true
/// dt_min  dt_max  error_tol }`; `solve::stepping`): the increment grows
/// after easy increments up to `dt_max`, shrinks on a cutback, on a
/// contact event (the number of active contact nodes changed: a first
/// contact or a release) and by the local error estimate of Zienkiewicz
/// & Xie (1991), `e = (beta - 1/6) dt^2 (a1 - a0)`, measured in the mass
/// norm relative to the increment's displacement (`error_tol`; 0: no
/// error control).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Adaptive {
    /// Smallest increment (time).
    pub dt_min: f64,
    /// Largest increment (time).
    pub dt_max: f64,
    /// Tolerance of the relative local error estimate (0: none).
    pub error_tol: f64,
}

/// Rayleigh (proportional) damping of a dynamic step: `C = alpha M + beta
/// K_0`, `K_0` the stiffness in the reference configuration (the elastic
/// one); a mode of circular frequency `omega` gets the damping ratio
/// `alpha / (2 omega) + beta omega / 2`.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct Rayleigh {
    /// Mass-proportional coefficient (1 / time).
    pub alpha: f64,
    /// Stiffness-proportional coefficient (time).
    pub beta: f64,
}

impl Rayleigh {
    /// Whether there is any damping.
    pub fn any(&self) -> bool {
        self.alpha != 0.0 || self.beta != 0.0
    }
}

/// The mass of contact-surface nodes in a dynamic step
/// (`crate::solve::contact_mass`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactMass {
    /// Moved to the other nodes of their cells (Khenous, Laborde & Renard
    /// 2008): no chatter, the energy of an impact conserved.
    #[default]
    Redistributed,
    /// The step's mass matrix everywhere (contact nodes bounce).
    Full,
    /// Only the share along the tool normal is moved: the nodes in contact
    /// with a rigid plane whose normal is a coordinate axis keep their
    /// lumped mass in the tangential directions (a frictionless surface
    /// layer keeps its inertia, e.g. the impact face of a Taylor bar), the
    /// other nodes take only the normal share of it; contact nodes of
    /// other masters are massless as with `Redistributed`.
    Normal,
}

/// An initial velocity component on a set of nodes (`initial_velocity`
/// items).
#[derive(Debug, Clone, PartialEq)]
pub struct InitialVelocity {
    /// Label from the deck.
    pub label: String,
    /// Global node numbers.
    pub nodes: Vec<usize>,
    /// Component (0 = x, 1 = y, 2 = z).
    pub component: usize,
    /// The velocity.
    pub value: f64,
}

/// A load step.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// Name from the deck.
    pub name: String,
    /// Start time (the previous step's end time, or 0).
    pub t_start: f64,
    /// End time (> t_start).
    pub t_end: f64,
    /// Number of equal increments initially tried.
    pub increments: usize,
    /// Smallest increment allowed by cutbacks, as a fraction of the initial
    /// increment (default 1/1024).
    pub min_fraction: f64,
    /// Newton settings.
    pub newton: NewtonSettings,
    /// `None`: quasi-static (no inertia); `Some`: implicit dynamics.
    pub dynamic: Option<Dynamic>,
}

/// A nodal or element field that can be written to VTU.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Field {
    /// Displacement vector.
    Displacement,
    /// Cauchy stress (xx, yy, zz, xy), nodal average of integration points.
    Stress,
    /// Small strain (xx, yy, zz, xy).
    Strain,
    /// von Mises equivalent stress.
    VonMises,
    /// Reaction forces at constrained dofs.
    Reaction,
    /// Contact gap, pressure and status at slave nodes.
    Contact,
    /// Nodal velocity (dynamic steps; 0 after a quasi-static increment).
    Velocity,
    /// Nodal acceleration (dynamic steps).
    Acceleration,
}

/// A quantity recorded at every increment into the CSV history.
#[derive(Debug, Clone, PartialEq)]
pub enum HistoryRequest {
    /// Sum of reaction forces (x, y) over a node set.
    Reaction {
        /// Column label, e.g. `reaction(disc.top)`.
        label: String,
        /// Global node numbers.
        nodes: Vec<usize>,
    },
    /// Mean displacement (x, y) over a node set.
    Displacement {
        /// Column label.
        label: String,
        /// Global node numbers.
        nodes: Vec<usize>,
    },
    /// Total contact force (x, y) exerted by the tool on the body.
    ContactForce {
        /// Column label.
        label: String,
        /// Index into `Model::contacts`.
        pair: usize,
    },
    /// Surface roughness of a node set at the current configuration: the
    /// columns `<label>_Ra`, `_Rq` and `_mean` ([`crate::output::roughness`]).
    Roughness {
        /// Column label, e.g. `roughness(sheet.rolled)`.
        label: String,
        /// Global node numbers.
        nodes: Vec<usize>,
        /// The height axis (0 x, 1 y, 2 z): the axis of smallest extent of
        /// the set's reference positions.
        axis: usize,
    },
}

/// The thickness of a sheet or tube between two of its boundary face sets
/// (`output { thickness = (sheet.top, sheet.bottom) }`, 3D): at each node
/// of the body, the sum of its distances to both deformed faces
/// ([`crate::output::thickness`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ThicknessRequest {
    /// `a, b` as written in the deck.
    pub label: String,
    /// The two face sets; the first is the one `thickness.csv` lists.
    pub faces: [Vec<crate::mesh::Facet>; 2],
    /// The nodes of the body (sorted).
    pub nodes: Vec<usize>,
}

/// Output settings.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputRequest {
    /// Write VTU every `every` converged increments (the last one always).
    pub every: usize,
    /// Fields written to VTU.
    pub fields: Vec<Field>,
    /// Histories written to `history.csv`.
    pub history: Vec<HistoryRequest>,
    /// The thickness map of a sheet or tube (`output { thickness = (a, b)
    /// }`, [`crate::output::thickness`]).
    pub thickness: Option<ThicknessRequest>,
    /// How VTU files store their arrays.
    pub format: VtuFormat,
    /// Names of the deck's units (`analysis { units = .. }`), for labels in
    /// summary.json, plots and VTU headers only: the engine computes without
    /// units. `None` when the deck declares no unit system.
    pub units: Option<UnitNames>,
}

/// The unit of each quantity kind in the deck's unit system (labels only).
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct UnitNames {
    /// The system's name in the deck (`SI`, `mm_N_s`, ..).
    pub system: String,
    /// Unit of length (`m`, `mm`).
    pub length: String,
    /// Unit of force (`N`, `kN`).
    pub force: String,
    /// Unit of stress and pressure (`Pa`, `MPa`, `GPa`).
    pub stress: String,
    /// Unit of time (`s`, `ms`).
    pub time: String,
    /// Unit of temperature (`K`).
    pub temperature: String,
    /// Unit of energy (`J`, `mJ`).
    pub energy: String,
}

/// How VTU files store their data arrays (`output { format = .. }`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum VtuFormat {
    /// Appended raw binary, zlib-compressed (ParaView's own layout).
    #[default]
    Binary,
    /// Inline text, numbers in their shortest round-trip form.
    Ascii,
}

impl Default for OutputRequest {
    fn default() -> Self {
        OutputRequest {
            every: 1,
            fields: vec![Field::Displacement, Field::Stress, Field::Reaction],
            history: Vec::new(),
            thickness: None,
            format: VtuFormat::Binary,
            units: None,
        }
    }
}
