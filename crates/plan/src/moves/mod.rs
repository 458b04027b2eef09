//! Disassembly by several moves: plans of finite translations, exact and off the grid,
//! with the puzzle's level.
//!
//! # The move model
//!
//! A *move* translates a set of parts of one subassembly along a direction `d` by a
//! finite distance, or to infinity, without the interiors of a moving and a fixed part
//! meeting on the way (sliding contact is free). For parts `i` (moving) and `j` (fixed)
//! the relative offsets at which they overlap are the interiors of the sums
//! `b ⊕ (−a)` of their convex pieces (`obstacles`); a move follows a straight line in
//! that space, and every distance along it is an exact rational.
//!
//! From a state the search tries:
//! - **directions**: `±x, ±y, ±z`; each outward normal of a contact (a facet of an
//!   obstacle the state lies on) and each line where two contact planes meet, both
//!   ways. These hold every extreme direction of the locally free cone, which the
//!   contact planes bound. At the subassembly's first state, when none of them frees a
//!   set, every direction of [`crate::partition`] is tried as well, so that level 1 is
//!   exactly "`partition` finds a solution". With [`MoveOptions::axes`] only the axes.
//! - **moving sets**: sets not holding the subassembly's first part (moving a set
//!   along `d` is moving the rest along `−d`) that hold every part a member pushes on
//!   at once along `d`: all of them up to 13 parts, beyond that the closure of each part
//!   and the complement of what each part and the first one push.
//! - **distances**: to infinity when nothing is ever met; otherwise the farthest free
//!   distance, and on the way every distance where a contact between a moving and a
//!   fixed part begins or ends (the moving parts' relative offset enters or leaves an
//!   obstacle's closed set); the nearest 64 of them. Along an axis, also every multiple
//!   of the grid step along it ([`directions::lattice_steps`]: the cell size of a voxel
//!   puzzle) up to the farthest distance, when there are at most 64; so the model
//!   without `axes` holds every move of the model with it, and never needs more moves.
//!
//! The search is breadth-first over exact states (offsets relative to the first part,
//! with congruent parts interchangeable), so the plan has the fewest moves in this
//! model; on voxel puzzles with `axes` the model is exactly the breadth-first search
//! over subset moves by whole grid steps along the axes (BurrTools' notion of level).
//! Once a move to infinity splits the subassembly, both sides are planned the same way
//! from where they are.

pub mod directions;
pub mod obstacles;
pub mod search;

use crate::progress::Progress;
use crate::{Part, PlanError};
use apart_kernel::{Int, Rational, Vec3};
use apart_pieces::Polytope;
use obstacles::{pair_obstacles, PairObstacles};
use rayon::prelude::*;
use search::{LocalMove, Outcome, Search, State};
use std::collections::VecDeque;
use std::time::Instant;

/// Parts a plan of moves takes (moving sets are bit sets of one machine word).
pub const MAX_PARTS: usize = 64;

/// How to search for moves.
#[derive(Clone, Debug)]
pub struct MoveOptions {
    /// Only moves along `±x, ±y, ±z`.
    pub axes: bool,
    /// Moves allowed per subassembly, up to and including its move to infinity.
    pub max_moves: usize,
    /// States allowed per subassembly's search.
    pub max_states: usize,
    /// Congruent parts are interchangeable (states that differ by swapping them are one).
    pub symmetry: bool,
}

impl Default for MoveOptions {
    fn default() -> MoveOptions {
        MoveOptions {
            axes: false,
            max_moves: 200,
            max_states: 2_000_000,
            symmetry: true,
        }
    }
}

/// One move of a plan.
#[derive(Clone, Debug)]
pub struct Move {
    /// The subassembly it works on.
    pub subassembly: Vec<usize>,
    /// The parts that move.
    pub moving: Vec<usize>,
    /// A primitive integer direction.
    pub direction: Vec3,
    /// The direction as a unit vector.
    pub unit: [f64; 3],
    /// The translation is `distance × direction` (grid units); `None`: to infinity.
    pub distance: Option<Rational>,
    /// Offsets of the subassembly's parts from their assembled pose after the move
    /// (grid units; moves to infinity are not counted).
    pub offsets: Vec<(usize, [Rational; 3])>,
    /// The search it belongs to (an index into [`MovePlan::searches`]).
    pub search: usize,
}

/// How the search of one subassembly ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SearchEnd {
    /// Its first move to infinity was found.
    Separated,
    /// Every reachable state was explored: no plan exists in the move model.
    Interlocked,
    /// No plan within the move limit (every state within it explored).
    MoveLimit,
    /// Cut off by the state limit.
    StateLimit,
    /// Cut off by the stop flag (time, memory, interrupt).
    Stopped,
}

impl SearchEnd {
    /// Its name in answers.
    pub fn name(self) -> &'static str {
        match self {
            SearchEnd::Separated => "separated",
            SearchEnd::Interlocked => "interlocked",
            SearchEnd::MoveLimit => "move limit",
            SearchEnd::StateLimit => "state limit",
            SearchEnd::Stopped => "stopped",
        }
    }
}

/// The search of one subassembly.
#[derive(Clone, Debug)]
pub struct GroupSearch {
    /// Its parts.
    pub subassembly: Vec<usize>,
    /// Moves to its first move to infinity (when separated).
    pub moves: Option<usize>,
    /// States explored.
    pub states: usize,
    /// How it ended.
    pub end: SearchEnd,
}

/// A plan of moves.
#[derive(Clone, Debug)]
pub struct MovePlan {
    /// Part names.
    pub names: Vec<String>,
    /// Every move, subassembly after subassembly.
    pub moves: Vec<Move>,
    /// Moves up to and including the first move to infinity of the whole assembly
    /// (`None` when it was not separated).
    pub level: Option<usize>,
    /// Every subassembly's search, in order.
    pub searches: Vec<GroupSearch>,
    /// Every part came apart.
    pub complete: bool,
    /// The stop flag cut the plan short.
    pub stopped: bool,
    /// States explored over all searches.
    pub states_explored: usize,
    /// Seconds spent making the obstacles.
    pub obstacle_seconds: f64,
    /// Seconds spent searching.
    pub search_seconds: f64,
}

/// Plans the disassembly of `parts` by moves (see the module documentation).
pub fn disassemble(
    parts: &[Part],
    opts: &MoveOptions,
    progress: &Progress,
) -> Result<MovePlan, PlanError> {
    let t0 = Instant::now();
    let n = parts.len();
    if let Some((k, p)) = parts.iter().enumerate().find(|(_, p)| p.pieces.is_empty()) {
        return Err(PlanError::NoPieces {
            part: k,
            name: p.name.clone(),
        });
    }
    if n > MAX_PARTS {
        return Err(PlanError::TooManyParts {
            parts: n,
            limit: MAX_PARTS,
        });
    }
    let pairs: Vec<(usize, usize)> = (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .collect();
    let obstacles: Vec<PairObstacles> = pairs
        .par_iter()
        .map(|&(i, j)| pair_obstacles(&parts[i].pieces, &parts[j].pieces))
        .collect::<Result<_, _>>()?;
    let index = |i: usize, j: usize| i * n - i * (i + 1) / 2 + (j - i - 1);
    let all: Vec<&Polytope> = parts.iter().flat_map(|p| &p.pieces).collect();
    let steps = directions::lattice_steps(&all);
    let shapes: Vec<Shape> = parts.iter().map(shape).collect();
    let obstacle_seconds = t0.elapsed().as_secs_f64();

    let t1 = Instant::now();
    let mut plan = MovePlan {
        names: parts.iter().map(|p| p.name.clone()).collect(),
        moves: Vec::new(),
        level: None,
        searches: Vec::new(),
        complete: true,
        stopped: false,
        states_explored: 0,
        obstacle_seconds,
        search_seconds: 0.0,
    };
    let zero = || [0, 1, 2].map(|_| Rational::zero());
    let mut offsets: Vec<[Rational; 3]> = (0..n).map(|_| zero()).collect();
    let mut queue: VecDeque<Vec<usize>> = VecDeque::from([(0..n).collect::<Vec<_>>()]);
    while let Some(group) = queue.pop_front() {
        let m = group.len();
        if m < 2 {
            continue;
        }
        if plan.stopped {
            plan.complete = false;
            continue;
        }
        let mut local: Vec<Option<&PairObstacles>> = vec![None; m * m];
        for a in 0..m {
            for b in a + 1..m {
                local[a * m + b] = Some(&obstacles[index(group[a], group[b])]);
            }
        }
        let (classes, anchors) = symmetry(&group, &shapes, opts.symmetry);
        let search = Search {
            obstacles: local,
            m,
            axes_only: opts.axes,
            steps: steps.clone(),
            classes,
            anchors,
            max_moves: opts.max_moves,
            max_states: opts.max_states,
        };
        let start: State = group
            .iter()
            .map(|&g| apart_kernel::rational::sub(&offsets[g], &offsets[group[0]]))
            .collect();
        let mut extra = || {
            if opts.axes {
                return Vec::new();
            }
            partition_escapes(parts, &group, &offsets).unwrap_or_default()
        };
        let (outcome, states) = search.run(start, &mut extra, progress);
        plan.states_explored += states;
        let k = plan.searches.len();
        let (end, path) = match outcome {
            Outcome::Separated(path) => (SearchEnd::Separated, path),
            Outcome::Exhausted => (SearchEnd::Interlocked, Vec::new()),
            Outcome::MoveLimit => (SearchEnd::MoveLimit, Vec::new()),
            Outcome::StateLimit => (SearchEnd::StateLimit, Vec::new()),
            Outcome::Stopped => (SearchEnd::Stopped, Vec::new()),
        };
        plan.searches.push(GroupSearch {
            subassembly: group.clone(),
            moves: (!path.is_empty()).then_some(path.len()),
            states,
            end,
        });
        if end != SearchEnd::Separated {
            plan.complete = false;
            plan.stopped |= end == SearchEnd::Stopped;
            continue;
        }
        if k == 0 {
            plan.level = Some(path.len());
        }
        let mut gone = 0u64;
        for mv in path {
            let (moving, direction, distance) = present(&group, mv);
            let d: [Rational; 3] = [0, 1, 2].map(|c| Rational::from_int(direction.get(c)));
            if let Some(t) = &distance {
                for &g in &moving {
                    offsets[g] = [0, 1, 2].map(|c| &offsets[g][c] + &(&d[c] * t));
                }
            } else {
                gone = moving.iter().fold(0, |x, g| {
                    x | 1 << group.iter().position(|h| h == g).unwrap()
                });
            }
            plan.moves.push(Move {
                subassembly: group.clone(),
                unit: direction.unit_f64(),
                moving,
                direction,
                distance,
                offsets: group.iter().map(|&g| (g, offsets[g].clone())).collect(),
                search: k,
            });
        }
        let (out, stay): (Vec<usize>, Vec<usize>) = (0..m).partition(|&a| gone >> a & 1 == 1);
        queue.push_back(out.into_iter().map(|a| group[a]).collect());
        queue.push_back(stay.into_iter().map(|a| group[a]).collect());
    }
    plan.search_seconds = t1.elapsed().as_secs_f64();
    Ok(plan)
}

/// The global parts of a local set.
fn members(group: &[usize], set: u64) -> Vec<usize> {
    (0..group.len())
        .filter(|&a| set >> a & 1 == 1)
        .map(|a| group[a])
        .collect()
}

/// A local move as the plan states it: the smaller side moves (the set, or the rest
/// along the opposite direction).
fn present(group: &[usize], mv: LocalMove) -> (Vec<usize>, Vec3, Option<Rational>) {
    let m = group.len();
    let all = search::all_parts(m);
    let size = mv.moving.count_ones() as usize;
    if 2 * size > m {
        let rest = all & !mv.moving;
        return (members(group, rest), mv.direction.neg(), mv.distance);
    }
    (members(group, mv.moving), mv.direction, mv.distance)
}

/// A part's pieces as sorted vertex lists relative to its anchor, and the anchor.
type Shape = (Vec<Vec<[Rational; 3]>>, [Rational; 3]);

/// A part's pieces as sorted vertex lists relative to its least vertex (its anchor),
/// and that anchor: two parts with equal lists are translates of each other.
fn shape(part: &Part) -> Shape {
    let true_vertices = |p: &Polytope| -> Vec<[Rational; 3]> {
        let den = Rational::from_int(p.den().clone());
        p.vertices()
            .iter()
            .map(|v| [0, 1, 2].map(|k| &Rational::from_int(v.get(k)) / &den))
            .collect()
    };
    let pieces: Vec<Vec<[Rational; 3]>> = part.pieces.iter().map(true_vertices).collect();
    let anchor = pieces
        .iter()
        .flatten()
        .min()
        .cloned()
        .expect("a part has pieces");
    let mut rel: Vec<Vec<[Rational; 3]>> = pieces
        .into_iter()
        .map(|vs| {
            let mut vs: Vec<[Rational; 3]> = vs
                .iter()
                .map(|v| apart_kernel::rational::sub(v, &anchor))
                .collect();
            vs.sort();
            vs
        })
        .collect();
    rel.sort();
    (rel, anchor)
}

/// Classes of congruent parts of a subassembly (local indices; the first part's class
/// is left out, as the first part stays put) and every part's anchor.
fn symmetry(group: &[usize], shapes: &[Shape], on: bool) -> (Vec<Vec<usize>>, Vec<[Rational; 3]>) {
    let anchors = group.iter().map(|&g| shapes[g].1.clone()).collect();
    let mut classes: Vec<Vec<usize>> = Vec::new();
    if !on {
        return (classes, anchors);
    }
    let mut taken = vec![false; group.len()];
    for a in 0..group.len() {
        if taken[a] {
            continue;
        }
        let class: Vec<usize> = (a..group.len())
            .filter(|&b| !taken[b] && shapes[group[b]].0 == shapes[group[a]].0)
            .collect();
        for &b in &class {
            taken[b] = true;
        }
        if class.len() > 1 && a != 0 {
            classes.push(class);
        }
    }
    (classes, anchors)
}

/// The moves to infinity `partition` finds for a subassembly where it stands (each as
/// a set without the first part).
fn partition_escapes(
    parts: &[Part],
    group: &[usize],
    offsets: &[[Rational; 3]],
) -> Result<Vec<LocalMove>, PlanError> {
    let mut l = Int::ONE;
    for &g in group {
        for c in &offsets[g] {
            l = apart_kernel::int::lcm(&l, &c.denom());
        }
    }
    let lr = Rational::from_int(l.clone());
    let moved: Vec<Part> = group
        .iter()
        .map(|&g| {
            let t = Vec3::from_ints(offsets[g].clone().map(|c| (&c * &lr).numer()));
            let pieces = parts[g]
                .pieces
                .iter()
                .map(|p| p.rescaled(&l).with_den(p.den().clone()).translated(&t))
                .collect();
            Part::from_pieces(parts[g].name.clone(), pieces)
        })
        .collect();
    let found = crate::partition_pieces(&moved, &crate::Options::default())?;
    let m = group.len();
    let all = search::all_parts(m);
    Ok(found
        .solutions
        .iter()
        .map(|s| {
            let set = s.moving.iter().fold(0u64, |x, &a| x | 1 << a);
            let (moving, direction) = if set & 1 == 1 {
                (all & !set, s.direction.neg())
            } else {
                (set, s.direction.clone())
            };
            LocalMove {
                moving,
                direction,
                distance: None,
            }
        })
        .collect())
}
