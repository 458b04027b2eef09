//! `Polytope::hull` (gift wrapping, `O(n h)`) against `Polytope::hull_of_points` (every
//! triple of points tried as a facet plane, `O(n^4)`): the same facet planes, the same
//! vertices and the same volume, on random and deliberately degenerate point sets
//! (lattice points, many coplanar and collinear points, duplicates, flat sets).

use apart_kernel::{Int, Vec3};
use apart_pieces::Polytope;
use proptest::prelude::*;

fn same_hull(pts: &[Vec3]) -> Result<(), TestCaseError> {
    let fast = Polytope::hull(pts);
    let slow = Polytope::hull_of_points(pts);
    match (fast, slow) {
        (Err(_), Err(_)) => {}
        (Ok(f), Ok(s)) => {
            let planes = |p: &Polytope| {
                let mut v: Vec<(Vec3, Int)> = p
                    .facets()
                    .iter()
                    .map(|f| (f.normal.clone(), f.offset.clone()))
                    .collect();
                v.sort_by_cached_key(|(n, o)| (n.to_ints(), o.clone()));
                v
            };
            let verts = |p: &Polytope| {
                let mut v: Vec<[Int; 3]> = p.vertices().iter().map(|x| x.to_ints()).collect();
                v.sort();
                v
            };
            prop_assert_eq!(planes(&f), planes(&s));
            prop_assert_eq!(verts(&f), verts(&s));
            prop_assert_eq!(f.volume6(), s.volume6());
        }
        (f, s) => prop_assert!(
            false,
            "hull {:?} but hull_of_points {:?}",
            f.is_ok(),
            s.is_ok()
        ),
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    #[test]
    fn random_points(pts in prop::collection::vec((-50i64..50, -50i64..50, -50i64..50), 4..24)) {
        let pts: Vec<Vec3> = pts.into_iter().map(|(x, y, z)| Vec3::new(x, y, z)).collect();
        same_hull(&pts)?;
    }

    /// Few values per coordinate: duplicates, lattice faces with many coplanar and
    /// collinear points, flat and collinear sets.
    #[test]
    fn lattice_points(pts in prop::collection::vec((0i64..3, 0i64..3, 0i64..3), 4..28)) {
        let pts: Vec<Vec3> = pts.into_iter().map(|(x, y, z)| Vec3::new(x, y, z)).collect();
        same_hull(&pts)?;
    }

    /// A prism: a random polygon's points at two heights, as the shrink's rounding of a
    /// tessellated cylinder piece gives (large caps, all points coplanar per cap).
    #[test]
    fn prisms(ring in prop::collection::vec((-1000i64..1000, -1000i64..1000), 3..12), h in 1i64..50) {
        let mut pts = Vec::new();
        for (x, y) in ring {
            pts.push(Vec3::new(x, y, 0));
            pts.push(Vec3::new(x, y, h));
        }
        same_hull(&pts)?;
    }

    /// Points far from the origin and on a slanted plane (big coordinates).
    #[test]
    fn slanted_and_far(pts in prop::collection::vec((-30i64..30, -30i64..30, 0i64..2), 4..20)) {
        let far = 1i64 << 40;
        let pts: Vec<Vec3> = pts
            .into_iter()
            .map(|(x, y, k)| Vec3::new(far + x, far + y + 3 * x, far + 2 * x - y + k * 7))
            .collect();
        same_hull(&pts)?;
    }
}

#[test]
fn a_regular_polygon_prism_with_hundreds_of_points() {
    // 400-gon prism on a 2^20 circle: every point is a vertex; the hull has 402 facets.
    let n = 400;
    let r = (1i64 << 20) as f64;
    let mut pts = Vec::new();
    for k in 0..n {
        let t = std::f64::consts::TAU * k as f64 / n as f64;
        let (x, y) = ((r * t.cos()).round() as i64, (r * t.sin()).round() as i64);
        pts.push(Vec3::new(x, y, -5));
        pts.push(Vec3::new(x, y, 5));
    }
    let h = Polytope::hull(&pts).unwrap();
    // Rounding may make a few ring points non-extreme; every facet must hold all points
    // inside, and the two caps are facets.
    for f in h.facets() {
        for p in &pts {
            assert!(f.normal.dot(p) <= f.offset);
        }
    }
    let caps = h
        .facets()
        .iter()
        .filter(|f| f.normal == Vec3::new(0, 0, 1) || f.normal == Vec3::new(0, 0, -1))
        .count();
    assert_eq!(caps, 2);
    assert_eq!(h.facets().len(), h.vertices().len() / 2 + 2);
}
