//! A closed torus as a binary STL, for benchmarks (shared by `benches/load.rs` and the
//! `check_mesh` example).

use std::io::Write;

/// Writes a torus with `n * m * 2` triangles (outward) as binary STL to `path`.
pub fn write_torus_stl(path: &std::path::Path, n: usize, m: usize) -> std::io::Result<u64> {
    let (big, small) = (10.0f64, 3.0f64);
    let p = |i: usize, j: usize| {
        let u = 2.0 * std::f64::consts::PI * (i % n) as f64 / n as f64;
        let v = 2.0 * std::f64::consts::PI * (j % m) as f64 / m as f64;
        [
            ((big + small * v.cos()) * u.cos()) as f32,
            ((big + small * v.cos()) * u.sin()) as f32,
            (small * v.sin()) as f32,
        ]
    };
    let mut out = Vec::with_capacity(84 + 50 * 2 * n * m);
    out.extend_from_slice(&[b' '; 80]);
    out.extend_from_slice(&((2 * n * m) as u32).to_le_bytes());
    for i in 0..n {
        for j in 0..m {
            let (a, b, c, d) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            for t in [[a, b, c], [a, c, d]] {
                out.extend_from_slice(&[0u8; 12]);
                for v in t {
                    for x in v {
                        out.extend_from_slice(&x.to_le_bytes());
                    }
                }
                out.extend_from_slice(&[0, 0]);
            }
        }
    }
    std::fs::File::create(path)?.write_all(&out)?;
    Ok(out.len() as u64)
}
