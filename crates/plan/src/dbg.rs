//! Directional blocking graphs and the subsets that can move.

/// The directional blocking graph of one direction (or cell): an arc `i → j` when part
/// `i`, moving along the direction, would hit part `j` (indices local to a subassembly).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Dbg {
    n: usize,
    arcs: Vec<(usize, usize)>,
}

impl Dbg {
    /// The graph on `n` nodes with the given arcs.
    pub fn new(n: usize, mut arcs: Vec<(usize, usize)>) -> Dbg {
        arcs.sort_unstable();
        arcs.dedup();
        Dbg { n, arcs }
    }

    /// Number of nodes.
    pub fn nodes(&self) -> usize {
        self.n
    }

    /// The arcs, sorted.
    pub fn arcs(&self) -> &[(usize, usize)] {
        &self.arcs
    }

    /// The minimal subsets that can move: the strongly connected components with no arc
    /// leaving them (each closed under blocking, none containing a smaller closed set),
    /// excluding the whole node set. Empty when the graph is strongly connected. Each
    /// subset is sorted; the list is sorted.
    pub fn minimal_moving_sets(&self) -> Vec<Vec<usize>> {
        if self.n <= 1 {
            return Vec::new();
        }
        if self.n <= 64 {
            return self.minimal_moving_sets_small();
        }
        let mut g = BitGraph::new(self.n);
        for &(a, b) in &self.arcs {
            g.block(a, b);
        }
        g.minimal_moving_sets()
    }

    /// [`Self::minimal_moving_sets`] for at most 64 nodes, with bit masks.
    fn minimal_moving_sets_small(&self) -> Vec<Vec<usize>> {
        let mut m = Masks::new(self.n);
        for &(a, b) in &self.arcs {
            m.block(a, b);
        }
        m.minimal_moving_set_lists()
    }

    /// [`Self::minimal_moving_sets`] by petgraph's strongly connected components (the
    /// reference the bit-set versions are tested against).
    #[cfg(test)]
    fn minimal_moving_sets_scc(&self) -> Vec<Vec<usize>> {
        use petgraph::algo::tarjan_scc;
        use petgraph::graph::{DiGraph, NodeIndex};
        let mut g: DiGraph<(), ()> = DiGraph::with_capacity(self.n, self.arcs.len());
        for _ in 0..self.n {
            g.add_node(());
        }
        for &(a, b) in &self.arcs {
            g.add_edge(NodeIndex::new(a), NodeIndex::new(b), ());
        }
        let sccs: Vec<Vec<usize>> = tarjan_scc(&g)
            .into_iter()
            .map(|c| c.into_iter().map(|v| v.index()).collect())
            .collect();
        if sccs.len() == 1 {
            return Vec::new();
        }
        let mut comp = vec![0usize; self.n];
        for (k, c) in sccs.iter().enumerate() {
            for &v in c {
                comp[v] = k;
            }
        }
        let mut has_out = vec![false; sccs.len()];
        for &(a, b) in &self.arcs {
            if comp[a] != comp[b] {
                has_out[comp[a]] = true;
            }
        }
        let mut out: Vec<Vec<usize>> = sccs
            .into_iter()
            .enumerate()
            .filter(|(k, _)| !has_out[*k])
            .map(|(_, mut c)| {
                c.sort_unstable();
                c
            })
            .collect();
        out.sort();
        out
    }

    /// True when `set` (sorted node list) can move: no arc leaves it.
    pub fn can_move(&self, set: &[usize]) -> bool {
        let mut inside = vec![false; self.n];
        for &v in set {
            inside[v] = true;
        }
        !set.is_empty()
            && set.len() < self.n
            && self.arcs.iter().all(|&(a, b)| !inside[a] || inside[b])
    }
}

/// A blocking graph on at most 64 nodes as adjacency bit masks: cheap enough to be
/// rebuilt for every cell of a large motion space instead of being stored.
#[derive(Clone, Copy, Debug)]
pub struct Masks {
    n: usize,
    adj: [u64; 64],
}

impl Masks {
    /// The graph without arcs on `n <= 64` nodes.
    pub fn new(n: usize) -> Masks {
        assert!(n <= 64, "bit-mask graphs hold at most 64 nodes");
        Masks { n, adj: [0; 64] }
    }

    /// Adds the arc `a → b` (`a` moving hits `b`).
    pub fn block(&mut self, a: usize, b: usize) {
        self.adj[a] |= 1 << b;
    }

    /// The node set of a mask, ascending.
    pub fn members(mask: u64) -> Vec<usize> {
        (0..64).filter(|&k| mask >> k & 1 == 1).collect()
    }

    /// The mask of a node set.
    pub fn mask_of(set: &[usize]) -> u64 {
        set.iter().fold(0, |m, &k| m | 1 << k)
    }

    /// True when the set `mask` can move: not empty, not everything, no arc leaving it.
    pub fn can_move(&self, mask: u64) -> bool {
        let all = self.all();
        if mask == 0 || mask & all == all {
            return false;
        }
        let mut m = mask;
        while m != 0 {
            let u = m.trailing_zeros() as usize;
            m &= m - 1;
            if self.adj[u] & !mask != 0 {
                return false;
            }
        }
        true
    }

    fn all(&self) -> u64 {
        if self.n == 64 {
            u64::MAX
        } else {
            (1u64 << self.n) - 1
        }
    }

    /// The minimal moving sets as sorted node lists, in the order of
    /// [`Dbg::minimal_moving_sets`].
    pub fn minimal_moving_set_lists(&self) -> Vec<Vec<usize>> {
        self.minimal_moving_sets()
            .into_iter()
            .map(Masks::members)
            .collect()
    }

    /// The minimal moving sets as masks, ascending by their sorted member lists: `reach[v]`,
    /// the nodes reachable from `v` (itself included), is a minimal closed set exactly
    /// when `v` is reachable back from each of them (its strongly connected component has
    /// no arc leaving it).
    pub fn minimal_moving_sets(&self) -> Vec<u64> {
        let n = self.n;
        if n <= 1 {
            return Vec::new();
        }
        let mut reach = [0u64; 64];
        for (v, r) in reach.iter_mut().enumerate().take(n) {
            let mut seen = 1u64 << v;
            let mut frontier = seen;
            while frontier != 0 {
                let mut next = 0u64;
                let mut f = frontier;
                while f != 0 {
                    let u = f.trailing_zeros() as usize;
                    f &= f - 1;
                    next |= self.adj[u];
                }
                frontier = next & !seen;
                seen |= next;
            }
            *r = seen;
        }
        let all = self.all();
        let mut sets: Vec<u64> = Vec::new();
        for v in 0..n {
            let r = reach[v];
            if r == all || sets.contains(&r) {
                continue;
            }
            let mut m = r;
            let mut sink = true;
            while m != 0 {
                let u = m.trailing_zeros() as usize;
                m &= m - 1;
                if reach[u] & (1 << v) == 0 {
                    sink = false;
                    break;
                }
            }
            if sink {
                sets.push(r);
            }
        }
        // Sink components are disjoint: order them by their smallest member, which is
        // the order of their sorted member lists.
        sets.sort_unstable_by_key(|m| m.trailing_zeros());
        sets
    }
}

/// A blocking graph on any number of nodes as rows of adjacency bits, with the minimal
/// moving sets by Tarjan's strongly connected components over the bits: no sorting of
/// arcs and no graph library, so that one can be built for every cell of a large motion
/// space (thousands of arcs on hundreds of parts) in microseconds.
#[derive(Clone, Debug)]
pub struct BitGraph {
    n: usize,
    words: usize,
    adj: Vec<u64>,
}

impl BitGraph {
    /// The graph without arcs on `n` nodes.
    pub fn new(n: usize) -> BitGraph {
        let words = n.div_ceil(64).max(1);
        BitGraph {
            n,
            words,
            adj: vec![0; n * words],
        }
    }

    /// Number of nodes.
    pub fn nodes(&self) -> usize {
        self.n
    }

    /// Adds the arc `a → b` (`a` moving hits `b`).
    #[inline]
    pub fn block(&mut self, a: usize, b: usize) {
        self.adj[a * self.words + b / 64] |= 1 << (b % 64);
    }

    fn row(&self, a: usize) -> &[u64] {
        &self.adj[a * self.words..(a + 1) * self.words]
    }

    /// The successors of `a`, ascending.
    fn successors(&self, a: usize) -> impl Iterator<Item = usize> + '_ {
        self.row(a).iter().enumerate().flat_map(|(k, &w)| {
            let mut w = w;
            std::iter::from_fn(move || {
                if w == 0 {
                    return None;
                }
                let t = w.trailing_zeros() as usize;
                w &= w - 1;
                Some(k * 64 + t)
            })
        })
    }

    /// True when `set` (distinct nodes) can move: not empty, not everything, no arc
    /// leaving it.
    pub fn can_move(&self, set: &[usize]) -> bool {
        if set.is_empty() || set.len() >= self.n {
            return false;
        }
        let mut mask = vec![0u64; self.words];
        for &v in set {
            mask[v / 64] |= 1 << (v % 64);
        }
        set.iter()
            .all(|&v| self.row(v).iter().zip(&mask).all(|(r, m)| r & !m == 0))
    }

    /// The minimal moving sets, as [`Dbg::minimal_moving_sets`]: the strongly connected
    /// components with no arc leaving them, unless there is only one; each sorted, the
    /// list sorted.
    pub fn minimal_moving_sets(&self) -> Vec<Vec<usize>> {
        let n = self.n;
        if n <= 1 {
            return Vec::new();
        }
        // Iterative Tarjan: `index` 0 = unvisited; `low`; components numbered in the
        // order they close (sinks first, but every component is checked below).
        const NONE: u32 = u32::MAX;
        let mut index = vec![0u32; n];
        let mut low = vec![0u32; n];
        let mut comp = vec![NONE; n];
        let mut stack: Vec<usize> = Vec::new();
        let mut next = 1u32;
        let mut comps = 0u32;
        // Call frames: node and the next word/bits of its row to scan.
        let mut frames: Vec<(usize, usize, u64)> = Vec::new();
        for root in 0..n {
            if index[root] != 0 {
                continue;
            }
            index[root] = next;
            low[root] = next;
            next += 1;
            stack.push(root);
            frames.push((root, 0, self.row(root)[0]));
            while let Some(&mut (v, ref mut k, ref mut bits)) = frames.last_mut() {
                // Next successor of v.
                let mut succ = None;
                loop {
                    if *bits != 0 {
                        let t = bits.trailing_zeros() as usize;
                        *bits &= *bits - 1;
                        succ = Some(*k * 64 + t);
                        break;
                    }
                    *k += 1;
                    if *k >= self.words {
                        break;
                    }
                    *bits = self.adj[v * self.words + *k];
                }
                match succ {
                    Some(w) if index[w] == 0 => {
                        index[w] = next;
                        low[w] = next;
                        next += 1;
                        stack.push(w);
                        frames.push((w, 0, self.row(w)[0]));
                    }
                    Some(w) => {
                        if comp[w] == NONE {
                            low[v] = low[v].min(index[w]);
                        }
                    }
                    None => {
                        frames.pop();
                        if let Some(&(u, _, _)) = frames.last() {
                            low[u] = low[u].min(low[v]);
                        }
                        if low[v] == index[v] {
                            while let Some(w) = stack.pop() {
                                comp[w] = comps;
                                if w == v {
                                    break;
                                }
                            }
                            comps += 1;
                        }
                    }
                }
            }
        }
        if comps == 1 {
            return Vec::new();
        }
        let mut has_out = vec![false; comps as usize];
        for v in 0..n {
            if self.successors(v).any(|w| comp[w] != comp[v]) {
                has_out[comp[v] as usize] = true;
            }
        }
        let mut sets: Vec<Vec<usize>> = vec![Vec::new(); comps as usize];
        for v in 0..n {
            if !has_out[comp[v] as usize] {
                sets[comp[v] as usize].push(v);
            }
        }
        let mut out: Vec<Vec<usize>> = sets.into_iter().filter(|s| !s.is_empty()).collect();
        // Members are pushed in increasing order; sink components are disjoint, so their
        // smallest members order them.
        out.sort_unstable_by_key(|s| s[0]);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cubes_in_a_row_along_x() {
        // i -> j for i < j: only the last cube can leave along +x.
        let arcs = (0..4)
            .flat_map(|i| (i + 1..4).map(move |j| (i, j)))
            .collect();
        let g = Dbg::new(4, arcs);
        assert_eq!(g.minimal_moving_sets(), vec![vec![3]]);
        assert!(g.can_move(&[2, 3]));
        assert!(!g.can_move(&[1]));
    }

    #[test]
    fn strongly_connected_and_empty() {
        let g = Dbg::new(3, vec![(0, 1), (1, 2), (2, 0)]);
        assert!(g.minimal_moving_sets().is_empty());
        let g = Dbg::new(3, vec![]);
        assert_eq!(g.minimal_moving_sets(), vec![vec![0], vec![1], vec![2]]);
        let g = Dbg::new(3, vec![(0, 1), (1, 0), (2, 0)]);
        assert_eq!(g.minimal_moving_sets(), vec![vec![0, 1]]);
    }

    #[test]
    fn bit_graphs_agree_with_tarjan_beyond_64_nodes() {
        // Random graphs of 65 to 300 nodes: sparse (many components), a cycle through
        // all, and a few extra arcs; can_move agrees on the sink sets and their unions.
        let mut rng = apart_testkit::solids::Lcg(777);
        let mut next = |m: u64| rng.below(m);
        for round in 0..60 {
            let n = 65 + next(236) as usize;
            let mut arcs = Vec::new();
            let count = next(4 * n as u64) as usize;
            for _ in 0..count {
                let (a, b) = (next(n as u64) as usize, next(n as u64) as usize);
                if a != b {
                    arcs.push((a, b));
                }
            }
            if round % 10 == 0 {
                arcs.extend((0..n).map(|v| (v, (v + 1) % n)));
            }
            let mut b = BitGraph::new(n);
            for &(x, y) in &arcs {
                b.block(x, y);
            }
            let g = Dbg::new(n, arcs);
            let want = g.minimal_moving_sets_scc();
            assert_eq!(b.minimal_moving_sets(), want);
            for m in &want {
                assert!(b.can_move(m) && g.can_move(m));
            }
            let all: Vec<usize> = (0..n).collect();
            assert!(!b.can_move(&all) && !b.can_move(&[]));
            for v in 0..n.min(20) {
                assert_eq!(b.can_move(&[v]), g.can_move(&[v]), "{v}");
            }
        }
    }

    #[test]
    fn bit_masks_agree_with_tarjan() {
        // Random graphs of 2 to 64 nodes and various densities (a small LCG keeps the
        // test deterministic), including complete and empty ones.
        let mut rng = apart_testkit::solids::Lcg(12345);
        let mut next = |m: u64| rng.below(m);
        for _ in 0..400 {
            let n = 2 + next(63) as usize;
            let density = next(100);
            let mut arcs = Vec::new();
            for a in 0..n {
                for b in 0..n {
                    if a != b && next(100 * n as u64) < density * 3 {
                        arcs.push((a, b));
                    }
                }
            }
            let mut b = BitGraph::new(n);
            for &(x, y) in &arcs {
                b.block(x, y);
            }
            let g = Dbg::new(n, arcs);
            assert_eq!(g.minimal_moving_sets_small(), g.minimal_moving_sets_scc());
            assert_eq!(b.minimal_moving_sets(), g.minimal_moving_sets_scc());
        }
    }
}
