//! Measures `repair` on ~50k-triangle meshes with T-junction seams (run with
//! `cargo run --release -p apart-mesh --example repair_time`): a seamed box, the same
//! with a third of its triangles reversed, as a float32 binary STL; and 4000 boxes in
//! one mesh, half of them inside out, split into bodies.

use apart_formats::{read_bytes, Format, Polygons, RawObject};
use apart_kernel::Grid;
use apart_mesh::repair::{bodies, repair, RepairOptions};
use apart_mesh::validate::validate;
use apart_mesh::Mesh;
use apart_testkit::defects::{
    box_soup, decimal_seamed_box, seamed_box, seamed_box_extent_unit, seamed_box_tjunctions,
};
use std::time::Instant;

fn run(name: &str, raw: &RawObject, grid: &Grid) -> Mesh {
    let (m, _) = Mesh::from_raw(raw, grid);
    let mut m = m.expect("a mesh");
    let n = m.triangles.len();
    let t = Instant::now();
    let r = repair(&mut m, &RepairOptions::default());
    let dt = t.elapsed();
    let (_, p) = validate(&mut m, grid);
    let errors = p.iter().filter(|p| p.is_error()).count();
    println!(
        "{name}: {n} triangles in, {} out, repair {:.1} ms ({r}); {errors} validation errors",
        m.triangles.len(),
        dt.as_secs_f64() * 1e3
    );
    m
}

fn main() {
    // Neighbouring faces disagree along every box edge.
    let div = [[60, 70], [70, 60], [66, 63], [63, 66], [64, 65], [65, 64]];
    let e = [0, 1, 2].map(|k| seamed_box_extent_unit(&div, k));
    let soup = seamed_box(e, div);
    let raw = |s: &apart_testkit::Soup| RawObject {
        name: None,
        vertices: s.vertices.clone(),
        faces: Polygons::from(s.faces.clone()),
    };
    let grid = Grid::unit(30);
    println!("(expected: {} T-junctions)", seamed_box_tjunctions(&div));
    run("seamed box", &raw(&soup), &grid);
    let mut flipped = soup.clone();
    for (i, f) in flipped.faces.iter_mut().enumerate() {
        if i % 3 == 0 {
            f.reverse();
        }
    }
    run(
        "seamed box, every third triangle reversed",
        &raw(&flipped),
        &grid,
    );
    let dec = decimal_seamed_box([4 * 10 * 21 * 13, 4 * 21 * 11 * 13, 4 * 16 * 13], div);
    let mut stl = Vec::new();
    dec.write_binary_stl(&mut stl).expect("writing to memory");
    let objects = read_bytes(&stl, Format::Stl, None).expect("reading back");
    let grid = Grid::choose(objects[0].vertices.iter().flatten().copied(), 30).expect("grid");
    run("decimal seamed box via float32 STL", &objects[0], &grid);

    let mut many = apart_testkit::Soup::default();
    for i in 0..4000 {
        let (x, y) = ((i % 64) as f64 * 3.0, (i / 64) as f64 * 3.0);
        let mut b = box_soup([x, y, 0.0], [x + 2.0, y + 2.0, 2.0]);
        if i % 2 == 1 {
            b.faces.iter_mut().for_each(|f| f.reverse());
        }
        many.append(&b);
    }
    let m = run("4000 boxes, half inside out", &raw(&many), &Grid::unit(30));
    let t = Instant::now();
    let parts = bodies(&m);
    println!(
        "bodies: {} in {:.1} ms",
        parts.len(),
        t.elapsed().as_secs_f64() * 1e3
    );
}
