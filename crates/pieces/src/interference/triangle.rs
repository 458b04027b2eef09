//! Whether a triangle meets a polytope's interior: the separating-axis test over the
//! facet normals of their difference.

use crate::polytope::Polytope;
use apart_kernel::Vec3;

/// True when the closed triangle `tri` (grid points) meets the interior of `p`: no
/// plane weakly separates them. The candidate normals are those of the facets of
/// `p − tri`: `p`'s facet normals, the triangle's normal, and the cross products of
/// `p`'s edge directions with the triangle's sides. A triangle lying on a facet of `p`,
/// or touching it at an edge or a point, does not meet it.
pub fn triangle_meets_interior(p: &Polytope, tri: &[[i64; 3]; 3]) -> bool {
    let den = p.den();
    let t = tri.map(|c| Vec3::from_i64(c).scale(den));
    // Separated along n when max_p n·x <= min_t n·y, or max_t n·y <= min_p n·x.
    let separated = |n: &Vec3| -> bool {
        let ht = t.iter().map(|y| n.dot(y)).max().expect("three corners");
        let lt = t.iter().map(|y| n.dot(y)).min().expect("three corners");
        p.support_value(n) <= lt || ht <= -p.support_value(&n.neg())
    };
    if p.facets().iter().any(|f| separated(&f.normal)) {
        return false;
    }
    let sides = [t[1].sub(&t[0]), t[2].sub(&t[1]), t[0].sub(&t[2])];
    let normal = sides[0].cross(&sides[1]);
    if !normal.is_zero() && separated(&normal.primitive()) {
        return false;
    }
    for e in p.edge_directions() {
        for s in &sides {
            let n = e.cross(s);
            if !n.is_zero() && separated(&n.primitive()) {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use apart_kernel::rational;
    use apart_kernel::{Int, Rational, Sign};

    /// The value `n · (den x) - offset` of facet `f` at an exact point `x`.
    fn level(p: &Polytope, f: &crate::Facet, x: &[Rational; 3]) -> Rational {
        let n = f
            .normal
            .to_ints()
            .map(|c| Rational::new(&c * p.den(), Int::from(1)));
        &rational::dot(&n, x) - &Rational::new(f.offset.clone(), Int::from(1))
    }

    /// Independent oracle: clip the triangle by every facet half-space (exact
    /// Sutherland-Hodgman); the clipped polygon meets the interior exactly when the mean
    /// of its vertices (a relative interior point) is strictly inside every facet.
    fn clipped_meets(p: &Polytope, tri: &[[i64; 3]; 3]) -> bool {
        let mut poly: Vec<[Rational; 3]> = tri.iter().map(|c| c.map(Rational::from)).collect();
        for f in p.facets() {
            let mut out = Vec::new();
            for k in 0..poly.len() {
                let (a, b) = (&poly[k], &poly[(k + 1) % poly.len()]);
                let (la, lb) = (level(p, f, a), level(p, f, b));
                if la.sign() != Sign::Positive {
                    out.push(a.clone());
                }
                let crosses = (la.sign() == Sign::Positive && lb.sign() == Sign::Negative)
                    || (la.sign() == Sign::Negative && lb.sign() == Sign::Positive);
                if crosses {
                    let t = &la / &(&la - &lb);
                    out.push(rational::add(a, &rational::sub(b, a).map(|c| &c * &t)));
                }
            }
            poly = out;
            if poly.is_empty() {
                return false;
            }
        }
        let k = Rational::from(poly.len() as i64);
        let mean = [0, 1, 2].map(|i| &poly.iter().fold(Rational::zero(), |s, q| &s + &q[i]) / &k);
        p.facets()
            .iter()
            .all(|f| level(p, f, &mean).sign() == Sign::Negative)
    }

    #[test]
    fn triangles_against_polytopes_agree_with_exact_clipping() {
        let cube = Polytope::cuboid([0, 0, 0], [4, 4, 4]).unwrap();
        let pts: Vec<Vec3> = [[0, 0, 0], [6, 1, 0], [1, 5, 1], [2, 2, 6], [5, 5, 4]]
            .map(Vec3::from_i64)
            .to_vec();
        let hull = Polytope::hull_of_points(&pts).unwrap();
        let halved = cube.clone().with_den(Int::from(2));
        let mut rng = apart_testkit::solids::Lcg(7);
        let (mut met, mut apart) = (0, 0);
        for p in [&cube, &hull, &halved] {
            for k in 0..3000 {
                // Small coordinates, so that touching, coplanar and shared-vertex cases
                // are frequent; every fifth triangle is flat on a line.
                let mut c = || (rng.unit() * 8.0).floor() as i64 - 1;
                let mut tri = [[c(), c(), c()], [c(), c(), c()], [c(), c(), c()]];
                if k % 5 == 0 {
                    tri[2] = [0, 1, 2].map(|i| 2 * tri[1][i] - tri[0][i]);
                }
                let got = triangle_meets_interior(p, &tri);
                assert_eq!(got, clipped_meets(p, &tri), "{tri:?}");
                if got {
                    met += 1;
                } else {
                    apart += 1;
                }
            }
        }
        assert!(met > 500 && apart > 500, "{met} {apart}");
        // On a facet, along an edge, at a corner: touching only.
        for tri in [
            [[0, 0, 4], [4, 0, 4], [0, 4, 4]],
            [[0, 0, 0], [4, 0, 0], [2, -3, 0]],
            [[4, 4, 4], [6, 5, 4], [5, 6, 7]],
        ] {
            assert!(!triangle_meets_interior(&cube, &tri));
        }
        // Through the middle, and just entering.
        assert!(triangle_meets_interior(
            &cube,
            &[[-1, 2, 2], [5, 2, 2], [2, 2, 5]]
        ));
        assert!(triangle_meets_interior(
            &cube,
            &[[3, 3, 3], [9, 9, 9], [9, 3, 9]]
        ));
    }
}
