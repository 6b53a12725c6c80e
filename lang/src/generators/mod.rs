//! The mesh generator registry: each built-in generator is one
//! declarative [`GeneratorDef`] — its keys (types, defaults, ranges,
//! dimensions, meaning), the named sets it produces, the rules that relate
//! its keys, and the function that builds the mesh. Parsing
//! ([`crate::parse::body`]), validation ([`crate::validate::bodies`]),
//! lowering ([`crate::lower::mesh`]) and the keyword reference all read the
//! entry, so a new generator is one file here plus one line in
//! [`REGISTRY`].
//!
//! Points and tuples declare their number of components
//! ([`crate::keys::Components`]), and a key of type
//! [`crate::keys::KeyType::Mesh`] takes another mesh as input (built first
//! and handed to [`GeneratorDef::build`] in key order): the shape a 3D
//! extrusion or revolution of a 2D mesh needs.

pub mod annulus;
pub mod disc;
pub mod rectangle;
pub mod solid;
pub mod sweep;

use crate::ast::settings::Settings;
use crate::ast::Generator;
use crate::keys::{Default, Key, KeyType, Range};
use crate::validate::Ctx;
use ctc_engine::mesh::{CellKind, Mesh, MeshError};
use std::collections::BTreeMap;
use std::fmt;

/// Whether a set provides edges (and their nodes) or only nodes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SetKind {
    /// Boundary edges and their nodes.
    Edges,
    /// Nodes only.
    Nodes,
    /// Boundary faces of a solid mesh and their nodes (they play the
    /// role edges play in planar meshes: pressure, contact).
    Faces,
}

/// A named set a generator creates.
#[derive(Debug, Clone, Copy)]
pub struct SetDecl {
    /// Name (referenced as `body.name`).
    pub name: &'static str,
    /// Edges or nodes.
    pub kind: SetKind,
    /// What it is.
    pub doc: &'static str,
    /// Present only when this holds (e.g. `start`/`end` of a partial ring).
    pub when: Option<fn(&Settings) -> bool>,
}

impl SetDecl {
    /// A set always present.
    pub const fn new(name: &'static str, kind: SetKind, doc: &'static str) -> SetDecl {
        SetDecl {
            name,
            kind,
            doc,
            when: None,
        }
    }

    /// A set present only when `when` holds.
    pub const fn when(mut self, when: fn(&Settings) -> bool) -> SetDecl {
        self.when = Some(when);
        self
    }
}

/// One built-in mesh generator.
pub struct GeneratorDef {
    /// Name in the deck (`mesh = <name> { .. }`).
    pub name: &'static str,
    /// What it meshes (one line).
    pub doc: &'static str,
    /// Its keys, in the order they are read and documented.
    pub keys: &'static [Key],
    /// The sets it creates.
    pub sets: &'static [SetDecl],
    /// Whether further sets are known only once the mesh is built (the
    /// sets of an input mesh): then any set name is accepted by validation
    /// and checked against the built mesh.
    pub open_sets: bool,
    /// Rules relating its keys, beyond each key's range (those are checked
    /// from the table).
    pub check: fn(&Generator, &mut Ctx<'_>),
    /// Number of cells it will make (checked against
    /// [`crate::validate::MAX_CELLS`] before anything is built).
    pub cells: fn(&Settings) -> i64,
    /// Builds the mesh from validated settings; `inputs` are the built
    /// meshes of its [`KeyType::Mesh`] keys, in key order.
    pub build: Build,
}

/// How a generator builds its mesh: planar (2D analyses) or solid (`3d`).
#[derive(Clone, Copy)]
pub enum Build {
    /// A planar mesh.
    Planar(fn(&Settings, &[Mesh]) -> Result<Mesh, MeshError>),
    /// A solid (3D) mesh.
    Solid(fn(&Settings, &[Mesh]) -> Result<Mesh<3>, MeshError>),
}

impl Build {
    /// Whether the generator makes a solid mesh.
    pub fn is_solid(&self) -> bool {
        matches!(self, Build::Solid(_))
    }
}

impl fmt::Debug for GeneratorDef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "GeneratorDef({})", self.name)
    }
}

impl PartialEq for GeneratorDef {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

impl GeneratorDef {
    /// The sets this generator creates with `settings`, plus the built-in
    /// `boundary` and `all`; `None` when they are only known once built.
    pub fn set_kinds(&self, settings: &Settings) -> Option<BTreeMap<String, SetKind>> {
        if self.open_sets {
            return None;
        }
        let mut m = BTreeMap::new();
        for s in self.sets {
            if s.when.is_none_or(|w| w(settings)) {
                m.insert(s.name.to_string(), s.kind);
            }
        }
        add_builtin_sets(&mut m);
        Some(m)
    }

    /// The cell kind of the `element` key.
    pub fn cell_kind(&self, settings: &Settings) -> CellKind {
        match settings.choice("element", self.keys) {
            Some("tri3") => CellKind::Tri3,
            _ => CellKind::Quad4,
        }
    }
}

/// Adds the sets every body has: `boundary` (edges) and `all` (nodes).
pub fn add_builtin_sets(m: &mut BTreeMap<String, SetKind>) {
    m.insert("boundary".to_string(), SetKind::Edges);
    m.insert("all".to_string(), SetKind::Nodes);
}

/// Every built-in generator, in the order they are listed to users.
pub static REGISTRY: &[&GeneratorDef] = &[
    &rectangle::RECTANGLE,
    &disc::HALF_DISC,
    &disc::QUARTER_DISC,
    &annulus::ANNULUS,
    &solid::BOX,
    &solid::TUBE,
    &solid::CYLINDER,
    &solid::SPHERE_OCTANT,
    &sweep::EXTRUDE,
    &sweep::REVOLVE,
];

/// The generator called `name`.
pub fn find(name: &str) -> Option<&'static GeneratorDef> {
    REGISTRY.iter().copied().find(|g| g.name == name)
}

/// The names of all generators.
pub fn names() -> Vec<&'static str> {
    REGISTRY.iter().map(|g| g.name).collect()
}

/// The `element = tri3 | quad4` key every planar generator has.
pub const ELEMENT: Key = Key::new(
    "element",
    KeyType::Choice(&["tri3", "quad4"]),
    "cell type: linear triangles or bilinear quadrilaterals",
)
.default(Default::Choice("quad4"));

/// The `order = 1 | 2` key of every generator: 2 lifts the linear cells to
/// quadratic ones by [`ctc_engine::mesh::elevate`].
pub const ORDER: Key = Key::new(
    "order",
    KeyType::Integer,
    "polynomial order of the cells: 1 linear, 2 quadratic (tri3 -> tri6, quad4 -> quad8, \
     tet4 -> tet10, hex8 -> hex20); new nodes at the straight midpoints, except that annulus, \
     discs, tube, cylinder, sphere_octant and revolve move a new node whose corners lie at \
     one distance from their centre / z axis onto that circle, cylinder or sphere",
)
.default(Default::Integer(1))
.range(Range::Closed(1.0, 2.0))
.labels(&["order"]);

/// The `integration = full | reduced` key of every generator (reduced:
/// quad8R / hex20R, 2x2 / 2x2x2 Gauss points; only with `order = 2` and
/// quadrilaterals / hexahedra).
pub const INTEGRATION: Key = Key::new(
    "integration",
    KeyType::Choice(&["full", "reduced"]),
    "Gauss rule of the quadratic cells: full (quad8 3x3, hex20 3x3x3) or reduced \
     (quad8R 2x2, hex20R 2x2x2, as CPE8R / C3D20R); needs `order = 2` and quad / hex cells",
)
.default(Default::Choice("full"));

/// Where the midside nodes of a quadratic mesh go besides the straight
/// midpoints: onto the arcs the generator meshes.
#[derive(Debug, Clone, Copy)]
pub enum Arcs {
    /// Every edge straight.
    None,
    /// A new node whose corners all lie at one distance from `center`
    /// (circle in 2D, sphere in 3D) moves radially onto that circle.
    About([f64; 3]),
    /// A new node whose corners all lie at one distance from the axis
    /// along coordinate `k` through the origin (`Axis(2)`: the z axis of
    /// tube, cylinder and revolve) moves radially onto that cylinder.
    Axis(usize),
}

/// The quadratic version of the generated linear `mesh` when the settings
/// ask for `order = 2` (else `mesh` itself): the cell kind from
/// `integration`, midside nodes placed on `arcs`.
pub fn with_order<const D: usize>(
    s: &Settings,
    keys: &[Key],
    mesh: Mesh<D>,
    arcs: Arcs,
) -> Result<Mesh<D>, MeshError> {
    if s.integer("order", keys).unwrap_or(1) != 2 {
        return Ok(mesh);
    }
    let reduced = s.choice("integration", keys) == Some("reduced");
    let targets = if reduced {
        [
            CellKind::Tri6,
            CellKind::Quad8R,
            CellKind::Tet10,
            CellKind::Hex20R,
        ]
    } else {
        [
            CellKind::Tri6,
            CellKind::Quad8,
            CellKind::Tet10,
            CellKind::Hex20,
        ]
    };
    let targets: Vec<CellKind> = targets.into_iter().filter(|t| t.dimension() == D).collect();
    let mut q = ctc_engine::mesh::elevate::elevate_each(&mesh, &targets)?;
    place_on_arcs(&mut q, mesh.nodes.len(), arcs);
    Ok(q)
}

/// Moves the new nodes (numbers from `first_new`) of `q` onto `arcs`.
fn place_on_arcs<const D: usize>(q: &mut Mesh<D>, first_new: usize, arcs: Arcs) {
    let (center, skip) = match arcs {
        Arcs::None => return,
        Arcs::About(c) => (c, None),
        Arcs::Axis(k) => ([0.0; 3], Some(k)),
    };
    // distance vector from the centre or the axis
    let radial = |p: &[f64; D]| -> [f64; D] {
        std::array::from_fn(|k| {
            if Some(k) == skip {
                0.0
            } else {
                p[k] - center[k]
            }
        })
    };
    let norm = |v: &[f64; D]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let mut done = vec![false; q.nodes.len()];
    for c in 0..q.cells.len() {
        let kind = q.cells.kind(c);
        let sets = ctc_engine::mesh::elevate::corner_sets(kind);
        let nodes = q.cells.nodes(c).to_vec();
        for (a, set) in sets.iter().enumerate().skip(kind.corner_count()) {
            let n = nodes[a];
            if n < first_new || done[n] {
                continue;
            }
            done[n] = true;
            let radii: Vec<f64> = set
                .iter()
                .map(|&i| norm(&radial(&q.nodes[nodes[i]])))
                .collect();
            let r = radii[0];
            let v = radial(&q.nodes[n]);
            let rn = norm(&v);
            if r <= 0.0 || rn <= 1e-12 * r || radii.iter().any(|x| (x - r).abs() > 1e-9 * r) {
                continue;
            }
            for k in 0..D {
                if Some(k) != skip {
                    q.nodes[n][k] = center[k] + v[k] * r / rn;
                }
            }
        }
    }
}

/// `integration = reduced` and `order = 2` only where they can be
/// honoured: reduced integration needs quadratic quadrilaterals or
/// hexahedra (`order = 2`, not tri / tet cells).
pub fn reduced_integration_needs_quadratic_quads(g: &Generator, ctx: &mut Ctx<'_>) {
    let s = &g.settings;
    let Some(span) = s.span("integration") else {
        return;
    };
    if s.choice("integration", g.def.keys) != Some("reduced") {
        return;
    }
    if s.integer("order", g.def.keys).unwrap_or(1) != 2 {
        ctx.err(
            crate::diagnostics::Diagnostic::error(
                "`integration = reduced` is for quadratic cells",
                span,
                "needs `order = 2`",
            )
            .with_help("add `order = 2` (quad8R / hex20R), or leave `integration` out"),
        );
    } else if matches!(s.choice("element", g.def.keys), Some("tri3" | "tet4")) {
        ctx.err(
            crate::diagnostics::Diagnostic::error(
                "`integration = reduced` has no rule for tri6 / tet10 cells",
                span,
                "quad8R / hex20R only",
            )
            .with_help("use `element = quad4` / `hex8`, or leave `integration` out"),
        );
    }
}

/// A division count as the engine takes it (at least 1).
pub fn count(n: Option<i64>) -> usize {
    n.map_or(1, |v| v.max(1) as usize)
}

/// The engine grading of a deck grading.
pub fn grading(g: &crate::ast::Grading) -> ctc_engine::mesh::generate::Grading {
    use crate::ast::Grading as G;
    use ctc_engine::mesh::generate::Grading as E;
    match g {
        G::Uniform => E::Uniform,
        G::Geometric(r) => E::Geometric { ratio: r.value },
        G::Center(r) => E::Center { ratio: r.value },
    }
}

/// Product of division counts, saturating, for [`GeneratorDef::cells`].
pub fn cell_product(counts: impl IntoIterator<Item = i64>) -> i64 {
    counts
        .into_iter()
        .fold(1i64, |c, n| c.saturating_mul(n.max(1)))
}

/// A required value missing after validation (cannot happen on a valid
/// deck; reported instead of panicking).
pub fn missing(generator: &str, key: &str) -> MeshError {
    MeshError::new(format!(
        "internal: `{key}` of the `{generator}` generator is missing after validation"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registry_names_are_unique_and_every_entry_documents_its_keys() {
        let mut names = names();
        let n = names.len();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), n);
        for g in REGISTRY {
            assert!(!g.doc.is_empty(), "{}", g.name);
            for k in g.keys {
                assert!(!k.doc.is_empty(), "{}.{}", g.name, k.name);
            }
            let mut keys = crate::keys::names(g.keys);
            keys.sort_unstable();
            let before = keys.len();
            keys.dedup();
            assert_eq!(keys.len(), before, "{}: duplicate key", g.name);
            assert!(g.set_kinds(&Settings::default()).is_some() || g.open_sets);
        }
    }
}
