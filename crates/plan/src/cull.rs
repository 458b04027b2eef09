//! Hierarchical culling of piece pairs: a group of piece pairs whose projections
//! provably lie inside a union already found adds nothing to a pair region, so its
//! Minkowski sums are never made.
//!
//! Each part's pieces form a tree of boxes (the kernel's [`Bvh`] of median splits over
//! integer bounds widened outward, so every box holds its pieces). For two nodes, `box(B) ⊕ −box(A)` is a box holding every sum
//! `b ⊕ −a` of their pieces, so its open projection holds theirs. When that projection
//! lies in the open union `U` of polygons already kept, every polygon of the group
//! does, and the union, and every blocking answer, stay the same without them.
//!
//! The containment test is exact. No arc and no point of `U`'s simplified map may meet
//! the open projection `P` (a floating-point cap around `P`, widened far beyond
//! rounding, picks the arcs and points worth an exact test): then no boundary point of
//! `U` lies in the connected `P`, so `P` is inside `U` or outside it, and one exact
//! interior point of `P` tested against the polygons of `U` decides which. A polygon
//! too wide for a cap (nearly a hemisphere, as the sums of pieces a small gap apart
//! are) has every arc and point of the map tested. The map's arcs are cut into pieces
//! of at most 90° first, so the float filters and the exact arc test hold for arcs of
//! any length.

use crate::clearance::{chord2, FArc};
use apart_kernel::fvec::dot;
use apart_kernel::int::{cmp_fractions, sign_of};
use apart_kernel::{Aabb, Bvh, Int, Sign, Vec3};
use apart_minkowski::{project, Projection};
use apart_pieces::Polytope;
use apart_sphere::region::RegionMap;
use apart_sphere::{Arc, SphericalPolygon};
use std::cmp::Ordering;

/// Pieces per leaf of a part's box tree ([`piece_tree`]): one, so that every piece pair
/// left after the groups gets the box test of its own sum before it is summed (on the
/// 20k-triangle nut and washer that leaves 2,299 sums of 20,002).
const LEAF: usize = 1;

/// Integer bounds holding a piece: its box ([`Polytope::integer_box`]) widened by 2, so
/// that every box has volume. `None` when a coordinate does not fit.
pub(crate) fn piece_box(p: &Polytope) -> Option<Aabb> {
    p.integer_box().map(|b| Aabb {
        min: b.min.map(|x| x - 2),
        max: b.max.map(|x| x + 2),
    })
}

/// The indices of the (at most) `k` pieces with the largest boxes.
pub(crate) fn largest(pieces: &[Polytope], k: usize) -> Vec<usize> {
    let size = |p: &Polytope| {
        piece_box(p).map_or(0i128, |b| {
            (0..3).map(|d| b.max[d] as i128 - b.min[d] as i128).sum()
        })
    };
    let mut order: Vec<(i128, usize)> = pieces
        .iter()
        .enumerate()
        .map(|(n, p)| (size(p), n))
        .collect();
    order.sort_unstable_by(|a, b| b.cmp(a));
    order.into_iter().take(k).map(|(_, n)| n).collect()
}

/// A part's box tree over its pieces ([`piece_box`]): the kernel's hierarchy of median
/// splits along the longest axis, one piece per leaf. `None` when some piece's
/// coordinates are too large for integer boxes (then nothing is culled).
pub(crate) fn piece_tree(pieces: &[Polytope]) -> Option<Bvh> {
    let boxes: Vec<Aabb> = pieces.iter().map(piece_box).collect::<Option<_>>()?;
    Some(Bvh::by_median_splits_with_leaf(boxes, LEAF))
}

/// The box `[lo_b − hi_a, hi_b − lo_a]` holding every `b ⊕ −a` of the pieces under nodes
/// `na` of `moving` and `nb` of `fixed`.
pub(crate) fn sum_box(moving: &Bvh, na: usize, fixed: &Bvh, nb: usize) -> Aabb {
    let (a, b) = (moving.node_box(na), fixed.node_box(nb));
    Aabb {
        min: std::array::from_fn(|k| b.min[k] - a.max[k]),
        max: std::array::from_fn(|k| b.max[k] - a.min[k]),
    }
}

/// The node pairs to visit after `(na, nb)`, in the order of the walk: the larger node
/// (by pieces, `moving`'s on a tie) split, its children in the tree's order (upper half
/// first). Both trees' leaves give none.
pub(crate) fn split_pair(
    moving: &Bvh,
    na: usize,
    fixed: &Bvh,
    nb: usize,
) -> Option<[(usize, usize); 2]> {
    match (moving.children(na), fixed.children(nb)) {
        (None, None) => None,
        (Some([a0, a1]), None) => Some([(a0, nb), (a1, nb)]),
        (None, Some([b0, b1])) => Some([(na, b0), (na, b1)]),
        (Some([a0, a1]), Some([b0, b1])) => {
            Some(if moving.items(na).len() >= fixed.items(nb).len() {
                [(a0, nb), (a1, nb)]
            } else {
                [(na, b0), (na, b1)]
            })
        }
    }
}

/// Every piece pair `(a, b)` (`a` of `moving`, `b` of `fixed`) under a chain of node
/// pairs that `keep` accepts and for which `leaf(a, b)` holds: `keep(sum, pairs)` gets
/// the box of the node pair's sums ([`sum_box`]) and how many piece pairs lie under it,
/// and returns whether to descend. Depth first from the roots in the order of
/// [`split_pair`]; the top of the walk runs in parallel, and the pairs come in the
/// order of the sequential walk.
pub(crate) fn pairs_where(
    moving: &Bvh,
    fixed: &Bvh,
    keep: &(dyn Fn(&Aabb, usize) -> bool + Sync),
    leaf: &(dyn Fn(usize, usize) -> bool + Sync),
) -> Vec<(usize, usize)> {
    /// Depth of node pairs down to which the walk forks.
    const PARALLEL_DEPTH: u32 = 8;
    fn walk(
        t: (&Bvh, &Bvh),
        na: usize,
        nb: usize,
        depth: u32,
        keep: &(dyn Fn(&Aabb, usize) -> bool + Sync),
        leaf: &(dyn Fn(usize, usize) -> bool + Sync),
        out: &mut Vec<(usize, usize)>,
    ) {
        let (moving, fixed) = t;
        let (under_a, under_b) = (moving.items(na), fixed.items(nb));
        if !keep(
            &sum_box(moving, na, fixed, nb),
            under_a.len() * under_b.len(),
        ) {
            return;
        }
        match split_pair(moving, na, fixed, nb) {
            Some([x, y]) if depth < PARALLEL_DEPTH => {
                let (mut first, second) = rayon::join(
                    || {
                        let mut v = Vec::new();
                        walk(t, x.0, x.1, depth + 1, keep, leaf, &mut v);
                        v
                    },
                    || {
                        let mut v = Vec::new();
                        walk(t, y.0, y.1, depth + 1, keep, leaf, &mut v);
                        v
                    },
                );
                first.extend(second);
                out.extend(first);
            }
            Some([x, y]) => {
                walk(t, x.0, x.1, depth + 1, keep, leaf, out);
                walk(t, y.0, y.1, depth + 1, keep, leaf, out);
            }
            None => {
                for &pa in under_a {
                    for &pb in under_b {
                        if leaf(pa as usize, pb as usize) {
                            out.push((pa as usize, pb as usize));
                        }
                    }
                }
            }
        }
    }
    let mut out = Vec::new();
    if let (Some(ra), Some(rb)) = (moving.root(), fixed.root()) {
        walk((moving, fixed), ra, rb, 0, keep, leaf, &mut out);
    }
    out
}

/// The open union of some polygons, ready for containment tests.
pub(crate) struct Cover<'a> {
    polygons: &'a [SphericalPolygon],
    /// The map's arcs cut into pieces of at most 90° ([`Arc::quarters`]), so that their
    /// float distances and the minor-arc parametrisation of the exact test hold.
    arcs: Vec<FArc>,
    points: Vec<[f64; 3]>,
    exact_arcs: Vec<Arc>,
    exact_points: Vec<Vec3>,
    /// Float boxes of the arcs: a polygon skips the groups of arcs beyond one of its sides.
    arc_tree: Bvh<f64>,
}

impl<'a> Cover<'a> {
    /// The union of `polygons`, whose simplified map is `map`.
    pub(crate) fn new(polygons: &'a [SphericalPolygon], map: &RegionMap) -> Cover<'a> {
        let exact_arcs: Vec<Arc> = map.arcs.iter().flat_map(|(a, _)| a.quarters()).collect();
        let arcs = exact_arcs.iter().map(FArc::of).collect();
        // A point where arcs end lies in `p` only if a closed arc does: only the other
        // points (isolated in the map) need a test of their own.
        let ends: rustc_hash::FxHashSet<Vec3> = map
            .arcs
            .iter()
            .flat_map(|(a, _)| [a.start.primitive(), a.end.primitive()])
            .collect();
        let exact_points: Vec<Vec3> = map
            .points
            .iter()
            .map(|(p, _)| p)
            .filter(|p| !ends.contains(&p.primitive()))
            .cloned()
            .collect();
        Cover {
            polygons,
            arcs,
            points: exact_points.iter().map(|p| p.unit_f64()).collect(),
            arc_tree: Bvh::by_median_splits(exact_arcs.iter().map(Arc::bbox).collect()),
            exact_arcs,
            exact_points,
        }
    }

    /// Exactly: true only when the open polygon `p` lies inside the union (false may
    /// also mean "not sure").
    pub(crate) fn contains(&self, p: &SphericalPolygon) -> bool {
        if self.polygons.is_empty() {
            return false;
        }
        if p.normals().len() < 3 {
            return false; // a hemisphere or a lune: not pointed, no interior point below
        }
        let normals: Vec<[f64; 3]> = p.normals().iter().map(|m| m.unit_f64()).collect();
        // Points within the cap's angle of its centre: chord² below 2 − 2 cos r, plus a
        // margin far beyond the rounding of unit vectors. Only those can meet `p`, and
        // they are tested exactly. A polygon too wide for a cap (nearly a hemisphere, as
        // the sums of pieces a small gap apart are) has every arc and point tested, each
        // behind the float filter of its own.
        let cap = crate::regions::cap_of(p).and_then(|cap| {
            cap.cos_radius
                .map(|cos_r| (cap.centre, 2.0 - 2.0 * cos_r + 1e-9))
        });
        let near = |q: &[f64; 3]| match &cap {
            Some((c, reach2)) => chord2(q, c) <= *reach2,
            None => !normals.iter().any(|m| dot(*m, *q) < -1e-9),
        };
        if self
            .points
            .iter()
            .zip(&self.exact_points)
            .any(|(q, x)| near(q) && p.contains_open(x))
        {
            return false;
        }
        // Neighbouring arcs of the map mostly lie outside `p` beyond the same side:
        // that side is tried first.
        let mut hint = 0;
        let met = std::cell::Cell::new(false);
        // Only arcs whose boxes meet the cap's box (padded far beyond the rounding) can
        // come within its reach. A polygon of few sides (a group's box) also skips every
        // group of arcs whose box lies beyond one of its sides; a many-sided one (a sum
        // with a curved piece) tests the float distance to its cap's centre.
        let reach = cap.as_ref().map(|(c, reach2)| {
            let r = reach2.sqrt() + 1e-9;
            Aabb {
                min: c.map(|x| x - r),
                max: c.map(|x| x + r),
            }
        });
        let few = normals.len() <= 8;
        self.arc_tree.query_by(
            |b| {
                !met.get()
                    && reach.as_ref().is_none_or(|r| b.overlaps(r))
                    && !(few && normals.iter().any(|m| box_beyond(m, b)))
            },
            |k| {
                let k = k as usize;
                let near = few
                    || cap
                        .as_ref()
                        .is_none_or(|(c, r2)| self.arcs[k].distance2(c) <= *r2);
                if !met.get()
                    && near
                    && arc_meets_open(&self.exact_arcs[k], &self.arcs[k], &normals, p, &mut hint)
                {
                    met.set(true);
                }
            },
        );
        let met = met.get();
        if met {
            return false;
        }
        // No boundary point of the union lies in `p`: one interior point decides. The
        // sum of a pointed polygon's corners (primitive already, as arc ends are) is
        // interior to it.
        let inner = p.corners().fold(Vec3::new(0, 0, 0), |s, c| s.add(c));
        p.contains_open(&inner) && self.polygons.iter().any(|q| q.contains_open(&inner))
    }
}

/// True when every point of the box `b` lies clearly (beyond rounding) on the negative
/// side of the unit normal `m`.
fn box_beyond(m: &[f64; 3], b: &Aabb<f64>) -> bool {
    let top: f64 = (0..3).map(|k| (m[k] * b.min[k]).max(m[k] * b.max[k])).sum();
    top < -1e-9
}

/// Exactly: does the closed minor arc `arc` meet the open convex polygon `p`? The arc's
/// directions are `(1 − t) s + t e` for `t` in `[0, 1]`; each inward normal `m` of `p`
/// asks `m·s + t (m·e − m·s) > 0`, an open bound on `t`, and the bounds leave an
/// interval exactly when the largest lower one is below the smallest upper one.
///
/// A floating-point filter decides first when it can: on unit vectors every product is
/// within 1e-15 of its true value: a constraint below `−FILTER` at both ends excludes the
/// arc, and when every bound on `t` has a slope above 1e-6 (so it is within 1e-8) an
/// interval or a gap wider than 1e-7 is sure. Arcs on or near a side of `p` are decided
/// exactly.
///
/// `hint` is the index of a side tried first, alone: when the arc lies beyond it the
/// answer is no at once; `hint` becomes the side that excluded the arc, if one did.
fn arc_meets_open(
    arc: &Arc,
    f: &FArc,
    normals: &[[f64; 3]],
    p: &SphericalPolygon,
    hint: &mut usize,
) -> bool {
    const FILTER: f64 = 1e-9;
    let (s, e) = f.ends();
    let beyond = |m: &[f64; 3]| dot(*m, s) < -FILTER && dot(*m, e) < -FILTER;
    if normals.get(*hint).is_some_and(beyond) {
        return false;
    }
    // The sides come in cyclic order: walk from the hint to a side more violated at
    // the arc's ends, and try it (a walk stuck early only leaves the arc to the scan).
    // A many-sided polygon (a sum with a curved piece) mostly excludes an arc there.
    let n = normals.len();
    if n > 8 && *hint < n {
        let g = |k: usize| dot(normals[k], s) + dot(normals[k], e);
        let (mut k, mut gk) = (*hint, g(*hint));
        for step in [1, n - 1] {
            loop {
                let j = (k + step) % n;
                let gj = g(j);
                if gj < gk {
                    (k, gk) = (j, gj);
                } else {
                    break;
                }
            }
        }
        if beyond(&normals[k]) {
            *hint = k;
            return false;
        }
    }

    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    let mut sure = true;
    for (k, m) in normals.iter().enumerate() {
        let (a, b) = (dot(*m, s), dot(*m, e));
        if a < -FILTER && b < -FILTER {
            *hint = k;
            return false;
        }
        // (A slope above 1e-6 keeps the rounding of t = −a / (b − a) below 1e-8.)
        if a.abs() <= FILTER || b.abs() <= FILTER || (b - a).abs() <= 1e-6 {
            sure = false;
            continue;
        }
        let t = -a / (b - a);
        if b > a {
            lo = lo.max(t);
        } else {
            hi = hi.min(t);
        }
    }
    if sure {
        // Every bound is clear of the rounding: a gap wider than it is an interval.
        if hi - lo > 1e-7 {
            return true;
        }
        if lo - hi > 1e-7 {
            return false;
        }
    }
    exact_arc_meets_open(arc, p)
}

/// The exact test of [`arc_meets_open`].
fn exact_arc_meets_open(arc: &Arc, p: &SphericalPolygon) -> bool {
    let (zero, one) = (Int::ZERO, Int::ONE);
    let (mut lo, mut lo_den) = (zero.clone(), one.clone());
    let (mut hi, mut hi_den) = (one.clone(), one);
    for m in p.normals() {
        let a = m.dot(&arc.start);
        let d = m.dot(&arc.end) - &a;
        match sign_of(&d) {
            Sign::Zero => {
                if a <= zero {
                    return false;
                }
            }
            // t > −a / d.
            Sign::Positive => {
                let x = -a;
                if cmp_fractions(&x, &d, &lo, &lo_den) == Ordering::Greater {
                    (lo, lo_den) = (x, d);
                }
            }
            // t < a / (−d).
            Sign::Negative => {
                let d = -d;
                if cmp_fractions(&a, &d, &hi, &hi_den) == Ordering::Less {
                    (hi, hi_den) = (a, d);
                }
            }
        }
    }
    cmp_fractions(&lo, &lo_den, &hi, &hi_den) == Ordering::Less
}

/// The piece pairs `(a, b)` (a piece of the moving part `i`, b of the fixed part `j`)
/// for which `need(a, b)` holds and whose group's bounding projection is not inside
/// `cover`: the pairs whose sums must still be made. Traversal of the two trees from
/// their roots, splitting the larger node.
pub(crate) fn uncovered_pairs(
    moving: &Bvh,
    fixed: &Bvh,
    cover: &Cover,
    need: &(dyn Fn(usize, usize) -> bool + Sync),
) -> Vec<(usize, usize)> {
    pairs_where(
        moving,
        fixed,
        &|sum, _| sum.contains(&[0; 3]) || !box_projection_covered(sum, cover),
        need,
    )
}

/// True when the open projection of the box `b` (not holding the origin) lies in the
/// cover.
pub(crate) fn box_projection_covered(b: &Aabb, cover: &Cover) -> bool {
    let Ok(b) = Polytope::cuboid(b.min, b.max) else {
        return false;
    };
    match project(&b) {
        Ok(Projection::Polygon(p)) => cover.contains(&p),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::regions::union_of;

    fn box_polygon(lo: [i64; 3], hi: [i64; 3]) -> SphericalPolygon {
        match project(&Polytope::cuboid(lo, hi).unwrap()).unwrap() {
            Projection::Polygon(p) => p,
            Projection::Everything => panic!("box holds the origin"),
        }
    }

    #[test]
    fn a_polygon_inside_the_union_is_contained_and_one_crossing_it_is_not() {
        // Two overlapping boxes above: their union holds a small box in the overlap,
        // not one reaching past them, not one across the gap between their outer
        // edges.
        let polys = vec![
            box_polygon([-4, -4, 10], [1, 4, 12]),
            box_polygon([-1, -4, 10], [4, 4, 12]),
        ];
        let map = union_of(&polys);
        let cover = Cover::new(&polys, &map);
        assert!(cover.contains(&box_polygon([-2, -1, 20], [2, 1, 22])));
        assert!(cover.contains(&box_polygon([-3, -3, 11], [3, 3, 11 + 1])));
        assert!(!cover.contains(&box_polygon([-6, -1, 11], [2, 1, 12])));
        assert!(!cover.contains(&box_polygon([5, 5, 1], [6, 6, 2])));
        // Nothing is contained in an empty union.
        let none = Cover::new(&[], &RegionMap::default());
        assert!(!none.contains(&box_polygon([-2, -1, 20], [2, 1, 22])));
    }

    #[test]
    fn nearly_hemispherical_polygons_are_tested_without_a_cap() {
        // Wide flat boxes just above the origin project to polygons reaching within a few
        // degrees of the horizon (too wide for a bounding cap), as sums of pieces a small
        // gap apart do. One inside the union is contained; one reaching past it is not.
        let polys = vec![
            box_polygon([-100, -100, 1], [0, 100, 3]),
            box_polygon([-1, -100, 1], [100, 100, 3]),
        ];
        let map = union_of(&polys);
        let cover = Cover::new(&polys, &map);
        let inside = box_polygon([-60, -60, 2], [60, 60, 3]);
        assert!(crate::regions::cap_of(&inside).is_none_or(|c| c.cos_radius.is_none()));
        assert!(cover.contains(&inside));
        assert!(!cover.contains(&box_polygon([-60, -60, 1], [60, 60, 3]).antipodal()));
        assert!(!cover.contains(&box_polygon([-150, -60, 1], [60, 60, 2])));
        assert!(!cover.contains(&box_polygon([-60, -60, 1], [60, 150, 2])));
    }

    #[test]
    fn the_float_filter_agrees_with_the_exact_arc_test() {
        // Arcs between small integer points (many on the polygons' sides, through their
        // corners, or along their circles) against box projections.
        let mut rng = apart_testkit::solids::Lcg(7);
        let mut next = |n: i64| rng.centred(n);
        let mut tested = [0usize; 2];
        for _ in 0..300 {
            let lo = [next(3), next(3), 4 + next(2)];
            let hi = [
                lo[0] + 1 + next(2).abs(),
                lo[1] + 1 + next(2).abs(),
                lo[2] + 2,
            ];
            let p = box_polygon(lo, hi);
            let normals: Vec<[f64; 3]> = p.normals().iter().map(|m| m.unit_f64()).collect();
            // The hint carries over from arc to arc, as in `Cover::contains`.
            let mut hint = 0;
            for _ in 0..20 {
                let s = Vec3::new(next(6), next(6), next(8));
                let e = Vec3::new(next(6), next(6), next(8));
                let Some(arc) = Arc::between(&s, &e) else {
                    continue;
                };
                let f = FArc::of(&arc);
                let exact = exact_arc_meets_open(&arc, &p);
                tested[usize::from(exact)] += 1;
                // Independent check: exact points along the arc found inside `p`.
                let along = |k: i64| {
                    let sk = Vec3::from_ints([0, 1, 2].map(|c| arc.start.get(c) * (64 - k)));
                    let ek = Vec3::from_ints([0, 1, 2].map(|c| arc.end.get(c) * k));
                    sk.add(&ek)
                };
                if (0..=64).any(|k| p.contains_open(&along(k))) {
                    assert!(exact, "{arc:?} has a point inside");
                }
                let filtered = arc_meets_open(&arc, &f, &normals, &p, &mut hint);
                assert_eq!(filtered, exact, "{arc:?}");
            }
        }
        assert!(tested[0] > 100 && tested[1] > 100, "{tested:?}");
    }

    /// Three open triangles with a common corner `x`, each 150° wide there, cover a
    /// neighbourhood of `x` but not `x`: the union's map has `x` as an isolated point
    /// (no arc ends there), and a small polygon around `x` is not inside the union,
    /// while one beside it is.
    #[test]
    fn an_isolated_uncovered_point_keeps_a_polygon_out() {
        let x = Vec3::new(0, 0, 10_000);
        let at = |deg: f64, r: f64| {
            let t = deg.to_radians();
            Vec3::new(
                (r * t.cos()).round() as i64,
                (r * t.sin()).round() as i64,
                10_000,
            )
        };
        let polygon = |corners: &[Vec3]| {
            let arcs = (0..corners.len())
                .map(|k| Arc::between(&corners[k], &corners[(k + 1) % corners.len()]).unwrap())
                .collect();
            SphericalPolygon::from_arcs(arcs).unwrap()
        };
        let polys: Vec<SphericalPolygon> = (0..3)
            .map(|k| {
                let a = 120.0 * k as f64 - 15.0;
                polygon(&[x.clone(), at(a, 1000.0), at(a + 150.0, 1000.0)])
            })
            .collect();
        let map = union_of(&polys);
        let ends: Vec<&Vec3> = map
            .arcs
            .iter()
            .flat_map(|(a, _)| [&a.start, &a.end])
            .collect();
        assert!(map
            .points
            .iter()
            .any(|(p, _)| p.primitive() == x.primitive()));
        assert!(!ends.iter().any(|e| e.primitive() == x.primitive()));
        let cover = Cover::new(&polys, &map);
        let around = polygon(&[at(0.0, 20.0), at(120.0, 20.0), at(240.0, 20.0)]);
        assert!(!cover.contains(&around));
        let beside = |c: f64| {
            let t = c.to_radians();
            let (cx, cy) = (
                (100.0 * t.cos()).round() as i64,
                (100.0 * t.sin()).round() as i64,
            );
            let corner = |dx: i64, dy: i64| Vec3::new(cx + dx, cy + dy, 10_000);
            polygon(&[corner(10, 0), corner(-5, 9), corner(-5, -9)])
        };
        for c in [0.0, 60.0, 120.0, 200.0, 300.0] {
            assert!(cover.contains(&beside(c)), "at {c}°");
        }
    }

    /// The filter with its walk over many sides: arcs near and across regular polygons
    /// of 9 to 200 sides (the walk starts from wherever the last arc left the hint)
    /// agree with the exact test.
    #[test]
    fn the_walk_over_many_sides_agrees_with_the_exact_arc_test() {
        let mut rng = apart_testkit::solids::Lcg(11);
        let mut tested = [0usize; 2];
        for round in 0..60 {
            let n = 9 + (round * 37) % 192;
            let r = 400.0 + (round % 7) as f64 * 100.0;
            let xy: Vec<[i64; 2]> = (0..n)
                .map(|k| {
                    let t = k as f64 * std::f64::consts::TAU / n as f64;
                    [(r * t.cos()).round() as i64, (r * t.sin()).round() as i64]
                })
                .collect();
            let corners: Vec<Vec3> = xy.iter().map(|c| Vec3::new(c[0], c[1], 1000)).collect();
            let arcs = (0..n)
                .filter_map(|k| Arc::between(&corners[k], &corners[(k + 1) % n]))
                .collect();
            let Ok(p) = SphericalPolygon::from_arcs(arcs) else {
                continue;
            };
            let normals: Vec<[f64; 3]> = p.normals().iter().map(|m| m.unit_f64()).collect();
            let mut hint = rng.below(n as u64) as usize;
            for _ in 0..60 {
                let (s, e) = if rng.below(2) == 0 {
                    // Anywhere across and around the polygon.
                    let mut point = || Vec3::new(rng.range(-700, 701), rng.range(-700, 701), 1000);
                    (point(), point())
                } else {
                    // Just outside a corner, along the boundary.
                    let c = xy[rng.below(n as u64) as usize];
                    let mut near = || {
                        let d = rng.range(-60, 61);
                        Vec3::new(c[0] * 11 / 10 + d, c[1] * 11 / 10 - d, 1000)
                    };
                    (near(), near())
                };
                let Some(arc) = Arc::between(&s, &e) else {
                    continue;
                };
                let f = FArc::of(&arc);
                let exact = exact_arc_meets_open(&arc, &p);
                tested[usize::from(exact)] += 1;
                let filtered = arc_meets_open(&arc, &f, &normals, &p, &mut hint);
                assert_eq!(filtered, exact, "{n} sides, {arc:?}");
            }
        }
        assert!(tested[0] > 300 && tested[1] > 300, "{tested:?}");
    }

    /// The cover test without its float filters and tree: every arc and point of the
    /// map tested exactly.
    fn contains_unfiltered(cover: &Cover, p: &SphericalPolygon) -> bool {
        !cover.polygons.is_empty()
            && p.normals().len() >= 3
            && !cover.exact_points.iter().any(|x| p.contains_open(x))
            && !cover.exact_arcs.iter().any(|a| exact_arc_meets_open(a, p))
            && {
                let inner = p.corners().fold(Vec3::new(0, 0, 0), |s, c| s.add(c));
                cover.polygons.iter().any(|q| q.contains_open(&inner))
            }
    }

    #[test]
    fn the_filtered_cover_test_agrees_with_the_unfiltered_one() {
        // Unions of boxes on a small grid (shared sides, corners on other boxes' sides)
        // and query boxes among them: the tree's box tests, the side filter and the
        // float arc test may only skip what cannot meet the polygon.
        let mut rng = apart_testkit::solids::Lcg(23);
        let mut next = |n: i64| rng.centred(n);
        let mut answers = [0usize; 2];
        for _ in 0..60 {
            let boxes = 2 + next(2).unsigned_abs() as usize * 2;
            let mut polys = Vec::new();
            let mut corners = Vec::new();
            for _ in 0..boxes {
                let lo = [next(5), next(5), 6 + next(2)];
                let hi = [
                    lo[0] + 1 + next(3).abs(),
                    lo[1] + 1 + next(3).abs(),
                    lo[2] + 1 + next(1).abs(),
                ];
                polys.push(box_polygon(lo, hi));
                corners.push((lo, hi));
            }
            let map = union_of(&polys);
            let cover = Cover::new(&polys, &map);
            for k in 0..40 {
                let (lo, hi) = if k % 4 == 3 {
                    // A box of the union at a thousand times the scale, each side moved
                    // out or in by one: sides cross the union's by a ten-thousandth.
                    let (a, b) = corners[k % boxes];
                    (
                        [0, 1, 2].map(|c| 1000 * a[c] + next(1)),
                        [0, 1, 2].map(|c| 1000 * b[c] + next(1)),
                    )
                } else if k % 2 == 0 {
                    let lo = [next(5), next(5), 6 + next(3)];
                    let hi = [
                        lo[0] + 1 + next(2).abs(),
                        lo[1] + 1 + next(2).abs(),
                        lo[2] + 1 + next(2).abs(),
                    ];
                    (lo, hi)
                } else {
                    // A box of the union at twice the scale, trimmed on some sides: its
                    // projection lies in that box's, sharing the untrimmed sides.
                    let (a, b) = corners[k % boxes];
                    let trim = [0, 1, 2].map(|_| next(1));
                    (
                        [0, 1, 2].map(|c| 2 * a[c] + i64::from(trim[c] > 0)),
                        [0, 1, 2].map(|c| 2 * b[c] - i64::from(trim[c] < 0)),
                    )
                };
                let q = box_polygon(lo, hi);
                let inside = cover.contains(&q);
                assert_eq!(inside, contains_unfiltered(&cover, &q), "{lo:?} {hi:?}");
                answers[usize::from(inside)] += 1;
            }
        }
        assert!(answers[0] > 200 && answers[1] > 100, "{answers:?}");
    }

    #[test]
    fn a_union_with_a_hole_contains_no_polygon_over_the_hole() {
        // Four boxes around a square hole above the origin: a polygon inside one of
        // them is contained, one over the hole is not, although every corner of it may
        // be.
        let polys = vec![
            box_polygon([-6, -6, 10], [-2, 6, 11]),
            box_polygon([2, -6, 10], [6, 6, 11]),
            box_polygon([-6, -6, 10], [6, -2, 11]),
            box_polygon([-6, 2, 10], [6, 6, 11]),
        ];
        let map = union_of(&polys);
        let cover = Cover::new(&polys, &map);
        assert!(cover.contains(&box_polygon([3, -1, 10], [5, 1, 11])));
        assert!(!cover.contains(&box_polygon([-1, -1, 10], [1, 1, 11])));
        assert!(!cover.contains(&box_polygon([-5, -5, 10], [5, 5, 11])));
    }
}
