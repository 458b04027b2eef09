//! Directional blocking graphs and the subsets that can move.

use petgraph::algo::tarjan_scc;
use petgraph::graph::{DiGraph, NodeIndex};

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
}
