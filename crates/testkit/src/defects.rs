//! Meshes with the defects of real CAD exports, each built so that the repaired result
//! is known in advance: the exact volume (in input units, integer coordinates unless a
//! generator says otherwise) and how many defects of each kind were injected.
//!
//! Every generator emits triangles (never larger polygons, except where a doc comment
//! says so), so the number of triangles and the counts of defects do not depend on how a
//! loader would split polygons.

use crate::Soup;

/// A face of an axis-aligned box: the corner it starts from and its two axes `u, v`,
/// with `u × v` pointing out of the box.
struct BoxFace {
    /// The axis normal to the face and whether the face lies at the high end of it.
    normal: usize,
    high: bool,
    u: usize,
    v: usize,
}

/// The six faces of a box, in the order `-x, +x, -y, +y, -z, +z`.
const FACES: [BoxFace; 6] = [
    BoxFace {
        normal: 0,
        high: false,
        u: 2,
        v: 1,
    },
    BoxFace {
        normal: 0,
        high: true,
        u: 1,
        v: 2,
    },
    BoxFace {
        normal: 1,
        high: false,
        u: 0,
        v: 2,
    },
    BoxFace {
        normal: 1,
        high: true,
        u: 2,
        v: 0,
    },
    BoxFace {
        normal: 2,
        high: false,
        u: 1,
        v: 0,
    },
    BoxFace {
        normal: 2,
        high: true,
        u: 0,
        v: 1,
    },
];

/// Appends face `f` of the box `lo..hi`, split into an `n × m` grid of cells (`n` along
/// the face's first axis, `m` along its second), two triangles per cell, outward.
fn grid_face(soup: &mut Soup, lo: [f64; 3], hi: [f64; 3], f: &BoxFace, n: u32, m: u32) {
    let base = soup.vertices.len() as u32;
    for j in 0..=m {
        for i in 0..=n {
            let mut p = lo;
            p[f.normal] = if f.high { hi[f.normal] } else { lo[f.normal] };
            p[f.u] = lo[f.u] + (hi[f.u] - lo[f.u]) * i as f64 / n as f64;
            p[f.v] = lo[f.v] + (hi[f.v] - lo[f.v]) * j as f64 / m as f64;
            soup.vertices.push(p);
        }
    }
    let at = |i: u32, j: u32| base + j * (n + 1) + i;
    for j in 0..m {
        for i in 0..n {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            soup.faces.push(vec![a, b, c]);
            soup.faces.push(vec![a, c, d]);
        }
    }
}

/// The box `lo..hi` as 12 outward triangles (two per face, faces in the order
/// `-x, +x, -y, +y, -z, +z`). Volume: the product of the extents. No defect.
pub fn box_soup(lo: [f64; 3], hi: [f64; 3]) -> Soup {
    seamed_box_at(lo, hi, [[1, 1]; 6])
}

fn seamed_box_at(lo: [f64; 3], hi: [f64; 3], div: [[u32; 2]; 6]) -> Soup {
    let mut soup = Soup::default();
    for (f, d) in FACES.iter().zip(div) {
        grid_face(&mut soup, lo, hi, f, d[0].max(1), d[1].max(1));
    }
    soup
}

/// Greatest common divisor.
pub fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// Least common multiple (of positive numbers).
pub fn lcm(a: u64, b: u64) -> u64 {
    a / gcd(a, b) * b
}

/// The box `0..extent` whose six faces (`-x, +x, -y, +y, -z, +z`) are each split into
/// its own grid of `div[f][0] × div[f][1]` cells (along the face's two axes: `z, y` for
/// `-x`, `y, z` for `+x`, `x, z` for `-y`, `z, x` for `+y`, `y, x` for `-z`, `x, y` for
/// `+z`), two triangles per cell. Where two faces meet, their vertices along the shared
/// box edge differ, so the edge is a T-junction seam: each face's grid vertices lie
/// inside the other face's unsplit edges.
///
/// Known answer: volume `extent[0] · extent[1] · extent[2]`; the number of vertex
/// insertions that make every seam conforming is [`seamed_box_tjunctions`]`(div)`.
/// Every vertex is on the integer grid when each extent is a multiple of the
/// divisions along its axis ([`seamed_box_extent_unit`]).
pub fn seamed_box(extent: [u64; 3], div: [[u32; 2]; 6]) -> Soup {
    seamed_box_at([0.0; 3], extent.map(|e| e as f64), div)
}

/// The number of cells of face `f` along `axis` (1 for the face's normal axis).
fn divisions_along(div: &[[u32; 2]; 6], f: usize, axis: usize) -> u64 {
    let face = &FACES[f];
    if face.u == axis {
        div[f][0].max(1) as u64
    } else if face.v == axis {
        div[f][1].max(1) as u64
    } else {
        1
    }
}

/// The smallest extent along `axis` that puts every vertex of
/// [`seamed_box`]`(_, div)` on the integer grid: the lcm of the divisions along it.
pub fn seamed_box_extent_unit(div: &[[u32; 2]; 6], axis: usize) -> u64 {
    (0..6).fold(1, |acc, f| lcm(acc, divisions_along(div, f, axis)))
}

/// The number of T-junction vertex insertions that make [`seamed_box`]`(_, div)`
/// conforming: along each of the 12 box edges, where the two faces split the edge into
/// `n` and `m` parts, each side gains the other's vertices that it lacks,
/// `(m - gcd(n, m)) + (n - gcd(n, m))`.
pub fn seamed_box_tjunctions(div: &[[u32; 2]; 6]) -> usize {
    let mut total = 0;
    for (f, ff) in FACES.iter().enumerate() {
        for (g, fg) in FACES.iter().enumerate().skip(f + 1) {
            let (a, b) = (ff.normal, fg.normal);
            if a == b {
                continue;
            }
            let axis = 3 - a - b;
            let (n, m) = (divisions_along(div, f, axis), divisions_along(div, g, axis));
            total += (n + m - 2 * gcd(n, m)) as usize;
        }
    }
    total
}

/// Rounds every coordinate to `f32` (what a binary STL stores), keeping the faces.
pub fn float32_rounded(soup: &Soup) -> Soup {
    Soup {
        vertices: soup
            .vertices
            .iter()
            .map(|v| v.map(|c| c as f32 as f64))
            .collect(),
        faces: soup.faces.clone(),
    }
}

/// A [`seamed_box`] in decimal millimetres far from the origin, as a CAD export would
/// write it: corner `(1000.1, -250.3, 40.7)`, extents `extent · step` with `step = 0.1`
/// (not representable in binary floating point). Written with
/// [`Soup::write_binary_stl`] its coordinates are rounded to `f32`.
///
/// Known answer: while every coordinate stays below 1024 in magnitude (extents below
/// 230), `f32` rounding moves a coordinate by at most `2^-15`, which on the grid
/// `h = 2^-10` is at most 1/32 of a step, whereas `c / h` (a multiple of 102.4) is at
/// least 0.1 away from a half-integer: each corner snaps to `round(c · 1024)` of its
/// decimal value, and the volume in grid units is the product of the snapped extents.
/// The T-junction count is [`seamed_box_tjunctions`]`(div)` (the seams are
/// axis-parallel, so the rounded seam vertices stay exactly on the edges).
pub fn decimal_seamed_box(extent: [u64; 3], div: [[u32; 2]; 6]) -> Soup {
    let lo = [1000.1, -250.3, 40.7];
    let hi = [0, 1, 2].map(|k| lo[k] + extent[k] as f64 * 0.1);
    seamed_box_at(lo, hi, div)
}

/// The corners of [`decimal_seamed_box`]: `(lo, hi)`.
pub fn decimal_seamed_box_corners(extent: [u64; 3]) -> ([f64; 3], [f64; 3]) {
    let lo = [1000.1, -250.3, 40.7];
    let hi = [0, 1, 2].map(|k| lo[k] + extent[k] as f64 * 0.1);
    (lo, hi)
}

/// The box `0..extent` (12 triangles) with the triangles listed in `which` (indices
/// below 12) appended a second time, same orientation. Known answer: volume the product
/// of the extents; duplicate faces `which.len()`.
pub fn duplicated_faces(extent: [u64; 3], which: &[usize]) -> Soup {
    let mut soup = box_soup([0.0; 3], extent.map(|e| e as f64));
    for &t in which {
        let f = soup.faces[t].clone();
        soup.faces.push(f);
    }
    soup
}

/// The box `0..extent` (12 triangles) with the triangles listed in `which` (distinct,
/// fewer than 6) reversed in place. Known answer: volume the product of the extents;
/// flipped faces `which.len()`, no flipped shell.
pub fn flipped_faces(extent: [u64; 3], which: &[usize]) -> Soup {
    let mut soup = box_soup([0.0; 3], extent.map(|e| e as f64));
    for &t in which {
        soup.faces[t].reverse();
    }
    soup
}

/// The box `0..extent`, every triangle reversed. Known answer: volume the product of
/// the extents; one flipped shell, no flipped face.
pub fn inside_out_box(extent: [u64; 3]) -> Soup {
    let mut soup = box_soup([0.0; 3], extent.map(|e| e as f64));
    for f in &mut soup.faces {
        f.reverse();
    }
    soup
}

/// The box `0..extent` with a hole of `k >= 3` edges in its top face (`z = extent[2]`).
/// For `k = 3` one of the two top triangles is missing. For `k >= 4` the whole top face
/// is missing and its rim carries `k` vertices (the 4 corners and `k - 4` more spread
/// over the rim's sides, at integer positions when `extent[0]` and `extent[1]` exceed
/// `k`); the four side faces are then polygons (not triangles) that include those rim
/// vertices. Known answer: volume the product of the extents; one hole closed by
/// `k - 2` triangles.
pub fn holed_box(extent: [u64; 3], k: usize) -> Soup {
    assert!(k >= 3, "a hole has at least 3 edges");
    let hi = extent.map(|e| e as f64);
    if k == 3 {
        let mut soup = box_soup([0.0; 3], hi);
        soup.faces.remove(11); // the second triangle of +z
        return soup;
    }
    let mut soup = Soup::default();
    // The -z face as two triangles.
    grid_face(&mut soup, [0.0; 3], hi, &FACES[4], 1, 1);
    // Rim corners counter-clockwise seen from +z: (0,0), (X,0), (X,Y), (0,Y).
    let corners = [[0.0, 0.0], [hi[0], 0.0], [hi[0], hi[1]], [0.0, hi[1]]];
    let extra = k - 4;
    // Extra vertices per side: spread as evenly as possible.
    let per_side: Vec<usize> = (0..4)
        .map(|s| extra / 4 + usize::from(s < extra % 4))
        .collect();
    for s in 0..4 {
        let (a, b) = (corners[s], corners[(s + 1) % 4]);
        let n = per_side[s] + 1;
        // Side wall of rim side s: bottom a, bottom b, then the rim from b back to a.
        let base = soup.vertices.len() as u32;
        soup.vertices.push([a[0], a[1], 0.0]);
        soup.vertices.push([b[0], b[1], 0.0]);
        let mut face = vec![base, base + 1];
        for i in (0..=n).rev() {
            let t = i as f64 / n as f64;
            let (x, y) = (
                (a[0] + (b[0] - a[0]) * t).round(),
                (a[1] + (b[1] - a[1]) * t).round(),
            );
            face.push(soup.vertices.len() as u32);
            soup.vertices.push([x, y, hi[2]]);
        }
        soup.faces.push(face);
    }
    soup
}

/// Two disjoint boxes in one soup: `0..a` and `(gap + a[0], 0, 0) + 0..b`. Known answer:
/// two bodies, of volumes `a0·a1·a2` and `b0·b1·b2` (in that order); nothing to repair.
pub fn two_boxes(a: [u64; 3], b: [u64; 3], gap: u64) -> Soup {
    let mut soup = box_soup([0.0; 3], a.map(|e| e as f64));
    let x = (a[0] + gap) as f64;
    soup.append(&box_soup(
        [x, 0.0, 0.0],
        [x + b[0] as f64, b[1] as f64, b[2] as f64],
    ));
    soup
}

/// Two unit-spaced boxes `0..(s,s,s)` and `(s,0,0)..(2s,s,s)` that share their wall
/// `x = s`, exported each with its own wall: after welding, the two copies of the wall
/// (2 triangles each, with the same diagonal) run opposite ways. Known answer: 4
/// cancelled faces, one body of volume `2 s³`.
pub fn boxes_sharing_a_wall(s: u64) -> Soup {
    let s = s as f64;
    let mut soup = box_soup([0.0; 3], [s, s, s]);
    let mut right = box_soup([s, 0.0, 0.0], [2.0 * s, s, s]);
    // Make the right box's -x wall use the same diagonal as the left box's +x wall:
    // the left wall's triangles, reversed.
    let left_wall: Vec<Vec<u32>> = soup.faces[2..4].to_vec();
    let base = right.vertices.len() as u32;
    right.vertices.extend_from_slice(&soup.vertices);
    for (k, f) in left_wall.iter().enumerate() {
        right.faces[k] = f.iter().rev().map(|&v| v + base).collect();
    }
    soup.append(&right);
    soup
}

/// Two boxes `0..(s,s,s)` and `(s,s,0)..(2s,2s,s)` touching along the edge
/// `x = y = s`. Known answer: nothing to repair; two bodies of volume `s³` each (the
/// surface is connected only through an edge used by four faces).
pub fn boxes_sharing_an_edge(s: u64) -> Soup {
    let s = s as f64;
    let mut soup = box_soup([0.0; 3], [s, s, s]);
    soup.append(&box_soup([s, s, 0.0], [2.0 * s, 2.0 * s, s]));
    soup
}

/// The box `0..outer` with the cavity `inner_lo..inner_hi` (strictly inside). With
/// `cavity_outward` the cavity shell is written outward like a solid (the usual export
/// defect: one flipped shell to repair), otherwise inward (valid as is). Known answer:
/// one body with two shells; volume `outer volume - cavity volume`.
pub fn hollow_box(
    outer: [u64; 3],
    inner_lo: [u64; 3],
    inner_hi: [u64; 3],
    cavity_outward: bool,
) -> Soup {
    let mut soup = box_soup([0.0; 3], outer.map(|e| e as f64));
    let mut cavity = box_soup(inner_lo.map(|e| e as f64), inner_hi.map(|e| e as f64));
    if !cavity_outward {
        for f in &mut cavity.faces {
            f.reverse();
        }
    }
    soup.append(&cavity);
    soup
}

/// A closed, consistently oriented surface that crosses itself: the box `0..10` whose
/// top corner `(10, 10, 10)` is pulled down to `(10, 10, -4)`, through the bottom face.
/// The top and the two walls at that corner become folds whose triangles pierce the
/// bottom face. Known answer: repair must change nothing (every edge is paired, the
/// volume stays positive), and validation must still report self-intersection.
pub fn self_crossing_fold() -> Soup {
    let mut soup = box_soup([0.0; 3], [10.0; 3]);
    for v in &mut soup.vertices {
        if *v == [10.0, 10.0, 10.0] {
            *v = [10.0, 10.0, -4.0];
        }
    }
    soup
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Six times the signed volume of a triangle soup (exact for small integers).
    fn volume6(s: &Soup) -> f64 {
        s.faces
            .iter()
            .flat_map(|f| (1..f.len() - 1).map(move |k| [f[0], f[k], f[k + 1]]))
            .map(|t| {
                let [a, b, c] = t.map(|i| s.vertices[i as usize]);
                a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0])
            })
            .sum()
    }

    #[test]
    fn generators_have_their_volumes() {
        assert_eq!(volume6(&box_soup([0.0; 3], [2.0, 3.0, 4.0])), 144.0);
        let div = [[2, 3], [1, 1], [4, 1], [1, 2], [3, 3], [1, 5]];
        let e = [0, 1, 2].map(|k| seamed_box_extent_unit(&div, k));
        assert_eq!(e, [12, 15, 2]);
        assert_eq!(volume6(&seamed_box(e, div)), 6.0 * (12 * 15 * 2) as f64);
        assert_eq!(volume6(&inside_out_box([1, 2, 3])), -36.0);
        assert_eq!(
            volume6(&hollow_box([4; 3], [1; 3], [3; 3], false)),
            6.0 * 56.0
        );
        assert_eq!(volume6(&boxes_sharing_a_wall(2)), 96.0);
        assert_eq!(box_soup([0.0; 3], [1.0; 3]).faces.len(), 12);
    }

    #[test]
    fn tjunction_counts() {
        assert_eq!(seamed_box_tjunctions(&[[1, 1]; 6]), 0);
        // Only +z split 2 × 1: its 4 rim edges, 2 of them (along x) split in 2.
        let mut div = [[1, 1]; 6];
        div[5] = [2, 1];
        assert_eq!(seamed_box_tjunctions(&div), 2);
        div[5] = [2, 3];
        assert_eq!(seamed_box_tjunctions(&div), 2 + 2 * 2);
        // Both faces at an edge split in 2: nothing to insert there.
        let div = [[2, 2]; 6];
        assert_eq!(seamed_box_tjunctions(&div), 0);
    }

    #[test]
    fn holed_box_rim() {
        for k in 3..12 {
            let s = holed_box([20, 20, 5], k);
            // Boundary edges: those used once.
            let mut edges = std::collections::HashMap::new();
            let key = |v: [f64; 3]| v.map(|c| c as i64);
            for f in &s.faces {
                for i in 0..f.len() {
                    let (a, b) = (
                        key(s.vertices[f[i] as usize]),
                        key(s.vertices[f[(i + 1) % f.len()] as usize]),
                    );
                    *edges
                        .entry(if a < b { (a, b) } else { (b, a) })
                        .or_insert(0) += 1;
                }
            }
            assert_eq!(edges.values().filter(|&&n| n == 1).count(), k, "k = {k}");
        }
    }
}
