//! Writes the shipped voxel interlocking puzzles: `cargo run --release -p apart-testkit
//! --example write_voxel_puzzles` (from the repository root).
//!
//! Each `examples/voxel-level-<N>` holds one puzzle found by
//! [`apart_testkit::voxel_generate::puzzle_of_level`] (the first seed whose level is
//! exactly `N`), one OFF mesh per piece (10 units per cell), an `assembly.json`, an
//! `expected.json` (`{"level": N, "axes": true}`: the level counts moves along the axes
//! only) and a README with the level, a witness plan and the cells layer by layer.
//!
//! With `-- --survey` it writes nothing and prints, for a few boxes and piece counts,
//! the level each of 8 seeds climbs to within 100 000 changes (aiming at 12) and the
//! time taken.

use apart_testkit::voxel_generate::{climb, layers_text, puzzle_of_level, write_puzzle};
use apart_testkit::voxel_puzzles::{level, solve, Level, Steps};
use std::fmt::Write as _;
use std::path::Path;

const AXIS_NAMES: [(&str, [i64; 3]); 6] = [
    ("+x", [1, 0, 0]),
    ("-x", [-1, 0, 0]),
    ("+y", [0, 1, 0]),
    ("-y", [0, -1, 0]),
    ("+z", [0, 0, 1]),
    ("-z", [0, 0, -1]),
];

fn survey() {
    let configs: [([i64; 3], usize); 5] = [
        ([4, 4, 4], 4),
        ([4, 4, 4], 5),
        ([5, 5, 5], 6),
        ([6, 6, 6], 6),
        ([6, 6, 6], 8),
    ];
    for (dims, count) in configs {
        let mut levels = Vec::new();
        let t = std::time::Instant::now();
        for seed in 0..8 {
            levels.push(climb(dims, count, 12, seed, 100_000).map_or(0, |(_, l)| l));
        }
        println!(
            "{}x{}x{}, {count} pieces: levels {levels:?} ({:.1} s)",
            dims[0],
            dims[1],
            dims[2],
            t.elapsed().as_secs_f64()
        );
    }
}

fn main() -> std::io::Result<()> {
    if std::env::args().any(|a| a == "--survey") {
        survey();
        return Ok(());
    }
    // (target level, box, pieces)
    let wanted: [(usize, [i64; 3], usize); 4] = [
        (2, [4, 4, 4], 4),
        (4, [4, 4, 4], 5),
        (6, [5, 5, 5], 6),
        (10, [4, 4, 4], 5),
    ];
    for (target, dims, count) in wanted {
        let (seed, pieces) = (0..200)
            .find_map(
                |seed| match puzzle_of_level(dims, count, target, seed, 200_000) {
                    Some((p, l)) if l == target => Some((seed, p)),
                    _ => None,
                },
            )
            .expect("a seed reaches the level");
        let (any, plan) = solve(&pieces, Steps::Any, 10_000_000);
        assert_eq!(any, Level::Moves(target), "the oracle agrees");
        let plan = plan.expect("a plan");
        let one = level(&pieces, Steps::One, 10_000_000);
        let name = format!("voxel-level-{target}");
        let dir = Path::new("examples").join(&name);
        let _ = std::fs::remove_dir_all(&dir);
        write_puzzle(&dir, &name, &pieces, 10)?;
        std::fs::write(
            dir.join("expected.json"),
            format!("{{ \"level\": {target}, \"axes\": true }}\n"),
        )?;
        let mut readme = format!(
            "# {name}\n\nA voxel interlocking puzzle: {count} pieces of unit cells (10 units per \
             cell) in a {}×{}×{} box, written by `cargo run --release -p apart-testkit --example \
             write_voxel_puzzles` (`puzzle_of_level({dims:?}, {count}, {target}, seed {seed}, \
             200000)`).\n\n**Level {target}** as computed by the oracle \
             (`apart_testkit::voxel_puzzles::level`, exhaustive breadth-first search over moves \
             of any subset of pieces along ±x, ±y, ±z by whole cells): the least number of \
             moves up to and including the first that takes a subset away for ever. With moves \
             of one cell at a time: {one:?}. Moves off the axes might do better, so \
             `expected.json` says `\"axes\": true`.\n\nA witness plan (steps of 10 units; \
             `piece_0` stays put):\n\n",
            dims[0], dims[1], dims[2]
        );
        for (i, m) in plan.iter().enumerate() {
            let axis = AXIS_NAMES
                .iter()
                .find(|(_, d)| *d == m.dir)
                .map_or("?", |(n, _)| n);
            let names: Vec<String> = m.pieces.iter().map(|p| format!("piece_{p}")).collect();
            let how = m.steps.map_or("for ever".to_string(), |s| {
                format!("{s} cell{}", if s == 1 { "" } else { "s" })
            });
            let _ = writeln!(
                readme,
                "{}. {} along {axis}, {how}",
                i + 1,
                names.join(", ")
            );
        }
        let _ = write!(
            readme,
            "\nCells by layer (digit = piece index, `.` = empty; y upwards, x rightwards):\n\n```\n{}```\n",
            layers_text(&pieces)
        );
        std::fs::write(dir.join("README.md"), readme)?;
        println!("wrote {} (seed {seed}, unit steps {one:?})", dir.display());
    }
    Ok(())
}
