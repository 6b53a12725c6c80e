//! Typed values shared by several constructs: points, set references,
//! geometric selections, time functions, gradings.

use crate::span::{Ident, Span, Spanned};
use std::fmt;

/// A point or vector `(x, y)`.
pub type Point = Spanned<[f64; 2]>;

/// A point or vector of space `(x, y, z)`.
pub type Point3 = Spanned<[f64; 3]>;

/// Coordinates as written in a selection: a planar [`Point`] `(x, y)` or a
/// [`Point3`] `(x, y, z)`; the analysis decides which is right (validation
/// checks it).
#[derive(Debug, Clone, PartialEq)]
pub enum Coords {
    /// `(x, y)`.
    Plane(Point),
    /// `(x, y, z)`.
    Space(Point3),
}

impl Coords {
    /// The coordinates, 2 or 3 of them.
    pub fn values(&self) -> &[f64] {
        match self {
            Coords::Plane(p) => &p.value,
            Coords::Space(p) => &p.value,
        }
    }

    /// The number of coordinates.
    pub fn len(&self) -> usize {
        self.values().len()
    }

    /// Never: a point has 2 or 3 coordinates (for clippy's `len` rule).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Where the point is written.
    pub fn span(&self) -> Span {
        match self {
            Coords::Plane(p) => p.span,
            Coords::Space(p) => p.span,
        }
    }
}

/// A pair of numbers `(a, b)`, each with its own span (for range errors).
pub type Pair = Spanned<[Spanned<f64>; 2]>;

/// A pair of whole numbers `(a, b)`, each with its own span.
pub type IntPair = Spanned<[Spanned<i64>; 2]>;

/// A reference to a set of nodes or edges of a body.
#[derive(Debug, Clone, PartialEq)]
pub struct SetRef {
    /// The body (`block` in `block.top`).
    pub body: Ident,
    /// Which part of the body.
    pub kind: SetRefKind,
    /// The whole reference.
    pub span: Span,
}

/// The ways of naming part of a body.
#[derive(Debug, Clone, PartialEq)]
pub enum SetRefKind {
    /// A named set: generator set, gmsh physical group, deck `set`, or the
    /// built-in `boundary` (edges) and `all` (nodes).
    Named(Ident),
    /// `body.nodes(..)`: nodes selected geometrically.
    Nodes(Spanned<Selection>),
    /// `body.node(near(x, y[, z]))`: the single node closest to a point.
    Node(Spanned<Selection>),
    /// `body.edges(..)`: boundary edges with both nodes selected (planar).
    Edges(Spanned<Selection>),
    /// `body.faces(..)`: boundary faces with every node selected (3d).
    Faces(Spanned<Selection>),
    /// `a.top + a.side - a.corner`: a union and difference of references
    /// to the same body, left to right (`true`: added, `false`: removed).
    Combination(Vec<(bool, SetRef)>),
}

/// A geometric selection, as written (2 or 3 coordinates: validation
/// checks them against the analysis).
#[derive(Debug, Clone, PartialEq)]
pub enum Selection {
    /// `x = value`.
    X(f64),
    /// `y = value`.
    Y(f64),
    /// `z = value` (3d).
    Z(f64),
    /// `box((x0, y0), (x1, y1))` or `box((x0, y0, z0), (x1, y1, z1))`.
    Box {
        /// First corner.
        min: Coords,
        /// Opposite corner.
        max: Coords,
    },
    /// `near(x, y)` or `near(x, y, z)`.
    Near(Coords),
}

impl Selection {
    /// The axis (0 = x, 1 = y, 2 = z) and value of `x = ..`, `y = ..`,
    /// `z = ..`.
    pub fn plane(&self) -> Option<(usize, f64)> {
        match self {
            Selection::X(v) => Some((0, *v)),
            Selection::Y(v) => Some((1, *v)),
            Selection::Z(v) => Some((2, *v)),
            Selection::Box { .. } | Selection::Near(_) => None,
        }
    }
}

/// `a, b[, c]` with numbers printed as a user writes them.
fn coords(c: &[f64]) -> String {
    c.iter().map(|v| num(*v)).collect::<Vec<_>>().join(", ")
}

impl fmt::Display for Selection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Selection::X(v) => write!(f, "x = {}", num(*v)),
            Selection::Y(v) => write!(f, "y = {}", num(*v)),
            Selection::Z(v) => write!(f, "z = {}", num(*v)),
            Selection::Box { min, max } => {
                write!(
                    f,
                    "box(({}), ({}))",
                    coords(min.values()),
                    coords(max.values())
                )
            }
            Selection::Near(p) => write!(f, "near({})", coords(p.values())),
        }
    }
}

impl fmt::Display for SetRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            SetRefKind::Named(n) => write!(
                f,
                "{}.{}",
                self.body,
                crate::ast::syntax::quoted_name(&n.name)
            ),
            SetRefKind::Combination(terms) => {
                for (i, (add, t)) in terms.iter().enumerate() {
                    if i > 0 {
                        f.write_str(if *add { " + " } else { " - " })?;
                    }
                    write!(f, "{t}")?;
                }
                Ok(())
            }
            SetRefKind::Nodes(s) => write!(f, "{}.nodes({})", self.body, s.value),
            SetRefKind::Node(s) => write!(f, "{}.node({})", self.body, s.value),
            SetRefKind::Edges(s) => write!(f, "{}.edges({})", self.body, s.value),
            SetRefKind::Faces(s) => write!(f, "{}.faces({})", self.body, s.value),
        }
    }
}

/// Formats a number the way a user would write it (shortest round-trip
/// form, exponent notation for very large or small magnitudes).
pub fn num(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 {
        "0".to_string()
    } else if (1e-4..1e7).contains(&a) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// A scalar function of the analysis time, as written.
#[derive(Debug, Clone, PartialEq)]
pub enum TimeFn {
    /// A plain number: constant in time.
    Number(f64),
    /// `constant(v)`.
    Constant(f64),
    /// `ramp(v0, v1)` over the whole analysis, or `ramp(v0, v1, t0, t1)`.
    Ramp {
        /// Start value.
        v0: f64,
        /// End value.
        v1: f64,
        /// Explicit time window `(t0, t1)`, if given.
        window: Option<[Spanned<f64>; 2]>,
    },
    /// `table((t, v), ..)`: piecewise linear.
    Table(Vec<Spanned<(f64, f64)>>),
}

impl fmt::Display for TimeFn {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TimeFn::Number(v) => write!(f, "{}", num(*v)),
            TimeFn::Constant(v) => write!(f, "constant({})", num(*v)),
            TimeFn::Ramp { v0, v1, window } => match window {
                None => write!(f, "ramp({}, {})", num(*v0), num(*v1)),
                Some([t0, t1]) => write!(
                    f,
                    "ramp({}, {}, {}, {})",
                    num(*v0),
                    num(*v1),
                    num(t0.value),
                    num(t1.value)
                ),
            },
            TimeFn::Table(pts) => {
                f.write_str("table(")?;
                for (i, p) in pts.iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    write!(f, "({}, {})", num(p.value.0), num(p.value.1))?;
                }
                f.write_str(")")
            }
        }
    }
}

/// Division spacing of a mesh generator direction.
#[derive(Debug, Clone, PartialEq)]
pub enum Grading {
    /// `uniform`.
    Uniform,
    /// `geometric(ratio)`: last / first division size.
    Geometric(Spanned<f64>),
    /// `center(ratio)`: end / middle division size.
    Center(Spanned<f64>),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_print_like_a_user_writes_them() {
        assert_eq!(num(0.0), "0");
        assert_eq!(num(210000.0), "210000");
        assert_eq!(num(0.3), "0.3");
        assert_eq!(num(1e-9), "1e-9");
        assert_eq!(num(-2.5e12), "-2.5e12");
    }

    #[test]
    fn set_refs_display_normalised() {
        let s = Span::default();
        let r = SetRef {
            body: Ident::new("block", s),
            kind: SetRefKind::Edges(Spanned::new(
                Selection::Box {
                    min: Coords::Plane(Spanned::new([-1.0, -0.01], s)),
                    max: Coords::Plane(Spanned::new([1.0, 0.01], s)),
                },
                s,
            )),
            span: s,
        };
        assert_eq!(r.to_string(), "block.edges(box((-1, -0.01), (1, 0.01)))");
        let near = Selection::Near(Coords::Space(Spanned::new([1.0, 2.0, -0.5], s)));
        let r = SetRef {
            kind: SetRefKind::Node(Spanned::new(near, s)),
            ..r
        };
        assert_eq!(r.to_string(), "block.node(near(1, 2, -0.5))");
        let faces = SetRef {
            kind: SetRefKind::Faces(Spanned::new(Selection::Z(0.0), s)),
            ..r
        };
        assert_eq!(faces.to_string(), "block.faces(z = 0)");
        let t = TimeFn::Ramp {
            v0: 0.0,
            v1: -0.05,
            window: None,
        };
        assert_eq!(t.to_string(), "ramp(0, -0.05)");
    }
}
