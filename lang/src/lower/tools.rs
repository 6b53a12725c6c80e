//! `tool` items -> `model::RigidTool` (radians, unit normals, default centres of rotation).

use super::{open_uniform_knots, Lowerer};
use crate::ast;
use ctc_engine::model::{RigidTool, ToolGeometry, ToolMotion, ToolSide};

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
        })
    }
}
