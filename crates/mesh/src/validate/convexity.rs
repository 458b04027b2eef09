//! Convexity, decided exactly and locally: a closed, connected, embedded surface whose
//! every edge is convex or flat (no reflex edge: for the two triangles at an edge, the
//! far vertex of one is never strictly outside the other's plane) bounds a convex body.
//! Reflex edges are counted while edges are classified (see [`super::edges`]).

use super::MeshInfo;

/// True when the validated surface bounds a convex solid.
pub(crate) fn is_convex(info: &MeshInfo, has_errors: bool) -> bool {
    info.closed
        && !has_errors
        && info.volume6.is_some()
        && info.shells == 1
        && info.reflex_edges == 0
        && info.touching_edges == 0
        && info.touching_vertices == 0
        && info.self_intersections == 0
}
