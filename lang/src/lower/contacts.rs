//! `contact` items -> `model::ContactPair` (tool or deformable master, method, strategy, friction).

use super::{mesh, Lowerer};
use crate::ast::{self, Method};
use crate::diagnostics::Diagnostic;
use crate::validate::Need;
use ctc_engine::model::{
    self as m, ContactMaster, ContactMethod, ContactPair, ContactStrategy, PenaltyKind,
};

/// One side of a contact pair for a relative penalty: its body, its edges
/// (2D) and its faces (3D).
type ContactSide = (usize, Vec<[usize; 2]>, Vec<ctc_engine::mesh::Facet>);

impl Lowerer<'_> {
    /// Whether body `b` has a cell of order 2.
    fn has_quadratic_cells(&self, b: &m::Body) -> bool {
        let cells = if self.solid {
            &self.mesh3.cells
        } else {
            &self.mesh.cells
        };
        b.cells
            .clone()
            .any(|c| c < cells.len() && cells.kind(c).order() > 1)
    }

    /// Why contact item `c` cannot run on quadratic faces, if it cannot:
    /// the span to mark, the message, the label and the help (the rules of
    /// `ctc_engine::solve::check::quadratic_contact_refusal`).
    fn quadratic_refusal(
        &self,
        c: &ast::Contact,
        bodies: &[m::Body],
    ) -> Option<(ast::Span, String, &'static str, &'static str)> {
        let quadratic = |side: &&ast::SetRef| {
            bodies
                .iter()
                .find(|b| b.name == side.body.name)
                .is_some_and(|b| self.has_quadratic_cells(b))
        };
        let nodal = |k: &Option<ast::Spanned<ast::PenaltyKind>>| {
            k.as_ref()
                .is_some_and(|k| k.value == ast::PenaltyKind::Nodal)
        };
        if c.master.is_some() {
            let sides: Vec<&ast::SetRef> = std::iter::once(&c.target)
                .chain(c.master.as_ref())
                .filter(|s| quadratic(s))
                .collect();
            let side = *sides.first()?;
            let mortar = c
                .formulation
                .as_ref()
                .filter(|f| f.value == ast::ContactFormulation::Mortar);
            // mortar on quadratic faces (both sides, or one: mixed orders),
            // area penalty / augmented Lagrangian, with or without friction
            // (mixed orders: 3D only), or frictionless single Lagrange
            // multipliers (2D seg3: `ctc_engine::contact::mortar::seg3`;
            // 3D tri6 / quad8 / quad9: `ctc_engine::contact::mortar::quadratic3d`)
            let refusal = |span, message: String, label, help| Some((span, message, label, help));
            if mortar.is_none() {
                return refusal(
                    side.span,
                    format!(
                        "node-to-segment contact between deformable bodies on quadratic faces is \
                         not available: body `{}` has quadratic cells",
                        side.body.name
                    ),
                    "this surface has midside nodes",
                    "add `formulation = mortar` (mortar integrates the gap over the quadratic \
                     faces), or mesh the pair with linear cells",
                );
            }
            // Coulomb friction (penalty, augmented Lagrangian:
            // `ctc_engine::contact::mortar::friction_quadratic`) lowers with
            // both sides quadratic, and in 3D with mixed orders (verified
            // there only); Lagrange-multiplier friction against a
            // deformable master is refused for every pair (`validate::contacts`)
            if let (Some(f), 1, false) = (&c.friction, sides.len(), self.solid) {
                return refusal(
                    f.span,
                    "friction with mortar between a linear and a quadratic side is not available \
                     in 2D"
                        .into(),
                    "mixed orders with friction",
                    "mesh both bodies with quadratic cells (friction on quadratic mortar is \
                     available), or drop `friction`",
                );
            }
            let method = c.method.as_ref()?;
            return match &method.value {
                Method::Penalty { kind, .. } | Method::AugmentedLagrange { kind, .. }
                    if nodal(kind) =>
                {
                    refusal(
                        method.span,
                        "a nodal penalty has no meaning on quadratic faces".into(),
                        "the gap is integrated over the quadratic faces",
                        "use `kind = area` (a pressure per unit gap)",
                    )
                }
                _ => None,
            };
        }
        if !quadratic(&&c.target) {
            return None;
        }
        let method = c.method.as_ref()?;
        match &method.value {
            Method::Lagrange { .. } if c.friction.is_some() => Some((
                method.span,
                "Lagrange-multiplier friction is not available on quadratic faces".into(),
                "quadratic slave faces with friction",
                "use `penalty` or `augmented_lagrange` with friction (frictionless Lagrange \
                 multipliers are available)",
            )),
            Method::Penalty { kind, .. } | Method::AugmentedLagrange { kind, .. }
                if nodal(kind) =>
            {
                Some((
                    method.span,
                    "a nodal penalty has no meaning on quadratic faces".into(),
                    "the gap is integrated over the quadratic faces",
                    "use `kind = area` (a pressure per unit gap)",
                ))
            }
            _ => None,
        }
    }

    /// The pairs; `tools` are the names of the lowered tools (curves in
    /// planar analyses, surfaces in `3d`), in `Model` order.
    pub(super) fn contacts(
        &mut self,
        bodies: &[m::Body],
        materials: &[m::Material],
        tools: &[&str],
    ) -> Vec<ContactPair> {
        let mut out = Vec::new();
        for c in &self.deck.contacts {
            if self.has_error_in(c.span) || self.body_failed(&c.target) {
                continue;
            }
            let Some(r) = self.resolve(&c.target, Need::Edges, "contact") else {
                continue;
            };
            let Some(body) = bodies.iter().position(|b| b.name == c.target.body.name) else {
                continue;
            };
            // contact on quadratic faces: rigid tools by the face-integrated
            // penalty or augmented Lagrangian (`contact::face_integrated`);
            // the rest is refused with a caret at its cause
            if let Some((span, message, label, help)) = self.quadratic_refusal(c, bodies) {
                self.diags
                    .push(Diagnostic::error(message, span, label).with_help(help));
                continue;
            }
            // heat across a 3D pair of deformable bodies: the node-to-facet
            // contact does not give the heat solver the master facet's
            // nodes (`thermal::coupling::contact_elements`), so such a pair
            // would exchange no heat at all; refused, not silently wrong
            if let (true, Some(_), Some(t)) = (self.solid, &c.master, &c.thermal) {
                self.diags.push(
                    Diagnostic::error(
                        "thermal contact between two deformable bodies is not available in 3D \
                         yet (heat crosses 3D contact against rigid tools only)",
                        t.span,
                        "heat exchange with a deformable master surface",
                    )
                    .with_help(
                        "make the master a rigid tool at a prescribed temperature \
                         (`tool_temperature`), or model the pair in 2D / axisymmetric \
                         (node-to-segment thermal contact)",
                    ),
                );
                continue;
            }
            let master = match &c.master {
                Some(m) => {
                    if self.body_failed(m) {
                        continue;
                    }
                    let Some(mr) = self.resolve(m, Need::Edges, "contact master") else {
                        continue;
                    };
                    let Some(mbody) = bodies.iter().position(|b| b.name == m.body.name) else {
                        continue;
                    };
                    let medges = mr.edges.unwrap_or_default();
                    let mfaces = mr.faces.unwrap_or_default();
                    let nodes = if mfaces.is_empty() {
                        mesh::edge_nodes(&medges)
                    } else {
                        let mut n: Vec<usize> =
                            mfaces.iter().flat_map(|f| f.nodes().to_vec()).collect();
                        n.sort_unstable();
                        n.dedup();
                        n
                    };
                    ContactMaster::Surface {
                        body: mbody,
                        nodes,
                        edges: medges,
                        faces: mfaces,
                    }
                }
                None => {
                    let Some(tool) = tools.iter().position(|t| *t == c.tool.name) else {
                        self.missing("the tool", c.tool.span);
                        continue;
                    };
                    ContactMaster::Tool(tool)
                }
            };
            let method = match c.method.as_ref().map(|m| &m.value) {
                Some(Method::Penalty {
                    kind,
                    stiffness: Some(s),
                    ..
                }) => ContactMethod::Penalty {
                    kind: match kind.as_ref().map(|k| k.value) {
                        Some(ast::PenaltyKind::Nodal) => PenaltyKind::Nodal,
                        _ => PenaltyKind::Area,
                    },
                    stiffness: s.value,
                },
                Some(Method::Lagrange { formulation }) => ContactMethod::Lagrange {
                    formulation: match formulation.as_ref().map(|f| f.value) {
                        Some(ast::LagrangeFormulation::Doubled) => m::LagrangeFormulation::Doubled,
                        Some(ast::LagrangeFormulation::Condensed) => {
                            m::LagrangeFormulation::Condensed
                        }
                        _ => m::LagrangeFormulation::Single,
                    },
                },
                Some(Method::AugmentedLagrange {
                    kind,
                    penalty: Some(p),
                    tolerance: Some(tol),
                    update,
                    ..
                }) => ContactMethod::AugmentedLagrange {
                    kind: match kind.as_ref().map(|k| k.value) {
                        Some(ast::PenaltyKind::Nodal) => PenaltyKind::Nodal,
                        _ => PenaltyKind::Area,
                    },
                    penalty: p.value,
                    tolerance: tol.value,
                    update: match update.as_ref().map(|u| u.value) {
                        Some(ast::MultiplierUpdate::Newton) => m::MultiplierUpdate::Newton,
                        _ => m::MultiplierUpdate::Converged,
                    },
                },
                _ => {
                    self.missing("a supported contact method", c.tool.span);
                    continue;
                }
            };
            let edges = r.edges.unwrap_or_default();
            let faces = r.faces.unwrap_or_default();
            let relative = match c.method.as_ref().map(|m| &m.value) {
                Some(Method::Penalty { relative, .. })
                | Some(Method::AugmentedLagrange { relative, .. }) => relative.as_ref(),
                _ => None,
            };
            let local_penalty = match relative {
                None => Vec::new(),
                Some(rel) => {
                    // the slave side, and the master side of a deformable pair
                    let mut sides = vec![(body, edges.clone(), faces.clone())];
                    if let ContactMaster::Surface {
                        body: mb,
                        edges: me,
                        faces: mf,
                        ..
                    } = &master
                    {
                        sides.push((*mb, me.clone(), mf.clone()));
                    }
                    let Some(local) = self.local_penalty(rel, &sides, bodies, materials) else {
                        continue;
                    };
                    local
                }
            };
            let nodes = if faces.is_empty() {
                // quadratic edges: their midside nodes are slave nodes too
                let mut n = mesh::edge_nodes(&edges);
                if !self.solid && self.has_quadratic_cells(&bodies[body]) {
                    let midsides = self.mesh.edge_midsides();
                    n.extend(
                        edges
                            .iter()
                            .filter_map(|&[a, b]| midsides.get(&(a.min(b), a.max(b))).copied()),
                    );
                    n.sort_unstable();
                    n.dedup();
                }
                n
            } else {
                let mut n: Vec<usize> = faces.iter().flat_map(|f| f.nodes().to_vec()).collect();
                n.sort_unstable();
                n.dedup();
                n
            };
            out.push(ContactPair {
                name: format!("{} -> {}", c.target, c.tool.name),
                body,
                nodes,
                edges,
                faces,
                master,
                strategy: match c.strategy.as_ref().map(|s| s.value) {
                    Some(ast::Strategy::DoublePass) => ContactStrategy::DoublePass,
                    Some(ast::Strategy::ModifiedDoublePass) => ContactStrategy::ModifiedDoublePass,
                    _ => ContactStrategy::SinglePass,
                },
                formulation: match c.formulation.as_ref().map(|s| s.value) {
                    Some(ast::ContactFormulation::Mortar) => m::ContactFormulation::Mortar,
                    _ => m::ContactFormulation::NodeToSegment,
                },
                smoothing: match c.smoothing.as_ref().map(|s| s.value) {
                    Some(ast::Smoothing::Nodal) => m::NormalSmoothing::Nodal,
                    Some(ast::Smoothing::Nagata) => m::NormalSmoothing::Nagata,
                    _ => m::NormalSmoothing::None,
                },
                search: match c.search.as_ref().map(|s| s.value) {
                    Some(ast::Search::Circle) => m::LocalSearch::Circle,
                    _ => m::LocalSearch::Memory,
                },
                method: match (
                    method,
                    local_penalty.iter().map(|&(_, k)| k).reduce(f64::max),
                ) {
                    // the stiffest node's value stands for the pair in messages
                    (ContactMethod::Penalty { kind, .. }, Some(k)) => {
                        ContactMethod::Penalty { kind, stiffness: k }
                    }
                    (
                        ContactMethod::AugmentedLagrange {
                            kind,
                            tolerance,
                            update,
                            ..
                        },
                        Some(k),
                    ) => ContactMethod::AugmentedLagrange {
                        kind,
                        penalty: k,
                        tolerance,
                        update,
                    },
                    (m, _) => m,
                },
                local_penalty,
                prof: c.prof.as_ref().map(|p| p.value),
                friction: c.friction.as_ref().and_then(|f| {
                    Some(m::Friction {
                        mu: f.value.mu.as_ref()?.value,
                        stiffness: f.value.stiffness.as_ref().map(|s| s.value),
                        first_impact: match f.value.first_impact.as_ref().map(|v| v.value) {
                            Some(ast::FirstImpact::Frictionless) => m::FirstImpact::Frictionless,
                            _ => m::FirstImpact::Intersect,
                        },
                        cut_at_impact: f.value.cut_at_impact.as_ref().is_some_and(|v| v.value),
                    })
                }),
            });
        }
        out
    }

    /// The per-node penalty coefficients of a relative penalty
    /// (`stiffness = 10 * E / h`) over the contact `sides` (body, edges,
    /// faces): `E` is the Young's modulus of the side's body and `h` the
    /// mean length of the side's facet edges meeting at the node. `None`
    /// after reporting a coefficient that is not a positive finite number.
    fn local_penalty(
        &mut self,
        rel: &ast::RelativeStiffness,
        sides: &[ContactSide],
        bodies: &[m::Body],
        materials: &[m::Material],
    ) -> Option<Vec<(usize, f64)>> {
        let mut out: Vec<(usize, f64)> = Vec::new();
        for (body, edges, faces) in sides {
            let young = materials[bodies[*body].material].law.young();
            // (sum of adjacent edge lengths, count) per node
            let mut sum: std::collections::BTreeMap<usize, (f64, usize)> = Default::default();
            let mut add = |a: usize, b: usize, len: f64| {
                for n in [a, b] {
                    let e = sum.entry(n).or_insert((0.0, 0));
                    e.0 += len;
                    e.1 += 1;
                }
            };
            if self.solid {
                let x = &self.mesh3.nodes;
                for f in faces {
                    let n = f.nodes();
                    for k in 0..n.len() {
                        let (a, b) = (n[k], n[(k + 1) % n.len()]);
                        let d: f64 = (0..3).map(|c| (x[a][c] - x[b][c]).powi(2)).sum();
                        add(a, b, d.sqrt());
                    }
                }
            } else {
                let x = &self.mesh.nodes;
                for &[a, b] in edges {
                    let d = ((x[a][0] - x[b][0]).powi(2) + (x[a][1] - x[b][1]).powi(2)).sqrt();
                    add(a, b, d);
                }
            }
            for (node, (total, count)) in sum {
                let h = total / count as f64;
                let mut env = rel.env.clone();
                env.params.push((
                    crate::span::Ident::new("E", rel.expr.span),
                    crate::expr::Quantity::plain(young),
                ));
                env.params.push((
                    crate::span::Ident::new("h", rel.expr.span),
                    crate::expr::Quantity::plain(h),
                ));
                let mut diags = Vec::new();
                let k = crate::expr::eval(&rel.expr, &mut env, &mut diags).and_then(|q| {
                    crate::expr::in_system(
                        q,
                        None,
                        false,
                        "the penalty coefficient",
                        rel.expr.span,
                        &env,
                        &mut diags,
                    )
                });
                match k {
                    Some(k) if k.value.is_finite() && k.value > 0.0 => {
                        out.push((node, k.value));
                    }
                    Some(k) => {
                        self.diags.push(
                            Diagnostic::error(
                                format!(
                                    "the penalty coefficient must be a positive number, but at \
                                     node {node} (E = {young}, h = {h:.6e}) it is {}",
                                    k.value
                                ),
                                rel.expr.span,
                                "evaluated per slave node",
                            )
                            .with_help("write it so it stays positive, e.g. `10 * E / h`"),
                        );
                        return None;
                    }
                    None => {
                        self.diags.append(&mut diags);
                        return None;
                    }
                }
            }
        }
        // a node on both sides (self contact) keeps its stiffest value
        out.sort_by(|a, b| a.0.cmp(&b.0).then(b.1.total_cmp(&a.1)));
        out.dedup_by_key(|e| e.0);
        Some(out)
    }
}
