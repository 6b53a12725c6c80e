//! Rules of `body` items: names, materials, kinematics, and the settings
//! of their mesh generators (ranges from the generator's key table, then
//! the generator's own rules, then the cell budget).

use super::{cell_limit, ranges, BodyInfo, Ctx};
use crate::ast::{Body, Dimension, FormulationKind, Generator, KinematicsKind, MeshDef, Span};
use crate::diagnostics::Diagnostic;
use crate::generators::add_builtin_sets;
use crate::suggest::did_you_mean;
use std::collections::BTreeMap;

/// Checks every body and records its sets for later references.
pub fn check(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    at_least_one(ctx);
    ctx.names_are_unique(deck.bodies.iter().map(|b| &b.name), "body");
    let dim = deck
        .analysis
        .first()
        .and_then(|a| a.dimension.as_ref())
        .map(|d| d.value);
    for b in &deck.bodies {
        kinematics_fit_material_and_dimension(b, dim, ctx);
        material_exists(b, ctx);
        let mut sets = None;
        if let Some(MeshDef::Generator(g)) = b.mesh.as_ref().map(|m| &m.value) {
            generator_fits_dimension(g, dim, ctx);
            generator_settings_valid(g, ctx);
            sets = g.def.set_kinds(&g.settings);
            selective_reduced_needs_quads(b, g, ctx);
            plastic_flow_locks_full_quads(b, g, dim, ctx);
        }
        let mut deck_sets = BTreeMap::new();
        if sets.is_none() {
            // A mesh file's sets are only known once it is read, but the
            // built-in ones exist anyway (and their kinds are known).
            add_builtin_sets(&mut deck_sets);
        }
        ctx.bodies
            .entry(b.name.name.clone())
            .or_insert(BodyInfo { sets, deck_sets });
    }
}

/// A deck has at least one body.
pub fn at_least_one(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    if deck.bodies.is_empty()
        && !deck.has_broken("body")
        && !deck.broken.iter().any(|b| b.keyword.is_empty())
    {
        ctx.err(
            Diagnostic::error("the deck has no `body`", Span::new(0, 0), "expected a `body`")
                .with_help("add e.g. `body block { mesh = rectangle { size = (1, 1)  divisions = (10, 10) }  material = steel }`"),
        );
    }
}

/// Kinematics against the material law and the analysis dimension:
/// plane stress has neither finite strain nor plasticity yet, and a
/// Neo-Hookean material needs `kinematics = finite`.
pub fn kinematics_fit_material_and_dimension(b: &Body, dim: Option<Dimension>, ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    let finite = b
        .kinematics
        .as_ref()
        .filter(|k| k.value == KinematicsKind::Finite);
    let material = b
        .material
        .as_ref()
        .and_then(|n| deck.materials.iter().find(|m| m.name.name == n.name));
    let plastic = material.is_some_and(|m| m.plastic.is_some());
    if dim == Some(Dimension::PlaneStress) {
        if let Some(k) = finite {
            ctx.err(
                Diagnostic::error(
                    "finite strain in plane stress is not supported yet",
                    k.span,
                    "not supported yet",
                )
                .with_help("use `dimension = plane_strain` or `axisymmetric`"),
            );
        } else if plastic {
            ctx.err(
                Diagnostic::error(
                    "plasticity in plane stress is not supported yet",
                    b.name.span,
                    "not supported yet",
                )
                .with_help("use `dimension = plane_strain` or `axisymmetric`"),
            );
        }
    }
    if let Some(m) = material.filter(|m| m.neo_hookean.is_some()) {
        if finite.is_none() {
            ctx.err(
                Diagnostic::error(
                    format!(
                        "material `{}` is Neo-Hookean, a finite-strain law: body `{}` needs \
                         `kinematics = finite`",
                        m.name.name, b.name.name
                    ),
                    b.name.span,
                    "small-strain body",
                )
                .with_help("add `kinematics = finite` to the body"),
            );
        }
    }
}

/// The body's material is defined.
pub fn material_exists(b: &Body, ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    let Some(m) = &b.material else { return };
    let names: Vec<&str> = deck
        .materials
        .iter()
        .map(|m| m.name.name.as_str())
        .collect();
    if names.contains(&m.name.as_str()) || deck.broken_named("material", &m.name) {
        return;
    }
    ctx.err(
        Diagnostic::error(
            format!("unknown material `{}`", m.name),
            m.span,
            "no material with this name",
        )
        .with_help(did_you_mean(&m.name, &names).unwrap_or_else(|| {
            format!(
                "define it with `material {} {{ elastic {{ E = ..  nu = .. }} }}`",
                m.name
            )
        })),
    );
}

/// Solid generators in `3d` analyses, planar ones in planar analyses.
pub fn generator_fits_dimension(g: &Generator, dim: Option<Dimension>, ctx: &mut Ctx<'_>) {
    let Some(dim) = dim else { return };
    let solid = dim == Dimension::ThreeD;
    if g.def.build.is_solid() == solid {
        return;
    }
    let names = |want: bool| -> String {
        crate::generators::REGISTRY
            .iter()
            .filter(|d| d.build.is_solid() == want)
            .map(|d| format!("`{}`", d.name))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let (message, help) = if solid {
        (
            format!(
                "`{}` makes a planar mesh, but the analysis is 3d",
                g.name.name
            ),
            format!(
                "use a solid generator ({}) or a gmsh file of tetrahedra / hexahedra",
                names(true)
            ),
        )
    } else {
        (
            format!(
                "`{}` makes a solid (3D) mesh, but the analysis is planar",
                g.name.name
            ),
            format!(
                "use `dimension = 3d`, or a planar generator ({})",
                names(false)
            ),
        )
    };
    ctx.err(Diagnostic::error(message, g.name.span, "wrong dimension").with_help(help));
}

/// A generator's settings: the ranges of its key table, its own rules,
/// and at most [`super::cell_limit`] cells ([`super::MAX_CELLS`]).
pub fn generator_settings_valid(g: &Generator, ctx: &mut Ctx<'_>) {
    ranges::settings_in_range(&g.settings, g.def.keys, ctx);
    (g.def.check)(g, ctx);
    crate::generators::reduced_integration_needs_quadratic_quads(g, ctx);
    let cells = (g.def.cells)(&g.settings);
    let limit = cell_limit();
    if cells > limit {
        ctx.err(
            Diagnostic::error(
                format!("the `{}` mesh would have {cells} cells", g.name.name),
                g.name.span,
                "too many cells",
            )
            .with_help(format!("at most {limit} cells per generated mesh")),
        );
    }
}

/// Warning: selective reduced integration does nothing on triangles.
pub fn selective_reduced_needs_quads(b: &Body, g: &Generator, ctx: &mut Ctx<'_>) {
    let Some(f) = &b.formulation else {
        return;
    };
    let tri3 = g.settings.get("element").is_some_and(|el| {
        matches!(
            el.value.value,
            crate::ast::settings::SettingValue::Choice("tri3")
        )
    });
    let quadratic = g.settings.integer("order", g.def.keys) == Some(2);
    if f.value == FormulationKind::SelectiveReduced && quadratic {
        ctx.err(
            Diagnostic::warning(
                "`selective_reduced` has no effect on quadratic cells",
                f.span,
                "quadratic cells use their full (or `integration = reduced`) Gauss rule",
            )
            .with_help(
                "leave `formulation` out with `order = 2`, or use `integration = reduced` \
                 (quad8R / hex20R)",
            ),
        );
        return;
    }
    if f.value == FormulationKind::SelectiveReduced && tri3 {
        ctx.err(
            Diagnostic::warning(
                "`selective_reduced` has no effect on triangles",
                f.span,
                "tri3 elements always use one integration point",
            )
            .with_help("use `element = quad4` for selective reduced integration"),
        );
    }
}

/// Warning: fully integrated quad4 / hex8 cells lock under plastic or
/// Norton-Hoff flow, which is incompressible (a 100 x 2 quad diaphragm
/// bulged by a gas pressure came out 16 % too stiff at the pole, with a
/// +-640 checkerboard in a stress of 20; `ctc verify
/// superplastic_free_bulge` uses F-bar). Generated meshes only (a mesh
/// file's cells are known after reading it).
pub fn plastic_flow_locks_full_quads(
    b: &Body,
    g: &Generator,
    dim: Option<Dimension>,
    ctx: &mut Ctx<'_>,
) {
    let deck = ctx.deck;
    let flows = b
        .material
        .as_ref()
        .and_then(|n| deck.materials.iter().find(|m| m.name.name == n.name))
        .is_some_and(|m| m.plastic.is_some() || m.norton_hoff.is_some());
    let full = b
        .formulation
        .as_ref()
        .is_none_or(|f| f.value == FormulationKind::Full);
    let simplex = matches!(
        g.settings.choice("element", g.def.keys),
        Some("tri3" | "tet4")
    );
    let quadratic = g.settings.integer("order", g.def.keys) == Some(2);
    if !flows || !full || simplex || quadratic || dim == Some(Dimension::PlaneStress) {
        return;
    }
    let span = b.formulation.as_ref().map_or(b.name.span, |f| f.span);
    ctx.err(
        Diagnostic::warning(
            format!(
                "fully integrated {} cells lock under plastic flow",
                if dim == Some(Dimension::ThreeD) {
                    "hex8"
                } else {
                    "quad4"
                }
            ),
            span,
            "plastic flow is incompressible: the volumetric constraint locks full integration",
        )
        .with_help(
            "add `formulation = selective_reduced` (F-bar at finite strain, B-bar at small \
             strain), as Abaqus' CPE4 / CAX4 / C3D8 do",
        ),
    );
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    #[test]
    fn annulus_divisions_must_span_less_than_half_a_turn() {
        let m = messages("body ring { mesh = annulus { center = (0, 0) inner = 1 outer = 2 radial = 1 circumferential = 2 } material = steel }");
        assert_eq!(
            m,
            [
                "circumferential divisions must be at least 3",
                "each circumferential division must span less than 180 degrees"
            ]
        );
    }

    #[test]
    fn generator_ranges_come_from_the_key_tables() {
        let m = messages(
            "body r { mesh = rectangle { size = (0, -1) divisions = (0, 2) grading = (geometric(-1), uniform) } material = steel }",
        );
        assert_eq!(
            m,
            [
                "width must be positive",
                "height must be positive",
                "divisions along x must be at least 1",
                "grading ratio must be positive"
            ]
        );
        let m = messages(
            "body d { mesh = half_disc { center = (0, 3) radius = 1 radial = 1 circumferential = 1 } material = steel }",
        );
        assert_eq!(m, ["circumferential divisions must be at least 2"]);
        let m = messages(
            "body d { mesh = quarter_disc { center = (0, 3) radius = 1 radial = 1 circumferential = 1 } material = steel }",
        );
        assert!(m.is_empty(), "{m:?}");
    }

    #[test]
    fn cell_budget() {
        let m = messages(
            "body r { mesh = rectangle { size = (1, 1) divisions = (3000, 3000) } material = steel }",
        );
        assert_eq!(m, ["the `rectangle` mesh would have 9000000 cells"]);
    }
}
