//! Pair regions computed when a planner first asks for them, and kept.
//!
//! [`BlockingRegions::compute`] makes the region of every pair of parts up front, which
//! grows with the square of the part count: half a million pairs for a thousand parts,
//! most of them far apart and never needed to find a step. A [`PairStore`] makes a
//! pair's region the first time it is asked for (in parallel for a batch of pairs), so
//! the incremental sequence planner pays only for the pairs near the parts it looks at
//! (and the far ones in their free directions). Each part's box is kept for the
//! planner's broad phase.

use crate::progress::Progress;
use crate::regions::{
    regions_in_batches, BlockingRegions, PairRegion, Part, PartData, RegionStats,
};
use crate::PlanError;
use apart_kernel::Aabb;
use rayon::prelude::*;
use rustc_hash::FxHashMap;
use std::sync::{Arc, Mutex, OnceLock, RwLock};

/// Pair regions made on demand and kept, with each part's box.
pub struct PairStore<'a> {
    parts: &'a [Part],
    data: Vec<OnceLock<PartData>>,
    boxes: Vec<Aabb>,
    map: RwLock<FxHashMap<(u32, u32), Arc<PairRegion>>>,
    stats: Mutex<RegionStats>,
}

impl<'a> PairStore<'a> {
    /// A store for `parts` with no region made yet. [`PlanError::NoPieces`] for a part
    /// without pieces.
    pub fn new(parts: &'a [Part]) -> Result<PairStore<'a>, PlanError> {
        for (k, p) in parts.iter().enumerate() {
            if p.pieces.is_empty() {
                return Err(PlanError::NoPieces {
                    part: k,
                    name: p.name.clone(),
                });
            }
        }
        let boxes = parts.par_iter().map(part_box).collect();
        let stats = RegionStats {
            pieces: parts.iter().map(|p| p.pieces.len()).sum(),
            ..Default::default()
        };
        Ok(PairStore {
            parts,
            data: (0..parts.len()).map(|_| OnceLock::new()).collect(),
            boxes,
            map: RwLock::default(),
            stats: Mutex::new(stats),
        })
    }

    /// The parts.
    pub fn parts(&self) -> &'a [Part] {
        self.parts
    }

    /// The integer box of each part (exact on the grid, rounded outward where a cut
    /// piece has rational vertices; a part too large for `i64` boxes gets a box holding
    /// everything).
    pub fn boxes(&self) -> &[Aabb] {
        &self.boxes
    }

    /// Counts and times of the regions made so far.
    pub fn stats(&self) -> RegionStats {
        let mut s = *self.stats.lock().unwrap_or_else(|e| e.into_inner());
        s.region_arcs = self.read().values().map(|r| r.region.arcs.len()).sum();
        s
    }

    /// Pair regions made so far.
    pub fn len(&self) -> usize {
        self.read().len()
    }

    /// True when no pair region has been made.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn read(&self) -> std::sync::RwLockReadGuard<'_, FxHashMap<(u32, u32), Arc<PairRegion>>> {
        self.map.read().unwrap_or_else(|e| e.into_inner())
    }

    fn data(&self, k: usize) -> &PartData {
        self.data[k].get_or_init(|| PartData::new(&self.parts[k]))
    }

    /// The region of the unordered pair `{i, j}` (stored as `Q_min,max`), if made.
    pub fn get(&self, i: usize, j: usize) -> Option<Arc<PairRegion>> {
        let key = (i.min(j) as u32, i.max(j) as u32);
        self.read().get(&key).cloned()
    }

    /// Piece pairs of the parts `i` and `j`.
    pub fn piece_pairs(&self, i: usize, j: usize) -> usize {
        self.parts[i].pieces.len() * self.parts[j].pieces.len()
    }

    /// Whether parts `i` and `j` touch, when known (their region was made).
    pub fn contact(&self, i: usize, j: usize) -> Option<bool> {
        self.get(i, j).map(|r| r.contact)
    }

    /// Makes the regions of the unordered pairs `pairs` not made yet, in parallel, a
    /// batch of pairs at a time. The stop flag of `progress` is watched between batches
    /// and pairs: stopped, nothing of the unfinished batch is kept.
    pub fn ensure(&self, pairs: &[(usize, usize)], progress: &Progress) -> Result<(), PlanError> {
        let mut todo: Vec<(usize, usize)> = {
            let map = self.read();
            pairs
                .iter()
                .map(|&(i, j)| (i.min(j), i.max(j)))
                .filter(|&(i, j)| i != j && !map.contains_key(&(i as u32, j as u32)))
                .collect()
        };
        todo.sort_unstable();
        todo.dedup();
        let mut made = Vec::new();
        let mut stats = RegionStats::default();
        regions_in_batches(
            self.parts,
            &|k| self.data(k),
            &todo,
            progress,
            &|| {},
            &mut |r, s, scale| {
                stats.add(s, scale);
                made.push(r);
            },
        )?;
        self.stats
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .add(&stats, 1.0);
        let mut map = self.map.write().unwrap_or_else(|e| e.into_inner());
        for r in made {
            map.insert((r.i as u32, r.j as u32), Arc::new(r));
        }
        Ok(())
    }

    /// The regions of every pair of the parts `sub` (global indices, increasing), made
    /// where missing, as [`BlockingRegions`] over local indices (part `k` of the result is
    /// `sub[k]`).
    pub fn regions_of(
        &self,
        sub: &[usize],
        progress: &Progress,
    ) -> Result<BlockingRegions, PlanError> {
        let pairs: Vec<(usize, usize)> = sub
            .iter()
            .enumerate()
            .flat_map(|(li, &i)| sub[li + 1..].iter().map(move |&j| (i, j)))
            .collect();
        self.ensure(&pairs, progress)?;
        let map = self.read();
        let local: Vec<PairRegion> = sub
            .iter()
            .enumerate()
            .flat_map(|(li, &i)| {
                let map = &map;
                sub.iter().enumerate().skip(li + 1).map(move |(lj, &j)| {
                    let key = (i.min(j) as u32, i.max(j) as u32);
                    let r = &map[&key];
                    // Stored with the smaller global index moving: `sub` is increasing,
                    // so that is the smaller local index too.
                    debug_assert!(i < j);
                    PairRegion {
                        i: li,
                        j: lj,
                        ..PairRegion::clone(r)
                    }
                })
            })
            .collect();
        drop(map);
        Ok(BlockingRegions::from_pairs(
            sub.iter().map(|&k| self.parts[k].name.clone()).collect(),
            sub.iter().map(|&k| self.parts[k].pieces.clone()).collect(),
            local,
            self.stats(),
        ))
    }
}

/// The exact integer box of `p`'s pieces (a rational vertex's coordinates rounded
/// outward), or one holding everything when a coordinate is too large for it.
fn part_box(p: &Part) -> Aabb {
    p.pieces
        .iter()
        .try_fold(Aabb::EMPTY, |b, q| Some(b.union(&q.integer_box()?)))
        .unwrap_or(Aabb {
            min: [-(1 << 62); 3],
            max: [1 << 62; 3],
        })
}
