//! The key tables of every block of the deck language (mesh generators
//! have theirs in [`crate::generators`]). The parser reads each block
//! through its table (`Fields::keyed`), so the keyword reference printed
//! by `ctc doc` and `docs/DECK.md` ([`crate::reference`]) is the parser's
//! own list of keys, types, defaults, ranges and dimensions.

use crate::keys::{Components, Default, Dim, Key, KeyType, Range};

const P2: Components = Components::Two;
const P3: Components = Components::Three;

/// `analysis { .. }`.
pub static ANALYSIS: [Key; 3] = [
    Key::new(
        "dimension",
        KeyType::Choice(&["plane_strain", "plane_stress", "axisymmetric", "3d"]),
        "kind of analysis (axisymmetric: x = r, y = z, forces are totals over 2 pi; 3d: solid x, y, z, no contact or heat yet)",
    )
    .required("add `dimension = plane_strain` (or `plane_stress`, `axisymmetric`)"),
    Key::new(
        "thickness",
        KeyType::Number,
        "out-of-plane thickness (plane analyses)",
    )
    .default(Default::Number(1.0))
    .range(Range::Positive)
    .dim(Dim::Length),
    Key::new(
        "units",
        KeyType::Choice(&["SI", "mm_N_s", "mm_kg_ms", "m_kg_s"]),
        "unit system of every number; numbers with a unit (`210 GPa`) are converted into it",
    ),
];

/// `elastic { .. }` and `neo_hookean { .. }` of a material.
pub static ELASTIC: [Key; 2] = [
    Key::new("E", KeyType::Number, "Young's modulus")
        .required("add Young's modulus, e.g. `E = 210e3`")
        .range(Range::Positive)
        .dim(Dim::Stress),
    Key::new("nu", KeyType::Number, "Poisson's ratio, in (-1, 0.5)")
        .required("add Poisson's ratio, e.g. `nu = 0.3`")
        .dim(Dim::None),
];

/// `neo_hookean { mu kappa }` (instead of `E nu`).
pub static NEO_HOOKEAN_MODULI: [Key; 2] = [
    Key::new("mu", KeyType::Number, "shear modulus")
        .required("add the shear modulus `mu = ..`")
        .range(Range::Positive)
        .dim(Dim::Stress),
    Key::new("kappa", KeyType::Number, "bulk modulus")
        .required("add the bulk modulus `kappa = ..`")
        .range(Range::Positive)
        .dim(Dim::Stress),
];

/// `plastic { .. }`.
pub static PLASTIC: [Key; 2] = [
    Key::new(
        "yield",
        KeyType::Number,
        "initial yield stress (not with `swift` or `johnson_cook`)",
    )
    .range(Range::Positive)
    .dim(Dim::Stress),
    Key::new(
        "hardening",
        KeyType::Choice(&[
            "linear { H }",
            "swift { K eps0 n }",
            "voce { sigma_inf delta }",
            "johnson_cook { A B n C rate0 m T_ref T_melt }",
        ]),
        "isotropic hardening law (absent: perfect plasticity)",
    ),
];

/// `linear { H }` hardening.
pub static LINEAR_HARDENING: [Key; 1] = [Key::new("H", KeyType::Number, "plastic modulus")
    .required("add the plastic modulus `H = ..`")
    .range(Range::NonNegative)
    .dim(Dim::Stress)];

/// `swift { K eps0 n }` hardening: `sigma_y = K (eps0 + ep)^n`.
pub static SWIFT_HARDENING: [Key; 3] = [
    Key::new("K", KeyType::Number, "strength coefficient")
        .required("add `K = ..` (sigma_y = K (eps0 + ep)^n)")
        .range(Range::Positive)
        .dim(Dim::Stress),
    Key::new("eps0", KeyType::Number, "pre-strain")
        .required("add `eps0 = ..`")
        .range(Range::Positive)
        .dim(Dim::None),
    Key::new("n", KeyType::Number, "hardening exponent")
        .required("add `n = ..`")
        .range(Range::Closed(0.0, 1.0))
        .dim(Dim::None),
];

/// `voce { sigma_inf delta }` hardening.
pub static VOCE_HARDENING: [Key; 2] = [
    Key::new("sigma_inf", KeyType::Number, "saturation stress (>= yield)")
        .required("add the saturation stress `sigma_inf = ..`")
        .dim(Dim::Stress),
    Key::new("delta", KeyType::Number, "saturation rate")
        .required("add the saturation rate `delta = ..`")
        .range(Range::Positive)
        .dim(Dim::None),
];

/// `johnson_cook { A B n C rate0 m T_ref T_melt }` hardening (Johnson &
/// Cook 1983): `sigma_y = (A + B ep^n) (1 + C ln(rate / rate0)) (1 -
/// T*^m)`.
pub static JOHNSON_COOK_HARDENING: [Key; 8] = [
    Key::new(
        "A",
        KeyType::Number,
        "yield stress at the reference rate and temperature",
    )
    .required("add `A = ..` (sigma_y = (A + B ep^n) ..)")
    .range(Range::Positive)
    .dim(Dim::Stress),
    Key::new("B", KeyType::Number, "hardening modulus")
        .required("add `B = ..`")
        .range(Range::NonNegative)
        .dim(Dim::Stress),
    Key::new("n", KeyType::Number, "hardening exponent, in (0, 1]")
        .required("add `n = ..`")
        .range(Range::Closed(0.0, 1.0))
        .dim(Dim::None),
    Key::new(
        "C",
        KeyType::Number,
        "strain-rate sensitivity (the factor 1 + C ln(rate / rate0), 1 below rate0)",
    )
    .required("add `C = ..` (0: rate independent)")
    .range(Range::NonNegative)
    .dim(Dim::None),
    Key::new("rate0", KeyType::Number, "reference plastic strain rate")
        .required("add `rate0 = ..` (e.g. 1 /s)")
        .range(Range::Positive)
        .dim(Dim::Frequency),
    Key::new(
        "m",
        KeyType::Number,
        "thermal softening exponent (the factor 1 - T*^m, T* = (T - T_ref) / (T_melt - T_ref))",
    )
    .required("add `m = ..`")
    .range(Range::Positive)
    .dim(Dim::None),
    Key::new("T_ref", KeyType::Number, "reference (room) temperature")
        .required("add `T_ref = ..`")
        .dim(Dim::Temperature),
    Key::new("T_melt", KeyType::Number, "melting temperature (> T_ref)")
        .required("add `T_melt = ..`")
        .dim(Dim::Temperature),
];

/// `viscoplastic { eta }` or `viscoplastic { rate exponent }` (Perzyna).
pub static VISCOPLASTIC: [Key; 3] = [
    Key::new(
        "eta",
        KeyType::Number,
        "Perzyna viscosity, linear over-stress: q - sigma_y = eta d(ep)/dt",
    )
    .range(Range::Positive)
    .dim(Dim::Viscosity),
    Key::new(
        "rate",
        KeyType::Number,
        "reference rate of the power over-stress d(ep)/dt = rate (q / sigma_y - 1)^exponent \
         (instead of eta, with `exponent`)",
    )
    .range(Range::Positive)
    .dim(Dim::Frequency),
    Key::new(
        "exponent",
        KeyType::Number,
        "rate exponent N of the power over-stress (with `rate`)",
    )
    .range(Range::Positive)
    .dim(Dim::None),
];

/// `control = strain_rate { target exponent max_change max_pressure at }`
/// of a follower pressure.
pub static RATE_CONTROL: [Key; 5] = [
    Key::new(
        "target",
        KeyType::Number,
        "the largest equivalent plastic strain rate of the pressed body to hold",
    )
    .required("add the target strain rate `target = ..` (1 / time)")
    .range(Range::Positive)
    .dim(Dim::Frequency),
    Key::new(
        "exponent",
        KeyType::Number,
        "exponent of the update: pressure x (target / rate)^exponent after each increment \
         (the body's Norton-Hoff m lands on the target)",
    )
    .default(Default::Number(0.5))
    .range(Range::Closed(0.0, 1.0))
    .dim(Dim::None),
    Key::new(
        "max_change",
        KeyType::Number,
        "largest factor by which the pressure changes in one increment",
    )
    .default(Default::Number(2.0))
    .dim(Dim::None),
    Key::new(
        "max_pressure",
        KeyType::Number,
        "the largest pressure the controller applies (the gas supply's limit): once the body \
         needs more to hold the target rate (a die corner filling), the pressure stays at this \
         cap and the rate falls below the target",
    )
    .range(Range::Positive)
    .dim(Dim::Stress),
    Key::new(
        "at",
        KeyType::Point(Components::Analysis),
        "monitor only the cells touching the body's node nearest to this point (the pole of \
         a bulge; default: the whole body)",
    )
    .dim(Dim::Length),
];

/// `norton_hoff { stress rate m }`.
pub static NORTON_HOFF: [Key; 3] = [
    Key::new(
        "stress",
        KeyType::Number,
        "flow stress at the reference rate: q = sigma_y(ep) + stress (d(ep)/dt / rate)^m",
    )
    .required("add the flow stress at the reference rate `stress = ..`")
    .range(Range::Positive)
    .dim(Dim::Stress),
    Key::new("rate", KeyType::Number, "reference equivalent strain rate")
        .required("add the reference strain rate `rate = ..` (1 / time)")
        .range(Range::Positive)
        .dim(Dim::Frequency),
    Key::new(
        "m",
        KeyType::Number,
        "strain-rate sensitivity, in (0, 1] (superplastic: about 0.5)",
    )
    .required("add the strain-rate sensitivity `m = ..`")
    .range(Range::Closed(0.0, 1.0))
    .dim(Dim::None),
];

/// `material NAME { .. }`.
pub static MATERIAL: [Key; 7] = [
    Key::new(
        "elastic",
        KeyType::Choice(&["{ E nu }"]),
        "small-strain (Hencky at finite strain) elasticity",
    ),
    Key::new(
        "neo_hookean",
        KeyType::Choice(&["{ E nu }", "{ mu kappa }"]),
        "Neo-Hookean hyperelasticity (needs `kinematics = finite`)",
    ),
    Key::new(
        "plastic",
        KeyType::Choice(&["{ yield hardening }"]),
        "J2 plasticity",
    ),
    Key::new(
        "viscoplastic",
        KeyType::Choice(&["{ eta }", "{ rate exponent }"]),
        "Perzyna viscoplasticity (with `plastic`)",
    ),
    Key::new(
        "norton_hoff",
        KeyType::Choice(&["{ stress rate m }"]),
        "Norton-Hoff viscoplasticity (the superplastic law; with or without `plastic`)",
    ),
    Key::new(
        "thermal",
        KeyType::Choice(&["{ .. }"]),
        "thermal properties (only decks with heat)",
    ),
    Key::new(
        "density",
        KeyType::Number,
        "mass density: the inertia of `dynamic` steps (needed by them)",
    )
    .default(Default::Number(0.0))
    .range(Range::NonNegative)
    .dim(Dim::Density),
];

/// `body NAME { .. }`.
pub static BODY: [Key; 5] = [
    Key::new(
        "mesh",
        KeyType::Mesh,
        "a generator (`rectangle { .. }`, ...) or `file \"part.msh\"` (gmsh, relative to the deck)",
    )
    .required("add e.g. `mesh = rectangle { size = (1, 1)  divisions = (10, 10) }`"),
    Key::new(
        "material",
        KeyType::Choice(&["NAME"]),
        "name of a `material`",
    )
    .required("add `material = <name of a material>`"),
    Key::new(
        "formulation",
        KeyType::Choice(&["full", "selective_reduced"]),
        "quad4 integration: full, or B-bar (small strain) / F-bar (finite strain)",
    )
    .default(Default::Choice("full")),
    Key::new(
        "kinematics",
        KeyType::Choice(&["small", "finite"]),
        "small strain, or total Lagrangian finite strain",
    )
    .default(Default::Choice("small")),
    Key::new(
        "thermal",
        KeyType::Choice(&["{ initial }"]),
        "initial temperature",
    ),
];

/// `tool NAME = plane { .. }`.
pub static PLANE: [Key; 3] = [
    Key::new("point", KeyType::Point(P2), "a point of the line")
        .required("add `point = (x, y)`")
        .dim(Dim::Length),
    Key::new(
        "normal",
        KeyType::Point(P2),
        "normal towards the free side (nonzero)",
    )
    .required("add `normal = (nx, ny)` pointing to the free side"),
    MOTION_KEY,
];

/// `tool NAME = polyline { .. }`.
pub static POLYLINE: [Key; 2] = [
    Key::new(
        "points",
        KeyType::Numbers(Components::Analysis),
        "vertices `[(x0, y0), (x1, y1), ..]`; the free side is on the left of the walk",
    )
    .required("add `points = [(x0, y0), (x1, y1), ..]`")
    .dim(Dim::Length),
    MOTION_KEY,
];

/// `tool NAME = arc { .. }`.
pub static ARC: [Key; 5] = [
    Key::new("center", KeyType::Point(P2), "centre")
        .required("add `center = (x, y)`")
        .dim(Dim::Length),
    Key::new("radius", KeyType::Number, "radius")
        .required("add `radius = ..`")
        .range(Range::Positive)
        .dim(Dim::Length),
    Key::new("start", KeyType::Number, "start angle")
        .required("add `start = <angle in degrees>`")
        .dim(Dim::AngleDegrees),
    Key::new("end", KeyType::Number, "end angle (|end - start| <= 360)")
        .required("add `end = <angle in degrees>`")
        .dim(Dim::AngleDegrees),
    MOTION_KEY,
];

/// `tool NAME = circle { .. }`.
pub static CIRCLE: [Key; 4] = [
    Key::new("center", KeyType::Point(P2), "centre")
        .required("add `center = (x, y)`")
        .dim(Dim::Length),
    Key::new("radius", KeyType::Number, "radius")
        .required("add `radius = ..`")
        .range(Range::Positive)
        .dim(Dim::Length),
    Key::new(
        "side",
        KeyType::Choice(&["outside", "inside"]),
        "where the bodies are",
    )
    .default(Default::Choice("outside")),
    MOTION_KEY,
];

/// `tool NAME = nurbs { .. }`.
pub static NURBS: [Key; 5] = [
    Key::new("degree", KeyType::Integer, "polynomial degree")
        .required("add `degree = 2` (or another degree >= 1)")
        .range(Range::AtLeast(1)),
    Key::new(
        "points",
        KeyType::Numbers(Components::Analysis),
        "control points `[(x, y), ..]`",
    )
    .required("add `points = [(x0, y0), ..]` (the control points)")
    .dim(Dim::Length),
    Key::new(
        "weights",
        KeyType::Numbers(Components::Analysis),
        "one positive weight per point",
    )
    .dim(Dim::None),
    Key::new(
        "knots",
        KeyType::Numbers(Components::Analysis),
        "non-decreasing knot vector (points + degree + 1); default open uniform",
    ),
    MOTION_KEY,
];

/// `tool NAME = plane { .. }` of a `3d` analysis (the half-space behind
/// the plane).
pub static PLANE_3D: [Key; 3] = [
    Key::new("point", KeyType::Point(P3), "a point of the plane")
        .required("add `point = (x, y, z)`")
        .dim(Dim::Length),
    Key::new(
        "normal",
        KeyType::Point(P3),
        "normal towards the free side (nonzero)",
    )
    .required("add `normal = (nx, ny, nz)` pointing to the free side"),
    MOTION_KEY,
];

/// The `side` key of the closed surface tools.
const SURFACE_SIDE: Key = Key::new(
    "side",
    KeyType::Choice(&["outside", "inside"]),
    "where the bodies are: outside the solid the surface bounds (a punch) or inside (a die)",
)
.default(Default::Choice("outside"));

/// `tool NAME = sphere { .. }` (`3d`).
pub static SPHERE: [Key; 4] = [
    Key::new("center", KeyType::Point(P3), "centre")
        .required("add `center = (x, y, z)`")
        .dim(Dim::Length),
    Key::new("radius", KeyType::Number, "radius")
        .required("add `radius = ..`")
        .range(Range::Positive)
        .dim(Dim::Length),
    SURFACE_SIDE,
    MOTION_KEY,
];

/// `tool NAME = cylinder { .. }` (`3d`, infinite).
pub static CYLINDER: [Key; 5] = [
    Key::new("point", KeyType::Point(P3), "a point of the axis")
        .required("add `point = (x, y, z)`")
        .dim(Dim::Length),
    Key::new("axis", KeyType::Point(P3), "axis direction (nonzero)")
        .required("add `axis = (ax, ay, az)`"),
    Key::new("radius", KeyType::Number, "radius")
        .required("add `radius = ..`")
        .range(Range::Positive)
        .dim(Dim::Length),
    SURFACE_SIDE,
    MOTION_KEY,
];

/// `tool NAME = cone { .. }` (`3d`, one nappe).
pub static CONE: [Key; 5] = [
    Key::new("apex", KeyType::Point(P3), "apex")
        .required("add `apex = (x, y, z)`")
        .dim(Dim::Length),
    Key::new(
        "axis",
        KeyType::Point(P3),
        "axis direction, from the apex into the cone (nonzero)",
    )
    .required("add `axis = (ax, ay, az)`"),
    Key::new("angle", KeyType::Number, "half opening angle (0 to 90)")
        .required("add `angle = <half angle in degrees>`")
        .dim(Dim::AngleDegrees),
    SURFACE_SIDE,
    MOTION_KEY,
];

/// `tool NAME = torus { .. }` (`3d`).
pub static TORUS: [Key; 6] = [
    Key::new("center", KeyType::Point(P3), "centre")
        .required("add `center = (x, y, z)`")
        .dim(Dim::Length),
    Key::new("axis", KeyType::Point(P3), "axis of revolution (nonzero)")
        .required("add `axis = (ax, ay, az)`"),
    Key::new(
        "major",
        KeyType::Number,
        "radius of the tube's centre circle",
    )
    .required("add `major = ..`")
    .range(Range::Positive)
    .dim(Dim::Length),
    Key::new("minor", KeyType::Number, "radius of the tube (< major)")
        .required("add `minor = ..`")
        .range(Range::Positive)
        .dim(Dim::Length),
    SURFACE_SIDE,
    MOTION_KEY,
];

/// `tool NAME = iges { .. }` (`3d`): CAD faces read from an IGES file.
pub static IGES: [Key; 3] = [
    Key::new(
        "file",
        KeyType::File,
        "IGES 5.3 file: trimmed surfaces (144), bounded surfaces (143), B-spline surfaces (128)",
    )
    .required("add `file = \"die.igs\"`"),
    Key::new(
        "flip",
        KeyType::Bool,
        "free side opposite `S_u x S_v` of the first face (faces are oriented consistently \
         across shared edges)",
    )
    .default(Default::Bool(false)),
    MOTION_KEY,
];

/// `tool NAME = stl { .. }` (`3d`): the triangles of an STL file.
pub static STL: [Key; 4] = [
    Key::new(
        "file",
        KeyType::File,
        "STL file, ASCII or binary: flat triangles, counter-clockwise seen from free space \
         (edges and vertices are cylinders and spheres of radius 0; the inside / outside sign \
         comes from angle-weighted pseudonormals)",
    )
    .required("add `file = \"punch.stl\"`"),
    Key::new(
        "flip",
        KeyType::Bool,
        "free space on the other side of the triangles (clockwise seen from free space)",
    )
    .default(Default::Bool(false)),
    Key::new(
        "closed",
        KeyType::Bool,
        "the triangles must close a solid: an edge of a single triangle (a hole in the surface) \
         is an error",
    )
    .default(Default::Bool(false)),
    MOTION_KEY,
];

/// The `motion { .. }` key of every tool.
const MOTION_KEY: Key = Key::new(
    "motion",
    KeyType::Choice(&["{ ux uy uz rotation moment center axis }"]),
    "rigid motion: rotate about `center` (3d: about `axis` through `center`), then translate",
);

/// `motion { .. }` of a tool.
pub static MOTION: [Key; 7] = [
    Key::new("ux", KeyType::Number, "translation along x (time function)").dim(Dim::Length),
    Key::new("uy", KeyType::Number, "translation along y (time function)").dim(Dim::Length),
    Key::new(
        "uz",
        KeyType::Number,
        "translation along z (time function; 3d)",
    )
    .dim(Dim::Length),
    Key::new(
        "rotation",
        KeyType::Number,
        "rotation, counter-clockwise (3d: right-handed about `axis`) (time function); \
         `rotation = free`: an unknown, the tool turns until the contact moment about `center` \
         balances `moment` (a free roller; plane strain / plane stress)",
    )
    .dim(Dim::AngleRadians),
    Key::new(
        "moment",
        KeyType::Number,
        "moment applied to a tool with `rotation = free`, counter-clockwise about `center`, per \
         unit thickness like the contact forces (time function; default 0)",
    )
    .dim(Dim::Any),
    Key::new(
        "center",
        KeyType::Point(Components::Analysis),
        "centre of rotation (3d: a point of the axis; default: the tool's reference point)",
    )
    .dim(Dim::Length),
    Key::new(
        "axis",
        KeyType::Point(P3),
        "rotation axis (3d; default (0, 0, 1))",
    ),
];

/// `contact SLAVE -> MASTER { .. }`.
pub static CONTACT: [Key; 8] = [
    Key::new(
        "method",
        KeyType::Choice(&[
            "penalty { .. }",
            "lagrange { .. }",
            "augmented_lagrange { .. }",
        ]),
        "enforcement of the normal contact condition",
    )
    .required("add `method = penalty { stiffness = .. }`"),
    Key::new(
        "prof",
        KeyType::Number,
        "search depth: nodes farther than this from the master are out of reach",
    )
    .range(Range::Positive)
    .dim(Dim::Length),
    Key::new(
        "friction",
        KeyType::Choice(&["coulomb { .. }"]),
        "friction law (absent: frictionless)",
    ),
    Key::new(
        "strategy",
        KeyType::Choice(&["single_pass", "double_pass", "modified_double_pass"]),
        "which side is the slave (deformable masters only)",
    )
    .default(Default::Choice("single_pass")),
    Key::new(
        "search",
        KeyType::Choice(&["memory", "circle"]),
        "local search of node-to-segment contact (Metafor memory, Cast3M circle)",
    )
    .default(Default::Choice("memory")),
    Key::new(
        "formulation",
        KeyType::Choice(&["node_to_segment", "mortar"]),
        "contact between deformable bodies: node-to-segment elements (3d: node-to-facet on \
         tri3 / quad4 faces), or mortar segment-to-segment (weighted gaps, dual Lagrange \
         multipliers; 3d: tri3 / quad4 facets clipped on the slave facet's plane; single \
         pass; penalty, augmented Lagrangian or Lagrange multipliers (2d and 3d, active set \
         by a semi-smooth Newton); Coulomb friction on the weighted slip (2d and 3d), penalty \
         or augmented Lagrangian)",
    )
    .default(Default::Choice("node_to_segment")),
    Key::new(
        "smoothing",
        KeyType::Choice(&["none", "nodal", "nagata"]),
        "master normal of node-to-segment contact: none (faceted, exact segment normals), \
         nodal (averaged nodal normals interpolated along each segment: continuous across the \
         master nodes, they give the gap, the force and the friction's tangent; planar \
         analyses) or nagata (3d node-to-facet: Nagata's quadratic \
         patches through the master facets' nodes and their area-weighted nodal normals, \
         which give the gap, the force and the friction's tangent plane)",
    )
    .default(Default::Choice("none")),
    Key::new("thermal", KeyType::Choice(&["{ .. }"]), "thermal contact"),
];

/// `penalty { .. }`.
pub static PENALTY: [Key; 2] = [
    Key::new(
        "kind",
        KeyType::Choice(&["area", "nodal"]),
        "area: pressure = stiffness x penetration (stiffness per area); nodal: force",
    )
    .default(Default::Choice("area")),
    Key::new(
        "stiffness",
        KeyType::Number,
        "penalty coefficient; relative to the mesh when written with `E` (the slave body's \
         Young's modulus) and `h` (the local size of the slave surface, per node): `10 * E / h`",
    )
    .required("add `stiffness = <penalty coefficient>`")
    .range(Range::Positive),
];

/// `lagrange { .. }`.
pub static LAGRANGE: [Key; 1] = [Key::new(
    "formulation",
    KeyType::Choice(&["single", "doubled", "condensed"]),
    "saddle point [K G^T; G 0], doubled multipliers (lambda1, q, lambda2), or the \
     multipliers condensed out at their slave nodes (dual mortar: D diagonal; the \
     displacements alone by LU, the same solution)",
)
.default(Default::Choice("single"))];

/// `augmented_lagrange { .. }`.
pub static AUGMENTED_LAGRANGE: [Key; 4] = [
    Key::new(
        "kind",
        KeyType::Choice(&["area", "nodal"]),
        "as for `penalty`",
    )
    .default(Default::Choice("area")),
    Key::new(
        "penalty",
        KeyType::Number,
        "penalty coefficient alpha; may be relative to the mesh as for `penalty`: `10 * E / h`",
    )
    .required("add `penalty = <penalty coefficient>`")
    .range(Range::Positive),
    Key::new("tolerance", KeyType::Number, "largest accepted penetration")
        .required("add `tolerance = <largest accepted penetration>`")
        .range(Range::Positive)
        .dim(Dim::Length),
    Key::new(
        "update",
        KeyType::Choice(&["converged", "newton"]),
        "Uzawa update after each converged Newton loop, or at every iteration",
    )
    .default(Default::Choice("converged")),
];

/// `friction = coulomb { .. }`.
pub static COULOMB: [Key; 4] = [
    Key::new("mu", KeyType::Number, "friction coefficient")
        .required("add `mu = <friction coefficient>`")
        .range(Range::NonNegative)
        .dim(Dim::None),
    Key::new(
        "stiffness",
        KeyType::Number,
        "tangential penalty alpha_T (kind of the normal penalty; default alpha_N / 10)",
    )
    .range(Range::Positive),
    Key::new(
        "first_impact",
        KeyType::Choice(&["intersect", "frictionless"]),
        "stick point at first touch: the constant-velocity intersection, or no friction in that increment",
    )
    .default(Default::Choice("intersect")),
    Key::new(
        "cut_at_impact",
        KeyType::Bool,
        "cut an increment at the fraction where a node first touches",
    )
    .default(Default::Bool(false)),
];

/// `thermal { .. }` of a material.
pub static MATERIAL_THERMAL: [Key; 8] = [
    Key::new("conductivity", KeyType::Number, "thermal conductivity")
        .required("add the thermal conductivity, e.g. `conductivity = 50`")
        .range(Range::Positive)
        .dim(Dim::Conductivity),
    Key::new(
        "capacity",
        KeyType::Number,
        "specific heat (rho c = 0: steady conduction)",
    )
    .default(Default::Number(0.0))
    .range(Range::NonNegative)
    .dim(Dim::SpecificHeat),
    Key::new("density", KeyType::Number, "mass density")
        .default(Default::Number(0.0))
        .range(Range::NonNegative)
        .dim(Dim::Density),
    Key::new(
        "expansion",
        KeyType::Number,
        "thermal expansion coefficient",
    )
    .default(Default::Number(0.0))
    .range(Range::NonNegative)
    .dim(Dim::Expansion),
    Key::new(
        "reference",
        KeyType::Number,
        "temperature of zero thermal strain",
    )
    .default(Default::Number(0.0))
    .dim(Dim::Temperature),
    Key::new(
        "taylor_quinney",
        KeyType::Number,
        "share of plastic work turned into heat",
    )
    .default(Default::Number(0.9))
    .range(Range::Closed(0.0, 1.0))
    .dim(Dim::None),
    Key::new(
        "young",
        KeyType::Number,
        "factor of E: a number or `table((T, factor), ..)`",
    )
    .range(Range::Positive)
    .dim(Dim::None),
    Key::new(
        "yield",
        KeyType::Number,
        "factor of the flow stress: a number or `table((T, factor), ..)`",
    )
    .range(Range::Positive)
    .dim(Dim::None),
];

/// `thermal { .. }` of a body.
pub static BODY_THERMAL: [Key; 1] = [Key::new("initial", KeyType::Number, "initial temperature")
    .default(Default::Number(0.0))
    .dim(Dim::Temperature)];

/// `thermal { .. }` of a contact.
pub static CONTACT_THERMAL: [Key; 5] = [
    Key::new(
        "conductance",
        KeyType::Choice(&["h", "power { h0 h1 n }", "table((p, h), ..)"]),
        "closed-gap conductance: constant, h0 + h1 p^n, or a table of the pressure",
    )
    .required("add e.g. `conductance = power { h0 = 1e3  h1 = 10  n = 1 }`"),
    Key::new(
        "gap_conductivity",
        KeyType::Number,
        "open gap: conductance k_gap / max(g, gap_min)",
    )
    .default(Default::Number(0.0))
    .range(Range::NonNegative)
    .dim(Dim::Conductivity),
    Key::new(
        "gap_min",
        KeyType::Number,
        "smallest gap of the gap conductance",
    )
    .default(Default::Number(1e-9))
    .range(Range::Positive)
    .dim(Dim::Length),
    Key::new(
        "friction_split",
        KeyType::Number,
        "share of the frictional heat going to the slave",
    )
    .default(Default::Number(0.5))
    .range(Range::Closed(0.0, 1.0))
    .dim(Dim::None),
    Key::new(
        "tool_temperature",
        KeyType::Number,
        "temperature of a rigid tool (time function; required with a tool)",
    )
    .dim(Dim::Temperature),
];

/// `power { .. }` conductance.
pub static POWER_CONDUCTANCE: [Key; 3] = [
    Key::new("h0", KeyType::Number, "conductance at zero pressure")
        .default(Default::Number(0.0))
        .range(Range::NonNegative)
        .dim(Dim::HeatTransfer),
    Key::new("h1", KeyType::Number, "coefficient of p^n")
        .default(Default::Number(0.0))
        .range(Range::NonNegative),
    Key::new("n", KeyType::Number, "exponent")
        .default(Default::Number(1.0))
        .range(Range::Positive)
        .dim(Dim::None),
];

/// `step NAME { .. }`.
pub static STEP: [Key; 5] = [
    Key::new(
        "time",
        KeyType::Numbers(P2),
        "time range `t0 .. t1` (steps follow each other)",
    )
    .required("add e.g. `time = 0 .. 1`")
    .dim(Dim::Time),
    Key::new("increments", KeyType::Integer, "number of equal increments")
        .default(Default::Integer(1))
        .range(Range::AtLeast(1)),
    Key::new(
        "min_increment",
        KeyType::Number,
        "smallest cutback increment as a fraction of the initial one, in (0, 1]",
    )
    .default(Default::Number(1.0 / 1024.0))
    .dim(Dim::None),
    Key::new(
        "newton",
        KeyType::Choice(&["{ tol tol_displacement max_iter line_search predictor stabilize }"]),
        "Newton settings",
    ),
    Key::new(
        "dynamic",
        KeyType::Choice(&[
            "{ scheme rho_inf beta gamma mass contact_mass rayleigh_alpha rayleigh_beta adaptive dt_min \
             dt_max error_tol max_rotation energy_tol }",
        ]),
        "implicit dynamics (inertia; a bare `dynamic` takes every default); without it the \
         step is quasi-static",
    ),
];

/// `dynamic { .. }` of a step.
pub static DYNAMIC: [Key; 14] = [
    Key::new(
        "scheme",
        KeyType::Choice(&["newmark", "hht", "generalized_alpha"]),
        "time integrator: Newmark (beta, gamma), HHT-alpha or Chung-Hulbert generalized-alpha \
         (rho_inf)",
    )
    .default(Default::Choice("generalized_alpha")),
    Key::new(
        "rho_inf",
        KeyType::Number,
        "spectral radius at infinite frequency: 1 no numerical dissipation, smaller damps \
         the high modes (hht: in [0.5, 1])",
    )
    .default(Default::Number(0.9))
    .range(Range::Closed(0.0, 1.0))
    .dim(Dim::None),
    Key::new("beta", KeyType::Number, "Newmark beta (newmark only)")
        .default(Default::Number(0.25))
        .range(Range::Positive)
        .dim(Dim::None),
    Key::new(
        "gamma",
        KeyType::Number,
        "Newmark gamma, >= 1/2 (newmark only)",
    )
    .default(Default::Number(0.5))
    .range(Range::Positive)
    .dim(Dim::None),
    Key::new(
        "mass",
        KeyType::Choice(&["consistent", "lumped"]),
        "mass matrix: consistent, or lumped (row sums; HRZ where a row sum is not positive)",
    )
    .default(Default::Choice("consistent")),
    Key::new(
        "contact_mass",
        KeyType::Choice(&["redistributed", "full", "normal"]),
        "mass of the nodes of contact surfaces: redistributed (moved to the other nodes of \
         their cells, Khenous-Laborde-Renard 2008: no chatter, impacts conserve energy), \
         full (the mass matrix everywhere: contact nodes bounce) or normal (only the share \
         along the normal of an axis-aligned rigid plane is moved, the tangential mass stays: \
         a frictionless face keeps its inertia; other masters as redistributed)",
    )
    .default(Default::Choice("redistributed")),
    Key::new(
        "rayleigh_alpha",
        KeyType::Number,
        "mass-proportional Rayleigh damping: C = rayleigh_alpha M + rayleigh_beta K_0 (K_0 the \
         stiffness in the reference configuration); damping ratio of a mode of circular \
         frequency w: rayleigh_alpha / (2 w) + rayleigh_beta w / 2",
    )
    .default(Default::Number(0.0))
    .range(Range::NonNegative)
    .dim(Dim::Frequency),
    Key::new(
        "rayleigh_beta",
        KeyType::Number,
        "stiffness-proportional Rayleigh damping (see rayleigh_alpha)",
    )
    .default(Default::Number(0.0))
    .range(Range::NonNegative)
    .dim(Dim::Time),
    Key::new(
        "adaptive",
        KeyType::Bool,
        "adaptive time stepping: the increment grows (x1.5) after two easy increments up to \
         dt_max, is halved on a cutback and on a contact event (first contact or release), \
         and follows the Zienkiewicz-Xie local error estimate (error_tol); false: the step's \
         equal increments, cut back and grown back to at most their initial size",
    )
    .default(Default::Bool(false)),
    Key::new(
        "dt_min",
        KeyType::Number,
        "smallest increment of adaptive stepping (absent: min_increment x the initial \
         increment)",
    )
    .range(Range::Positive)
    .dim(Dim::Time),
    Key::new(
        "dt_max",
        KeyType::Number,
        "largest increment of adaptive stepping (absent: 10 x the initial increment)",
    )
    .range(Range::Positive)
    .dim(Dim::Time),
    Key::new(
        "error_tol",
        KeyType::Number,
        "tolerance of the Zienkiewicz-Xie local error estimate |(beta - 1/6) dt^2 (a1 - a0)|_M \
         / |u1 - u0|_M of adaptive stepping: an increment above twice it is redone smaller, \
         the next size is dt (error_tol / error)^(1/3) within [dt / 2, 1.5 dt] (0: no error \
         control)",
    )
    .default(Default::Number(1e-2))
    .range(Range::NonNegative)
    .dim(Dim::None),
    Key::new(
        "max_rotation",
        KeyType::Number,
        "largest rotation of a cell in one increment, in radians (the rigid rotation best \
         fitting its nodes' motion): a converged increment that turns a cell by more is redone \
         at 0.9 dt max_rotation / rotation, and the next increment is kept below the same \
         bound (adaptive or not); generalized-alpha's trapezoidal work follows the strain \
         energy only while increments turn the bodies by small angles (a fast-spinning free \
         part gains energy: e.g. 0.05); absent: no limit",
    )
    .range(Range::Positive)
    .dim(Dim::None),
    Key::new(
        "energy_tol",
        KeyType::Number,
        "largest energy one increment may create, relative to the largest energy of the run: \
         a converged increment whose kinetic energy, internal and damping work and stored \
         penalty energy (1/2 f_n (-g) of the closed contact nodes) grow by more than the work \
         of the loads and supports plus this share is redone at 0.9 dt sqrt(energy_tol / \
         created) (at least dt / 4), and the next increment is kept below the same bound \
         (adaptive or not): penalty contact whose springs give back more than they stored (a \
         node released from deeper than it closed through, chatter) is resolved in time \
         instead of feeding the bodies; only increments in which contact forces act are \
         weighed (a run without contact is not touched); absent: 1e-3; 0: no control",
    )
    .range(Range::NonNegative)
    .dim(Dim::None),
];

/// `spring NODES [-> NODES] { .. }`: a spring and a dashpot from each node
/// to the ground or to a node of the second set.
pub static SPRING: [Key; 3] = [
    Key::new(
        "stiffness",
        KeyType::Number,
        "spring stiffness k of each node (or node pair of `spring a -> b`), in every direction \
         (force -k u; planar: for the thickness, axisymmetric: over 2 pi)",
    )
    .default(Default::Number(0.0))
    .range(Range::NonNegative)
    .dim(Dim::PenaltyNodal),
    Key::new(
        "damping",
        KeyType::Number,
        "dashpot coefficient c of each node (or node pair), in every direction (force -c v; \
         dynamic steps)",
    )
    .default(Default::Number(0.0))
    .range(Range::NonNegative)
    .dim(Dim::Dashpot),
    Key::new(
        "release_at",
        KeyType::Number,
        "time from which the links of `spring a -> b` are gone (a released part: a blade off its disc flies on with its velocity); no dashpot on a released link",
    )
    .range(Range::NonNegative)
    .dim(Dim::Time),
];

/// `rigid_body NODES { .. }`: the nodes move as one rigid body (planar: 3
/// dofs; 3d: 6 dofs).
pub static RIGID_BODY: [Key; 12] = [
    Key::new(
        "center",
        KeyType::Point(Components::Analysis),
        "the body's centre: its pilot node (translation, bearings, mass) and the point its rotation turns about",
    )
    .required("add `center = (x, y)` (3d: `(x, y, z)`)")
    .dim(Dim::Length),
    Key::new(
        "axis",
        KeyType::Point(P3),
        "3d: the axis of a prescribed `rotation` / `angular_velocity` (any length; default (0, 0, 1))",
    ),
    Key::new(
        "mass",
        KeyType::Number,
        "mass of the body at its centre, besides its nodes' own (planar: for the thickness)",
    )
    .default(Default::Number(0.0))
    .range(Range::NonNegative)
    .dim(Dim::Mass),
    Key::new(
        "inertia",
        KeyType::Number,
        "rotary inertia about the centre, besides its nodes' own (mass x length^2; planar: about the normal; 3d: the same about every axis)",
    )
    .default(Default::Number(0.0))
    .range(Range::NonNegative)
    .dim(Dim::Any),
    Key::new(
        "inertia_diagonal",
        KeyType::Numbers(P3),
        "3d: the inertia tensor's diagonal (Jxx, Jyy, Jzz) about the centre (instead of `inertia`; needs `mass`: carried by six tied point masses)",
    )
    .dim(Dim::Any),
    Key::new(
        "inertia_products",
        KeyType::Numbers(P3),
        "3d: the inertia tensor's off-diagonal terms (Jxy, Jyz, Jzx) (default 0)",
    )
    .dim(Dim::Any),
    Key::new(
        "rotation",
        KeyType::Number,
        "prescribed rotation theta(t), counter-clockwise (3d: about `axis`; time function); without it and `angular_velocity` the rotation is free (planar: under `moment`)",
    )
    .dim(Dim::AngleRadians),
    Key::new(
        "angular_velocity",
        KeyType::Number,
        "prescribed angular velocity omega(t) (time function, counter-clockwise), integrated from theta(0) = 0 (a ramp: theta sampled at 64 points per segment)",
    )
    .dim(Dim::Frequency),
    Key::new(
        "moment",
        KeyType::Number,
        "moment applied to a free planar rotation, counter-clockwise (time function; default 0; not in 3d)",
    )
    .dim(Dim::Any),
    Key::new(
        "stiffness",
        KeyType::Number,
        "bearing: a spring from the centre to the ground, every direction",
    )
    .default(Default::Number(0.0))
    .range(Range::NonNegative)
    .dim(Dim::PenaltyNodal),
    Key::new(
        "damping",
        KeyType::Number,
        "bearing: a dashpot from the centre to the ground (dynamic steps)",
    )
    .default(Default::Number(0.0))
    .range(Range::NonNegative)
    .dim(Dim::Dashpot),
    Key::new(
        "tie_stiffness",
        KeyType::Number,
        "stiffness of the spring tying each node to its place on the rigid body (a penalty: the nodes follow the rigid motion to |f| / k)",
    )
    .required("add `tie_stiffness = <force/length>` (e.g. 1e3 x the element stiffness)")
    .range(Range::Positive)
    .dim(Dim::PenaltyNodal),
];

/// `point_mass NODES { .. }`.
pub static POINT_MASS: [Key; 1] = [Key::new(
    "mass",
    KeyType::Number,
    "the mass at each node (planar: for the thickness, axisymmetric: over 2 pi; dynamic steps)",
)
.range(Range::Positive)
.dim(Dim::Mass)];

/// `newton { .. }` of a step.
pub static NEWTON: [Key; 6] = [
    Key::new("tol", KeyType::Number, "relative residual tolerance")
        .default(Default::Number(1e-8))
        .range(Range::Positive)
        .dim(Dim::None),
    Key::new(
        "tol_displacement",
        KeyType::Number,
        "relative displacement-correction tolerance",
    )
    .default(Default::Number(1e-8))
    .range(Range::Positive)
    .dim(Dim::None),
    Key::new("max_iter", KeyType::Integer, "iterations before a cutback")
        .default(Default::Integer(25))
        .range(Range::AtLeast(1)),
    Key::new("line_search", KeyType::Bool, "backtracking line search").default(Default::Bool(true)),
    Key::new(
        "predictor",
        KeyType::Bool,
        "start each increment from the linear extrapolation of the step's last two converged \
         states (kept only when its residual is smaller than the plain start's)",
    )
    .default(Default::Bool(true)),
    Key::new(
        "stabilize",
        KeyType::Number,
        "vanishing stabilization of the bodies held only by contact: springs of c x the mean \
         stiffness diagonal on the increment displacement, ramped to 0 at the step end \
         (bare `stabilize`: c = 1e-5)",
    )
    .range(Range::Positive)
    .dim(Dim::None),
];

/// `output { .. }`.
pub static OUTPUT: [Key; 5] = [
    Key::new(
        "every",
        KeyType::Integer,
        "write fields every n converged increments",
    )
    .default(Default::Integer(1))
    .range(Range::AtLeast(1)),
    Key::new(
        "fields",
        KeyType::Choice(&[
            "displacement",
            "stress",
            "strain",
            "von_mises",
            "reaction",
            "contact",
            "velocity",
            "acceleration",
        ]),
        "list of VTU fields `[displacement, stress, ..]` (velocity and acceleration: decks \
         with a dynamic step)",
    ),
    Key::new(
        "history",
        KeyType::Choice(&[
            "reaction(set)",
            "displacement(set)",
            "contact_force(set -> master)",
            "roughness(set)",
        ]),
        "list of history.csv columns: reaction sums, mean displacements and contact forces \
         (`<label>_x`, `_y`[, `_z`]); `roughness(set)`: the profile roughness of the set's \
         deformed nodes, detrended by the least-squares mean line (plane in 3d) of the heights \
         along the axis of the set's smallest extent: `<label>_Ra` (arithmetic mean \
         deviation), `_Rq` (root mean square), `_mean` (mean height); 2d weights are the \
         nodes' tributary lengths",
    ),
    Key::new(
        "thickness",
        KeyType::Choice(&["(body.faces, body.faces)"]),
        "thickness map of a sheet or tube between two face sets of one body (3d): at each node \
         the sum of its distances to both deformed faces; the VTU point field `thickness`, \
         `thickness.csv` (the first set's nodes by reference distance from the origin), the \
         history columns `thickness_min` and its reference position, and `thickness.svg` \
         from `ctc run`",
    ),
    Key::new(
        "format",
        KeyType::Choice(&["binary", "ascii"]),
        "how VTU files store their arrays: appended raw binary, zlib-compressed, or inline text",
    )
    .default(Default::Choice("binary")),
];

/// Every table with the block it describes, for the keyword reference
/// and for the tests that the parser accepts exactly these keys.
pub static ALL: &[(&str, &[Key])] = &[
    ("analysis", &ANALYSIS),
    ("material", &MATERIAL),
    ("material.elastic", &ELASTIC),
    ("material.neo_hookean", &ELASTIC),
    ("material.neo_hookean (moduli)", &NEO_HOOKEAN_MODULI),
    ("material.plastic", &PLASTIC),
    ("material.plastic.hardening = linear", &LINEAR_HARDENING),
    ("material.plastic.hardening = swift", &SWIFT_HARDENING),
    ("material.plastic.hardening = voce", &VOCE_HARDENING),
    (
        "material.plastic.hardening = johnson_cook",
        &JOHNSON_COOK_HARDENING,
    ),
    ("material.viscoplastic", &VISCOPLASTIC),
    ("material.norton_hoff", &NORTON_HOFF),
    ("pressure.control.strain_rate", &RATE_CONTROL),
    ("material.thermal", &MATERIAL_THERMAL),
    ("body", &BODY),
    ("body.thermal", &BODY_THERMAL),
    ("tool = plane", &PLANE),
    ("tool = polyline", &POLYLINE),
    ("tool = arc", &ARC),
    ("tool = circle", &CIRCLE),
    ("tool = nurbs", &NURBS),
    ("tool = plane (3d)", &PLANE_3D),
    ("tool = sphere", &SPHERE),
    ("tool = cylinder", &CYLINDER),
    ("tool = cone", &CONE),
    ("tool = torus", &TORUS),
    ("tool = iges", &IGES),
    ("tool = stl", &STL),
    ("tool.motion", &MOTION),
    ("contact", &CONTACT),
    ("contact.method = penalty", &PENALTY),
    ("contact.method = lagrange", &LAGRANGE),
    ("contact.method = augmented_lagrange", &AUGMENTED_LAGRANGE),
    ("contact.friction = coulomb", &COULOMB),
    ("contact.thermal", &CONTACT_THERMAL),
    ("contact.thermal.conductance = power", &POWER_CONDUCTANCE),
    ("step", &STEP),
    ("step.newton", &NEWTON),
    ("step.dynamic", &DYNAMIC),
    ("spring", &SPRING),
    ("point_mass", &POINT_MASS),
    ("rigid_body", &RIGID_BODY),
    ("output", &OUTPUT),
];
