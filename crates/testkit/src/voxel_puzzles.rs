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
//! [`random_puzzle`] cuts a box of cells into pieces at random (seeded), for property
//! tests. Pieces grown at random come apart in one move (300 seeds of 4 pieces in a
//! 3×3×3 box: all level 1); puzzles of higher levels need a constructive generator.

use crate::solids::Lcg;
use std::collections::{HashMap, HashSet, VecDeque};

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

/// The level of `pieces` (at least two, cells disjoint), exploring at most `max_states`
/// states.
///
/// # Panics
/// With fewer than two pieces, or more than 16.
pub fn level(pieces: &[Vec<Cell>], steps: Steps, max_states: usize) -> Level {
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
