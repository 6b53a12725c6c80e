//! `half_disc { .. }` and `quarter_disc { .. }`: polar-structured discs
//! (straight rays, a triangle fan at the centre, 2:1 ring coarsening).

use super::{
    cell_product, count, grading, missing, Build, GeneratorDef, SetDecl, SetKind, ELEMENT,
};
use crate::ast::settings::Settings;
use crate::ast::Generator;
use crate::keys::{Components, Default, Dim, Key, KeyType, Range};
use crate::validate::Ctx;
use ctc_engine::mesh::generate::{self, MeshSpec};
use ctc_engine::mesh::{Mesh, MeshError};

const CENTER: Key = Key::new(
    "center",
    KeyType::Point(Components::Two),
    "centre of the full circle",
)
.required("add `center = (x, y)`")
.dim(Dim::Length);
const RADIUS: Key = Key::new("radius", KeyType::Number, "radius")
    .required("add `radius = ..`")
    .range(Range::Positive)
    .dim(Dim::Length);
const RADIAL: Key = Key::new("radial", KeyType::Integer, "divisions along the radius")
    .required("add `radial = <radial divisions>`")
    .range(Range::AtLeast(1))
    .labels(&["radial divisions"]);
const RADIAL_GRADING: Key = Key::new(
    "radial_grading",
    KeyType::Grading,
    "radial spacing (ratio < 1 refines towards the arc)",
)
.default(Default::Uniform)
.range(Range::Positive)
.labels(&["grading ratio"]);
const CIRCUMFERENTIAL_GRADING: Key = Key::new(
    "circumferential_grading",
    KeyType::Grading,
    "spacing along the arc (`center(r)`, r > 1, refines towards the pole)",
)
.default(Default::Uniform)
.range(Range::Positive)
.labels(&["grading ratio"]);
const UPPER: Key = Key::new(
    "upper",
    KeyType::Bool,
    "`true`: the part above the centre; `false`: below (pole at -90 degrees)",
)
.default(Default::Bool(false));

/// The keys of a disc whose arc has `min` divisions at least.
const fn disc_keys(span: &'static str, min: i64) -> [Key; 10] {
    [
        CENTER,
        RADIUS,
        RADIAL,
        Key::new("circumferential", KeyType::Integer, span)
            .required("add `circumferential = <divisions along the arc>`")
            .range(Range::AtLeast(min))
            .labels(&["circumferential divisions"]),
        RADIAL_GRADING,
        CIRCUMFERENTIAL_GRADING,
        UPPER,
        ELEMENT,
        super::ORDER,
        super::INTEGRATION,
    ]
}

/// The keys of `half_disc`.
pub static HALF_KEYS: [Key; 10] = disc_keys("divisions along the half circle", 2);

/// The keys of `quarter_disc`.
pub static QUARTER_KEYS: [Key; 10] = disc_keys("divisions along the quarter circle", 1);

/// `half_disc`.
pub static HALF_DISC: GeneratorDef = GeneratorDef {
    name: "half_disc",
    doc: "half disc below (or above) its diameter",
    keys: &HALF_KEYS,
    sets: &[
        SetDecl::new("arc", SetKind::Edges, "the curved boundary"),
        SetDecl::new("flat", SetKind::Edges, "the diameter"),
        SetDecl::new("center", SetKind::Nodes, "the centre node"),
    ],
    open_sets: false,
    check: no_rules,
    cells,
    build: Build::Planar(build_half),
};

/// `quarter_disc`.
pub static QUARTER_DISC: GeneratorDef = GeneratorDef {
    name: "quarter_disc",
    doc: "quarter disc on the x >= center.x side, below (or above) the centre \
          (the axisymmetric half-section of a sphere)",
    keys: &QUARTER_KEYS,
    sets: &[
        SetDecl::new("arc", SetKind::Edges, "the curved boundary"),
        SetDecl::new("flat", SetKind::Edges, "the straight edge on y = center.y"),
        SetDecl::new("axis", SetKind::Edges, "the straight edge on x = center.x"),
        SetDecl::new("center", SetKind::Nodes, "the centre node"),
    ],
    open_sets: false,
    check: no_rules,
    cells,
    build: Build::Planar(build_quarter),
};

/// The discs' keys need no rule beyond their ranges.
fn no_rules(_: &Generator, _: &mut Ctx<'_>) {}

fn cells(s: &Settings) -> i64 {
    cell_product(
        ["radial", "circumferential"]
            .into_iter()
            .filter_map(|k| s.integer(k, &HALF_KEYS)),
    )
}

/// The common values of both discs.
struct Disc {
    center: [f64; 2],
    radius: f64,
    radial: usize,
    circumferential: usize,
    radial_grading: generate::Grading,
    circumferential_grading: generate::Grading,
    upper: bool,
}

fn disc(s: &Settings, keys: &[Key], name: &str) -> Result<Disc, MeshError> {
    Ok(Disc {
        center: s
            .pair("center", keys)
            .ok_or_else(|| missing(name, "center"))?,
        radius: s
            .number("radius", keys)
            .ok_or_else(|| missing(name, "radius"))?,
        radial: count(s.integer("radial", keys)),
        circumferential: count(s.integer("circumferential", keys)),
        radial_grading: grading(&s.grading("radial_grading")),
        circumferential_grading: grading(&s.grading("circumferential_grading")),
        upper: s.bool("upper", keys).unwrap_or(false),
    })
}

fn build_half(s: &Settings, _inputs: &[Mesh]) -> Result<Mesh, MeshError> {
    let d = disc(s, &HALF_KEYS, "half_disc")?;
    let arcs = super::Arcs::About([d.center[0], d.center[1], 0.0]);
    let linear = generate::generate(&MeshSpec::HalfDisc {
        center: d.center,
        radius: d.radius,
        radial: d.radial,
        circumferential: d.circumferential,
        radial_grading: d.radial_grading,
        circumferential_grading: d.circumferential_grading,
        upper: d.upper,
        kind: HALF_DISC.cell_kind(s),
    })?;
    super::with_order(s, &HALF_KEYS, linear, arcs)
}

fn build_quarter(s: &Settings, _inputs: &[Mesh]) -> Result<Mesh, MeshError> {
    let d = disc(s, &QUARTER_KEYS, "quarter_disc")?;
    let arcs = super::Arcs::About([d.center[0], d.center[1], 0.0]);
    let linear = generate::generate(&MeshSpec::QuarterDisc {
        center: d.center,
        radius: d.radius,
        radial: d.radial,
        circumferential: d.circumferential,
        radial_grading: d.radial_grading,
        circumferential_grading: d.circumferential_grading,
        upper: d.upper,
        kind: QUARTER_DISC.cell_kind(s),
    })?;
    super::with_order(s, &QUARTER_KEYS, linear, arcs)
}
