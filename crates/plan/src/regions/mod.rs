//! Blocked regions of pairs of parts, computed once and shared by every planner.
//!
//! For parts `i < j`, `Q_ij` is the open set of directions along which `i`, moving, hits
//! the interior of `j`: the union of the open central projections of
//! `b ⊕ (−a)` over pieces `a` of `i` and `b` of `j`. `Q_ji = −Q_ij`. Each union is
//! simplified to the arcs and points where the blocked status changes before any
//! overlay of several pairs.

mod pair;
mod prune;
mod union;

pub use union::union_of;

pub(crate) use prune::{cap_of, prune_contained};
pub(crate) use union::union_of_pruned;

use crate::cull::piece_tree;
use crate::pairs::PieceInfo;
use crate::progress::{phases, Progress};
use crate::PlanError;
use apart_kernel::{Bvh, Vec3};
use apart_pieces::Polytope;
use apart_sphere::region::RegionMap;
use apart_sphere::SphericalPolygon;
use pair::pair_region;
use rayon::prelude::*;
use std::time::Instant;

pub use apart_assembly::Part;

/// The parts of an assembly, checked to have convex pieces, as the loader gave them
/// (declared pieces, the part itself when convex, or its exact convex decomposition:
/// the planners never decompose, and take the assembly's parts as they are, their
/// `name` and `pieces`). [`PlanError::NoPieces`] for a part without pieces, as an
/// assembly built by hand rather than by `apart_assembly::load` may have.
pub fn parts_of(assembly: &apart_assembly::Assembly) -> Result<&[Part], PlanError> {
    if let Some((k, p)) = assembly
        .parts
        .iter()
        .enumerate()
        .find(|(_, p)| p.pieces.is_empty())
    {
        return Err(PlanError::NoPieces {
            part: k,
            name: p.name.clone(),
        });
    }
    Ok(&assembly.parts)
}

/// The blocked region of one unordered pair of parts.
#[derive(Clone, Debug)]
pub struct PairRegion {
    /// The moving part (smaller index).
    pub i: usize,
    /// The fixed part.
    pub j: usize,
    /// The open polygons of the piece pairs, less those inside another (they add no
    /// direction): `i` moving along `d` hits `j` iff `d` lies in the interior of at
    /// least one.
    pub polygons: Vec<SphericalPolygon>,
    /// Their union, simplified.
    pub region: RegionMap,
    /// The parts touch (some piece pair's sum has the origin on its boundary).
    pub contact: bool,
}

impl PairRegion {
    /// Exactly: does `i` moving along `d` hit `j`?
    pub fn blocks(&self, d: &Vec3) -> bool {
        self.polygons.iter().any(|p| p.contains_open(d))
    }

    /// Exactly: does `i` moving along `x + εy` hit `j`, for every small enough `ε > 0`?
    pub fn blocks_perturbed(&self, x: &Vec3, y: &Vec3) -> bool {
        self.polygons
            .iter()
            .any(|p| p.contains_open_perturbed(x, y))
    }
}

/// Timings and sizes of the region computation.
#[derive(Clone, Copy, Debug, Default)]
pub struct RegionStats {
    /// Convex pieces in the assembly.
    pub pieces: usize,
    /// Full Minkowski sums computed.
    pub sums: usize,
    /// Touching piece pairs whose projection came from the small sum of their face
    /// neighbourhoods (their contact cone).
    pub contact_cones: usize,
    /// Piece pairs skipped: their projection lies in an open hemisphere already in the
    /// pair's union (a face contact's), so it changes nothing.
    pub skipped: usize,
    /// Piece pairs not summed because a group of them (under two nodes of the parts'
    /// piece trees) projects inside the union of the contact cones and of the largest
    /// pieces' sums ([`crate::cull`]).
    pub culled: usize,
    /// Arcs in the simplified pair regions.
    pub region_arcs: usize,
    /// Seconds spent on Minkowski sums, and on the projections of pieces apart (made
    /// from the facets facing the origin, without a sum: `project_apart`).
    pub sums_seconds: f64,
    /// Seconds spent on central projections of whole sums.
    pub projection_seconds: f64,
    /// Seconds spent on per-pair unions.
    pub unions_seconds: f64,
}

/// What computing a pair's region needs of one part: its pieces' data for the exact
/// culls and its box tree over its pieces.
pub(crate) struct PartData {
    pub(crate) info: Vec<PieceInfo>,
    pub(crate) tree: Option<Bvh>,
}

impl PartData {
    pub(crate) fn new(p: &Part) -> PartData {
        PartData {
            info: p.pieces.iter().map(PieceInfo::new).collect(),
            tree: piece_tree(&p.pieces),
        }
    }
}

/// Piece pairs whose data may be alive at once (see [`BlockingRegions::compute`]).
const PAIR_BATCH: usize = 1 << 16;

impl RegionStats {
    /// Adds the counts of another computation, and its times scaled by `scale`.
    pub(crate) fn add(&mut self, o: &RegionStats, scale: f64) {
        self.sums += o.sums;
        self.contact_cones += o.contact_cones;
        self.skipped += o.skipped;
        self.culled += o.culled;
        self.sums_seconds += o.sums_seconds * scale;
        self.projection_seconds += o.projection_seconds * scale;
        self.unions_seconds += o.unions_seconds * scale;
    }

    /// The time of the three phases.
    fn seconds(&self) -> f64 {
        self.sums_seconds + self.projection_seconds + self.unions_seconds
    }
}

/// The blocked regions of every pair of parts.
#[derive(Clone, Debug)]
pub struct BlockingRegions {
    names: Vec<String>,
    pieces: Vec<Vec<Polytope>>,
    pairs: Vec<PairRegion>,
    index: Vec<usize>,
    /// Timings and sizes.
    pub stats: RegionStats,
}

impl BlockingRegions {
    /// Computes the regions of all pairs (Minkowski sums, projections and unions run in
    /// parallel over piece pairs and pairs of parts).
    ///
    /// Every piece pair's exact separating axes are found first ([`crate::pairs`]).
    /// Touching pairs get their projection, the contact cone, from the small sum of their
    /// face neighbourhoods. A pair lying weakly below along an axis `n` has its projection
    /// in `{n·x >= 0}`; when a face contact of the same two parts already put the open
    /// hemisphere `{n·x > 0}` in the union, the pair changes neither the union nor any
    /// blocking answer (its open polygon lies in that hemisphere), so it is not summed.
    /// The remaining pairs are summed in full.
    pub fn compute(parts: &[Part]) -> Result<BlockingRegions, PlanError> {
        BlockingRegions::compute_with(parts, &Progress::new())
    }

    /// [`BlockingRegions::compute`], reporting the pairs of parts done of all pairs
    /// ([`phases::PAIR_REGIONS`]) and watching the stop flag: between batches of pairs,
    /// before each pair, and between the culling rounds and sum chunks of a pair with
    /// many piece pairs. Stopped, it returns [`PlanError::Stopped`] (regions of only
    /// some pairs would answer no question correctly).
    pub fn compute_with(parts: &[Part], progress: &Progress) -> Result<BlockingRegions, PlanError> {
        let n = parts.len();
        for (k, p) in parts.iter().enumerate() {
            if p.pieces.is_empty() {
                return Err(PlanError::NoPieces {
                    part: k,
                    name: p.name.clone(),
                });
            }
        }
        let pairs: Vec<(usize, usize)> = (0..n)
            .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
            .collect();
        let mut stats = RegionStats {
            pieces: parts.iter().map(|p| p.pieces.len()).sum(),
            ..Default::default()
        };
        let data: Vec<PartData> = parts.par_iter().map(PartData::new).collect();
        let mut regions = Vec::with_capacity(pairs.len());
        let counter = progress.counter(phases::PAIR_REGIONS, pairs.len());
        regions_in_batches(
            parts,
            &|k| &data[k],
            &pairs,
            progress,
            &|| counter.add(1),
            &mut |r, s, scale| {
                stats.add(s, scale);
                regions.push(r);
            },
        )?;
        stats.region_arcs = regions.iter().map(|r| r.region.arcs.len()).sum();
        let mut index = vec![usize::MAX; n * n];
        for (k, r) in regions.iter().enumerate() {
            index[r.i * n + r.j] = k;
        }
        Ok(BlockingRegions {
            names: parts.iter().map(|p| p.name.clone()).collect(),
            pieces: parts.iter().map(|p| p.pieces.clone()).collect(),
            pairs: regions,
            index,
            stats,
        })
    }

    /// Regions of the parts `names` (with their `pieces`) from the regions of every
    /// unordered pair `(i, j)`, `i < j`, in local indices, in any order.
    pub(crate) fn from_pairs(
        names: Vec<String>,
        pieces: Vec<Vec<Polytope>>,
        mut pairs: Vec<PairRegion>,
        stats: RegionStats,
    ) -> BlockingRegions {
        let n = names.len();
        pairs.sort_by_key(|r| (r.i, r.j));
        let mut index = vec![usize::MAX; n * n];
        for (k, r) in pairs.iter().enumerate() {
            index[r.i * n + r.j] = k;
        }
        BlockingRegions {
            names,
            pieces,
            pairs,
            index,
            stats,
        }
    }

    /// Number of parts.
    pub fn part_count(&self) -> usize {
        self.names.len()
    }

    /// Part names.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The convex pieces of part `k`.
    pub fn pieces(&self, k: usize) -> &[Polytope] {
        &self.pieces[k]
    }

    /// All pair regions.
    pub fn pairs(&self) -> &[PairRegion] {
        &self.pairs
    }

    /// The region of the unordered pair `{i, j}` (stored as `Q_min,max`).
    pub fn pair(&self, i: usize, j: usize) -> &PairRegion {
        let (a, b) = (i.min(j), i.max(j));
        &self.pairs[self.index[a * self.names.len() + b]]
    }

    /// True when parts `i` and `j` touch.
    pub fn touch(&self, i: usize, j: usize) -> bool {
        i != j && self.pair(i, j).contact
    }

    /// Exactly: does part `i` moving along `d` hit part `j`?
    pub fn blocks(&self, i: usize, j: usize, d: &Vec3) -> bool {
        let r = self.pair(i, j);
        if i < j {
            r.blocks(d)
        } else {
            r.blocks(&d.neg())
        }
    }
}

/// Makes the regions of the unordered pairs `pairs` (`i < j`), `data(k)` giving part
/// `k`'s data, in batches of at most [`PAIR_BATCH`] piece pairs (a bigger pair alone),
/// each batch's pairs in parallel: only a batch's piece-pair data is alive at once, and
/// what is kept is each pair's pruned polygons and union. Each region goes to
/// `keep(region, stats, scale)` (the pairs of a batch ran side by side: their phase
/// times are shares of the batch's, `scale` times theirs), in the order of `pairs`,
/// and `done()` is called as each pair is made. The stop flag is watched between
/// batches and pairs: stopped, nothing of the unfinished batch is kept.
pub(crate) fn regions_in_batches<'d>(
    parts: &[Part],
    data: &(dyn Fn(usize) -> &'d PartData + Sync),
    pairs: &[(usize, usize)],
    progress: &Progress,
    done: &(dyn Fn() + Sync),
    keep: &mut dyn FnMut(PairRegion, &RegionStats, f64),
) -> Result<(), PlanError> {
    let stopped = || PlanError::Stopped {
        phase: phases::PAIR_REGIONS,
    };
    let mut rest = pairs;
    while !rest.is_empty() {
        if progress.stopped() {
            return Err(stopped());
        }
        let mut take = 0;
        let mut load = 0;
        while take < rest.len() {
            let (i, j) = rest[take];
            let jobs = parts[i].pieces.len() * parts[j].pieces.len();
            if take > 0 && load + jobs > PAIR_BATCH {
                break;
            }
            load += jobs;
            take += 1;
        }
        let (batch, tail) = rest.split_at(take);
        rest = tail;
        let t = Instant::now();
        let made: Vec<(PairRegion, RegionStats)> = batch
            .par_iter()
            .map(|&(i, j)| {
                if progress.stopped() {
                    return Err(stopped());
                }
                let mut s = RegionStats::default();
                let r = pair_region(parts, (data(i), data(j)), i, j, &mut s, progress);
                done();
                r.map(|r| (r, s))
            })
            .collect::<Result<_, _>>()?;
        let wall = t.elapsed().as_secs_f64();
        let busy: f64 = made.iter().map(|(_, s)| s.seconds()).sum();
        let scale = if busy > wall { wall / busy } else { 1.0 };
        for (r, s) in made {
            keep(r, &s, scale);
        }
    }
    Ok(())
}
