//! Rigid tool geometry in the tool's **reference** frame.
//!
//! A tool is split into *entities* (a polyline segment, an arc, a NURBS knot
//! span, the whole plane or circle). For a query point `x` each entity returns
//! the closest point of that entity and, from it, a signed gap, the unit normal
//! pointing into free space and the normal rate `h` such that
//! `d n / d x = h (t ⊗ t)` (`t` the unit tangent). The tool's gap at `x` is the
//! candidate with the smallest `|gap|`, i.e. the signed distance to the closest
//! point of the whole tool (ties: lowest entity index), see
//! [`crate::contact::search`].
//!
//! Sign convention: the gap is positive on the free side (where the body may
//! be: the left of an open curve walked in its given direction, the chosen
//! side of a circle, the normal side of a plane) and negative inside the tool.
//!
//! Non-smooth points:
//! - a **corner** shared by two entities (polyline vertex, C0 knot of a NURBS,
//!   seam of a closed curve) is treated as a circle of radius 0: when it is
//!   the closest point, the normal is the direction from the corner to the
//!   node and `|gap|` is the distance to the corner, so the normal field has no
//!   hole ("no projection but the node is inside") and no overlap;
//!   see [`corner`].
//! - a **free end** of an open curve acts as a rounded end: the gap is the
//!   (positive) distance to the end, also behind it, where the node is past
//!   the tool's extent and therefore not inside it.

pub mod arc;
pub mod circle;
pub mod corner;
pub mod nurbs;
pub mod plane;
pub mod polyline;

use crate::geom::Aabb;
use crate::model::ToolGeometry;

/// Where on the entity the closest point lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Foot {
    /// A regular point of the curve: the normal is the curve normal.
    Interior,
    /// A corner shared by two entities (radius-0 circle rule).
    Corner,
    /// A free end of an open curve (rounded end on the free side).
    End,
}

/// Closest-point projection of a point on a tool entity (reference frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// The closest point of the entity.
    pub point: [f64; 2],
    /// Signed gap: distance to `point`, positive on the free side.
    pub gap: f64,
    /// Unit normal at the projection, pointing into free space; the query
    /// point is `point + gap * normal`.
    pub normal: [f64; 2],
    /// Normal rate `h`: `d normal / d x = h (t ⊗ t)`, `t` the unit tangent.
    /// `h = kappa / (1 + kappa * gap)` on a curve of curvature `kappa`
    /// (positive when the tool is convex seen from the free side), 0 for a
    /// straight entity, `1 / gap` at a corner or a free end.
    pub normal_rate: f64,
    /// What kind of point `point` is.
    pub foot: Foot,
    /// Curve parameter of `point` (segment: `index + xi`; arc/circle: angle,
    /// radians; NURBS: knot parameter; plane: abscissa along the line).
    pub param: f64,
}

impl Projection {
    /// Projection on a regular curve point of curvature `curvature`.
    pub fn on_curve(
        point: [f64; 2],
        gap: f64,
        normal: [f64; 2],
        curvature: f64,
        param: f64,
    ) -> Self {
        Projection {
            point,
            gap,
            normal,
            normal_rate: normal_rate(curvature, gap),
            foot: Foot::Interior,
            param,
        }
    }
}

/// `h = kappa / (1 + kappa g)`, the rate of change of the normal of a curve
/// of curvature `kappa` seen from a point at signed distance `g` (derived
/// from `x = C(s) + g n(s)`, `dn/ds = kappa t`: `ds = t.dx / (1 + kappa g)`).
/// At a focal point (`1 + kappa g = 0`, the node at the centre of curvature)
/// the normal is undefined; 0 is returned there.
pub fn normal_rate(curvature: f64, gap: f64) -> f64 {
    let d = 1.0 + curvature * gap;
    if d.abs() <= 1e-12 {
        0.0
    } else {
        curvature / d
    }
}

/// A rigid tool's geometry prepared for projection and search.
#[derive(Debug, Clone, PartialEq)]
pub enum ToolShape {
    /// Infinite line.
    Plane(plane::Plane),
    /// Connected segments (open, or closed when the first and last points
    /// coincide).
    Polyline(polyline::Polyline),
    /// Circular arc.
    Arc(arc::Arc),
    /// Full circle.
    Circle(circle::Circle),
    /// NURBS curve, one entity per non-empty knot span.
    Nurbs(nurbs::Nurbs),
}

impl ToolShape {
    /// Prepares `geometry`; errors describe what is wrong in user terms.
    pub fn new(geometry: &ToolGeometry) -> Result<Self, String> {
        Ok(match geometry {
            ToolGeometry::Plane { point, normal } => {
                ToolShape::Plane(plane::Plane::new(*point, *normal)?)
            }
            ToolGeometry::Polyline { points } => {
                ToolShape::Polyline(polyline::Polyline::new(points)?)
            }
            ToolGeometry::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => ToolShape::Arc(arc::Arc::new(*center, *radius, *start_angle, *end_angle)?),
            ToolGeometry::Circle {
                center,
                radius,
                side,
            } => ToolShape::Circle(circle::Circle::new(*center, *radius, *side)?),
            ToolGeometry::Nurbs {
                degree,
                control_points,
                weights,
                knots,
            } => ToolShape::Nurbs(nurbs::Nurbs::new(*degree, control_points, weights, knots)?),
        })
    }

    /// Number of entities (segments, spans; 1 for plane, arc and circle).
    pub fn entity_count(&self) -> usize {
        match self {
            ToolShape::Plane(_) | ToolShape::Arc(_) | ToolShape::Circle(_) => 1,
            ToolShape::Polyline(p) => p.segment_count(),
            ToolShape::Nurbs(n) => n.span_count(),
        }
    }

    /// Bounding box of entity `e` in the reference frame.
    pub fn bounding_box(&self, e: usize) -> Aabb<2> {
        match self {
            ToolShape::Plane(_) => Aabb::<2>::everything(),
            ToolShape::Polyline(p) => p.bounding_box(e),
            ToolShape::Arc(a) => a.bounding_box(),
            ToolShape::Circle(c) => c.bounding_box(),
            ToolShape::Nurbs(n) => n.bounding_box(e),
        }
    }

    /// Closest point of entity `e` to `x` (reference frame), or `None` at a
    /// singular point (the centre of a circle or arc, where every point is
    /// closest and the normal is undefined).
    pub fn project(&self, e: usize, x: [f64; 2]) -> Option<Projection> {
        match self {
            ToolShape::Plane(p) => Some(p.project(x)),
            ToolShape::Polyline(p) => p.project(e, x),
            ToolShape::Arc(a) => a.project(x),
            ToolShape::Circle(c) => c.project(x),
            ToolShape::Nurbs(n) => n.project(e, x),
        }
    }

    /// The entities sharing an end with `e` (previous, next), if any.
    pub fn neighbours(&self, e: usize) -> [Option<usize>; 2] {
        let (count, closed) = match self {
            ToolShape::Polyline(p) => (p.segment_count(), p.is_closed()),
            ToolShape::Nurbs(n) => (n.span_count(), n.is_closed()),
            _ => return [None, None],
        };
        let prev = if e > 0 {
            Some(e - 1)
        } else if closed && count > 1 {
            Some(count - 1)
        } else {
            None
        };
        let next = if e + 1 < count {
            Some(e + 1)
        } else if closed && count > 1 {
            Some(0)
        } else {
            None
        };
        [prev, next]
    }
}

/// Checks a tool geometry; the message says what is wrong and how to fix it.
pub fn check(geometry: &ToolGeometry) -> Result<(), String> {
    ToolShape::new(geometry).map(|_| ())
}

/// Whether every coordinate of `p` is finite.
pub(crate) fn finite(p: [f64; 2]) -> bool {
    p[0].is_finite() && p[1].is_finite()
}
