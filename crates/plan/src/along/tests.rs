//! Tests of the direction queries' exact filters and bounds.

use super::broad::{line_meets_exact, line_meets_int_box};
use super::clearance_search::{axes_bound, box_angle};
use super::DirectionQuery;
use crate::pairs::ray_meets_int_box;
use crate::regions::Part;
use apart_kernel::fvec;
use apart_kernel::Vec3;
use apart_pieces::Polytope;
use rustc_hash::FxHashMap;

/// A seeded generator of integers in `[-m, m]` (testkit's generator).
fn rng(seed: u64) -> impl FnMut(i64) -> i64 {
    let mut g = apart_testkit::solids::Lcg(seed);
    move |m| g.range(-m, m + 1)
}

/// The angle from unit `u` to the direction of `y` (radians).
fn angle(u: [f64; 3], y: [f64; 3]) -> f64 {
    fvec::norm(fvec::cross(u, y)).atan2(fvec::dot(u, y))
}

/// Points of the box `[lo, hi]` on a 7 × 7 × 7 grid (corners, edges and faces
/// included).
fn samples(lo: [i64; 3], hi: [i64; 3]) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    for i in 0..7 {
        for j in 0..7 {
            for k in 0..7 {
                let t = [i, j, k].map(|s| s as f64 / 6.0);
                out.push(std::array::from_fn(|c| {
                    lo[c] as f64 + t[c] * (hi[c] - lo[c]) as f64
                }));
            }
        }
    }
    out
}

/// The touching normals' counts of [`DirectionQuery::candidates_in`] (pairs of parts
/// from the hierarchy of their boxes, counted in parallel) are those of the loop over
/// every pair of parts and every piece pair the trees' walk gives, with each pair's
/// full axes: on lattices on a unit grid (where the piece boxes' widening reaches
/// several neighbours) and random boxes, for everything and for random subsets.
#[test]
fn touching_counts_are_those_of_every_pair() {
    use apart_testkit::solids::Lcg;
    let cube = |o: [i64; 3], s: i64| Polytope::cuboid(o, o.map(|c| c + s)).unwrap();
    let lattice = |n: i64, step: i64| -> Vec<Part> {
        let mut out = Vec::new();
        for x in 0..n {
            for y in 0..n {
                for z in 0..n {
                    let o = [x * step, y * step, z * step];
                    out.push(Part::from_pieces(format!("c{x}{y}{z}"), vec![cube(o, 1)]));
                }
            }
        }
        out
    };
    let boxes: Vec<Part> = apart_testkit::solids::random_boxes(60, 15, 3)
        .into_iter()
        .enumerate()
        .map(|(i, b)| {
            let pieces = b
                .into_iter()
                .map(|(lo, hi)| Polytope::cuboid(lo, hi).unwrap());
            Part::from_pieces(format!("p{i}"), pieces.collect())
        })
        .collect();
    let mut g = Lcg(3);
    let mut met = 0;
    for parts in [lattice(4, 1), lattice(3, 2), boxes] {
        let q = DirectionQuery::new(&parts).unwrap();
        let all: Vec<usize> = (0..parts.len()).collect();
        let mut subs = vec![all];
        for _ in 0..3 {
            subs.push((0..parts.len()).filter(|_| g.below(2) == 1).collect());
        }
        for sub in subs {
            let mut want: FxHashMap<Vec3, usize> = FxHashMap::default();
            for (li, &i) in sub.iter().enumerate() {
                for &j in &sub[li + 1..] {
                    let p = q.pair(i, j);
                    for k in q.tree_pairs(i, j, &|sum| sum.contains(&[0; 3])) {
                        if let Some(n) = crate::pairs::touching_normal(q.axes(p, k)) {
                            *want.entry(n.primitive()).or_default() += 1;
                        }
                    }
                }
            }
            met += want.len();
            // A fresh query (nothing cached: the coordinate axes alone where they
            // answer), and the one whose caches the loop filled.
            let fresh = DirectionQuery::new(&parts).unwrap();
            assert_eq!(fresh.touching_counts(&sub), want);
            assert_eq!(q.touching_counts(&sub), want);
        }
    }
    assert!(met > 10, "{met}");
}

/// The line test's float filter never decides wrongly (boxes with faces through the
/// origin, touching the line at a point, coordinates near the 2^62 bound), and the
/// line meets every box that a ray along `x` or `−x` meets.
#[test]
fn the_line_test_is_exact() {
    let mut r = rng(5);
    let scales = [1i64, 3, 1 << 20, 1 << 59];
    let mut met = [0usize; 2];
    for round in 0..20_000 {
        let s = scales[round % 4];
        let c = |r: &mut dyn FnMut(i64) -> i64| r(4) * s;
        let lo = [c(&mut r), c(&mut r), c(&mut r)];
        let hi: [i64; 3] = std::array::from_fn(|k| lo[k] + r(4).abs() * s);
        let x = [r(3), r(3), r(3)];
        if x == [0; 3] {
            continue;
        }
        let got = line_meets_int_box(lo, hi, &x);
        let (lo, hi) = (lo.map(i128::from), hi.map(i128::from));
        assert_eq!(got, line_meets_exact(lo, hi, &x), "{lo:?} {hi:?} {x:?}");
        let nx = x.map(|c| -c);
        if ray_meets_int_box(lo, hi, &x) || ray_meets_int_box(lo, hi, &nx) {
            assert!(got);
        }
        met[usize::from(got)] += 1;
    }
    assert!(met[0] > 1000 && met[1] > 1000, "{met:?}");
}

#[test]
fn the_box_bound_is_below_every_point_of_the_box() {
    let mut r = rng(11);
    for _ in 0..2000 {
        let lo = [r(60), r(60), r(60)];
        let hi = [0, 1, 2].map(|c| lo[c] + r(20).abs() + 1);
        let d = Vec3::new(r(5), r(5), r(5));
        if d.is_zero() {
            continue;
        }
        let u = d.unit_f64();
        let bound = box_angle(lo, hi, &u);
        for y in samples(lo, hi) {
            if y != [0.0; 3] {
                assert!(bound <= angle(u, y) + 1e-12, "{lo:?} {hi:?} {d:?}");
            }
        }
        // Tight at a corner it reaches: some sample is within the grid's spacing.
        let best = samples(lo, hi)
            .into_iter()
            .filter(|y| *y != [0.0; 3])
            .map(|y| angle(u, y))
            .fold(f64::INFINITY, f64::min);
        assert!(bound >= 0.0 && bound <= best + 1e-12);
    }
}

#[test]
fn the_axes_bound_is_below_every_direction_of_the_sum() {
    // Two boxes a gap apart: their sum b ⊕ −a is the box of differences, sampled
    // exactly; the bound from their separating axes and gaps stays below every one.
    let mut r = rng(29);
    let mut positive = 0;
    for _ in 0..1500 {
        let alo = [r(40), r(40), r(40)];
        let ahi = [0, 1, 2].map(|c| alo[c] + r(30).abs() + 1);
        let mut blo = [r(40), r(40), r(40)];
        let axis = (r(1) + 1) as usize;
        blo[axis] = ahi[axis] + r(3).abs(); // b above a along the axis, maybe touching
        let bhi = [0, 1, 2].map(|c| blo[c] + r(30).abs() + 1);
        let (a, b) = (
            Polytope::cuboid(alo, ahi).unwrap(),
            Polytope::cuboid(blo, bhi).unwrap(),
        );
        let (ia, ib) = (
            crate::pairs::PieceInfo::new(&a),
            crate::pairs::PieceInfo::new(&b),
        );
        let ax = crate::pairs::axes(&a, &ia, &b, &ib);
        let d = Vec3::new(r(4), r(4), r(4));
        if d.is_zero() {
            continue;
        }
        let boxes = (&ia.float_bounds, &ib.float_bounds);
        let bound = axes_bound(&ax, (&a, &b), boxes, &d);
        // The same boxes stored with a denominator of 96 bits give the same bound.
        let k = apart_kernel::Int::from(3).pow(60);
        let big = |p: &Polytope| {
            let pts: Vec<Vec3> = p.vertices().iter().map(|v| v.scale(&k)).collect();
            Polytope::hull_of_points(&pts).unwrap().with_den(k.clone())
        };
        let (ab, bb) = (big(&a), big(&b));
        let (iab, ibb) = (
            crate::pairs::PieceInfo::new(&ab),
            crate::pairs::PieceInfo::new(&bb),
        );
        let axb = crate::pairs::axes(&ab, &iab, &bb, &ibb);
        let boxes = (&iab.float_bounds, &ibb.float_bounds);
        let again = axes_bound(&axb, (&ab, &bb), boxes, &d);
        assert!((again - bound).abs() <= 1e-9, "{again} vs {bound}");
        let u = d.unit_f64();
        let (lo, hi) = (
            std::array::from_fn(|c| blo[c] - ahi[c]),
            std::array::from_fn(|c| bhi[c] - alo[c]),
        );
        for y in samples(lo, hi) {
            if y != [0.0; 3] {
                assert!(
                    bound <= angle(u, y) + 1e-12,
                    "{alo:?} {ahi:?} {blo:?} {bhi:?} {d:?}"
                );
            }
        }
        positive += usize::from(bound > 0.0);
    }
    assert!(
        positive > 100,
        "the bound is rarely informative: {positive}"
    );
}
