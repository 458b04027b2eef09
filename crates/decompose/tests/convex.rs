//! Oracle: a convex solid decomposes into one piece, its hull.

use apart_decompose::{decompose, reflex_edges, verify, Options};
use apart_kernel::Vec3;
use apart_pieces::Polytope;
use proptest::prelude::*;

/// The boundary of the hull of `pts` as triangles (fans over its facets; many coplanar
/// triangles and flat edges).
fn hull_mesh(pts: &[Vec3]) -> Option<(Polytope, Vec<Vec3>, Vec<[u32; 3]>)> {
    let hull = Polytope::hull_of_points(pts).ok()?;
    let points = hull.vertices().to_vec();
    let mut tris = Vec::new();
    for f in hull.facets() {
        for i in 1..f.cycle.len() - 1 {
            tris.push([f.cycle[0], f.cycle[i], f.cycle[i + 1]]);
        }
    }
    Some((hull, points, tris))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    #[test]
    fn convex_solid_is_one_piece(
        raw in proptest::collection::vec((-1000i64..1000, -1000i64..1000, -1000i64..1000), 4..14)
    ) {
        let pts: Vec<Vec3> = raw.iter().map(|&(x, y, z)| Vec3::new(x, y, z)).collect();
        let Some((hull, points, tris)) = hull_mesh(&pts) else { return Ok(()) };
        prop_assert!(reflex_edges(&points, &tris).is_empty());
        let d = decompose(&points, &tris, &Options::default()).unwrap();
        prop_assert_eq!(d.pieces.len(), 1);
        prop_assert_eq!(d.pieces[0].volume(), hull.volume());
        prop_assert_eq!(d.pieces[0].vertices().len(), hull.vertices().len());
        verify(&points, &tris, &d.pieces).unwrap();
    }
}

#[test]
fn large_coordinates_near_the_limit() {
    // A thin slanted tetrahedron with coordinates near 2^39.
    let b = 1i64 << 39;
    let pts = vec![
        Vec3::new(-b + 1, -b + 3, -b + 7),
        Vec3::new(b - 5, -b + 2, 11),
        Vec3::new(3, b - 13, -b + 17),
        Vec3::new(-b + 19, 23, b - 29),
    ];
    let (hull, points, tris) = hull_mesh(&pts).unwrap();
    let d = decompose(&points, &tris, &Options::default()).unwrap();
    assert_eq!(d.pieces.len(), 1);
    assert_eq!(d.pieces[0].volume(), hull.volume());
    verify(&points, &tris, &d.pieces).unwrap();
}
