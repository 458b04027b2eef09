//! Whether a pair of parts blocks a direction: pairs of boxes by their box of
//! differences, the others by their separating axes, then by their polygons (contact
//! cones first, full sums deepest on the ray first), stopping at the first blocker.

use super::cache::PairRef;
use super::DirectionQuery;
use crate::pairs::{classify, open_box_blocks, ray_meets_box, FloatBox, Sep};
use crate::PlanError;
use apart_kernel::Vec3;
use rayon::prelude::*;

impl DirectionQuery<'_> {
    /// The piece pairs among `near` (from [`DirectionQuery::along_ray`]) that `x` does
    /// not put outside their closed projections, with their status: the ray along `x`
    /// meets the box of the pair's sum (exactly), and the axes do not exclude `x`. In
    /// increasing order.
    pub(super) fn classify_near(
        &self,
        p: PairRef<'_>,
        near: Vec<usize>,
        x: &Vec3,
    ) -> Vec<(usize, Sep)> {
        let (i, j, nb) = (p.i, p.j, p.nb);
        let sep = |k: usize| {
            let (a, b) = (k / nb, k % nb);
            let (pa, pb) = (&self.parts[i].pieces[a], &self.parts[j].pieces[b]);
            if !ray_meets_box(&self.info[i][a], pa.den(), &self.info[j][b], pb.den(), x) {
                return None;
            }
            let s = classify(self.axes(p, k), x);
            (s != Sep::Outside).then_some((k, s))
        };
        if near.len() <= 64 {
            return near.into_iter().filter_map(sep).collect();
        }
        near.into_par_iter()
            .with_min_len(64)
            .filter_map(sep)
            .collect()
    }

    /// What the pairs of boxes among the piece pairs `near` of parts `i < j` say of `x`,
    /// without the pair's caches (each by its open box of differences): `Some(true)`
    /// when one blocks; `Some(false)` when every piece pair is a pair of boxes and none
    /// blocks (or overlaps); else `None`.
    pub(super) fn boxes_block(&self, i: usize, j: usize, near: &[usize], x: &Vec3) -> Option<bool> {
        let nb = self.parts[j].pieces.len();
        let mut all = true;
        for &k in near {
            let (a, b) = (k / nb, k % nb);
            if !(self.boxy[i][a] && self.boxy[j][b]) {
                all = false;
                continue;
            }
            let (pa, pb) = (&self.parts[i].pieces[a], &self.parts[j].pieces[b]);
            match open_box_blocks(&self.info[i][a], pa.den(), &self.info[j][b], pb.den(), x) {
                Some(true) => return Some(true),
                Some(false) => {}
                None => all = false,
            }
        }
        all.then_some(false)
    }

    /// For a pair of parts at `x` (its smaller part moving along `x`): a piece pair
    /// whose open polygon contains `x` (then `x` is blocked), or `None`. Pairs of boxes
    /// first (by their box of differences), then touching pairs (cheap cones), then the
    /// others (full sums), deepest on the ray first, in growing chunks, stopping at the
    /// first that blocks.
    pub(super) fn blocker(
        &self,
        p: PairRef<'_>,
        sep: &[(usize, Sep)],
        x: &Vec3,
    ) -> Result<Option<usize>, PlanError> {
        if sep.iter().all(|(_, s)| *s != Sep::Unknown) {
            return Ok(None);
        }
        let (i, j, nb) = (p.i, p.j, p.nb);
        // Pairs of boxes first, each decided by its open box of differences.
        let mut undecided = Vec::new();
        for k in sep
            .iter()
            .filter(|(_, s)| *s == Sep::Unknown)
            .map(|(k, _)| *k)
        {
            let (a, b) = (k / nb, k % nb);
            if self.boxy[i][a] && self.boxy[j][b] {
                let (pa, pb) = (&self.parts[i].pieces[a], &self.parts[j].pieces[b]);
                match open_box_blocks(&self.info[i][a], pa.den(), &self.info[j][b], pb.den(), x) {
                    Some(true) => return Ok(Some(k)),
                    Some(false) => continue,
                    None => {}
                }
            }
            undecided.push(k);
        }
        let (touching, others): (Vec<usize>, Vec<usize>) = undecided
            .into_iter()
            .partition(|&k| self.axes(p, k).iter().any(|a| !a.strict));
        // Pairs whose sum's box the ray crosses nearest its middle first (the likeliest
        // to block), in chunks growing from 2 to 64: the first blocker is often among
        // the first few.
        let u = x.unit_f64();
        let mut depth: Vec<(f64, usize)> = others
            .iter()
            .map(|&k| {
                let (a, b) = (&self.info[i][k / nb], &self.info[j][k % nb]);
                (ray_depth(a.float_bounds, b.float_bounds, &u), k)
            })
            .collect();
        depth.sort_by(|p, q| q.0.total_cmp(&p.0).then(p.1.cmp(&q.1)));
        let others: Vec<usize> = depth.into_iter().map(|(_, k)| k).collect();
        let mut chunks: Vec<&[usize]> = vec![&touching[..]];
        let (mut start, mut size) = (0, 2);
        while start < others.len() {
            let end = (start + size).min(others.len());
            chunks.push(&others[start..end]);
            (start, size) = (end, (size * 2).min(64));
        }
        let hit = |k: usize| -> Result<Option<usize>, PlanError> {
            Ok(self.polygon(p, k)?.contains_open(x).then_some(k))
        };
        for chunk in chunks {
            let found = if chunk.len() == 1 {
                hit(chunk[0])?
            } else {
                let hits: Vec<Option<usize>> = chunk
                    .par_iter()
                    .map(|&k| hit(k))
                    .collect::<Result<_, _>>()?;
                hits.into_iter().flatten().next()
            };
            if found.is_some() {
                return Ok(found);
            }
        }
        Ok(None)
    }

    /// Whether part `i`, moving along `d`, hits part `j` (an arc `i → j` of the blocking
    /// graph at `d`), from the piece pairs alone: no cell kind, so no polygon is made
    /// for a pair that `d` does not enter. What "can this set move along `d`" needs.
    pub fn hits(&self, i: usize, j: usize, d: &Vec3) -> Result<bool, PlanError> {
        let d = d.primitive();
        // Part i along d meets j exactly when j along −d meets i: the pair is stored once.
        let (i, j, x) = if i < j { (i, j, d) } else { (j, i, d.neg()) };
        let near = self.along_ray(i, j, &x);
        if let Some(blocked) = self.boxes_block(i, j, &near, &x) {
            return Ok(blocked);
        }
        let p = self.pair(i, j);
        let sep = self.classify_near(p, near, &x);
        Ok(self.blocker(p, &sep, &x)?.is_some())
    }
}

/// How deep inside the box of the sum `b ⊕ −a` (boxes `(lo, hi)` of `a` and `b`) the
/// ray along the unit vector `u` runs: the relative depth (0 to 1/2) of its chord's
/// middle point, least over the axes; 0 when it misses. Floating point, a preference.
fn ray_depth(a: FloatBox, b: FloatBox, u: &[f64; 3]) -> f64 {
    let lo: [f64; 3] = std::array::from_fn(|k| b.0[k] - a.1[k]);
    let hi: [f64; 3] = std::array::from_fn(|k| b.1[k] - a.0[k]);
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for k in 0..3 {
        if u[k] != 0.0 {
            let (p, q) = (lo[k] / u[k], hi[k] / u[k]);
            t0 = t0.max(p.min(q));
            t1 = t1.min(p.max(q));
        }
    }
    if t1 < t0 || !t1.is_finite() {
        return 0.0;
    }
    let t = 0.5 * (t0 + t1);
    (0..3)
        .map(|k| {
            let (w, p) = (hi[k] - lo[k], t * u[k]);
            if w > 0.0 {
                ((p - lo[k]).min(hi[k] - p) / w).max(0.0)
            } else {
                0.0
            }
        })
        .fold(0.5, f64::min)
}
