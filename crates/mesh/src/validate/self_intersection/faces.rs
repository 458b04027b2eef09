//! Certified planar faces: large input faces whose triangles provably cover a simple
//! polygon once, so that they need no test against each other, and the pairs of one of
//! their triangles with a triangle outside.

use super::planes::Flat;
use super::polygon::simple_polygon_2d;
use super::{Found, NONE};
use crate::mesh::Mesh;
use apart_kernel::orient;
use apart_kernel::Aabb;
use apart_kernel::Bvh;
use apart_kernel::Sign;
use rayon::prelude::*;

/// Faces of at least this many triangles are tried for a planar certificate.
const CERTIFY_MIN: usize = 16;

/// A large planar face whose triangles are certified to cover it once ([`certified_groups`]).
pub(super) struct Face {
    /// Its triangles.
    pub(super) triangles: Vec<u32>,
    /// Three corners spanning its plane.
    plane: [[i64; 3]; 3],
    /// Its boundary polygon's vertices, and its sides as `(min, max)` vertex pairs.
    rim_vertices: std::collections::HashSet<u32>,
    rim_sides: std::collections::HashSet<(u32, u32)>,
    /// The box of its triangles, and a hierarchy over their boxes (in `triangles` order).
    bvh: Bvh,
    bounds: Aabb,
}

impl Face {
    /// True when triangle `tri` (not of this face) meets no triangle of it beyond a
    /// vertex or an edge they share: it lies strictly on one side of the face's plane,
    /// or on one side touching the plane at a vertex of the boundary polygon or along a
    /// side of it. The face's triangles cover the polygon once and meet its boundary
    /// only at its vertices and sides (the certificate), so any other contact would be
    /// a point of the plane inside the polygon.
    fn clears(&self, mesh: &Mesh, tri: &[u32; 3]) -> bool {
        let [a, b, c] = &self.plane;
        let s = tri.map(|v| orient::orient3d(a, b, c, &mesh.vertices[v as usize]));
        if s.contains(&Sign::Positive) && s.contains(&Sign::Negative) {
            return false;
        }
        let on: Vec<u32> = (0..3)
            .filter(|&k| s[k] == Sign::Zero)
            .map(|k| tri[k])
            .collect();
        match on[..] {
            [] => true,
            [v] => self.rim_vertices.contains(&v),
            [v, w] => self.rim_sides.contains(&(v.min(w), v.max(w))),
            _ => false,
        }
    }
}

/// The input faces of at least [`CERTIFY_MIN`] triangles certified to have pairwise
/// disjoint interiors and to meet only at shared edges and vertices. The certificate,
/// exact and independent of how the face was split: the triangles are coplanar and turn
/// the same way, no directed edge is used twice, and the edges used in one direction
/// only form one simple closed polygon (each of its vertices has one edge in and one
/// out, one cycle, and no two of its sides meet beyond the vertex they share). The
/// triangles then form a 2-chain whose boundary is that polygon, so each point is
/// covered as often as the polygon winds around it: once inside, never twice. A large
/// non-convex cap (a star's) is thus not tested against itself, which would cost the
/// square of its triangles.
pub(super) fn certified_groups(mesh: &Mesh, distinct: &[bool], flats: &[Flat]) -> Vec<Face> {
    // Only faces of many triangles: counted first, so that a mesh of a million
    // single-triangle faces costs one pass and no map.
    let Some(&top) = mesh.source_faces.iter().max() else {
        return Vec::new();
    };
    let mut count = vec![0u32; top as usize + 1];
    for &f in &mesh.source_faces {
        count[f as usize] += 1;
    }
    let mut by_face: std::collections::HashMap<u32, Vec<u32>> = Default::default();
    for (t, &f) in mesh.source_faces.iter().enumerate() {
        if count[f as usize] as usize >= CERTIFY_MIN {
            by_face.entry(f).or_default().push(t as u32);
        }
    }
    let mut faces: Vec<(u32, Face)> = by_face
        .into_par_iter()
        .filter_map(|(f, ts)| {
            let cycle = certify_planar(mesh, &ts, distinct, flats)?;
            let n = cycle.len();
            let rim_sides = (0..n)
                .map(|k| {
                    let (v, w) = (cycle[k], cycle[(k + 1) % n]);
                    (v.min(w), v.max(w))
                })
                .collect();
            let boxes: Vec<Aabb> = ts
                .iter()
                .map(|&t| Aabb::of(mesh.corners(t as usize)))
                .collect();
            let bounds = boxes.iter().fold(Aabb::EMPTY, |b, x| b.union(x));
            Some((
                f,
                Face {
                    plane: mesh.corners(ts[0] as usize).map(|p| *p),
                    triangles: ts,
                    rim_vertices: cycle.into_iter().collect(),
                    rim_sides,
                    bvh: Bvh::new(boxes),
                    bounds,
                },
            ))
        })
        .collect();
    faces.sort_by_key(|(f, _)| *f);
    faces.into_iter().map(|(_, face)| face).collect()
}

/// The pairs of triangles with one in a certified face and the other outside it (in no
/// face, or in another one: each such pair once, from the face of smaller index),
/// whose boxes meet and which share no vertex (those are found around their vertices),
/// unless the face [clears](Face::clears) the other triangle.
pub(super) fn against_faces(
    mesh: &Mesh,
    bvh: &Bvh,
    faces: &[Face],
    in_group: &[u32],
    distinct: &[bool],
    flats: &[Flat],
    limit: usize,
) -> Found {
    if faces.is_empty() {
        return Found::new();
    }
    let tris = &mesh.triangles;
    let face_boxes = Bvh::new(faces.iter().map(|f| f.bounds).collect());
    (0..tris.len() as u32)
        .into_par_iter()
        .with_min_len(1024)
        .fold(Found::new, |mut found, t| {
            let b = bvh.boxes()[t as usize];
            let own = in_group[t as usize];
            face_boxes.query(&b, |g| {
                if own != NONE && g <= own {
                    return;
                }
                let face = &faces[g as usize];
                if face.clears(mesh, &tris[t as usize]) {
                    return;
                }
                face.bvh.query(&b, |k| {
                    let s = face.triangles[k as usize];
                    let (lo, hi) = (t.min(s), t.max(s));
                    let (a, c) = (&tris[lo as usize], &tris[hi as usize]);
                    let shared = distinct[lo as usize]
                        && distinct[hi as usize]
                        && a.iter().any(|v| c.contains(v));
                    if !shared {
                        found.test_filtered(mesh, flats, lo, hi, limit);
                    }
                });
            });
            found
        })
        .reduce(Found::new, |a, b| a.merge(b, limit))
}

/// The certificate of [`certified_groups`] for the triangles `ts`: their boundary
/// polygon's vertices in order, or `None`.
fn certify_planar(mesh: &Mesh, ts: &[u32], distinct: &[bool], flats: &[Flat]) -> Option<Vec<u32>> {
    if ts
        .iter()
        .any(|&t| !distinct[t as usize] || !flats[t as usize].ok)
    {
        return None;
    }
    let first = &flats[ts[0] as usize];
    let [a, b, c] = mesh.corners(ts[0] as usize).map(|p| *p);
    let axis = first.axis as usize;
    let turn = orient::orient2d(&first.flat[0], &first.flat[1], &first.flat[2]);
    let mut edges = std::collections::HashSet::with_capacity(3 * ts.len());
    for &t in ts {
        let tri = mesh.triangles[t as usize];
        let corners = mesh.corners(t as usize);
        if corners
            .iter()
            .any(|p| orient::orient3d(&a, &b, &c, p) != Sign::Zero)
        {
            return None;
        }
        let q = corners.map(|p| orient::project(p, axis));
        if orient::orient2d(&q[0], &q[1], &q[2]) != turn {
            return None;
        }
        for k in 0..3 {
            if !edges.insert((tri[k], tri[(k + 1) % 3])) {
                return None;
            }
        }
    }
    // The edges used in one direction only, as `next[from] = to`.
    let mut next: std::collections::HashMap<u32, u32> = Default::default();
    for &(u, v) in &edges {
        if !edges.contains(&(v, u)) && next.insert(u, v).is_some() {
            return None;
        }
    }
    let (&start, _) = next.iter().min()?;
    let mut cycle = vec![start];
    let mut at = start;
    while let Some(&v) = next.get(&at) {
        if v == start {
            break;
        }
        if cycle.len() > next.len() {
            return None;
        }
        cycle.push(v);
        at = v;
    }
    if next.get(&at) != Some(&start) || cycle.len() != next.len() {
        return None;
    }
    let q: Vec<[i64; 2]> = cycle
        .iter()
        .map(|&v| orient::project(&mesh.vertices[v as usize], axis))
        .collect();
    simple_polygon_2d(&q).then_some(cycle)
}
