//! Exact interference and contact of translated convex pieces.
//!
//! A piece is an unplaced polytope plus a rational translation; tests work on the stored
//! integers and the translation directly, so no translated polytope (with its larger
//! denominators) is built on the hot path of detection.

use crate::exact::{Point, Q};
use apart_kernel::int::sign_of;
use apart_kernel::{Int, Sign, Vec3};
use apart_pieces::Polytope;

/// Exactly: do the interiors of `a + ta` and `b + tb` meet? (Touching is not
/// interference.) Separating-axis test over facet normals and edge cross products.
pub fn overlaps(a: &Polytope, ta: &Point, b: &Polytope, tb: &Point) -> bool {
    let d = ta.sub(tb);
    let (da, db) = (a.den(), b.den());
    // Separated along n when [la, ha]/da + n·d and [lb, hb]/db touch or are apart.
    let separated = |n: &Vec3| -> bool {
        let (ha, _) = a.support(n);
        let (hb, _) = b.support(n);
        let (na, _) = a.support(&n.neg());
        let (nb, _) = b.support(&n.neg());
        let (la, lb) = (-na, -nb);
        let nd = n.to_ints();
        let nd = &nd[0] * &d.x[0] + &nd[1] * &d.x[1] + &nd[2] * &d.x[2];
        let w = &d.w;
        let dadb = da * db;
        // a below b: ha/da + nd/w <= lb/db.
        let below = &(&ha * db) * w - &(&lb * da) * w + &nd * &dadb;
        if sign_of(&below) != Sign::Positive {
            return true;
        }
        // b below a: hb/db <= la/da + nd/w.
        let above = &(&hb * da) * w - &(&la * db) * w - &nd * &dadb;
        sign_of(&above) != Sign::Positive
    };
    for f in a.facets() {
        if separated(&f.normal) {
            return false;
        }
    }
    for f in b.facets() {
        if separated(&f.normal) {
            return false;
        }
    }
    for ea in a.edge_directions() {
        for eb in b.edge_directions() {
            let n = ea.cross(eb);
            if !n.is_zero() && separated(&n.primitive()) {
                return false;
            }
        }
    }
    true
}

/// The polytope moved by a rational translation (denominator multiplied by `t.w`).
pub fn translated(p: &Polytope, t: &Point) -> Polytope {
    let den = p.den().clone();
    let shift = Vec3::from_ints(t.x.clone().map(|c| c * &den));
    p.rescaled(&t.w)
        .with_den(Int::ONE)
        .translated(&shift)
        .with_den(&den * &t.w)
}

/// How two closed convex pieces with disjoint interiors touch.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Touch {
    /// The vertices (and more) of the contact set `a ∩ b`.
    pub(crate) points: Vec<[Q; 3]>,
    /// Some plane separating them has `a` on its upper side (`b` supports `a`).
    pub(crate) supports: bool,
}

/// The contact of `a` and `b` (closed sets, interiors disjoint): `None` when they do not
/// touch. The points are a superset of the vertices of `a ∩ b`: vertices of one in the
/// other, and crossings of the edges of one with the facets of the other.
pub(crate) fn touch(a: &Polytope, b: &Polytope) -> Option<Touch> {
    let (a, b) = Polytope::common(a, b);
    let den = a.den().clone();
    let pts = apart_pieces::interference::contact_points(&a, &b);
    if pts.is_empty() {
        return None;
    }
    let mut points: Vec<[Q; 3]> = pts
        .into_iter()
        .map(|(x, w)| Point::new(x.to_ints(), &w * &den).to_q())
        .collect();
    points.sort();
    points.dedup();
    // b supports a: a separating plane n with max_b n·x = min_a n·x and n_z > 0.
    let touching_up = |n: &Vec3| -> bool {
        if n.get(2) <= Int::ZERO {
            return false;
        }
        let (hb, _) = b.support(n);
        let (ha_neg, _) = a.support(&n.neg());
        hb + ha_neg == Int::ZERO
    };
    let mut supports = b.facets().iter().any(|f| touching_up(&f.normal))
        || a.facets().iter().any(|f| touching_up(&f.normal.neg()));
    if !supports {
        'outer: for ea in a.edge_directions() {
            for eb in b.edge_directions() {
                let n = ea.cross(eb);
                if n.is_zero() {
                    continue;
                }
                let n = n.primitive();
                if touching_up(&n) || touching_up(&n.neg()) {
                    supports = true;
                    break 'outer;
                }
            }
        }
    }
    Some(Touch { points, supports })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::{q, qfrac};

    fn unit(o: [i64; 3]) -> Polytope {
        let pts: Vec<Vec3> = (0..8)
            .map(|i| Vec3::new(o[0] + (i & 1), o[1] + (i >> 1 & 1), o[2] + (i >> 2 & 1)))
            .collect();
        Polytope::hull_of_points(&pts).unwrap()
    }

    #[test]
    fn translated_overlap_matches_materialized() {
        let a = unit([0, 0, 0]);
        let b = unit([0, 0, 0]);
        let origin = Point::origin();
        for (t, expect) in [
            ([q(1), q(0), q(0)], false),
            ([qfrac(1, 2), qfrac(1, 3), q(0)], true),
            ([qfrac(1, 2), q(1), qfrac(1, 2)], false),
            ([qfrac(-99, 100), qfrac(99, 100), qfrac(1, 7)], true),
        ] {
            let p = Point::from_q(&t);
            assert_eq!(overlaps(&a, &p, &b, &origin), expect, "{t:?}");
            let moved = translated(&a, &p);
            assert_eq!(
                apart_pieces::interference::interiors_disjoint(&moved, &b),
                !expect
            );
        }
    }

    #[test]
    fn contacts_and_support() {
        let low = unit([0, 0, 0]);
        let high = translated(&unit([0, 0, 0]), &Point::from_q(&[qfrac(1, 2), q(0), q(1)]));
        let t = touch(&high, &low).unwrap();
        assert!(t.supports);
        assert_eq!(t.points.len(), 4); // the rectangle [1/2, 1] x [0, 1] at z = 1
        let side = unit([1, 0, 0]);
        let t = touch(&side, &low).unwrap();
        assert!(!t.supports); // side by side
        assert!(touch(&unit([3, 0, 0]), &low).is_none());
    }
}
