//! Prisms: solids that are one polygon (with holes) extruded straight, such as washers,
//! tubes, plates with holes and most sheet parts, decomposed in the plane of their cap.
//!
//! A closed solid is a right prism along a primitive integer normal `n` when every vertex
//! lies on one of two planes `n · x = c0 < c1` and every triangle either lies in one of
//! them or has a normal perpendicular to `n`. Then the solid is `Q × [c0, c1]` along `n`:
//! a line parallel to `n` can only enter or leave the solid through a face not parallel
//! to it, so with `c0 < n · x < c1` the whole chord of the line between the two planes is
//! inside; and the triangles on the upper plane tile `Q` (the surface is closed and does
//! not cross itself).
//!
//! The pieces are those triangles merged greedily across shared edges while the union
//! stays convex (Hertel and Mehlhorn's method), each extruded back to a prism. Every
//! decision is an exact orientation of integer points in the cap's plane. The pieces'
//! vertices are the cap's own vertices and their images on the lower plane, which are
//! grid points whenever `(c1 - c0) n / (n · n)` is an integer vector (always along a
//! coordinate axis); otherwise, or when the solid is not such a prism, the general
//! partition runs instead. A partition of a prism may cut it anywhere, with pieces of
//! large denominators; these pieces are as short as the input.

use crate::solid::Solid;
use apart_kernel::orient::{dominant_axis, orient2d, project};
use apart_kernel::{Sign, Vec3};
use apart_pieces::Polytope;
use rustc_hash::FxHashMap;

/// Solids of fewer triangles are left to the partition: it takes a millisecond there, and
/// its planes through several reflex edges may leave fewer pieces.
pub(crate) const MIN_TRIANGLES: usize = 256;

/// The convex pieces of `solid` when it is a right prism whose lower cap is on the grid
/// (see the module documentation) of at least [`MIN_TRIANGLES`] triangles, with the
/// number of merges made; `None` otherwise.
pub(crate) fn pieces(solid: &Solid) -> Option<(Vec<Polytope>, usize)> {
    if solid.tris.len() < MIN_TRIANGLES {
        return None;
    }
    let (axis, top, shift) = shape(solid)?;
    let (polys, merges) = merge_cap(solid, &top, axis)?;
    let mut out = Vec::with_capacity(polys.len());
    for poly in polys {
        let mut pts: Vec<Vec3> = Vec::with_capacity(2 * poly.len());
        for &v in &poly {
            let p = solid.pts[v as usize];
            pts.push(Vec3::from_i64(p));
            pts.push(Vec3::from_i64([0, 1, 2].map(|k| p[k] - shift[k])));
        }
        out.push(Polytope::hull(&pts).ok()?);
    }
    // A safety net against a surface that is not what the validation promised: the
    // pieces' volumes add up to the solid's.
    let total = out
        .iter()
        .fold(apart_kernel::Int::ZERO, |s, p| s + p.volume6());
    (total == solid.volume6).then_some((out, merges))
}

/// The prism's normal (as a primitive vector), its upper cap's triangles and the integer
/// vector from the upper plane to the lower one, when the solid is such a prism.
fn shape(solid: &Solid) -> Option<([i128; 3], Vec<u32>, [i64; 3])> {
    // The normal is shared by the cap triangles: the most frequent triangle normals
    // (up to sign) are tried, a few of them (a plate's walls share normals too).
    let mut freq: FxHashMap<[i128; 3], usize> = FxHashMap::default();
    for plane in &solid.planes {
        *freq.entry(plane.unoriented().n).or_default() += 1;
    }
    let mut common: Vec<([i128; 3], usize)> = freq.into_iter().collect();
    common.sort_unstable_by(|x, y| y.1.cmp(&x.1).then_with(|| x.0.cmp(&y.0)));
    common.iter().take(3).find_map(|(n, _)| along(solid, n))
}

/// [`shape`] along the primitive normal `n`.
fn along(solid: &Solid, n: &[i128; 3]) -> Option<([i128; 3], Vec<u32>, [i64; 3])> {
    let height = |p: &[i64; 3]| -> Option<i128> {
        let h = [0, 1, 2].map(|k| n[k].checked_mul(p[k] as i128));
        h[0]?.checked_add(h[1]?)?.checked_add(h[2]?)
    };
    let (mut lo, mut hi) = (i128::MAX, i128::MIN);
    for p in &solid.pts {
        let h = height(p)?;
        lo = lo.min(h);
        hi = hi.max(h);
    }
    // Every vertex on one of the two planes (unused points are not in the mesh's
    // points: the loader keeps only used ones, and a stray one only makes us decline).
    for p in &solid.pts {
        let h = height(p)?;
        if h != lo && h != hi {
            return None;
        }
    }
    if lo == hi {
        return None;
    }
    let neg = n.map(|v| -v);
    let mut top = Vec::new();
    for (t, tri) in solid.tris.iter().enumerate() {
        let m = &solid.planes[t].n;
        let hs = tri.map(|v| height(&solid.pts[v as usize]));
        if hs.iter().all(|h| *h == Some(hi)) {
            if m != n {
                return None; // a face on the upper plane facing down
            }
            top.push(t as u32);
        } else if hs.iter().all(|h| *h == Some(lo)) {
            if *m != neg {
                return None;
            }
        } else {
            let dot = [0, 1, 2]
                .iter()
                .try_fold(0i128, |s, &k| s.checked_add(m[k].checked_mul(n[k])?))?;
            if dot != 0 {
                return None;
            }
        }
    }
    // The step from the upper plane to the lower one: (hi - lo) n / (n · n), integral.
    let nn = n
        .iter()
        .try_fold(0i128, |s, v| s.checked_add(v.checked_mul(*v)?))?;
    let d = hi - lo;
    let mut shift = [0i64; 3];
    for k in 0..3 {
        let x = d.checked_mul(n[k])?;
        if x % nn != 0 {
            return None;
        }
        shift[k] = i64::try_from(x / nn).ok()?;
    }
    Some((*n, top, shift))
}

/// The upper cap's triangles merged greedily across shared edges into convex polygons
/// (counter-clockwise seen from outside), and the number of merges.
fn merge_cap(solid: &Solid, top: &[u32], n: [i128; 3]) -> Option<(Vec<Vec<u32>>, usize)> {
    let axis = dominant_axis(&n);
    // Orientations in the projection carry the sign of n's dominant component.
    let s = if n[axis] > 0 {
        Sign::Positive
    } else {
        Sign::Negative
    };
    let p2 = |v: u32| project(&solid.pts[v as usize], axis);
    // Whether the boundary turns left or runs straight on at `u`, coming from `a` and
    // going to `b` (a reversal is not convex).
    let convex = |a: u32, u: u32, b: u32| -> bool {
        let (pa, pu, pb) = (p2(a), p2(u), p2(b));
        match orient2d(&pa, &pu, &pb) * s {
            Sign::Positive => true,
            Sign::Negative => false,
            Sign::Zero => {
                let (d1, d2) = (
                    [pu[0] - pa[0], pu[1] - pa[1]],
                    [pb[0] - pu[0], pb[1] - pu[1]],
                );
                (d1[0] as i128 * d2[0] as i128 + d1[1] as i128 * d2[1] as i128) > 0
            }
        }
    };
    let mut polys: Vec<Vec<u32>> = top
        .iter()
        .map(|&t| solid.tris[t as usize].to_vec())
        .collect();
    let mut owner: FxHashMap<(u32, u32), u32> = FxHashMap::default();
    for (i, p) in polys.iter().enumerate() {
        for k in 0..3 {
            if owner.insert((p[k], p[(k + 1) % 3]), i as u32).is_some() {
                return None; // a directed edge used twice on the cap
            }
        }
    }
    let (reflex, aligned) = reflex_vertices(&owner, &p2, s)?;
    let mut shared: Vec<(u32, u32)> = owner
        .keys()
        .filter(|(a, b)| a < b && owner.contains_key(&(*b, *a)))
        .copied()
        .collect();
    // Edges between convex corners of the cap first (they can always go: a union of
    // pieces around a convex corner is convex there), then those at one reflex corner,
    // then at two; the longest first in each class (their removal tends to leave
    // fewer, fatter pieces), then by index, to stay deterministic.
    let at_reflex = |(a, b): &(u32, u32)| {
        reflex.binary_search(a).is_ok() as u8 + reflex.binary_search(b).is_ok() as u8
    };
    let len2 = |(a, b): &(u32, u32)| {
        let (pa, pb) = (solid.pts[*a as usize], solid.pts[*b as usize]);
        (0..3)
            .map(|k| (pa[k] as f64 - pb[k] as f64).powi(2))
            .sum::<f64>()
    };
    shared.sort_by(|x, y| {
        at_reflex(x)
            .cmp(&at_reflex(y))
            .then_with(|| len2(y).total_cmp(&len2(x)))
            .then_with(|| x.cmp(y))
    });
    let mut alive = vec![true; polys.len()];
    let mut merges = 0;
    for (a, b) in shared {
        let (Some(&pi), Some(&qi)) = (owner.get(&(a, b)), owner.get(&(b, a))) else {
            continue;
        };
        if pi == qi {
            continue;
        }
        let (p, q) = (&polys[pi as usize], &polys[qi as usize]);
        let at = |poly: &[u32], v: u32| poly.iter().position(|&x| x == v);
        let (Some(ia), Some(ja)) = (at(p, a), at(q, a)) else {
            return None;
        };
        let (Some(ib), Some(jb)) = (at(p, b), at(q, b)) else {
            return None;
        };
        let (pn, qn) = (p.len(), q.len());
        // In p the edge runs a -> b, in q b -> a.
        if p[(ia + 1) % pn] != b || q[(jb + 1) % qn] != a {
            return None;
        }
        let prev_p_a = p[(ia + pn - 1) % pn];
        let next_p_b = p[(ib + 1) % pn];
        let next_q_a = q[(ja + 1) % qn];
        let prev_q_b = q[(jb + qn - 1) % qn];
        if !(convex(prev_p_a, a, next_q_a) && convex(prev_q_b, b, next_p_b)) {
            continue;
        }
        // p from b round to a, then q after a round to before b.
        let mut merged = Vec::with_capacity(pn + qn - 2);
        for k in 0..pn {
            merged.push(p[(ib + k) % pn]);
            if p[(ib + k) % pn] == a {
                break;
            }
        }
        for k in 1..qn - 1 {
            merged.push(q[(ja + k) % qn]);
        }
        owner.remove(&(a, b));
        owner.remove(&(b, a));
        for k in 0..merged.len() {
            owner.insert((merged[k], merged[(k + 1) % merged.len()]), pi);
        }
        polys[pi as usize] = merged;
        polys[qi as usize] = Vec::new();
        alive[qi as usize] = false;
        merges += 1;
    }
    let out: Vec<Vec<u32>> = polys
        .into_iter()
        .zip(alive)
        .filter(|(_, a)| *a)
        .map(|(p, _)| p)
        .collect();
    // Any convex partition has at least r / 2 + 1 pieces (a cut removes at most two
    // reflex vertices). Greedy merging stays near r + 1 and cannot cut along a line
    // through several reflex vertices, as the partition's planes do (a comb's base
    // line): its result is kept when it is within one of the bound, or when few reflex
    // vertices line up with others (a tessellated curve's never do).
    let r = reflex.len();
    (out.len() <= r.div_ceil(2) + 1 || (out.len() <= r + 1 && 4 * aligned <= r))
        .then_some((out, merges))
}

/// A line in the cap's plane: its primitive direction and the cross product of its
/// points with it.
type Line = ([i64; 2], i128);

/// The cap's reflex vertices (sorted), and how many of them lie on the line of a boundary edge
/// at another reflex vertex that is not its neighbour along that edge (where a cut
/// through both could resolve them together). `None` when some boundary vertex has
/// more than one boundary edge in or out (the cap pinches there).
fn reflex_vertices(
    owner: &FxHashMap<(u32, u32), u32>,
    p2: &impl Fn(u32) -> [i64; 2],
    s: Sign,
) -> Option<(Vec<u32>, usize)> {
    let mut next: FxHashMap<u32, u32> = FxHashMap::default();
    let mut prev: FxHashMap<u32, u32> = FxHashMap::default();
    for &(a, b) in owner.keys() {
        if owner.contains_key(&(b, a)) {
            continue;
        }
        if next.insert(a, b).is_some() || prev.insert(b, a).is_some() {
            return None;
        }
    }
    let mut reflex: Vec<u32> = Vec::new();
    for (&v, &b) in &next {
        let a = *prev.get(&v)?;
        if orient2d(&p2(a), &p2(v), &p2(b)) * s == Sign::Negative {
            reflex.push(v);
        }
    }
    reflex.sort_unstable();
    // The lines of the boundary edges at reflex vertices, as a primitive direction
    // (canonical sign) and the cross product of a point with it, and the reflex
    // vertices on each with the boundary neighbour along the line.
    let line = |a: [i64; 2], b: [i64; 2]| -> Line {
        let d = [b[0] - a[0], b[1] - a[1]];
        let g =
            apart_kernel::int::gcd_u128(d[0].unsigned_abs() as u128, d[1].unsigned_abs() as u128)
                .max(1) as i64;
        let mut d = [d[0] / g, d[1] / g];
        if d[0] < 0 || (d[0] == 0 && d[1] < 0) {
            d = [-d[0], -d[1]];
        }
        (d, a[0] as i128 * d[1] as i128 - a[1] as i128 * d[0] as i128)
    };
    let mut on: FxHashMap<Line, Vec<(u32, u32)>> = FxHashMap::default();
    for &v in &reflex {
        for w in [next[&v], prev[&v]] {
            on.entry(line(p2(v), p2(w))).or_default().push((v, w));
        }
    }
    let mut aligned: Vec<u32> = Vec::new();
    for members in on.values() {
        for &(v, w) in members {
            if members.iter().any(|&(u, _)| u != v && u != w) {
                aligned.push(v);
            }
        }
    }
    aligned.sort_unstable();
    aligned.dedup();
    Some((reflex, aligned.len()))
}
