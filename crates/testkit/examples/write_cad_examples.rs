//! Writes the shipped real-CAD examples: `cargo run -p apart-testkit --example
//! write_cad_examples` (from the repository root).
//!
//! - `examples/cad-pin-in-hole`: a pin of 64 segments in a hole of 64 segments turned by
//!   half a segment, so the tessellations interpenetrate by `4 (1 − cos(π/64)) ≈ 4.8e-3`
//!   (use `--tolerance auto`);
//! - `examples/cad-seams`: a box exported as one binary STL with T-junction seams
//!   (faces subdivided differently on each side) and float32 coordinates far from the
//!   origin, under a lid written as a separate STL, plus two loose washers exported
//!   together in one file (split into two parts on load).

use apart_testkit::curved::{pin_in_hole, write_off_dir};
use apart_testkit::defects::{
    box_soup, decimal_seamed_box, decimal_seamed_box_corners, float32_rounded,
};
use apart_testkit::Soup;
use std::path::Path;

fn stl(path: &Path, soup: &Soup) -> std::io::Result<()> {
    let mut bytes = Vec::new();
    float32_rounded(soup).write_binary_stl(&mut bytes)?;
    std::fs::write(path, bytes)
}

fn main() -> std::io::Result<()> {
    let pin = Path::new("examples/cad-pin-in-hole");
    let _ = std::fs::remove_dir_all(pin);
    write_off_dir(&pin_in_hole(64, 64, std::f64::consts::PI / 64.0), pin)?;

    let seams = Path::new("examples/cad-seams");
    let _ = std::fs::remove_dir_all(seams);
    std::fs::create_dir_all(seams)?;
    let extent = [40, 30, 20];
    let div = [[2, 3], [3, 2], [4, 1], [1, 4], [2, 2], [5, 3]];
    stl(&seams.join("base.stl"), &decimal_seamed_box(extent, div))?;
    let (lo, hi) = decimal_seamed_box_corners(extent);
    stl(
        &seams.join("lid.stl"),
        &box_soup([lo[0], lo[1], hi[2]], [hi[0], hi[1], hi[2] + 0.5]),
    )?;
    // Two washers (square, for exactness) lying on the lid, exported as one mesh.
    let mut washers = box_soup(
        [lo[0] + 0.5, lo[1] + 0.5, hi[2] + 0.5],
        [lo[0] + 1.5, lo[1] + 1.5, hi[2] + 0.7],
    );
    washers.append(&box_soup(
        [lo[0] + 2.0, lo[1] + 0.5, hi[2] + 0.5],
        [lo[0] + 3.0, lo[1] + 1.5, hi[2] + 0.7],
    ));
    stl(&seams.join("washers.stl"), &washers)?;
    println!("wrote {} and {}", pin.display(), seams.display());
    Ok(())
}
