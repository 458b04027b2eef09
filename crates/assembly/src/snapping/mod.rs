//! Relations between parts that snapping changed: two parts apart before snapping that
//! touch (or overlap) after, two that overlapped by less than a grid step and only touch
//! (or are apart) after, two that touched and are apart after. Each is a warning naming
//! both parts, the distance or depth before snapping, a point near it, and the grid
//! bits that would keep the relation.
//!
//! Cheap by construction: only pairs of triangles of different parts whose snapped boxes
//! come within [`REACH`] grid steps of each other are looked at. Snapping rounds each
//! coordinate on its own and is monotone, so two input triangles whose boxes meet keep
//! meeting boxes, and snapped triangles that meet have meeting boxes: every pair whose
//! relation can change is among those.
//!
//! The relation after snapping is exact: snapped triangles meet by the mesh crate's exact
//! test, and interiors overlap by the loader's exact overlap test (asked only for the few
//! pairs where it decides the warning). The relation before snapping is measured in
//! `f64` on the input coordinates of the same triangles, which only decides whether to
//! warn:
//!
//! - *apart*: every pair of triangles is farther apart than the rounding noise of its
//!   coordinates (the distance reported is the smallest);
//! - *overlapping*: some point of a triangle of one part lies behind a face of the other,
//!   strictly inside the prism over that face, less than two grid steps deep, with no
//!   other face of that part in between (so the point lies inside it); the depth
//!   reported is the deepest such;
//! - *touching* otherwise.
// Float measures here are written so that a NaN (from a degenerate triangle) fails
// every test: `!(x > 0.0)` is meant, not `x <= 0.0`.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod geometry;

use crate::load::fmt_len;
use crate::model::Part;
use crate::overlap;
use apart_formats::escape::escape;
use apart_kernel::fvec::{add, cross, norm, scale, sub, F3};
use apart_kernel::grid::MAX_BITS;
use apart_kernel::progress::Progress;
use apart_kernel::Aabb;
use apart_kernel::Bvh;
use apart_kernel::Grid;
use apart_mesh::intersect::triangles_meet;
use apart_mesh::{Mesh, Problem};
use geometry::{distance, max_abs, witness, Tri, NOISE};
use rayon::prelude::*;

/// Grid steps by which triangle boxes are grown when looking for pairs: snapping
/// moves a point by at most `sqrt(3)/2` steps, two points by at most `sqrt(3)`
/// steps relative to each other.
pub(crate) const REACH: i64 = 2;

fn grow(b: Aabb, r: i64) -> Aabb {
    Aabb {
        min: b.min.map(|c| c.saturating_sub(r)),
        max: b.max.map(|c| c.saturating_add(r)),
    }
}

fn tri_box(m: &Mesh, t: u32) -> Aabb {
    let [a, b, c] = m.corners(t as usize);
    Aabb::of([a, b, c])
}

/// Input coordinates of triangle `t`, relative to `origin`.
fn input_tri(m: &Mesh, raw: &[F3], t: u32, origin: F3) -> Tri {
    m.triangles[t as usize].map(|v| sub(raw[v as usize], origin))
}

/// One side of a part pair: a part's mesh, input coordinates, and the unit normals
/// of its input triangles near the other part (zero elsewhere, and for degenerate
/// ones).
#[derive(Clone, Copy)]
struct Side<'a> {
    mesh: &'a Mesh,
    raw: &'a [F3],
    normals: &'a [F3],
}

/// Unit normals of the input triangles `near` of `m` (indexed by triangle).
fn unit_normals(m: &Mesh, raw: &[F3], near: &[u32]) -> Vec<F3> {
    let mut out = vec![[0.0; 3]; m.triangles.len()];
    for &t in near {
        let [a, b, c] = m.triangles[t as usize].map(|v| raw[v as usize]);
        let n = cross(sub(b, a), sub(c, a));
        let l = norm(n);
        if l > 0.0 && l.is_finite() {
            out[t as usize] = scale(n, 1.0 / l);
        }
    }
    out
}

/// Witnesses of triangle `t` of `s` inside the part of `o`, behind its triangles
/// `near`.
fn witnesses(deepest: &mut (f64, F3), s: Side, t: u32, o: Side, near: &[u32], cap: f64) {
    let origin = s.raw[s.mesh.triangles[t as usize][0] as usize];
    let tt = input_tri(s.mesh, s.raw, t, origin);
    let faces: Vec<(Tri, F3)> = near
        .iter()
        .map(|&u| (input_tri(o.mesh, o.raw, u, origin), o.normals[u as usize]))
        .collect();
    for k in 0..faces.len() {
        if let Some((d, x)) = witness(&tt, &faces, k, cap, deepest.0) {
            *deepest = (d, add(x, origin));
        }
    }
}

/// For each triangle `t` of `ts` (of mesh `m`), the triangles of `os` (of mesh `o`)
/// whose boxes come within [`REACH`] steps of its box, when there are some.
fn near_lists(m: &Mesh, ts: &[u32], o: &Mesh, os: &[u32]) -> Vec<(u32, Vec<u32>)> {
    let bvh = Bvh::new(os.iter().map(|&u| grow(tri_box(o, u), REACH)).collect());
    ts.par_iter()
        .map(|&t| {
            let mut c = Vec::new();
            bvh.query(&tri_box(m, t), |k| c.push(os[k as usize]));
            (t, c)
        })
        .filter(|(_, c)| !c.is_empty())
        .collect()
}

/// The triangles of two parts near each other, and what their pairs say, each
/// measure taken only when [`judge`] needs it.
struct Near<'a> {
    a: Side<'a>,
    b: Side<'a>,
    /// Each triangle of `a` near `b`, with the triangles of `b` near it.
    from_a: Vec<(u32, Vec<u32>)>,
    /// The triangles of `a` and of `b` near the other part.
    near: [Vec<u32>; 2],
    /// Overlap witnesses count up to this depth (two grid steps).
    cap: f64,
    /// The unit normals of the near triangles, indexed by triangle, for `a` and `b`.
    normals: [Vec<F3>; 2],
    /// Whether the boxes of the input coordinates overlap in volume (otherwise the
    /// input parts cannot overlap).
    inputs_overlap: bool,
}

/// Whether the boxes of two sets of points overlap in volume (exact comparisons).
fn boxes_overlap_open(p: &[F3], q: &[F3]) -> bool {
    let bounds = |v: &[F3]| v.iter().fold(Aabb::<f64>::EMPTY, |b, x| b.with(x));
    bounds(p).overlaps_open(&bounds(q))
}

/// The deeper of two overlap witnesses (the first on a tie).
fn deeper(p: (f64, F3), q: (f64, F3)) -> (f64, F3) {
    if q.0 > p.0 {
        q
    } else {
        p
    }
}

/// The nearer of two distances (the first on a tie).
fn nearer(p: (f64, F3), q: (f64, F3)) -> (f64, F3) {
    if q.0 < p.0 {
        q
    } else {
        p
    }
}

impl Near<'_> {
    /// Whether some snapped triangles of the two parts meet (exact).
    fn meet(&self) -> bool {
        let (ma, mb) = (self.a.mesh, self.b.mesh);
        self.from_a.par_iter().any(|(t, near)| {
            let (ta, boxed) = (ma.corners(*t as usize), tri_box(ma, *t));
            near.iter().any(|&u| {
                boxed.overlaps(&tri_box(mb, u))
                    && triangles_meet(ta, mb.corners(u as usize)).is_some()
            })
        })
    }

    /// The distance between input triangles `t` of `a` and `u` of `b`, the point
    /// halfway between their nearest points, and the rounding noise of the measure.
    fn distance(&self, t: u32, u: u32) -> (f64, F3, f64) {
        let (a, b) = (&self.a, &self.b);
        let origin = a.raw[a.mesh.triangles[t as usize][0] as usize];
        let fa = input_tri(a.mesh, a.raw, t, origin);
        let fb = input_tri(b.mesh, b.raw, u, origin);
        let (d, x) = distance(&fa, &fb);
        (d, add(x, origin), NOISE * max_abs(fa.iter().chain(&fb)))
    }

    /// Where some input triangles are within rounding noise of each other (the
    /// first such pair in order), if any are.
    fn touch(&self) -> Option<F3> {
        self.from_a.par_iter().find_map_first(|(t, near)| {
            near.iter().find_map(|&u| {
                let (d, x, noise) = self.distance(*t, u);
                (d <= noise).then_some(x)
            })
        })
    }

    /// The smallest distance between input triangles, and where.
    fn gap(&self) -> (f64, F3) {
        let none = (f64::INFINITY, [0.0; 3]);
        self.from_a
            .par_iter()
            .map(|(t, near)| {
                near.iter().fold(none, |best, &u| {
                    let (d, x, _) = self.distance(*t, u);
                    nearer(best, (d, x))
                })
            })
            .reduce(|| none, nearer)
    }

    /// The deepest overlap of the input parts found (0: none), and where: points of
    /// each part's triangles inside the other, less than `cap` deep.
    fn depth(&self) -> (f64, F3) {
        let none = (0.0, [0.0; 3]);
        if !self.inputs_overlap {
            return none;
        }
        let deepest = |lists: &[(u32, Vec<u32>)], s: Side, o: Side| {
            lists
                .par_iter()
                .fold(
                    || none,
                    |mut acc, (t, near)| {
                        witnesses(&mut acc, s, *t, o, near, self.cap);
                        acc
                    },
                )
                .reduce(|| none, deeper)
        };
        let (sa, sb) = (self.side(0), self.side(1));
        // The pairs seen from `b`'s triangles, built only here: most pairs never
        // need a depth.
        let from_b = near_lists(sb.mesh, &self.near[1], sa.mesh, &self.near[0]);
        deeper(deepest(&self.from_a, sa, sb), deepest(&from_b, sb, sa))
    }

    /// Part `k`'s side (0: `a`, 1: `b`) with its near triangles' unit normals.
    fn side(&self, k: usize) -> Side<'_> {
        let s = if k == 0 { &self.a } else { &self.b };
        Side {
            normals: &self.normals[k],
            ..*s
        }
    }
}

/// The near triangles of parts `a` and `b` (with input coordinates `ra`, `rb` of
/// their vertices), if any.
fn near<'a>(a: &'a Part, ra: &'a [F3], b: &'a Part, rb: &'a [F3], grid: &Grid) -> Option<Near<'a>> {
    let (ma, mb) = (a.mesh.as_ref()?, b.mesh.as_ref()?);
    let (ga, gb) = (grow(a.bbox?, REACH), grow(b.bbox?, REACH));
    let region = Aabb {
        min: [0, 1, 2].map(|k| ga.min[k].max(gb.min[k])),
        max: [0, 1, 2].map(|k| ga.max[k].min(gb.max[k])),
    };
    if region.is_empty() {
        return None;
    }
    let near = |m: &Mesh| -> Vec<u32> {
        (0..m.triangles.len() as u32)
            .filter(|&t| tri_box(m, t).overlaps(&region))
            .collect()
    };
    let (na, nb) = (near(ma), near(mb));
    if na.is_empty() || nb.is_empty() {
        return None;
    }
    let from_a = near_lists(ma, &na, mb, &nb);
    if from_a.is_empty() {
        return None;
    }
    let normals = [unit_normals(ma, ra, &na), unit_normals(mb, rb, &nb)];
    let side = |mesh, raw| Side {
        mesh,
        raw,
        normals: &[],
    };
    Some(Near {
        a: side(ma, ra),
        b: side(mb, rb),
        from_a,
        near: [na, nb],
        cap: 2.0 * grid.step(),
        normals,
        inputs_overlap: boxes_overlap_open(ra, rb),
    })
}

/// The smallest `--grid-bits` whose step is at most a quarter of `len`, if any.
fn bits_for(grid: &Grid, len: f64) -> Option<u32> {
    if !(len > 0.0) {
        return None;
    }
    let more = (4.0 * grid.step() / len).log2().ceil().max(1.0);
    let bits = grid.bits as f64 + more;
    (bits <= MAX_BITS as f64).then_some(bits as u32)
}

/// `--grid-bits N (step S) keeps <what>`, or why no grid does.
fn finer(grid: &Grid, len: f64, what: &str) -> String {
    match bits_for(grid, len) {
        Some(b) => format!(
            "--grid-bits {b} (step {}) keeps {what}",
            fmt_len(grid.step() / 2f64.powi((b - grid.bits) as i32))
        ),
        None => format!(
            "even --grid-bits {MAX_BITS} (step {}) is too coarse to keep {what} at these coordinates",
            fmt_len(grid.step() / 2f64.powi((MAX_BITS - grid.bits) as i32))
        ),
    }
}

fn fmt_point(p: F3) -> String {
    let c = p.map(|v| {
        if v == 0.0 {
            "0".to_string()
        } else if (1e-3..1e12).contains(&v.abs()) {
            let s = format!("{v:.6}");
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            format!("{v:.6e}")
        }
    });
    format!("near ({}, {}, {})", c[0], c[1], c[2])
}

/// The warning for parts `a` and `b`, if snapping changed how they meet, and
/// whether their interiors overlap after snapping, when that was decided.
fn judge(a: &Part, b: &Part, near: &Near, grid: &Grid) -> (Option<Problem>, Option<bool>) {
    let mut known_overlap = None;
    let warning = warning(a, b, near, grid, &mut known_overlap);
    (warning, known_overlap)
}

/// [`judge`]'s warning; `known_overlap` caches the exact overlap test.
fn warning(
    a: &Part,
    b: &Part,
    near: &Near,
    grid: &Grid,
    known_overlap: &mut Option<bool>,
) -> Option<Problem> {
    let step = fmt_len(grid.step());
    let pair = format!(
        "part \"{}\" and part \"{}\"",
        escape(&a.name),
        escape(&b.name)
    );
    // The measures, each taken once and only when the answer needs it (the witness
    // scan behind `depth` is the costliest).
    let touch = near.touch();
    let meet = near.meet();
    let mut overlap_after = || *known_overlap.get_or_insert_with(|| overlap::parts_overlap(a, b));
    // Touching before snapping and meeting after: only an overlap that snapping
    // removed could be reported, and none was if the parts still overlap (as
    // interpenetrating tessellations do).
    if touch.is_some() && meet && overlap_after() {
        return None;
    }
    let depth = near.depth();
    let (message, at) = if depth.0 > 0.0 {
        if overlap_after() {
            return None;
        }
        let (depth, at) = depth;
        let after = match meet {
            true => "they only touch after snapping",
            false => "they are apart after snapping",
        };
        (
            format!(
                "snapping to the grid (step {step}) removed an overlap of depth {} between {pair}: {after}; {}, and --tolerance {} then accepts it as contact",
                fmt_len(depth),
                finer(grid, depth, "the overlap (reported as an error)"),
                fmt_len(depth)
            ),
            at,
        )
    } else if let Some(at) = touch {
        if meet {
            return None;
        }
        (
            format!(
                "snapping to the grid (step {step}) separated {pair}, which touched before snapping: they are apart after it; a larger --grid-bits (at most {MAX_BITS}) makes the gap smaller"
            ),
            at,
        )
    } else {
        if !meet {
            return None;
        }
        let (gap, at) = near.gap();
        if !gap.is_finite() {
            return None;
        }
        let after = match overlap_after() {
            true => "they overlap after snapping",
            false => "they touch after snapping",
        };
        (
            format!(
                "snapping to the grid (step {step}) closed a gap of {} between {pair}: {after}; {}",
                fmt_len(gap),
                finer(grid, gap, "the gap")
            ),
            at,
        )
    };
    Some(
        Problem::warning(message)
            .at(fmt_point(at))
            .in_part(a.name.clone()),
    )
}

/// Warnings for every pair of parts whose relation snapping changed. `raw[k]` holds
/// the input coordinates of the vertices of part `k`'s mesh (`None`: the part has no
/// usable mesh and is left out).
/// Also returns the pairs `(i, j)` (sorted) of parts whose interiors the check found
/// disjoint after snapping (exactly), so that the overlap check need not test them
/// again. Once the stop flag of `progress` is raised, no further pair is judged.
pub(crate) fn changed_relations(
    parts: &[Part],
    raw: &[Option<Vec<F3>>],
    grid: &Grid,
    progress: &Progress,
) -> (Vec<Problem>, Vec<(usize, usize)>) {
    let usable: Vec<usize> = (0..parts.len())
        .filter(|&k| raw[k].is_some() && parts[k].mesh.is_some() && parts[k].bbox.is_some())
        .collect();
    let mut pairs = Vec::new();
    for (x, &i) in usable.iter().enumerate() {
        let bi = grow(parts[i].bbox.expect("usable"), REACH);
        for &j in &usable[x + 1..] {
            if bi.overlaps(&parts[j].bbox.expect("usable")) {
                pairs.push((i, j));
            }
        }
    }
    let judged: Vec<_> = pairs
        .par_iter()
        .filter_map(|&(i, j)| {
            if progress.stopped() {
                return None;
            }
            let (ra, rb) = (raw[i].as_deref()?, raw[j].as_deref()?);
            let near = near(&parts[i], ra, &parts[j], rb, grid)?;
            Some(((i, j), judge(&parts[i], &parts[j], &near, grid)))
        })
        .collect();
    let disjoint = judged
        .iter()
        .filter(|(_, (_, overlap))| *overlap == Some(false))
        .map(|&(pair, _)| pair)
        .collect();
    let warnings = judged.into_iter().filter_map(|(_, (w, _))| w).collect();
    (warnings, disjoint)
}
