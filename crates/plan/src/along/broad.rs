//! The broad phase of a [`DirectionQuery`]: the pairs of parts whose boxes a line
//! meets or which touch (walks of the parts' box hierarchy), and within a pair of
//! parts the piece pairs a ray or a contact may involve (walks of the piece trees).

use super::DirectionQuery;
use crate::cull::{pairs_where, sum_box};
use crate::pairs::ray_meets_int_box;
use apart_kernel::{Aabb, Bvh, Vec3};

/// Whether the line `{t x : t real}` meets the closed box `[lo, hi]`, exactly, for
/// bounds below 2^62 in magnitude and a direction below 2^62 (products in `i128`).
pub(super) fn line_meets_int_box(lo: [i64; 3], hi: [i64; 3], x: &[i64; 3]) -> bool {
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
pub(super) fn line_meets_exact(lo: [i128; 3], hi: [i128; 3], x: &[i64; 3]) -> bool {
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

impl DirectionQuery<'_> {
    /// The piece pairs of `{i, j}` whose sum's box the ray along `x` may meet (a
    /// superset, from the parts' box trees; every pair without them), in increasing order.
    pub(super) fn along_ray(&self, i: usize, j: usize, x: &Vec3) -> Vec<usize> {
        match x.as_small() {
            Some(xs) => self.tree_pairs(i, j, &|sum| {
                ray_meets_int_box(sum.min.map(i128::from), sum.max.map(i128::from), xs)
            }),
            None => (0..self.parts[i].pieces.len() * self.parts[j].pieces.len()).collect(),
        }
    }

    /// The piece pairs `k` of `{i, j}` under node pairs of the parts' box trees whose
    /// box of sums `keep` accepts, in increasing order (every pair without trees).
    pub(super) fn tree_pairs(
        &self,
        i: usize,
        j: usize,
        keep: &(dyn Fn(&Aabb) -> bool + Sync),
    ) -> Vec<usize> {
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

    /// The piece pairs of `{i, j}` whose boxes touch or overlap (a superset, from the
    /// parts' box trees; every pair without them): the only ones that can touch.
    pub(super) fn touching_pairs(&self, i: usize, j: usize) -> Vec<usize> {
        self.tree_pairs(i, j, &|sum| sum.contains(&[0; 3]))
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
    pub(super) fn pairs_along(&self, sub: &[usize], d: &Vec3) -> Vec<(usize, usize)> {
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
    pub(super) fn pairs_touching(&self, sub: &[usize]) -> Vec<(usize, usize)> {
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
}
