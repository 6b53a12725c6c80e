//! `tool` items -> `model::RigidTool` (planar curves) or
//! `model::SurfaceTool` (3d surfaces): radians, unit normals and axes,
//! default centres of rotation.

use super::{open_uniform_knots, Lowerer};
use crate::ast;
use ctc_engine::model::{
    RigidTool, SurfaceMotion, SurfaceTool, ToolGeometry, ToolMotion, ToolSide,
};
use ctc_geom::analytic::{Analytic, Cone, Cylinder, Plane, Sphere, Torus};
use ctc_geom::{Side, Vec3};

impl Lowerer<'_> {
    pub(super) fn tools(&mut self) -> Vec<RigidTool> {
        let mut out = Vec::new();
        for t in &self.deck.tools {
            if self.has_error_in(t.span) {
                continue;
            }
            let Some((geometry, reference)) = self.tool_geometry(t) else {
                self.missing("a tool setting", t.kind.span);
                continue;
            };
            let mut motion = ToolMotion::fixed();
            motion.center = reference;
            if let Some(mo) = &t.motion {
                if let Some(f) = &mo.ux {
                    motion.ux = self.tf(f);
                }
                if let Some(f) = &mo.uy {
                    motion.uy = self.tf(f);
                }
                if let Some(f) = &mo.rotation {
                    motion.rotation = self.tf(f);
                }
                if let Some(c) = &mo.center {
                    motion.center = c.value;
                }
            }
            out.push(RigidTool {
                name: t.name.name.clone(),
                geometry,
                motion,
            });
        }
        out
    }

    /// The surface tools of a `3d` analysis.
    pub(super) fn surfaces(&mut self) -> Vec<SurfaceTool> {
        let mut out = Vec::new();
        for t in &self.deck.tools {
            if self.has_error_in(t.span) {
                continue;
            }
            let ast::ToolGeometry::Surface(g) = &t.geometry else {
                continue;
            };
            let Some((geometry, reference)) = surface_geometry(g) else {
                self.missing("a tool setting", t.kind.span);
                continue;
            };
            let mut motion = SurfaceMotion::fixed();
            motion.center = reference;
            if let Some(mo) = &t.motion {
                for (k, f) in [&mo.ux, &mo.uy, &mo.uz].into_iter().enumerate() {
                    if let Some(f) = f {
                        motion.translation[k] = self.tf(f);
                    }
                }
                if let Some(f) = &mo.rotation {
                    motion.rotation = self.tf(f);
                }
                if let Some(c) = &mo.center3 {
                    motion.center = c.value;
                }
                if let Some(a) = &mo.axis {
                    let v = Vec3::from(a.value);
                    if v.norm() > 0.0 {
                        motion.axis = (v / v.norm()).into();
                    }
                }
            }
            out.push(SurfaceTool {
                name: t.name.name.clone(),
                geometry,
                motion,
            });
        }
        out
    }

    /// The engine geometry and the tool's reference point (default centre
    /// of rotation: circle/arc centre, plane point, first point otherwise).
    pub(super) fn tool_geometry(&self, t: &ast::Tool) -> Option<(ToolGeometry, [f64; 2])> {
        Some(match &t.geometry {
            ast::ToolGeometry::Plane { point, normal } => {
                let p = point.as_ref()?.value;
                let n = normal.as_ref()?.value;
                let len = (n[0] * n[0] + n[1] * n[1]).sqrt();
                if len == 0.0 {
                    return None;
                }
                (
                    ToolGeometry::Plane {
                        point: p,
                        normal: [n[0] / len, n[1] / len],
                    },
                    p,
                )
            }
            ast::ToolGeometry::Polyline { points } => {
                let pts: Vec<[f64; 2]> = points.as_ref()?.value.iter().map(|p| p.value).collect();
                let first = *pts.first()?;
                (ToolGeometry::Polyline { points: pts }, first)
            }
            ast::ToolGeometry::Arc {
                center,
                radius,
                start,
                end,
            } => {
                let c = center.as_ref()?.value;
                (
                    ToolGeometry::Arc {
                        center: c,
                        radius: radius.as_ref()?.value,
                        start_angle: start.as_ref()?.value.to_radians(),
                        end_angle: end.as_ref()?.value.to_radians(),
                    },
                    c,
                )
            }
            ast::ToolGeometry::Circle {
                center,
                radius,
                side,
            } => {
                let c = center.as_ref()?.value;
                let side = match side.as_ref().map(|s| s.value) {
                    Some(ast::Side::Inside) => ToolSide::Inside,
                    _ => ToolSide::Outside,
                };
                (
                    ToolGeometry::Circle {
                        center: c,
                        radius: radius.as_ref()?.value,
                        side,
                    },
                    c,
                )
            }
            ast::ToolGeometry::Nurbs {
                degree,
                points,
                weights,
                knots,
            } => {
                let degree = usize::try_from(degree.as_ref()?.value).ok()?;
                let control_points: Vec<[f64; 2]> =
                    points.as_ref()?.value.iter().map(|p| p.value).collect();
                let n = control_points.len();
                let first = *control_points.first()?;
                let weights = match weights {
                    Some(w) => w.value.iter().map(|x| x.value).collect(),
                    None => vec![1.0; n],
                };
                let knots = match knots {
                    Some(k) => k.value.iter().map(|x| x.value).collect(),
                    None => open_uniform_knots(n, degree),
                };
                (
                    ToolGeometry::Nurbs {
                        degree,
                        control_points,
                        weights,
                        knots,
                    },
                    first,
                )
            }
            // a 3d surface in a planar deck: refused by validation
            ast::ToolGeometry::Surface(_) => return None,
        })
    }
}

/// The `ctc-geom` surface and its reference point (default centre of
/// rotation: the plane's point, the centre, a point of the axis, the
/// apex); `None` when a setting is missing or invalid (validation has
/// reported it).
fn surface_geometry(g: &ast::SurfaceGeometry) -> Option<(Analytic, [f64; 3])> {
    let v = |p: &Option<ast::Point3>| p.as_ref().map(|p| Vec3::from(p.value));
    let side = |s: &Option<ast::Spanned<ast::Side>>| match s.as_ref().map(|s| s.value) {
        Some(ast::Side::Inside) => Side::Inside,
        _ => Side::Outside,
    };
    let num = |x: &Option<ast::Spanned<f64>>| x.as_ref().map(|x| x.value);
    Some(match g {
        ast::SurfaceGeometry::Plane { point, normal } => {
            let p = v(point)?;
            (
                Analytic::Plane(Plane::new(p, v(normal)?, Side::Outside).ok()?),
                p.into(),
            )
        }
        ast::SurfaceGeometry::Sphere {
            center,
            radius,
            side: s,
        } => {
            let c = v(center)?;
            (
                Analytic::Sphere(Sphere::new(c, num(radius)?, side(s)).ok()?),
                c.into(),
            )
        }
        ast::SurfaceGeometry::Cylinder {
            point,
            axis,
            radius,
            side: s,
        } => {
            let p = v(point)?;
            (
                Analytic::Cylinder(Cylinder::new(p, v(axis)?, num(radius)?, side(s)).ok()?),
                p.into(),
            )
        }
        ast::SurfaceGeometry::Cone {
            apex,
            axis,
            angle,
            side: s,
        } => {
            let a = v(apex)?;
            (
                Analytic::Cone(Cone::new(a, v(axis)?, num(angle)?.to_radians(), side(s)).ok()?),
                a.into(),
            )
        }
        ast::SurfaceGeometry::Torus {
            center,
            axis,
            major,
            minor,
            side: s,
        } => {
            let c = v(center)?;
            (
                Analytic::Torus(Torus::new(c, v(axis)?, num(major)?, num(minor)?, side(s)).ok()?),
                c.into(),
            )
        }
    })
}
