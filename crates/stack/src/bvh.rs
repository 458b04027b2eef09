//! A bounding-volume hierarchy of axis-aligned boxes: the broad phase of interference
//! detection. Boxes are doubles rounded outwards, so a query never misses an overlap;
//! the exact tests come after.

/// A box `[lo, hi]` in doubles.
pub type FBox = [[f64; 3]; 2];

/// True when the closed boxes overlap.
pub fn overlap(a: &FBox, b: &FBox) -> bool {
    (0..3).all(|i| a[0][i] <= b[1][i] && b[0][i] <= a[1][i])
}

fn union(a: &FBox, b: &FBox) -> FBox {
    [
        [0, 1, 2].map(|i| a[0][i].min(b[0][i])),
        [0, 1, 2].map(|i| a[1][i].max(b[1][i])),
    ]
}

#[derive(Clone, Debug)]
struct Node {
    bounds: FBox,
    /// Leaf: `items[start..start + len]`; inner: children `start` and `start + 1`.
    start: usize,
    len: usize,
}

/// A static hierarchy over a list of boxes (median splits along the longest axis).
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    items: Vec<usize>,
    boxes: Vec<FBox>,
}

const LEAF: usize = 4;

impl Bvh {
    /// Builds the hierarchy of `boxes` (item `k` is `boxes[k]`).
    pub fn build(boxes: Vec<FBox>) -> Bvh {
        let mut bvh = Bvh {
            nodes: Vec::new(),
            items: (0..boxes.len()).collect(),
            boxes,
        };
        if !bvh.boxes.is_empty() {
            bvh.nodes.push(Node {
                bounds: [[0.0; 3]; 2],
                start: 0,
                len: 0,
            });
            bvh.split(0, 0, bvh.items.len());
        }
        bvh
    }

    fn split(&mut self, node: usize, start: usize, end: usize) {
        let mut b = self.boxes[self.items[start]];
        for &k in &self.items[start + 1..end] {
            b = union(&b, &self.boxes[k]);
        }
        self.nodes[node].bounds = b;
        if end - start <= LEAF {
            self.nodes[node].start = start;
            self.nodes[node].len = end - start;
            return;
        }
        let axis = (0..3)
            .max_by(|&i, &j| (b[1][i] - b[0][i]).total_cmp(&(b[1][j] - b[0][j])))
            .unwrap();
        let mid = (start + end) / 2;
        let boxes = &self.boxes;
        self.items[start..end].select_nth_unstable_by(mid - start, |&x, &y| {
            (boxes[x][0][axis] + boxes[x][1][axis])
                .total_cmp(&(boxes[y][0][axis] + boxes[y][1][axis]))
        });
        let left = self.nodes.len();
        for _ in 0..2 {
            self.nodes.push(Node {
                bounds: [[0.0; 3]; 2],
                start: 0,
                len: 0,
            });
        }
        self.nodes[node].start = left;
        self.nodes[node].len = 0;
        self.split(left, start, mid);
        self.split(left + 1, mid, end);
    }

    /// Every item whose box overlaps `q` (closed boxes), appended to `out`.
    pub fn query(&self, q: &FBox, out: &mut Vec<usize>) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n];
            if !overlap(&node.bounds, q) {
                continue;
            }
            if node.len > 0 {
                for &k in &self.items[node.start..node.start + node.len] {
                    if overlap(&self.boxes[k], q) {
                        out.push(k);
                    }
                }
            } else {
                stack.push(node.start);
                stack.push(node.start + 1);
            }
        }
    }

    /// Number of boxes.
    pub fn len(&self) -> usize {
        self.boxes.len()
    }

    /// True when there are no boxes.
    pub fn is_empty(&self) -> bool {
        self.boxes.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn query_matches_brute_force() {
        let mut boxes = Vec::new();
        let mut s: u64 = 7;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 33) as f64 / (1u64 << 31) as f64 * 100.0
        };
        for _ in 0..300 {
            let lo = [rnd(), rnd(), rnd()];
            boxes.push([lo, [lo[0] + 5.0, lo[1] + 3.0, lo[2] + 8.0]]);
        }
        let bvh = Bvh::build(boxes.clone());
        for _ in 0..50 {
            let lo = [rnd(), rnd(), rnd()];
            let q = [lo, [lo[0] + 10.0, lo[1] + 10.0, lo[2] + 10.0]];
            let mut got = Vec::new();
            bvh.query(&q, &mut got);
            got.sort();
            let want: Vec<usize> = (0..boxes.len())
                .filter(|&k| overlap(&boxes[k], &q))
                .collect();
            assert_eq!(got, want);
        }
    }
}
