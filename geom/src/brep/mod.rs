//! BREP tools: trimmed faces with holes, their edges and vertices, and the
//! neighbour-first face search.
//!
//! A query point `x` takes the closest point of the whole tool:
//! - a face whose surface foot is an orthogonal projection inside its
//!   boundary (parity test) gives an **interior** foot: the surface normal
//!   and the offset-surface curvature;
//! - a face whose foot falls outside its boundary contributes the closest
//!   points of its edges: an **edge** foot is a cylinder of radius 0 along
//!   the edge, a **vertex** foot (the edge's closest point clamped at its
//!   end) a sphere of radius 0; their sign is that of `(x - P) . N`, `N` the
//!   pseudonormal (sum of the two faces' normals along an edge,
//!   angle-weighted sum at a vertex: Baerentzen & Aanaes 2005), positive at a
//!   free boundary (a node past the tool's extent is not inside it);
//! - a foot outside its face's boundary but within the seam tolerance of it
//!   (3D distance) is still accepted as interior, so a node does not fall
//!   through the seam between two faces that meet only to the CAD
//!   tolerance.
//!
//! Faces are tested last face first, then its neighbours (faces sharing an
//! edge or a vertex), then the rest, and a face whose box is farther than the
//! best candidate (or than the search distance) is skipped.

pub mod edge;
pub mod face;
pub mod search;
pub mod tool;

pub use edge::Coedge;
pub use face::Face;
pub use search::{Counters, SearchState};
pub use tool::{BrepOptions, BrepTool, Vertex};
