//! The solid a surface winds around, for a mesh that is not a closed manifold: open
//! edges, non-manifold edges whose faces do not alternate, faces that cross, doubled
//! walls, overlapping shells.
//!
//! The part is the set of points whose winding number with respect to its oriented
//! faces is at least 1. That number is defined (the same for every ray that counts it)
//! once the surface has no net boundary, so the open boundary is first closed where that
//! can be done without guessing (loops that are planar or nearly so, and seams whose
//! two sides lie within the seam width; see `apart_mesh::repair::loops`); any other
//! loop leaves the part refused, with its loops and their sizes. The solid is then cut
//! into convex cells by the exact winding-number decomposition
//! (`apart_decompose::decompose_union`), which keeps a cell exactly when its winding
//! number is at least 1: every piece is inside the solid or it is not, with no
//! tolerance. A surface whose total signed volume is negative is taken as inside out
//! and reversed first (the solid is then where it winds at most -1).
//!
//! Everything is reported: the defects, the loops closed, the faces that enclose
//! nothing (the same winding number, at least 1 or at most 0, on both sides, decided
//! exactly at an interior point of each face), the cells kept, and the volume before
//! (the signed volume, the integral of the winding number) and after.

use crate::model::WindingReport;
use crate::options::LoadOptions;
use apart_decompose::{decompose_union, DecomposeError};
use apart_kernel::plane::HPoint;
use apart_kernel::{Grid, Int, Rational};
use apart_mesh::locate::Locator;
use apart_mesh::repair::loops::{close_loops, nonmanifold_edges, LoopClosing, PLANAR};
use apart_mesh::{fmt_point, Mesh, Problem, ProblemKind};
use apart_pieces::Polytope;
use rayon::prelude::*;

/// A seam may be this fraction of the part's size wide (unless a larger tolerance was
/// stated): a tenth of the largest tolerance `--tolerance auto` may choose.
pub const SEAM_WIDTH: f64 = 1e-4;

/// The solid a surface winds around: its pieces, the surface with its caps, and what
/// was done.
pub(super) struct WindingSolid {
    pub pieces: Vec<Polytope>,
    pub mesh: Mesh,
    pub report: WindingReport,
}

/// The problems that the solid of the winding number resolves: the surface's own
/// defects, not those of its vertices, faces or pieces.
pub(super) fn resolves(p: &Problem) -> bool {
    p.is_error()
        && matches!(
            p.kind,
            ProblemKind::OpenBoundary
                | ProblemKind::InconsistentOrientation
                | ProblemKind::NonManifold
                | ProblemKind::SelfIntersection
                | ProblemKind::Shell
                | ProblemKind::ZeroVolume
        )
}

/// The solid `mesh` winds around, or the problems that refuse it (open loops that are
/// neither planar nor seams, an empty solid, a stopped or failed decomposition).
pub(super) fn winding_solid(
    mesh: &Mesh,
    crossing_pairs: usize,
    grid: &Grid,
    opts: &LoadOptions,
) -> Result<WindingSolid, Vec<Problem>> {
    let mut mesh = mesh.clone();
    let nonmanifold = nonmanifold_edges(&mesh);
    let gap = seam_width(&mesh, grid, opts);
    let closing = close_loops(&mut mesh, gap);
    if !closing.open.is_empty() {
        return Err(open_loops(&closing, grid, gap));
    }
    let volume6 = mesh.volume6();
    let inside_out = volume6 < Int::ZERO;
    if inside_out {
        mesh.flip();
    }
    let mut triangles = mesh.triangles.clone();
    triangles.extend(closing.balance.iter().map(
        |t| {
            if inside_out {
                [t[0], t[2], t[1]]
            } else {
                *t
            }
        },
    ));
    let d_opts = apart_decompose::Options {
        stop: Some(opts.progress.stop_flag()),
        ..Default::default()
    };
    let d = match decompose_union(&mesh.points(), &triangles, &d_opts) {
        Ok(d) => d,
        Err(DecomposeError::NotPositive) => {
            return Err(vec![Problem::error(
                "the surface winds around nothing: no point has a winding number of at least 1",
            )
            .with_kind(ProblemKind::ZeroVolume)])
        }
        Err(DecomposeError::Stopped) => {
            return Err(vec![Problem::error(
                "stopped while finding the solid the surface winds around",
            )])
        }
        Err(e) => {
            return Err(vec![Problem::error(format!(
                "the solid the surface winds around could not be computed: {e}"
            ))
            .with_kind(ProblemKind::Decomposition)])
        }
    };
    let (lowest, highest) = d.stats.winding.unwrap_or((0, 1));
    let after = d
        .pieces
        .iter()
        .fold(Rational::zero(), |s, p| &s + &p.volume());
    let report = WindingReport {
        part: String::new(),
        open_edges: closing.boundary_edges,
        nonmanifold_edges: nonmanifold,
        crossing_pairs,
        loops_closed: closing.planar + closing.seams,
        seams_closed: closing.seams,
        cap_triangles: closing.triangles,
        faces_dropped: faces_enclosing_nothing(&mesh),
        cells_kept: d.stats.partition_pieces,
        pieces: d.pieces.len(),
        inside_out,
        lowest_winding: lowest,
        highest_winding: highest,
        volume_before: Rational::new(if inside_out { -volume6 } else { volume6 }, Int::from(6)),
        volume_after: after,
    };
    Ok(WindingSolid {
        pieces: d.pieces,
        mesh,
        report,
    })
}

/// The widest seam closed, in grid units: [`SEAM_WIDTH`] of the part's box diagonal, or
/// the stated fixed tolerance when larger.
fn seam_width(mesh: &Mesh, grid: &Grid, opts: &LoadOptions) -> f64 {
    let diagonal = mesh.bbox().map_or(0.0, |b| {
        (0..3)
            .map(|k| ((b.max[k] - b.min[k]) as f64).powi(2))
            .sum::<f64>()
            .sqrt()
    });
    let stated = match opts.tolerance {
        crate::Tolerance::Fixed(t) => t / grid.step(),
        _ => 0.0,
    };
    (SEAM_WIDTH * diagonal).max(stated)
}

/// The refusal of a surface with loops that cannot be closed.
fn open_loops(c: &LoopClosing, grid: &Grid, gap: f64) -> Vec<Problem> {
    let mut out = vec![Problem::error(format!(
        "the surface is open and {} of its boundary loops cannot be closed: a loop is closed only when it is planar (every vertex within {}% of its size from its plane) or a seam narrower than {}",
        c.open.len(),
        PLANAR * 100.0,
        fmt_length(gap * grid.step())
    ))
    .with_kind(ProblemKind::OpenBoundary)];
    let mut open = c.open.clone();
    open.sort_by(|a, b| b.size.total_cmp(&a.size));
    for o in open.iter().take(5) {
        out.push(
            Problem::error(format!(
                "open loop of {} edges, {} across, up to {} from its plane",
                o.edges,
                fmt_length(o.size * grid.step()),
                fmt_length(o.deviation * grid.step())
            ))
            .with_kind(ProblemKind::OpenBoundary)
            .at(fmt_point(grid, &o.at)),
        );
    }
    if open.len() > 5 {
        out.push(
            Problem::error(format!("... and {} more open loops", open.len() - 5))
                .with_kind(ProblemKind::OpenBoundary),
        );
    }
    out
}

/// A length in input units, with four significant digits.
fn fmt_length(v: f64) -> String {
    format!("{}", (v * 1e4).round() / 1e4).replace("inf", "∞")
}

/// Faces with the same side of 1 in winding number on both sides: inside the solid
/// (an interior wall, a doubled face) or outside it (a fin). Decided exactly at the
/// centroid of each face, from the winding number of the other faces there; a face
/// whose centroid lies on another face is counted as bounding the solid.
fn faces_enclosing_nothing(mesh: &Mesh) -> usize {
    // The surface three times larger, so that each face's centroid is a grid point and
    // the exact predicates keep to machine integers.
    let tripled = Mesh {
        vertices: mesh.vertices.iter().map(|v| v.map(|c| 3 * c)).collect(),
        ..mesh.clone()
    };
    let locator = Locator::new(&tripled);
    (0..mesh.triangles.len() as u32)
        .into_par_iter()
        .with_min_len(256)
        .filter(|&t| {
            let [a, b, c] = mesh.corners(t as usize);
            let centroid = HPoint::int([0, 1, 2].map(|k| a[k] + b[k] + c[k]));
            let Some(others) = locator.winding_filtered(&centroid, |u| u != t) else {
                return false;
            };
            // `others` is counted along +x from the centroid moved by (0, ε, ε²). When
            // the face is not parallel to x, points just in front of it and just behind
            // it see the same other faces ahead, and the face itself ahead when its
            // normal points against x (from the front, adding -1) or along x (from the
            // back, adding +1). When it is parallel to x, the moved point lies on the
            // side its normal's y (or else z) component points to, and the ray does not
            // cross the face: `others` is the winding number on that side.
            let n = apart_kernel::orient::normal(a, b, c);
            let (front, back) = if n[0] != 0 {
                (others - i64::from(n[0] < 0), others + i64::from(n[0] > 0))
            } else if (if n[1] != 0 { n[1] } else { n[2] }) > 0 {
                (others, others + 1)
            } else {
                (others - 1, others)
            };
            (front >= 1) == (back >= 1)
        })
        .count()
}

/// The solid of the faces as given, when orienting them (to agree with their
/// neighbours) changed the surface and the faces as given wind nowhere negatively: then
/// the disagreeing faces are a fold (flaps doubled back inside the solid, raising its
/// winding number), not faces an exporter flipped (which make it negative where they
/// turn against the rest). `None` keeps the oriented surface: the two are the same
/// chain once the open loops are capped (single flipped faces), or the faces as given
/// have no solid, or wind negatively somewhere.
pub(super) fn as_given(
    unoriented: &Mesh,
    oriented: &Mesh,
    grid: &Grid,
    opts: &LoadOptions,
) -> Option<WindingSolid> {
    let mut capped = unoriented.clone();
    let probe = close_loops(&mut capped, 0.0);
    if probe.open.is_empty() && same_chain(&capped.triangles, &oriented.triangles) {
        return None;
    }
    // Validation has not looked at these faces: their crossings are not counted.
    let solid = winding_solid(unoriented, 0, grid, opts).ok()?;
    (solid.report.lowest_winding >= 0 && !solid.report.inside_out).then_some(solid)
}

/// Two lists of oriented triangles are the same chain: each oriented triangle used as
/// often in both, a triangle and its reverse cancelling.
fn same_chain(a: &[[u32; 3]], b: &[[u32; 3]]) -> bool {
    let mut count: std::collections::HashMap<[u32; 3], i64> = Default::default();
    for (list, sign) in [(a, 1), (b, -1)] {
        for t in list {
            let k = (0..3).min_by_key(|&k| t[k]).expect("three corners");
            let (m, x, y) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            let (key, s) = if x < y {
                ([m, x, y], sign)
            } else {
                ([m, y, x], -sign)
            };
            *count.entry(key).or_default() += s;
        }
    }
    count.values().all(|&c| c == 0)
}

/// The note of a part made by the winding rule: what the surface had, what was closed,
/// what the solid is.
pub(super) fn note(r: &WindingReport, as_given: bool, grid: &Grid) -> String {
    let mut had = Vec::new();
    let mut say = |n: usize, one: &str, many: &str| {
        if n > 0 {
            had.push(format!("{n} {}", if n == 1 { one } else { many }));
        }
    };
    say(r.open_edges, "open edge", "open edges");
    say(
        r.nonmanifold_edges,
        "non-manifold edge",
        "non-manifold edges",
    );
    say(
        r.crossing_pairs,
        "pair of crossing faces",
        "pairs of crossing faces",
    );
    let mut text = format!(
        "repaired: the surface is not a closed manifold ({}); the part is the solid it winds around (winding number at least 1)",
        if had.is_empty() { "its shells overlap".to_string() } else { had.join(", ") }
    );
    if r.loops_closed > 0 {
        text += &format!(
            ", after closing {} boundary {} ({} {}, {} triangles)",
            r.loops_closed,
            if r.loops_closed == 1 { "loop" } else { "loops" },
            r.seams_closed,
            if r.seams_closed == 1 { "seam" } else { "seams" },
            r.cap_triangles
        );
    }
    if r.inside_out {
        text += ", the surface reversed (it was inside out)";
    }
    if as_given {
        text += ", the faces oriented as given (those that disagree with their neighbours fold back inside the solid: turning them would carve it, and they make no winding number negative)";
    }
    text += &format!(
        ": {} faces enclose nothing, {} cells kept as {} exact convex {}, volume {} (signed, of the surface) → {}",
        r.faces_dropped,
        r.cells_kept,
        r.pieces,
        if r.pieces == 1 { "piece" } else { "pieces" },
        crate::fmt_volume(&r.volume_before, grid),
        crate::fmt_volume(&r.volume_after, grid)
    );
    text
}
