//! Closed-form reference solutions, each checked by its own unit tests
//! against the numeric instances of `VERIFICATION-CASES.md`.
//!
//! - [`hertz`]: Hertz contact of a cylinder (plane strain) and a sphere;
//! - [`lame`]: thick-walled cylinder under internal pressure (Lamé);
//! - [`patch`]: the uniform state of a block pressed onto a rigid plane
//!   through an area penalty (contact patch test).

pub mod hertz;
pub mod lame;
pub mod patch;
