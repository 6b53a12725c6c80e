//! Rules of the `analysis` block.

use super::Ctx;
use crate::ast::{Analysis, Dimension, Span};
use crate::diagnostics::Diagnostic;

/// Checks the `analysis` block.
pub fn check(ctx: &mut Ctx<'_>) {
    exactly_one(ctx);
    let Some(a) = ctx.deck.analysis.first() else {
        return;
    };
    three_d_deformable_contact_supported(a, ctx);
    thickness_only_in_plane_analyses(a, ctx);
}

/// Whether the deck's analysis is `3d`.
pub fn is_solid(ctx: &Ctx<'_>) -> bool {
    ctx.deck
        .analysis
        .first()
        .and_then(|a| a.dimension.as_ref())
        .is_some_and(|d| d.value == Dimension::ThreeD)
}

/// A deck has exactly one `analysis` block.
pub fn exactly_one(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    if deck.analysis.is_empty() && !deck.has_broken("analysis") {
        ctx.err(
            Diagnostic::error(
                "the deck has no `analysis` block",
                Span::new(0, 0),
                "expected an `analysis` block",
            )
            .with_help(
                "add `analysis { dimension = plane_strain }` (or `plane_stress`, `axisymmetric`)",
            ),
        );
    }
    for extra in deck.analysis.iter().skip(1) {
        let line = ctx.line(deck.analysis[0].keyword);
        ctx.err(
            Diagnostic::error(
                "more than one `analysis` block",
                extra.keyword,
                "second `analysis` block",
            )
            .with_help(format!("the first one is on line {line}; merge them")),
        );
    }
}

/// `dimension = 3d` solves solids in contact with rigid surface tools,
/// frictionless or with Coulomb friction (penalty, augmented Lagrangian,
/// Lagrange multipliers), with heat conduction and thermal contact against
/// the tools, and two deformable solids in node-to-facet contact (every
/// strategy and method; Coulomb friction with the penalty and augmented
/// Lagrangian methods) or mortar contact (single pass; penalty, augmented
/// Lagrangian or single Lagrange multipliers; Coulomb friction with the
/// penalty and augmented Lagrangian methods: [`super::contacts`] refuses
/// the rest),
/// self contact (every method; Coulomb friction with the penalty and
/// augmented Lagrangian methods; the redundant Lagrange rows of two-way
/// pairs are dropped by the engine, `contact::redundancy`); normal
/// smoothing: `nagata` in 3d only (planar analyses have no facets; Coulomb
/// friction on the patches with the penalty and augmented Lagrangian
/// methods), `nodal` (planar) is refused in 3d.
pub fn three_d_deformable_contact_supported(a: &Analysis, ctx: &mut Ctx<'_>) {
    if a.dimension.as_ref().map(|d| d.value) != Some(Dimension::ThreeD) {
        // Nagata patches are surfaces over 3d facets
        for c in &ctx.deck.contacts {
            if let Some(s) = c
                .smoothing
                .as_ref()
                .filter(|s| s.value == crate::ast::Smoothing::Nagata)
            {
                ctx.err(
                    Diagnostic::error(
                        "`smoothing = nagata` is for the master facets of 3d contact",
                        s.span,
                        "a 3d smoothing in a planar analysis",
                    )
                    .with_help("use `smoothing = nodal` (nodal normals along the master segments)"),
                );
            }
        }
        return;
    }
    let deck = ctx.deck;
    let mut refuse = |what: &str, span: Span, help: &str| {
        ctx.err(
            Diagnostic::error(
                format!("3d contact between deformable bodies (node-to-facet) has no {what} yet"),
                span,
                "not supported in 3d yet",
            )
            .with_help(help.to_string()),
        );
    };
    for c in deck.contacts.iter().filter(|c| c.master.is_some()) {
        if let Some(s) = c
            .smoothing
            .as_ref()
            .filter(|s| s.value == crate::ast::Smoothing::Nodal)
        {
            refuse(
                "nodal normal smoothing (the planar nodal normals along segments)",
                s.span,
                "drop `smoothing` (faceted master)",
            );
        }
    }
}

/// `thickness` is positive, and ignored (warning) in axisymmetric analyses.
pub fn thickness_only_in_plane_analyses(a: &Analysis, ctx: &mut Ctx<'_>) {
    let Some(t) = &a.thickness else { return };
    if a.dimension.as_ref().map(|d| d.value) == Some(Dimension::Axisymmetric) {
        ctx.err(
            Diagnostic::warning(
                "`thickness` is ignored in axisymmetric analyses",
                t.span,
                "ignored",
            )
            .with_help("axisymmetric results are totals over the full 2*pi; remove `thickness`"),
        );
    } else {
        ctx.must_be_positive(&a.thickness, "thickness");
    }
}
