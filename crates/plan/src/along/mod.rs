//! One direction without the motion-space arrangement, and a quick first solution.
//!
//! [`dbg_along`] answers what `partition --direction` asks: the exact blocking graph at
//! `d`, its minimal moving sets, and the kind of motion-space cell `d` lies in, from
//! per-piece-pair tests only ([`crate::pairs`]): exact separating axes decide most pairs,
//! touching pairs get their contact cone from a small sum of face neighbourhoods, and
//! only the remaining pairs are summed in full, stopping for an ordered pair of parts as
//! soon as one piece pair blocks it. Only pairs of parts whose box of sums the line
//! along `±d` meets are looked at, found in a hierarchy of the parts' boxes, so a query
//! costs what the parts near that line cost, not the square of the part count.
//!
//! The cell kind is local: near `d`, a pair's blocked set is everything when `d` is
//! blocked, and otherwise the union of the piece pairs' polygons whose closure contains
//! `d` (the others lie at a positive distance). So the motion space near `d` is the
//! arrangement of those polygons' sides through `d`, and their tangent cones at `d`
//! decide whether `d` lies in a vertex, an edge or a face of it.

mod blocking;
mod broad;
mod cache;
mod candidates;
mod cell;
mod clearance_search;
mod cover;
mod first;
#[cfg(test)]
mod tests;
mod tolerance;

pub use first::partition_first;
pub use tolerance::{holds_without_tolerance, Motion};

use crate::cull::piece_tree;
use crate::dbg::Dbg;
use crate::motion_space::CellKind;
use crate::pairs::{is_axis_box, PieceInfo};
use crate::regions::Part;
use crate::PlanError;
use apart_kernel::{Aabb, Bvh, Vec3};
use cache::PairCaches;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The exact answer at one direction.
#[derive(Clone, Debug)]
pub struct DirectionAnswer {
    /// The direction (primitive).
    pub direction: Vec3,
    /// The kind of motion-space cell it lies in (as [`crate::MotionSpace::locate`] says).
    pub cell: CellKind,
    /// The directional blocking graph: over global part indices from
    /// [`DirectionQuery::answer`], over positions in the subassembly from
    /// [`DirectionQuery::answer_in`].
    pub dbg: Dbg,
    /// Its minimal moving sets (global part indices).
    pub moving: Vec<Vec<usize>>,
}

/// Work counters of a [`DirectionQuery`].
#[derive(Clone, Copy, Debug, Default)]
pub struct QueryStats {
    /// Piece pairs of different parts.
    pub piece_pairs: usize,
    /// Pairs whose separating axes were computed (the box test did not decide).
    pub axes: usize,
    /// Contact cones from face neighbourhoods.
    pub contact_cones: usize,
    /// Full Minkowski sums.
    pub sums: usize,
}

/// The exact integer box of a part's pieces (a rational vertex's coordinates rounded
/// outward), or `None` when a bound exceeds 2^60 in magnitude.
fn exact_box(p: &Part) -> Option<Aabb> {
    p.pieces
        .iter()
        .try_fold(Aabb::EMPTY, |b, q| Some(b.union(&q.integer_box()?)))
}

/// A box holding every point of the grid that a part without integer piece boxes may
/// reach: the box of its sum with any other part's box holds the origin, so it meets
/// every ray (piece boxes stay below 2^60 + 3, sums below 2^62).
const EVERYWHERE: Aabb = Aabb {
    min: [-(1 << 61); 3],
    max: [1 << 61; 3],
};

/// Per-direction queries on an assembly's convex pieces, caching every piece pair's
/// separating axes and projection between queries.
pub struct DirectionQuery<'a> {
    parts: &'a [Part],
    info: Vec<Vec<PieceInfo>>,
    /// Which pieces are axis-aligned boxes (a pair of them blocks a direction exactly
    /// when the open ray meets their open box of differences: no polygon needed).
    boxy: Vec<Vec<bool>>,
    /// Each part's box tree over its pieces (`None` when its coordinates are too large
    /// for integer boxes: then every piece pair is visited).
    trees: Vec<Option<Bvh>>,
    /// Each part's box, exact (rounded outward where a cut piece has rational vertices;
    /// [`EVERYWHERE`] without a tree): a pair of parts whose box of sums a ray misses
    /// has no piece pair whose closed projection holds its direction.
    boxes: Vec<Aabb>,
    /// Each part's tree's root box (its piece boxes widened; [`EVERYWHERE`] without a
    /// tree): what the piece trees' walks test first, for the touching pairs and the
    /// clearance search, which follow those walks.
    reach: Vec<Aabb>,
    /// The hierarchy over `reach` (holding `boxes`): the broad phase over parts.
    part_tree: Bvh,
    /// The piece-pair caches of the part pairs asked for so far.
    cache: PairCaches,
    n_axes: AtomicUsize,
    n_cones: AtomicUsize,
    n_sums: AtomicUsize,
}

impl<'a> DirectionQuery<'a> {
    /// Prepares the pieces (bounds and box trees only; everything else on demand).
    pub fn new(parts: &'a [Part]) -> Result<DirectionQuery<'a>, PlanError> {
        for (k, p) in parts.iter().enumerate() {
            if p.pieces.is_empty() {
                return Err(PlanError::NoPieces {
                    part: k,
                    name: p.name.clone(),
                });
            }
        }
        let info = parts
            .par_iter()
            .map(|p| p.pieces.iter().map(PieceInfo::new).collect())
            .collect();
        let boxy = parts
            .par_iter()
            .map(|p| p.pieces.iter().map(is_axis_box).collect())
            .collect();
        let trees: Vec<Option<Bvh>> = parts.par_iter().map(|p| piece_tree(&p.pieces)).collect();
        let reach: Vec<Aabb> = trees
            .iter()
            .map(|t| {
                t.as_ref()
                    .and_then(|t| t.root().map(|r| *t.node_box(r)))
                    .unwrap_or(EVERYWHERE)
            })
            .collect();
        let boxes = parts
            .par_iter()
            .zip(&trees)
            .map(|(p, t)| t.as_ref().and_then(|_| exact_box(p)).unwrap_or(EVERYWHERE))
            .collect();
        let part_tree = Bvh::new(reach.clone());
        Ok(DirectionQuery {
            parts,
            info,
            boxy,
            trees,
            boxes,
            reach,
            part_tree,
            cache: PairCaches::new(),
            n_axes: AtomicUsize::new(0),
            n_cones: AtomicUsize::new(0),
            n_sums: AtomicUsize::new(0),
        })
    }

    /// Work done so far.
    pub fn stats(&self) -> QueryStats {
        // Pairs of pieces of different parts: (Σ p)² − Σ p², halved.
        let (sum, squares) = self.parts.iter().fold((0usize, 0usize), |(s, q), p| {
            let k = p.pieces.len();
            (s + k, q + k * k)
        });
        QueryStats {
            piece_pairs: (sum * sum - squares) / 2,
            axes: self.n_axes.load(Ordering::Relaxed),
            contact_cones: self.n_cones.load(Ordering::Relaxed),
            sums: self.n_sums.load(Ordering::Relaxed),
        }
    }
}

/// The exact blocking graph, minimal moving sets and cell kind at `d`, from per-piece-
/// pair tests only (no arrangement of the whole motion space).
pub fn dbg_along(parts: &[Part], d: &Vec3) -> Result<DirectionAnswer, PlanError> {
    DirectionQuery::new(parts)?.answer(d)
}
