//! Predicates and constructions on the sphere of directions.
//!
//! A point of the sphere is a non-zero integer vector (never normalised: two vectors are
//! the same point when they are parallel with the same orientation; after
//! [`Vec3::primitive`] that is plain equality). A great circle is given by a non-zero
//! integer normal. An *oriented minor arc* from `s` to `e` on the circle with normal `n`
//! runs counter-clockwise around `n` and is shorter than a half circle, so
//! `det(n, s, e) > 0`.
//!
//! Bit bounds below are for grid coordinates of `B` bits: Minkowski vertices have `B + 1`
//! bits, arc normals (cross of two vertices) `2B + 3`, intersections of two great circles
//! (cross of two normals) `4B + 7`.

use crate::predicates::{det3_sign, dot_sign, parallel};
use crate::{Sign, Vec3};

/// Side of sphere point `p` with respect to the great circle with normal `n`: positive
/// on the side `n` points to. Degree 2; bits `bits(n) + bits(p) + 2`, at most
/// `(2B + 3) + (4B + 7) + 2 = 6B + 12`.
#[inline]
pub fn circle_side(n: &Vec3, p: &Vec3) -> Sign {
    dot_sign(n, p)
}

/// One of the two intersection points of the great circles with normals `n1` and `n2`,
/// as a primitive vector (the other is its negation). `None` when the circles coincide.
/// Bits at most `bits(n1) + bits(n2) + 1`, i.e. `4B + 7`.
pub fn circle_intersection(n1: &Vec3, n2: &Vec3) -> Option<Vec3> {
    let p = n1.cross(n2);
    if p.is_zero() {
        None
    } else {
        Some(p.primitive())
    }
}

/// Order of two points `p`, `q` on the great circle with normal `n`: positive when `q`
/// lies in the open half circle counter-clockwise (around `n`) after `p`, negative when in
/// the half circle before it, zero when `q = ±p`. This is "position along an arc".
/// Degree 3; bits `bits(n) + bits(p) + bits(q) + 3`, at most `10B + 20`.
#[inline]
pub fn ccw_along(n: &Vec3, p: &Vec3, q: &Vec3) -> Sign {
    det3_sign(n, p, q)
}

/// Orientation of three sphere points: positive when `c` lies to the left of the great
/// circle through `a` then `b` (i.e. on the side of `a × b`). Degree 3.
#[inline]
pub fn orientation(a: &Vec3, b: &Vec3, c: &Vec3) -> Sign {
    det3_sign(a, b, c)
}

/// Angular order of two great circles through the point `v`: the sign of
/// `det(n1, n2, v)`. With tangents `t_i = n_i × v`, `det(v, t1, t2) = |v|² det(n1, n2, v)`,
/// so this compares the directions of the two circles around `v` without constructing the
/// tangents. Degree 3; bits at most `2(2B + 3) + (4B + 7) + 3 = 8B + 16`.
#[inline]
pub fn circles_around(v: &Vec3, n1: &Vec3, n2: &Vec3) -> Sign {
    det3_sign(n1, n2, v)
}

/// True when `p` and `q` are the same sphere point (non-zero, parallel, same orientation).
#[inline]
pub fn same_point(p: &Vec3, q: &Vec3) -> bool {
    crate::predicates::same_direction(p, q)
}

/// True when `p` and `q` are antipodal sphere points.
#[inline]
pub fn antipodal(p: &Vec3, q: &Vec3) -> bool {
    !p.is_zero() && !q.is_zero() && parallel(p, q) && dot_sign(p, q) == Sign::Negative
}

/// Where a point of a great circle lies with respect to a closed minor arc of it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArcPosition {
    /// Not on the closed arc.
    Outside,
    /// At the arc's start point.
    Start,
    /// At the arc's end point.
    End,
    /// In the open arc.
    Interior,
}

/// Position of `p` (assumed on the circle of normal `n`) relative to the oriented minor
/// arc from `s` to `e`. Exact; two or three [`ccw_along`] evaluations.
pub fn arc_position(n: &Vec3, s: &Vec3, e: &Vec3, p: &Vec3) -> ArcPosition {
    let a = ccw_along(n, s, p);
    let b = ccw_along(n, p, e);
    match (a, b) {
        (Sign::Positive, Sign::Positive) => ArcPosition::Interior,
        (Sign::Zero, _) => {
            if dot_sign(s, p) == Sign::Positive {
                ArcPosition::Start
            } else {
                ArcPosition::Outside
            }
        }
        (_, Sign::Zero) => {
            if dot_sign(e, p) == Sign::Positive {
                ArcPosition::End
            } else {
                ArcPosition::Outside
            }
        }
        _ => ArcPosition::Outside,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arc_positions_on_equator() {
        let n = Vec3::new(0, 0, 1);
        let s = Vec3::new(1, 0, 0);
        let e = Vec3::new(0, 1, 0);
        assert_eq!(ccw_along(&n, &s, &e), Sign::Positive);
        assert_eq!(
            arc_position(&n, &s, &e, &Vec3::new(1, 1, 0)),
            ArcPosition::Interior
        );
        assert_eq!(
            arc_position(&n, &s, &e, &Vec3::new(3, 0, 0)),
            ArcPosition::Start
        );
        assert_eq!(
            arc_position(&n, &s, &e, &Vec3::new(0, 2, 0)),
            ArcPosition::End
        );
        assert_eq!(
            arc_position(&n, &s, &e, &Vec3::new(-1, 0, 0)),
            ArcPosition::Outside
        );
        assert_eq!(
            arc_position(&n, &s, &e, &Vec3::new(0, -1, 0)),
            ArcPosition::Outside
        );
        assert_eq!(
            arc_position(&n, &s, &e, &Vec3::new(-1, -1, 0)),
            ArcPosition::Outside
        );
        assert_eq!(
            arc_position(&n, &s, &e, &Vec3::new(1, -1, 0)),
            ArcPosition::Outside
        );
    }

    #[test]
    fn intersections_and_order_around() {
        let p = circle_intersection(&Vec3::new(0, 0, 2), &Vec3::new(0, 4, 0)).unwrap();
        assert_eq!(p, Vec3::new(-1, 0, 0));
        assert!(circle_intersection(&Vec3::new(1, 1, 1), &Vec3::new(-2, -2, -2)).is_none());
        assert!(antipodal(&Vec3::new(1, 2, 3), &Vec3::new(-2, -4, -6)));
        assert!(same_point(&Vec3::new(1, 2, 3), &Vec3::new(2, 4, 6)));
        // Around the north pole, the circle x=0 comes counter-clockwise after y=0 when
        // measured by the normals' order.
        let v = Vec3::new(0, 0, 1);
        assert_eq!(
            circles_around(&v, &Vec3::new(0, 1, 0), &Vec3::new(-1, 0, 0)),
            Sign::Positive
        );
    }
}
