//! `tool name = kind { .. }` for the rigid surface tools of `3d` analyses:
//! `plane` written with `(x, y, z)` points, `sphere`, `cylinder`, `cone`,
//! `torus`, the CAD faces of an IGES file (`iges`) and the triangles of an
//! STL file (`stl`). (Whether the analysis is `3d` is a rule of validation:
//! `validate::tools::dimension_matches_analysis`.)

use super::fields::Fields;
use super::values::{self, Diags};
use crate::ast::syntax::Block;
use crate::ast::{Point3, Side, Spanned, SurfaceGeometry};
use crate::span::Span;

/// Surface kinds only a `3d` analysis has.
pub const KINDS: [&str; 6] = ["sphere", "cylinder", "cone", "torus", "iges", "stl"];

const SIDES: [(&str, Side); 2] = [("outside", Side::Outside), ("inside", Side::Inside)];

/// Whether a `plane` block is written in space: its `point` or `normal`
/// has three coordinates.
pub fn is_spatial_plane(block: &Block) -> bool {
    block.entries.iter().any(|e| {
        (e.key.name == "point" || e.key.name == "normal")
            && match &e.body {
                crate::ast::syntax::EntryBody::Assign(v) => values::tuple_len(v) == Some(3),
                _ => false,
            }
    })
}

fn point3(f: &mut Fields<'_>, key: &str, diags: &mut Diags) -> Option<Point3> {
    let v = f.value(key, diags)?;
    values::point3(v, diags)
}

fn require<T>(f: &Fields<'_>, v: &Option<T>, key: &str, at: Span, help: &str, diags: &mut Diags) {
    f.require(v, key, at, help, diags);
}

/// Reads the block of surface kind `kind` (`plane`, or one of [`KINDS`]);
/// returns the geometry and the `motion` block. `None` for another kind.
pub fn parse<'b>(
    kind: &str,
    block: &'b Block,
    at: Span,
    diags: &mut Diags,
) -> Option<(SurfaceGeometry, Option<&'b Block>)> {
    let what = format!("`{kind}` tool");
    let side = |f: &mut Fields<'_>, diags: &mut Diags| -> Option<Spanned<Side>> {
        f.choice("side", "side", &SIDES, diags)
    };
    Some(match kind {
        "plane" => {
            let mut f = Fields::keyed(block, what, &crate::tables::PLANE_3D);
            let point = point3(&mut f, "point", diags);
            let normal = point3(&mut f, "normal", diags);
            let motion = f.block("motion", diags);
            require(&f, &point, "point", at, "add `point = (x, y, z)`", diags);
            require(
                &f,
                &normal,
                "normal",
                at,
                "add `normal = (nx, ny, nz)` pointing to the free side",
                diags,
            );
            f.finish(diags);
            (SurfaceGeometry::Plane { point, normal }, motion)
        }
        "sphere" => {
            let mut f = Fields::keyed(block, what, &crate::tables::SPHERE);
            let center = point3(&mut f, "center", diags);
            let radius = f.number("radius", diags);
            let side = side(&mut f, diags);
            let motion = f.block("motion", diags);
            require(&f, &center, "center", at, "add `center = (x, y, z)`", diags);
            require(&f, &radius, "radius", at, "add `radius = ..`", diags);
            f.finish(diags);
            (
                SurfaceGeometry::Sphere {
                    center,
                    radius,
                    side,
                },
                motion,
            )
        }
        "cylinder" => {
            let mut f = Fields::keyed(block, what, &crate::tables::CYLINDER);
            let point = point3(&mut f, "point", diags);
            let axis = point3(&mut f, "axis", diags);
            let radius = f.number("radius", diags);
            let side = side(&mut f, diags);
            let motion = f.block("motion", diags);
            require(&f, &point, "point", at, "add `point = (x, y, z)`", diags);
            require(&f, &axis, "axis", at, "add `axis = (ax, ay, az)`", diags);
            require(&f, &radius, "radius", at, "add `radius = ..`", diags);
            f.finish(diags);
            (
                SurfaceGeometry::Cylinder {
                    point,
                    axis,
                    radius,
                    side,
                },
                motion,
            )
        }
        "cone" => {
            let mut f = Fields::keyed(block, what, &crate::tables::CONE);
            let apex = point3(&mut f, "apex", diags);
            let axis = point3(&mut f, "axis", diags);
            let angle = f.number("angle", diags);
            let side = side(&mut f, diags);
            let motion = f.block("motion", diags);
            require(&f, &apex, "apex", at, "add `apex = (x, y, z)`", diags);
            require(&f, &axis, "axis", at, "add `axis = (ax, ay, az)`", diags);
            require(
                &f,
                &angle,
                "angle",
                at,
                "add `angle = <half angle in degrees>`",
                diags,
            );
            f.finish(diags);
            (
                SurfaceGeometry::Cone {
                    apex,
                    axis,
                    angle,
                    side,
                },
                motion,
            )
        }
        "torus" => {
            let mut f = Fields::keyed(block, what, &crate::tables::TORUS);
            let center = point3(&mut f, "center", diags);
            let axis = point3(&mut f, "axis", diags);
            let major = f.number("major", diags);
            let minor = f.number("minor", diags);
            let side = side(&mut f, diags);
            let motion = f.block("motion", diags);
            require(&f, &center, "center", at, "add `center = (x, y, z)`", diags);
            require(&f, &axis, "axis", at, "add `axis = (ax, ay, az)`", diags);
            require(&f, &major, "major", at, "add `major = ..`", diags);
            require(&f, &minor, "minor", at, "add `minor = ..`", diags);
            f.finish(diags);
            (
                SurfaceGeometry::Torus {
                    center,
                    axis,
                    major,
                    minor,
                    side,
                },
                motion,
            )
        }
        "iges" => {
            let mut f = Fields::keyed(block, what, &crate::tables::IGES);
            let file = f
                .value("file", diags)
                .and_then(|v| values::text(v, "a file path in quotes", diags));
            let flip = f.boolean("flip", diags);
            let motion = f.block("motion", diags);
            require(&f, &file, "file", at, "add `file = \"die.igs\"`", diags);
            f.finish(diags);
            (SurfaceGeometry::Iges { file, flip }, motion)
        }
        "stl" => {
            let mut f = Fields::keyed(block, what, &crate::tables::STL);
            let file = f
                .value("file", diags)
                .and_then(|v| values::text(v, "a file path in quotes", diags));
            let flip = f.boolean("flip", diags);
            let closed = f.boolean("closed", diags);
            let motion = f.block("motion", diags);
            require(&f, &file, "file", at, "add `file = \"punch.stl\"`", diags);
            f.finish(diags);
            (SurfaceGeometry::Stl { file, flip, closed }, motion)
        }
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use crate::ast::{Side, SurfaceGeometry, ToolGeometry};
    use crate::parse::test_support::{parse_messages, parse_ok};

    #[test]
    fn every_surface_kind_and_the_spatial_plane() {
        let deck = parse_ok(
            "tool ball = sphere { center = (0, 0, 1)  radius = 0.5\n motion { uz = ramp(0, -0.1) } }\n\
             tool floor = plane { point = (0, 0, 0)  normal = (0, 0, 1) }\n\
             tool roll = cylinder { point = (0, 0, 2)  axis = (1, 0, 0)  radius = 1  side = inside }\n\
             tool tip = cone { apex = (0, 0, 0)  axis = (0, 0, 1)  angle = 30 }\n\
             tool ring = torus { center = (0, 0, 0)  axis = (0, 0, 1)  major = 2  minor = 0.5\n\
               motion { rotation = 0.2  center = (0, 0, 0)  axis = (0, 0, 1) } }",
        );
        assert_eq!(deck.tools.len(), 5);
        let s = |i: usize| match &deck.tools[i].geometry {
            ToolGeometry::Surface(s) => s.clone(),
            g => panic!("{g:?}"),
        };
        match s(0) {
            SurfaceGeometry::Sphere { center, radius, .. } => {
                assert_eq!(center.unwrap().value, [0.0, 0.0, 1.0]);
                assert_eq!(radius.unwrap().value, 0.5);
            }
            g => panic!("{g:?}"),
        }
        assert!(deck.tools[0].motion.as_ref().unwrap().uz.is_some());
        match s(1) {
            SurfaceGeometry::Plane { normal, .. } => {
                assert_eq!(normal.unwrap().value, [0.0, 0.0, 1.0])
            }
            g => panic!("{g:?}"),
        }
        match s(2) {
            SurfaceGeometry::Cylinder { side, .. } => {
                assert_eq!(side.unwrap().value, Side::Inside)
            }
            g => panic!("{g:?}"),
        }
        assert!(matches!(s(3), SurfaceGeometry::Cone { .. }));
        let m = deck.tools[4].motion.as_ref().unwrap();
        assert_eq!(m.center3.as_ref().unwrap().value, [0.0; 3]);
        assert_eq!(m.axis.as_ref().unwrap().value, [0.0, 0.0, 1.0]);
    }

    #[test]
    fn a_spatial_point_needs_three_coordinates_and_required_keys_are_named() {
        assert_eq!(
            parse_messages("tool b = sphere { center = (0, 1)  radius = 1 }"),
            ["expected a point `(x, y, z)`, found a tuple of 2"]
        );
        assert_eq!(
            parse_messages("tool b = cylinder { point = (0, 0, 0)  radius = 1 }"),
            ["missing `axis` in the `cylinder` tool"]
        );
    }
}
