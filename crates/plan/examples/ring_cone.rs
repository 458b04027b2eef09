//! Times the ring-and-cone partition (for profiling).
#[path = "../tests/common/mod.rs"]
mod common;
fn main() {
    use apart_kernel::Vec3;
    let ring = apart_testkit::shapes::Ring::new(64);
    let r = ring.radius;
    let shape = ring.shape();
    let points: Vec<Vec3> = shape.points.iter().map(|&p| Vec3::from_i64(p)).collect();
    let lower = apart_decompose::decompose(&points, &shape.tris, &Default::default()).unwrap();
    let upper: Vec<apart_pieces::Polytope> = lower
        .pieces
        .iter()
        .map(|p| p.translated(&Vec3::new(0, 0, 16 * r)))
        .collect();
    let n = 80;
    let mut pts: Vec<Vec3> = (0..n)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            Vec3::new(
                (14.0 * r as f64 * t.cos()).round() as i64,
                (14.0 * r as f64 * t.sin()).round() as i64,
                -20 * r,
            )
        })
        .collect();
    pts.push(Vec3::new(0, 0, 40 * r));
    let mut tris: Vec<[u32; 3]> = (0..n as u32)
        .map(|k| [k, (k + 1) % n as u32, n as u32])
        .collect();
    for k in 1..n as u32 - 1 {
        tris.push([0, k + 1, k]);
    }
    let cone = apart_pieces::Polytope::from_triangles(&pts, &tris).unwrap();
    let parts = vec![
        common::part("a", lower.pieces),
        common::part("b", upper),
        common::part("cone", vec![cone]),
    ];
    for _ in 0..3 {
        let t = std::time::Instant::now();
        let p = apart_plan::partition_pieces(&parts, &Default::default()).unwrap();
        println!("{:?} {:?}", t.elapsed(), p.stats.seconds);
    }
}
