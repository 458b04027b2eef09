//! Vertices where the solid touches itself: the triangles around the vertex form more
//! than one fan ("umbrella"), like the apex shared by two cones (a bowtie). Valid, and
//! reported as a note. Only vertices whose edges are all manifold are examined; the
//! others are already reported through their edges.

use super::edges::{third, HalfEdges};
use crate::mesh::Mesh;
use rayon::prelude::*;

/// Vertices with more than one umbrella.
pub(crate) fn touching_vertices(mesh: &Mesh, he: &HalfEdges) -> Vec<u32> {
    (0..mesh.vertices.len() as u32)
        .into_par_iter()
        .with_min_len(4096)
        .filter(|&a| umbrellas(mesh, he, a).is_some_and(|k| k > 1))
        .collect()
}

/// The number of umbrellas around `a`, or `None` when some edge at `a` is not manifold.
fn umbrellas(mesh: &Mesh, he: &HalfEdges, a: u32) -> Option<usize> {
    let out = he.from(a);
    if out.is_empty() {
        return Some(0);
    }
    // Every edge at `a` used once in each direction.
    let mut targets = Vec::with_capacity(out.len());
    for (i, &e) in out.iter().enumerate() {
        let b = (e >> 32) as u32;
        if i > 0 && (out[i - 1] >> 32) as u32 == b {
            return None;
        }
        if he.between(b, a).len() != 1 {
            return None;
        }
        targets.push(b);
    }
    let mut seen = vec![false; out.len()];
    let mut count = 0;
    for start in 0..out.len() {
        if seen[start] {
            continue;
        }
        count += 1;
        // Walk around `a`: triangle (a, b, c) is followed by the one with a → c.
        let mut k = start;
        loop {
            seen[k] = true;
            let t = out[k] as u32;
            let c = third(&mesh.triangles[t as usize], a, targets[k]);
            k = targets.binary_search(&c).ok()?;
            if seen[k] {
                break;
            }
        }
    }
    Some(count)
}
