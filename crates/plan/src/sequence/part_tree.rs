//! A box tree over the parts of a subassembly from which parts are removed as they leave.
//!
//! The kernel's [`Bvh`] (median splits) over the parts' boxes, with a Fenwick tree of
//! the parts still present over the tree's order: a node none of whose parts is left is
//! skipped in one range count, so a walk costs what the parts present near it cost, not
//! what every part that ever was there would. Rebuilt by the owner when fewer than half
//! of its parts are left.

use apart_kernel::{Aabb, Bvh};

/// Parts (global indices) in a box tree, some removed.
pub(crate) struct PartTree {
    /// The parts the tree was built over; tree item `k` is `parts[k]`.
    parts: Vec<usize>,
    bvh: Bvh,
    /// Position of each item in the tree's order.
    at: Vec<u32>,
    /// Fenwick tree over positions: 1 for an item still present.
    alive: Vec<i32>,
    /// Items still present, by item.
    present: Vec<bool>,
    count: usize,
    /// The item of each part.
    item_of: rustc_hash::FxHashMap<usize, u32>,
}

impl PartTree {
    /// The tree over `parts` (global indices), with `boxes` the boxes of every part
    /// (by global index).
    pub(crate) fn new(parts: Vec<usize>, boxes: &[Aabb]) -> PartTree {
        let bvh = Bvh::by_median_splits(parts.iter().map(|&k| boxes[k]).collect());
        let at = bvh.positions();
        let n = parts.len();
        let mut alive = vec![0i32; n + 1];
        // All present: the Fenwick array of ones.
        for (i, a) in alive.iter_mut().enumerate().skip(1) {
            *a = (i & i.wrapping_neg()) as i32;
        }
        PartTree {
            item_of: parts
                .iter()
                .enumerate()
                .map(|(k, &p)| (p, k as u32))
                .collect(),
            present: vec![true; n],
            count: n,
            parts,
            bvh,
            at,
            alive,
        }
    }

    /// Parts still present.
    pub(crate) fn len(&self) -> usize {
        self.count
    }

    /// Parts the tree was built over.
    pub(crate) fn built(&self) -> usize {
        self.parts.len()
    }

    /// Removes the part of item `k` (by item index).
    fn remove_item(&mut self, k: usize) {
        if !std::mem::replace(&mut self.present[k], false) {
            return;
        }
        self.count -= 1;
        let mut i = self.at[k] as usize + 1;
        while i < self.alive.len() {
            self.alive[i] -= 1;
            i += i & i.wrapping_neg();
        }
    }

    /// Removes the parts `gone` (global indices; those not in the tree are ignored).
    pub(crate) fn remove(&mut self, gone: &[usize]) {
        for g in gone {
            if let Some(&k) = self.item_of.get(g) {
                self.remove_item(k as usize);
            }
        }
    }

    /// Present items at positions below `p`.
    fn prefix(&self, mut p: usize) -> i32 {
        let mut s = 0;
        while p > 0 {
            s += self.alive[p];
            p &= p - 1;
        }
        s
    }

    /// Calls `f(part)` for every present part whose box `may_hold` accepts, skipping
    /// every node whose box it rejects or under which no part is present, in the tree's
    /// order. `may_hold` must accept a box holding an accepted one.
    pub(crate) fn query_by(
        &self,
        may_hold: &mut impl FnMut(&Aabb) -> bool,
        f: &mut impl FnMut(usize),
    ) {
        let Some(root) = self.bvh.root() else {
            return;
        };
        let mut stack = vec![root];
        while let Some(n) = stack.pop() {
            let span = self.bvh.span(n);
            if self.prefix(span.end) == self.prefix(span.start) {
                continue;
            }
            if !may_hold(self.bvh.node_box(n)) {
                continue;
            }
            match self.bvh.children(n) {
                Some([x, y]) => {
                    stack.push(y);
                    stack.push(x);
                }
                None => {
                    for &k in self.bvh.items(n) {
                        let k = k as usize;
                        if self.present[k] && may_hold(&self.bvh.boxes()[k]) {
                            f(self.parts[k]);
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn removed_parts_are_never_reported() {
        // A row of 100 unit boxes; remove every third, query ranges.
        let boxes: Vec<Aabb> = (0..100)
            .map(|x| Aabb {
                min: [x, 0, 0],
                max: [x + 1, 1, 1],
            })
            .collect();
        let mut t = PartTree::new((0..100).collect(), &boxes);
        let gone: Vec<usize> = (0..100).step_by(3).collect();
        t.remove(&gone);
        t.remove(&[1]);
        assert_eq!(t.len(), 100 - gone.len() - 1);
        for lo in [0i64, 17, 50, 98] {
            let q = Aabb {
                min: [lo, 0, 0],
                max: [lo + 10, 1, 1],
            };
            let mut got = Vec::new();
            t.query_by(&mut |b| b.overlaps(&q), &mut |k| got.push(k));
            got.sort_unstable();
            let want: Vec<usize> = (0..100usize)
                .filter(|&k| k % 3 != 0 && k != 1 && boxes[k].overlaps(&q))
                .collect();
            assert_eq!(got, want);
        }
    }
}
