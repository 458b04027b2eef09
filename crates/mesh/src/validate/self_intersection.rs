//! Self-intersection: two triangles of one mesh that meet beyond what they share
//! (a common vertex or edge after welding). Broad phase: the hierarchy over triangle
//! boxes, queried in parallel for every triangle; narrow phase: the exact tests of
//! [`crate::intersect::triangle_pair`].

use crate::bvh::Bvh;
use crate::intersect::{triangle_pair, Contact};
use crate::mesh::Mesh;

/// The first `limit` intersecting pairs `(t, u, contact)` with `t < u`, in order, and
/// the total number of intersecting pairs.
pub(crate) fn self_intersections(
    mesh: &Mesh,
    bvh: &Bvh,
    limit: usize,
) -> (Vec<(u32, u32, Contact)>, usize) {
    let (mut found, count) = bvh.self_pairs(
        || (Vec::new(), 0usize),
        |(kept, count), t, u| {
            let (tt, uu) = (mesh.triangles[t as usize], mesh.triangles[u as usize]);
            if let Some(c) = triangle_pair(&mesh.vertices, tt, uu) {
                *count += 1;
                keep_smallest(kept, (t, u, c), limit);
            }
        },
        |(mut a, n), (b, m)| {
            for x in b {
                keep_smallest(&mut a, x, limit);
            }
            (a, n + m)
        },
    );
    found.sort_by_key(|&(t, u, _)| (t, u));
    (found, count)
}

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
