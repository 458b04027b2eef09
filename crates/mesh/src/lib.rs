//! The solid model of apart: snapping to the integer grid, welding, triangulating,
//! repairing and validating one closed solid, exactly, and locating points in it.
//!
//! The flow for one object starts from the floating-point
//! [`RawObject`](apart_formats::RawObject)s that apart-formats reads
//! ([`apart_formats::read_file`]), then [`Mesh::from_raw`] (snap with the assembly's
//! [`apart_kernel::Grid`], weld equal grid points, triangulate polygons), optionally
//! [`repair::repair`] (exact repair of export defects: T-junctions, duplicate faces,
//! small holes, shell orientation; then [`repair::bodies`] splits several solids
//! apart), then [`validate::validate`] (closed, oriented, manifold up to valid
//! self-contacts, not self-intersecting, positive volume; convex or not). Every
//! decision after snapping is an exact integer predicate. Problems are values
//! ([`Problem`]) that name the element; nothing here panics on bad input.
//!
//! ```
//! use apart_formats::{read_bytes, Format};
//! use apart_kernel::Grid;
//! use apart_mesh::validate::check_solid;
//! let off = b"OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";
//! let objects = read_bytes(off, Format::Off, None).unwrap();
//! let grid = Grid::choose(objects[0].vertices.iter().flatten().copied(), 30).unwrap();
//! let (mesh, info, problems) = check_solid(&objects[0], &grid);
//! assert!(problems.is_empty());
//! let info = info.unwrap();
//! assert!(info.convex);
//! assert_eq!(info.volume_units(&grid).unwrap().to_string(), "1/6");
//! assert_eq!(mesh.unwrap().triangles.len(), 4);
//! ```

pub mod intersect;
pub mod locate;
mod mesh;
mod problem;
pub mod repair;
#[cfg(test)]
mod test_shapes;
mod triangulate;
pub mod validate;
mod weld;

pub use mesh::{fmt_point, Mesh};
pub use problem::{optional_path_text, path_text, path_texts, Problem, ProblemKind, Severity};
