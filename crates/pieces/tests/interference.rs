//! Property tests of the filtered separating-axis test against an independent oracle:
//! the interiors of two convex polytopes meet exactly when the mean of the vertices of
//! their intersection (a superset from `contact_points`) lies strictly inside both.
//! Random hulls on a small grid give coincident vertices, shared faces and edges, and
//! touching placements are built on purpose; rational denominators and huge coordinates
//! exercise the big-number paths.

use apart_kernel::int::Int;
use apart_kernel::HPoint;
use apart_kernel::Vec3;
use apart_pieces::interference::{
    below_along, contact_points, facet_axes, interiors_disjoint, interiors_meet_translated,
    separating_normal,
};
use apart_pieces::Polytope;
use proptest::prelude::*;

/// Whether the interiors meet, by the oracle (exact, without separating axes).
fn oracle_overlap(a: &Polytope, b: &Polytope) -> bool {
    let (a, b) = Polytope::common(a, b);
    let pts = contact_points(&a, &b);
    if pts.is_empty() {
        return false;
    }
    // Mean of x_i / w_i as P / q with q = prod-free common form: sum over i of
    // x_i * (L / w_i), over L * len, with L the product of distinct w_i.
    let mut l = Int::ONE;
    for (_, w) in &pts {
        if (&l % w) != Int::ZERO {
            l *= w;
        }
    }
    let mut p = Vec3::new(0, 0, 0);
    for (x, w) in &pts {
        p = p.add(&x.scale(&(&l / w)));
    }
    let q = &l * Int::from(pts.len());
    // p / q are stored coordinates (den times the true ones): strictly inside when
    // n · p < offset · q for every facet of both.
    [&a, &b].iter().all(|poly| {
        poly.facets()
            .iter()
            .all(|f| f.normal.dot(&p) < &f.offset * &q)
    })
}

fn hull(pts: &[(i64, i64, i64)], scale: i64) -> Option<Polytope> {
    let v: Vec<Vec3> = pts
        .iter()
        .map(|&(x, y, z)| Vec3::new(x * scale, y * scale, z * scale))
        .collect();
    Polytope::hull_of_points(&v).ok()
}

fn check(a: &Polytope, b: &Polytope) -> Result<(), TestCaseError> {
    let expect = oracle_overlap(a, b);
    prop_assert_eq!(interiors_disjoint(a, b), !expect);
    prop_assert_eq!(interiors_disjoint(b, a), !expect);
    // The facet axes and single-axis comparisons, against exact supports over every
    // vertex (true coordinates: cross-multiplied by the denominators).
    let brute = |n: &Vec3| -> Option<bool> {
        let (ha, _) = a.support(n);
        let (hb, _) = b.support(&n.neg());
        let lhs = ha * b.den() + hb * a.den();
        (lhs <= Int::ZERO).then_some(lhs < Int::ZERO)
    };
    let mut expect_axes = Vec::new();
    for f in a.facets() {
        if let Some(s) = brute(&f.normal) {
            expect_axes.push((f.normal.clone(), s));
        }
    }
    for f in b.facets() {
        if let Some(s) = brute(&f.normal.neg()) {
            expect_axes.push((f.normal.neg(), s));
        }
    }
    prop_assert_eq!(facet_axes(a, b), expect_axes);
    for k in 0..3 {
        for s in [1, -1] {
            let mut e = [0i64; 3];
            e[k] = s;
            let n = Vec3::from_i64(e);
            prop_assert_eq!(below_along(a, b, &n), brute(&n));
        }
    }
    if let Some(n) = separating_normal(a, b) {
        // The returned plane separates, checked on the true coordinates.
        let (ha, _) = a.support(&n);
        let (hb, _) = b.support(&n.neg());
        prop_assert!(ha * b.den() + hb * a.den() <= Int::ZERO);
    }
    Ok(())
}

fn points() -> impl Strategy<Value = Vec<(i64, i64, i64)>> {
    prop::collection::vec((-4i64..5, -4i64..5, -4i64..5), 4..12)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn random_hulls_on_a_small_grid(pa in points(), pb in points(), da in 1i64..4, db in 1i64..4) {
        let (Some(a), Some(b)) = (hull(&pa, 1), hull(&pb, 1)) else { return Ok(()) };
        check(&a, &b)?;
        check(&a.with_den(Int::from(da)), &b.with_den(Int::from(db)))?;
    }

    #[test]
    fn touching_placements(pa in points(), pick in 0usize..64, shift in (-3i64..4, -3i64..4)) {
        let Some(a) = hull(&pa, 1) else { return Ok(()) };
        // B = A moved by its width along an axis plus a small shift across: it touches
        // along a face, an edge or a vertex, or overlaps, or is apart.
        let axis = pick % 3;
        let lo = a.vertices().iter().map(|v| v.get(axis)).min().unwrap();
        let hi = a.vertices().iter().map(|v| v.get(axis)).max().unwrap();
        let w = apart_kernel::int::to_i64(&(hi - lo)).unwrap();
        let mut t = [shift.0, shift.1, shift.0 + shift.1];
        t[axis] = w;
        let b = a.translated(&Vec3::from_i64(t));
        check(&a, &b)?;
        // Vertex against vertex: B moved by the difference of two vertices of A.
        let n = a.vertices().len();
        let d = a.vertices()[pick % n].sub(&a.vertices()[(pick / 3) % n]);
        check(&a, &a.translated(&d))?;
    }

    #[test]
    fn huge_coordinates(pa in points(), pb in points(), k in 30u32..40) {
        let s = 1i64 << k;
        let (Some(a), Some(b)) = (hull(&pa, s), hull(&pb, s)) else { return Ok(()) };
        let big = Int::from(s) * Int::from(s) * Int::from(7);
        check(&a.rescaled(&big), &b)?;
    }

    #[test]
    fn translated_pieces_agree_with_translated_polytopes(
        pa in points(), pb in points(), da in 1i64..4, db in 1i64..4,
        t in (-9i64..10, -9i64..10, -9i64..10), w in 1i64..4,
    ) {
        let (Some(a), Some(b)) = (hull(&pa, 1), hull(&pb, 1)) else { return Ok(()) };
        let (a, b) = (a.with_den(Int::from(da)), b.with_den(Int::from(db)));
        // a + t/w, built: stored integers scaled by w, shifted by t den, over den w.
        let moved = a
            .rescaled(&Int::from(w))
            .with_den(Int::ONE)
            .translated(&Vec3::new(t.0, t.1, t.2).scale(&Int::from(da)))
            .with_den(Int::from(da * w));
        let shift = HPoint::from_wide([t.0 as i128, t.1 as i128, t.2 as i128], w as i128);
        let expect = oracle_overlap(&moved, &b);
        prop_assert_eq!(interiors_meet_translated(&a, &shift, &b), expect);
        prop_assert_eq!(interiors_disjoint(&moved, &b), !expect);
    }
}
