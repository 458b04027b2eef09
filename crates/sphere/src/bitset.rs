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

/// Words of a [`MapSet`] held inline: maps below `64 * INLINE_WORDS` (the `n (n − 1)`
/// maps of up to 20 parts) are bits in the set itself.
const INLINE_WORDS: usize = 6;
const INLINE_BITS: u32 = 64 * INLINE_WORDS as u32;

/// A set of map indices: the blocking status of a cell. A motion space of `n` parts has
/// `n (n − 1)` maps. Up to 20 parts the set is a bit array held inline (no allocation,
/// 48 bytes, where a dense assembly's cells are covered by about half the maps); with a
/// member of 384 or more it is a sorted list, since few of many maps cover any one cell
/// and a [`BitSet`] would take `n² / 8` bytes per cell.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub struct MapSet {
    repr: Repr,
}

/// Canonical: `Sorted` exactly when some member is at least `INLINE_BITS`, so that the
/// derived equality and hash are those of the sets.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
enum Repr {
    Inline([u64; INLINE_WORDS]),
    Sorted(Vec<u32>),
}

impl Default for MapSet {
    fn default() -> MapSet {
        MapSet {
            repr: Repr::Inline([0; INLINE_WORDS]),
        }
    }
}

impl MapSet {
    /// Sets of members all below this are held inline (no allocation); a larger member
    /// makes the set a sorted list of 4 bytes per member.
    pub const INLINE_MAPS: usize = INLINE_BITS as usize;

    /// The empty set.
    pub fn new() -> MapSet {
        MapSet::default()
    }

    /// The set of `members`, which must be strictly increasing.
    pub fn from_sorted(members: Vec<u32>) -> MapSet {
        debug_assert!(members.windows(2).all(|w| w[0] < w[1]), "not sorted");
        match members.last() {
            Some(&m) if m >= INLINE_BITS => MapSet {
                repr: Repr::Sorted(members),
            },
            _ => {
                let mut words = [0; INLINE_WORDS];
                for m in members {
                    words[m as usize / 64] |= 1 << (m % 64);
                }
                MapSet {
                    repr: Repr::Inline(words),
                }
            }
        }
    }

    /// Whether `i` is in the set.
    #[inline]
    pub fn get(&self, i: usize) -> bool {
        match &self.repr {
            Repr::Inline(w) => i < INLINE_BITS as usize && w[i / 64] >> (i % 64) & 1 == 1,
            Repr::Sorted(m) => m.binary_search(&(i as u32)).is_ok(),
        }
    }

    /// Adds (`v = true`) or removes `i`.
    pub fn set(&mut self, i: usize, v: bool) {
        let i = u32::try_from(i).expect("map index below 2^32");
        match &mut self.repr {
            Repr::Inline(w) if i < INLINE_BITS => {
                let bit = 1u64 << (i % 64);
                if v {
                    w[i as usize / 64] |= bit;
                } else {
                    w[i as usize / 64] &= !bit;
                }
            }
            Repr::Inline(_) => {
                if v {
                    let mut members: Vec<u32> = self.iter().map(|m| m as u32).collect();
                    members.push(i);
                    self.repr = Repr::Sorted(members);
                }
            }
            Repr::Sorted(m) => {
                match (m.binary_search(&i), v) {
                    (Err(k), true) => m.insert(k, i),
                    (Ok(k), false) => {
                        m.remove(k);
                    }
                    _ => {}
                }
                self.settle();
            }
        }
    }

    /// Back to the inline form when no member is large any more.
    fn settle(&mut self) {
        if let Repr::Sorted(m) = &mut self.repr {
            if m.last().is_none_or(|&l| l < INLINE_BITS) {
                let m = std::mem::take(m);
                *self = MapSet::from_sorted(m);
            }
        }
    }

    /// Sets each `(i, on)` of `changes`, sorted by `i`; of several changes of one `i`, the
    /// last wins. Linear in the set and the changes.
    pub fn merge(&mut self, changes: &[(u32, bool)]) {
        let Repr::Sorted(members) = &self.repr else {
            for &(i, on) in changes {
                self.set(i as usize, on);
            }
            return;
        };
        let mut out = Vec::with_capacity(members.len() + changes.len());
        let mut old = members.iter().copied().peekable();
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
        self.repr = Repr::Sorted(out);
        self.settle();
    }

    /// True when the changes need no sorting to apply (the inline form sets bits one by
    /// one in order).
    pub(crate) fn is_inline(&self) -> bool {
        matches!(self.repr, Repr::Inline(_))
    }

    /// True when no integer is in the set.
    pub fn is_empty(&self) -> bool {
        match &self.repr {
            Repr::Inline(w) => w.iter().all(|&x| x == 0),
            Repr::Sorted(m) => m.is_empty(),
        }
    }

    /// Number of members.
    pub fn count(&self) -> usize {
        match &self.repr {
            Repr::Inline(w) => w.iter().map(|x| x.count_ones() as usize).sum(),
            Repr::Sorted(m) => m.len(),
        }
    }

    /// The members in increasing order.
    pub fn iter(&self) -> impl Iterator<Item = usize> + '_ {
        let (words, sorted): (&[u64], &[u32]) = match &self.repr {
            Repr::Inline(w) => (w, &[]),
            Repr::Sorted(m) => (&[], m),
        };
        let bits = words.iter().enumerate().flat_map(|(k, &w)| {
            let mut w = w;
            std::iter::from_fn(move || {
                (w != 0).then(|| {
                    let b = w.trailing_zeros() as usize;
                    w &= w - 1;
                    64 * k + b
                })
            })
        });
        bits.chain(sorted.iter().map(|&i| i as usize))
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

    /// Random sets, changes and merges across the inline bound (a member of 384 or
    /// more turns the set into a sorted list, and removing it turns it back) agree with
    /// a `BTreeSet`, and equal sets compare and hash equal whatever their history.
    #[test]
    fn map_set_agrees_with_btree_across_the_inline_bound() {
        use std::collections::BTreeSet;
        use std::hash::{BuildHasher, RandomState};
        let hasher = RandomState::new();
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = |n: u64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed % n
        };
        for _ in 0..200 {
            let mut m = MapSet::new();
            let mut r = BTreeSet::new();
            for _ in 0..60 {
                let i = if next(4) == 0 {
                    380 + next(20)
                } else {
                    next(400)
                } as u32;
                let on = next(3) != 0;
                if next(5) == 0 {
                    let mut changes: Vec<(u32, bool)> = (0..next(6))
                        .map(|_| (next(420) as u32, next(2) == 0))
                        .collect();
                    changes.sort_by_key(|c| c.0);
                    for &(k, v) in &changes {
                        if v {
                            r.insert(k);
                        } else {
                            r.remove(&k);
                        }
                    }
                    m.merge(&changes);
                } else {
                    m.set(i as usize, on);
                    if on {
                        r.insert(i);
                    } else {
                        r.remove(&i);
                    }
                }
                let members: Vec<usize> = r.iter().map(|&k| k as usize).collect();
                assert_eq!(m.iter().collect::<Vec<_>>(), members);
                assert_eq!(m.count(), r.len());
                assert_eq!(m.is_empty(), r.is_empty());
                assert!(r.iter().all(|&k| m.get(k as usize)));
                assert!(!m.get(1000));
                let fresh = MapSet::from_sorted(r.iter().copied().collect());
                assert_eq!(m, fresh);
                assert_eq!(hasher.hash_one(&m), hasher.hash_one(&fresh));
            }
        }
    }
}
