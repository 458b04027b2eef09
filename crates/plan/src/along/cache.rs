//! The piece-pair caches of a [`DirectionQuery`]: each pair's separating axes and
//! polygon, made on first use and kept between queries, in blocks made on demand.

use super::DirectionQuery;
use crate::pairs::{axes, pair_polygon, Axis, PairPolygon};
use crate::PlanError;
use apart_sphere::SphericalPolygon;
use rustc_hash::FxHashMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{OnceLock, PoisonError, RwLock};

/// Piece pairs per block of [`DirectionQuery`]'s cache.
pub(super) const BLOCK: usize = 64;

/// Lazily computed data of one piece pair (`a` of the smaller part index, `b` of the
/// larger).
#[derive(Default)]
pub(super) struct PairCache {
    pub(super) axes: OnceLock<Vec<Axis>>,
    pub(super) polygon: OnceLock<Result<PairPolygon, String>>,
}

/// One part pair's piece pairs (`a * |j| + b`), in blocks of at most [`BLOCK`] made when
/// a pair in them is first asked for: two parts of a thousand pieces each make a million
/// pairs, of which a query touches few.
pub(super) type PairBlocks = Box<[OnceLock<Box<[PairCache]>>]>;

/// Shards of [`PairCaches`]' map (queries run on every thread).
const SHARDS: usize = 16;

/// Chunks of [`Arena`]: chunk `c` holds `64 << c` slots.
const CHUNKS: usize = 40;

/// Slots that never move once made, handed out one at a time: references into them
/// live as long as the arena, whatever is added later.
struct Arena<T> {
    chunks: Vec<OnceLock<Box<[OnceLock<T>]>>>,
    next: AtomicUsize,
}

impl<T> Arena<T> {
    fn new() -> Arena<T> {
        Arena {
            chunks: (0..CHUNKS).map(|_| OnceLock::new()).collect(),
            next: AtomicUsize::new(0),
        }
    }

    /// Slot `k` (its chunk made on first use).
    fn slot(&self, k: usize) -> &OnceLock<T> {
        let c = (k / 64 + 1).ilog2() as usize;
        let start = 64 * ((1 << c) - 1);
        let chunk = self.chunks[c].get_or_init(|| (0..64 << c).map(|_| OnceLock::new()).collect());
        &chunk[k - start]
    }
}

/// The piece-pair caches of the part pairs asked for so far: a map from a part pair to
/// its slot in an arena, filled on demand (memory grows with the pairs a query looks
/// at, not with the square of the part count).
pub(super) struct PairCaches {
    shards: Vec<RwLock<FxHashMap<(u32, u32), usize>>>,
    slots: Arena<PairBlocks>,
}

impl PairCaches {
    pub(super) fn new() -> PairCaches {
        PairCaches {
            shards: (0..SHARDS).map(|_| RwLock::default()).collect(),
            slots: Arena::new(),
        }
    }

    /// The blocks of parts `i < j`, if made.
    pub(super) fn peek(&self, i: usize, j: usize) -> Option<&PairBlocks> {
        let k = self.shards[shard(i, j)]
            .read()
            .unwrap_or_else(PoisonError::into_inner)
            .get(&(i as u32, j as u32))
            .copied()?;
        self.slots.slot(k).get()
    }

    /// The blocks of parts `i < j` with `m` piece pairs, made when first asked for.
    pub(super) fn get(&self, i: usize, j: usize, m: usize) -> &PairBlocks {
        let key = (i as u32, j as u32);
        let shard = &self.shards[shard(i, j)];
        let found = shard
            .read()
            .unwrap_or_else(PoisonError::into_inner)
            .get(&key)
            .copied();
        let k = found.unwrap_or_else(|| {
            let mut map = shard.write().unwrap_or_else(PoisonError::into_inner);
            *map.entry(key).or_insert_with(|| {
                // The slot is filled before its index is published under the lock.
                let k = self.slots.next.fetch_add(1, Ordering::Relaxed);
                let blocks = (0..m.div_ceil(BLOCK)).map(|_| OnceLock::new()).collect();
                let _ = self.slots.slot(k).set(blocks);
                k
            })
        });
        self.slots
            .slot(k)
            .get()
            .expect("a pair's slot is filled before it is published")
    }
}

/// The shard of the pair of parts `i < j`.
fn shard(i: usize, j: usize) -> usize {
    (i.wrapping_mul(0x9E37_79B9) ^ j) % SHARDS
}

/// A pair of parts `i < j` (`nb` pieces in `j`, `m` piece pairs) and its piece-pair
/// caches.
#[derive(Clone, Copy)]
pub(super) struct PairRef<'q> {
    pub(super) i: usize,
    pub(super) j: usize,
    pub(super) nb: usize,
    m: usize,
    blocks: &'q PairBlocks,
}

impl<'q> PairRef<'q> {
    /// The cache of piece pair `k`.
    pub(super) fn cell(self, k: usize) -> &'q PairCache {
        let start = k / BLOCK * BLOCK;
        let block = self.blocks[k / BLOCK].get_or_init(|| {
            (start..self.m.min(start + BLOCK))
                .map(|_| PairCache::default())
                .collect()
        });
        &block[k - start]
    }
}

impl DirectionQuery<'_> {
    /// The pair of parts `i < j` with its piece-pair caches (looked up once for all
    /// the pair's piece pairs).
    pub(super) fn pair(&self, i: usize, j: usize) -> PairRef<'_> {
        let nb = self.parts[j].pieces.len();
        let m = self.parts[i].pieces.len() * nb;
        PairRef {
            i,
            j,
            nb,
            m,
            blocks: self.cache.get(i, j, m),
        }
    }

    /// The separating axes of piece pair `k`.
    pub(super) fn axes<'q>(&self, p: PairRef<'q>, k: usize) -> &'q [Axis] {
        let (a, b, i, j) = (k / p.nb, k % p.nb, p.i, p.j);
        p.cell(k).axes.get_or_init(|| {
            self.n_axes.fetch_add(1, Ordering::Relaxed);
            axes(
                &self.parts[i].pieces[a],
                &self.info[i][a],
                &self.parts[j].pieces[b],
                &self.info[j][b],
            )
        })
    }

    /// The closed polygon of piece pair `k` (its Minkowski sum's projection, or its
    /// contact cone).
    pub(super) fn polygon<'q>(
        &self,
        p: PairRef<'q>,
        k: usize,
    ) -> Result<&'q SphericalPolygon, PlanError> {
        let (a, b, i, j) = (k / p.nb, k % p.nb, p.i, p.j);
        let axes = self.axes(p, k);
        let r = p.cell(k).polygon.get_or_init(|| {
            let r = pair_polygon(
                &self.parts[i].pieces[a],
                &self.info[i][a],
                &self.parts[j].pieces[b],
                &self.info[j][b],
                axes,
            );
            match r {
                Ok((p, full)) => {
                    let c = if full { &self.n_sums } else { &self.n_cones };
                    c.fetch_add(1, Ordering::Relaxed);
                    Ok(p)
                }
                Err(e) => Err(e),
            }
        });
        match r {
            Ok(PairPolygon::Polygon(p, _)) => Ok(p),
            Ok(PairPolygon::Overlap) => Err(PlanError::Overlap {
                parts: (i, j),
                names: (self.parts[i].name.clone(), self.parts[j].name.clone()),
                pieces: (a, b),
            }),
            Err(e) => Err(crate::pairs::internal(
                (&self.parts[i].name, &self.parts[j].name),
                e.clone(),
            )),
        }
    }
}
