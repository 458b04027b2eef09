//! apart: exact assembly partitioning, sequencing and separation of polyhedral parts.
//!
//! This facade re-exports the library crates, following the data flow:
//! [`kernel`] (exact integers, grid, predicates), [`formats`] (mesh files: readers and
//! writers), [`mesh`] (snapping, repair and validation of one solid), [`assembly`]
//! (the assembly model and its loader), [`pieces`] (exact convex polytopes),
//! [`decompose`] (exact convex decomposition), [`minkowski`] (convex sums and their
//! projection onto the sphere), [`sphere`] (arrangements of great-circle arcs),
//! [`plan`] (partitioning, sequences, separation), [`stack`] (placement by c-space
//! obstacles and stacking), [`jobs`] (each job with its typed answer, shared with the
//! Python binding) and [`draw`] (pictures and exports). The `apart` binary holds flags
//! and output only.
//!
//! ```no_run
//! let loaded = apart::assembly::load(std::path::Path::new("examples/split-star"), &Default::default()).unwrap();
//! let result = apart::partition(&loaded.assembly, &apart::plan::Options::default()).unwrap();
//! println!("{} solutions", result.solutions.len());
//! ```

pub use apart_assembly as assembly;
pub use apart_decompose as decompose;
pub use apart_draw as draw;
pub use apart_formats as formats;
pub use apart_jobs as jobs;
pub use apart_kernel as kernel;
pub use apart_mesh as mesh;
pub use apart_minkowski as minkowski;
pub use apart_pieces as pieces;
pub use apart_plan as plan;
pub use apart_sphere as sphere;
pub use apart_stack as stack;

pub use apart_plan::partition;
