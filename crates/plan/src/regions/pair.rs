//! The blocked region of one pair of parts: separating axes of every piece pair,
//! contact cones of touching ones, full sums of the others not already covered, then
//! the pruned polygons' union.

use super::prune::{pruned, pruned_split};
use super::union::{merge_unions, union_of_pruned};
use super::{PairRegion, Part, PartData, RegionStats};
use crate::cull::{largest, uncovered_pairs, Cover};
use crate::pairs::{axes, below_along_any, contact_polygon, Axis, PairPolygon};
use crate::progress::{phases, Progress};
use crate::PlanError;
use apart_kernel::{Bvh, Vec3};
use apart_minkowski::{project, project_apart, sum_prepared, Projection};
use apart_pieces::Polytope;
use apart_sphere::region::RegionMap;
use apart_sphere::SphericalPolygon;
use rayon::prelude::*;
use rustc_hash::{FxHashMap, FxHashSet};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// A touching piece pair's contact cone, and whether the pieces touch.
type Cone = (SphericalPolygon, bool);

/// Piece pairs to sum in a part pair from which on groups of them are culled. Low: a
/// part of few large pieces (a bolt's 600-sided shaft) against one of many makes few
/// pairs but costly sums and polygons (bolt and nut of the 50k joint: 2,708 pairs summed
/// in 66 s and 2.3 GB without culling, 1,376 in 18 s and 333 MB with it).
const CULL_MIN: usize = 1 << 8;

/// Piece pairs summed per culling round at most.
const CULL_ROUND: usize = 1 << 10;

/// The largest pieces of each part whose pairwise sums seed the culling union.
const CULL_SEEDS_PER_PART: usize = 8;

/// Full sums whose polygons are made before those inside another are dropped.
const PRUNE_CHUNK: usize = 1 << 14;

/// The region of parts `i < j`: separating axes of every piece pair, contact cones of
/// touching ones, full sums for the rest except those a face contact's hemisphere
/// already covers, then the pruned polygons' union (timings added to `stats`). The stop
/// flag is checked between culling rounds and between chunks of sums.
pub(super) fn pair_region(
    parts: &[Part],
    (di, dj): (&PartData, &PartData),
    i: usize,
    j: usize,
    stats: &mut RegionStats,
    progress: &Progress,
) -> Result<PairRegion, PlanError> {
    let pair = PiecePairs::new(parts, (di, dj), i, j);
    let t = Instant::now();
    let contacts = pair.contacts()?;
    let cone_count = contacts.cones.len();
    stats.contact_cones += cone_count;
    let hemispheres = face_hemispheres(&contacts.cones);
    let axes_seconds = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let todo = pair.uncovered(&contacts, &hemispheres);
    // The near pairs' axes are no longer needed (memory).
    let Contacts { cones, near, .. } = contacts;
    drop(near);
    stats.skipped += pair.jobs.len() - todo.len() - cone_count;
    // The contact cones, then the full sums' polygons a chunk at a time, each chunk
    // pruned of polygons inside another before the next is made (memory: a polygon
    // inside another of its chunk lies inside a kept one, so pruning by chunks and then
    // all the kept ones together keeps the same union).
    let mut contact = false;
    let polygons = cones
        .into_iter()
        .map(|(p, touch)| {
            contact |= touch;
            p
        })
        .collect();
    let mut found = Found {
        polygons,
        contact,
        prune_seconds: 0.0,
    };
    // Many pairs: the largest pieces' sums first, then rounds of the groups of pairs
    // whose bounding projection is not inside the union so far (crate::cull); a round's
    // polygons inside that union are dropped, the rest extend it.
    let (todo, united) = match (&di.tree, &dj.tree) {
        (Some(ti), Some(tj)) if todo.len() >= CULL_MIN => {
            let (map, summed) = pair.cull_rounds((ti, tj), &todo, &mut found, progress)?;
            stats.culled += todo.len() - summed;
            stats.sums += summed;
            (Vec::new(), Some(map))
        }
        _ => (todo, None),
    };
    stats.sums += todo.len();
    pair.sum_in_chunks(&todo, &mut found, progress)?;
    let Found {
        polygons,
        contact,
        prune_seconds,
    } = found;
    let wall = t.elapsed().as_secs_f64() - prune_seconds;
    let (sn, pn) = pair.sum_and_projection_nanos();
    let share = if sn + pn > 0.0 { sn / (sn + pn) } else { 1.0 };
    stats.sums_seconds += axes_seconds + wall * share;
    stats.projection_seconds += wall * (1.0 - share);

    let t = Instant::now();
    // Only the polygons that add to the union are kept (memory).
    let (polygons, region) = match united {
        Some(map) => (polygons, map),
        None => {
            let polygons = pruned(polygons);
            let region = union_of_pruned(&polygons);
            (polygons, region)
        }
    };
    stats.unions_seconds += prune_seconds + t.elapsed().as_secs_f64();
    Ok(PairRegion {
        i,
        j,
        polygons,
        region,
        contact,
    })
}

/// The piece pairs `(a, b)` of parts `i < j` (pair `k` is `a * |j| + b`), with what
/// making their polygons needs and the time spent on sums and on projections.
struct PiecePairs<'p> {
    parts: &'p [Part],
    pi: &'p [Polytope],
    pj: &'p [Polytope],
    di: &'p PartData,
    dj: &'p PartData,
    i: usize,
    j: usize,
    jobs: Vec<(usize, usize)>,
    sum_ns: AtomicU64,
    proj_ns: AtomicU64,
}

/// What the first pass over the piece pairs finds: the contact cones of touching pairs
/// (`is_cone` marks them), and the separating axes of the pairs near each other that
/// are neither touching nor strictly apart.
struct Contacts {
    is_cone: Vec<bool>,
    cones: Vec<Cone>,
    near: FxHashMap<usize, Vec<Axis>>,
}

/// The polygons of a pair made so far, whether some piece pair touches, and the time
/// spent pruning them.
struct Found {
    polygons: Vec<SphericalPolygon>,
    contact: bool,
    prune_seconds: f64,
}

/// The open hemispheres already in the union: the contact cones of face contacts.
fn face_hemispheres(cones: &[Cone]) -> FxHashSet<Vec3> {
    let mut hemispheres: FxHashSet<Vec3> = Default::default();
    for (p, _) in cones {
        if p.normals().len() == 1 {
            hemispheres.insert(p.normals()[0].clone());
        }
    }
    hemispheres
}

impl<'p> PiecePairs<'p> {
    /// Every piece pair of parts `i < j`.
    fn new(
        parts: &'p [Part],
        (di, dj): (&'p PartData, &'p PartData),
        i: usize,
        j: usize,
    ) -> PiecePairs<'p> {
        let (pi, pj) = (&parts[i].pieces, &parts[j].pieces);
        let jobs: Vec<(usize, usize)> = (0..pi.len())
            .flat_map(|a| (0..pj.len()).map(move |b| (a, b)))
            .collect();
        PiecePairs {
            parts,
            pi,
            pj,
            di,
            dj,
            i,
            j,
            jobs,
            sum_ns: AtomicU64::new(0),
            proj_ns: AtomicU64::new(0),
        }
    }

    /// The error of pieces `a` and `b` whose interiors overlap.
    fn overlap(&self, a: usize, b: usize) -> PlanError {
        let (i, j) = (self.i, self.j);
        PlanError::Overlap {
            parts: (i, j),
            names: (self.parts[i].name.clone(), self.parts[j].name.clone()),
            pieces: (a, b),
        }
    }

    /// An internal error of `what` for the two parts.
    fn internal(&self, what: &str, e: impl std::fmt::Display) -> PlanError {
        PlanError::Internal(format!(
            "{what} {} and {}: {e}",
            self.parts[self.i].name, self.parts[self.j].name
        ))
    }

    /// Separating axes of every piece pair (exact; coordinate axes first, which settle
    /// far-apart pairs at once). Touching pairs get their projection, the contact cone,
    /// from the small sum of their face neighbourhoods (the same polygon as the full
    /// sum's); the others near each other keep their axes for the cover test
    /// ([`PiecePairs::uncovered`]), and pairs strictly apart along a coordinate axis
    /// keep nothing (their axes are those coordinate axes, found again if the test
    /// needs them): most of a big pair's 10^6 piece pairs are such, and their axes were
    /// most of its memory.
    fn contacts(&self) -> Result<Contacts, PlanError> {
        enum First {
            Near(Vec<Axis>),
            Cone(Cone),
        }
        let (pi, pj, di, dj, jobs) = (self.pi, self.pj, self.di, self.dj, &self.jobs);
        let first: Vec<(usize, First)> = (0..jobs.len())
            .into_par_iter()
            .with_min_len(16)
            .filter_map(|k| {
                let (a, b) = jobs[k];
                let ax = axes(&pi[a], &di.info[a], &pj[b], &dj.info[b]);
                let Some(n) = crate::pairs::touching_normal(&ax) else {
                    return (!ax.iter().any(|x| x.strict)).then_some(Ok((k, First::Near(ax))));
                };
                match contact_polygon(&pi[a], &di.info[a], &pj[b], &dj.info[b], n) {
                    None => Some(Ok((k, First::Near(ax)))),
                    Some(Ok(PairPolygon::Polygon(p, touch))) => {
                        Some(Ok((k, First::Cone((p, touch)))))
                    }
                    Some(Ok(PairPolygon::Overlap)) => Some(Err(self.overlap(a, b))),
                    Some(Err(e)) => Some(Err(self.internal("pieces of", e))),
                }
            })
            .collect::<Result<_, _>>()?;
        let mut contacts = Contacts {
            is_cone: vec![false; jobs.len()],
            cones: Vec::new(),
            near: Default::default(),
        };
        for (k, f) in first {
            match f {
                First::Cone(c) => {
                    contacts.is_cone[k] = true;
                    contacts.cones.push(c);
                }
                First::Near(ax) => {
                    contacts.near.insert(k, ax);
                }
            }
        }
        Ok(contacts)
    }

    /// The piece pairs left to sum: neither touching (their cones are made) nor covered
    /// by `hemispheres`. A pair lying weakly below along an axis n has its projection
    /// in the closed hemisphere {n·x >= 0}: it adds nothing when the open one is in the
    /// union.
    fn uncovered(&self, contacts: &Contacts, hemispheres: &FxHashSet<Vec3>) -> Vec<usize> {
        let (pi, pj, di, dj) = (self.pi, self.pj, self.di, self.dj);
        let covered = |k: usize| {
            if hemispheres.is_empty() {
                return false;
            }
            let (a, b) = self.jobs[k];
            let in_union =
                |ax: &[Axis]| ax.iter().any(|ax| hemispheres.contains(&ax.n.primitive()));
            let by_axes = match contacts.near.get(&k) {
                Some(ax) => in_union(ax),
                None => in_union(&axes(&pi[a], &di.info[a], &pj[b], &dj.info[b])),
            };
            by_axes || below_along_any(&pi[a], &pj[b], hemispheres)
        };
        (0..self.jobs.len())
            .into_par_iter()
            .with_min_len(64)
            .filter(|&k| !contacts.is_cone[k] && !covered(k))
            .collect()
    }

    /// The polygon of piece pair `k` from its pieces apart (the facets facing the
    /// origin, without the sum) or its full Minkowski sum, with whether the pieces
    /// touch; the time of sums and projections counted.
    fn polygon(&self, k: usize) -> Result<Cone, PlanError> {
        let (a, b) = self.jobs[k];
        let cpu = |t: Instant| t.elapsed().as_nanos() as u64;
        let t0 = Instant::now();
        let (sb, sa) = (
            self.dj.info[b].fixed(&self.pj[b]),
            self.di.info[a].reflected(&self.pi[a]),
        );
        // Apart: the projection from the facets facing the origin, without the sum.
        if let Some(p) = project_apart(sb, sa) {
            self.sum_ns.fetch_add(cpu(t0), Ordering::Relaxed);
            return p
                .map(|p| (p, false))
                .map_err(|e| self.internal("projection for", e));
        }
        let m = sum_prepared(sb, sa).map_err(|e| self.internal("Minkowski sum of", e))?;
        self.sum_ns.fetch_add(cpu(t0), Ordering::Relaxed);
        let t1 = Instant::now();
        let out = match project(&m) {
            Ok(Projection::Polygon(p)) => {
                // Touching: no facet has the origin strictly outside.
                let contact = m
                    .facets()
                    .iter()
                    .all(|f| f.offset >= apart_kernel::Int::ZERO);
                Ok((p, contact))
            }
            Ok(Projection::Everything) => Err(self.overlap(a, b)),
            Err(e) => Err(self.internal("projection for", e)),
        };
        self.proj_ns.fetch_add(cpu(t1), Ordering::Relaxed);
        out
    }

    /// The polygons of the pairs `ks`, made in parallel (the first error in their
    /// order).
    fn polygons(&self, ks: &[usize]) -> Result<Vec<Cone>, PlanError> {
        ks.par_iter().map(|&k| self.polygon(k)).collect()
    }

    /// The nanoseconds spent on sums and on projections so far.
    fn sum_and_projection_nanos(&self) -> (f64, f64) {
        (
            self.sum_ns.load(Ordering::Relaxed) as f64,
            self.proj_ns.load(Ordering::Relaxed) as f64,
        )
    }

    /// The pairs `todo` (many) culled by rounds, with the parts' piece trees `ti`, `tj`:
    /// the largest pieces' sums first, then rounds of the groups of pairs whose bounding
    /// projection is not inside the union so far; a round's polygons inside that union
    /// are dropped, the rest extend it. Returns the union of `found`'s polygons and the
    /// number of pairs summed.
    fn cull_rounds(
        &self,
        (ti, tj): (&Bvh, &Bvh),
        todo: &[usize],
        found: &mut Found,
        progress: &Progress,
    ) -> Result<(RegionMap, usize), PlanError> {
        let (pi, pj) = (self.pi, self.pj);
        let mut need = vec![false; self.jobs.len()];
        for &k in todo {
            need[k] = true;
        }
        let (li, lj) = (
            largest(pi, CULL_SEEDS_PER_PART),
            largest(pj, CULL_SEEDS_PER_PART),
        );
        let mut round: Vec<usize> = li
            .iter()
            .flat_map(|&a| lj.iter().map(move |&b| a * pj.len() + b))
            .filter(|&k| need[k])
            .collect();
        let mut map = union_of_pruned(&found.polygons);
        let mut summed = 0;
        let mut settled = found.polygons.is_empty();
        loop {
            if progress.stopped() {
                return Err(stopped());
            }
            for &k in &round {
                need[k] = false;
            }
            summed += round.len();
            let made = self.polygons(&round)?;
            let t0 = Instant::now();
            let cover = Cover::new(&found.polygons, &map);
            found.contact |= made.iter().any(|(_, touch)| *touch);
            let new: Vec<SphericalPolygon> = made
                .into_par_iter()
                .filter_map(|(p, _)| (!cover.contains(&p)).then_some(p))
                .collect();
            if !new.is_empty() {
                // The round's own union, merged into the union so far.
                let new = pruned(new);
                map = merge_unions(&map, &found.polygons, &union_of_pruned(&new), &new);
                // The round's polygons are pruned, and so are the union's after the
                // first prune (the contact cones before it are not).
                let split = settled.then_some(found.polygons.len());
                found.polygons.extend(new);
                found.polygons = pruned_split(std::mem::take(&mut found.polygons), split);
                settled = true;
            }
            let cover = Cover::new(&found.polygons, &map);
            let rest = uncovered_pairs(ti, tj, &cover, &|a, b| need[a * pj.len() + b]);
            found.prune_seconds += t0.elapsed().as_secs_f64();
            if rest.is_empty() {
                break;
            }
            // A round: every pair left when few are, else pairs spread evenly over the
            // trees' order (spatially spread, so each round widens the union where it is
            // thinnest).
            let step = rest.len().div_ceil(CULL_ROUND);
            round = rest
                .iter()
                .step_by(step)
                .map(|&(a, b)| a * pj.len() + b)
                .collect();
        }
        Ok((map, summed))
    }

    /// The polygons of the pairs `todo`, a chunk at a time, each chunk pruned when
    /// there are several, added to `found`.
    fn sum_in_chunks(
        &self,
        todo: &[usize],
        found: &mut Found,
        progress: &Progress,
    ) -> Result<(), PlanError> {
        for chunk in todo.chunks(PRUNE_CHUNK) {
            if progress.stopped() {
                return Err(stopped());
            }
            let made = self.polygons(chunk)?;
            let t0 = Instant::now();
            let made: Vec<SphericalPolygon> = made
                .into_iter()
                .map(|(p, touch)| {
                    found.contact |= touch;
                    p
                })
                .collect();
            found.polygons.extend(if todo.len() > PRUNE_CHUNK {
                pruned(made)
            } else {
                made
            });
            found.prune_seconds += t0.elapsed().as_secs_f64();
        }
        Ok(())
    }
}

/// The error of a computation stopped by the progress' flag.
fn stopped() -> PlanError {
    PlanError::Stopped {
        phase: phases::PAIR_REGIONS,
    }
}
