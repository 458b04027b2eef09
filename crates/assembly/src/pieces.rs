//! Declared convex pieces: each must be a valid closed solid and convex, and the pieces
//! of one part must have disjoint interiors.

use crate::convex::{convex_polytope, QUADRATIC_LIMIT};
use crate::witness::{fmt_witness, simplest, verified_in_polytopes};
use apart_formats::RawObject;
use apart_kernel::{Aabb, Bvh, Grid, HPoint, Int};
use apart_mesh::locate::Locator;
use apart_mesh::validate::check_solid;
use apart_mesh::{fmt_point, Problem, ProblemKind};
use apart_pieces::interference::{interior_witness, triangle_meets_interior};
use apart_pieces::{Polytope, PolytopeError};
use rayon::prelude::*;

/// A piece's integer box ([`Polytope::integer_box`]). A piece beyond that box's range
/// (never one on a grid, whose coordinates stay below 2^52) gets a box holding every
/// other, which costs tests and never hides an overlap.
pub(crate) fn piece_box(p: &Polytope) -> Aabb {
    const FAR: i64 = 1 << 61;
    p.integer_box().unwrap_or(Aabb {
        min: [-FAR; 3],
        max: [FAR; 3],
    })
}

/// The convex polytope of a piece, or the problems that prevent it.
pub(crate) fn convex_piece(raw: &RawObject, grid: &Grid) -> Result<Polytope, Vec<Problem>> {
    let (mesh, info, problems) = check_solid(raw, grid);
    let (Some(mesh), Some(info)) = (mesh, info) else {
        return Err(problems);
    };
    if problems.iter().any(Problem::is_error) || info.volume6.is_none() {
        return Err(problems);
    }
    if mesh.triangles.len() > QUADRATIC_LIMIT && !info.convex {
        let mut out = problems;
        out.push(
            Problem::error(format!(
                "declared piece is not convex: it has {} reflex edges{}",
                info.reflex_edges,
                if info.shells > 1 {
                    " and several shells"
                } else {
                    ""
                }
            ))
            .with_kind(ProblemKind::Piece),
        );
        return Err(out);
    }
    match convex_polytope(&mesh) {
        Ok(p) => Ok(p),
        Err(e) => {
            let face = |t: usize| format!("face {}", mesh.source_faces[t]);
            let (element, why) = match e {
                PolytopeError::NotConvex { triangle, vertex } => (
                    Some(format!(
                        "{}, vertex {} at {}",
                        face(triangle),
                        mesh.source_vertices[vertex],
                        fmt_point(grid, &mesh.vertices[vertex])
                    )),
                    "the vertex lies outside the plane of the face".to_string(),
                ),
                PolytopeError::DegenerateTriangle { triangle } => (
                    Some(face(triangle)),
                    "the face has collinear vertices".to_string(),
                ),
                other => (None, other.to_string()),
            };
            let mut p = Problem::error(format!("declared piece is not convex: {why}"))
                .with_kind(ProblemKind::Piece);
            p.element = element;
            let mut out = problems;
            out.push(p);
            Err(out)
        }
    }
}

/// How many overlapping pairs of one part's pieces are listed before the search stops:
/// one is enough to refuse the part, and a list of thousands of copies of one piece
/// would otherwise cost a quadratic search and its memory.
pub(crate) const MAX_LISTED_OVERLAPS: usize = 20;

/// Pieces of one part whose interiors overlap, each with a point strictly inside both;
/// at most [`MAX_LISTED_OVERLAPS`], then one problem saying the list stops. Candidate
/// pairs come from a hierarchy of the pieces' boxes, so the search is `n log n` plus
/// the pairs whose boxes overlap.
pub(crate) fn overlapping_pieces(
    pieces: &[Polytope],
    labels: &[String],
    grid: &Grid,
) -> Vec<Problem> {
    let boxes: Vec<_> = pieces.iter().map(piece_box).collect();
    let bvh = Bvh::new(boxes.clone());
    let mut out = Vec::new();
    for i in 0..pieces.len() {
        let mut near = Vec::new();
        bvh.query(&boxes[i], |j| {
            if j as usize > i && boxes[i].overlaps_open(&boxes[j as usize]) {
                near.push(j as usize);
            }
        });
        near.sort_unstable();
        for j in near {
            if out.len() == MAX_LISTED_OVERLAPS {
                out.push(
                    Problem::error(format!(
                        "more pieces overlap; the list stops at {MAX_LISTED_OVERLAPS} pairs"
                    ))
                    .with_kind(ProblemKind::Piece),
                );
                return out;
            }
            let (a, b) = (&pieces[i], &pieces[j]);
            if let Some(w) = interior_witness(a, b).filter(|w| verified_in_polytopes(w, a, b)) {
                let w = simplest(w, grid, |r| verified_in_polytopes(r, a, b));
                out.push(
                    Problem::error(format!(
                        "the pieces overlap: {} lies strictly inside both",
                        fmt_witness(&w, grid)
                    ))
                    .at(format!("pieces {} and {}", labels[i], labels[j]))
                    .with_kind(ProblemKind::Piece),
                );
            }
        }
    }
    out
}

/// Declared pieces that do not lie within the part's solid: a triangle of its mesh
/// passes through a piece's interior, or a piece lies outside it. With the pieces'
/// interiors disjoint and their volumes adding up to the part's, pieces that all lie
/// within the solid make it up exactly (volumes alone would take a piece anywhere).
/// `locator` is built on the part's valid, closed mesh. Exact: the triangles near a
/// piece are tested by a separating-axis test, then one interior point is located.
pub(crate) fn pieces_outside_mesh(
    pieces: &[Polytope],
    labels: &[String],
    locator: &Locator,
    grid: &Grid,
) -> Vec<Problem> {
    let mesh = locator.mesh();
    pieces
        .par_iter()
        .zip(labels)
        .filter_map(|(p, label)| {
            let mut crossing = None;
            locator.bvh().query(&piece_box(p), |t| {
                if crossing.is_none() {
                    let c = mesh.corners(t as usize).map(|c| *c);
                    if triangle_meets_interior(p, &c) {
                        crossing = Some(c);
                    }
                }
            });
            let what = match crossing {
                Some(c) => format!(
                    "the declared piece is not within the part: the mesh's triangle {} {} {} passes through its interior",
                    fmt_point(grid, &c[0]),
                    fmt_point(grid, &c[1]),
                    fmt_point(grid, &c[2])
                ),
                None => {
                    // No triangle meets the open piece: it is wholly inside or outside.
                    let n = p.vertices().len() as i64;
                    let sum = p.vertices().iter().fold([Int::ZERO; 3], |s, v| {
                        let c = v.to_ints();
                        [0, 1, 2].map(|k| &s[k] + &c[k])
                    });
                    let centre = HPoint::from_big(sum, p.den() * &Int::from(n));
                    if locator.strictly_inside(&centre) {
                        return None;
                    }
                    "the declared piece lies outside the part's mesh".to_string()
                }
            };
            Some(
                Problem::error(what)
                    .at(format!("piece {label}"))
                    .with_kind(ProblemKind::Piece),
            )
        })
        .collect()
}
