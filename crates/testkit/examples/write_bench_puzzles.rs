//! Writes every puzzle of the voxel benchmark fixture (`data/voxel_bench.json`) as an
//! assembly folder `DIR/<name>` (with its `expected.json`), and prints one line per
//! puzzle: `<folder> <pieces> <dims> <level>`.
//!
//! `cargo run --release -p apart-testkit --example write_bench_puzzles -- DIR`

use apart_testkit::voxel_bench::{bench_puzzles, write_bench_puzzle};
use std::path::PathBuf;

fn main() -> std::io::Result<()> {
    let dir = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "voxel-bench".into()),
    );
    for p in bench_puzzles() {
        let out = dir.join(&p.name);
        write_bench_puzzle(&out, &p)?;
        let d = p.dims;
        println!(
            "{} {} {}x{}x{} {}",
            out.display(),
            p.pieces.len(),
            d[0],
            d[1],
            d[2],
            p.level
        );
    }
    Ok(())
}
