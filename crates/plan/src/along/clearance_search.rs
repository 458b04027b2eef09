//! The angular clearance of a moving set at a direction: a best-first search over
//! groups of piece pairs, bounded below by the angle to their boxes of sums and by
//! their separating axes, summing only the pairs that may come nearer than the best.

use super::DirectionQuery;
use crate::clearance::{chord2, to_angle, FArc};
use crate::cull::{split_pair, sum_box};
use crate::pairs::{Axis, FloatBox};
use crate::PlanError;
use apart_kernel::{Bvh, Vec3};
use apart_sphere::SphericalPolygon;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

impl DirectionQuery<'_> {
    /// Angular clearance (radians) at `d` of the moving set `moving` (global indices):
    /// the distance to the nearest direction along which a part of `moving` hits a part
    /// outside it. Groups of piece pairs (node pairs of the parts' box trees, under
    /// groups of part pairs: a moving part against a node of the staying parts' box
    /// hierarchy) are visited best first by a lower bound, the angle from `d` to the cone
    /// over the box of their sums ([`box_angle`]); a single pair's bound also uses the
    /// hemispheres of its separating axes. The search stops once the bound exceeds the
    /// best distance so far (within a relative 1e-6), so the value is the true distance
    /// (in floating point) or at most a millionth more.
    pub fn clearance(&self, d: &Vec3, moving: &[usize]) -> Result<f64, PlanError> {
        let mut stays = vec![true; self.parts.len()];
        for &k in moving {
            stays[k] = false;
        }
        let rest: Vec<usize> = (0..self.parts.len()).filter(|&j| stays[j]).collect();
        self.clearance_against(d, moving, &rest)
    }

    /// [`DirectionQuery::clearance`] against the parts `rest` only (global indices; the
    /// parts of a subassembly that stay).
    pub fn clearance_against(
        &self,
        d: &Vec3,
        moving: &[usize],
        rest: &[usize],
    ) -> Result<f64, PlanError> {
        let mut search = Search::new(self, d, rest);
        // Pairs of parts without box trees: each piece pair on its own, in the order of
        // their bounds.
        let loose = search.seed(moving, rest);
        for (bound, p, q, flip, k) in loose {
            if bound >= slack(search.best) {
                break;
            }
            search.visit(p, q, flip, k)?;
        }
        search.best_first()?;
        Ok(search.best)
    }
}

/// A group in the search's queue, least bound first. Bounds are non-negative, so their
/// bit patterns order like the values. A group of part pairs (kind 0: moving part `p`
/// against the staying parts under node `q` of their hierarchy) comes before the
/// piece-pair groups (kind 1: nodes `na`, `nb` of the trees of parts `p < q`, at `−d`
/// when `flip`) of equal bound.
type Key = Reverse<(u64, u8, usize, usize, bool, usize, usize)>;

/// The queue key of the piece pairs under nodes `na` of part `p`'s tree and `nb` of
/// part `q`'s.
fn key(bound: f64, p: usize, q: usize, flip: bool, na: usize, nb: usize) -> Key {
    Reverse((bound.max(0.0).to_bits(), 1, p, q, flip, na, nb))
}

/// The queue key of moving part `p` against the staying parts under `node`.
fn group(bound: f64, p: usize, node: usize) -> Key {
    Reverse((bound.max(0.0).to_bits(), 0, p, node, false, 0, 0))
}

/// A piece pair of parts without box trees: its bound, the parts `p < q`, whether it is
/// seen at `−d`, and its index `k` among the pair's piece pairs.
type Loose = (f64, usize, usize, bool, usize);

/// The bound below which a group is still visited. A pair is skipped when its bound is
/// within a relative 1e-6 of the best so far: the value may exceed the true distance by
/// that much, no more. Under a tolerance every pair of a planar contact lies at about
/// the same distance (the contact's great circle), and each would otherwise be summed
/// to shave the last digits.
fn slack(best: f64) -> f64 {
    best * (1.0 - 1e-6)
}

/// One clearance search: the direction both ways, the staying parts with box trees in
/// a hierarchy of their boxes, the queue of groups and the best distance so far.
struct Search<'s, 'a> {
    query: &'s DirectionQuery<'a>,
    /// `d` and `−d` as unit vectors.
    units: [[f64; 3]; 2],
    /// `d` and `−d`.
    xs: [Vec3; 2],
    /// The staying parts with box trees (global indices).
    treed: Vec<usize>,
    /// The hierarchy of their boxes (items are positions in `treed`).
    staying: Bvh,
    heap: BinaryHeap<Key>,
    best: f64,
}

impl<'s, 'a> Search<'s, 'a> {
    /// The search at `d` against the staying parts `rest`, with nothing queued.
    fn new(query: &'s DirectionQuery<'a>, d: &Vec3, rest: &[usize]) -> Search<'s, 'a> {
        let treed: Vec<usize> = rest
            .iter()
            .copied()
            .filter(|&j| query.trees[j].is_some())
            .collect();
        let staying = Bvh::new(treed.iter().map(|&j| query.reach[j]).collect());
        Search {
            query,
            units: [d.unit_f64(), d.neg().unit_f64()],
            xs: [d.clone(), d.neg()],
            treed,
            staying,
            heap: BinaryHeap::new(),
            best: std::f64::consts::PI,
        }
    }

    /// The bound of moving part `i` against the staying parts under `node`: the angle
    /// to the box of their sums with `i`'s, less a margin far above its rounding, so
    /// that it is below the bound of every pair under it (then the pairs are visited in
    /// the order, and with the stop, of a search seeded with all of them).
    fn group_bound(&self, i: usize, node: usize) -> f64 {
        let (a, b) = (&self.query.reach[i], self.staying.node_box(node));
        let lo = std::array::from_fn(|k| b.min[k] - a.max[k]);
        let hi = std::array::from_fn(|k| b.max[k] - a.min[k]);
        box_angle(lo, hi, &self.units[0]) - 1e-6
    }

    /// Queues each moving part with a box tree against the root of the staying parts'
    /// hierarchy, and returns the piece pairs of every other pair of a moving and a
    /// staying part, bounded by the floating-point box of their sum, sorted by bound
    /// (the order of the loop over every pair kept on ties).
    fn seed(&mut self, moving: &[usize], rest: &[usize]) -> Vec<Loose> {
        let query = self.query;
        let untreed: Vec<usize> = rest
            .iter()
            .copied()
            .filter(|&j| query.trees[j].is_none())
            .collect();
        let mut loose: Vec<Loose> = Vec::new();
        for i in moving.iter().copied() {
            let against: &[usize] = if query.trees[i].is_some() {
                if let Some(root) = self.staying.root() {
                    self.heap.push(group(self.group_bound(i, root), i, root));
                }
                &untreed
            } else {
                rest
            };
            for j in against.iter().copied() {
                // Map i -> j is P_ab of the pair (min, max) at d when i < j, at −d else.
                let (p, q, flip) = if i < j { (i, j, false) } else { (j, i, true) };
                let u = &self.units[usize::from(flip)];
                let (fa, fq) = (&query.info[p], &query.info[q]);
                for (a, (alo, ahi)) in fa.iter().map(|i| &i.float_bounds).enumerate() {
                    for (b, (blo, bhi)) in fq.iter().map(|i| &i.float_bounds).enumerate() {
                        let lo = std::array::from_fn(|k| blo[k] - ahi[k]);
                        let hi = std::array::from_fn(|k| bhi[k] - alo[k]);
                        loose.push((box_angle_f64(lo, hi, u), p, q, flip, a * fq.len() + b));
                    }
                }
            }
        }
        loose.sort_by(|a, b| a.0.total_cmp(&b.0));
        loose
    }

    /// One piece pair `k` of parts `p < q` whose bound is below the best: a tighter
    /// bound from its separating axes, then its polygon. Pieces a gap apart (every
    /// contact under a tolerance) have boxes that meet, so the box bound is 0 for pairs
    /// that the contact's own axis puts far from the direction.
    fn visit(&mut self, p: usize, q: usize, flip: bool, k: usize) -> Result<(), PlanError> {
        let query = self.query;
        let x = &self.xs[usize::from(flip)];
        let m = query.parts[q].pieces.len();
        let (a, b) = (&query.parts[p].pieces[k / m], &query.parts[q].pieces[k % m]);
        let boxes = (
            &query.info[p][k / m].float_bounds,
            &query.info[q][k % m].float_bounds,
        );
        let pair = query.pair(p, q);
        if axes_bound(query.axes(pair, k), (a, b), boxes, x) >= slack(self.best) {
            return Ok(());
        }
        let poly = query.polygon(pair, k)?;
        self.best = self.best.min(distance(poly, x));
        Ok(())
    }

    /// Pops the groups least bound first until the bound reaches the best distance:
    /// groups of part pairs are split into their nodes' children or their part pairs'
    /// roots, groups of piece pairs into their trees' children or their piece pairs.
    fn best_first(&mut self) -> Result<(), PlanError> {
        while let Some(Reverse((bits, kind, p, q, flip, na, nb))) = self.heap.pop() {
            if f64::from_bits(bits) >= slack(self.best) {
                break;
            }
            if kind == 0 {
                self.split_group(p, q);
            } else {
                self.split_pieces(p, q, flip, na, nb)?;
            }
        }
        Ok(())
    }

    /// Moving part `p` against the staying parts under `node`: the node's children
    /// queued, or at a leaf each part pair's tree roots.
    fn split_group(&mut self, p: usize, node: usize) {
        let query = self.query;
        match self.staying.children(node) {
            Some(children) => {
                for c in children {
                    if self.staying.node_box(c).is_empty() {
                        continue;
                    }
                    let bound = self.group_bound(p, c);
                    if bound < slack(self.best) {
                        self.heap.push(group(bound, p, c));
                    }
                }
            }
            None => {
                for &s in self.staying.items(node) {
                    let j = self.treed[s as usize];
                    let (p, q, flip) = if p < j { (p, j, false) } else { (j, p, true) };
                    let (Some(tp), Some(tq)) = (&query.trees[p], &query.trees[q]) else {
                        continue;
                    };
                    if let (Some(ra), Some(rb)) = (tp.root(), tq.root()) {
                        let s = sum_box(tp, ra, tq, rb);
                        let bound = box_angle(s.min, s.max, &self.units[usize::from(flip)]);
                        if bound < slack(self.best) {
                            self.heap.push(key(bound, p, q, flip, ra, rb));
                        }
                    }
                }
            }
        }
    }

    /// The piece pairs under nodes `na` and `nb` of the trees of parts `p < q`: the
    /// node pairs' children queued, or at two leaves each piece pair visited.
    fn split_pieces(
        &mut self,
        p: usize,
        q: usize,
        flip: bool,
        na: usize,
        nb: usize,
    ) -> Result<(), PlanError> {
        let query = self.query;
        let (Some(tp), Some(tq)) = (&query.trees[p], &query.trees[q]) else {
            return Ok(());
        };
        match split_pair(tp, na, tq, nb) {
            Some(children) => {
                for (ca, cb) in children {
                    let s = sum_box(tp, ca, tq, cb);
                    let bound = box_angle(s.min, s.max, &self.units[usize::from(flip)]);
                    if bound < slack(self.best) {
                        self.heap.push(key(bound, p, q, flip, ca, cb));
                    }
                }
            }
            None => {
                let m = query.parts[q].pieces.len();
                for &a in tp.items(na) {
                    for &b in tq.items(nb) {
                        self.visit(p, q, flip, a as usize * m + b as usize)?;
                    }
                }
            }
        }
        Ok(())
    }
}

/// A lower bound of the angle (radians) from `x` to the closed projection of the piece
/// pair `(a, b)` (the directions of `b ⊕ −a`) from its separating axes. Along a unit
/// axis `n̂` the pieces are a gap `g >= 0` apart (`a` below), so every point `y` of the
/// sum has `n̂ · y >= g`, and the sum's box bounds `x̂ · y <= h`. In the plane of `x̂`
/// and `n̂` (`n̂ = c x̂ + s e`), a point with `x̂ · y = u` is at least `atan((g − c u) /
/// (s u))` from `x̂`, least at `u = h`; for `g = 0` this is the closed hemisphere's
/// `asin(−n̂ · x̂)`. So a pair sliding past `x` a tolerance's gap apart (`n` square to
/// `x`) is as far as the gap seen from the sum's far end, not 0. Floating point,
/// widened by 1e-9 (relative to the coordinates in lengths, radians in angles); only
/// used to skip sums in [`DirectionQuery::clearance`].
pub(super) fn axes_bound(
    axes: &[Axis],
    (a, b): (&apart_pieces::Polytope, &apart_pieces::Polytope),
    ((alo, ahi), (blo, bhi)): (&FloatBox, &FloatBox),
    x: &Vec3,
) -> f64 {
    use apart_kernel::fvec;
    use std::f64::consts::FRAC_PI_2;
    let u = x.unit_f64();
    let mut scale = 0.0f64;
    let mut h = 0.0;
    for k in 0..3 {
        let (lo, hi) = (blo[k] - ahi[k], bhi[k] - alo[k]);
        h += (u[k] * lo).max(u[k] * hi);
        for v in [alo[k], ahi[k], blo[k], bhi[k]] {
            scale = scale.max(v.abs());
        }
    }
    let margin = 1e-9 * scale;
    let h = h + margin;
    let (pa, pb) = (a.shadow().map(|s| &s.points), b.shadow().map(|s| &s.points));
    axes.iter()
        .map(|ax| {
            let n = ax.n.unit_f64();
            let c = fvec::dot(u, n);
            let s = fvec::norm(fvec::cross(u, n));
            // The closed hemisphere n̂ · y >= 0.
            let hemisphere = (s.atan2(c) - FRAC_PI_2 - 1e-9).max(0.0);
            let gap = match (pa, pb) {
                (Some(pa), Some(pb)) if ax.strict => {
                    let top_a = pa
                        .iter()
                        .map(|v| fvec::dot(n, *v))
                        .fold(f64::NEG_INFINITY, f64::max);
                    let low_b = pb
                        .iter()
                        .map(|v| fvec::dot(n, *v))
                        .fold(f64::INFINITY, f64::min);
                    low_b - top_a - margin
                }
                _ => 0.0,
            };
            let cap = if gap <= 0.0 || !gap.is_finite() || !h.is_finite() {
                0.0
            } else if h <= 0.0 {
                FRAC_PI_2 - 1e-9
            } else if gap - c * h <= 0.0 || s <= 0.0 {
                0.0
            } else {
                ((gap - c * h).atan2(s * h) - 1e-9).max(0.0)
            };
            hemisphere.max(cap)
        })
        .fold(0.0, f64::max)
}

/// Angle (radians) from direction `x` to the closed polygon `p`.
fn distance(p: &SphericalPolygon, x: &Vec3) -> f64 {
    if p.contains_closed(x) {
        return 0.0;
    }
    let u = x.unit_f64();
    let c2 = p
        .boundary()
        .iter()
        .map(|a| FArc::of(a).distance2(&u))
        .fold(4.0, f64::min);
    to_angle(c2)
}

/// [`box_angle_f64`] of an integer box.
pub(super) fn box_angle(lo: [i64; 3], hi: [i64; 3], u: &[f64; 3]) -> f64 {
    box_angle_f64(lo.map(|x| x as f64), hi.map(|x| x as f64), u)
}

/// A lower bound of the angle (radians) from unit `u` to the direction of every point
/// of the closed box `[lo, hi]`: 0 when the box, widened by a relative 1e-9, holds the
/// origin or meets the ray along `u`; else the distance to the arcs of the box's 12
/// edges, less 1e-9 (the cone over a convex set without the origin is bounded by its
/// silhouette, which is made of edges). Floating point; only used to order and skip
/// the clearance search.
fn box_angle_f64(lo: [f64; 3], hi: [f64; 3], u: &[f64; 3]) -> f64 {
    use apart_kernel::fvec;
    let scale = (0..3)
        .map(|k| lo[k].abs().max(hi[k].abs()))
        .fold(0.0, f64::max);
    let pad = scale * 1e-9 + f64::MIN_POSITIVE;
    let (lo, hi) = (lo.map(|x| x - pad), hi.map(|x| x + pad));
    if (0..3).all(|k| lo[k] <= 0.0 && 0.0 <= hi[k]) {
        return 0.0;
    }
    // The ray t u (t > 0) against the slabs.
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for k in 0..3 {
        if u[k] == 0.0 {
            if lo[k] > 0.0 || hi[k] < 0.0 {
                t1 = -1.0;
            }
            continue;
        }
        let (a, b) = (lo[k] / u[k], hi[k] / u[k]);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    if t0 <= t1 {
        return 0.0;
    }
    let corners: [[f64; 3]; 8] = std::array::from_fn(|c| {
        fvec::normalize(std::array::from_fn(|k| {
            if c >> k & 1 == 1 {
                hi[k]
            } else {
                lo[k]
            }
        }))
    });
    let mut c2 = 4.0f64;
    for c in 0..8 {
        for k in (0..3).filter(|k| c >> k & 1 == 0) {
            let (a, b) = (corners[c], corners[c | 1 << k]);
            let n = fvec::cross(a, b);
            let len = fvec::norm(n);
            c2 = c2.min(if len > 1e-12 {
                FArc::new(a, b, n.map(|x| x / len)).distance2(u)
            } else {
                chord2(u, &a).min(chord2(u, &b))
            });
        }
    }
    (to_angle(c2) - 1e-9).max(0.0)
}
