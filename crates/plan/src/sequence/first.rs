//! Plans without the pair regions: each subassembly splits along the first likely
//! direction that frees part of it.
//!
//! [`sequence`](super::sequence) computes every pair's blocked region once and ranks
//! every free region of every step, which on tessellated parts costs most of the run.
//! [`sequence_first`] asks a [`DirectionQuery`] instead: for each subassembly it tests
//! the likely directions ([`DirectionQuery::candidates_in`]: the axes, the axes of
//! tessellated cylinders, the normals of touching planes) one at a time, exactly, and
//! moves the smallest minimal moving set of the first one that has any. Only a
//! subassembly that none of them splits gets the full computation (its own pair regions
//! and [`best_step`](super::best_step)'s ranking), so the plan is as complete as the
//! ranked one: a subassembly is reported interlocked only when no direction frees any
//! subset of it. (Whether a subassembly can be split depends on its parts alone, so
//! any split of a plan that can be completed leaves parts that can be split again.)

use super::{
    best_step_with, rank, split_recursively, Choice, Keys, Sequence, SequenceOptions, Step,
};
use crate::along::DirectionQuery;
use crate::motion_space::CellKind;
use crate::progress::{Progress, Stopped};
use crate::regions::{BlockingRegions, Part};
use crate::PlanError;
use apart_kernel::Vec3;

/// A complete disassembly plan whose steps move along the first likely direction that
/// frees a subset ([module docs](self)), falling back to the full pair regions of a
/// subassembly that no likely direction splits ([`Sequence::full_searches`] counts them).
///
/// Of the options, `base` (the other side moves the opposite way instead) and
/// `max_depth` shape every step; the ranking preferences (`prefer_single`,
/// `prefer_connected`, `prefer_axes`) apply to the fallback's steps only, and
/// `tolerance` and `keep_solutions` need the pair regions of every step, so they are
/// ignored here. At the chosen direction the moving set is the smallest minimal one
/// (then the lowest part indices); a face step's clearance is the exact query's
/// ([`DirectionQuery::clearance_against`]), an edge or vertex step's 0. The stop flag of
/// `progress` is watched before each step, as [`sequence_with`](super::sequence_with)
/// does.
pub fn sequence_first(
    parts: &[Part],
    opts: &SequenceOptions,
    progress: &Progress,
) -> Result<Sequence, PlanError> {
    sequence_first_with(parts, opts, progress, &mut |_| {})
}

/// [`sequence_first`], handing each step to `on_step` as it is found.
pub fn sequence_first_with(
    parts: &[Part],
    opts: &SequenceOptions,
    progress: &Progress,
    on_step: &mut dyn FnMut(&Step),
) -> Result<Sequence, PlanError> {
    let query = DirectionQuery::new(parts)?;
    let names = parts.iter().map(|p| p.name.clone()).collect();
    let mut full_searches = 0;
    let mut plan = split_recursively(
        names,
        opts,
        progress,
        on_step,
        |sub, inner| match likely_step(&query, sub, opts)? {
            Some(step) => Ok(Ok(Some(step))),
            None => {
                full_searches += 1;
                full_step(parts, sub, opts, inner)
            }
        },
    )?;
    plan.full_searches = full_searches;
    Ok(plan)
}

/// The step along the first likely direction of `sub` that frees a subset, or `None`
/// when none does.
fn likely_step(
    query: &DirectionQuery,
    sub: &[usize],
    opts: &SequenceOptions,
) -> Result<Option<Step>, PlanError> {
    let candidates = query.candidates_in(sub);
    for (tried, d) in candidates.iter().enumerate() {
        if let Some(mut step) = step_along(query, sub, opts, d)? {
            step.choice.candidates = tried + 1;
            return Ok(Some(step));
        }
    }
    Ok(None)
}

/// The step of `sub` along `d` when `d` frees a subset of it: the smallest minimal
/// moving set there (then the lowest part indices), or, holding the base, its
/// complement along `−d`; `None` when nothing moves along `d`. A face step's clearance
/// is the exact query's, an edge or vertex step's 0. (The step's
/// [`Choice::candidates`] is 1: the caller counts the directions it tried.)
pub(super) fn step_along(
    query: &DirectionQuery,
    sub: &[usize],
    opts: &SequenceOptions,
    d: &Vec3,
) -> Result<Option<Step>, PlanError> {
    let ans = query.answer_in(sub, d)?;
    // Each minimal set moves along d, or, holding the base, its complement moves
    // along −d (the same relative motion). The motion space of a subassembly is
    // symmetric under d -> −d, so both lie in cells of the same kind.
    let Some((moving, direction)) = ans
        .moving
        .iter()
        .map(|s| match opts.base {
            Some(b) if s.contains(&b) => (
                sub.iter().copied().filter(|k| !s.contains(k)).collect(),
                ans.direction.neg(),
            ),
            _ => (s.clone(), ans.direction.clone()),
        })
        .min_by(|a: &(Vec<usize>, Vec3), b| a.0.len().cmp(&b.0.len()).then_with(|| a.0.cmp(&b.0)))
    else {
        return Ok(None);
    };
    let rest: Vec<usize> = sub
        .iter()
        .copied()
        .filter(|k| !moving.contains(k))
        .collect();
    let clearance_deg = if ans.cell == CellKind::Face {
        query
            .clearance_against(&direction, &moving, &rest)?
            .to_degrees()
    } else {
        0.0
    };
    let keys = Keys {
        connected: None,
        single: moving.len() == 1,
        axis: rank::is_axis(&direction),
        cell: ans.cell,
        clearance_deg,
        parts: moving.len(),
    };
    Ok(Some(Step {
        subassembly: sub.to_vec(),
        moving,
        unit: direction.unit_f64(),
        direction,
        cell: ans.cell,
        clearance_deg,
        depth: 0,
        tolerance: None,
        choice: Choice {
            keys,
            candidates: 1,
            runner_up: None,
        },
        solutions: None,
        rule: super::Rule::Likely,
    }))
}

/// The ranked step of `sub` from its own pair regions (global indices in the step), or
/// `None` when it is interlocked.
fn full_step(
    parts: &[Part],
    sub: &[usize],
    opts: &SequenceOptions,
    progress: &Progress,
) -> Result<Result<Option<Step>, Stopped>, PlanError> {
    let own: Vec<Part> = sub.iter().map(|&k| parts[k].clone()).collect();
    let regions = match BlockingRegions::compute_with(&own, progress) {
        Ok(r) => r,
        Err(PlanError::Stopped { .. }) => return Ok(Err(Stopped)),
        Err(e) => return Err(e),
    };
    let local = SequenceOptions {
        base: opts.base.and_then(|b| sub.iter().position(|&k| k == b)),
        tolerance: false,
        keep_solutions: super::KeepSolutions::Nothing,
        ..opts.clone()
    };
    let all: Vec<usize> = (0..sub.len()).collect();
    Ok(
        best_step_with(&regions, &all, &local, false, progress).map(|found| {
            found.map(|mut step| {
                let global = |s: &[usize]| -> Vec<usize> { s.iter().map(|&k| sub[k]).collect() };
                step.subassembly = global(&step.subassembly);
                step.moving = global(&step.moving);
                if let Some(r) = step.choice.runner_up.as_mut() {
                    r.moving = global(&r.moving);
                }
                step.rule = super::Rule::Full;
                step
            })
        }),
    )
}
