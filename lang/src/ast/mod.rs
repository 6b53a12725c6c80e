//! The typed AST of a `.ctc` deck. Every node carries the [`Span`] of the
//! text it came from.
//!
//! - [`syntax`]: the generic block/value syntax produced by the grammar;
//! - [`values`]: points, set references, selections, time functions, gradings;
//! - [`items`]: one node type per top-level construct;
//! - [`settings`]: values read through a key table (mesh generators);
//! - [`thermal`]: `thermal` blocks and thermal load items.

pub mod items;
pub mod settings;
pub mod syntax;
pub mod thermal;
pub mod values;

pub use crate::span::{Ident, Span, Spanned};
pub use items::*;
pub use values::*;

/// A parsed deck: its items grouped by kind, each group in deck order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Deck {
    /// `analysis { .. }` blocks (exactly one is valid).
    pub analysis: Vec<Analysis>,
    /// `material` items.
    pub materials: Vec<Material>,
    /// `body` items.
    pub bodies: Vec<Body>,
    /// `set` items.
    pub sets: Vec<SetDef>,
    /// `tool` items.
    pub tools: Vec<Tool>,
    /// `contact` items.
    pub contacts: Vec<Contact>,
    /// `fix` and `displace` items.
    pub boundaries: Vec<Boundary>,
    /// `pressure` and `force` items.
    pub loads: Vec<LoadDef>,
    /// `step` items.
    pub steps: Vec<Step>,
    /// `output` blocks (at most one is valid).
    pub outputs: Vec<Output>,
    /// Items that did not parse (already reported).
    pub broken: Vec<BrokenItem>,
    /// `temperature`, `heat_flux` and `convection` items.
    pub thermal_loads: Vec<thermal::ThermalLoad>,
    /// `let` parameters, in deck order.
    pub lets: Vec<Let>,
    /// `initial_velocity` items.
    pub initial_velocities: Vec<InitialVelocity>,
    /// `spring` and `point_mass` items.
    pub discrete: Vec<DiscreteItem>,
    /// `gravity` items.
    pub gravity: Vec<Gravity>,
}

impl Deck {
    /// Whether an item of kind `keyword` that failed to parse may have been
    /// named `name` (so references to `name` should not be reported).
    pub fn broken_named(&self, keyword: &str, name: &str) -> bool {
        self.broken
            .iter()
            .any(|b| b.keyword == keyword && b.name.as_deref().is_none_or(|n| n == name))
    }

    /// Whether an item of kind `keyword` failed to parse.
    pub fn has_broken(&self, keyword: &str) -> bool {
        self.broken.iter().any(|b| b.keyword == keyword)
    }
}
