//! Disassembly sequences by recursive two-handed partitioning.
//!
//! A subassembly splits into two at each step: one side translates to infinity along a
//! direction, the other stays. Reversing the steps (each side moving back along the
//! opposite direction) gives an assembly sequence.
//!
//! - [`sequence_parts`] (what `apart sequence` runs) makes pair regions as it needs them
//!   and keeps each part's own free directions from step to step, so a step costs what
//!   the parts it touches cost; small subassemblies get the full ranking ([`Ranking`],
//!   [`Rule`]).
//! - [`sequence`] and [`sequence_with`] take the pair regions of the whole assembly
//!   ([`BlockingRegions`]) and rank every step over the overlay of the regions of the
//!   parts involved.
//! - [`sequence_first`] takes the first likely direction that frees a subset.

use crate::motion_space::{CellKind, MotionSpace};
use crate::partition::free_clearance;
use crate::partition::{cell_solutions, dbg_at, face_solutions, Quota, Solution};
use crate::progress::{phases, Progress, Stopped};
use crate::regions::BlockingRegions;
use crate::PlanError;
use apart_kernel::Vec3;
use apart_minkowski::minkowski_difference;
use std::time::Instant;

mod first;
mod local;
mod part_tree;
mod rank;
pub use first::{sequence_first, sequence_first_with};
pub use local::{LocalStats, RANKED_ARCS, RANKED_PARTS, RANKED_PIECE_PAIRS};
pub use rank::{Choice, Criterion, Keys, Rival};

/// Choices a planner wants.
#[derive(Clone, Debug, Default)]
pub struct SequenceOptions {
    /// Prefer steps that move a single part.
    pub prefer_single: bool,
    /// Prefer steps whose two sides are each connected through contacts (paper 003 §6).
    pub prefer_connected: bool,
    /// Prefer directions along the coordinate axes when they separate.
    pub prefer_axes: bool,
    /// A part that never moves (the other side moves instead).
    pub base: Option<usize>,
    /// Split at most this many levels deep (the root is level 0).
    pub max_depth: Option<usize>,
    /// For each step, compute the largest uniform growth of the parts that keeps the
    /// separation (see [`growth_tolerance`]).
    pub tolerance: bool,
    /// Which steps keep every solution of their motion space in [`Step::solutions`]
    /// (to draw them; costs the edge and vertex solutions' enumeration and memory).
    pub keep_solutions: KeepSolutions,
    /// How [`sequence_parts`] chooses each subassembly's step (the other planners
    /// always rank over the full motion space).
    pub ranking: Ranking,
}

/// How [`sequence_parts`] chooses a subassembly's step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Ranking {
    /// The full ranking ([`best_step`]) for a subassembly of at most [`RANKED_PARTS`]
    /// parts, [`RANKED_PIECE_PAIRS`] piece pairs and a motion space of at most
    /// [`RANKED_ARCS`] arcs; the local rules otherwise.
    #[default]
    Auto,
    /// The full ranking for every subassembly: every pair region of the subassembly
    /// and its whole motion space, at every step.
    Full,
    /// The local rules for every subassembly of three or more parts (see [`Rule`]).
    Local,
}

/// Which rule chose a step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Rule {
    /// Ranked over every candidate of the subassembly's full motion space ([`best_step`]):
    /// the widest-clearance face over every minimal moving set, with the preferences.
    #[default]
    Ranked,
    /// A single part, from its own free directions: the widest-clearance face among
    /// single parts (else an edge, else a vertex); a set of several parts may have had
    /// a wider one.
    Single,
    /// Two touching parts together, from their own free directions (when no single part
    /// leaves along a face): the widest-clearance face among such pairs.
    Pair,
    /// A likely direction (an axis, a tessellated cylinder's axis, a touching plane's
    /// normal) that frees a subset: the first in a face, else the first at all, and the
    /// smallest minimal moving set there.
    Likely,
    /// Ranked over the full motion space after no single part and no likely direction
    /// split the subassembly (the check that says "interlocked" when nothing is found).
    Full,
}

impl Rule {
    /// The rule's key in JSON answers: `"ranked"`, `"single"`, `"pair"`, `"likely"`,
    /// `"full"`.
    pub fn key(self) -> &'static str {
        match self {
            Rule::Ranked => "ranked",
            Rule::Single => "single",
            Rule::Pair => "pair",
            Rule::Likely => "likely",
            Rule::Full => "full",
        }
    }
}

/// Which steps of a plan keep their solutions ([`SequenceOptions::keep_solutions`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum KeepSolutions {
    /// No step (the default).
    #[default]
    Nothing,
    /// Every step.
    EveryStep,
    /// Only the step of this index in [`Sequence::steps`] (0-based).
    Step(usize),
}

impl KeepSolutions {
    /// Whether the step of index `k` in [`Sequence::steps`] keeps its solutions.
    pub fn keeps(self, k: usize) -> bool {
        match self {
            KeepSolutions::Nothing => false,
            KeepSolutions::EveryStep => true,
            KeepSolutions::Step(j) => j == k,
        }
    }
}

/// One step: `moving` leaves `subassembly` along `direction`; the rest stays.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// The parts being split (global indices, sorted).
    pub subassembly: Vec<usize>,
    /// The parts that move (global indices, sorted).
    pub moving: Vec<usize>,
    /// Exact direction, an integer vector inside the chosen cell.
    pub direction: Vec3,
    /// The direction as a unit vector.
    pub unit: [f64; 3],
    /// The kind of motion-space cell of the direction.
    pub cell: CellKind,
    /// Angular distance from the direction to the nearest blocked direction (0 for edges
    /// and vertices), in degrees.
    pub clearance_deg: f64,
    /// Level in the disassembly tree (the whole assembly splits at level 0).
    pub depth: usize,
    /// Largest uniform growth of every part that keeps this separation; when computed.
    pub tolerance: Option<Growth>,
    /// Why this step was chosen (see [`best_step`]).
    pub choice: Choice,
    /// Every solution of the subassembly's motion space, as
    /// [`partition_subset`](crate::partition_subset) lists them with default options
    /// (faces by decreasing clearance, then edges, then vertices); `None` unless
    /// [`SequenceOptions::keep_solutions`] asks for them.
    pub solutions: Option<Vec<Solution>>,
    /// The rule that chose it.
    pub rule: Rule,
}

impl Step {
    /// The parts of the subassembly that stay (global indices, sorted).
    pub fn staying(&self) -> Vec<usize> {
        self.subassembly
            .iter()
            .copied()
            .filter(|k| !self.moving.contains(k))
            .collect()
    }
}

/// How much the parts may grow before a step becomes impossible.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Growth {
    /// Growth by a ball of this radius (grid units) still lets the step happen.
    Finite(f64),
    /// No growth blocks the step (the sides leave each other at once).
    Unbounded,
}

/// A disassembly plan.
#[derive(Clone, Debug)]
pub struct Sequence {
    /// Part names.
    pub names: Vec<String>,
    /// Steps in disassembly order (depth-first: the side that moved is taken apart before
    /// the side that stayed).
    pub steps: Vec<Step>,
    /// Subassemblies found interlocked (no proper subset can translate away).
    pub stuck: Vec<Vec<usize>>,
    /// Subassemblies left whole because of the depth limit.
    pub unsplit: Vec<Vec<usize>>,
    /// Subassemblies not yet split when the stop flag of a [`Progress`] ended the run
    /// (see [`Sequence::stopped`]), in the order they would have been split; empty
    /// otherwise.
    pub pending: Vec<Vec<usize>>,
    /// The stop flag ended the run early: `steps` are the steps found until then (each a
    /// valid step of the plan, in order) and `pending` the subassemblies still to split.
    /// Never set by [`sequence`], which takes no [`Progress`].
    pub stopped: bool,
    /// Seconds spent overlaying regions and analysing graphs for the steps (the shared
    /// pair regions are computed before, once); for [`sequence_first`], the whole plan.
    pub step_seconds: f64,
    /// Subassemblies that [`sequence_first`] or [`sequence_parts`] split (or found
    /// interlocked) from their full motion space because no simpler move split them; 0
    /// for [`sequence`].
    pub full_searches: usize,
    /// The work of [`sequence_parts`]: singles computed, likely directions tried, steps
    /// by rule (zero for the other planners).
    pub local: LocalStats,
    /// Pair regions made by [`sequence_parts`] (the others take them made), and their
    /// counts and times.
    pub regions: Option<(usize, crate::regions::RegionStats)>,
}

impl Sequence {
    /// Every step as a motion (its moving set, the subassembly it leaves, its
    /// direction), as [`crate::along::holds_without_tolerance`] takes them.
    pub fn motions(&self) -> Vec<crate::along::Motion<'_>> {
        self.steps
            .iter()
            .map(|s| {
                (
                    s.moving.as_slice(),
                    Some(s.subassembly.as_slice()),
                    &s.direction,
                )
            })
            .collect()
    }

    /// True when every part ends up separate.
    pub fn complete(&self) -> bool {
        self.stuck.is_empty() && self.unsplit.is_empty() && self.pending.is_empty()
    }

    /// A plan of no step yet for parts `names`: nothing split, nothing pending (the plan
    /// of an assembly of one part).
    pub fn empty(names: Vec<String>) -> Sequence {
        Sequence {
            names,
            steps: Vec::new(),
            stuck: Vec::new(),
            unsplit: Vec::new(),
            pending: Vec::new(),
            stopped: false,
            step_seconds: 0.0,
            full_searches: 0,
            local: LocalStats::default(),
            regions: None,
        }
    }

    /// The plan of a run stopped before its first step (while the pair regions were
    /// computed): no step, the whole assembly pending.
    pub fn stopped_before_steps(names: Vec<String>) -> Sequence {
        let n = names.len();
        Sequence {
            pending: if n >= 2 {
                vec![(0..n).collect()]
            } else {
                Vec::new()
            },
            stopped: true,
            ..Sequence::empty(names)
        }
    }
}

/// Plans a complete disassembly of all parts.
pub fn sequence(regions: &BlockingRegions, opts: &SequenceOptions) -> Sequence {
    sequence_with(regions, opts, &Progress::new())
}

/// [`sequence`], reporting the splits made of the `parts - 1` a complete plan needs
/// ([`phases::SEQUENCE`]; a subassembly found interlocked or left whole by the depth
/// limit counts as its `size - 1`), and watching the stop flag before each step and
/// while a step's motion space is searched. Stopped, it returns the steps found so far
/// (a step being chosen when the flag rose is dropped, since its candidates may be
/// incomplete) with the subassemblies still to split in [`Sequence::pending`].
pub fn sequence_with(
    regions: &BlockingRegions,
    opts: &SequenceOptions,
    progress: &Progress,
) -> Sequence {
    // Steps found so far: the index of the next one, for `keep_solutions`.
    let mut found_steps = 0;
    let Ok(plan) = split_recursively(
        regions.names().to_vec(),
        opts,
        progress,
        &mut |_| {},
        |sub, inner| {
            let keep = opts.keep_solutions.keeps(found_steps);
            let found = best_step_with(regions, sub, opts, keep, inner).map(|found| {
                found.map(|mut step| {
                    if opts.tolerance {
                        step.tolerance = Some(growth_tolerance(regions, &step));
                    }
                    step
                })
            });
            if matches!(found, Ok(Some(_))) {
                found_steps += 1;
            }
            Ok::<_, std::convert::Infallible>(found)
        },
    );
    plan
}

/// A complete disassembly plan of `parts` whose cost per step follows what the step
/// changes: pair regions are made when first needed, each part's free directions alone
/// are kept and recomputed only when a part its union used leaves, and a subassembly's
/// full motion space is built only when [`SequenceOptions::ranking`] asks for the full
/// ranking or nothing simpler splits it ([`Rule`]; the [module docs of the planner]
/// give the rules). Each step is handed to `on_step` as it is found; the stop flag of
/// `progress` is watched before each step and between its phases, and
/// [`Progress::affordable`] is asked before a motion space is built (refused, the run
/// stops as if the flag rose, with the steps found so far).
///
/// With [`Ranking::Full`] the plan is [`sequence_with`]'s, step for step.
///
/// [module docs of the planner]: local
pub fn sequence_parts(
    parts: &[crate::regions::Part],
    opts: &SequenceOptions,
    progress: &Progress,
    on_step: &mut dyn FnMut(&Step),
) -> Result<Sequence, PlanError> {
    let mut planner = local::Planner::new(parts, opts)?;
    let names = parts.iter().map(|p| p.name.clone()).collect();
    let mut found_steps = 0;
    let mut plan = split_recursively(names, opts, progress, on_step, |sub, inner| {
        let keep = opts.keep_solutions.keeps(found_steps);
        let found = planner.step(sub, keep, inner)?;
        let found = found.map(|f| {
            f.map(|mut step| {
                if opts.tolerance {
                    step.tolerance = Some(growth_of(&|k| parts[k].pieces.as_slice(), &step));
                }
                step
            })
        });
        if matches!(found, Ok(Some(_))) {
            found_steps += 1;
        }
        Ok::<_, PlanError>(found)
    })?;
    plan.local = planner.stats;
    plan.full_searches = planner.stats.full_searches;
    plan.regions = Some((planner.regions_made(), planner.region_stats()));
    Ok(plan)
}

/// The recursion of both planners: splits the whole assembly of parts `names`, then
/// depth-first the side that moved before the side that stayed, each subassembly by
/// `step` (given it and the silent progress for its own phases; `Ok(None)`:
/// interlocked, `Err(Stopped)`: the flag rose), handing each step found to `on_step`
/// as it is found (the order of [`Sequence::steps`]), honouring `opts.max_depth`, reporting
/// the splits made ([`phases::SEQUENCE`]) and watching the stop flag before each step.
fn split_recursively<E>(
    names: Vec<String>,
    opts: &SequenceOptions,
    progress: &Progress,
    on_step: &mut dyn FnMut(&Step),
    mut step: impl FnMut(&[usize], &Progress) -> Result<Result<Option<Step>, Stopped>, E>,
) -> Result<Sequence, E> {
    let t = Instant::now();
    let n = names.len();
    let mut plan = Sequence::empty(names);
    let mut stack = vec![((0..n).collect::<Vec<usize>>(), 0usize)];
    let total = n.saturating_sub(1);
    let mut done = 0;
    progress.report(phases::SEQUENCE, 0, total);
    // The steps' own phases (overlay, free regions) would interleave with the count of
    // steps: they only watch the flag.
    let inner = progress.silent();
    while let Some((sub, depth)) = stack.pop() {
        if sub.len() < 2 {
            continue;
        }
        if progress.stopped() {
            plan.pending.push(sub);
            continue;
        }
        if opts.max_depth.is_some_and(|m| depth >= m) {
            done += sub.len() - 1;
            progress.report(phases::SEQUENCE, done, total);
            plan.unsplit.push(sub);
            continue;
        }
        match step(&sub, &inner)? {
            Err(Stopped) => plan.pending.push(sub),
            Ok(None) => {
                done += sub.len() - 1;
                progress.report(phases::SEQUENCE, done, total);
                plan.stuck.push(sub)
            }
            Ok(Some(mut step)) => {
                step.depth = depth;
                let rest = step.staying();
                let moving = step.moving.clone();
                on_step(&step);
                plan.steps.push(step);
                done += 1;
                progress.report(phases::SEQUENCE, done, total);
                stack.push((rest, depth + 1));
                stack.push((moving, depth + 1));
            }
        }
    }
    plan.stopped = !plan.pending.is_empty();
    plan.step_seconds = t.elapsed().as_secs_f64();
    Ok(plan)
}

/// The preferred way to split `sub`, or `None` when it is interlocked.
///
/// How steps are ranked: every candidate (a moving set and a direction along which it
/// is free) is compared by these keys in order, the first difference deciding:
/// 1. with `prefer_connected`, both sides stay connected through contacts;
/// 2. with `prefer_single`, a single part moves;
/// 3. with `prefer_axes`, the direction is ±x, ±y or ±z;
/// 4. a face (an open region of free directions) before an edge (a sliding arc) before
///    a vertex (an isolated direction);
/// 5. the larger clearance (angular distance to the nearest blocked direction);
/// 6. fewer moving parts;
/// 7. the lowest part indices, then the direction (a fixed tie-break).
///
/// The candidates are the deepest direction of every free region of every minimal
/// moving set (face solutions); with `prefer_axes`, also every minimal moving set of
/// each of the six axis directions (tested exactly, whatever the cell kind there), and
/// when the chosen set is free along an axis that direction replaces its own. Edges and
/// vertices are enumerated only when the best face or axis candidate misses the
/// preference for single or connected moves: otherwise none of them could rank first.
/// With `base`, a set holding the base is replaced by its complement moving the
/// opposite way. [`Step::choice`] records the keys, the number of candidates and the
/// runner-up with the key it lost on. The step keeps its solutions ([`Step::solutions`])
/// unless [`SequenceOptions::keep_solutions`] is [`KeepSolutions::Nothing`].
pub fn best_step(regions: &BlockingRegions, sub: &[usize], opts: &SequenceOptions) -> Option<Step> {
    let keep = opts.keep_solutions != KeepSolutions::Nothing;
    best_step_with(regions, sub, opts, keep, &Progress::new()).expect("no stop was requested")
}

/// [`best_step`], keeping the solutions with `keep`, giving up with [`Stopped`] when the
/// stop flag rises before the step is chosen (checked after the overlay and after each
/// enumeration of candidates).
fn best_step_with(
    regions: &BlockingRegions,
    sub: &[usize],
    opts: &SequenceOptions,
    keep: bool,
    progress: &Progress,
) -> Result<Option<Step>, Stopped> {
    let quota = || Quota::unlimited().watching(progress.clone());
    let ms = MotionSpace::build(regions, sub);
    if progress.stopped() {
        return Err(Stopped);
    }
    let mut candidates = face_solutions(regions, &ms, &mut quota());
    // The face solutions lead the candidates; kept, they lead the step's solutions.
    let faces = candidates.len();
    if opts.prefer_axes {
        candidates.extend(axis_candidates(regions, &ms));
    }
    let mut best = rank::choose(regions, &ms, opts, &candidates);
    let mut cells = None;
    if best.as_ref().is_none_or(|(missed, _, _)| *missed) {
        let found = cell_solutions(&ms, &mut quota());
        if keep {
            cells = Some(found.clone());
        }
        candidates.extend(found);
        best = rank::choose(regions, &ms, opts, &candidates);
    }
    // What partition_subset lists: the face solutions, then the edges and vertices.
    let solutions = keep.then(|| {
        let mut all = candidates[..faces].to_vec();
        all.extend(cells.unwrap_or_else(|| cell_solutions(&ms, &mut quota())));
        all
    });
    // A set chosen along another direction may also be free along an axis, where it
    // is not a minimal moving set (so not yet a candidate): it moves along the axis.
    if let Some((_, chosen, _)) = best.as_ref().filter(|_| opts.prefer_axes) {
        if !rank::is_axis(&chosen.direction) {
            let along = set_along_axes(regions, &ms, &chosen.moving);
            if !along.is_empty() {
                candidates.extend(along);
                best = rank::choose(regions, &ms, opts, &candidates);
            }
        }
    }
    // (Raised at any point, the flag may have cut an enumeration short.)
    if progress.stopped() {
        return Err(Stopped);
    }
    let Some((_, best, choice)) = best else {
        return Ok(None);
    };
    Ok(Some(Step {
        subassembly: ms.parts().to_vec(),
        moving: best.moving,
        unit: best.direction.unit_f64(),
        direction: best.direction,
        cell: best.cell,
        clearance_deg: best.clearance_deg,
        depth: 0,
        tolerance: None,
        choice,
        solutions,
        rule: Rule::Ranked,
    }))
}

/// The six axis directions +x, +y, +z, -x, -y, -z.
pub(crate) fn axes() -> impl Iterator<Item = Vec3> {
    (0..6).map(|k| {
        let mut c = [0i64; 3];
        c[k % 3] = if k < 3 { 1 } else { -1 };
        Vec3::from_i64(c)
    })
}

/// A solution of the (global) set `moving` along `d`, where it is free: its cell kind
/// and clearance in `ms`.
pub(crate) fn solution_at(
    ms: &MotionSpace,
    moving: Vec<usize>,
    local: &[usize],
    d: Vec3,
) -> Solution {
    let (cell, _) = ms.locate(&d);
    let clearance = if cell == CellKind::Face {
        free_clearance(ms, local, &d.unit_f64())
    } else {
        0.0
    };
    Solution {
        cell,
        unit: d.unit_f64(),
        direction: d,
        moving,
        clearance_deg: clearance.to_degrees(),
    }
}

/// Solutions along the six axis directions, exactly evaluated.
fn axis_candidates(regions: &BlockingRegions, ms: &MotionSpace) -> Vec<Solution> {
    let mut out = Vec::new();
    for d in axes() {
        let g = dbg_at(regions, ms.parts(), &d);
        for m in g.minimal_moving_sets() {
            let moving = m.iter().map(|&k| ms.parts()[k]).collect();
            out.push(solution_at(ms, moving, &m, d.clone()));
        }
    }
    out
}

/// The (global) set `moving` along every axis direction where it is free against the
/// other parts of `ms` (the exact blocking test of every pair across).
fn set_along_axes(regions: &BlockingRegions, ms: &MotionSpace, moving: &[usize]) -> Vec<Solution> {
    let local: Vec<usize> = (0..ms.parts().len())
        .filter(|&k| moving.contains(&ms.parts()[k]))
        .collect();
    let rest: Vec<usize> = ms
        .parts()
        .iter()
        .copied()
        .filter(|k| !moving.contains(k))
        .collect();
    axes()
        .filter(|d| {
            moving
                .iter()
                .all(|&i| rest.iter().all(|&j| !regions.blocks(i, j, d)))
        })
        .map(|d| solution_at(ms, moving.to_vec(), &local, d))
        .collect()
}

/// The largest uniform growth `s` (grid units) of every part that keeps `step`'s
/// separation (paper 000 §6): each part grown by a ball of radius `s`, so each convex
/// sum `b ⊕ (−a)` of a moving piece `a` and a staying piece `b` grows by a ball of radius
/// `2s`, contained in the sum with its facet planes moved out by `2s` (the approximation
/// from outside). Contacts the step leaves at once (facets through the origin whose
/// outward normal has a positive component along the direction) do not grow: parts
/// lifted off a face stay possible however large they are made; sliding contacts grow,
/// so a zero-clearance slide has tolerance 0 and a gap `g` around a peg gives `g / 2`.
/// The ray along the direction must avoid the interior of every grown sum. Measured in
/// floating point (a tolerance to compare with manufacturing accuracy, not a
/// combinatorial decision), to about 1e-9 relative.
pub fn growth_tolerance(regions: &BlockingRegions, step: &Step) -> Growth {
    growth_of(&|k| regions.pieces(k), step)
}

/// [`growth_tolerance`] with the pieces of part `k` given by `pieces(k)`.
fn growth_of<'p>(pieces: &dyn Fn(usize) -> &'p [apart_pieces::Polytope], step: &Step) -> Growth {
    let d = step.unit;
    let rest: Vec<usize> = step.staying();
    let mut best = f64::INFINITY;
    for &i in &step.moving {
        for &j in &rest {
            for a in pieces(i) {
                for b in pieces(j) {
                    let Ok(m) = minkowski_difference(b, a) else {
                        continue;
                    };
                    let den = apart_kernel::int::to_f64(m.den());
                    // Facets as unit normals, offsets in grid units, and whether they grow.
                    let facets: Vec<([f64; 3], f64, bool)> = m
                        .facets()
                        .iter()
                        .map(|f| {
                            let n = f.normal.approx();
                            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                            let u = f.normal.unit_f64();
                            let left = f.offset == apart_kernel::Int::ZERO
                                && apart_kernel::predicates::dot_sign(&f.normal, &step.direction)
                                    == apart_kernel::Sign::Positive;
                            (u, apart_kernel::int::to_f64(&f.offset) / len / den, !left)
                        })
                        .collect();
                    best = best.min(pair_tolerance(&facets, &d));
                }
            }
        }
    }
    if best.is_finite() {
        Growth::Finite(best)
    } else {
        Growth::Unbounded
    }
}

/// Largest `s >= 0` such that the ray `{k d : k > 0}` avoids the interior of
/// `{x : n · x <= c + 2s}` (bisection; `0` when blocked already at `s = 0`).
fn pair_tolerance(facets: &[([f64; 3], f64, bool)], d: &[f64; 3]) -> f64 {
    let blocked = |s: f64| -> bool {
        let (mut lo, mut hi) = (0f64, f64::INFINITY);
        for (n, c, grows) in facets {
            let nd = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
            let c = if *grows { c + 2.0 * s } else { *c };
            if nd.abs() < 1e-15 {
                if c <= 0.0 {
                    return false;
                }
            } else if nd > 0.0 {
                hi = hi.min(c / nd);
            } else {
                lo = lo.max(c / nd);
            }
        }
        lo < hi
    };
    if blocked(0.0) {
        return 0.0;
    }
    let mut hi = 1.0;
    while !blocked(hi) {
        hi *= 2.0;
        if hi > 1e15 {
            return f64::INFINITY; // never blocks (the growth cannot reach the ray)
        }
    }
    let mut lo = 0.0;
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if blocked(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    lo
}
