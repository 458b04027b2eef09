//! Writes the parametric test parts of the stacking planner (apart-testkit's
//! `sheet_metal`) as OFF meshes under `examples/sheet-metal/` (run from the repository
//! root): `cargo run -p apart-stack --example generate_parts`.

#[path = "../tests/common/parts.rs"]
mod parts;

use apart_testkit::sheet_metal::{channel, complex_part, cube, triangle_part};
use std::path::Path;

fn main() -> std::io::Result<()> {
    let dir = Path::new("examples/sheet-metal");
    std::fs::create_dir_all(dir)?;
    for part in [cube(10), channel(), triangle_part(), complex_part()] {
        let file = dir.join(format!("{}.off", part.name));
        std::fs::write(&file, part.mesh.off_text())?;
        let model = parts::model(part);
        println!(
            "{}: {} convex pieces -> {}",
            model.name,
            model.pieces.len(),
            file.display()
        );
    }
    Ok(())
}
