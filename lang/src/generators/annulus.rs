//! `annulus { .. }`: an annular sector (or full ring) of structured cells.

use super::{
    cell_product, count, grading, missing, Build, GeneratorDef, SetDecl, SetKind, ELEMENT,
};
use crate::ast::settings::Settings;
use crate::ast::{num, Generator};
use crate::diagnostics::Diagnostic;
use crate::keys::{Components, Default, Dim, Key, KeyType, Range};
use crate::validate::Ctx;
use ctc_engine::mesh::generate::{self, MeshSpec};
use ctc_engine::mesh::{Mesh, MeshError};

/// The keys of `annulus`.
pub static KEYS: [Key; 11] = [
    Key::new("center", KeyType::Point(Components::Two), "centre")
        .required("add `center = (x, y)`")
        .dim(Dim::Length),
    Key::new("inner", KeyType::Number, "inner radius")
        .required("add `inner = <inner radius>`")
        .range(Range::Positive)
        .labels(&["inner radius"])
        .dim(Dim::Length),
    Key::new("outer", KeyType::Number, "outer radius (> inner)")
        .required("add `outer = <outer radius>`")
        .dim(Dim::Length),
    Key::new(
        "start",
        KeyType::Number,
        "start angle, counter-clockwise from x",
    )
    .default(Default::Number(0.0))
    .dim(Dim::AngleDegrees),
    Key::new(
        "end",
        KeyType::Number,
        "end angle (> start, at most start + 360: 360 apart is a full ring)",
    )
    .default(Default::Number(360.0))
    .dim(Dim::AngleDegrees),
    Key::new("radial", KeyType::Integer, "divisions across the ring")
        .required("add `radial = <radial divisions>`")
        .range(Range::AtLeast(1))
        .labels(&["radial divisions"]),
    Key::new(
        "circumferential",
        KeyType::Integer,
        "divisions along the ring (>= 3 for a full ring, each < 180 degrees)",
    )
    .required("add `circumferential = <divisions along the arc>`"),
    Key::new("radial_grading", KeyType::Grading, "radial spacing")
        .default(Default::Uniform)
        .range(Range::Positive)
        .labels(&["grading ratio"]),
    ELEMENT,
    super::ORDER,
    super::INTEGRATION,
];

/// `annulus`.
pub static ANNULUS: GeneratorDef = GeneratorDef {
    name: "annulus",
    doc: "annular sector between two radii, from `start` to `end` degrees",
    keys: &KEYS,
    sets: &[
        SetDecl::new("inner", SetKind::Edges, "the inner arc"),
        SetDecl::new("outer", SetKind::Edges, "the outer arc"),
        SetDecl::new(
            "start",
            SetKind::Edges,
            "the radial edge at `start` (sectors only)",
        )
        .when(partial),
        SetDecl::new(
            "end",
            SetKind::Edges,
            "the radial edge at `end` (sectors only)",
        )
        .when(partial),
    ],
    open_sets: false,
    check,
    cells,
    build: Build::Planar(build),
};

/// Start and end angles (defaults 0 and 360).
fn angles(s: &Settings) -> (f64, f64) {
    (
        s.number("start", &KEYS).unwrap_or(0.0),
        s.number("end", &KEYS).unwrap_or(360.0),
    )
}

/// Whether the annulus is a sector (not a full ring).
fn partial(s: &Settings) -> bool {
    let (a, b) = angles(s);
    (b - a - 360.0).abs() > 1e-9
}

/// Rules of the annulus: outer > inner, a sweep in (0, 360], enough
/// circumferential divisions, each under 180 degrees.
fn check(g: &Generator, ctx: &mut Ctx<'_>) {
    outer_exceeds_inner(g, ctx);
    sweep_in_range(g, ctx);
    circumferential_divisions_fit(g, ctx);
}

/// `outer > inner`.
fn outer_exceeds_inner(g: &Generator, ctx: &mut Ctx<'_>) {
    let s = &g.settings;
    if let (Some(i), Some(o)) = (s.spanned_number("inner"), s.spanned_number("outer")) {
        if o.value <= i.value && i.value > 0.0 {
            ctx.err(Diagnostic::error(
                "the outer radius must be larger than the inner radius",
                o.span,
                format!("outer = {} <= inner = {}", num(o.value), num(i.value)),
            ));
        }
    }
}

/// `start < end <= start + 360`.
fn sweep_in_range(g: &Generator, ctx: &mut Ctx<'_>) {
    let s = &g.settings;
    let (a, b) = angles(s);
    let at = s.span("end").or(s.span("start")).unwrap_or(g.name.span);
    if b <= a {
        ctx.err(Diagnostic::error(
            "the annulus `end` angle must be larger than `start`",
            at,
            format!("start = {}, end = {}", num(a), num(b)),
        ));
    } else if b - a > 360.0 + 1e-9 {
        ctx.err(Diagnostic::error(
            "an annulus spans at most 360 degrees",
            at,
            format!("end - start = {}", num(b - a)),
        ));
    }
}

/// At least 3 divisions for a full ring (1 for a sector), each spanning
/// less than 180 degrees.
fn circumferential_divisions_fit(g: &Generator, ctx: &mut Ctx<'_>) {
    let s = &g.settings;
    let c = s.spanned_integer("circumferential");
    let min = if partial(s) { 1 } else { 3 };
    ctx.at_least(&c, min, "circumferential divisions");
    let (a, b) = angles(s);
    if let Some(c) = c.filter(|c| c.value >= 1) {
        let sweep = b - a;
        if sweep > 0.0 && sweep / c.value as f64 >= 180.0 {
            ctx.err(Diagnostic::error(
                "each circumferential division must span less than 180 degrees",
                c.span,
                format!("{} division(s) over {} degrees", c.value, num(sweep)),
            ));
        }
    }
}

fn cells(s: &Settings) -> i64 {
    cell_product(
        ["radial", "circumferential"]
            .into_iter()
            .filter_map(|k| s.integer(k, &KEYS)),
    )
}

fn build(s: &Settings, inputs: &[Mesh]) -> Result<Mesh, MeshError> {
    let [x, y] = s.pair("center", &KEYS).unwrap_or([0.0, 0.0]);
    super::with_order(
        s,
        &KEYS,
        build_linear(s, inputs)?,
        super::Arcs::About([x, y, 0.0]),
    )
}

fn build_linear(s: &Settings, _inputs: &[Mesh]) -> Result<Mesh, MeshError> {
    let (start_angle, end_angle) = angles(s);
    generate::generate(&MeshSpec::Annulus {
        center: s
            .pair("center", &KEYS)
            .ok_or_else(|| missing("annulus", "center"))?,
        inner: s
            .number("inner", &KEYS)
            .ok_or_else(|| missing("annulus", "inner"))?,
        outer: s
            .number("outer", &KEYS)
            .ok_or_else(|| missing("annulus", "outer"))?,
        start_angle,
        end_angle,
        radial: count(s.integer("radial", &KEYS)),
        circumferential: count(s.integer("circumferential", &KEYS)),
        radial_grading: grading(&s.grading("radial_grading")),
        kind: ANNULUS.cell_kind(s),
    })
}
