//! Exact convex hull of integer points in space, by gift wrapping over facets.
//!
//! Every facet is found as a supporting plane through a hull edge: the plane is turned
//! about the edge's line until no point lies beyond it (exact orientation tests), and
//! the facet is the 2-D hull of every point on that plane, so coplanar and collinear
//! points need no special case. Work is `O(n h)` for `n` points and `h` facet edges;
//! the shrink of a tolerance uses it to put pieces back on the grid.

use crate::hull2d::hull_in_plane;
use crate::polytope::{Polytope, PolytopeError};
use apart_kernel::predicates::dot_sign;
use apart_kernel::{Int, Sign, Vec3};
use rustc_hash::FxHashSet;
use std::hash::Hash;

/// The arithmetic of the gift wrapping: exact vectors (points, differences, normals)
/// and the scalars of their dot products.
trait Arith {
    /// A point, a difference or a normal.
    type V: Clone + Eq + Hash;
    /// A dot product (a plane's offset).
    type S: Clone + Eq + Hash;
    fn sub(a: &Self::V, b: &Self::V) -> Self::V;
    fn cross(a: &Self::V, b: &Self::V) -> Self::V;
    fn dot(a: &Self::V, b: &Self::V) -> Self::S;
    fn dot_sign(a: &Self::V, b: &Self::V) -> Sign;
    fn is_zero(a: &Self::V) -> bool;
    fn neg(a: &Self::V) -> Self::V;
    fn primitive(a: &Self::V) -> Self::V;
    fn up() -> Self::V;
    /// The squared length, for comparisons.
    fn norm2(a: &Self::V) -> Self::S;
    fn less(a: &Self::S, b: &Self::S) -> bool;
}

/// Any integers: the kernel's exact vectors.
struct Exact;

impl Arith for Exact {
    type V = Vec3;
    type S = Int;
    fn sub(a: &Vec3, b: &Vec3) -> Vec3 {
        a.sub(b)
    }
    fn cross(a: &Vec3, b: &Vec3) -> Vec3 {
        a.cross(b)
    }
    fn dot(a: &Vec3, b: &Vec3) -> Int {
        a.dot(b)
    }
    fn dot_sign(a: &Vec3, b: &Vec3) -> Sign {
        dot_sign(a, b)
    }
    fn is_zero(a: &Vec3) -> bool {
        a.is_zero()
    }
    fn neg(a: &Vec3) -> Vec3 {
        a.neg()
    }
    fn primitive(a: &Vec3) -> Vec3 {
        a.primitive()
    }
    fn up() -> Vec3 {
        Vec3::new(0, 0, 1)
    }
    fn norm2(a: &Vec3) -> Int {
        a.dot(a)
    }
    fn less(a: &Int, b: &Int) -> bool {
        a < b
    }
}

/// Points with coordinates below 2^40 in `i128`: differences below 2^41, cross products
/// of differences below 2^83, their dot products with differences or points below 2^125.
struct Small;

/// Coordinates of points [`Small`] takes are below this.
const SMALL: i64 = 1 << 40;

impl Arith for Small {
    type V = [i128; 3];
    type S = i128;
    fn sub(a: &[i128; 3], b: &[i128; 3]) -> [i128; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }
    fn cross(a: &[i128; 3], b: &[i128; 3]) -> [i128; 3] {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }
    fn dot(a: &[i128; 3], b: &[i128; 3]) -> i128 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }
    fn dot_sign(a: &[i128; 3], b: &[i128; 3]) -> Sign {
        match Self::dot(a, b).cmp(&0) {
            std::cmp::Ordering::Less => Sign::Negative,
            std::cmp::Ordering::Equal => Sign::Zero,
            std::cmp::Ordering::Greater => Sign::Positive,
        }
    }
    fn is_zero(a: &[i128; 3]) -> bool {
        *a == [0; 3]
    }
    fn neg(a: &[i128; 3]) -> [i128; 3] {
        a.map(|x| -x)
    }
    fn primitive(a: &[i128; 3]) -> [i128; 3] {
        let gcd = |mut x: u128, mut y: u128| {
            while y != 0 {
                (x, y) = (y, x % y);
            }
            x
        };
        let g = gcd(
            gcd(a[0].unsigned_abs(), a[1].unsigned_abs()),
            a[2].unsigned_abs(),
        );
        if g <= 1 {
            return *a;
        }
        a.map(|x| x / g as i128)
    }
    fn up() -> [i128; 3] {
        [0, 0, 1]
    }
    fn norm2(a: &[i128; 3]) -> i128 {
        Self::dot(a, a)
    }
    fn less(a: &i128, b: &i128) -> bool {
        a < b
    }
}

/// Gift wrapping about the line through `a` along `d`: the point `p` of `pts` (off the
/// line, and off `skip_plane` when given) that turns the plane through the line
/// farthest in one fixed sense, `det(d, p - a, q - a) >= 0` for every other candidate
/// `q`. When all points lie within less than half a turn about the line, the plane
/// through the line and `p` is a supporting plane (the one at that end of the range).
/// `None` when no candidate is left.
fn wrap<A: Arith>(
    pts: &[A::V],
    a: &A::V,
    d: &A::V,
    skip_plane: Option<(&A::V, &A::S)>,
) -> Option<usize> {
    let off_line = |q: &A::V| !A::is_zero(&A::cross(d, &A::sub(q, a)));
    let on_skipped = |q: &A::V| skip_plane.is_some_and(|(n, o)| A::dot(n, q) == *o);
    let mut best = pts.iter().position(|q| off_line(q) && !on_skipped(q))?;
    // q lies beyond the plane through the line and `best` when it turns the plane
    // further: det(d, best - a, q - a) = m · (q - a) < 0 with m = d × (best - a) (one
    // fixed sense of rotation). Points on the line give 0 and are never taken.
    let mut m = A::cross(d, &A::sub(&pts[best], a));
    for (i, q) in pts.iter().enumerate() {
        if i != best && A::dot_sign(&m, &A::sub(q, a)) == Sign::Negative {
            best = i;
            m = A::cross(d, &A::sub(q, a));
        }
    }
    Some(best)
}

/// The supporting plane through `a`, `b` and `c` (not collinear) as a primitive
/// outward normal and offset, when no point lies strictly beyond it.
fn supporting<A: Arith>(pts: &[A::V], a: &A::V, b: &A::V, c: &A::V) -> Option<(A::V, A::S)> {
    let n = A::primitive(&A::cross(&A::sub(b, a), &A::sub(c, a)));
    if A::is_zero(&n) {
        return None;
    }
    let (mut above, mut below) = (false, false);
    for q in pts {
        match A::dot_sign(&n, &A::sub(q, a)) {
            Sign::Positive => above = true,
            Sign::Negative => below = true,
            Sign::Zero => {}
        }
        if above && below {
            return None;
        }
    }
    let n = match (above, below) {
        (true, true) => return None,
        (true, false) => A::neg(&n),
        _ => n,
    };
    let off = A::dot(&n, a);
    Some((n, off))
}

/// A first facet plane of the hull of `pts` (sorted, at least 4 distinct points).
///
/// The lexicographically smallest point `a` is a vertex, and the plane `x = a.x`
/// supports the hull there; turning it about the vertical line through `a` gives a
/// second supporting plane. Its points are either a facet, or they lie on one line,
/// which is then an edge from `a`, and turning about that edge gives a facet. Both
/// turns stay within less than half a turn, where gift wrapping is exact.
fn first_facet<A: Arith>(pts: &[A::V]) -> Option<(A::V, A::S)> {
    let a = &pts[0];
    let up = A::up();
    let p = wrap::<A>(pts, a, &up, None)?;
    let n = A::cross(&up, &A::sub(&pts[p], a));
    let on: Vec<&A::V> = pts
        .iter()
        .filter(|q| A::dot_sign(&n, &A::sub(q, a)) == Sign::Zero)
        .collect();
    let mut far = *on.first()?;
    for q in &on {
        // The last of equally far points, as `max_by_key` would take.
        if !A::less(&A::norm2(&A::sub(q, a)), &A::norm2(&A::sub(far, a))) {
            far = q;
        }
    }
    let d = A::sub(far, a);
    if let Some(c) = on
        .iter()
        .find(|q| !A::is_zero(&A::cross(&d, &A::sub(q, a))))
    {
        return supporting::<A>(pts, a, far, c);
    }
    // Collinear: the edge runs from `a` to the farthest point on the line.
    let c = wrap::<A>(pts, a, &d, None)?;
    supporting::<A>(pts, a, far, &pts[c])
}

/// The facets of the hull of `pts` (sorted, distinct, at least 4; `all` the same points
/// as the kernel's vectors) as outward normals, offsets and vertex cycles.
#[allow(clippy::type_complexity)]
fn facets_of<A: Arith>(
    pts: &[A::V],
    all: &[Vec3],
    normal: impl Fn(&A::V) -> Vec3,
    offset: impl Fn(&A::S) -> Int,
) -> Result<Vec<(Vec3, Int, Vec<u32>)>, PolytopeError> {
    let first = first_facet::<A>(pts).ok_or(PolytopeError::Flat)?;
    let mut facets: Vec<(Vec3, Int, Vec<u32>)> = Vec::new();
    let mut seen: FxHashSet<(A::V, A::S)> = FxHashSet::default();
    let mut edges: FxHashSet<(u32, u32)> = FxHashSet::default();
    let mut queue = vec![first];
    while let Some((n, off)) = queue.pop() {
        if !seen.insert((n.clone(), off.clone())) {
            continue;
        }
        let on: Vec<u32> = (0..pts.len() as u32)
            .filter(|&i| A::dot(&n, &pts[i as usize]) == off)
            .collect();
        let sub: Vec<Vec3> = on.iter().map(|&i| all[i as usize].clone()).collect();
        let nv = normal(&n);
        let cycle: Vec<u32> = hull_in_plane(&nv, &sub)
            .into_iter()
            .map(|i| on[i])
            .collect();
        if cycle.len() < 3 {
            return Err(PolytopeError::Flat);
        }
        for k in 0..cycle.len() {
            let (u, v) = (cycle[k], cycle[(k + 1) % cycle.len()]);
            edges.insert((u, v));
            if edges.contains(&(v, u)) {
                continue; // the neighbour across this edge is known
            }
            let (pu, pv) = (&pts[u as usize], &pts[v as usize]);
            let e = A::sub(pv, pu);
            // Turn the facet's plane about the edge, away from the facet: the first
            // candidate is off the facet's plane, and the sense of rotation is whichever
            // `wrap` uses; `supporting` checks the result exactly and the other sense is
            // tried when it is not the neighbour.
            let turn = |d: &A::V| {
                wrap::<A>(pts, pu, d, Some((&n, &off)))
                    .and_then(|q| supporting::<A>(pts, pu, pv, &pts[q]))
                    .filter(|(m, o)| !(m == &n && o == &off))
            };
            let next = turn(&e)
                .or_else(|| turn(&A::neg(&e)))
                .ok_or(PolytopeError::Flat)?;
            queue.push(next);
        }
        facets.push((nv, offset(&off), cycle));
    }
    Ok(facets)
}

impl Polytope {
    /// The convex hull of integer points (any number; exact), with facets as maximal
    /// coplanar polygons. `Err(Flat)` when the points span no volume. Points below
    /// 2^40 take machine integers, others the kernel's exact vectors.
    pub fn hull(points: &[Vec3]) -> Result<Polytope, PolytopeError> {
        let mut pts: Vec<Vec3> = points.to_vec();
        pts.sort_by_cached_key(|p| p.to_ints());
        pts.dedup();
        if pts.len() < 4 {
            return Err(PolytopeError::Flat);
        }
        let small: Option<Vec<[i128; 3]>> = pts
            .iter()
            .map(|p| {
                p.as_small()
                    .filter(|c| c.iter().all(|x| x.abs() < SMALL))
                    .map(|c| c.map(i128::from))
            })
            .collect();
        let facets = match small {
            Some(sp) if sp.len() > INCREMENTAL_FROM => match incremental::facets(&sp, &pts) {
                Some(f) => f,
                None => facets_of::<Small>(&sp, &pts, |n| Vec3::from_i128(*n), |o| Int::from(*o))?,
            },
            Some(sp) => facets_of::<Small>(&sp, &pts, |n| Vec3::from_i128(*n), |o| Int::from(*o))?,
            None => facets_of::<Exact>(&pts, &pts, Vec3::clone, Int::clone)?,
        };
        Polytope::assemble(&pts, facets)
    }
}

/// Points from which [`Polytope::hull`] finds the facets by an incremental hull (in
/// machine integers) before ordering them as gift wrapping would: gift wrapping costs
/// `O(n h)`, two scans of every point per edge, which made the 8 large pieces of a
/// tessellated ring cost more to re-hull after the shrink than its 1,138 small ones.
const INCREMENTAL_FROM: usize = 40;

/// The facets of [`facets_of`] (the same list, in the same order, with the same
/// cycles) from an incremental convex hull with conflict lists (Quickhull's order:
/// the farthest point of a facet's outside set first), `O(n log n)` in practice: its
/// triangles grouped by plane give every facet and, across each edge, its neighbour,
/// so gift wrapping's walk is replayed without its scans. Exact in `i128`: points
/// below 2^40 have differences below 2^41 and orientations below 2^126.
///
/// Why a discarded point is never needed: a point strictly above a facet removed for
/// `p` and outside the new hull is strictly above one of the new facets (the segment
/// from it to a point just inside the removed facet leaves the new hull through a new
/// facet), so reassigning the removed facets' points to the new facets loses none; a
/// point above no new facet lies in the hull of the others, so it is no vertex.
mod incremental {
    use super::*;
    use rustc_hash::FxHashMap;

    type P = [i128; 3];

    fn sub(a: &P, b: &P) -> P {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }

    fn cross(a: &P, b: &P) -> P {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }

    fn dot(a: &P, b: &P) -> i128 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    struct Tri {
        v: [u32; 3],
        n: P,
        alive: bool,
        out: Vec<u32>,
    }

    /// Triangles, outward (counter-clockwise seen from outside), each directed edge
    /// owned by one live triangle.
    struct Hull<'a> {
        pts: &'a [P],
        tris: Vec<Tri>,
        edge: FxHashMap<(u32, u32), u32>,
    }

    impl Hull<'_> {
        /// `(b - a) × (c - a) · (p - a)`: positive when `p` is strictly above.
        fn height(&self, t: usize, p: u32) -> i128 {
            let tri = &self.tris[t];
            dot(
                &tri.n,
                &sub(&self.pts[p as usize], &self.pts[tri.v[0] as usize]),
            )
        }

        fn add(&mut self, v: [u32; 3]) -> u32 {
            let [a, b, c] = v.map(|i| self.pts[i as usize]);
            let id = self.tris.len() as u32;
            for k in 0..3 {
                self.edge.insert((v[k], v[(k + 1) % 3]), id);
            }
            self.tris.push(Tri {
                v,
                n: cross(&sub(&b, &a), &sub(&c, &a)),
                alive: true,
                out: Vec::new(),
            });
            id
        }

        /// Gives `q` to the first of `cands` it lies strictly above; `false` when none.
        fn assign(&mut self, q: u32, cands: &[u32]) -> bool {
            for &t in cands {
                if self.height(t as usize, q) > 0 {
                    self.tris[t as usize].out.push(q);
                    return true;
                }
            }
            false
        }
    }

    /// Four points spanning space, the first three not collinear, or `None`.
    fn simplex(pts: &[P]) -> Option<[u32; 4]> {
        let a = 0usize;
        let b = (1..pts.len()).find(|&i| pts[i] != pts[a])?;
        let ab = sub(&pts[b], &pts[a]);
        let c = (0..pts.len()).find(|&i| cross(&ab, &sub(&pts[i], &pts[a])) != [0; 3])?;
        let n = cross(&ab, &sub(&pts[c], &pts[a]));
        let d = (0..pts.len()).find(|&i| dot(&n, &sub(&pts[i], &pts[a])) != 0)?;
        Some([a, b, c, d].map(|i| i as u32))
    }

    /// The triangles of the hull of `pts` (distinct points), or `None` when flat.
    fn triangles(pts: &[P]) -> Option<Hull<'_>> {
        let [a, b, c, d] = simplex(pts)?;
        let mut h = Hull {
            pts,
            tris: Vec::new(),
            edge: FxHashMap::default(),
        };
        // Faces of the tetrahedron, each turned away from the opposite corner.
        let below = {
            let n = cross(
                &sub(&pts[b as usize], &pts[a as usize]),
                &sub(&pts[c as usize], &pts[a as usize]),
            );
            dot(&n, &sub(&pts[d as usize], &pts[a as usize])) < 0
        };
        let faces = if below {
            [[a, b, c], [a, d, b], [b, d, c], [c, d, a]]
        } else {
            [[a, c, b], [a, b, d], [b, c, d], [c, a, d]]
        };
        let first: Vec<u32> = faces.iter().map(|&f| h.add(f)).collect();
        for q in 0..pts.len() as u32 {
            if ![a, b, c, d].contains(&q) {
                h.assign(q, &first);
            }
        }
        let mut work: Vec<u32> = first;
        while let Some(t) = work.pop() {
            let t = t as usize;
            if !h.tris[t].alive || h.tris[t].out.is_empty() {
                continue;
            }
            // The farthest point of the outside set (heights are exact; any choice is
            // correct, the farthest keeps the hull small).
            let p = *h.tris[t]
                .out
                .iter()
                .max_by_key(|&&q| h.height(t, q))
                .expect("non-empty");
            // The facets p sees, from t across edges, and the horizon.
            let mut visible = vec![t as u32];
            let mut seen: FxHashMap<u32, bool> = FxHashMap::default();
            seen.insert(t as u32, true);
            let mut horizon: Vec<(u32, u32)> = Vec::new();
            let mut k = 0;
            while k < visible.len() {
                let x = visible[k] as usize;
                k += 1;
                let v = h.tris[x].v;
                for e in 0..3 {
                    let (u, w) = (v[e], v[(e + 1) % 3]);
                    let y = *h.edge.get(&(w, u))?;
                    let vis = match seen.get(&y) {
                        Some(&s) => s,
                        None => {
                            let s = h.height(y as usize, p) > 0;
                            seen.insert(y, s);
                            if s {
                                visible.push(y);
                            }
                            s
                        }
                    };
                    if !vis {
                        horizon.push((u, w));
                    }
                }
            }
            let mut orphans: Vec<u32> = Vec::new();
            for &x in &visible {
                let tri = &mut h.tris[x as usize];
                tri.alive = false;
                orphans.append(&mut tri.out);
                let v = tri.v;
                for e in 0..3 {
                    h.edge.remove(&(v[e], v[(e + 1) % 3]));
                }
            }
            let fresh: Vec<u32> = horizon.iter().map(|&(u, w)| h.add([u, w, p])).collect();
            for q in orphans {
                if q != p {
                    h.assign(q, &fresh);
                }
            }
            work.extend(fresh);
        }
        Some(h)
    }

    fn primitive(n: &P) -> P {
        let g = apart_kernel::int::gcd_u128(
            apart_kernel::int::gcd_u128(n[0].unsigned_abs(), n[1].unsigned_abs()),
            n[2].unsigned_abs(),
        );
        if g <= 1 {
            *n
        } else {
            n.map(|x| x / g as i128)
        }
    }

    /// See the module: `None` when the points are flat or a facet's edge is split by a
    /// point of the triangulation (then gift wrapping decides).
    pub(super) fn facets(pts: &[P], all: &[Vec3]) -> Option<Vec<(Vec3, Int, Vec<u32>)>> {
        let h = triangles(pts)?;
        // Facets: live triangles grouped by primitive plane.
        let mut plane_of: Vec<u32> = vec![u32::MAX; h.tris.len()];
        let mut ids: FxHashMap<(P, i128), u32> = FxHashMap::default();
        let mut verts: Vec<Vec<u32>> = Vec::new();
        for (t, tri) in h.tris.iter().enumerate() {
            if !tri.alive {
                continue;
            }
            let n = primitive(&tri.n);
            let key = (n, dot(&n, &pts[tri.v[0] as usize]));
            let id = *ids.entry(key).or_insert_with(|| {
                verts.push(Vec::new());
                verts.len() as u32 - 1
            });
            plane_of[t] = id;
            verts[id as usize].extend_from_slice(&tri.v);
        }
        for v in &mut verts {
            v.sort_unstable();
            v.dedup();
        }
        // Gift wrapping's walk, its neighbours read off the triangles.
        let first = first_facet::<Small>(pts)?;
        let mut out = Vec::new();
        let mut done: FxHashSet<(P, i128)> = FxHashSet::default();
        let mut edges: FxHashSet<(u32, u32)> = FxHashSet::default();
        let mut queue = vec![first];
        let mut star: Option<FxHashMap<u32, Vec<u32>>> = None;
        while let Some((n, off)) = queue.pop() {
            if !done.insert((n, off)) {
                continue;
            }
            let id = *ids.get(&(n, off))?;
            let on = &verts[id as usize];
            let sub_pts: Vec<Vec3> = on.iter().map(|&i| all[i as usize].clone()).collect();
            let nv = Vec3::from_i128(n);
            let cycle: Vec<u32> = hull_in_plane(&nv, &sub_pts)
                .into_iter()
                .map(|i| on[i])
                .collect();
            if cycle.len() < 3 {
                return None;
            }
            for k in 0..cycle.len() {
                let (u, v) = (cycle[k], cycle[(k + 1) % cycle.len()]);
                edges.insert((u, v));
                if edges.contains(&(v, u)) {
                    continue;
                }
                // The triangle on the other side of the edge, in the neighbour facet
                // (across its first piece when points of the edge split it).
                let t = match h.edge.get(&(v, u)) {
                    Some(&t) => t,
                    None => {
                        let star = star.get_or_insert_with(|| {
                            let mut m: FxHashMap<u32, Vec<u32>> = FxHashMap::default();
                            for &(a, b) in h.edge.keys() {
                                m.entry(a).or_default().push(b);
                            }
                            m
                        });
                        let (pu, pv) = (&pts[u as usize], &pts[v as usize]);
                        let d = sub(pv, pu);
                        let w = *star.get(&u)?.iter().find(|&&w| {
                            let e = sub(&pts[w as usize], pu);
                            cross(&e, &d) == [0; 3] && dot(&e, &d) > 0
                        })?;
                        *h.edge.get(&(w, u))?
                    }
                };
                let m = plane_of[t as usize];
                if m == id {
                    return None;
                }
                let tri = &h.tris[t as usize];
                let nn = primitive(&tri.n);
                queue.push((nn, dot(&nn, &pts[tri.v[0] as usize])));
            }
            out.push((nv, Int::from(off), cycle));
        }
        (out.len() == verts.len()).then_some(out)
    }

    #[cfg(test)]
    mod tests {
        use super::*;
        use proptest::prelude::*;

        /// The incremental facets against gift wrapping's (the same list, order and
        /// cycles), whenever the incremental path answers.
        fn same(raw: &[[i64; 3]]) -> Result<bool, TestCaseError> {
            let mut all: Vec<Vec3> = raw.iter().map(|p| Vec3::new(p[0], p[1], p[2])).collect();
            all.sort_by_cached_key(|p| p.to_ints());
            all.dedup();
            let sp: Vec<P> = all
                .iter()
                .map(|p| p.as_small().unwrap().map(i128::from))
                .collect();
            let fast = facets(&sp, &all);
            let slow = facets_of::<Small>(&sp, &all, |n| Vec3::from_i128(*n), |o| Int::from(*o));
            match (fast, slow) {
                (Some(f), Ok(s)) => {
                    prop_assert_eq!(f, s);
                    Ok(true)
                }
                (None, _) => Ok(false),
                (Some(_), Err(e)) => {
                    prop_assert!(false, "incremental hull where gift wrapping says {e:?}");
                    Ok(false)
                }
            }
        }

        proptest! {
            #![proptest_config(ProptestConfig::with_cases(300))]
            #[test]
            fn random_points(pts in prop::collection::vec(prop::array::uniform3(-1000i64..1000), 4..120)) {
                same(&pts)?;
            }

            /// Few values per coordinate: many coplanar and collinear points.
            #[test]
            fn lattice_points(pts in prop::collection::vec(prop::array::uniform3(0i64..4), 4..80)) {
                same(&pts)?;
            }

            /// Rounded points of a thin prism (as the shrink leaves a tessellated wall's
            /// piece) and of a sphere: nearly coplanar, many facets.
            #[test]
            fn rounded_prisms_and_spheres(n in 8usize..200, r in 10.0f64..1e6, h in 1i64..50, sphere in any::<bool>()) {
                let mut pts = Vec::new();
                for i in 0..n {
                    let a = i as f64 / n as f64 * std::f64::consts::TAU;
                    if sphere {
                        let b = (i as f64 * 0.618).fract() * std::f64::consts::PI;
                        pts.push([(r * a.cos() * b.sin()).round() as i64, (r * a.sin() * b.sin()).round() as i64, (r * b.cos()).round() as i64]);
                    } else {
                        for z in [0, h] {
                            pts.push([(r * a.cos()).round() as i64, (r * a.sin()).round() as i64, z]);
                        }
                    }
                }
                same(&pts)?;
            }
        }

        /// The incremental path answers on every one of these inputs, degenerate ones
        /// included (it is not skipped), with the same facets as gift wrapping.
        #[test]
        fn answers_on_most_inputs() {
            let mut g = apart_testkit::solids::Lcg(12345);
            let mut next = |m: i64| g.range(-m, m + 1);
            let (mut answered, mut total) = (0, 0);
            for case in 0..400 {
                let m = [3, 50, 1000, 1 << 30][case % 4];
                let n = 5 + case % 90;
                let pts: Vec<[i64; 3]> = (0..n).map(|_| [next(m), next(m), next(m)]).collect();
                total += 1;
                if same(&pts).unwrap() {
                    answered += 1;
                }
            }
            assert_eq!(answered, total);
        }

        /// The incremental path answers on typical inputs (it is not always skipped).
        #[test]
        fn answers_on_a_prism() {
            let mut pts = Vec::new();
            for i in 0..100 {
                let a = i as f64 / 100.0 * std::f64::consts::TAU;
                for z in [0, 7] {
                    pts.push([
                        (5000.0 * a.cos()).round() as i64,
                        (5000.0 * a.sin()).round() as i64,
                        z,
                    ]);
                }
            }
            assert!(same(&pts).unwrap());
        }
    }
}
