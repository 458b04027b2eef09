//! Closed integer meshes built from grids and polygons, and a seeded random generator:
//! the one copy of the voxel, grid-union and ear-clipping generators that the
//! decomposition, planning and stacking tests share.

use std::collections::HashMap;
use std::fmt::Write as _;

/// A closed triangle mesh with integer coordinates, outward triangles.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct IntMesh {
    /// Vertex coordinates.
    pub points: Vec<[i64; 3]>,
    /// Triangles as vertex indices, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

impl IntMesh {
    /// The mesh as OFF text (integer coordinates, one triangle a line).
    pub fn off_text(&self) -> String {
        let mut s = String::from("OFF\n");
        let _ = writeln!(s, "{} {} 0", self.points.len(), self.triangles.len());
        for p in &self.points {
            let _ = writeln!(s, "{} {} {}", p[0], p[1], p[2]);
        }
        for t in &self.triangles {
            let _ = writeln!(s, "3 {} {} {}", t[0], t[1], t[2]);
        }
        s
    }

    /// Six times the enclosed volume (divergence theorem; exact for closed meshes).
    pub fn volume6(&self) -> i128 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.points[i as usize].map(i128::from));
                let cross = [
                    b[1] * c[2] - b[2] * c[1],
                    b[2] * c[0] - b[0] * c[2],
                    b[0] * c[1] - b[1] * c[0],
                ];
                a[0] * cross[0] + a[1] * cross[1] + a[2] * cross[2]
            })
            .sum()
    }
}

/// The union of the filled cells of the rectilinear grid `xs × ys × zs` (strictly
/// increasing coordinates): its boundary, two outward triangles per grid rectangle
/// between a filled and an empty cell. Points are numbered in order of first use.
pub fn rectilinear(g: [&[i64]; 3], filled: impl Fn([usize; 3]) -> bool) -> IntMesh {
    let n = [g[0].len() - 1, g[1].len() - 1, g[2].len() - 1];
    let full = |c: [i64; 3]| -> bool {
        (0..3).all(|a| c[a] >= 0 && (c[a] as usize) < n[a])
            && filled([c[0] as usize, c[1] as usize, c[2] as usize])
    };
    let mut ids: HashMap<[i64; 3], u32> = HashMap::new();
    let mut points = Vec::new();
    let mut id = |p: [i64; 3]| -> u32 {
        *ids.entry(p).or_insert_with(|| {
            points.push(p);
            (points.len() - 1) as u32
        })
    };
    let mut triangles = Vec::new();
    let coord = |i: [usize; 3]| [g[0][i[0]], g[1][i[1]], g[2][i[2]]];
    for a in 0..3 {
        let (u, v) = ((a + 1) % 3, (a + 2) % 3);
        for p in 0..=n[a] {
            for iu in 0..n[u] {
                for iv in 0..n[v] {
                    let mut lo = [0i64; 3];
                    lo[a] = p as i64 - 1;
                    lo[u] = iu as i64;
                    lo[v] = iv as i64;
                    let mut hi = lo;
                    hi[a] += 1;
                    let (fl, fh) = (full(lo), full(hi));
                    if fl == fh {
                        continue;
                    }
                    let mut base = [0usize; 3];
                    base[a] = p;
                    base[u] = iu;
                    base[v] = iv;
                    let mut c1 = base;
                    c1[u] += 1;
                    let mut c2 = c1;
                    c2[v] += 1;
                    let mut c3 = base;
                    c3[v] += 1;
                    let q = [base, c1, c2, c3].map(|c| id(coord(c)));
                    if fl {
                        triangles.push([q[0], q[1], q[2]]);
                        triangles.push([q[0], q[2], q[3]]);
                    } else {
                        triangles.push([q[0], q[2], q[1]]);
                        triangles.push([q[0], q[3], q[2]]);
                    }
                }
            }
        }
    }
    IntMesh { points, triangles }
}

/// The cells of a `dims` voxel grid of unit cubes listed in `on`, cell `(x, y, z)` at
/// index `(x · dims[1] + y) · dims[2] + z`: the boundary of their union.
pub fn voxels(dims: [usize; 3], on: &[bool]) -> IntMesh {
    let axis = |n: usize| (0..=n as i64).collect::<Vec<_>>();
    let (xs, ys, zs) = (axis(dims[0]), axis(dims[1]), axis(dims[2]));
    rectilinear([&xs, &ys, &zs], |c| {
        on[(c[0] * dims[1] + c[1]) * dims[2] + c[2]]
    })
}

/// Triangles of a simple counter-clockwise polygon by ear clipping (exact orientation
/// tests), as index triples into `poly`.
pub fn ear_clip(poly: &[[i64; 2]]) -> Vec<[usize; 3]> {
    let orient = |a: [i64; 2], b: [i64; 2], c: [i64; 2]| -> i128 {
        (b[0] - a[0]) as i128 * (c[1] - a[1]) as i128
            - (b[1] - a[1]) as i128 * (c[0] - a[0]) as i128
    };
    let mut idx: Vec<usize> = (0..poly.len()).collect();
    let mut out = Vec::new();
    while idx.len() > 3 {
        let n = idx.len();
        let ear = (0..n)
            .find(|&k| {
                let (i, j, l) = (idx[(k + n - 1) % n], idx[k], idx[(k + 1) % n]);
                if orient(poly[i], poly[j], poly[l]) <= 0 {
                    return false;
                }
                idx.iter().all(|&m| {
                    m == i
                        || m == j
                        || m == l
                        || orient(poly[i], poly[j], poly[m]) < 0
                        || orient(poly[j], poly[l], poly[m]) < 0
                        || orient(poly[l], poly[i], poly[m]) < 0
                })
            })
            .expect("a simple polygon has an ear");
        out.push([idx[(ear + n - 1) % n], idx[ear], idx[(ear + 1) % n]]);
        idx.remove(ear);
    }
    out.push([idx[0], idx[1], idx[2]]);
    out
}

/// Twice the signed area of a polygon (positive when counter-clockwise).
pub fn area2(poly: &[[i64; 2]]) -> i128 {
    (0..poly.len())
        .map(|k| {
            let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
            p[0] as i128 * q[1] as i128 - p[1] as i128 * q[0] as i128
        })
        .sum()
}

/// A small deterministic random generator (Knuth's MMIX linear congruential
/// generator, the high bits kept), so that tests never depend on a seed's luck and
/// give the same cases on every machine.
#[derive(Clone, Debug)]
pub struct Lcg(pub u64);

/// The six faces of a cuboid, counter-clockwise seen from outside, as corner indices
/// into [`cuboid_corners`]: corner `b` takes coordinate `k` from the high end when bit
/// `k` of `b` is set.
pub const CUBOID_QUADS: [[u32; 4]; 6] = [
    [0, 2, 3, 1],
    [4, 5, 7, 6],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 4, 6, 2],
    [1, 3, 7, 5],
];

/// The eight corners of the cuboid `lo..hi`, numbered as [`CUBOID_QUADS`] expects.
pub fn cuboid_corners<T: Copy>(lo: [T; 3], hi: [T; 3]) -> Vec<[T; 3]> {
    (0..8)
        .map(|b| [0, 1, 2].map(|k| if b >> k & 1 == 1 { hi[k] } else { lo[k] }))
        .collect()
}

impl Lcg {
    /// Advances the state and returns its high 31 bits.
    pub fn next_bits(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0 >> 33
    }

    /// A number in `0..n` (`n > 0`).
    pub fn below(&mut self, n: u64) -> u64 {
        self.next_bits() % n
    }

    /// A number in `lo..hi` (`lo < hi`).
    pub fn range(&mut self, lo: i64, hi: i64) -> i64 {
        lo + self.below((hi - lo) as u64) as i64
    }

    /// A number in `-n..=n` (`n >= 0`).
    pub fn centred(&mut self, n: i64) -> i64 {
        self.range(-n, n + 1)
    }

    /// Advances the state and returns a float in `[0, 1)` from its high 53 bits.
    pub fn unit(&mut self) -> f64 {
        self.next_bits();
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `n` random disjoint integer boxes `(lo, hi)` linked into `k` parts, box `i` in part
/// `i mod k` (paper 003, section 5.2: the random-boxes benchmark), from `seed`.
pub fn random_boxes(n: usize, k: usize, seed: u64) -> Vec<Vec<([i64; 3], [i64; 3])>> {
    let mut rng = Lcg(seed);
    let mut next = |m: i64| rng.below(m as u64) as i64;
    let side = 12 * (n as f64).cbrt().ceil() as i64 + 12;
    let mut boxes: Vec<([i64; 3], [i64; 3])> = Vec::new();
    while boxes.len() < n {
        let lo = [next(side), next(side), next(side)];
        let hi = [
            lo[0] + 2 + next(8),
            lo[1] + 2 + next(8),
            lo[2] + 2 + next(8),
        ];
        let overlaps = boxes
            .iter()
            .any(|(a, b)| (0..3).all(|d| lo[d] < b[d] && a[d] < hi[d]));
        if !overlaps {
            boxes.push((lo, hi));
        }
    }
    let mut parts = vec![Vec::new(); k];
    for (i, b) in boxes.into_iter().enumerate() {
        parts[i % k].push(b);
    }
    parts
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn voxel_unions_are_closed_with_their_volume() {
        // An L of three unit cubes: volume 3, every edge used once each way.
        let on = [true, false, true, false, true, false, false, false];
        let m = voxels([2, 2, 2], &on);
        assert_eq!(m.volume6(), 6 * 3);
        let mut edges = HashMap::new();
        for t in &m.triangles {
            for k in 0..3 {
                *edges.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
            }
        }
        for (&(a, b), &n) in &edges {
            assert_eq!(n, 1);
            assert_eq!(edges.get(&(b, a)), Some(&1));
        }
    }

    #[test]
    fn ears_cover_the_polygon() {
        let l = [[0, 0], [4, 0], [4, 1], [1, 1], [1, 3], [0, 3]];
        let tris = ear_clip(&l);
        assert_eq!(tris.len(), l.len() - 2);
        let sum: i128 = tris
            .iter()
            .map(|t| area2(&[l[t[0]], l[t[1]], l[t[2]]]))
            .sum();
        assert_eq!(sum, area2(&l));
        assert!(tris.iter().all(|t| area2(&[l[t[0]], l[t[1]], l[t[2]]]) > 0));
    }

    #[test]
    fn the_generator_is_the_mmix_lcg() {
        let mut r = Lcg(99);
        let s = 99u64
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        assert_eq!(r.next_bits(), s >> 33);
        assert!((0..100).all(|_| (3..7).contains(&r.range(3, 7))));
    }
}
