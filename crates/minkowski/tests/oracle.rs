//! The blocked polygon of two convex pieces against the brute-force definition.
//!
//! Oracle (ARCHITECTURE.md, invariants): the open ray `{k d : k > 0}` meets the interior of
//! `M = b ⊕ (−a)` iff some `k > 0` satisfies every facet inequality of `M` strictly, with
//! `M` taken as the convex hull of all vertex differences (computed by the independent
//! all-triples hull, not by the Minkowski code). Directions are small integer vectors,
//! so many lie exactly on boundaries, and pieces sit on a tiny grid, so contacts (shared
//! faces, edges, vertices) are frequent.

use apart_kernel::{Int, Rational, Sign, Vec3};
use apart_minkowski::{blocked_polygon, minkowski_difference, Blocking};
use apart_pieces::Polytope;
use proptest::prelude::*;

fn ray_meets_interior(m: &Polytope, d: &Vec3) -> bool {
    // k in (lo, hi); lo >= 0.
    let mut lo = Rational::zero();
    let mut hi: Option<Rational> = None;
    for f in m.facets() {
        let nd = f.normal.dot(d);
        let c = f.offset.clone();
        if nd == Int::ZERO {
            if c <= Int::ZERO {
                return false;
            }
        } else if nd > Int::ZERO {
            let b = Rational::new(c, nd);
            hi = Some(match hi {
                Some(h) if h < b => h,
                _ => b,
            });
        } else {
            let b = Rational::new(c, nd);
            if b > lo {
                lo = b;
            }
        }
    }
    match hi {
        Some(h) => lo < h,
        None => true,
    }
}

fn brute_difference(b: &Polytope, a: &Polytope) -> Polytope {
    let mut s = Vec::new();
    for y in b.vertices() {
        for x in a.vertices() {
            s.push(y.sub(x));
        }
    }
    Polytope::hull_of_points(&s).unwrap()
}

fn piece() -> impl Strategy<Value = Polytope> {
    prop_oneof![
        // Boxes on a tiny grid: touching everywhere.
        (
            prop::array::uniform3(-2i64..=1),
            prop::array::uniform3(1i64..=2)
        )
            .prop_map(|(lo, size)| {
                let mut pts = Vec::new();
                for i in 0..8 {
                    pts.push(Vec3::new(
                        lo[0] + (i & 1) * size[0],
                        lo[1] + (i >> 1 & 1) * size[1],
                        lo[2] + (i >> 2) * size[2],
                    ));
                }
                Polytope::hull_of_points(&pts).unwrap()
            }),
        // Random small convex polytopes.
        prop::collection::vec(prop::array::uniform3(-3i64..=3), 4..9).prop_filter_map(
            "flat",
            |c| {
                let pts: Vec<Vec3> = c.into_iter().map(Vec3::from).collect();
                Polytope::hull_of_points(&pts).ok()
            }
        ),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn sum_matches_hull_of_differences(a in piece(), b in piece()) {
        let m = minkowski_difference(&b, &a).unwrap();
        let brute = brute_difference(&b, &a);
        let mut va: Vec<String> = m.vertices().iter().map(|v| format!("{v:?}")).collect();
        let mut vb: Vec<String> = brute.vertices().iter().map(|v| format!("{v:?}")).collect();
        va.sort();
        vb.sort();
        prop_assert_eq!(va, vb);
        prop_assert_eq!(m.facets().len(), brute.facets().len());
        prop_assert_eq!(m.volume6(), brute.volume6());
    }

    #[test]
    fn blocked_iff_ray_meets_interior(a in piece(), b in piece(), dirs in prop::collection::vec(prop::array::uniform3(-2i64..=2), 30)) {
        let brute = brute_difference(&b, &a);
        let origin_inside = brute.locate(&Vec3::ZERO) == apart_pieces::Containment::Inside;
        match blocked_polygon(&a, &b).unwrap() {
            Blocking::Overlap => prop_assert!(origin_inside),
            Blocking::Polygon(q) => {
                prop_assert!(!origin_inside);
                for d in dirs {
                    let d = Vec3::from(d);
                    if d.is_zero() { continue; }
                    prop_assert_eq!(q.contains_open(&d), ray_meets_interior(&brute, &d), "direction {:?}", d);
                }
                // Every side is a minor arc counter-clockwise around its inward normal.
                for arc in q.boundary() {
                    prop_assert_eq!(apart_kernel::predicates::det3_sign(&arc.normal, &arc.start, &arc.end), Sign::Positive);
                }
            }
        }
    }

    /// Q_ji = −Q_ij: the blocked polygon of (b moving, a fixed) is the antipode.
    #[test]
    fn antipodal_symmetry(a in piece(), b in piece(), dirs in prop::collection::vec(prop::array::uniform3(-2i64..=2), 20)) {
        if let (Blocking::Polygon(p), Blocking::Polygon(q)) = (blocked_polygon(&a, &b).unwrap(), blocked_polygon(&b, &a).unwrap()) {
            for d in dirs {
                let d = Vec3::from(d);
                if d.is_zero() { continue; }
                prop_assert_eq!(p.contains_open(&d), q.contains_open(&d.neg()));
            }
        }
    }
}
