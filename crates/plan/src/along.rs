//! One direction without the motion-space arrangement, and a quick first solution.
//!
//! [`dbg_along`] answers what `partition --direction` asks: the exact blocking graph at
//! `d`, its minimal moving sets, and the kind of motion-space cell `d` lies in, from
//! per-piece-pair tests only ([`crate::pairs`]): exact separating axes decide most pairs,
//! touching pairs get their contact cone from a small sum of face neighbourhoods, and
//! only the remaining pairs are summed in full, stopping for an ordered pair of parts as
//! soon as one piece pair blocks it. Only pairs of parts whose box of sums the line
//! along `±d` meets are looked at, found in a hierarchy of the parts' boxes, so a query
//! costs what the parts near that line cost, not the square of the part count.
//!
//! The cell kind is local: near `d`, a pair's blocked set is everything when `d` is
//! blocked, and otherwise the union of the piece pairs' polygons whose closure contains
//! `d` (the others lie at a positive distance). So the motion space near `d` is the
//! arrangement of those polygons' sides through `d`, and their tangent cones at `d`
//! decide whether `d` lies in a vertex, an edge or a face of it.

use crate::clearance::{chord2, to_angle, FArc};
use crate::cull::{pairs_where, piece_tree, split_pair, sum_box};
use crate::dbg::Dbg;
use crate::motion_space::CellKind;
use crate::pairs::{
    axes, box_graze_normal, classify, classify_boxes, is_axis_box, open_box_blocks, pair_polygon,
    ray_meets_box, ray_meets_int_box, Axis, FloatBox, PairPolygon, PieceInfo, Sep,
};
use crate::partition::{Partitioning, PhaseSeconds, Solution, Stats};
use crate::regions::{BlockingRegions, Part};
use crate::PlanError;
use apart_kernel::predicates::{det3_sign, dot_sign};
use apart_kernel::{Aabb, Bvh, Sign, Vec3};
use apart_sphere::SphericalPolygon;
use rayon::prelude::*;
use rustc_hash::FxHashMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{OnceLock, PoisonError, RwLock};
use std::time::Instant;

/// The exact answer at one direction.
#[derive(Clone, Debug)]
pub struct DirectionAnswer {
    /// The direction (primitive).
    pub direction: Vec3,
    /// The kind of motion-space cell it lies in (as [`crate::MotionSpace::locate`] says).
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

/// One part pair's piece pairs (`a * |j| + b`), in blocks of at most [`BLOCK`] made when
/// a pair in them is first asked for: two parts of a thousand pieces each make a million
/// pairs, of which a query touches few.
type PairBlocks = Box<[OnceLock<Box<[PairCache]>>]>;

/// Shards of [`PairCaches`]' map (queries run on every thread).
const SHARDS: usize = 16;

/// Chunks of [`Arena`]: chunk `c` holds `64 << c` slots.
const CHUNKS: usize = 40;

/// Slots that never move once made, handed out one at a time: references into them
/// live as long as the arena, whatever is added later.
struct Arena<T> {
    chunks: Vec<OnceLock<Box<[OnceLock<T>]>>>,
    next: AtomicUsize,
}

impl<T> Arena<T> {
    fn new() -> Arena<T> {
        Arena {
            chunks: (0..CHUNKS).map(|_| OnceLock::new()).collect(),
            next: AtomicUsize::new(0),
        }
    }

    /// Slot `k` (its chunk made on first use).
    fn slot(&self, k: usize) -> &OnceLock<T> {
        let c = (k / 64 + 1).ilog2() as usize;
        let start = 64 * ((1 << c) - 1);
        let chunk = self.chunks[c].get_or_init(|| (0..64 << c).map(|_| OnceLock::new()).collect());
        &chunk[k - start]
    }
}

/// The piece-pair caches of the part pairs asked for so far: a map from a part pair to
/// its slot in an arena, filled on demand (memory grows with the pairs a query looks
/// at, not with the square of the part count).
struct PairCaches {
    shards: Vec<RwLock<FxHashMap<(u32, u32), usize>>>,
    slots: Arena<PairBlocks>,
}

impl PairCaches {
    fn new() -> PairCaches {
        PairCaches {
            shards: (0..SHARDS).map(|_| RwLock::default()).collect(),
            slots: Arena::new(),
        }
    }

    /// The blocks of parts `i < j`, if made.
    fn peek(&self, i: usize, j: usize) -> Option<&PairBlocks> {
        let k = self.shards[shard(i, j)]
            .read()
            .unwrap_or_else(PoisonError::into_inner)
            .get(&(i as u32, j as u32))
            .copied()?;
        self.slots.slot(k).get()
    }

    /// The blocks of parts `i < j` with `m` piece pairs, made when first asked for.
    fn get(&self, i: usize, j: usize, m: usize) -> &PairBlocks {
        let key = (i as u32, j as u32);
        let shard = &self.shards[shard(i, j)];
        let found = shard
            .read()
            .unwrap_or_else(PoisonError::into_inner)
            .get(&key)
            .copied();
        let k = found.unwrap_or_else(|| {
            let mut map = shard.write().unwrap_or_else(PoisonError::into_inner);
            *map.entry(key).or_insert_with(|| {
                // The slot is filled before its index is published under the lock.
                let k = self.slots.next.fetch_add(1, Ordering::Relaxed);
                let blocks = (0..m.div_ceil(BLOCK)).map(|_| OnceLock::new()).collect();
                let _ = self.slots.slot(k).set(blocks);
                k
            })
        });
        self.slots
            .slot(k)
            .get()
            .expect("a pair's slot is filled before it is published")
    }
}

/// Whether the line `{t x : t real}` meets the closed box `[lo, hi]`, exactly, for
/// bounds below 2^62 in magnitude and a direction below 2^62 (products in `i128`).
fn line_meets_int_box(lo: [i64; 3], hi: [i64; 3], x: &[i64; 3]) -> bool {
    // In floating point first: each bound of t within a relative 2^-51 of its value,
    // so bounds further apart than a relative 1e-12 decide.
    let (mut low, mut high) = (f64::NEG_INFINITY, f64::INFINITY);
    for k in 0..3 {
        if x[k] == 0 {
            if lo[k] > 0 || hi[k] < 0 {
                return false;
            }
            continue;
        }
        let (l, u) = (lo[k] as f64 / x[k] as f64, hi[k] as f64 / x[k] as f64);
        let (l, u) = if x[k] > 0 { (l, u) } else { (u, l) };
        low = low.max(l);
        high = high.min(u);
    }
    let margin = 1e-12 * (low.abs() + high.abs());
    if low < high - margin {
        return true;
    }
    if low > high + margin {
        return false;
    }
    line_meets_exact(lo.map(i128::from), hi.map(i128::from), x)
}

/// [`line_meets_int_box`] without the float filter.
fn line_meets_exact(lo: [i128; 3], hi: [i128; 3], x: &[i64; 3]) -> bool {
    // The largest lower and smallest upper bound of t, as fractions with positive
    // denominators.
    let mut lower: Option<(i128, i128)> = None;
    let mut upper: Option<(i128, i128)> = None;
    for k in 0..3 {
        let xk = i128::from(x[k]);
        let (l, u, den) = match xk.cmp(&0) {
            std::cmp::Ordering::Equal => {
                if lo[k] > 0 || hi[k] < 0 {
                    return false;
                }
                continue;
            }
            std::cmp::Ordering::Greater => (lo[k], hi[k], xk),
            std::cmp::Ordering::Less => (-hi[k], -lo[k], -xk),
        };
        if lower.is_none_or(|(n, d)| l * d > n * den) {
            lower = Some((l, den));
        }
        if upper.is_none_or(|(n, d)| u * d < n * den) {
            upper = Some((u, den));
        }
    }
    match (lower, upper) {
        (Some((l, dl)), Some((u, du))) => l * du <= u * dl,
        _ => true,
    }
}

/// Node pairs down to which [`self_walk`] forks.
const WALK_PARALLEL_DEPTH: u32 = 6;

/// Calls `leaf(p, q, out)` for every pair of distinct boxes under node `n` of `tree`
/// that lie under two nodes `meets` accepts all the way down (a walk of the hierarchy
/// against itself; `meets(a, b)` must accept boxes holding boxes it accepts, and be
/// symmetric).
fn self_walk<L>(
    tree: &Bvh,
    n: usize,
    depth: u32,
    meets: &(impl Fn(&Aabb, &Aabb) -> bool + Sync),
    leaf: &L,
    out: &mut Vec<(usize, usize)>,
) where
    L: Fn(u32, u32, &mut Vec<(usize, usize)>) + Sync,
{
    match tree.children(n) {
        None => {
            let items = tree.items(n);
            for (k, &p) in items.iter().enumerate() {
                for &q in &items[k + 1..] {
                    leaf(p, q, out);
                }
            }
        }
        Some([a, b]) if depth < WALK_PARALLEL_DEPTH => {
            let ((mut x, y), z) = rayon::join(
                || {
                    rayon::join(
                        || {
                            let mut v = Vec::new();
                            self_walk(tree, a, depth + 1, meets, leaf, &mut v);
                            v
                        },
                        || {
                            let mut v = Vec::new();
                            self_walk(tree, b, depth + 1, meets, leaf, &mut v);
                            v
                        },
                    )
                },
                || {
                    let mut v = Vec::new();
                    cross_walk(tree, [a, b], depth + 1, meets, leaf, &mut v);
                    v
                },
            );
            x.extend(y);
            x.extend(z);
            out.extend(x);
        }
        Some([a, b]) => {
            self_walk(tree, a, depth + 1, meets, leaf, out);
            self_walk(tree, b, depth + 1, meets, leaf, out);
            cross_walk(tree, [a, b], depth + 1, meets, leaf, out);
        }
    }
}

/// [`self_walk`] for the pairs with one box under node `a` and one under node `b`
/// (disjoint subtrees).
fn cross_walk<L>(
    tree: &Bvh,
    [a, b]: [usize; 2],
    depth: u32,
    meets: &(impl Fn(&Aabb, &Aabb) -> bool + Sync),
    leaf: &L,
    out: &mut Vec<(usize, usize)>,
) where
    L: Fn(u32, u32, &mut Vec<(usize, usize)>) + Sync,
{
    if !meets(tree.node_box(a), tree.node_box(b)) {
        return;
    }
    // Split the node with more boxes (a leaf never).
    let split_a = match (tree.children(a), tree.children(b)) {
        (None, None) => {
            for &p in tree.items(a) {
                for &q in tree.items(b) {
                    leaf(p, q, out);
                }
            }
            return;
        }
        (Some(_), None) => true,
        (None, Some(_)) => false,
        (Some(_), Some(_)) => tree.items(a).len() >= tree.items(b).len(),
    };
    let [x, y] = if split_a {
        tree.children(a).map(|[c, d]| [[c, b], [d, b]])
    } else {
        tree.children(b).map(|[c, d]| [[a, c], [a, d]])
    }
    .expect("a node with children");
    if depth < WALK_PARALLEL_DEPTH {
        let (mut v, w) = rayon::join(
            || {
                let mut v = Vec::new();
                cross_walk(tree, x, depth + 1, meets, leaf, &mut v);
                v
            },
            || {
                let mut v = Vec::new();
                cross_walk(tree, y, depth + 1, meets, leaf, &mut v);
                v
            },
        );
        v.extend(w);
        out.extend(v);
    } else {
        cross_walk(tree, x, depth + 1, meets, leaf, out);
        cross_walk(tree, y, depth + 1, meets, leaf, out);
    }
}

/// The sum of two counts (the second added into the first).
fn merge_counts(
    mut a: FxHashMap<Vec3, usize>,
    b: FxHashMap<Vec3, usize>,
) -> FxHashMap<Vec3, usize> {
    for (v, c) in b {
        *a.entry(v).or_default() += c;
    }
    a
}

/// The shard of the pair of parts `i < j`.
fn shard(i: usize, j: usize) -> usize {
    (i.wrapping_mul(0x9E37_79B9) ^ j) % SHARDS
}

/// The exact integer box of a part's pieces (a rational vertex's coordinates rounded
/// outward), or `None` when a bound exceeds 2^60 in magnitude.
fn exact_box(p: &Part) -> Option<Aabb> {
    p.pieces
        .iter()
        .try_fold(Aabb::EMPTY, |b, q| Some(b.union(&q.integer_box()?)))
}

/// A box holding every point of the grid that a part without integer piece boxes may
/// reach: the box of its sum with any other part's box holds the origin, so it meets
/// every ray (piece boxes stay below 2^60 + 3, sums below 2^62).
const EVERYWHERE: Aabb = Aabb {
    min: [-(1 << 61); 3],
    max: [1 << 61; 3],
};

/// Per-direction queries on an assembly's convex pieces, caching every piece pair's
/// separating axes and projection between queries.
pub struct DirectionQuery<'a> {
    parts: &'a [Part],
    info: Vec<Vec<PieceInfo>>,
    /// Which pieces are axis-aligned boxes (a pair of them blocks a direction exactly
    /// when the open ray meets their open box of differences: no polygon needed).
    boxy: Vec<Vec<bool>>,
    /// Each part's box tree over its pieces (`None` when its coordinates are too large
    /// for integer boxes: then every piece pair is visited).
    trees: Vec<Option<Bvh>>,
    /// Each part's box, exact (rounded outward where a cut piece has rational vertices;
    /// [`EVERYWHERE`] without a tree): a pair of parts whose box of sums a ray misses
    /// has no piece pair whose closed projection holds its direction.
    boxes: Vec<Aabb>,
    /// Each part's tree's root box (its piece boxes widened; [`EVERYWHERE`] without a
    /// tree): what the piece trees' walks test first, for the touching pairs and the
    /// clearance search, which follow those walks.
    reach: Vec<Aabb>,
    /// The hierarchy over `reach` (holding `boxes`): the broad phase over parts.
    part_tree: Bvh,
    /// The piece-pair caches of the part pairs asked for so far.
    cache: PairCaches,
    n_axes: AtomicUsize,
    n_cones: AtomicUsize,
    n_sums: AtomicUsize,
}

impl<'a> DirectionQuery<'a> {
    /// Prepares the pieces (bounds and box trees only; everything else on demand).
    pub fn new(parts: &'a [Part]) -> Result<DirectionQuery<'a>, PlanError> {
        for (k, p) in parts.iter().enumerate() {
            if p.pieces.is_empty() {
                return Err(PlanError::NoPieces {
                    part: k,
                    name: p.name.clone(),
                });
            }
        }
        let info = parts
            .par_iter()
            .map(|p| p.pieces.iter().map(PieceInfo::new).collect())
            .collect();
        let boxy = parts
            .par_iter()
            .map(|p| p.pieces.iter().map(is_axis_box).collect())
            .collect();
        let trees: Vec<Option<Bvh>> = parts.par_iter().map(|p| piece_tree(&p.pieces)).collect();
        let reach: Vec<Aabb> = trees
            .iter()
            .map(|t| {
                t.as_ref()
                    .and_then(|t| t.root().map(|r| *t.node_box(r)))
                    .unwrap_or(EVERYWHERE)
            })
            .collect();
        let boxes = parts
            .par_iter()
            .zip(&trees)
            .map(|(p, t)| t.as_ref().and_then(|_| exact_box(p)).unwrap_or(EVERYWHERE))
            .collect();
        let part_tree = Bvh::new(reach.clone());
        Ok(DirectionQuery {
            parts,
            info,
            boxy,
            trees,
            boxes,
            reach,
            part_tree,
            cache: PairCaches::new(),
            n_axes: AtomicUsize::new(0),
            n_cones: AtomicUsize::new(0),
            n_sums: AtomicUsize::new(0),
        })
    }

    /// Work done so far.
    pub fn stats(&self) -> QueryStats {
        // Pairs of pieces of different parts: (Σ p)² − Σ p², halved.
        let (sum, squares) = self.parts.iter().fold((0usize, 0usize), |(s, q), p| {
            let k = p.pieces.len();
            (s + k, q + k * k)
        });
        QueryStats {
            piece_pairs: (sum * sum - squares) / 2,
            axes: self.n_axes.load(Ordering::Relaxed),
            contact_cones: self.n_cones.load(Ordering::Relaxed),
            sums: self.n_sums.load(Ordering::Relaxed),
        }
    }

    /// The pair of parts `i < j` with its piece-pair caches (looked up once for all
    /// the pair's piece pairs).
    fn pair(&self, i: usize, j: usize) -> PairRef<'_> {
        let nb = self.parts[j].pieces.len();
        let m = self.parts[i].pieces.len() * nb;
        PairRef {
            i,
            j,
            nb,
            m,
            blocks: self.cache.get(i, j, m),
        }
    }

    /// The separating axes of piece pair `k`.
    fn axes<'q>(&self, p: PairRef<'q>, k: usize) -> &'q [Axis] {
        let (a, b, i, j) = (k / p.nb, k % p.nb, p.i, p.j);
        p.cell(k).axes.get_or_init(|| {
            self.n_axes.fetch_add(1, Ordering::Relaxed);
            axes(
                &self.parts[i].pieces[a],
                &self.info[i][a],
                &self.parts[j].pieces[b],
                &self.info[j][b],
            )
        })
    }

    /// The closed polygon of piece pair `k` (its Minkowski sum's projection, or its
    /// contact cone).
    fn polygon<'q>(&self, p: PairRef<'q>, k: usize) -> Result<&'q SphericalPolygon, PlanError> {
        let (a, b, i, j) = (k / p.nb, k % p.nb, p.i, p.j);
        let axes = self.axes(p, k);
        let r = p.cell(k).polygon.get_or_init(|| {
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
        if ti.len() == 1 && tj.len() == 1 {
            // One piece each: the roots' test alone.
            return if keep(&sum_box(ti, 1, tj, 1)) {
                vec![0]
            } else {
                Vec::new()
            };
        }
        let mut out: Vec<usize> = pairs_where(ti, tj, &|sum, _| keep(sum), &|_, _| true)
            .into_iter()
            .map(|(a, b)| a * nb + b)
            .collect();
        out.sort_unstable();
        out
    }

    /// The piece pairs among `near` (from [`DirectionQuery::along_ray`]) that `x` does
    /// not put outside their closed projections, with their status: the ray along `x`
    /// meets the box of the pair's sum (exactly), and the axes do not exclude `x`. In
    /// increasing order.
    fn classify_near(&self, p: PairRef<'_>, near: Vec<usize>, x: &Vec3) -> Vec<(usize, Sep)> {
        let (i, j, nb) = (p.i, p.j, p.nb);
        let sep = |k: usize| {
            let (a, b) = (k / nb, k % nb);
            let (pa, pb) = (&self.parts[i].pieces[a], &self.parts[j].pieces[b]);
            if !ray_meets_box(&self.info[i][a], pa.den(), &self.info[j][b], pb.den(), x) {
                return None;
            }
            let s = classify(self.axes(p, k), x);
            (s != Sep::Outside).then_some((k, s))
        };
        if near.len() <= 64 {
            return near.into_iter().filter_map(sep).collect();
        }
        near.into_par_iter()
            .with_min_len(64)
            .filter_map(sep)
            .collect()
    }

    /// What the pairs of boxes among the piece pairs `near` of parts `i < j` say of `x`,
    /// without the pair's caches (each by its open box of differences): `Some(true)`
    /// when one blocks; `Some(false)` when every piece pair is a pair of boxes and none
    /// blocks (or overlaps); else `None`.
    fn boxes_block(&self, i: usize, j: usize, near: &[usize], x: &Vec3) -> Option<bool> {
        let nb = self.parts[j].pieces.len();
        let mut all = true;
        for &k in near {
            let (a, b) = (k / nb, k % nb);
            if !(self.boxy[i][a] && self.boxy[j][b]) {
                all = false;
                continue;
            }
            let (pa, pb) = (&self.parts[i].pieces[a], &self.parts[j].pieces[b]);
            match open_box_blocks(&self.info[i][a], pa.den(), &self.info[j][b], pb.den(), x) {
                Some(true) => return Some(true),
                Some(false) => {}
                None => all = false,
            }
        }
        all.then_some(false)
    }

    /// For a pair of parts at `x` (its smaller part moving along `x`): a piece pair
    /// whose open polygon contains `x` (then `x` is blocked), or `None`. Pairs of boxes
    /// first (by their box of differences), then touching pairs (cheap cones), then the
    /// others (full sums), deepest on the ray first, in growing chunks, stopping at the
    /// first that blocks.
    fn blocker(
        &self,
        p: PairRef<'_>,
        sep: &[(usize, Sep)],
        x: &Vec3,
    ) -> Result<Option<usize>, PlanError> {
        if sep.iter().all(|(_, s)| *s != Sep::Unknown) {
            return Ok(None);
        }
        let (i, j, nb) = (p.i, p.j, p.nb);
        // Pairs of boxes first, each decided by its open box of differences.
        let mut undecided = Vec::new();
        for k in sep
            .iter()
            .filter(|(_, s)| *s == Sep::Unknown)
            .map(|(k, _)| *k)
        {
            let (a, b) = (k / nb, k % nb);
            if self.boxy[i][a] && self.boxy[j][b] {
                let (pa, pb) = (&self.parts[i].pieces[a], &self.parts[j].pieces[b]);
                match open_box_blocks(&self.info[i][a], pa.den(), &self.info[j][b], pb.den(), x) {
                    Some(true) => return Ok(Some(k)),
                    Some(false) => continue,
                    None => {}
                }
            }
            undecided.push(k);
        }
        let (touching, others): (Vec<usize>, Vec<usize>) = undecided
            .into_iter()
            .partition(|&k| self.axes(p, k).iter().any(|a| !a.strict));
        // Pairs whose sum's box the ray crosses nearest its middle first (the likeliest
        // to block), in chunks growing from 2 to 64: the first blocker is often among
        // the first few.
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
        let hit = |k: usize| -> Result<Option<usize>, PlanError> {
            Ok(self.polygon(p, k)?.contains_open(x).then_some(k))
        };
        for chunk in chunks {
            let found = if chunk.len() == 1 {
                hit(chunk[0])?
            } else {
                let hits: Vec<Option<usize>> = chunk
                    .par_iter()
                    .map(|&k| hit(k))
                    .collect::<Result<_, _>>()?;
                hits.into_iter().flatten().next()
            };
            if found.is_some() {
                return Ok(found);
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
        let near = self.along_ray(i, j, &x);
        if let Some(blocked) = self.boxes_block(i, j, &near, &x) {
            return Ok(blocked);
        }
        let p = self.pair(i, j);
        let sep = self.classify_near(p, near, &x);
        Ok(self.blocker(p, &sep, &x)?.is_some())
    }

    /// For a pair of parts at `x = σ d` (its smaller part moving along `x`): whether `x`
    /// is blocked and, when it is not, what the pair adds near `d` to the union of the
    /// tangent cones of the maps free at `d` ([`Cover`]): the cones of the polygons
    /// already made (those the blocking test summed) whose closure holds `x`, and the
    /// piece pairs left ([`Pending`]: `x` on the boundary of a separating axis'
    /// hemisphere, or a pair of boxes not blocking), made only if their cone may add
    /// something. Cones are given in the frame of `d` (normals times `σ`).
    fn near_cones(&self, i: usize, j: usize, x: &Vec3, flip: bool) -> Result<NearCones, PlanError> {
        let near = self.along_ray(i, j, x);
        match self.boxes_block(i, j, &near, x) {
            Some(true) => return Ok((true, Vec::new(), Vec::new())),
            Some(false) => {
                // Pairs of boxes, none blocking: each whose closed polygon may hold x is
                // left to decide (classified by its coordinate axes, which are all its
                // axes), without the pair's caches.
                let nb = self.parts[j].pieces.len();
                let pending = near
                    .into_iter()
                    .filter_map(|k| {
                        let (a, b) = (k / nb, k % nb);
                        let (pa, pb) = (&self.parts[i].pieces[a], &self.parts[j].pieces[b]);
                        let (ia, ib) = (&self.info[i][a], &self.info[j][b]);
                        if !ray_meets_box(ia, pa.den(), ib, pb.den(), x) {
                            return None;
                        }
                        let (s, touching) = classify_boxes(pa, ia, pb, ib, x);
                        (s != Sep::Outside).then_some(Pending {
                            i,
                            j,
                            k,
                            flip,
                            touching,
                        })
                    })
                    .collect();
                return Ok((false, Vec::new(), pending));
            }
            None => {}
        }
        let p = self.pair(i, j);
        let sep = self.classify_near(p, near, x);
        if self.blocker(p, &sep, x)?.is_some() {
            return Ok((true, Vec::new(), Vec::new()));
        }
        let orient = |q: &Vec3| if flip { q.neg() } else { q.clone() };
        let mut cones = Vec::new();
        let mut pending = Vec::new();
        for &(k, s) in &sep {
            if s == Sep::Unknown && p.cell(k).polygon.get().is_some() {
                // Summed by the blocking test (it tries every undecided pair when none
                // blocks, except pairs of boxes).
                let poly = self.polygon(p, k)?;
                if poly.contains_closed(x) {
                    cones.push(active(poly.normals(), x).map(orient).collect());
                }
                continue;
            }
            pending.push(Pending {
                i: p.i,
                j: p.j,
                k,
                flip,
                touching: self.axes(p, k).iter().any(|a| !a.strict),
            });
        }
        Ok((false, cones, pending))
    }

    /// What the parts' exact boxes say of the pair of parts `i < j` at `x` (the smaller
    /// part moving along `x`): nothing near `x` when the ray misses their box of sums
    /// `S`; not blocked, with its tangent cones at `x` inside `{n · y > 0}`, for every
    /// coordinate axis `n` square to `x` along which `S` lies weakly above the origin
    /// (then every piece pair's sum does too); else undecided.
    fn part_level(&self, i: usize, j: usize, x: &Vec3) -> Level {
        let Some(xs) = x.as_small() else {
            return Level::Open;
        };
        let (a, b) = (&self.boxes[i], &self.boxes[j]);
        let lo: [i128; 3] = std::array::from_fn(|k| i128::from(b.min[k] - a.max[k]));
        let hi: [i128; 3] = std::array::from_fn(|k| i128::from(b.max[k] - a.min[k]));
        if !ray_meets_int_box(lo, hi, xs) {
            return Level::Miss;
        }
        let mut mask = 0u8;
        for k in (0..3).filter(|&k| xs[k] == 0) {
            if lo[k] >= 0 {
                mask |= 1 << (2 * k);
            }
            if hi[k] <= 0 {
                mask |= 1 << (2 * k + 1);
            }
        }
        if mask == 0 {
            return Level::Open;
        }
        Level::Free {
            mask,
            touching: (0..3).all(|k| lo[k] <= 0 && 0 <= hi[k]),
        }
    }

    /// The cones an [`Item`] adds to the cover near `d` (none when the cover holds it).
    fn item_cones(
        &self,
        item: &Item,
        d: &Vec3,
        cover: &Cover,
    ) -> Result<Vec<Vec<Vec3>>, PlanError> {
        match item {
            Item::Piece(p) => Ok(self.pending_cone(p, d, cover)?.into_iter().collect()),
            &Item::Pair { i, j, flip, mask } => {
                // The coordinate axes of the parts' boxes, in the frame of d.
                let bound: Vec<Vec3> = (0..6)
                    .filter(|b| mask >> b & 1 == 1)
                    .map(|b| {
                        let mut e = [0i64; 3];
                        e[b / 2] = if (b % 2 == 1) != flip { -1 } else { 1 };
                        Vec3::from_i64(e)
                    })
                    .collect();
                if cover.holds(&bound) {
                    return Ok(Vec::new());
                }
                let x = if flip { d.neg() } else { d.clone() };
                let (blocked, mut cones, pending) = self.near_cones(i, j, &x, flip)?;
                debug_assert!(!blocked, "the parts' boxes leave the pair free");
                for p in &pending {
                    cones.extend(self.pending_cone(p, d, cover)?);
                }
                Ok(cones)
            }
        }
    }

    /// The cone of a [`Pending`] piece pair unless the cover already holds it: `None`
    /// when a cone holding its own lies in the cover (from its axes through the
    /// direction, or, for a pair of boxes, from where the ray grazes their box of
    /// differences), or (for pairs not touching) when the pair lies weakly below along
    /// the normal of one of the cover's half-planes; else the polygon is made, and its
    /// cone returned when its closure holds the direction.
    fn pending_cone(
        &self,
        p: &Pending,
        d: &Vec3,
        cover: &Cover,
    ) -> Result<Option<Vec<Vec3>>, PlanError> {
        let pair = self.pair(p.i, p.j);
        let x = if p.flip { d.neg() } else { d.clone() };
        let orient = |n: &Vec3| if p.flip { n.neg() } else { n.clone() };
        let nb = self.parts[p.j].pieces.len();
        let (a, b) = (p.k / nb, p.k % nb);
        // Free: weakly below along the axes through x, so its cone lies in theirs.
        let mut bound: Vec<Vec3> = self
            .axes(pair, p.k)
            .iter()
            .filter(|a| !a.strict && dot_sign(&a.n, &x) == Sign::Zero)
            .map(|a| orient(&a.n))
            .collect();
        if bound.is_empty() && self.boxy[p.i][a] && self.boxy[p.j][b] {
            // A pair of boxes the ray grazes at an edge or corner of their box of
            // differences.
            let (pa, pb) = (&self.parts[p.i].pieces[a], &self.parts[p.j].pieces[b]);
            let (ia, ib) = (&self.info[p.i][a], &self.info[p.j][b]);
            bound.extend(box_graze_normal(ia, pa.den(), ib, pb.den(), &x).map(|c| orient(&c)));
        }
        if cover.holds(&bound) {
            return Ok(None);
        }
        if !p.touching && !cover.halves.is_empty() {
            // Below along n, the open polygon lies in {n · y > 0}: in the frame of d
            // that half-plane's normal is σ n.
            let h: rustc_hash::FxHashSet<Vec3> = cover
                .halves
                .iter()
                .map(|n| if p.flip { n.neg() } else { n.clone() })
                .collect();
            let (pa, pb) = (&self.parts[p.i].pieces[a], &self.parts[p.j].pieces[b]);
            if crate::pairs::below_along_any(pa, pb, &h) {
                return Ok(None);
            }
        }
        let poly = self.polygon(pair, p.k)?;
        Ok(poly
            .contains_closed(&x)
            .then(|| active(poly.normals(), &x).map(orient).collect()))
    }

    /// The exact blocking graph at `d`, its minimal moving sets and the cell kind.
    pub fn answer(&self, d: &Vec3) -> Result<DirectionAnswer, PlanError> {
        let all: Vec<usize> = (0..self.parts.len()).collect();
        self.answer_in(&all, d)
    }

    /// [`DirectionQuery::answer`] within the subassembly `sub` (global part indices,
    /// increasing): the blocking graph among its parts (vertex `k` of [`Dbg`] stands for
    /// part `sub[k]`), its minimal moving sets in global indices, and the cell kind of `d`
    /// in the subassembly's motion space. Only the pairs of parts whose box of sums the
    /// line along `±d` meets are looked at (found in the part boxes' hierarchy): no other
    /// piece pair has `±d` in its closed projection.
    pub fn answer_in(&self, sub: &[usize], d: &Vec3) -> Result<DirectionAnswer, PlanError> {
        let d = d.primitive();
        let nd = d.neg();
        let n = sub.len();
        let near = self.pairs_along(sub, &d);
        // Each pair's arcs at d, its cones there and what is left to decide near d; in
        // pair order, so that the first error is the one a sequential loop would meet.
        // (A pair that its parts' boxes leave free, most of them, allocates nothing.)
        #[derive(Default)]
        struct Found {
            blocked: [bool; 2],
            free: [Option<(u8, bool)>; 2],
            cones: Vec<Vec<Vec3>>,
            pending: Vec<Pending>,
        }
        let found: Vec<Result<Found, PlanError>> = near
            .par_iter()
            .map(|&(li, lj)| {
                let (i, j) = (sub[li], sub[lj]);
                let mut f = Found::default();
                for (x, flip) in [(&d, false), (&nd, true)] {
                    match self.part_level(i, j, x) {
                        Level::Miss => {}
                        Level::Free { mask, touching } => {
                            f.free[usize::from(flip)] = Some((mask, touching));
                        }
                        Level::Open => {
                            let (b, c, pending) = self.near_cones(i, j, x, flip)?;
                            f.blocked[usize::from(flip)] = b;
                            f.cones.extend(c);
                            f.pending.extend(pending);
                        }
                    }
                }
                Ok(f)
            })
            .collect();
        let mut arcs = Vec::new();
        let mut cover = Cover::new(&d);
        // Touching ones first (contact cones: cheap, and their half-planes hold most
        // others), each in pair order.
        let (mut first, mut later) = (Vec::new(), Vec::new());
        for (&(li, lj), f) in near.iter().zip(found) {
            let f = f?;
            if f.blocked[0] {
                arcs.push((li, lj));
            }
            if f.blocked[1] {
                arcs.push((lj, li));
            }
            for c in &f.cones {
                cover.add(c);
            }
            let (i, j) = (sub[li], sub[lj]);
            for (flip, free) in [false, true].into_iter().zip(f.free) {
                if let Some((mask, touching)) = free {
                    let item = Item::Pair { i, j, flip, mask };
                    if touching { &mut first } else { &mut later }.push(item);
                }
            }
            for p in f.pending {
                if p.touching { &mut first } else { &mut later }.push(Item::Piece(p));
            }
        }
        first.extend(later);
        let items = first;
        // What is left, in chunks growing from 8 to 1024, each tested against the cover
        // so far: once it holds every direction around d, nothing more is made.
        let (mut start, mut size) = (0, 8);
        while start < items.len() && !cover.is_everything() {
            let end = (start + size).min(items.len());
            let cones: Vec<Result<Vec<Vec<Vec3>>, PlanError>> = items[start..end]
                .par_iter()
                .map(|item| self.item_cones(item, &d, &cover))
                .collect();
            for c in cones {
                for c in c? {
                    cover.add(&c);
                }
            }
            (start, size) = (end, (size * 2).min(1024));
        }
        let dbg = Dbg::new(n, arcs);
        let moving = dbg
            .minimal_moving_sets()
            .into_iter()
            .map(|s| s.into_iter().map(|k| sub[k]).collect())
            .collect();
        Ok(DirectionAnswer {
            cell: cover.kind(),
            direction: d,
            dbg,
            moving,
        })
    }

    /// The hierarchy over the widened boxes (`reach`) of the parts `sub` (increasing),
    /// reporting positions in `sub`: the query's own for every part, else one built for
    /// them.
    fn tree_of(&self, sub: &[usize]) -> std::borrow::Cow<'_, Bvh> {
        if sub.len() == self.parts.len() {
            std::borrow::Cow::Borrowed(&self.part_tree)
        } else {
            std::borrow::Cow::Owned(Bvh::new(sub.iter().map(|&k| self.reach[k]).collect()))
        }
    }

    /// The pairs `(li, lj)`, `li < lj`, of positions in `sub` whose parts' box of sums
    /// `box(sub[lj]) ⊕ −box(sub[li])` the line along `d` meets (exactly: any other pair
    /// has no piece pair whose closed projection holds `d` or `−d`), sorted: a walk of
    /// the hierarchy against itself, skipping node pairs whose box of sums the line
    /// misses. Every pair when `d` is too large for machine integers.
    fn pairs_along(&self, sub: &[usize], d: &Vec3) -> Vec<(usize, usize)> {
        let Some(&x) = d.as_small() else {
            return (0..sub.len())
                .flat_map(|li| (li + 1..sub.len()).map(move |lj| (li, lj)))
                .collect();
        };
        let tree = self.tree_of(sub);
        let Some(root) = tree.root() else {
            return Vec::new();
        };
        let meets = |a: &Aabb, b: &Aabb| {
            !a.is_empty() && !b.is_empty() && {
                let lo = std::array::from_fn(|k| b.min[k] - a.max[k]);
                let hi = std::array::from_fn(|k| b.max[k] - a.min[k]);
                line_meets_int_box(lo, hi, &x)
            }
        };
        // The hierarchy's boxes hold the exact ones: it is walked with them, and each
        // pair found is tested with its own.
        let leaf = |li: u32, lj: u32, out: &mut Vec<(usize, usize)>| {
            let (li, lj) = (li.min(lj) as usize, li.max(lj) as usize);
            if meets(&self.boxes[sub[li]], &self.boxes[sub[lj]]) {
                out.push((li, lj));
            }
        };
        let mut out = Vec::new();
        self_walk(&tree, root, 0, &meets, &leaf, &mut out);
        out.sort_unstable();
        out
    }

    /// The pairs `(li, lj)`, `li < lj`, of positions in `sub` whose parts' widened boxes
    /// touch or overlap (the piece trees' walks for touching pairs start there), sorted.
    fn pairs_touching(&self, sub: &[usize]) -> Vec<(usize, usize)> {
        let tree = self.tree_of(sub);
        let mut out: Vec<(usize, usize)> = tree.self_pairs(
            Vec::new,
            |v: &mut Vec<(usize, usize)>, a, b| v.push((a as usize, b as usize)),
            |mut a, b| {
                a.extend(b);
                a
            },
        );
        out.sort_unstable();
        out
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
        let normals = self.touching_counts(sub);
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

    /// The first touching axis of piece pair `k` of parts `i < j` (primitive), from its
    /// cached axes, else from axes computed and not kept (the coordinate ones alone when
    /// they answer): most pairs whose boxes touch are never asked for again.
    fn touching_normal(&self, i: usize, j: usize, k: usize) -> Option<Vec3> {
        let cached = self.cache.peek(i, j).and_then(|blocks| {
            let block = blocks[k / BLOCK].get()?;
            block[k % BLOCK].axes.get()
        });
        let n = match cached {
            Some(axes) => crate::pairs::touching_normal(axes).cloned(),
            None => {
                let nb = self.parts[j].pieces.len();
                let (a, b) = (k / nb, k % nb);
                self.n_axes.fetch_add(1, Ordering::Relaxed);
                crate::pairs::first_touching_axis(
                    &self.parts[i].pieces[a],
                    &self.info[i][a],
                    &self.parts[j].pieces[b],
                    &self.info[j][b],
                )
            }
        };
        n.map(|n| n.primitive())
    }

    /// How many touching piece pairs of the parts `sub` have each touching normal
    /// (primitive): computed lazily, only for pairs of parts whose boxes touch or
    /// overlap, and in them only piece pairs whose boxes do. The counts do not depend
    /// on the order of the pairs.
    fn touching_counts(&self, sub: &[usize]) -> FxHashMap<Vec3, usize> {
        type Counts = FxHashMap<Vec3, usize>;
        let count = |mut m: Counts, v: Vec3| {
            *m.entry(v).or_default() += 1;
            m
        };
        let merge = |a: Counts, b: Counts| {
            if a.len() >= b.len() {
                merge_counts(a, b)
            } else {
                merge_counts(b, a)
            }
        };
        self.pairs_touching(sub)
            .into_par_iter()
            .with_min_len(64)
            .fold(Counts::default, |m, (li, lj)| {
                let (i, j) = (sub[li], sub[lj]);
                let ks = self.touching_pairs(i, j);
                if ks.len() <= 64 {
                    ks.into_iter()
                        .filter_map(|k| self.touching_normal(i, j, k))
                        .fold(m, count)
                } else {
                    // Many piece pairs (large parts, few of them): in parallel.
                    let found: Counts = ks
                        .into_par_iter()
                        .with_min_len(64)
                        .filter_map(|k| self.touching_normal(i, j, k))
                        .fold(Counts::default, count)
                        .reduce(Counts::default, merge);
                    merge(m, found)
                }
            })
            .reduce(Counts::default, merge)
    }

    /// The piece pairs of `{i, j}` whose boxes touch or overlap (a superset, from the
    /// parts' box trees; every pair without them): the only ones that can touch.
    fn touching_pairs(&self, i: usize, j: usize) -> Vec<usize> {
        self.tree_pairs(i, j, &|sum| sum.contains(&[0; 3]))
    }

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
        use std::cmp::Reverse;
        use std::collections::BinaryHeap;
        // Bounds are non-negative, so their bit patterns order like the values. A group
        // of part pairs (kind 0: moving part `p` against the staying parts under node `q`
        // of their hierarchy) comes before the piece-pair groups (kind 1) of equal bound.
        type Key = Reverse<(u64, u8, usize, usize, bool, usize, usize)>;
        let key = |bound: f64, p, q, flip, na, nb| -> Key {
            Reverse((bound.max(0.0).to_bits(), 1, p, q, flip, na, nb))
        };
        let group = |bound: f64, p, node| -> Key {
            Reverse((bound.max(0.0).to_bits(), 0, p, node, false, 0, 0))
        };
        let units = [d.unit_f64(), d.neg().unit_f64()];
        let xs = [d.clone(), d.neg()];
        let mut heap: BinaryHeap<Key> = BinaryHeap::new();
        // Pairs of parts without box trees: each piece pair on its own, bounded by the
        // floating-point box of its sum.
        let mut loose: Vec<(f64, usize, usize, bool, usize)> = Vec::new();
        let treed: Vec<usize> = rest
            .iter()
            .copied()
            .filter(|&j| self.trees[j].is_some())
            .collect();
        let untreed: Vec<usize> = rest
            .iter()
            .copied()
            .filter(|&j| self.trees[j].is_none())
            .collect();
        // The staying parts with box trees, in a hierarchy of their boxes.
        let staying = Bvh::new(treed.iter().map(|&j| self.reach[j]).collect());
        // The bound of moving part `i` against the staying parts under `node`: the angle
        // to the box of their sums with `i`'s, less a margin far above its rounding, so
        // that it is below the bound of every pair under it (then the pairs are visited
        // in the order, and with the stop, of a search seeded with all of them).
        let group_bound = |i: usize, node: usize| {
            let (a, b) = (&self.reach[i], staying.node_box(node));
            let lo = std::array::from_fn(|k| b.min[k] - a.max[k]);
            let hi = std::array::from_fn(|k| b.max[k] - a.min[k]);
            box_angle(lo, hi, &units[0]) - 1e-6
        };
        for i in moving.iter().copied() {
            let against: &[usize] = if self.trees[i].is_some() {
                if let Some(root) = staying.root() {
                    heap.push(group(group_bound(i, root), i, root));
                }
                &untreed
            } else {
                rest
            };
            for j in against.iter().copied() {
                // Map i -> j is P_ab of the pair (min, max) at d when i < j, at −d else.
                let (p, q, flip) = if i < j { (i, j, false) } else { (j, i, true) };
                let u = &units[usize::from(flip)];
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
        // The order of the loop over every pair (moving, staying), kept on ties.
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
            let pair = self.pair(p, q);
            if axes_bound(self.axes(pair, k), (a, b), boxes, x) >= slack(*best) {
                return Ok(());
            }
            let poly = self.polygon(pair, k)?;
            *best = best.min(distance(poly, x));
            Ok::<(), PlanError>(())
        };
        for (bound, p, q, flip, k) in loose {
            if bound >= slack(best) {
                break;
            }
            visit(p, q, flip, k, &mut best)?;
        }
        while let Some(Reverse((bits, kind, p, q, flip, na, nb))) = heap.pop() {
            if f64::from_bits(bits) >= slack(best) {
                break;
            }
            if kind == 0 {
                // Moving part p against the staying parts under node q.
                match staying.children(q) {
                    Some(children) => {
                        for c in children {
                            if staying.node_box(c).is_empty() {
                                continue;
                            }
                            let bound = group_bound(p, c);
                            if bound < slack(best) {
                                heap.push(group(bound, p, c));
                            }
                        }
                    }
                    None => {
                        for &s in staying.items(q) {
                            let j = treed[s as usize];
                            let (p, q, flip) = if p < j { (p, j, false) } else { (j, p, true) };
                            let (Some(tp), Some(tq)) = (&self.trees[p], &self.trees[q]) else {
                                continue;
                            };
                            if let (Some(ra), Some(rb)) = (tp.root(), tq.root()) {
                                let s = sum_box(tp, ra, tq, rb);
                                let bound = box_angle(s.min, s.max, &units[usize::from(flip)]);
                                if bound < slack(best) {
                                    heap.push(key(bound, p, q, flip, ra, rb));
                                }
                            }
                        }
                    }
                }
                continue;
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

/// A piece pair `k` of parts `i < j` that a direction does not enter but whose closed
/// polygon may hold it (on the boundary of a separating axis' hemisphere, or a pair of
/// boxes), whose polygon is made only when needed.
struct Pending {
    i: usize,
    j: usize,
    k: usize,
    /// At `−d` (the pair's cone is then given with negated normals).
    flip: bool,
    /// Some axis is not strict (the pieces may touch).
    touching: bool,
}

impl<'q> PairRef<'q> {
    /// The cache of piece pair `k`.
    fn cell(self, k: usize) -> &'q PairCache {
        let start = k / BLOCK * BLOCK;
        let block = self.blocks[k / BLOCK].get_or_init(|| {
            (start..self.m.min(start + BLOCK))
                .map(|_| PairCache::default())
                .collect()
        });
        &block[k - start]
    }
}

/// What the parts' boxes say of a pair of parts at a direction ([`DirectionQuery::part_level`]).
enum Level {
    /// No piece pair's closed polygon holds it.
    Miss,
    /// Free, with every tangent cone inside the half-planes of the coordinate axes in
    /// `mask` (bit `2k`: `+e_k`, bit `2k + 1`: `−e_k`); `touching`: the boxes meet.
    Free { mask: u8, touching: bool },
    /// Undecided: the piece pairs are asked.
    Open,
}

/// What is left to decide near `d` after the blocking tests: a piece pair, or a pair
/// of parts free at `±d` by their boxes (its piece pairs asked only if its bound may
/// add something to the cover).
enum Item {
    Piece(Pending),
    Pair {
        i: usize,
        j: usize,
        flip: bool,
        mask: u8,
    },
}

/// What [`DirectionQuery::near_cones`] finds of a pair of parts at a direction: whether
/// it is blocked, the cones it adds, and its piece pairs left to decide.
type NearCones = (bool, Vec<Vec<Vec3>>, Vec<Pending>);

/// A pair of parts `i < j` (`nb` pieces in `j`, `m` piece pairs) and its piece-pair
/// caches.
#[derive(Clone, Copy)]
struct PairRef<'q> {
    i: usize,
    j: usize,
    nb: usize,
    m: usize,
    blocks: &'q PairBlocks,
}

/// The normals of `normals` square to `x` (the sides of a polygon through `x`).
fn active<'n>(normals: &'n [Vec3], x: &'n Vec3) -> impl Iterator<Item = &'n Vec3> + 'n {
    normals.iter().filter(move |q| dot_sign(q, x) == Sign::Zero)
}

/// Orders directions `s`, `t` (square to `d`, not zero) by their counter-clockwise angle
/// around `d` from `r`, in `[0, 2π)`: the half turn from `r`, then the one from `−r`, in
/// each a direction before those counter-clockwise from it.
fn around(d: &Vec3, r: &Vec3, s: &Vec3, t: &Vec3) -> std::cmp::Ordering {
    use std::cmp::Ordering::{Equal, Greater, Less};
    let half = |v: &Vec3| match det3_sign(d, r, v) {
        Sign::Positive => 0,
        Sign::Negative => 1,
        Sign::Zero => usize::from(dot_sign(r, v) != Sign::Positive),
    };
    half(s)
        .cmp(&half(t))
        .then_with(|| match det3_sign(d, s, t) {
            Sign::Positive => Less,
            Sign::Negative => Greater,
            Sign::Zero => Equal,
        })
}

/// A direction strictly inside the open sector from ray `a` counter-clockwise to ray `b`
/// around `d` (at most a half turn): their sum, or the perpendicular on that side for
/// a half turn.
fn inside(d: &Vec3, a: &Vec3, b: &Vec3) -> Vec3 {
    match det3_sign(d, a, b) {
        Sign::Positive => a.add(b),
        _ => d.cross(a),
    }
}

/// True when `y` lies in the open cone `{y : c · y > 0 for every c}`.
fn in_cone(cone: &[Vec3], y: &Vec3) -> bool {
    cone.iter().all(|c| dot_sign(c, y) == Sign::Positive)
}

/// The union of open tangent cones at `d` of the maps free at `d`, and with it the kind
/// of motion-space cell `d` lies in. The other maps (blocked at `d`, or with no polygon
/// whose closure holds `d`) keep their status all around `d`, so only these decide
/// which statuses near `d` equal `d`'s (all of them free). Near `d` the motion space is
/// the arrangement of the cones' side lines through `d` (each a pair of rays): `d` is in
/// a face when a sector between consecutive rays is outside the union (a face beside
/// `d` has its status), else on an edge when a ray is (an arc from `d` with its status,
/// and no such face), else a vertex: what [`crate::MotionSpace::locate`] finds in the
/// overlay of the pairs' regions (a line that is no arc of the overlay has the status
/// of the sectors on both sides, so it decides nothing), without building it.
///
/// Kept as the rays around `d` (primitive, square to `d`) counter-clockwise from the
/// first, each with whether the union holds it and the open sector after it: a cone
/// added splits the sectors its rays fall in (the pieces inherit their sector's
/// status, as the earlier cones' sides are elsewhere) and covers what it holds.
struct Cover {
    d: Vec3,
    rays: Vec<(Vec3, bool, bool)>,
    /// Normals of the half-planes in the union.
    halves: rustc_hash::FxHashSet<Vec3>,
}

impl Cover {
    fn new(d: &Vec3) -> Cover {
        Cover {
            d: d.clone(),
            rays: Vec::new(),
            halves: Default::default(),
        }
    }

    /// The open sector after ray `k`, as a direction inside it.
    fn sector(&self, k: usize) -> Vec3 {
        let b = &self.rays[(k + 1) % self.rays.len()].0;
        inside(&self.d, &self.rays[k].0, b)
    }

    /// True when the union holds every direction around `d`.
    fn is_everything(&self) -> bool {
        !self.rays.is_empty() && self.rays.iter().all(|&(_, r, s)| r && s)
    }

    /// The kind of cell `d` lies in.
    fn kind(&self) -> CellKind {
        if self.rays.is_empty() || self.rays.iter().any(|r| !r.2) {
            CellKind::Face
        } else if self.rays.iter().any(|r| !r.1) {
            CellKind::Edge
        } else {
            CellKind::Vertex
        }
    }

    /// Adds the open cone of the normals `cone` (each square to `d`).
    fn add(&mut self, cone: &[Vec3]) {
        for c in cone {
            let t = c.cross(&self.d).primitive();
            for r in [t.neg(), t] {
                if self.rays.iter().any(|(q, _, _)| *q == r) {
                    continue;
                }
                let Some(r0) = self.rays.first().map(|q| q.0.clone()) else {
                    self.rays.push((r, false, false));
                    continue;
                };
                let at = self.rays[1..]
                    .iter()
                    .position(|(q, _, _)| around(&self.d, &r0, &r, q).is_lt())
                    .map_or(self.rays.len(), |p| p + 1);
                let status = self.rays[at - 1].2;
                self.rays.insert(at, (r, status, status));
            }
        }
        for k in 0..self.rays.len() {
            if !self.rays[k].1 && in_cone(cone, &self.rays[k].0) {
                self.rays[k].1 = true;
            }
            if !self.rays[k].2 && in_cone(cone, &self.sector(k)) {
                self.rays[k].2 = true;
            }
        }
        if let [c] = cone {
            self.halves.insert(c.primitive());
        }
    }

    /// True when the union holds the open cone of the normals `cone` (each square to
    /// `d`; none: every direction): no ray or sector outside the union meets it. A
    /// sector is cut by the cone's rays inside it into pieces each inside the cone or
    /// outside.
    fn holds(&self, cone: &[Vec3]) -> bool {
        if self.rays.is_empty() {
            return false;
        }
        let n = self.rays.len();
        (0..n).all(|k| {
            let (a, ray, sector) = (&self.rays[k].0, self.rays[k].1, self.rays[k].2);
            if !ray && in_cone(cone, a) {
                return false;
            }
            if sector {
                return true;
            }
            let b = &self.rays[(k + 1) % n].0;
            let mut cuts: Vec<Vec3> = cone
                .iter()
                .flat_map(|c| {
                    let t = c.cross(&self.d).primitive();
                    [t.neg(), t]
                })
                .filter(|t| t != a && around(&self.d, a, t, b).is_lt())
                .collect();
            cuts.sort_by(|s, t| around(&self.d, a, s, t));
            cuts.dedup();
            let mut from = a;
            for to in cuts.iter().chain([b]) {
                if in_cone(cone, &inside(&self.d, from, to)) {
                    return false;
                }
                from = to;
            }
            true
        })
    }
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
    // The motions by their (moving set, subassembly), in the order first met.
    type Key<'a> = (&'a [usize], Option<&'a [usize]>);
    let mut index: FxHashMap<Key, usize> = FxHashMap::default();
    let mut groups: Vec<(Key, Vec<usize>)> = Vec::new();
    for (k, (moving, among, _)) in motions.iter().enumerate() {
        let key = (*moving, *among);
        let g = *index.entry(key).or_insert_with(|| {
            groups.push((key, Vec::new()));
            groups.len() - 1
        });
        groups[g].1.push(k);
    }
    let overlapping = asm
        .tolerance
        .as_ref()
        .map_or(&[][..], |t| &t.overlapping[..]);
    // Each part's side in the group at hand: 0 not in its subassembly, 1 moving, 2
    // staying (reset after each group).
    let mut side = vec![0u8; asm.parts.len()];
    for ((moving, among), ks) in groups {
        let mut members: Vec<usize> =
            among.map_or_else(|| (0..asm.parts.len()).collect(), <[usize]>::to_vec);
        members.sort_unstable();
        members.dedup();
        for &k in &members {
            side[k] = 2;
        }
        for &k in moving {
            if side[k] == 2 {
                side[k] = 1;
            }
        }
        // A moving part whose interior overlapped a part of the rest before shrinking
        // starts inside it: nothing holds without the tolerance (as the query below would
        // find, after building it).
        let starts_inside = overlapping
            .iter()
            .any(|&(i, j)| side[i] != 0 && side[j] != 0 && side[i] != side[j]);
        // Two sides, each the union of its parts' unshrunk pieces.
        let mut sides = [Vec::new(), Vec::new()];
        if !starts_inside {
            for &k in &members {
                let p = &asm.parts[k];
                let pieces = if p.unshrunk_pieces.is_empty() {
                    &p.pieces
                } else {
                    &p.unshrunk_pieces
                };
                sides[usize::from(side[k] == 2)].extend(pieces.iter().cloned());
            }
        }
        for &k in &members {
            side[k] = 0;
        }
        if starts_inside {
            continue;
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
}
