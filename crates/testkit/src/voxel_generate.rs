//! Voxel interlocking puzzles of a chosen level, found by hill climbing on the level
//! that [`crate::voxel_puzzles::level`] computes, and their boundary meshes.
//!
//! Random partitions of a box come apart in one move, so [`puzzle_of_level`] starts from
//! one and changes it a cell at a time: a cell passes from a piece to a neighbouring
//! piece, or a piece gives up a cell to the void or takes an empty neighbour cell (at most
//! a fifth of the box empty), keeping every piece face-connected, at least two cells and
//! a 2-manifold solid (no two of its cubes meeting only along an edge or at a corner). A
//! change is kept when the puzzle still comes apart and its level (moves of any number
//! of steps) does not drop, nor, at the same level, the number of separating moves from
//! the states one move short of it rise (fewer ways out lead to longer ones); it stops
//! at the first puzzle of the target level or more. Everything is deterministic from the
//! seed. Measured (`write_voxel_puzzles --survey`: 8 seeds, 100 000 changes, aiming at
//! 12, release build): 4×4×4 with 4 pieces reaches levels 5 to 9 (about 3 s a seed),
//! with 5 pieces 5 to 10; 5×5×5 with 6 pieces 6 to 13 (about 4 s); 6×6×6 with 6 pieces
//! 3 to 13 and with 8 pieces 5 to 12 (8 to 15 s) — some seeds stall, so callers try
//! several.
//!
//! The level counts the first separation only, and a climbed puzzle often leaves its
//! remaining pieces interlocked once the first group has gone, so a planner's plan stops
//! there. [`complete_puzzle_of_level`] (and [`climb_with`]) keep only puzzles that come
//! apart completely ([`disassembles_completely`]: some, or every, shortest first
//! separation leaves two groups that separate again from where their pieces are,
//! recursively). With `Separations::Every` the climb is hardly slower and reaches about
//! as high (`write_voxel_puzzles --survey-complete`, release, two seeds at a time):
//! 4×4×4 with 4 pieces, 6 seeds of 100 000 changes aiming at 12: levels 7 to 10 (30 s);
//! with 5 pieces 5 to 8 (46 s); 5×5×5 with 6 pieces, 4 seeds of 50 000: 8 to 12
//! (17 s); with 7 pieces, 2 seeds of 30 000: 8 and 9; 6×6×6 with 8 pieces: 13 and 5.

use crate::solids::{rectilinear, IntMesh, Lcg};
use crate::voxel_puzzles::{
    disassembles_completely, level_and_exits, random_puzzle, Cell, Separations,
};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::Path;

const FACES: [Cell; 6] = [
    [1, 0, 0],
    [-1, 0, 0],
    [0, 1, 0],
    [0, -1, 0],
    [0, 0, 1],
    [0, 0, -1],
];

/// A puzzle of `count` pieces in the box `dims` (cells `0..dims[a]`) whose level is at
/// least `target_level`, with that level, from `seed`, trying at most `budget` changes;
/// `None` when the budget runs out first.
pub fn puzzle_of_level(
    dims: [i64; 3],
    count: usize,
    target_level: usize,
    seed: u64,
    budget: usize,
) -> Option<(Vec<Vec<Cell>>, usize)> {
    climb(dims, count, target_level, seed, budget).filter(|(_, l)| *l >= target_level)
}

/// The climb of [`puzzle_of_level`]: the puzzle it ends with (at `target_level` or
/// when the budget runs out) and its level; `None` only when no admissible starting
/// partition was found (pieces too small for the box).
pub fn climb(
    dims: [i64; 3],
    count: usize,
    target_level: usize,
    seed: u64,
    budget: usize,
) -> Option<(Vec<Vec<Cell>>, usize)> {
    climb_with(dims, count, target_level, seed, budget, None)
}

/// [`puzzle_of_level`] for puzzles that come apart completely
/// ([`disassembles_completely`] in the sense of `which`): the climb keeps only such
/// puzzles (the starting partition too), so every step is one.
pub fn complete_puzzle_of_level(
    dims: [i64; 3],
    count: usize,
    target_level: usize,
    seed: u64,
    budget: usize,
    which: Separations,
) -> Option<(Vec<Vec<Cell>>, usize)> {
    climb_with(dims, count, target_level, seed, budget, Some(which))
        .filter(|(_, l)| *l >= target_level)
}

/// The climb of [`climb`], keeping only puzzles that come apart completely when
/// `complete` says in which sense.
pub fn climb_with(
    dims: [i64; 3],
    count: usize,
    target_level: usize,
    seed: u64,
    budget: usize,
    complete: Option<Separations>,
) -> Option<(Vec<Vec<Cell>>, usize)> {
    let mut rng = Lcg(seed ^ 0x9e37_79b9_7f4a_7c15);
    let cells = (dims[0] * dims[1] * dims[2]) as usize;
    let max_void = cells / 5;
    let index = |c: Cell| ((c[0] * dims[1] + c[1]) * dims[2] + c[2]) as usize;
    let inside = |c: Cell| (0..3).all(|a| c[a] >= 0 && c[a] < dims[a]);
    // A starting partition whose pieces are all admissible.
    let mut owner: Vec<Option<usize>> = vec![None; cells];
    let mut tries = 0u64;
    loop {
        let p = random_puzzle(dims, count, seed.wrapping_mul(1000).wrapping_add(tries));
        tries += 1;
        if p.iter().all(|c| c.len() >= 2 && manifold(c))
            && complete.is_none_or(|which| disassembles_completely(&p, 200_000, which))
        {
            for (i, piece) in p.iter().enumerate() {
                for c in piece {
                    owner[index(*c)] = Some(i);
                }
            }
            break;
        }
        if tries > 1000 {
            return None;
        }
    }
    let all: Vec<Cell> = (0..dims[0])
        .flat_map(|x| (0..dims[1]).flat_map(move |y| (0..dims[2]).map(move |z| [x, y, z])))
        .collect();
    let pieces_of = |owner: &[Option<usize>]| -> Vec<Vec<Cell>> {
        let mut p = vec![Vec::new(); count];
        for c in &all {
            if let Some(i) = owner[index(*c)] {
                p[i].push(*c);
            }
        }
        p
    };
    // Higher levels first, then fewer ways out at that level.
    let score = |p: &[Vec<Cell>]| {
        let found = level_and_exits(p, 200_000).map(|(l, e)| (l, -(e as i64)))?;
        match complete {
            Some(which) if !disassembles_completely(p, 200_000, which) => None,
            _ => Some(found),
        }
    };
    let mut current = score(&pieces_of(&owner))?;
    for _ in 0..budget {
        if current.0 >= target_level {
            break;
        }
        let c = all[rng.below(all.len() as u64) as usize];
        let d = FACES[rng.below(6) as usize];
        let q = [c[0] + d[0], c[1] + d[1], c[2] + d[2]];
        let mut next = owner.clone();
        // Either the owner of `c` takes the cell `q`, or `c` becomes empty.
        let Some(taker) = owner[index(c)] else {
            continue;
        };
        let voids = owner.iter().filter(|o| o.is_none()).count();
        let changed: Vec<usize>;
        if inside(q) && rng.below(4) != 0 {
            let giver = owner[index(q)];
            if giver == Some(taker) || (giver.is_none() && voids == 0) {
                continue;
            }
            next[index(q)] = Some(taker);
            changed = [Some(taker), giver].into_iter().flatten().collect();
        } else {
            if voids >= max_void {
                continue;
            }
            next[index(c)] = None;
            changed = vec![taker];
        }
        let p = pieces_of(&next);
        if changed
            .iter()
            .any(|&i| p[i].len() < 2 || !connected(&p[i]) || !manifold(&p[i]))
        {
            continue;
        }
        if let Some(l) = score(&p) {
            if l >= current {
                current = l;
                owner = next;
            }
        }
    }
    Some((pieces_of(&owner), current.0))
}

/// The cells are face-connected (and there is at least one).
pub fn connected(cells: &[Cell]) -> bool {
    let Some(&first) = cells.first() else {
        return false;
    };
    let set: std::collections::HashSet<Cell> = cells.iter().copied().collect();
    let mut seen = std::collections::HashSet::from([first]);
    let mut stack = vec![first];
    while let Some(c) = stack.pop() {
        for d in FACES {
            let q = [c[0] + d[0], c[1] + d[1], c[2] + d[2]];
            if set.contains(&q) && seen.insert(q) {
                stack.push(q);
            }
        }
    }
    seen.len() == set.len()
}

/// The union of the cells is a 2-manifold solid: around every grid edge the four cells
/// are not two diagonal ones alone, and around every grid vertex the eight cells in and
/// the eight out are each face-connected (or empty).
pub fn manifold(cells: &[Cell]) -> bool {
    let set: std::collections::HashSet<Cell> = cells.iter().copied().collect();
    let mut vertices: Vec<Cell> = cells
        .iter()
        .flat_map(|c| (0..8).map(move |b| [0, 1, 2].map(|k| c[k] + (b >> k & 1))))
        .collect();
    vertices.sort_unstable();
    vertices.dedup();
    vertices.iter().all(|v| {
        // Cell `b` of the 2×2×2 block around `v` has its minimum corner at v − 1 + bits.
        let full: [bool; 8] = std::array::from_fn(|b| {
            set.contains(&[0, 1, 2].map(|k| v[k] - 1 + (b as i64 >> k & 1)))
        });
        [true, false].iter().all(|&side| {
            let members: Vec<usize> = (0..8).filter(|&b| full[b] == side).collect();
            let Some(&first) = members.first() else {
                return true;
            };
            let mut seen = 1u8 << first;
            let mut stack = vec![first];
            while let Some(b) = stack.pop() {
                for k in 0..3 {
                    let o = b ^ (1 << k);
                    if full[o] == side && seen >> o & 1 == 0 {
                        seen |= 1 << o;
                        stack.push(o);
                    }
                }
            }
            seen.count_ones() as usize == members.len()
        })
    })
}

/// The boundary of one piece: two outward triangles per unit square between a cell of
/// the piece and a cell outside it, coordinates scaled by `scale`.
pub fn piece_mesh(cells: &[Cell], scale: i64) -> IntMesh {
    let lo = [0, 1, 2].map(|a| cells.iter().map(|c| c[a]).min().unwrap_or(0));
    let hi = [0, 1, 2].map(|a| cells.iter().map(|c| c[a]).max().unwrap_or(0) + 1);
    let set: std::collections::HashSet<Cell> = cells.iter().copied().collect();
    let axis = |a: usize| (lo[a]..=hi[a]).map(|v| v * scale).collect::<Vec<_>>();
    let (xs, ys, zs) = (axis(0), axis(1), axis(2));
    rectilinear([&xs, &ys, &zs], |i| {
        set.contains(&[0, 1, 2].map(|a| lo[a] + i[a] as i64))
    })
}

/// Writes a voxel puzzle as an assembly folder: `piece_<i>.off` for each piece (its
/// [`piece_mesh`]) and an `assembly.json` naming them, creating the folder.
pub fn write_puzzle(
    dir: &Path,
    name: &str,
    pieces: &[Vec<Cell>],
    scale: i64,
) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let mut json = format!("{{\n  \"name\": \"{name}\",\n  \"parts\": [\n");
    for (i, p) in pieces.iter().enumerate() {
        std::fs::write(
            dir.join(format!("piece_{i}.off")),
            piece_mesh(p, scale).off_text(),
        )?;
        let comma = if i + 1 < pieces.len() { "," } else { "" };
        let _ = writeln!(
            json,
            "    {{\"name\": \"piece_{i}\", \"mesh\": \"piece_{i}.off\"}}{comma}"
        );
    }
    json.push_str("  ]\n}\n");
    std::fs::write(dir.join("assembly.json"), json)
}

/// The pieces' cells as text, one layer of the box per block (`z` upwards), each cell
/// the piece's index (`.` empty), for READMEs and messages.
pub fn layers_text(pieces: &[Vec<Cell>]) -> String {
    let owner: HashMap<Cell, usize> = pieces
        .iter()
        .enumerate()
        .flat_map(|(i, p)| p.iter().map(move |c| (*c, i)))
        .collect();
    let lo = [0, 1, 2].map(|a| owner.keys().map(|c| c[a]).min().unwrap_or(0));
    let hi = [0, 1, 2].map(|a| owner.keys().map(|c| c[a]).max().unwrap_or(0));
    let mut s = String::new();
    for z in lo[2]..=hi[2] {
        let _ = writeln!(s, "z = {z}:");
        for y in (lo[1]..=hi[1]).rev() {
            for x in lo[0]..=hi[0] {
                match owner.get(&[x, y, z]) {
                    Some(i) => {
                        let _ = write!(s, "{i}");
                    }
                    None => s.push('.'),
                }
            }
            s.push('\n');
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::voxel_puzzles::{level, replay, solve, Level, Move, Steps};

    fn check_pieces(p: &[Vec<Cell>], dims: [i64; 3], count: usize) {
        assert_eq!(p.len(), count);
        let mut all: Vec<Cell> = p.iter().flatten().copied().collect();
        let cells = all.len();
        all.sort_unstable();
        all.dedup();
        assert_eq!(all.len(), cells, "pieces are disjoint");
        assert!(all
            .iter()
            .all(|c| (0..3).all(|a| c[a] >= 0 && c[a] < dims[a])));
        assert!(
            5 * cells >= 4 * (dims[0] * dims[1] * dims[2]) as usize,
            "mostly full"
        );
        for piece in p {
            assert!(piece.len() >= 2 && connected(piece) && manifold(piece));
        }
    }

    #[test]
    fn generated_puzzles_have_the_level_they_claim() {
        let dims = [4, 4, 3];
        let mut levels = Vec::new();
        for seed in 0..3 {
            let Some((p, l)) = puzzle_of_level(dims, 4, 3, seed, 20_000) else {
                continue;
            };
            check_pieces(&p, dims, 4);
            assert!(l >= 3);
            assert_eq!(level(&p, Steps::Any, 1_000_000), Level::Moves(l));
            let (again, plan) = solve(&p, Steps::Any, 1_000_000);
            assert_eq!(again, Level::Moves(l));
            let plan = plan.expect("a plan");
            assert_eq!(plan.len(), l);
            assert!(replay(&p, &plan), "seed {seed}: {plan:?}");
            // Unit steps never do better, and their plan moves one cell at a time.
            let (one, unit_plan) = solve(&p, Steps::One, 1_000_000);
            if let Level::Moves(one) = one {
                assert!(one >= l);
                let unit_plan = unit_plan.expect("a plan");
                assert_eq!(unit_plan.len(), one);
                assert!(unit_plan[..one - 1].iter().all(|m| m.steps == Some(1)));
                assert!(replay(&p, &unit_plan));
            }
            levels.push(l);
        }
        assert!(!levels.is_empty(), "some seed reaches level 3");
    }

    #[test]
    fn complete_climbs_give_puzzles_that_come_apart_completely() {
        use crate::voxel_puzzles::{complete_plan, disassembles_completely, Separations};
        let dims = [4, 4, 3];
        let mut found = 0;
        for seed in 0..3 {
            let Some((p, l)) =
                complete_puzzle_of_level(dims, 4, 3, seed, 20_000, Separations::Every)
            else {
                continue;
            };
            check_pieces(&p, dims, 4);
            assert_eq!(level(&p, Steps::Any, 1_000_000), Level::Moves(l));
            assert!(disassembles_completely(&p, 1_000_000, Separations::Every));
            let stages = complete_plan(&p, 1_000_000).expect("a complete plan");
            assert_eq!(stages[0].plan.len(), l, "the first stage has the level");
            assert_eq!(stages.len(), 3, "four pieces, three splits");
            found += 1;
        }
        assert!(found > 0, "some seed reaches level 3");
    }

    #[test]
    fn a_plan_with_a_blocked_move_does_not_replay() {
        // The key in the L slot of the voxel_puzzles tests: rising first is blocked.
        let slot = [[1, 1, 1], [1, 2, 1], [1, 2, 2]];
        let frame: Vec<Cell> = (0..36)
            .map(|i| [i % 3, i / 3 % 4, i / 12])
            .filter(|c| !slot.contains(c))
            .collect();
        let p = vec![frame, vec![[1, 1, 1]]];
        let (l, plan) = solve(&p, Steps::Any, 1000);
        assert_eq!(l, Level::Moves(2));
        let plan = plan.unwrap();
        assert!(replay(&p, &plan));
        assert_eq!(plan[0].dir, [0, 1, 0]);
        let mut wrong = plan.clone();
        wrong.swap(0, 1);
        assert!(!replay(&p, &wrong));
        let rise = Move {
            pieces: vec![1],
            dir: [0, 0, 1],
            steps: None,
        };
        assert!(!replay(&p, &[rise]));
    }

    #[test]
    fn manifold_rejects_cubes_meeting_along_an_edge_or_a_corner() {
        assert!(manifold(&[[0, 0, 0], [1, 0, 0], [1, 1, 0]]));
        assert!(!manifold(&[[0, 0, 0], [1, 1, 0]]));
        assert!(!manifold(&[[0, 0, 0], [1, 1, 1]]));
        // An L of three with the fourth corner cube on top, touching one only along
        // an edge through the gap.
        assert!(!manifold(&[[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 1]]));
        assert!(connected(&[[0, 0, 0], [1, 0, 0], [1, 1, 0]]));
        assert!(!connected(&[[0, 0, 0], [1, 1, 0]]));
    }

    #[test]
    fn piece_meshes_are_closed_with_the_cells_volume() {
        let cells = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 1, 1]];
        let m = piece_mesh(&cells, 10);
        assert_eq!(m.volume6(), 6 * 4 * 1000);
        let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
        for t in &m.triangles {
            for k in 0..3 {
                *edges.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
            }
        }
        assert!(edges
            .iter()
            .all(|(&(a, b), &c)| c == 1 && edges.get(&(b, a)) == Some(&1)));
        // Boundary squares: 4 cubes × 6 faces − 2 × 3 shared faces = 18, 2 triangles each.
        assert_eq!(m.triangles.len(), 36);
    }
}
