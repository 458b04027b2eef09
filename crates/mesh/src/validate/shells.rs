//! Shells: the connected components of the surface, triangles being connected across
//! manifold edges (a solid touching itself along an edge or at a vertex has one shell
//! per side of the contact).

/// Union-find with path halving and union by size.
struct Dsu {
    parent: Vec<u32>,
    size: Vec<u32>,
}

impl Dsu {
    fn new(n: usize) -> Dsu {
        Dsu {
            parent: (0..n as u32).collect(),
            size: vec![1; n],
        }
    }

    fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let p = self.parent[x as usize];
            self.parent[x as usize] = self.parent[p as usize];
            x = self.parent[x as usize];
        }
        x
    }

    fn union(&mut self, a: u32, b: u32) {
        let (mut a, mut b) = (self.find(a), self.find(b));
        if a == b {
            return;
        }
        if self.size[a as usize] < self.size[b as usize] {
            std::mem::swap(&mut a, &mut b);
        }
        self.parent[b as usize] = a;
        self.size[a as usize] += self.size[b as usize];
    }
}

/// The shell of every triangle (numbered 0, 1, ... in order of first triangle) and the
/// number of shells.
pub(crate) fn shells(triangles: usize, pairs: &[(u32, u32)]) -> (Vec<u32>, usize) {
    let mut d = Dsu::new(triangles);
    for &(a, b) in pairs {
        d.union(a, b);
    }
    let mut id = vec![u32::MAX; triangles];
    let mut label = vec![u32::MAX; triangles];
    let mut count = 0u32;
    for t in 0..triangles as u32 {
        let r = d.find(t) as usize;
        if label[r] == u32::MAX {
            label[r] = count;
            count += 1;
        }
        id[t as usize] = label[r];
    }
    (id, count as usize)
}

#[cfg(test)]
mod tests {
    #[test]
    fn components() {
        let (id, n) = super::shells(5, &[(0, 1), (3, 4), (1, 0)]);
        assert_eq!(n, 3);
        assert_eq!(id, vec![0, 0, 1, 2, 2]);
    }
}
