//! IGES (Initial Graphics Exchange Specification 5.3) import of trimmed
//! NURBS geometry, and a small writer.
//!
//! Read: the fixed 80-column ASCII form ([`records`]), the Global section's
//! delimiters ([`params`]: Hollerith strings, `E`/`D` exponents, defaults),
//! the Directory entries and the Parameter data, then the entities
//! 128 (rational B-spline surface), 126 (rational B-spline curve), 110
//! (line), 100 (circular arc), 102 (composite curve), 142 (curve on a
//! parametric surface), 144 (trimmed surface), 143 (bounded surface, with
//! its 141 boundaries) and 124 (transformation matrix). Entities of other
//! types are listed in [`IgesFile::unsupported`] with their type and line;
//! one that a face needs is an [`IgesErrorKind::Unsupported`] error. Bad
//! files give an [`IgesError`] with the line, never a panic.
//!
//! Not supported (each a typed error naming the entity): trimming curves
//! given in model space only (142 without a parameter-space curve, 141 of
//! type 0), a 126 restricted to part of its knot range, the compressed and
//! binary forms.

pub mod error;
pub mod params;
pub mod reader;
pub mod records;
pub mod writer;

pub use error::{IgesError, IgesErrorKind};
pub use reader::{read, Entry, Global, IgesFile, ImportedFace, Unsupported};
pub use writer::Writer;
