//! `rectangle { origin size divisions grading element }`: an axis-aligned
//! rectangle of structured cells.

use super::{
    cell_product, count, grading, missing, Build, GeneratorDef, SetDecl, SetKind, ELEMENT,
};
use crate::ast::settings::Settings;
use crate::ast::Generator;
use crate::keys::{Components, Default, Dim, Key, KeyType, Range};
use crate::validate::Ctx;
use ctc_engine::mesh::generate::{self, MeshSpec};
use ctc_engine::mesh::{Mesh, MeshError};

/// The keys of `rectangle`.
pub static KEYS: [Key; 7] = [
    Key::new(
        "origin",
        KeyType::Point(Components::Two),
        "lower-left corner",
    )
    .default(Default::Numbers(&[0.0, 0.0]))
    .dim(Dim::Length),
    Key::new(
        "size",
        KeyType::Numbers(Components::Two),
        "width and height",
    )
    .required("add `size = (width, height)`")
    .range(Range::Positive)
    .labels(&["width", "height"])
    .dim(Dim::Length),
    Key::new(
        "divisions",
        KeyType::Integers(Components::Two),
        "number of cells along x and y",
    )
    .required("add `divisions = (nx, ny)`")
    .range(Range::AtLeast(1))
    .labels(&["divisions along x", "divisions along y"]),
    Key::new(
        "grading",
        KeyType::Gradings(Components::Two),
        "spacing of the divisions along x and y",
    )
    .default(Default::Uniform)
    .range(Range::Positive)
    .labels(&["grading ratio"]),
    ELEMENT,
    super::ORDER,
    super::INTEGRATION,
];

/// `rectangle`.
pub static RECTANGLE: GeneratorDef = GeneratorDef {
    name: "rectangle",
    doc: "axis-aligned rectangle [x0, x0 + width] x [y0, y0 + height] of structured cells \
          (tri3: each quad split along the diagonal pointing to the centre)",
    keys: &KEYS,
    sets: &[
        SetDecl::new("bottom", SetKind::Edges, "edges at y = y0"),
        SetDecl::new("right", SetKind::Edges, "edges at x = x0 + width"),
        SetDecl::new("top", SetKind::Edges, "edges at y = y0 + height"),
        SetDecl::new("left", SetKind::Edges, "edges at x = x0"),
        SetDecl::new("corner_bl", SetKind::Nodes, "bottom-left corner node"),
        SetDecl::new("corner_br", SetKind::Nodes, "bottom-right corner node"),
        SetDecl::new("corner_tr", SetKind::Nodes, "top-right corner node"),
        SetDecl::new("corner_tl", SetKind::Nodes, "top-left corner node"),
    ],
    open_sets: false,
    check: no_rules,
    cells,
    build: Build::Planar(build),
};

/// The rectangle's keys need no rule beyond their ranges.
fn no_rules(_: &Generator, _: &mut Ctx<'_>) {}

fn cells(s: &Settings) -> i64 {
    cell_product(s.integers("divisions").unwrap_or_default())
}

fn build(s: &Settings, inputs: &[Mesh]) -> Result<Mesh, MeshError> {
    super::with_order(s, &KEYS, build_linear(s, inputs)?, super::Arcs::None)
}

fn build_linear(s: &Settings, _inputs: &[Mesh]) -> Result<Mesh, MeshError> {
    let size = s
        .pair("size", &KEYS)
        .ok_or_else(|| missing("rectangle", "size"))?;
    let d = s
        .integers("divisions")
        .filter(|d| d.len() == 2)
        .ok_or_else(|| missing("rectangle", "divisions"))?;
    let g = s.gradings("grading", 2);
    generate::generate(&MeshSpec::Rectangle {
        origin: s.pair("origin", &KEYS).unwrap_or([0.0, 0.0]),
        size,
        divisions: [count(Some(d[0])), count(Some(d[1]))],
        grading: [grading(&g[0]), grading(&g[1])],
        kind: RECTANGLE.cell_kind(s),
    })
}
