//! Large polygons through snapping and validation: a prism over a
//! 100,000-gon, convex and toothed, is checked in near-linear time.

/// A prism over a `k`-gon (radius 1000, height 10; every other vertex at `inner`
/// times the radius), its caps single polygons.
fn prism(k: usize, inner: f64) -> apart_formats::RawObject {
    let mut vertices = Vec::with_capacity(2 * k);
    for z in [0.0, 10.0] {
        for i in 0..k {
            let a = std::f64::consts::TAU * i as f64 / k as f64;
            let r = if i % 2 == 1 { 1000.0 * inner } else { 1000.0 };
            vertices.push([r * a.cos(), r * a.sin(), z]);
        }
    }
    let k32 = k as u32;
    let mut faces = apart_formats::Polygons::new();
    faces.push(&(0..k32).rev().collect::<Vec<_>>());
    faces.push(&(k32..2 * k32).collect::<Vec<_>>());
    for i in 0..k32 {
        let j = (i + 1) % k32;
        faces.push(&[i, j, k32 + j, k32 + i]);
    }
    apart_formats::RawObject {
        name: None,
        vertices,
        faces,
    }
}

/// Checking a prism over a 100,000-gon: ear clipping, fans whose triangles' boxes meet
/// every rim face, a cap's sweep triangles tested against each other, and deep teeth
/// whose nearly parallel sides' boxes meet would each be quadratic (minutes). Seconds.
#[test]
fn large_polygons_are_checked_in_near_linear_time() {
    let k = 100_000;
    // Convex (a strip), non-convex with teeth as deep as they are wide (the sweep), and a
    // star whose teeth are 30 % of its radius: thousands of times deeper than wide, its
    // rim's faces nearly parallel to their neighbours (their boxes meet quadratically
    // many others; their slabs do not).
    for inner in [1.0, 1.0 - std::f64::consts::TAU / k as f64, 0.7] {
        let raw = prism(k, inner);
        let grid = apart_kernel::Grid::choose(raw.vertices.iter().flatten().copied(), 30).unwrap();
        let t = std::time::Instant::now();
        let (_, info, problems) = apart_mesh::validate::check_solid(&raw, &grid);
        let s = t.elapsed().as_secs_f64();
        assert!(problems.is_empty(), "{inner}: {problems:?}");
        let info = info.unwrap();
        assert_eq!(info.triangles, 4 * k - 4);
        assert!(info.closed && info.self_intersections == 0);
        assert!(s < 60.0, "{inner}: {s} s");
    }
}
