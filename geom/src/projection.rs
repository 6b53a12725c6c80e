//! The result of a closest-point projection, shared by every tool.

use crate::{Mat3, Vec2, Vec3};

/// Which side of a closed or two-sided surface is free space.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The body is outside (a punch, a roller): gap = distance outside.
    Outside,
    /// The body is inside (a container, a die cavity): gap = distance inside.
    Inside,
}

impl Side {
    /// `+1` for [`Side::Outside`], `-1` for [`Side::Inside`].
    pub fn sign(self) -> f64 {
        match self {
            Side::Outside => 1.0,
            Side::Inside => -1.0,
        }
    }
}

/// Where on the tool the closest point lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FootKind {
    /// A regular point of a smooth surface: the normal is the surface normal.
    Interior,
    /// A point of an edge (a curve where faces meet, or a free boundary):
    /// treated as a cylinder of radius 0 around the edge.
    Edge,
    /// A vertex (the end of edges, the apex of a cone): treated as a sphere
    /// of radius 0.
    Vertex,
}

/// Closest-point projection of a query point on a tool (reference frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// The closest point of the tool (the foot).
    pub point: Vec3,
    /// Signed distance to `point`: positive on the free side.
    pub gap: f64,
    /// Unit normal at the foot pointing into free space; `x = point + gap *
    /// normal` and `normal = dg/dx`.
    pub normal: Vec3,
    /// `dn/dx`: derivative of the normal with respect to the query point
    /// (symmetric, `curvature * normal = 0`).
    pub curvature: Mat3,
    /// What kind of point the foot is.
    pub kind: FootKind,
    /// Parameter of the foot: `(u, v)` on a surface, `(t, 0)` on an edge
    /// curve, `(0, 0)` at a vertex.
    pub param: Vec2,
    /// The tool entity holding the foot (face, edge or vertex index of a
    /// BREP tool; triangle, edge or vertex of a mesh; 0 for analytical tools).
    pub entity: usize,
    /// Newton iterations spent (0 for closed forms).
    pub iterations: u32,
    /// Residual of the foot-point equations at the returned foot: the sine
    /// of the angle between `x - point` and the tangent plane, or the
    /// tangential offset over `1e-4` of the tool size for points nearer than
    /// that (0 for closed forms).
    pub residual: f64,
}

impl Projection {
    /// A projection on a smooth surface point with zero iterations.
    pub fn closed_form(point: Vec3, gap: f64, normal: Vec3, curvature: Mat3) -> Self {
        Projection {
            point,
            gap,
            normal,
            curvature,
            kind: FootKind::Interior,
            param: Vec2::zeros(),
            entity: 0,
            iterations: 0,
            residual: 0.0,
        }
    }

    /// The same projection with another foot kind.
    pub fn with_kind(mut self, kind: FootKind) -> Self {
        self.kind = kind;
        self
    }
}

/// Why a projection gave no answer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ProjectionError {
    /// The closest point is not unique and the normal is undefined (the
    /// centre of a sphere, the axis of a cylinder or torus, the centre of
    /// curvature of a surface point).
    Singular {
        /// The query point (reference frame).
        at: Vec3,
    },
    /// The Newton iteration on the foot-point equations did not converge
    /// from any seed.
    NotConverged {
        /// Iterations spent over all seeds.
        iterations: u32,
        /// Smallest residual reached (sine of the angle to the tangent plane).
        residual: f64,
        /// Parameter with that residual.
        param: Vec2,
    },
    /// The point is farther from the tool than the search distance given
    /// (no candidate entity was tested).
    OutOfReach,
}

impl std::fmt::Display for ProjectionError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ProjectionError::Singular { at } => write!(
                f,
                "the closest point to ({}, {}, {}) is not unique (a centre or an axis of the tool)",
                at.x, at.y, at.z
            ),
            ProjectionError::NotConverged {
                iterations,
                residual,
                param,
            } => write!(
                f,
                "the projection did not converge after {iterations} Newton iterations \
                 (residual {residual:.3e} at u = {}, v = {})",
                param.x, param.y
            ),
            ProjectionError::OutOfReach => write!(f, "the point is out of the search distance"),
        }
    }
}

impl std::error::Error for ProjectionError {}
