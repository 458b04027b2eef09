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
            Some(sp) => facets_of::<Small>(&sp, &pts, |n| Vec3::from_i128(*n), |o| Int::from(*o))?,
            None => facets_of::<Exact>(&pts, &pts, Vec3::clone, Int::clone)?,
        };
        Polytope::assemble(&pts, facets)
    }
}
