//! Floating-point geometry of input triangles: nearest points, distances, crossings,
//! and the witness of a point of one part lying just behind a face of another. These
//! measures only decide whether snapping changed a relation worth a warning; the
//! relation after snapping is decided exactly elsewhere.
// Float measures here are written so that a NaN (from a degenerate triangle) fails
// every test: `!(x > 0.0)` is meant, not `x <= 0.0`.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use apart_kernel::fvec::{add, cross, dot, lerp, norm, scale, sub, F3};

/// A triangle of input coordinates.
pub(super) type Tri = [F3; 3];

/// Rounding noise of a float measure, relative to the magnitude of the (local)
/// coordinates it is computed from.
pub(super) const NOISE: f64 = 64.0 * f64::EPSILON;

pub(super) fn max_abs<'a>(points: impl IntoIterator<Item = &'a F3>) -> f64 {
    points
        .into_iter()
        .flat_map(|p| p.iter())
        .fold(0.0, |m: f64, c| m.max(c.abs()))
}

/// The point of triangle `t` nearest to `p` (Ericson, Real-Time Collision Detection,
/// 5.1.5).
pub(super) fn closest_on_triangle(p: F3, t: &Tri) -> F3 {
    let [a, b, c] = *t;
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return add(a, scale(ab, d1 / (d1 - d3)));
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return add(a, scale(ac, d2 / (d2 - d6)));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return add(b, scale(sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6))));
    }
    let denom = 1.0 / (va + vb + vc);
    add(a, add(scale(ab, vb * denom), scale(ac, vc * denom)))
}

/// The nearest points of segments `p1 q1` and `p2 q2` (Ericson 5.1.9).
pub(super) fn closest_on_segments(p1: F3, q1: F3, p2: F3, q2: F3) -> (F3, F3) {
    let (d1, d2, r) = (sub(q1, p1), sub(q2, p2), sub(p1, p2));
    let (a, e, f) = (dot(d1, d1), dot(d2, d2), dot(d2, r));
    let (s, t);
    if a == 0.0 && e == 0.0 {
        return (p1, p2);
    }
    if a == 0.0 {
        s = 0.0;
        t = (f / e).clamp(0.0, 1.0);
    } else {
        let c = dot(d1, r);
        if e == 0.0 {
            t = 0.0;
            s = (-c / a).clamp(0.0, 1.0);
        } else {
            let b = dot(d1, d2);
            let denom = a * e - b * b;
            let s0 = match denom != 0.0 {
                true => ((b * f - c * e) / denom).clamp(0.0, 1.0),
                false => 0.0,
            };
            let t0 = (b * s0 + f) / e;
            (s, t) = if t0 < 0.0 {
                ((-c / a).clamp(0.0, 1.0), 0.0)
            } else if t0 > 1.0 {
                (((b - c) / a).clamp(0.0, 1.0), 1.0)
            } else {
                (s0, t0)
            };
        }
    }
    (add(p1, scale(d1, s)), add(p2, scale(d2, t)))
}

/// Where segment `p q` crosses triangle `t` (not in its plane), if it does.
pub(super) fn segment_crosses(p: F3, q: F3, t: &Tri) -> Option<F3> {
    let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
    let (dp, dq) = (dot(n, sub(p, t[0])), dot(n, sub(q, t[0])));
    if (dp > 0.0 && dq > 0.0) || (dp < 0.0 && dq < 0.0) || dp == dq {
        return None;
    }
    let x = lerp(p, q, dp / (dp - dq));
    let inside = (0..3).all(|i| {
        let (a, b) = (t[i], t[(i + 1) % 3]);
        dot(n, cross(sub(b, a), sub(x, a))) >= 0.0
    });
    inside.then_some(x)
}

/// The distance between segment `p q` and triangle `t`.
pub(super) fn segment_distance(p: F3, q: F3, t: &Tri) -> f64 {
    if segment_crosses(p, q, t).is_some() {
        return 0.0;
    }
    let mut best = norm(sub(p, closest_on_triangle(p, t)));
    best = best.min(norm(sub(q, closest_on_triangle(q, t))));
    for i in 0..3 {
        let (x, y) = closest_on_segments(p, q, t[i], t[(i + 1) % 3]);
        best = best.min(norm(sub(x, y)));
    }
    best
}

/// The distance between two triangles, and the point halfway between their nearest
/// points. NaN measures of degenerate triangles are skipped.
pub(super) fn distance(a: &Tri, b: &Tri) -> (f64, F3) {
    for (s, t) in [(a, b), (b, a)] {
        for i in 0..3 {
            if let Some(x) = segment_crosses(s[i], s[(i + 1) % 3], t) {
                return (0.0, x);
            }
        }
    }
    let mut best = (f64::INFINITY, a[0]);
    let mut consider = |x: F3, y: F3| {
        let d = norm(sub(x, y));
        if d < best.0 {
            best = (d, lerp(x, y, 0.5));
        }
    };
    for (s, t) in [(a, b), (b, a)] {
        for p in s {
            consider(*p, closest_on_triangle(*p, t));
        }
    }
    for i in 0..3 {
        for j in 0..3 {
            let (x, y) = closest_on_segments(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]);
            consider(x, y);
        }
    }
    best
}

/// The part of convex polygon `poly` on the side `dot(w, x - a) >= 0`.
pub(super) fn clip(poly: &[F3], a: F3, w: F3) -> Vec<F3> {
    let mut out = Vec::with_capacity(poly.len() + 1);
    for (i, &p) in poly.iter().enumerate() {
        let q = poly[(i + 1) % poly.len()];
        let (dp, dq) = (dot(w, sub(p, a)), dot(w, sub(q, a)));
        if dp >= 0.0 {
            out.push(p);
        }
        if (dp >= 0.0) != (dq >= 0.0) {
            out.push(lerp(p, q, dp / (dp - dq)));
        }
    }
    out
}

/// A point of triangle `t` (of one part) inside the other part just behind its face
/// `f = faces[k]` (outward, counter-clockwise), less than `cap` deep: the deepest
/// depth of `t` behind `f` within the prism over `f`, and the point. The other
/// `faces` are those of the other part near `t`: none may lie between the point and
/// `f`.
/// Coordinates are relative to a nearby origin; only depths above `floor` count.
pub(super) fn witness(
    t: &Tri,
    faces: &[(Tri, F3)],
    k: usize,
    cap: f64,
    floor: f64,
) -> Option<(f64, F3)> {
    let (f, n) = (&faces[k].0, faces[k].1);
    if n == [0.0; 3] {
        return None;
    }
    let z = |x: F3| dot(n, sub(x, f[0]));
    // The part of `t` over `f` lies between the heights of `t`'s corners. (Most
    // pairs end at the first test, before the noise bound is computed.)
    let zt = t.map(z);
    let (lo, hi) = (zt[0].min(zt[1]).min(zt[2]), zt[0].max(zt[1]).max(zt[2]));
    if lo >= 0.0 || hi < -cap || -lo <= floor {
        return None;
    }
    let noise = NOISE * max_abs(t.iter().chain(f));
    if !(lo < -noise) {
        return None;
    }
    let mut walls = [(f[0], n); 3];
    let mut poly: Vec<F3> = t.to_vec();
    for i in 0..3 {
        let (a, b) = (f[i], f[(i + 1) % 3]);
        let w = cross(n, sub(b, a));
        let lw = norm(w);
        if !(lw > 0.0) {
            return None;
        }
        walls[i] = (a, scale(w, 1.0 / lw));
        poly = clip(&poly, a, walls[i].1);
        if poly.is_empty() {
            return None;
        }
    }
    let (vmin, zmin) = poly
        .iter()
        .map(|&v| (v, z(v)))
        .fold(
            (poly[0], f64::INFINITY),
            |a, b| if b.1 < a.1 { b } else { a },
        );
    if !(zmin < -noise) || -zmin > cap || -zmin <= floor {
        return None;
    }
    let c = scale(
        poly.iter().fold([0.0; 3], |s, &v| add(s, v)),
        1.0 / poly.len() as f64,
    );
    let margin = |x: F3| {
        walls
            .iter()
            .map(|(a, w)| dot(*w, sub(x, *a)))
            .fold(f64::INFINITY, f64::min)
    };
    let mc = margin(c);
    if !(mc > noise) {
        return None;
    }
    // A point strictly inside the prism and strictly behind the face: the centroid,
    // or a point between the deepest vertex and the centroid.
    let zc = z(c);
    let x = if zc < -noise {
        c
    } else {
        let l = 0.5 * (-noise - zmin) / (zc - zmin);
        if !(l * mc > noise) {
            return None;
        }
        lerp(vmin, c, l)
    };
    let foot = sub(x, scale(n, z(x)));
    let between = faces
        .iter()
        .enumerate()
        .any(|(j, o)| j != k && segment_distance(x, foot, &o.0) <= noise);
    if between {
        return None;
    }
    Some((-zmin, x))
}
