//! Rules of `contact` items: the slave surface and the master (tool or
//! body surface), duplicate pairs, method and friction parameters,
//! combinations not supported yet.

use super::{sets, Ctx, Need};
use crate::ast::{Method, Span};
use crate::diagnostics::Diagnostic;
use crate::suggest::did_you_mean;
use std::collections::BTreeMap;

/// Checks every contact pair.
pub fn check(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    let tool_names: Vec<&str> = deck.tools.iter().map(|t| t.name.name.as_str()).collect();
    let mut seen: BTreeMap<String, Span> = BTreeMap::new();
    for c in &deck.contacts {
        sets::set_ref(&c.target, Need::Edges, "contact", ctx);
        if let Some(m) = &c.master {
            // deformable master surface: a boundary of a body
            sets::set_ref(m, Need::Edges, "contact master", ctx);
        } else if !tool_names.contains(&c.tool.name.as_str())
            && !deck.broken_named("tool", &c.tool.name)
        {
            ctx.err(
                Diagnostic::error(
                    format!("unknown tool `{}`", c.tool.name),
                    c.tool.span,
                    "no tool with this name",
                )
                .with_help(did_you_mean(&c.tool.name, &tool_names).unwrap_or_else(
                    || {
                        format!(
                        "define it, e.g. `tool {} = plane {{ point = (0, 0)  normal = (0, 1) }}`",
                        c.tool.name
                    )
                    },
                )),
            );
        }
        let key = format!("{} -> {}", c.target, c.tool.name);
        if let Some(first) = seen.get(&key) {
            let line = ctx.line(*first);
            ctx.err(
                Diagnostic::error(
                    format!("contact pair `{key}` is defined twice"),
                    c.target.span.to(c.tool.span),
                    "duplicate pair",
                )
                .with_help(format!("the first definition is on line {line}")),
            );
        } else {
            seen.insert(key, c.target.span);
        }
        match c.method.as_ref().map(|m| &m.value) {
            // A relative coefficient (`10 * E / h`) is checked per slave
            // node when lowered.
            Some(Method::Penalty {
                stiffness,
                relative: None,
                ..
            }) => ctx.must_be_positive(stiffness, "penalty stiffness"),
            Some(Method::Penalty { .. }) => {}
            Some(Method::AugmentedLagrange {
                penalty,
                tolerance,
                relative,
                ..
            }) => {
                if relative.is_none() {
                    ctx.must_be_positive(penalty, "augmented Lagrangian penalty");
                }
                ctx.must_be_positive(tolerance, "augmented Lagrangian tolerance");
            }
            Some(Method::Lagrange { .. }) | None => {}
        }
        ctx.must_be_positive(&c.prof, "prof");
        if let Some(f) = &c.friction {
            if let Some(mu) = f
                .value
                .mu
                .as_ref()
                .filter(|m| m.value < 0.0 || m.value.is_nan())
            {
                ctx.err(Diagnostic::error(
                    "friction coefficient `mu` must not be negative",
                    mu.span,
                    "must be >= 0",
                ));
            }
            ctx.must_be_positive(&f.value.stiffness, "friction stiffness");
            if let (Some(_), Some(m)) = (&c.master, &c.method) {
                if matches!(m.value, Method::Lagrange { .. }) {
                    ctx.err(
                        Diagnostic::error(
                            "Lagrange-multiplier friction against a deformable master is not \
                                 supported yet",
                            f.span,
                            "not supported yet",
                        )
                        .with_help(
                            "use `method = penalty { .. }` or `augmented_lagrange { .. }` \
                                 (regularized friction) for contact between deformable bodies",
                        ),
                    );
                }
            }
        }
        if let (None, Some(st)) = (&c.master, &c.strategy) {
            ctx.err(
                Diagnostic::error(
                    "`strategy` applies to deformable masters only",
                    st.span,
                    "the master is a rigid tool",
                )
                .with_help(
                    "a rigid tool is always the master (single pass); write the master as \
                         `body.set` for contact between deformable bodies",
                ),
            );
        }
        mortar_supported(c, ctx);
        smoothing_supported(c, ctx);
        for r in &c.reserved {
            ctx.err(
                Diagnostic::error(
                    format!("`{}` is not supported yet", r.name),
                    r.span,
                    "not supported yet",
                )
                .with_help("contact is frictionless for now"),
            );
        }
    }
}

/// `smoothing = nodal`: a deformable master, node-to-segment, not the
/// doubled Lagrange form (its `L D L^T` needs a symmetric tangent; the
/// smoothed element's is not).
fn smoothing_supported(c: &crate::ast::Contact, ctx: &mut Ctx<'_>) {
    let Some(s) = c
        .smoothing
        .as_ref()
        .filter(|s| s.value != crate::ast::Smoothing::None)
    else {
        return;
    };
    let nodal = s.value == crate::ast::Smoothing::Nodal;
    let chosen = if nodal { "nodal" } else { "nagata" };
    let mut refuse = |what: &str, span: Span, help: &str| {
        ctx.err(
            Diagnostic::error(
                format!("normal smoothing {what}"),
                span,
                format!("not supported with `smoothing = {chosen}`"),
            )
            .with_secondary(s.span, "smoothing chosen here")
            .with_help(help.to_string()),
        );
    };
    if c.master.is_none() {
        refuse(
            "needs a deformable master surface",
            c.tool.span,
            "rigid tools have their exact geometry (arcs, NURBS): drop `smoothing`, or write \
             the master as `body.set`",
        );
    }
    if let Some(f) = c
        .formulation
        .as_ref()
        .filter(|f| f.value == crate::ast::ContactFormulation::Mortar)
    {
        refuse(
            "is for node-to-segment contact",
            f.span,
            "drop `smoothing` (mortar integrates the gap along the slave surface)",
        );
    }
    if let Some(m) = c.method.as_ref().filter(|m| {
        nodal
            && matches!(
                &m.value,
                Method::Lagrange { formulation: Some(f) }
                    if f.value == crate::ast::LagrangeFormulation::Doubled
            )
    }) {
        refuse(
            "with doubled Lagrange multipliers is not supported (its L D L^T factorization \
             needs a symmetric tangent)",
            m.span,
            "use `method = lagrange { }` (single multipliers, LU)",
        );
    }
}

/// `formulation = mortar`: a deformable master other than the slave
/// surface, single pass, penalty, augmented Lagrangian or (single
/// multipliers, 2D and 3D) Lagrange multipliers; Coulomb friction (penalty
/// or augmented Lagrangian).
fn mortar_supported(c: &crate::ast::Contact, ctx: &mut Ctx<'_>) {
    let Some(f) = c
        .formulation
        .as_ref()
        .filter(|f| f.value == crate::ast::ContactFormulation::Mortar)
    else {
        return;
    };
    let mut refuse = |what: &str, span: Span, help: &str| {
        ctx.err(
            Diagnostic::error(
                format!("mortar contact {what}"),
                span,
                "not supported with mortar",
            )
            .with_secondary(f.span, "mortar chosen here")
            .with_help(help.to_string()),
        );
    };
    match &c.master {
        None => refuse(
            "needs a deformable master surface",
            c.tool.span,
            "write the master as `body.set`, or drop `formulation = mortar` (a rigid tool is \
             always node-to-tool)",
        ),
        Some(m) if m.to_string() == c.target.to_string() => refuse(
            "of a surface with itself (self contact) is not supported yet",
            m.span,
            "use `formulation = node_to_segment` for self contact",
        ),
        Some(_) => {}
    }
    if let Some(st) = c
        .strategy
        .as_ref()
        .filter(|s| s.value != crate::ast::Strategy::SinglePass)
    {
        refuse(
            "is single pass (the integration side is the slave)",
            st.span,
            "remove `strategy`, or use `formulation = node_to_segment` for double passes",
        );
    }
    if let Some(m) = c.method.as_ref() {
        if let Method::Lagrange { formulation } = &m.value {
            if formulation
                .as_ref()
                .is_some_and(|f| f.value == crate::ast::LagrangeFormulation::Doubled)
            {
                refuse(
                    "with doubled Lagrange multipliers is not supported (its L D L^T \
                     factorization needs a symmetric tangent; mortar's is not)",
                    m.span,
                    "use `method = lagrange { }` (single multipliers, LU)",
                );
            }
        }
    }
    if c.thermal.is_some() {
        refuse(
            "with thermal contact is not supported yet",
            c.target.span,
            "use `formulation = node_to_segment` for thermal contact",
        );
    }
    // friction (2D and 3D): penalty and augmented Lagrangian;
    // Lagrange-multiplier friction against a deformable master is refused
    // above for every formulation
}
