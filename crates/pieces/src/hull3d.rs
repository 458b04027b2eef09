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

/// Gift wrapping about the line through `a` along `d`: the point `p` of `pts` (off the
/// line, and off `skip_plane` when given) that turns the plane through the line
/// farthest in one fixed sense, `det(d, p - a, q - a) >= 0` for every other candidate
/// `q`. When all points lie within less than half a turn about the line, the plane
/// through the line and `p` is a supporting plane (the one at that end of the range).
/// `None` when no candidate is left.
fn wrap(pts: &[Vec3], a: &Vec3, d: &Vec3, skip_plane: Option<(&Vec3, &Int)>) -> Option<usize> {
    let off_line = |q: &Vec3| !d.cross(&q.sub(a)).is_zero();
    let on_skipped = |q: &Vec3| skip_plane.is_some_and(|(n, o)| n.dot(q) == *o);
    let mut best = pts.iter().position(|q| off_line(q) && !on_skipped(q))?;
    // q lies beyond the plane through the line and `best` when it turns the plane
    // further: det(d, best - a, q - a) = m · (q - a) < 0 with m = d × (best - a) (one
    // fixed sense of rotation). Points on the line give 0 and are never taken.
    let mut m = d.cross(&pts[best].sub(a));
    for (i, q) in pts.iter().enumerate() {
        if i != best && dot_sign(&m, &q.sub(a)) == Sign::Negative {
            best = i;
            m = d.cross(&q.sub(a));
        }
    }
    Some(best)
}

/// The supporting plane through `a`, `b` and `c` (not collinear) as a primitive
/// outward normal and offset, when no point lies strictly beyond it.
fn supporting(pts: &[Vec3], a: &Vec3, b: &Vec3, c: &Vec3) -> Option<(Vec3, Int)> {
    let n = b.sub(a).cross(&c.sub(a)).primitive();
    if n.is_zero() {
        return None;
    }
    let (mut above, mut below) = (false, false);
    for q in pts {
        match dot_sign(&n, &q.sub(a)) {
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
        (true, false) => n.neg(),
        _ => n,
    };
    let off = n.dot(a);
    Some((n, off))
}

/// A first facet plane of the hull of `pts` (sorted, at least 4 distinct points).
///
/// The lexicographically smallest point `a` is a vertex, and the plane `x = a.x`
/// supports the hull there; turning it about the vertical line through `a` gives a
/// second supporting plane. Its points are either a facet, or they lie on one line,
/// which is then an edge from `a`, and turning about that edge gives a facet. Both
/// turns stay within less than half a turn, where gift wrapping is exact.
fn first_facet(pts: &[Vec3]) -> Option<(Vec3, Int)> {
    let a = &pts[0];
    let up = Vec3::new(0, 0, 1);
    let p = wrap(pts, a, &up, None)?;
    let n = up.cross(&pts[p].sub(a));
    let on: Vec<&Vec3> = pts
        .iter()
        .filter(|q| n.dot(&q.sub(a)) == Int::ZERO)
        .collect();
    let far = on.iter().max_by_key(|q| q.sub(a).dot(&q.sub(a)))?;
    let d = far.sub(a);
    if let Some(c) = on.iter().find(|q| !d.cross(&q.sub(a)).is_zero()) {
        return supporting(pts, a, far, c);
    }
    // Collinear: the edge runs from `a` to the farthest point on the line.
    let c = wrap(pts, a, &d, None)?;
    supporting(pts, a, far, &pts[c])
}

impl Polytope {
    /// The convex hull of integer points (any number; exact), with facets as maximal
    /// coplanar polygons. `Err(Flat)` when the points span no volume.
    pub fn hull(points: &[Vec3]) -> Result<Polytope, PolytopeError> {
        let mut pts: Vec<Vec3> = points.to_vec();
        pts.sort_by_cached_key(|p| p.to_ints());
        pts.dedup();
        if pts.len() < 4 {
            return Err(PolytopeError::Flat);
        }
        let first = first_facet(&pts).ok_or(PolytopeError::Flat)?;
        let mut facets: Vec<(Vec3, Int, Vec<u32>)> = Vec::new();
        let mut seen: FxHashSet<(Vec3, Int)> = FxHashSet::default();
        let mut edges: FxHashSet<(u32, u32)> = FxHashSet::default();
        let mut queue = vec![first];
        while let Some((n, off)) = queue.pop() {
            if !seen.insert((n.clone(), off.clone())) {
                continue;
            }
            let on: Vec<u32> = (0..pts.len() as u32)
                .filter(|&i| n.dot(&pts[i as usize]) == off)
                .collect();
            let sub: Vec<Vec3> = on.iter().map(|&i| pts[i as usize].clone()).collect();
            let cycle: Vec<u32> = hull_in_plane(&n, &sub).into_iter().map(|i| on[i]).collect();
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
                let e = pv.sub(pu);
                // Turn the facet's plane about the edge, away from the facet: the
                // first candidate is off the facet's plane, and the sense of rotation
                // is whichever `wrap` uses; `supporting` checks the result exactly and
                // the other sense is tried when it is not the neighbour.
                let turn = |d: &Vec3| {
                    wrap(&pts, pu, d, Some((&n, &off)))
                        .and_then(|q| supporting(&pts, pu, pv, &pts[q]))
                        .filter(|(m, o)| !(m == &n && o == &off))
                };
                let next = turn(&e)
                    .or_else(|| turn(&e.neg()))
                    .ok_or(PolytopeError::Flat)?;
                queue.push(next);
            }
            facets.push((n, off, cycle));
        }
        Polytope::assemble(&pts, facets)
    }
}
