//! The test kit: one way to build a [`Model`](crate::model::Model) by hand
//! and one observer that records a run, shared by the unit tests, the
//! integration tests of every crate and the verification harness.
//!
//! Tests describe a scene by what it contains (`.body(..)`, `.fix(..)`,
//! `.step(..)`) instead of spelling out every field of the model, so a
//! change of the model's shape (dimension as a parameter, new fields) is
//! made here once instead of in every test.
//!
//! - [`builder`]: [`ModelBuilder`], the fluent model builder;
//! - [`recorder`]: [`Recorder`], an observer keeping every converged
//!   increment, iteration, cutback and warning, and [`solve`];
//! - [`grid`]: structured (optionally jittered) meshes and mesh merging;
//! - [`solid`]: the 3D patch and objectivity scenes (cargo tests and
//!   `ctc verify` run the same function);
//! - [`laws`]: one instance of every nonlinear material law;
//! - [`Rng`]: a deterministic xorshift generator.

pub mod builder;
pub mod grid;
pub mod laws;
pub mod recorder;
pub mod solid;

pub use builder::{ramp, ModelBuilder};
pub use recorder::{solve, Increment, Recorder};

/// Deterministic xorshift generator (tests must not depend on a seed source).
#[derive(Debug, Clone)]
pub struct Rng(pub u64);

impl Rng {
    /// Uniform in [0, 1).
    pub fn next_f64(&mut self) -> f64 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        self.0 = x;
        (x >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [-1, 1).
    pub fn sym(&mut self) -> f64 {
        2.0 * self.next_f64() - 1.0
    }
}
