//! Property tests of `Polytope::shrunk_exact` and `Polytope::shrunk` against their definitions: the intersection of the
//! facet half-spaces moved inward by `eps · ⌈256 |n|⌉ / 256`. Checked exactly on random
//! hulls, independently of the clipping code: every vertex of the result satisfies every
//! moved half-space, lies on at least three moved planes whose normals span space, and
//! lies at least `eps` inside every original facet plane.

use apart_kernel::int::Int;
use apart_kernel::{Rational, Vec3};
use apart_pieces::Polytope;
use proptest::prelude::*;

/// `⌈256 |n|⌉` by bisection on `k² >= 65536 |n|²` (independent of the library's Newton).
fn bound256(n: &Vec3) -> Int {
    let target = n.dot(n) * Int::from(65536);
    let (mut lo, mut hi) = (Int::ZERO, &target + Int::ONE); // lo² < target <= hi²
    while &hi - &lo > Int::ONE {
        let mid: Int = (&lo + &hi) / Int::from(2);
        if &mid * &mid >= target {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn shrunk_is_the_moved_half_space_intersection(
        pts in prop::collection::vec((-40i64..40, -40i64..40, -40i64..40), 5..14),
        num in 1i64..6,
        den in 1i64..4,
    ) {
        let pts: Vec<Vec3> = pts.into_iter().map(|(x, y, z)| Vec3::new(x, y, z)).collect();
        let Ok(p) = Polytope::hull_of_points(&pts) else { return Ok(()) };
        let (num, den) = (Int::from(num), Int::from(den));
        let moved: Vec<(Vec3, Rational)> = p
            .facets()
            .iter()
            .map(|f| {
                let shift = Rational::new(&num * bound256(&f.normal), &den * Int::from(256));
                (f.normal.clone(), &Rational::from_int(f.offset.clone()) - &shift)
            })
            .collect();
        match p.shrunk_exact(&num, &den) {
            // Nothing left is allowed for thin hulls; the unit tests check known cases.
            None => {}
            Some(s) => {
                prop_assert!(s.volume() < p.volume());
                for v in s.vertices() {
                    let x = |k: usize| Rational::new(v.get(k), s.den().clone());
                    let dot = |n: &Vec3| &(&(&Rational::from_int(n.get(0)) * &x(0))
                        + &(&Rational::from_int(n.get(1)) * &x(1)))
                        + &(&Rational::from_int(n.get(2)) * &x(2));
                    let mut tight = Vec::new();
                    for (nrm, off) in &moved {
                        let d = dot(nrm);
                        prop_assert!(d <= *off, "a vertex violates a moved plane");
                        if d == *off { tight.push(nrm.clone()); }
                    }
                    // At least three tight planes with independent normals.
                    let mut spans = false;
                    'outer: for a in 0..tight.len() {
                        for b in a + 1..tight.len() {
                            for c in b + 1..tight.len() {
                                if tight[a].dot(&tight[b].cross(&tight[c])) != Int::ZERO {
                                    spans = true;
                                    break 'outer;
                                }
                            }
                        }
                    }
                    prop_assert!(spans, "a vertex is not a vertex of the moved half-spaces");
                    // At least eps inside every original facet: (c - n·x)^2 >= eps^2 |n|^2.
                    for f in p.facets() {
                        let gap = &Rational::from_int(f.offset.clone()) - &dot(&f.normal);
                        let eps = Rational::new(num.clone(), den.clone());
                        let lhs = &gap * &gap;
                        let rhs = &(&eps * &eps) * &Rational::from_int(f.normal.dot(&f.normal));
                        prop_assert!(gap > Rational::zero() && lhs >= rhs);
                    }
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// Whatever way `shrunk` takes (an exact or a scaled cut, then back on the grid),
    /// every vertex of the result lies at least eps inside every facet plane of the
    /// piece: the piece made at least eps smaller, the guarantee a tolerance states.
    #[test]
    fn shrunk_keeps_every_vertex_eps_inside(
        pts in prop::collection::vec((-400i64..400, -400i64..400, -4000i64..4000), 5..40),
        num in 1i64..6,
        den in 1i64..4,
    ) {
        let pts: Vec<Vec3> = pts.into_iter().map(|(x, y, z)| Vec3::new(x, y, z)).collect();
        let Ok(p) = Polytope::hull_of_points(&pts) else { return Ok(()) };
        let (num, den) = (Int::from(num), Int::from(den));
        for s in [p.shrunk(&num, &den), p.shrunk_by_scaling(&num, &den)].into_iter().flatten() {
            prop_assert!(s.volume() < p.volume());
            let eps = Rational::new(num.clone(), den.clone());
            for v in s.vertices() {
                for f in p.facets() {
                    let x = |k: usize| Rational::new(v.get(k), s.den().clone());
                    let dot = &(&(&Rational::from_int(f.normal.get(0)) * &x(0))
                        + &(&Rational::from_int(f.normal.get(1)) * &x(1)))
                        + &(&Rational::from_int(f.normal.get(2)) * &x(2));
                    let gap = &Rational::from_int(f.offset.clone()) - &dot;
                    let rhs = &(&eps * &eps) * &Rational::from_int(f.normal.dot(&f.normal));
                    prop_assert!(gap > Rational::zero() && &gap * &gap >= rhs);
                }
            }
        }
    }
}

/// The vertices of a polytope, each as its true coordinates times `k` (to compare two
/// polytopes' vertex sets exactly: each scaled by the other's denominator), sorted.
fn vertex_set(p: &Polytope, k: &Int) -> Vec<[Int; 3]> {
    let mut v: Vec<[Int; 3]> = p.vertices().iter().map(|v| v.scale(k).to_ints()).collect();
    v.sort();
    v
}

/// Whether two polytopes have the same vertices (exactly, whatever their denominators).
fn same_vertices(s: &Polytope, t: &Polytope) -> bool {
    vertex_set(s, t.den()) == vertex_set(t, s.den())
}

/// And not much smaller: `shrunk` (whose cut by eps + 1 step may be computed in
/// floating point) holds the exact cut by eps + 2 steps, whose every vertex lies in
/// it (a vertex moved by less than a step leaves the eroded cut inside the hull).
/// Pieces of up to 32 facets, where the cut is not a scaling.
fn holds_the_exact_cut_two_steps_deeper(
    pts: &[Vec3],
    num: i64,
    den: i64,
) -> Result<(), TestCaseError> {
    let Ok(p) = Polytope::hull_of_points(pts) else {
        return Ok(());
    };
    if p.facets().len() > 32 {
        return Ok(());
    }
    let (num, den) = (Int::from(num), Int::from(den));
    let deeper = &num + Int::from(2) * &den;
    let Some(inner) = p.shrunk_exact(&deeper, &den) else {
        return Ok(());
    };
    let s = p.shrunk(&num, &den);
    prop_assert!(
        s.is_some(),
        "the deeper cut is not empty, so neither is the shrunk piece"
    );
    let s = s.unwrap();
    // The same solid stored with a denominator of 96 bits (as decomposed pieces are),
    // and listed in another order, shrinks to the same piece.
    let k = Int::from(3).pow(60);
    let scaled: Vec<Vec3> = p.vertices().iter().rev().map(|v| v.scale(&k)).collect();
    let q = Polytope::hull_of_points(&scaled).unwrap().with_den(k);
    let t = q.shrunk(&num, &den);
    prop_assert!(
        t.as_ref().is_some_and(|t| same_vertices(t, &s)),
        "{t:?} vs {s:?}"
    );
    for v in inner.vertices() {
        for f in s.facets() {
            // n · (v / den_inner) <= offset / den_s.
            prop_assert!(
                f.normal.dot(v) * s.den() <= &f.offset * inner.den(),
                "a vertex of the cut two steps deeper lies outside the shrunk piece"
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn shrunk_holds_the_exact_cut_two_steps_deeper(
        pts in prop::collection::vec((-400i64..400, -400i64..400, -4000i64..4000), 5..12),
        num in 1i64..6,
        den in 1i64..4,
    ) {
        let pts: Vec<Vec3> = pts.into_iter().map(|(x, y, z)| Vec3::new(x, y, z)).collect();
        holds_the_exact_cut_two_steps_deeper(&pts, num, den)?;
    }
}

/// A case that fails when the float cut runs in the piece's stored order on coordinates
/// rounded twice: the 96-bit copy's shrink then has a vertex two steps away.
#[test]
fn the_96_bit_copy_shrinks_to_the_same_piece_when_rounded_twice() {
    let pts = [
        (-367, -6, -1335),
        (-8, -297, -3819),
        (123, 66, -2924),
        (-203, 97, -1564),
        (-3, 0, 0),
    ]
    .map(|(x, y, z)| Vec3::new(x, y, z));
    holds_the_exact_cut_two_steps_deeper(&pts, 3, 1).unwrap();
}

/// Cases where near-parallel facets made the float cut's vertex-plane incidences
/// inconsistent (before each face was clipped on its own): the cut came out empty, or
/// lost a vertex of the exact cut two steps deeper.
#[test]
fn near_parallel_facets_lose_nothing_of_the_cut() {
    for pts in [
        [
            (-54, 265, -3964),
            (-162, -330, 2974),
            (21, 119, -2673),
            (29, -372, -3016),
            (33, 0, 0),
            (-149, 194, -457),
        ],
        [
            (-120, -353, 3329),
            (0, 0, 0),
            (0, 0, 1),
            (-342, -321, -1091),
            (183, -363, 616),
            (-35, -331, -3638),
        ],
    ] {
        let pts = pts.map(|(x, y, z)| Vec3::new(x, y, z));
        holds_the_exact_cut_two_steps_deeper(&pts, 1, 1).unwrap();
    }
}
