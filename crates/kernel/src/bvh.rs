//! The broad phase of every geometric search (self-intersection, point location, part
//! against part, piece against piece): which boxes meet.
//!
//! [`Bvh`] is a bounding-volume hierarchy. Boxes are ordered along a Morton (Z-order)
//! curve of their centres, grouped into leaves of a few boxes, and a complete binary
//! tree is built over the leaves in heap layout (node `i` has children `2i` and
//! `2i + 1`): a parallel sort plus a linear pass. Or the tree is that of recursive
//! median splits ([`Bvh::by_median_splits`], [`Bvh::by_median_splits_with_leaf`]),
//! whose shape callers may walk themselves ([`Bvh::root`], [`Bvh::children`],
//! [`Bvh::node_box`], [`Bvh::items`]). A query walks the tree with an explicit stack
//! and reports boxes in the build's order.
//!
//! [`sweep_pairs`] and [`sweep_pairs_between`] do the same job by sort and sweep along
//! x, for small sets whose pairs must come in the order along x (the order in which a
//! caller builds its output).

use crate::aabb::{Aabb, Coord};
use rayon::prelude::*;
use std::ops::ControlFlow;

const LEAF: usize = 4;

/// A hierarchy over a list of boxes, answering "which boxes meet this box".
#[derive(Clone, Debug)]
pub struct Bvh<T: Coord = i64> {
    boxes: Vec<Aabb<T>>,
    /// Box indices in the build's order; every node's boxes are a range of it.
    order: Vec<u32>,
    /// Node boxes by node index (index 0 unused, the root is 1).
    nodes: Vec<Aabb<T>>,
    /// Each node's boxes: `order[start..end]`.
    spans: Vec<[u32; 2]>,
    /// Each node's children, the one whose boxes come first in `order` first (`[0, 0]`
    /// for a leaf: node 0 is never a child).
    kids: Vec<[u32; 2]>,
}

/// Spreads the low 10 bits of `v` to every third bit.
fn spread(v: u64) -> u64 {
    let mut x = v & 0x3ff;
    x = (x | x << 16) & 0x0300_00ff;
    x = (x | x << 8) & 0x0300_f00f;
    x = (x | x << 4) & 0x030c_30c3;
    x = (x | x << 2) & 0x0924_9249;
    x
}

impl<T: Coord> Default for Bvh<T> {
    /// The hierarchy of no boxes.
    fn default() -> Bvh<T> {
        Bvh::from_order(Vec::new(), Vec::new())
    }
}

/// Groups of at most this many boxes are not split further by [`Bvh::by_median_splits`].
const MEDIAN_LEAF: usize = 4;

/// Adds to `bvh` the node of the boxes `items` (at `order[start..]`) and, unless there
/// are at most `leaf` of them, its children: the boxes split at the median of their
/// centres along the longest axis of their bounds (the last of equally long ones; `len/2`
/// below, the rest above), the upper half first in `order` and in the node's children.
/// Nodes are numbered in preorder with the lower half's subtree first. Returns the node.
fn median_node<T: Coord>(bvh: &mut Bvh<T>, items: &mut [u32], start: usize, leaf: usize) -> u32 {
    let boxes = &bvh.boxes;
    let b = items[1..].iter().fold(boxes[items[0] as usize], |b, &k| {
        b.union(&boxes[k as usize])
    });
    let id = bvh.nodes.len() as u32;
    bvh.nodes.push(b);
    bvh.spans.push([start as u32, (start + items.len()) as u32]);
    bvh.kids.push([0, 0]);
    if items.len() <= leaf {
        return id;
    }
    let axis = (0..3)
        .max_by(|&i, &j| T::cmp_differences(b.max[i], b.min[i], b.max[j], b.min[j]))
        .expect("three axes");
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |&x, &y| {
        let (x, y) = (&boxes[x as usize], &boxes[y as usize]);
        T::cmp_sums(x.min[axis], x.max[axis], y.min[axis], y.max[axis])
    });
    // The upper half first (each half keeps its arrangement, so its own splits are
    // those of the half left in place).
    items.rotate_left(mid);
    let upper_len = items.len() - mid;
    let (upper, lower) = items.split_at_mut(upper_len);
    let low = median_node(bvh, lower, start + upper_len, leaf);
    let up = median_node(bvh, upper, start, leaf);
    bvh.kids[id as usize] = [up, low];
    id
}

impl<T: Coord> Bvh<T> {
    /// Builds the hierarchy over `boxes` (their indices are what queries report).
    pub fn new(boxes: Vec<Aabb<T>>) -> Bvh<T> {
        let all = boxes.iter().fold(Aabb::EMPTY, |a, b| a.union(b));
        // Centres quantised to 10 bits per axis (in floating point: the order only
        // affects speed, never results).
        let lo = all.min.map(T::to_f64);
        let scale: [f64; 3] =
            [0, 1, 2].map(|k| 1023.0 / (2.0 * ((all.max[k].to_f64() - lo[k]).max(1.0))));
        let mut keys: Vec<u64> = boxes
            .par_iter()
            .enumerate()
            .with_min_len(8192)
            .map(|(i, b)| {
                let mut code = 0u64;
                for k in 0..3 {
                    let c = b.min[k].to_f64() + b.max[k].to_f64() - 2.0 * lo[k];
                    let q = (c * scale[k]).clamp(0.0, 1023.0) as u64;
                    code |= spread(q) << k;
                }
                code << 32 | i as u64
            })
            .collect();
        keys.par_sort_unstable();
        let order: Vec<u32> = keys.iter().map(|k| *k as u32).collect();
        drop(keys);
        Bvh::from_order(boxes, order)
    }

    /// Builds the hierarchy of recursive median splits along the longest axis over
    /// `boxes`, down to groups of at most 4, instead of the Morton curve (sequential; for
    /// a few hundred boxes rebuilt often). Queries report boxes in that order, upper
    /// halves first: the order in which placement has always met its fixed pieces, which
    /// its cell decomposition (and so its counters) follows.
    pub fn by_median_splits(boxes: Vec<Aabb<T>>) -> Bvh<T> {
        Bvh::by_median_splits_with_leaf(boxes, MEDIAN_LEAF)
    }

    /// [`Bvh::by_median_splits`] down to groups of at most `leaf` boxes (at least 1):
    /// a node of more is split at the median of its boxes' centres along the longest
    /// axis of its box (the last of equally long ones, compared exactly for integers),
    /// `len / 2` boxes in the lower half and the rest in the upper, which comes first.
    /// Nodes are numbered in preorder, the lower half's subtree first.
    pub fn by_median_splits_with_leaf(boxes: Vec<Aabb<T>>, leaf: usize) -> Bvh<T> {
        let n = boxes.len();
        let mut bvh = Bvh {
            boxes,
            order: (0..n as u32).collect(),
            nodes: vec![Aabb::EMPTY],
            spans: vec![[0, 0]],
            kids: vec![[0, 0]],
        };
        if n > 0 {
            let mut items = std::mem::take(&mut bvh.order);
            median_node(&mut bvh, &mut items, 0, leaf.max(1));
            bvh.order = items;
        }
        bvh
    }

    /// The hierarchy over `boxes` grouped into leaves along `order`, in heap layout.
    fn from_order(boxes: Vec<Aabb<T>>, order: Vec<u32>) -> Bvh<T> {
        let n = boxes.len();
        let leaves = n.div_ceil(LEAF).max(1).next_power_of_two();
        let mut nodes = vec![Aabb::EMPTY; 2 * leaves];
        nodes[leaves..]
            .par_iter_mut()
            .enumerate()
            .with_min_len(1024)
            .for_each(|(l, node)| {
                for &p in order.iter().skip(l * LEAF).take(LEAF) {
                    *node = node.union(&boxes[p as usize]);
                }
            });
        for i in (1..leaves).rev() {
            nodes[i] = nodes[2 * i].union(&nodes[2 * i + 1]);
        }
        let mut spans = vec![[0u32; 2]; 2 * leaves];
        for (l, span) in spans[leaves..].iter_mut().enumerate() {
            *span = [(l * LEAF).min(n) as u32, ((l + 1) * LEAF).min(n) as u32];
        }
        for i in (1..leaves).rev() {
            spans[i] = [spans[2 * i][0], spans[2 * i + 1][1]];
        }
        let mut kids = vec![[0u32; 2]; 2 * leaves];
        for (i, k) in kids.iter_mut().enumerate().take(leaves).skip(1) {
            *k = [2 * i as u32, 2 * i as u32 + 1];
        }
        Bvh {
            boxes,
            order,
            nodes,
            spans,
            kids,
        }
    }

    /// The boxes, by index.
    pub fn boxes(&self) -> &[Aabb<T>] {
        &self.boxes
    }

    /// Number of boxes.
    pub fn len(&self) -> usize {
        self.boxes.len()
    }

    /// True when there are no boxes.
    pub fn is_empty(&self) -> bool {
        self.boxes.is_empty()
    }

    /// Visits every unordered pair of distinct boxes `(i, j)`, `i < j`, that meet,
    /// traversing the tree against itself (in parallel near the root). Each visit
    /// updates an accumulator of the thread that made it; the accumulators are merged.
    pub fn self_pairs<A: Send>(
        &self,
        init: impl Fn() -> A + Sync,
        visit: impl Fn(&mut A, u32, u32) + Sync,
        merge: impl Fn(A, A) -> A + Sync,
    ) -> A {
        self.self_pairs_pruned(init, visit, merge, |_, _| false)
    }

    /// [`Bvh::self_pairs`], skipping every pair with one box under node `x` and the
    /// other under node `y` when `prune(x, y)` (`x == y`: pairs within the subtree of
    /// `x`). Nodes are numbered as in [`Bvh::node_labels`].
    pub fn self_pairs_pruned<A: Send>(
        &self,
        init: impl Fn() -> A + Sync,
        visit: impl Fn(&mut A, u32, u32) + Sync,
        merge: impl Fn(A, A) -> A + Sync,
        prune: impl Fn(usize, usize) -> bool + Sync,
    ) -> A {
        if self.boxes.is_empty() {
            return init();
        }
        let ctx = PairCtx {
            bvh: self,
            _acc: std::marker::PhantomData,
            init: &init,
            visit: &visit,
            merge: &merge,
            prune: &prune,
        };
        ctx.within(1, 0)
    }

    /// A label for every node (by node index: the root is 1, every child has a larger
    /// index than its parent; index 0 is unused and gets `empty`): `leaf` of the boxes
    /// of each leaf (`empty` for a leaf without any), `join` of the children for inner
    /// nodes.
    pub fn node_labels<L: Clone + Send + Sync>(
        &self,
        leaf: impl Fn(&[u32]) -> L + Sync,
        join: impl Fn(&L, &L) -> L,
        empty: L,
    ) -> Vec<L> {
        let mut labels = vec![empty.clone(); self.nodes.len()];
        labels
            .par_iter_mut()
            .enumerate()
            .skip(1)
            .with_min_len(1024)
            .for_each(|(i, label)| {
                let prims = self.items(i);
                if self.is_leaf(i) && !prims.is_empty() {
                    *label = leaf(prims);
                }
            });
        for i in (1..self.nodes.len()).rev() {
            if let Some([x, y]) = self.children(i) {
                labels[i] = join(&labels[x], &labels[y]);
            }
        }
        labels
    }

    /// The root node, or `None` for no boxes.
    #[inline]
    pub fn root(&self) -> Option<usize> {
        (!self.boxes.is_empty()).then_some(1)
    }

    /// The two children of node `n`, the one whose boxes come first in the build's order
    /// first (`None` for a leaf).
    #[inline]
    pub fn children(&self, n: usize) -> Option<[usize; 2]> {
        let [x, y] = self.kids[n];
        (x != 0).then_some([x as usize, y as usize])
    }

    /// True when node `n` has no children.
    #[inline]
    fn is_leaf(&self, n: usize) -> bool {
        self.kids[n][0] == 0
    }

    /// The box of node `n`: the smallest holding every box under it.
    #[inline]
    pub fn node_box(&self, n: usize) -> &Aabb<T> {
        &self.nodes[n]
    }

    /// The indices of the boxes under node `n`, in the build's order.
    #[inline]
    pub fn items(&self, n: usize) -> &[u32] {
        let [lo, hi] = self.spans[n];
        &self.order[lo as usize..hi as usize]
    }

    /// The positions in the build's order of the boxes under node `n` (what
    /// [`Bvh::items`] lists): nested for a node and its children, so that a caller can
    /// keep per-position data (counts of boxes still alive) in a range tree.
    #[inline]
    pub fn span(&self, n: usize) -> std::ops::Range<usize> {
        let [lo, hi] = self.spans[n];
        lo as usize..hi as usize
    }

    /// The position in the build's order of every box (the inverse of the order).
    pub fn positions(&self) -> Vec<u32> {
        let mut at = vec![0u32; self.order.len()];
        for (k, &b) in self.order.iter().enumerate() {
            at[b as usize] = k as u32;
        }
        at
    }

    /// Calls `f(i)` for every box `i` that meets the closed box `q`, in the build's order
    /// (Morton or median splits).
    #[inline]
    pub fn query(&self, q: &Aabb<T>, f: impl FnMut(u32)) {
        self.query_by(|b| b.overlaps(q), f);
    }

    /// Calls `f(i)` for every box `i` that `may_hold(box)` accepts, skipping every node
    /// whose box it rejects, in the build's order. `may_hold` must accept a box that
    /// contains an accepted one (as "meets a region" does).
    #[inline]
    pub fn query_by(&self, may_hold: impl Fn(&Aabb<T>) -> bool, mut f: impl FnMut(u32)) {
        if self.boxes.is_empty() {
            return;
        }
        let mut stack = [0usize; 64];
        let mut top = 1;
        stack[0] = 1;
        while top > 0 {
            top -= 1;
            let i = stack[top];
            if !may_hold(&self.nodes[i]) {
                continue;
            }
            let [x, y] = self.kids[i];
            if x == 0 {
                for &p in self.items(i) {
                    if may_hold(&self.boxes[p as usize]) {
                        f(p);
                    }
                }
            } else {
                stack[top] = y as usize;
                stack[top + 1] = x as usize;
                top += 2;
            }
        }
    }
}

/// Depth down to which the self-traversal forks into parallel tasks.
const PARALLEL_DEPTH: u32 = 10;

struct PairCtx<'a, T: Coord, A, I, V, M, P> {
    bvh: &'a Bvh<T>,
    _acc: std::marker::PhantomData<fn() -> A>,
    init: &'a I,
    visit: &'a V,
    merge: &'a M,
    prune: &'a P,
}

impl<T, A, I, V, M, P> PairCtx<'_, T, A, I, V, M, P>
where
    T: Coord,
    A: Send,
    I: Fn() -> A + Sync,
    V: Fn(&mut A, u32, u32) + Sync,
    M: Fn(A, A) -> A + Sync,
    P: Fn(usize, usize) -> bool + Sync,
{
    /// Pairs inside the subtree of node `i`.
    fn within(&self, i: usize, depth: u32) -> A {
        let b = self.bvh;
        if (self.prune)(i, i) {
            return (self.init)();
        }
        let Some([x, y]) = b.children(i) else {
            let mut acc = (self.init)();
            self.leaf_pairs(i, &mut acc);
            return acc;
        };
        if b.nodes[i].is_empty() {
            return (self.init)();
        }
        if depth < PARALLEL_DEPTH {
            let (p, (q, r)) = rayon::join(
                || self.within(x, depth + 1),
                || {
                    rayon::join(
                        || self.within(y, depth + 1),
                        || self.across(x, y, depth + 1),
                    )
                },
            );
            (self.merge)(p, (self.merge)(q, r))
        } else {
            let mut acc = (self.init)();
            self.within_seq(i, &mut acc);
            acc
        }
    }

    /// Pairs of boxes of leaf `i`.
    fn leaf_pairs(&self, i: usize, acc: &mut A) {
        let b = self.bvh;
        let prims = b.items(i);
        for (k, &p) in prims.iter().enumerate() {
            for &q in &prims[k + 1..] {
                if b.boxes[p as usize].overlaps(&b.boxes[q as usize]) {
                    (self.visit)(acc, p.min(q), p.max(q));
                }
            }
        }
    }

    fn within_seq(&self, i: usize, acc: &mut A) {
        let b = self.bvh;
        if (self.prune)(i, i) {
            return;
        }
        let Some([x, y]) = b.children(i) else {
            self.leaf_pairs(i, acc);
            return;
        };
        if b.nodes[i].is_empty() {
            return;
        }
        self.within_seq(x, acc);
        self.within_seq(y, acc);
        self.across_seq(x, y, acc);
    }

    /// Pairs with one box under node `x` and the other under node `y` (disjoint
    /// subtrees).
    fn across(&self, x: usize, y: usize, depth: u32) -> A {
        let b = self.bvh;
        let (Some([x0, x1]), Some([y0, y1])) = (b.children(x), b.children(y)) else {
            let mut acc = (self.init)();
            self.across_seq(x, y, &mut acc);
            return acc;
        };
        if depth >= PARALLEL_DEPTH || !b.nodes[x].overlaps(&b.nodes[y]) || (self.prune)(x, y) {
            let mut acc = (self.init)();
            self.across_seq(x, y, &mut acc);
            return acc;
        }
        let (l, r) = rayon::join(
            || {
                let (p, q) = rayon::join(
                    || self.across(x0, y0, depth + 1),
                    || self.across(x0, y1, depth + 1),
                );
                (self.merge)(p, q)
            },
            || {
                let (p, q) = rayon::join(
                    || self.across(x1, y0, depth + 1),
                    || self.across(x1, y1, depth + 1),
                );
                (self.merge)(p, q)
            },
        );
        (self.merge)(l, r)
    }

    fn across_seq(&self, x: usize, y: usize, acc: &mut A) {
        let b = self.bvh;
        if !b.nodes[x].overlaps(&b.nodes[y]) || (self.prune)(x, y) {
            return;
        }
        match (b.children(x), b.children(y)) {
            (None, None) => {
                for &p in b.items(x) {
                    let bp = &b.boxes[p as usize];
                    if !bp.overlaps(&b.nodes[y]) {
                        continue;
                    }
                    for &q in b.items(y) {
                        if bp.overlaps(&b.boxes[q as usize]) {
                            (self.visit)(acc, p.min(q), p.max(q));
                        }
                    }
                }
            }
            (Some([x0, x1]), None) => {
                self.across_seq(x0, y, acc);
                self.across_seq(x1, y, acc);
            }
            (None, Some([y0, y1])) => {
                self.across_seq(x, y0, acc);
                self.across_seq(x, y1, acc);
            }
            (Some([x0, x1]), Some([y0, y1])) => {
                self.across_seq(x0, y0, acc);
                self.across_seq(x0, y1, acc);
                self.across_seq(x1, y0, acc);
                self.across_seq(x1, y1, acc);
            }
        }
    }
}

/// The indices of `boxes` ordered by their low x (a stable sort: ties keep index order).
pub fn by_low_x<T: Coord>(boxes: &[Aabb<T>]) -> Vec<u32> {
    let mut order: Vec<u32> = (0..boxes.len() as u32).collect();
    order.sort_by(|&i, &j| boxes[i as usize].min[0].total_cmp(&boxes[j as usize].min[0]));
    order
}

/// Calls `f(i, j)` for every pair of distinct boxes that meet (closed), by sort and
/// sweep along x: `i` runs over the boxes in the order of their low x (a stable sort),
/// `j` over the boxes after `i` in that order whose low x is at most `i`'s high x.
/// Stops at the first `f` that breaks, and returns its value.
pub fn sweep_pairs<T: Coord, B>(
    boxes: &[Aabb<T>],
    mut f: impl FnMut(usize, usize) -> ControlFlow<B>,
) -> ControlFlow<B> {
    let order = by_low_x(boxes);
    for x in 0..order.len() {
        sweep_step(boxes, &order, x, |i, j| f(i as usize, j as usize))?;
    }
    ControlFlow::Continue(())
}

/// One step of [`sweep_pairs`] at position `x` of the [`by_low_x`] order `order`:
/// `f(order[x], j)` for every later box `j` whose low x is at most `order[x]`'s high x
/// and that meets it (a caller can run the steps in slices, in parallel).
pub fn sweep_step<T: Coord, B>(
    boxes: &[Aabb<T>],
    order: &[u32],
    x: usize,
    mut f: impl FnMut(u32, u32) -> ControlFlow<B>,
) -> ControlFlow<B> {
    let i = order[x];
    let bi = &boxes[i as usize];
    for &j in &order[x + 1..] {
        let bj = &boxes[j as usize];
        if bj.min[0] > bi.max[0] {
            break;
        }
        if bi.overlaps(bj) {
            f(i, j)?;
        }
    }
    ControlFlow::Continue(())
}

/// Index pairs `(i, j)` whose boxes `a[i]` and `b[j]` meet (closed), by sort and sweep
/// along x; `a_by_low_x` and `b_by_low_x` are the lists' [`by_low_x`] orders. The two
/// lists merge with ties to `a` (the order a stable sort of all of `a`'s boxes then all
/// of `b`'s would give), and each pair comes when the later of its two boxes is swept,
/// after the pairs of earlier boxes.
pub fn sweep_pairs_between<T: Coord>(
    a: &[Aabb<T>],
    a_by_low_x: &[u32],
    b: &[Aabb<T>],
    b_by_low_x: &[u32],
) -> Vec<(usize, usize)> {
    let mut events: Vec<(T, bool, usize)> = Vec::with_capacity(a.len() + b.len());
    let (mut ia, mut ib) = (a_by_low_x.iter().peekable(), b_by_low_x.iter().peekable());
    loop {
        let from_b = match (ia.peek(), ib.peek()) {
            (Some(&&i), Some(&&j)) => a[i as usize].min[0]
                .total_cmp(&b[j as usize].min[0])
                .is_gt(),
            (Some(_), None) => false,
            (None, Some(_)) => true,
            (None, None) => break,
        };
        let (k, x) = if from_b {
            let j = *ib.next().unwrap() as usize;
            (j, b[j].min[0])
        } else {
            let i = *ia.next().unwrap() as usize;
            (i, a[i].min[0])
        };
        events.push((x, from_b, k));
    }
    let (mut act_a, mut act_b): (Vec<usize>, Vec<usize>) = (Vec::new(), Vec::new());
    let mut out = Vec::new();
    // Each side's expired boxes are dropped only when that side is scanned: the pairs
    // and their order are those of dropping both at every event, and a large list's
    // long active set (the Gaussian arcs of a many-sided prism's caps all reach a pole)
    // is not walked at each of its own events.
    for (lo, from_b, i) in events {
        if from_b {
            act_a.retain(|&k| a[k].max[0] >= lo);
            out.extend(
                act_a
                    .iter()
                    .filter(|&&k| a[k].overlaps(&b[i]))
                    .map(|&k| (k, i)),
            );
            act_b.push(i);
        } else {
            act_b.retain(|&k| b[k].max[0] >= lo);
            out.extend(
                act_b
                    .iter()
                    .filter(|&&k| a[i].overlaps(&b[k]))
                    .map(|&k| (i, k)),
            );
            act_a.push(i);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn query_matches_brute_force() {
        let mut boxes = Vec::new();
        let mut rng = apart_testkit::solids::Lcg(12345);
        let mut rnd = |m: i64| rng.below(m as u64) as i64;
        for _ in 0..1000 {
            let p = [rnd(1000), rnd(1000), rnd(1000)];
            let d = [rnd(50), rnd(50), rnd(50)];
            boxes.push(Aabb::of([&p, &[p[0] + d[0], p[1] + d[1], p[2] + d[2]]]));
        }
        let bvh = Bvh::new(boxes.clone());
        for q in boxes.iter().take(100) {
            let mut got = Vec::new();
            bvh.query(q, |i| got.push(i));
            got.sort();
            let want: Vec<u32> = (0..boxes.len() as u32)
                .filter(|&i| boxes[i as usize].overlaps(q))
                .collect();
            assert_eq!(got, want);
        }
        Bvh::new(Vec::new()).query(&boxes[0], |_| panic!("empty"));
        assert_self_pairs_match_brute_force(&bvh, &boxes);
    }

    /// `bvh`'s self pairs are every pair of `boxes` that meet, checked pair by pair.
    fn assert_self_pairs_match_brute_force<T: Coord>(bvh: &Bvh<T>, boxes: &[Aabb<T>]) {
        let mut got = bvh.self_pairs(
            Vec::new,
            |v, i, j| v.push((i, j)),
            |mut a, b| {
                a.extend(b);
                a
            },
        );
        got.sort();
        let mut want = Vec::new();
        for i in 0..boxes.len() as u32 {
            for j in i + 1..boxes.len() as u32 {
                if boxes[i as usize].overlaps(&boxes[j as usize]) {
                    want.push((i, j));
                }
            }
        }
        assert_eq!(got, want);
    }

    /// Median-split queries report the boxes meeting the query in one fixed order: the
    /// upper half of each split (by box centres along the longest axis) before the lower.
    #[test]
    fn median_split_order() {
        let mut rng = apart_testkit::solids::Lcg(7);
        let mut rnd = || rng.next_bits() as f64 / (1u64 << 31) as f64 * 100.0;
        let boxes: Vec<Aabb<f64>> = (0..300)
            .map(|_| {
                let lo = [rnd(), rnd(), rnd()];
                Aabb::from_axes(&[
                    [lo[0], lo[0] + 5.0],
                    [lo[1], lo[1] + 3.0],
                    [lo[2], lo[2] + 8.0],
                ])
            })
            .collect();
        let bvh = Bvh::by_median_splits(boxes.clone());
        assert_eq!(bvh.len(), 300);
        let everything = Aabb::from_axes(&[[-1.0, 200.0]; 3]);
        let mut all = Vec::new();
        bvh.query(&everything, |i| all.push(i));
        let mut sorted = all.clone();
        sorted.sort();
        assert_eq!(sorted, (0..300).collect::<Vec<u32>>());
        let rank: Vec<usize> = {
            let mut r = vec![0; 300];
            for (k, &i) in all.iter().enumerate() {
                r[i as usize] = k;
            }
            r
        };
        // The first split: along the longest axis (z here: 8 wide boxes over the same
        // spread), the upper half of the centres first.
        let c = |i: usize| boxes[i].min[2] + boxes[i].max[2];
        let first: Vec<usize> = all[..150].iter().map(|&i| i as usize).collect();
        let lowest_upper = first.iter().map(|&i| c(i)).fold(f64::INFINITY, f64::min);
        assert!(all[150..].iter().all(|&i| c(i as usize) <= lowest_upper));
        for _ in 0..50 {
            let lo = [rnd(), rnd(), rnd()];
            let q = Aabb::from_axes(&[
                [lo[0], lo[0] + 10.0],
                [lo[1], lo[1] + 10.0],
                [lo[2], lo[2] + 10.0],
            ]);
            let mut got = Vec::new();
            bvh.query(&q, |i| got.push(i));
            let mut want: Vec<u32> = (0..300u32)
                .filter(|&k| boxes[k as usize].overlaps(&q))
                .collect();
            want.sort_by_key(|&k| rank[k as usize]);
            assert_eq!(got, want);
        }
        let empty = Bvh::<f64>::default();
        assert!(empty.is_empty());
        empty.query(&everything, |_| panic!("empty"));
    }

    /// The median-split tree's nodes, walked by the node API, against brute force: every
    /// node holds the boxes under it, its box is their union, a split node's children
    /// part its boxes (the upper half first, `len / 2` boxes in the lower one, no lower
    /// centre along the longest axis above an upper one), leaves hold at most the leaf
    /// size, children are numbered after their parent in preorder with the lower half's
    /// subtree first, and the self pairs and labels of the tree are those of brute force.
    #[test]
    fn median_split_nodes() {
        let mut rng = apart_testkit::solids::Lcg(31);
        let mut rnd = |m: i64| rng.below(m as u64) as i64;
        for (n, leaf) in [(0, 1), (1, 1), (2, 1), (7, 1), (97, 1), (200, 3), (255, 4)] {
            let boxes: Vec<Aabb<i64>> = (0..n)
                .map(|_| {
                    let p = [rnd(400), rnd(100), rnd(1000) - 500];
                    let d = [rnd(30), rnd(30), rnd(30)];
                    Aabb::of([&p, &[p[0] + d[0], p[1] + d[1], p[2] + d[2]]])
                })
                .collect();
            let bvh = Bvh::by_median_splits_with_leaf(boxes.clone(), leaf);
            let Some(root) = bvh.root() else {
                assert_eq!(n, 0);
                continue;
            };
            let mut all = bvh.items(root).to_vec();
            all.sort();
            assert_eq!(all, (0..n as u32).collect::<Vec<_>>());
            // Preorder, lower subtree first: a walk visiting the second child first
            // meets the nodes in increasing index order.
            let mut stack = vec![root];
            let mut seen = Vec::new();
            while let Some(i) = stack.pop() {
                seen.push(i);
                let items = bvh.items(i);
                let union = items
                    .iter()
                    .fold(Aabb::EMPTY, |b, &k| b.union(&boxes[k as usize]));
                assert_eq!(*bvh.node_box(i), union);
                match bvh.children(i) {
                    None => assert!(!items.is_empty() && items.len() <= leaf),
                    Some([up, low]) => {
                        assert!(items.len() > leaf);
                        let (u, l) = (bvh.items(up), bvh.items(low));
                        assert_eq!(l.len(), items.len() / 2);
                        assert_eq!([u, l].concat(), items);
                        let b = bvh.node_box(i);
                        let ext = |k: usize| b.max[k] - b.min[k];
                        let axis = (0..3).max_by_key(|&k| ext(k)).unwrap();
                        let c =
                            |k: &u32| boxes[*k as usize].min[axis] + boxes[*k as usize].max[axis];
                        assert!(l.iter().map(c).max() <= u.iter().map(c).min());
                        assert!(up > i && low > i);
                        stack.push(up);
                        stack.push(low);
                    }
                }
            }
            assert!(seen.windows(2).all(|w| w[0] < w[1]), "{seen:?}");
            assert_self_pairs_match_brute_force(&bvh, &boxes);
            let counts = bvh.node_labels(|p| p.len(), |a, b| a + b, 0);
            assert!((1..counts.len()).all(|i| counts[i] == bvh.items(i).len()));
        }
    }

    #[test]
    fn sweeps_match_brute_force() {
        let mut rng = apart_testkit::solids::Lcg(99);
        let mut rnd = |m: i64| rng.below(m as u64) as i64;
        let mut boxes: Vec<Aabb<f64>> = Vec::new();
        for _ in 0..300 {
            let p = [rnd(100), rnd(100), rnd(100)].map(|v| v as f64);
            let d = [rnd(10), rnd(10), rnd(10)].map(|v| v as f64);
            boxes.push(Aabb::of([&p, &[p[0] + d[0], p[1] + d[1], p[2] + d[2]]]));
        }
        let brute = |a: &[Aabb<f64>], b: &[Aabb<f64>], distinct: bool| {
            let mut want = Vec::new();
            for (i, x) in a.iter().enumerate() {
                for (j, y) in b.iter().enumerate() {
                    if (!distinct || i < j) && x.overlaps(y) {
                        want.push((i, j));
                    }
                }
            }
            want
        };
        let mut got = Vec::new();
        let flow = sweep_pairs(&boxes, |i, j| {
            got.push((i.min(j), i.max(j)));
            ControlFlow::<()>::Continue(())
        });
        assert_eq!(flow, ControlFlow::Continue(()));
        got.sort();
        assert_eq!(got, brute(&boxes, &boxes, true));
        let first = sweep_pairs(&boxes, |i, j| ControlFlow::Break((i, j)))
            .break_value()
            .unwrap();
        assert!(first.0 != first.1 && boxes[first.0].overlaps(&boxes[first.1]));
        let (a, b) = boxes.split_at(120);
        let mut got = sweep_pairs_between(a, &by_low_x(a), b, &by_low_x(b));
        got.sort();
        assert_eq!(got, brute(a, b, false));
    }
}
