//! Interlocking voxel puzzles and their level by brute force: the independent oracle for
//! planners of several moves.
//!
//! A puzzle is a set of pieces, each a set of unit cubes on the integer grid (cell
//! `[x, y, z]` is the cube `[x, x+1] × [y, y+1] × [z, z+1]`), with disjoint cells. A
//! *move* translates a non-empty proper subset of the pieces along one axis (±x, ±y, ±z)
//! by a whole number of steps without any cell of a moving piece meeting a cell of a
//! fixed one on the way (cells meet when equal; sliding along faces is free). A move
//! whose subset can go on along its axis for ever (no fixed cell ahead in the subset's
//! shadow) separates the puzzle. The **level** is the least number of moves up to and
//! including the first that separates, as BurrTools and the level-L interlocking puzzles
//! count it.
//!
//! [`level`] is a breadth-first search over the states (offsets of every piece
//! relative to piece 0, which never moves: moving a subset that holds piece 0 by `d` is
//! the same state as moving the other pieces by `-d`), with moves of any number of
//! steps (`Steps::Any`, the BurrTools notion) or of one step only (`Steps::One`). It is
//! exhaustive and exact: a puzzle whose search space is exhausted without a separating
//! move has no level.
//!
//! The search looks up, for each ordered pair of pieces, the table of relative offsets at
//! which they share a cell (computed once from the cells), so a state costs a few table
//! look-ups per subset and direction; the tests check it against the first, plain
//! version that hashes every cell of every state. [`solve`] also returns a witness plan,
//! and [`replay`] checks any plan with plain sets of cells.
//!
//! [`random_puzzle`] cuts a box of cells into pieces at random (seeded), for property
//! tests. Pieces grown at random come apart in one move (300 seeds of 4 pieces in a
//! 3×3×3 box: all level 1); [`crate::voxel_generate`] climbs to higher levels.

use crate::solids::Lcg;
use std::collections::HashMap;

/// A grid cell (the unit cube with this minimum corner).
pub type Cell = [i64; 3];

/// How far one move may go.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Steps {
    /// Any whole number of steps along the axis (the BurrTools notion of a move).
    Any,
    /// One step.
    One,
}

/// The level of a puzzle, or why the search has none.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Level {
    /// The least number of moves up to and including the first that separates.
    Moves(usize),
    /// Every reachable state was explored (this many) and none separates.
    Interlocked(usize),
    /// The search stopped at the state limit.
    Unknown,
}

const AXES: [[i64; 3]; 6] = [
    [1, 0, 0],
    [-1, 0, 0],
    [0, 1, 0],
    [0, -1, 0],
    [0, 0, 1],
    [0, 0, -1],
];

/// One move of a plan: the pieces that move (never piece 0, which the search holds
/// still), the axis direction, and how many steps (`None`: for ever, the separating move).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Move {
    /// Indices of the moving pieces, increasing.
    pub pieces: Vec<usize>,
    /// The direction, one of ±x, ±y, ±z.
    pub dir: Cell,
    /// Whole steps along `dir`, or `None` for the last move, which goes on for ever.
    pub steps: Option<i64>,
}

/// The level of `pieces` (at least two, cells disjoint), exploring at most `max_states`
/// states.
///
/// # Panics
/// With fewer than two pieces, or more than 16.
pub fn level(pieces: &[Vec<Cell>], steps: Steps, max_states: usize) -> Level {
    solve(pieces, steps, max_states).0
}

/// The level and, when there is one, a witness plan of that many moves found by the
/// same search: replaying it from the assembled puzzle, every move is free and the last
/// separates.
///
/// # Panics
/// With fewer than two pieces, or more than 16.
pub fn solve(pieces: &[Vec<Cell>], steps: Steps, max_states: usize) -> (Level, Option<Vec<Move>>) {
    let (level, plan, _) = search(pieces, steps, max_states, false, None);
    (level, plan)
}

/// The level (moves of any number of steps) and how many separating moves there are
/// from the states one move short of it (pairs of a state and a subset and direction
/// that can go on for ever): the fewer, the harder the last move is to find. `None`
/// without a level within `max_states` states.
pub fn level_and_exits(pieces: &[Vec<Cell>], max_states: usize) -> Option<(usize, usize)> {
    match search(pieces, Steps::Any, max_states, true, None) {
        (Level::Moves(l), _, exits) => Some((l, exits)),
        _ => None,
    }
}

/// The breadth-first search; with `count_exits`, it finishes the layer where the first
/// separating move was found and counts the separating moves from that layer, and
/// pushes each distinct pair of a state and a separating subset of that layer, with a
/// plan up to it, onto `last`.
fn search(
    pieces: &[Vec<Cell>],
    steps: Steps,
    max_states: usize,
    count_exits: bool,
    mut last: Option<&mut Vec<Exit>>,
) -> (Level, Option<Vec<Move>>, usize) {
    let n = pieces.len();
    assert!((2..=16).contains(&n), "2 to 16 pieces");
    let table = Collisions::new(pieces);
    let start: State = [[0; 3]; 16];
    let mut seen: HashMap<State, usize> = HashMap::from([(start, 0)]);
    // Every state found, with the index of the state it was reached from and the move.
    let mut states: Vec<(State, usize, u32, Cell, i64)> = vec![(start, 0, 0, [0; 3], 0)];
    let mut depth = vec![0usize];
    let mut head = 0;
    let mut found: Option<(usize, Vec<Move>)> = None;
    let mut exits = 0;
    while head < states.len() {
        if let Some((l, plan)) = &found {
            if depth[head] + 1 > *l {
                return (Level::Moves(*l), Some(plan.clone()), exits);
            }
        }
        let state = states[head].0;
        // Subsets without piece 0 (moving a subset with it is moving the rest back).
        for mask in (2u32..(1 << n) - 1).step_by(2) {
            for d in AXES {
                let mut k = 1;
                while table.fits(&state, n, mask, d, k) {
                    if table.escapes(&state, n, mask, d, k) {
                        exits += 1;
                        let path = || {
                            let mut plan = vec![mv(mask, n, d, None)];
                            let mut at = head;
                            while at != 0 {
                                let (_, from, m, dir, s) = states[at];
                                plan.push(mv(m, n, dir, Some(s)));
                                at = from;
                            }
                            plan.reverse();
                            plan
                        };
                        if let Some(last) = last.as_deref_mut() {
                            // A state's exits are pushed together.
                            let seen = last
                                .iter()
                                .rev()
                                .take_while(|e| e.state == head)
                                .any(|e| e.mask == mask);
                            if !seen {
                                last.push(Exit {
                                    state: head,
                                    mask,
                                    offsets: state[..n].iter().map(|o| o.map(i64::from)).collect(),
                                    plan: path(),
                                });
                            }
                        }
                        if found.is_none() {
                            found = Some((depth[head] + 1, path()));
                        }
                        if !count_exits {
                            let (l, plan) = found.expect("just found");
                            return (Level::Moves(l), Some(plan), exits);
                        }
                        break;
                    }
                    if found.is_some() {
                        // Only the separating moves of this last layer are still counted.
                        k += 1;
                        if steps == Steps::One {
                            break;
                        }
                        continue;
                    }
                    let mut next = state;
                    for (i, o) in next.iter_mut().enumerate().take(n) {
                        if mask >> i & 1 == 1 {
                            for a in 0..3 {
                                let v = i64::from(o[a]) + k * d[a];
                                o[a] = i16::try_from(v).expect("offsets fit in i16");
                            }
                        }
                    }
                    if let std::collections::hash_map::Entry::Vacant(e) = seen.entry(next) {
                        e.insert(states.len());
                        states.push((next, head, mask, d, k));
                        depth.push(depth[head] + 1);
                        if states.len() > max_states {
                            return (Level::Unknown, None, exits);
                        }
                    }
                    if steps == Steps::One {
                        break;
                    }
                    k += 1;
                }
            }
        }
        head += 1;
    }
    match found {
        Some((l, plan)) => (Level::Moves(l), Some(plan), exits),
        None => (Level::Interlocked(states.len()), None, exits),
    }
}

/// Replays `plan` on the assembled puzzle with plain sets of cells, independently of
/// the search: true when every finite move goes step by step without two pieces sharing
/// a cell, every move but the last is finite, and the last can go on for ever (its
/// pieces, pushed step by step past every other cell along its axis, never meet one).
pub fn replay(pieces: &[Vec<Cell>], plan: &[Move]) -> bool {
    let mut at: Vec<Vec<Cell>> = pieces.to_vec();
    let moves = plan.len();
    for (m, mv) in plan.iter().enumerate() {
        let last = m + 1 == moves;
        if last != mv.steps.is_none() || mv.pieces.is_empty() {
            return false;
        }
        let fixed: HashMap<Cell, usize> = at
            .iter()
            .enumerate()
            .filter(|(i, _)| !mv.pieces.contains(i))
            .flat_map(|(i, p)| p.iter().map(move |c| (*c, i)))
            .collect();
        // Every coordinate is within `reach` of 0, so the last move's pieces are past
        // every fixed cell along its axis after `2 reach + 1` steps.
        let reach = at
            .iter()
            .map(|p| {
                p.iter()
                    .flat_map(|c| c.iter().map(|v| v.abs()))
                    .max()
                    .unwrap_or(0)
            })
            .max()
            .unwrap_or(0);
        let steps = mv.steps.unwrap_or(2 * reach + 1);
        for k in 1..=steps {
            let clash = mv.pieces.iter().any(|&i| {
                at[i]
                    .iter()
                    .any(|c| fixed.contains_key(&[0, 1, 2].map(|a| c[a] + k * mv.dir[a])))
            });
            if clash {
                return false;
            }
        }
        for &i in &mv.pieces {
            for c in &mut at[i] {
                *c = [0, 1, 2].map(|a| c[a] + steps * mv.dir[a]);
            }
        }
    }
    moves > 0
}

/// Offsets of the pieces (piece 0 always at the origin; unused entries zero).
type State = [[i16; 3]; 16];

/// A separating move of the last layer: the index of the state it leaves from, the
/// subset that goes (bit `i`: piece `i`), every piece's offset in that state, and a
/// shortest plan ending with it.
struct Exit {
    state: usize,
    mask: u32,
    offsets: Vec<Cell>,
    plan: Vec<Move>,
}

/// Which of the shortest first separations complete disassembly asks about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Separations {
    /// Some shortest separation leaves two groups that come apart completely.
    Some,
    /// Every shortest separation does (whichever a planner picks, it can go on).
    Every,
}

/// One stage of a complete disassembly: the pieces of a group (indices into the whole
/// puzzle, placed where the earlier stages left them) and a shortest plan separating it
/// in two, its moves naming pieces of the whole puzzle (the group's first piece stays
/// put).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Stage {
    /// The group's pieces, increasing.
    pub group: Vec<usize>,
    /// The moves, the last going on for ever.
    pub plan: Vec<Move>,
}

/// A complete disassembly: a shortest first separation (so the first stage has the
/// puzzle's level), then recursively a shortest separation of each group from the
/// positions its pieces have after it (the group that left keeps its pieces' relative
/// offsets), down to single pieces; stages in depth-first order. `None` when no choice
/// among the shortest separations comes apart completely (or a search reaches
/// `max_states`).
pub fn complete_plan(pieces: &[Vec<Cell>], max_states: usize) -> Option<Vec<Stage>> {
    let ids: Vec<usize> = (0..pieces.len()).collect();
    let mut stages = Vec::new();
    let mut memo = HashMap::new();
    complete(
        pieces,
        &ids,
        max_states,
        Separations::Some,
        &mut memo,
        Some(&mut stages),
    )
    .then_some(stages)
}

/// Whether the puzzle comes apart completely: some (or every) shortest first separation
/// leaves two groups that, from their positions then, each come apart completely in
/// the same sense, recursively down to single pieces. False also when a search of a
/// group reaches `max_states`.
pub fn disassembles_completely(
    pieces: &[Vec<Cell>],
    max_states: usize,
    which: Separations,
) -> bool {
    let ids: Vec<usize> = (0..pieces.len()).collect();
    complete(pieces, &ids, max_states, which, &mut HashMap::new(), None)
}

/// The recursion of [`complete_plan`] and [`disassembles_completely`] on a group
/// `pieces` (placed) whose pieces are `ids` of the whole puzzle; `memo` remembers the
/// answer for groups already seen (cells moved so the group's least corner is 0).
fn complete(
    pieces: &[Vec<Cell>],
    ids: &[usize],
    max_states: usize,
    which: Separations,
    memo: &mut HashMap<Vec<Vec<Cell>>, bool>,
    mut stages: Option<&mut Vec<Stage>>,
) -> bool {
    if pieces.len() < 2 {
        return true;
    }
    let lo = [0, 1, 2].map(|a| pieces.iter().flatten().map(|c| c[a]).min().unwrap_or(0));
    let key: Vec<Vec<Cell>> = pieces
        .iter()
        .map(|p| p.iter().map(|c| [0, 1, 2].map(|a| c[a] - lo[a])).collect())
        .collect();
    if stages.is_none() {
        if let Some(&known) = memo.get(&key) {
            return known;
        }
    }
    let mut exits = Vec::new();
    let found = search(pieces, Steps::Any, max_states, true, Some(&mut exits)).0;
    let mut answer = matches!(found, Level::Moves(_)) && which == Separations::Every;
    if matches!(found, Level::Moves(_)) {
        for exit in &exits {
            // Each group from the state the separating move leaves.
            let mut ok = true;
            let mut sub_stages = Vec::new();
            for goes in [false, true] {
                let members: Vec<usize> = (0..pieces.len())
                    .filter(|&i| (exit.mask >> i & 1 == 1) == goes)
                    .collect();
                let placed: Vec<Vec<Cell>> = members
                    .iter()
                    .map(|&i| {
                        let o = exit.offsets[i];
                        pieces[i]
                            .iter()
                            .map(|c| [0, 1, 2].map(|a| c[a] + o[a]))
                            .collect()
                    })
                    .collect();
                let sub_ids: Vec<usize> = members.iter().map(|&i| ids[i]).collect();
                let out = stages.as_ref().map(|_| &mut sub_stages);
                if !complete(&placed, &sub_ids, max_states, which, memo, out) {
                    ok = false;
                    break;
                }
            }
            match which {
                Separations::Every if !ok => {
                    answer = false;
                    break;
                }
                Separations::Some if ok => {
                    answer = true;
                    if let Some(stages) = stages.as_deref_mut() {
                        let plan = exit
                            .plan
                            .iter()
                            .map(|m| Move {
                                pieces: m.pieces.iter().map(|&i| ids[i]).collect(),
                                dir: m.dir,
                                steps: m.steps,
                            })
                            .collect();
                        stages.push(Stage {
                            group: ids.to_vec(),
                            plan,
                        });
                        stages.append(&mut sub_stages);
                    }
                    break;
                }
                _ => {}
            }
        }
    }
    memo.insert(key, answer);
    answer
}

fn mv(mask: u32, n: usize, dir: Cell, steps: Option<i64>) -> Move {
    Move {
        pieces: (0..n).filter(|i| mask >> i & 1 == 1).collect(),
        dir,
        steps,
    }
}

/// For every ordered pair of pieces `(i, j)`, the relative offsets `o_i − o_j` at which
/// they share a cell: `{b − a : a ∈ P_i, b ∈ P_j}`, as a dense table over the cube
/// `[−e, e]³` (outside it no cells can meet).
struct Collisions {
    n: usize,
    e: i64,
    side: i64,
    meet: Vec<Vec<bool>>,
}

impl Collisions {
    fn new(pieces: &[Vec<Cell>]) -> Collisions {
        let n = pieces.len();
        let (lo, hi) = pieces
            .iter()
            .flatten()
            .flat_map(|c| c.iter().copied())
            .fold((i64::MAX, i64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
        let e = (hi - lo).max(0);
        let side = 2 * e + 1;
        let mut meet = vec![vec![false; (side * side * side) as usize]; n * n];
        for i in 0..n {
            for j in 0..n {
                for a in &pieces[i] {
                    for b in &pieces[j] {
                        let r = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
                        let idx = ((r[0] + e) * side + r[1] + e) * side + r[2] + e;
                        meet[i * n + j][idx as usize] = true;
                    }
                }
            }
        }
        Collisions { n, e, side, meet }
    }

    /// Pieces `i` and `j` share a cell when `o_i − o_j = r`.
    fn meets(&self, i: usize, j: usize, r: Cell) -> bool {
        let e = self.e;
        if r.iter().any(|v| v.abs() > e) {
            return false;
        }
        let idx = ((r[0] + e) * self.side + r[1] + e) * self.side + r[2] + e;
        self.meet[i * self.n + j][idx as usize]
    }

    /// The relative offset of moving piece `i` (moved by `k · d`) to fixed piece `j`.
    fn rel(state: &State, i: usize, j: usize, d: Cell, k: i64) -> Cell {
        [0, 1, 2].map(|a| i64::from(state[i][a]) + k * d[a] - i64::from(state[j][a]))
    }

    /// The pieces of `mask`, moved by `k · d`, meet no cell of the others (every
    /// intermediate step is free too, checked by the caller's increasing `k`).
    fn fits(&self, state: &State, n: usize, mask: u32, d: Cell, k: i64) -> bool {
        (0..n).filter(|i| mask >> i & 1 == 1).all(|i| {
            (0..n)
                .filter(|j| mask >> j & 1 == 0)
                .all(|j| !self.meets(i, j, Self::rel(state, i, j, d, k)))
        })
    }

    /// After `k` steps the subset can go on along `d` for ever: no pair meets at any
    /// later step (once the offset is past `e` along `d` it has left the table for good).
    fn escapes(&self, state: &State, n: usize, mask: u32, d: Cell, k: i64) -> bool {
        (0..n).filter(|i| mask >> i & 1 == 1).all(|i| {
            (0..n).filter(|j| mask >> j & 1 == 0).all(|j| {
                let mut r = Self::rel(state, i, j, d, k);
                // Step on until the offset is past the table along the axis.
                loop {
                    if self.meets(i, j, r) {
                        return false;
                    }
                    let along: i64 = (0..3).map(|a| r[a] * d[a]).sum();
                    if along > self.e {
                        return true;
                    }
                    r = [r[0] + d[0], r[1] + d[1], r[2] + d[2]];
                }
            })
        })
    }
}

/// A random puzzle: the box `dims` of cells cut into `count` pieces grown from random
/// seeds (each cell joins a neighbouring piece at random until all are taken), so the
/// pieces are face-connected and fill the box.
pub fn random_puzzle(dims: [i64; 3], count: usize, seed: u64) -> Vec<Vec<Cell>> {
    let mut rng = Lcg(seed);
    let cells: Vec<Cell> = (0..dims[0])
        .flat_map(|x| (0..dims[1]).flat_map(move |y| (0..dims[2]).map(move |z| [x, y, z])))
        .collect();
    let mut owner: HashMap<Cell, usize> = HashMap::new();
    let mut frontier: Vec<(Cell, usize)> = Vec::new();
    for i in 0..count {
        loop {
            let c = cells[(rng.next_bits() as usize) % cells.len()];
            if let std::collections::hash_map::Entry::Vacant(e) = owner.entry(c) {
                e.insert(i);
                frontier.push((c, i));
                break;
            }
        }
    }
    while owner.len() < cells.len() && !frontier.is_empty() {
        let k = (rng.next_bits() as usize) % frontier.len();
        let (c, i) = frontier[k];
        let free: Vec<Cell> = AXES
            .iter()
            .map(|d| [c[0] + d[0], c[1] + d[1], c[2] + d[2]])
            .filter(|q| (0..3).all(|a| q[a] >= 0 && q[a] < dims[a]) && !owner.contains_key(q))
            .collect();
        if free.is_empty() {
            frontier.swap_remove(k);
            continue;
        }
        let q = free[(rng.next_bits() as usize) % free.len()];
        owner.insert(q, i);
        frontier.push((q, i));
    }
    let mut pieces = vec![Vec::new(); count];
    for (c, i) in owner {
        pieces[i].push(c);
    }
    for p in &mut pieces {
        p.sort_unstable();
    }
    pieces
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::{HashSet, VecDeque};

    // The first, slow and plain version of the search (a hash map of occupied cells
    // per state), kept to check the table-driven one on random puzzles.
    fn naive_level(pieces: &[Vec<Cell>], steps: Steps, max_states: usize) -> Level {
        let n = pieces.len();
        assert!((2..=16).contains(&n), "2 to 16 pieces");
        let start: Vec<Cell> = vec![[0; 3]; n];
        let mut seen: HashSet<Vec<Cell>> = HashSet::from([start.clone()]);
        let mut queue = VecDeque::from([(start, 0usize)]);
        // Bounding extent: a subset that has moved past every other piece's cells is free.
        let span = pieces
            .iter()
            .flatten()
            .flat_map(|c| c.iter().copied())
            .fold((i64::MAX, i64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
        let reach = span.1 - span.0 + 2;
        while let Some((state, depth)) = queue.pop_front() {
            let occupied = occupancy(pieces, &state);
            // Subsets without piece 0 (moving a subset with it is moving the rest back).
            for mask in 1u32..(1 << n) - 1 {
                if mask & 1 == 1 {
                    continue;
                }
                for d in AXES {
                    let mut k = 1;
                    loop {
                        if !fits(pieces, &state, &occupied, mask, d, k) {
                            break;
                        }
                        if k > 2 * reach || escapes(pieces, &state, &occupied, mask, d, k) {
                            return Level::Moves(depth + 1);
                        }
                        let mut next = state.clone();
                        for (i, o) in next.iter_mut().enumerate() {
                            if mask >> i & 1 == 1 {
                                *o = [o[0] + k * d[0], o[1] + k * d[1], o[2] + k * d[2]];
                            }
                        }
                        if seen.insert(next.clone()) {
                            if seen.len() > max_states {
                                return Level::Unknown;
                            }
                            queue.push_back((next, depth + 1));
                        }
                        if steps == Steps::One {
                            break;
                        }
                        k += 1;
                    }
                }
            }
        }
        Level::Interlocked(seen.len())
    }

    /// Which piece holds each occupied cell in `state`.
    fn occupancy(pieces: &[Vec<Cell>], state: &[Cell]) -> HashMap<Cell, usize> {
        let mut m = HashMap::new();
        for (i, (p, o)) in pieces.iter().zip(state).enumerate() {
            for c in p {
                m.insert([c[0] + o[0], c[1] + o[1], c[2] + o[2]], i);
            }
        }
        m
    }

    /// The pieces of `mask`, moved by `k · d`, meet no cell of the others (and every
    /// intermediate step is free too, checked by the caller's increasing `k`).
    fn fits(
        pieces: &[Vec<Cell>],
        state: &[Cell],
        occupied: &HashMap<Cell, usize>,
        mask: u32,
        d: Cell,
        k: i64,
    ) -> bool {
        pieces.iter().zip(state).enumerate().all(|(i, (p, o))| {
            mask >> i & 1 == 0
                || p.iter().all(|c| {
                    let q = [
                        c[0] + o[0] + k * d[0],
                        c[1] + o[1] + k * d[1],
                        c[2] + o[2] + k * d[2],
                    ];
                    occupied.get(&q).is_none_or(|&j| mask >> j & 1 == 1)
                })
        })
    }

    /// No cell of another piece lies ahead of a moving cell (beyond `k` steps) along `d`:
    /// the subset can go on for ever.
    fn escapes(
        pieces: &[Vec<Cell>],
        state: &[Cell],
        occupied: &HashMap<Cell, usize>,
        mask: u32,
        d: Cell,
        k: i64,
    ) -> bool {
        let axis = d.iter().position(|&v| v != 0).expect("an axis");
        let sign = d[axis];
        pieces.iter().zip(state).enumerate().all(|(i, (p, o))| {
            mask >> i & 1 == 0
                || p.iter().all(|c| {
                    let q = [
                        c[0] + o[0] + k * d[0],
                        c[1] + o[1] + k * d[1],
                        c[2] + o[2] + k * d[2],
                    ];
                    !occupied.iter().any(|(r, &j)| {
                        mask >> j & 1 == 0
                            && (0..3).all(|a| a == axis || r[a] == q[a])
                            && (r[axis] - q[axis]) * sign > 0
                    })
                })
        })
    }

    #[test]
    fn the_table_search_agrees_with_the_plain_one_on_generated_puzzles() {
        let mut found = 0;
        for seed in 0..3 {
            if let Some((p, l)) =
                crate::voxel_generate::puzzle_of_level([4, 4, 3], 4, 3, seed, 20_000)
            {
                assert!(l >= 3);
                for steps in [Steps::Any, Steps::One] {
                    assert_eq!(level(&p, steps, 100_000), naive_level(&p, steps, 100_000));
                }
                found += 1;
            }
        }
        assert!(found > 0);
    }

    #[test]
    fn the_table_search_agrees_with_the_plain_one() {
        let mut levels = Vec::new();
        for seed in 0..60 {
            let p = random_puzzle([3, 3, 3], 3 + (seed % 3) as usize, seed);
            if p.iter().any(Vec::is_empty) {
                continue;
            }
            for steps in [Steps::Any, Steps::One] {
                let fast = level(&p, steps, 20_000);
                assert_eq!(
                    fast,
                    naive_level(&p, steps, 20_000),
                    "seed {seed} {steps:?}"
                );
                levels.push(fast);
            }
        }
        assert!(levels.len() > 60);
    }

    #[test]
    fn two_stacked_cubes_come_apart_in_one_move() {
        let p = vec![vec![[0, 0, 0]], vec![[0, 0, 1]]];
        assert_eq!(level(&p, Steps::Any, 1000), Level::Moves(1));
    }

    #[test]
    fn a_cube_in_a_closed_box_is_interlocked() {
        // A 3x3x3 shell around its centre cube.
        let shell: Vec<Cell> = (0..27)
            .map(|i| [i % 3, i / 3 % 3, i / 9])
            .filter(|c| *c != [1, 1, 1])
            .collect();
        let p = vec![shell, vec![[1, 1, 1]]];
        assert!(matches!(level(&p, Steps::Any, 1000), Level::Interlocked(_)));
    }

    #[test]
    fn a_key_in_an_l_slot_needs_two_moves() {
        // A frame, the box [0,3)x[0,4)x[0,3) of cells less an L-shaped slot
        // {(1,1,1), (1,2,1), (1,2,2)}, holds a key at (1,1,1): it cannot rise ((1,1,2)
        // is frame), sink or leave sideways; it slides to (1,2,1), then rises out.
        let slot = [[1, 1, 1], [1, 2, 1], [1, 2, 2]];
        let frame: Vec<Cell> = (0..36)
            .map(|i| [i % 3, i / 3 % 4, i / 12])
            .filter(|c| !slot.contains(c))
            .collect();
        let p = vec![frame, vec![[1, 1, 1]]];
        assert_eq!(level(&p, Steps::Any, 1000), Level::Moves(2));
        assert_eq!(level(&p, Steps::One, 1000), Level::Moves(2));
    }

    /// Replays the stages of a complete plan, each on its group where the earlier
    /// stages left it, and checks that they split the puzzle down to single pieces.
    fn replay_stages(pieces: &[Vec<Cell>], stages: &[Stage]) {
        let mut at = pieces.to_vec();
        let mut groups = vec![(0..pieces.len()).collect::<Vec<_>>()];
        for stage in stages {
            let k = groups
                .iter()
                .position(|g| *g == stage.group)
                .expect("a group");
            let group = groups.remove(k);
            let local: Vec<Vec<Cell>> = group.iter().map(|&i| at[i].clone()).collect();
            let plan: Vec<Move> = stage
                .plan
                .iter()
                .map(|m| Move {
                    pieces: m
                        .pieces
                        .iter()
                        .map(|i| group.binary_search(i).unwrap())
                        .collect(),
                    dir: m.dir,
                    steps: m.steps,
                })
                .collect();
            assert!(replay(&local, &plan), "{stage:?}");
            for m in &plan {
                for &i in &m.pieces {
                    for c in &mut at[group[i]] {
                        *c = [0, 1, 2].map(|a| c[a] + m.steps.unwrap_or(0) * m.dir[a]);
                    }
                }
            }
            let goes = &stage.plan.last().unwrap().pieces;
            let (a, b): (Vec<usize>, Vec<usize>) = group.iter().partition(|i| goes.contains(i));
            groups.extend([a, b].into_iter().filter(|g| g.len() > 1));
        }
        assert!(groups.is_empty(), "left together: {groups:?}");
    }

    #[test]
    fn a_stack_of_slabs_and_a_key_in_a_slot_come_apart_completely() {
        let slabs: Vec<Vec<Cell>> = (0..3)
            .map(|z| (0..9).map(|i| [i % 3, i / 3, z]).collect())
            .collect();
        let stages = complete_plan(&slabs, 10_000).expect("complete");
        assert_eq!(stages.len(), 2);
        replay_stages(&slabs, &stages);
        for which in [Separations::Some, Separations::Every] {
            assert!(disassembles_completely(&slabs, 10_000, which));
        }
        // The key in the L slot, with a loose cube on the frame: the first stage has the
        // level, 2 moves.
        let slot = [[1, 1, 1], [1, 2, 1], [1, 2, 2]];
        let frame: Vec<Cell> = (0..36)
            .map(|i| [i % 3, i / 3 % 4, i / 12])
            .filter(|c| !slot.contains(c))
            .collect();
        let p = vec![frame, vec![[1, 1, 1]], vec![[0, 0, 3]]];
        let stages = complete_plan(&p, 10_000).expect("complete");
        assert_eq!(stages[0].plan.len(), 1, "the loose cube goes first");
        replay_stages(&p, &stages);
        assert_eq!(stages.iter().map(|s| s.plan.len()).sum::<usize>(), 3);
    }

    #[test]
    fn a_shell_left_around_its_cube_is_not_complete() {
        // The closed shell around its centre cube, and a loose cube beside it: the loose
        // cube slides away (level 1), but the rest stays interlocked.
        let shell: Vec<Cell> = (0..27)
            .map(|i| [i % 3, i / 3 % 3, i / 9])
            .filter(|c| *c != [1, 1, 1])
            .collect();
        let p = vec![shell, vec![[1, 1, 1]], vec![[3, 1, 1]]];
        assert_eq!(level(&p, Steps::Any, 10_000), Level::Moves(1));
        assert_eq!(complete_plan(&p, 10_000), None);
        for which in [Separations::Some, Separations::Every] {
            assert!(!disassembles_completely(&p, 10_000, which));
        }
    }

    #[test]
    fn unit_steps_never_need_fewer_moves_than_any_steps() {
        for seed in 0..30 {
            let p = random_puzzle([3, 3, 2], 3, seed);
            if p.iter().any(Vec::is_empty) {
                continue;
            }
            let any = level(&p, Steps::Any, 20_000);
            let one = level(&p, Steps::One, 20_000);
            if let (Level::Moves(a), Level::Moves(o)) = (&any, &one) {
                assert!(a <= o, "seed {seed}: {any:?} vs {one:?}");
            }
        }
    }

    #[test]
    fn random_puzzles_fill_their_box_with_disjoint_pieces() {
        let p = random_puzzle([4, 3, 2], 4, 7);
        let mut all: Vec<Cell> = p.iter().flatten().copied().collect();
        all.sort_unstable();
        all.dedup();
        assert_eq!(all.len(), 24);
        assert_eq!(p.iter().map(Vec::len).sum::<usize>(), 24);
    }
}
