//! Writes the shipped level-2 assemblies of `apart_testkit::moves`: `cargo run --release
//! -p apart-testkit --example write_move_examples` (from the repository root) writes
//! `examples/l-slot`, `examples/keyhole`, `examples/drawer` and
//! `examples/diagonal-two-move`, each with a README and an `expected.json`.
//!
//! With `-- --displaced DIR` it writes instead, under `DIR`, each assembly with its
//! moving part displaced by the least first move, which `apart partition` must
//! separate.

use apart_testkit::moves::{all, write_parts};
use std::path::{Path, PathBuf};

fn main() -> std::io::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let displaced = args
        .iter()
        .position(|a| a == "--displaced")
        .map(|i| PathBuf::from(&args[i + 1]));
    for a in all() {
        if let Some(root) = &displaced {
            let dir = root.join(a.name);
            let _ = std::fs::remove_dir_all(&dir);
            write_parts(&dir, a.name, &a.displaced(a.first_range[0]))?;
            println!("wrote {}", dir.display());
            continue;
        }
        let dir = Path::new("examples").join(a.name);
        let _ = std::fs::remove_dir_all(&dir);
        write_parts(&dir, a.name, &a.parts)?;
        std::fs::write(dir.join("expected.json"), a.expected_json())?;
        let [lo, hi] = a.first_range;
        let readme = format!(
            "# {}\n\n{}\n\n**Level 2** (by construction, see `apart_testkit::moves`): no single \
             translation in any direction separates the parts (`apart partition` reports them \
             interlocked); part `{}` first moves along {:?} only, by {lo} to {hi} times that \
             vector, and then leaves along {:?}. Every part is a union of convex prisms with \
             integer coordinates, written as declared pieces. Written by `cargo run --release \
             -p apart-testkit --example write_move_examples`.\n",
            a.name, a.about, a.parts[a.moving].name, a.first, a.second
        );
        std::fs::write(dir.join("README.md"), readme)?;
        println!("wrote {}", dir.display());
    }
    Ok(())
}
