//! Plans of several moves: the shipped examples against their known answers, voxel
//! puzzles against the brute-force level oracle, partition's agreement on level 1, and
//! every plan replayed by the exact sweep oracle.

mod common;

use apart::assembly::{load, LoadOptions};
use apart::kernel::Rational;
use apart::plan::{
    disassemble, partition_pieces, parts_of, MoveOptions, Options, Progress, SearchEnd,
};
use apart_testkit::voxel_puzzles::{level, random_puzzle, Level, Steps};
use common::{replay_moves, voxel_parts};
use std::path::Path;

fn axes() -> MoveOptions {
    MoveOptions {
        axes: true,
        ..MoveOptions::default()
    }
}

fn expected(name: &str) -> serde_json::Value {
    let p = Path::new("examples").join(name).join("expected.json");
    serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
}

fn ints(v: &serde_json::Value) -> [i64; 3] {
    [0, 1, 2].map(|k| v[k].as_i64().unwrap())
}

#[test]
fn off_grid_examples_take_their_known_first_move_then_leave() {
    for name in ["l-slot", "keyhole", "drawer", "diagonal-two-move"] {
        let e = expected(name);
        let loaded = load(&Path::new("examples").join(name), &LoadOptions::default()).unwrap();
        let parts = parts_of(&loaded.assembly).unwrap();
        // Interlocked for single moves: partition finds nothing.
        let p = partition_pieces(parts, &Options::default()).unwrap();
        assert!(p.solutions.is_empty(), "{name}: partition frees it");
        let plan = disassemble(parts, &MoveOptions::default(), &Progress::new()).unwrap();
        assert_eq!(
            plan.level,
            Some(e["level"].as_u64().unwrap() as usize),
            "{name}"
        );
        assert!(plan.complete, "{name}");
        replay_moves(parts, &plan).unwrap_or_else(|m| panic!("{name}: {m}"));
        // The first move: the stated part along the stated direction, as far as stated.
        let first = &plan.moves[0];
        let mover = loaded
            .assembly
            .parts
            .iter()
            .position(|p| p.name == e["moving"])
            .unwrap();
        let d = ints(&e["first_move"]);
        let (lo, hi) = (ints(&e["first_move_min"]), ints(&e["first_move_max"]));
        let t = first.distance.clone().expect("a finite first move");
        let step = loaded.assembly.grid.step();
        let shift: Vec<f64> = (0..3)
            .map(|k| t.to_f64() * first.direction.approx()[k] * step)
            .collect();
        if first.moving == vec![mover] {
            for k in 0..3 {
                let (a, b) = (lo[k].min(hi[k]) as f64, lo[k].max(hi[k]) as f64);
                assert!(
                    shift[k] >= a - 1e-9 && shift[k] <= b + 1e-9,
                    "{name}: {shift:?}"
                );
                // Parallel to the stated direction, same way.
                assert_eq!(first.direction.approx()[k].signum(), (d[k] as f64).signum());
            }
        } else {
            // The rest moved the opposite way: the same relative motion.
            assert!(first.moving.iter().all(|&k| k != mover), "{name}");
            let got = first.direction.approx();
            for (g, w) in got.iter().zip(d) {
                assert_eq!(g.signum(), -(w as f64).signum());
            }
        }
    }
}

#[test]
fn voxel_examples_have_the_level_the_oracle_found() {
    for entry in std::fs::read_dir("examples").unwrap() {
        let dir = entry.unwrap().path();
        let name = dir.file_name().unwrap().to_string_lossy().to_string();
        if !name.starts_with("voxel-level-") {
            continue;
        }
        let e = expected(&name);
        let loaded = load(&dir, &LoadOptions::default()).unwrap();
        let parts = parts_of(&loaded.assembly).unwrap();
        let plan = disassemble(parts, &axes(), &Progress::new()).unwrap();
        assert_eq!(
            plan.level,
            Some(e["level"].as_u64().unwrap() as usize),
            "{name}"
        );
        replay_moves(parts, &plan).unwrap_or_else(|m| panic!("{name}: {m}"));
    }
}

/// Random puzzles: with `--axes`, the level is the oracle's over moves of any number of
/// whole steps, never more than its level over single steps, and the plan replays.
#[test]
fn axis_levels_match_the_brute_force_search() {
    let mut levels = std::collections::BTreeMap::new();
    for seed in 0..60u64 {
        let dims = [[3, 3, 2], [3, 3, 3], [4, 3, 2]][seed as usize % 3];
        let cells = random_puzzle(dims, 3 + (seed % 3) as usize, seed);
        if cells.iter().any(Vec::is_empty) {
            continue;
        }
        let parts = voxel_parts(&cells, 4);
        let plan = disassemble(&parts, &axes(), &Progress::new()).unwrap();
        match level(&cells, Steps::Any, 500_000) {
            Level::Moves(l) => {
                assert_eq!(plan.level, Some(l), "seed {seed}");
                *levels.entry(l).or_insert(0) += 1;
                if let Level::Moves(one) = level(&cells, Steps::One, 500_000) {
                    assert!(l <= one, "seed {seed}");
                }
            }
            Level::Interlocked(_) => {
                assert_eq!(plan.searches[0].end, SearchEnd::Interlocked, "seed {seed}")
            }
            Level::Unknown => continue,
        }
        replay_moves(&parts, &plan).unwrap_or_else(|m| panic!("seed {seed}: {m}"));
    }
    assert!(!levels.is_empty());
}

/// Level 1 is exactly "partition finds a solution", without `--axes` too.
#[test]
fn partition_and_disassemble_agree_on_level_one() {
    let mut both = [0usize; 2];
    for seed in 0..40u64 {
        let cells = random_puzzle([3, 3, 2], 3, seed);
        if cells.iter().any(Vec::is_empty) {
            continue;
        }
        let parts = voxel_parts(&cells, 2);
        let p = partition_pieces(&parts, &Options::default()).unwrap();
        let plan = disassemble(&parts, &MoveOptions::default(), &Progress::new()).unwrap();
        assert_eq!(p.solutions.is_empty(), plan.level != Some(1), "seed {seed}");
        both[usize::from(plan.level == Some(1))] += 1;
        replay_moves(&parts, &plan).unwrap_or_else(|m| panic!("seed {seed}: {m}"));
    }
    for name in ["split-star", "dovetail-and-cap", "linked-rings", "l-slot"] {
        let loaded = load(&Path::new("examples").join(name), &LoadOptions::default()).unwrap();
        let parts = parts_of(&loaded.assembly).unwrap();
        let p = partition_pieces(parts, &Options::default()).unwrap();
        let plan = disassemble(parts, &MoveOptions::default(), &Progress::new()).unwrap();
        assert_eq!(p.solutions.is_empty(), plan.level != Some(1), "{name}");
        replay_moves(parts, &plan).unwrap_or_else(|m| panic!("{name}: {m}"));
    }
}

/// Generated puzzles of higher levels (the generator climbs from random cuts): the
/// level with `--axes` is the oracle's, at most its single-step level, and replays.
#[test]
fn generated_puzzles_of_higher_levels_match_the_oracle() {
    let mut top = 0;
    for seed in 0..6u64 {
        let dims = [[4, 4, 3], [4, 4, 4], [3, 4, 4]][seed as usize % 3];
        let Some((cells, l)) =
            apart_testkit::voxel_generate::climb(dims, 4 + seed as usize % 2, 8, seed, 20_000)
        else {
            continue;
        };
        let parts = voxel_parts(&cells, 1);
        let plan = disassemble(&parts, &axes(), &Progress::new()).unwrap();
        assert_eq!(plan.level, Some(l), "seed {seed}");
        if let Level::Moves(one) = level(&cells, Steps::One, 2_000_000) {
            assert!(l <= one, "seed {seed}");
        }
        replay_moves(&parts, &plan).unwrap_or_else(|m| panic!("seed {seed}: {m}"));
        // Free-cone moves include every axis move: never more moves.
        let free = disassemble(&parts, &MoveOptions::default(), &Progress::new()).unwrap();
        assert!(
            free.level.is_some_and(|f| f <= l),
            "seed {seed}: {:?}",
            free.level
        );
        replay_moves(&parts, &free).unwrap_or_else(|m| panic!("seed {seed}: {m}"));
        top = top.max(l);
    }
    assert!(top >= 3, "the generator reached level {top} only");
}

#[test]
fn a_key_in_an_l_slot_slides_one_cell_then_leaves() {
    // Cells three grid units wide: the slide is 3.
    let slot = [[1, 1, 1], [1, 2, 1], [1, 2, 2]];
    let frame: Vec<[i64; 3]> = (0..36)
        .map(|i| [i % 3, i / 3 % 4, i / 12])
        .filter(|c| !slot.contains(c))
        .collect();
    let parts = voxel_parts(&[frame, vec![[1, 1, 1]]], 3);
    for opts in [axes(), MoveOptions::default()] {
        let plan = disassemble(&parts, &opts, &Progress::new()).unwrap();
        assert_eq!(plan.level, Some(2));
        assert_eq!(plan.moves[0].distance, Some(Rational::from(3)));
        replay_moves(&parts, &plan).unwrap();
    }
}

#[test]
fn bounds_say_whether_the_search_was_exhaustive() {
    let loaded = load(Path::new("examples/l-slot"), &LoadOptions::default()).unwrap();
    let parts = parts_of(&loaded.assembly).unwrap();
    let one = MoveOptions {
        max_moves: 1,
        ..MoveOptions::default()
    };
    let plan = disassemble(parts, &one, &Progress::new()).unwrap();
    assert_eq!(plan.searches[0].end, SearchEnd::MoveLimit);
    assert!(!plan.complete && plan.level.is_none());
    let few = MoveOptions {
        max_states: 1,
        ..MoveOptions::default()
    };
    let plan = disassemble(parts, &few, &Progress::new()).unwrap();
    assert_eq!(plan.searches[0].end, SearchEnd::StateLimit);
    let rings = load(Path::new("examples/linked-rings"), &LoadOptions::default()).unwrap();
    let plan = disassemble(
        parts_of(&rings.assembly).unwrap(),
        &MoveOptions::default(),
        &Progress::new(),
    )
    .unwrap();
    assert_eq!(plan.searches[0].end, SearchEnd::Interlocked);
}

/// The benchmark's puzzles (4 to 8 pieces up to 6x6x6, levels 2 to 10, each level and
/// complete disassembly found by the oracle): the same level, complete, replayed.
#[test]
fn benchmark_puzzles_have_the_oracles_levels() {
    for p in apart_testkit::voxel_bench::bench_puzzles() {
        let parts = voxel_parts(&p.pieces, 2);
        let plan = disassemble(&parts, &axes(), &Progress::new()).unwrap();
        assert_eq!(plan.level, Some(p.level), "{}", p.name);
        assert!(plan.complete, "{}", p.name);
        replay_moves(&parts, &plan).unwrap_or_else(|m| panic!("{}: {m}", p.name));
    }
}
