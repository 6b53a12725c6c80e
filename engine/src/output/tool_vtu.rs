//! The rigid tools' geometry at one increment (`tool_<k>_<NNNN>.vtu`), so
//! ParaView shows the tools beside the bodies.
//!
//! Each tool is a chain of straight line cells (VTK_LINE) walked with the
//! free side on the **left** (the convention of [`crate::model::ToolGeometry`]):
//! polylines by their vertices, arcs and circles by one point every 5
//! degrees (at least 8 segments), NURBS curves by 16 points per knot span,
//! planes as one segment over the extent of the bodies (their current
//! bounding box projected on the line, widened by 10 % of its diagonal on
//! each side). A circle with the body outside is walked clockwise, inside
//! counter-clockwise, so its free side too is on the left.
//!
//! Points are the tool's **current** position (the reference geometry
//! placed by its rigid motion at the increment's time), z = 0; the body
//! files hold reference coordinates plus `displacement`, so in ParaView
//! apply "Warp By Vector" to the body block only. Cell data:
//! `free_side` (the unit normal of each segment pointing to the side where
//! bodies may be: glyph it to see a reversed tool). Field data: `TIME`,
//! `CYCLE`, `TOOL` (the tool's index). The PVD lists tool `k` as part
//! `k + 1` (the bodies are part 0), one block per tool.

use super::encode::{fmt_f64, Arrays, Encoding};
use crate::contact::geometry::ToolShape;
use crate::contact::motion::Placement;
use crate::model::{RigidTool, ToolGeometry};
use std::f64::consts::TAU;
use std::fmt::Write;

/// Segments per NURBS knot span.
const PER_SPAN: usize = 16;

/// Largest angle between two samples of an arc or circle (5 degrees).
const ARC_STEP: f64 = TAU / 72.0;

/// The file name of tool `k` at increment `increment`.
pub fn file_name(k: usize, increment: usize) -> String {
    format!("tool_{k}_{increment:04}.vtu")
}

/// Points of `tool`'s reference geometry walked with the free side on the
/// left, in the current frame of `placement`; `extent` is the bodies'
/// current bounding box `[min, max]` (used by planes only, which are
/// infinite).
fn walk(tool: &RigidTool, placement: &Placement, extent: [[f64; 2]; 2]) -> Vec<[f64; 2]> {
    let arc = |center: [f64; 2], radius: f64, start: f64, sweep: f64| {
        let n = ((sweep.abs() / ARC_STEP).ceil() as usize).max(8);
        (0..=n)
            .map(|i| {
                let a = start + sweep * i as f64 / n as f64;
                [center[0] + radius * a.cos(), center[1] + radius * a.sin()]
            })
            .collect::<Vec<_>>()
    };
    let reference = match &tool.geometry {
        ToolGeometry::Plane { point, normal } => {
            // in the current frame: the line through the placed point
            let p = placement.to_current(*point);
            let len = normal[0].hypot(normal[1]);
            if !(len > 0.0 && len.is_finite()) {
                return Vec::new();
            }
            let n = placement.rotate([normal[0] / len, normal[1] / len]);
            // walk direction with the normal on its left
            let d = [n[1], -n[0]];
            let [lo, hi] = extent;
            let diag = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
            let pad = 0.1 * diag.max(f64::MIN_POSITIVE);
            let mut s = [f64::INFINITY, f64::NEG_INFINITY];
            for c in [lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]] {
                let t = (c[0] - p[0]) * d[0] + (c[1] - p[1]) * d[1];
                s = [s[0].min(t), s[1].max(t)];
            }
            if !(s[0].is_finite() && s[1].is_finite()) {
                s = [0.0, 0.0];
            }
            let (a, b) = (s[0] - pad, s[1] + pad);
            return vec![
                [p[0] + a * d[0], p[1] + a * d[1]],
                [p[0] + b * d[0], p[1] + b * d[1]],
            ];
        }
        ToolGeometry::Polyline { points } => points.clone(),
        ToolGeometry::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        } => arc(*center, *radius, *start_angle, end_angle - start_angle),
        ToolGeometry::Circle {
            center,
            radius,
            side,
        } => {
            // body outside: clockwise (free side on the left is outside)
            let sweep = match side {
                crate::model::ToolSide::Outside => -TAU,
                crate::model::ToolSide::Inside => TAU,
            };
            arc(*center, *radius, 0.0, sweep)
        }
        ToolGeometry::Nurbs { .. } => match ToolShape::new(&tool.geometry) {
            Ok(ToolShape::Nurbs(n)) => {
                let mut pts = Vec::with_capacity(n.span_count() * PER_SPAN + 1);
                for s in 0..n.span_count() {
                    let (ua, ub) = n.span_range(s);
                    let first = if s == 0 { 0 } else { 1 };
                    for i in first..=PER_SPAN {
                        let u = ua + (ub - ua) * i as f64 / PER_SPAN as f64;
                        pts.push(n.point(s, u));
                    }
                }
                pts
            }
            _ => Vec::new(),
        },
    };
    reference
        .into_iter()
        .map(|p| placement.to_current(p))
        .collect()
}

/// The current bounding box `[min, max]` of the nodes `nodes + u` (the
/// first two coordinates); a unit box at the origin without nodes.
pub fn extent<const D: usize>(nodes: &[[f64; D]], u: &[[f64; D]]) -> [[f64; 2]; 2] {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for (x, d) in nodes.iter().zip(u) {
        for c in 0..2.min(D) {
            let v = x[c] + d[c];
            if v.is_finite() {
                lo[c] = lo[c].min(v);
                hi[c] = hi[c].max(v);
            }
        }
    }
    if !(lo[0] <= hi[0] && lo[1] <= hi[1]) {
        return [[0.0, 0.0], [1.0, 1.0]];
    }
    [lo, hi]
}

/// The points of tool `tool` at time `time` (current frame), walked with
/// the free side on the left.
pub fn current_points(tool: &RigidTool, time: f64, extent: [[f64; 2]; 2]) -> Vec<[f64; 2]> {
    walk(tool, &Placement::at(&tool.motion, time), extent)
}

/// The VTU file's bytes of tool number `k` at `time` (increment
/// `increment`); `extent` is the bodies' current bounding box.
pub fn tool_vtu(
    tool: &RigidTool,
    k: usize,
    time: f64,
    increment: usize,
    extent: [[f64; 2]; 2],
    encoding: Encoding,
) -> Vec<u8> {
    let pts = current_points(tool, time, extent);
    let segments = pts.len().saturating_sub(1);
    let mut s = String::with_capacity(2048);
    let mut a = Arrays::new(encoding);
    s.push_str("<?xml version=\"1.0\"?>\n");
    let _ = writeln!(
        s,
        "<!-- ctc rigid tool `{}` at time {} (increment {}): current position; free side on \
         the left of the walk, cell array free_side points to it. -->",
        tool.name.replace("--", "- -"),
        fmt_f64(time),
        increment
    );
    let _ = writeln!(
        s,
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\"{}>\n  <UnstructuredGrid>",
        a.compressor_attribute()
    );
    s.push_str("    <FieldData>\n");
    a.array(&mut s, "      ", "TIME", 0, " NumberOfTuples=\"1\"", [time]);
    a.array(
        &mut s,
        "      ",
        "CYCLE",
        0,
        " NumberOfTuples=\"1\"",
        [increment as i64],
    );
    a.array(
        &mut s,
        "      ",
        "TOOL",
        0,
        " NumberOfTuples=\"1\"",
        [k as i64],
    );
    s.push_str("    </FieldData>\n");
    let _ = writeln!(
        s,
        "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{segments}\">",
        pts.len()
    );
    const IN: &str = "        ";
    s.push_str("      <CellData Vectors=\"free_side\">\n");
    a.array(
        &mut s,
        IN,
        "free_side",
        3,
        "",
        pts.windows(2).flat_map(|w| {
            let d = [w[1][0] - w[0][0], w[1][1] - w[0][1]];
            let l = d[0].hypot(d[1]);
            if l > 0.0 {
                [-d[1] / l, d[0] / l, 0.0]
            } else {
                [0.0; 3]
            }
        }),
    );
    s.push_str("      </CellData>\n      <Points>\n");
    a.array(
        &mut s,
        IN,
        "coordinates",
        3,
        "",
        pts.iter().flat_map(|p| [p[0], p[1], 0.0]),
    );
    s.push_str("      </Points>\n      <Cells>\n");
    a.array(
        &mut s,
        IN,
        "connectivity",
        1,
        "",
        (0..segments).flat_map(|i| [i as i64, i as i64 + 1]),
    );
    a.array(
        &mut s,
        IN,
        "offsets",
        1,
        "",
        (1..=segments).map(|i| 2 * i as i64),
    );
    a.array(&mut s, IN, "types", 1, "", (0..segments).map(|_| 3u8));
    s.push_str("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n");
    a.finish(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{TimeFunction, ToolMotion, ToolSide};
    use crate::output::vtu_read::Vtu;

    fn tool(geometry: ToolGeometry, uy: f64) -> RigidTool {
        RigidTool {
            name: "t".into(),
            geometry,
            motion: ToolMotion {
                uy: TimeFunction::Ramp {
                    t0: 0.0,
                    t1: 1.0,
                    v0: 0.0,
                    v1: uy,
                },
                ..ToolMotion::fixed()
            },
            free_rotation: None,
        }
    }

    /// Signed area of a closed walk (> 0 counter-clockwise).
    fn area(p: &[[f64; 2]]) -> f64 {
        p.windows(2)
            .map(|w| w[0][0] * w[1][1] - w[1][0] * w[0][1])
            .sum::<f64>()
            / 2.0
    }

    #[test]
    fn a_plane_spans_the_bodies_and_its_free_side_is_its_normal() {
        let t = tool(
            ToolGeometry::Plane {
                point: [0.0, 1.0],
                normal: [0.0, -1.0],
            },
            -0.5,
        );
        let ext = [[0.0, 0.0], [2.0, 1.0]];
        let p = current_points(&t, 1.0, ext);
        // moved down by 0.5, walked towards -x (normal -y on the left)
        assert_eq!(p.len(), 2);
        let pad = 0.1 * 5f64.sqrt();
        assert!((p[0][0] - (2.0 + pad)).abs() < 1e-12 && (p[1][0] + pad).abs() < 1e-12);
        assert!((p[0][1] - 0.5).abs() < 1e-15 && (p[1][1] - 0.5).abs() < 1e-15);
        let v = Vtu::read(&tool_vtu(&t, 3, 1.0, 7, ext, Encoding::Binary)).unwrap();
        assert_eq!((v.points, v.cells), (2, 1));
        let n = &v.cell("free_side").unwrap().values;
        assert!(n[0].abs() < 1e-15 && (n[1] + 1.0).abs() < 1e-15, "{n:?}");
        assert_eq!(v.field("TOOL").unwrap().values, [3.0]);
        assert_eq!(v.field("CYCLE").unwrap().values, [7.0]);
    }

    #[test]
    fn circles_and_arcs_are_walked_with_the_free_side_on_the_left() {
        let ext = [[0.0; 2], [1.0; 2]];
        for (side, sign) in [(ToolSide::Outside, -1.0), (ToolSide::Inside, 1.0)] {
            let t = tool(
                ToolGeometry::Circle {
                    center: [0.0, 2.0],
                    radius: 1.0,
                    side,
                },
                0.0,
            );
            let p = current_points(&t, 0.0, ext);
            assert!(p.len() >= 73);
            let a = area(&p);
            // the polygon of 72 chords: area a bit below pi
            assert!(sign * a > 3.1 && sign * a < std::f64::consts::PI, "{a}");
            for q in &p {
                assert!(((q[0]).hypot(q[1] - 2.0) - 1.0).abs() < 1e-14);
            }
        }
        let t = tool(
            ToolGeometry::Arc {
                center: [0.0, 0.0],
                radius: 2.0,
                start_angle: 0.0,
                end_angle: 0.1,
            },
            1.0,
        );
        let p = current_points(&t, 0.5, ext);
        // at least 8 segments, moved up by 0.5
        assert_eq!(p.len(), 9);
        assert!((p[0][0] - 2.0).abs() < 1e-15 && (p[0][1] - 0.5).abs() < 1e-15);
    }

    #[test]
    fn polylines_and_nurbs_pass_through_their_ends() {
        let ext = [[0.0; 2], [1.0; 2]];
        let t = tool(
            ToolGeometry::Polyline {
                points: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]],
            },
            2.0,
        );
        assert_eq!(
            current_points(&t, 0.25, ext),
            [[0.0, 0.5], [1.0, 0.5], [1.0, 1.5]]
        );
        let t = tool(
            ToolGeometry::Nurbs {
                degree: 2,
                control_points: vec![[0.0, 0.0], [1.0, 1.0], [2.0, 0.0], [3.0, 1.0]],
                weights: vec![1.0; 4],
                knots: vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
            },
            0.0,
        );
        let p = current_points(&t, 0.0, ext);
        assert_eq!(p.len(), 2 * PER_SPAN + 1);
        assert!(p[0] == [0.0, 0.0] && (p[2 * PER_SPAN][0] - 3.0).abs() < 1e-14);
    }
}
