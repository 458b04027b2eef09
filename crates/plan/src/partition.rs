//! Partitioning: every direction and subset that separates a (sub)assembly by one
//! infinite translation.

use crate::clearance::{deep_direction, FArc};
use crate::dbg::{Dbg, Masks};
use crate::motion_space::{CellKind, MotionSpace};
use crate::regions::{BlockingRegions, PartPieces};
use crate::PlanError;
use apart_kernel::Vec3;
use apart_sphere::BitSet;
use rayon::prelude::*;
use rustc_hash::FxHashMap as HashMap;
use std::time::Instant;

/// Choices for [`partition`].
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// Stop at the first solution found (faces, then edges, then vertices).
    pub first: bool,
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
    /// as the diagonal does for the corner cube of a block).
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
    /// All solutions: faces by decreasing clearance, then edges, then vertices.
    pub solutions: Vec<Solution>,
    /// Sizes and timings.
    pub stats: Stats,
}

/// Partitions an assembly loaded by `apart-assembly` (parts without declared pieces must
/// be convex until automatic decomposition is available).
pub fn partition(
    assembly: &apart_assembly::Assembly,
    opts: &Options,
) -> Result<Partitioning, PlanError> {
    partition_pieces(&crate::regions::parts_of(assembly)?, opts)
}

/// Partitions an assembly given as convex pieces per part.
pub fn partition_pieces(parts: &[PartPieces], opts: &Options) -> Result<Partitioning, PlanError> {
    let regions = BlockingRegions::compute(parts)?;
    let all: Vec<usize> = (0..parts.len()).collect();
    Ok(partition_subset(&regions, &all, opts).0)
}

/// Partitions the subassembly `subset` (global part indices) from precomputed regions;
/// also returns its motion space (for drawing and direction queries).
pub fn partition_subset(
    regions: &BlockingRegions,
    subset: &[usize],
    opts: &Options,
) -> (Partitioning, MotionSpace) {
    let t = Instant::now();
    let ms = MotionSpace::build(regions, subset);
    let overlay = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let solutions = solutions(regions, &ms, opts);
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
        interlocked: solutions.is_empty(),
        solutions,
        stats,
    };
    (p, ms)
}

/// Every (cell, minimal moving subset) of the motion space, or the first one.
fn solutions(regions: &BlockingRegions, ms: &MotionSpace, opts: &Options) -> Vec<Solution> {
    let arr = ms.arrangement();
    let st = ms.statuses();
    let mut memo: HashMap<BitSet, Vec<Vec<usize>>> = HashMap::default();
    let mut sets = |s: &BitSet| -> Vec<Vec<usize>> {
        // Up to 64 parts the bit-mask graph is cheaper to rebuild than to look up.
        if let Some(m) = ms.masks(s) {
            return m.minimal_moving_set_lists();
        }
        memo.entry(s.clone())
            .or_insert_with(|| ms.dbg(s).minimal_moving_sets())
            .clone()
    };
    let global =
        |local: Vec<usize>| -> Vec<usize> { local.into_iter().map(|k| ms.parts()[k]).collect() };
    let mut out = Vec::new();

    // Face solutions, one per moving set and connected region where it is free; their
    // deep directions are independent searches, run in parallel.
    let free_regions = free_regions(ms, opts.first);
    let directions: Vec<(Vec3, f64)> = free_regions
        .par_iter()
        .map(|r| region_direction(regions, ms, r))
        .collect();
    for (r, (direction, clearance)) in free_regions.into_iter().zip(directions) {
        out.push(Solution {
            cell: CellKind::Face,
            unit: direction.unit_f64(),
            direction,
            moving: global(r.moving),
            clearance_deg: clearance.to_degrees(),
        });
        if opts.first {
            return out;
        }
    }
    out.sort_by(|a, b| {
        b.clearance_deg
            .total_cmp(&a.clearance_deg)
            .then_with(|| a.moving.cmp(&b.moving))
    });

    for cell in ms.edge_cells() {
        let e = cell[0] as usize;
        let moving = sets(&st.edges[e]);
        if moving.is_empty() {
            continue;
        }
        let direction = arr.edge_arc(e as u32).interior_point().primitive();
        for m in moving {
            out.push(Solution {
                cell: CellKind::Edge,
                unit: direction.unit_f64(),
                direction: direction.clone(),
                moving: global(m),
                clearance_deg: 0.0,
            });
        }
        if opts.first {
            out.truncate(1);
            return out;
        }
    }
    for v in ms.real_vertices() {
        let moving = sets(&st.vertices[v]);
        if moving.is_empty() {
            continue;
        }
        let direction = arr.vertices()[v].point.clone();
        for m in moving {
            out.push(Solution {
                cell: CellKind::Vertex,
                unit: direction.unit_f64(),
                direction: direction.clone(),
                moving: global(m),
                clearance_deg: 0.0,
            });
        }
        if opts.first {
            out.truncate(1);
            return out;
        }
    }
    // Edges and vertices in a stable order: by kind, moving set, then direction.
    let faces = out.iter().take_while(|s| s.cell == CellKind::Face).count();
    out[faces..].sort_by(|a, b| {
        a.cell
            .cmp(&b.cell)
            .then_with(|| a.moving.cmp(&b.moving))
            .then_with(|| a.direction.to_strings().cmp(&b.direction.to_strings()))
    });
    out
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

/// A connected region of faces where one moving set is free: the set can translate
/// along every direction of the region's closure.
struct FreeRegion {
    /// The moving set (local indices), a minimal moving set of `seed`.
    moving: Vec<usize>,
    /// A face of the region where `moving` is a minimal moving set.
    seed: u32,
    /// The real half-edges bounding the region (region on their left).
    boundary: Vec<u32>,
}

/// For every face and each of its minimal moving sets, the connected region of faces
/// where that set is free, each region once (only the first with `first`). The free set
/// of a moving set is closed (blocked sets are open), so faces are joined across every
/// real edge with the set free on both sides, and the region's boundary is the edges
/// with the set blocked on the other side.
fn free_regions(ms: &MotionSpace, first: bool) -> Vec<FreeRegion> {
    let arr = ms.arrangement();
    let graphs = FaceGraphs::new(ms);
    let mut ids: HashMap<Vec<usize>, usize> = HashMap::default();
    let mut seen: rustc_hash::FxHashSet<(u32, usize)> = Default::default();
    let mut out = Vec::new();
    for f in 0..arr.faces().len() as u32 {
        for m in graphs.sets(f) {
            let next = ids.len();
            let id = *ids.entry(m.clone()).or_insert(next);
            if !seen.insert((f, id)) {
                continue;
            }
            let mut boundary = Vec::new();
            let mut todo = vec![f];
            while let Some(g) = todo.pop() {
                for &c in &arr.faces()[g as usize] {
                    for h in arr.cycle_half_edges(c) {
                        if arr.edges()[(h / 2) as usize].structural {
                            continue;
                        }
                        let other = arr.face_of(h ^ 1);
                        if graphs.can_move(other, &m) {
                            if seen.insert((other, id)) {
                                todo.push(other);
                            }
                        } else {
                            boundary.push(h);
                        }
                    }
                }
            }
            out.push(FreeRegion {
                moving: m,
                seed: f,
                boundary,
            });
            if first {
                return out;
            }
        }
    }
    out
}

/// The blocking graph of every face: rebuilt from the face's status as bit masks when
/// there are at most 64 parts (cheaper than storing one per face of a large motion
/// space), else built once per distinct status.
enum FaceGraphs<'a> {
    Masks(&'a MotionSpace),
    Memo {
        face_graph: Vec<usize>,
        graphs: Vec<(Dbg, Vec<Vec<usize>>)>,
    },
}

impl<'a> FaceGraphs<'a> {
    fn new(ms: &'a MotionSpace) -> FaceGraphs<'a> {
        if ms.parts().len() <= 64 {
            return FaceGraphs::Masks(ms);
        }
        let mut index: HashMap<&BitSet, usize> = HashMap::default();
        let mut graphs: Vec<(Dbg, Vec<Vec<usize>>)> = Vec::new();
        let face_graph = ms
            .statuses()
            .faces
            .iter()
            .map(|s| {
                *index.entry(s).or_insert_with(|| {
                    let g = ms.dbg(s);
                    let sets = g.minimal_moving_sets();
                    graphs.push((g, sets));
                    graphs.len() - 1
                })
            })
            .collect();
        FaceGraphs::Memo { face_graph, graphs }
    }

    fn masks(ms: &MotionSpace, f: u32) -> Masks {
        ms.masks(&ms.statuses().faces[f as usize])
            .expect("at most 64 parts")
    }

    /// The minimal moving sets of face `f` (local indices, sorted).
    fn sets(&self, f: u32) -> Vec<Vec<usize>> {
        match self {
            FaceGraphs::Masks(ms) => Self::masks(ms, f).minimal_moving_set_lists(),
            FaceGraphs::Memo { face_graph, graphs } => graphs[face_graph[f as usize]].1.clone(),
        }
    }

    /// True when the local set `m` can move in face `f`.
    fn can_move(&self, f: u32, m: &[usize]) -> bool {
        match self {
            FaceGraphs::Masks(ms) => Self::masks(ms, f).can_move(Masks::mask_of(m)),
            FaceGraphs::Memo { face_graph, graphs } => graphs[face_graph[f as usize]].0.can_move(m),
        }
    }
}

/// Angular distance (radians) from unit `u`, a direction where the local set `moving` is
/// free, to the nearest direction where it is blocked: to the nearest real edge with the
/// set free on one side and blocked on the other.
pub(crate) fn free_clearance(ms: &MotionSpace, moving: &[usize], u: &[f64; 3]) -> f64 {
    let arr = ms.arrangement();
    let st = ms.statuses();
    let mut free: HashMap<&BitSet, bool> = HashMap::default();
    let mut c2 = 4.0f64;
    for (e, edge) in arr.edges().iter().enumerate() {
        if edge.structural {
            continue;
        }
        let h = 2 * e as u32;
        let mut is_free = |f: u32| {
            let s = &st.faces[f as usize];
            *free.entry(s).or_insert_with(|| match ms.masks(s) {
                Some(m) => m.can_move(Masks::mask_of(moving)),
                None => ms.dbg(s).can_move(moving),
            })
        };
        if is_free(arr.face_of(h)) != is_free(arr.face_of(h ^ 1)) {
            let arc = arr.edge_arc(e as u32);
            let fa = FArc::new(
                arc.start.unit_f64(),
                arc.end.unit_f64(),
                arc.normal.unit_f64(),
            );
            c2 = c2.min(fa.distance2(u));
        }
    }
    crate::clearance::to_angle(c2)
}

/// A direction deep inside a free region with its clearance (radians): the angular
/// distance to the region's boundary, the directions where the moving set is blocked.
/// The direction is verified exactly (inside a face, the set a minimal moving set there); the fallback is
/// an exact point of the seed face found without floating point.
fn region_direction(regions: &BlockingRegions, ms: &MotionSpace, r: &FreeRegion) -> (Vec3, f64) {
    let arr = ms.arrangement();
    let arcs: Vec<FArc> = r
        .boundary
        .iter()
        .map(|&h| {
            let arc = arr.half_edge_arc(h);
            FArc::new(
                arc.start.unit_f64(),
                arc.end.unit_f64(),
                arc.normal.unit_f64(),
            )
        })
        .collect();
    // The set must be a minimal moving set at the reported direction (it is free in the
    // whole region, but minimal only where no smaller subset of it is free). The direction
    // may lie on an arc where only other parts' blocking changes (the diagonal for a
    // corner cube of a block): it is inside the set's free region all the same.
    let verify = |d: &Vec3| -> bool {
        !d.is_zero()
            && dbg_at(regions, ms.parts(), d)
                .minimal_moving_sets()
                .contains(&r.moving)
    };
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
