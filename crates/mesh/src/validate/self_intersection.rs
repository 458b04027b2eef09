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

use crate::intersect::{triangle_pair, Contact};
use crate::mesh::Mesh;
use apart_kernel::fvec;
use apart_kernel::orient;
use apart_kernel::Aabb;
use apart_kernel::Bvh;
use apart_kernel::Sign;
use rayon::prelude::*;

/// Intersecting pairs found so far: the smallest `limit` of them, their number, and
/// how many exact narrow-phase tests were run.
struct Found {
    kept: Vec<(u32, u32, Contact)>,
    count: usize,
    tests: usize,
}

impl Found {
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

    // Thin triangles (the slivers of a tessellated cap) are boxed in pieces: the box
    // phase then meets far fewer pairs. `owner[p]` is the triangle of box `p`; the boxes
    // of triangle `t` are `first[t]..first[t + 1]`.
    let flats: Vec<Flat> = tris
        .par_iter()
        .with_min_len(8192)
        .map(|t| Flat::of(mesh, t))
        .collect();
    // Certified planar faces leave the hierarchy: their triangles are never tested
    // against each other, and against the others through a hierarchy of their own.
    let groups = certified_groups(mesh, &distinct, &flats);
    let mut in_group = vec![NONE; tris.len()];
    for (g, face) in groups.iter().enumerate() {
        for &t in &face.triangles {
            in_group[t as usize] = g as u32;
        }
    }
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
    let (owner, first, own_bvh): (Vec<u32>, Vec<u32>, Option<Bvh>) = if chunked {
        let mut owner = Vec::new();
        let mut first = Vec::with_capacity(tris.len() + 1);
        let mut boxes = Vec::new();
        for (t, b) in pieces.into_iter().enumerate() {
            first.push(boxes.len() as u32);
            owner.extend(std::iter::repeat_n(t as u32, b.len()));
            boxes.extend(b);
        }
        first.push(boxes.len() as u32);
        (owner, first, Some(Bvh::new(boxes)))
    } else {
        let n = tris.len() as u32;
        ((0..n).collect(), (0..=n).collect(), None)
    };
    let bvh_of_triangles = bvh;
    let bvh = own_bvh.as_ref().unwrap_or(bvh);
    let boxes_of = bvh.boxes();
    // Every leaf's slab along the normal of its first triangle. Inner nodes get none:
    // theirs would rarely separate anything and would cost a test per pair of nodes
    // (a tenth of the validation of a million-triangle torus).
    let slabs = bvh.node_labels(
        |prims| Slab::of_triangles(mesh, prims.iter().map(|&p| owner[p as usize])),
        |_, _| Slab::NONE,
        Slab::NONE,
    );

    // Every node's vertices common to all its triangles (sorted, `NONE` padding;
    // all `NONE` when some triangle has a repeated index).
    let labels = bvh.node_labels(
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
    );
    let shares = |a: &[u32; 3], b: &[u32; 3]| a.iter().any(|x| *x != NONE && b.contains(x));
    // Whether boxes `p` of `t` and `q` of `u` are the first pair of their boxes that
    // meets (in index order), so that each triangle pair is tested once.
    let first_meeting = |t: u32, p: u32, u: u32, q: u32| -> bool {
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
    };
    let boxes = bvh.self_pairs_pruned(
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
            if distinct[t as usize] && distinct[u as usize] && shares(tt, uu) {
                return; // around their shared vertex
            }
            if first_meeting(t, p, u, q) {
                found.test_filtered(mesh, &flats, t, u, limit);
            }
        },
        |a, b| a.merge(b, limit),
        // Empty nodes have no common vertex, so they are never pruned (nothing to skip).
        |x, y| shares(&labels[x], &labels[y]) || Slab::apart(&slabs[x], &slabs[y]),
    );
    let faces = against_faces(
        mesh,
        bvh_of_triangles,
        &groups,
        &in_group,
        &distinct,
        &flats,
        limit,
    );
    let all = boxes.merge(around, limit).merge(faces, limit);
    let mut found = all.kept;
    found.sort_by_key(|&(t, u, _)| (t, u));
    (found, all.count, all.tests)
}

/// A bound on a node's triangles: their box, and the interval `[lo, hi]` of `u · x`
/// over their vertices for the unit normal `u` of the first of them (floating point).
/// Triangles that are nearly parallel and close together (the deep teeth of a star,
/// the flanks of a thread) have boxes that meet in quadratically many pairs, but thin
/// slabs: two nodes whose slabs are apart by more than the rounding error are skipped.
/// It is only a filter: a pair it cannot separate is left to the boxes and the exact
/// tests.
#[derive(Clone, Copy, Debug)]
struct Slab {
    u: [f64; 3],
    lo: f64,
    hi: f64,
    min: [f64; 3],
    max: [f64; 3],
    ok: bool,
}

impl Slab {
    const NONE: Slab = Slab {
        u: [0.0; 3],
        lo: 0.0,
        hi: 0.0,
        min: [0.0; 3],
        max: [0.0; 3],
        ok: false,
    };

    /// The slab of the triangles `ts` along the normal of the first one; none when
    /// one of them has no area (the exact test's answer on such a triangle is not a
    /// question of where it lies, so nothing is skipped for it).
    fn of_triangles(mesh: &Mesh, ts: impl Iterator<Item = u32> + Clone) -> Slab {
        let corners = |t: u32| mesh.corners(t as usize).map(|p| p.map(|c| c as f64));
        let flat = |t: u32| {
            let [a, b, c] = mesh.corners(t as usize);
            orient::normal(a, b, c) == [0; 3]
        };
        if ts.clone().any(flat) {
            return Slab::NONE;
        }
        let Some(u) = ts.clone().find_map(|t| {
            let [a, b, c] = corners(t);
            let n = fvec::cross(fvec::sub(b, a), fvec::sub(c, a));
            let len = fvec::norm(n);
            (len > 0.0 && len.is_finite()).then(|| n.map(|x| x / len))
        }) else {
            return Slab::NONE;
        };
        Slab::of_points(u, ts.flat_map(corners))
    }

    /// The slab of the polygon sides `ks` of `q` (in the plane `z = 0`) along the
    /// normal of the first one with a length.
    fn of_sides(q: &[[i64; 2]], ks: &[u32]) -> Slab {
        let ends = |k: u32| {
            let (a, b) = (q[k as usize], q[(k as usize + 1) % q.len()]);
            [a, b].map(|p| [p[0] as f64, p[1] as f64, 0.0])
        };
        let Some(u) = ks.iter().find_map(|&k| {
            let [a, b] = ends(k);
            let n = [a[1] - b[1], b[0] - a[0], 0.0];
            let len = fvec::norm(n);
            (len > 0.0 && len.is_finite()).then(|| n.map(|x| x / len))
        }) else {
            return Slab::NONE;
        };
        Slab::of_points(u, ks.iter().flat_map(|&k| ends(k)))
    }

    /// The slab of `points` along the unit vector `u`, with their box.
    fn of_points(u: [f64; 3], points: impl Iterator<Item = [f64; 3]>) -> Slab {
        let mut s = Slab {
            u,
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
            min: [f64::INFINITY; 3],
            max: [f64::NEG_INFINITY; 3],
            ok: true,
        };
        for p in points {
            let d = fvec::dot(u, p);
            s.lo = s.lo.min(d);
            s.hi = s.hi.max(d);
            s.min = [0, 1, 2].map(|k| s.min[k].min(p[k]));
            s.max = [0, 1, 2].map(|k| s.max[k].max(p[k]));
        }
        s
    }

    /// An interval holding `v · x` for every point `x` the slab bounds (in its box and
    /// its slab), `v` a unit vector: through the box alone, and through the slab with
    /// `v · x = w · x + (v − w) · x` for `w = ±u`; the tighter of the two ends.
    fn along(&self, v: &[f64; 3]) -> (f64, f64) {
        let c = [0, 1, 2].map(|k| 0.5 * (self.min[k] + self.max[k]));
        let e = [0, 1, 2].map(|k| 0.5 * (self.max[k] - self.min[k]));
        let spread = |w: &[f64; 3]| (0..3).map(|k| w[k].abs() * e[k]).sum::<f64>();
        let (bc, bs) = (fvec::dot(*v, c), spread(v));
        // The slab along `u` or `−u`, whichever is nearer `v` (the two sides of a thin
        // tooth face opposite ways).
        let (w, lo, hi) = match fvec::dot(*v, self.u) < 0.0 {
            false => (self.u, self.lo, self.hi),
            true => (self.u.map(|x| -x), -self.hi, -self.lo),
        };
        let d = fvec::sub(*v, w);
        let (dc, ds) = (fvec::dot(d, c), spread(&d));
        ((bc - bs).max(lo + dc - ds), (bc + bs).min(hi + dc + ds))
    }

    /// A bound on the rounding errors of the slab's sums: far above them (about 2^-52
    /// of the coordinates' magnitude per operation), far below any real gap.
    fn margin(&self) -> f64 {
        let m = (0..3)
            .map(|k| self.min[k].abs().max(self.max[k].abs()))
            .fold(0.0, f64::max);
        1e-9 * (1.0 + m)
    }

    /// The slab of two nodes: along `a`'s normal, covering `b` through [`Slab::along`].
    fn join(a: &Slab, b: &Slab) -> Slab {
        if !a.ok || !b.ok {
            return Slab::NONE;
        }
        let (lo, hi) = b.along(&a.u);
        Slab {
            u: a.u,
            lo: a.lo.min(lo),
            hi: a.hi.max(hi),
            min: [0, 1, 2].map(|k| a.min[k].min(b.min[k])),
            max: [0, 1, 2].map(|k| a.max[k].max(b.max[k])),
            ok: true,
        }
    }

    /// True when a plane along one of the two normals separates the nodes by more than
    /// the rounding margin (so no triangle of one meets a triangle of the other).
    fn apart(a: &Slab, b: &Slab) -> bool {
        if !a.ok || !b.ok {
            return false;
        }
        let m = a.margin().max(b.margin());
        let off = |s: &Slab, o: &Slab| {
            let (lo, hi) = o.along(&s.u);
            hi < s.lo - m || lo > s.hi + m
        };
        off(a, b) || off(b, a)
    }
}

/// Faces of at least this many triangles are tried for a planar certificate.
const CERTIFY_MIN: usize = 16;

/// A large planar face whose triangles are certified to cover it once ([`certified_groups`]).
struct Face {
    /// Its triangles.
    triangles: Vec<u32>,
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
fn certified_groups(mesh: &Mesh, distinct: &[bool], flats: &[Flat]) -> Vec<Face> {
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
fn against_faces(
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

/// True when the closed polygon `q` (distinct points, at least 3) is simple: sides meet
/// only at the vertex two consecutive sides share, and there they do not fold back.
/// Sides are paired through a hierarchy of their boxes; each meeting pair is decided by
/// exact orientation tests (points of sides whose boxes meet differ by less than 2^33,
/// so the products fit `i128`).
fn simple_polygon_2d(q: &[[i64; 2]]) -> bool {
    let n = q.len();
    if n < 3 {
        return false;
    }
    let side = |k: usize| (&q[k], &q[(k + 1) % n]);
    let boxes: Vec<Aabb> = (0..n)
        .map(|k| {
            let (a, b) = side(k);
            Aabb::of([&[a[0], a[1], 0], &[b[0], b[1], 0]])
        })
        .collect();
    if boxes
        .iter()
        .any(|b| (0..2).any(|k| b.max[k] - b.min[k] >= 1 << 31))
    {
        return false;
    }
    let bvh = Bvh::new(boxes);
    // Sides of deep thin teeth are nearly parallel: their boxes meet quadratically many
    // others, their slabs do not.
    let slabs = bvh.node_labels(|ks| Slab::of_sides(q, ks), Slab::join, Slab::NONE);
    let bad = bvh.self_pairs_pruned(
        || false,
        |bad, i, j| {
            if *bad {
                return;
            }
            let (i, j) = (i as usize, j as usize);
            let ((a, b), (c, d)) = (side(i), side(j));
            *bad = if (i + 1) % n == j || (j + 1) % n == i {
                // Consecutive: they share one vertex `m`; the others `x`, `y`.
                let (x, m, y) = if (i + 1) % n == j {
                    (a, b, d)
                } else {
                    (c, d, b)
                };
                let back = [0, 1].map(|k| (x[k] - m[k]) as i128 * (y[k] - m[k]) as i128);
                orient::orient2d(x, m, y) == Sign::Zero && back[0] + back[1] > 0
            } else {
                segments_meet(a, b, c, d)
            };
        },
        |x, y| x || y,
        |x, y| Slab::apart(&slabs[x], &slabs[y]),
    );
    !bad
}

/// True when the closed segments `ab` and `cd` share a point (exact).
fn segments_meet(a: &[i64; 2], b: &[i64; 2], c: &[i64; 2], d: &[i64; 2]) -> bool {
    let within = |p: &[i64; 2], q: &[i64; 2], r: &[i64; 2]| {
        (0..2).all(|k| r[k] >= p[k].min(q[k]) && r[k] <= p[k].max(q[k]))
    };
    let (o1, o2) = (orient::orient2d(a, b, c), orient::orient2d(a, b, d));
    let (o3, o4) = (orient::orient2d(c, d, a), orient::orient2d(c, d, b));
    if o1 != Sign::Zero && o2 != Sign::Zero && o3 != Sign::Zero && o4 != Sign::Zero {
        return o1 != o2 && o3 != o4;
    }
    (o1 == Sign::Zero && within(a, b, c))
        || (o2 == Sign::Zero && within(a, b, d))
        || (o3 == Sign::Zero && within(c, d, a))
        || (o4 == Sign::Zero && within(c, d, b))
}

/// A triangle's plane `n · (x − a) = 0`, `n = (b − a) × (c − a)`, kept when the edge
/// vectors fit in 31 bits (so `n` fits in `i64`) and `n ≠ 0`, with the triangle's
/// projection along the dominant axis of `n`: the box phase's exact filter
/// ([`apart_by_planes`]) then needs no cross product per pair.
#[derive(Clone, Copy)]
struct Flat {
    n: [i64; 3],
    axis: u8,
    /// The corners projected along `axis` (see `orient::project`).
    flat: [[i64; 2]; 3],
    ok: bool,
}

/// Edge vector components below this bound (2^31) keep `n` and the filter's sums exact.
const FLAT_BOUND: i64 = 1 << 31;

impl Flat {
    fn of(mesh: &Mesh, t: &[u32; 3]) -> Flat {
        let [a, b, c] = t.map(|v| mesh.vertices[v as usize]);
        let none = Flat {
            n: [0; 3],
            axis: 0,
            flat: [[0; 2]; 3],
            ok: false,
        };
        let (u, v) = (
            [0, 1, 2].map(|k| b[k] - a[k]),
            [0, 1, 2].map(|k| c[k] - a[k]),
        );
        if u.iter()
            .chain(&v)
            .any(|x| x.unsigned_abs() >= FLAT_BOUND as u64)
        {
            return none;
        }
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        if n == [0; 3] {
            return none;
        }
        let axis = orient::dominant_axis(&n.map(|x| x as i128));
        Flat {
            n,
            axis: axis as u8,
            flat: [a, b, c].map(|p| orient::project(&p, axis)),
            ok: true,
        }
    }

    /// Signs of `n · (p − a)` for the corners `p` of `other`, `a` being `corner`
    /// (exact: the triangles' boxes meet and both have edges below 2^31, so every
    /// `p − a` is below 2^32 and each sum below 2^97).
    #[inline]
    fn sides(&self, corner: &[i64; 3], other: [&[i64; 3]; 3]) -> [Sign; 3] {
        let n = self.n.map(|x| x as i128);
        other.map(|p| {
            let d = [0, 1, 2].map(|k| (p[k] - corner[k]) as i128);
            debug_assert!(d.iter().all(|x| x.unsigned_abs() <= 1 << 32));
            Sign::of_i128(n[0] * d[0] + n[1] * d[1] + n[2] * d[2])
        })
    }
}

/// True when triangles `t` and `u` (no shared vertex index, meeting boxes) are shown
/// disjoint by one lying strictly on one side of the other's plane, or, when coplanar,
/// by an edge line of one with the other strictly outside (exact; `false` means
/// undecided).
fn apart_by_planes(mesh: &Mesh, flats: &[Flat], t: u32, u: u32) -> bool {
    let (ft, fu) = (&flats[t as usize], &flats[u as usize]);
    if !ft.ok || !fu.ok {
        return false;
    }
    let corners = |x: u32| mesh.triangles[x as usize].map(|v| &mesh.vertices[v as usize]);
    let (ct, cu) = (corners(t), corners(u));
    let one_side = |s: [Sign; 3]| s[0] != Sign::Zero && s[0] == s[1] && s[1] == s[2];
    let su = ft.sides(ct[0], cu);
    if one_side(su) {
        return true;
    }
    if su != [Sign::Zero; 3] {
        return one_side(fu.sides(cu[0], ct));
    }
    // Coplanar, both non-degenerate: parallel normals have the same dominant axis.
    ft.axis == fu.axis && crate::intersect::coplanar_apart(&ft.flat, &fu.flat)
}

/// Slabs a thin triangle's box is cut into along its longest side.
const SLABS: usize = 4;
/// Coordinates below this bound (2^48) are interpolated in `f64` well within the
/// boxes' margin.
const SLAB_BOUND: f64 = (1u64 << 48) as f64;

/// The boxes covering triangle `t` (not degenerate): its own box (`bvh`'s), or, when
/// the triangle is thin across its box, the boxes of its parts in [`SLABS`] slabs along the box's
/// longest side (computed in floating point, grown by 2 units and cut to the whole
/// box: each still contains its part) when their areas add up to less than half of it.
fn piece_boxes(mesh: &Mesh, t: usize, bvh: &Bvh) -> Vec<Aabb> {
    let whole = bvh.boxes()[t];
    let ext = [0, 1, 2].map(|k| whole.max[k] - whole.min[k]);
    // Area across the two largest sides (flat boxes of flat caps have a zero side).
    let area = |e: [i64; 3]| {
        let mut e = e.map(|x| x as f64 + 1.0);
        e.sort_by(f64::total_cmp);
        e[1] * e[2]
    };
    let axis = (0..3).max_by_key(|&k| ext[k]).unwrap_or(0);
    let corners = mesh.corners(t).map(|c| c.map(|x| x as f64));
    if ext[axis] < 64 || corners.iter().flatten().any(|x| x.abs() >= SLAB_BOUND) {
        return vec![whole];
    }
    let (lo, w) = (whole.min[axis] as f64, ext[axis] as f64 / SLABS as f64);
    let mut out = Vec::with_capacity(SLABS);
    for i in 0..SLABS {
        let (s0, s1) = (lo + w * i as f64, lo + w * (i + 1) as f64);
        let mut b = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
        let mut add = |p: [f64; 3]| {
            for k in 0..3 {
                b[0][k] = b[0][k].min(p[k]);
                b[1][k] = b[1][k].max(p[k]);
            }
        };
        for (j, p) in corners.iter().enumerate() {
            if (s0..=s1).contains(&p[axis]) {
                add(*p);
            }
            let q = corners[(j + 1) % 3];
            for cut in [s0, s1] {
                let (dp, dq) = (p[axis] - cut, q[axis] - cut);
                if (dp < 0.0) != (dq < 0.0) {
                    let l = dp / (dp - dq);
                    add([0, 1, 2].map(|k| p[k] + l * (q[k] - p[k])));
                }
            }
        }
        if b[0][0] > b[1][0] {
            continue; // nothing of the triangle in this slab
        }
        let part = Aabb {
            min: [0, 1, 2].map(|k| (b[0][k].floor() as i64 - 2).max(whole.min[k])),
            max: [0, 1, 2].map(|k| (b[1][k].ceil() as i64 + 2).min(whole.max[k])),
        };
        out.push(part);
    }
    let parts: f64 = out
        .iter()
        .map(|b| area([0, 1, 2].map(|k| b.max[k] - b.min[k])))
        .sum();
    if out.is_empty() || 2.0 * parts >= area(ext) {
        return vec![whole];
    }
    out
}

/// No vertex (padding in a node's common vertices).
const NONE: u32 = u32::MAX;

/// Stars up to this size test all their pairs; larger ones filter by direction boxes.
const SMALL_STAR: usize = 24;

/// Pairs of triangles with distinct vertex indices sharing at least one vertex, each
/// found around its smallest shared vertex.
fn around_vertices(mesh: &Mesh, distinct: &[bool], limit: usize) -> Found {
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn mesh(vertices: Vec<[i64; 3]>, triangles: Vec<[u32; 3]>) -> Mesh {
        Mesh {
            source_faces: (0..triangles.len() as u32).collect(),
            source_vertices: (0..vertices.len() as u32).collect(),
            vertices,
            triangles,
        }
    }

    fn bvh(m: &Mesh) -> Bvh {
        Bvh::new(
            (0..m.triangles.len())
                .map(|t| Aabb::of(m.corners(t)))
                .collect(),
        )
    }

    /// The oracle, the former search without its hierarchy: every pair of triangles
    /// whose boxes meet, tested exactly, in order. (The box filter is part of the
    /// answer: on degenerate triangles `triangle_pair` may report pairs whose boxes
    /// are apart.)
    fn brute_force(m: &Mesh) -> Vec<(u32, u32, Contact)> {
        let n = m.triangles.len() as u32;
        let mut out = Vec::new();
        for t in 0..n {
            for u in t + 1..n {
                let (tt, uu) = (m.triangles[t as usize], m.triangles[u as usize]);
                let apart =
                    !Aabb::of(m.corners(t as usize)).overlaps(&Aabb::of(m.corners(u as usize)));
                if apart {
                    continue;
                }
                if let Some(c) = triangle_pair(&m.vertices, tt, uu) {
                    out.push((t, u, c));
                }
            }
        }
        out
    }

    /// Compares the broad phases with the oracle (all pairs, and the first few), and
    /// returns the number of exact tests.
    fn agrees(m: &Mesh) -> Result<usize, TestCaseError> {
        let want = brute_force(m);
        let b = bvh(m);
        let (got, count, tests) = self_intersections_counted(m, &b, usize::MAX);
        prop_assert_eq!(&got, &want);
        prop_assert_eq!(count, want.len());
        let (first, count) = self_intersections(m, &b, 3);
        prop_assert_eq!(&first[..], &want[..want.len().min(3)]);
        prop_assert_eq!(count, want.len());
        Ok(tests)
    }

    /// A fan of `n` triangles around vertex 0: the apex at the centre of a circle of
    /// radius `r` (or on it, like a tessellated cap fanned from one rim vertex), rim
    /// points rounded to the grid, lifted by `lift(k)` off the plane.
    fn fan(n: usize, r: f64, on_rim: bool, lift: impl Fn(usize) -> i64) -> Mesh {
        let mut v = vec![if on_rim { [r as i64, 0, 0] } else { [0, 0, 0] }];
        let ring = if on_rim { n + 2 } else { n };
        let first = usize::from(on_rim);
        for k in first..ring {
            let a = 2.0 * std::f64::consts::PI * k as f64 / ring as f64;
            v.push([
                (r * a.cos()).round() as i64,
                (r * a.sin()).round() as i64,
                lift(k),
            ]);
        }
        let rim = v.len() as u32 - 1;
        let mut t = Vec::new();
        for k in 1..=n as u32 {
            let next = if on_rim { k + 1 } else { k % rim + 1 };
            if next <= rim {
                t.push([0, k, next]);
            }
        }
        mesh(v, t)
    }

    /// A fan around the origin whose rim turns `turns` times (radius 1000 on the first
    /// turn, 1200 on the second), every triangle from input face 0.
    fn one_face_fan(rim: usize, turns: usize) -> Mesh {
        let mut v = vec![[0, 0, 0]];
        for k in 0..rim {
            let a = turns as f64 * std::f64::consts::TAU * k as f64 / rim as f64;
            let r = if k < rim / turns { 1000.0 } else { 1200.0 };
            v.push([
                (r * a.cos()).round() as i64,
                (r * a.sin()).round() as i64,
                0,
            ]);
        }
        let t: Vec<[u32; 3]> = (1..=rim as u32)
            .map(|k| [0, k, k % rim as u32 + 1])
            .collect();
        let mut m = mesh(v, t);
        m.source_faces.fill(0);
        m
    }

    #[test]
    fn a_planar_face_is_certified_only_when_its_triangles_cover_it_once() {
        let certified = |m: &Mesh| {
            let distinct = vec![true; m.triangles.len()];
            let flats: Vec<Flat> = m.triangles.iter().map(|t| Flat::of(m, t)).collect();
            certified_groups(m, &distinct, &flats).len()
        };
        // One turn: a 2-chain bounded by a simple polygon, certified, nothing crosses.
        let m = one_face_fan(32, 1);
        assert_eq!(certified(&m), 1);
        agrees(&m).unwrap();
        // Two turns: the same edge rules hold, but the rim crosses itself and the
        // triangles overlap; not certified, and every pair is found as by the oracle.
        let m = one_face_fan(32, 2);
        assert_eq!(certified(&m), 0);
        agrees(&m).unwrap();
        assert!(!brute_force(&m).is_empty());
        // A triangle flipped, or an edge used twice: not certified.
        let mut m = one_face_fan(32, 1);
        m.triangles[3].swap(1, 2);
        assert_eq!(certified(&m), 0);
        let mut m = one_face_fan(32, 1);
        m.triangles[5] = m.triangles[4];
        assert_eq!(certified(&m), 0);
    }

    #[test]
    fn a_star_cap_is_checked_in_near_linear_time() {
        // A prism over a non-convex star of 4000 sides: its caps' triangles span the
        // star (quadratically many meeting boxes); certified, they are not paired.
        let n = 4000usize;
        let mut v = Vec::new();
        for z in [0, 1000] {
            for k in 0..n {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                let r = if k % 2 == 0 { 1.0e6 } else { 0.7e6 };
                v.push([(r * a.cos()).round(), (r * a.sin()).round(), z as f64]);
            }
        }
        let mut faces: Vec<Vec<u32>> = vec![
            (0..n as u32).rev().collect(),
            (n as u32..2 * n as u32).collect(),
        ];
        for k in 0..n as u32 {
            let j = (k + 1) % n as u32;
            faces.push(vec![k, j, j + n as u32, k + n as u32]);
        }
        let raw = apart_formats::RawObject {
            name: None,
            vertices: v,
            faces: apart_formats::Polygons::from(faces),
        };
        let (m, problems) = Mesh::from_raw(&raw, &apart_kernel::Grid::unit(40));
        let m = m.unwrap();
        assert!(problems.is_empty(), "{problems:?}");
        let (found, count, tests) = self_intersections_counted(&m, &bvh(&m), 10);
        assert!(found.is_empty() && count == 0, "{found:?}");
        assert!(tests < 40 * n, "{tests} exact tests");
    }

    #[test]
    fn large_fans_need_few_exact_tests() {
        for on_rim in [false, true] {
            for lift in [0, 1] {
                let n = 3000;
                let m = fan(n, 1e6, on_rim, |k| lift * ((k as i64 * 7919) % 13));
                let (found, count, tests) = self_intersections_counted(&m, &bvh(&m), 10);
                assert!(found.is_empty() && count == 0, "{on_rim} {lift}: {found:?}");
                // n²/2 = 4.5 million pairs share the apex; a few per triangle are tested.
                assert!(tests < 20 * n, "{on_rim} {lift}: {tests} exact tests");
            }
        }
    }

    #[test]
    fn thin_triangles_are_boxed_in_pieces_and_still_found() {
        // The radial slivers of a fan are cut into slab boxes; triangles laid across the
        // fan in its plane and through it are found exactly as by the oracle.
        let mut m = fan(120, 5000.0, false, |_| 0);
        let b = bvh(&m);
        let cut = (0..m.triangles.len())
            .filter(|&t| piece_boxes(&m, t, &b).len() > 1)
            .count();
        assert!(cut > 60, "{cut} of 120 slivers cut");
        let nv = m.vertices.len() as u32;
        m.vertices.extend([
            [-4000, 300, 0],
            [4000, 700, 0],
            [0, 2500, -50],
            [0, 2400, 60],
        ]);
        m.triangles
            .extend([[nv, nv + 1, 7], [nv + 2, nv + 3, 40], [nv, nv + 3, 90]]);
        let found = agrees(&m).unwrap();
        assert!(found > 0);
        let (got, count, _) = self_intersections_counted(&m, &bvh(&m), usize::MAX);
        assert!(count > 0 && got.len() == count);
    }

    fn point(r: i64) -> impl Strategy<Value = [i64; 3]> {
        [-r..=r, -r..=r, -r..=r]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1000))]

        /// Fans (flat, or with a wavy rim), with triangles added across them: some
        /// in their plane, some through the apex, some on rim vertices.
        #[test]
        fn fans_with_crossing_triangles_match_the_oracle(
            n in 3usize..90,
            on_rim in any::<bool>(),
            wavy in 0i64..3,
            extra in prop::collection::vec(
                (0u32..1000, 0u32..1000, point(1200), any::<bool>(), 0u8..3), 0..6),
        ) {
            let mut m = fan(n, 1000.0, on_rim, |k| wavy * ((k as i64 * 31) % 5 - 2));
            let nv = m.vertices.len() as u32;
            for (a, b, mut p, flat, kind) in extra {
                if flat {
                    p[2] = 0;
                }
                m.vertices.push(p);
                let q = m.vertices.len() as u32 - 1;
                let (a, b) = (a % nv, b % nv);
                let tri = match kind {
                    0 => [0, a, q],         // through the apex
                    1 => [a, b, q],         // on two fan vertices
                    _ => [a, q, (a + 1) % nv], // on a rim edge
                };
                if tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2] {
                    m.triangles.push(tri);
                }
            }
            let tests = agrees(&m)?;
            let _ = tests;
        }

        /// Flat fans that are one input face (certified, out of the hierarchy), with a
        /// second fan-face standing across the first or not, and triangles added on
        /// their vertices, rim sides and planes: every pair as by the oracle.
        #[test]
        fn certified_faces_with_crossing_triangles_match_the_oracle(
            n in 16usize..60,
            on_rim in any::<bool>(),
            across in prop::option::of(-1200i64..1200),
            extra in prop::collection::vec(
                (0u32..1000, 0u32..1000, point(1200), 0u8..4, 0u8..3), 0..8),
        ) {
            let mut m = fan(n, 1000.0, on_rim, |_| 0);
            m.source_faces.fill(0);
            let nv = m.vertices.len() as u32;
            if let Some(y) = across {
                // The same fan stood up in the plane y = `y`.
                let base = m.vertices.len() as u32;
                let stood: Vec<[i64; 3]> =
                    m.vertices[..nv as usize].iter().map(|p| [p[0], y, p[1]]).collect();
                m.vertices.extend(stood);
                let tris: Vec<[u32; 3]> = m.triangles.iter().map(|t| t.map(|v| v + base)).collect();
                m.source_faces.extend(std::iter::repeat_n(1, tris.len()));
                m.triangles.extend(tris);
            }
            let all = m.vertices.len() as u32;
            for (k, (a, b, mut p, plane, kind)) in extra.into_iter().enumerate() {
                match plane {
                    0 => p[2] = 0,
                    1 => p[2] = p[2].signum(),
                    _ => {}
                }
                m.vertices.push(p);
                let q = m.vertices.len() as u32 - 1;
                let (a, b) = (a % all, b % all);
                let tri = match kind {
                    0 => [a, b, q],
                    1 => [a, q, (a + 1) % all],
                    _ => [0, a, q],
                };
                if tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2] {
                    m.triangles.push(tri);
                    m.source_faces.push(2 + k as u32);
                }
            }
            let distinct: Vec<bool> =
                m.triangles.iter().map(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]).collect();
            let flats: Vec<Flat> = m.triangles.iter().map(|t| Flat::of(&m, t)).collect();
            let faces = certified_groups(&m, &distinct, &flats).len();
            prop_assert_eq!(faces, 1 + usize::from(across.is_some()));
            agrees(&m)?;
        }

        /// Polygons on a small grid (touching, folding back, crossing, collinear), and
        /// thin stars: simplicity as decided by every pair of sides.
        #[test]
        fn simple_polygons_match_every_pair_of_sides(
            pts in prop::collection::vec([-4i64..=4, -4i64..=4], 3..12),
            star in prop::option::of((8usize..200, 0.05f64..0.95, any::<u8>())),
        ) {
            let q: Vec<[i64; 2]> = match star {
                None => pts,
                Some((n, inner, bend)) => {
                    let mut q: Vec<[i64; 2]> = (0..2 * n)
                        .map(|k| {
                            let a = std::f64::consts::PI * k as f64 / n as f64;
                            let r = if k % 2 == 0 { 1.0e6 } else { 1.0e6 * inner };
                            [(r * a.cos()).round() as i64, (r * a.sin()).round() as i64]
                        })
                        .collect();
                    // Sometimes pull a tip across its neighbours.
                    if bend % 3 == 0 {
                        let k = 2 * (bend as usize % n);
                        q[k] = [-q[k][0] / 2, -q[k][1] / 2];
                    }
                    q
                }
            };
            let n = q.len();
            let mut want = true;
            for i in 0..n {
                for j in i + 1..n {
                    let (a, b) = (&q[i], &q[(i + 1) % n]);
                    let (c, d) = (&q[j], &q[(j + 1) % n]);
                    let bad = if j == i + 1 || (i == 0 && j == n - 1) {
                        let (x, m, y) = if j == i + 1 { (a, b, d) } else { (c, d, b) };
                        let back = [0, 1].map(|k| (x[k] - m[k]) as i128 * (y[k] - m[k]) as i128);
                        orient::orient2d(x, m, y) == Sign::Zero && back[0] + back[1] > 0
                    } else {
                        segments_meet(a, b, c, d)
                    };
                    want &= !bad;
                }
            }
            prop_assert_eq!(simple_polygon_2d(&q), want);
        }

        /// Random triangles on a tiny grid: coplanar, collinear and coincident
        /// vertices, repeated indices, doubled faces, big stars.
        #[test]
        fn degenerate_meshes_match_the_oracle(
            verts in prop::collection::vec(point(2), 1..12),
            tris in prop::collection::vec([0u32..12, 0u32..12, 0u32..12], 0..70),
        ) {
            let nv = verts.len() as u32;
            // triangle_pair takes three distinct indices (meshes never repeat one).
            let tris = tris
                .into_iter()
                .map(|t| t.map(|x| x % nv))
                .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
                .collect();
            agrees(&mesh(verts, tris))?;
        }

        /// Big stars on a tiny grid around one vertex (the direction-box path).
        #[test]
        fn big_degenerate_stars_match_the_oracle(
            verts in prop::collection::vec(point(3), 2..40),
            tris in prop::collection::vec((0u32..40, 0u32..40), 25..80),
        ) {
            let nv = verts.len() as u32;
            let tris = tris
                .into_iter()
                .map(|(a, b)| [0, 1 + a % (nv - 1), b % nv])
                .filter(|t| t[2] != 0 && t[1] != t[2])
                .collect();
            agrees(&mesh(verts, tris))?;
        }
    }
}
