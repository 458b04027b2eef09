//! Partitioning: every direction and subset that separates a (sub)assembly by one
//! infinite translation.

use crate::clearance::{deep_direction, FArc};
use crate::dbg::Dbg;
use crate::motion_space::{CellKind, MotionSpace};
use crate::progress::{phases, Progress};
use crate::regions::{BlockingRegions, Part};
use crate::PlanError;
use apart_kernel::Vec3;
use apart_sphere::{EdgeId, FaceId, HalfEdge};
use rayon::prelude::*;
use rustc_hash::FxHashMap as HashMap;
use std::time::Instant;

/// Choices for [`partition`].
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// Stop at the first solution found (faces, then edges, then vertices).
    pub first: bool,
    /// List at most this many solutions (`None`: all). Enumeration stops once the list is
    /// full, so memory and the time spent on solutions stay bounded; the solutions kept
    /// are the best faces, then the first edges and vertices found, and
    /// [`Partitioning::truncated`] says whether any was left out.
    pub max_solutions: Option<usize>,
    /// List at most this many solutions of each cell kind per moving set (`None`: all):
    /// the faces of widest clearance, then the first edges and vertices found. Every
    /// solution is still counted in [`Partitioning::sets`], so a listing of many loose
    /// parts stays small without losing its counts.
    pub max_per_set: Option<usize>,
}

/// One way to separate: `moving` translates along `direction`, the rest stays.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// The kind of solution: `Face`, a region of directions (faces of the motion space
    /// and the arcs between them) where `moving` is free with positive clearance; `Edge`,
    /// a sliding arc; `Vertex`, an isolated direction. Cells are maximal: an arc or a
    /// vertex with the blocking graph of a face beside it is part of that face (the
    /// boundary of one pair's open blocked set where nothing else changes), and a vertex
    /// with the graph of an edge cell through it is part of that edge.
    pub cell: CellKind,
    /// An exact integer direction of the solution where `moving` is a minimal moving set:
    /// the vertex itself, an interior point of the edge, or a simple direction deep
    /// inside the region (it may lie on an arc where only other parts' blocking changes,
    /// as the diagonal does for the corner cube of a block). Where a smaller set is also
    /// free in part of the region, the direction is found deep inside the faces around
    /// the region's first face where `moving` is minimal, unless a simple one near the
    /// region's deepest point is minimal too.
    pub direction: Vec3,
    /// The same direction as a unit vector.
    pub unit: [f64; 3],
    /// The parts that move (global indices, sorted): a minimal movable subset.
    pub moving: Vec<usize>,
    /// For faces, the angular distance in degrees from `direction` to the nearest
    /// direction where `moving` is blocked (the boundary of the connected region of
    /// directions where it is free); 0 for edges and vertices.
    pub clearance_deg: f64,
}

/// Seconds spent in each phase.
#[derive(Clone, Copy, Debug, Default)]
pub struct PhaseSeconds {
    /// Minkowski sums.
    pub sums: f64,
    /// Central projections.
    pub projection: f64,
    /// Per-pair unions.
    pub unions: f64,
    /// Overlay of all pairs (the motion space).
    pub overlay: f64,
    /// Blocking graphs, components and solution directions.
    pub graphs: f64,
}

/// Sizes and timings of a partitioning run.
#[derive(Clone, Copy, Debug, Default)]
pub struct Stats {
    /// Convex pieces.
    pub pieces: usize,
    /// Minkowski sums.
    pub sums: usize,
    /// Arcs inserted into the motion-space overlay.
    pub arcs: usize,
    /// Real vertices of the motion space.
    pub vertices: usize,
    /// Real edges of the motion space.
    pub edges: usize,
    /// Faces of the motion space.
    pub faces: usize,
    /// Phase timings.
    pub seconds: PhaseSeconds,
}

/// The result of partitioning.
#[derive(Clone, Debug)]
pub struct Partitioning {
    /// Part names (global order).
    pub names: Vec<String>,
    /// True when no proper subset can move along any direction.
    pub interlocked: bool,
    /// All solutions (or those the limits of [`Options`] keep): faces by decreasing
    /// clearance, then edges, then vertices.
    pub solutions: Vec<Solution>,
    /// True when [`Options::max_solutions`] or [`Options::max_per_set`] left out at least
    /// one solution (never set by [`Options::first`], which asks for one).
    pub truncated: bool,
    /// Every moving set found, with its number of solutions of each kind (listed or
    /// not), in the order of first discovery; complete unless
    /// [`Options::max_solutions`] or [`Options::first`] stopped the enumeration.
    pub sets: Vec<MovingSet>,
    /// Sizes and timings.
    pub stats: Stats,
    /// The stop flag of a [`Progress`] cut the run short: `solutions` and `sets` hold
    /// what was found until then (each solution valid, but not all of them), and
    /// `interlocked` is false (unknown). Never set by the functions without a
    /// [`Progress`].
    pub stopped: bool,
}

/// A moving set and how many solutions it has.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MovingSet {
    /// The parts that move (global indices, sorted).
    pub moving: Vec<usize>,
    /// Its solutions of each kind: faces, edges, vertices.
    pub counts: [usize; 3],
}

impl Partitioning {
    /// The number of solutions found, listed or not.
    pub fn solution_count(&self) -> usize {
        self.sets
            .iter()
            .map(|s| s.counts.iter().sum::<usize>())
            .sum()
    }

    /// The answer for an assembly of fewer than two parts: nothing to separate, no
    /// solution, not interlocked, complete.
    pub fn nothing_to_separate(names: Vec<String>) -> Partitioning {
        Partitioning {
            names,
            interlocked: false,
            solutions: Vec::new(),
            truncated: false,
            sets: Vec::new(),
            stats: Stats::default(),
            stopped: false,
        }
    }

    /// The answer of a run stopped before it found anything (while it computed the pair
    /// regions): no solution, not interlocked, [`Partitioning::stopped`].
    pub fn stopped_before_solutions(names: Vec<String>, pieces: usize) -> Partitioning {
        let mut p = Partitioning::nothing_to_separate(names);
        p.stats.pieces = pieces;
        p.stopped = true;
        p
    }
}

/// Partitions an assembly loaded by `apart-assembly`, each part by its convex pieces
/// (declared, or made by the loader's exact decomposition of a non-convex part).
pub fn partition(
    assembly: &apart_assembly::Assembly,
    opts: &Options,
) -> Result<Partitioning, PlanError> {
    partition_pieces(crate::regions::parts_of(assembly)?, opts)
}

/// Partitions an assembly given as convex pieces per part.
pub fn partition_pieces(parts: &[Part], opts: &Options) -> Result<Partitioning, PlanError> {
    partition_pieces_with(parts, opts, &Progress::new())
}

/// [`partition_pieces`] with progress reports and the stop flag of `progress` (see
/// [`BlockingRegions::compute_with`] and [`partition_subset_with`]). Stopped while the
/// pair regions are computed, the answer has no solution
/// ([`Partitioning::stopped_before_solutions`]).
pub fn partition_pieces_with(
    parts: &[Part],
    opts: &Options,
    progress: &Progress,
) -> Result<Partitioning, PlanError> {
    let regions = match BlockingRegions::compute_with(parts, progress) {
        Ok(r) => r,
        Err(PlanError::Stopped { .. }) => {
            return Ok(Partitioning::stopped_before_solutions(
                parts.iter().map(|p| p.name.clone()).collect(),
                parts.iter().map(|p| p.pieces.len()).sum(),
            ))
        }
        Err(e) => return Err(e),
    };
    let all: Vec<usize> = (0..parts.len()).collect();
    Ok(partition_subset_with(&regions, &all, opts, progress).0)
}

/// Partitions the subassembly `subset` (global part indices) from precomputed regions;
/// also returns its motion space (for drawing and direction queries).
pub fn partition_subset(
    regions: &BlockingRegions,
    subset: &[usize],
    opts: &Options,
) -> (Partitioning, MotionSpace) {
    let (p, ms) = partition_subset_with(regions, subset, opts, &Progress::new());
    (p, ms.expect("never stopped without a stop request"))
}

/// [`partition_subset`], reporting [`phases::MOTION_SPACE`] (the overlay, one
/// indivisible build), then [`phases::FREE_REGIONS`] (faces scanned),
/// [`phases::DIRECTIONS`] (free regions given a direction) and [`phases::CELLS`] (edges
/// and vertices scanned), and watching the stop flag before and after the overlay, every
/// 256 faces or cells, and before each region's direction. Stopped, the answer holds
/// the solutions found so far, [`Partitioning::stopped`] is set, and the motion space
/// is `None` when the flag was raised before it was built.
pub fn partition_subset_with(
    regions: &BlockingRegions,
    subset: &[usize],
    opts: &Options,
    progress: &Progress,
) -> (Partitioning, Option<MotionSpace>) {
    let pieces = regions.stats.pieces;
    if progress.stopped() {
        let p = Partitioning::stopped_before_solutions(regions.names().to_vec(), pieces);
        return (p, None);
    }
    let t = Instant::now();
    progress.report(phases::MOTION_SPACE, 0, 1);
    let ms = MotionSpace::build(regions, subset);
    progress.report(phases::MOTION_SPACE, 1, 1);
    let overlay = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let (solutions, truncated, sets, stopped) = solutions(regions, &ms, opts, progress);
    let graphs = t.elapsed().as_secs_f64();
    let arr = ms.arrangement();
    let rs = regions.stats;
    let stats = Stats {
        pieces: rs.pieces,
        sums: rs.sums + rs.contact_cones,
        arcs: ms.input_arcs,
        vertices: ms.real_vertices().count(),
        edges: ms.edge_cells().len(),
        faces: arr.faces().len(),
        seconds: PhaseSeconds {
            sums: rs.sums_seconds,
            projection: rs.projection_seconds,
            unions: rs.unions_seconds,
            overlay,
            graphs,
        },
    };
    let p = Partitioning {
        names: regions.names().to_vec(),
        interlocked: !stopped && sets.is_empty(),
        solutions,
        truncated,
        sets,
        stats,
        stopped,
    };
    (p, Some(ms))
}

/// Every (cell, minimal moving subset) of the motion space, or the first one, or as
/// many as the limits of `opts` keep; whether a limit left one out; the count of
/// every moving set; and whether the stop flag cut the enumeration short.
fn solutions(
    regions: &BlockingRegions,
    ms: &MotionSpace,
    opts: &Options,
    progress: &Progress,
) -> (Vec<Solution>, bool, Vec<MovingSet>, bool) {
    let mut quota = Quota::new(opts).watching(progress.clone());
    let mut out = face_solutions(regions, ms, &mut quota);
    if !(quota.full() || opts.first && !out.is_empty() || quota.stopped) {
        out.extend(cell_solutions(ms, &mut quota));
    }
    let sets = quota
        .order
        .iter()
        .map(|m| MovingSet {
            moving: m.iter().map(|&k| ms.parts()[k]).collect(),
            counts: quota.tally[m],
        })
        .collect();
    (out, quota.truncated, sets, quota.stopped)
}

/// How many solutions may still be listed, in all and per moving set and kind, and how
/// many each moving set has.
pub(crate) struct Quota {
    first: bool,
    max: Option<usize>,
    per_set: Option<usize>,
    listed: usize,
    /// Solutions found per (local) moving set and kind, listed or not.
    tally: HashMap<Vec<usize>, [usize; 3]>,
    /// The moving sets in the order they were first found.
    order: Vec<Vec<usize>>,
    /// A solution was left out because of a limit.
    truncated: bool,
    /// Reports progress; its stop flag cuts the enumeration short.
    progress: Progress,
    /// The stop flag cut the enumeration short.
    pub(crate) stopped: bool,
}

/// What to do with one more solution.
#[derive(PartialEq, Eq)]
enum Admit {
    /// List it.
    Yes,
    /// Its moving set has its quota of this kind: count it, do not list it.
    SkipSet,
    /// The list is full: stop.
    Stop,
}

impl Quota {
    pub(crate) fn new(opts: &Options) -> Quota {
        Quota {
            first: opts.first,
            max: if opts.first {
                Some(1)
            } else {
                opts.max_solutions
            },
            per_set: opts.max_per_set,
            listed: 0,
            tally: HashMap::default(),
            order: Vec::new(),
            truncated: false,
            progress: Progress::new(),
            stopped: false,
        }
    }

    /// The same quota, reporting to `progress` and watching its stop flag.
    pub(crate) fn watching(mut self, progress: Progress) -> Quota {
        self.progress = progress;
        self
    }

    /// No limit at all.
    pub(crate) fn unlimited() -> Quota {
        Quota::new(&Options::default())
    }

    fn full(&self) -> bool {
        self.max.is_some_and(|m| self.listed >= m)
    }

    /// Whether a solution of (local) moving set `m` and kind `cell` may be listed;
    /// counts it unless the list is full.
    fn admit(&mut self, m: &[usize], cell: CellKind) -> Admit {
        if self.full() {
            // (Asking for the first solution leaves nothing out.)
            self.truncated |= !self.first;
            return Admit::Stop;
        }
        let kind = match cell {
            CellKind::Face => 0,
            CellKind::Edge => 1,
            CellKind::Vertex => 2,
        };
        let counts = match self.tally.get_mut(m) {
            Some(c) => c,
            None => {
                self.order.push(m.to_vec());
                self.tally.entry(m.to_vec()).or_insert([0; 3])
            }
        };
        counts[kind] += 1;
        if self.per_set.is_some_and(|k| counts[kind] > k) {
            self.truncated = true;
            return Admit::SkipSet;
        }
        self.listed += 1;
        Admit::Yes
    }
}

/// The face solutions (one per moving set and connected region where it is free) that
/// `quota` admits, by decreasing clearance (the widest of each set first); their deep
/// directions are independent searches, run in parallel.
pub(crate) fn face_solutions(
    regions: &BlockingRegions,
    ms: &MotionSpace,
    quota: &mut Quota,
) -> Vec<Solution> {
    face_solutions_of(regions, ms, quota, &|_| true)
}

/// [`face_solutions`] of the (local) moving sets `wanted` accepts only.
pub(crate) fn face_solutions_of(
    regions: &BlockingRegions,
    ms: &MotionSpace,
    quota: &mut Quota,
    wanted: &dyn Fn(&[usize]) -> bool,
) -> Vec<Solution> {
    let progress = quota.progress.clone();
    let (mut free_regions, cut) = free_regions(ms, quota.first, &progress);
    free_regions.retain(|r| wanted(&r.moving));
    let counter = progress.counter(phases::DIRECTIONS, free_regions.len());
    let directions: Vec<Option<(Vec3, f64)>> = free_regions
        .par_iter()
        .map(|r| {
            if progress.stopped() {
                return None;
            }
            let found = region_direction(regions, ms, r);
            counter.add(1);
            Some(found)
        })
        .collect();
    // Stopped: the regions given a direction are solutions all the same.
    quota.stopped |= cut || directions.iter().any(Option::is_none);
    let mut found: Vec<(FreeRegion, Vec3, f64)> = free_regions
        .into_iter()
        .zip(directions)
        .filter_map(|(r, d)| d.map(|(d, c)| (r, d, c)))
        .collect();
    found.sort_by(|a, b| {
        b.2.total_cmp(&a.2)
            .then_with(|| a.0.moving.cmp(&b.0.moving))
    });
    let mut out = Vec::new();
    for (r, direction, clearance) in found {
        match quota.admit(&r.moving, CellKind::Face) {
            Admit::Yes => out.push(Solution {
                cell: CellKind::Face,
                unit: direction.unit_f64(),
                direction,
                moving: r.moving.iter().map(|&k| ms.parts()[k]).collect(),
                clearance_deg: clearance.to_degrees(),
            }),
            Admit::SkipSet => {}
            Admit::Stop => break,
        }
    }
    out
}

/// The edge and vertex solutions that `quota` admits: edges, then vertices, each by
/// moving set, then direction.
pub(crate) fn cell_solutions(ms: &MotionSpace, quota: &mut Quota) -> Vec<Solution> {
    let arr = ms.arrangement();
    let st = ms.statuses();
    let global = |local: &[usize]| -> Vec<usize> { local.iter().map(|&k| ms.parts()[k]).collect() };
    let mut out = Vec::new();
    let progress = quota.progress.clone();
    let counter = progress.counter(
        phases::CELLS,
        ms.edge_cells().len() + ms.real_vertices().count(),
    );
    let cells = ms
        .edge_cells()
        .iter()
        .map(|cell| {
            (
                CellKind::Edge,
                &st.edges[cell[0].index()],
                Cell::Edge(cell[0]),
            )
        })
        .chain(
            ms.real_vertices()
                .map(|v| (CellKind::Vertex, &st.vertices[v], Cell::Vertex(v))),
        );
    'cells: for (k, (kind, status, cell)) in cells.enumerate() {
        if k % STOP_EVERY == 0 {
            if progress.stopped() {
                quota.stopped = true;
                break;
            }
            counter.add(if k == 0 { 0 } else { STOP_EVERY });
        }
        let mut direction = None;
        for m in ms.minimal_moving_sets(status) {
            match quota.admit(&m, kind) {
                Admit::Yes => {
                    // (Made only for listed solutions: an exact interior point of an arc.)
                    let d = direction
                        .get_or_insert_with(|| match cell {
                            Cell::Edge(e) => arr.edge_arc(e).interior_point().primitive(),
                            Cell::Vertex(v) => arr.vertices()[v].point.clone(),
                        })
                        .clone();
                    out.push(Solution {
                        cell: kind,
                        unit: d.unit_f64(),
                        direction: d,
                        moving: global(&m),
                        clearance_deg: 0.0,
                    })
                }
                Admit::SkipSet => {}
                Admit::Stop => break 'cells,
            }
        }
    }
    if !quota.stopped {
        // (The cells after the last multiple of STOP_EVERY, or those a full list left.)
        counter.add(usize::MAX);
    }
    out.sort_by_cached_key(|s| (s.cell, s.moving.clone(), s.direction.to_strings()));
    out
}

/// Faces or cells scanned between two looks at the stop flag (and progress reports).
const STOP_EVERY: usize = 256;

/// An edge cell (by its first arrangement edge) or a vertex cell.
#[derive(Clone, Copy)]
enum Cell {
    Edge(EdgeId),
    Vertex(usize),
}

/// The exact blocking graph at direction `d` for the parts of `ms`, from the pair
/// regions' polygons (independent of the overlay).
pub fn dbg_at(regions: &BlockingRegions, parts: &[usize], d: &Vec3) -> Dbg {
    let mut arcs = Vec::new();
    for (li, &i) in parts.iter().enumerate() {
        for (lj, &j) in parts.iter().enumerate() {
            if i != j && regions.blocks(i, j, d) {
                arcs.push((li, lj));
            }
        }
    }
    Dbg::new(parts.len(), arcs)
}

/// Exactly: is the local set `moving` (sorted) a minimal moving set of `parts` along
/// `d`? It is when no member hits a part outside it (it can move) and its own blocking
/// graph is strongly connected (no smaller set inside it can): `|m| · |parts|` pair tests
/// instead of the whole graph's `|parts|²`.
fn is_minimal_moving_set(
    regions: &BlockingRegions,
    parts: &[usize],
    moving: &[usize],
    d: &Vec3,
) -> bool {
    if moving.is_empty() || moving.len() >= parts.len() {
        return false;
    }
    let inside = |k: usize| moving.binary_search(&k).is_ok();
    let free = moving.iter().all(|&a| {
        (0..parts.len())
            .filter(|&b| !inside(b))
            .all(|b| !regions.blocks(parts[a], parts[b], d))
    });
    if !free {
        return false;
    }
    if moving.len() == 1 {
        return true;
    }
    let arcs = moving
        .iter()
        .enumerate()
        .flat_map(|(x, &a)| {
            moving
                .iter()
                .enumerate()
                .filter(move |&(y, _)| y != x)
                .filter(move |&(_, &b)| regions.blocks(parts[a], parts[b], d))
                .map(move |(y, _)| (x, y))
        })
        .collect();
    // Strongly connected exactly when no proper subset of it can move.
    Dbg::new(moving.len(), arcs)
        .minimal_moving_sets()
        .is_empty()
}

/// A connected region of faces where one moving set is free: the set can translate
/// along every direction of the region's closure.
struct FreeRegion {
    /// The moving set (local indices), a minimal moving set of `seed`.
    moving: Vec<usize>,
    /// A face of the region where `moving` is a minimal moving set.
    seed: FaceId,
    /// The real half-edges bounding the region (region on their left).
    boundary: Vec<HalfEdge>,
}

/// For every face and each of its minimal moving sets, the connected region of faces
/// where that set is free, each region once (only the first with `first`). The free
/// set of a moving set is closed (blocked sets are open), so faces are joined across
/// every real edge with the set free on both sides, and the region's boundary is the
/// edges with the set blocked on the other side. The faces already in a region of a set
/// are one bit each per set. Also whether the stop flag cut the scan short.
fn free_regions(ms: &MotionSpace, first: bool, progress: &Progress) -> (Vec<FreeRegion>, bool) {
    let arr = ms.arrangement();
    let st = ms.statuses();
    let faces = arr.faces().len();
    let mut ids: HashMap<Vec<usize>, usize> = HashMap::default();
    let mut seen: Vec<Vec<u64>> = Vec::new();
    let mark = |seen: &mut [Vec<u64>], id: usize, f: FaceId| -> bool {
        let (w, b) = (f.index() / 64, 1u64 << (f.index() % 64));
        let new = seen[id][w] & b == 0;
        seen[id][w] |= b;
        new
    };
    let mut alone: Vec<Option<apart_sphere::BitSet>> = vec![None; faces];
    let mut out = Vec::new();
    let counter = progress.counter(phases::FREE_REGIONS, faces);
    for f in arr.face_ids() {
        if f.index() % STOP_EVERY == 0 {
            if progress.stopped() {
                return (out, true);
            }
            counter.add(if f.index() == 0 { 0 } else { STOP_EVERY });
        }
        for m in ms.minimal_moving_sets(&st.faces[f.index()]) {
            let next = ids.len();
            let id = *ids.entry(m.clone()).or_insert(next);
            if id == seen.len() {
                seen.push(vec![0; faces.div_ceil(64)]);
            }
            if seen[id][f.index() / 64] >> (f.index() % 64) & 1 == 1 {
                continue;
            }
            if first && !out.is_empty() {
                counter.add(faces);
                return (out, false);
            }
            mark(&mut seen, id, f);
            let mut boundary = Vec::new();
            let mut todo = vec![f];
            while let Some(g) = todo.pop() {
                for h in arr.real_half_edges(g) {
                    let other = arr.face(h.twin());
                    let (w, b) = (other.index() / 64, 1u64 << (other.index() % 64));
                    let free = seen[id][w] & b != 0
                        || match m[..] {
                            // One part alone: the face's parts free alone, found once.
                            [a] => alone[other.index()]
                                .get_or_insert_with(|| ms.free_alone(&st.faces[other.index()]))
                                .get(a),
                            _ => ms.can_move(&st.faces[other.index()], &m),
                        };
                    if free {
                        if mark(&mut seen, id, other) {
                            todo.push(other);
                        }
                    } else {
                        boundary.push(h);
                    }
                }
            }
            out.push(FreeRegion {
                moving: m,
                seed: f,
                boundary,
            });
        }
    }
    counter.add(faces);
    (out, false)
}

/// Angular distance (radians) from unit `u`, a direction where the local set `moving` is
/// free, to the nearest direction where it is blocked: to the nearest real edge with the
/// set free on one side and blocked on the other.
pub(crate) fn free_clearance(ms: &MotionSpace, moving: &[usize], u: &[f64; 3]) -> f64 {
    let arr = ms.arrangement();
    let st = ms.statuses();
    let mut free: Vec<Option<bool>> = vec![None; arr.faces().len()];
    let mut c2 = 4.0f64;
    for e in arr.edge_ids() {
        if arr.edge(e).structural {
            continue;
        }
        let mut is_free = |f: FaceId| {
            *free[f.index()].get_or_insert_with(|| ms.can_move(&st.faces[f.index()], moving))
        };
        if is_free(arr.face(e.forward())) != is_free(arr.face(e.backward())) {
            let arc = arr.edge_arc(e);
            c2 = c2.min(FArc::of(&arc).distance2(u));
        }
    }
    crate::clearance::to_angle(c2)
}

/// Candidates the exact check may reject in a region where a smaller set is free
/// somewhere before the search turns to the faces where the set is minimal.
const QUICK_REJECTED: usize = 16;

/// The boundary of the faces around the seed of `r` where its set is a minimal moving
/// set (joined across real edges), when some face of the region lies outside them;
/// `None` when the set is minimal on the whole region, whose boundary is then the same.
fn minimal_zone(ms: &MotionSpace, r: &FreeRegion) -> Option<Vec<HalfEdge>> {
    let arr = ms.arrangement();
    let st = ms.statuses();
    // Per face: whether the set is minimal there, once known (the seed: it is).
    let mut minimal: Vec<Option<bool>> = vec![None; arr.faces().len()];
    minimal[r.seed.index()] = Some(true);
    let mut todo = vec![r.seed];
    let mut boundary = Vec::new();
    let mut smaller = false;
    while let Some(g) = todo.pop() {
        for h in arr.real_half_edges(g) {
            let other = arr.face(h.twin());
            let status = &st.faces[other.index()];
            match minimal[other.index()] {
                Some(true) => {}
                Some(false) => boundary.push(h),
                None if ms.is_minimal_moving_set(status, &r.moving) => {
                    minimal[other.index()] = Some(true);
                    todo.push(other);
                }
                None => {
                    minimal[other.index()] = Some(false);
                    smaller |= ms.can_move(status, &r.moving);
                    boundary.push(h);
                }
            }
        }
    }
    smaller.then_some(boundary)
}

/// A direction deep inside a free region with its clearance (radians): the angular
/// distance to the region's boundary, the directions where the moving set is blocked.
/// The direction is verified exactly (inside a face, the set a minimal moving set there); the fallback is
/// an exact point of the seed face found without floating point.
fn region_direction(regions: &BlockingRegions, ms: &MotionSpace, r: &FreeRegion) -> (Vec3, f64) {
    let arr = ms.arrangement();
    let farc = |&h: &HalfEdge| FArc::of(&arr.half_edge_arc(h));
    let arcs: Vec<FArc> = r.boundary.iter().map(farc).collect();
    // Where a smaller set is free too, the set is free but not minimal, and a direction
    // there is no solution of it: the search keeps to the faces around the seed where
    // the set is minimal, and the clearance is measured to the region's boundary.
    // (A direction found within a few rejections is kept: the search over the whole
    // region finds it first.)
    // The set must be a minimal moving set at the reported direction (it is free in the
    // whole region, but minimal only where no smaller subset of it is free). The direction
    // may lie on an arc where only other parts' blocking changes (the diagonal for a
    // corner cube of a block): it is inside the set's free region all the same.
    let verify = |d: &Vec3| -> bool {
        !d.is_zero() && is_minimal_moving_set(regions, ms.parts(), &r.moving, d)
    };
    if let Some(zone) = minimal_zone(ms, r) {
        if let Some(found) = crate::clearance::quick_direction(&arcs, &verify, QUICK_REJECTED) {
            return found;
        }
        let zone: Vec<FArc> = zone.iter().map(farc).collect();
        if let Some((d, _)) = deep_direction(&zone, &[], &verify) {
            let c = crate::clearance::clearance(&d.unit_f64(), &arcs, &[]);
            return (d, c);
        }
    }
    if let Some(found) = deep_direction(&arcs, &[], &verify) {
        return found;
    }
    let d = ms.face_sample(r.seed);
    debug_assert!(
        verify(&d),
        "the exact face sample has the set as a minimal moving set"
    );
    let c = if arcs.is_empty() {
        std::f64::consts::PI
    } else {
        crate::clearance::clearance(&d.unit_f64(), &arcs, &[])
    };
    (d, c)
}
