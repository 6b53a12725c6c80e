//! `tool` items -> `model::RigidTool` (planar curves) or
//! `model::SurfaceTool` (3d surfaces): radians, unit normals and axes,
//! default centres of rotation.

use super::{open_uniform_knots, Lowerer};
use crate::ast;
use crate::diagnostics::Diagnostic;
use ctc_engine::model::{
    RigidTool, SurfaceMotion, SurfaceShape, SurfaceTool, TimeFunction, ToolGeometry, ToolMotion,
    ToolSide,
};
use ctc_geom::analytic::{Analytic, Cone, Cylinder, Plane, Sphere, Torus};
use ctc_geom::{Side, Vec3};

/// A tool with `rotation = free`, made free once the model is built
/// (`ctc_engine::solve::free_tool::make_free` appends its pilot node).
pub(super) struct FreeTool {
    /// Index in `Model::tools`.
    pub tool: usize,
    /// The applied moment.
    pub moment: TimeFunction,
    /// Where `free` is written.
    pub span: crate::ast::Span,
}

impl Lowerer<'_> {
    /// The planar tools, and the free ones (`rotation = free`): tool
    /// index, applied moment and the span of `free`.
    pub(super) fn tools(&mut self) -> (Vec<RigidTool>, Vec<FreeTool>) {
        let mut out = Vec::new();
        let mut free = Vec::new();
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
                if let Some(span) = mo.free {
                    let moment = mo
                        .moment
                        .as_ref()
                        .map_or(TimeFunction::Constant(0.0), |f| self.tf(f));
                    free.push(FreeTool {
                        tool: out.len(),
                        moment,
                        span,
                    });
                }
            }
            out.push(RigidTool {
                name: t.name.name.clone(),
                geometry,
                motion,
                free_rotation: None,
            });
        }
        (out, free)
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
            let (geometry, reference) = match g {
                ast::SurfaceGeometry::Iges { file, flip } => {
                    let Some(file) = file else {
                        self.missing("the IGES file", t.kind.span);
                        continue;
                    };
                    let flip = flip.as_ref().is_some_and(|f| f.value);
                    match cad_tool(file, flip, self.src) {
                        Ok((tool, reference)) => (SurfaceShape::Brep(tool), reference),
                        Err(d) => {
                            self.diags.push(d);
                            continue;
                        }
                    }
                }
                ast::SurfaceGeometry::Stl { file, flip, closed } => {
                    let Some(file) = file else {
                        self.missing("the STL file", t.kind.span);
                        continue;
                    };
                    let flip = flip.as_ref().is_some_and(|f| f.value);
                    let closed = closed.as_ref().is_some_and(|f| f.value);
                    match stl_tool(file, flip, closed, self.src) {
                        Ok((mesh, reference)) => (SurfaceShape::Mesh(mesh), reference),
                        Err(d) => {
                            self.diags.push(d);
                            continue;
                        }
                    }
                }
                _ => {
                    let Some((a, reference)) = surface_geometry(g) else {
                        self.missing("a tool setting", t.kind.span);
                        continue;
                    };
                    (SurfaceShape::Analytic(a), reference)
                }
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

/// The bytes of a tool's geometry file (`kind`: IGES, STL), its path
/// relative to the deck file that names it; a file that cannot be read is
/// a diagnostic at the name.
fn tool_file(
    file: &ast::Spanned<String>,
    kind: &str,
    src: &crate::source::Source,
) -> Result<Vec<u8>, Diagnostic> {
    let path = src.directory_at(file.span.start).join(&file.value);
    std::fs::read(&path).map_err(|e| {
        Diagnostic::error(
            format!("cannot read {kind} file `{}`: {e}", file.value),
            file.span,
            if e.kind() == std::io::ErrorKind::NotFound {
                "file not found"
            } else {
                "cannot read this file"
            },
        )
        .with_help(format!(
            "looked for `{}`; paths are relative to the deck's directory",
            path.display()
        ))
    })
}

/// The CAD tool of an IGES file (relative to the deck file that names it)
/// and its reference point (the centre of its box): every face of the
/// file, oriented consistently across shared edges from the first face
/// (`S_u x S_v` into free space, or the other side with `flip`). Errors
/// name the file and its line.
fn cad_tool(
    file: &ast::Spanned<String>,
    flip: bool,
    src: &crate::source::Source,
) -> Result<(std::sync::Arc<ctc_geom::brep::BrepTool>, [f64; 3]), Diagnostic> {
    use ctc_geom::brep::{BrepOptions, BrepTool};
    let bytes = tool_file(file, "IGES", src)?;
    let text = String::from_utf8(bytes).map_err(|_| {
        Diagnostic::error(
            format!("error in IGES file `{}`: it is not text", file.value),
            file.span,
            "in this IGES file",
        )
    })?;
    let bad = |line: Option<usize>, message: String| {
        let at = line.map_or(String::new(), |l| format!(" (line {l})"));
        Diagnostic::error(
            format!("error in IGES file `{}`{at}: {message}", file.value),
            file.span,
            "in this IGES file",
        )
    };
    let iges = ctc_geom::iges::read(&text).map_err(|e| bad(Some(e.line), e.message))?;
    let faces: Vec<_> = iges
        .faces()
        .map_err(|e| bad(Some(e.line), e.message))?
        .into_iter()
        .map(|f| f.face)
        .collect();
    if faces.is_empty() {
        return Err(bad(
            None,
            "it holds no surface (entities 144, 143 or 128)".into(),
        ));
    }
    let mut tool = BrepTool::new(faces, BrepOptions::default()).map_err(|m| bad(None, m))?;
    tool.orient(0, if flip { -1.0 } else { 1.0 })
        .map_err(|m| bad(None, m))?;
    let c = (tool.bbox.min + tool.bbox.max) * 0.5;
    Ok((std::sync::Arc::new(tool), [c[0], c[1], c[2]]))
}

/// The triangulated tool of an STL file (ASCII or binary, relative to the
/// deck file that names it) and its reference point (the centre of its
/// box): corners merged within 1e-9 of the box's diagonal, free space on
/// the side the triangles turn counter-clockwise to (the other with
/// `flip`); with `closed`, a free edge is an error. Every error names the
/// file and its cause (a truncated or non-STL file, a non-finite
/// coordinate, a zero-area triangle, an edge of three triangles,
/// inconsistent orientation, a hole): the deck is refused, nothing panics.
fn stl_tool(
    file: &ast::Spanned<String>,
    flip: bool,
    closed: bool,
    src: &crate::source::Source,
) -> Result<(std::sync::Arc<ctc_geom::trimesh::TriMesh>, [f64; 3]), Diagnostic> {
    use ctc_geom::trimesh::{stl, TriMesh};
    let bytes = tool_file(file, "STL", src)?;
    let bad = |message: String| {
        Diagnostic::error(
            format!("error in STL file `{}`: {message}", file.value),
            file.span,
            "in this STL file",
        )
    };
    let corners = stl::read(&bytes).map_err(|e| {
        bad(if e.line == 0 {
            e.message.clone()
        } else {
            format!(
                "line {} (a triangle's number in a binary file): {}",
                e.line, e.message
            )
        })
    })?;
    let (mut lo, mut hi) = (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY));
    for p in corners.iter().flatten() {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    let merge = 1e-9 * (hi - lo).norm();
    let side = if flip { Side::Inside } else { Side::Outside };
    let mesh = TriMesh::from_soup(&corners, merge, side).map_err(|m| {
        let m = m.strip_prefix("triangle mesh: ").unwrap_or(&m).to_string();
        bad(format!("{m} (triangles are numbered from 1 in file order)"))
    })?;
    if closed {
        if let Some(e) = mesh.edge_free.iter().position(|&f| f) {
            let [a, b] = mesh.edges[e];
            let (pa, pb) = (mesh.vertices[a], mesh.vertices[b]);
            return Err(bad(format!(
                "the surface is not closed: the edge from ({}, {}, {}) to ({}, {}, {}) belongs \
                 to one triangle only ({} such edges)",
                pa.x,
                pa.y,
                pa.z,
                pb.x,
                pb.y,
                pb.z,
                mesh.edge_free.iter().filter(|&&f| f).count()
            ))
            .with_help("close the surface, or remove `closed = true` to accept an open one"));
        }
    }
    let c = (lo + hi) * 0.5;
    Ok((std::sync::Arc::new(mesh), [c[0], c[1], c[2]]))
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
        ast::SurfaceGeometry::Iges { .. } | ast::SurfaceGeometry::Stl { .. } => return None,
    })
}
