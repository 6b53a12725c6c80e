//! Rules of `tool` items (rigid analytical tools).

use super::{time_fns, Ctx};
use crate::ast::{num, Point, Point3, Spanned, SurfaceGeometry, Tool, ToolGeometry};
use crate::diagnostics::Diagnostic;

/// Checks every tool.
pub fn check(ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    ctx.names_are_unique(deck.tools.iter().map(|t| &t.name), "tool");
    for t in &deck.tools {
        dimension_matches_analysis(t, ctx);
        geometry_valid(t, ctx);
        if let Some(m) = &t.motion {
            for f in [&m.ux, &m.uy, &m.uz, &m.rotation, &m.moment]
                .into_iter()
                .flatten()
            {
                time_fns::ramp_and_table_times_increase(f, ctx);
            }
            free_rotation(t, m, ctx);
        }
        is_used(t, ctx);
    }
}

/// The geometry of a tool: nonzero plane normal, polyline and arc lengths,
/// positive radii, consistent NURBS data.
pub fn geometry_valid(t: &Tool, ctx: &mut Ctx<'_>) {
    match &t.geometry {
        ToolGeometry::Plane { normal, .. } => {
            if let Some(n) = normal
                .as_ref()
                .filter(|n| n.value[0] == 0.0 && n.value[1] == 0.0)
            {
                ctx.err(Diagnostic::error(
                    "the plane normal is zero",
                    n.span,
                    "normal = (0, 0)",
                ));
            }
        }
        ToolGeometry::Polyline { points } => {
            if let Some(p) = points {
                polyline_segments_nonzero(p, ctx);
            }
        }
        ToolGeometry::Arc {
            radius, start, end, ..
        } => {
            ctx.must_be_positive(radius, "radius");
            if let (Some(s), Some(e)) = (start, end) {
                let sweep = (e.value - s.value).abs();
                if sweep == 0.0 {
                    ctx.err(Diagnostic::error(
                        "the arc has no length",
                        e.span,
                        format!("start = end = {}", num(e.value)),
                    ));
                } else if sweep > 360.0 {
                    ctx.err(Diagnostic::error(
                        "an arc spans at most 360 degrees",
                        e.span,
                        format!("|end - start| = {}", num(sweep)),
                    ));
                }
            }
        }
        ToolGeometry::Circle { radius, .. } => ctx.must_be_positive(radius, "radius"),
        ToolGeometry::Nurbs {
            degree,
            points,
            weights,
            knots,
        } => nurbs_data_consistent(degree, points, weights, knots, ctx),
        ToolGeometry::Surface(g) => surface_valid(g, ctx),
    }
}

/// Curve tools belong to planar analyses, surface tools (and the `uz`,
/// `axis` and 3-coordinate `center` of a motion) to `3d` ones.
pub fn dimension_matches_analysis(t: &Tool, ctx: &mut Ctx<'_>) {
    let solid = super::analysis::is_solid(ctx);
    let surface = matches!(t.geometry, ToolGeometry::Surface(_));
    if solid && !surface {
        ctx.err(
            Diagnostic::error(
                format!(
                    "a `{}` tool is a curve of planar analyses; the analysis is `3d`",
                    t.kind.name
                ),
                t.kind.span,
                "a planar tool",
            )
            .with_help(
                "in 3d use a surface: `plane` with `(x, y, z)` points, `sphere`, `cylinder`, \
                 `cone`, `torus`, `iges` or `stl`",
            ),
        );
    } else if !solid && surface {
        ctx.err(
            Diagnostic::error(
                format!(
                    "a `{}` tool with `(x, y, z)` points needs a `3d` analysis",
                    t.kind.name
                ),
                t.kind.span,
                "a 3d surface",
            )
            .with_help("set `analysis { dimension = 3d }`, or give planar `(x, y)` points"),
        );
    }
    let Some(m) = &t.motion else { return };
    if solid {
        if let Some(c) = &m.center {
            ctx.err(Diagnostic::error(
                "the centre of rotation of a 3d tool has three coordinates",
                c.span,
                "expected `(x, y, z)`",
            ));
        }
    } else {
        let spatial = [
            m.uz.as_ref().map(|f| f.span),
            m.center3.as_ref().map(|c| c.span),
        ]
        .into_iter()
        .chain([m.axis.as_ref().map(|a| a.span)]);
        for span in spatial.flatten() {
            ctx.err(
                Diagnostic::error(
                    "`uz`, `axis` and a 3-coordinate `center` need a `3d` analysis",
                    span,
                    "a 3d motion",
                )
                .with_help(
                    "planar tools move by `ux`, `uy` and `rotation` about `center = (x, y)`",
                ),
            );
        }
    }
}

/// A nonzero vector.
fn nonzero(v: &Option<Point3>, what: &str, ctx: &mut Ctx<'_>) {
    if let Some(v) = v.as_ref().filter(|v| v.value.iter().all(|c| *c == 0.0)) {
        ctx.err(Diagnostic::error(
            format!("the {what} is zero"),
            v.span,
            "(0, 0, 0)",
        ));
    }
}

/// The geometry of a surface tool: nonzero normals and axes, positive
/// radii, a cone's half angle strictly between 0 and 90 degrees, a torus
/// tube thinner than its centre circle.
pub fn surface_valid(g: &SurfaceGeometry, ctx: &mut Ctx<'_>) {
    match g {
        SurfaceGeometry::Plane { normal, .. } => nonzero(normal, "plane normal", ctx),
        SurfaceGeometry::Sphere { radius, .. } => ctx.must_be_positive(radius, "radius"),
        SurfaceGeometry::Cylinder { axis, radius, .. } => {
            nonzero(axis, "cylinder axis", ctx);
            ctx.must_be_positive(radius, "radius");
        }
        SurfaceGeometry::Cone { axis, angle, .. } => {
            nonzero(axis, "cone axis", ctx);
            if let Some(a) = angle
                .as_ref()
                .filter(|a| !(a.value > 0.0 && a.value < 90.0))
            {
                ctx.err(Diagnostic::error(
                    "the half angle of a cone is between 0 and 90 degrees",
                    a.span,
                    format!("angle = {}", num(a.value)),
                ));
            }
        }
        // the file is read (and its errors reported) when the deck is lowered
        SurfaceGeometry::Iges { .. } | SurfaceGeometry::Stl { .. } => {}
        SurfaceGeometry::Torus {
            axis, major, minor, ..
        } => {
            nonzero(axis, "torus axis", ctx);
            ctx.must_be_positive(major, "major radius");
            ctx.must_be_positive(minor, "minor radius");
            if let (Some(a), Some(b)) = (major, minor) {
                if b.value >= a.value && a.value > 0.0 {
                    ctx.err(
                        Diagnostic::error(
                            "the tube of a torus is thinner than its centre circle",
                            b.span,
                            format!("minor = {} >= major = {}", num(b.value), num(a.value)),
                        )
                        .with_help("a ring torus needs minor < major"),
                    );
                }
            }
        }
    }
}

/// Warning for a tool no contact pair uses.
pub fn is_used(t: &Tool, ctx: &mut Ctx<'_>) {
    let deck = ctx.deck;
    let used = deck.contacts.iter().any(|c| c.tool.name == t.name.name);
    let dangling = deck
        .contacts
        .iter()
        .any(|c| !deck.tools.iter().any(|t| t.name.name == c.tool.name));
    if !used && !dangling && !deck.has_broken("contact") {
        ctx.err(Diagnostic::warning(
            format!("tool `{}` is not used by any contact pair", t.name.name),
            t.name.span,
            "unused",
        ));
    }
}

/// At least 2 points, no zero-length segment.
pub fn polyline_segments_nonzero(p: &Spanned<Vec<Point>>, ctx: &mut Ctx<'_>) {
    if p.value.len() < 2 {
        ctx.err(Diagnostic::error(
            "a polyline needs at least 2 points",
            p.span,
            format!("{} point(s)", p.value.len()),
        ));
    }
    for w in p.value.windows(2) {
        if w[0].value == w[1].value {
            ctx.err(
                Diagnostic::error(
                    "zero-length polyline segment",
                    w[1].span,
                    "same point as the previous one",
                )
                .with_help("remove the repeated point"),
            );
        }
    }
}

/// Degree >= 1, enough control points, one positive weight per point, a
/// non-decreasing knot vector of the right length whose multiplicities do
/// not disconnect the curve.
pub fn nurbs_data_consistent(
    degree: &Option<Spanned<i64>>,
    points: &Option<Spanned<Vec<Point>>>,
    weights: &Option<Spanned<Vec<Spanned<f64>>>>,
    knots: &Option<Spanned<Vec<Spanned<f64>>>>,
    ctx: &mut Ctx<'_>,
) {
    ctx.at_least(degree, 1, "degree");
    let p = degree.as_ref().map(|d| d.value).filter(|d| *d >= 1);
    let n = points.as_ref().map(|pts| pts.value.len());
    if let (Some(p), Some(n), Some(pts)) = (p, n, points) {
        if (n as i64) < p + 1 {
            ctx.err(
                Diagnostic::error(
                    format!("a degree {p} curve needs at least {} control points", p + 1),
                    pts.span,
                    format!("{n} control point(s)"),
                )
                .with_help("add control points or lower the degree"),
            );
        }
    }
    if let Some(w) = weights {
        if let Some(n) = n.filter(|n| *n != w.value.len()) {
            ctx.err(Diagnostic::error(
                "one weight per control point is needed",
                w.span,
                format!("{} weights for {n} control points", w.value.len()),
            ));
        }
        for x in w.value.iter().filter(|x| x.value <= 0.0) {
            ctx.err(Diagnostic::error(
                "NURBS weights must be positive",
                x.span,
                format!("weight = {}", num(x.value)),
            ));
        }
    }
    let (Some(k), Some(p), Some(n)) = (knots, p, n) else {
        return;
    };
    let want = n as i64 + p + 1;
    if k.value.len() as i64 != want {
        ctx.err(
            Diagnostic::error(
                format!("the knot vector needs {want} knots (control points + degree + 1)"),
                k.span,
                format!("{} knots", k.value.len()),
            )
            .with_help("leave `knots` out for an open uniform knot vector"),
        );
        return;
    }
    for w in k.value.windows(2) {
        if w[1].value < w[0].value {
            ctx.err(Diagnostic::error(
                "knots must be non-decreasing",
                w[1].span,
                format!("{} < {}", num(w[1].value), num(w[0].value)),
            ));
            return;
        }
    }
    let (p, n) = (p as usize, n);
    // Multiplicities: at most p + 1 at the ends, p inside (beyond that
    // the curve breaks apart).
    let mut start = 0;
    while start < k.value.len() {
        let mut end = start + 1;
        while end < k.value.len() && k.value[end].value == k.value[start].value {
            end += 1;
        }
        let at_end = start == 0 || end == k.value.len();
        let max = if at_end { p + 1 } else { p };
        if end - start > max {
            ctx.err(
                Diagnostic::error(
                    format!(
                        "knot {} is repeated {} times",
                        num(k.value[start].value),
                        end - start
                    ),
                    k.value[start].span.to(k.value[end - 1].span),
                    format!("at most {max} here for degree {p}"),
                )
                .with_help(
                    "a knot repeated more than the degree inside the vector disconnects the curve",
                ),
            );
            return;
        }
        start = end;
    }
    if k.value[p].value >= k.value[n].value {
        ctx.err(Diagnostic::error(
            "the knot vector spans no parameter range",
            k.span,
            format!("knot {} and knot {} are equal", p + 1, n + 1),
        ));
    }
}

/// `rotation = free` (a free roller, `ctc_engine::solve::free_tool`):
/// planar plane strain / plane stress analyses, quasi-static steps (no
/// rotational inertia), pairs by penalty or augmented Lagrangian (the
/// coupling of the angle is built on the nodal forces and tangents);
/// `moment` only with it.
pub fn free_rotation(t: &Tool, m: &crate::ast::Motion, ctx: &mut Ctx<'_>) {
    let Some(free) = m.free else {
        if let Some(mo) = &m.moment {
            ctx.err(
                Diagnostic::error(
                    "`moment` acts on a tool free to rotate",
                    mo.span,
                    "the rotation is prescribed",
                )
                .with_help("add `rotation = free`, or remove `moment`"),
            );
        }
        return;
    };
    let dimension = ctx
        .deck
        .analysis
        .first()
        .and_then(|a| a.dimension.as_ref())
        .map(|d| d.value);
    match dimension {
        Some(crate::ast::Dimension::ThreeD) => ctx.err(
            Diagnostic::error(
                "a free rotation is available for planar tools only",
                free,
                "3d tool",
            )
            .with_help("prescribe the rotation with a time function"),
        ),
        Some(crate::ast::Dimension::Axisymmetric) => ctx.err(
            Diagnostic::error(
                "a free rotation needs a plane strain or plane stress analysis",
                free,
                "axisymmetric tool",
            )
            .with_help(
                "an axisymmetric tool is a ring, whose cross-section does not turn as a rigid body",
            ),
        ),
        _ => {}
    }
    if ctx.deck.steps.iter().any(|s| s.dynamic.is_some()) {
        ctx.err(
            Diagnostic::error(
                "a free rotation is solved in quasi-static steps only",
                free,
                "no rotational inertia",
            )
            .with_help("remove `dynamic` from the steps, or prescribe the rotation"),
        );
    }
    let deck = ctx.deck;
    for c in deck
        .contacts
        .iter()
        .filter(|c| c.master.is_none() && c.tool.name == t.name.name)
    {
        if let Some(method) = c
            .method
            .as_ref()
            .filter(|m| matches!(m.value, crate::ast::Method::Lagrange { .. }))
        {
            ctx.err(
                Diagnostic::error(
                    "Lagrange multipliers are not available against a tool free to rotate",
                    method.span,
                    "lagrange",
                )
                .with_help("use `penalty` or `augmented_lagrange`"),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    #[test]
    fn nurbs_knot_multiplicity_is_bounded_by_the_degree() {
        let m = messages("tool c = nurbs { degree = 1 points = [(0,0), (1,1), (2,0), (3, 0)] knots = [0, 0, 0.5, 0.5, 1, 1] }\ncontact block.top -> c { method = penalty { stiffness = 1 } }");
        assert_eq!(m, ["knot 0.5 is repeated 2 times"]);
    }

    #[test]
    fn nurbs_knots_are_checked() {
        let m = messages("tool c = nurbs { degree = 2 points = [(0,0), (1,1), (2,0)] weights = [1, -1, 1] knots = [0, 0, 1, 1] }\ncontact block.top -> c { method = penalty { stiffness = 1 } }");
        assert_eq!(
            m,
            [
                "NURBS weights must be positive",
                "the knot vector needs 6 knots (control points + degree + 1)"
            ]
        );
    }
}
