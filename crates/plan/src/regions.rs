//! Blocked regions of pairs of parts, computed once and shared by every planner.
//!
//! For parts `i < j`, `Q_ij` is the open set of directions along which `i`, moving, hits
//! the interior of `j`: the union of the open central projections of
//! `b ⊕ (−a)` over pieces `a` of `i` and `b` of `j`. `Q_ji = −Q_ij`. Each union is
//! simplified to the arcs and points where the blocked status changes before any
//! overlay of several pairs.

use crate::cull::{largest, piece_tree, uncovered_pairs, Cover};
use crate::pairs::{axes, below_along_any, contact_polygon, Axis, PairPolygon, PieceInfo};
use crate::progress::{phases, Progress};
use crate::PlanError;
use apart_kernel::fvec::dot;
use apart_kernel::{Bvh, Vec3};
use apart_minkowski::{project, project_apart, sum_prepared, Projection};
use apart_pieces::Polytope;
use apart_sphere::overlay::{cell_statuses, PointStatus, SideLabel};
use apart_sphere::region::{region_inputs, simplify_union, RegionMap, Sides};
use apart_sphere::{Arrangement, BitSet, InputArc, InputPoint, SphericalPolygon};
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

/// A touching piece pair's contact cone, and whether the pieces touch.
type Cone = (SphericalPolygon, bool);

/// Piece pairs to sum in a part pair from which on groups of them are culled. Low: a
/// part of few large pieces (a bolt's 600-sided shaft) against one of many makes few
/// pairs but costly sums and polygons (bolt and nut of the 50k joint: 2,708 pairs summed
/// in 66 s and 2.3 GB without culling, 1,376 in 18 s and 333 MB with it).
const CULL_MIN: usize = 1 << 8;

/// Piece pairs summed per culling round at most.
const CULL_ROUND: usize = 1 << 10;

/// The largest pieces of each part whose pairwise sums seed the culling union.
const CULL_SEEDS_PER_PART: usize = 8;

/// Full sums whose polygons are made before those inside another are dropped.
const PRUNE_CHUNK: usize = 1 << 14;

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

/// The region of parts `i < j`: separating axes of every piece pair, contact cones of
/// touching ones, full sums for the rest except those a face contact's hemisphere
/// already covers, then the pruned polygons' union (timings added to `stats`). The stop
/// flag is checked between culling rounds and between chunks of sums.
pub(crate) fn pair_region(
    parts: &[Part],
    (di, dj): (&PartData, &PartData),
    i: usize,
    j: usize,
    stats: &mut RegionStats,
    progress: &Progress,
) -> Result<PairRegion, PlanError> {
    let stopped = || PlanError::Stopped {
        phase: phases::PAIR_REGIONS,
    };
    let (pi, pj) = (&parts[i].pieces, &parts[j].pieces);
    let jobs: Vec<(usize, usize)> = (0..pi.len())
        .flat_map(|a| (0..pj.len()).map(move |b| (a, b)))
        .collect();
    let t = Instant::now();
    let name_err = |e: String| {
        PlanError::Internal(format!(
            "pieces of {} and {}: {e}",
            parts[i].name, parts[j].name
        ))
    };
    let overlap = |a: usize, b: usize| PlanError::Overlap {
        parts: (i, j),
        names: (parts[i].name.clone(), parts[j].name.clone()),
        pieces: (a, b),
    };
    // Separating axes of every piece pair (exact; coordinate axes first, which settle
    // far-apart pairs at once). Touching pairs get their projection, the contact cone,
    // from the small sum of their face neighbourhoods (the same polygon as the full
    // sum's); the others near each other keep their axes for the cover test below, and
    // pairs strictly apart along a coordinate axis keep nothing (their axes are those
    // coordinate axes, found again in a moment if the test needs them): most of a big
    // pair's 10^6 piece pairs are such, and their axes were most of its memory.
    enum First {
        Near(Vec<Axis>),
        Cone(Cone),
    }
    let first: Vec<(usize, First)> = (0..jobs.len())
        .into_par_iter()
        .with_min_len(16)
        .filter_map(|k| {
            let (a, b) = jobs[k];
            let ax = axes(&pi[a], &di.info[a], &pj[b], &dj.info[b]);
            let Some(n) = crate::pairs::touching_normal(&ax) else {
                return (!ax.iter().any(|x| x.strict)).then_some(Ok((k, First::Near(ax))));
            };
            match contact_polygon(&pi[a], &di.info[a], &pj[b], &dj.info[b], n) {
                None => Some(Ok((k, First::Near(ax)))),
                Some(Ok(PairPolygon::Polygon(p, touch))) => Some(Ok((k, First::Cone((p, touch))))),
                Some(Ok(PairPolygon::Overlap)) => Some(Err(overlap(a, b))),
                Some(Err(e)) => Some(Err(name_err(e))),
            }
        })
        .collect::<Result<_, _>>()?;
    let mut is_cone = vec![false; jobs.len()];
    let mut cones: Vec<Cone> = Vec::new();
    let mut near: rustc_hash::FxHashMap<usize, Vec<Axis>> = Default::default();
    for (k, f) in first {
        match f {
            First::Cone(c) => {
                is_cone[k] = true;
                cones.push(c);
            }
            First::Near(ax) => {
                near.insert(k, ax);
            }
        }
    }
    let cone_count = cones.len();
    stats.contact_cones += cone_count;
    // Open hemispheres already in the union (face contacts).
    let mut hemispheres: rustc_hash::FxHashSet<Vec3> = Default::default();
    for (p, _) in &cones {
        if p.normals().len() == 1 {
            hemispheres.insert(p.normals()[0].clone());
        }
    }
    // A pair lying weakly below along an axis n has its projection in the closed
    // hemisphere {n·x >= 0}: it adds nothing when the open one is in the union.
    let covered = |k: usize| {
        if hemispheres.is_empty() {
            return false;
        }
        let (a, b) = jobs[k];
        let in_union = |ax: &[Axis]| ax.iter().any(|ax| hemispheres.contains(&ax.n.primitive()));
        let by_axes = match near.get(&k) {
            Some(ax) => in_union(ax),
            None => in_union(&axes(&pi[a], &di.info[a], &pj[b], &dj.info[b])),
        };
        by_axes || below_along_any(&pi[a], &pj[b], &hemispheres)
    };
    let axes_seconds = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let cpu = |t: Instant| t.elapsed().as_nanos() as u64;
    let sum_ns = std::sync::atomic::AtomicU64::new(0);
    let proj_ns = std::sync::atomic::AtomicU64::new(0);
    let todo: Vec<usize> = (0..jobs.len())
        .into_par_iter()
        .with_min_len(64)
        .filter(|&k| !is_cone[k] && !covered(k))
        .collect();
    drop(near);
    stats.skipped += jobs.len() - todo.len() - cone_count;
    let polygon_of = |k: usize| -> Result<Cone, PlanError> {
        let (a, b) = jobs[k];
        let t0 = Instant::now();
        let (sb, sa) = (dj.info[b].fixed(&pj[b]), di.info[a].reflected(&pi[a]));
        // Apart: the projection from the facets facing the origin, without the sum.
        if let Some(p) = project_apart(sb, sa) {
            sum_ns.fetch_add(cpu(t0), std::sync::atomic::Ordering::Relaxed);
            return p.map(|p| (p, false)).map_err(|e| {
                PlanError::Internal(format!(
                    "projection for {} and {}: {e}",
                    parts[i].name, parts[j].name
                ))
            });
        }
        let m = sum_prepared(sb, sa).map_err(|e| {
            PlanError::Internal(format!(
                "Minkowski sum of {} and {}: {e}",
                parts[i].name, parts[j].name
            ))
        })?;
        sum_ns.fetch_add(cpu(t0), std::sync::atomic::Ordering::Relaxed);
        let t1 = Instant::now();
        let out = match project(&m) {
            Ok(Projection::Polygon(p)) => {
                // Touching: no facet has the origin strictly outside.
                let contact = m
                    .facets()
                    .iter()
                    .all(|f| f.offset >= apart_kernel::Int::ZERO);
                Ok((p, contact))
            }
            Ok(Projection::Everything) => Err(overlap(a, b)),
            Err(e) => Err(PlanError::Internal(format!(
                "projection for {} and {}: {e}",
                parts[i].name, parts[j].name
            ))),
        };
        proj_ns.fetch_add(cpu(t1), std::sync::atomic::Ordering::Relaxed);
        out
    };
    // The contact cones, then the full sums' polygons a chunk at a time, each chunk
    // pruned of polygons inside another before the next is made (memory: a polygon
    // inside another of its chunk lies inside a kept one, so pruning by chunks and then
    // all the kept ones together keeps the same union).
    let mut contact = false;
    let mut polygons: Vec<SphericalPolygon> = cones
        .into_iter()
        .map(|(p, touch)| {
            contact |= touch;
            p
        })
        .collect();
    // Many pairs: the largest pieces' sums first, then rounds of the groups of pairs
    // whose bounding projection is not inside the union so far (crate::cull); a round's
    // polygons inside that union are dropped, the rest extend it.
    let mut united: Option<RegionMap> = None;
    let mut prune_seconds = 0.0;
    let todo = match (&di.tree, &dj.tree) {
        (Some(ti), Some(tj)) if todo.len() >= CULL_MIN => {
            let mut need = vec![false; jobs.len()];
            for &k in &todo {
                need[k] = true;
            }
            let (li, lj) = (
                largest(pi, CULL_SEEDS_PER_PART),
                largest(pj, CULL_SEEDS_PER_PART),
            );
            let mut round: Vec<usize> = li
                .iter()
                .flat_map(|&a| lj.iter().map(move |&b| a * pj.len() + b))
                .filter(|&k| need[k])
                .collect();
            let mut map = union_of_pruned(&polygons);
            let mut summed = 0;
            let mut settled = polygons.is_empty();
            loop {
                if progress.stopped() {
                    return Err(stopped());
                }
                for &k in &round {
                    need[k] = false;
                }
                summed += round.len();
                let made: Vec<Cone> = round
                    .par_iter()
                    .map(|&k| polygon_of(k))
                    .collect::<Result<_, _>>()?;
                let t0 = Instant::now();
                let cover = Cover::new(&polygons, &map);
                contact |= made.iter().any(|(_, touch)| *touch);
                let new: Vec<SphericalPolygon> = made
                    .into_par_iter()
                    .filter_map(|(p, _)| (!cover.contains(&p)).then_some(p))
                    .collect();
                if !new.is_empty() {
                    // The round's own union, merged into the union so far.
                    let new = pruned(new);
                    map = merge_unions(&map, &polygons, &union_of_pruned(&new), &new);
                    // The round's polygons are pruned, and so are the union's after the
                    // first prune (the contact cones before it are not).
                    let split = settled.then_some(polygons.len());
                    polygons.extend(new);
                    polygons = pruned_split(std::mem::take(&mut polygons), split);
                    settled = true;
                }
                let cover = Cover::new(&polygons, &map);
                let rest = uncovered_pairs(ti, tj, &cover, &|a, b| need[a * pj.len() + b]);
                prune_seconds += t0.elapsed().as_secs_f64();
                if rest.is_empty() {
                    break;
                }
                // A round: every pair left when few are, else pairs spread evenly
                // over the trees' order (spatially spread, so each round widens the
                // union where it is thinnest).
                let step = rest.len().div_ceil(CULL_ROUND);
                round = rest
                    .iter()
                    .step_by(step)
                    .map(|&(a, b)| a * pj.len() + b)
                    .collect();
            }
            stats.culled += todo.len() - summed;
            stats.sums += summed;
            united = Some(map);
            Vec::new()
        }
        _ => todo,
    };
    stats.sums += todo.len();
    for chunk in todo.chunks(PRUNE_CHUNK) {
        if progress.stopped() {
            return Err(stopped());
        }
        let made: Vec<Cone> = chunk
            .par_iter()
            .map(|&k| polygon_of(k))
            .collect::<Result<_, _>>()?;
        let t0 = Instant::now();
        let made: Vec<SphericalPolygon> = made
            .into_iter()
            .map(|(p, touch)| {
                contact |= touch;
                p
            })
            .collect();
        polygons.extend(if todo.len() > PRUNE_CHUNK {
            pruned(made)
        } else {
            made
        });
        prune_seconds += t0.elapsed().as_secs_f64();
    }
    let wall = t.elapsed().as_secs_f64() - prune_seconds;
    let (sn, pn) = (sum_ns.into_inner() as f64, proj_ns.into_inner() as f64);
    let share = if sn + pn > 0.0 { sn / (sn + pn) } else { 1.0 };
    stats.sums_seconds += axes_seconds + wall * share;
    stats.projection_seconds += wall * (1.0 - share);

    let t = Instant::now();
    // Only the polygons that add to the union are kept (memory).
    let (polygons, region) = match united {
        Some(map) => (polygons, map),
        None => {
            let polygons = pruned(polygons);
            let region = union_of_pruned(&polygons);
            (polygons, region)
        }
    };
    stats.unions_seconds += prune_seconds + t.elapsed().as_secs_f64();
    Ok(PairRegion {
        i,
        j,
        polygons,
        region,
        contact,
    })
}

/// True when the open polygon `p` lies inside the open polygon `q` (then `p` adds
/// nothing to a union containing `q`). A pointed polygon or lune is the conic hull of its
/// corners, so it suffices that every corner lies in the closed `q`; a hemisphere lies in
/// another only when they are equal.
fn contained_in(p: &SphericalPolygon, q: &SphericalPolygon) -> bool {
    if p.normals().len() == 1 {
        return q.normals().len() == 1 && q.normals()[0] == p.normals()[0];
    }
    p.corners().all(|c| q.contains_closed(c))
}

/// A floating-point bounding cap of a pointed polygon (three or more sides): the unit
/// mean `centre` of its corners, which lies inside it, and the cosine of the largest
/// angle from the centre to a corner; the cap holds the whole polygon when that angle is
/// below 90°. Only a filter: it rejects a containment that the exact test would reject.
pub(crate) struct Cap {
    pub(crate) centre: [f64; 3],
    /// Cosine of the cap's radius widened by 1e-6 rad (far beyond float rounding);
    /// `None` when the cap is not convex (no bound).
    pub(crate) cos_radius: Option<f64>,
    /// The unit corner farthest from the centre (the first of equally far ones).
    pub(crate) far: [f64; 3],
}

pub(crate) fn cap_of(p: &SphericalPolygon) -> Option<Cap> {
    if p.normals().len() < 3 {
        return None;
    }
    let units: Vec<[f64; 3]> = p.corners().map(|c| c.unit_f64()).collect();
    cap_of_units(&units)
}

/// [`cap_of`] from the polygon's unit corners.
fn cap_of_units(units: &[[f64; 3]]) -> Option<Cap> {
    let sum = units
        .iter()
        .fold([0.0; 3], |s, u| [s[0] + u[0], s[1] + u[1], s[2] + u[2]]);
    let len = dot(sum, sum).sqrt();
    if len.is_nan() || len <= 1e-6 {
        return None;
    }
    let centre = sum.map(|c| c / len);
    let far = *units
        .iter()
        .min_by(|a, b| dot(**a, centre).total_cmp(&dot(**b, centre)))?;
    let min_cos = dot(far, centre).min(1.0).clamp(-1.0, 1.0);
    let radius = min_cos.acos() + 1e-6;
    Some(Cap {
        centre,
        cos_radius: (radius < 1.5).then(|| radius.cos()),
        far,
    })
}

/// Floating-point data of a polygon for the containment filter of [`prune_contained`]:
/// its bounding cap, unit corners and unit inward normals, and for a polygon whose
/// corners all lie in the open hemisphere of a point `h` (the cap's centre, or the sum of
/// the inward normals), the factors `1 / (h · c)` that map each corner `c` to the
/// gnomonic plane at `h`.
struct Approx {
    cap: Option<Cap>,
    corners: Vec<[f64; 3]>,
    normals: Vec<[f64; 3]>,
    gnomonic: Vec<f64>,
}

impl Approx {
    fn new(p: &SphericalPolygon) -> Approx {
        let corners: Vec<[f64; 3]> = p.corners().map(|c| c.unit_f64()).collect();
        let pointed = p.normals().len() >= 3;
        let cap = if pointed {
            cap_of_units(&corners)
        } else {
            None
        };
        let normals: Vec<[f64; 3]> = p.normals().iter().map(|n| n.unit_f64()).collect();
        // The gnomonic centre: the cap's, or else the sum of the inward normals, which
        // has a positive product with every point of a pointed polygon (the normals
        // span space, and each has a non-negative product with the point).
        let factors = |h: [f64; 3]| -> Option<Vec<f64>> {
            let f: Vec<f64> = corners.iter().map(|u| dot(*u, h)).collect();
            f.iter()
                .all(|&x| x > 1e-6)
                .then(|| f.iter().map(|x| 1.0 / x).collect())
        };
        let normals_centre = || {
            let sum = normals
                .iter()
                .fold([0.0; 3], |s, n| [s[0] + n[0], s[1] + n[1], s[2] + n[2]]);
            let len = dot(sum, sum).sqrt();
            (pointed && len > 1e-6).then(|| sum.map(|x| x / len))
        };
        let gnomonic = cap
            .as_ref()
            .and_then(|c| factors(c.centre))
            .or_else(|| normals_centre().and_then(factors))
            .unwrap_or_default();
        Approx {
            cap,
            corners,
            normals,
            gnomonic,
        }
    }

    /// False when `self` provably cannot lie in `q`: its cap's centre or its farthest
    /// corner, two of its points, lies outside `q`'s cap (widened far beyond rounding).
    fn may_lie_in_cap(&self, q: &Approx) -> bool {
        let (
            Some(cp),
            Some(Cap {
                centre,
                cos_radius: Some(c),
                ..
            }),
        ) = (&self.cap, &q.cap)
        else {
            return true;
        };
        dot(cp.centre, *centre) >= *c && dot(cp.far, *centre) >= *c
    }

    /// False when a corner of `self` lies clearly outside the closed `q` (a unit normal
    /// of `q` with a unit corner below −1e-12, far beyond rounding): then `self` is not
    /// in `q`. True says nothing. With the gnomonic factors the corner minimising each
    /// normal is found by a walk: `n·c / (h·c)` is linear on the gnomonic image, a convex
    /// polygon, so along the boundary it falls to its minimum and rises again, and the
    /// minimiser turns with `q`'s normals; a walk stopped early only weakens the filter.
    fn may_lie_in(&self, q: &Approx) -> bool {
        const MARGIN: f64 = -1e-12;
        let m = self.corners.len();
        if m == 0 || self.gnomonic.len() != m {
            return !q
                .normals
                .iter()
                .any(|n| self.corners.iter().any(|c| dot(*n, *c) < MARGIN));
        }
        let g = |n: &[f64; 3], k: usize| dot(*n, self.corners[k]) * self.gnomonic[k];
        let mut i = 0;
        for n in &q.normals {
            let mut gi = g(n, i);
            for step in [1, m - 1] {
                loop {
                    let j = (i + step) % m;
                    let gj = g(n, j);
                    if gj < gi {
                        (i, gi) = (j, gj);
                    } else {
                        break;
                    }
                }
            }
            if dot(*n, self.corners[i]) < MARGIN {
                return false;
            }
        }
        true
    }
}

/// The indices of the polygons not contained in another (one of several equal ones
/// kept), in the order the union builds them. Float filters (caps, then a walk of the
/// corners against the other's normals) reject most pairs before the exact test. With
/// `split` `Some(s)`, the polygons before `s` and those from `s` on are each pruned
/// already (none lies in another of its group), so only pairs across the two groups are
/// compared: the same indices, as no pair within a group is contained.
pub(crate) fn prune_contained(polygons: &[SphericalPolygon], split: Option<usize>) -> Vec<usize> {
    let approx: Vec<Approx> = polygons.par_iter().map(Approx::new).collect();
    let mut keep: Vec<usize> = Vec::with_capacity(polygons.len());
    // Larger polygons (fewer, more permissive constraints) first: hemispheres, lunes.
    let mut order: Vec<usize> = (0..polygons.len()).collect();
    order.sort_by_key(|&k| polygons[k].normals().len());
    let apart = |p: usize, q: usize| split.is_some_and(|s| (p < s) == (q < s));
    let inside = |p: usize, q: usize| {
        !apart(p, q)
            && approx[p].may_lie_in_cap(&approx[q])
            && approx[p].may_lie_in(&approx[q])
            && contained_in(&polygons[p], &polygons[q])
    };
    for k in order {
        if !keep.iter().any(|&q| inside(k, q)) {
            keep.retain(|&q| !inside(q, k));
            keep.push(k);
        }
    }
    keep
}

/// The polygons not contained in another, in the union's order: the same open union,
/// and the same answers to every blocking test (an open polygon inside another adds
/// no direction), with less to store.
pub(crate) fn pruned(polygons: Vec<SphericalPolygon>) -> Vec<SphericalPolygon> {
    pruned_split(polygons, None)
}

/// [`pruned`] of polygons in two groups each pruned already ([`prune_contained`]).
fn pruned_split(polygons: Vec<SphericalPolygon>, split: Option<usize>) -> Vec<SphericalPolygon> {
    let keep = prune_contained(&polygons, split);
    let mut slots: Vec<Option<SphericalPolygon>> = polygons.into_iter().map(Some).collect();
    keep.into_iter()
        .map(|k| slots[k].take().expect("each index kept once"))
        .collect()
}

/// The simplified union of open convex polygons.
pub fn union_of(polygons: &[SphericalPolygon]) -> RegionMap {
    union_of_pruned(&pruned(polygons.to_vec()))
}

/// Polygons united in one arrangement; more are united by halves.
const UNION_LEAF: usize = 16;

/// [`union_of`] for polygons none of which lies in another: divide and conquer. The two
/// halves' simplified unions are overlaid (their boundaries only, which are far smaller
/// than all the polygons' when the polygons overlap), and the overlay's cells take their
/// status from the two maps' labels, from one cell evaluated exactly on the polygons.
pub(crate) fn union_of_pruned(polygons: &[SphericalPolygon]) -> RegionMap {
    if polygons.len() <= UNION_LEAF {
        return union_in_one_arrangement(polygons);
    }
    let (lo, hi) = polygons.split_at(polygons.len() / 2);
    let (a, b) = rayon::join(|| union_of_pruned(lo), || union_of_pruned(hi));
    merge_unions(&a, lo, &b, hi)
}

/// The simplified union of two simplified unions, `a` of the polygons `pa` and `b` of
/// `pb`: their boundaries overlaid, each cell's status from the polygons.
fn merge_unions(
    a: &RegionMap,
    pa: &[SphericalPolygon],
    b: &RegionMap,
    pb: &[SphericalPolygon],
) -> RegionMap {
    let (arcs, points) = region_inputs(&[a, b]);
    let (arr, _) = Arrangement::build(arcs, points);
    let st = cell_statuses(&arr, 2, |x, y| {
        let mut s = BitSet::new(2);
        s.set(0, pa.iter().any(|p| p.contains_open_perturbed(x, y)));
        s.set(1, pb.iter().any(|p| p.contains_open_perturbed(x, y)));
        s
    });
    simplify_union(&arr, &st)
}

/// The union of a few polygons in one arrangement of all their arcs.
fn union_in_one_arrangement(polygons: &[SphericalPolygon]) -> RegionMap {
    if polygons.is_empty() {
        return RegionMap::default();
    }
    if polygons.len() == 1 {
        let p = &polygons[0];
        return RegionMap {
            arcs: p
                .boundary()
                .iter()
                .map(|a| {
                    (
                        a.clone(),
                        Sides {
                            pos: true,
                            on: false,
                            neg: false,
                        },
                    )
                })
                .collect(),
            points: p.corners().map(|c| (c.clone(), false)).collect(),
        };
    }
    let mut arcs = Vec::new();
    let mut points = Vec::new();
    for (k, p) in polygons.iter().enumerate() {
        let map = k as u32;
        for a in p.boundary() {
            arcs.push(InputArc {
                arc: a.clone(),
                label: Some(SideLabel {
                    map,
                    pos: true,
                    on: false,
                    neg: false,
                }),
            });
        }
        for c in p.corners() {
            points.push(InputPoint {
                point: c.clone(),
                label: PointStatus { map, on: false },
            });
        }
    }
    let (arr, _) = Arrangement::build(arcs, points);
    let st = cell_statuses(&arr, polygons.len(), |x, y| {
        let mut s = BitSet::new(polygons.len());
        for (k, p) in polygons.iter().enumerate() {
            s.set(k, p.contains_open_perturbed(x, y));
        }
        s
    });
    simplify_union(&arr, &st)
}

#[cfg(test)]
mod prune_tests {
    use super::*;
    use apart_minkowski::{project, Projection};

    /// The projection of a box (as a Minkowski sum) that misses the origin.
    fn box_polygon(lo: [i64; 3], hi: [i64; 3]) -> Option<SphericalPolygon> {
        let b = Polytope::cuboid(lo, hi).ok()?;
        match project(&b).ok()? {
            Projection::Polygon(p) => Some(p),
            Projection::Everything => None,
        }
    }

    /// `prune_contained` without its float filters.
    fn brute(polygons: &[SphericalPolygon]) -> Vec<usize> {
        let mut keep: Vec<usize> = Vec::new();
        let mut order: Vec<usize> = (0..polygons.len()).collect();
        order.sort_by_key(|&k| polygons[k].normals().len());
        for k in order {
            let p = &polygons[k];
            if !keep.iter().any(|&q| contained_in(p, &polygons[q])) {
                keep.retain(|&q| !contained_in(&polygons[q], p));
                keep.push(k);
            }
        }
        keep
    }

    /// Prunes `polygons` with the filters and checks it keeps what the exact test alone
    /// keeps; the number pruned. Also prunes its two halves first and then the two pruned
    /// halves together, comparing only across them, and checks that keeps the same.
    fn pruned_as_brute(polygons: &[SphericalPolygon]) -> usize {
        let fast = prune_contained(polygons, None);
        assert_eq!(fast, brute(polygons));
        let (a, b) = polygons.split_at(polygons.len() / 2);
        let mut halves = pruned(a.to_vec());
        let split = halves.len();
        halves.extend(pruned(b.to_vec()));
        let keep = prune_contained(&halves, Some(split));
        assert_eq!(keep, prune_contained(&halves, None));
        polygons.len() - fast.len()
    }

    /// The status of `map` at `d`, read off the labels of an arrangement of the map and
    /// the point `d` (the polygons only give the status of one cell).
    fn map_status_at(map: &RegionMap, d: &Vec3, polygons: &[SphericalPolygon]) -> bool {
        let (arcs, mut points) = region_inputs(&[map]);
        points.push(InputPoint {
            point: d.clone(),
            label: PointStatus { map: 1, on: true },
        });
        let (arr, _) = Arrangement::build(arcs, points);
        let st = cell_statuses(&arr, 2, |x, y| {
            let mut s = BitSet::new(2);
            s.set(0, polygons.iter().any(|p| p.contains_open_perturbed(x, y)));
            s
        });
        let v = arr
            .vertices()
            .iter()
            .position(|v| v.point.primitive() == d.primitive())
            .expect("the point is a vertex");
        st.vertices[v].get(0)
    }

    #[test]
    fn pruning_by_chunks_keeps_the_union() {
        // What pair_region does with many sums: prune each chunk, then all kept ones.
        let mut rng = apart_testkit::solids::Lcg(4242u64);
        let mut next = |m: i64| rng.below(m as u64) as i64;
        for _ in 0..20 {
            let mut all = Vec::new();
            for _ in 0..30 {
                let lo = [next(9) - 4, next(9) - 4, next(5) + 1];
                let hi = [
                    lo[0] + next(4) + 1,
                    lo[1] + next(4) + 1,
                    lo[2] + next(4) + 1,
                ];
                all.extend(box_polygon(lo, hi));
            }
            let mut kept = Vec::new();
            for chunk in all.chunks(7) {
                kept.extend(pruned(chunk.to_vec()));
            }
            let kept = pruned(kept);
            assert_eq!(kept.len(), prune_contained(&all, None).len());
            for _ in 0..40 {
                let d = Vec3::new(next(15) - 7, next(15) - 7, next(9) - 1);
                if d.is_zero() {
                    continue;
                }
                let blocked = |ps: &[SphericalPolygon]| ps.iter().any(|p| p.contains_open(&d));
                assert_eq!(blocked(&kept), blocked(&all), "{d:?}");
            }
        }
    }

    #[test]
    fn halves_united_give_the_union() {
        let mut rng = apart_testkit::solids::Lcg(987u64);
        let mut next = |m: i64| rng.below(m as u64) as i64;
        for _ in 0..6 {
            let mut polygons = Vec::new();
            while polygons.len() < 3 * UNION_LEAF {
                let lo = [next(13) - 6, next(13) - 6, next(13) - 6];
                let hi = [
                    lo[0] + next(5) + 1,
                    lo[1] + next(5) + 1,
                    lo[2] + next(5) + 1,
                ];
                polygons.extend(box_polygon(lo, hi));
            }
            let polygons = pruned(polygons);
            assert!(polygons.len() > UNION_LEAF, "the halves are used");
            let map = union_of_pruned(&polygons);
            for _ in 0..25 {
                let d = Vec3::new(next(21) - 10, next(21) - 10, next(21) - 10);
                if d.is_zero() {
                    continue;
                }
                let inside = polygons.iter().any(|p| p.contains_open(&d));
                assert_eq!(map_status_at(&map, &d, &polygons), inside, "{d:?}");
            }
        }
    }

    #[test]
    fn the_cap_filter_keeps_every_containment() {
        let mut rng = apart_testkit::solids::Lcg(12345u64);
        let mut next = |m: i64| rng.below(m as u64) as i64;
        let mut pruned = 0;
        for _ in 0..200 {
            // Boxes on a small grid, grown copies (nested projections), equal copies and
            // boxes touching the origin's planes: many containments and shared sides.
            let mut polygons = Vec::new();
            for _ in 0..10 {
                let lo = [next(9) - 4, next(9) - 4, next(5) + 1];
                let hi = [
                    lo[0] + next(4) + 1,
                    lo[1] + next(4) + 1,
                    lo[2] + next(4) + 1,
                ];
                polygons.extend(box_polygon(lo, hi));
                let g = next(3);
                polygons.extend(box_polygon(
                    [lo[0] - g, lo[1] - g, lo[2]],
                    [hi[0] + g, hi[1] + g, hi[2] + g],
                ));
            }
            pruned += pruned_as_brute(&polygons);
        }
        assert!(pruned > 100, "the generator must produce containments");
    }

    #[test]
    fn the_corner_walk_keeps_every_containment_of_many_sided_polygons() {
        // Projections of prisms over integer n-gons (8 to 40 sides), with grown copies
        // (nested projections), shifted copies, and bases far wider than their height
        // above the origin (nearly hemispheres, the shape of pieces a small gap apart):
        // the float walk must never reject a true containment.
        let mut rng = apart_testkit::solids::Lcg(99u64);
        let mut next = |m: i64| rng.below(m as u64) as i64;
        let prism = |c: [i64; 2], r: i64, n: usize, z: [i64; 2]| {
            let mut pts = Vec::new();
            for k in 0..n {
                let t = k as f64 * std::f64::consts::TAU / n as f64;
                let (x, y) = (
                    (r as f64 * t.cos()).round() as i64,
                    (r as f64 * t.sin()).round() as i64,
                );
                for h in z {
                    pts.push(Vec3::new(c[0] + x, c[1] + y, h));
                }
            }
            let hull = Polytope::hull_of_points(&pts).ok()?;
            match project(&hull).ok()? {
                Projection::Polygon(p) => Some(p),
                Projection::Everything => None,
            }
        };
        let mut pruned = 0;
        let mut sides = 0;
        for _ in 0..24 {
            let mut polygons = Vec::new();
            for _ in 0..6 {
                let n = 8 + next(33) as usize;
                let c = [next(41) - 20, next(41) - 20];
                let r = 10 + next(200);
                let near = next(2) == 0;
                let z0 = 1 + next(if near { 3 } else { 60 });
                let z = [z0, z0 + 1 + next(20)];
                polygons.extend(prism(c, r, n, z));
                polygons.extend(prism(c, r + next(3), n, [z[0], z[1] + next(3)]));
                polygons.extend(prism([c[0] + next(3) - 1, c[1]], r, n, z));
            }
            sides += polygons.iter().map(|p| p.normals().len()).sum::<usize>();
            pruned += pruned_as_brute(&polygons);
        }
        assert!(
            pruned > 24,
            "the generator must produce containments ({pruned})"
        );
        assert!(sides > 24 * 18 * 8, "many-sided polygons ({sides})");
    }

    #[test]
    fn the_walk_from_the_normals_centre_keeps_every_containment() {
        // Prisms over most of a circle (its corners crowd one side), wide and just above
        // the origin: corners fall behind the corners' mean direction, so the walk runs
        // in the gnomonic plane of the inward normals' sum. Grown, shifted and equal
        // copies make containments; the float filters must keep every one.
        let mut rng = apart_testkit::solids::Lcg(7u64);
        let mut next = |m: i64| rng.below(m as u64) as i64;
        let arc_prism = |c: [i64; 2], r: i64, n: usize, turn: f64, z: [i64; 2]| {
            let mut pts = Vec::new();
            for k in 0..=n {
                let t = k as f64 * turn / n as f64;
                let (x, y) = (
                    (r as f64 * t.cos()).round() as i64,
                    (r as f64 * t.sin()).round() as i64,
                );
                for h in z {
                    pts.push(Vec3::new(c[0] + x, c[1] + y, h));
                }
            }
            match project(&Polytope::hull(&pts).ok()?).ok()? {
                Projection::Polygon(p) => Some(p),
                Projection::Everything => None,
            }
        };
        let (mut pruned, mut from_normals) = (0, 0);
        for _ in 0..24 {
            let mut polygons = Vec::new();
            for _ in 0..6 {
                let n = 12 + next(40) as usize;
                let turn = std::f64::consts::PI * (1.0 + next(50) as f64 / 100.0);
                let c = [next(21) - 10, next(21) - 10];
                let r = 500 + next(2000);
                let z = [1 + next(2), 3 + next(5)];
                polygons.extend(arc_prism(c, r, n, turn, z));
                polygons.extend(arc_prism(c, r + next(3), n, turn, [z[0], z[1] + next(3)]));
                polygons.extend(arc_prism([c[0] + next(3) - 1, c[1]], r, n, turn, z));
            }
            for p in &polygons {
                let a = Approx::new(p);
                let at_cap = a
                    .cap
                    .as_ref()
                    .is_some_and(|c| a.corners.iter().all(|u| dot(*u, c.centre) > 1e-6));
                from_normals += usize::from(!at_cap && !a.gnomonic.is_empty());
            }
            pruned += pruned_as_brute(&polygons);
        }
        assert!(
            pruned > 24,
            "the generator must produce containments ({pruned})"
        );
        assert!(
            from_normals > 100,
            "walks from the normals' sum ({from_normals})"
        );
    }
}
