//! The incremental sequence planner: steps whose cost follows what a step changes.
//!
//! Every step of [`sequence_with`](super::sequence_with) overlays the regions of every
//! pair of parts still present, though a step only removes the pairs of the parts that
//! left. This planner instead keeps, for each part, what frees it alone: the
//! complement of the union of its pair regions with the parts still beside it (its own
//! small overlay, a two-map motion space), and after a step recomputes only the parts
//! whose union used a part that left. Pair regions are made when first needed
//! ([`PairStore`]): those of parts whose boxes touch, and those of farther parts whose
//! box of sums projects outside the union found so far (a far part hides behind nearer
//! ones: [`crate::cull`]'s exact containment test, a round of the nearest such parts at
//! a time).
//!
//! The same is kept for each pair of touching parts (a rigid group of two: a pin in its
//! block), computed when no single part can leave along a face.
//!
//! A subassembly is split by the first rule that applies (see [`Rule`]):
//! 1. a single part free along a face (an open region of directions): the one of widest
//!    clearance (with `prefer_axes`, a part free along an axis first, moving along it);
//! 2. a pair of touching parts free along a face, the one of widest clearance;
//! 3. a set of parts along a likely direction (the axes, the axes of tessellated
//!    cylinders, the normals of touching planes: [`DirectionQuery::candidates_in`]) in
//!    a face: the first such direction, the smallest minimal moving set there;
//! 4. a single part, then a pair, along a sliding arc (edge) or an isolated direction
//!    (vertex): edges first, then the lowest part indices;
//! 5. a set of parts along the first likely direction that frees one at all;
//! 6. the full motion space of the subassembly, ranked as small subassemblies are
//!    ([`best_step`](super::best_step)): only now is a subassembly called interlocked.
//!
//! With `prefer_single`, single parts (rules 1 and 4) come first. Small subassemblies
//! (see [`Ranking::Auto`]) get the full ranking directly.

mod free_alone;

use super::rank::{self, Choice, Criterion, Keys, Rival};
use super::{best_step_with, part_tree::PartTree, Ranking, Rule, SequenceOptions, Step};
use crate::along::DirectionQuery;
use crate::motion_space::{CellKind, MotionSpace};
use crate::partition::Solution;
use crate::progress::{Progress, Stopped};
use crate::regions::{union_of_pruned, RegionStats};
use crate::store::PairStore;
use crate::PlanError;
use free_alone::{costly, everything, isolated, owned_union, single};
use rayon::prelude::*;
use rustc_hash::FxHashMap;
use std::cmp::Reverse;

/// Subassemblies of at most this many parts may get the full ranking directly
/// ([`Ranking::Auto`]).
pub const RANKED_PARTS: usize = 24;
/// ... when the piece pairs of all their part pairs are at most this many (every pair
/// region of the subassembly is made for the full ranking) ...
pub const RANKED_PIECE_PAIRS: usize = 20_000;
/// ... and their motion space would overlay at most this many arcs (the pair regions'
/// arcs and their antipodes, [`MotionSpace::estimate`]: the arrangement grows with
/// their crossings, about their square on dense assemblies).
pub const RANKED_ARCS: usize = 10_000;

/// Pairs of a moving part and a fixed one (global indices).
type Pairs = Vec<(usize, usize)>;

/// A group of one part `(i, NONE)` or two touching parts `(i, j)`, `i < j`.
type Group = (u32, u32);
const NONE: u32 = u32::MAX;

fn members(g: Group) -> Vec<usize> {
    if g.1 == NONE {
        vec![g.0 as usize]
    } else {
        vec![g.0 as usize, g.1 as usize]
    }
}

/// What frees a group alone within its subassembly.
#[derive(Clone, Debug)]
struct Single {
    /// The parts of the polygons of its union, none inside another (global indices,
    /// sorted): while they all stay in its subassembly, the union (which the other
    /// parts' polygons do not change), and this answer, stay the same.
    blockers: Vec<usize>,
    /// The parts whose boxes touch the group's (global indices, sorted): every part
    /// it may touch.
    touching: Vec<usize>,
    /// Its best motion (a face of widest clearance, else the first edge, else the first
    /// vertex), `None` when it is blocked everywhere.
    best: Option<Solution>,
    /// With `prefer_axes`, its best motion along an axis, if one is free.
    axis: Option<Solution>,
    /// Its answer may have changed (a blocker left).
    dirty: bool,
}

/// Counts of the incremental planner's work, for reports.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LocalStats {
    /// Parts whose free set alone was computed (recomputations included).
    pub singles: usize,
    /// Pairs of touching parts whose free set was computed (recomputations included).
    pub pairs: usize,
    /// Likely directions tested over a whole subassembly.
    pub likely_directions: usize,
    /// Steps by rule: ranked over the full motion space of a small subassembly, single
    /// part, likely direction, full search after the others found nothing.
    pub ranked: usize,
    /// Steps that moved a single part from its own free set.
    pub single_steps: usize,
    /// Steps that moved a pair of touching parts from their own free set.
    pub pair_steps: usize,
    /// Steps along a likely direction.
    pub likely_steps: usize,
    /// Subassemblies searched in full because no single part and no likely direction
    /// split them.
    pub full_searches: usize,
}

/// The planner's state across the steps of one plan.
pub(super) struct Planner<'a> {
    store: PairStore<'a>,
    query: DirectionQuery<'a>,
    opts: SequenceOptions,
    /// The free sets of groups, by group.
    groups: FxHashMap<Group, Single>,
    /// For each part `j`, groups whose [`Single::blockers`] held `j` when computed (may
    /// hold stale entries: marking one dirty again does no harm), and the groups holding
    /// it.
    used_by: Vec<Vec<Group>>,
    groups_of: Vec<Vec<Group>>,
    /// The subassembly each part is in (an id), and the box tree of each subassembly
    /// that has one.
    owner: Vec<u32>,
    next_id: u32,
    trees: FxHashMap<u32, PartTree>,
    pub(super) stats: LocalStats,
}

impl<'a> Planner<'a> {
    pub(super) fn new(
        parts: &'a [crate::regions::Part],
        opts: &SequenceOptions,
    ) -> Result<Planner<'a>, PlanError> {
        let n = parts.len();
        Ok(Planner {
            store: PairStore::new(parts)?,
            query: DirectionQuery::new(parts)?,
            opts: opts.clone(),
            groups: FxHashMap::default(),
            used_by: vec![Vec::new(); n],
            groups_of: vec![Vec::new(); n],
            owner: vec![0; n],
            next_id: 1,
            trees: FxHashMap::default(),
            stats: LocalStats::default(),
        })
    }

    /// Counts and times of the pair regions made so far.
    pub(super) fn region_stats(&self) -> RegionStats {
        self.store.stats()
    }

    /// The pair regions made so far.
    pub(super) fn regions_made(&self) -> usize {
        self.store.len()
    }

    /// The step splitting `sub` (global indices, increasing), `None` when it is
    /// interlocked; `keep`: the step keeps its solutions (only a ranked step has them).
    pub(super) fn step(
        &mut self,
        sub: &[usize],
        keep: bool,
        progress: &Progress,
    ) -> Result<Result<Option<Step>, Stopped>, PlanError> {
        let ranked = match self.opts.ranking {
            Ranking::Full => true,
            Ranking::Local => sub.len() <= 2,
            Ranking::Auto => match self.cheap(sub, progress) {
                Ok(c) => c,
                Err(PlanError::Stopped { .. }) => return Ok(Err(Stopped)),
                Err(e) => return Err(e),
            },
        };
        let found = if ranked {
            let r = self.ranked_step(sub, keep, progress)?;
            if matches!(r, Ok(Some(_))) {
                self.stats.ranked += 1;
            }
            r
        } else {
            self.local_step(sub, keep, progress)?
        };
        if let Ok(Some(step)) = &found {
            self.split(sub, &step.moving);
        }
        Ok(found)
    }

    /// Whether the full ranking of `sub` is cheap ([`Ranking::Auto`]): few parts, few
    /// piece pairs, and a small estimated motion space (its pair regions are made).
    fn cheap(&self, sub: &[usize], progress: &Progress) -> Result<bool, PlanError> {
        if sub.len() <= 2 {
            return Ok(true);
        }
        if sub.len() > RANKED_PARTS {
            return Ok(false);
        }
        let parts = self.store.parts();
        let pieces: Vec<usize> = sub.iter().map(|&k| parts[k].pieces.len()).collect();
        let total: usize = pieces.iter().sum();
        let squares: usize = pieces.iter().map(|p| p * p).sum();
        if (total * total - squares) / 2 > RANKED_PIECE_PAIRS {
            return Ok(false);
        }
        let regions = self.store.regions_of(sub, progress)?;
        let all: Vec<usize> = (0..sub.len()).collect();
        Ok(MotionSpace::estimate(&regions, &all).arcs <= RANKED_ARCS)
    }

    /// The ranked step of `sub` over its whole motion space (every pair region of `sub`
    /// made), after asking `progress` whether its estimated memory is affordable.
    fn ranked_step(
        &mut self,
        sub: &[usize],
        keep: bool,
        progress: &Progress,
    ) -> Result<Result<Option<Step>, Stopped>, PlanError> {
        let regions = match self.store.regions_of(sub, progress) {
            Ok(r) => r,
            Err(PlanError::Stopped { .. }) => return Ok(Err(Stopped)),
            Err(e) => return Err(e),
        };
        let all: Vec<usize> = (0..sub.len()).collect();
        let estimate = MotionSpace::estimate(&regions, &all);
        if !progress.affordable(crate::progress::phases::MOTION_SPACE, estimate.bytes) {
            progress.request_stop();
            return Ok(Err(Stopped));
        }
        let local = SequenceOptions {
            base: self
                .opts
                .base
                .and_then(|b| sub.iter().position(|&k| k == b)),
            tolerance: false,
            ..self.opts.clone()
        };
        let global = |s: &[usize]| -> Vec<usize> { s.iter().map(|&k| sub[k]).collect() };
        Ok(
            best_step_with(&regions, &all, &local, keep, progress).map(|found| {
                found.map(|mut step| {
                    step.subassembly = global(&step.subassembly);
                    step.moving = global(&step.moving);
                    if let Some(r) = step.choice.runner_up.as_mut() {
                        r.moving = global(&r.moving);
                    }
                    if let Some(sols) = step.solutions.as_mut() {
                        for s in sols {
                            s.moving = global(&s.moving);
                        }
                    }
                    step.rule = Rule::Ranked;
                    step
                })
            }),
        )
    }

    /// The step of `sub` by the local rules (module docs).
    fn local_step(
        &mut self,
        sub: &[usize],
        keep: bool,
        progress: &Progress,
    ) -> Result<Result<Option<Step>, Stopped>, PlanError> {
        macro_rules! watch {
            ($e:expr) => {
                match $e {
                    Ok(x) => x,
                    Err(PlanError::Stopped { .. }) => return Ok(Err(Stopped)),
                    Err(e) => return Err(e),
                }
            };
        }
        let singles: Vec<Group> = sub
            .iter()
            .filter(|&&i| Some(i) != self.opts.base)
            .map(|&i| (i as u32, NONE))
            .collect();
        watch!(self.refresh(sub, &singles, progress));
        let singles = self.ranked(sub, &singles, progress);
        let prefer_axes = self.opts.prefer_axes;
        let face = |c: &Ranked| {
            c.top
                .first()
                .is_some_and(|(key, sol)| sol.cell == CellKind::Face || (prefer_axes && !key.0))
        };
        if face(&singles) || (self.opts.prefer_single && singles.count > 0) {
            self.stats.single_steps += 1;
            return Ok(Ok(Some(group_step(sub, &singles, Rule::Single))));
        }
        if progress.stopped() {
            return Ok(Err(Stopped));
        }
        let pairs = self.touching_pairs(sub);
        watch!(self.refresh(sub, &pairs, progress));
        let pairs = self.ranked(sub, &pairs, progress);
        if face(&pairs) {
            self.stats.pair_steps += 1;
            return Ok(Ok(Some(group_step(sub, &pairs, Rule::Pair))));
        }
        if progress.stopped() {
            return Ok(Err(Stopped));
        }
        // Sets of parts along likely directions: a face first.
        let likely = match self.likely(sub, progress)? {
            Err(Stopped) => return Ok(Err(Stopped)),
            Ok(l) => l,
        };
        if let Some(step) = likely.as_ref().filter(|s| s.cell == CellKind::Face) {
            self.stats.likely_steps += 1;
            return Ok(Ok(Some(step.clone())));
        }
        if singles.count > 0 {
            self.stats.single_steps += 1;
            return Ok(Ok(Some(group_step(sub, &singles, Rule::Single))));
        }
        if pairs.count > 0 {
            self.stats.pair_steps += 1;
            return Ok(Ok(Some(group_step(sub, &pairs, Rule::Pair))));
        }
        if let Some(step) = likely {
            self.stats.likely_steps += 1;
            return Ok(Ok(Some(step)));
        }
        // Nothing simpler: the full motion space decides, and says interlocked.
        self.stats.full_searches += 1;
        let r = self.ranked_step(sub, keep, progress)?;
        Ok(r.map(|found| {
            found.map(|step| Step {
                rule: Rule::Full,
                ..step
            })
        }))
    }

    /// The groups of `groups` that can leave, best first (with `prefer_connected`, the
    /// first whose staying side stays connected through contacts leads).
    fn ranked(&self, sub: &[usize], groups: &[Group], progress: &Progress) -> Ranked {
        let keyed = groups.iter().filter_map(|g| {
            let s = self.groups.get(g)?;
            let (axis, sol) = match (&s.axis, &s.best) {
                (Some(a), _) if self.opts.prefer_axes => (true, a),
                (_, Some(b)) => (false, b),
                _ => return None,
            };
            let key = (
                self.opts.prefer_axes && !axis,
                sol.cell,
                Reverse(ordered(sol.clearance_deg)),
                *g,
            );
            Some((key, sol))
        });
        if self.opts.prefer_connected {
            let mut all: Vec<(GroupKey, &Solution)> = keyed.collect();
            all.sort_by_key(|a| a.0);
            if let Some(k) = (0..all.len())
                .find(|&k| self.connected_without(sub, &members(all[k].0 .3), progress))
            {
                let chosen = all.remove(k);
                all.insert(0, chosen);
            }
            return Ranked {
                count: all.len(),
                top: all
                    .into_iter()
                    .take(2)
                    .map(|(k, s)| (k, s.clone()))
                    .collect(),
            };
        }
        // The best two in one pass (a step needs the best and the runner-up only).
        let mut count = 0;
        let mut top: Vec<(GroupKey, &Solution)> = Vec::with_capacity(3);
        for (key, sol) in keyed {
            count += 1;
            if top.len() < 2 || key < top[1].0 {
                top.push((key, sol));
                top.sort_by_key(|a| a.0);
                top.truncate(2);
            }
        }
        Ranked {
            count,
            top: top.into_iter().map(|(k, s)| (k, s.clone())).collect(),
        }
    }

    /// The pairs of touching parts of `sub` (neither the base), from the blockers of
    /// their single parts (which hold every part whose box touches theirs).
    fn touching_pairs(&self, sub: &[usize]) -> Vec<Group> {
        let id = self.owner[sub[0]];
        let mut out = Vec::new();
        for &i in sub {
            if Some(i) == self.opts.base {
                continue;
            }
            let Some(s) = self.groups.get(&(i as u32, NONE)) else {
                continue;
            };
            for &j in &s.touching {
                if j > i
                    && self.owner[j] == id
                    && Some(j) != self.opts.base
                    && self.store.contact(i, j) == Some(true)
                {
                    out.push((i as u32, j as u32));
                }
            }
        }
        out
    }

    /// The step along the likely directions of `sub`: the first direction in a face of
    /// the motion space that frees a subset, else the first that frees one at all;
    /// at it the smallest minimal moving set (the other side, the opposite way, when it
    /// holds the base).
    fn likely(
        &mut self,
        sub: &[usize],
        progress: &Progress,
    ) -> Result<Result<Option<Step>, Stopped>, PlanError> {
        let candidates = self.query.candidates_in(sub);
        let mut first: Option<Step> = None;
        for (tried, d) in candidates.iter().enumerate() {
            if progress.stopped() {
                return Ok(Err(Stopped));
            }
            self.stats.likely_directions += 1;
            let found = super::first::step_along(&self.query, sub, &self.opts, d)?;
            let Some(mut step) = found else {
                continue;
            };
            step.choice.candidates = tried + 1;
            step.rule = Rule::Likely;
            if step.cell == CellKind::Face {
                return Ok(Ok(Some(step)));
            }
            first.get_or_insert(step);
        }
        Ok(Ok(first))
    }

    /// Whether `sub` without `gone` stays connected through contacts (the pair regions
    /// of touching boxes are made for it).
    fn connected_without(&self, sub: &[usize], gone: &[usize], progress: &Progress) -> bool {
        let rest: Vec<usize> = sub.iter().copied().filter(|k| !gone.contains(k)).collect();
        if rest.len() <= 1 {
            return true;
        }
        let boxes = self.store.boxes();
        let tree = PartTree::new(rest.clone(), boxes);
        let at: FxHashMap<usize, usize> = rest.iter().enumerate().map(|(k, &p)| (p, k)).collect();
        let mut pairs = Vec::new();
        for &i in &rest {
            tree.query_by(&mut |b| b.overlaps(&boxes[i]), &mut |j| {
                if j > i {
                    pairs.push((i, j));
                }
            });
        }
        if self.store.ensure(&pairs, progress).is_err() {
            return false;
        }
        let mut parent: Vec<usize> = (0..rest.len()).collect();
        fn find(p: &mut [usize], mut x: usize) -> usize {
            while p[x] != x {
                p[x] = p[p[x]];
                x = p[x];
            }
            x
        }
        for (i, j) in pairs {
            if self.store.contact(i, j) == Some(true) {
                let (a, b) = (find(&mut parent, at[&i]), find(&mut parent, at[&j]));
                parent[a] = b;
            }
        }
        let root = find(&mut parent, 0);
        (0..rest.len()).all(|k| find(&mut parent, k) == root)
    }

    /// Makes the free set of every group of `groups` (all in `sub`) not known or dirty.
    fn refresh(
        &mut self,
        sub: &[usize],
        groups: &[Group],
        progress: &Progress,
    ) -> Result<(), PlanError> {
        let todo: Vec<Group> = groups
            .iter()
            .copied()
            .filter(|g| self.groups.get(g).is_none_or(|s| s.dirty))
            .collect();
        if todo.is_empty() {
            return Ok(());
        }
        let id = self.owner[sub[0]];
        let rebuild = self
            .trees
            .get(&id)
            .is_none_or(|t| t.len() != sub.len() || 2 * t.len() < t.built());
        if rebuild {
            self.trees
                .insert(id, PartTree::new(sub.to_vec(), self.store.boxes()));
        }
        let tree = &self.trees[&id];
        let boxes = self.store.boxes();
        // The pairs of a member and a part whose boxes touch first, all at once.
        let near: Vec<Vec<(usize, usize)>> = todo
            .par_iter()
            .map(|&g| {
                let m = members(g);
                let mut out = Vec::new();
                for &i in &m {
                    tree.query_by(&mut |b| b.overlaps(&boxes[i]), &mut |j| {
                        if !m.contains(&j) {
                            out.push((i, j));
                        }
                    });
                }
                out.sort_unstable();
                out
            })
            .collect();
        let store = &self.store;
        let cheap: Vec<(usize, usize)> = near
            .iter()
            .flatten()
            .copied()
            .filter(|&(i, j)| !costly(store, i, j))
            .collect();
        store.ensure(&cheap, progress)?;
        // The costly pairs that a group needs whole: those of groups left with more than
        // isolated directions by their cheap pairs (the others test their few free
        // directions by rays instead).
        let whole: Vec<(usize, usize)> = todo
            .par_iter()
            .zip(&near)
            .flat_map_iter(|(_, near)| {
                let (cheap, costly): (Pairs, Pairs) = near
                    .iter()
                    .partition(|&&(i, j)| !costly(store, i, j) || store.get(i, j).is_some());
                if costly.is_empty() {
                    return Vec::new();
                }
                let (polygons, _) = owned_union(store, &cheap, Vec::new(), Vec::new());
                let map = union_of_pruned(&polygons);
                if everything(&map, &polygons) || isolated(&map, &polygons) {
                    Vec::new()
                } else {
                    costly
                }
            })
            .collect();
        store.ensure(&whole, progress)?;
        let (query, opts) = (&self.query, &self.opts);
        let found: Vec<Single> = todo
            .par_iter()
            .zip(near)
            .map(|(&g, near)| single(store, query, tree, &members(g), near, opts, progress))
            .collect::<Result<_, _>>()?;
        for (g, s) in todo.into_iter().zip(found) {
            if g.1 == NONE {
                self.stats.singles += 1;
            } else {
                self.stats.pairs += 1;
            }
            for &j in &s.blockers {
                self.used_by[j].push(g);
            }
            if self.groups.insert(g, s).is_none() {
                for i in members(g) {
                    self.groups_of[i].push(g);
                }
            }
        }
        Ok(())
    }

    /// Records that `moving` left `sub`: the two sides become subassemblies of their
    /// own, and the groups of each whose union used a part of the other are dirty.
    fn split(&mut self, sub: &[usize], moving: &[usize]) {
        let id = self.owner[sub[0]];
        let staying: Vec<usize> = sub
            .iter()
            .copied()
            .filter(|k| !moving.contains(k))
            .collect();
        // The smaller side gets a new id; the larger keeps the id and the box tree.
        let (small, large) = if moving.len() <= staying.len() {
            (moving.to_vec(), staying)
        } else {
            (staying, moving.to_vec())
        };
        let new = self.next_id;
        self.next_id += 1;
        for &k in &small {
            self.owner[k] = new;
        }
        if large.len() < 2 {
            self.trees.remove(&id);
        } else if let Some(t) = self.trees.get_mut(&id) {
            t.remove(&small);
        }
        let owner = &self.owner;
        let same = |g: Group| members(g).iter().all(|&k| owner[k] == owner[g.0 as usize]);
        // The larger side: groups whose union used a part of the smaller one.
        for &j in &small {
            for g in std::mem::take(&mut self.used_by[j]) {
                if owner[g.0 as usize] == id && same(g) {
                    if let Some(s) = self.groups.get_mut(&g) {
                        s.dirty = true;
                    }
                }
            }
        }
        // The smaller side: groups whose union used a part of the larger one; groups
        // across the two sides are gone.
        for &i in &small {
            for g in std::mem::take(&mut self.groups_of[i]) {
                if !same(g) {
                    self.groups.remove(&g);
                    continue;
                }
                if let Some(s) = self.groups.get_mut(&g) {
                    if s.blockers.iter().any(|&j| owner[j] != new) {
                        s.dirty = true;
                    }
                }
                self.groups_of[i].push(g);
            }
        }
    }
}

/// The groups that can leave a subassembly, ranked: how many, and the best two.
struct Ranked {
    count: usize,
    top: Vec<(GroupKey, Solution)>,
}

/// The step moving the best of the ranked groups `ranked` out of `sub`.
fn group_step(sub: &[usize], ranked: &Ranked, rule: Rule) -> Step {
    let (_, sol) = &ranked.top[0];
    let runner_up = ranked.top.get(1).map(|(_, s)| Rival {
        moving: s.moving.clone(),
        direction: s.direction.clone(),
        keys: keys_of(s),
        lost_on: first_difference(sol, s),
    });
    Step {
        subassembly: sub.to_vec(),
        moving: sol.moving.clone(),
        unit: sol.direction.unit_f64(),
        direction: sol.direction.clone(),
        cell: sol.cell,
        clearance_deg: sol.clearance_deg,
        depth: 0,
        tolerance: None,
        choice: Choice {
            keys: keys_of(sol),
            candidates: ranked.count,
            runner_up,
        },
        solutions: None,
        rule,
    }
}

/// The sort key of a group's motion: with `prefer_axes` a group free along an axis
/// first, then face before edge before vertex, then the larger clearance, then the
/// lower part indices.
type GroupKey = (bool, CellKind, Reverse<i64>, Group);

/// A float made totally ordered for sort keys (as the full ranking orders them).
fn ordered(x: f64) -> i64 {
    (x * 1e9).round() as i64
}

fn keys_of(s: &Solution) -> Keys {
    Keys {
        connected: None,
        single: s.moving.len() == 1,
        axis: rank::is_axis(&s.direction),
        cell: s.cell,
        clearance_deg: s.clearance_deg,
        parts: s.moving.len(),
    }
}

/// The first key on which the single motion `b` ranks after `a`.
fn first_difference(a: &Solution, b: &Solution) -> Criterion {
    if rank::is_axis(&a.direction) != rank::is_axis(&b.direction) {
        Criterion::Axis
    } else if a.cell != b.cell {
        Criterion::Cell
    } else if ordered(a.clearance_deg) != ordered(b.clearance_deg) {
        Criterion::Clearance
    } else {
        Criterion::Order
    }
}
