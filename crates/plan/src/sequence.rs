//! Disassembly sequences by recursive two-handed partitioning.
//!
//! A subassembly splits into two at each step: one side translates to infinity along a
//! direction, the other stays. The pair regions are computed once for the whole assembly
//! ([`BlockingRegions`]); each step only overlays the regions of the parts involved.
//! Reversing the steps (each side moving back along the opposite direction) gives an
//! assembly sequence.

use crate::motion_space::{CellKind, MotionSpace};
use crate::partition::free_clearance;
use crate::partition::{cell_solutions, dbg_at, face_solutions, Quota, Solution};
use crate::regions::BlockingRegions;
use apart_kernel::Vec3;
use apart_minkowski::minkowski_difference;
use std::time::Instant;

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
    pub tolerance: Option<Tolerance>,
}

/// How much the parts may grow before a step becomes impossible.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tolerance {
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
    /// Seconds spent overlaying regions and analysing graphs for the steps (the shared
    /// pair regions are computed before, once).
    pub step_seconds: f64,
}

impl Sequence {
    /// True when every part ends up separate.
    pub fn complete(&self) -> bool {
        self.stuck.is_empty() && self.unsplit.is_empty()
    }
}

/// Plans a complete disassembly of all parts.
pub fn sequence(regions: &BlockingRegions, opts: &SequenceOptions) -> Sequence {
    let t = Instant::now();
    let all: Vec<usize> = (0..regions.part_count()).collect();
    let mut stack = vec![(all, 0usize)];
    let mut steps = Vec::new();
    let mut stuck = Vec::new();
    let mut unsplit = Vec::new();
    while let Some((sub, depth)) = stack.pop() {
        if sub.len() < 2 {
            continue;
        }
        if opts.max_depth.is_some_and(|m| depth >= m) {
            unsplit.push(sub);
            continue;
        }
        match best_step(regions, &sub, opts) {
            None => stuck.push(sub),
            Some(mut step) => {
                step.depth = depth;
                if opts.tolerance {
                    step.tolerance = Some(growth_tolerance(regions, &step));
                }
                let rest: Vec<usize> = sub
                    .iter()
                    .copied()
                    .filter(|k| !step.moving.contains(k))
                    .collect();
                let moving = step.moving.clone();
                steps.push(step);
                stack.push((rest, depth + 1));
                stack.push((moving, depth + 1));
            }
        }
    }
    Sequence {
        names: regions.names().to_vec(),
        steps,
        stuck,
        unsplit,
        step_seconds: t.elapsed().as_secs_f64(),
    }
}

/// The preferred way to split `sub`, or `None` when it is interlocked.
///
/// Face solutions come first in every preference order except when a preference for
/// single or connected moves puts an edge or vertex ahead: the edges and vertices are
/// enumerated only when the best face (or axis) candidate misses such a preference.
pub fn best_step(regions: &BlockingRegions, sub: &[usize], opts: &SequenceOptions) -> Option<Step> {
    let ms = MotionSpace::build(regions, sub);
    let mut candidates = face_solutions(regions, &ms, &mut Quota::unlimited());
    if opts.prefer_axes {
        candidates.extend(axis_candidates(regions, &ms));
    }
    let mut best = choose(regions, &ms, opts, &candidates);
    if best.as_ref().is_none_or(|(missed, _)| *missed) {
        candidates.extend(cell_solutions(&ms, &mut Quota::unlimited()));
        best = choose(regions, &ms, opts, &candidates);
    }
    let (_, best) = best?;
    Some(Step {
        subassembly: ms.parts().to_vec(),
        moving: best.moving,
        unit: best.direction.unit_f64(),
        direction: best.direction,
        cell: best.cell,
        clearance_deg: best.clearance_deg,
        depth: 0,
        tolerance: None,
    })
}

/// The preferred candidate, and whether it misses a preference for single or connected
/// moves (only then can an edge or vertex be preferred to a face).
fn choose(
    regions: &BlockingRegions,
    ms: &MotionSpace,
    opts: &SequenceOptions,
    candidates: &[Solution],
) -> Option<(bool, Solution)> {
    let mut candidates: Vec<Solution> = candidates.to_vec();
    // The complement of a moving set moves the opposite way: needed when the base part
    // is in the minimal set.
    if opts.base.is_some() {
        let comp: Vec<Solution> = candidates
            .iter()
            .map(|s| Solution {
                moving: ms
                    .parts()
                    .iter()
                    .copied()
                    .filter(|k| !s.moving.contains(k))
                    .collect(),
                direction: s.direction.neg(),
                unit: s.unit.map(|x| -x),
                ..s.clone()
            })
            .collect();
        candidates.extend(comp);
    }
    candidates.retain(|s| opts.base.is_none_or(|b| !s.moving.contains(&b)));
    let key = |s: &Solution| {
        let rest: Vec<usize> = ms
            .parts()
            .iter()
            .copied()
            .filter(|k| !s.moving.contains(k))
            .collect();
        // (Only computed when asked for: a contact search per candidate.)
        let connected =
            !opts.prefer_connected || (connected(regions, &s.moving) && connected(regions, &rest));
        let axis = is_axis(&s.direction);
        (
            opts.prefer_connected && !connected,
            opts.prefer_single && s.moving.len() != 1,
            s.cell,
            opts.prefer_axes && !axis,
            std::cmp::Reverse(ordered(s.clearance_deg)),
            s.moving.len(),
            s.moving.clone(),
            s.direction.to_strings(),
        )
    };
    candidates
        .into_iter()
        .map(|s| (key(&s), s))
        .min_by(|a, b| a.0.cmp(&b.0))
        .map(|(k, s)| (k.0 || k.1, s))
}

/// A float made totally ordered for sort keys (clearances are finite).
fn ordered(x: f64) -> i64 {
    (x * 1e9).round() as i64
}

fn is_axis(d: &Vec3) -> bool {
    let p = d.primitive();
    let c = p.to_strings();
    c.iter().filter(|x| x.as_str() == "0").count() == 2
}

/// True when `set` is connected in the contact graph (empty and single sets are).
fn connected(regions: &BlockingRegions, set: &[usize]) -> bool {
    if set.len() <= 1 {
        return true;
    }
    let mut seen = vec![false; set.len()];
    let mut stack = vec![0];
    seen[0] = true;
    while let Some(a) = stack.pop() {
        for b in 0..set.len() {
            if !seen[b] && regions.touch(set[a], set[b]) {
                seen[b] = true;
                stack.push(b);
            }
        }
    }
    seen.into_iter().all(|x| x)
}

/// Solutions along the six axis directions, exactly evaluated.
fn axis_candidates(regions: &BlockingRegions, ms: &MotionSpace) -> Vec<Solution> {
    let mut out = Vec::new();
    for k in 0..6 {
        let mut c = [0i64; 3];
        c[k % 3] = if k < 3 { 1 } else { -1 };
        let d = Vec3::from_i64(c);
        let g = dbg_at(regions, ms.parts(), &d);
        let sets = g.minimal_moving_sets();
        if sets.is_empty() {
            continue;
        }
        let (cell, _) = ms.locate(&d);
        for m in sets {
            let clearance = if cell == CellKind::Face {
                free_clearance(ms, &m, &d.unit_f64())
            } else {
                0.0
            };
            out.push(Solution {
                cell,
                direction: d.clone(),
                unit: d.unit_f64(),
                moving: m.into_iter().map(|k| ms.parts()[k]).collect(),
                clearance_deg: clearance.to_degrees(),
            });
        }
    }
    out
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
pub fn growth_tolerance(regions: &BlockingRegions, step: &Step) -> Tolerance {
    let d = step.unit;
    let rest: Vec<usize> = step
        .subassembly
        .iter()
        .copied()
        .filter(|k| !step.moving.contains(k))
        .collect();
    let mut best = f64::INFINITY;
    for &i in &step.moving {
        for &j in &rest {
            for a in regions.pieces(i) {
                for b in regions.pieces(j) {
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
        Tolerance::Finite(best)
    } else {
        Tolerance::Unbounded
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
