//! How the sequence planner ranks the ways to split a subassembly, and why it chose one.
//!
//! A candidate is a moving set and a direction along which it is free. Candidates are
//! compared by these keys, in this order; the first key where two differ decides:
//!
//! 1. with `prefer_connected`: both sides stay connected through contacts;
//! 2. with `prefer_single`: a single part moves;
//! 3. with `prefer_axes`: the direction is ±x, ±y or ±z;
//! 4. the cell kind of the direction: a face (an open region of free directions) before
//!    an edge (a sliding arc) before a vertex (an isolated direction);
//! 5. the larger clearance (angular distance to the nearest blocked direction; 0 on
//!    edges and vertices);
//! 6. fewer moving parts;
//! 7. the lowest part indices, then the direction's coordinates (a fixed tie-break, so
//!    that plans are reproducible).

use super::SequenceOptions;
use crate::motion_space::{CellKind, MotionSpace};
use crate::partition::Solution;
use crate::regions::BlockingRegions;
use apart_kernel::Vec3;
use std::cmp::Reverse;

/// The ranking keys, in the order they are compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Criterion {
    /// Both sides stay connected through contacts (compared only with `prefer_connected`).
    Connected,
    /// A single part moves (compared only with `prefer_single`).
    Single,
    /// The direction is ±x, ±y or ±z (compared only with `prefer_axes`).
    Axis,
    /// A face before an edge before a vertex.
    Cell,
    /// The larger clearance.
    Clearance,
    /// Fewer moving parts.
    FewerParts,
    /// The lowest part indices, then the direction (a fixed tie-break).
    Order,
}

impl Criterion {
    /// The criterion's key in JSON answers (`"lost_on"`): `"fewer_parts"` and the like.
    pub fn key(self) -> &'static str {
        match self {
            Criterion::Connected => "connected",
            Criterion::Single => "single",
            Criterion::Axis => "axis",
            Criterion::Cell => "cell",
            Criterion::Clearance => "clearance",
            Criterion::FewerParts => "fewer_parts",
            Criterion::Order => "order",
        }
    }

    /// The criterion in words: "the axis preference (--prefer-axes)".
    pub fn describe(self) -> &'static str {
        match self {
            Criterion::Connected => "the preference for connected sides (--prefer-connected)",
            Criterion::Single => "the preference for single parts (--prefer-single)",
            Criterion::Axis => "the axis preference (--prefer-axes)",
            Criterion::Cell => "its cell kind (face before edge before vertex)",
            Criterion::Clearance => "its larger clearance",
            Criterion::FewerParts => "its fewer moving parts",
            Criterion::Order => "the tie-break (lowest part indices, then direction)",
        }
    }
}

/// A candidate's values of the ranking keys.
#[derive(Clone, Debug, PartialEq)]
pub struct Keys {
    /// Both sides connected through contacts; `None` when not asked
    /// (`prefer_connected` off: the contact search is skipped).
    pub connected: Option<bool>,
    /// A single part moves.
    pub single: bool,
    /// The direction is ±x, ±y or ±z.
    pub axis: bool,
    /// The kind of motion-space cell of the direction.
    pub cell: CellKind,
    /// Clearance in degrees (0 for edges and vertices).
    pub clearance_deg: f64,
    /// The number of moving parts.
    pub parts: usize,
}

/// The best candidate the chosen one beat.
#[derive(Clone, Debug, PartialEq)]
pub struct Rival {
    /// Its moving parts (global indices, sorted).
    pub moving: Vec<usize>,
    /// Its direction.
    pub direction: Vec3,
    /// Its keys.
    pub keys: Keys,
    /// The first key on which it lost.
    pub lost_on: Criterion,
}

/// Why a step was chosen: its keys, how many candidates were ranked, and the runner-up.
#[derive(Clone, Debug, PartialEq)]
pub struct Choice {
    /// The chosen candidate's keys.
    pub keys: Keys,
    /// Candidates ranked (distinct moving set and direction pairs), the chosen included;
    /// for a step [`sequence_first`](super::sequence_first) took along a likely
    /// direction (nothing ranked, no runner-up), the likely directions tried, its own
    /// included.
    pub candidates: usize,
    /// The best of the others; `None` when there was no other.
    pub runner_up: Option<Rival>,
}

/// The sort key of a candidate: smaller is better, compared component by component in
/// the order of [`Criterion`].
type SortKey = (
    bool,
    bool,
    bool,
    CellKind,
    Reverse<i64>,
    usize,
    Vec<usize>,
    [String; 3],
);

/// The preferred candidate with why it was chosen, and whether it misses a preference
/// for single or connected moves (only then can an edge or vertex not yet listed be
/// preferred to it).
pub(super) fn choose(
    regions: &BlockingRegions,
    ms: &MotionSpace,
    opts: &SequenceOptions,
    candidates: &[Solution],
) -> Option<(bool, Solution, Choice)> {
    let mut candidates: Vec<Solution> = candidates.to_vec();
    // The complement of a moving set moves the opposite way: needed when the base part
    // is in the minimal set.
    if opts.base.is_some() {
        let comp: Vec<Solution> = candidates
            .iter()
            .map(|s| Solution {
                moving: rest_of(ms, &s.moving),
                direction: s.direction.neg(),
                unit: s.unit.map(|x| -x),
                ..s.clone()
            })
            .collect();
        candidates.extend(comp);
    }
    candidates.retain(|s| opts.base.is_none_or(|b| !s.moving.contains(&b)));
    let mut ranked: Vec<(SortKey, Keys, Solution)> = candidates
        .into_iter()
        .map(|s| {
            let keys = keys_of(regions, ms, opts, &s);
            (sort_key(opts, &keys, &s), keys, s)
        })
        .collect();
    ranked.sort_by(|a, b| a.0.cmp(&b.0));
    // The same moving set and direction can come twice (a face's deep direction that
    // is also an axis): the best-ranked copy stays.
    let mut seen = std::collections::HashSet::new();
    ranked.retain(|(k, _, _)| seen.insert((k.6.clone(), k.7.clone())));
    let count = ranked.len();
    let mut it = ranked.into_iter();
    let (best_key, keys, best) = it.next()?;
    let runner_up = it.next().map(|(k, keys, s)| Rival {
        lost_on: first_difference(&best_key, &k),
        moving: s.moving,
        direction: s.direction,
        keys,
    });
    let missed = best_key.0 || best_key.1;
    Some((
        missed,
        best,
        Choice {
            keys,
            candidates: count,
            runner_up,
        },
    ))
}

/// The parts of `ms` not in `set`.
fn rest_of(ms: &MotionSpace, set: &[usize]) -> Vec<usize> {
    ms.parts()
        .iter()
        .copied()
        .filter(|k| !set.contains(k))
        .collect()
}

fn keys_of(
    regions: &BlockingRegions,
    ms: &MotionSpace,
    opts: &SequenceOptions,
    s: &Solution,
) -> Keys {
    // (Only computed when asked for: a contact search per candidate.)
    let connected = opts
        .prefer_connected
        .then(|| connected(regions, &s.moving) && connected(regions, &rest_of(ms, &s.moving)));
    Keys {
        connected,
        single: s.moving.len() == 1,
        axis: is_axis(&s.direction),
        cell: s.cell,
        clearance_deg: s.clearance_deg,
        parts: s.moving.len(),
    }
}

fn sort_key(opts: &SequenceOptions, k: &Keys, s: &Solution) -> SortKey {
    (
        opts.prefer_connected && k.connected == Some(false),
        opts.prefer_single && !k.single,
        opts.prefer_axes && !k.axis,
        k.cell,
        Reverse(ordered(k.clearance_deg)),
        k.parts,
        s.moving.clone(),
        s.direction.primitive().to_strings(),
    )
}

/// The first criterion on which `a` and `b` differ.
fn first_difference(a: &SortKey, b: &SortKey) -> Criterion {
    if a.0 != b.0 {
        Criterion::Connected
    } else if a.1 != b.1 {
        Criterion::Single
    } else if a.2 != b.2 {
        Criterion::Axis
    } else if a.3 != b.3 {
        Criterion::Cell
    } else if a.4 != b.4 {
        Criterion::Clearance
    } else if a.5 != b.5 {
        Criterion::FewerParts
    } else {
        Criterion::Order
    }
}

/// A float made totally ordered for sort keys (clearances are finite).
fn ordered(x: f64) -> i64 {
    (x * 1e9).round() as i64
}

/// True for the six directions ±x, ±y, ±z (any positive multiple).
pub(super) fn is_axis(d: &Vec3) -> bool {
    let c = d.primitive().to_strings();
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
