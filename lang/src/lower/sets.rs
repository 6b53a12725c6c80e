//! Resolving set references against the global mesh: named sets,
//! geometric selections (through `ctc_engine::mesh::select`), and the checks
//! that a selection is not empty and has edges where edges are needed.

use super::mesh::edge_nodes_in;
use crate::ast::{self, num, Selection, SetRef, SetRefKind};
use crate::diagnostics::Diagnostic;
use crate::span::Spanned;
use crate::suggest::did_you_mean;
use crate::validate::Need;
use ctc_engine::mesh::select::{self, Selection as EngineSelection};
use ctc_engine::mesh::Facet;
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

/// The engine selection in dimension `D` for a selection written in the
/// deck (box corners may be given in any order), or the diagnostic of a
/// coordinate count that does not fit the analysis (validation reports it
/// first: [`crate::validate::sets::selection_fits_dimension`]).
pub fn engine_selection<const D: usize>(
    s: &Spanned<Selection>,
) -> Result<EngineSelection<D>, Diagnostic> {
    if let Some(d) = crate::validate::sets::dimension_mismatch(s, D == 3) {
        return Err(d);
    }
    let point = |c: &[f64]| -> [f64; D] { std::array::from_fn(|k| c[k]) };
    Ok(match &s.value {
        Selection::X(x) => EngineSelection::XEquals(*x),
        Selection::Y(y) => EngineSelection::YEquals(*y),
        Selection::Z(z) => EngineSelection::ZEquals(*z),
        Selection::Box { min, max } => {
            let (a, b) = (point(min.values()), point(max.values()));
            EngineSelection::Box {
                min: std::array::from_fn(|k| a[k].min(b[k])),
                max: std::array::from_fn(|k| a[k].max(b[k])),
            }
        }
        Selection::Near(p) => EngineSelection::Nearest(point(p.values())),
    })
}

const AXES: [&str; 3] = ["x", "y", "z"];

/// "`b` spans x in [..] and y in [..]" (and z in 3d), to help with empty
/// selections.
fn extent<const D: usize>(mesh: &Mesh<D>, body: &str, nodes: &Range<usize>) -> String {
    let Some((lo, hi)) = select::bounds(mesh, nodes.clone()) else {
        return format!("`{body}` has no node with finite coordinates");
    };
    let parts: Vec<String> = (0..D)
        .map(|k| format!("{} in [{}, {}]", AXES[k], num(lo[k]), num(hi[k])))
        .collect();
    let (last, first) = parts.split_last().expect("D >= 2");
    format!("`{body}` spans {} and {last}", first.join(", "))
}

/// "boundary edge" or "boundary face".
fn facet_word<const D: usize>() -> &'static str {
    if D == 2 {
        "boundary edge"
    } else {
        "boundary face"
    }
}

/// The diagnostic of a selection that selects nothing, naming the cause:
/// the coordinate range of the body for a plane, its extent for a box, and
/// for facets whether nodes matched but no facet has all its nodes
/// selected.
fn empty_selection<const D: usize>(
    mesh: &Mesh<D>,
    range: &Range<usize>,
    boundary: &[Facet],
    r: &SetRef,
    s: &Spanned<Selection>,
    sel: &EngineSelection<D>,
    facets: bool,
) -> Diagnostic {
    let body = &r.body.name;
    let what = if facets { facet_word::<D>() } else { "node" };
    let candidates: Vec<usize> = range.clone().collect();
    let tol = select::tolerance(mesh, candidates.iter().copied());
    let d = |label: String| Diagnostic::error(format!("selection `{r}` is empty"), s.span, label);
    // what the nodes of the body say about it
    let nodes = select::select_nodes(mesh, &candidates, sel);
    let on_boundary: Vec<usize> = {
        let b = super::mesh::facet_nodes(boundary);
        nodes
            .iter()
            .copied()
            .filter(|n| b.binary_search(n).is_ok())
            .collect()
    };
    let condition = match sel.plane() {
        Some((axis, v)) => format!("{} = {}", AXES[axis], num(v)),
        None => "in this box".to_string(),
    };
    let with = if sel.plane().is_some() {
        if facets {
            format!("with all its nodes at {condition}")
        } else {
            format!("has {condition}")
        }
    } else if facets {
        "with all its nodes in this box".to_string()
    } else {
        "lies in this box".to_string()
    };
    if facets && !nodes.is_empty() {
        let call = if D == 2 { "edges(..)" } else { "faces(..)" };
        let help = match (on_boundary.len(), nodes.len()) {
            (0, 1) => format!(
                "1 node of `{body}` matches, but it is inside the body: `{call}` takes the \
                 {what}s whose nodes are all selected"
            ),
            (0, n) => format!(
                "{n} nodes of `{body}` match, but they are all inside the body: `{call}` takes \
                 the {what}s whose nodes are all selected"
            ),
            (1, _) => format!(
                "1 node on the boundary of `{body}` matches, but no {what} has all its nodes \
                 selected"
            ),
            (n, _) => format!(
                "{n} nodes on the boundary of `{body}` match, but no {what} has all its nodes \
                 among them"
            ),
        };
        return d(format!("no {what} of `{body}` {with}")).with_help(help);
    }
    match sel.plane() {
        Some((axis, _)) => {
            let range_text = match select::bounds(mesh, range.clone()) {
                Some((lo, hi)) => format!(
                    "its {} range is {} .. {}",
                    AXES[axis],
                    num(lo[axis]),
                    num(hi[axis])
                ),
                None => "it has no node with finite coordinates".to_string(),
            };
            d(format!("no {what} of `{body}` {with}; {range_text}")).with_help(format!(
                "coordinates match within {tol:.1e} (1e-6 x the diagonal of `{body}`)"
            ))
        }
        None => d(format!("no {what} of `{body}` {with}")).with_help(extent(mesh, body, range)),
    }
}

/// Resolves a geometric selection `body.nodes(..)`, `body.node(..)`,
/// `body.edges(..)` (planar) or `body.faces(..)` (3d) in dimension `D`:
/// nodes of the body's node `range`, or facets of its `boundary` with every
/// node selected.
fn geometric<const D: usize>(
    mesh: &Mesh<D>,
    range: &Range<usize>,
    r: &SetRef,
    need: Need,
    user: &str,
) -> Result<Resolved, Diagnostic> {
    let body = &r.body.name;
    let (s, facets) = match &r.kind {
        SetRefKind::Nodes(s) | SetRefKind::Node(s) => (s, false),
        SetRefKind::Edges(s) | SetRefKind::Faces(s) => (s, true),
        SetRefKind::Named(_) | SetRefKind::Combination(_) => {
            unreachable!("geometric selections only")
        }
    };
    let sel = engine_selection::<D>(s)?;
    if let Some(d) = crate::validate::sets::facet_kind_mismatch(r, D == 3) {
        return Err(d);
    }
    if need == Need::Edges && !facets {
        let (word, call) = if D == 2 {
            ("edges", "edges")
        } else {
            ("faces", "faces")
        };
        return Err(Diagnostic::error(
            format!("`{user}` needs boundary {word}, but `{r}` is a set of nodes"),
            r.span,
            "nodes only",
        )
        .with_help(format!(
            "select boundary {word} with `{body}.{call}({})`",
            s.value
        )));
    }
    let boundary = mesh
        .facet_set(&format!("{body}.boundary"))
        .unwrap_or_default();
    if !facets {
        let candidates: Vec<usize> = range.clone().collect();
        let nodes = select::select_nodes(mesh, &candidates, &sel);
        if nodes.is_empty() {
            return Err(empty_selection(mesh, range, &boundary, r, s, &sel, false));
        }
        return Ok(Resolved {
            nodes,
            edges: None,
            faces: None,
        });
    }
    let chosen = select::select_facets(mesh, &boundary, &sel);
    if chosen.is_empty() {
        return Err(empty_selection(mesh, range, &boundary, r, s, &sel, true));
    }
    let nodes = super::mesh::facet_nodes(&chosen);
    Ok(if D == 2 {
        Resolved {
            nodes,
            edges: Some(chosen.iter().map(Facet::edge).collect()),
            faces: None,
        }
    } else {
        Resolved {
            nodes,
            edges: None,
            faces: Some(chosen),
        }
    })
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
                        (None, Some(e)) => edge_nodes_in(mesh, e),
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
        SetRefKind::Nodes(_)
        | SetRefKind::Node(_)
        | SetRefKind::Edges(_)
        | SetRefKind::Faces(_) => geometric(mesh, range, r, need, user)?,
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
/// sets, face sets), unions / differences of them, and the geometric
/// selections `nodes(..)`, `node(near(x, y, z))`, `faces(..)`.
pub fn resolve_solid(
    mesh: &Mesh<3>,
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
            SetRefKind::Nodes(_)
            | SetRefKind::Node(_)
            | SetRefKind::Edges(_)
            | SetRefKind::Faces(_) => geometric(mesh, range, r, need, user)?,
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
        Some(e) => edge_nodes_in(mesh, e),
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
    use crate::span::Span;
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
        assert_eq!(e.label, "no node of `b` has y = -4; its y range is 0 .. 2");
        let e = res("b.nodes(box((5, 0), (6, 1)))", Need::Nodes).unwrap_err();
        assert_eq!(e.label, "no node of `b` lies in this box");
        assert_eq!(
            e.help.as_deref(),
            Some("`b` spans x in [0, 4] and y in [0, 2]")
        );
        // nodes at x = 2 exist, but only 2 of them on the boundary, not an edge
        let e = res("b.edges(x = 2)", Need::Edges).unwrap_err();
        assert_eq!(
            e.label,
            "no boundary edge of `b` with all its nodes at x = 2"
        );
        assert_eq!(
            e.help.as_deref(),
            Some("2 nodes on the boundary of `b` match, but no boundary edge has all its nodes among them")
        );
    }

    /// A hex8 brick [0, 2] x [0, 1] x [0, 1] (4 x 2 x 2 cells) placed as
    /// body `block` after a first body `other` (so node numbers are shifted).
    fn brick() -> (Mesh<3>, BTreeMap<String, Range<usize>>) {
        use ctc_engine::mesh::generate::solid::brick;
        let make = |o: f64| {
            brick(
                [o, 0.0, 0.0],
                [2.0, 1.0, 1.0],
                [4, 2, 2],
                [Grading::Uniform; 3],
                CellKind::Hex8,
            )
            .expect("brick")
        };
        let mut g = Mesh::<3>::default();
        let mut bodies = BTreeMap::new();
        for (name, o) in [("other", 10.0), ("block", 0.0)] {
            let (placed, _) =
                super::super::mesh::append_solid(&mut g, name, make(o), Span::default());
            bodies.insert(name.to_string(), placed.nodes);
        }
        (g, bodies)
    }

    fn res3(text: &str, need: Need) -> Result<Resolved, Diagnostic> {
        let (g, bodies) = brick();
        let mut d = crate::parse::values::Diags::new();
        let r = set_ref(&value_of(text), &mut d).expect("a set reference");
        resolve_solid(&g, &bodies, &r, need, "test")
    }

    #[test]
    fn set_resolution_3d_geometric_selections() {
        let (g, bodies) = brick();
        let range = bodies["block"].clone();
        let top = res3("block.nodes(z = 1)", Need::Nodes).unwrap();
        assert_eq!(top.nodes, g.node_sets["block.zmax"]);
        assert!(top.nodes.iter().all(|n| range.contains(n)));
        // relative tolerance: 1e-6 x sqrt(6) ~ 2.45e-6
        let near_top = res3("block.nodes(z = 1.000002)", Need::Nodes).unwrap();
        assert_eq!(near_top.nodes, top.nodes);
        assert!(res3("block.nodes(z = 1.000003)", Need::Nodes).is_err());
        let faces = res3("block.faces(z = 1)", Need::Edges).unwrap();
        let mut want = g.face_sets["block.zmax"].clone();
        let mut got = faces.faces.clone().unwrap();
        want.sort();
        got.sort();
        assert_eq!(got, want);
        assert_eq!(faces.nodes, top.nodes);
        let boxed = res3("block.faces(box((0, 0, 1), (1, 1, 1)))", Need::Edges).unwrap();
        assert_eq!(boxed.faces.unwrap().len(), 4);
        let b = res3("block.nodes(box((2, 1, 1), (1.5, 0, 0.5)))", Need::Nodes).unwrap();
        assert_eq!(b.nodes.len(), 2 * 3 * 2);
        let n = res3("block.node(near(1.9, 0.1, 0.6))", Need::Nodes).unwrap();
        assert_eq!(n.nodes.len(), 1);
        assert_eq!(g.nodes[n.nodes[0]], [2.0, 0.0, 0.5]);
        // combinations of selections keep faces
        let c = res3("block.faces(z = 1) + block.faces(x = 0)", Need::Edges).unwrap();
        assert_eq!(c.faces.unwrap().len(), 8 + 4);
    }

    #[test]
    fn set_resolution_3d_empty_selections_name_the_cause() {
        let e = res3("block.nodes(z = 2.5)", Need::Nodes).unwrap_err();
        assert_eq!(e.message, "selection `block.nodes(z = 2.5)` is empty");
        assert_eq!(
            e.label,
            "no node of `block` has z = 2.5; its z range is 0 .. 1"
        );
        let e = res3("block.faces(z = 0.5)", Need::Edges).unwrap_err();
        assert_eq!(
            e.label,
            "no boundary face of `block` with all its nodes at z = 0.5"
        );
        assert_eq!(
            e.help.as_deref(),
            Some("12 nodes on the boundary of `block` match, but no boundary face has all its nodes among them")
        );
        let e = res3(
            "block.faces(box((0.4, 0.4, 0.4), (0.6, 0.6, 0.6)))",
            Need::Edges,
        )
        .unwrap_err();
        assert_eq!(
            e.help.as_deref(),
            Some("1 node of `block` matches, but it is inside the body: `faces(..)` takes the boundary faces whose nodes are all selected")
        );
        let e = res3("block.nodes(box((3, 0, 0), (4, 1, 1)))", Need::Nodes).unwrap_err();
        assert_eq!(
            e.help.as_deref(),
            Some("`block` spans x in [0, 2], y in [0, 1] and z in [0, 1]")
        );
        let e = res3("block.nodes(box((0, 0), (1, 1)))", Need::Nodes).unwrap_err();
        assert_eq!(
            e.message,
            "a box corner has 2 coordinates, but the analysis is 3d"
        );
        let e = res3("block.edges(z = 0)", Need::Edges).unwrap_err();
        assert_eq!(e.message, "`edges(..)` in a 3d analysis");
        let e = res3("block.nodes(z = 1)", Need::Edges).unwrap_err();
        assert_eq!(
            e.message,
            "`test` needs boundary faces, but `block.nodes(z = 1)` is a set of nodes"
        );
    }
}
