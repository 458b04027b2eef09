//! Self-intersection: two triangles of one mesh that meet beyond what they share
//! (a common vertex or edge after welding). Narrow phase: the exact tests of
//! [`crate::intersect::triangle_pair`]. Two broad phases split the pairs between them:
//!
//! - Pairs of triangles sharing a vertex `v` (both with three distinct vertex indices)
//!   are found around `v`. Two such triangles meet beyond what they share exactly when
//!   their corner cones at `v` share a direction: their intersection is convex and
//!   contains `v`, so any other common point `p` brings the whole segment `v p` with it.
//!   A corner cone meets the unit sphere around `v` in an arc; a small box around that
//!   arc (floating point, made larger than its rounding error) is a filter, and only
//!   triangles whose boxes overlap are tested exactly. A fan of `n` triangles around
//!   one vertex (a tessellated cap) then costs `O(n log n)` box work and `O(n)` exact
//!   tests instead of `n²/2` exact tests. Each pair is taken at its smallest shared
//!   vertex only.
//! - All other pairs come from the hierarchy over triangle boxes, traversed against
//!   itself in parallel. A node whose triangles all share one vertex (a piece of a
//!   fan) is skipped against another such node with the same vertex, so a fan's pairs
//!   are not even enumerated there. A triangle thin across its box (a cap's radial
//!   sliver) is boxed in slabs instead, and a pair whose boxes meet is first filtered
//!   exactly by planes computed once per triangle (one triangle strictly on one side
//!   of the other's plane, or, coplanar, outside an edge line of it).

mod faces;
mod hierarchy;
mod pieces;
mod planes;
mod polygon;
mod slab;
mod stars;
#[cfg(test)]
mod tests;

use crate::intersect::{triangle_pair, Contact};
use crate::mesh::Mesh;
use apart_kernel::Bvh;
use faces::{against_faces, certified_groups, Face};
use hierarchy::Pieces;
use planes::{apart_by_planes, Flat};
use rayon::prelude::*;
use stars::around_vertices;

/// Intersecting pairs found so far: the smallest `limit` of them, their number, and
/// how many exact narrow-phase tests were run.
struct Found {
    kept: Vec<(u32, u32, Contact)>,
    count: usize,
    tests: usize,
}

impl Found {
    /// Nothing found yet.
    fn new() -> Found {
        Found {
            kept: Vec::new(),
            count: 0,
            tests: 0,
        }
    }

    /// Runs the exact test on triangles `t < u`, unless their [`Flat`]s show them apart.
    fn test_filtered(&mut self, mesh: &Mesh, flats: &[Flat], t: u32, u: u32, limit: usize) {
        if !apart_by_planes(mesh, flats, t, u) {
            self.test(mesh, t, u, limit);
        }
    }

    /// Runs the exact test on triangles `t < u`.
    fn test(&mut self, mesh: &Mesh, t: u32, u: u32, limit: usize) {
        let (tt, uu) = (mesh.triangles[t as usize], mesh.triangles[u as usize]);
        self.tests += 1;
        if let Some(c) = triangle_pair(&mesh.vertices, tt, uu) {
            self.count += 1;
            keep_smallest(&mut self.kept, (t, u, c), limit);
        }
    }

    /// Both sets of pairs, still the smallest `limit`, with their counts added.
    fn merge(mut self, o: Found, limit: usize) -> Found {
        for x in o.kept {
            keep_smallest(&mut self.kept, x, limit);
        }
        self.count += o.count;
        self.tests += o.tests;
        self
    }
}

/// The first `limit` intersecting pairs `(t, u, contact)` with `t < u`, in order, and
/// the total number of intersecting pairs.
pub(crate) fn self_intersections(
    mesh: &Mesh,
    bvh: &Bvh,
    limit: usize,
) -> (Vec<(u32, u32, Contact)>, usize) {
    let (found, count, _) = self_intersections_counted(mesh, bvh, limit);
    (found, count)
}

/// [`self_intersections`], also returning the number of exact narrow-phase tests.
pub(crate) fn self_intersections_counted(
    mesh: &Mesh,
    bvh: &Bvh,
    limit: usize,
) -> (Vec<(u32, u32, Contact)>, usize, usize) {
    let tris = &mesh.triangles;
    // Triangles with three distinct vertex indices: their pairs sharing a vertex are
    // the stars' business.
    let distinct: Vec<bool> = tris
        .par_iter()
        .with_min_len(8192)
        .map(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .collect();
    let around = around_vertices(mesh, &distinct, limit);

    let flats: Vec<Flat> = tris
        .par_iter()
        .with_min_len(8192)
        .map(|t| Flat::of(mesh, t))
        .collect();
    // Certified planar faces leave the hierarchy: their triangles are never tested
    // against each other, and against the others through a hierarchy of their own.
    let groups = certified_groups(mesh, &distinct, &flats);
    let in_group = group_of_triangles(tris.len(), &groups);
    let boxes = Pieces::new(mesh, bvh, &groups, &in_group, &flats)
        .pairs(mesh, bvh, &distinct, &flats, limit);
    let faces = against_faces(mesh, bvh, &groups, &in_group, &distinct, &flats, limit);
    let all = boxes.merge(around, limit).merge(faces, limit);
    let mut found = all.kept;
    found.sort_by_key(|&(t, u, _)| (t, u));
    (found, all.count, all.tests)
}

/// The certified face of every one of `n` triangles (its index in `groups`), or `NONE`.
fn group_of_triangles(n: usize, groups: &[Face]) -> Vec<u32> {
    let mut in_group = vec![NONE; n];
    for (g, face) in groups.iter().enumerate() {
        for &t in &face.triangles {
            in_group[t as usize] = g as u32;
        }
    }
    in_group
}

/// No vertex (padding in a node's common vertices).
const NONE: u32 = u32::MAX;

/// Adds `x` to `kept` when fewer than `limit` are kept, or in place of the largest
/// pair kept when `x` is smaller.
fn keep_smallest(kept: &mut Vec<(u32, u32, Contact)>, x: (u32, u32, Contact), limit: usize) {
    if kept.len() < limit {
        kept.push(x);
        return;
    }
    if let Some((i, m)) = kept.iter().enumerate().max_by_key(|(_, &(t, u, _))| (t, u)) {
        if (x.0, x.1) < (m.0, m.1) {
            kept[i] = x;
        }
    }
}
