//! Constitutive laws.
