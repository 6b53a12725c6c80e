//! Building each body's mesh (a registry generator — [`crate::generators`]
//! — or a gmsh file), checking it, and appending it to the global mesh with
//! qualified set names.

use crate::ast::settings::SettingValue;
use crate::ast::{Generator, MeshDef};
use crate::diagnostics::Diagnostic;
use crate::generators::Build;
use crate::source::Source;
use crate::span::{Span, Spanned};
use ctc_engine::mesh::{gmsh, validate, Mesh, MeshError};
use std::collections::BTreeSet;
use std::ops::Range;

/// At most this many mesh check errors are listed per body.
const MAX_MESH_ERRORS: usize = 5;

/// Builds (generates or reads) and checks the mesh of body `body`.
pub fn build(body: &str, mesh: &Spanned<MeshDef>, src: &Source) -> Result<Mesh, Vec<Diagnostic>> {
    let m = make(body, mesh, src)?;
    checked(
        body,
        mesh,
        m,
        "gmsh files must contain 2D triangles or quadrangles",
    )
}

/// Builds (generates or reads) and checks the solid mesh of body `body`
/// (a `3d` analysis).
pub fn build_solid(
    body: &str,
    mesh: &Spanned<MeshDef>,
    src: &Source,
) -> Result<Mesh<3>, Vec<Diagnostic>> {
    let fail = |message: String, label: &str| vec![Diagnostic::error(message, mesh.span, label)];
    let m = match &mesh.value {
        MeshDef::Generator(g) => match g.def.build {
            Build::Solid(f) => f(&g.settings, &inputs(body, g, src)?).map_err(|e: MeshError| {
                fail(
                    format!("cannot generate the mesh of body `{body}`: {}", e.message),
                    "mesh generation failed",
                )
            })?,
            Build::Planar(_) => {
                return Err(fail(
                    format!(
                        "`{}` makes a planar mesh, but the analysis is 3d",
                        g.name.name
                    ),
                    "wrong dimension",
                ))
            }
        },
        MeshDef::File(f) => {
            let bytes = read_bytes(f, src)?;
            gmsh::parse_solid_bytes(&bytes).map_err(|e| file_error(f, e))?
        }
    };
    checked(
        body,
        mesh,
        m,
        "gmsh files of 3d analyses must contain tetrahedra or hexahedra",
    )
}

/// The mesh checks shared by both dimensions.
fn checked<const D: usize>(
    body: &str,
    mesh: &Spanned<MeshDef>,
    m: Mesh<D>,
    empty_help: &str,
) -> Result<Mesh<D>, Vec<Diagnostic>> {
    if m.cells.is_empty() {
        return Err(vec![Diagnostic::error(
            format!("the mesh of body `{body}` has no cells"),
            mesh.span,
            "empty mesh",
        )
        .with_help(empty_help)]);
    }
    if let Err(errors) = validate::check(&m) {
        let n = errors.len();
        let mut out: Vec<Diagnostic> = errors
            .iter()
            .take(MAX_MESH_ERRORS)
            .map(|e| {
                Diagnostic::error(
                    format!("invalid mesh for body `{body}`: {e}"),
                    mesh.span,
                    "bad mesh",
                )
            })
            .collect();
        if n > MAX_MESH_ERRORS {
            if let Some(last) = out.last_mut() {
                last.help = Some(format!(
                    "{} more mesh errors not shown",
                    n - MAX_MESH_ERRORS
                ));
            }
        }
        return Err(out);
    }
    Ok(m)
}

/// Generates or reads a mesh (without checking it): a generator's input
/// meshes first, in key order.
fn make(body: &str, mesh: &Spanned<MeshDef>, src: &Source) -> Result<Mesh, Vec<Diagnostic>> {
    match &mesh.value {
        MeshDef::Generator(g) => {
            let inputs = inputs(body, g, src)?;
            let Build::Planar(build) = g.def.build else {
                return Err(vec![Diagnostic::error(
                    format!(
                        "`{}` makes a solid (3D) mesh, but the analysis is planar",
                        g.name.name
                    ),
                    mesh.span,
                    "wrong dimension",
                )]);
            };
            build(&g.settings, &inputs).map_err(|e: MeshError| {
                vec![Diagnostic::error(
                    format!("cannot generate the mesh of body `{body}`: {}", e.message),
                    mesh.span,
                    "mesh generation failed",
                )]
            })
        }
        MeshDef::File(f) => read_file(f, src),
    }
}

/// The built input meshes of a generator (its keys of type mesh).
fn inputs(body: &str, g: &Generator, src: &Source) -> Result<Vec<Mesh>, Vec<Diagnostic>> {
    let mut out = Vec::new();
    for s in &g.settings.entries {
        if let SettingValue::Mesh(m) = &s.value.value {
            out.push(make(body, m, src)?);
        }
    }
    Ok(out)
}

fn read_file(f: &Spanned<String>, src: &Source) -> Result<Mesh, Vec<Diagnostic>> {
    let bytes = read_bytes(f, src)?;
    gmsh::parse_bytes(&bytes).map_err(|e| file_error(f, e))
}

/// A mesh file error at the file name.
fn file_error(f: &Spanned<String>, e: MeshError) -> Vec<Diagnostic> {
    let at = match e.line {
        Some(l) => format!(", line {l}"),
        None => String::new(),
    };
    vec![Diagnostic::error(
        format!("error in mesh file `{}`{at}: {}", f.value, e.message),
        f.span,
        "in this mesh file",
    )]
}

/// The bytes of a mesh file (relative to the deck's directory).
fn read_bytes(f: &Spanned<String>, src: &Source) -> Result<Vec<u8>, Vec<Diagnostic>> {
    // relative to the file the mesh is written in (an included file's own
    // directory)
    let path = src.directory_at(f.span.start).join(&f.value);
    let bytes = std::fs::read(&path).map_err(|e| {
        let label = match e.kind() {
            std::io::ErrorKind::NotFound => "file not found".to_string(),
            _ => "cannot read this file".to_string(),
        };
        vec![Diagnostic::error(
            format!("cannot read mesh file `{}`: {e}", f.value),
            f.span,
            label,
        )
        .with_help(format!(
            "looked for `{}`; mesh paths are relative to the deck's directory",
            path.display()
        ))]
    })?;
    Ok(bytes)
}

/// For axisymmetric analyses (x = r): an error if the mesh reaches x < 0
/// (beyond a round-off tolerance relative to the mesh size).
pub fn negative_radius(body: &str, m: &Mesh, at: Span) -> Option<Diagnostic> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for p in &m.nodes {
        for &c in p {
            lo = lo.min(c);
            hi = hi.max(c);
        }
    }
    let tol = 1e-9 * (hi - lo).abs().max(f64::MIN_POSITIVE);
    let min_x = m.nodes.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
    (min_x < -tol).then(|| {
        Diagnostic::error(
            format!(
                "body `{body}` reaches x = {} < 0 in an axisymmetric analysis",
                crate::ast::num(min_x)
            ),
            at,
            "x is the radius r and must be >= 0",
        )
        .with_help("move the mesh to x >= 0 (the axis of revolution is x = 0)")
    })
}

/// Where a body landed in the global mesh.
#[derive(Debug, Clone)]
pub struct Placed {
    /// Global node numbers.
    pub nodes: Range<usize>,
    /// Global cell numbers.
    pub cells: Range<usize>,
}

/// Appends `m` (the mesh of body `body`) to `global`: node and cell numbers
/// are offset, sets are renamed `body.set`, every edge set gets a node set,
/// and the built-in sets `body.boundary` (edges) and `body.all` (nodes) are
/// added. Returns warnings (mesh sets shadowed by the built-in ones).
pub fn append(global: &mut Mesh, body: &str, m: Mesh, at: Span) -> (Placed, Vec<Diagnostic>) {
    let mut warnings = Vec::new();
    let node_off = global.nodes.len();
    let cell_off = global.cells.len();
    let n_nodes = m.nodes.len();
    global.nodes.extend_from_slice(&m.nodes);
    global.cells.extend_shifted(&m.cells, node_off);
    let cells = cell_off..global.cells.len();
    for name in ["boundary", "all"] {
        if m.node_sets.contains_key(name) || m.edge_sets.contains_key(name) {
            warnings.push(Diagnostic::warning(
                format!("the mesh of body `{body}` has its own set `{name}`; the built-in `{body}.{name}` replaces it"),
                at,
                "shadowed set",
            ));
        }
    }
    for (name, nodes) in &m.node_sets {
        let mut v: Vec<usize> = nodes.iter().map(|n| n + node_off).collect();
        v.sort_unstable();
        v.dedup();
        global.node_sets.insert(format!("{body}.{name}"), v);
    }
    for (name, edges) in &m.edge_sets {
        let v: Vec<[usize; 2]> = edges
            .iter()
            .map(|e| [e[0] + node_off, e[1] + node_off])
            .collect();
        let key = format!("{body}.{name}");
        if !global.node_sets.contains_key(&key) {
            let nodes = edge_nodes_in(global, &v);
            global.node_sets.insert(key.clone(), nodes);
        }
        global.edge_sets.insert(key, v);
    }
    let boundary = global.boundary_edges(cells.clone());
    let boundary_nodes = edge_nodes_in(global, &boundary);
    global
        .node_sets
        .insert(format!("{body}.boundary"), boundary_nodes);
    global
        .edge_sets
        .insert(format!("{body}.boundary"), boundary);
    global.node_sets.insert(
        format!("{body}.all"),
        (node_off..node_off + n_nodes).collect(),
    );
    (
        Placed {
            nodes: node_off..node_off + n_nodes,
            cells,
        },
        warnings,
    )
}

/// Appends the solid mesh `m` of body `body` to `global`: node and cell
/// numbers offset, sets renamed `body.set` (face sets with their node
/// sets), and the built-in sets `body.boundary` (every boundary face, in
/// outward order) and `body.all` added.
pub fn append_solid(
    global: &mut Mesh<3>,
    body: &str,
    m: Mesh<3>,
    at: Span,
) -> (Placed, Vec<Diagnostic>) {
    let mut warnings = Vec::new();
    let node_off = global.nodes.len();
    let cell_off = global.cells.len();
    let n_nodes = m.nodes.len();
    global.nodes.extend_from_slice(&m.nodes);
    global.cells.extend_shifted(&m.cells, node_off);
    let cells = cell_off..global.cells.len();
    for name in ["boundary", "all"] {
        if m.node_sets.contains_key(name) || m.face_sets.contains_key(name) {
            warnings.push(Diagnostic::warning(
                format!("the mesh of body `{body}` has its own set `{name}`; the built-in `{body}.{name}` replaces it"),
                at,
                "shadowed set",
            ));
        }
    }
    for (name, nodes) in &m.node_sets {
        let mut v: Vec<usize> = nodes.iter().map(|n| n + node_off).collect();
        v.sort_unstable();
        v.dedup();
        global.node_sets.insert(format!("{body}.{name}"), v);
    }
    for (name, faces) in &m.face_sets {
        let v: Vec<ctc_engine::mesh::Facet> = faces.iter().map(|f| f.shifted(node_off)).collect();
        let key = format!("{body}.{name}");
        global
            .node_sets
            .entry(key.clone())
            .or_insert_with(|| facet_nodes(&v));
        global.face_sets.insert(key, v);
    }
    let boundary = global.boundary_facets(cells.clone());
    global
        .node_sets
        .insert(format!("{body}.boundary"), facet_nodes(&boundary));
    global
        .face_sets
        .insert(format!("{body}.boundary"), boundary);
    global.node_sets.insert(
        format!("{body}.all"),
        (node_off..node_off + n_nodes).collect(),
    );
    (
        Placed {
            nodes: node_off..node_off + n_nodes,
            cells,
        },
        warnings,
    )
}

/// The distinct nodes of `facets`, sorted.
pub fn facet_nodes(facets: &[ctc_engine::mesh::Facet]) -> Vec<usize> {
    let set: BTreeSet<usize> = facets.iter().flat_map(|f| f.nodes().to_vec()).collect();
    set.into_iter().collect()
}

/// The distinct nodes of `edges`, sorted.
pub fn edge_nodes(edges: &[[usize; 2]]) -> Vec<usize> {
    let set: BTreeSet<usize> = edges.iter().flat_map(|e| [e[0], e[1]]).collect();
    set.into_iter().collect()
}

/// The distinct nodes of `edges` of `mesh` with the midside nodes of its
/// quadratic cells' edges ([`Mesh::edge_midsides`]), sorted.
pub fn edge_nodes_in(mesh: &Mesh, edges: &[[usize; 2]]) -> Vec<usize> {
    let midsides = mesh.edge_midsides();
    if midsides.is_empty() {
        return edge_nodes(edges);
    }
    let set: BTreeSet<usize> = edges
        .iter()
        .flat_map(|&e| Mesh::edge_facet(&midsides, e).nodes().to_vec())
        .collect();
    set.into_iter().collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use ctc_engine::mesh::Cell;

    fn unit_square() -> Mesh {
        let mut m = Mesh::new(
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            vec![Cell::quad(0, 1, 2, 3)],
        );
        m.edge_sets.insert("bottom".into(), vec![[0, 1]]);
        m.node_sets.insert("corner".into(), vec![2]);
        m
    }

    #[test]
    fn append_offsets_numbers_and_qualifies_sets() {
        let mut g = Mesh::default();
        let (a, w) = append(&mut g, "a", unit_square(), Span::default());
        assert!(w.is_empty());
        let (b, _) = append(&mut g, "b", unit_square(), Span::default());
        assert_eq!(a.nodes, 0..4);
        assert_eq!(b.nodes, 4..8);
        assert_eq!(b.cells, 1..2);
        assert_eq!(g.cells.nodes(1), &[4, 5, 6, 7]);
        assert_eq!(g.edge_sets["b.bottom"], vec![[4, 5]]);
        assert_eq!(g.node_sets["b.bottom"], vec![4, 5]);
        assert_eq!(g.node_sets["b.corner"], vec![6]);
        assert_eq!(g.node_sets["b.all"], vec![4, 5, 6, 7]);
        assert_eq!(g.edge_sets["b.boundary"].len(), 4);
        assert_eq!(g.node_sets["b.boundary"], vec![4, 5, 6, 7]);
        // Boundary edges keep the body on their left (counter-clockwise cell).
        assert!(g.edge_sets["a.boundary"].contains(&[0, 1]));
    }

    #[test]
    fn missing_mesh_file_is_a_diagnostic_at_the_path() {
        let src = Source::new("/nonexistent-dir/deck.ctc", "");
        let f = Spanned::new("part.msh".to_string(), Span::new(10, 20));
        let mesh = Spanned::new(MeshDef::File(f), Span::new(5, 20));
        let e = build("b", &mesh, &src).unwrap_err();
        assert_eq!(e[0].span, Span::new(10, 20));
        assert!(e[0].message.starts_with("cannot read mesh file `part.msh`"));
        assert_eq!(e[0].label, "file not found");
    }
}
