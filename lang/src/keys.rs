//! Key tables: the keys of a construct's block with their value type,
//! default, range, physical dimension and meaning.
//!
//! One table serves three readers: the parser reads a block through it
//! ([`crate::parse::fields::Fields::keyed`] and
//! [`crate::parse::settings`]), validation checks the ranges it declares
//! ([`crate::validate::ranges`]), and the keyword reference prints it.
//! Tables are `static` data, written with the `const` builder methods of
//! [`Key`]:
//!
//! ```
//! use ctc_lang::keys::{Components, Dim, Key, KeyType, Range};
//! const RADIUS: Key = Key::new("radius", KeyType::Number, "radius of the disc")
//!     .required("add `radius = ..`")
//!     .range(Range::Positive)
//!     .dim(Dim::Length);
//! const CENTER: Key = Key::new("center", KeyType::Point(Components::Two), "centre");
//! assert_eq!(RADIUS.range, Range::Positive);
//! assert_eq!(CENTER.ty.describe(), "a point `(x, y)`");
//! ```

use crate::units::Exponents;
use std::fmt;

/// How many components a point or tuple has.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Components {
    /// Always `(x, y)`.
    Two,
    /// Always `(x, y, z)`.
    Three,
    /// As many as the analysis has space dimensions (2 for the planar
    /// analyses, 3 for `3d`): checked by validation, which knows it.
    Analysis,
}

impl Components {
    /// The counts accepted while parsing (before the analysis is known).
    pub fn accepts(self, n: usize) -> bool {
        match self {
            Components::Two => n == 2,
            Components::Three => n == 3,
            Components::Analysis => n == 2 || n == 3,
        }
    }

    /// "a pair", "a triple" or "a tuple", followed by `suffix`.
    pub fn noun(self, suffix: &str) -> String {
        let n = match self {
            Components::Two => "a pair",
            Components::Three => "a triple",
            Components::Analysis => "a tuple",
        };
        format!("{n}{suffix}")
    }

    /// The tuple written out, e.g. `(x, y)`.
    pub fn tuple(self, names: [&str; 3]) -> String {
        match self {
            Components::Two => format!("({}, {})", names[0], names[1]),
            Components::Three => format!("({}, {}, {})", names[0], names[1], names[2]),
            Components::Analysis => format!("({}, {}[, {}])", names[0], names[1], names[2]),
        }
    }
}

/// The type of a key's value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KeyType {
    /// A number.
    Number,
    /// A whole number.
    Integer,
    /// `true` or `false`.
    Bool,
    /// A point or vector.
    Point(Components),
    /// A tuple of numbers, e.g. a size `(width, height)`.
    Numbers(Components),
    /// A tuple of whole numbers, e.g. divisions `(nx, ny)`.
    Integers(Components),
    /// A grading: `uniform`, `geometric(ratio)` or `center(ratio)`.
    Grading,
    /// A tuple of gradings, one per direction.
    Gradings(Components),
    /// One name among these.
    Choice(&'static [&'static str]),
    /// Another mesh (a generator or `file "part.msh"`), input of a
    /// generator that transforms it (extrusion, revolution).
    Mesh,
    /// A file path in quotes, relative to the deck's directory.
    File,
}

impl KeyType {
    /// The expected value in words ("a number", "a point `(x, y)`").
    pub fn describe(self) -> String {
        match self {
            KeyType::Number => "a number".into(),
            KeyType::Integer => "a whole number".into(),
            KeyType::Bool => "`true` or `false`".into(),
            KeyType::Point(c) => format!("a point `{}`", c.tuple(["x", "y", "z"])),
            KeyType::Numbers(c) => format!("{} `{}`", c.noun(""), c.tuple(["a", "b", "c"])),
            KeyType::Integers(c) => format!(
                "{} of whole numbers `{}`",
                c.noun(""),
                c.tuple(["nx", "ny", "nz"])
            ),
            KeyType::Grading => {
                "a grading (`uniform`, `geometric(ratio)` or `center(ratio)`)".into()
            }
            KeyType::Gradings(c) => {
                format!("{} of gradings `{}`", c.noun(""), c.tuple(["x", "y", "z"]))
            }
            KeyType::Choice(names) => crate::suggest::one_of(names),
            KeyType::Mesh => "a mesh (a generator `name { .. }` or `file \"part.msh\"`)".into(),
            KeyType::File => "a file path in quotes (relative to the deck's directory)".into(),
        }
    }
}

/// The values a key accepts beyond its type.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Range {
    /// Any value of the type.
    Any,
    /// `> 0` (for tuples: every component; for gradings: the ratio).
    Positive,
    /// `>= 0`.
    NonNegative,
    /// Whole numbers `>= n`.
    AtLeast(i64),
    /// `[lo, hi]`.
    Closed(f64, f64),
}

impl fmt::Display for Range {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Range::Any => f.write_str("any"),
            Range::Positive => f.write_str("> 0"),
            Range::NonNegative => f.write_str(">= 0"),
            Range::AtLeast(n) => write!(f, ">= {n}"),
            Range::Closed(lo, hi) => {
                write!(f, "[{}, {}]", crate::ast::num(*lo), crate::ast::num(*hi))
            }
        }
    }
}

/// The physical dimension of a key's value (what its unit measures).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dim {
    /// Not declared: a number with a unit keeps its own dimension.
    Any,
    /// A pure number (count, ratio, exponent, coefficient).
    None,
    /// Length.
    Length,
    /// Plane angle in degrees.
    AngleDegrees,
    /// Plane angle in radians.
    AngleRadians,
    /// Stress, pressure, modulus.
    Stress,
    /// Time.
    Time,
    /// Force.
    Force,
    /// Temperature.
    Temperature,
    /// Mass density.
    Density,
    /// Thermal conductivity (W/(m K)).
    Conductivity,
    /// Specific heat capacity (J/(kg K)).
    SpecificHeat,
    /// Thermal expansion coefficient (1/K).
    Expansion,
    /// Viscosity of a Perzyna law (stress x time).
    Viscosity,
    /// Area penalty (stress / length).
    PenaltyArea,
    /// Nodal penalty (force / length).
    PenaltyNodal,
    /// Heat transfer coefficient (W/(m^2 K)).
    HeatTransfer,
    /// Heat flux (W/m^2).
    HeatFlux,
    /// Velocity (length / time).
    Velocity,
    /// Frequency, rate (1 / time).
    Frequency,
    /// Mass.
    Mass,
    /// Dashpot coefficient (force x time / length).
    Dashpot,
}

impl Dim {
    /// The dimension in words, for the keyword reference.
    pub fn describe(self) -> &'static str {
        match self {
            Dim::Any => "any",
            Dim::None => "-",
            Dim::Length => "length",
            Dim::AngleDegrees => "angle (degrees)",
            Dim::AngleRadians => "angle (radians)",
            Dim::Stress => "stress",
            Dim::Time => "time",
            Dim::Force => "force",
            Dim::Temperature => "temperature",
            Dim::Density => "density",
            Dim::Conductivity => "conductivity",
            Dim::SpecificHeat => "specific heat",
            Dim::Expansion => "1/temperature",
            Dim::Viscosity => "stress x time",
            Dim::PenaltyArea => "stress/length",
            Dim::PenaltyNodal => "force/length",
            Dim::HeatTransfer => "power/(area temperature)",
            Dim::HeatFlux => "power/area",
            Dim::Velocity => "length/time",
            Dim::Frequency => "1/time",
            Dim::Mass => "mass",
            Dim::Dashpot => "force x time/length",
        }
    }

    /// The exponents of the dimension (`None` for [`Dim::Any`]).
    pub fn exponents(self) -> Option<Exponents> {
        let k = Exponents::TEMPERATURE;
        Some(match self {
            Dim::Any => return None,
            Dim::None => Exponents::NONE,
            Dim::Length => Exponents::LENGTH,
            Dim::AngleDegrees | Dim::AngleRadians => Exponents::ANGLE,
            Dim::Stress => Exponents::STRESS,
            Dim::Time => Exponents::TIME,
            Dim::Force => Exponents::FORCE,
            Dim::Temperature => k,
            Dim::Density => Exponents::mlt(1, -3, 0),
            Dim::Conductivity => Exponents::POWER.per(Exponents::LENGTH).per(k),
            Dim::SpecificHeat => Exponents::ENERGY.per(Exponents::MASS).per(k),
            Dim::Expansion => Exponents::NONE.per(k),
            Dim::Viscosity => Exponents::STRESS.times(Exponents::TIME),
            Dim::PenaltyArea => Exponents::STRESS.per(Exponents::LENGTH),
            Dim::PenaltyNodal => Exponents::FORCE.per(Exponents::LENGTH),
            Dim::HeatTransfer => Exponents::POWER.per(Exponents::LENGTH.pow(2)).per(k),
            Dim::HeatFlux => Exponents::POWER.per(Exponents::LENGTH.pow(2)),
            Dim::Velocity => Exponents::LENGTH.per(Exponents::TIME),
            Dim::Frequency => Exponents::NONE.per(Exponents::TIME),
            Dim::Mass => Exponents::MASS,
            Dim::Dashpot => Exponents::FORCE
                .times(Exponents::TIME)
                .per(Exponents::LENGTH),
        })
    }
}

/// The default of a key that may be left out.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Default {
    /// No default: the key is required, or leaving it out means "none".
    None,
    /// A number.
    Number(f64),
    /// A whole number.
    Integer(i64),
    /// A boolean.
    Bool(bool),
    /// A choice.
    Choice(&'static str),
    /// A point or number tuple.
    Numbers(&'static [f64]),
    /// `uniform` grading (for every direction of a grading tuple).
    Uniform,
}

impl fmt::Display for Default {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Default::None => f.write_str("-"),
            Default::Number(x) => f.write_str(&crate::ast::num(*x)),
            Default::Integer(n) => write!(f, "{n}"),
            Default::Bool(b) => write!(f, "{b}"),
            Default::Choice(c) => f.write_str(c),
            Default::Numbers(xs) => {
                let parts: Vec<String> = xs.iter().map(|x| crate::ast::num(*x)).collect();
                write!(f, "({})", parts.join(", "))
            }
            Default::Uniform => f.write_str("uniform"),
        }
    }
}

/// One key of a block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Key {
    /// The key as written in the deck.
    pub name: &'static str,
    /// The type of its value.
    pub ty: KeyType,
    /// What it means (one line, for the keyword reference).
    pub doc: &'static str,
    /// `Some(help)` when the key is required: the help of the "missing
    /// key" diagnostic, e.g. "add `radius = ..`".
    pub required: Option<&'static str>,
    /// The value used when the key is left out.
    pub default: Default,
    /// Accepted values.
    pub range: Range,
    /// Names of the value (or of each component of a tuple) in range
    /// diagnostics, e.g. `["width", "height"]`; empty: the key's name.
    pub labels: &'static [&'static str],
    /// Physical dimension ([`Dim::Any`] when not declared).
    pub dim: Dim,
}

impl Key {
    /// An optional key without default, range or dimension.
    pub const fn new(name: &'static str, ty: KeyType, doc: &'static str) -> Key {
        Key {
            name,
            ty,
            doc,
            required: None,
            default: Default::None,
            range: Range::Any,
            labels: &[],
            dim: Dim::Any,
        }
    }

    /// Makes the key required; `help` says what to add.
    pub const fn required(mut self, help: &'static str) -> Key {
        self.required = Some(help);
        self
    }

    /// Sets the default.
    pub const fn default(mut self, d: Default) -> Key {
        self.default = d;
        self
    }

    /// Sets the accepted range.
    pub const fn range(mut self, r: Range) -> Key {
        self.range = r;
        self
    }

    /// Sets the names used in range diagnostics.
    pub const fn labels(mut self, l: &'static [&'static str]) -> Key {
        self.labels = l;
        self
    }

    /// Sets the physical dimension.
    pub const fn dim(mut self, d: Dim) -> Key {
        self.dim = d;
        self
    }

    /// The name of component `i` (or of the whole value) in diagnostics.
    pub fn label(&self, i: usize) -> &'static str {
        self.labels
            .get(i)
            .or(self.labels.first())
            .copied()
            .unwrap_or(self.name)
    }
}

/// The names of a table's keys, in table order.
pub fn names(keys: &[Key]) -> Vec<&'static str> {
    keys.iter().map(|k| k.name).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn key_builder_and_descriptions() {
        const K: Key = Key::new("divisions", KeyType::Integers(Components::Two), "d")
            .required("add it")
            .range(Range::AtLeast(1))
            .labels(&["divisions along x", "divisions along y"]);
        assert_eq!(K.label(1), "divisions along y");
        assert_eq!(K.required, Some("add it"));
        assert_eq!(K.ty.describe(), "a pair of whole numbers `(nx, ny)`");
        assert_eq!(Key::new("r", KeyType::Number, "").label(0), "r");
        assert_eq!(Range::Closed(0.0, 1.0).to_string(), "[0, 1]");
        assert_eq!(Default::Numbers(&[0.0, 0.0]).to_string(), "(0, 0)");
        assert!(Components::Analysis.accepts(3) && !Components::Two.accepts(3));
    }
}
