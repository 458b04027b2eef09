//! Plans of several moves against the brute-force voxel oracle and known cases.

use apart_pieces::Polytope;
use apart_plan::{disassemble, MoveOptions, Part, Progress, SearchEnd};
use apart_testkit::voxel_puzzles::{level, random_puzzle, Cell, Level, Steps};

/// Cells merged greedily into boxes (runs along x, rows along y, layers along z),
/// scaled by `s`.
fn boxes(cells: &[Cell], s: i64) -> Vec<Polytope> {
    let mut left: std::collections::BTreeSet<Cell> = cells.iter().copied().collect();
    let mut out = Vec::new();
    while let Some(&c) = left.iter().next() {
        let has = |l: &std::collections::BTreeSet<Cell>, lo: Cell, hi: Cell| {
            (lo[0]..hi[0])
                .all(|x| (lo[1]..hi[1]).all(|y| (lo[2]..hi[2]).all(|z| l.contains(&[x, y, z]))))
        };
        let mut hi = [c[0] + 1, c[1] + 1, c[2] + 1];
        for k in 0..3 {
            loop {
                let mut lo2 = c;
                lo2[k] = hi[k];
                let mut hi2 = hi;
                hi2[k] = hi[k] + 1;
                if has(&left, lo2, hi2) {
                    hi[k] += 1;
                } else {
                    break;
                }
            }
        }
        for x in c[0]..hi[0] {
            for y in c[1]..hi[1] {
                for z in c[2]..hi[2] {
                    left.remove(&[x, y, z]);
                }
            }
        }
        out.push(Polytope::cuboid(c.map(|v| v * s), hi.map(|v| v * s)).unwrap());
    }
    out
}

fn parts(pieces: &[Vec<Cell>], s: i64) -> Vec<Part> {
    pieces
        .iter()
        .enumerate()
        .map(|(k, p)| Part::from_pieces(format!("p{k}"), boxes(p, s)))
        .collect()
}

fn axes() -> MoveOptions {
    MoveOptions {
        axes: true,
        ..MoveOptions::default()
    }
}

#[test]
fn a_key_in_an_l_slot_needs_two_moves() {
    let slot = [[1, 1, 1], [1, 2, 1], [1, 2, 2]];
    let frame: Vec<Cell> = (0..36)
        .map(|i| [i % 3, i / 3 % 4, i / 12])
        .filter(|c| !slot.contains(c))
        .collect();
    let p = parts(&[frame, vec![[1, 1, 1]]], 2);
    for opts in [axes(), MoveOptions::default()] {
        let plan = disassemble(&p, &opts, &Progress::new()).unwrap();
        assert_eq!(plan.level, Some(2), "{plan:#?}");
        assert!(plan.complete);
    }
}

#[test]
fn levels_with_axes_match_the_brute_force_search() {
    let mut seen = [0usize; 8];
    for seed in 0..40 {
        let cells = random_puzzle([3, 3, 2], 3 + (seed % 2) as usize, seed);
        if cells.iter().any(Vec::is_empty) {
            continue;
        }
        let want = level(&cells, Steps::Any, 200_000);
        let plan = disassemble(&parts(&cells, 2), &axes(), &Progress::new()).unwrap();
        match want {
            Level::Moves(l) => {
                assert_eq!(plan.level, Some(l), "seed {seed}");
                seen[l.min(7)] += 1;
            }
            Level::Interlocked(_) => {
                assert_eq!(plan.searches[0].end, SearchEnd::Interlocked, "seed {seed}")
            }
            Level::Unknown => {}
        }
    }
    eprintln!("levels seen: {seen:?}");
}
