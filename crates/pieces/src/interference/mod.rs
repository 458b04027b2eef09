//! Exact interference of two convex polytopes: do their interiors meet, and where.

mod depth;
mod filter;
mod triangle;
mod witness;

pub use depth::{overlap_deeper_than, overlap_depth, overlap_with_depth};
pub use triangle::triangle_meets_interior;
pub use witness::{contact_points, interior_witness};

use crate::polytope::Polytope;
use apart_kernel::int::{self, Int};
use apart_kernel::{fvec, HPoint, Sign, Vec3};
use filter::{compare, float_range, unit, FilteredPair};

/// True when some plane weakly separates `a` and `b` (their interiors are disjoint).
///
/// Separating-axis test over the exact candidate normals of two convex polytopes: the
/// facet normals of both and the cross products of their edge directions. Touching
/// polytopes (shared faces, edges, points) are separated.
pub fn interiors_disjoint(a: &Polytope, b: &Polytope) -> bool {
    separating_normal(a, b).is_some()
}

/// True when the interiors of `a + t` and `b` meet, for an exact translation `t`
/// (touching is not interference), without building the translated polytope: the
/// separating-axis test over the same candidate normals as [`interiors_disjoint`],
/// with `n · t` added to `a`'s support values, all cross-multiplied by the
/// denominators. For placement, where pieces are tested at many rational positions.
pub fn interiors_meet_translated(a: &Polytope, t: &HPoint, b: &Polytope) -> bool {
    let (da, db) = (a.den(), b.den());
    let (x, w) = (t.num(), t.den());
    // Separated along n when [la, ha]/da + n·t and [lb, hb]/db touch or are apart.
    let separated = |n: &Vec3| -> bool {
        let ha = a.support_value(n);
        let hb = b.support_value(n);
        let na = a.support_value(&n.neg());
        let nb = b.support_value(&n.neg());
        let (la, lb) = (-na, -nb);
        let nd = n.to_ints();
        let nd = &nd[0] * &x[0] + &nd[1] * &x[1] + &nd[2] * &x[2];
        let dadb = da * db;
        // a below b: ha/da + nd/w <= lb/db.
        let below = &(&ha * db) * w - &(&lb * da) * w + &nd * &dadb;
        if int::sign_of(&below) != Sign::Positive {
            return true;
        }
        // b below a: hb/db <= la/da + nd/w.
        let above = &(&hb * da) * w - &(&la * db) * w - &nd * &dadb;
        int::sign_of(&above) != Sign::Positive
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

/// A normal `n` with `max_a n·x <= min_b n·y`, if any (the plane separates with `a` below).
///
/// The candidate normals are tried behind a floating-point filter: an axis along which
/// the shadows overlap by more than a proven bound of the rounding error cannot
/// separate and is skipped, facet normals are tried in the order of how far the other
/// polytope's centre lies beyond the facet, and the exact support values are taken over
/// only the vertices within the error bound of the floating-point extreme. Every
/// decision is exact; the filter only prunes.
pub fn separating_normal(a: &Polytope, b: &Polytope) -> Option<Vec3> {
    match filtered_relation(a, b) {
        Some(Relation::Apart(n)) => Some(n),
        Some(Relation::Overlapping(_)) => None,
        None => exact_separating_normal(a, b),
    }
}

/// What the filtered separating-axis test found.
enum Relation {
    /// A separating normal (`a` below).
    Apart(Vec3),
    /// No separating axis; with a common interior point `(X, W)` when one was found.
    Overlapping(Option<(Vec3, Int)>),
}

/// [`separating_normal`] without a filter: every candidate axis, exact supports.
fn exact_separating_normal(a: &Polytope, b: &Polytope) -> Option<Vec3> {
    if a.den() != b.den() {
        let (a, b) = Polytope::common(a, b);
        return exact_separating_normal(&a, &b);
    }
    let separates = |n: &Vec3| -> bool {
        let ha = a.support_value(n);
        let hb = b.support_value(&n.neg());
        // max_a n·x <= min_b n·y  <=>  ha + hb' <= 0 with hb' = max_b (-n)·y.
        ha + hb <= Int::ZERO
    };
    for f in a.facets() {
        if separates(&f.normal) {
            return Some(f.normal.clone());
        }
    }
    for f in b.facets() {
        let n = f.normal.neg();
        if separates(&n) {
            return Some(n);
        }
    }
    for da in a.edge_directions() {
        for db in b.edge_directions() {
            let n = da.cross(db);
            if n.is_zero() {
                continue;
            }
            let n = n.primitive();
            if separates(&n) {
                return Some(n);
            }
            let m = n.neg();
            if separates(&m) {
                return Some(m);
            }
        }
    }
    None
}

/// Every facet normal of `a`, and negated facet normal of `b`, along which `a` lies
/// weakly below `b` (`max_a n·x <= min_b n·y`), with whether strictly: the facet
/// separating axes of a pair, exact, behind the floating-point filter.
pub fn facet_axes(a: &Polytope, b: &Polytope) -> Vec<(Vec3, bool)> {
    let Some(fp) = FilteredPair::new(a, b) else {
        return exact_facet_axes(a, b);
    };
    let mut out: Vec<(usize, bool, (Vec3, bool))> = fp
        .facet_candidates()
        .into_iter()
        .filter_map(|(_, of_b, i, u)| Some((i, of_b, fp.below_candidate(of_b, i, &u)?)))
        .collect();
    // The order of the facets, a's first, as the unfiltered version gives.
    out.sort_by_key(|&(i, of_b, _)| (of_b, i));
    out.into_iter().map(|x| x.2).collect()
}

/// [`facet_axes`] without the filter: every facet, exact supports.
fn exact_facet_axes(a: &Polytope, b: &Polytope) -> Vec<(Vec3, bool)> {
    let mut out = Vec::new();
    for f in a.facets() {
        let hb = b.support_value(&f.normal.neg());
        if let Some(s) = compare(&f.offset, a.den(), &-hb, b.den()) {
            out.push((f.normal.clone(), s));
        }
    }
    for f in b.facets() {
        let ha = a.support_value(&f.normal.neg());
        if let Some(s) = compare(&f.offset, b.den(), &-ha, a.den()) {
            out.push((f.normal.neg(), s));
        }
    }
    out
}

/// Whether `a` lies weakly below `b` along `n` (`max_a n·x <= min_b n·y`, true
/// coordinates), and whether strictly; `None` when not. Exact, behind the filter.
pub fn below_along(a: &Polytope, b: &Polytope, n: &Vec3) -> Option<bool> {
    match (FilteredPair::new(a, b), unit(n)) {
        (Some(fp), Some(u)) => fp.below(n, &u),
        _ => {
            let ha = a.support_value(n);
            let hb = b.support_value(&n.neg());
            compare(&ha, a.den(), &-hb, b.den())
        }
    }
}

/// [`separating_normal`] and [`interior_witness`] behind the floating-point filter:
/// `None` when a polytope has no shadow (the filter does not apply).
fn filtered_relation(a: &Polytope, b: &Polytope) -> Option<Relation> {
    let fp = FilteredPair::new(a, b)?;
    for (_, of_b, i, u) in fp.facet_candidates() {
        if let Some((n, _)) = fp.below_candidate(of_b, i, &u) {
            return Some(Relation::Apart(n));
        }
    }
    // Before the edge axes (quadratic in the edge directions): a common interior point
    // proves that nothing separates.
    if let Some(p) = fp.common_interior_point() {
        return Some(Relation::Overlapping(Some(p)));
    }
    for da in a.edge_directions() {
        for db in b.edge_directions() {
            let n = da.cross(db);
            if n.is_zero() {
                continue;
            }
            let Some(u) = unit(&n) else {
                // No float axis: decide this one exactly.
                for m in [n.clone(), n.neg()] {
                    if below_along(a, b, &m).is_some() {
                        return Some(Relation::Apart(m.primitive()));
                    }
                }
                continue;
            };
            let ((alo, ahi), (blo, bhi)) = (float_range(fp.sa, &u), float_range(fp.sb, &u));
            if fp.below_given(&n, &u, ahi, blo).is_some() {
                return Some(Relation::Apart(n.primitive()));
            }
            let (m, mu) = (n.neg(), fvec::neg(u));
            if fp.below_given(&m, &mu, -alo, -bhi).is_some() {
                return Some(Relation::Apart(m.primitive()));
            }
        }
    }
    Some(Relation::Overlapping(None))
}

#[cfg(test)]
mod tests {
    use super::*;
    use apart_kernel::Rational;

    fn boxp(lo: [i64; 3], hi: [i64; 3]) -> Polytope {
        Polytope::cuboid(lo, hi).unwrap()
    }

    pub(super) fn strictly_inside(p: &Polytope, w: &[Rational; 3]) -> bool {
        p.facets().iter().all(|f| {
            let mut s = Rational::from_int(-f.offset.clone());
            for (k, c) in w.iter().enumerate() {
                s = &s + &(&Rational::from_int(f.normal.get(k)) * c);
            }
            s.sign() == Sign::Negative
        })
    }

    #[test]
    fn touching_boxes_do_not_interfere() {
        let a = boxp([0, 0, 0], [2, 2, 2]);
        assert!(interiors_disjoint(&a, &boxp([2, 0, 0], [4, 2, 2]))); // shared face
        assert!(interiors_disjoint(&a, &boxp([2, 2, 0], [4, 4, 2]))); // shared edge
        assert!(interiors_disjoint(&a, &boxp([2, 2, 2], [4, 4, 4]))); // shared vertex
        assert!(interior_witness(&a, &boxp([2, 0, 0], [4, 2, 2])).is_none());
    }

    #[test]
    fn overlapping_boxes_have_a_witness() {
        let a = boxp([0, 0, 0], [2, 2, 2]);
        for b in [
            boxp([1, 1, 1], [3, 3, 3]),
            boxp([0, 0, 0], [2, 2, 2]),
            boxp([-1, 1, -1], [3, 2, 3]),
        ] {
            let w = interior_witness(&a, &b).expect("overlap");
            assert!(strictly_inside(&a, &w) && strictly_inside(&b, &w), "{w:?}");
        }
    }

    #[test]
    fn crossing_without_vertices_inside() {
        // Two long bars crossing like a plus sign: no vertex of either is inside the other.
        let a = boxp([-4, -1, 0], [4, 1, 1]);
        let b = boxp([-1, -4, 0], [1, 4, 1]);
        let w = interior_witness(&a, &b).expect("overlap");
        assert!(strictly_inside(&a, &w) && strictly_inside(&b, &w));
    }
}

#[cfg(test)]
mod den_tests {
    use super::*;
    use apart_kernel::Rational;
    use apart_kernel::Vec3;

    #[test]
    fn different_denominators() {
        // The cube [0, 1]^3 stored with denominator 2, and [1, 2] x [0, 1] x [0, 1].
        let pts = |lo: i64, s: i64| -> Vec<Vec3> {
            (0..8)
                .map(|i| Vec3::new(lo + (i & 1) * s, (i >> 1 & 1) * s, (i >> 2) * s))
                .collect()
        };
        let a = Polytope::hull_of_points(&pts(0, 2))
            .unwrap()
            .with_den(apart_kernel::Int::from(2));
        let b = Polytope::hull_of_points(&pts(1, 1)).unwrap();
        assert_eq!(a.volume(), Rational::from_int(1));
        assert!(interiors_disjoint(&a, &b));
        // Overlap: the unit cube itself, stored with denominator 3.
        let d = Polytope::hull_of_points(&pts(0, 3))
            .unwrap()
            .with_den(apart_kernel::Int::from(3));
        let w = interior_witness(&a, &d).expect("same cube");
        for c in &w {
            assert_eq!(
                *c,
                Rational::new(apart_kernel::Int::from(1), apart_kernel::Int::from(2))
            );
        }
    }
}
