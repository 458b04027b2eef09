//! Tests of the piece-pair arguments against the full sums they replace.

use super::axes::cmp_bound;
use super::boxes::{open_small_box_blocks, ray_meets_box_exact};
use super::contact::face_neighbourhood;
use super::*;
use crate::regions::Part;
use apart_kernel::int::cmp_fractions;
use apart_kernel::Vec3;
use apart_testkit::curved;

proptest::proptest! {
    /// The float-first comparison of box bounds agrees with the exact one, on equal
    /// fractions in other terms, neighbours one unit apart over huge denominators,
    /// and bounds of either sign around zero.
    #[test]
    fn box_bounds_compare_as_their_fractions(
        x in -(1i64 << 62)..(1i64 << 62),
        near in -2i64..=2,
        dx_bits in 0u32..200,
        k in 1i64..1000,
        odd in 0u32..3,
    ) {
        let dx = (Int::ONE << dx_bits as usize) + Int::from(odd);
        let x = Int::from(x);
        // y / dy: x / dx in other terms (times k), moved by `near` units of dy.
        let dy = &dx * Int::from(k);
        let y = &x * Int::from(k) + Int::from(near);
        let f = |n: &Int, d: &Int| apart_kernel::Rational::new(n.clone(), d.clone()).to_f64();
        for (a, da, b, db) in [(&x, &dx, &y, &dy), (&y, &dy, &x, &dx)] {
            proptest::prop_assert_eq!(
                cmp_bound(f(a, da), a, da, f(b, db), b, db),
                cmp_fractions(a, da, b, db)
            );
        }
    }
}

/// A seeded generator of integers in `[0, m)` (testkit's generator).
fn below(seed: u64) -> impl FnMut(i64) -> i64 {
    let mut rng = apart_testkit::solids::Lcg(seed);
    move |m| rng.below(m as u64) as i64
}

/// A random axis-aligned box from `next` (`next(m)` in `[0, m)`): a lower corner in
/// `[-6, 6]`, sides of 1 to 4, over a denominator of 1 to 3.
fn random_cuboid(next: &mut dyn FnMut(i64) -> i64) -> Polytope {
    let den = 1 + next(3);
    let lo = [next(13) - 6, next(13) - 6, next(13) - 6];
    let hi = [
        lo[0] + 1 + next(4),
        lo[1] + 1 + next(4),
        lo[2] + 1 + next(4),
    ];
    Polytope::cuboid(lo, hi).unwrap().with_den(Int::from(den))
}

fn generated(name: &str, parts: &[curved::NamedSoup]) -> Vec<Part> {
    let dir = std::env::temp_dir().join(format!("apart-pairs-{}-{name}", std::process::id()));
    curved::write_off_dir(parts, &dir).unwrap();
    let loaded = apart_assembly::load(&dir, &Default::default()).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert!(loaded.is_valid(), "{:?}", loaded.problems);
    crate::parts_of(&loaded.assembly).unwrap().to_vec()
}

fn normals(p: &SphericalPolygon) -> Vec<[String; 3]> {
    let mut v: Vec<[String; 3]> = p.normals().iter().map(|q| q.to_strings()).collect();
    v.sort();
    v.dedup();
    v
}

/// The `i128` ray–box test agrees with the arbitrary-precision one: random boxes with
/// touching, overlapping and far-apart bounds (degenerate: shared faces, zero
/// direction components), up to the fast path's 2^61 bounds and 2^62 directions.
#[test]
fn small_ray_box_test_agrees_with_the_exact_one() {
    let mut rng = apart_testkit::solids::Lcg(7);
    let scales = [3i64, 1000, 1 << 40, (1 << 61) - 1];
    let mut met = [0usize; 2];
    for round in 0..20_000 {
        let s = scales[round % scales.len()];
        let coord = |r: &mut apart_testkit::solids::Lcg| -> i64 {
            // Few distinct values in each scale: shared faces and touching boxes.
            let k = r.range(-3, 4);
            (k * (s / 3)).clamp(-s, s)
        };
        let mut boxes = Vec::new();
        for _ in 0..2 {
            let (mut lo, mut hi) = ([0i64; 3], [0i64; 3]);
            for k in 0..3 {
                let (u, v) = (coord(&mut rng), coord(&mut rng));
                lo[k] = u.min(v);
                hi[k] = u.max(v).max(lo[k] + 1).min(s);
                lo[k] = lo[k].min(hi[k] - 1);
            }
            boxes.push(Polytope::cuboid(lo, hi).unwrap());
        }
        let xs = 1i64 << rng.below(62);
        let x = Vec3::from_i64([0, 1, 2].map(|_| rng.range(-2, 3) * (xs / 2).max(1)));
        if x.is_zero() {
            continue;
        }
        let (ia, ib) = (PieceInfo::new(&boxes[0]), PieceInfo::new(&boxes[1]));
        assert!(ia.small.is_some() && ib.small.is_some() && x.as_small().is_some());
        let fast = ray_meets_box(&ia, &Int::ONE, &ib, &Int::ONE, &x);
        let exact = ray_meets_box_exact(&ia, &Int::ONE, &ib, &Int::ONE, &x);
        assert_eq!(fast, exact, "{:?} {:?} {x:?}", ia.bounds.min, ib.bounds.max);
        met[fast as usize] += 1;
    }
    assert!(met[0] > 1000 && met[1] > 1000, "{met:?}");
}

/// Every contact cone equals the full sum's projection (same inward normals), and the
/// axes never cull a direction the full polygon holds.
#[test]
fn contact_cones_and_axes_agree_with_full_sums() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut cases: Vec<Vec<Part>> = Vec::new();
    for name in [
        "peg-in-the-hole",
        "dovetail-and-cap",
        "hinge",
        "split-star-5",
    ] {
        let loaded = apart_assembly::load(&dir.join(name), &Default::default()).unwrap();
        cases.push(crate::parts_of(&loaded.assembly).unwrap().to_vec());
    }
    cases.push(generated("plug", &curved::plug_and_socket(20 * 16 - 8)));
    cases.push(generated("pin", &curved::pin_in_hole(12, 12, 0.0)));
    cases.push(generated("nut", &curved::nut_on_bolt(10, 2)));
    // A tessellated cone's tip on a box's edge, on a box's corner and on another
    // tip: the contacts lie on no face's relative interior, so the tip's
    // neighbourhood (the tip and a 120-point ring, not the whole piece) is hulled.
    let cone = |s: i64| {
        let mut pts = vec![Vec3::new(0, 0, 0)];
        for (z, r) in [(100.0, 1000.0), (1000.0, 3000.0)] {
            for k in 0..120 {
                let t = k as f64 * std::f64::consts::TAU / 120.0;
                let (x, y) = ((r * t.cos()).round() as i64, (r * t.sin()).round() as i64);
                pts.push(Vec3::new(x, y, s * z as i64));
            }
        }
        Polytope::hull(&pts).unwrap()
    };
    let tip = cone(1).vertices().iter().position(|v| v.is_zero()).unwrap() as u32;
    let Some(Some(near)) = face_neighbourhood(&cone(1), &[tip]) else {
        panic!("the tip's neighbourhood is a part of the cone")
    };
    assert_eq!(near.vertices().len(), 121);
    let part = |name: &str, p: Polytope| Part::from_pieces(name, vec![p]);
    for hi in [[0, 5000, 0], [0, 0, 0]] {
        let block = Polytope::cuboid([-5000, -5000, -5000], hi).unwrap();
        cases.push(vec![part("cone", cone(1)), part("block", block)]);
    }
    cases.push(vec![part("up", cone(1)), part("down", cone(-1))]);
    let dirs: Vec<Vec3> = (0..27)
        .map(|i| Vec3::new(i % 3 - 1, (i / 3) % 3 - 1, i / 9 - 1))
        .filter(|d| !d.is_zero())
        .chain([Vec3::new(1, 2, 3), Vec3::new(-3, 1, 7)])
        .collect();
    let mut cones = 0;
    for parts in &cases {
        for (i, pi) in parts.iter().enumerate() {
            for pj in &parts[i + 1..] {
                for a in &pi.pieces {
                    for b in &pj.pieces {
                        let (ia, ib) = (PieceInfo::new(a), PieceInfo::new(b));
                        let ax = axes(a, &ia, b, &ib);
                        let PairPolygon::Polygon(full, contact) =
                            full_polygon(a, &ia, b, &ib).unwrap()
                        else {
                            panic!("overlap")
                        };
                        for d in &dirs {
                            if !ray_meets_box(&ia, a.den(), &ib, b.den(), d) {
                                assert!(!full.contains_closed(d));
                            }
                            match classify(&ax, d) {
                                Sep::Outside => assert!(!full.contains_closed(d)),
                                Sep::Free => assert!(!full.contains_open(d)),
                                Sep::Unknown => {}
                            }
                        }
                        assert_eq!(
                            first_touching_axis(a, &ia, b, &ib).as_ref(),
                            touching_normal(&ax)
                        );
                        let Some(n) = touching_normal(&ax) else {
                            continue;
                        };
                        match contact_polygon(a, &ia, b, &ib, n) {
                            Some(Ok(PairPolygon::Polygon(p, true))) => {
                                assert!(contact);
                                assert_eq!(normals(&p), normals(&full));
                                cones += 1;
                            }
                            None => assert!(!contact),
                            other => panic!("{other:?}"),
                        }
                    }
                }
            }
        }
    }
    assert!(cones > 50, "{cones}");
}

/// For boxes the sum is the box of [`ray_meets_box`], so the test is exact: it holds
/// exactly when the closed projection holds the direction (random boxes with
/// denominators, touching and apart, and directions with zero components).
#[test]
fn the_ray_meets_the_box_exactly_when_the_projection_holds_the_direction() {
    let mut next = below(5);
    let mut seen = [0usize; 2];
    for _ in 0..400 {
        let (a, b) = (random_cuboid(&mut next), random_cuboid(&mut next));
        let (ia, ib) = (PieceInfo::new(&a), PieceInfo::new(&b));
        let Ok(PairPolygon::Polygon(full, _)) = full_polygon(&a, &ia, &b, &ib) else {
            continue; // interiors overlap: every direction is blocked
        };
        for _ in 0..12 {
            let d = Vec3::new(next(5) - 2, next(5) - 2, next(5) - 2);
            if d.is_zero() {
                continue;
            }
            let meets = ray_meets_box(&ia, a.den(), &ib, b.den(), &d);
            assert_eq!(meets, full.contains_closed(&d), "{a:?} {b:?} {d:?}");
            seen[usize::from(meets)] += 1;
        }
    }
    assert!(seen[0] > 500 && seen[1] > 200, "{seen:?}");
}

/// For boxes the open box of differences decides blocking exactly: the open ray meets
/// its interior exactly when the open projection holds the direction, and the
/// interior holds the origin exactly when the pieces overlap (random boxes with
/// denominators, touching, apart and overlapping, directions with zero components).
#[test]
fn the_open_box_decides_blocking_for_boxes() {
    let mut next = below(11);
    let mut seen = [0usize; 4];
    for _ in 0..400 {
        let (a, b) = (random_cuboid(&mut next), random_cuboid(&mut next));
        assert!(is_axis_box(&a) && is_axis_box(&b));
        let (ia, ib) = (PieceInfo::new(&a), PieceInfo::new(&b));
        let full = full_polygon(&a, &ia, &b, &ib).unwrap();
        for _ in 0..12 {
            let d = Vec3::new(next(5) - 2, next(5) - 2, next(5) - 2);
            if d.is_zero() {
                continue;
            }
            let got = open_box_blocks(&ia, a.den(), &ib, b.den(), &d);
            if let (Some(c), PairPolygon::Polygon(p, _)) =
                (box_graze_normal(&ia, a.den(), &ib, b.den(), &d), &full)
            {
                // Grazing: on the polygon's boundary, and every perturbed direction
                // inside it on the positive side of c.
                assert!(p.contains_closed(&d) && !p.contains_open(&d));
                assert_eq!(c.dot(&d), Int::ZERO);
                for y in (0..27).map(|i| Vec3::new(i % 3 - 1, (i / 3) % 3 - 1, i / 9 - 1)) {
                    if p.contains_open_perturbed(&d, &y) {
                        assert!(c.dot(&y) > Int::ZERO, "{a:?} {b:?} {d:?} {y:?} {c:?}");
                    }
                }
                seen[3] += 1;
            }
            let ax = axes(&a, &ia, &b, &ib);
            assert_eq!(
                classify_boxes(&a, &ia, &b, &ib, &d),
                (classify(&ax, &d), ax.iter().any(|x| !x.strict))
            );
            if let (Some(sa), Some(sb), Some(x)) = (&ia.small, &ib.small, d.as_small()) {
                // The i128 path (taken above) and the exact one agree.
                let (big_a, big_b) = (
                    PieceInfo {
                        small: None,
                        ..PieceInfo::new(&a)
                    },
                    PieceInfo {
                        small: None,
                        ..PieceInfo::new(&b)
                    },
                );
                assert_eq!(
                    open_small_box_blocks(sa, sb, x),
                    open_box_blocks(&big_a, a.den(), &big_b, b.den(), &d)
                );
            }
            match &full {
                PairPolygon::Polygon(p, _) => {
                    assert_eq!(got, Some(p.contains_open(&d)), "{a:?} {b:?} {d:?}");
                    seen[usize::from(p.contains_open(&d))] += 1;
                }
                PairPolygon::Overlap => {
                    assert_eq!(got, None);
                    seen[2] += 1;
                }
            }
        }
    }
    assert!(
        seen[..3].iter().all(|&k| k > 50) && seen[3] > 20,
        "{seen:?}"
    );
}
