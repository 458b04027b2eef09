//! Convex pieces of parts: exact convex polytopes and their interference.
//!
//! A part of an assembly is a union of convex pieces with pairwise disjoint interiors.
//! A [`Polytope`] has integer (grid) vertices and facet planes with primitive integer
//! normals, so every test on it is exact. This crate knows nothing about files or
//! assemblies: it receives points and triangles.
//!
//! ```
//! use apart_kernel::Vec3;
//! use apart_pieces::{Polytope, interference::interiors_disjoint};
//! let cube = |o: i64| {
//!     let pts: Vec<Vec3> = (0..8)
//!         .map(|i| Vec3::new(o + (i & 1) * 2, (i >> 1 & 1) * 2, (i >> 2) * 2))
//!         .collect();
//!     Polytope::hull_of_points(&pts).unwrap()
//! };
//! assert_eq!(cube(0).facets().len(), 6);
//! assert!(interiors_disjoint(&cube(0), &cube(2))); // they share a face
//! assert!(!interiors_disjoint(&cube(0), &cube(1)));
//! ```

mod climb;
pub mod hull2d;
pub mod hull3d;
pub mod interference;
pub mod polytope;
pub mod shrink;

pub use polytope::{Containment, Edge, Facet, Polytope, PolytopeError, Shadow};
