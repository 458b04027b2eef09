//! Likely separating directions of a subassembly: the coordinate axes, edge
//! directions shared by many pieces, and the most common touching normals.

use super::cache::BLOCK;
use super::DirectionQuery;
use apart_kernel::Vec3;
use rayon::prelude::*;
use rustc_hash::FxHashMap;
use std::sync::atomic::Ordering;

impl DirectionQuery<'_> {
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
    pub(super) fn touching_counts(&self, sub: &[usize]) -> FxHashMap<Vec3, usize> {
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
