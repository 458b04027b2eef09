//! The simplified union of open convex polygons, by halves.

use super::prune::pruned;
use apart_sphere::overlay::{cell_statuses, PointStatus, SideLabel};
use apart_sphere::region::{region_inputs, simplify_union, RegionMap, Sides};
use apart_sphere::{Arrangement, BitSet, InputArc, InputPoint, SphericalPolygon};

/// The simplified union of open convex polygons.
pub fn union_of(polygons: &[SphericalPolygon]) -> RegionMap {
    union_of_pruned(&pruned(polygons.to_vec()))
}

/// Polygons united in one arrangement; more are united by halves.
pub(super) const UNION_LEAF: usize = 16;

/// [`union_of`] for polygons none of which lies in another: divide and conquer. The two
/// halves' simplified unions are overlaid (their boundaries only, which are far smaller
/// than all the polygons' when the polygons overlap), and the overlay's cells take their
/// status from the two maps' labels, from one cell evaluated exactly on the polygons.
pub(crate) fn union_of_pruned(polygons: &[SphericalPolygon]) -> RegionMap {
    if polygons.len() <= UNION_LEAF {
        return union_in_one_arrangement(polygons);
    }
    let (lo, hi) = polygons.split_at(polygons.len() / 2);
    let (a, b) = rayon::join(|| union_of_pruned(lo), || union_of_pruned(hi));
    merge_unions(&a, lo, &b, hi)
}

/// The simplified union of two simplified unions, `a` of the polygons `pa` and `b` of
/// `pb`: their boundaries overlaid, each cell's status from the polygons.
pub(super) fn merge_unions(
    a: &RegionMap,
    pa: &[SphericalPolygon],
    b: &RegionMap,
    pb: &[SphericalPolygon],
) -> RegionMap {
    let (arcs, points) = region_inputs(&[a, b]);
    let (arr, _) = Arrangement::build(arcs, points);
    let st = cell_statuses(&arr, 2, |x, y| {
        let mut s = BitSet::new(2);
        s.set(0, pa.iter().any(|p| p.contains_open_perturbed(x, y)));
        s.set(1, pb.iter().any(|p| p.contains_open_perturbed(x, y)));
        s
    });
    simplify_union(&arr, &st)
}

/// The union of a few polygons in one arrangement of all their arcs.
fn union_in_one_arrangement(polygons: &[SphericalPolygon]) -> RegionMap {
    if polygons.is_empty() {
        return RegionMap::default();
    }
    if polygons.len() == 1 {
        let p = &polygons[0];
        return RegionMap {
            arcs: p
                .boundary()
                .iter()
                .map(|a| {
                    (
                        a.clone(),
                        Sides {
                            pos: true,
                            on: false,
                            neg: false,
                        },
                    )
                })
                .collect(),
            points: p.corners().map(|c| (c.clone(), false)).collect(),
        };
    }
    let mut arcs = Vec::new();
    let mut points = Vec::new();
    for (k, p) in polygons.iter().enumerate() {
        let map = k as u32;
        for a in p.boundary() {
            arcs.push(InputArc {
                arc: a.clone(),
                label: Some(SideLabel {
                    map,
                    pos: true,
                    on: false,
                    neg: false,
                }),
            });
        }
        for c in p.corners() {
            points.push(InputPoint {
                point: c.clone(),
                label: PointStatus { map, on: false },
            });
        }
    }
    let (arr, _) = Arrangement::build(arcs, points);
    let st = cell_statuses(&arr, polygons.len(), |x, y| {
        let mut s = BitSet::new(polygons.len());
        for (k, p) in polygons.iter().enumerate() {
            s.set(k, p.contains_open_perturbed(x, y));
        }
        s
    });
    simplify_union(&arr, &st)
}
