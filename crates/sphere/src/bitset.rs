//! Sets of small integers (the maps covering a cell, the arcs of a DBG): dense bits
//! ([`BitSet`]) or a sorted list ([`MapSet`]).

/// A set of integers below a fixed bound, one bit each.
#[derive(Clone, PartialEq, Eq, Hash, Debug, Default)]
pub struct BitSet {
    words: Vec<u64>,
}

impl BitSet {
    /// The empty set of integers below `n`.
    pub fn new(n: usize) -> BitSet {
        BitSet {
            words: vec![0; n.div_ceil(64)],
        }
    }

    /// Whether `i` is in the set.
    #[inline]
    pub fn get(&self, i: usize) -> bool {
        self.words[i / 64] >> (i % 64) & 1 == 1
    }

    /// Adds (`v = true`) or removes `i`.
    #[inline]
    pub fn set(&mut self, i: usize, v: bool) {
        let bit = 1u64 << (i % 64);
        if v {
            self.words[i / 64] |= bit;
        } else {
            self.words[i / 64] &= !bit;
        }
    }

    /// True when no integer is in the set.
    pub fn is_empty(&self) -> bool {
        self.words.iter().all(|&w| w == 0)
    }

    /// Number of members.
    pub fn count(&self) -> usize {
        self.words.iter().map(|w| w.count_ones() as usize).sum()
    }

    /// The members in increasing order.
    pub fn iter(&self) -> impl Iterator<Item = usize> + '_ {
        self.words.iter().enumerate().flat_map(|(k, &w)| {
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

    /// Adds every member of `other` (same bound).
    pub fn union_with(&mut self, other: &BitSet) {
        for (a, b) in self.words.iter_mut().zip(&other.words) {
            *a |= b;
        }
    }
}

/// A set of map indices as a sorted list: the blocking status of a cell when there are
/// many maps (a motion space of `n` parts has `n (n − 1)` of them) and few cover any one
/// cell, where a [`BitSet`] would take `n² / 8` bytes per cell.
#[derive(Clone, PartialEq, Eq, Hash, Debug, Default)]
pub struct MapSet {
    members: Vec<u32>,
}

impl MapSet {
    /// The empty set.
    pub fn new() -> MapSet {
        MapSet::default()
    }

    /// The set of `members`, which must be strictly increasing.
    pub fn from_sorted(members: Vec<u32>) -> MapSet {
        debug_assert!(members.windows(2).all(|w| w[0] < w[1]), "not sorted");
        MapSet { members }
    }

    /// Whether `i` is in the set.
    #[inline]
    pub fn get(&self, i: usize) -> bool {
        self.members.binary_search(&(i as u32)).is_ok()
    }

    /// Adds (`v = true`) or removes `i`.
    pub fn set(&mut self, i: usize, v: bool) {
        let i = u32::try_from(i).expect("map index below 2^32");
        match (self.members.binary_search(&i), v) {
            (Err(k), true) => self.members.insert(k, i),
            (Ok(k), false) => {
                self.members.remove(k);
            }
            _ => {}
        }
    }

    /// Sets each `(i, on)` of `changes`, sorted by `i`; of several changes of one `i`, the
    /// last wins. One merge, linear in the set and the changes.
    pub fn merge(&mut self, changes: &[(u32, bool)]) {
        let mut out = Vec::with_capacity(self.members.len() + changes.len());
        let mut old = self.members.iter().copied().peekable();
        let mut k = 0;
        while k < changes.len() {
            let i = changes[k].0;
            // The last change of i.
            while k + 1 < changes.len() && changes[k + 1].0 == i {
                k += 1;
            }
            while let Some(&m) = old.peek() {
                if m >= i {
                    break;
                }
                out.push(m);
                old.next();
            }
            if old.peek() == Some(&i) {
                old.next();
            }
            if changes[k].1 {
                out.push(i);
            }
            k += 1;
        }
        out.extend(old);
        self.members = out;
    }

    /// True when no integer is in the set.
    pub fn is_empty(&self) -> bool {
        self.members.is_empty()
    }

    /// Number of members.
    pub fn count(&self) -> usize {
        self.members.len()
    }

    /// The members in increasing order.
    pub fn iter(&self) -> impl Iterator<Item = usize> + '_ {
        self.members.iter().map(|&i| i as usize)
    }

    /// The members, increasing.
    pub fn as_slice(&self) -> &[u32] {
        &self.members
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_get_iter() {
        let mut b = BitSet::new(130);
        assert!(b.is_empty());
        for i in [0, 63, 64, 129] {
            b.set(i, true);
        }
        b.set(63, false);
        assert_eq!(b.iter().collect::<Vec<_>>(), vec![0, 64, 129]);
        assert_eq!(b.count(), 3);
        assert!(b.get(129) && !b.get(1));
    }

    #[test]
    fn map_set_agrees_with_bit_set() {
        let mut b = BitSet::new(300);
        let mut m = MapSet::new();
        for (k, i) in [5usize, 299, 0, 64, 5, 128, 64].into_iter().enumerate() {
            let v = k % 3 != 2;
            b.set(i, v);
            m.set(i, v);
            assert_eq!(b.iter().collect::<Vec<_>>(), m.iter().collect::<Vec<_>>());
        }
        assert_eq!(b.count(), m.count());
        assert!(m.get(299) && !m.get(1) && !m.is_empty());
        let mut merged = m.clone();
        merged.merge(&[
            (0, true),
            (5, false),
            (5, true),
            (7, true),
            (299, false),
            (400, true),
        ]);
        let mut one_by_one = m.clone();
        for (i, v) in [(0, true), (5, true), (7, true), (299, false), (400, true)] {
            one_by_one.set(i, v);
        }
        assert_eq!(merged, one_by_one);
        assert_eq!(MapSet::from_sorted(vec![0, 299]), {
            let mut x = MapSet::new();
            x.set(299, true);
            x.set(0, true);
            x
        });
    }
}
