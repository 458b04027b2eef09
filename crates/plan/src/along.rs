//! One direction without the motion-space arrangement, and a quick first solution.
//!
//! [`dbg_along`] answers what `partition --direction` asks: the exact blocking graph at
//! `d`, its minimal moving sets, and the kind of motion-space cell `d` lies in, from
//! per-piece-pair tests only ([`crate::pairs`]): exact separating axes decide most pairs,
//! touching pairs get their contact cone from a small sum of face neighbourhoods, and
//! only the remaining pairs are summed in full, stopping for an ordered pair of parts as
//! soon as one piece pair blocks it.
//!
//! The cell kind is local: near `d`, a pair's blocked set is everything when `d` is
//! blocked, and otherwise the union of the piece pairs' polygons whose closure contains
//! `d` (the others lie at a positive distance). So the motion space built from just
//! those polygons (at `d` and `−d`, which the reversed pair sees) has, at `d`, the same
//! vertex, edge or face as the full one.

use crate::clearance::{chord2, to_angle, FArc};
use crate::cull::{pairs_where, piece_tree, split_pair, sum_box};
use crate::dbg::Dbg;
use crate::motion_space::{CellKind, MotionSpace};
use crate::pairs::{
    axes, classify, pair_polygon, ray_meets_box, ray_meets_int_box, Axis, FloatBox, PairPolygon,
    PieceInfo, Sep,
};
use crate::partition::{Partitioning, PhaseSeconds, Solution, Stats};
use crate::regions::{BlockingRegions, Part};
use crate::PlanError;
use apart_kernel::{Aabb, Bvh, Vec3};
use apart_sphere::SphericalPolygon;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::OnceLock;
use std::time::Instant;

/// The exact answer at one direction.
#[derive(Clone, Debug)]
pub struct DirectionAnswer {
    /// The direction (primitive).
    pub direction: Vec3,
    /// The kind of motion-space cell it lies in (as [`MotionSpace::locate`] says).
    pub cell: CellKind,
    /// The directional blocking graph: over global part indices from
    /// [`DirectionQuery::answer`], over positions in the subassembly from
    /// [`DirectionQuery::answer_in`].
    pub dbg: Dbg,
    /// Its minimal moving sets (global part indices).
    pub moving: Vec<Vec<usize>>,
}

/// Work counters of a [`DirectionQuery`].
#[derive(Clone, Copy, Debug, Default)]
pub struct QueryStats {
    /// Piece pairs of different parts.
    pub piece_pairs: usize,
    /// Pairs whose separating axes were computed (the box test did not decide).
    pub axes: usize,
    /// Contact cones from face neighbourhoods.
    pub contact_cones: usize,
    /// Full Minkowski sums.
    pub sums: usize,
}

/// Piece pairs per block of [`DirectionQuery`]'s cache.
const BLOCK: usize = 64;

/// Lazily computed data of one piece pair (`a` of the smaller part index, `b` of the
/// larger).
#[derive(Default)]
struct PairCache {
    axes: OnceLock<Vec<Axis>>,
    polygon: OnceLock<Result<PairPolygon, String>>,
}

/// Per-direction queries on an assembly's convex pieces, caching every piece pair's
/// separating axes and projection between queries.
pub struct DirectionQuery<'a> {
    parts: &'a [Part],
    info: Vec<Vec<PieceInfo>>,
    /// Each part's box tree over its pieces (`None` when its coordinates are too large
    /// for integer boxes: then every piece pair is visited).
    trees: Vec<Option<Bvh>>,
    /// Unordered part pairs `i < j` and their piece-pair caches (`a * |j| + b`), in
    /// blocks of [`BLOCK`] allocated when a pair in them is first asked for: two parts
    /// of a thousand pieces each make a million pairs, of which a query touches few.
    cache: Vec<Vec<OnceLock<Box<[PairCache]>>>>,
    pair_index: Vec<usize>,
    n_axes: AtomicUsize,
    n_cones: AtomicUsize,
    n_sums: AtomicUsize,
}

impl<'a> DirectionQuery<'a> {
    /// Prepares the pieces (bounds only; everything else on demand).
    pub fn new(parts: &'a [Part]) -> Result<DirectionQuery<'a>, PlanError> {
        for (k, p) in parts.iter().enumerate() {
            if p.pieces.is_empty() {
                return Err(PlanError::NoPieces {
                    part: k,
                    name: p.name.clone(),
                });
            }
        }
        let n = parts.len();
        let info = parts
            .par_iter()
            .map(|p| p.pieces.iter().map(PieceInfo::new).collect())
            .collect();
        let trees = parts.par_iter().map(|p| piece_tree(&p.pieces)).collect();
        let mut pair_index = vec![usize::MAX; n * n];
        let mut cache = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                pair_index[i * n + j] = cache.len();
                let m = parts[i].pieces.len() * parts[j].pieces.len();
                cache.push((0..m.div_ceil(BLOCK)).map(|_| OnceLock::new()).collect());
            }
        }
        Ok(DirectionQuery {
            parts,
            info,
            trees,
            cache,
            pair_index,
            n_axes: AtomicUsize::new(0),
            n_cones: AtomicUsize::new(0),
            n_sums: AtomicUsize::new(0),
        })
    }

    /// Work done so far.
    pub fn stats(&self) -> QueryStats {
        let n = self.parts.len();
        QueryStats {
            piece_pairs: (0..n)
                .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
                .map(|(i, j)| self.parts[i].pieces.len() * self.parts[j].pieces.len())
                .sum(),
            axes: self.n_axes.load(Ordering::Relaxed),
            contact_cones: self.n_cones.load(Ordering::Relaxed),
            sums: self.n_sums.load(Ordering::Relaxed),
        }
    }

    /// The cache of piece pair `k` of parts `i < j`.
    fn pair(&self, i: usize, j: usize, k: usize) -> &PairCache {
        let blocks = &self.cache[self.pair_index[i * self.parts.len() + j]];
        let block =
            blocks[k / BLOCK].get_or_init(|| (0..BLOCK).map(|_| PairCache::default()).collect());
        &block[k % BLOCK]
    }

    fn axes(&self, i: usize, j: usize, k: usize) -> &[Axis] {
        let nb = self.parts[j].pieces.len();
        let (a, b) = (k / nb, k % nb);
        self.pair(i, j, k).axes.get_or_init(|| {
            self.n_axes.fetch_add(1, Ordering::Relaxed);
            axes(
                &self.parts[i].pieces[a],
                &self.info[i][a],
                &self.parts[j].pieces[b],
                &self.info[j][b],
            )
        })
    }

    fn polygon(&self, i: usize, j: usize, k: usize) -> Result<&SphericalPolygon, PlanError> {
        let nb = self.parts[j].pieces.len();
        let (a, b) = (k / nb, k % nb);
        let axes = self.axes(i, j, k);
        let r = self.pair(i, j, k).polygon.get_or_init(|| {
            let r = pair_polygon(
                &self.parts[i].pieces[a],
                &self.info[i][a],
                &self.parts[j].pieces[b],
                &self.info[j][b],
                axes,
            );
            match r {
                Ok((p, full)) => {
                    let c = if full { &self.n_sums } else { &self.n_cones };
                    c.fetch_add(1, Ordering::Relaxed);
                    Ok(p)
                }
                Err(e) => Err(e),
            }
        });
        match r {
            Ok(PairPolygon::Polygon(p, _)) => Ok(p),
            Ok(PairPolygon::Overlap) => Err(PlanError::Overlap {
                parts: (i, j),
                names: (self.parts[i].name.clone(), self.parts[j].name.clone()),
                pieces: (a, b),
            }),
            Err(e) => Err(crate::pairs::internal(
                (&self.parts[i].name, &self.parts[j].name),
                e.clone(),
            )),
        }
    }

    /// The piece pairs of `{i, j}` whose sum's box the ray along `x` may meet (a
    /// superset, from the parts' box trees; every pair without them), in increasing order.
    fn along_ray(&self, i: usize, j: usize, x: &Vec3) -> Vec<usize> {
        match x.as_small() {
            Some(xs) => self.tree_pairs(i, j, &|sum| {
                ray_meets_int_box(sum.min.map(i128::from), sum.max.map(i128::from), xs)
            }),
            None => (0..self.parts[i].pieces.len() * self.parts[j].pieces.len()).collect(),
        }
    }

    /// The piece pairs `k` of `{i, j}` under node pairs of the parts' box trees whose
    /// box of sums `keep` accepts, in increasing order (every pair without trees).
    fn tree_pairs(&self, i: usize, j: usize, keep: &(dyn Fn(&Aabb) -> bool + Sync)) -> Vec<usize> {
        let nb = self.parts[j].pieces.len();
        let (Some(ti), Some(tj)) = (&self.trees[i], &self.trees[j]) else {
            return (0..self.parts[i].pieces.len() * nb).collect();
        };
        let mut out: Vec<usize> = pairs_where(ti, tj, &|sum, _| keep(sum), &|_, _| true)
            .into_iter()
            .map(|(a, b)| a * nb + b)
            .collect();
        out.sort_unstable();
        out
    }

    /// The piece pairs of `{i, j}` that `x` does not put outside their closed
    /// projections, with their status: the ray along `x` meets the box of the pair's sum
    /// (exactly), and the axes do not exclude `x`. In increasing order.
    fn classify_all(&self, i: usize, j: usize, x: &Vec3) -> Vec<(usize, Sep)> {
        let nb = self.parts[j].pieces.len();
        let near = self.along_ray(i, j, x);
        near.into_par_iter()
            .with_min_len(64)
            .filter_map(|k| {
                let (a, b) = (k / nb, k % nb);
                let (pa, pb) = (&self.parts[i].pieces[a], &self.parts[j].pieces[b]);
                if !ray_meets_box(&self.info[i][a], pa.den(), &self.info[j][b], pb.den(), x) {
                    return None;
                }
                let s = classify(self.axes(i, j, k), x);
                (s != Sep::Outside).then_some((k, s))
            })
            .collect()
    }

    /// For the pair `{i, j}` (`i < j`) at `x` (part `i` moving along `x`): a piece pair
    /// whose open polygon contains `x` (then `x` is blocked), or `None`. Touching pairs
    /// first (cheap cones), then the others (full sums), deepest on the ray first, in
    /// growing chunks, stopping at the first that blocks.
    fn blocker(
        &self,
        i: usize,
        j: usize,
        sep: &[(usize, Sep)],
        x: &Vec3,
    ) -> Result<Option<usize>, PlanError> {
        let (touching, others): (Vec<usize>, Vec<usize>) = sep
            .iter()
            .filter(|(_, s)| *s == Sep::Unknown)
            .map(|(k, _)| *k)
            .partition(|&k| self.axes(i, j, k).iter().any(|a| !a.strict));
        // Pairs whose sum's box the ray crosses nearest its middle first (the likeliest
        // to block), in chunks growing from 2 to 64: the first blocker is often among
        // the first few.
        let nb = self.parts[j].pieces.len();
        let u = x.unit_f64();
        let mut depth: Vec<(f64, usize)> = others
            .iter()
            .map(|&k| {
                let (a, b) = (&self.info[i][k / nb], &self.info[j][k % nb]);
                (ray_depth(a.float_bounds, b.float_bounds, &u), k)
            })
            .collect();
        depth.sort_by(|p, q| q.0.total_cmp(&p.0).then(p.1.cmp(&q.1)));
        let others: Vec<usize> = depth.into_iter().map(|(_, k)| k).collect();
        let mut chunks: Vec<&[usize]> = vec![&touching[..]];
        let (mut start, mut size) = (0, 2);
        while start < others.len() {
            let end = (start + size).min(others.len());
            chunks.push(&others[start..end]);
            (start, size) = (end, (size * 2).min(64));
        }
        for chunk in chunks {
            let hit: Vec<Option<usize>> = chunk
                .par_iter()
                .map(|&k| -> Result<Option<usize>, PlanError> {
                    Ok(self.polygon(i, j, k)?.contains_open(x).then_some(k))
                })
                .collect::<Result<_, _>>()?;
            if let Some(k) = hit.into_iter().flatten().next() {
                return Ok(Some(k));
            }
        }
        Ok(None)
    }

    /// Whether part `i`, moving along `d`, hits part `j` (an arc `i → j` of the blocking
    /// graph at `d`), from the piece pairs alone: no cell kind, so no polygon is made
    /// for a pair that `d` does not enter. What "can this set move along `d`" needs.
    pub fn hits(&self, i: usize, j: usize, d: &Vec3) -> Result<bool, PlanError> {
        let d = d.primitive();
        // Part i along d meets j exactly when j along −d meets i: the pair is stored once.
        let (i, j, x) = if i < j { (i, j, d) } else { (j, i, d.neg()) };
        let sep = self.classify_all(i, j, &x);
        Ok(self.blocker(i, j, &sep, &x)?.is_some())
    }

    /// For the pair `{i, j}` (`i < j`) at `x` (part `i` moving along `x`): a polygon
    /// containing `x` in its interior when blocked, else every polygon whose closure
    /// contains `x`.
    fn local(&self, i: usize, j: usize, x: &Vec3) -> Result<(bool, Vec<usize>), PlanError> {
        let sep = self.classify_all(i, j, x);
        if let Some(k) = self.blocker(i, j, &sep, x)? {
            return Ok((true, vec![k]));
        }
        // Not blocked: every polygon whose closure holds x, touching pairs first. A
        // polygon inside the open hemisphere of a face contact of the same parts changes
        // nothing near x (its open set lies in that hemisphere, which is in the union),
        // so non-touching pairs covered that way are not summed.
        let (touching, others): (Vec<usize>, Vec<usize>) = sep
            .iter()
            .map(|(k, _)| *k)
            .partition(|&k| self.axes(i, j, k).iter().any(|a| !a.strict));
        let mut on: Vec<Option<usize>> = touching
            .par_iter()
            .map(|&k| -> Result<Option<usize>, PlanError> {
                Ok(self.polygon(i, j, k)?.contains_closed(x).then_some(k))
            })
            .collect::<Result<_, _>>()?;
        let mut h: rustc_hash::FxHashSet<Vec3> = Default::default();
        for &k in &touching {
            let p = self.polygon(i, j, k)?;
            if p.normals().len() == 1 {
                h.insert(p.normals()[0].clone());
            }
        }
        let nb = self.parts[j].pieces.len();
        let more: Vec<Option<usize>> = others
            .par_iter()
            .map(|&k| -> Result<Option<usize>, PlanError> {
                let (a, b) = (k / nb, k % nb);
                let covered = !h.is_empty()
                    && (self
                        .axes(i, j, k)
                        .iter()
                        .any(|ax| h.contains(&ax.n.primitive()))
                        || crate::pairs::below_along_any(
                            &self.parts[i].pieces[a],
                            &self.parts[j].pieces[b],
                            &h,
                        ));
                if covered {
                    return Ok(None);
                }
                Ok(self.polygon(i, j, k)?.contains_closed(x).then_some(k))
            })
            .collect::<Result<_, _>>()?;
        on.extend(more);
        Ok((false, on.into_iter().flatten().collect()))
    }

    /// The exact blocking graph at `d`, its minimal moving sets and the cell kind.
    pub fn answer(&self, d: &Vec3) -> Result<DirectionAnswer, PlanError> {
        let all: Vec<usize> = (0..self.parts.len()).collect();
        self.answer_in(&all, d)
    }

    /// [`DirectionQuery::answer`] within the subassembly `sub` (global part indices,
    /// increasing): the blocking graph among its parts (vertex `k` of [`Dbg`] stands for
    /// part `sub[k]`), its minimal moving sets in global indices, and the cell kind of `d`
    /// in the subassembly's motion space.
    pub fn answer_in(&self, sub: &[usize], d: &Vec3) -> Result<DirectionAnswer, PlanError> {
        let d = d.primitive();
        let n = sub.len();
        let mut arcs = Vec::new();
        let mut local: Vec<Vec<SphericalPolygon>> = Vec::new();
        let mut any = false;
        for (li, &i) in sub.iter().enumerate() {
            for (lj, &j) in sub.iter().enumerate().skip(li + 1) {
                let mut keep: Vec<usize> = Vec::new();
                for (x, arc) in [(d.clone(), (li, lj)), (d.neg(), (lj, li))] {
                    let (blocked, ks) = self.local(i, j, &x)?;
                    if blocked {
                        arcs.push(arc);
                    }
                    keep.extend(ks);
                }
                keep.sort_unstable();
                keep.dedup();
                any |= !keep.is_empty();
                local.push(
                    keep.iter()
                        .map(|&k| self.polygon(i, j, k).cloned())
                        .collect::<Result<_, _>>()?,
                );
            }
        }
        let dbg = Dbg::new(n, arcs);
        let moving = dbg
            .minimal_moving_sets()
            .into_iter()
            .map(|s| s.into_iter().map(|k| sub[k]).collect())
            .collect();
        let cell = if any {
            let names: Vec<String> = sub.iter().map(|&k| self.parts[k].name.clone()).collect();
            let regions = BlockingRegions::from_polygons(names, local);
            let all: Vec<usize> = (0..n).collect();
            MotionSpace::build(&regions, &all).locate(&d).0
        } else {
            CellKind::Face
        };
        Ok(DirectionAnswer {
            direction: d,
            cell,
            dbg,
            moving,
        })
    }

    /// Likely separating directions, most likely first: the coordinate axes, axes of
    /// tessellated cylinders (edge directions shared by many pieces), and normals of
    /// touching planes between different parts; each with both signs.
    pub fn candidates(&self) -> Vec<Vec3> {
        let all: Vec<usize> = (0..self.parts.len()).collect();
        self.candidates_in(&all)
    }

    /// [`DirectionQuery::candidates`] of the subassembly `sub` (global part indices,
    /// increasing): its pieces' edge directions and the touching planes among its parts.
    pub fn candidates_in(&self, sub: &[usize]) -> Vec<Vec3> {
        let mut out: Vec<Vec3> = Vec::new();
        let push = |v: Vec3, out: &mut Vec<Vec3>| {
            let v = v.primitive();
            for s in [v.clone(), v.neg()] {
                if !s.is_zero() && !out.contains(&s) {
                    out.push(s);
                }
            }
        };
        for e in [[0, 0, 1], [1, 0, 0], [0, 1, 0]] {
            push(Vec3::from_i64(e), &mut out);
        }
        let mut count: rustc_hash::FxHashMap<Vec3, usize> = Default::default();
        for p in sub.iter().flat_map(|&k| &self.parts[k].pieces) {
            for e in p.edge_directions() {
                *count.entry(e.clone()).or_default() += 1;
            }
        }
        let mut common: Vec<(usize, Vec3)> = count
            .into_iter()
            .filter(|(_, c)| *c >= 4)
            .map(|(v, c)| (c, v))
            .collect();
        common.sort_by(|a, b| {
            b.0.cmp(&a.0)
                .then_with(|| a.1.to_strings().cmp(&b.1.to_strings()))
        });
        for (_, v) in common.into_iter().take(4) {
            push(v, &mut out);
        }
        // Touching planes: normals of the axes of touching piece pairs (computed lazily:
        // only pairs whose boxes touch or overlap).
        let mut normals: rustc_hash::FxHashMap<Vec3, usize> = Default::default();
        for (li, &i) in sub.iter().enumerate() {
            for &j in &sub[li + 1..] {
                let found: Vec<Vec3> = self
                    .touching_pairs(i, j)
                    .into_par_iter()
                    .with_min_len(64)
                    .filter_map(|k| crate::pairs::touching_normal(self.axes(i, j, k)).cloned())
                    .collect();
                for v in found {
                    *normals.entry(v.primitive()).or_default() += 1;
                }
            }
        }
        let mut normals: Vec<(usize, Vec3)> = normals.into_iter().map(|(v, c)| (c, v)).collect();
        normals.sort_by(|a, b| {
            b.0.cmp(&a.0)
                .then_with(|| a.1.to_strings().cmp(&b.1.to_strings()))
        });
        for (_, v) in normals.into_iter().take(16) {
            push(v, &mut out);
        }
        out
    }

    /// The piece pairs of `{i, j}` whose boxes touch or overlap (a superset, from the
    /// parts' box trees; every pair without them): the only ones that can touch.
    fn touching_pairs(&self, i: usize, j: usize) -> Vec<usize> {
        self.tree_pairs(i, j, &|sum| sum.contains(&[0; 3]))
    }

    /// Angular clearance (radians) at `d` of the moving set `moving` (global indices):
    /// the distance to the nearest direction along which a part of `moving` hits a part
    /// outside it. Groups of piece pairs (node pairs of the parts' box trees) are visited
    /// best first by a lower bound, the angle from `d` to the cone over the box of their
    /// sums ([`box_angle`]); a single pair's bound also uses the hemispheres of its
    /// separating axes. The search stops once the bound exceeds the best distance so far
    /// (within a relative 1e-6), so the value is the true distance (in floating point) or
    /// at most a millionth more.
    pub fn clearance(&self, d: &Vec3, moving: &[usize]) -> Result<f64, PlanError> {
        let rest: Vec<usize> = (0..self.parts.len())
            .filter(|j| !moving.contains(j))
            .collect();
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
        use std::cmp::Reverse;
        use std::collections::BinaryHeap;
        // Bounds are non-negative, so their bit patterns order like the values.
        type Key = Reverse<(u64, usize, usize, bool, usize, usize)>;
        let key = |bound: f64, p, q, flip, na, nb| -> Key {
            Reverse((bound.max(0.0).to_bits(), p, q, flip, na, nb))
        };
        let units = [d.unit_f64(), d.neg().unit_f64()];
        let xs = [d.clone(), d.neg()];
        let mut heap: BinaryHeap<Key> = BinaryHeap::new();
        // Pairs of parts without box trees: each piece pair on its own, bounded by the
        // floating-point box of its sum.
        let mut loose: Vec<(f64, usize, usize, bool, usize)> = Vec::new();
        for i in moving.iter().copied() {
            for j in rest.iter().copied() {
                // Map i -> j is P_ab of the pair (min, max) at d when i < j, at −d else.
                let (p, q, flip) = if i < j { (i, j, false) } else { (j, i, true) };
                let u = &units[usize::from(flip)];
                if let (Some(tp), Some(tq)) = (&self.trees[p], &self.trees[q]) {
                    if let (Some(ra), Some(rb)) = (tp.root(), tq.root()) {
                        let s = sum_box(tp, ra, tq, rb);
                        heap.push(key(box_angle(s.min, s.max, u), p, q, flip, ra, rb));
                    }
                    continue;
                }
                let (fa, fq) = (&self.info[p], &self.info[q]);
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
        let mut best = std::f64::consts::PI;
        // A pair is skipped when its bound is within a relative 1e-6 of the best so far:
        // the value may exceed the true distance by that much, no more. Under a
        // tolerance every pair of a planar contact lies at about the same distance (the
        // contact's great circle), and each would otherwise be summed to shave the last
        // digits.
        let slack = |best: f64| best * (1.0 - 1e-6);
        // One piece pair whose bound is below the best: a tighter bound from its
        // separating axes, then its polygon. Pieces a gap apart (every contact under a
        // tolerance) have boxes that meet, so the box bound is 0 for pairs that the
        // contact's own axis puts far from x.
        let visit = |p: usize, q: usize, flip: bool, k: usize, best: &mut f64| {
            let x = &xs[usize::from(flip)];
            let m = self.parts[q].pieces.len();
            let (a, b) = (&self.parts[p].pieces[k / m], &self.parts[q].pieces[k % m]);
            let boxes = (
                &self.info[p][k / m].float_bounds,
                &self.info[q][k % m].float_bounds,
            );
            if axes_bound(self.axes(p, q, k), (a, b), boxes, x) >= slack(*best) {
                return Ok(());
            }
            let poly = self.polygon(p, q, k)?;
            *best = best.min(distance(poly, x));
            Ok::<(), PlanError>(())
        };
        for (bound, p, q, flip, k) in loose {
            if bound >= slack(best) {
                break;
            }
            visit(p, q, flip, k, &mut best)?;
        }
        while let Some(Reverse((bits, p, q, flip, na, nb))) = heap.pop() {
            if f64::from_bits(bits) >= slack(best) {
                break;
            }
            let (Some(tp), Some(tq)) = (&self.trees[p], &self.trees[q]) else {
                continue;
            };
            match split_pair(tp, na, tq, nb) {
                Some(children) => {
                    for (ca, cb) in children {
                        let s = sum_box(tp, ca, tq, cb);
                        let bound = box_angle(s.min, s.max, &units[usize::from(flip)]);
                        if bound < slack(best) {
                            heap.push(key(bound, p, q, flip, ca, cb));
                        }
                    }
                }
                None => {
                    let m = self.parts[q].pieces.len();
                    for &a in tp.items(na) {
                        for &b in tq.items(nb) {
                            visit(p, q, flip, a as usize * m + b as usize, &mut best)?;
                        }
                    }
                }
            }
        }
        Ok(best)
    }

    /// The first solution of candidate directions ([`DirectionQuery::candidates`]): the
    /// first candidate with a minimal moving set, as a [`Solution`] of the exact kind of
    /// its cell (its direction is the candidate itself; a face solution's clearance is
    /// [`DirectionQuery::clearance`] there). `None` when no candidate separates.
    pub fn first_solution(&self) -> Result<Option<Solution>, PlanError> {
        for d in self.candidates() {
            let ans = self.answer(&d)?;
            if let Some(m) = ans.moving.first() {
                let clearance = if ans.cell == CellKind::Face {
                    self.clearance(&ans.direction, m)?.to_degrees()
                } else {
                    0.0
                };
                return Ok(Some(Solution {
                    cell: ans.cell,
                    unit: ans.direction.unit_f64(),
                    direction: ans.direction,
                    moving: m.clone(),
                    clearance_deg: clearance,
                }));
            }
        }
        Ok(None)
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
fn axes_bound(
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
fn box_angle(lo: [i64; 3], hi: [i64; 3], u: &[f64; 3]) -> f64 {
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

/// How deep inside the box of the sum `b ⊕ −a` (boxes `(lo, hi)` of `a` and `b`) the
/// ray along the unit vector `u` runs: the relative depth (0 to 1/2) of its chord's
/// middle point, least over the axes; 0 when it misses. Floating point, a preference.
fn ray_depth(a: FloatBox, b: FloatBox, u: &[f64; 3]) -> f64 {
    let lo: [f64; 3] = std::array::from_fn(|k| b.0[k] - a.1[k]);
    let hi: [f64; 3] = std::array::from_fn(|k| b.1[k] - a.0[k]);
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for k in 0..3 {
        if u[k] != 0.0 {
            let (p, q) = (lo[k] / u[k], hi[k] / u[k]);
            t0 = t0.max(p.min(q));
            t1 = t1.min(p.max(q));
        }
    }
    if t1 < t0 || !t1.is_finite() {
        return 0.0;
    }
    let t = 0.5 * (t0 + t1);
    (0..3)
        .map(|k| {
            let (w, p) = (hi[k] - lo[k], t * u[k]);
            if w > 0.0 {
                ((p - lo[k]).min(hi[k] - p) / w).max(0.0)
            } else {
                0.0
            }
        })
        .fold(0.5, f64::min)
}

/// The exact blocking graph, minimal moving sets and cell kind at `d`, from per-piece-
/// pair tests only (no arrangement of the whole motion space).
pub fn dbg_along(parts: &[Part], d: &Vec3) -> Result<DirectionAnswer, PlanError> {
    DirectionQuery::new(parts)?.answer(d)
}

/// `partition` with `first`: tries [`DirectionQuery::first_solution`] and falls back to
/// the full computation ([`crate::partition_subset`]) when no candidate separates. The
/// fast path's statistics count only the sums it computed.
pub fn partition_first(parts: &[Part]) -> Result<Partitioning, PlanError> {
    let t = Instant::now();
    let q = DirectionQuery::new(parts)?;
    if let Some(s) = q.first_solution()? {
        let st = q.stats();
        return Ok(Partitioning {
            names: parts.iter().map(|p| p.name.clone()).collect(),
            interlocked: false,
            sets: vec![crate::partition::MovingSet {
                moving: s.moving.clone(),
                counts: match s.cell {
                    crate::CellKind::Face => [1, 0, 0],
                    crate::CellKind::Edge => [0, 1, 0],
                    crate::CellKind::Vertex => [0, 0, 1],
                },
            }],
            solutions: vec![s],
            truncated: false,
            stopped: false,
            stats: Stats {
                pieces: parts.iter().map(|p| p.pieces.len()).sum(),
                sums: st.sums + st.contact_cones,
                seconds: PhaseSeconds {
                    graphs: t.elapsed().as_secs_f64(),
                    ..Default::default()
                },
                ..Default::default()
            },
        });
    }
    let regions = BlockingRegions::compute(parts)?;
    let all: Vec<usize> = (0..parts.len()).collect();
    Ok(crate::partition_subset(
        &regions,
        &all,
        &crate::Options {
            first: true,
            ..Default::default()
        },
    )
    .0)
}

/// A motion found by a planner: a set of parts moving along a direction away from the
/// other parts of a subassembly (`among`; `None`: the whole assembly).
pub type Motion<'a> = (&'a [usize], Option<&'a [usize]>, &'a Vec3);

/// For motions found under a tolerance: whether each also holds for the parts as given,
/// decided exactly from the unshrunk pieces (the moving parts against the others of the
/// subassembly, per-piece-pair tests). A motion that separates parts whose unshrunk
/// pieces overlap never holds. `None` without a tolerance.
pub fn holds_without_tolerance(
    asm: &apart_assembly::Assembly,
    motions: &[Motion],
) -> Result<Option<Vec<bool>>, PlanError> {
    if asm.tolerance.is_none() {
        return Ok(None);
    }
    let mut out = vec![false; motions.len()];
    type Group<'a> = (&'a [usize], Option<&'a [usize]>, Vec<usize>);
    let mut groups: Vec<Group> = Vec::new();
    for (k, (moving, among, _)) in motions.iter().enumerate() {
        match groups
            .iter_mut()
            .find(|(m, a, _)| m == moving && a == among)
        {
            Some((_, _, ks)) => ks.push(k),
            None => groups.push((moving, *among, vec![k])),
        }
    }
    let overlapping = asm
        .tolerance
        .as_ref()
        .map_or(&[][..], |t| &t.overlapping[..]);
    for (moving, among, ks) in groups {
        // A moving part whose interior overlapped a part of the rest before shrinking
        // starts inside it: nothing holds without the tolerance (as the query below would
        // find, after building it).
        let takes_part = |k: usize| among.is_none_or(|a| a.contains(&k));
        if overlapping.iter().any(|&(i, j)| {
            takes_part(i) && takes_part(j) && (moving.contains(&i) != moving.contains(&j))
        }) {
            continue;
        }
        // Two sides, each the union of its parts' unshrunk pieces.
        let mut sides = [Vec::new(), Vec::new()];
        for (k, p) in asm.parts.iter().enumerate() {
            if among.is_some_and(|a| !a.contains(&k)) {
                continue;
            }
            let pieces = if p.unshrunk_pieces.is_empty() {
                &p.pieces
            } else {
                &p.unshrunk_pieces
            };
            sides[usize::from(!moving.contains(&k))].extend(pieces.iter().cloned());
        }
        let [a, b] = sides;
        let two = [Part::from_pieces("moving", a), Part::from_pieces("rest", b)];
        let query = match DirectionQuery::new(&two) {
            Ok(q) => q,
            Err(PlanError::Overlap { .. }) => continue,
            Err(e) => return Err(e),
        };
        for k in ks {
            // The moving side (part 0) moves along d unless it hits the rest (part 1).
            out[k] = match query.hits(0, 1, motions[k].2) {
                Ok(hit) => !hit,
                Err(PlanError::Overlap { .. }) => false,
                Err(e) => return Err(e),
            };
        }
    }
    Ok(Some(out))
}

#[cfg(test)]
mod tests {
    use super::*;
    use apart_kernel::fvec;
    use apart_pieces::Polytope;

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
}
