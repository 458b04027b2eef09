//! Convex Minkowski sums and their central projection onto the sphere of directions.
//!
//! For convex pieces `a` (of a moving part) and `b` (of a fixed part), `a` translated
//! along `d` eventually meets the interior of `b` exactly when the open ray
//! `{k d : k > 0}` meets the interior of `M = b ⊕ (−a)`, i.e. when `d` lies in the
//! interior of the central projection of `M` ([`projection::project`]).
//!
//! ```
//! use apart_kernel::Vec3;
//! use apart_pieces::Polytope;
//! use apart_minkowski::{blocked_polygon, Blocking};
//! let cube = |z: i64| {
//!     let pts: Vec<Vec3> = (0..8).map(|i| Vec3::new(i & 1, i >> 1 & 1, z + (i >> 2))).collect();
//!     Polytope::hull_of_points(&pts).unwrap()
//! };
//! // The upper cube (moving) hits the lower one exactly when it moves downwards.
//! let Blocking::Polygon(q) = blocked_polygon(&cube(1), &cube(0)).unwrap() else { panic!() };
//! assert!(q.contains_open(&Vec3::new(1, -2, -1)));
//! assert!(!q.contains_open(&Vec3::new(1, 0, 0))); // sliding along the shared face is free
//! ```

pub mod projection;
pub mod sum;

pub use projection::{project, Projection};
pub use sum::{minkowski_difference, minkowski_sum, project_apart, sum_prepared, Summand};

use apart_pieces::{Polytope, PolytopeError};
use apart_sphere::polygon::PolygonError;
use apart_sphere::SphericalPolygon;

/// The directions along which a moving convex piece hits a fixed one.
#[derive(Clone, Debug)]
pub enum Blocking {
    /// `moving + k d` meets the interior of `fixed` for some `k > 0` exactly when `d`
    /// lies in the interior of this polygon.
    Polygon(SphericalPolygon),
    /// The pieces' interiors already overlap.
    Overlap,
}

/// Why a blocked polygon could not be computed (an internal inconsistency, reported
/// rather than hidden).
#[derive(Clone, Debug)]
pub enum BlockingError {
    /// The Minkowski sum did not close up.
    Sum(PolytopeError),
    /// The projection did not form a polygon.
    Projection(PolygonError),
}

impl std::fmt::Display for BlockingError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            BlockingError::Sum(e) => write!(f, "Minkowski sum: {e}"),
            BlockingError::Projection(e) => write!(f, "projection: {e}"),
        }
    }
}

impl std::error::Error for BlockingError {}

/// The blocked directions of convex piece `moving` against convex piece `fixed`: the
/// central projection of `fixed ⊕ (−moving)`.
pub fn blocked_polygon(moving: &Polytope, fixed: &Polytope) -> Result<Blocking, BlockingError> {
    let m = minkowski_difference(fixed, moving).map_err(BlockingError::Sum)?;
    match project(&m).map_err(BlockingError::Projection)? {
        Projection::Polygon(p) => Ok(Blocking::Polygon(p)),
        Projection::Everything => Ok(Blocking::Overlap),
    }
}
