//! NURBS: basis functions, rational curves and tensor-product surfaces with
//! derivatives, point projection on surfaces, exact constructions.

pub mod basis;
pub mod build;
pub mod curve;
pub mod project;
pub mod surface;

pub use curve::{CurveDerivs, NurbsCurve};
pub use project::{ProjectOptions, SurfaceFoot};
pub use surface::{NurbsSurface, SurfaceDerivs};
