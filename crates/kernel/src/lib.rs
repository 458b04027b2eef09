//! The exact kernel of apart.
//!
//! Inputs are snapped once to an integer [`Grid`]; from then on every combinatorial
//! decision in apart is the sign of a polynomial in integers, computed by a predicate of
//! this crate. Nothing here knows about meshes, parts or assemblies.
//!
//! - [`Vec3`]: exact integer vectors (machine integers below 2^62, arbitrary precision
//!   above), used for grid points, direction vectors and great-circle normals.
//! - [`predicates`]: filtered exact signs of dot products and 3x3 determinants.
//! - [`spherical`]: the sphere-of-directions predicates built on them (side of a great
//!   circle, intersection of two circles, position along an arc, order around a vertex).
//! - [`orient`]: orientation of grid points (`[i64; 3]`) and of exact points against
//!   grid triangles.
//! - [`plane`]: exact planes and half-spaces ([`Plane`], [`BigPlane`]) and the
//!   homogeneous points where they meet ([`HPoint`]), with their float filter.
//! - [`Rational`]: exact fractions (on machine words while they fit) for volumes,
//!   reported points and placement, and [`rational`]'s helpers on rational vectors.
//! - [`Aabb`] and [`bvh`]: axis-aligned boxes (exact on the grid or with rational
//!   corners, or floats for filters and pictures) and the broad phase over them (a
//!   hierarchy, or sort and sweep).
//! - [`fvec`]: float vectors, for pictures, measurements and the shadows of float
//!   filters (no float decides anything).
//! - [`progress`]: progress reports and a stop flag shared by the long planners.
//! - [`budget`]: the memory budget's counting allocator, shared by the command line
//!   and the Python extension (this crate's only unsafe code).
//!
//! ```
//! use apart_kernel::{Vec3, Sign, predicates::det3_sign, spherical::circle_intersection};
//! let (a, b) = (Vec3::new(1, 1, 1), Vec3::new(1, -1, 1));
//! let n = a.cross(&b); // the great circle through a and b
//! assert_eq!(det3_sign(&n, &a, &b), Sign::Positive);
//! let p = circle_intersection(&n, &Vec3::new(0, 0, 1)).unwrap();
//! assert_eq!(p.primitive(), p);
//! ```

pub mod aabb;
pub mod budget;
pub mod bvh;
pub mod fvec;
pub mod grid;
pub mod int;
pub mod orient;
pub mod plane;
pub mod predicates;
pub mod progress;
pub mod rational;
mod sign;
pub mod spherical;
mod vec3;
mod wide;

pub use aabb::Aabb;
pub use bvh::Bvh;
pub use grid::{Grid, GridError};
pub use int::Int;
pub use plane::{BigPlane, HPoint, Plane};
pub use rational::Rational;
pub use sign::Sign;
pub use vec3::{Components, Vec3, SMALL_BITS};
