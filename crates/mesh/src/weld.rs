//! Snapping input coordinates to the grid and welding equal grid points.
//!
//! Welding is sort-based: each vertex becomes a key (its integer coordinates, then its
//! input index), the keys are sorted in parallel, and each run of equal coordinates
//! becomes one vertex. Welded vertices keep the order of their first appearance in the
//! input, so small meshes keep their numbering.

use apart_kernel::Grid;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU32, Ordering};

/// Snapped and welded vertices.
#[derive(Debug)]
pub(crate) struct Welded {
    /// Distinct grid points, in order of first appearance.
    pub points: Vec<[i64; 3]>,
    /// For every input vertex, its welded index.
    pub remap: Vec<u32>,
    /// For every welded point, the first input vertex that snapped to it.
    pub first: Vec<u32>,
}

/// `grid.snap(v)`, fast: for the usual exponents, multiplying by `2^-exp` is exact (as
/// is the kernel's two-step scaling), and rounding half away from zero is done with a
/// truncating conversion rather than a libm call. `None` for a non-finite value or one
/// outside the grid (`|q| >= 2^bits`).
#[inline]
fn snap_one(v: f64, inv_h: Option<f64>, grid: &Grid, limit: u64) -> Option<i64> {
    if !v.is_finite() {
        return None;
    }
    let q = match inv_h {
        Some(s) => {
            let x = v * s;
            if x.abs() >= 4503599627370496.0 {
                return None; // beyond 2^52, hence beyond every grid's range
            }
            let i = x as i64; // truncates towards zero
            let frac = x - i as f64; // exact
            if frac >= 0.5 {
                i + 1
            } else if frac <= -0.5 {
                i - 1
            } else {
                i
            }
        }
        None => grid.snap(v),
    };
    (q.unsigned_abs() < limit).then_some(q)
}

/// Snaps every coordinate as `grid.snap` does. Vertices with a non-finite coordinate, or
/// outside the grid's range, are returned in the second list (and snapped to 0).
pub(crate) fn snap_all(vertices: &[[f64; 3]], grid: &Grid) -> (Vec<[i64; 3]>, Vec<usize>) {
    let inv_h = (-1000..=1000)
        .contains(&grid.exp)
        .then(|| f64::from_bits(((1023 - grid.exp as i64) as u64) << 52));
    let limit = 1u64 << grid.bits.min(53);
    let snapped: Vec<Option<[i64; 3]>> = vertices
        .par_iter()
        .with_min_len(8192)
        .map(|v| {
            Some([
                snap_one(v[0], inv_h, grid, limit)?,
                snap_one(v[1], inv_h, grid, limit)?,
                snap_one(v[2], inv_h, grid, limit)?,
            ])
        })
        .collect();
    let bad: Vec<usize> = snapped
        .iter()
        .enumerate()
        .filter(|(_, p)| p.is_none())
        .map(|(i, _)| i)
        .collect();
    let points = snapped.into_iter().map(|p| p.unwrap_or([0; 3])).collect();
    (points, bad)
}

/// Welds equal grid points.
pub(crate) fn weld(points: &[[i64; 3]]) -> Welded {
    let n = points.len();
    let max = points
        .par_iter()
        .map(|p| p.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0))
        .max()
        .unwrap_or(0);
    // head[i] = the smallest input index with the same coordinates as i.
    let head: Vec<u32> = if max < 1 << 30 {
        heads_packed(points)
    } else {
        heads_general(points)
    };
    // Number the heads in input order; every vertex takes its head's number.
    let mut number = vec![u32::MAX; n];
    let mut first = Vec::new();
    let mut out = Vec::new();
    for i in 0..n {
        if head[i] as usize == i {
            number[i] = first.len() as u32;
            first.push(i as u32);
            out.push(points[i]);
        }
    }
    let remap = head
        .par_iter()
        .with_min_len(8192)
        .map(|&h| number[h as usize])
        .collect();
    Welded {
        points: out,
        remap,
        first,
    }
}

/// Group heads for coordinates below 2^30: (x, y, z, index) packed into one u128
/// (31 + 31 + 31 + 32 bits, order-preserving), partitioned by a hash of the coordinates
/// into cache-sized buckets (equal points share a bucket) in parallel chunks, and each
/// bucket sorted and scanned in parallel.
fn heads_packed(points: &[[i64; 3]]) -> Vec<u32> {
    let n = points.len();
    let off = 1i64 << 30;
    let pack = |i: usize, p: &[i64; 3]| {
        ((p[0] + off) as u128) << 94
            | ((p[1] + off) as u128) << 63
            | ((p[2] + off) as u128) << 32
            | i as u128
    };
    let bits = (usize::BITS - (n / 1024).leading_zeros()).min(16);
    let nb = 1usize << bits;
    let bucket = |p: &[i64; 3]| -> usize {
        if bits == 0 {
            return 0;
        }
        let h = (p[0] as u64)
            .wrapping_mul(0x9E37_79B9_7F4A_7C15)
            .wrapping_add((p[1] as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F))
            .wrapping_add((p[2] as u64).wrapping_mul(0x1656_67B1_9E37_79F9));
        (h.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> (64 - bits)) as usize
    };
    // Each chunk sorts its keys by bucket (a counting sort) on its own.
    let chunk = n.div_ceil(2 * rayon::current_num_threads()).max(1 << 14);
    let chunks: Vec<(Vec<usize>, Vec<u128>)> = points
        .par_chunks(chunk)
        .enumerate()
        .map(|(c, ps)| {
            let base = c * chunk;
            let ids: Vec<u32> = ps.iter().map(|p| bucket(p) as u32).collect();
            let mut offsets = vec![0usize; nb + 1];
            for &b in &ids {
                offsets[b as usize + 1] += 1;
            }
            for b in 0..nb {
                offsets[b + 1] += offsets[b];
            }
            let mut cursor = offsets.clone();
            let mut keys = vec![0u128; ps.len()];
            for (k, p) in ps.iter().enumerate() {
                let b = ids[k] as usize;
                keys[cursor[b]] = pack(base + k, p);
                cursor[b] += 1;
            }
            (offsets, keys)
        })
        .collect();
    let head: Vec<AtomicU32> = (0..n).map(|_| AtomicU32::new(0)).collect();
    (0..nb)
        .into_par_iter()
        .with_min_len(64)
        .for_each_init(Vec::new, |all: &mut Vec<u128>, b| {
            all.clear();
            for (offsets, keys) in &chunks {
                all.extend_from_slice(&keys[offsets[b]..offsets[b + 1]]);
            }
            all.sort_unstable();
            let mut current = u128::MAX;
            let mut h = 0u32;
            for &k in all.iter() {
                let i = (k & 0xffff_ffff) as u32;
                if k >> 32 != current {
                    current = k >> 32;
                    h = i;
                }
                head[i as usize].store(h, Ordering::Relaxed);
            }
        });
    head.into_iter().map(AtomicU32::into_inner).collect()
}

/// Group heads for any coordinates: a parallel sort of (point, index).
fn heads_general(points: &[[i64; 3]]) -> Vec<u32> {
    let mut keys: Vec<([i64; 3], u32)> = points
        .par_iter()
        .enumerate()
        .map(|(i, p)| (*p, i as u32))
        .collect();
    keys.par_sort_unstable();
    let mut head = vec![0u32; points.len()];
    let mut current: Option<[i64; 3]> = None;
    let mut h = 0u32;
    for (p, i) in keys {
        if current != Some(p) {
            current = Some(p);
            h = i;
        }
        head[i as usize] = h;
    }
    head
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn welds_equal_points_in_first_appearance_order() {
        let pts = vec![[5, 0, 0], [0, 0, 0], [5, 0, 0], [-3, 2, 1], [0, 0, 0]];
        let w = weld(&pts);
        assert_eq!(w.points, vec![[5, 0, 0], [0, 0, 0], [-3, 2, 1]]);
        assert_eq!(w.remap, vec![0, 1, 0, 2, 1]);
        assert_eq!(w.first, vec![0, 1, 3]);
    }

    #[test]
    fn matches_a_hash_map_on_many_duplicates() {
        use std::collections::HashMap;
        let mut x = 88172645463325252u64;
        for (range, n) in [(7i64, 100_000usize), (1 << 29, 50_000), (1 << 45, 30_000)] {
            let pts: Vec<[i64; 3]> = (0..n)
                .map(|_| {
                    let mut c = [0i64; 3];
                    for v in &mut c {
                        x ^= x << 13;
                        x ^= x >> 7;
                        x ^= x << 17;
                        // Few distinct values per axis: many duplicates.
                        *v = ((x % 5) as i64 - 2) * (range / 3);
                    }
                    c
                })
                .collect();
            let w = weld(&pts);
            let mut seen: HashMap<[i64; 3], u32> = HashMap::new();
            let mut order = Vec::new();
            for (i, p) in pts.iter().enumerate() {
                let id = *seen.entry(*p).or_insert_with(|| {
                    order.push(i as u32);
                    order.len() as u32 - 1
                });
                assert_eq!(w.remap[i], id);
            }
            assert_eq!(w.first, order);
            assert_eq!(w.points.len(), seen.len());
        }
    }

    #[test]
    fn large_coordinates_take_the_general_path() {
        let b = 1i64 << 40;
        let pts = vec![[b, -b, 0], [0, 0, 0], [b, -b, 0], [b, -b, 1]];
        let w = weld(&pts);
        assert_eq!(w.remap, vec![0, 1, 0, 2]);
    }

    #[test]
    fn fast_snapping_matches_the_kernel() {
        let mut x = 0x2545F4914F6CDD1Du64;
        for bits in [4u32, 20, 30, 45, apart_kernel::grid::MAX_BITS] {
            for _ in 0..2000 {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                let scale = [1e-9, 0.37, 3.0, 1e6, 1e15][(x % 5) as usize];
                let v = ((x >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * scale;
                let g = Grid::choose([v, scale], bits).unwrap();
                // Values exactly halfway between grid points, and their neighbours.
                let h = g.step();
                for w in [
                    v,
                    (v / h).trunc() * h + h / 2.0,
                    -(v / h).trunc() * h - h / 2.0,
                ] {
                    let (s, bad) = snap_all(&[[w, 0.0, 0.0]], &g);
                    if bad.is_empty() {
                        assert_eq!(s[0][0], g.snap(w), "{w} on {g:?}");
                    }
                }
            }
        }
        let g = Grid::unit(30);
        let (_, bad) = snap_all(
            &[[f64::NAN, 0.0, 0.0], [0.0, 2e9, 0.0], [1.0, 2.0, 3.0]],
            &g,
        );
        assert_eq!(bad, vec![0, 1]);
    }

    #[test]
    fn snapping_merges_nearby_values() {
        let g = Grid::choose([1.0, 0.1], 4).unwrap(); // h = 2^-3
        let (s, _) = snap_all(&[[0.1, 0.0, 0.0], [0.11, 0.0, 0.0], [1.0, 0.0, 0.0]], &g);
        let w = weld(&s);
        assert_eq!(w.points.len(), 2); // 0.1 and 0.11 both snap to 1/8
        assert_eq!(w.points[0], [1, 0, 0]);
    }
}
