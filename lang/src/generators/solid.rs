//! Solid (3D) generators: `box`, `tube`, `cylinder` and `sphere_octant`
//! (`ctc_engine::mesh::generate::solid`), hex8 or tet4 cells. They are
//! accepted only in `dimension = 3d` analyses (and the planar generators
//! only in planar ones).

use super::{cell_product, count, grading, missing, Build, GeneratorDef, SetDecl, SetKind};
use crate::ast::settings::Settings;
use crate::ast::Generator;
use crate::keys::{Components, Default, Dim, Key, KeyType, Range};
use crate::validate::Ctx;
use ctc_engine::mesh::generate::solid;
use ctc_engine::mesh::{CellKind, Mesh, MeshError};

/// The `element = hex8 | tet4` key of the solid generators.
pub const SOLID_ELEMENT: Key = Key::new(
    "element",
    KeyType::Choice(&["hex8", "tet4"]),
    "cell type: trilinear hexahedra, or linear tetrahedra (each hexahedron split in six)",
)
.default(Default::Choice("hex8"));

/// The cell kind of a solid generator's `element` key.
fn solid_kind(s: &Settings, keys: &[Key]) -> CellKind {
    match s.choice("element", keys) {
        Some("tet4") => CellKind::Tet4,
        _ => CellKind::Hex8,
    }
}

/// The keys of `box`.
pub static BOX_KEYS: [Key; 7] = [
    Key::new(
        "origin",
        KeyType::Point(Components::Three),
        "corner with the smallest coordinates",
    )
    .default(Default::Numbers(&[0.0, 0.0, 0.0]))
    .dim(Dim::Length),
    Key::new(
        "size",
        KeyType::Numbers(Components::Three),
        "edge lengths along x, y and z",
    )
    .required("add `size = (a, b, c)`")
    .range(Range::Positive)
    .labels(&["size along x", "size along y", "size along z"])
    .dim(Dim::Length),
    Key::new(
        "divisions",
        KeyType::Integers(Components::Three),
        "number of cells along x, y and z",
    )
    .required("add `divisions = (nx, ny, nz)`")
    .range(Range::AtLeast(1))
    .labels(&[
        "divisions along x",
        "divisions along y",
        "divisions along z",
    ]),
    Key::new(
        "grading",
        KeyType::Gradings(Components::Three),
        "spacing of the divisions along x, y and z",
    )
    .default(Default::Uniform)
    .range(Range::Positive)
    .labels(&["grading ratio"]),
    SOLID_ELEMENT,
    super::ORDER,
    super::INTEGRATION,
];

/// `box`.
pub static BOX: GeneratorDef = GeneratorDef {
    name: "box",
    doc: "axis-aligned brick [x0, x0 + a] x [y0, y0 + b] x [z0, z0 + c] of structured cells \
          (3d analyses; tet4: each hexahedron split in six around its diagonal)",
    keys: &BOX_KEYS,
    sets: &[
        SetDecl::new("xmin", SetKind::Faces, "faces at x = x0"),
        SetDecl::new("xmax", SetKind::Faces, "faces at x = x0 + a"),
        SetDecl::new("ymin", SetKind::Faces, "faces at y = y0"),
        SetDecl::new("ymax", SetKind::Faces, "faces at y = y0 + b"),
        SetDecl::new("zmin", SetKind::Faces, "faces at z = z0"),
        SetDecl::new("zmax", SetKind::Faces, "faces at z = z0 + c"),
        SetDecl::new("origin", SetKind::Nodes, "the corner node at the origin"),
    ],
    open_sets: false,
    check: no_rules,
    cells: box_cells,
    build: Build::Solid(build_box),
};

fn no_rules(_: &Generator, _: &mut Ctx<'_>) {}

fn tet_factor(s: &Settings, keys: &[Key]) -> i64 {
    if solid_kind(s, keys) == CellKind::Tet4 {
        6
    } else {
        1
    }
}

fn box_cells(s: &Settings) -> i64 {
    cell_product(s.integers("divisions").unwrap_or_default())
        .saturating_mul(tet_factor(s, &BOX_KEYS))
}

fn triple(v: Option<Vec<f64>>) -> Option<[f64; 3]> {
    let v = v?;
    (v.len() == 3).then(|| [v[0], v[1], v[2]])
}

fn build_box(s: &Settings, inputs: &[Mesh]) -> Result<Mesh<3>, MeshError> {
    super::with_order(
        s,
        &BOX_KEYS,
        build_box_linear(s, inputs)?,
        super::Arcs::None,
    )
}

fn build_box_linear(s: &Settings, _inputs: &[Mesh]) -> Result<Mesh<3>, MeshError> {
    let size = triple(s.numbers("size", &BOX_KEYS)).ok_or_else(|| missing("box", "size"))?;
    let d = s
        .integers("divisions")
        .filter(|d| d.len() == 3)
        .ok_or_else(|| missing("box", "divisions"))?;
    let g = s.gradings("grading", 3);
    if g.len() != 3 {
        return Err(missing("box", "grading"));
    }
    solid::brick(
        triple(s.numbers("origin", &BOX_KEYS)).unwrap_or([0.0; 3]),
        size,
        [count(Some(d[0])), count(Some(d[1])), count(Some(d[2]))],
        [grading(&g[0]), grading(&g[1]), grading(&g[2])],
        solid_kind(s, &BOX_KEYS),
    )
}

/// The keys of `tube`.
pub static TUBE_KEYS: [Key; 12] = [
    Key::new("inner", KeyType::Number, "inner radius")
        .required("add `inner = <radius>`")
        .range(Range::Positive)
        .dim(Dim::Length),
    Key::new("outer", KeyType::Number, "outer radius (> inner)")
        .required("add `outer = <radius>`")
        .range(Range::Positive)
        .dim(Dim::Length),
    Key::new(
        "angle",
        KeyType::Number,
        "sector angle from the x axis about z, degrees (360: a ring)",
    )
    .default(Default::Number(360.0))
    .range(Range::Positive),
    Key::new("height", KeyType::Number, "length along z from z = 0")
        .required("add `height = <length>`")
        .range(Range::Positive)
        .dim(Dim::Length),
    Key::new(
        "divisions",
        KeyType::Integers(Components::Three),
        "radial, circumferential and axial divisions",
    )
    .required("add `divisions = (radial, circumferential, axial)`")
    .range(Range::AtLeast(1))
    .labels(&[
        "radial divisions",
        "circumferential divisions",
        "axial divisions",
    ]),
    Key::new(
        "radial_grading",
        KeyType::Grading,
        "spacing of the radial divisions",
    )
    .default(Default::Uniform)
    .range(Range::Positive),
    Key::new(
        "imperfection",
        KeyType::Number,
        "amplitude a of a seeded geometric imperfection: every node moves radially (the whole \
         wall alike) by a cos(n theta) sin(m pi z / height), n = `imperfection_waves`, m = \
         `imperfection_half_waves` (m = 0: uniform along z); the sets are those of the perfect \
         tube; |a| < inner",
    )
    .default(Default::Number(0.0))
    .dim(Dim::Length),
    Key::new(
        "imperfection_waves",
        KeyType::Integer,
        "circumferential waves n of the imperfection (0: axisymmetric; a sector with symmetry \
         planes keeps a cos(n theta) shape when n times its angle is a multiple of 180 degrees)",
    )
    .default(Default::Integer(0))
    .range(Range::AtLeast(0))
    .labels(&["imperfection waves"]),
    Key::new(
        "imperfection_half_waves",
        KeyType::Integer,
        "axial half-waves m of the imperfection over the height (0: uniform along z)",
    )
    .default(Default::Integer(1))
    .range(Range::AtLeast(0))
    .labels(&["imperfection half-waves"]),
    SOLID_ELEMENT,
    super::ORDER,
    super::INTEGRATION,
];

/// `tube`.
pub static TUBE: GeneratorDef = GeneratorDef {
    name: "tube",
    doc: "sector of the tube inner <= r <= outer about the z axis, 0 <= z <= height, \
          structured in (r, theta, z) (3d analyses)",
    keys: &TUBE_KEYS,
    sets: &[
        SetDecl::new("inner", SetKind::Faces, "faces at r = inner"),
        SetDecl::new("outer", SetKind::Faces, "faces at r = outer"),
        SetDecl::new("zmin", SetKind::Faces, "faces at z = 0"),
        SetDecl::new("zmax", SetKind::Faces, "faces at z = height"),
        SetDecl::new("start", SetKind::Faces, "faces at theta = 0 (open sectors)")
            .when(open_sector),
        SetDecl::new(
            "end",
            SetKind::Faces,
            "faces at theta = angle (open sectors)",
        )
        .when(open_sector),
    ],
    open_sets: false,
    check: no_rules,
    cells: tube_cells,
    build: Build::Solid(build_tube),
};

fn open_sector(s: &Settings) -> bool {
    s.number("angle", &TUBE_KEYS).is_none_or(|a| a < 360.0)
}

fn tube_cells(s: &Settings) -> i64 {
    cell_product(s.integers("divisions").unwrap_or_default())
        .saturating_mul(tet_factor(s, &TUBE_KEYS))
}

fn build_tube(s: &Settings, inputs: &[Mesh]) -> Result<Mesh<3>, MeshError> {
    let mut mesh = super::with_order(
        s,
        &TUBE_KEYS,
        build_tube_linear(s, inputs)?,
        super::Arcs::Axis(2),
    )?;
    // the imperfection moves every node, the quadratic cells' new nodes too
    let amplitude = s.number("imperfection", &TUBE_KEYS).unwrap_or(0.0);
    if amplitude != 0.0 {
        let whole = |k: &str| {
            s.integer(k, &TUBE_KEYS)
                .and_then(|v| usize::try_from(v).ok())
                .unwrap_or(0)
        };
        let num = |k: &str| s.number(k, &TUBE_KEYS).ok_or_else(|| missing("tube", k));
        solid::tube_imperfection(
            &mut mesh,
            amplitude,
            whole("imperfection_waves"),
            whole("imperfection_half_waves"),
            num("height")?,
            num("inner")?,
        )?;
    }
    Ok(mesh)
}

fn build_tube_linear(s: &Settings, _inputs: &[Mesh]) -> Result<Mesh<3>, MeshError> {
    let num = |k: &str| s.number(k, &TUBE_KEYS).ok_or_else(|| missing("tube", k));
    let d = s
        .integers("divisions")
        .filter(|d| d.len() == 3)
        .ok_or_else(|| missing("tube", "divisions"))?;
    solid::tube(
        num("inner")?,
        num("outer")?,
        num("angle")?,
        num("height")?,
        [count(Some(d[0])), count(Some(d[1])), count(Some(d[2]))],
        grading(&s.grading("radial_grading")),
        solid_kind(s, &TUBE_KEYS),
    )
}

/// The keys of `cylinder`.
pub static CYLINDER_KEYS: [Key; 7] = [
    Key::new("radius", KeyType::Number, "radius")
        .required("add `radius = <radius>`")
        .range(Range::Positive)
        .dim(Dim::Length),
    Key::new(
        "angle",
        KeyType::Number,
        "sector angle from the x axis about z, degrees: 90, 180, 270 or 360",
    )
    .default(Default::Number(360.0))
    .range(Range::Positive),
    Key::new("height", KeyType::Number, "length along z from z = 0")
        .required("add `height = <length>`")
        .range(Range::Positive)
        .dim(Dim::Length),
    Key::new(
        "divisions",
        KeyType::Integers(Components::Three),
        "core (cells along each edge of the square core of a quarter), ring (cells from \
         the core to the surface) and axial divisions",
    )
    .required("add `divisions = (core, ring, axial)`")
    .range(Range::AtLeast(1))
    .labels(&["core divisions", "ring divisions", "axial divisions"]),
    SOLID_ELEMENT,
    super::ORDER,
    super::INTEGRATION,
];

/// `cylinder`.
pub static CYLINDER: GeneratorDef = GeneratorDef {
    name: "cylinder",
    doc: "solid cylinder r <= radius about the z axis, 0 <= z <= height (or a sector of whole \
          quarters), hex-structured with an O-grid: a square core of half the radius and a \
          ring blended to the surface, no degenerate cell on the axis (3d analyses)",
    keys: &CYLINDER_KEYS,
    sets: &[
        SetDecl::new("outer", SetKind::Faces, "faces at r = radius"),
        SetDecl::new("zmin", SetKind::Faces, "faces at z = 0"),
        SetDecl::new("zmax", SetKind::Faces, "faces at z = height"),
        SetDecl::new("start", SetKind::Faces, "faces at theta = 0 (open sectors)")
            .when(open_cylinder),
        SetDecl::new(
            "end",
            SetKind::Faces,
            "faces at theta = angle (open sectors)",
        )
        .when(open_cylinder),
    ],
    open_sets: false,
    check: no_rules,
    cells: cylinder_cells,
    build: Build::Solid(build_cylinder),
};

fn open_cylinder(s: &Settings) -> bool {
    s.number("angle", &CYLINDER_KEYS).is_none_or(|a| a < 360.0)
}

fn cylinder_cells(s: &Settings) -> i64 {
    let d = s.integers("divisions").unwrap_or_default();
    let get = |k: usize| d.get(k).copied().unwrap_or(1);
    let quarters = s
        .number("angle", &CYLINDER_KEYS)
        .map_or(4, |a| ((a / 90.0).round() as i64).clamp(1, 4));
    // per quarter and layer: core m^2 plus two rings of m x ring cells
    let (m, ring) = (get(0), get(1));
    m.saturating_mul(m.saturating_add(ring.saturating_mul(2)))
        .saturating_mul(get(2))
        .saturating_mul(quarters)
        .saturating_mul(tet_factor(s, &CYLINDER_KEYS))
}

fn build_cylinder(s: &Settings, inputs: &[Mesh]) -> Result<Mesh<3>, MeshError> {
    super::with_order(
        s,
        &CYLINDER_KEYS,
        build_cylinder_linear(s, inputs)?,
        super::Arcs::Axis(2),
    )
}

fn build_cylinder_linear(s: &Settings, _inputs: &[Mesh]) -> Result<Mesh<3>, MeshError> {
    let num = |k: &str| {
        s.number(k, &CYLINDER_KEYS)
            .ok_or_else(|| missing("cylinder", k))
    };
    let d = s
        .integers("divisions")
        .filter(|d| d.len() == 3)
        .ok_or_else(|| missing("cylinder", "divisions"))?;
    solid::cylinder(
        num("radius")?,
        num("angle")?,
        num("height")?,
        [count(Some(d[0])), count(Some(d[1])), count(Some(d[2]))],
        solid_kind(s, &CYLINDER_KEYS),
    )
}

/// The keys of `sphere_octant`.
pub static SPHERE_KEYS: [Key; 8] = [
    Key::new("inner", KeyType::Number, "inner radius")
        .required("add `inner = <radius>`")
        .range(Range::Positive)
        .dim(Dim::Length),
    Key::new("outer", KeyType::Number, "outer radius (> inner)")
        .required("add `outer = <radius>`")
        .range(Range::Positive)
        .dim(Dim::Length),
    Key::new("radial", KeyType::Integer, "radial divisions")
        .required("add `radial = <divisions>`")
        .range(Range::AtLeast(1)),
    Key::new(
        "tangential",
        KeyType::Integer,
        "divisions along each edge of the three cube-sphere patches",
    )
    .required("add `tangential = <divisions>`")
    .range(Range::AtLeast(1)),
    Key::new(
        "radial_grading",
        KeyType::Grading,
        "spacing of the radial divisions",
    )
    .default(Default::Uniform)
    .range(Range::Positive),
    SOLID_ELEMENT,
    super::ORDER,
    super::INTEGRATION,
];

/// `sphere_octant`.
pub static SPHERE_OCTANT: GeneratorDef = GeneratorDef {
    name: "sphere_octant",
    doc: "octant x, y, z >= 0 of the spherical shell inner <= r <= outer, hex-structured as \
          a cubed sphere (three patches, no pole) (3d analyses)",
    keys: &SPHERE_KEYS,
    sets: &[
        SetDecl::new("inner", SetKind::Faces, "faces at r = inner"),
        SetDecl::new("outer", SetKind::Faces, "faces at r = outer"),
        SetDecl::new("xmin", SetKind::Faces, "faces in the plane x = 0"),
        SetDecl::new("ymin", SetKind::Faces, "faces in the plane y = 0"),
        SetDecl::new("zmin", SetKind::Faces, "faces in the plane z = 0"),
    ],
    open_sets: false,
    check: no_rules,
    cells: sphere_cells,
    build: Build::Solid(build_sphere),
};

fn sphere_cells(s: &Settings) -> i64 {
    let t = s.integer("tangential", &SPHERE_KEYS).unwrap_or(1);
    let r = s.integer("radial", &SPHERE_KEYS).unwrap_or(1);
    cell_product([3, t, t, r]).saturating_mul(tet_factor(s, &SPHERE_KEYS))
}

fn build_sphere(s: &Settings, inputs: &[Mesh]) -> Result<Mesh<3>, MeshError> {
    super::with_order(
        s,
        &SPHERE_KEYS,
        build_sphere_linear(s, inputs)?,
        super::Arcs::About([0.0; 3]),
    )
}

fn build_sphere_linear(s: &Settings, _inputs: &[Mesh]) -> Result<Mesh<3>, MeshError> {
    let num = |k: &str| {
        s.number(k, &SPHERE_KEYS)
            .ok_or_else(|| missing("sphere_octant", k))
    };
    let int = |k: &str| {
        s.integer(k, &SPHERE_KEYS)
            .ok_or_else(|| missing("sphere_octant", k))
    };
    solid::sphere_octant(
        num("inner")?,
        num("outer")?,
        count(Some(int("radial")?)),
        count(Some(int("tangential")?)),
        grading(&s.grading("radial_grading")),
        solid_kind(s, &SPHERE_KEYS),
    )
}
