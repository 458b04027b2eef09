//! The box phase of the self-intersection search: the hierarchy over the triangles'
//! boxes (thin triangles boxed in pieces, certified faces left out) traversed against
//! itself, for the pairs that share no vertex.

use super::faces::Face;
use super::pieces::piece_boxes;
use super::planes::Flat;
use super::slab::Slab;
use super::{Found, NONE};
use crate::mesh::Mesh;
use apart_kernel::Aabb;
use apart_kernel::Bvh;
use rayon::prelude::*;

/// The boxes of the box phase. Thin triangles (the slivers of a tessellated cap) are
/// boxed in pieces: the box phase then meets far fewer pairs. `owner[p]` is the
/// triangle of box `p`; the boxes of triangle `t` are `first[t]..first[t + 1]`.
pub(super) struct Pieces {
    owner: Vec<u32>,
    first: Vec<u32>,
    /// The hierarchy over the pieces, or `None` when they are the triangles' own boxes
    /// one for one (the hierarchy of the triangles then serves).
    bvh: Option<Bvh>,
}

impl Pieces {
    /// The boxes of every triangle outside the certified faces `groups` (`in_group[t]`
    /// the face of triangle `t`, or `NONE`): its own box from `bvh`, or the boxes of
    /// its pieces when it is thin.
    pub(super) fn new(
        mesh: &Mesh,
        bvh: &Bvh,
        groups: &[Face],
        in_group: &[u32],
        flats: &[Flat],
    ) -> Pieces {
        let tris = &mesh.triangles;
        let pieces: Vec<Vec<Aabb>> = (0..tris.len())
            .into_par_iter()
            .with_min_len(4096)
            .map(|t| match (in_group[t] != NONE, flats[t].ok) {
                (true, _) => Vec::new(),
                (false, true) => piece_boxes(mesh, t, bvh),
                (false, false) => vec![bvh.boxes()[t]],
            })
            .collect();
        let chunked = !groups.is_empty() || pieces.iter().any(|b| b.len() > 1);
        if !chunked {
            let n = tris.len() as u32;
            return Pieces {
                owner: (0..n).collect(),
                first: (0..=n).collect(),
                bvh: None,
            };
        }
        let mut owner = Vec::new();
        let mut first = Vec::with_capacity(tris.len() + 1);
        let mut boxes = Vec::new();
        for (t, b) in pieces.into_iter().enumerate() {
            first.push(boxes.len() as u32);
            owner.extend(std::iter::repeat_n(t as u32, b.len()));
            boxes.extend(b);
        }
        first.push(boxes.len() as u32);
        Pieces {
            owner,
            first,
            bvh: Some(Bvh::new(boxes)),
        }
    }

    /// Whether boxes `p` of `t` and `q` of `u` are the first pair of their boxes that
    /// meets (in index order), so that each triangle pair is tested once.
    fn first_meeting(&self, boxes_of: &[Aabb], t: u32, p: u32, u: u32, q: u32) -> bool {
        let first = &self.first;
        let (rt, ru) = (
            first[t as usize]..first[t as usize + 1],
            first[u as usize]..first[u as usize + 1],
        );
        if rt.len() == 1 && ru.len() == 1 {
            return true;
        }
        for i in rt {
            for j in ru.clone() {
                if (i, j) == (p, q) {
                    return true;
                }
                if boxes_of[i as usize].overlaps(&boxes_of[j as usize]) {
                    return false;
                }
            }
        }
        true
    }

    /// The intersecting pairs of triangles whose boxes meet and which share no vertex
    /// (pairs sharing one are found around it), each tested once. `bvh` is the
    /// hierarchy over the triangles' own boxes, used when no triangle was cut.
    pub(super) fn pairs(
        &self,
        mesh: &Mesh,
        bvh: &Bvh,
        distinct: &[bool],
        flats: &[Flat],
        limit: usize,
    ) -> Found {
        let tris = &mesh.triangles;
        let owner = &self.owner;
        let bvh = self.bvh.as_ref().unwrap_or(bvh);
        let boxes_of = bvh.boxes();
        // Every leaf's slab along the normal of its first triangle. Inner nodes get none:
        // theirs would rarely separate anything and would cost a test per pair of nodes
        // (a tenth of the validation of a million-triangle torus).
        let slabs = bvh.node_labels(
            |prims| Slab::of_triangles(mesh, prims.iter().map(|&p| owner[p as usize])),
            |_, _| Slab::NONE,
            Slab::NONE,
        );
        let labels = self.common_vertices(mesh, bvh, distinct);
        bvh.self_pairs_pruned(
            Found::new,
            |found, p, q| {
                let (mut t, mut u) = (owner[p as usize], owner[q as usize]);
                let (mut p, mut q) = (p, q);
                if t == u {
                    return;
                }
                if t > u {
                    (t, u, p, q) = (u, t, q, p);
                }
                let (tt, uu) = (&tris[t as usize], &tris[u as usize]);
                if distinct[t as usize] && distinct[u as usize] && shares_vertex(tt, uu) {
                    return; // around their shared vertex
                }
                if self.first_meeting(boxes_of, t, p, u, q) {
                    found.test_filtered(mesh, flats, t, u, limit);
                }
            },
            |a, b| a.merge(b, limit),
            // Empty nodes have no common vertex, so they are never pruned (nothing to skip).
            |x, y| shares_vertex(&labels[x], &labels[y]) || Slab::apart(&slabs[x], &slabs[y]),
        )
    }

    /// Every node's vertices common to all its triangles (sorted, `NONE` padding;
    /// all `NONE` when some triangle has a repeated index).
    fn common_vertices(&self, mesh: &Mesh, bvh: &Bvh, distinct: &[bool]) -> Vec<[u32; 3]> {
        let (tris, owner) = (&mesh.triangles, &self.owner);
        bvh.node_labels(
            |prims| {
                let first = owner[prims[0] as usize] as usize;
                let mut common = if distinct[first] {
                    tris[first]
                } else {
                    [NONE; 3]
                };
                for &p in &prims[1..] {
                    let p = owner[p as usize] as usize;
                    let t = &tris[p];
                    for c in common.iter_mut() {
                        if !distinct[p] || !t.contains(c) {
                            *c = NONE;
                        }
                    }
                }
                common.sort_unstable();
                common
            },
            |a, b| {
                let mut c = [NONE; 3];
                let mut n = 0;
                for x in a {
                    if *x != NONE && b.contains(x) {
                        c[n] = *x;
                        n += 1;
                    }
                }
                c
            },
            [NONE; 3],
        )
    }
}

/// True when the vertex lists `a` and `b` (with `NONE` padding) share a vertex.
fn shares_vertex(a: &[u32; 3], b: &[u32; 3]) -> bool {
    a.iter().any(|x| *x != NONE && b.contains(x))
}
