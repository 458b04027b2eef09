//! Pairs of triangles sharing a vertex, found around that vertex: only triangles whose
//! corner cones at the vertex may share a direction (their direction boxes meet) are
//! tested exactly.

use super::Found;
use crate::mesh::Mesh;
use apart_kernel::fvec;
use apart_kernel::Aabb;
use apart_kernel::Bvh;
use rayon::prelude::*;

/// Stars up to this size test all their pairs; larger ones filter by direction boxes.
const SMALL_STAR: usize = 24;

/// Pairs of triangles with distinct vertex indices sharing at least one vertex, each
/// found around its smallest shared vertex.
pub(super) fn around_vertices(mesh: &Mesh, distinct: &[bool], limit: usize) -> Found {
    let nv = mesh.vertices.len();
    let mut start = vec![0u32; nv + 1];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if distinct[t] {
            for &v in tri {
                start[v as usize + 1] += 1;
            }
        }
    }
    for v in 0..nv {
        start[v + 1] += start[v];
    }
    let mut star = vec![0u32; start[nv] as usize];
    let mut next = start.clone();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if distinct[t] {
            for &v in tri {
                star[next[v as usize] as usize] = t as u32;
                next[v as usize] += 1;
            }
        }
    }
    (0..nv)
        .into_par_iter()
        .with_min_len(256)
        .fold(Found::new, |mut found, v| {
            let s = &star[start[v] as usize..start[v + 1] as usize];
            star_pairs(mesh, v as u32, s, &mut found, limit);
            found
        })
        .reduce(Found::new, |a, b| a.merge(b, limit))
}

/// The pairs of the star `s` (triangles around vertex `v`) whose smallest shared
/// vertex is `v` and whose corner cones at `v` may share a direction.
fn star_pairs(mesh: &Mesh, v: u32, s: &[u32], found: &mut Found, limit: usize) {
    let tris = &mesh.triangles;
    let visit = |found: &mut Found, t: u32, u: u32| {
        let (t, u) = (t.min(u), t.max(u));
        let uu = &tris[u as usize];
        let first = tris[t as usize]
            .iter()
            .filter(|x| uu.contains(x))
            .min()
            .copied();
        if first == Some(v) {
            found.test(mesh, t, u, limit);
        }
    };
    if s.len() <= SMALL_STAR {
        for (i, &t) in s.iter().enumerate() {
            for &u in &s[i + 1..] {
                visit(found, t, u);
            }
        }
        return;
    }
    let boxes: Vec<Aabb> = s.iter().map(|&t| direction_box(mesh, v, t)).collect();
    let local = Bvh::new(boxes);
    let more = local.self_pairs(
        Found::new,
        |found, i, j| visit(found, s[i as usize], s[j as usize]),
        |a, b| a.merge(b, limit),
    );
    *found = std::mem::replace(found, Found::new()).merge(more, limit);
}

/// Fixed-point scale of direction boxes (directions are at most 1 / `MIN_HALF` long).
const DIR_SCALE: f64 = (1u64 << 40) as f64;
/// Below this cosine of half the corner angle, a corner gets the box of all directions.
const MIN_HALF: f64 = 1e-3;
/// Margin added around direction boxes, far beyond their rounding error (about
/// `1e-15 / MIN_HALF²`).
const DIR_PAD: f64 = 1e-7;

/// A box (in directions scaled by [`DIR_SCALE`]) containing every unit vector `(p − v)
/// / |p − v|` for `p ≠ v` in triangle `t`, which has `v` as a vertex.
///
/// With `a`, `b` the unit vectors along the triangle's edges from `v`, the corner's
/// directions form the shorter arc between them, which lies in the trapezoid between
/// the chord `a b` and the chord scaled by `1 / m`, `m = |a + b| / 2` (the cosine of
/// half the angle): the scaled chord touches the unit sphere at the arc's midpoint.
/// Degenerate corners (an edge of length zero, collinear vertices) and corners close
/// to a straight angle get the box of all directions.
fn direction_box(mesh: &Mesh, v: u32, t: u32) -> Aabb {
    let all = Aabb {
        min: [-2 * DIR_SCALE as i64; 3],
        max: [2 * DIR_SCALE as i64; 3],
    };
    let p = |x: u32| &mesh.vertices[x as usize];
    let o = p(v);
    let tri = mesh.triangles[t as usize];
    let others: Vec<u32> = tri.iter().copied().filter(|&x| x != v).collect();
    let (b, c) = (p(others[0]), p(others[1]));
    if apart_kernel::orient::collinear(o, b, c) {
        return all; // also when b or c coincides with v
    }
    let unit = |q: &[i64; 3]| {
        let d = [0, 1, 2].map(|k| (q[k] as i128 - o[k] as i128) as f64);
        let len = fvec::norm(d);
        d.map(|x| x / len)
    };
    let (ub, uc) = (unit(b), unit(c));
    let s = [0, 1, 2].map(|k| ub[k] + uc[k]);
    let m = fvec::norm(s) / 2.0;
    if m.is_nan() || m < MIN_HALF {
        return all;
    }
    let mut bx = Aabb::EMPTY;
    for k in 0..3 {
        let xs = [ub[k], uc[k], ub[k] / m, uc[k] / m];
        let lo = xs.iter().copied().fold(f64::INFINITY, f64::min) - DIR_PAD;
        let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max) + DIR_PAD;
        bx.min[k] = (lo * DIR_SCALE).floor() as i64;
        bx.max[k] = (hi * DIR_SCALE).ceil() as i64;
    }
    bx
}
