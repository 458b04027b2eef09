//! Exact repair of the defects of real CAD exports, run on a snapped mesh before
//! validation: files with T-junction seams, duplicated, flipped or cancelling faces,
//! small holes and inconsistently oriented shells are common, and each repair is
//! decided by exact integer predicates, so it never moves a vertex nor guesses with a
//! tolerance. Everything done is counted in a [`RepairReport`].
//!
//! The steps, in order ([`repair`]):
//! 1. remove zero-area triangles, extra copies of a triangle, and pairs of copies
//!    running opposite ways;
//! 2. split triangles at T-junctions (vertices strictly inside an unpaired edge), until
//!    nothing changes, then step 1 again on the result;
//! 3. close boundary loops of at most [`RepairOptions::max_hole_edges`] edges;
//! 4. make each shell consistently oriented, then outward (a cavity inward);
//! 5. drop the vertices no triangle uses.
//!
//! What repair cannot fix is left for validation to report: faces that genuinely cross,
//! non-manifold edges, larger holes. [`bodies`] then splits a repaired mesh into
//! separate solids.

mod bodies;
mod clean;
mod compact;
mod edges;
mod holes;
pub mod loops;
mod nesting;
mod orient;
mod report;
mod tjunction;

pub use bodies::bodies;
pub use report::RepairReport;

use crate::mesh::Mesh;

/// What [`repair`] may do.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RepairOptions {
    /// Boundary loops with at most this many edges are closed (default 64).
    pub max_hole_edges: usize,
}

impl Default for RepairOptions {
    fn default() -> RepairOptions {
        RepairOptions { max_hole_edges: 64 }
    }
}

/// Repairs `mesh` in place (see the module documentation for the steps) and reports
/// every repair made. New triangles keep the source face of the triangle they were
/// split from, or for a hole of a triangle along it; unused vertices are dropped with
/// their `source_vertices`. Never panics; an empty report means the mesh is unchanged
/// (up to the numbering of unused vertices).
pub fn repair(mesh: &mut Mesh, opts: &RepairOptions) -> RepairReport {
    repair_keeping_orientation(mesh, opts).0
}

/// [`repair`], and when orienting flipped faces or shells, the mesh as it was before
/// (every other repair made, vertices numbered alike): for a caller that reads the
/// faces' own orientation (the winding-number rule) and must decide which to trust.
pub fn repair_keeping_orientation(
    mesh: &mut Mesh,
    opts: &RepairOptions,
) -> (RepairReport, Option<Mesh>) {
    let mut report = RepairReport::default();
    clean::clean(mesh, &mut report);
    let before = report.tjunctions;
    tjunction::split(mesh, &mut report);
    if report.tjunctions > before {
        clean::clean(mesh, &mut report);
    }
    holes::close(mesh, opts.max_hole_edges, &mut report);
    let unoriented = mesh.clone();
    orient::orient(mesh, &mut report);
    compact::drop_unused_vertices(mesh);
    let flipped = report.flipped_faces > 0 || report.flipped_shells > 0;
    let unoriented = flipped.then(|| {
        let mut u = unoriented;
        compact::drop_unused_vertices(&mut u);
        u
    });
    (report, unoriented)
}
