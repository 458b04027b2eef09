//! Writes `examples/split-star/`: the Split Star puzzle of six congruent parts (red,
//! green, blue, purple, yellow, turquoise), one OFF per part (faces outward) and an
//! `assembly.json` manifest. Run from anywhere:
//! `cargo run -p apart-assembly --example generate_examples [-- OUT_DIR]`.
//!
//! Red is given by its ten vertices and sixteen triangles; the other parts are its
//! images under axis permutations and mirrorings (a mirroring reverses the faces so
//! that they stay outward).

use apart_formats::{off, Polygons};
use std::path::PathBuf;

const RED: [[f64; 3]; 10] = [
    [-2.0, 0.0, 0.0],
    [-2.0, 0.0, 2.0],
    [-1.0, -1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [0.0, 0.0, 0.0],
    [0.0, 0.0, 2.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [2.0, 0.0, 0.0],
    [2.0, 0.0, 2.0],
];

/// Red's faces, counter-clockwise seen from outside.
const RED_FACES: [[u32; 3]; 16] = [
    [2, 1, 0],
    [0, 1, 3],
    [0, 3, 2],
    [6, 8, 9],
    [7, 9, 8],
    [6, 7, 8],
    [2, 4, 6],
    [2, 3, 4],
    [7, 6, 4],
    [7, 4, 3],
    [1, 2, 5],
    [5, 2, 6],
    [5, 6, 9],
    [9, 7, 5],
    [5, 7, 3],
    [5, 3, 1],
];

fn main() -> std::io::Result<()> {
    let out = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/split-star")
        });
    std::fs::create_dir_all(&out)?;
    type Map = fn([f64; 3]) -> [f64; 3];
    let blue: Map = |[x, y, z]| [z, x, y];
    let yellow: Map = |[x, y, z]| [y, z, x];
    let parts: [(&str, Map, bool); 6] = [
        ("red", |p| p, false),
        ("green", |[x, y, z]| [x, y, -z], true),
        ("blue", blue, false),
        (
            "purple",
            |p| {
                let [x, y, z] = [p[2], p[0], p[1]];
                [-x, y, z]
            },
            true,
        ),
        ("yellow", yellow, false),
        (
            "turquoise",
            |p| {
                let [x, y, z] = [p[1], p[2], p[0]];
                [x, -y, z]
            },
            true,
        ),
    ];
    let mut manifest = String::from("{\n  \"name\": \"split-star\",\n  \"parts\": [\n");
    for (k, (name, map, mirror)) in parts.iter().enumerate() {
        let vertices: Vec<[f64; 3]> = RED.iter().map(|&p| map(p)).collect();
        let mut faces = Polygons::from_triangles(&RED_FACES);
        if *mirror {
            faces.reverse_each();
        }
        let mut file = std::fs::File::create(out.join(format!("{name}.off")))?;
        off::write(&mut file, &vertices, &faces)?;
        let comma = if k + 1 < parts.len() { "," } else { "" };
        manifest.push_str(&format!(
            "    {{\"name\": \"{name}\", \"mesh\": \"{name}.off\"}}{comma}\n"
        ));
    }
    manifest.push_str("  ]\n}\n");
    std::fs::write(out.join("assembly.json"), manifest)?;
    println!("wrote {}", out.display());
    Ok(())
}
