//! Tests of the pruning filters and of the union by halves.

use super::*;
use crate::regions::union::{union_of_pruned, UNION_LEAF};
use apart_kernel::Vec3;
use apart_minkowski::{project, Projection};
use apart_pieces::Polytope;
use apart_sphere::overlay::{cell_statuses, PointStatus};
use apart_sphere::region::{region_inputs, RegionMap};
use apart_sphere::{Arrangement, BitSet, InputPoint};

/// The projection of a box (as a Minkowski sum) that misses the origin.
fn box_polygon(lo: [i64; 3], hi: [i64; 3]) -> Option<SphericalPolygon> {
    let b = Polytope::cuboid(lo, hi).ok()?;
    match project(&b).ok()? {
        Projection::Polygon(p) => Some(p),
        Projection::Everything => None,
    }
}

/// `prune_contained` without its float filters.
fn brute(polygons: &[SphericalPolygon]) -> Vec<usize> {
    let mut keep: Vec<usize> = Vec::new();
    let mut order: Vec<usize> = (0..polygons.len()).collect();
    order.sort_by_key(|&k| polygons[k].normals().len());
    for k in order {
        let p = &polygons[k];
        if !keep.iter().any(|&q| contained_in(p, &polygons[q])) {
            keep.retain(|&q| !contained_in(&polygons[q], p));
            keep.push(k);
        }
    }
    keep
}

/// Prunes `polygons` with the filters and checks it keeps what the exact test alone
/// keeps; the number pruned. Also prunes its two halves first and then the two pruned
/// halves together, comparing only across them, and checks that keeps the same.
fn pruned_as_brute(polygons: &[SphericalPolygon]) -> usize {
    let fast = prune_contained(polygons, None);
    assert_eq!(fast, brute(polygons));
    let (a, b) = polygons.split_at(polygons.len() / 2);
    let mut halves = pruned(a.to_vec());
    let split = halves.len();
    halves.extend(pruned(b.to_vec()));
    let keep = prune_contained(&halves, Some(split));
    assert_eq!(keep, prune_contained(&halves, None));
    polygons.len() - fast.len()
}

/// The status of `map` at `d`, read off the labels of an arrangement of the map and
/// the point `d` (the polygons only give the status of one cell).
fn map_status_at(map: &RegionMap, d: &Vec3, polygons: &[SphericalPolygon]) -> bool {
    let (arcs, mut points) = region_inputs(&[map]);
    points.push(InputPoint {
        point: d.clone(),
        label: PointStatus { map: 1, on: true },
    });
    let (arr, _) = Arrangement::build(arcs, points);
    let st = cell_statuses(&arr, 2, |x, y| {
        let mut s = BitSet::new(2);
        s.set(0, polygons.iter().any(|p| p.contains_open_perturbed(x, y)));
        s
    });
    let v = arr
        .vertices()
        .iter()
        .position(|v| v.point.primitive() == d.primitive())
        .expect("the point is a vertex");
    st.vertices[v].get(0)
}

#[test]
fn pruning_by_chunks_keeps_the_union() {
    // What pair_region does with many sums: prune each chunk, then all kept ones.
    let mut rng = apart_testkit::solids::Lcg(4242u64);
    let mut next = |m: i64| rng.below(m as u64) as i64;
    for _ in 0..20 {
        let mut all = Vec::new();
        for _ in 0..30 {
            let lo = [next(9) - 4, next(9) - 4, next(5) + 1];
            let hi = [
                lo[0] + next(4) + 1,
                lo[1] + next(4) + 1,
                lo[2] + next(4) + 1,
            ];
            all.extend(box_polygon(lo, hi));
        }
        let mut kept = Vec::new();
        for chunk in all.chunks(7) {
            kept.extend(pruned(chunk.to_vec()));
        }
        let kept = pruned(kept);
        assert_eq!(kept.len(), prune_contained(&all, None).len());
        for _ in 0..40 {
            let d = Vec3::new(next(15) - 7, next(15) - 7, next(9) - 1);
            if d.is_zero() {
                continue;
            }
            let blocked = |ps: &[SphericalPolygon]| ps.iter().any(|p| p.contains_open(&d));
            assert_eq!(blocked(&kept), blocked(&all), "{d:?}");
        }
    }
}

#[test]
fn halves_united_give_the_union() {
    let mut rng = apart_testkit::solids::Lcg(987u64);
    let mut next = |m: i64| rng.below(m as u64) as i64;
    for _ in 0..6 {
        let mut polygons = Vec::new();
        while polygons.len() < 3 * UNION_LEAF {
            let lo = [next(13) - 6, next(13) - 6, next(13) - 6];
            let hi = [
                lo[0] + next(5) + 1,
                lo[1] + next(5) + 1,
                lo[2] + next(5) + 1,
            ];
            polygons.extend(box_polygon(lo, hi));
        }
        let polygons = pruned(polygons);
        assert!(polygons.len() > UNION_LEAF, "the halves are used");
        let map = union_of_pruned(&polygons);
        for _ in 0..25 {
            let d = Vec3::new(next(21) - 10, next(21) - 10, next(21) - 10);
            if d.is_zero() {
                continue;
            }
            let inside = polygons.iter().any(|p| p.contains_open(&d));
            assert_eq!(map_status_at(&map, &d, &polygons), inside, "{d:?}");
        }
    }
}

#[test]
fn the_cap_filter_keeps_every_containment() {
    let mut rng = apart_testkit::solids::Lcg(12345u64);
    let mut next = |m: i64| rng.below(m as u64) as i64;
    let mut pruned = 0;
    for _ in 0..200 {
        // Boxes on a small grid, grown copies (nested projections), equal copies and
        // boxes touching the origin's planes: many containments and shared sides.
        let mut polygons = Vec::new();
        for _ in 0..10 {
            let lo = [next(9) - 4, next(9) - 4, next(5) + 1];
            let hi = [
                lo[0] + next(4) + 1,
                lo[1] + next(4) + 1,
                lo[2] + next(4) + 1,
            ];
            polygons.extend(box_polygon(lo, hi));
            let g = next(3);
            polygons.extend(box_polygon(
                [lo[0] - g, lo[1] - g, lo[2]],
                [hi[0] + g, hi[1] + g, hi[2] + g],
            ));
        }
        pruned += pruned_as_brute(&polygons);
    }
    assert!(pruned > 100, "the generator must produce containments");
}

#[test]
fn the_corner_walk_keeps_every_containment_of_many_sided_polygons() {
    // Projections of prisms over integer n-gons (8 to 40 sides), with grown copies
    // (nested projections), shifted copies, and bases far wider than their height
    // above the origin (nearly hemispheres, the shape of pieces a small gap apart):
    // the float walk must never reject a true containment.
    let mut rng = apart_testkit::solids::Lcg(99u64);
    let mut next = |m: i64| rng.below(m as u64) as i64;
    let prism = |c: [i64; 2], r: i64, n: usize, z: [i64; 2]| {
        let mut pts = Vec::new();
        for k in 0..n {
            let t = k as f64 * std::f64::consts::TAU / n as f64;
            let (x, y) = (
                (r as f64 * t.cos()).round() as i64,
                (r as f64 * t.sin()).round() as i64,
            );
            for h in z {
                pts.push(Vec3::new(c[0] + x, c[1] + y, h));
            }
        }
        let hull = Polytope::hull_of_points(&pts).ok()?;
        match project(&hull).ok()? {
            Projection::Polygon(p) => Some(p),
            Projection::Everything => None,
        }
    };
    let mut pruned = 0;
    let mut sides = 0;
    for _ in 0..24 {
        let mut polygons = Vec::new();
        for _ in 0..6 {
            let n = 8 + next(33) as usize;
            let c = [next(41) - 20, next(41) - 20];
            let r = 10 + next(200);
            let near = next(2) == 0;
            let z0 = 1 + next(if near { 3 } else { 60 });
            let z = [z0, z0 + 1 + next(20)];
            polygons.extend(prism(c, r, n, z));
            polygons.extend(prism(c, r + next(3), n, [z[0], z[1] + next(3)]));
            polygons.extend(prism([c[0] + next(3) - 1, c[1]], r, n, z));
        }
        sides += polygons.iter().map(|p| p.normals().len()).sum::<usize>();
        pruned += pruned_as_brute(&polygons);
    }
    assert!(
        pruned > 24,
        "the generator must produce containments ({pruned})"
    );
    assert!(sides > 24 * 18 * 8, "many-sided polygons ({sides})");
}

#[test]
fn the_walk_from_the_normals_centre_keeps_every_containment() {
    // Prisms over most of a circle (its corners crowd one side), wide and just above
    // the origin: corners fall behind the corners' mean direction, so the walk runs
    // in the gnomonic plane of the inward normals' sum. Grown, shifted and equal
    // copies make containments; the float filters must keep every one.
    let mut rng = apart_testkit::solids::Lcg(7u64);
    let mut next = |m: i64| rng.below(m as u64) as i64;
    let arc_prism = |c: [i64; 2], r: i64, n: usize, turn: f64, z: [i64; 2]| {
        let mut pts = Vec::new();
        for k in 0..=n {
            let t = k as f64 * turn / n as f64;
            let (x, y) = (
                (r as f64 * t.cos()).round() as i64,
                (r as f64 * t.sin()).round() as i64,
            );
            for h in z {
                pts.push(Vec3::new(c[0] + x, c[1] + y, h));
            }
        }
        match project(&Polytope::hull(&pts).ok()?).ok()? {
            Projection::Polygon(p) => Some(p),
            Projection::Everything => None,
        }
    };
    let (mut pruned, mut from_normals) = (0, 0);
    for _ in 0..24 {
        let mut polygons = Vec::new();
        for _ in 0..6 {
            let n = 12 + next(40) as usize;
            let turn = std::f64::consts::PI * (1.0 + next(50) as f64 / 100.0);
            let c = [next(21) - 10, next(21) - 10];
            let r = 500 + next(2000);
            let z = [1 + next(2), 3 + next(5)];
            polygons.extend(arc_prism(c, r, n, turn, z));
            polygons.extend(arc_prism(c, r + next(3), n, turn, [z[0], z[1] + next(3)]));
            polygons.extend(arc_prism([c[0] + next(3) - 1, c[1]], r, n, turn, z));
        }
        for p in &polygons {
            let a = Approx::new(p);
            let at_cap = a
                .cap
                .as_ref()
                .is_some_and(|c| a.corners.iter().all(|u| dot(*u, c.centre) > 1e-6));
            from_normals += usize::from(!at_cap && !a.gnomonic.is_empty());
        }
        pruned += pruned_as_brute(&polygons);
    }
    assert!(
        pruned > 24,
        "the generator must produce containments ({pruned})"
    );
    assert!(
        from_normals > 100,
        "walks from the normals' sum ({from_normals})"
    );
}
