//! Typed nodes of the top-level items of a deck.
//!
//! Optional fields are `None` when the deck does not give them; required
//! fields are `Option` too, so that a deck with a missing field still yields
//! a node (the missing field has already been reported) and later checks
//! keep running.

use super::settings::Settings;
use super::values::{Point, Point3, SetRef, TimeFn};
use crate::generators::GeneratorDef;
use crate::span::{Ident, Span, Spanned};

/// `analysis { .. }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Analysis {
    /// `dimension = ..`.
    pub dimension: Option<Spanned<Dimension>>,
    /// `thickness = ..`.
    pub thickness: Option<Spanned<f64>>,
    /// `units = SI | mm_N_s | ..`: the unit system of every number.
    pub units: Option<Spanned<&'static str>>,
    /// The `analysis` keyword.
    pub keyword: Span,
    /// The whole item.
    pub span: Span,
}

/// `dimension` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dimension {
    /// `plane_strain`.
    PlaneStrain,
    /// `plane_stress`.
    PlaneStress,
    /// `axisymmetric`.
    Axisymmetric,
    /// `3d`: a solid (x, y, z), no contact or heat conduction yet.
    ThreeD,
}

/// `let name = expression`.
#[derive(Debug, Clone, PartialEq)]
pub struct Let {
    /// The parameter.
    pub name: Ident,
    /// Its expression (evaluated when parsed).
    pub value: super::syntax::Value,
    /// The whole item.
    pub span: Span,
}

/// `material name { .. }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// The material's name.
    pub name: Ident,
    /// `elastic { E = .. nu = .. }`.
    pub elastic: Option<Elastic>,
    /// `neo_hookean { E = .. nu = .. }` (instead of `elastic`).
    pub neo_hookean: Option<Elastic>,
    /// `plastic { yield = ..  hardening = .. }`.
    pub plastic: Option<Plastic>,
    /// `viscoplastic { eta = .. }` or `viscoplastic { rate = ..  exponent = .. }`.
    pub viscoplastic: Option<Viscoplastic>,
    /// `norton_hoff { stress = ..  rate = ..  m = .. }`.
    pub norton_hoff: Option<NortonHoff>,
    /// Reserved blocks present, by key.
    pub reserved: Vec<Ident>,
    /// The whole item.
    pub span: Span,
    /// `thermal { .. }`.
    pub thermal: Option<super::thermal::MaterialThermal>,
    /// `density = ..`: mass density (inertia of dynamic steps).
    pub density: Option<Spanned<f64>>,
}

/// `elastic { .. }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Elastic {
    /// `E`: Young's modulus.
    pub young: Option<Spanned<f64>>,
    /// `nu`: Poisson's ratio.
    pub poisson: Option<Spanned<f64>>,
    /// The `elastic` block (key to closing brace).
    pub span: Span,
}

/// `plastic { yield = ..  hardening = .. }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Plastic {
    /// `yield`: initial yield stress (not with `swift`).
    pub yield_stress: Option<Spanned<f64>>,
    /// `hardening = ..` (absent: perfect plasticity).
    pub hardening: Option<Spanned<Hardening>>,
    /// The `plastic` block.
    pub span: Span,
}

/// Isotropic hardening laws of the deck.
#[derive(Debug, Clone, PartialEq)]
pub enum Hardening {
    /// `linear { H = .. }`.
    Linear {
        /// `H`: plastic modulus.
        modulus: Option<Spanned<f64>>,
    },
    /// `swift { K = ..  eps0 = ..  n = .. }`.
    Swift {
        /// `K`.
        k: Option<Spanned<f64>>,
        /// `eps0`.
        eps0: Option<Spanned<f64>>,
        /// `n`.
        n: Option<Spanned<f64>>,
    },
    /// `voce { sigma_inf = ..  delta = .. }`.
    Voce {
        /// `sigma_inf`.
        sigma_inf: Option<Spanned<f64>>,
        /// `delta`.
        delta: Option<Spanned<f64>>,
    },
    /// `johnson_cook { A  B  n  C  rate0  m  T_ref  T_melt }`, in the order
    /// of `tables::JOHNSON_COOK_HARDENING`.
    JohnsonCook {
        /// The eight parameters (`None`: missing, reported).
        values: [Option<Spanned<f64>>; 8],
    },
}

/// `viscoplastic { eta = .. }` (Perzyna, linear over-stress) or
/// `viscoplastic { rate = ..  exponent = .. }` (Perzyna, power over-stress).
#[derive(Debug, Clone, PartialEq)]
pub struct Viscoplastic {
    /// `eta`: viscosity (stress x time).
    pub eta: Option<Spanned<f64>>,
    /// `rate`: reference rate of the power law (1 / time).
    pub rate: Option<Spanned<f64>>,
    /// `exponent`: rate exponent `N` of the power law.
    pub exponent: Option<Spanned<f64>>,
    /// The block.
    pub span: Span,
}

/// `norton_hoff { stress = ..  rate = ..  m = .. }`: `q = sigma_y(ep) +
/// stress (r / rate)^m` (`sigma_y = 0` without a `plastic` block).
#[derive(Debug, Clone, PartialEq)]
pub struct NortonHoff {
    /// `stress`: flow stress at the reference rate.
    pub stress: Option<Spanned<f64>>,
    /// `rate`: reference equivalent strain rate (1 / time).
    pub rate: Option<Spanned<f64>>,
    /// `m`: strain-rate sensitivity, in (0, 1].
    pub m: Option<Spanned<f64>>,
    /// The block.
    pub span: Span,
}

/// `kinematics` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KinematicsKind {
    /// `small`.
    Small,
    /// `finite`.
    Finite,
}

/// `body name { .. }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// The body's name.
    pub name: Ident,
    /// `mesh = ..`.
    pub mesh: Option<Spanned<MeshDef>>,
    /// `material = name`.
    pub material: Option<Ident>,
    /// `formulation = ..`.
    pub formulation: Option<Spanned<FormulationKind>>,
    /// `kinematics = small | finite`.
    pub kinematics: Option<Spanned<KinematicsKind>>,
    /// The whole item.
    pub span: Span,
    /// `thermal { initial = .. }`.
    pub thermal: Option<super::thermal::BodyThermal>,
}

/// `formulation` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FormulationKind {
    /// `full`.
    Full,
    /// `selective_reduced`.
    SelectiveReduced,
}

/// Where a body's mesh comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum MeshDef {
    /// A built-in generator.
    Generator(Box<Generator>),
    /// `file "path"`: a gmsh file relative to the deck.
    File(Spanned<String>),
}

/// A built-in mesh generator with its settings.
#[derive(Debug, Clone, PartialEq)]
pub struct Generator {
    /// The generator name as written (`rectangle`, ...).
    pub name: Ident,
    /// Its registry entry ([`crate::generators`]).
    pub def: &'static GeneratorDef,
    /// The keys given, read through the entry's key table.
    pub settings: Settings,
}

/// `set name = ref`.
#[derive(Debug, Clone, PartialEq)]
pub struct SetDef {
    /// The set's name (referenced afterwards as `body.name`).
    pub name: Ident,
    /// What it selects.
    pub target: SetRef,
    /// The whole item.
    pub span: Span,
}

/// `tool name = kind { .. }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Tool {
    /// The tool's name.
    pub name: Ident,
    /// The geometry kind as written (`circle`, ...).
    pub kind: Ident,
    /// The geometry settings.
    pub geometry: ToolGeometry,
    /// `motion { .. }`.
    pub motion: Option<Motion>,
    /// The whole item.
    pub span: Span,
}

/// `side` values of a circle tool.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// `outside`.
    Outside,
    /// `inside`.
    Inside,
}

/// Geometry settings of each tool kind.
#[derive(Debug, Clone, PartialEq)]
pub enum ToolGeometry {
    /// `plane { point normal }`.
    Plane {
        /// A point of the line.
        point: Option<Point>,
        /// Normal towards free space.
        normal: Option<Point>,
    },
    /// `polyline { points }`.
    Polyline {
        /// Vertices.
        points: Option<Spanned<Vec<Point>>>,
    },
    /// `arc { center radius start end }` (degrees).
    Arc {
        /// Centre.
        center: Option<Point>,
        /// Radius.
        radius: Option<Spanned<f64>>,
        /// Start angle, degrees.
        start: Option<Spanned<f64>>,
        /// End angle, degrees.
        end: Option<Spanned<f64>>,
    },
    /// `circle { center radius side }`.
    Circle {
        /// Centre.
        center: Option<Point>,
        /// Radius.
        radius: Option<Spanned<f64>>,
        /// Where the body is (default outside).
        side: Option<Spanned<Side>>,
    },
    /// `nurbs { degree points weights knots }`.
    Nurbs {
        /// Polynomial degree.
        degree: Option<Spanned<i64>>,
        /// Control points.
        points: Option<Spanned<Vec<Point>>>,
        /// Weights (default all 1).
        weights: Option<Spanned<Vec<Spanned<f64>>>>,
        /// Knot vector (default open uniform).
        knots: Option<Spanned<Vec<Spanned<f64>>>>,
    },
    /// A rigid surface of a `3d` analysis (`plane` with `(x, y, z)`
    /// points, `sphere`, `cylinder`, `cone`, `torus`).
    Surface(SurfaceGeometry),
}

/// Geometry settings of the rigid surface tools of `3d` analyses.
#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceGeometry {
    /// `plane { point normal }`: the half-space behind the plane.
    Plane {
        /// A point of the plane.
        point: Option<Point3>,
        /// Normal towards free space.
        normal: Option<Point3>,
    },
    /// `sphere { center radius side }`.
    Sphere {
        /// Centre.
        center: Option<Point3>,
        /// Radius.
        radius: Option<Spanned<f64>>,
        /// Where the body is (default outside).
        side: Option<Spanned<Side>>,
    },
    /// `cylinder { point axis radius side }` (infinite).
    Cylinder {
        /// A point of the axis.
        point: Option<Point3>,
        /// Axis direction.
        axis: Option<Point3>,
        /// Radius.
        radius: Option<Spanned<f64>>,
        /// Where the body is (default outside).
        side: Option<Spanned<Side>>,
    },
    /// `cone { apex axis angle side }` (one nappe, opening along `axis`).
    Cone {
        /// Apex.
        apex: Option<Point3>,
        /// Axis direction (into the nappe).
        axis: Option<Point3>,
        /// Half opening angle, degrees.
        angle: Option<Spanned<f64>>,
        /// Where the body is (default outside).
        side: Option<Spanned<Side>>,
    },
    /// `torus { center axis major minor side }`.
    Torus {
        /// Centre.
        center: Option<Point3>,
        /// Axis of revolution.
        axis: Option<Point3>,
        /// Radius of the centre circle of the tube.
        major: Option<Spanned<f64>>,
        /// Radius of the tube.
        minor: Option<Spanned<f64>>,
        /// Where the body is (default outside).
        side: Option<Spanned<Side>>,
    },
    /// `iges { file flip }`: CAD faces of an IGES file.
    Iges {
        /// The file, relative to the deck's directory.
        file: Option<Spanned<String>>,
        /// Free side opposite `S_u x S_v` of the first face.
        flip: Option<Spanned<bool>>,
    },
    /// `stl { file flip closed }`: the triangles of an STL file.
    Stl {
        /// The file, relative to the deck's directory.
        file: Option<Spanned<String>>,
        /// Free side behind the triangles (clockwise seen from free space).
        flip: Option<Spanned<bool>>,
        /// The surface must be closed (a solid): a free edge is an error.
        closed: Option<Spanned<bool>>,
    },
}

/// `motion { ux uy uz rotation moment center axis }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Motion {
    /// Translation along x.
    pub ux: Option<Spanned<TimeFn>>,
    /// Translation along y.
    pub uy: Option<Spanned<TimeFn>>,
    /// Translation along z (`3d` analyses).
    pub uz: Option<Spanned<TimeFn>>,
    /// Rotation, radians.
    pub rotation: Option<Spanned<TimeFn>>,
    /// `rotation = free`: the rotation is an unknown (its span).
    pub free: Option<Span>,
    /// `moment = ..`: the moment applied to a free tool (time function).
    pub moment: Option<Spanned<TimeFn>>,
    /// Centre of rotation (planar analyses).
    pub center: Option<Point>,
    /// A point of the rotation axis (`3d` analyses: `center = (x, y, z)`).
    pub center3: Option<Point3>,
    /// Rotation axis (`3d` analyses; default z).
    pub axis: Option<Point3>,
    /// The `motion` block.
    pub span: Span,
}

/// `contact ref -> tool { .. }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Contact {
    /// The slave surface.
    pub target: SetRef,
    /// The master tool's name.
    pub tool: Ident,
    /// `method = ..`.
    pub method: Option<Spanned<Method>>,
    /// `prof = ..`.
    pub prof: Option<Spanned<f64>>,
    /// Reserved keys present (none at the moment).
    pub reserved: Vec<Ident>,
    /// The whole item.
    pub span: Span,
    /// `thermal { .. }`.
    pub thermal: Option<super::thermal::ContactThermal>,
    /// `friction = coulomb { .. }`.
    pub friction: Option<Spanned<Friction>>,
    /// Deformable master surface `body.set` (then `tool` holds its text
    /// and span); `None` for a rigid tool.
    pub master: Option<SetRef>,
    /// `strategy = single_pass | double_pass | modified_double_pass`.
    pub strategy: Option<Spanned<Strategy>>,
    /// `search = memory | circle`.
    pub search: Option<Spanned<Search>>,
    /// `formulation = node_to_segment | mortar`.
    pub formulation: Option<Spanned<ContactFormulation>>,
    /// `smoothing = none | nodal | nagata`.
    pub smoothing: Option<Spanned<Smoothing>>,
}

/// `smoothing = ..` of a node-to-segment pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Smoothing {
    /// `none`: the faceted master surface.
    None,
    /// `nodal`: nodal normals interpolated along the segments.
    Nodal,
    /// `nagata`: Nagata patches on the 3d master facets.
    Nagata,
}

/// `formulation = ..` of a contact pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactFormulation {
    /// `node_to_segment`.
    NodeToSegment,
    /// `mortar`.
    Mortar,
}

/// `friction = coulomb { mu stiffness first_impact cut_at_impact }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Friction {
    /// Coulomb coefficient.
    pub mu: Option<Spanned<f64>>,
    /// Tangential penalty (default alpha_N / 10).
    pub stiffness: Option<Spanned<f64>>,
    /// `intersect` (default) or `frictionless`.
    pub first_impact: Option<Spanned<FirstImpact>>,
    /// Cut the increment at the first impact (default false).
    pub cut_at_impact: Option<Spanned<bool>>,
}

/// `first_impact = ..` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FirstImpact {
    /// `intersect`.
    Intersect,
    /// `frictionless`.
    Frictionless,
}

/// `strategy = ..` of a contact pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Strategy {
    /// `single_pass`.
    SinglePass,
    /// `double_pass`.
    DoublePass,
    /// `modified_double_pass`.
    ModifiedDoublePass,
}

/// `search = ..` of a contact pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Search {
    /// `memory` (Metafor).
    Memory,
    /// `circle` (Cast3M).
    Circle,
}

/// `penalty` kinds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PenaltyKind {
    /// `nodal`.
    Nodal,
    /// `area`.
    Area,
}

/// Contact enforcement methods.
#[derive(Debug, Clone, PartialEq)]
pub enum Method {
    /// `penalty { kind stiffness }`.
    Penalty {
        /// Nodal or area (default area).
        kind: Option<Spanned<PenaltyKind>>,
        /// Penalty coefficient (for a relative one, its value at `E = 1`,
        /// `h = 1`: the validated expression's placeholder).
        stiffness: Option<Spanned<f64>>,
        /// The stiffness as an expression of the slave body's `E` and the
        /// local element size `h`, evaluated per slave node at lowering.
        relative: Option<RelativeStiffness>,
    },
    /// `lagrange { formulation }`.
    Lagrange {
        /// `single` (default) or `doubled`.
        formulation: Option<Spanned<LagrangeFormulation>>,
    },
    /// `augmented_lagrange { kind penalty tolerance update }`.
    AugmentedLagrange {
        /// Nodal or area (default area).
        kind: Option<Spanned<PenaltyKind>>,
        /// Penalty coefficient alpha (see `Penalty::stiffness`).
        penalty: Option<Spanned<f64>>,
        /// alpha as an expression of `E` and `h` (see `Penalty::relative`).
        relative: Option<RelativeStiffness>,
        /// Largest accepted penetration.
        tolerance: Option<Spanned<f64>>,
        /// `converged` (default) or `newton`.
        update: Option<Spanned<MultiplierUpdate>>,
    },
}

/// A penalty coefficient written relative to the mesh and the material,
/// e.g. `stiffness = 10 * E / h`: `E` is the Young's modulus of the slave
/// body's material and `h` the local size of the slave surface at each
/// node (the mean length of the slave facet edges that meet there). The
/// expression is checked when parsed and evaluated per slave node when the
/// deck is lowered, in the parameters and unit system it was written in.
#[derive(Debug, Clone)]
pub struct RelativeStiffness {
    /// The expression.
    pub expr: crate::ast::syntax::Value,
    /// The parameters and unit system at the expression.
    pub env: crate::expr::Env,
}

impl PartialEq for RelativeStiffness {
    /// Two relative stiffnesses are the same when written the same (the
    /// environment follows from the deck).
    fn eq(&self, other: &Self) -> bool {
        self.expr == other.expr
    }
}

/// The names a relative penalty coefficient is written in.
pub const RELATIVE_NAMES: [&str; 2] = ["E", "h"];

/// `lagrange { formulation = .. }` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LagrangeFormulation {
    /// `single`: `[K G^T; G 0]`.
    Single,
    /// `doubled`: multipliers `lambda1, q, lambda2`.
    Doubled,
    /// `condensed`: the multipliers eliminated at their slave nodes, the
    /// displacements alone.
    Condensed,
}

/// `augmented_lagrange { update = .. }` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MultiplierUpdate {
    /// After each converged Newton loop.
    Converged,
    /// At every Newton iteration.
    Newton,
}

/// Displacement components.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Component {
    /// `ux` (x, or r in axisymmetric).
    X,
    /// `uy` (y, or z in axisymmetric).
    Y,
    /// `uz` (3d analyses only).
    Z,
}

impl Component {
    /// 0 for x, 1 for y, 2 for z.
    pub fn index(self) -> usize {
        match self {
            Component::X => 0,
            Component::Y => 1,
            Component::Z => 2,
        }
    }
}

/// `fix` or `displace`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BoundaryKind {
    /// `fix ref { ux uy }`: components held at zero.
    Fix,
    /// `displace ref { ux = f(t) }`: prescribed components.
    Displace,
}

/// `fix ref { .. }` or `displace ref { .. }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Boundary {
    /// Fix or displace.
    pub kind: BoundaryKind,
    /// The keyword.
    pub keyword: Span,
    /// The nodes.
    pub target: SetRef,
    /// Components with their prescribed value (zero for `fix`).
    pub components: Vec<(Spanned<Component>, Spanned<TimeFn>)>,
    /// The whole item.
    pub span: Span,
}

/// `pressure`, `traction` or `force`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoadKind {
    /// `pressure ref { p = f(t) }` on edges (planar) or faces (3d).
    Pressure,
    /// `traction ref { tx = .. ty = .. tz = .. }`: a dead traction per unit
    /// reference area on edges (planar) or faces (3d).
    Traction,
    /// `force ref { fx = .. fy = .. }` per node.
    Force,
}

/// `gravity { gx = F(t)  gy = F(t)  gz = F(t) }`: an acceleration acting
/// on every body with a density and every point mass.
#[derive(Debug, Clone, PartialEq)]
pub struct Gravity {
    /// The keyword.
    pub keyword: Span,
    /// One value per component given.
    pub values: Vec<(Option<Component>, Spanned<TimeFn>)>,
    /// The whole item.
    pub span: Span,
}

/// `pressure ref { .. }` or `force ref { .. }`.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadDef {
    /// Pressure or force.
    pub kind: LoadKind,
    /// The keyword.
    pub keyword: Span,
    /// Edges (pressure) or nodes (force).
    pub target: SetRef,
    /// Pressure: one entry with component `None`; traction and force: one
    /// per component.
    pub values: Vec<(Option<Component>, Spanned<TimeFn>)>,
    /// Pressure: `follower = true` (on the deformed surface), if given.
    pub follower: Option<Spanned<bool>>,
    /// Pressure: `control = strain_rate { .. }`, if given.
    pub control: Option<Spanned<RateControlDef>>,
    /// The whole item.
    pub span: Span,
}

/// `control = strain_rate { target = ..  exponent = ..  max_change = ..  at = .. }`
/// of a follower `pressure`: the pressure-cycle controller.
#[derive(Debug, Clone, PartialEq)]
pub struct RateControlDef {
    /// `target`: the largest equivalent plastic strain rate to hold.
    pub target: Option<Spanned<f64>>,
    /// `exponent` of the update `(target / rate)^exponent`.
    pub exponent: Option<Spanned<f64>>,
    /// `max_change`: the largest factor change in one increment.
    pub max_change: Option<Spanned<f64>>,
    /// `max_pressure`: the cap of the applied pressure.
    pub max_pressure: Option<Spanned<f64>>,
    /// `at = (x, y[, z])`: monitor the cells touching the body's node
    /// nearest to this point (the pole of a bulge) instead of the body.
    pub at: Option<crate::ast::Coords>,
}

/// `initial_velocity ref { vx = ..  vy = ..  vz = .. }`: the velocity of
/// a node set at the start of the analysis (dynamic steps).
#[derive(Debug, Clone, PartialEq)]
pub struct InitialVelocity {
    /// The keyword.
    pub keyword: Span,
    /// The nodes.
    pub target: SetRef,
    /// One value per component given.
    pub values: Vec<(Component, Spanned<f64>)>,
    /// The whole item.
    pub span: Span,
}

/// Which discrete element an item places at each node of its set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DiscreteKind {
    /// `spring NODES { stiffness  damping }`: to the ground, or `spring
    /// NODES -> NODES { .. }`: between the nodes of two sets.
    Spring,
    /// `point_mass NODES { mass }`.
    PointMass,
    /// `rigid_body NODES { center  mass  inertia  rotation | angular_velocity
    /// | moment  stiffness  damping  tie_stiffness }`.
    RigidBody,
}

/// `spring NODES { .. }` or `point_mass NODES { .. }`: discrete elements at
/// every node of a set.
#[derive(Debug, Clone, PartialEq)]
pub struct DiscreteItem {
    /// Which element.
    pub kind: DiscreteKind,
    /// The keyword.
    pub keyword: Span,
    /// The nodes.
    pub target: SetRef,
    /// `spring a.x -> b.y`: the nodes at the other end (`None`: the
    /// ground).
    pub other: Option<SetRef>,
    /// `stiffness` (springs).
    pub stiffness: Option<Spanned<f64>>,
    /// `damping` (springs: the dashpot).
    pub damping: Option<Spanned<f64>>,
    /// `mass` (point masses, rigid bodies).
    pub mass: Option<Spanned<f64>>,
    /// `release_at` (links).
    pub release_at: Option<Spanned<f64>>,
    /// The keys of a rigid body (`None` for the other items).
    pub rigid: Option<RigidKeys>,
    /// The whole item.
    pub span: Span,
}

/// The keys of `rigid_body NODES { .. }` besides `mass`, `stiffness`
/// (bearing) and `damping` (bearing).
#[derive(Debug, Clone, PartialEq)]
pub struct RigidKeys {
    /// `center = (x, y)` (3d: `(x, y, z)`).
    pub center: Option<super::values::Coords>,
    /// `axis = (ax, ay, az)` (3d: the axis of a prescribed rotation).
    pub axis: Option<Point3>,
    /// `inertia` (planar: about the normal; 3d: the isotropic `J I`).
    pub inertia: Option<Spanned<f64>>,
    /// `inertia_diagonal = (Jxx, Jyy, Jzz)` (3d).
    pub inertia_diagonal: Option<Point3>,
    /// `inertia_products = (Jxy, Jyz, Jzx)` (3d).
    pub inertia_products: Option<Point3>,
    /// `rotation = F(t)`.
    pub rotation: Option<Spanned<TimeFn>>,
    /// `angular_velocity = F(t)`.
    pub angular_velocity: Option<Spanned<TimeFn>>,
    /// `moment = F(t)`.
    pub moment: Option<Spanned<TimeFn>>,
    /// `tie_stiffness`.
    pub tie_stiffness: Option<Spanned<f64>>,
}

/// `step name { .. }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// The step's name (optional in the deck).
    pub name: Option<Ident>,
    /// The `step` keyword.
    pub keyword: Span,
    /// `time = t0 .. t1`.
    pub time: Option<Spanned<[Spanned<f64>; 2]>>,
    /// `increments = n`.
    pub increments: Option<Spanned<i64>>,
    /// `min_increment = fraction`.
    pub min_increment: Option<Spanned<f64>>,
    /// `newton { .. }`.
    pub newton: Option<Newton>,
    /// `dynamic { .. }` (or a bare `dynamic`): implicit dynamics; `None`:
    /// quasi-static.
    pub dynamic: Option<Dynamic>,
    /// The whole item.
    pub span: Span,
}

/// The time integrator named by `dynamic { scheme = .. }`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DynamicScheme {
    /// `newmark` (`beta`, `gamma`).
    Newmark,
    /// `hht` (`rho_inf` in [1/2, 1]).
    Hht,
    /// `generalized_alpha` (`rho_inf` in [0, 1]).
    GeneralizedAlpha,
}

/// `dynamic { scheme = ..  rho_inf = ..  beta = ..  gamma = ..  mass = .. }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Dynamic {
    /// `scheme = newmark | hht | generalized_alpha`.
    pub scheme: Option<Spanned<DynamicScheme>>,
    /// `rho_inf`: spectral radius at infinite frequency (hht,
    /// generalized_alpha).
    pub rho_inf: Option<Spanned<f64>>,
    /// `beta` (newmark).
    pub beta: Option<Spanned<f64>>,
    /// `gamma` (newmark).
    pub gamma: Option<Spanned<f64>>,
    /// `mass = consistent | lumped`.
    pub mass: Option<Spanned<ctc_engine::model::MassMatrix>>,
    /// `contact_mass = redistributed | full`.
    pub contact_mass: Option<Spanned<ctc_engine::model::ContactMass>>,
    /// `rayleigh_alpha`: mass-proportional damping (1 / time).
    pub rayleigh_alpha: Option<Spanned<f64>>,
    /// `rayleigh_beta`: stiffness-proportional damping (time).
    pub rayleigh_beta: Option<Spanned<f64>>,
    /// `adaptive = true | false`: adaptive time stepping.
    pub adaptive: Option<Spanned<bool>>,
    /// `dt_min`: smallest adaptive increment (time).
    pub dt_min: Option<Spanned<f64>>,
    /// `dt_max`: largest adaptive increment (time).
    pub dt_max: Option<Spanned<f64>>,
    /// `error_tol`: tolerance of the local error estimate.
    pub error_tol: Option<Spanned<f64>>,
    /// `max_rotation`: the largest rotation of a cell per increment
    /// (radians).
    pub max_rotation: Option<Spanned<f64>>,
    /// `energy_tol`: the largest energy an increment may create, relative
    /// to the largest energy of the run.
    pub energy_tol: Option<Spanned<f64>>,
    /// The `dynamic` entry.
    pub span: Span,
}

/// `newton { tol tol_displacement max_iter line_search predictor stabilize }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Newton {
    /// Residual tolerance.
    pub tol: Option<Spanned<f64>>,
    /// Displacement-correction tolerance.
    pub tol_displacement: Option<Spanned<f64>>,
    /// Maximum iterations.
    pub max_iter: Option<Spanned<i64>>,
    /// Line search on/off.
    pub line_search: Option<Spanned<bool>>,
    /// Increment predictor on/off.
    pub predictor: Option<Spanned<bool>>,
    /// `stabilize = c` or a bare `stabilize` (the default factor).
    pub stabilize: Option<Spanned<f64>>,
    /// The block.
    pub span: Span,
}

/// Output fields.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldName {
    /// `displacement`.
    Displacement,
    /// `stress`.
    Stress,
    /// `strain`.
    Strain,
    /// `von_mises`.
    VonMises,
    /// `reaction`.
    Reaction,
    /// `contact`.
    Contact,
    /// `velocity` (dynamic steps).
    Velocity,
    /// `acceleration` (dynamic steps).
    Acceleration,
}

/// `output { format = .. }`: how VTU files store their arrays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputFormat {
    /// `binary`: appended raw, zlib-compressed (the default).
    Binary,
    /// `ascii`: inline text.
    Ascii,
}

/// History requests as written.
#[derive(Debug, Clone, PartialEq)]
pub enum History {
    /// `reaction(ref)`.
    Reaction(SetRef),
    /// `displacement(ref)`.
    Displacement(SetRef),
    /// `contact_force(ref -> tool)`.
    ContactForce(SetRef, Ident),
    /// `roughness(ref)`: Ra, Rq and mean height of the deformed set.
    Roughness(SetRef),
}

/// `output { .. }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Output {
    /// `every = n`.
    pub every: Option<Spanned<i64>>,
    /// `fields = [..]`.
    pub fields: Option<Spanned<Vec<Spanned<FieldName>>>>,
    /// `history = [..]`.
    pub history: Option<Vec<Spanned<History>>>,
    /// `format = binary | ascii`.
    pub format: Option<Spanned<OutputFormat>>,
    /// `thickness = (body.a, body.b)`: the thickness map between two face
    /// sets of one body (3d).
    pub thickness: Option<Spanned<[SetRef; 2]>>,
    /// The `output` keyword.
    pub keyword: Span,
    /// The whole item.
    pub span: Span,
}

/// An item whose text could not be parsed (already reported as a syntax
/// error). Kept so that references to its name are not reported again as
/// unknown names.
#[derive(Debug, Clone, PartialEq)]
pub struct BrokenItem {
    /// The item keyword (`material`, `body`, ...).
    pub keyword: String,
    /// The item's name, if one could be recognised.
    pub name: Option<String>,
    /// The item's text.
    pub span: Span,
}
