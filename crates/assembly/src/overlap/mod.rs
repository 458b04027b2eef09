//! Parts whose interiors overlap. Every pair of usable parts whose bounding boxes
//! overlap in volume is tested, in parallel; an overlap is reported with a point
//! strictly inside both parts, verified exactly.
//!
//! - Both parts have convex pieces (declared, or the part itself when convex): every
//!   pair of pieces is tested with [`interior_witness`] (separating axes; complete).
//! - Otherwise the boundaries are compared ([`boundary::overlap`]): complete up to the
//!   degenerate case described there.

pub(crate) mod boundary;

use crate::model::{Assembly, Part};
use crate::options::LoadOptions;
use crate::pieces::piece_box;
use crate::witness::{fmt_witness, simplest, verified_in_polytopes};
use apart_kernel::bvh::{by_low_x, sweep_pairs_between};
use apart_kernel::progress::phases;
use apart_kernel::{Aabb, Rational};
use apart_kernel::{Grid, HPoint};
use apart_mesh::locate::Locator;
use apart_mesh::{Mesh, Problem, ProblemKind};
use apart_pieces::interference::interior_witness;
use apart_pieces::Polytope;
use rayon::prelude::*;
use std::borrow::Cow;

/// True when the part can take part in overlap tests: convex pieces, or a closed,
/// non-self-intersecting boundary.
fn usable(p: &Part) -> bool {
    !p.pieces.is_empty() || mesh_usable(p)
}

fn mesh_usable(p: &Part) -> bool {
    p.mesh.is_some()
        && p.info
            .as_ref()
            .is_some_and(|i| i.closed && i.volume6.is_some() && i.self_intersections == 0)
}

/// A polytope with grid vertices (denominator 1, as every declared or convex piece
/// the loader builds) as an outward triangle mesh (fans over its facets).
pub(crate) fn polytope_mesh(p: &Polytope) -> Mesh {
    debug_assert!(*p.den() == apart_kernel::Int::ONE);
    let vertices: Vec<[i64; 3]> = p
        .vertices()
        .iter()
        .map(|v| v.as_small().copied().unwrap_or([0; 3]))
        .collect();
    let mut triangles = Vec::new();
    let mut source_faces = Vec::new();
    for (f, facet) in p.facets().iter().enumerate() {
        let c = &facet.cycle;
        for k in 1..c.len() - 1 {
            triangles.push([c[0], c[k], c[k + 1]]);
            source_faces.push(f as u32);
        }
    }
    Mesh {
        source_vertices: (0..vertices.len() as u32).collect(),
        vertices,
        triangles,
        source_faces,
    }
}

/// A point strictly inside both parts, if their interiors overlap: the simplest such
/// point found (see [`simplest`]), for a readable witness.
pub(crate) fn part_overlap(a: &Part, b: &Part, grid: &Grid) -> Option<[Rational; 3]> {
    overlap_point(a, b, Some(grid))
}

/// Whether the interiors of two parts overlap (exact), without simplifying the witness.
pub(crate) fn parts_overlap(a: &Part, b: &Part) -> bool {
    overlap_point(a, b, None).is_some()
}

/// A point strictly inside both parts, made [`simplest`] on `grid` when one is given.
fn overlap_point(a: &Part, b: &Part, grid: Option<&Grid>) -> Option<[Rational; 3]> {
    // Each part lies in its box: parts whose boxes only touch cannot overlap (their
    // pieces' boxes, rounded outward, may still).
    if let (Some(ba), Some(bb)) = (a.bbox, b.bbox) {
        if !ba.overlaps_open(&bb) {
            return None;
        }
    }
    if !a.pieces.is_empty() && !b.pieces.is_empty() {
        // The first overlapping pair in index order (the same answer on any number of
        // threads).
        let mut pairs = open_box_pairs(&a.pieces, &b.pieces);
        pairs.sort_unstable();
        let (pa, pb, w) = pairs.par_iter().find_map_first(|&(i, j)| {
            let (pa, pb) = (&a.pieces[i], &b.pieces[j]);
            let w = interior_witness(pa, pb)?;
            verified_in_polytopes(&w, pa, pb).then_some((pa, pb, w))
        })?;
        return Some(match grid {
            Some(g) => simplest(w, g, |r| verified_in_polytopes(r, pa, pb)),
            None => w,
        });
    }
    let (sa, sb) = (solids(a), solids(b));
    for ma in &sa {
        for mb in &sb {
            let (Some(ba), Some(bb)) = (ma.bbox(), mb.bbox()) else {
                continue;
            };
            if !ba.overlaps_open(&bb) {
                continue;
            }
            if let Some(w) = boundary::overlap(ma, mb) {
                let Some(g) = grid else {
                    return Some(w.to_rationals());
                };
                let (la, lb) = (Locator::new(ma), Locator::new(mb));
                return Some(simplest(w.to_rationals(), g, |r| {
                    let q = HPoint::from_rationals(r);
                    la.strictly_inside(&q) && lb.strictly_inside(&q)
                }));
            }
        }
    }
    None
}

/// The pairs `(i, j)` of pieces `a[i]`, `b[j]` whose open boxes meet (only those can
/// overlap), by sort and sweep.
pub(crate) fn open_box_pairs(a: &[Polytope], b: &[Polytope]) -> Vec<(usize, usize)> {
    let ba: Vec<Aabb> = a.iter().map(piece_box).collect();
    let bb: Vec<Aabb> = b.iter().map(piece_box).collect();
    sweep_pairs_between(&ba, &by_low_x(&ba), &bb, &by_low_x(&bb))
        .into_iter()
        .filter(|&(i, j)| ba[i].overlaps_open(&bb[j]))
        .collect()
}

/// The solids standing for a part in the boundary test: its mesh when usable, else its
/// pieces as meshes.
fn solids(p: &Part) -> Vec<Cow<'_, Mesh>> {
    match (&p.mesh, mesh_usable(p)) {
        (Some(m), true) => vec![Cow::Borrowed(m)],
        _ => p
            .pieces
            .iter()
            .map(|q| Cow::Owned(polytope_mesh(q)))
            .collect(),
    }
}

/// How many overlapping pairs of parts are listed before the check stops: one refuses
/// the assembly, and thousands of copies of one part would otherwise cost a test and a
/// message per pair (4.5 million for 3,000 copies).
pub(crate) const MAX_LISTED_OVERLAPS: usize = 100;

/// Problems for the pairs of parts whose interiors overlap, the first
/// [`MAX_LISTED_OVERLAPS`] in pair order (then one problem saying the list stops); the
/// pairs `disjoint` (`(i, j)`, `i < j`, sorted) are already known not to. Candidate
/// pairs come from a hierarchy of the parts' boxes, part by part, and are tested in
/// parallel batches in order, so the answer is the same on any number of threads and
/// the search ends as soon as the list is full, or once the stop flag is raised.
pub(crate) fn check_parts(
    asm: &Assembly,
    opts: &LoadOptions,
    disjoint: &[(usize, usize)],
) -> Vec<Problem> {
    let parts = &asm.parts;
    let boxes: Vec<Aabb> = parts
        .iter()
        .map(|p| p.bbox.filter(|_| usable(p)).unwrap_or(Aabb::EMPTY))
        .collect();
    let bvh = apart_kernel::Bvh::new(boxes.clone());
    let counter = opts.progress.counter(phases::OVERLAPS, parts.len());
    let mut out: Vec<Problem> = Vec::new();
    for i in 0..parts.len() {
        if opts.progress.stopped() {
            break;
        }
        counter.add(1);
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
        for batch in near.chunks(64) {
            if opts.progress.stopped() {
                return out;
            }
            let found: Vec<Problem> = batch
                .par_iter()
                .filter_map(|&j| overlap_problem(asm, i, j))
                .collect();
            for p in found {
                if out.len() == MAX_LISTED_OVERLAPS {
                    out.push(
                        Problem::error(format!(
                            "more parts overlap; the list stops at {MAX_LISTED_OVERLAPS} pairs"
                        ))
                        .with_kind(ProblemKind::Overlap {
                            other: Box::new(String::new()),
                        }),
                    );
                    return out;
                }
                out.push(p);
            }
        }
    }
    out
}

/// The problem of parts `i` and `j` when their interiors overlap, with a witness point
/// and (for parts with pieces) the depth.
fn overlap_problem(asm: &Assembly, i: usize, j: usize) -> Option<Problem> {
    let (a, b) = (&asm.parts[i], &asm.parts[j]);
    let w = part_overlap(a, b, &asm.grid)?;
    // The depth is measured on convex pieces; parts compared by their boundaries only
    // get the witness.
    let depth = crate::tolerance::deepest_piece_overlap(&a.pieces, &b.pieces)
        .map(|d| format!(" by a depth of {:.3e}", d * asm.grid.step()))
        .unwrap_or_default();
    Some(
        Problem::error(format!(
            "overlaps part \"{}\"{depth}: {} lies strictly inside both",
            b.name,
            fmt_witness(&w, &asm.grid)
        ))
        .in_part(a.name.clone())
        .with_kind(ProblemKind::Overlap {
            other: Box::new(b.name.clone()),
        }),
    )
}
