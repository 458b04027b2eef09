//! Exact interference of two convex polytopes: do their interiors meet, and where.

use crate::polytope::{Containment, Polytope};
use apart_kernel::int::{self, Int};
use apart_kernel::{Rational, Sign, Vec3};

/// True when some plane weakly separates `a` and `b` (their interiors are disjoint).
///
/// Separating-axis test over the exact candidate normals of two convex polytopes: the
/// facet normals of both and the cross products of their edge directions. Touching
/// polytopes (shared faces, edges, points) are separated.
pub fn interiors_disjoint(a: &Polytope, b: &Polytope) -> bool {
    separating_normal(a, b).is_some()
}

/// A normal `n` with `max_a n·x <= min_b n·y`, if any (the plane separates with `a` below).
pub fn separating_normal(a: &Polytope, b: &Polytope) -> Option<Vec3> {
    if a.den() != b.den() {
        let (a, b) = Polytope::common(a, b);
        return separating_normal(&a, &b);
    }
    let separates = |n: &Vec3| -> bool {
        let (ha, _) = a.support(n);
        let (hb, _) = b.support(&n.neg());
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

/// When the interiors of `a` and `b` meet, a point in both interiors (exact rational
/// coordinates); `None` when they are disjoint or only touch.
///
/// The witness is the average of a superset of the vertices of `a ∩ b` (vertices of one
/// inside the other, and crossings of edges of one with facets of the other): a convex
/// combination giving every vertex of the full-dimensional intersection positive weight,
/// hence an interior point of it.
pub fn interior_witness(a: &Polytope, b: &Polytope) -> Option<[Rational; 3]> {
    if a.den() != b.den() {
        let (a, b) = Polytope::common(a, b);
        return interior_witness(&a, &b);
    }
    if interiors_disjoint(a, b) {
        return None;
    }
    let pts = contact_points(a, b);
    debug_assert!(!pts.is_empty());
    // Average of x_i / w_i.
    let mut sum = [Rational::zero(), Rational::zero(), Rational::zero()];
    for (x, w) in &pts {
        for (k, s) in sum.iter_mut().enumerate() {
            *s = &*s + &Rational::new(x.get(k), w.clone());
        }
    }
    // The stored integers are den times the coordinates.
    let n = Rational::from_int(Int::from(pts.len()) * a.den());
    let inv = Rational::new(n.denom().clone(), n.numer().clone());
    Some(sum.map(|s| &s * &inv))
}

/// A superset of the vertices of `a ∩ b` for two closed convex polytopes at the same
/// denominator, as homogeneous points `(x, w)`, `w > 0` (coordinates `x / (w · den)`):
/// the vertices of one inside or on the other, and the crossings of the edges of one with
/// the facets of the other that lie in the other. Empty when `a` and `b` do not meet.
pub fn contact_points(a: &Polytope, b: &Polytope) -> Vec<(Vec3, Int)> {
    debug_assert_eq!(
        a.den(),
        b.den(),
        "contact_points needs a common denominator"
    );
    let mut pts: Vec<(Vec3, Int)> = Vec::new();
    for (p, q) in [(a, b), (b, a)] {
        for v in p.vertices() {
            if q.locate(v) != Containment::Outside {
                pts.push((v.clone(), Int::ONE));
            }
        }
        for e in p.edges() {
            let (s, t) = (
                &p.vertices()[e.ends[0] as usize],
                &p.vertices()[e.ends[1] as usize],
            );
            let d = t.sub(s);
            for f in q.facets() {
                // n·(s + λ d) = c  =>  λ = (c - n·s) / (n·d), strictly inside (0, 1).
                let den = f.normal.dot(&d);
                if den == Int::ZERO {
                    continue;
                }
                let num = &f.offset - f.normal.dot(s);
                let (num, den) = if den < Int::ZERO {
                    (-num, -den)
                } else {
                    (num, den)
                };
                if num <= Int::ZERO || num >= den {
                    continue;
                }
                // Point = (s * den + d * num) / den.
                let x = s.scale(&den).add(&d.scale(&num));
                if locate_homogeneous(q, &x, &den) != Containment::Outside {
                    pts.push((x, den));
                }
            }
        }
    }
    pts
}

fn locate_homogeneous(p: &Polytope, x: &Vec3, w: &Int) -> Containment {
    let mut on = false;
    for f in p.facets() {
        match int::sign_of(&(f.normal.dot(x) - &f.offset * w)) {
            Sign::Positive => return Containment::Outside,
            Sign::Zero => on = true,
            Sign::Negative => {}
        }
    }
    if on {
        Containment::Boundary
    } else {
        Containment::Inside
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn boxp(lo: [i64; 3], hi: [i64; 3]) -> Polytope {
        Polytope::cuboid(lo, hi).unwrap()
    }

    fn strictly_inside(p: &Polytope, w: &[Rational; 3]) -> bool {
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

/// How deep the interiors of `a` and `b` overlap: the shortest translation that
/// separates them, in true coordinates, measured in floating point (a report for people,
/// never a decision). Taken over the candidate separating axes of [`separating_normal`]
/// (facet normals of both, and the cross products of edge directions while there are
/// at most 4096 of them), so it is the exact penetration depth up to rounding, or an
/// upper bound of it when the cross products were left out. Zero for touching or
/// disjoint polytopes.
pub fn overlap_depth(a: &Polytope, b: &Polytope) -> f64 {
    signed_depth(a, b).depth.max(0.0)
}

/// Whether the interiors of `a` and `b` overlap (exact), and how deep (measured, as
/// [`overlap_depth`]; 0 when they do not). A floating-point filter decides first: a
/// clear gap along one axis proves them apart, a clear overlap along every candidate
/// axis proves them overlapping, each beyond a proven bound of the rounding error; the
/// exact separating-axis test decides the rest.
pub fn overlap_with_depth(a: &Polytope, b: &Polytope) -> (bool, f64) {
    let s = signed_depth(a, b);
    let overlapping = if s.depth < -s.error {
        false
    } else if s.depth > s.error && s.all_axes {
        true
    } else {
        !interiors_disjoint(a, b)
    };
    (
        overlapping,
        if overlapping { s.depth.max(0.0) } else { 0.0 },
    )
}

/// The smallest signed overlap over the candidate axes (negative: a gap), whether every
/// candidate axis was tried, and a bound of the rounding error.
struct SignedDepth {
    depth: f64,
    all_axes: bool,
    error: f64,
}

fn signed_depth(a: &Polytope, b: &Polytope) -> SignedDepth {
    let pts = |p: &Polytope| -> Vec<[f64; 3]> {
        // Exact values divided once: `approx` is only proportional for big vectors.
        p.vertices()
            .iter()
            .map(|v| [0, 1, 2].map(|k| Rational::new(v.get(k), p.den().clone()).to_f64()))
            .collect()
    };
    let (pa, pb) = (pts(a), pts(b));
    // Every coordinate is below m in magnitude. Each vertex coordinate and each unit
    // axis component carries a relative error of at most 2^-52, so a dot product of a
    // vertex with a unit axis is off by less than 8 m 2^-52, and a signed overlap (a
    // difference of two extremes) by less than 16 m 2^-52; 2^-40 m leaves a margin.
    let m = pa
        .iter()
        .chain(&pb)
        .flatten()
        .fold(0f64, |x, c| x.max(c.abs()));
    let error = m * 2f64.powi(-40);
    let range = |ps: &[[f64; 3]], u: &[f64; 3]| {
        ps.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                let t = p[0] * u[0] + p[1] * u[1] + p[2] * u[2];
                (lo.min(t), hi.max(t))
            })
    };
    let overlap_along = |n: [f64; 3]| -> f64 {
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        if len == 0.0 || !len.is_finite() {
            return f64::INFINITY;
        }
        let u = n.map(|c| c / len);
        let ((alo, ahi), (blo, bhi)) = (range(&pa, &u), range(&pb, &u));
        (ahi - blo).min(bhi - alo)
    };
    let mut best = f64::INFINITY;
    for f in a.facets().iter().chain(b.facets()) {
        best = best.min(overlap_along(f.normal.approx()));
    }
    let (ea, eb) = (a.edge_directions(), b.edge_directions());
    let all_axes = ea.len() * eb.len() <= 4096;
    if all_axes {
        for da in ea {
            for db in eb {
                let n = da.cross(db);
                if !n.is_zero() {
                    best = best.min(overlap_along(n.approx()));
                }
            }
        }
    }
    SignedDepth {
        depth: if best.is_finite() { best } else { 0.0 },
        all_axes: all_axes && best.is_finite(),
        error: if m.is_finite() { error } else { f64::INFINITY },
    }
}

#[cfg(test)]
mod depth_tests {
    use super::*;

    #[test]
    fn depth_of_overlapping_boxes_is_the_smallest_push() {
        let a = Polytope::cuboid([0, 0, 0], [10, 10, 10]).unwrap();
        // Overlap 3 in x, 10 in y and z: the push is 3.
        let b = Polytope::cuboid([7, 0, 0], [20, 10, 10]).unwrap();
        assert_eq!(overlap_depth(&a, &b), 3.0);
        // Touching: zero. Apart: zero.
        let c = Polytope::cuboid([10, 0, 0], [20, 10, 10]).unwrap();
        assert_eq!(overlap_depth(&a, &c), 0.0);
        let d = Polytope::cuboid([12, 0, 0], [20, 10, 10]).unwrap();
        assert_eq!(overlap_depth(&a, &d), 0.0);
        // A corner poking in diagonally: the octahedron-like tip of a tetrahedron
        // reaching 1 unit past the plane x + y + z = 30 of the box corner region.
        let t = Polytope::hull_of_points(
            &[[9, 9, 9], [20, 9, 9], [9, 20, 9], [9, 9, 20]].map(Vec3::from_i64),
        )
        .unwrap();
        // The tetrahedron's corner (9,9,9) is 1 inside each of the box's faces x=10,
        // y=10, z=10: pushing it out along x by 1 suffices.
        assert!((overlap_depth(&a, &t) - 1.0).abs() < 1e-12);
        // Rational pieces: the same boxes with denominator 4 (coordinates / 4).
        let a4 = a.clone().with_den(Int::from(4));
        let b4 = b.clone().with_den(Int::from(4));
        assert_eq!(overlap_depth(&a4, &b4), 0.75);
    }

    #[test]
    fn the_filtered_decision_agrees_with_the_exact_test() {
        // Overlapping, touching (face, edge, corner), apart, and overlapping by much
        // less than a unit at a scale where the filter must step aside.
        let a = Polytope::cuboid([0, 0, 0], [10, 10, 10]).unwrap();
        let cases = [
            ([7, 0, 0], [20, 10, 10]),
            ([10, 0, 0], [20, 10, 10]),
            ([10, 10, 0], [20, 20, 10]),
            ([10, 10, 10], [20, 20, 20]),
            ([11, 0, 0], [20, 10, 10]),
            ([-5, -5, -5], [15, 15, 15]),
        ];
        for (lo, hi) in cases {
            let b = Polytope::cuboid(lo, hi).unwrap();
            let (o, d) = overlap_with_depth(&a, &b);
            assert_eq!(o, !interiors_disjoint(&a, &b), "{lo:?} {hi:?}");
            assert_eq!(d > 0.0, o);
        }
        // Far from the origin, overlapping by 1 / 2^20 (a denominator): the filter's
        // bound is larger than the overlap, so the exact test decides.
        let big = 1i64 << 40;
        let a = Polytope::cuboid([big, 0, 0], [big + 10, 10, 10])
            .unwrap()
            .rescaled(&Int::from(1u64 << 20));
        let b = Polytope::cuboid(
            [(big + 10) << 20, 0, 0],
            [(big + 20) << 20, 10 << 20, 10 << 20],
        )
        .unwrap()
        .with_den(Int::from(1u64 << 20))
        .translated(&Vec3::new(-1, 0, 0));
        let _ = b; // translated by whole units; build the sliver directly instead
        let c = Polytope::cuboid(
            [((big + 10) << 20) - 1, 0, 0],
            [(big + 20) << 20, 10 << 20, 10 << 20],
        )
        .unwrap()
        .with_den(Int::from(1u64 << 20));
        let (o, _) = overlap_with_depth(&a, &c);
        assert!(o);
        assert!(!interiors_disjoint(&a, &c));
    }
}
