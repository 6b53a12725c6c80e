//! Solid (3D) generators swept from a planar mesh
//! (`ctc_engine::mesh::generate::sweep`): `extrude` along z and `revolve`
//! about the z axis. The planar mesh is any planar generator or a gmsh
//! file of triangles / quadrangles; quad4 cells sweep into hex8, tri3 cells
//! into tet4 (three per prism, conforming). The planar mesh's edge sets
//! become face sets of the same name, its node sets node sets, so the
//! sets are only known once it is built (`open_sets`).

use super::{cell_product, count, grading, missing, Build, GeneratorDef, SetDecl, SetKind};
use crate::ast::settings::Settings;
use crate::ast::{Generator, MeshDef};
use crate::diagnostics::Diagnostic;
use crate::keys::{Default, Dim, Key, KeyType, Range};
use crate::validate::Ctx;
use ctc_engine::mesh::generate::sweep;
use ctc_engine::mesh::{Mesh, MeshError};

/// The keys of `extrude`.
pub static EXTRUDE_KEYS: [Key; 6] = [
    Key::new(
        "base",
        KeyType::Mesh,
        "the planar mesh to extrude (a planar generator or `file \"section.msh\"`), in the \
         plane z = 0",
    )
    .required("add e.g. `base = rectangle { size = (1, 1)  divisions = (10, 10) }`"),
    Key::new("length", KeyType::Number, "extrusion length along z")
        .required("add `length = <length>`")
        .range(Range::Positive)
        .dim(Dim::Length),
    Key::new("layers", KeyType::Integer, "divisions along z")
        .required("add `layers = <number of layers>`")
        .range(Range::AtLeast(1)),
    Key::new("grading", KeyType::Grading, "spacing of the layers")
        .default(Default::Uniform)
        .range(Range::Positive),
    super::ORDER,
    super::INTEGRATION,
];

/// `extrude`.
pub static EXTRUDE: GeneratorDef = GeneratorDef {
    name: "extrude",
    doc: "a planar mesh extruded along z from z = 0 (quad4 -> hex8, tri3 -> tet4); its edge \
          sets become face sets, its node sets node sets (3d analyses)",
    keys: &EXTRUDE_KEYS,
    sets: &[
        SetDecl::new("zmin", SetKind::Faces, "faces at z = 0"),
        SetDecl::new("zmax", SetKind::Faces, "faces at z = length"),
    ],
    open_sets: true,
    check: base_is_planar,
    cells: extrude_cells,
    build: Build::Solid(build_extrude),
};

/// The keys of `revolve`.
pub static REVOLVE_KEYS: [Key; 5] = [
    Key::new(
        "section",
        KeyType::Mesh,
        "the planar mesh to revolve: x is the radius (>= 0; tri3 cells may touch the axis), y the \
         axial coordinate (z in 3d)",
    )
    .required(
        "add e.g. `section = rectangle { origin = (1, 0)  size = (1, 1)  divisions = (4, 4) }`",
    ),
    Key::new(
        "angle",
        KeyType::Number,
        "angle of revolution about z from the x axis, degrees (360: a closed ring)",
    )
    .default(Default::Number(360.0))
    .range(Range::Positive),
    Key::new("segments", KeyType::Integer, "divisions of the angle")
        .required("add `segments = <number of divisions of the angle>`")
        .range(Range::AtLeast(1)),
    super::ORDER,
    super::INTEGRATION,
];

/// `revolve`.
pub static REVOLVE: GeneratorDef = GeneratorDef {
    name: "revolve",
    doc: "a planar section (x = radius >= 0, y = axial) revolved about the z axis \
          (quad4 -> hex8, tri3 -> tet4; tri3 cells may reach the axis, where their nodes are \
          kept once); its edge sets become face sets, its node sets node sets (3d analyses)",
    keys: &REVOLVE_KEYS,
    sets: &[
        SetDecl::new("start", SetKind::Faces, "faces at angle 0 (open sectors)"),
        SetDecl::new(
            "end",
            SetKind::Faces,
            "faces at the end angle (open sectors)",
        ),
    ],
    open_sets: true,
    check: section_is_planar,
    cells: revolve_cells,
    build: Build::Solid(build_revolve),
};

/// `base` is a planar mesh, and its own settings are valid.
fn base_is_planar(g: &Generator, ctx: &mut Ctx<'_>) {
    input_is_planar(g, "base", ctx);
}

/// `section` is a planar mesh, and its own settings are valid; the angle
/// is at most a full turn.
fn section_is_planar(g: &Generator, ctx: &mut Ctx<'_>) {
    input_is_planar(g, "section", ctx);
    if let Some(a) = g.settings.get("angle") {
        if let crate::ast::settings::SettingValue::Number(x) = a.value.value {
            if x > 360.0 {
                ctx.err(
                    Diagnostic::error(
                        format!("the angle of `revolve` is at most 360 degrees, got {x}"),
                        a.value.span,
                        "more than a full turn",
                    )
                    .with_help("use `angle = 360` for a closed ring"),
                );
            }
        }
    }
}

fn input_is_planar(g: &Generator, key: &str, ctx: &mut Ctx<'_>) {
    let Some(m) = g.settings.mesh(key) else {
        return;
    };
    if let MeshDef::Generator(inner) = &m.value {
        if inner.def.build.is_solid() {
            ctx.err(
                Diagnostic::error(
                    format!(
                        "the {key} of `{}` must be a planar mesh, but `{}` makes a solid one",
                        g.name.name, inner.name.name
                    ),
                    inner.name.span,
                    "a solid generator",
                )
                .with_help("use a planar generator (`rectangle`, `annulus`, ..) or a gmsh file of triangles / quadrangles"),
            );
            return;
        }
        crate::validate::bodies::generator_settings_valid(inner, ctx);
        input_is_linear(g, inner, key, ctx);
    }
}

/// The swept mesh is linear: `order = 2` goes on the sweep (which lifts
/// the swept hex8 / tet4 cells), not on its planar input.
fn input_is_linear(g: &Generator, inner: &Generator, key: &str, ctx: &mut Ctx<'_>) {
    if inner.settings.integer("order", inner.def.keys) != Some(2) {
        return;
    }
    for k in ["order", "integration"] {
        if let Some(span) = inner.settings.span(k) {
            ctx.err(
                Diagnostic::error(
                    format!(
                        "the {key} of `{}` must be linear: `{k}` goes on `{}` itself",
                        g.name.name, g.name.name
                    ),
                    span,
                    "on the planar input",
                )
                .with_help(format!(
                    "move `{k}` out of `{}` into `{} {{ .. }}`: the swept hex8 / tet4 cells are \
                     lifted to hex20 / tet10",
                    inner.name.name, g.name.name
                )),
            );
        }
    }
}

/// Cells of the planar input (0 for a file: known once read), or `None`.
fn input_cells(s: &Settings, key: &str) -> i64 {
    match s.mesh(key).map(|m| &m.value) {
        // a triangle's prism makes three tetrahedra
        Some(MeshDef::Generator(inner)) => (inner.def.cells)(&inner.settings).saturating_mul(3),
        _ => 0,
    }
}

fn extrude_cells(s: &Settings) -> i64 {
    cell_product([
        input_cells(s, "base"),
        s.integer("layers", &EXTRUDE_KEYS).unwrap_or(1),
    ])
}

fn revolve_cells(s: &Settings) -> i64 {
    cell_product([
        input_cells(s, "section"),
        s.integer("segments", &REVOLVE_KEYS).unwrap_or(1),
    ])
}

fn build_extrude(s: &Settings, inputs: &[Mesh]) -> Result<Mesh<3>, MeshError> {
    super::with_order(
        s,
        &EXTRUDE_KEYS,
        build_extrude_linear(s, inputs)?,
        super::Arcs::None,
    )
}

fn build_extrude_linear(s: &Settings, inputs: &[Mesh]) -> Result<Mesh<3>, MeshError> {
    let base = inputs.first().ok_or_else(|| missing("extrude", "base"))?;
    sweep::extrude(
        base,
        s.number("length", &EXTRUDE_KEYS)
            .ok_or_else(|| missing("extrude", "length"))?,
        count(s.integer("layers", &EXTRUDE_KEYS)),
        grading(&s.grading("grading")),
    )
}

fn build_revolve(s: &Settings, inputs: &[Mesh]) -> Result<Mesh<3>, MeshError> {
    super::with_order(
        s,
        &REVOLVE_KEYS,
        build_revolve_linear(s, inputs)?,
        super::Arcs::Axis(2),
    )
}

fn build_revolve_linear(s: &Settings, inputs: &[Mesh]) -> Result<Mesh<3>, MeshError> {
    let section = inputs
        .first()
        .ok_or_else(|| missing("revolve", "section"))?;
    sweep::revolve(
        section,
        s.number("angle", &REVOLVE_KEYS)
            .ok_or_else(|| missing("revolve", "angle"))?,
        count(s.integer("segments", &REVOLVE_KEYS)),
    )
}
