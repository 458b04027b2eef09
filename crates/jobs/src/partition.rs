//! Partitioning: every direction and minimal subset that separates the assembly by one
//! infinite translation, listed by moving set and bounded; or one direction's blocking
//! graph and the minimal sets that move along it.

use crate::{InputFacts, JobError, Progress, Status};
use apart_assembly::{LoadSeconds, Loaded};
use apart_kernel::progress::phases;
use apart_kernel::{Grid, Vec3};
use apart_plan::along::{holds_without_tolerance, Motion};
use apart_plan::{
    dbg_along, partition_first, partition_subset_with, parts_of, BlockingRegions, CellKind,
    MotionSpace, Options, Partitioning, PlanError,
};
use serde::Serialize;
use std::collections::HashMap;

/// Moving sets listed by default.
pub const DEFAULT_LIMIT: usize = 20;
/// Solutions of each kind (face, edge, vertex) listed per moving set by default.
pub const EXAMPLES_PER_KIND: usize = 5;

/// What a partition lists: at most `sets` moving sets (`None`: all), each with at most
/// `per_set` solutions of each kind (`None`: all). Every solution is counted either way.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Listing {
    /// Moving sets listed at most.
    pub sets: Option<usize>,
    /// Solutions of each kind listed per moving set at most.
    pub per_set: Option<usize>,
}

impl Default for Listing {
    /// 20 moving sets, 5 solutions of each kind per set.
    fn default() -> Listing {
        Listing {
            sets: Some(DEFAULT_LIMIT),
            per_set: Some(EXAMPLES_PER_KIND),
        }
    }
}

impl Listing {
    /// Everything.
    pub fn all() -> Listing {
        Listing {
            sets: None,
            per_set: None,
        }
    }
}

/// How to partition.
#[derive(Clone, Debug, Default)]
pub struct PartitionOptions {
    /// Stop at the first solution (faces, then edges, then vertices).
    pub first: bool,
    /// At most this many solutions searched for (`None`: all).
    pub max_solutions: Option<usize>,
    /// What the answer lists.
    pub listing: Listing,
    /// Keep the pair regions and every solution for pictures of the motion space.
    pub keep_for_pictures: bool,
}

/// One listed solution.
#[derive(Clone, Debug, Serialize)]
pub struct SolutionAnswer {
    /// "face", "edge" or "vertex".
    pub cell: &'static str,
    /// The direction as a unit vector.
    pub direction: [f64; 3],
    /// The exact integer direction.
    pub exact_direction: [String; 3],
    /// The parts that move.
    pub moving: Vec<String>,
    /// The angle from the direction to the nearest blocked one (faces; 0 otherwise).
    pub clearance_deg: f64,
    /// Under a tolerance: the motion also holds for the parts as given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub holds_without_tolerance: Option<bool>,
}

/// One moving set and how many solutions move it.
#[derive(Clone, Debug, Serialize)]
pub struct GroupAnswer {
    /// The parts that move.
    pub moving: Vec<String>,
    /// Solutions moving this set (faces + edges + vertices).
    pub solutions: usize,
    /// Face solutions.
    pub faces: usize,
    /// Edge (sliding) solutions.
    pub edges: usize,
    /// Vertex (isolated direction) solutions.
    pub vertices: usize,
    /// The largest clearance of its face solutions; null without a face solution.
    pub best_clearance_deg: Option<f64>,
    /// How many of its solutions the answer lists.
    pub listed: usize,
    /// Indices in [`PartitionAnswer::solutions`] of its listed solutions.
    #[serde(skip)]
    pub members: Vec<usize>,
}

/// The seconds of a load's stages.
#[derive(Clone, Debug, Serialize)]
pub struct LoadStages {
    /// Reading files.
    pub read: f64,
    /// Validating meshes.
    pub validate: f64,
    /// Decomposing into convex pieces.
    pub decompose: f64,
    /// Checking what snapping changed.
    pub snapping: f64,
    /// Checking overlaps.
    pub overlaps: f64,
}

impl LoadStages {
    /// The stages of a load.
    pub fn of(s: &LoadSeconds) -> LoadStages {
        LoadStages {
            read: s.read,
            validate: s.validate,
            decompose: s.decompose,
            snapping: s.snapping,
            overlaps: s.overlaps,
        }
    }
}

/// Where a partition's time went (seconds).
#[derive(Clone, Debug, Serialize)]
pub struct PartitionSeconds {
    /// The whole job, when the front end states it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub total: Option<f64>,
    /// Loading, when the front end loaded the assembly for this answer.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub load: Option<f64>,
    /// The load's stages, with `load`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub load_stages: Option<LoadStages>,
    /// Minkowski sums.
    pub sums: f64,
    /// Their projections onto the sphere.
    pub projection: f64,
    /// Unions per pair of parts.
    pub unions: f64,
    /// The motion-space overlay.
    pub overlay: f64,
    /// Blocking graphs and solutions.
    pub graphs: f64,
}

/// The sizes of a partition's structures.
#[derive(Clone, Debug, Serialize)]
pub struct PartitionStats {
    /// Convex pieces.
    pub pieces: usize,
    /// Minkowski sums.
    pub sums: usize,
    /// Arcs of the motion space.
    pub arcs: usize,
    /// Vertices of the motion space.
    pub vertices: usize,
    /// Edges of the motion space.
    pub edges: usize,
    /// Faces of the motion space.
    pub faces: usize,
    /// Time per phase.
    pub seconds: PartitionSeconds,
}

/// The answer of a partition.
#[derive(Clone, Debug, Serialize)]
pub struct PartitionAnswer {
    /// What the answer holds under.
    #[serde(flatten)]
    pub input: InputFacts,
    /// Complete, or cut short.
    #[serde(flatten)]
    pub status: Status,
    /// No subset can move (false when the search was stopped: unknown).
    pub interlocked: bool,
    /// The assembly has one part: there is nothing to separate.
    pub nothing_to_separate: bool,
    /// Part names.
    pub parts: Vec<String>,
    /// Every solution found (not only those listed).
    pub solution_count: usize,
    /// Distinct moving sets among them.
    pub moving_set_count: usize,
    /// Moving sets listed at most (null: all).
    pub limit: Option<usize>,
    /// Some solutions are counted but not listed.
    pub truncated: bool,
    /// The listed moving sets, in the order of their best solution.
    pub groups: Vec<GroupAnswer>,
    /// The listed solutions: faces by decreasing clearance, then edges, then vertices.
    pub solutions: Vec<SolutionAnswer>,
    /// Sizes and times.
    pub stats: PartitionStats,
    /// The cell kind of each listed solution.
    #[serde(skip)]
    pub kinds: Vec<CellKind>,
    /// Solutions of the moving sets not listed.
    #[serde(skip)]
    pub unlisted_solutions: usize,
}

/// A partition's answer, and what its pictures need when they were asked for.
pub struct PartitionRun {
    /// The answer.
    pub answer: PartitionAnswer,
    /// The pair regions and the planner's full result (with
    /// [`PartitionOptions::keep_for_pictures`], when the run was not stopped).
    pub for_pictures: Option<(BlockingRegions, Partitioning)>,
}

/// Partitions a loaded assembly (valid: see [`crate::gate`]). A run stopped by the flag
/// of `progress` returns what it found with the status "stopped". The motion space is
/// refused with [`JobError::OverBudget`] when `progress` says its estimated memory does
/// not fit.
pub fn partition(
    loaded: &Loaded,
    units: Option<&str>,
    opts: &PartitionOptions,
    progress: &Progress,
) -> Result<PartitionRun, JobError> {
    let asm = &loaded.assembly;
    if asm.parts.len() < 2 {
        let names = asm.parts.iter().map(|p| p.name.clone()).collect();
        let p = Partitioning::nothing_to_separate(names);
        let mut answer = answer(loaded, units, &p, opts.listing)?;
        answer.nothing_to_separate = true;
        return Ok(PartitionRun {
            answer,
            for_pictures: None,
        });
    }
    let parts = parts_of(asm)?;
    if opts.first && !opts.keep_for_pictures {
        // Likely directions first; the full computation only when none separates.
        let p = partition_first(parts)?;
        return Ok(PartitionRun {
            answer: answer(loaded, units, &p, opts.listing)?,
            for_pictures: None,
        });
    }
    let regions = match BlockingRegions::compute_with(parts, progress) {
        Ok(r) => r,
        // Stopped while the pair regions were computed: no solution yet.
        Err(PlanError::Stopped { .. }) => {
            let names = parts.iter().map(|p| p.name.clone()).collect();
            let pieces = parts.iter().map(|p| p.pieces.len()).sum();
            let p = Partitioning::stopped_before_solutions(names, pieces);
            return Ok(PartitionRun {
                answer: answer(loaded, units, &p, opts.listing)?,
                for_pictures: None,
            });
        }
        Err(e) => return Err(e.into()),
    };
    let all: Vec<usize> = (0..parts.len()).collect();
    afford_motion_space(&regions, &all, progress)?;
    let plan_opts = Options {
        first: opts.first,
        max_solutions: opts.max_solutions,
        // Every solution is kept and the listing cut afterwards: the planner's own
        // `max_per_set` keeps the first edges and vertices found, not the first in the
        // listing's order.
        max_per_set: None,
    };
    // (Its motion space is dropped here: a picture needs one cut at the equator.)
    let (p, _) = partition_subset_with(&regions, &all, &plan_opts, progress);
    let answer = answer(loaded, units, &p, opts.listing)?;
    let for_pictures = (opts.keep_for_pictures && !p.stopped).then_some((regions, p));
    Ok(PartitionRun {
        answer,
        for_pictures,
    })
}

/// From this estimate on, the motion space about to be built is noted to the user
/// ([`Progress::note`]).
pub const NOTED_ESTIMATE: u64 = 2 << 30;

/// Asks the budget of `progress` whether the motion space of `subset` fits, by its
/// estimated memory (a lower bound: the arcs and the cells' blocking statuses), and
/// notes a large one.
pub fn afford_motion_space(
    regions: &BlockingRegions,
    subset: &[usize],
    progress: &Progress,
) -> Result<(), JobError> {
    let e = MotionSpace::estimate(regions, subset);
    let what = format!(
        "the motion space of {} parts ({} arcs, {:.0} blocked pairs per cell) needs at least {} MiB",
        e.parts,
        e.arcs,
        e.blocked_per_cell,
        e.bytes >> 20
    );
    if !progress.affordable(phases::MOTION_SPACE, e.bytes) {
        return Err(JobError::OverBudget {
            phase: phases::MOTION_SPACE,
            what,
            bytes: e.bytes,
        });
    }
    if e.bytes >= NOTED_ESTIMATE {
        progress.note(phases::MOTION_SPACE, &what);
    }
    Ok(())
}

fn kind_index(c: CellKind) -> usize {
    match c {
        CellKind::Face => 0,
        CellKind::Edge => 1,
        CellKind::Vertex => 2,
    }
}

fn names_of(names: &[String], set: &[usize]) -> Vec<String> {
    set.iter().map(|&k| names[k].clone()).collect()
}

/// One moving set while the solutions are grouped.
struct Group {
    first: usize,
    counts: [usize; 3],
    best_clearance: Option<f64>,
    members: Vec<usize>,
}

/// The answer of a partitioning, listed as `listing` says: moving sets in the order of
/// their best solution, each with its first solutions of each kind; the counts cover
/// every solution.
fn answer(
    loaded: &Loaded,
    units: Option<&str>,
    p: &Partitioning,
    listing: Listing,
) -> Result<PartitionAnswer, JobError> {
    let mut index: HashMap<&[usize], usize> = HashMap::new();
    let mut groups: Vec<Group> = Vec::new();
    let mut kept: Vec<usize> = Vec::new();
    for (k, s) in p.solutions.iter().enumerate() {
        let g = *index.entry(s.moving.as_slice()).or_insert_with(|| {
            groups.push(Group {
                first: k,
                counts: [0; 3],
                best_clearance: None,
                members: Vec::new(),
            });
            groups.len() - 1
        });
        let group = &mut groups[g];
        let kind = kind_index(s.cell);
        if listing.sets.is_none_or(|n| g < n)
            && listing.per_set.is_none_or(|n| group.counts[kind] < n)
        {
            group.members.push(kept.len());
            kept.push(k);
        }
        group.counts[kind] += 1;
        if s.cell == CellKind::Face {
            let c = group.best_clearance.get_or_insert(s.clearance_deg);
            *c = c.max(s.clearance_deg);
        }
    }
    // The planner counts every solution, listed or not.
    let tally: HashMap<&[usize], [usize; 3]> = p
        .sets
        .iter()
        .map(|s| (s.moving.as_slice(), s.counts))
        .collect();
    for g in &mut groups {
        if let Some(c) = tally.get(p.solutions[g.first].moving.as_slice()) {
            g.counts = *c;
        }
    }
    let motions: Vec<Motion> = kept
        .iter()
        .map(|&k| {
            let s = &p.solutions[k];
            (s.moving.as_slice(), None, &s.direction)
        })
        .collect();
    let holds = holds_without_tolerance(&loaded.assembly, &motions)?;
    let solutions = kept
        .iter()
        .enumerate()
        .map(|(i, &k)| {
            let s = &p.solutions[k];
            SolutionAnswer {
                cell: s.cell.name(),
                direction: s.unit,
                exact_direction: s.direction.to_strings(),
                moving: names_of(&p.names, &s.moving),
                clearance_deg: s.clearance_deg,
                holds_without_tolerance: holds.as_ref().map(|h| h[i]),
            }
        })
        .collect();
    let total = p.solution_count();
    let shown = listing.sets.map_or(groups.len(), |n| n.min(groups.len()));
    let unlisted_solutions = groups[shown..]
        .iter()
        .map(|g| g.counts.iter().sum::<usize>())
        .sum();
    let moving_set_count = p.sets.len().max(groups.len());
    let s = &p.stats;
    Ok(PartitionAnswer {
        input: InputFacts::of(loaded, units),
        status: Status::of(p.stopped),
        interlocked: p.interlocked,
        nothing_to_separate: false,
        parts: p.names.clone(),
        solution_count: total,
        moving_set_count,
        limit: listing.sets,
        truncated: kept.len() < total || p.truncated,
        kinds: kept.iter().map(|&k| p.solutions[k].cell).collect(),
        groups: groups
            .into_iter()
            .take(shown)
            .map(|g| GroupAnswer {
                moving: names_of(&p.names, &p.solutions[g.first].moving),
                solutions: g.counts.iter().sum(),
                faces: g.counts[0],
                edges: g.counts[1],
                vertices: g.counts[2],
                best_clearance_deg: g.best_clearance,
                listed: g.members.len(),
                members: g.members,
            })
            .collect(),
        solutions,
        unlisted_solutions,
        stats: PartitionStats {
            pieces: s.pieces,
            sums: s.sums,
            arcs: s.arcs,
            vertices: s.vertices,
            edges: s.edges,
            faces: s.faces,
            seconds: PartitionSeconds {
                total: None,
                load: None,
                load_stages: None,
                sums: s.seconds.sums,
                projection: s.seconds.projection,
                unions: s.seconds.unions,
                overlay: s.seconds.overlay,
                graphs: s.seconds.graphs,
            },
        },
    })
}

/// One direction's blocking graph and the minimal sets that move along it.
#[derive(Clone, Debug, Serialize)]
pub struct DirectionAnswer {
    /// What the answer holds under.
    #[serde(flatten)]
    pub input: InputFacts,
    /// The direction as a unit vector.
    pub direction: [f64; 3],
    /// The exact integer direction.
    pub exact_direction: [String; 3],
    /// The kind of motion-space cell it lies in.
    pub cell: &'static str,
    /// The blocking graph's arcs `[a, b]`: `a`, moving along the direction, hits `b`.
    pub blocks: Vec<[String; 2]>,
    /// The minimal sets that move.
    pub moving: Vec<Vec<String>>,
    /// Under a tolerance: for each moving set, the motion also holds for the parts as
    /// given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub holds_without_tolerance: Option<Vec<bool>>,
}

/// Why a direction given as three numbers cannot be asked about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DirectionError {
    /// One of the numbers is infinite or NaN.
    NonFinite,
    /// The numbers snap to the zero vector.
    Zero,
}

/// Snaps a direction given in floats like coordinates: to a primitive integer vector
/// on a grid of 30 bits (the `--direction X,Y,Z` of the CLI, `direction=` in Python).
pub fn snap_direction(v: [f64; 3]) -> Result<Vec3, DirectionError> {
    if v.iter().any(|x| !x.is_finite()) {
        return Err(DirectionError::NonFinite);
    }
    let g = Grid::choose(v, 30).map_err(|_| DirectionError::NonFinite)?;
    let d = Vec3::new(g.snap(v[0]), g.snap(v[1]), g.snap(v[2])).primitive();
    if d.is_zero() {
        return Err(DirectionError::Zero);
    }
    Ok(d)
}

/// The blocking graph of one direction `d` (a primitive integer vector) and the
/// minimal sets that move along it: per-piece-pair tests only, no motion space.
pub fn direction(
    loaded: &Loaded,
    units: Option<&str>,
    d: &Vec3,
) -> Result<DirectionAnswer, JobError> {
    let parts = parts_of(&loaded.assembly)?;
    let names: Vec<String> = parts.iter().map(|p| p.name.clone()).collect();
    let answer = dbg_along(parts, d)?;
    let blocks = answer
        .dbg
        .arcs()
        .iter()
        .map(|&(a, b)| [names[a].clone(), names[b].clone()])
        .collect();
    let motions: Vec<Motion> = answer
        .moving
        .iter()
        .map(|m| (m.as_slice(), None, d))
        .collect();
    let holds = holds_without_tolerance(&loaded.assembly, &motions)?;
    Ok(DirectionAnswer {
        input: InputFacts::of(loaded, units),
        direction: d.unit_f64(),
        exact_direction: d.to_strings(),
        cell: answer.cell.name(),
        blocks,
        moving: answer.moving.iter().map(|m| names_of(&names, m)).collect(),
        holds_without_tolerance: holds,
    })
}
