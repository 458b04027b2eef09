//! The Minkowski sum (polygon merges of parallel faces, float-filtered extreme faces,
//! summands of different denominators summed unscaled) against the old exact path (the
//! 2-D hull of all pairwise vertex sums on summands brought to a common denominator):
//! identical polytopes, vertex for vertex and facet for facet, on degenerate inputs
//! (tiny grids: shared facet normals, parallel edges, coplanar faces, touching
//! summands), and the central projections of the differences against the old
//! projection, on the same shapes under big integer linear maps and translations
//! (coordinates of hundreds of bits), and with different big denominators. The
//! projection made from the facets facing the origin alone ([`project_apart`]) against
//! the projection of the whole sum, on the same shapes and on many-sided prisms near
//! small pieces.

#[path = "support/reference.rs"]
mod reference;

use apart_kernel::{Int, Vec3};
use apart_minkowski::{
    minkowski_difference, minkowski_sum, project, project_apart, Projection, Summand,
};
use apart_pieces::Polytope;
use apart_sphere::SphericalPolygon;
use proptest::prelude::*;
use reference::{identical, reference_project, reference_sum, same_projection};

/// Hull of small grid points (degenerate on purpose); `None` when flat.
fn grid_hull(pts: &[[i64; 3]]) -> Option<Polytope> {
    let v: Vec<Vec3> = pts.iter().map(|&c| Vec3::from(c)).collect();
    Polytope::hull_of_points(&v).ok()
}

/// A big integer from a seed: about `bits` bits, sign from the seed.
fn big(seed: u64, bits: u32) -> Int {
    let mut x = Int::from(seed | 1);
    let mut s = seed;
    while apart_kernel::int::bit_len(&x) < bits {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        x = (x << 61usize) + Int::from(s >> 3);
    }
    if seed & 2 == 0 {
        -x
    } else {
        x
    }
}

/// The points mapped by `m` (integer, invertible) and translated by `t`.
fn mapped(pts: &[[i64; 3]], m: &[[i64; 3]; 3], t: &[Int; 3]) -> Option<Polytope> {
    let v: Vec<Vec3> = pts
        .iter()
        .map(|c| {
            let r = |k: usize| {
                Int::from(m[k][0]) * Int::from(c[0])
                    + Int::from(m[k][1]) * Int::from(c[1])
                    + Int::from(m[k][2]) * Int::from(c[2])
                    + &t[k]
            };
            Vec3::from_ints([r(0), r(1), r(2)])
        })
        .collect();
    Polytope::hull_of_points(&v).ok()
}

/// The points `pts[k] / dens[k % dens.len()]` (each vertex with its own denominator, as
/// where cut planes meet), stored over the least common multiple of those; `None` when
/// flat.
fn own_denominators(pts: &[[i64; 3]], dens: &[u64]) -> Option<Polytope> {
    let d = |k: usize| Int::from(dens[k % dens.len()]);
    let common = (0..pts.len()).fold(Int::ONE, |l, k| apart_kernel::int::lcm(&l, &d(k)));
    let v: Vec<Vec3> = pts
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let f = &common / d(k);
            Vec3::from_ints(c.map(|x| Int::from(x) * &f))
        })
        .collect();
    Polytope::hull_of_points(&v)
        .ok()
        .map(|p| p.with_den(common))
}

fn det(m: &[[i64; 3]; 3]) -> i128 {
    let m = m.map(|r| r.map(|x| x as i128));
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

fn points() -> impl Strategy<Value = Vec<[i64; 3]>> {
    prop_oneof![
        // Boxes: every normal axis-aligned, shared with any other box.
        (
            prop::array::uniform3(-2i64..=1),
            prop::array::uniform3(1i64..=3)
        )
            .prop_map(|(lo, s)| {
                (0..8)
                    .map(|i| {
                        [
                            lo[0] + (i & 1) * s[0],
                            lo[1] + (i >> 1 & 1) * s[1],
                            lo[2] + (i >> 2) * s[2],
                        ]
                    })
                    .collect()
            }),
        // Random points on a tiny grid: coplanar points, parallel faces and edges.
        prop::collection::vec(prop::array::uniform3(-2i64..=2), 4..14),
        // Prisms over a random polygon in z: vertical facets, parallel top and bottom.
        (
            prop::collection::vec(prop::array::uniform2(-3i64..=3), 3..8),
            1i64..=3
        )
            .prop_map(|(xy, h)| xy
                .iter()
                .flat_map(|p| [[p[0], p[1], 0], [p[0], p[1], h]])
                .collect()),
        // Wider random points.
        prop::collection::vec(prop::array::uniform3(-40i64..=40), 4..30),
    ]
}

/// The same boundary, up to where its cycle starts.
fn same_cycle(a: &SphericalPolygon, b: &SphericalPolygon) -> bool {
    let (x, y) = (a.boundary(), b.boundary());
    x.len() == y.len()
        && (x.is_empty()
            || (0..y.len()).any(|k| (0..x.len()).all(|t| x[t] == y[(t + k) % y.len()])))
}

/// `project_apart` against the projection of the whole difference `p ⊕ (−q)`: `None`
/// exactly when no facet has the origin strictly outside, else the same polygon (or
/// both fail).
fn check_apart(p: &Polytope, q: &Polytope) -> Result<(), TestCaseError> {
    let whole = minkowski_difference(p, q).expect("difference");
    let apart = project_apart(&Summand::new(p.clone()), &Summand::new(q.reflected()));
    let outside = whole.facets().iter().any(|f| f.offset < Int::ZERO);
    match (apart, project(&whole)) {
        (None, _) => prop_assert!(!outside, "{:?} ⊖ {:?}: the origin is outside", p, q),
        (Some(Ok(a)), Ok(Projection::Polygon(b))) => {
            prop_assert!(outside);
            prop_assert!(
                same_cycle(&a, &b),
                "{:?} ⊖ {:?}: {:?} against {:?}",
                p,
                q,
                a,
                b
            );
        }
        (Some(a), b) => prop_assert!(false, "{:?} ⊖ {:?}: {:?} against {:?}", p, q, a, b),
    }
    Ok(())
}

fn check(p: &Polytope, q: &Polytope) -> Result<(), TestCaseError> {
    check_apart(p, q)?;
    let fast = minkowski_sum(p, q).expect("sum");
    let old = reference_sum(p, q).expect("reference");
    prop_assert!(identical(&fast, &old), "{:?} ⊕ {:?}", p, q);
    let fast = minkowski_difference(p, q).expect("difference");
    let old = reference_sum(p, &q.reflected()).expect("reference");
    prop_assert!(identical(&fast, &old), "{:?} ⊖ {:?}", p, q);
    // The central projection (silhouette, contact hemisphere, lune or cone).
    match (project(&fast), reference_project(&fast)) {
        (Ok(a), Ok(b)) => prop_assert!(same_projection(&a, &b), "projection of {:?} ⊖ {:?}", p, q),
        (a, b) => prop_assert_eq!(a.is_ok(), b.is_ok()),
    }
    Ok(())
}

/// A prism over a regular `n`-gon of radius `r` (rounded to the grid) from `z0` to
/// `z1`, centred at `(cx, cy)`: a tessellated cylinder.
fn cylinder(n: usize, r: f64, (cx, cy): (i64, i64), (z0, z1): (i64, i64)) -> Option<Polytope> {
    let mut pts = Vec::new();
    for k in 0..n {
        let t = k as f64 * std::f64::consts::TAU / n as f64;
        let (x, y) = ((r * t.cos()).round() as i64, (r * t.sin()).round() as i64);
        pts.push(Vec3::new(cx + x, cy + y, z0));
        pts.push(Vec3::new(cx + x, cy + y, z1));
    }
    Polytope::hull(&pts).ok()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// A many-sided cylinder against a small piece beside it, above it, touching it
    /// or a step away: most of the sum's facets and edges are dropped by the float
    /// filters, and the facets facing the origin alone make the polygon.
    #[test]
    fn many_sided_prism_near_a_small_piece(
        n in 3usize..400,
        a in points(),
        at in prop::array::uniform3(-3i64..=3),
        side in 0usize..4,
        scale in prop::sample::select(vec![1i64, 7, 1 << 20]),
    ) {
        let r = 1000.0;
        let Some(c) = cylinder(n, r, (0, 0), (0, 2000)) else { return Ok(()) };
        // Place the small piece just outside (or on) the cylinder's side, top or bottom.
        let base: [i64; 3] = match side {
            0 => [1003, 0, 1000],
            1 => [0, -1003, 500],
            2 => [0, 0, 2002],
            _ => [700, 700, -2],
        };
        let moved: Vec<[i64; 3]> = a
            .iter()
            .map(|v| [0, 1, 2].map(|k| base[k] + at[k] + v[k]))
            .collect();
        let Some(b) = grid_hull(&moved) else { return Ok(()) };
        let (c, b) = (c.rescaled(&Int::from(scale)), b.rescaled(&Int::from(scale)));
        check_apart(&b, &c)?;
        check_apart(&c, &b)?;
        check_apart(&b.clone().with_den(Int::from(scale + 2)), &c)?;
    }

    #[test]
    fn small_grid_pieces(a in points(), b in points()) {
        let (Some(p), Some(q)) = (grid_hull(&a), grid_hull(&b)) else { return Ok(()) };
        check(&p, &q)?;
        check(&p, &p)?;
    }

    /// The same shapes under one big linear map (parallelism, shared normals and
    /// contacts survive), translated by big vectors, with big different denominators.
    #[test]
    fn big_coordinates_and_denominators(
        a in points(),
        b in points(),
        m in prop::array::uniform3(prop::array::uniform3(-(1i64 << 40)..(1i64 << 40))),
        seeds in prop::array::uniform4(any::<u64>()),
        bits in prop::array::uniform3(60u32..400),
        dens in prop::array::uniform2(1u64..1000),
    ) {
        prop_assume!(det(&m) != 0);
        let ta = [big(seeds[0], bits[0]), big(seeds[1], bits[1]), big(seeds[2], bits[2])];
        let tb = [big(seeds[3], bits[0]), Int::from(seeds[1] >> 20), -big(seeds[2], bits[2])];
        let (Some(p), Some(q)) = (mapped(&a, &m, &ta), mapped(&b, &m, &tb)) else { return Ok(()) };
        check(&p, &q)?;
        // Declared denominators: a shared big one, and two different ones.
        let d = big(seeds[0] ^ seeds[3], bits[1]);
        let d = if d < Int::ZERO { -d } else { d };
        check(&p.clone().with_den(d.clone()), &q.clone().with_den(d.clone()))?;
        let dq = &d * Int::from(dens[0]) + Int::from(dens[1]);
        check(&p.clone().with_den(d), &q.clone().with_den(dq))?;
        // Rescaled (the same polytope stored with bigger integers).
        check(&p.rescaled(&Int::from(dens[0])), &q)?;
    }

    /// Touching and coincident: a piece against translated copies of itself and of
    /// a box around it, under a big map.
    #[test]
    fn coincident_and_touching(
        a in points(),
        m in prop::array::uniform3(prop::array::uniform3(-(1i64 << 30)..(1i64 << 30))),
        shift in prop::array::uniform3(-3i64..=3),
    ) {
        prop_assume!(det(&m) != 0);
        let zero = [Int::ZERO, Int::ZERO, Int::ZERO];
        let Some(p) = mapped(&a, &m, &zero) else { return Ok(()) };
        let moved: Vec<[i64; 3]> =
            a.iter().map(|c| [c[0] + shift[0], c[1] + shift[1], c[2] + shift[2]]).collect();
        let Some(q) = mapped(&moved, &m, &zero) else { return Ok(()) };
        check(&p, &q)?;
        let boxed: Vec<[i64; 3]> = (0..8)
            .map(|i| [(i & 1) * 4 - 2, (i >> 1 & 1) * 4 - 2, (i >> 2) * 4 - 2])
            .collect();
        let b = mapped(&boxed, &m, &zero).expect("a box under an invertible map");
        check(&p, &b)?;
        check(&b, &p)?;
    }
    /// Vertices with their own denominators (small primes, and big ones as long as
    /// a cut plane's), so that the common denominator is far longer than any vertex's:
    /// the projection from lowest terms per vertex is the whole difference's.
    #[test]
    fn vertices_with_their_own_denominators(
        a in points(),
        b in points(),
        da in prop::collection::vec(prop::sample::select(vec![1u64, 2, 3, 5, 7, 11, 13, (1 << 61) - 1, 1_000_000_007]), 1..6),
        db in prop::collection::vec(prop::sample::select(vec![1u64, 2, 3, 5, 7, 11, 13, (1 << 61) - 1, 1_000_000_007]), 1..6),
    ) {
        let (Some(p), Some(q)) = (own_denominators(&a, &da), own_denominators(&b, &db)) else {
            return Ok(());
        };
        check(&p, &q)?;
        check(&q, &p)?;
    }
}
