//! How every edge is used: by one triangle (open boundary), by two with opposite
//! directions (manifold), by two with the same direction (inconsistent orientation), by
//! 2k >= 4 triangles alternating in direction around it (a solid touching itself along
//! the edge: valid), or otherwise (non-manifold).
//!
//! Half-edges `a → b` are bucketed by their start vertex (a counting sort) and each
//! bucket is sorted by end vertex, so both directions of an edge are found by binary
//! search; vertices are processed in parallel.

use crate::mesh::Mesh;
use apart_kernel::orient::orient3d;
use apart_kernel::predicates::{det3_sign, dot_sign};
use apart_kernel::{Sign, Vec3};
use rayon::prelude::*;
use std::cmp::Ordering;

/// Half-edges bucketed by start vertex, each bucket sorted by end vertex.
pub(crate) struct HalfEdges {
    offsets: Vec<usize>,
    /// `end << 32 | triangle`.
    entries: Vec<u64>,
}

impl HalfEdges {
    pub(crate) fn new(mesh: &Mesh) -> HalfEdges {
        let nv = mesh.vertices.len();
        let mut offsets = vec![0usize; nv + 1];
        for t in &mesh.triangles {
            for &v in t {
                offsets[v as usize + 1] += 1;
            }
        }
        for i in 0..nv {
            offsets[i + 1] += offsets[i];
        }
        let mut cursor = offsets.clone();
        let mut entries = vec![0u64; 3 * mesh.triangles.len()];
        for (ti, t) in mesh.triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k] as usize, t[(k + 1) % 3]);
                entries[cursor[a]] = (b as u64) << 32 | ti as u64;
                cursor[a] += 1;
            }
        }
        let mut buckets: Vec<&mut [u64]> = Vec::with_capacity(nv);
        let mut rest: &mut [u64] = &mut entries;
        for i in 0..nv {
            let (head, tail) = rest.split_at_mut(offsets[i + 1] - offsets[i]);
            buckets.push(head);
            rest = tail;
        }
        buckets
            .par_iter_mut()
            .with_min_len(4096)
            .for_each(|b| b.sort_unstable());
        HalfEdges { offsets, entries }
    }

    /// The half-edges leaving `a`, as `end << 32 | triangle`, sorted.
    pub(crate) fn from(&self, a: u32) -> &[u64] {
        &self.entries[self.offsets[a as usize]..self.offsets[a as usize + 1]]
    }

    /// The triangles of the half-edges `a → b`.
    pub(crate) fn between(&self, a: u32, b: u32) -> &[u64] {
        let s = self.from(a);
        let lo = s.partition_point(|&e| (e >> 32) < b as u64);
        let hi = s.partition_point(|&e| (e >> 32) <= b as u64);
        &s[lo..hi]
    }
}

/// The vertex of triangle `t` other than `a` and `b`.
#[inline]
pub(crate) fn third(t: &[u32; 3], a: u32, b: u32) -> u32 {
    (t[0] as u64 + t[1] as u64 + t[2] as u64 - a as u64 - b as u64) as u32
}

/// The classified edges of a mesh (edges as `(a, b)` with `a < b`).
#[derive(Default)]
pub(crate) struct EdgeUse {
    pub boundary: Vec<(u32, u32)>,
    /// Edge and the two triangles running along it in the same direction.
    pub inconsistent: Vec<(u32, u32, u32, u32)>,
    /// Edge and number of triangles.
    pub nonmanifold: Vec<(u32, u32, usize)>,
    /// Edge and number of triangles (alternating: valid).
    pub touching: Vec<(u32, u32, usize)>,
    /// Triangle pairs across manifold edges.
    pub pairs: Vec<(u32, u32)>,
    /// Manifold edges whose dihedral angle inside the solid exceeds 180 degrees (as
    /// oriented now).
    pub reflex: usize,
    /// Manifold edges whose dihedral angle is below 180 degrees (reflex once flipped).
    pub convex: usize,
}

impl EdgeUse {
    fn merge(mut self, o: EdgeUse) -> EdgeUse {
        self.boundary.extend(o.boundary);
        self.inconsistent.extend(o.inconsistent);
        self.nonmanifold.extend(o.nonmanifold);
        self.touching.extend(o.touching);
        self.pairs.extend(o.pairs);
        self.reflex += o.reflex;
        self.convex += o.convex;
        self
    }

    /// True when every edge is manifold or a valid touching edge.
    pub fn closed(&self) -> bool {
        self.boundary.is_empty() && self.inconsistent.is_empty() && self.nonmanifold.is_empty()
    }
}

/// Classifies every edge.
pub(crate) fn classify(mesh: &Mesh, he: &HalfEdges) -> EdgeUse {
    let nv = mesh.vertices.len() as u32;
    let mut out = (0..nv)
        .into_par_iter()
        .with_min_len(2048)
        .fold(EdgeUse::default, |mut acc, a| {
            let bucket = he.from(a);
            let mut i = 0;
            while i < bucket.len() {
                let b = (bucket[i] >> 32) as u32;
                let mut j = i + 1;
                while j < bucket.len() && (bucket[j] >> 32) as u32 == b {
                    j += 1;
                }
                let fwd = &bucket[i..j];
                i = j;
                let back = he.between(b, a);
                if a > b && !back.is_empty() {
                    continue; // handled from b
                }
                // Orient the record as (lo, hi) with its forward and backward uses.
                let (lo, hi, f, g) = if a < b {
                    (a, b, fwd, back)
                } else {
                    (b, a, back, fwd)
                };
                classify_edge(mesh, &mut acc, lo, hi, f, g);
            }
            acc
        })
        .reduce(EdgeUse::default, EdgeUse::merge);
    out.boundary.sort_unstable();
    out.inconsistent.sort_unstable();
    out.nonmanifold.sort_unstable();
    out.touching.sort_unstable();
    out
}

fn classify_edge(mesh: &Mesh, acc: &mut EdgeUse, a: u32, b: u32, f: &[u64], g: &[u64]) {
    let tri = |e: u64| e as u32;
    match (f.len(), g.len()) {
        (1, 0) | (0, 1) => acc.boundary.push((a, b)),
        (1, 1) => {
            let (t1, t2) = (tri(f[0]), tri(g[0]));
            acc.pairs.push((t1, t2));
            // t1 runs a → b: its corners in order are (a, b, c).
            let c = third(&mesh.triangles[t1 as usize], a, b);
            let d = third(&mesh.triangles[t2 as usize], a, b);
            let v = |i: u32| &mesh.vertices[i as usize];
            match orient3d(v(a), v(b), v(c), v(d)) {
                Sign::Positive => acc.reflex += 1,
                Sign::Negative => acc.convex += 1,
                Sign::Zero => {}
            }
        }
        (2, 0) => acc.inconsistent.push((a, b, tri(f[0]), tri(f[1]))),
        (0, 2) => acc.inconsistent.push((a, b, tri(g[0]), tri(g[1]))),
        (x, y) if x == y && alternating(mesh, a, b, f, g) => acc.touching.push((a, b, x + y)),
        (x, y) => acc.nonmanifold.push((a, b, x + y)),
    }
}

/// True when the triangles around edge `a b`, in angular order about it, alternate
/// between running `a → b` (`f`) and `b → a` (`g`): the wedges between them are then
/// alternately inside and outside the solid.
fn alternating(mesh: &Mesh, a: u32, b: u32, f: &[u64], g: &[u64]) -> bool {
    let p = |i: u32| Vec3::from_i64(mesh.vertices[i as usize]);
    let (pa, pb) = (p(a), p(b));
    let u = pb.sub(&pa);
    let mut around: Vec<(Vec3, bool)> = f
        .iter()
        .map(|&e| (e, true))
        .chain(g.iter().map(|&e| (e, false)))
        .map(|(e, dir)| {
            (
                p(third(&mesh.triangles[e as u32 as usize], a, b)).sub(&pa),
                dir,
            )
        })
        .collect();
    let r0 = around[0].0.clone();
    let n0 = u.cross(&r0);
    // Angle class about u measured from r0: 0 at r0, 1 in (0, π), 2 at π, 3 in (π, 2π).
    let class = |r: &Vec3| match det3_sign(&u, &r0, r) {
        Sign::Positive => 1,
        Sign::Negative => 3,
        Sign::Zero => {
            if dot_sign(&n0, &u.cross(r)) == Sign::Positive {
                0
            } else {
                2
            }
        }
    };
    around.sort_by(|(r1, _), (r2, _)| {
        let (c1, c2) = (class(r1), class(r2));
        c1.cmp(&c2).then_with(|| match det3_sign(&u, r1, r2) {
            Sign::Positive => Ordering::Less,
            Sign::Negative => Ordering::Greater,
            Sign::Zero => Ordering::Equal,
        })
    });
    let n = around.len();
    (0..n).all(|i| around[i].1 != around[(i + 1) % n].1)
}
