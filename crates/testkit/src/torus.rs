//! A closed torus as binary STL, for loading benchmarks: large, closed, outward and free
//! of self-intersections, with `f32` coordinates as real exports have.

use std::io::Write;

/// A torus (radii 10 and 3) of `n` segments around its axis and `m` around its tube,
/// `2 n m` outward triangles, as the bytes of a binary STL file.
pub fn torus_stl(n: usize, m: usize) -> Vec<u8> {
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
    out
}

/// Writes [`torus_stl`]`(n, m)` to `path` and returns its size in bytes.
pub fn write_torus_stl(path: &std::path::Path, n: usize, m: usize) -> std::io::Result<u64> {
    let out = torus_stl(n, m);
    std::fs::File::create(path)?.write_all(&out)?;
    Ok(out.len() as u64)
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_header_counts_every_triangle() {
        let bytes = super::torus_stl(6, 4);
        assert_eq!(bytes.len(), 84 + 50 * 2 * 6 * 4);
        assert_eq!(u32::from_le_bytes(bytes[80..84].try_into().unwrap()), 48);
    }
}
