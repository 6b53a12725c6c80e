//! AST of the thermal constructs: the `thermal` blocks of materials,
//! bodies and contacts, and the thermal load items `temperature`,
//! `heat_flux` and `convection`.

use super::values::{SetRef, TimeFn};
use crate::span::{Span, Spanned};

/// `thermal { .. }` in a material.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialThermal {
    /// `conductivity = k` (> 0).
    pub conductivity: Option<Spanned<f64>>,
    /// `capacity = c` (specific heat, >= 0).
    pub capacity: Option<Spanned<f64>>,
    /// `density = rho` (>= 0).
    pub density: Option<Spanned<f64>>,
    /// `expansion = alpha` (>= 0, default 0).
    pub expansion: Option<Spanned<f64>>,
    /// `reference = T_ref`: zero thermal strain (default 0).
    pub reference: Option<Spanned<f64>>,
    /// `taylor_quinney = beta` in [0, 1] (default 0.9).
    pub taylor_quinney: Option<Spanned<f64>>,
    /// `young = table((T, factor), ..)`: Young's modulus factor.
    pub young: Option<Spanned<Vec<(f64, f64)>>>,
    /// `yield = table((T, factor), ..)`: flow stress factor.
    pub yield_factor: Option<Spanned<Vec<(f64, f64)>>>,
    /// The block.
    pub span: Span,
}

/// `thermal { initial = T0 }` in a body.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyThermal {
    /// `initial = T0` (default 0).
    pub initial: Option<Spanned<f64>>,
    /// The block.
    pub span: Span,
}

/// Contact conductance law.
#[derive(Debug, Clone, PartialEq)]
pub enum Conductance {
    /// `conductance = h`: constant.
    Constant(Spanned<f64>),
    /// `power { h0 = .. h1 = .. n = .. }`: `h0 + h1 p^n`.
    Power {
        /// `h0` (default 0).
        h0: Option<Spanned<f64>>,
        /// `h1` (default 0).
        h1: Option<Spanned<f64>>,
        /// `n` (default 1).
        n: Option<Spanned<f64>>,
    },
    /// `conductance = table((p, h), ..)`.
    Table(Vec<(f64, f64)>),
}

/// `thermal { .. }` in a contact.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactThermal {
    /// `conductance = ..` (required).
    pub conductance: Option<Spanned<Conductance>>,
    /// `gap_conductivity = k_gap` (default 0: no heat across an open gap).
    pub gap_conductivity: Option<Spanned<f64>>,
    /// `gap_min = g_min` (default 1e-6 x the pair's scale... fixed 1e-9).
    pub gap_min: Option<Spanned<f64>>,
    /// `friction_split = f` in [0, 1] (default 0.5).
    pub friction_split: Option<Spanned<f64>>,
    /// `tool_temperature = ..` (rigid tools; time function).
    pub tool_temperature: Option<Spanned<TimeFn>>,
    /// The block.
    pub span: Span,
}

/// Kinds of thermal load items.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ThermalLoadKind {
    /// `temperature set { value = .. }`.
    Temperature,
    /// `heat_flux set { q = .. }`.
    HeatFlux,
    /// `convection set { h = ..  ambient = .. }`.
    Convection,
}

/// A `temperature`, `heat_flux` or `convection` item.
#[derive(Debug, Clone, PartialEq)]
pub struct ThermalLoad {
    /// Which item.
    pub kind: ThermalLoadKind,
    /// Where.
    pub target: SetRef,
    /// The prescribed temperature, flux or ambient temperature.
    pub value: Option<Spanned<TimeFn>>,
    /// Convection film coefficient `h`.
    pub film: Option<Spanned<f64>>,
    /// The whole item.
    pub span: Span,
}
