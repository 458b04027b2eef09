//! Loads, welds and validates one mesh file and prints the time of each stage:
//! `cargo run --release -p apart-mesh --example check_mesh -- FILE`, or
//! `... -- --torus N M FILE` to first write an `N * M * 2`-triangle torus as binary STL.
//! Run it under `/usr/bin/time -v` for the peak memory.

use apart_kernel::Grid;
use apart_mesh::{validate, Mesh};
use apart_testkit::torus;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = if args.first().map(String::as_str) == Some("--torus") {
        let (n, m) = (args[1].parse().unwrap(), args[2].parse().unwrap());
        let path = std::path::PathBuf::from(&args[3]);
        torus::write_torus_stl(&path, n, m).expect("write torus");
        path
    } else {
        std::path::PathBuf::from(args.first().expect("usage: check_mesh FILE"))
    };
    let t0 = Instant::now();
    let objects = apart_formats::read_file(&path).unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(1)
    });
    let t1 = Instant::now();
    let raw = &objects[0];
    let grid = Grid::choose(raw.vertices.iter().flatten().copied(), 30).expect("grid");
    let (mesh, problems) = Mesh::from_raw(raw, &grid);
    let t2 = Instant::now();
    let mut mesh = mesh.expect("mesh");
    let (info, more) = validate::validate(&mut mesh, &grid);
    let t3 = Instant::now();
    let bytes = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
    let total = (t3 - t0).as_secs_f64();
    println!(
        "{}: {} triangles, {} vertices; read {:.3} s, snap+weld+triangulate {:.3} s, validate {:.3} s; total {:.3} s, {:.1} MB/s",
        path.display(),
        info.triangles,
        info.vertices,
        (t1 - t0).as_secs_f64(),
        (t2 - t1).as_secs_f64(),
        (t3 - t2).as_secs_f64(),
        total,
        bytes as f64 / 1e6 / total
    );
    println!(
        "closed {}, shells {}, reflex edges {}, convex {}, self-intersections {}, volume {:?}",
        info.closed,
        info.shells,
        info.reflex_edges,
        info.convex,
        info.self_intersections,
        info.volume_units(&grid).map(|v| v.to_f64())
    );
    for p in problems.iter().chain(&more) {
        println!("{p}");
    }
}
