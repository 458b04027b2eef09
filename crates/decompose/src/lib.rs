//! Exact convex decomposition of polyhedral solids.
//!
//! A part given as integer points and outward triangles (closed, consistently oriented,
//! not self-intersecting; it may touch itself along edges or at vertices, have any genus
//! and many coplanar triangles) is cut into convex [`Polytope`] pieces whose union is
//! exactly the part and whose interiors are pairwise disjoint. Nothing is approximated:
//! every decision is the sign of an integer polynomial, and every piece vertex is the
//! intersection of three planes through input points (or of the bounding box).
//!
//! Method: a binary space partition of a box around the part (see `partition`), cutting
//! at reflex edges with planes through input points, until the part is convex in each
//! cell; then greedy merging of pieces whose union is convex (see `merge`).
//!
//! A surface that crosses itself (as real CAD tessellations do) is handled by
//! [`decompose_union`]: the convex pieces of its union solid `{w >= 1}`, `w` the winding
//! number, by a partition that goes on until no triangle meets a cell's open interior
//! (see `union`).
//!
//! ```
//! use apart_kernel::Vec3;
//! use apart_decompose::{decompose, verify, Options};
//! // An L-shaped block: the unit cubes (0,0,0), (1,0,0) and (0,1,0), two high in z.
//! let p = |x, y, z| Vec3::new(x, y, z);
//! let pts = vec![
//!     p(0, 0, 0), p(2, 0, 0), p(2, 1, 0), p(1, 1, 0), p(1, 2, 0), p(0, 2, 0),
//!     p(0, 0, 2), p(2, 0, 2), p(2, 1, 2), p(1, 1, 2), p(1, 2, 2), p(0, 2, 2),
//! ];
//! let mut tris = vec![];
//! // Bottom and top as fans around the reflex corner, sides as quads.
//! for i in [0u32, 1, 4, 5] {
//!     tris.push([3, (i + 1) % 6, i]);
//!     tris.push([9, i + 6, (i + 1) % 6 + 6]);
//! }
//! for i in 0..6u32 {
//!     let j = (i + 1) % 6;
//!     tris.push([i, j, j + 6]);
//!     tris.push([i, j + 6, i + 6]);
//! }
//! let d = decompose(&pts, &tris, &Options::default()).unwrap();
//! assert_eq!((d.reflex_edges, d.pieces.len()), (1, 2));
//! verify(&pts, &tris, &d.pieces).unwrap();
//! ```

mod cell;
mod fragments;
mod merge;
mod partition;
mod reflex;
mod solid;
mod split;
mod union;
mod verify;

/// Input coordinates must be below this power of two in magnitude (so that planes
/// through three input points fit `i128`; see [`apart_kernel::plane`]).
pub const MAX_COORD_BITS: u32 = 40;
pub use reflex::reflex_edges;
pub use verify::verify;

use apart_kernel::Vec3;
use apart_pieces::Polytope;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Instant;

/// Settings of [`decompose`].
#[derive(Clone, Debug)]
pub struct Options {
    /// Merge pieces whose union is convex after the partition (default true).
    pub merge: bool,
    /// Process independent cells in parallel with rayon (default true).
    pub parallel: bool,
    /// Raised by another thread to stop [`decompose_union`] early, which then fails
    /// with [`DecomposeError::Stopped`] (default: none).
    pub stop: Option<Arc<AtomicBool>>,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            merge: true,
            parallel: true,
            stop: None,
        }
    }
}

/// Counters and timing of one decomposition.
#[derive(Clone, Debug, Default)]
pub struct Stats {
    /// Cells split by a plane.
    pub splits: usize,
    /// Cells visited (split, leaf, or empty).
    pub cells: usize,
    /// Pieces produced by the partition, before merging.
    pub partition_pieces: usize,
    /// Pairs of pieces merged.
    pub merges: usize,
    /// `floor(log2)` of the largest vertex denominator `W` over the pieces (0 when every
    /// vertex is an integer point); a piece's common denominator can be larger.
    pub max_den_bits: u32,
    /// For [`decompose_union`]: the least winding number in a box around the surface,
    /// exactly (at most 0; below 0 where the surface is partly inside out), and the
    /// greatest one met (at least 1; a cell found to lie entirely in the solid is kept
    /// without looking further, so a larger value may hide there). `None` for
    /// [`decompose`].
    pub winding: Option<(i64, i64)>,
    /// Wall-clock time.
    pub seconds: f64,
}

/// The convex pieces of a solid.
#[derive(Clone, Debug)]
pub struct Decomposition {
    /// Convex pieces with pairwise disjoint interiors whose union is the solid.
    pub pieces: Vec<Polytope>,
    /// Number of reflex edges of the solid (see [`reflex_edges`]).
    pub reflex_edges: usize,
    /// Counters and timing.
    pub stats: Stats,
}

/// Why a mesh cannot be decomposed.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum DecomposeError {
    /// No triangles.
    #[error("the mesh has no triangles")]
    Empty,
    /// A triangle refers to a point that does not exist.
    #[error("triangle {triangle} refers to a missing point")]
    BadIndex {
        /// The triangle.
        triangle: usize,
    },
    /// A coordinate is too large (at least 2^MAX_COORD_BITS in magnitude).
    #[error("point {point} has a coordinate beyond 2^{}", MAX_COORD_BITS)]
    CoordinateTooLarge {
        /// The point.
        point: usize,
    },
    /// A triangle has collinear corners.
    #[error("triangle {triangle} has collinear corners")]
    DegenerateTriangle {
        /// The triangle.
        triangle: usize,
    },
    /// An edge is not used equally often in both directions (open or inconsistently
    /// oriented surface).
    #[error(
        "edge {edge:?} is not used once each way: the surface is open or inconsistently oriented"
    )]
    NotClosed {
        /// The edge's end points.
        edge: [u32; 2],
    },
    /// The triangles around a non-manifold edge do not alternate in orientation, or two
    /// of them coincide.
    #[error("the triangles around edge {edge:?} do not bound a solid")]
    BadNonManifoldEdge {
        /// The edge's end points.
        edge: [u32; 2],
    },
    /// The enclosed volume is not positive (inward orientation or no volume).
    #[error("the enclosed volume is not positive: triangles are oriented inward, or flat")]
    NotPositive,
    /// A failure of the algorithm on input it should handle (a bug: please report).
    #[error("internal error: {0}")]
    Internal(String),
    /// The stop flag of [`Options::stop`] was raised.
    #[error("stopped")]
    Stopped,
}

/// Why a set of pieces is not a decomposition of a solid.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum VerifyError {
    /// The solid itself is invalid.
    #[error("invalid solid: {0}")]
    Input(DecomposeError),
    /// A piece is not a convex full-dimensional polytope.
    #[error("piece {piece} is not convex: {reason}")]
    NotConvex {
        /// The piece.
        piece: usize,
        /// What is wrong.
        reason: String,
    },
    /// Two pieces overlap.
    #[error("pieces {a} and {b} overlap")]
    Overlap {
        /// First piece.
        a: usize,
        /// Second piece.
        b: usize,
    },
    /// The pieces' volumes do not add up to the solid's.
    #[error("the pieces' volumes add up to {found}, the solid's volume is {expected}")]
    VolumeMismatch {
        /// The solid's volume.
        expected: String,
        /// The sum over the pieces.
        found: String,
    },
    /// A triangle of the solid passes through the interior of a piece.
    #[error("triangle {triangle} passes through the interior of piece {piece}")]
    CrossesBoundary {
        /// The piece.
        piece: usize,
        /// The triangle.
        triangle: usize,
    },
    /// A piece lies outside the solid.
    #[error("piece {piece} lies outside the solid")]
    Outside {
        /// The piece.
        piece: usize,
    },
    /// Every ray tried from the piece's interior point was degenerate.
    #[error("could not classify an interior point of piece {piece}")]
    Undecided {
        /// The piece.
        piece: usize,
    },
}

/// Decomposes the closed solid bounded by `triangles` (outward, over `points`) into
/// convex pieces, exactly.
///
/// The mesh is checked for closure, orientation, degenerate triangles, the pairing at
/// non-manifold edges and positive volume, but not for self-intersection (the mesh
/// crate's validation does that); on a self-intersecting mesh the pieces are
/// meaningless, and [`verify`] rejects them.
pub fn decompose(
    points: &[Vec3],
    triangles: &[[u32; 3]],
    opts: &Options,
) -> Result<Decomposition, DecomposeError> {
    let start = Instant::now();
    let solid = solid::Solid::new(points, triangles)?;
    let reflex = solid.edges.iter().filter(|e| e.reflex).count();
    let part = partition::Partition::new(&solid, opts.parallel);
    let cells = part.run()?;
    let partition_pieces = cells.len();
    let (cells, merges) = if opts.merge {
        merge::merge(cells)
    } else {
        (cells, 0)
    };
    let (max_den_bits, pieces) = finish(&cells, opts.parallel)?;
    Ok(Decomposition {
        pieces,
        reflex_edges: reflex,
        stats: Stats {
            splits: part.counters.splits.load(Ordering::Relaxed),
            cells: part.counters.cells.load(Ordering::Relaxed),
            partition_pieces,
            merges,
            max_den_bits,
            winding: None,
            seconds: start.elapsed().as_secs_f64(),
        },
    })
}

/// The largest vertex denominator's bits and the cells as polytopes (in parallel when
/// asked: a tenth of a tessellated part's decomposition).
fn finish(cells: &[cell::Cell], parallel: bool) -> Result<(u32, Vec<Polytope>), DecomposeError> {
    let max_den_bits = cells
        .iter()
        .map(|c| c.max_den_bits().saturating_sub(1))
        .max()
        .unwrap_or(0);
    let pieces = if parallel {
        cells.par_iter().map(|c| c.to_polytope()).collect()
    } else {
        cells
            .iter()
            .map(|c| c.to_polytope())
            .collect::<Result<Vec<_>, _>>()
    }
    .map_err(|e| DecomposeError::Internal(format!("a piece is not a polytope: {e}")))?;
    Ok((max_den_bits, pieces))
}

/// Checks that the leaves of the union partition fill its box exactly (their volumes
/// add up to the box's): a partition that lost a cell would silently drop part of the
/// solid, so it is reported as an internal error instead.
fn check_cover(
    leaves: &[union::Leaf],
    surface: &solid::Solid,
    parallel: bool,
) -> Result<(), DecomposeError> {
    let volume = |l: &union::Leaf| l.cell.to_polytope().map(|p| p.volume());
    let volumes: Vec<_> = if parallel {
        leaves.par_iter().map(volume).collect()
    } else {
        leaves.iter().map(volume).collect()
    };
    let mut total = apart_kernel::Rational::zero();
    for v in volumes {
        let v =
            v.map_err(|e| DecomposeError::Internal(format!("a cell is not a polytope: {e}")))?;
        total = &total + &v;
    }
    let (lo, hi) = union::partition_box(surface);
    let boxed = (0..3).fold(apart_kernel::Int::from(1), |p, k| {
        p * apart_kernel::Int::from(hi[k] - lo[k])
    });
    if total != apart_kernel::Rational::from_int(boxed.clone()) {
        return Err(DecomposeError::Internal(format!(
            "the cells of the winding-number partition fill {total} of their box's volume {boxed}"
        )));
    }
    Ok(())
}

/// Decomposes the union solid of a closed, possibly self-crossing triangle surface into
/// convex pieces, exactly: the pieces have pairwise disjoint interiors and their union is
/// the closure of `{x : w(x) >= 1}`, `w` the winding number of the surface.
///
/// Accepted: any triangles over points with coordinates below `2^MAX_COORD_BITS` such that
/// every edge (pair of point indices) is used equally often in both directions. The
/// triangles may cross, overlap, coincide or touch; shells may nest or be repeated
/// (`w >= 2` is inside); triangles with collinear corners count for closure only (a
/// corner repeated in a triangle makes no edge); regions of negative winding (inside-out
/// parts, e.g. a dent pushed through the opposite face) are outside, like `w = 0`, and
/// show in [`Stats::winding`]. Rejected: no
/// triangles, bad indices, too large coordinates, an edge not used equally often both
/// ways ([`DecomposeError::NotClosed`]), and an empty union
/// ([`DecomposeError::NotPositive`]). `reflex_edges` is 0: the union's edges are not
/// input edges. On a valid solid the result is the same solid as [`decompose`]'s, usually
/// in as many pieces, in 1 to 2 times the time.
///
/// Method (see `union`): a binary space partition by planes through input points (first
/// through reflex and non-manifold elements, as [`decompose`] cuts, then the triangles'
/// own planes) until no triangle meets a cell's open interior, each such cell kept when
/// the exact winding number of an interior point is at least 1 (a cell still crossed by
/// triangles is kept whole when an exact bound shows `w >= 1` all over it); then the
/// same merging as [`decompose`].
pub fn decompose_union(
    points: &[Vec3],
    triangles: &[[u32; 3]],
    opts: &Options,
) -> Result<Decomposition, DecomposeError> {
    let start = Instant::now();
    let surface = solid::Solid::surface(points, triangles)?;
    let part = union::UnionPartition::new(&surface, opts.parallel, opts.stop.clone());
    let leaves = part.run()?;
    check_cover(&leaves, &surface, opts.parallel)?;
    let lo = leaves.iter().map(|l| l.w).min().unwrap_or(0);
    let hi = leaves.iter().map(|l| l.w).max().unwrap_or(0);
    let cells: Vec<cell::Cell> = leaves
        .into_iter()
        .filter(|l| l.w >= 1)
        .map(|l| l.cell)
        .collect();
    if cells.is_empty() {
        return Err(DecomposeError::NotPositive);
    }
    let partition_pieces = cells.len();
    let (cells, merges) = if opts.merge {
        merge::merge(cells)
    } else {
        (cells, 0)
    };
    let (max_den_bits, pieces) = finish(&cells, opts.parallel)?;
    Ok(Decomposition {
        pieces,
        reflex_edges: 0,
        stats: Stats {
            splits: part.counters.splits.load(Ordering::Relaxed),
            cells: part.counters.cells.load(Ordering::Relaxed),
            partition_pieces,
            merges,
            max_den_bits,
            winding: Some((lo, hi)),
            seconds: start.elapsed().as_secs_f64(),
        },
    })
}
