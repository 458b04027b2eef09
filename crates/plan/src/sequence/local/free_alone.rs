//! What frees a group (one part or two touching ones) alone within its subassembly:
//! the union of its pair regions with the nearest parts, then the far ones not hidden
//! behind them, then its own small motion space or, when only isolated directions are
//! left free, rays.

use super::{ordered, Pairs, Single};
use crate::along::DirectionQuery;
use crate::cull::{box_projection_covered, Cover};
use crate::motion_space::{CellKind, MotionSpace};
use crate::pairs::ray_meets_int_box;
use crate::partition::{cell_solutions, face_solutions_of, Quota, Solution};
use crate::progress::Progress;
use crate::regions::{prune_contained, union_of_pruned, BlockingRegions, PairRegion, RegionStats};
use crate::sequence::part_tree::PartTree;
use crate::sequence::rank;
use crate::sequence::{solution_at, SequenceOptions};
use crate::store::PairStore;
use crate::PlanError;
use apart_kernel::{Aabb, Vec3};
use apart_sphere::region::RegionMap;
use apart_sphere::SphericalPolygon;
use rustc_hash::FxHashSet;
use std::cmp::Reverse;

/// Far parts whose pair regions are added to a part's union in its first round; each
/// further round takes twice as many.
const FAR_ROUND: usize = 16;

/// The polygons of the pair `{i, j}` as `i` moving sees them.
fn oriented(store: &PairStore, i: usize, j: usize) -> Vec<SphericalPolygon> {
    let r = store.get(i, j).expect("pair region made before use");
    if i < j {
        r.polygons.clone()
    } else {
        r.polygons.iter().map(SphericalPolygon::antipodal).collect()
    }
}

/// True when the union `map` of the non-empty polygon list is the whole sphere.
pub(super) fn everything(map: &RegionMap, polygons: &[SphericalPolygon]) -> bool {
    !polygons.is_empty() && map.arcs.is_empty() && map.points.is_empty()
}

/// The squared gap between two boxes (0 when they touch or overlap), in floats: only
/// an order of far parts.
fn gap2(a: &Aabb, b: &Aabb) -> f64 {
    (0..3)
        .map(|k| {
            let g = (b.min[k] as f64 - a.max[k] as f64).max(a.min[k] as f64 - b.max[k] as f64);
            g.max(0.0).powi(2)
        })
        .sum()
}

/// Pairs of parts with more piece pairs than this are costly: made whole only for a
/// group that needs more than a few directions tested (see [`single`]).
const COSTLY: usize = 256;

pub(super) fn costly(store: &PairStore, i: usize, j: usize) -> bool {
    store.piece_pairs(i, j) > COSTLY
}

/// The polygons of the pairs `pairs` (a member moving, a part fixed; regions made)
/// added to `polygons` (with their parts `owners`), none inside another.
pub(super) fn owned_union(
    store: &PairStore,
    pairs: &[(usize, usize)],
    mut polygons: Vec<SphericalPolygon>,
    mut owners: Vec<usize>,
) -> (Vec<SphericalPolygon>, Vec<usize>) {
    for &(i, j) in pairs {
        for p in oriented(store, i, j) {
            polygons.push(p);
            owners.push(j);
        }
    }
    let keep = prune_contained(&polygons, None);
    let mut slots: Vec<Option<SphericalPolygon>> = polygons.into_iter().map(Some).collect();
    let owners = keep.iter().map(|&k| owners[k]).collect();
    let polygons = keep
        .into_iter()
        .map(|k| slots[k].take().expect("kept once"))
        .collect();
    (polygons, owners)
}

/// True when what the union `map` of the non-empty `polygons` leaves free is a finite
/// set of isolated directions.
pub(super) fn isolated(map: &RegionMap, polygons: &[SphericalPolygon]) -> bool {
    !polygons.is_empty() && map.arcs.is_empty() && map.points.iter().any(|(_, on)| !on)
}

/// What frees the group `set` (one part or two) alone among the parts of `tree`, given
/// the pairs `near` of a member and a part whose boxes touch (the regions of those not
/// [`costly`] made, and of the costly ones those the group needs whole).
///
/// The union of the cheap pairs' polygons comes first, then the costly pairs' (made
/// whole) while it leaves more than isolated directions free, then the far pairs whose
/// box of sums is not provably inside it, a round of the nearest at a time. Once only
/// isolated directions are left free, each is tested by rays instead
/// ([`DirectionQuery::hits`], against every part whose box of sums the ray meets): the
/// union of a part's regions then needs no more arrangements.
pub(super) fn single(
    store: &PairStore,
    query: &DirectionQuery,
    tree: &PartTree,
    set: &[usize],
    near: Vec<(usize, usize)>,
    opts: &SequenceOptions,
    progress: &Progress,
) -> Result<Single, PlanError> {
    let touching: Vec<usize> = {
        let mut t: Vec<usize> = near.iter().map(|&(_, j)| j).collect();
        t.sort_unstable();
        t.dedup();
        t
    };
    let (cheap, rest): (Pairs, Pairs) = near
        .into_iter()
        .partition(|&(i, j)| !costly(store, i, j) || store.get(i, j).is_some());
    let mut union = GroupUnion::of(store, &cheap);
    union.add_costly(store, rest, progress)?;
    union.add_far(store, tree, set, progress)?;
    if union.isolated() {
        let GroupUnion {
            owners, map, used, ..
        } = union;
        return isolated_answer(store, query, tree, set, &map, &used, owners, touching);
    }
    // The union is that of the polygons kept, so it stays the same while their parts
    // stay: they are the blockers.
    let GroupUnion {
        polygons,
        owners,
        map,
        ..
    } = union;
    let mut blockers = owners;
    blockers.sort_unstable();
    blockers.dedup();
    if everything(&map, &polygons) {
        return Ok(Single {
            blockers,
            touching,
            best: None,
            axis: None,
            dirty: false,
        });
    }
    let (best, axis) = own_motion_space(store, set, polygons, map, opts);
    Ok(Single {
        blockers,
        touching,
        best,
        axis,
        dirty: false,
    })
}

/// The union of a group's polygons so far: the polygons (none inside another) and the
/// part each comes from, their simplified union, and the pairs (a member and a part)
/// whose regions are in it.
struct GroupUnion {
    polygons: Vec<SphericalPolygon>,
    owners: Vec<usize>,
    map: RegionMap,
    used: FxHashSet<(usize, usize)>,
}

impl GroupUnion {
    /// The union of the regions of `pairs` (made).
    fn of(store: &PairStore, pairs: &[(usize, usize)]) -> GroupUnion {
        let used = pairs.iter().copied().collect();
        let (polygons, owners) = owned_union(store, pairs, Vec::new(), Vec::new());
        let map = union_of_pruned(&polygons);
        GroupUnion {
            polygons,
            owners,
            map,
            used,
        }
    }

    /// Adds the regions of `pairs` (made).
    fn add(&mut self, store: &PairStore, pairs: &[(usize, usize)]) {
        self.used.extend(pairs.iter().copied());
        let (polygons, owners) = (
            std::mem::take(&mut self.polygons),
            std::mem::take(&mut self.owners),
        );
        (self.polygons, self.owners) = owned_union(store, pairs, polygons, owners);
        self.map = union_of_pruned(&self.polygons);
    }

    /// True when it is the whole sphere.
    fn everything(&self) -> bool {
        everything(&self.map, &self.polygons)
    }

    /// True when it leaves only isolated directions free.
    fn isolated(&self) -> bool {
        isolated(&self.map, &self.polygons)
    }

    /// Adds the costly pairs `rest`, made whole, the smallest first, while the union
    /// leaves more than isolated directions free.
    fn add_costly(
        &mut self,
        store: &PairStore,
        mut rest: Pairs,
        progress: &Progress,
    ) -> Result<(), PlanError> {
        rest.sort_by_key(|&(i, j)| (store.piece_pairs(i, j), i, j));
        let mut rest = rest.into_iter();
        while !self.everything() && !self.isolated() {
            let Some((i, j)) = rest.next() else {
                break;
            };
            store.ensure(&[(i, j)], progress)?;
            self.add(store, &[(i, j)]);
        }
        Ok(())
    }

    /// Adds the far pairs (a member of `set` and a part of `tree`) whose box of sums is
    /// not provably inside the union, nearest first, a round at a time (each twice the
    /// last), until none is left, or the union is everything or leaves only isolated
    /// directions.
    fn add_far(
        &mut self,
        store: &PairStore,
        tree: &PartTree,
        set: &[usize],
        progress: &Progress,
    ) -> Result<(), PlanError> {
        let mut round = FAR_ROUND;
        while !self.everything() && !self.isolated() {
            let mut far = self.far_pairs(store, tree, set);
            if far.is_empty() {
                break;
            }
            far.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            far.truncate(round);
            round *= 2;
            let pairs: Vec<(usize, usize)> = far.iter().map(|&(_, p)| p).collect();
            store.ensure(&pairs, progress)?;
            self.add(store, &pairs);
        }
        Ok(())
    }

    /// The pairs of a member of `set` and a part of `tree` not in the union yet whose
    /// boxes touch or whose box of sums is not provably inside the union, with the
    /// squared gap between their boxes.
    fn far_pairs(
        &self,
        store: &PairStore,
        tree: &PartTree,
        set: &[usize],
    ) -> Vec<(f64, (usize, usize))> {
        let boxes = store.boxes();
        let cover = Cover::new(&self.polygons, &self.map);
        let hemispheres = hemisphere_normals(&self.polygons);
        let in_hemisphere = |sum: &Aabb| {
            hemispheres.iter().any(|n| {
                (0..3)
                    .map(|k| (n[k] * sum.min[k] as i128).min(n[k] * sum.max[k] as i128))
                    .sum::<i128>()
                    > 0
            })
        };
        let mut far: Vec<(f64, (usize, usize))> = Vec::new();
        for &i in set {
            let bi = boxes[i];
            tree.query_by(
                &mut |b| {
                    let sum = Aabb {
                        min: std::array::from_fn(|k| b.min[k] - bi.max[k]),
                        max: std::array::from_fn(|k| b.max[k] - bi.min[k]),
                    };
                    sum.contains(&[0; 3])
                        || !(in_hemisphere(&sum) || box_projection_covered(&sum, &cover))
                },
                &mut |j| {
                    if !set.contains(&j) && !self.used.contains(&(i, j)) {
                        far.push((gap2(&bi, &boxes[j]), (i, j)));
                    }
                },
            );
        }
        far
    }
}

/// The normals, in machine integers, of the open hemispheres among `polygons` (face
/// contacts): a box of sums whose corners all lie strictly inside one projects inside
/// the union (exact, before the general test).
fn hemisphere_normals(polygons: &[SphericalPolygon]) -> Vec<[i128; 3]> {
    polygons
        .iter()
        .filter(|p| p.normals().len() == 1)
        .filter_map(|p| {
            let n = &p.normals()[0];
            let c = [n.get(0), n.get(1), n.get(2)];
            let small = c.map(|x| apart_kernel::int::to_i64(&x));
            match small {
                [Some(a), Some(b), Some(c)] => Some([a as i128, b as i128, c as i128]),
                _ => None,
            }
        })
        .collect()
}

/// The best motion of the group `set` in its own motion space, the group against the
/// union `map` of the others' `polygons` (a face of widest clearance, else the first
/// edge, else the first vertex), and with `prefer_axes` its best motion along an axis.
fn own_motion_space(
    store: &PairStore,
    set: &[usize],
    polygons: Vec<SphericalPolygon>,
    map: RegionMap,
    opts: &SequenceOptions,
) -> (Option<Solution>, Option<Solution>) {
    let name = set
        .iter()
        .map(|&k| store.parts()[k].name.as_str())
        .collect::<Vec<_>>()
        .join(" + ");
    let pair = PairRegion {
        i: 0,
        j: 1,
        polygons,
        region: map,
        contact: false,
    };
    let regions = BlockingRegions::from_pairs(
        vec![name, "the rest".into()],
        vec![Vec::new(), Vec::new()],
        vec![pair],
        RegionStats::default(),
    );
    let ms = MotionSpace::build(&regions, &[0, 1]);
    let as_part = |mut s: Solution| {
        s.moving = set.to_vec();
        s
    };
    let mut best = face_solutions_of(&regions, &ms, &mut Quota::unlimited(), &|m| m == [0])
        .into_iter()
        .next()
        .map(as_part);
    if best.is_none() {
        best = cell_solutions(&ms, &mut Quota::unlimited())
            .into_iter()
            .find(|s| s.moving == [0])
            .map(as_part);
    }
    let axis = if opts.prefer_axes {
        let polygons = &regions.pair(0, 1).polygons;
        crate::sequence::axes()
            .filter(|d| !polygons.iter().any(|p| p.contains_open(d)))
            .map(|d| solution_at(&ms, set.to_vec(), &[0], d))
            .min_by(|a, b| {
                (a.cell, Reverse(ordered(a.clearance_deg)))
                    .cmp(&(b.cell, Reverse(ordered(b.clearance_deg))))
            })
    } else {
        None
    };
    (best, axis)
}

/// The answer of a group whose union so far leaves only isolated directions free: each
/// is tested by rays against every part of `tree` whose box of sums the ray meets (the
/// pairs in `used` are in the union already), and those no part blocks are its
/// solutions (vertices).
#[allow(clippy::too_many_arguments)]
fn isolated_answer(
    store: &PairStore,
    query: &DirectionQuery,
    tree: &PartTree,
    set: &[usize],
    map: &RegionMap,
    used: &rustc_hash::FxHashSet<(usize, usize)>,
    owners: Vec<usize>,
    touching: Vec<usize>,
) -> Result<Single, PlanError> {
    let boxes = store.boxes();
    let mut blockers = owners;
    let mut free: Vec<Vec3> = Vec::new();
    let mut points: Vec<Vec3> = map
        .points
        .iter()
        .filter(|(_, on)| !on)
        .map(|(p, _)| p.primitive())
        .collect();
    points.sort_by_cached_key(|p| p.to_strings());
    points.dedup();
    'points: for p in points {
        for &i in set {
            let bi = boxes[i];
            let mut candidates: Vec<usize> = Vec::new();
            tree.query_by(
                &mut |b| {
                    let lo = std::array::from_fn(|k| b.min[k] as i128 - bi.max[k] as i128);
                    let hi = std::array::from_fn(|k| b.max[k] as i128 - bi.min[k] as i128);
                    (0..3).all(|k| lo[k] <= 0 && hi[k] >= 0)
                        || p.as_small().is_none_or(|x| ray_meets_int_box(lo, hi, x))
                },
                &mut |j| {
                    if !set.contains(&j) && !used.contains(&(i, j)) {
                        candidates.push(j);
                    }
                },
            );
            candidates.sort_unstable();
            for j in candidates {
                if query.hits(i, j, &p)? {
                    blockers.push(j);
                    continue 'points;
                }
            }
        }
        free.push(p);
    }
    blockers.sort_unstable();
    blockers.dedup();
    let solution = |d: &Vec3| Solution {
        cell: CellKind::Vertex,
        unit: d.unit_f64(),
        direction: d.clone(),
        moving: set.to_vec(),
        clearance_deg: 0.0,
    };
    Ok(Single {
        blockers,
        touching,
        best: free.first().map(solution),
        axis: free.iter().find(|d| rank::is_axis(d)).map(solution),
        dirty: false,
    })
}
