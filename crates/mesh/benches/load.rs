//! Loading benchmark: a ~1,000,000-triangle torus written as binary STL is read,
//! snapped, welded and validated (including the self-intersection check).

use apart_kernel::Grid;
use apart_mesh::{validate, Mesh};
use apart_testkit::torus;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::time::Instant;

fn load(path: &std::path::Path) -> usize {
    let objects = apart_formats::read_file(path).expect("read");
    let raw = &objects[0];
    let grid = Grid::choose(raw.vertices.iter().flatten().copied(), 30).expect("grid");
    let (mesh, _) = Mesh::from_raw(raw, &grid);
    let mut mesh = mesh.expect("mesh");
    let (info, problems) = validate::validate(&mut mesh, &grid);
    assert!(problems.is_empty() && info.closed && info.self_intersections == 0);
    info.triangles
}

fn bench(c: &mut Criterion) {
    let dir = std::env::temp_dir().join(format!("apart-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("torus-1m.stl");
    let bytes = torus::write_torus_stl(&path, 1000, 500).unwrap();
    let t = Instant::now();
    let n = load(&path);
    let s = t.elapsed().as_secs_f64();
    println!(
        "torus: {n} triangles, {:.1} MB, first load {s:.3} s = {:.1} MB/s",
        bytes as f64 / 1e6,
        bytes as f64 / 1e6 / s
    );
    let mut g = c.benchmark_group("load");
    g.sample_size(10);
    g.measurement_time(std::time::Duration::from_secs(20));
    g.throughput(Throughput::Bytes(bytes));
    g.bench_function("stl_1m_triangles_load_weld_validate", |b| {
        b.iter(|| load(&path))
    });
    g.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, bench);
criterion_main!(benches);
