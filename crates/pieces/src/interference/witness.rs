//! Where two overlapping polytopes meet: an exact point of both interiors, and the
//! candidate vertices of their intersection.

use super::{exact_separating_normal, filtered_relation, Relation};
use crate::polytope::{Containment, Polytope};
use apart_kernel::int::{self, Int};
use apart_kernel::{Rational, Sign, Vec3};

/// When the interiors of `a` and `b` meet, a point in both interiors (exact rational
/// coordinates); `None` when they are disjoint or only touch.
///
/// The witness is an average of vertices of each lying inside the other when the
/// floating-point filter finds one that checks exactly; otherwise the average of a
/// superset of the vertices of `a ∩ b` (vertices of one inside the other, and crossings
/// of edges of one with facets of the other): a convex combination giving every vertex
/// of the full-dimensional intersection positive weight, hence an interior point of it.
pub fn interior_witness(a: &Polytope, b: &Polytope) -> Option<[Rational; 3]> {
    match filtered_relation(a, b) {
        Some(Relation::Apart(_)) => return None,
        Some(Relation::Overlapping(Some((x, w)))) => {
            return Some([0, 1, 2].map(|k| Rational::new(x.get(k), w.clone())));
        }
        Some(Relation::Overlapping(None)) => {}
        None => {
            if exact_separating_normal(a, b).is_some() {
                return None;
            }
        }
    }
    if a.den() != b.den() {
        let (a, b) = Polytope::common(a, b);
        return interior_witness(&a, &b);
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

/// Where the homogeneous point `x / w` (`w > 0`, stored coordinates) lies in `p`.
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
