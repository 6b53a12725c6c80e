//! Rules of `set` items and of set references anywhere in the deck.

use super::{Ctx, Need, SetKind};
use crate::ast::{Selection, SetRef, SetRefKind};
use crate::diagnostics::Diagnostic;
use crate::span::Spanned;
use crate::suggest::did_you_mean;

/// Checks every `set` item (in deck order: a set is known to the items
/// after it) and records it on its body.
pub fn check(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    for s in &deck.sets {
        let ok = set_ref(&s.target, Need::Nodes, "set", ctx);
        let Some(info) = ctx.bodies.get(&s.target.body.name) else {
            ctx.orphan_sets.push(s.name.name.clone());
            continue;
        };
        let name = &s.name.name;
        let clash = info.deck_sets.contains_key(name)
            || info.sets.as_ref().is_some_and(|m| m.contains_key(name));
        if clash {
            // rule: a set name is defined once per body
            let what = if matches!(name.as_str(), "boundary" | "all") {
                format!("`{name}` is a built-in set of every body")
            } else {
                format!("body `{}` already has a set `{name}`", s.target.body.name)
            };
            ctx.err(
                Diagnostic::error(
                    format!("set `{}.{name}` is defined twice", s.target.body.name),
                    s.name.span,
                    what,
                )
                .with_help("choose another name"),
            );
            continue;
        }
        let kind = match &s.target.kind {
            SetRefKind::Edges(_) => SetKind::Edges,
            SetRefKind::Faces(_) => SetKind::Faces,
            // Unknown kind (set of a mesh file): be permissive here, the
            // lowering checks it against the mesh.
            SetRefKind::Named(_) => ok.unwrap_or(SetKind::Edges),
            // a union / difference of edge (face) sets keeps its edges
            // (faces): `set sides = b.boundary - b.zmin - b.zmax`; terms of
            // unknown kind (sets of a mesh file, of `extrude`): permissive,
            // as for a named set
            SetRefKind::Combination(_) => ok.unwrap_or(SetKind::Edges),
            _ => SetKind::Nodes,
        };
        if let Some(info) = ctx.bodies.get_mut(&s.target.body.name) {
            info.deck_sets.insert(name.clone(), kind);
        }
    }
}

/// A set reference names a known body and one of its sets, with edges
/// where `need` asks for them; returns the kind of the set when known.
/// `user` names the item in messages.
pub fn set_ref(r: &SetRef, need: Need, user: &str, ctx: &mut Ctx<'_>) -> Option<SetKind> {
    if let SetRefKind::Combination(terms) = &r.kind {
        return combination(r, terms, need, user, ctx);
    }
    let solid = super::analysis::is_solid(ctx);
    if let SetRefKind::Nodes(s)
    | SetRefKind::Node(s)
    | SetRefKind::Edges(s)
    | SetRefKind::Faces(s) = &r.kind
    {
        if ctx.bodies.contains_key(&r.body.name) && !selection_fits_dimension(r, s, solid, ctx) {
            return None;
        }
    }
    let deck = ctx.deck;
    let body = &r.body.name;
    let Some(info) = ctx.bodies.get(body) else {
        if !deck.broken_named("body", body) {
            let names: Vec<&str> = deck.bodies.iter().map(|b| b.name.name.as_str()).collect();
            ctx.err(
                Diagnostic::error(
                    format!("unknown body `{body}`"),
                    r.body.span,
                    "no body with this name",
                )
                .with_help_opt(did_you_mean(body, &names)),
            );
        }
        return None;
    };
    let kind = match &r.kind {
        SetRefKind::Nodes(_) | SetRefKind::Node(_) => Some(SetKind::Nodes),
        SetRefKind::Edges(_) => Some(SetKind::Edges),
        SetRefKind::Faces(_) => Some(SetKind::Faces),
        SetRefKind::Combination(_) => None,
        SetRefKind::Named(n) => {
            let found = info
                .deck_sets
                .get(&n.name)
                .or_else(|| info.sets.as_ref().and_then(|m| m.get(&n.name)))
                .copied();
            match (&info.sets, found) {
                (_, Some(k)) => Some(k),
                (None, None) => None,
                (Some(_), None) if ctx.orphan_sets.contains(&n.name) => None,
                (Some(known), None) => {
                    let mut names: Vec<&str> = known.keys().map(String::as_str).collect();
                    names.extend(info.deck_sets.keys().map(String::as_str));
                    let d = Diagnostic::error(
                        format!("body `{body}` has no set `{}`", n.name),
                        n.span,
                        "no set with this name",
                    )
                    .with_help(did_you_mean(&n.name, &names).unwrap_or_else(|| {
                        format!("its sets are {}", crate::suggest::one_of(&names))
                    }));
                    ctx.err(d);
                    return None;
                }
            }
        }
    };
    if need == Need::Edges && kind == Some(SetKind::Nodes) {
        let (word, call) = if solid {
            ("faces", "faces")
        } else {
            ("edges", "edges")
        };
        let help = match &r.kind {
            SetRefKind::Nodes(s) => {
                format!("select boundary {word} with `{body}.{call}({})`", s.value)
            }
            _ => format!("use a set with {word}, e.g. `{body}.boundary` or `{body}.{call}(..)`"),
        };
        ctx.err(
            Diagnostic::error(
                format!("`{user}` needs boundary {word}, but `{r}` is a set of nodes"),
                r.span,
                "nodes only",
            )
            .with_help(help),
        );
    }
    kind
}

/// Rule: a geometric selection has the coordinates of the analysis
/// (`z = ..` and `(x, y, z)` points in 3d only, `(x, y)` points in planar
/// analyses only) and selects the facets the analysis has (`edges(..)` in
/// planar analyses, `faces(..)` in 3d). Reports and returns false when not.
pub fn selection_fits_dimension(
    r: &SetRef,
    s: &Spanned<Selection>,
    solid: bool,
    ctx: &mut Ctx<'_>,
) -> bool {
    let d = dimension_mismatch(s, solid).or_else(|| facet_kind_mismatch(r, solid));
    match d {
        Some(d) => {
            ctx.err(d);
            false
        }
        None => true,
    }
}

/// The diagnostic of a selection whose coordinates do not fit the analysis
/// (`solid`: a 3d analysis), at the offending coordinate or point.
pub fn dimension_mismatch(s: &Spanned<Selection>, solid: bool) -> Option<Diagnostic> {
    let (n, analysis, point) = if solid {
        (3, "3d", "(x, y, z)")
    } else {
        (2, "planar", "(x, y)")
    };
    match &s.value {
        Selection::Z(_) if !solid => Some(
            Diagnostic::error(
                "`z = ..` in a planar analysis",
                s.span,
                "no z coordinate in 2D",
            )
            .with_help("planar analyses have x and y only; use `dimension = 3d` for solids"),
        ),
        Selection::X(_) | Selection::Y(_) | Selection::Z(_) => None,
        Selection::Box { min, max } => [min, max].into_iter().find(|c| c.len() != n).map(|c| {
            Diagnostic::error(
                format!(
                    "a box corner has {} coordinates, but the analysis is {analysis}",
                    c.len()
                ),
                c.span(),
                format!("expected {point}"),
            )
            .with_help(if solid {
                "a 3d analysis selects with `box((x0, y0, z0), (x1, y1, z1))`"
            } else {
                "a planar analysis selects with `box((x0, y0), (x1, y1))`"
            })
        }),
        Selection::Near(p) if p.len() != n => Some(
            Diagnostic::error(
                format!(
                    "`near` has {} coordinates, but the analysis is {analysis}",
                    p.len()
                ),
                p.span(),
                format!("expected `near{point}`"),
            )
            .with_help(format!("the point is {point} in a {analysis} analysis")),
        ),
        Selection::Near(_) => None,
    }
}

/// The diagnostic of `edges(..)` in a 3d analysis or `faces(..)` in a
/// planar one.
pub fn facet_kind_mismatch(r: &SetRef, solid: bool) -> Option<Diagnostic> {
    let body = &r.body.name;
    match &r.kind {
        SetRefKind::Edges(s) if solid => Some(
            Diagnostic::error(
                "`edges(..)` in a 3d analysis",
                r.span,
                "solids have boundary faces",
            )
            .with_help(format!(
                "select boundary faces with `{body}.faces({})`",
                s.value
            )),
        ),
        SetRefKind::Faces(s) if !solid => Some(
            Diagnostic::error(
                "`faces(..)` in a planar analysis",
                r.span,
                "planar bodies have boundary edges",
            )
            .with_help(format!(
                "select boundary edges with `{body}.edges({})`",
                s.value
            )),
        ),
        _ => None,
    }
}

/// A union / difference: every term must exist; it has edges when every
/// term has edges (removing a node set leaves nodes only).
fn combination(
    r: &SetRef,
    terms: &[(bool, SetRef)],
    need: Need,
    user: &str,
    ctx: &mut Ctx<'_>,
) -> Option<SetKind> {
    let mut kinds = Vec::new();
    for (_, t) in terms {
        kinds.push(set_ref(t, Need::Nodes, user, ctx));
    }
    if kinds.iter().any(Option::is_none) {
        return None;
    }
    // the built-in `boundary` is recorded as edges in every analysis: in
    // 3d it is the boundary faces, so edges and faces mix into faces
    // (`b.boundary - b.zmin - b.zmax`)
    let facets = |k: &Option<SetKind>| matches!(k, Some(SetKind::Edges | SetKind::Faces));
    let kind = if !kinds.iter().all(facets) {
        SetKind::Nodes
    } else if super::analysis::is_solid(ctx) {
        SetKind::Faces
    } else {
        SetKind::Edges
    };
    if need == Need::Edges && kind == SetKind::Nodes {
        let (_, nodes_only) = terms
            .iter()
            .zip(&kinds)
            .find(|(_, k)| **k == Some(SetKind::Nodes))
            .map(|(t, _)| t)
            .expect("a node-only term");
        ctx.err(
            Diagnostic::error(
                format!("`{user}` needs boundary edges, but `{r}` is a set of nodes"),
                r.span,
                "nodes only",
            )
            .with_secondary(nodes_only.span, "a set of nodes")
            .with_help("every set of the combination must have edges"),
        );
    }
    Some(kind)
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    #[test]
    fn unknown_names_with_suggestions() {
        let m = messages("set s = blok.nodes(x = 0)\ndisplace block.tpo { uy = -1 }\ncontact block.top -> punh { method = penalty { stiffness = 1 } }\ntool punch = circle { center = (0, 2) radius = 1 }");
        assert_eq!(
            m,
            [
                "unknown body `blok`",
                "unknown tool `punh`",
                "body `block` has no set `tpo`"
            ]
        );
    }

    #[test]
    fn edges_needed_for_pressure_and_contact() {
        let m = messages("pressure block.nodes(y = 1) { p = 1 }\npressure block.corner_tl { p = 1 }\npressure block.edges(y = 1) { p = 1 }");
        assert_eq!(
            m,
            [
                "`pressure` needs boundary edges, but `block.nodes(y = 1)` is a set of nodes",
                "`pressure` needs boundary edges, but `block.corner_tl` is a set of nodes"
            ]
        );
    }

    #[test]
    fn deck_sets_are_known_to_later_references() {
        let m = messages(
            "set clamp = block.edges(y = 0)\npressure block.clamp { p = 1 }\nset clamp = block.top",
        );
        assert_eq!(m, ["set `block.clamp` is defined twice"]);
    }

    /// A `set` item naming a union / difference keeps the terms' edges
    /// (faces in 3d): pressure and contact take it; with a node-only term
    /// it is a set of nodes.
    #[test]
    fn deck_sets_of_combinations_keep_their_facets() {
        let m = messages(
            "set sides = block.boundary - block.top
pressure block.sides { p = 1 }
             set mixed = block.top + block.nodes(y = 0)
pressure block.mixed { p = 1 }",
        );
        assert_eq!(
            m,
            ["`pressure` needs boundary edges, but `block.mixed` is a set of nodes"]
        );
        let m = solid(
            "set sides = block.boundary - block.zmin - block.zmax
             pressure block.sides { p = 1 }
             set mixed = block.zmax + block.nodes(z = 0)
pressure block.mixed { p = 1 }",
        );
        assert_eq!(
            m,
            ["`pressure` needs boundary faces, but `block.mixed` is a set of nodes"]
        );
    }

    /// A unit-cube `block` (hex8) in a 3d analysis followed by `extra`.
    fn solid(extra: &str) -> Vec<String> {
        crate::validate::test_support::messages_of(&format!(
            "analysis {{ dimension = 3d }}\n\
             material steel {{ elastic {{ E = 210e3  nu = 0.3 }} }}\n\
             body block {{ mesh = box {{ size = (1, 1, 1)  divisions = (2, 2, 2) }}  material = steel }}\n\
             fix block.zmin {{ ux uy uz }}\n\
             step load {{ time = 0 .. 1  increments = 1 }}\n{extra}"
        ))
    }

    #[test]
    fn selection_fits_dimension_3d_selections_in_a_3d_analysis() {
        let m = solid(
            "fix block.nodes(z = 0) { uz }\n\
             fix block.node(near(0, 0, 0)) { ux uy }\n\
             fix block.faces(box((0, 0, 0), (1, 0, 1))) { uy }\n\
             pressure block.faces(z = 1) { p = 1 }\n\
             set top = block.faces(z = 1)\npressure block.top { p = 1 }",
        );
        assert!(m.is_empty(), "{m:?}");
    }

    #[test]
    fn selection_fits_dimension_wrong_coordinate_counts() {
        let m = solid(
            "fix block.nodes(box((0, 0), (1, 1))) { uz }\n\
             fix block.node(near(0, 0)) { ux }\n\
             fix block.edges(z = 0) { ux }\n\
             pressure block.nodes(z = 1) { p = 1 }",
        );
        assert_eq!(
            m,
            [
                "a box corner has 2 coordinates, but the analysis is 3d",
                "`near` has 2 coordinates, but the analysis is 3d",
                "`edges(..)` in a 3d analysis",
                "`pressure` needs boundary faces, but `block.nodes(z = 1)` is a set of nodes",
            ]
        );
        let m = messages(
            "fix block.nodes(z = 0) { ux }\n\
             fix block.node(near(0, 0, 1)) { ux }\n\
             fix block.nodes(box((0, 0, 0), (1, 1, 1))) { ux }\n\
             pressure block.faces(y = 1) { p = 1 }",
        );
        assert_eq!(
            m,
            [
                "`z = ..` in a planar analysis",
                "`near` has 3 coordinates, but the analysis is planar",
                "a box corner has 3 coordinates, but the analysis is planar",
                "`faces(..)` in a planar analysis",
            ]
        );
    }
}
