//! `tool name = kind { .. }` for the rigid analytical tools (plane,
//! polyline, arc, circle, nurbs) and their `motion { .. }` block.

use super::fields::Fields;
use super::values::{self, Diags};
use super::ItemParts;
use crate::ast::syntax::{Block, ValueKind};
use crate::ast::{Motion, Side, Tool, ToolGeometry};
use crate::diagnostics::Diagnostic;
use crate::suggest::did_you_mean;

/// Tool geometry kinds (curves of planar analyses, then the surfaces of
/// `3d` ones, [`super::surface`]).
pub const KINDS: [&str; 11] = [
    "plane", "polyline", "arc", "circle", "nurbs", "sphere", "cylinder", "cone", "torus", "iges",
    "stl",
];

const SIDES: [(&str, Side); 2] = [("outside", Side::Outside), ("inside", Side::Inside)];

/// Converts a `tool` item.
pub fn parse(item: ItemParts, diags: &mut Diags) -> Option<Tool> {
    let mut names = item.names.into_iter();
    let name = names.next()?;
    let kind = names.next()?;
    let block = item.block?;
    let at = kind.span;
    let what = format!("`{}` tool", kind.name);
    let motion_block: Option<&Block>;
    let spatial = kind.name == "plane" && super::surface::is_spatial_plane(&block);
    let geometry = match kind.name.as_str() {
        k if spatial || super::surface::KINDS.contains(&k) => {
            let (g, m) = super::surface::parse(k, &block, at, diags)?;
            motion_block = m;
            ToolGeometry::Surface(g)
        }
        "plane" => {
            let mut f = Fields::keyed(&block, what, &crate::tables::PLANE);
            let point = f.point("point", diags);
            let normal = f.point("normal", diags);
            motion_block = f.block("motion", diags);
            f.require(&point, "point", at, "add `point = (x, y)`", diags);
            f.require(
                &normal,
                "normal",
                at,
                "add `normal = (nx, ny)` pointing to the free side",
                diags,
            );
            f.finish(diags);
            ToolGeometry::Plane { point, normal }
        }
        "polyline" => {
            let mut f = Fields::keyed(&block, what, &crate::tables::POLYLINE);
            let points = f
                .value("points", diags)
                .and_then(|v| values::point_list(v, diags));
            motion_block = f.block("motion", diags);
            f.require(
                &points,
                "points",
                at,
                "add `points = [(x0, y0), (x1, y1), ..]`",
                diags,
            );
            f.finish(diags);
            ToolGeometry::Polyline { points }
        }
        "arc" => {
            let mut f = Fields::keyed(&block, what, &crate::tables::ARC);
            let center = f.point("center", diags);
            let radius = f.number("radius", diags);
            let start = f.number("start", diags);
            let end = f.number("end", diags);
            motion_block = f.block("motion", diags);
            f.require(&center, "center", at, "add `center = (x, y)`", diags);
            f.require(&radius, "radius", at, "add `radius = ..`", diags);
            f.require(
                &start,
                "start",
                at,
                "add `start = <angle in degrees>`",
                diags,
            );
            f.require(&end, "end", at, "add `end = <angle in degrees>`", diags);
            f.finish(diags);
            ToolGeometry::Arc {
                center,
                radius,
                start,
                end,
            }
        }
        "circle" => {
            let mut f = Fields::keyed(&block, what, &crate::tables::CIRCLE);
            let center = f.point("center", diags);
            let radius = f.number("radius", diags);
            let side = f.choice("side", "side", &SIDES, diags);
            motion_block = f.block("motion", diags);
            f.require(&center, "center", at, "add `center = (x, y)`", diags);
            f.require(&radius, "radius", at, "add `radius = ..`", diags);
            f.finish(diags);
            ToolGeometry::Circle {
                center,
                radius,
                side,
            }
        }
        "nurbs" => {
            let mut f = Fields::keyed(&block, what, &crate::tables::NURBS);
            let degree = f.integer("degree", diags);
            let points = f
                .value("points", diags)
                .and_then(|v| values::point_list(v, diags));
            let weights = f
                .value("weights", diags)
                .and_then(|v| values::number_list(v, diags));
            let knots = f
                .value("knots", diags)
                .and_then(|v| values::number_list(v, diags));
            motion_block = f.block("motion", diags);
            f.require(
                &degree,
                "degree",
                at,
                "add `degree = 2` (or another degree >= 1)",
                diags,
            );
            f.require(
                &points,
                "points",
                at,
                "add `points = [(x0, y0), ..]` (the control points)",
                diags,
            );
            f.finish(diags);
            ToolGeometry::Nurbs {
                degree,
                points,
                weights,
                knots,
            }
        }
        other => {
            diags.push(
                Diagnostic::error(
                    format!("unknown tool kind `{other}`"),
                    kind.span,
                    "not a tool kind",
                )
                .with_help(did_you_mean(other, KINDS).unwrap_or_else(|| {
                    "expected `plane`, `polyline`, `arc`, `circle` or `nurbs` (planar), or \
                     `sphere`, `cylinder`, `cone`, `torus`, `iges` or `stl` (3d)"
                        .to_string()
                })),
            );
            return None;
        }
    };
    let motion = motion_block.map(|b| {
        let mut f = Fields::keyed(b, "`motion` block", &crate::tables::MOTION);
        let ux = f.time_fn("ux", diags);
        let uy = f.time_fn("uy", diags);
        let uz = f.time_fn("uz", diags);
        // `rotation = free`: the angle is an unknown (a free roller)
        let (rotation, free) = match f.value("rotation", diags) {
            Some(v) if matches!(&v.kind, ValueKind::Path(p) if p.len() == 1 && p[0].name == "free") => {
                (None, Some(v.span))
            }
            Some(v) => (values::time_fn_of(v, f.dim("rotation"), diags), None),
            None => (None, None),
        };
        let moment = f.time_fn("moment", diags);
        let (center, center3) = match f.value("center", diags) {
            Some(v) if values::tuple_len(v) == Some(3) => (None, values::point3(v, diags)),
            Some(v) => (values::point(v, diags), None),
            None => (None, None),
        };
        let axis = f
            .value("axis", diags)
            .and_then(|v| values::point3(v, diags));
        let m = Motion {
            ux,
            uy,
            uz,
            rotation,
            free,
            moment,
            center,
            center3,
            axis,
            span: b.span,
        };
        f.finish(diags);
        m
    });
    Some(Tool {
        name,
        kind,
        geometry,
        motion,
        span: item.span,
    })
}

#[cfg(test)]
mod tests {
    use crate::ast::{Side, TimeFn, ToolGeometry};
    use crate::parse::test_support::{parse_messages, parse_ok};

    #[test]
    fn all_tool_kinds() {
        let deck = parse_ok(
            "tool punch = circle { center = (0, 1)  radius = 1  side = outside\n motion { uy = ramp(0, -0.02) rotation = 0.1 center = (0, 1) } }\n\
             tool floor = plane { point = (0, 0)  normal = (0, 1) }\n\
             tool die   = polyline { points = [(0, 0), (1, 0), (2, 1)] }\n\
             tool roll  = arc { center = (0, 0)  radius = 1  start = 180  end = 360 }\n\
             tool cad   = nurbs { degree = 2  points = [(0,0), (1,1), (2,0)]  weights = [1, 0.75, 1]\n knots = [0, 0, 0, 1, 1, 1] }",
        );
        assert_eq!(deck.tools.len(), 5);
        let t = &deck.tools[0];
        assert_eq!(t.name.name, "punch");
        match &t.geometry {
            ToolGeometry::Circle { side, radius, .. } => {
                assert_eq!(side.as_ref().unwrap().value, Side::Outside);
                assert_eq!(radius.as_ref().unwrap().value, 1.0);
            }
            g => panic!("{g:?}"),
        }
        let m = t.motion.as_ref().unwrap();
        assert_eq!(
            m.uy.as_ref().unwrap().value,
            TimeFn::Ramp {
                v0: 0.0,
                v1: -0.02,
                window: None
            }
        );
        assert_eq!(m.rotation.as_ref().unwrap().value, TimeFn::Number(0.1));
        match &deck.tools[4].geometry {
            ToolGeometry::Nurbs {
                degree,
                points,
                weights,
                knots,
            } => {
                assert_eq!(degree.as_ref().unwrap().value, 2);
                assert_eq!(points.as_ref().unwrap().value.len(), 3);
                assert_eq!(weights.as_ref().unwrap().value[1].value, 0.75);
                assert_eq!(knots.as_ref().unwrap().value.len(), 6);
            }
            g => panic!("{g:?}"),
        }
    }

    #[test]
    fn unknown_tool_kind_and_motion_key() {
        assert_eq!(
            parse_messages("tool t = circel { }"),
            ["unknown tool kind `circel`"]
        );
        assert_eq!(
            parse_messages("tool t = plane { point = (0,0) normal = (0,1) motion { uw = 1 } }"),
            ["unknown key `uw` in the `motion` block"]
        );
    }
}
