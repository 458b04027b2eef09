//! apart: exact assembly partitioning of polyhedral parts.
//!
//! This facade re-exports the library crates, following the data flow:
//! [`kernel`] (exact integers, grid, predicates), [`mesh`] (mesh files, snapping,
//! validation of one solid), [`pieces`] (exact convex polytopes), [`assembly`] (the
//! assembly model and its loader). The `apart` binary holds flags and output only.

pub use apart_assembly as assembly;
pub use apart_kernel as kernel;
pub use apart_mesh as mesh;
pub use apart_pieces as pieces;
