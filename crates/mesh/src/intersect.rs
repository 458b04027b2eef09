//! Exact intersection tests between triangles and segments on the grid.
//!
//! Triangles of one mesh may legitimately share a vertex or an edge (after welding,
//! equal points have equal indices). [`triangle_pair`] reports an intersection only
//! when the closed triangles meet beyond the convex hull of their shared vertices.

use apart_kernel::orient::{
    cross, dominant_axis, in_closed_triangle_2d, normal, orient2d, orient3d, orient3d_many,
    project, segments_meet_2d, sub, P3,
};
use apart_kernel::{Int, Rational, Sign};

/// How two triangles of a mesh meet beyond what they share.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Contact {
    /// They cross or touch in a point or segment that is not shared.
    Intersect,
    /// They are coplanar and overlap in an area.
    Overlap,
}

/// Closed segment `p q` against closed triangle `a b c` (non-degenerate).
pub fn segment_meets_triangle(p: &P3, q: &P3, a: &P3, b: &P3, c: &P3) -> bool {
    let op = orient3d(a, b, c, p);
    let oq = orient3d(a, b, c, q);
    if op != Sign::Zero && op == oq {
        return false;
    }
    if op == Sign::Zero && oq == Sign::Zero {
        let k = dominant_axis(&normal(a, b, c));
        let [p2, q2, a2, b2, c2] = [p, q, a, b, c].map(|v| project(v, k));
        return in_closed_triangle_2d(&p2, &a2, &b2, &c2)
            || segments_meet_2d(&p2, &q2, &a2, &b2)
            || segments_meet_2d(&p2, &q2, &b2, &c2)
            || segments_meet_2d(&p2, &q2, &c2, &a2);
    }
    // The line crosses the plane once, within the segment; is that point in the triangle?
    let s1 = orient3d(p, q, a, b);
    let s2 = orient3d(p, q, b, c);
    let s3 = orient3d(p, q, c, a);
    let has_pos = [s1, s2, s3].contains(&Sign::Positive);
    let has_neg = [s1, s2, s3].contains(&Sign::Negative);
    !(has_pos && has_neg)
}

/// Closed triangles `t` and `u` with no shared vertex: do they meet?
pub fn triangles_meet(t: [&P3; 3], u: [&P3; 3]) -> Option<Contact> {
    let [a, b, c] = t;
    let [d, e, f] = u;
    let ou = orient3d_many(a, b, c, u);
    if ou[0] != Sign::Zero && ou[0] == ou[1] && ou[1] == ou[2] {
        return None;
    }
    // When u lies in t's plane, t lies in u's (or u is degenerate and every orientation
    // against it is zero): the test of t against u's plane below could not exit, so
    // coplanar pairs skip it.
    // (A degenerate t has every point in its "plane": then the test is still needed.)
    let coplanar = ou.iter().all(|s| *s == Sign::Zero);
    if !coplanar || apart_kernel::orient::collinear(a, b, c) {
        let ot = orient3d_many(d, e, f, t);
        if ot[0] != Sign::Zero && ot[0] == ot[1] && ot[1] == ot[2] {
            return None;
        }
    }
    if coplanar {
        let k = dominant_axis(&normal(a, b, c));
        let t2 = t.map(|v| project(v, k));
        let u2 = u.map(|v| project(v, k));
        if coplanar_apart(&t2, &u2) {
            return None;
        }
        return coplanar_contact(&t2, &u2);
    }
    edges_through(t, u)
}

/// Closed coplanar triangles `t2` and `u2`, projected along the dominant axis of their
/// plane: do they meet, and with a positive area or only along a boundary?
fn coplanar_contact(t2: &[[i64; 2]; 3], u2: &[[i64; 2]; 3]) -> Option<Contact> {
    let edges_meet = (0..3).any(|i| {
        (0..3).any(|j| segments_meet_2d(&t2[i], &t2[(i + 1) % 3], &u2[j], &u2[(j + 1) % 3]))
    });
    let inside = in_closed_triangle_2d(&t2[0], &u2[0], &u2[1], &u2[2])
        || in_closed_triangle_2d(&u2[0], &t2[0], &t2[1], &t2[2]);
    if !(edges_meet || inside) {
        return None;
    }
    // Positive-area overlap, or only touching along a boundary?
    Some(if coplanar_overlap_area(t2, u2) {
        Contact::Overlap
    } else {
        Contact::Intersect
    })
}

/// Closed triangles `t` and `u` not in one plane: they meet when an edge of one meets
/// the other.
fn edges_through(t: [&P3; 3], u: [&P3; 3]) -> Option<Contact> {
    let [a, b, c] = t;
    let [d, e, f] = u;
    let hit = (0..3).any(|i| segment_meets_triangle(t[i], t[(i + 1) % 3], d, e, f))
        || (0..3).any(|i| segment_meets_triangle(u[i], u[(i + 1) % 3], a, b, c));
    hit.then_some(Contact::Intersect)
}

/// True when some edge line of one of two non-degenerate triangles in the plane has
/// the other strictly on its outer side: then the closed triangles are disjoint, and
/// conversely (separating axes of two convex polygons). False for a degenerate one.
/// A cheap first exit for the many disjoint coplanar pairs of flat tessellations
/// (radial slivers of an annulus, whose boxes overlap widely).
pub(crate) fn coplanar_apart(t: &[[i64; 2]; 3], u: &[[i64; 2]; 3]) -> bool {
    let st = orient2d(&t[0], &t[1], &t[2]);
    let su = orient2d(&u[0], &u[1], &u[2]);
    if st == Sign::Zero || su == Sign::Zero {
        return false;
    }
    [(t, u, st), (u, t, su)].iter().any(|&(x, y, s)| {
        (0..3).any(|i| {
            let (a, b) = (&x[i], &x[(i + 1) % 3]);
            y.iter().all(|p| orient2d(a, b, p) == -s)
        })
    })
}

/// True when two coplanar triangles (projected to the same plane) share interior points.
pub fn coplanar_overlap_area(t: &[[i64; 2]; 3], u: &[[i64; 2]; 3]) -> bool {
    // Separating axis on the six edge lines: the interiors are disjoint exactly when
    // some edge line has one triangle weakly on each side.
    let side = |a: &[i64; 2], b: &[i64; 2], p: &[i64; 2]| orient2d(a, b, p);
    for (x, y) in [(t, u), (u, t)] {
        let s = orient2d(&x[0], &x[1], &x[2]);
        for i in 0..3 {
            let (a, b) = (&x[i], &x[(i + 1) % 3]);
            if y.iter().all(|p| side(a, b, p) != s) {
                return false;
            }
        }
    }
    true
}

/// The intersection test for two triangles of one mesh (vertex indices `t`, `u` into
/// `v`), allowing what they share: a common vertex or a common edge.
pub fn triangle_pair(v: &[P3], t: [u32; 3], u: [u32; 3]) -> Option<Contact> {
    // Shared corners, as (index in t, index in u), without allocating.
    let mut shared = [(0usize, 0usize); 3];
    let mut n = 0;
    for (i, &a) in t.iter().enumerate() {
        for (j, &b) in u.iter().enumerate() {
            if a == b {
                shared[n] = (i, j);
                n += 1;
            }
        }
    }
    let p = |i: u32| &v[i as usize];
    match n {
        0 => triangles_meet(t.map(p), u.map(p)),
        1 => shared_vertex(v, t, u, shared[0]),
        2 => {
            // Rotate t so the shared edge is t[0] t[1]; c and d are the other vertices.
            let (i0, i1) = (shared[0].0, shared[1].0);
            let k = 3 - i0 - i1; // t's free vertex
            let j = 3 - shared[0].1 - shared[1].1; // u's free vertex
            let (a, b, c, d) = (p(t[(k + 1) % 3]), p(t[(k + 2) % 3]), p(t[k]), p(u[j]));
            if orient3d(a, b, c, d) != Sign::Zero {
                return None;
            }
            let axis = dominant_axis(&normal(a, b, c));
            let [a2, b2, c2, d2] = [a, b, c, d].map(|x| project(x, axis));
            (orient2d(&a2, &b2, &c2) == orient2d(&a2, &b2, &d2)).then_some(Contact::Overlap)
        }
        _ => Some(Contact::Overlap), // the same three vertices
    }
}

/// Triangles sharing exactly one vertex meet beyond it exactly when their corner cones
/// at that vertex share a non-zero direction (their intersection is convex and contains
/// the vertex).
fn shared_vertex(v: &[P3], t: [u32; 3], u: [u32; 3], (i, j): (usize, usize)) -> Option<Contact> {
    let p = |x: u32| &v[x as usize];
    let o = p(t[i]);
    let (b, c) = (p(t[(i + 1) % 3]), p(t[(i + 2) % 3]));
    let (e, f) = (p(u[(j + 1) % 3]), p(u[(j + 2) % 3]));
    // Fast exits: one triangle strictly on one side of the other's plane.
    let sb = orient3d(o, e, f, b);
    let sc = orient3d(o, e, f, c);
    if sb != Sign::Zero && sb == sc {
        return None;
    }
    let se = orient3d(o, b, c, e);
    let sf = orient3d(o, b, c, f);
    if se != Sign::Zero && se == sf {
        return None;
    }
    if sb == Sign::Zero && sc == Sign::Zero {
        let (u1, u2, w1, w2) = (sub(b, o), sub(c, o), sub(e, o), sub(f, o));
        // Coplanar: 2-D cones at the shared vertex.
        let k = dominant_axis(&cross(&u1, &u2));
        let [u1, u2, w1, w2] = [u1, u2, w1, w2].map(|x| project(&x, k));
        let z = [0i64, 0];
        let ccw = |a: [i64; 2], b: [i64; 2]| {
            if orient2d(&z, &a, &b) == Sign::Positive {
                (a, b)
            } else {
                (b, a)
            }
        };
        let (u1, u2) = ccw(u1, u2);
        let (w1, w2) = ccw(w1, w2);
        let in_cone = |r: &[i64; 2], a: &[i64; 2], b: &[i64; 2]| {
            orient2d(&z, a, r) != Sign::Negative && orient2d(&z, r, b) != Sign::Negative
        };
        let meet = in_cone(&w1, &u1, &u2)
            || in_cone(&w2, &u1, &u2)
            || in_cone(&u1, &w1, &w2)
            || in_cone(&u2, &w1, &w2);
        if !meet {
            return None;
        }
        // Area overlap unless the cones only share a boundary ray: near the vertex the
        // triangles are their cones, so compare the triangles (0, u1, u2) and (0, w1, w2).
        let area = coplanar_overlap_area(&[z, u1, u2], &[z, w1, w2]);
        return Some(if area {
            Contact::Overlap
        } else {
            Contact::Intersect
        });
    }
    // Different planes: T1 ∩ T2 is a segment [o, p] of the line where the planes meet.
    // If p ≠ o, it lies on the boundary of one triangle: on its far edge (which then
    // meets the other triangle), or on one of its edges from o (whose far end then lies
    // in the other's plane, with its direction inside the other's corner at o). Each
    // test is an orientation in 3-D or, within one plane, in a 2-D projection.
    if segment_meets_triangle(b, c, o, e, f) || segment_meets_triangle(e, f, o, b, c) {
        return Some(Contact::Intersect);
    }
    let in_corner = |x: &P3, p: &P3, q: &P3| {
        // x lies in the plane of (o, p, q): is x - o in the closed cone of p - o, q - o?
        let k = dominant_axis(&normal(o, p, q));
        let [o2, p2, q2, x2] = [o, p, q, x].map(|v| project(v, k));
        let s = orient2d(&o2, &p2, &q2);
        orient2d(&o2, &p2, &x2) != -s && orient2d(&o2, &x2, &q2) != -s
    };
    let hit = (sb == Sign::Zero && in_corner(b, e, f))
        || (sc == Sign::Zero && in_corner(c, e, f))
        || (se == Sign::Zero && in_corner(e, b, c))
        || (sf == Sign::Zero && in_corner(f, b, c));
    hit.then_some(Contact::Intersect)
}

/// Where the closed segment `p q` meets the closed triangle `a b c`, as parameters
/// `t` in [0, 1] along the segment (both ends of the overlap when the segment
/// lies in the triangle's plane). Used to split edges of one solid at the faces of
/// another.
pub fn segment_triangle_params(p: &P3, q: &P3, a: &P3, b: &P3, c: &P3) -> Vec<Rational> {
    let mut out = Vec::new();
    if !segment_meets_triangle(p, q, a, b, c) {
        return out;
    }
    let n = normal(a, b, c);
    let dot = |x: &P3| -> Int {
        let d = sub(x, a);
        Int::from(n[0]) * Int::from(d[0])
            + Int::from(n[1]) * Int::from(d[1])
            + Int::from(n[2]) * Int::from(d[2])
    };
    let (dp, dq) = (dot(p), dot(q));
    if dp != dq {
        // t = dp / (dp - dq).
        let den = &dp - &dq;
        out.push(Rational::new(dp, den));
        return out;
    }
    // In the plane: clip the segment against the three edge lines (parameters where it
    // crosses each, plus its ends when inside).
    let k = dominant_axis(&n);
    let [p2, q2, a2, b2, c2] = [p, q, a, b, c].map(|v| project(v, k));
    if in_closed_triangle_2d(&p2, &a2, &b2, &c2) {
        out.push(Rational::zero());
    }
    if in_closed_triangle_2d(&q2, &a2, &b2, &c2) {
        out.push(Rational::from_int(1));
    }
    for (x, y) in [(&a2, &b2), (&b2, &c2), (&c2, &a2)] {
        if !segments_meet_2d(&p2, &q2, x, y) {
            continue;
        }
        // p + t (q - p) on the line x y: t = orient(x, y, p) / (orient(x, y, p) - orient(x, y, q)).
        let o = |s: &[i64; 2]| -> Int {
            Int::from(
                (y[0] - x[0]) as i128 * (s[1] - x[1]) as i128
                    - (y[1] - x[1]) as i128 * (s[0] - x[0]) as i128,
            )
        };
        let (op, oq) = (o(&p2), o(&q2));
        if op != oq {
            let den = &op - &oq;
            out.push(Rational::new(op, den));
        } else {
            // Collinear with the edge: the edge's ends, as parameters along p q.
            let d = [q2[0] - p2[0], q2[1] - p2[1]];
            let len = Int::from(d[0] as i128 * d[0] as i128 + d[1] as i128 * d[1] as i128);
            for e in [x, y] {
                let num = Int::from(
                    (e[0] - p2[0]) as i128 * d[0] as i128 + (e[1] - p2[1]) as i128 * d[1] as i128,
                );
                if num >= Int::ZERO && num <= len && len > Int::ZERO {
                    out.push(Rational::new(num, len.clone()));
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shared_edge_cases() {
        let v = vec![
            [0, 0, 0],
            [2, 0, 0],
            [0, 2, 0],
            [0, -2, 0],
            [1, 1, 0],
            [0, 0, 2],
        ];
        assert_eq!(triangle_pair(&v, [0, 1, 2], [1, 0, 3]), None); // flat, opposite sides
        assert_eq!(triangle_pair(&v, [0, 1, 2], [1, 0, 5]), None); // bent along the edge
        assert_eq!(
            triangle_pair(&v, [0, 1, 2], [1, 0, 4]),
            Some(Contact::Overlap)
        ); // folded
        assert_eq!(
            triangle_pair(&v, [0, 1, 2], [0, 2, 1]),
            Some(Contact::Overlap)
        ); // doubled
    }

    #[test]
    fn shared_vertex_cases() {
        let v = vec![
            [0, 0, 0],
            [2, 0, 0],
            [0, 2, 0], // 0..2: base triangle in z = 0
            [-2, 0, 0],
            [0, -2, 0], // 3, 4: flat, opposite quadrant
            [1, 1, 2],
            [1, 1, -2], // 5, 6
            [1, 0, 0],
            [2, 2, 0], // 7, 8
        ];
        assert_eq!(triangle_pair(&v, [0, 1, 2], [0, 3, 4]), None);
        // A triangle through the shared vertex piercing the base one.
        assert_eq!(
            triangle_pair(&v, [0, 1, 2], [0, 5, 6]),
            Some(Contact::Intersect)
        );
        // Standing on the shared vertex only, above the plane.
        assert_eq!(triangle_pair(&v, [0, 1, 2], [0, 5, 3]), None);
        // Coplanar, overlapping in area.
        assert_eq!(
            triangle_pair(&v, [0, 1, 2], [0, 8, 2]),
            Some(Contact::Overlap)
        );
        // Coplanar, sharing a boundary ray (a T-junction along the x axis).
        assert_eq!(
            triangle_pair(&v, [0, 1, 2], [0, 4, 7]),
            Some(Contact::Intersect)
        );
        // Bowtie: two triangles meeting at the apex only, in different planes.
        assert_eq!(triangle_pair(&v, [0, 1, 5], [0, 3, 6]), None);
    }

    #[test]
    fn disjoint_and_crossing() {
        let t = [&[0, 0, 0], &[4, 0, 0], &[0, 4, 0]];
        assert_eq!(
            triangles_meet(t, [&[1, 1, -1], &[1, 1, 1], &[2, 1, 1]]),
            Some(Contact::Intersect)
        );
        assert_eq!(
            triangles_meet(t, [&[5, 5, -1], &[5, 5, 1], &[6, 5, 1]]),
            None
        );
        // Touching at a point (vertex of one inside the other).
        assert_eq!(
            triangles_meet(t, [&[1, 1, 0], &[1, 1, 3], &[2, 1, 3]]),
            Some(Contact::Intersect)
        );
        // Coplanar, one inside the other.
        assert_eq!(
            triangles_meet(t, [&[1, 1, 0], &[2, 1, 0], &[1, 2, 0]]),
            Some(Contact::Overlap)
        );
        // Coplanar, touching along part of an edge only.
        assert_eq!(
            triangles_meet(t, [&[1, 0, 0], &[2, -3, 0], &[3, 0, 0]]),
            Some(Contact::Intersect)
        );
        assert_eq!(
            triangles_meet(t, [&[5, 0, 0], &[6, -3, 0], &[7, 0, 0]]),
            None
        );
    }

    #[test]
    fn segment_params() {
        let (a, b, c) = ([0, 0, 0], [4, 0, 0], [0, 4, 0]);
        let r = |n: i64, d: i64| Rational::new(Int::from(n), Int::from(d));
        let t = segment_triangle_params(&[1, 1, -1], &[1, 1, 3], &a, &b, &c);
        assert_eq!(t, vec![r(1, 4)]);
        // In the plane, crossing the triangle: enters at x = 0, leaves at x + y = 4.
        let mut t = segment_triangle_params(&[-1, 1, 0], &[5, 1, 0], &a, &b, &c);
        t.sort();
        t.dedup();
        assert_eq!(t, vec![r(1, 6), r(2, 3)]);
        assert!(segment_triangle_params(&[9, 9, -1], &[9, 9, 1], &a, &b, &c).is_empty());
    }
}

#[cfg(test)]
mod oracle {
    //! An independent derivation of the shared-vertex test: the corner cones at the
    //! shared vertex meet outside it exactly when both contain +l or both contain -l,
    //! l = n1 × n2 (non-coplanar case), or by 2-D cone tests (coplanar case), with big
    //! integers.
    use super::*;
    use apart_kernel::predicates::det3_sign;
    use apart_kernel::Vec3;
    use proptest::prelude::*;

    fn cones_meet(o: &P3, b: &P3, c: &P3, e: &P3, f: &P3) -> bool {
        let v = |x: &P3| Vec3::from_i64(sub(x, o));
        let (u1, u2, w1, w2) = (v(b), v(c), v(e), v(f));
        let n1 = u1.cross(&u2);
        let n2 = w1.cross(&w2);
        let l = n1.cross(&n2);
        if l.is_zero() {
            // Coplanar: some boundary ray of one cone in the other (closed) cone.
            let inside = |r: &Vec3, a: &Vec3, b: &Vec3, n: &Vec3| {
                det3_sign(a, r, n) != Sign::Negative && det3_sign(r, b, n) != Sign::Negative
            };
            return inside(&w1, &u1, &u2, &n1)
                || inside(&w2, &u1, &u2, &n1)
                || inside(&u1, &w1, &w2, &n2)
                || inside(&u2, &w1, &w2, &n2);
        }
        let (p1, q1) = (det3_sign(&u1, &l, &n1), det3_sign(&l, &u2, &n1));
        let (p2, q2) = (det3_sign(&w1, &l, &n2), det3_sign(&l, &w2, &n2));
        let plus = [p1, q1, p2, q2].iter().all(|s| *s != Sign::Negative);
        let minus = [p1, q1, p2, q2].iter().all(|s| *s != Sign::Positive);
        plus || minus
    }

    fn pt() -> impl Strategy<Value = [i64; 3]> {
        [-2i64..3, -2i64..3, -2i64..3]
    }

    /// `triangles_meet` as it was before its first exits for coplanar pairs.
    fn triangles_meet_former(t: [&P3; 3], u: [&P3; 3]) -> Option<Contact> {
        let [a, b, c] = t;
        let [d, e, f] = u;
        let ou = [d, e, f].map(|v| orient3d(a, b, c, v));
        if ou[0] != Sign::Zero && ou[0] == ou[1] && ou[1] == ou[2] {
            return None;
        }
        let ot = [a, b, c].map(|v| orient3d(d, e, f, v));
        if ot[0] != Sign::Zero && ot[0] == ot[1] && ot[1] == ot[2] {
            return None;
        }
        if ou.iter().all(|s| *s == Sign::Zero) {
            let k = dominant_axis(&normal(a, b, c));
            let t2 = t.map(|v| project(v, k));
            let u2 = u.map(|v| project(v, k));
            return coplanar_contact(&t2, &u2);
        }
        edges_through(t, u)
    }

    fn flat_pt() -> impl Strategy<Value = [i64; 3]> {
        [-3i64..4, -3i64..4, 0i64..1]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]
        #[test]
        fn coplanar_first_exit_changes_nothing(
            t in [flat_pt(), flat_pt(), flat_pt()],
            u in [flat_pt(), flat_pt(), flat_pt()],
            tilt in 0i64..3,
        ) {
            // In z = 0, or all lifted onto one tilted plane z = tilt * x.
            let lift = |p: [i64; 3]| [p[0], p[1], tilt * p[0]];
            let (t, u) = (t.map(lift), u.map(lift));
            let (tr, ur) = ([&t[0], &t[1], &t[2]], [&u[0], &u[1], &u[2]]);
            prop_assert_eq!(triangles_meet(tr, ur), triangles_meet_former(tr, ur));
        }

        #[test]
        fn first_exits_change_nothing(
            t in [pt(), pt(), pt()],
            u in [pt(), pt(), pt()],
        ) {
            let (tr, ur) = ([&t[0], &t[1], &t[2]], [&u[0], &u[1], &u[2]]);
            prop_assert_eq!(triangles_meet(tr, ur), triangles_meet_former(tr, ur));
        }

        #[test]
        fn plane_signs_match_orient3d(
            p in proptest::array::uniform6(proptest::array::uniform3(-(1i64 << 30) + 1..(1i64 << 30))),
        ) {
            let got = orient3d_many(&p[0], &p[1], &p[2], [&p[3], &p[4], &p[5]]);
            let want = [3, 4, 5].map(|i| orient3d(&p[0], &p[1], &p[2], &p[i]));
            prop_assert_eq!(got, want);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]
        #[test]
        fn shared_vertex_matches_the_cone_oracle(b in pt(), c in pt(), e in pt(), f in pt()) {
            let o = [0i64, 0, 0];
            let v = vec![o, b, c, e, f];
            if apart_kernel::orient::collinear(&o, &b, &c) || apart_kernel::orient::collinear(&o, &e, &f)
                || [b, c].contains(&e) || [b, c].contains(&f) {
                return Ok(()); // not two triangles sharing exactly one vertex
            }
            let got = triangle_pair(&v, [0, 1, 2], [0, 3, 4]).is_some();
            prop_assert_eq!(got, cones_meet(&o, &b, &c, &e, &f));
        }
    }
}
