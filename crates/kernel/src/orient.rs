//! Exact orientation predicates on snapped grid points (`[i64; 3]` with fewer than 54
//! bits), and on exact points ([`HPoint`]) against grid triangles.
//!
//! Bit bounds, for coordinates below 2^B: differences below 2^(B+1); `orient3d` is a
//! degree-3 polynomial below 6 · 2^(3B+3) (96 bits for the default B = 30), evaluated
//! with an `i64` cross product and `i128` dot product when the differences fit 30 bits,
//! in `i128` when they fit 41 bits, and by the kernel's filtered exact [`det3_sign`]
//! otherwise; `orient2d` and cross products are degree 2 (at most 110 bits
//! for B = 53) and always fit `i128`.

use crate::int::{sign_of, Int};
use crate::plane::HPoint;
use crate::predicates::{det3_i128, det3_sign};
use crate::{Sign, Vec3};

/// A grid point.
pub type P3 = [i64; 3];

/// `b - a`.
#[inline]
pub fn sub(b: &P3, a: &P3) -> P3 {
    [b[0] - a[0], b[1] - a[1], b[2] - a[2]]
}

#[inline]
fn bits3(vs: [&P3; 3]) -> u32 {
    let mut m = 0u64;
    for v in vs {
        m |= v[0].unsigned_abs() | v[1].unsigned_abs() | v[2].unsigned_abs();
    }
    64 - m.leading_zeros()
}

/// Sign of det[u; v; w] for difference vectors.
#[inline]
pub fn det3(u: &P3, v: &P3, w: &P3) -> Sign {
    let bits = bits3([u, v, w]);
    if bits <= 31 {
        // v × w in i64 (each product below 2^62, each difference below 2^63: the
        // differences of coordinates below 2^30 fit), then u · (v × w) with 64 x 64 ->
        // 128-bit products.
        let c = [
            v[1] * w[2] - v[2] * w[1],
            v[2] * w[0] - v[0] * w[2],
            v[0] * w[1] - v[1] * w[0],
        ];
        return Sign::of_i128(
            u[0] as i128 * c[0] as i128 + u[1] as i128 * c[1] as i128 + u[2] as i128 * c[2] as i128,
        );
    }
    if bits <= 41 {
        Sign::of_i128(det3_i128(u, v, w))
    } else {
        det3_sign(
            &Vec3::from_i64(*u),
            &Vec3::from_i64(*v),
            &Vec3::from_i64(*w),
        )
    }
}

/// Orientation of `d` relative to the plane of the triangle `a, b, c`: positive when `d`
/// lies on the side the normal `(b - a) × (c - a)` points to (outside, for an outward
/// triangle), zero when the four points are coplanar.
#[inline]
pub fn orient3d(a: &P3, b: &P3, c: &P3, d: &P3) -> Sign {
    det3(&sub(b, a), &sub(c, a), &sub(d, a))
}

/// `[orient3d(a, b, c, p) for p in ps]`, sharing the plane's normal between the three
/// tests when the coordinates' differences fit the machine-integer path.
#[inline]
pub fn orient3d_many(a: &P3, b: &P3, c: &P3, ps: [&P3; 3]) -> [Sign; 3] {
    let (u, v) = (sub(b, a), sub(c, a));
    let w = ps.map(|p| sub(p, a));
    if bits3([&u, &v, &w[0]]).max(bits3([&w[1], &w[2], &w[2]])) <= 31 {
        // As in `det3`: the cross product in i64, the dot products in i128.
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        return w.map(|x| {
            Sign::of_i128(
                x[0] as i128 * n[0] as i128
                    + x[1] as i128 * n[1] as i128
                    + x[2] as i128 * n[2] as i128,
            )
        });
    }
    w.map(|x| det3(&u, &v, &x))
}

/// `(b - a) × (c - a)`, exact.
#[inline]
pub fn normal(a: &P3, b: &P3, c: &P3) -> [i128; 3] {
    cross(&sub(b, a), &sub(c, a))
}

/// `u × v`, exact (components below 2^109 for 54-bit inputs).
#[inline]
pub fn cross(u: &P3, v: &P3) -> [i128; 3] {
    let (u0, u1, u2) = (u[0] as i128, u[1] as i128, u[2] as i128);
    let (v0, v1, v2) = (v[0] as i128, v[1] as i128, v[2] as i128);
    [u1 * v2 - u2 * v1, u2 * v0 - u0 * v2, u0 * v1 - u1 * v0]
}

/// True when `a`, `b`, `c` are collinear (including coincident).
#[inline]
pub fn collinear(a: &P3, b: &P3, c: &P3) -> bool {
    // Component by component: `==` on `[i128; 3]` compiles to a `memcmp` call.
    let n = normal(a, b, c);
    n[0] == 0 && n[1] == 0 && n[2] == 0
}

/// The axis along which `n` has its largest magnitude (the one to drop when projecting
/// a plane with normal `n`).
#[inline]
pub fn dominant_axis(n: &[i128; 3]) -> usize {
    let a = n.map(|v| v.unsigned_abs());
    if a[0] >= a[1] && a[0] >= a[2] {
        0
    } else if a[1] >= a[2] {
        1
    } else {
        2
    }
}

/// The projection dropping `axis`, keeping the cyclic order of the other two, so that
/// `orient2d` of projected points has the sign of component `axis` of the 3-D normal.
#[inline]
pub fn project(p: &P3, axis: usize) -> [i64; 2] {
    match axis {
        0 => [p[1], p[2]],
        1 => [p[2], p[0]],
        _ => [p[0], p[1]],
    }
}

/// Sign of `(b - a) × (c - a)` in the plane: positive for a left turn.
#[inline]
pub fn orient2d(a: &[i64; 2], b: &[i64; 2], c: &[i64; 2]) -> Sign {
    let (ux, uy) = ((b[0] - a[0]) as i128, (b[1] - a[1]) as i128);
    let (vx, vy) = ((c[0] - a[0]) as i128, (c[1] - a[1]) as i128);
    Sign::of_i128(ux * vy - uy * vx)
}

/// True when `p` lies in the closed triangle `a, b, c` (any orientation; a degenerate
/// triangle contains the points of its hull segment).
#[inline]
pub fn in_closed_triangle_2d(p: &[i64; 2], a: &[i64; 2], b: &[i64; 2], c: &[i64; 2]) -> bool {
    let s = orient2d(a, b, c);
    if s == Sign::Zero {
        return on_segment_2d(p, a, b) || on_segment_2d(p, b, c) || on_segment_2d(p, a, c);
    }
    let d1 = orient2d(a, b, p);
    let d2 = orient2d(b, c, p);
    let d3 = orient2d(c, a, p);
    d1 != -s && d2 != -s && d3 != -s
}

/// True when `p` lies on the closed segment `a b` (a point when `a = b`).
#[inline]
pub fn on_segment_2d(p: &[i64; 2], a: &[i64; 2], b: &[i64; 2]) -> bool {
    orient2d(a, b, p) == Sign::Zero
        && p[0] >= a[0].min(b[0])
        && p[0] <= a[0].max(b[0])
        && p[1] >= a[1].min(b[1])
        && p[1] <= a[1].max(b[1])
}

/// True when the closed segments `a b` and `c d` share a point.
#[inline]
pub fn segments_meet_2d(a: &[i64; 2], b: &[i64; 2], c: &[i64; 2], d: &[i64; 2]) -> bool {
    let d1 = orient2d(c, d, a);
    let d2 = orient2d(c, d, b);
    let d3 = orient2d(a, b, c);
    let d4 = orient2d(a, b, d);
    if d1 != Sign::Zero && d1 == d2 || d3 != Sign::Zero && d3 == d4 {
        return false;
    }
    if d1 != Sign::Zero || d2 != Sign::Zero || d3 != Sign::Zero || d4 != Sign::Zero {
        return true; // proper crossing or an endpoint touching the other segment's line inside
    }
    // All four collinear: do the projections overlap?
    on_segment_2d(a, c, d)
        || on_segment_2d(b, c, d)
        || on_segment_2d(c, a, b)
        || on_segment_2d(d, a, b)
}

/// Sign of `n · (p - a)` for the normal `n = (b - a) × (c - a)` of triangle `a b c`:
/// [`orient3d`]`(a, b, c, p)` for an exact point `p`.
pub fn orient3d_point(a: &P3, b: &P3, c: &P3, p: &HPoint) -> Sign {
    if let Some(q) = p.as_int() {
        return orient3d(a, b, c, q);
    }
    let (num, den) = (p.num(), p.den());
    let n = normal(a, b, c);
    let mut s = Int::ZERO;
    for k in 0..3 {
        s += Int::from(n[k]) * (&num[k] - den * Int::from(a[k]));
    }
    sign_of(&s)
}

/// [`orient2d`]`(u, v, p)` in the projection dropping `axis` ([`project`]), for an
/// exact point `p`.
pub fn orient2d_point(u: &P3, v: &P3, p: &HPoint, axis: usize) -> Sign {
    let (u2, v2) = (project(u, axis), project(v, axis));
    if let Some(q) = p.as_int() {
        return orient2d(&u2, &v2, &project(q, axis));
    }
    let (num, den) = (p.num(), p.den());
    let q = match axis {
        0 => [&num[1], &num[2]],
        1 => [&num[2], &num[0]],
        _ => [&num[0], &num[1]],
    };
    let e0 = Int::from(v2[0] as i128 - u2[0] as i128);
    let e1 = Int::from(v2[1] as i128 - u2[1] as i128);
    let d0 = q[0] - den * Int::from(u2[0]);
    let d1 = q[1] - den * Int::from(u2[1]);
    sign_of(&(e0 * d1 - e1 * d0))
}

/// True when the exact point `p` lies on the closed triangle `a b c` (non-degenerate).
pub fn on_triangle(p: &HPoint, a: &P3, b: &P3, c: &P3) -> bool {
    if orient3d_point(a, b, c, p) != Sign::Zero {
        return false;
    }
    let k = dominant_axis(&normal(a, b, c));
    let s = orient2d(&project(a, k), &project(b, k), &project(c, k));
    [(a, b), (b, c), (c, a)]
        .iter()
        .all(|(u, v)| orient2d_point(u, v, p, k) != -s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientation_signs() {
        let o = [0, 0, 0];
        let (x, y, z) = ([1, 0, 0], [0, 1, 0], [0, 0, 1]);
        assert_eq!(orient3d(&o, &x, &y, &z), Sign::Positive);
        assert_eq!(orient3d(&o, &y, &x, &z), Sign::Negative);
        assert_eq!(orient3d(&o, &x, &y, &[5, 7, 0]), Sign::Zero);
        // Large coordinates take the kernel's exact path.
        let b = 1i64 << 52;
        assert_eq!(
            orient3d(&[-b, -b, -b], &[b, -b, -b], &[-b, b, -b], &[0, 0, 1 - b]),
            Sign::Positive
        );
        assert_eq!(
            orient3d(&[-b, -b, -b], &[b, -b, -b], &[-b, b, -b], &[3, 5, -b]),
            Sign::Zero
        );
    }

    #[test]
    fn projection_keeps_the_normal_sign() {
        let (a, b, c) = ([0, 0, 0], [0, 2, 1], [0, -1, 3]);
        let n = normal(&a, &b, &c);
        let k = dominant_axis(&n);
        assert_eq!(k, 0);
        let s = orient2d(&project(&a, k), &project(&b, k), &project(&c, k));
        assert_eq!(s, Sign::of_i128(n[k]));
        for k in 0..3 {
            let (a, b, c) = ([0, 0, 0], [1, 0, 0], [0, 1, 0]);
            let n = normal(&a, &b, &c);
            let s = orient2d(&project(&a, k), &project(&b, k), &project(&c, k));
            assert_eq!(s, Sign::of_i128(n[k]));
        }
    }

    fn oracle(a: &P3, b: &P3, c: &P3, d: &P3) -> Sign {
        let v = |p: &P3| crate::Vec3::from_i64(*p);
        let (u, w, x) = (v(b).sub(&v(a)), v(c).sub(&v(a)), v(d).sub(&v(a)));
        crate::int::sign_of(&u.dot(&w.cross(&x)))
    }

    proptest::proptest! {
        /// orient3d against a big-integer evaluation, over every evaluation path
        /// (differences of 30, 41 and 53 bits), on random and on exactly coplanar points.
        #[test]
        fn orient3d_matches_big_integers(bits in proptest::sample::select(vec![8u32, 29, 30, 31, 40, 41, 42, 52]),
                                         raw in proptest::array::uniform12(proptest::num::i64::ANY),
                                         k in -3i64..4, l in -3i64..4) {
            let m = (1i64 << bits) - 1;
            let p = |i: usize| [raw[i] % m, raw[i + 1] % m, raw[i + 2] % m];
            let (a, b, c, d) = (p(0), p(3), p(6), p(9));
            proptest::prop_assert_eq!(orient3d(&a, &b, &c, &d), oracle(&a, &b, &c, &d));
            // d on the plane: a + k (b - a) + l (c - a), when it stays in range.
            let e = [0, 1, 2].map(|i| a[i] as i128 + k as i128 * (b[i] - a[i]) as i128 + l as i128 * (c[i] - a[i]) as i128);
            if e.iter().all(|v| v.unsigned_abs() < 1 << 53) {
                let e = e.map(|v| v as i64);
                proptest::prop_assert_eq!(orient3d(&a, &b, &c, &e), Sign::Zero);
                proptest::prop_assert_eq!(oracle(&a, &b, &c, &e), Sign::Zero);
            }
        }
    }

    #[test]
    fn segments_and_triangles() {
        let (a, b, c) = ([0, 0], [4, 0], [0, 4]);
        assert!(in_closed_triangle_2d(&[1, 1], &a, &b, &c));
        assert!(in_closed_triangle_2d(&[2, 2], &a, &b, &c)); // on the hypotenuse
        assert!(!in_closed_triangle_2d(&[3, 3], &a, &b, &c));
        assert!(segments_meet_2d(&[0, 0], &[2, 2], &[0, 2], &[2, 0]));
        assert!(segments_meet_2d(&[0, 0], &[2, 0], &[2, 0], &[3, 5])); // shared endpoint
        assert!(!segments_meet_2d(&[0, 0], &[1, 0], &[2, 0], &[3, 0])); // collinear apart
        assert!(segments_meet_2d(&[0, 0], &[2, 0], &[1, 0], &[3, 0])); // collinear overlap
        assert!(!segments_meet_2d(&[0, 0], &[1, 1], &[0, 1], &[-1, 2]));
    }

    proptest::proptest! {
        /// The machine-integer path at its bit limit (coordinates below 2^30, so
        /// differences of up to 31 bits) agrees with arbitrary precision.
        #[test]
        fn det3_at_the_fast_path_limit(
            c in proptest::array::uniform9(proptest::prop_oneof![
                -(1i64 << 31) + 1..(1i64 << 31),
                proptest::prelude::Just((1i64 << 31) - 1),
                proptest::prelude::Just(-(1i64 << 31) + 1),
            ]),
        ) {
            let (u, v, w) = ([c[0], c[1], c[2]], [c[3], c[4], c[5]], [c[6], c[7], c[8]]);
            let want = crate::predicates::det3_sign(
                &crate::Vec3::from_i64(u),
                &crate::Vec3::from_i64(v),
                &crate::Vec3::from_i64(w),
            );
            proptest::prop_assert_eq!(det3(&u, &v, &w), want);
        }
    }
}
