//! A stated tolerance: parts made `eps` smaller, so that overlaps up to a stated depth
//! count as contact.
//!
//! CAD exports of curved fits interpenetrate by micrometres where both sides of a fit are
//! tessellated. A tolerance is not an epsilon in a predicate: it is a stated change of
//! the input. Every convex piece is shrunk by at least `eps` (facet planes moved inward,
//! exact rationals: [`Polytope::shrunk`]), the overlap check runs again, exactly, on
//! the shrunk pieces, and the planners then work on those pieces. Two pieces that overlap
//! by a depth below `2 eps` are disjoint once both are shrunk; deeper overlaps stay
//! errors, with a witness point and the measured depth.
//!
//! `eps` given in input units is a binary floating-point number, hence an exact dyadic
//! rational; it is used exactly (no rounding to the grid). [`Tolerance::Auto`] finds the
//! smallest `eps` (rounded up to 8 significant bits) that makes the assembly valid, up to
//! `1e-3` of the assembly's size.

use crate::model::{Assembly, Part};
use crate::options::LoadOptions;
use crate::witness::fmt_witness;
use apart_kernel::progress::{phases, Progress};
use apart_kernel::Aabb;
use apart_kernel::{Grid, Rational};
use apart_mesh::{Problem, ProblemKind};
use apart_pieces::interference::{overlap_deeper_than, overlap_with_depth};
use apart_pieces::shrink::max_face_shift;
use apart_pieces::Polytope;
use rayon::prelude::*;

/// How much smaller parts may be made to accept overlaps as contact.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Tolerance {
    /// No tolerance: any overlap is an error (the default).
    #[default]
    None,
    /// Every piece made this much smaller (input units, positive).
    Fixed(f64),
    /// The smallest tolerance that makes the assembly valid, up to [`AUTO_LIMIT`] of
    /// the assembly's size.
    Auto,
}

/// The largest tolerance [`Tolerance::Auto`] may choose, as a fraction of the largest
/// extent of the assembly's bounding box.
pub const AUTO_LIMIT: f64 = 1e-3;

/// The tolerance an assembly was loaded under.
#[derive(Clone, Debug, PartialEq)]
pub struct AppliedTolerance {
    /// Every piece was made at least this much smaller (input units).
    pub eps: f64,
    /// The same, exactly (input units).
    pub exact: Rational,
    /// Chosen by [`Tolerance::Auto`].
    pub auto: bool,
    /// The deepest overlap between parts before shrinking (input units; 0 when none).
    pub deepest_overlap: f64,
    /// Pairs of parts whose overlap the tolerance turned into contact.
    pub accepted_overlaps: usize,
    /// The pairs of parts `(i, j)`, `i < j`, sorted, whose interiors overlapped before
    /// shrinking: a motion of one against the other cannot hold without the tolerance.
    pub overlapping: Vec<(usize, usize)>,
    /// Pieces thinner than `2 eps` that vanished.
    pub vanished_pieces: usize,
    /// The farthest any face moved inward (input units; at least `eps`): tessellated
    /// pieces are scaled about an inner point rather than cut exactly, which moves some
    /// faces more (see [`Polytope::shrunk`]).
    pub max_shift: f64,
}

/// An overlap between two parts, measured on their pieces.
struct Overlap {
    i: usize,
    j: usize,
    /// The deepest piece pair's depth (grid units).
    depth: f64,
}

/// How many overlapping pairs of parts a tolerance is measured on before the loader
/// gives up: a product of thousands of parts has a few overlapping fits per part, while
/// thousands of copies of one part overlap in millions of pairs, which no tolerance is
/// for (and measuring each would take minutes).
pub const MAX_OVERLAPPING_PAIRS: usize = 200_000;

/// The deepest overlap of two parts' pieces (grid units), or `None` when their
/// interiors are disjoint. The piece pairs whose open boxes meet are tested in parallel;
/// once one overlap is found, a pair is measured only as far as it could be deeper
/// ([`overlap_deeper_than`]), so the many shallow overlaps of a tessellated fit cost one
/// axis each. The result is the same maximum.
pub(crate) fn deepest_piece_overlap(a: &[Polytope], b: &[Polytope]) -> Option<f64> {
    use std::sync::atomic::{AtomicU64, Ordering};
    let pairs = crate::overlap::open_box_pairs(a, b);
    // The deepest overlap so far as the bits of a non-negative f64 (which order like
    // the values); NONE before the first.
    const NONE: u64 = u64::MAX;
    let deepest = AtomicU64::new(NONE);
    pairs.par_iter().with_min_len(16).for_each(|&(i, j)| {
        let seen = deepest.load(Ordering::Relaxed);
        let found = if seen == NONE {
            match overlap_with_depth(&a[i], &b[j]) {
                (true, d) => Some(d.max(0.0)),
                (false, _) => None,
            }
        } else {
            overlap_deeper_than(&a[i], &b[j], f64::from_bits(seen))
        };
        if let Some(d) = found {
            // +0.0 for zero (-0.0 would not order by its bits).
            let bits = if d > 0.0 { d.to_bits() } else { 0 };
            let _ = deepest.fetch_update(Ordering::Relaxed, Ordering::Relaxed, |x| {
                (x == NONE || x < bits).then_some(bits)
            });
        }
    });
    let d = deepest.into_inner();
    (d != NONE).then(|| f64::from_bits(d))
}

/// Why [`overlaps`] gave no list.
enum Unmeasured {
    /// More than this many pairs overlap.
    TooMany(usize),
    /// The stop flag was raised.
    Stopped,
}

/// The overlapping pairs of parts, but for the pairs `disjoint` (known not to).
/// In pair order: candidates from a hierarchy of the parts' boxes, part by part, tested
/// in parallel batches, the stop flag of `progress` checked before each.
fn overlaps(
    parts: &[Part],
    disjoint: &[(usize, usize)],
    progress: &Progress,
) -> Result<Vec<Overlap>, Unmeasured> {
    let boxes: Vec<Aabb> = parts
        .iter()
        .map(|p| match p.pieces.is_empty() {
            true => Aabb::EMPTY,
            false => p.bbox.unwrap_or(Aabb::EMPTY),
        })
        .collect();
    let bvh = apart_kernel::Bvh::new(boxes.clone());
    let mut out = Vec::new();
    for i in 0..parts.len() {
        if boxes[i].is_empty() {
            continue;
        }
        let mut near = Vec::new();
        bvh.query(&boxes[i], |j| {
            let j = j as usize;
            if j > i
                && boxes[i].overlaps_open(&boxes[j])
                && disjoint.binary_search(&(i, j)).is_err()
            {
                near.push(j);
            }
        });
        near.sort_unstable();
        for batch in near.chunks(256) {
            if progress.stopped() {
                return Err(Unmeasured::Stopped);
            }
            out.par_extend(batch.par_iter().filter_map(|&j| {
                deepest_piece_overlap(&parts[i].pieces, &parts[j].pieces).map(|depth| Overlap {
                    i,
                    j,
                    depth,
                })
            }));
            if out.len() > MAX_OVERLAPPING_PAIRS {
                return Err(Unmeasured::TooMany(MAX_OVERLAPPING_PAIRS));
            }
        }
    }
    Ok(out)
}

/// The error when too many pairs overlap for a tolerance to be measured.
fn too_many_overlaps(n: usize) -> Problem {
    Problem::error(format!(
        "more than {n} pairs of parts overlap: copies of parts on each other, not the overlaps of tessellated fits that a tolerance accepts; the tolerance is not applied (without it, apart check lists the first overlaps)"
    ))
    .with_kind(ProblemKind::Tolerance)
}

/// `v` (input units, finite, positive) in grid units, exactly.
fn to_grid_units(v: f64, grid: &Grid) -> Rational {
    &dyadic(v) * &Rational::pow2(-grid.exp)
}

/// The exact value of a finite `f64` (zero for infinities and NaN, which [`apply`]
/// rejects first).
pub fn dyadic(v: f64) -> Rational {
    Rational::from_f64(v).unwrap_or_else(Rational::zero)
}

/// `x` rounded up to 8 significant bits (a short, exact number to state).
fn round_up_8_bits(x: f64) -> f64 {
    if x <= 0.0 || !x.is_finite() {
        return x;
    }
    let e = x.log2().floor() as i32 - 7;
    let s = 2f64.powi(e);
    let r = (x / s).ceil() * s;
    if r < x {
        r + s
    } else {
        r
    }
}

/// Every piece of every part shrunk by `eps` (grid units), in parallel. Returns the
/// number of pieces that vanished and the farthest any face moved (grid units).
fn shrink_all(parts: &mut [Part], eps: &Rational) -> (usize, f64) {
    let (num, den) = (eps.numer().clone(), eps.denom().clone());
    parts
        .par_iter_mut()
        .map(|p| {
            let shrunk: Vec<(Option<Polytope>, f64)> = p
                .unshrunk_pieces
                .par_iter()
                .map(|q| {
                    let s = q.shrunk(&num, &den);
                    let shift = s.as_ref().map_or(0.0, |s| max_face_shift(q, s));
                    (s, shift)
                })
                .collect();
            let before = shrunk.len();
            let shift = shrunk.iter().map(|x| x.1).fold(0.0, f64::max);
            p.pieces = shrunk.into_iter().filter_map(|x| x.0).collect();
            (before - p.pieces.len(), shift)
        })
        .reduce(|| (0, 0.0), |a, b| (a.0 + b.0, a.1.max(b.1)))
}

/// Applies `tol` to an assembly whose parts have their pieces (the loader's last step,
/// in place of the plain overlap check): shrinks the pieces, and returns the problems of
/// the overlap check on the shrunk pieces (deeper overlaps as errors with a witness and
/// the measured depth; accepted overlaps and vanished pieces as notes).
/// `disjoint` lists pairs of parts `(i, j)`, `i < j`, sorted, already known not to
/// overlap. Once the stop flag is raised, the problems are incomplete (the loader then
/// fails).
pub(crate) fn apply(
    asm: &mut Assembly,
    tol: Tolerance,
    opts: &LoadOptions,
    disjoint: &[(usize, usize)],
) -> Vec<Problem> {
    let grid = asm.grid;
    let counter = opts.progress.counter(phases::OVERLAPS, 1);
    let before = match overlaps(&asm.parts, disjoint, &opts.progress) {
        Ok(b) => b,
        Err(why) => {
            asm.tolerance = None;
            return match why {
                Unmeasured::TooMany(n) => vec![too_many_overlaps(n)],
                Unmeasured::Stopped => Vec::new(),
            };
        }
    };
    counter.add(1);
    let deepest = before.iter().map(|o| o.depth).fold(0.0, f64::max) * grid.step();
    let mut problems = Vec::new();
    let (eps, auto, limit) = match choose_eps(asm, tol, &before, deepest) {
        Ok(chosen) => chosen,
        Err(problem) => {
            asm.tolerance = None;
            problems.push(problem);
            return problems;
        }
    };
    if auto && eps > limit {
        problems.push(Problem::error(format!(
            "tolerance auto: the deepest overlap, {deepest:.3e}, needs a tolerance of {eps:.3e}, beyond the limit of {AUTO_LIMIT} of the assembly's size ({limit:.3e}); these overlaps are modelling errors, not tessellation"
        ))
        .with_kind(ProblemKind::Tolerance));
    }
    let eps = match auto && eps > limit {
        true => round_up_8_bits(limit).min(limit).max(f64::MIN_POSITIVE),
        false => eps,
    };
    for p in &mut asm.parts {
        p.unshrunk_pieces = std::mem::take(&mut p.pieces);
    }
    let shrunk = shrink_until_apart(asm, disjoint, (eps, auto, limit), opts, &mut problems);
    report(asm, &before, &shrunk, deepest, &mut problems);
    asm.tolerance = Some(AppliedTolerance {
        eps: shrunk.eps,
        exact: dyadic(shrunk.eps),
        auto,
        deepest_overlap: deepest,
        accepted_overlaps: before.len().saturating_sub(shrunk.after.len()),
        overlapping: {
            let mut v: Vec<(usize, usize)> = before.iter().map(|o| (o.i, o.j)).collect();
            v.sort_unstable();
            v
        },
        vanished_pieces: shrunk.vanished,
        max_shift: (shrunk.max_shift * grid.step()).max(shrunk.eps),
    });
    problems
}

/// The tolerance to apply (input units), whether it was chosen automatically, and the
/// largest an automatic one may be ([`AUTO_LIMIT`] of the assembly's largest extent);
/// `Err` with the problem when no tolerance applies: a stated one that is not a finite
/// positive length, or an automatic one with nothing to accept.
fn choose_eps(
    asm: &Assembly,
    tol: Tolerance,
    before: &[Overlap],
    deepest: f64,
) -> Result<(f64, bool, f64), Problem> {
    let grid = asm.grid;
    let size = asm
        .parts
        .iter()
        .filter_map(|p| p.bbox)
        .fold(Aabb::EMPTY, |b, x| b.union(&x));
    let extent = if size.is_empty() {
        0.0
    } else {
        (0..3)
            .map(|k| grid.to_units(size.max[k]) - grid.to_units(size.min[k]))
            .fold(0.0, f64::max)
    };
    let limit = AUTO_LIMIT * extent;
    match tol {
        Tolerance::None => unreachable!("apply is called with a tolerance"),
        Tolerance::Fixed(e) if !(e.is_finite() && e > 0.0) => Err(Problem::error(format!(
            "tolerance {e} is not a finite positive length"
        ))
        .with_kind(ProblemKind::Tolerance)),
        Tolerance::Fixed(e) => Ok((e, false, limit)),
        Tolerance::Auto if before.is_empty() => Err(Problem::note(
            "tolerance auto: no part overlaps another, so none is needed",
        )
        .with_kind(ProblemKind::Tolerance)),
        Tolerance::Auto => Ok((round_up_8_bits(deepest / 2.0 * (1.0 + 1e-9)), true, limit)),
    }
}

/// The parts' pieces once shrunk, and what overlaps remain.
struct Shrunk {
    /// The tolerance finally applied (input units).
    eps: f64,
    /// Pieces that vanished.
    vanished: usize,
    /// The farthest any face moved (grid units).
    max_shift: f64,
    /// The pairs of parts that still overlap.
    after: Vec<Overlap>,
}

/// Shrinks every piece by `eps` and measures the overlaps left; an automatic tolerance
/// (`auto`) is doubled, up to `limit`, while some remain, since the depth it was chosen
/// from is a floating-point measurement that may fall short.
fn shrink_until_apart(
    asm: &mut Assembly,
    disjoint: &[(usize, usize)],
    (mut eps, auto, limit): (f64, bool, f64),
    opts: &LoadOptions,
    problems: &mut Vec<Problem>,
) -> Shrunk {
    loop {
        let (vanished, max_shift) = shrink_all(&mut asm.parts, &to_grid_units(eps, &asm.grid));
        // Shrunk pieces lie inside the originals: disjoint parts stay disjoint.
        let (after, stopped) = match overlaps(&asm.parts, disjoint, &opts.progress) {
            Ok(a) => (a, false),
            Err(Unmeasured::TooMany(n)) => {
                // Shrinking only separates: as many overlaps as before at most.
                problems.push(too_many_overlaps(n));
                (Vec::new(), false)
            }
            Err(Unmeasured::Stopped) => (Vec::new(), true),
        };
        // A stated tolerance is kept as stated.
        if stopped || !auto || after.is_empty() || eps * 2.0 > limit {
            return Shrunk {
                eps,
                vanished,
                max_shift,
                after,
            };
        }
        eps *= 2.0;
    }
}

/// The problems of a tolerance applied: overlaps deeper than it accepts (errors with
/// the depth measured before shrinking and a witness), the overlaps accepted and the
/// pieces that vanished (notes), and parts of which nothing is left (errors).
fn report(
    asm: &Assembly,
    before: &[Overlap],
    shrunk: &Shrunk,
    deepest: f64,
    problems: &mut Vec<Problem>,
) {
    let (grid, eps) = (asm.grid, shrunk.eps);
    for o in &shrunk.after {
        let (a, b) = (&asm.parts[o.i], &asm.parts[o.j]);
        let depth = before
            .iter()
            .find(|x| x.i == o.i && x.j == o.j)
            .map_or(o.depth, |x| x.depth)
            * grid.step();
        let witness = crate::overlap::part_overlap(a, b, &grid)
            .map(|w| format!(": {} lies strictly inside both", fmt_witness(&w, &grid)))
            .unwrap_or_default();
        problems.push(
            Problem::error(format!(
                "overlaps part \"{}\" by a depth of {depth:.3e}, deeper than the tolerance accepts (parts made {eps:.3e} smaller){witness}",
                b.name
            ))
            .in_part(a.name.clone())
            .with_kind(ProblemKind::Overlap {
                other: Box::new(b.name.clone()),
            }),
        );
    }
    let accepted = before.len().saturating_sub(shrunk.after.len());
    if accepted > 0 {
        problems.push(Problem::note(format!(
            "{accepted} overlapping pair{} of parts (deepest {deepest:.3e}) count as contact for parts made {eps:.3e} smaller",
            if accepted == 1 { "" } else { "s" }
        ))
        .with_kind(ProblemKind::Tolerance));
    }
    let vanished = shrunk.vanished;
    if vanished > 0 {
        problems.push(
            Problem::note(format!(
                "{vanished} convex piece{} thinner than twice the tolerance vanished",
                if vanished == 1 { "" } else { "s" }
            ))
            .with_kind(ProblemKind::Tolerance),
        );
    }
    for p in &asm.parts {
        if p.pieces.is_empty() && !p.unshrunk_pieces.is_empty() {
            problems.push(
                Problem::error(format!(
                    "nothing is left of the part once made {eps:.3e} smaller: it is thinner than twice the tolerance"
                ))
                .in_part(p.name.clone())
                .with_kind(ProblemKind::Tolerance),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use apart_kernel::Int;

    #[test]
    fn the_deepest_overlap_is_the_largest_of_every_pair() {
        // Two rows of boxes of different sizes and offsets, overlapping by various
        // depths (and some only touching or apart): the pruned parallel search finds
        // the largest depth any pair has, as every pair measured in turn says.
        let mut g = apart_testkit::solids::Lcg(7);
        let mut next = |m: i64| g.below(m as u64) as i64;
        for _ in 0..20 {
            let row = |next: &mut dyn FnMut(i64) -> i64, z: i64| -> Vec<Polytope> {
                (0..30)
                    .map(|k| {
                        let x = 100 * k + next(50);
                        let lo = [x, next(40), z - next(30)];
                        let hi = [x + 60 + next(80), 60 + next(40), z + 1 + next(30)];
                        Polytope::cuboid(lo, hi).unwrap()
                    })
                    .collect()
            };
            let a = row(&mut next, 0);
            let b = row(&mut next, 40);
            let naive = a
                .iter()
                .flat_map(|pa| b.iter().map(move |pb| overlap_with_depth(pa, pb)))
                .filter(|(o, _)| *o)
                .map(|(_, d)| d)
                .fold(None, |m: Option<f64>, d| Some(m.map_or(d, |m| m.max(d))));
            assert_eq!(deepest_piece_overlap(&a, &b), naive);
        }
    }

    #[test]
    fn dyadic_is_exact() {
        assert_eq!(dyadic(0.5), Rational::new(Int::ONE, Int::from(2)));
        assert_eq!(dyadic(3.0), Rational::from_int(Int::from(3)));
        assert_eq!(dyadic(-0.75), Rational::new(Int::from(-3), Int::from(4)));
        // 0.1 is not 1/10 but the nearest double, 3602879701896397 / 2^55.
        assert_eq!(
            dyadic(0.1),
            Rational::new(Int::from(3602879701896397u64), Int::ONE << 55usize)
        );
        assert_eq!(dyadic(0.1).to_f64(), 0.1);
    }

    #[test]
    fn rounding_up_keeps_8_bits_and_never_goes_down() {
        for x in [1e-6, 3.3e-7, 0.125, 1.0, 255.5, 1234.5678] {
            let r = round_up_8_bits(x);
            assert!(r >= x && r <= x * (1.0 + 1.0 / 64.0), "{x} -> {r}");
            let m = r / 2f64.powi(r.log2().floor() as i32 - 7);
            assert_eq!(m, m.round(), "{x} -> {r}: more than 8 significant bits");
        }
    }
}
