//! Resolving set references against the global mesh: named sets,
//! geometric selections (through `ctc_engine::mesh::select`), and the checks
//! that a selection is not empty and has edges where edges are needed.

use super::mesh::edge_nodes;
use crate::ast::{self, num, Selection, SetRef, SetRefKind};
use crate::diagnostics::Diagnostic;
use crate::suggest::did_you_mean;
use crate::validate::Need;
use ctc_engine::mesh::select::{self, Selection as EngineSelection};
use ctc_engine::mesh::Mesh;
use std::collections::BTreeMap;
use std::ops::Range;

/// The nodes (and edges, when the set has them) a reference designates.
#[derive(Debug, Clone, PartialEq)]
pub struct Resolved {
    /// Global node numbers, sorted, distinct.
    pub nodes: Vec<usize>,
    /// Boundary edges, when the reference designates edges.
    pub edges: Option<Vec<[usize; 2]>>,
    /// Boundary faces (solid meshes), when the reference designates faces.
    pub faces: Option<Vec<ctc_engine::mesh::Facet>>,
}

/// The engine selection for a selection written in the deck (box corners
/// may be given in any order).
pub fn engine_selection(s: &Selection) -> EngineSelection {
    match s {
        Selection::X(x) => EngineSelection::XEquals(*x),
        Selection::Y(y) => EngineSelection::YEquals(*y),
        Selection::Box { min, max } => EngineSelection::Box {
            min: [min[0].min(max[0]), min[1].min(max[1])],
            max: [min[0].max(max[0]), min[1].max(max[1])],
        },
        Selection::Near(p) => EngineSelection::Nearest(*p),
    }
}

/// "`b` spans x in [..] and y in [..]", to help with empty selections.
fn extent(mesh: &Mesh, body: &str, nodes: &Range<usize>) -> String {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in &mesh.nodes[nodes.clone()] {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    format!(
        "`{body}` spans x in [{}, {}] and y in [{}, {}]",
        num(lo[0]),
        num(hi[0]),
        num(lo[1]),
        num(hi[1])
    )
}

/// Resolves `r` in `mesh`; `bodies` maps body names to their node ranges.
/// `user` names the item for messages (`pressure`, `contact`, ...).
pub fn resolve(
    mesh: &Mesh,
    bodies: &BTreeMap<String, Range<usize>>,
    r: &SetRef,
    need: Need,
    user: &str,
) -> Result<Resolved, Diagnostic> {
    let body = &r.body.name;
    let Some(range) = bodies.get(body) else {
        let names: Vec<&str> = bodies.keys().map(String::as_str).collect();
        return Err(Diagnostic::error(
            format!("unknown body `{body}`"),
            r.body.span,
            "no body with this name",
        )
        .with_help_opt(did_you_mean(body, &names)));
    };
    let nodes_only = |what: String| {
        Diagnostic::error(
            format!("`{user}` needs boundary edges, but `{r}` is a set of nodes"),
            r.span,
            what,
        )
        .with_help(format!(
            "use a set with edges, e.g. `{body}.boundary` or `{body}.edges(..)`"
        ))
    };
    if let SetRefKind::Combination(terms) = &r.kind {
        return combine(mesh, bodies, r, terms, need, user);
    }
    let resolved = match &r.kind {
        SetRefKind::Combination(_) => unreachable!("handled above"),
        SetRefKind::Named(n) => {
            let key = format!("{body}.{}", n.name);
            let edges = mesh.edge_sets.get(&key).cloned();
            let nodes = mesh.node_sets.get(&key).cloned();
            match (nodes, edges) {
                (None, None) => {
                    let prefix = format!("{body}.");
                    let names: Vec<&str> = mesh
                        .node_sets
                        .keys()
                        .chain(mesh.edge_sets.keys())
                        .filter_map(|k| k.strip_prefix(&prefix))
                        .collect();
                    let mut names = names;
                    names.sort_unstable();
                    names.dedup();
                    return Err(Diagnostic::error(
                        format!("body `{body}` has no set `{}`", n.name),
                        n.span,
                        "no set with this name",
                    )
                    .with_help(did_you_mean(&n.name, &names).unwrap_or_else(|| {
                        format!("its sets are {}", crate::suggest::one_of(&names))
                    })));
                }
                (nodes, edges) => {
                    if need == Need::Edges && edges.is_none() {
                        return Err(nodes_only("nodes only".to_string()));
                    }
                    let nodes = match (&nodes, &edges) {
                        (Some(n), _) => n.clone(),
                        (None, Some(e)) => edge_nodes(e),
                        (None, None) => Vec::new(),
                    };
                    if nodes.is_empty() {
                        return Err(Diagnostic::error(
                            format!("set `{r}` is empty"),
                            r.span,
                            "no nodes in this set",
                        ));
                    }
                    Resolved {
                        nodes,
                        edges,
                        faces: None,
                    }
                }
            }
        }
        SetRefKind::Nodes(s) | SetRefKind::Node(s) => {
            if need == Need::Edges {
                return Err(nodes_only("nodes only".to_string()));
            }
            let candidates: Vec<usize> = range.clone().collect();
            let nodes = select::select_nodes(mesh, &candidates, &engine_selection(&s.value));
            if nodes.is_empty() {
                return Err(Diagnostic::error(
                    format!("selection `{r}` is empty"),
                    s.span,
                    format!("no node of `{body}` matches"),
                )
                .with_help(extent(mesh, body, range)));
            }
            Resolved {
                nodes,
                edges: None,
                faces: None,
            }
        }
        SetRefKind::Edges(s) => {
            let boundary = mesh
                .edge_sets
                .get(&format!("{body}.boundary"))
                .cloned()
                .unwrap_or_default();
            let edges = select::select_edges(mesh, &boundary, &engine_selection(&s.value));
            if edges.is_empty() {
                return Err(Diagnostic::error(
                    format!("selection `{r}` is empty"),
                    s.span,
                    format!("no boundary edge of `{body}` matches"),
                )
                .with_help(format!(
                    "edges are boundary edges with both nodes selected; {}",
                    extent(mesh, body, range)
                )));
            }
            Resolved {
                nodes: edge_nodes(&edges),
                edges: Some(edges),
                faces: None,
            }
        }
    };
    Ok(resolved)
}

/// Deck `set` items become `body.name` sets of the global mesh, in order.
impl super::Lowerer<'_> {
    pub(super) fn sets(&mut self) {
        for s in &self.deck.sets {
            if self.has_error_in(s.span) || !self.body_nodes.contains_key(&s.target.body.name) {
                // Already reported (or its body's mesh failed).
                self.skipped_sets.push(s.name.name.clone());
                continue;
            }
            let Some(r) = self.resolve(&s.target, Need::Nodes, "set") else {
                self.skipped_sets.push(s.name.name.clone());
                continue;
            };
            let key = format!("{}.{}", s.target.body.name, s.name.name);
            if self.solid {
                if let Some(faces) = r.faces {
                    self.mesh3.face_sets.insert(key.clone(), faces);
                }
                self.mesh3.node_sets.insert(key, r.nodes);
                continue;
            }
            if let Some(edges) = r.edges {
                self.mesh.edge_sets.insert(key.clone(), edges);
            }
            self.mesh.node_sets.insert(key, r.nodes);
        }
    }

    /// Whether references to this body must be skipped: it has no mesh
    /// (its mesh failed, or it is unknown, both already reported).
    pub(super) fn body_failed(&mut self, r: &ast::SetRef) -> bool {
        if self.body_nodes.contains_key(&r.body.name) {
            return false;
        }
        if !self.deck.bodies.iter().any(|b| b.name.name == r.body.name) {
            self.missing("the body", r.body.span);
        }
        true
    }
}

/// Resolves `r` in the solid mesh of a `3d` analysis: named sets (node
/// sets, face sets), unions / differences of them, and the node selections
/// `nodes(x = ..)`, `nodes(y = ..)`; other selections are planar-only.
pub fn resolve_solid(
    mesh: &Mesh<3>,
    bodies: &BTreeMap<String, Range<usize>>,
    r: &SetRef,
    need: Need,
    user: &str,
) -> Result<Resolved, Diagnostic> {
    use ctc_engine::mesh::Facet;
    let body = &r.body.name;
    let Some(range) = bodies.get(body) else {
        let names: Vec<&str> = bodies.keys().map(String::as_str).collect();
        return Err(Diagnostic::error(
            format!("unknown body `{body}`"),
            r.body.span,
            "no body with this name",
        )
        .with_help_opt(did_you_mean(body, &names)));
    };
    let needs_faces = |what: &str| {
        Diagnostic::error(
            format!("`{user}` needs boundary faces, but `{r}` is a set of nodes"),
            r.span,
            what.to_string(),
        )
        .with_help(format!("use a set with faces, e.g. `{body}.boundary`"))
    };
    let resolved =
        match &r.kind {
            SetRefKind::Named(n) => {
                let key = format!("{body}.{}", n.name);
                let faces = mesh.face_sets.get(&key).cloned();
                let nodes = mesh.node_sets.get(&key).cloned();
                if nodes.is_none() && faces.is_none() {
                    let prefix = format!("{body}.");
                    let mut names: Vec<&str> = mesh
                        .node_sets
                        .keys()
                        .chain(mesh.face_sets.keys())
                        .filter_map(|k| k.strip_prefix(&prefix))
                        .collect();
                    names.sort_unstable();
                    names.dedup();
                    return Err(Diagnostic::error(
                        format!("body `{body}` has no set `{}`", n.name),
                        n.span,
                        "no set with this name",
                    )
                    .with_help(did_you_mean(&n.name, &names).unwrap_or_else(|| {
                        format!("its sets are {}", crate::suggest::one_of(&names))
                    })));
                }
                let nodes = match (nodes, &faces) {
                    (Some(n), _) => n,
                    (None, Some(f)) => super::mesh::facet_nodes(f),
                    (None, None) => Vec::new(),
                };
                Resolved {
                    nodes,
                    edges: None,
                    faces,
                }
            }
            SetRefKind::Combination(terms) => {
                let mut nodes: Vec<usize> = Vec::new();
                let mut removed: Vec<usize> = Vec::new();
                let mut faces: Option<Vec<Facet>> = Some(Vec::new());
                let mut removed_faces: Vec<Facet> = Vec::new();
                for (add, t) in terms {
                    let x = resolve_solid(mesh, bodies, t, Need::Nodes, user)?;
                    if *add {
                        nodes.extend(&x.nodes);
                        match (&mut faces, x.faces) {
                            (Some(f), Some(tf)) => f.extend(tf),
                            _ => faces = None,
                        }
                    } else {
                        removed.extend(&x.nodes);
                        match x.faces {
                            Some(tf) => removed_faces.extend(tf),
                            None => faces = None,
                        }
                    }
                }
                removed.sort_unstable();
                nodes.sort_unstable();
                nodes.dedup();
                nodes.retain(|n| removed.binary_search(n).is_err());
                let faces = faces.map(|mut f| {
                    let mut seen = std::collections::BTreeSet::new();
                    f.retain(|x| !removed_faces.contains(x) && seen.insert(*x));
                    f
                });
                let nodes = match &faces {
                    Some(f) => super::mesh::facet_nodes(f),
                    None => nodes,
                };
                Resolved {
                    nodes,
                    edges: None,
                    faces,
                }
            }
            SetRefKind::Nodes(s) | SetRefKind::Node(s) => {
                let (axis, value) = match &s.value {
                    Selection::X(x) => (0, *x),
                    Selection::Y(y) => (1, *y),
                    _ => {
                        return Err(Diagnostic::error(
                            format!("selection `{r}` is planar-only"),
                            s.span,
                            "not available in 3d analyses",
                        )
                        .with_help("use `nodes(x = ..)`, `nodes(y = ..)` or a named set"))
                    }
                };
                let tol = 1e-9 * solid_size(mesh, range).max(f64::MIN_POSITIVE);
                let nodes: Vec<usize> = range
                    .clone()
                    .filter(|&n| (mesh.nodes[n][axis] - value).abs() <= tol)
                    .collect();
                Resolved {
                    nodes,
                    edges: None,
                    faces: None,
                }
            }
            SetRefKind::Edges(s) => {
                return Err(Diagnostic::error(
                    format!("selection `{r}` is planar-only"),
                    s.span,
                    "no edges in 3d analyses",
                )
                .with_help(format!("use a named face set, e.g. `{body}.boundary`")));
            }
        };
    if need == Need::Edges && resolved.faces.is_none() {
        return Err(needs_faces("nodes only"));
    }
    if resolved.nodes.is_empty() {
        return Err(Diagnostic::error(
            format!("set `{r}` is empty"),
            r.span,
            "no nodes in this set",
        ));
    }
    Ok(resolved)
}

/// Bounding-box diagonal of a body's nodes.
fn solid_size(mesh: &Mesh<3>, nodes: &Range<usize>) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &mesh.nodes[nodes.clone()] {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt()
}

/// Resolves `a + b - c`: nodes of the added terms minus those of the
/// removed ones; edges likewise when every term has edges.
fn combine(
    mesh: &Mesh,
    bodies: &BTreeMap<String, Range<usize>>,
    r: &SetRef,
    terms: &[(bool, SetRef)],
    need: Need,
    user: &str,
) -> Result<Resolved, Diagnostic> {
    let mut nodes: Vec<usize> = Vec::new();
    let mut removed: Vec<usize> = Vec::new();
    let mut edges: Option<Vec<[usize; 2]>> = Some(Vec::new());
    let mut removed_edges: Vec<[usize; 2]> = Vec::new();
    for (add, t) in terms {
        let x = resolve(mesh, bodies, t, Need::Nodes, user)?;
        if *add {
            nodes.extend(&x.nodes);
            match (&mut edges, x.edges) {
                (Some(e), Some(te)) => e.extend(te),
                _ => edges = None,
            }
        } else {
            removed.extend(&x.nodes);
            match x.edges {
                Some(te) => removed_edges.extend(te),
                None => edges = None,
            }
        }
    }
    removed.sort_unstable();
    nodes.sort_unstable();
    nodes.dedup();
    nodes.retain(|n| removed.binary_search(n).is_err());
    let edges = edges.map(|mut e| {
        let mut seen = std::collections::BTreeSet::new();
        e.retain(|x| !removed_edges.contains(x) && seen.insert(*x));
        e
    });
    if need == Need::Edges && edges.is_none() {
        return Err(Diagnostic::error(
            format!("`{user}` needs boundary edges, but `{r}` is a set of nodes"),
            r.span,
            "nodes only",
        )
        .with_help("every set of the combination must have edges"));
    }
    let nodes = match &edges {
        Some(e) => edge_nodes(e),
        None => nodes,
    };
    if nodes.is_empty() {
        return Err(Diagnostic::error(
            format!("set `{r}` is empty"),
            r.span,
            "no nodes left",
        ));
    }
    Ok(Resolved {
        nodes,
        edges,
        faces: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse::test_support::value_of;
    use crate::parse::values::set_ref;
    use ctc_engine::mesh::generate::{generate, Grading, MeshSpec};
    use ctc_engine::mesh::CellKind;

    /// A 4 x 2 quad rectangle [0, 4] x [0, 2], placed as body `b`.
    fn rectangle() -> (Mesh, BTreeMap<String, Range<usize>>) {
        let m = generate(&MeshSpec::Rectangle {
            origin: [0.0, 0.0],
            size: [4.0, 2.0],
            divisions: [4, 2],
            grading: [Grading::Uniform, Grading::Uniform],
            kind: CellKind::Quad4,
        })
        .expect("rectangle generator");
        let mut g = Mesh::default();
        let (placed, _) = super::super::mesh::append(&mut g, "b", m, Default::default());
        let mut bodies = BTreeMap::new();
        bodies.insert("b".to_string(), placed.nodes);
        (g, bodies)
    }

    fn res(text: &str, need: Need) -> Result<Resolved, Diagnostic> {
        let (g, bodies) = rectangle();
        let mut d = crate::parse::values::Diags::new();
        let r = set_ref(&value_of(text), &mut d).expect("a set reference");
        resolve(&g, &bodies, &r, need, "test")
    }

    #[test]
    fn set_resolution_named_sets_of_a_rectangle() {
        let top = res("b.top", Need::Edges).unwrap();
        assert_eq!(top.nodes.len(), 5);
        assert_eq!(top.edges.as_ref().unwrap().len(), 4);
        let all = res("b.all", Need::Nodes).unwrap();
        assert_eq!(all.nodes.len(), 15);
        let boundary = res("b.boundary", Need::Edges).unwrap();
        assert_eq!(boundary.edges.unwrap().len(), 12);
        let e = res("b.tpo", Need::Nodes).unwrap_err();
        assert_eq!(e.help.as_deref(), Some("did you mean `top`?"));
        let e = res("b.corner_bl", Need::Edges).unwrap_err();
        assert!(e.message.contains("needs boundary edges"));
    }

    #[test]
    fn set_resolution_geometric_selections() {
        let left = res("b.nodes(x = 0)", Need::Nodes).unwrap();
        assert_eq!(left.nodes.len(), 3);
        let bottom = res("b.edges(y = 0)", Need::Edges).unwrap();
        assert_eq!(bottom.edges.as_ref().unwrap().len(), 4);
        assert_eq!(bottom.nodes.len(), 5);
        // Corners in any order; only the column x = 1 lies in [0.5, 1.5].
        let boxed = res("b.nodes(box((1.5, 2.5), (0.5, -1)))", Need::Nodes).unwrap();
        let (g, _) = rectangle();
        assert_eq!(boxed.nodes.len(), 3);
        assert!(boxed.nodes.iter().all(|&n| g.nodes[n][0] == 1.0));
        let near = res("b.node(near(3.9, 0.1))", Need::Nodes).unwrap();
        assert_eq!(near.nodes.len(), 1);
    }

    #[test]
    fn set_resolution_empty_selection_is_an_error_at_the_selection() {
        let e = res("b.nodes(y = -4)", Need::Nodes).unwrap_err();
        assert_eq!(e.message, "selection `b.nodes(y = -4)` is empty");
        assert_eq!(
            e.help.as_deref(),
            Some("`b` spans x in [0, 4] and y in [0, 2]")
        );
    }
}
