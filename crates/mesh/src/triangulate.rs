//! Splitting snapped polygons into triangles, exactly.
//!
//! - triangles are kept as they are (unless they have zero area);
//! - planar, strictly convex polygons are split by a fan (up to [`SMALL`] vertices) or
//!   by a strip zigzagging between the two ends of the vertex list (larger ones);
//! - other planar polygons (non-convex, or with vertices in the middle of a side) are
//!   split by ear clipping (up to [`SMALL`] vertices) or by a sweep into monotone
//!   pieces (larger ones, `O(n log n)`, [`sweep`]), with every turn and containment
//!   decided by exact orientation tests in the plane's projection;
//! - polygons that snapping made non-planar are split like their projection when it is
//!   simple (a fan up to [`SMALL`] vertices), and reported;
//! - polygons that are not simple are split by a fan (a strip above [`SMALL`]
//!   vertices), and reported.
//!
//! Large polygons get strips and sweeps rather than fans and ear clipping because both
//! are quadratic: ear clipping in its search for ears, and a fan in the validation
//! that follows: every triangle of a fan spans the polygon, so its bounding box meets
//! those of the faces around the polygon's rim (a prism over a 100,000-gon has ten
//! billion such pairs, and took minutes to check). A strip's and a sweep's triangles are
//! thin slabs across the polygon, each meeting the boxes of a few rim faces only.

mod sweep;

use apart_kernel::orient::{
    collinear, dominant_axis, in_closed_triangle_2d, normal, orient2d, orient3d, project,
};
use apart_kernel::Sign;

/// Polygons up to this many vertices keep the simple methods (fan, ear clipping).
pub(crate) const SMALL: usize = 32;
/// When the sweep fails on a planar polygon (one touching itself), ear clipping is
/// still tried up to this many vertices (its cost grows with the square).
const EAR_CLIP_MAX: usize = 1024;

/// What happened to a polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Outcome {
    /// Split into triangles (maybe just one).
    Ok,
    /// No area: dropped.
    ZeroArea,
    /// Not planar after snapping: split like its projection, or by a fan or strip.
    NonPlanar,
    /// Planar but not a simple polygon: split by a fan or strip.
    NotSimple,
}

/// Appends the triangles of `polygon` (indices into `points`) to `out`.
pub(crate) fn triangulate(
    polygon: &[u32],
    points: &[[i64; 3]],
    out: &mut Vec<[u32; 3]>,
) -> Outcome {
    // Drop consecutive repeats (cyclically): snapping may have merged neighbours.
    let mut p: Vec<u32> = Vec::with_capacity(polygon.len());
    for &v in polygon {
        if p.last() != Some(&v) {
            p.push(v);
        }
    }
    while p.len() > 1 && p.first() == p.last() {
        p.pop();
    }
    let at = |i: u32| &points[i as usize];
    if p.len() < 3 {
        return Outcome::ZeroArea;
    }
    if p.len() == 3 {
        if collinear(at(p[0]), at(p[1]), at(p[2])) {
            return Outcome::ZeroArea;
        }
        out.push([p[0], p[1], p[2]]);
        return Outcome::Ok;
    }
    let n = p.len();
    // A reference plane through three non-collinear vertices.
    let Some((i, j)) = reference_pair(&p, points) else {
        return Outcome::ZeroArea;
    };
    let (a, b, c) = (at(p[0]), at(p[i]), at(p[j]));
    if p.iter().any(|&v| orient3d(a, b, c, at(v)) != Sign::Zero) {
        if n > SMALL {
            // Project along the axis the polygon faces most (Newell's normal, in
            // floating point: any axis is exact, this one keeps it simple).
            let axis = newell_axis(&p, points);
            let q: Vec<[i64; 2]> = p.iter().map(|&v| project(at(v), axis)).collect();
            let before = out.len();
            if let Some(s) = orientation_2d(&q) {
                if strictly_convex(&q, s) {
                    strip(&p, points, out);
                    return Outcome::NonPlanar;
                }
                if sweep::triangulate(&p, &q, s, out) {
                    return Outcome::NonPlanar;
                }
            }
            out.truncate(before);
            strip(&p, points, out);
        } else {
            fan(&p, points, out);
        }
        return Outcome::NonPlanar;
    }
    let axis = dominant_axis(&normal(a, b, c));
    let q: Vec<[i64; 2]> = p.iter().map(|&v| project(at(v), axis)).collect();
    let not_simple = |out: &mut Vec<[u32; 3]>| {
        if n > SMALL {
            strip(&p, points, out);
        } else {
            fan(&p, points, out);
        }
        Outcome::NotSimple
    };
    let Some(orientation) = orientation_2d(&q) else {
        return not_simple(out);
    };
    if strictly_convex(&q, orientation) {
        if n > SMALL {
            strip(&p, points, out);
        } else {
            for k in 1..n - 1 {
                out.push([p[0], p[k], p[k + 1]]);
            }
        }
        return Outcome::Ok;
    }
    if n > SMALL && sweep::triangulate(&p, &q, orientation, out) {
        return Outcome::Ok;
    }
    let before = out.len();
    if n <= EAR_CLIP_MAX && ear_clip(&p, &q, orientation, out) {
        Outcome::Ok
    } else {
        out.truncate(before);
        not_simple(out)
    }
}

/// The axis of the largest component of the polygon's Newell normal (its area vector).
fn newell_axis(p: &[u32], points: &[[i64; 3]]) -> usize {
    let mut n = [0f64; 3];
    for (k, &v) in p.iter().enumerate() {
        let (a, b) = (&points[v as usize], &points[p[(k + 1) % p.len()] as usize]);
        let f = |i: usize| a[i] as f64;
        let g = |i: usize| b[i] as f64;
        n[0] += (f(1) - g(1)) * (f(2) + g(2));
        n[1] += (f(2) - g(2)) * (f(0) + g(0));
        n[2] += (f(0) - g(0)) * (f(1) + g(1));
    }
    let m = n.map(f64::abs);
    if m[0] >= m[1] && m[0] >= m[2] {
        0
    } else if m[1] >= m[2] {
        1
    } else {
        2
    }
}

/// A strip zigzagging between the two ends of the vertex list, skipping triangles of
/// zero area: `(0, 1, n-1), (1, n-2, n-1), (1, 2, n-2), ...`. For a convex polygon
/// its triangles are slabs across the polygon (a valid triangulation, like a fan).
fn strip(p: &[u32], points: &[[i64; 3]], out: &mut Vec<[u32; 3]>) {
    let (mut lo, mut hi) = (0usize, p.len() - 1);
    let mut forward = true;
    while hi - lo >= 2 {
        let t = if forward {
            lo += 1;
            [p[lo - 1], p[lo], p[hi]]
        } else {
            hi -= 1;
            [p[lo], p[hi], p[hi + 1]]
        };
        forward = !forward;
        if !collinear(
            &points[t[0] as usize],
            &points[t[1] as usize],
            &points[t[2] as usize],
        ) {
            out.push(t);
        }
    }
}

/// Indices `i < j` with `p[0], p[i], p[j]` not collinear.
fn reference_pair(p: &[u32], points: &[[i64; 3]]) -> Option<(usize, usize)> {
    let a = &points[p[0] as usize];
    let i = (1..p.len()).find(|&i| points[p[i] as usize] != *a)?;
    let b = &points[p[i] as usize];
    let j = (i + 1..p.len()).find(|&j| !collinear(a, b, &points[p[j] as usize]))?;
    Some((i, j))
}

/// A fan from the first vertex, skipping triangles of zero area.
fn fan(p: &[u32], points: &[[i64; 3]], out: &mut Vec<[u32; 3]>) {
    for k in 1..p.len() - 1 {
        let t = [p[0], p[k], p[k + 1]];
        if !collinear(
            &points[t[0] as usize],
            &points[t[1] as usize],
            &points[t[2] as usize],
        ) {
            out.push(t);
        }
    }
}

/// The turn at the lexicographically smallest vertex, which is convex in a simple
/// polygon: the polygon's orientation in the projection. `None` when it is a straight
/// turn (then the polygon is not simple).
fn orientation_2d(q: &[[i64; 2]]) -> Option<Sign> {
    let n = q.len();
    let m = (0..n).min_by_key(|&i| (q[i], i))?;
    let s = orient2d(&q[(m + n - 1) % n], &q[m], &q[(m + 1) % n]);
    (s != Sign::Zero).then_some(s)
}

/// Every turn strictly in the polygon's orientation, and the boundary winds once (the
/// edge directions cross the horizontal exactly twice).
fn strictly_convex(q: &[[i64; 2]], s: Sign) -> bool {
    let n = q.len();
    if (0..n).any(|i| orient2d(&q[(i + n - 1) % n], &q[i], &q[(i + 1) % n]) != s) {
        return false;
    }
    let dys: Vec<i64> = (0..n)
        .map(|i| (q[(i + 1) % n][1] - q[i][1]).signum())
        .filter(|&d| d != 0)
        .collect();
    let m = dys.len();
    let changes = (0..m).filter(|&i| dys[i] != dys[(i + 1) % m]).count();
    changes == 2
}

/// Ear clipping on the projected polygon `q` (orientation `s`), emitting triangles of
/// `p`'s indices. Only vertices that are not strictly convex can lie inside an ear, so
/// only they are checked. Returns false when no ear can be found (not a simple polygon).
fn ear_clip(p: &[u32], q: &[[i64; 2]], s: Sign, out: &mut Vec<[u32; 3]>) -> bool {
    let n = p.len();
    let mut prev: Vec<usize> = (0..n).map(|i| (i + n - 1) % n).collect();
    let mut next: Vec<usize> = (0..n).map(|i| (i + 1) % n).collect();
    let convex =
        |i: usize, prev: &[usize], next: &[usize]| orient2d(&q[prev[i]], &q[i], &q[next[i]]) == s;
    let mut concave: Vec<usize> = (0..n).filter(|&i| !convex(i, &prev, &next)).collect();
    let mut alive = vec![true; n];
    let mut left = n;
    let mut i = 0usize;
    let mut since_last = 0usize;
    while left > 3 {
        if since_last > left {
            return false;
        }
        since_last += 1;
        let (a, c) = (prev[i], next[i]);
        let is_ear = convex(i, &prev, &next)
            && !concave.iter().any(|&m| {
                alive[m]
                    && m != a
                    && m != c
                    && m != i
                    && q[m] != q[a]
                    && q[m] != q[i]
                    && q[m] != q[c]
                    && in_closed_triangle_2d(&q[m], &q[a], &q[i], &q[c])
            });
        if !is_ear {
            i = c;
            continue;
        }
        out.push([p[a], p[i], p[c]]);
        alive[i] = false;
        next[a] = c;
        prev[c] = a;
        left -= 1;
        since_last = 0;
        concave.retain(|&m| alive[m] && !convex(m, &prev, &next));
        i = a;
    }
    let a = prev[i];
    let c = next[i];
    let last = orient2d(&q[a], &q[i], &q[c]);
    if last == -s {
        return false; // the rest turns the other way: the polygon crosses itself
    }
    if last == s {
        out.push([p[a], p[i], p[c]]);
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area2(ts: &[[u32; 3]], pts: &[[i64; 3]]) -> i128 {
        // Twice the projected (xy) signed area.
        ts.iter()
            .map(|t| {
                normal(
                    &pts[t[0] as usize],
                    &pts[t[1] as usize],
                    &pts[t[2] as usize],
                )[2]
            })
            .sum()
    }

    #[test]
    fn convex_quad_by_fan() {
        let pts = vec![[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0]];
        let mut out = Vec::new();
        assert_eq!(triangulate(&[0, 1, 2, 3], &pts, &mut out), Outcome::Ok);
        assert_eq!(out, vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn collinear_midpoints_keep_the_area_and_the_vertices() {
        // A square with a vertex in the middle of every side.
        let pts = vec![
            [0, 0, 0],
            [1, 0, 0],
            [2, 0, 0],
            [2, 1, 0],
            [2, 2, 0],
            [1, 2, 0],
            [0, 2, 0],
            [0, 1, 0],
        ];
        let poly: Vec<u32> = (0..8).collect();
        let mut out = Vec::new();
        assert_eq!(triangulate(&poly, &pts, &mut out), Outcome::Ok);
        assert_eq!(out.len(), 6);
        assert_eq!(area2(&out, &pts), 8);
        for t in &out {
            assert!(!collinear(
                &pts[t[0] as usize],
                &pts[t[1] as usize],
                &pts[t[2] as usize]
            ));
        }
        // Every side piece is an edge of some triangle (no T-junction).
        for k in 0..8u32 {
            let e = (k, (k + 1) % 8);
            assert!(out
                .iter()
                .any(|t| (0..3).any(|i| (t[i], t[(i + 1) % 3]) == e)));
        }
    }

    #[test]
    fn non_convex_by_ear_clipping() {
        // An L shape, clockwise seen from +z, in the plane z = 5.
        let pts = vec![
            [0, 0, 5],
            [0, 3, 5],
            [1, 3, 5],
            [1, 1, 5],
            [3, 1, 5],
            [3, 0, 5],
        ];
        let mut out = Vec::new();
        assert_eq!(
            triangulate(&[0, 1, 2, 3, 4, 5], &pts, &mut out),
            Outcome::Ok
        );
        assert_eq!(out.len(), 4);
        assert_eq!(area2(&out, &pts), -10);
        // A comb in a vertical plane.
        let pts: Vec<[i64; 3]> = [
            [0, 0],
            [6, 0],
            [6, 3],
            [5, 3],
            [5, 1],
            [4, 1],
            [4, 3],
            [2, 3],
            [2, 1],
            [1, 1],
            [1, 3],
            [0, 3],
        ]
        .iter()
        .map(|v| [7, v[0], v[1]])
        .collect();
        let poly: Vec<u32> = (0..12).collect();
        let mut out = Vec::new();
        assert_eq!(triangulate(&poly, &pts, &mut out), Outcome::Ok);
        assert_eq!(out.len(), 10);
        let a: i128 = out
            .iter()
            .map(|t| {
                normal(
                    &pts[t[0] as usize],
                    &pts[t[1] as usize],
                    &pts[t[2] as usize],
                )[0]
            })
            .sum();
        assert_eq!(a, 2 * (18 - 2 - 2));
    }

    #[test]
    fn degenerate_polygons() {
        let pts = vec![[0, 0, 0], [1, 1, 1], [2, 2, 2], [3, 3, 3]];
        let mut out = Vec::new();
        assert_eq!(triangulate(&[0, 1, 2], &pts, &mut out), Outcome::ZeroArea);
        assert_eq!(
            triangulate(&[0, 1, 2, 3], &pts, &mut out),
            Outcome::ZeroArea
        );
        assert_eq!(triangulate(&[0, 0, 1], &pts, &mut out), Outcome::ZeroArea);
        assert_eq!(
            triangulate(&[2, 2, 2, 2], &pts, &mut out),
            Outcome::ZeroArea
        );
        assert!(out.is_empty());
    }

    #[test]
    fn non_planar_and_non_simple() {
        let pts = vec![[0, 0, 0], [2, 0, 0], [2, 2, 1], [0, 2, 0]];
        let mut out = Vec::new();
        assert_eq!(
            triangulate(&[0, 1, 2, 3], &pts, &mut out),
            Outcome::NonPlanar
        );
        assert_eq!(out.len(), 2);
        // A bow tie (self-crossing quad).
        let pts = vec![[0, 0, 0], [2, 2, 0], [2, 0, 0], [0, 2, 0]];
        let mut out = Vec::new();
        assert_eq!(
            triangulate(&[0, 1, 2, 3], &pts, &mut out),
            Outcome::NotSimple
        );
        // A pentagram winds twice: its triangles overlap, which the self-intersection
        // check of the solid reports; here it must at least not be taken as convex.
        let q: Vec<[i64; 2]> = vec![[0, 10], [6, -8], [-10, 3], [10, 3], [-6, -8]];
        let s = orientation_2d(&q).unwrap();
        assert!(!strictly_convex(&q, s));
    }

    /// A ring of `n` points (radius `r`, every other one at `inner` times it), lifted
    /// by `lift(k)` off the plane z = 0.
    fn ring(n: usize, r: f64, inner: f64, lift: impl Fn(usize) -> i64) -> Vec<[i64; 3]> {
        (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                let r = if k % 2 == 1 { r * inner } else { r };
                [
                    (r * a.cos()).round() as i64,
                    (r * a.sin()).round() as i64,
                    lift(k),
                ]
            })
            .collect()
    }

    /// `n - 2` triangles of non-zero area covering the polygon's projected area once.
    fn covers(poly: &[u32], pts: &[[i64; 3]], out: &[[u32; 3]]) {
        assert_eq!(out.len(), poly.len() - 2);
        let q: Vec<[i64; 2]> = poly.iter().map(|&v| project(&pts[v as usize], 2)).collect();
        let twice: i128 = (0..q.len())
            .map(|i| {
                let (a, b) = (q[i], q[(i + 1) % q.len()]);
                a[0] as i128 * b[1] as i128 - b[0] as i128 * a[1] as i128
            })
            .sum();
        assert_eq!(area2(out, pts), twice);
        for t in out {
            assert_eq!(
                orient2d(
                    &project(&pts[t[0] as usize], 2),
                    &project(&pts[t[1] as usize], 2),
                    &project(&pts[t[2] as usize], 2)
                ),
                Sign::of_i128(twice)
            );
        }
    }

    #[test]
    fn large_polygons() {
        let n = 5000;
        let poly: Vec<u32> = (0..n as u32).collect();
        // Convex: a strip, whose triangles are slabs (none spans from one side of the
        // circle to a point a quarter turn away, as a fan's do).
        // (Radius 1e9: the rounded ring stays strictly convex; at 1e6 it does not,
        // and goes to the sweep, whose triangles are slabs too.)
        for r in [1e9, 1e6] {
            let pts = ring(n, r, 1.0, |_| 0);
            let mut out = Vec::new();
            assert_eq!(triangulate(&poly, &pts, &mut out), Outcome::Ok);
            covers(&poly, &pts, &out);
            assert!(out.iter().filter(|t| t.contains(&0)).count() <= 3);
        }
        // Non-convex, both orientations: the sweep.
        let pts = ring(n, 1e6, 0.9, |_| 7);
        for poly in [poly.clone(), poly.iter().rev().copied().collect()] {
            let mut out = Vec::new();
            assert_eq!(triangulate(&poly, &pts, &mut out), Outcome::Ok);
            covers(&poly, &pts, &out);
        }
        // Not planar (a wavy rim): split like its projection, and reported.
        for inner in [1.0, 0.9] {
            let pts = ring(n, 1e6, inner, |k| (k % 3) as i64);
            let mut out = Vec::new();
            assert_eq!(triangulate(&poly, &pts, &mut out), Outcome::NonPlanar);
            covers(&poly, &pts, &out);
        }
        // Not simple (a vertex moved across the polygon): a strip, reported.
        let mut pts = ring(n, 1e6, 0.9, |_| 0);
        pts[10] = [-pts[10][0], -pts[10][1], 0];
        let mut out = Vec::new();
        assert_eq!(triangulate(&poly, &pts, &mut out), Outcome::NotSimple);
        assert!(out.len() <= n - 2);
    }
}
