//! Writes the parametric test parts of the stacking planner as OFF meshes under
//! `examples/sheet-metal/` (run from the repository root):
//! `cargo run -p apart-stack --example generate_parts`.

use apart_stack::parts::{channel, complex_part, cube, triangle_part, write_off};
use std::path::Path;

fn main() -> std::io::Result<()> {
    let dir = Path::new("examples/sheet-metal");
    std::fs::create_dir_all(dir)?;
    for part in [cube(10), channel(), triangle_part(), complex_part()] {
        let file = dir.join(format!("{}.off", part.name));
        write_off(&part, &file)?;
        println!(
            "{}: {} convex pieces -> {}",
            part.name,
            part.pieces.len(),
            file.display()
        );
    }
    Ok(())
}
