//! Declared convex pieces: each must be a valid closed solid and convex, and the pieces
//! of one part must have disjoint interiors.

use crate::convex::{convex_polytope, QUADRATIC_LIMIT};
use crate::load::polytope_bbox;
use crate::witness::{fmt_witness, simplest, verified_in_polytopes};
use apart_formats::RawObject;
use apart_kernel::Grid;
use apart_mesh::validate::check_solid;
use apart_mesh::{fmt_point, Problem, ProblemKind};
use apart_pieces::interference::interior_witness;
use apart_pieces::{Polytope, PolytopeError};
use std::path::PathBuf;

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

/// Pieces of one part whose interiors overlap, each with a point strictly inside both.
pub(crate) fn overlapping_pieces(
    pieces: &[Polytope],
    sources: &[PathBuf],
    grid: &Grid,
) -> Vec<Problem> {
    let boxes: Vec<_> = pieces.iter().map(polytope_bbox).collect();
    let mut out = Vec::new();
    for i in 0..pieces.len() {
        for j in i + 1..pieces.len() {
            if !boxes[i].overlaps_open(&boxes[j]) {
                continue;
            }
            let (a, b) = (&pieces[i], &pieces[j]);
            if let Some(w) = interior_witness(a, b).filter(|w| verified_in_polytopes(w, a, b)) {
                let w = simplest(w, grid, |r| verified_in_polytopes(r, a, b));
                out.push(
                    Problem::error(format!(
                        "the pieces overlap: {} lies strictly inside both",
                        fmt_witness(&w, grid)
                    ))
                    .at(format!(
                        "pieces {} and {}",
                        sources[i].display(),
                        sources[j].display()
                    ))
                    .with_kind(ProblemKind::Piece),
                );
            }
        }
    }
    out
}
