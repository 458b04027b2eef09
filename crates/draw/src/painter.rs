//! The drawing order of flat polygons for a vector picture (painter's algorithm done
//! right): far polygons first, so that nearer ones paint over them.
//!
//! Sorting by one depth per polygon (centroid or farthest corner) is wrong for long
//! faces: a long floor face can be nearer at one end than a small face is at its
//! centre. Here the order comes from the polygons that actually overlap in the picture:
//!
//! 1. every pair whose projections overlap (in more than a sliver) is compared over
//!    their common region, where the difference of their depths is affine, so its sign
//!    at the region's corners decides which one is in front there;
//! 2. these "drawn before" constraints are sorted topologically, first between groups
//!    (the faces of the parts, so that a face is drawn in one go, with no anti-aliased
//!    seams inside it), then, inside a cycle of groups, between polygons (strongly
//!    connected components in topological order);
//! 3. a component with more than one polygon (a cycle of overlaps, or two polygons
//!    that pierce each other) is ordered by a binary space partition of its polygons,
//!    which splits them along each other's planes until no cycle remains.
//!
//! Polygons live in picture space: `x` right and `y` down in pixels, `z` the depth away
//! from the eye in pixels too (the orthographic camera is a similarity, so planes and
//! their sides are those of the scene). The eye looks along `+z`.

use apart_kernel::bvh::sweep_pairs;
use apart_kernel::{fvec, Aabb};
use std::ops::ControlFlow;

/// A convex planar polygon in picture space with the index of what it draws.
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    /// Corners `(x, y, depth)`, in order around the polygon.
    pub points: Vec<[f64; 3]>,
    /// The caller's index (which triangle of which part, for its colour).
    pub tag: usize,
    /// Polygons of one group (one face of one part) are kept together in the order
    /// where nothing between them must be drawn, so that they can be drawn as one path
    /// (no anti-aliased seams between them).
    pub group: usize,
}

/// Overlaps of projections smaller than this (square pixels) impose no order.
const SLIVER: f64 = 1e-3;

/// `polygons` reordered (and where needed split) so that drawing them in order, each
/// over the previous ones, shows at every point the polygon nearest the eye.
pub fn painter_order(polygons: Vec<Polygon>) -> Vec<Polygon> {
    let n = polygons.len();
    if n < 2 {
        return polygons;
    }
    let size = extent(&polygons);
    // Tolerance of depth comparisons and plane sides: far below a pixel, far above the
    // rounding of coordinates of this size.
    let tol = 1e-7 * size.max(1.0);
    let boxes: Vec<Aabb<f64>> = polygons.iter().map(|p| bbox2(&p.points)).collect();
    // after[a] lists the polygons that must be drawn after a (a is behind them).
    let mut after: Vec<Vec<u32>> = vec![Vec::new(); n];
    let _ = sweep_pairs(&boxes, |a, b| {
        match compare(&polygons[a], &polygons[b], tol) {
            Order::Unrelated => {}
            Order::Before => after[a].push(b as u32),
            Order::After => after[b].push(a as u32),
            Order::Pierce => {
                after[a].push(b as u32);
                after[b].push(a as u32);
            }
        }
        ControlFlow::<()>::Continue(())
    });
    // Whole groups (faces) first: a face drawn in one go leaves no seams. The groups'
    // "drawn before" graph is sorted the same way; a cycle of groups (faces that are
    // each in front of the other somewhere) is ordered polygon by polygon.
    let mut dense: std::collections::HashMap<usize, usize> = Default::default();
    let group_of: Vec<usize> = polygons
        .iter()
        .map(|p| {
            let next = dense.len();
            *dense.entry(p.group).or_insert(next)
        })
        .collect();
    let mut group_after: Vec<Vec<u32>> = vec![Vec::new(); dense.len()];
    for (a, bs) in after.iter().enumerate() {
        for &b in bs {
            let (ga, gb) = (group_of[a], group_of[b as usize]);
            if ga != gb {
                group_after[ga].push(gb as u32);
            }
        }
    }
    for list in &mut group_after {
        list.sort_unstable();
        list.dedup();
    }
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); dense.len()];
    for (k, &g) in group_of.iter().enumerate() {
        members[g].push(k);
    }
    let mut slots: Vec<Option<Polygon>> = polygons.into_iter().map(Some).collect();
    let mut out = Vec::with_capacity(n);
    for groups in components_in_order(&group_after) {
        let mut subset: Vec<usize> = groups
            .iter()
            .flat_map(|&g| members[g].iter().copied())
            .collect();
        if groups.len() == 1 {
            out.extend(subset.iter().filter_map(|&k| slots[k].take()));
            continue;
        }
        subset.sort_unstable();
        // The polygons of the cycle of groups, with the constraints among them.
        let local: std::collections::HashMap<usize, usize> =
            subset.iter().enumerate().map(|(i, &k)| (k, i)).collect();
        let sub_after: Vec<Vec<u32>> = subset
            .iter()
            .map(|&k| {
                after[k]
                    .iter()
                    .filter_map(|b| local.get(&(*b as usize)).map(|&i| i as u32))
                    .collect()
            })
            .collect();
        let sub_groups: Vec<usize> = subset.iter().map(|&k| group_of[k]).collect();
        let components = grouped(components_in_order(&sub_after), &sub_after, &sub_groups);
        for comp in components {
            if comp.len() == 1 {
                out.extend(slots[subset[comp[0]]].take());
            } else {
                let cycle: Vec<Polygon> = comp
                    .iter()
                    .filter_map(|&i| slots[subset[i]].take())
                    .collect();
                out.extend(bsp_order(cycle, tol));
            }
        }
    }
    out
}

/// How two polygons must be drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Order {
    /// Their projections do not overlap (or they touch in their common plane).
    Unrelated,
    /// The first is behind the second wherever both are seen: draw it first.
    Before,
    /// The first is in front of the second.
    After,
    /// Each is in front somewhere: they pierce each other.
    Pierce,
}

fn compare(a: &Polygon, b: &Polygon, tol: f64) -> Order {
    let (Some(pa), Some(pb)) = (Plane::of(&a.points), Plane::of(&b.points)) else {
        return Order::Unrelated;
    };
    let flat = |p: &Polygon| -> Vec<[f64; 2]> { p.points.iter().map(|q| [q[0], q[1]]).collect() };
    let common = clip2(&flat(a), &flat(b));
    if common.len() < 3 || area2(&common).abs() < SLIVER {
        return Order::Unrelated;
    }
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for q in &common {
        // Depth of a minus depth of b: positive where a is farther.
        let d = pa.depth_at(q[0], q[1]) - pb.depth_at(q[0], q[1]);
        lo = lo.min(d);
        hi = hi.max(d);
    }
    match (lo < -tol, hi > tol) {
        (false, false) => Order::Unrelated,
        (false, true) => Order::Before,
        (true, false) => Order::After,
        (true, true) => Order::Pierce,
    }
}

/// A plane `n · p = d` with `n_z < 0` (its positive side faces the eye).
#[derive(Clone, Copy, Debug)]
struct Plane {
    n: [f64; 3],
    d: f64,
}

impl Plane {
    /// The plane of a polygon, by Newell's method; `None` when it is degenerate or seen
    /// edge-on (it then covers nothing in the picture).
    fn of(points: &[[f64; 3]]) -> Option<Plane> {
        let mut n = [0.0; 3];
        let mut c = [0.0; 3];
        for (k, p) in points.iter().enumerate() {
            let q = points[(k + 1) % points.len()];
            n[0] += (p[1] - q[1]) * (p[2] + q[2]);
            n[1] += (p[2] - q[2]) * (p[0] + q[0]);
            n[2] += (p[0] - q[0]) * (p[1] + q[1]);
            for i in 0..3 {
                c[i] += p[i] / points.len() as f64;
            }
        }
        let len = fvec::norm(n);
        if !len.is_finite() || len <= 0.0 {
            return None;
        }
        let mut n = n.map(|v| v / len);
        if n[2] > 0.0 {
            n = n.map(|v| -v);
        }
        if n[2].abs() < 1e-12 {
            return None;
        }
        Some(Plane {
            n,
            d: fvec::dot(n, c),
        })
    }

    /// Signed distance of `p` (positive on the eye's side).
    fn side(&self, p: &[f64; 3]) -> f64 {
        fvec::dot(self.n, *p) - self.d
    }

    /// The depth of the plane above picture point `(x, y)`.
    fn depth_at(&self, x: f64, y: f64) -> f64 {
        (self.d - self.n[0] * x - self.n[1] * y) / self.n[2]
    }
}

/// Strongly connected components of the graph `after` (edges a → b: a before b), in
/// topological order (Kosaraju: finishing order on the graph, then components of the
/// reverse graph in reverse finishing order). Iterative, for graphs of any depth.
fn components_in_order(after: &[Vec<u32>]) -> Vec<Vec<usize>> {
    let n = after.len();
    let mut order = Vec::with_capacity(n);
    let mut seen = vec![false; n];
    for s in 0..n {
        if seen[s] {
            continue;
        }
        seen[s] = true;
        let mut stack = vec![(s, 0usize)];
        while let Some(&mut (v, ref mut i)) = stack.last_mut() {
            if let Some(&w) = after[v].get(*i) {
                *i += 1;
                if !seen[w as usize] {
                    seen[w as usize] = true;
                    stack.push((w as usize, 0));
                }
            } else {
                order.push(v);
                stack.pop();
            }
        }
    }
    let mut before: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (a, bs) in after.iter().enumerate() {
        for &b in bs {
            before[b as usize].push(a as u32);
        }
    }
    let mut comp = vec![usize::MAX; n];
    let mut out: Vec<Vec<usize>> = Vec::new();
    for &s in order.iter().rev() {
        if comp[s] != usize::MAX {
            continue;
        }
        let c = out.len();
        comp[s] = c;
        let mut members = vec![s];
        let mut stack = vec![s];
        while let Some(v) = stack.pop() {
            for &w in &before[v] {
                if comp[w as usize] == usize::MAX {
                    comp[w as usize] = c;
                    members.push(w as usize);
                    stack.push(w as usize);
                }
            }
        }
        members.sort_unstable();
        out.push(members);
    }
    out
}

/// The components (in topological order) reordered so that components of one polygon
/// of the same group follow each other wherever the constraints allow (Kahn's
/// algorithm, preferring a ready component of the last one's group, then the earliest).
fn grouped(components: Vec<Vec<usize>>, after: &[Vec<u32>], group_of: &[usize]) -> Vec<Vec<usize>> {
    let m = components.len();
    let mut comp_of = vec![0usize; after.len()];
    for (c, members) in components.iter().enumerate() {
        for &v in members {
            comp_of[v] = c;
        }
    }
    let group = |c: usize| match components[c].as_slice() {
        [v] => Some(group_of[*v]),
        _ => None,
    };
    let mut succ: Vec<Vec<usize>> = vec![Vec::new(); m];
    let mut indegree = vec![0usize; m];
    for (a, bs) in after.iter().enumerate() {
        for &b in bs {
            let (ca, cb) = (comp_of[a], comp_of[b as usize]);
            if ca != cb {
                succ[ca].push(cb);
                indegree[cb] += 1;
            }
        }
    }
    let mut ready: std::collections::BTreeSet<usize> =
        (0..m).filter(|&c| indegree[c] == 0).collect();
    let mut ready_in: std::collections::HashMap<usize, Vec<usize>> = Default::default();
    for &c in &ready {
        if let Some(g) = group(c) {
            ready_in.entry(g).or_default().push(c);
        }
    }
    let mut order = Vec::with_capacity(m);
    let mut last: Option<usize> = None;
    while !ready.is_empty() {
        let same = last.and_then(|g| {
            let list = ready_in.get_mut(&g)?;
            while let Some(c) = list.pop() {
                if ready.contains(&c) {
                    return Some(c);
                }
            }
            None
        });
        let c = same.unwrap_or_else(|| *ready.iter().next().expect("not empty"));
        ready.remove(&c);
        last = group(c);
        order.push(c);
        for &d in &succ[c] {
            indegree[d] -= 1;
            if indegree[d] == 0 {
                ready.insert(d);
                if let Some(g) = group(d) {
                    ready_in.entry(g).or_default().push(d);
                }
            }
        }
    }
    debug_assert_eq!(order.len(), m, "the components form a DAG");
    let mut slots: Vec<Option<Vec<usize>>> = components.into_iter().map(Some).collect();
    order.into_iter().filter_map(|c| slots[c].take()).collect()
}

/// Back-to-front order of polygons by a binary space partition: the largest polygon's
/// plane splits the others into those behind it, on it and in front of it (splitting
/// polygons that cross it); behind first, then on, then in front, recursively.
fn bsp_order(polygons: Vec<Polygon>, tol: f64) -> Vec<Polygon> {
    enum Task {
        Sort(Vec<Polygon>),
        Emit(Vec<Polygon>),
    }
    let mut out = Vec::new();
    let mut tasks = vec![Task::Sort(polygons)];
    while let Some(task) = tasks.pop() {
        let mut set = match task {
            Task::Emit(ps) => {
                out.extend(ps);
                continue;
            }
            Task::Sort(set) => set,
        };
        if set.len() < 2 {
            out.extend(set);
            continue;
        }
        // The splitter: the largest polygon with a plane.
        let pick = (0..set.len())
            .filter(|&k| Plane::of(&set[k].points).is_some())
            .max_by(|&a, &b| {
                area3(&set[a].points)
                    .total_cmp(&area3(&set[b].points))
                    .then(b.cmp(&a))
            });
        let Some(pick) = pick else {
            out.extend(set);
            continue;
        };
        let splitter = set.swap_remove(pick);
        let plane = Plane::of(&splitter.points).expect("checked");
        let (mut back, mut on, mut front) = (Vec::new(), vec![splitter], Vec::new());
        for p in set {
            let sides: Vec<f64> = p.points.iter().map(|q| plane.side(q)).collect();
            let below = sides.iter().any(|&s| s < -tol);
            let above = sides.iter().any(|&s| s > tol);
            match (below, above) {
                (false, false) => on.push(p),
                (true, false) => back.push(p),
                (false, true) => front.push(p),
                (true, true) => {
                    let (b, f) = split(&p, &sides, tol);
                    back.extend(b);
                    front.extend(f);
                }
            }
        }
        // Popped last first: behind, then on the plane, then in front.
        tasks.push(Task::Sort(front));
        tasks.push(Task::Emit(on));
        tasks.push(Task::Sort(back));
    }
    out
}

/// The parts of convex `p` behind and in front of a plane, given each corner's side.
fn split(p: &Polygon, sides: &[f64], tol: f64) -> (Option<Polygon>, Option<Polygon>) {
    let (mut back, mut front) = (Vec::new(), Vec::new());
    let n = p.points.len();
    for k in 0..n {
        let (a, b) = (p.points[k], p.points[(k + 1) % n]);
        let (sa, sb) = (sides[k], sides[(k + 1) % n]);
        if sa <= tol {
            back.push(a);
        }
        if sa >= -tol {
            front.push(a);
        }
        if (sa < -tol && sb > tol) || (sa > tol && sb < -tol) {
            let t = sa / (sa - sb);
            let c = [0, 1, 2].map(|i| a[i] + (b[i] - a[i]) * t);
            back.push(c);
            front.push(c);
        }
    }
    let keep = |pts: Vec<[f64; 3]>| {
        (pts.len() >= 3).then_some(Polygon {
            points: pts,
            tag: p.tag,
            group: p.group,
        })
    };
    (keep(back), keep(front))
}

/// `subject` clipped to convex `clip` (Sutherland–Hodgman), both convex 2-D polygons
/// in either orientation.
fn clip2(subject: &[[f64; 2]], clip: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let orient = if area2(clip) >= 0.0 { 1.0 } else { -1.0 };
    let mut out: Vec<[f64; 2]> = subject.to_vec();
    for k in 0..clip.len() {
        if out.is_empty() {
            break;
        }
        let (a, b) = (clip[k], clip[(k + 1) % clip.len()]);
        // Inside: left of a → b for a counter-clockwise clip polygon.
        let side =
            |p: [f64; 2]| orient * ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]));
        let input = std::mem::take(&mut out);
        for j in 0..input.len() {
            let (p, q) = (input[j], input[(j + 1) % input.len()]);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                out.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                let t = sp / (sp - sq);
                out.push([p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t]);
            }
        }
    }
    out
}

/// Signed area of a 2-D polygon (positive counter-clockwise in a y-up frame).
fn area2(p: &[[f64; 2]]) -> f64 {
    let mut s = 0.0;
    for k in 0..p.len() {
        let (a, b) = (p[k], p[(k + 1) % p.len()]);
        s += a[0] * b[1] - b[0] * a[1];
    }
    s / 2.0
}

/// Area of a planar polygon in space.
fn area3(p: &[[f64; 3]]) -> f64 {
    let mut n = [0.0; 3];
    for k in 1..p.len().saturating_sub(1) {
        let (a, b, c) = (p[0], p[k], p[k + 1]);
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        n[0] += u[1] * v[2] - u[2] * v[1];
        n[1] += u[2] * v[0] - u[0] * v[2];
        n[2] += u[0] * v[1] - u[1] * v[0];
    }
    fvec::norm(n) / 2.0
}

/// The box of the projection onto the picture (`z = 0`).
fn bbox2(p: &[[f64; 3]]) -> Aabb<f64> {
    let mut b = Aabb::EMPTY;
    for q in p {
        b = b.with(&[q[0], q[1], 0.0]);
    }
    b
}

/// The largest coordinate magnitude, for tolerances.
fn extent(polygons: &[Polygon]) -> f64 {
    polygons
        .iter()
        .flat_map(|p| p.points.iter())
        .flat_map(|q| q.iter())
        .fold(
            0.0f64,
            |m, &c| if c.is_finite() { m.max(c.abs()) } else { m },
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad(tag: usize, corners: [[f64; 3]; 4]) -> Polygon {
        Polygon {
            points: corners.to_vec(),
            tag,
            group: tag,
        }
    }

    #[test]
    fn faces_stay_together_when_nothing_comes_between() {
        // Two faces of two triangles each, side by side, and a tile over the seam of
        // the first: the first face's triangles are drawn one after the other.
        let tri = |tag, group, p: [[f64; 3]; 3]| Polygon {
            points: p.to_vec(),
            tag,
            group,
        };
        let polygons = vec![
            tri(
                0,
                7,
                [[0.0, 0.0, 50.0], [40.0, 0.0, 50.0], [0.0, 40.0, 50.0]],
            ),
            tri(
                1,
                8,
                [[50.0, 0.0, 50.0], [90.0, 0.0, 50.0], [50.0, 40.0, 50.0]],
            ),
            tri(
                2,
                7,
                [[40.0, 0.0, 50.0], [40.0, 40.0, 50.0], [0.0, 40.0, 50.0]],
            ),
            tri(
                3,
                8,
                [[90.0, 0.0, 50.0], [90.0, 40.0, 50.0], [50.0, 40.0, 50.0]],
            ),
            tri(
                4,
                9,
                [[10.0, 10.0, 10.0], [30.0, 10.0, 10.0], [10.0, 30.0, 10.0]],
            ),
        ];
        let order: Vec<usize> = painter_order(polygons).iter().map(|p| p.group).collect();
        let runs = order.windows(2).filter(|w| w[0] != w[1]).count() + 1;
        assert_eq!(runs, 3, "{order:?}");
        assert_eq!(
            order.last(),
            Some(&9),
            "the tile is nearer than the face under it"
        );
    }

    /// The tag seen at `(x, y)` when the polygons are painted in order: the last one
    /// whose projection contains the point.
    fn seen(order: &[Polygon], x: f64, y: f64) -> Option<usize> {
        order
            .iter()
            .rev()
            .find(|p| {
                let flat: Vec<[f64; 2]> = p.points.iter().map(|q| [q[0], q[1]]).collect();
                let s = area2(&flat).signum();
                (0..flat.len()).all(|k| {
                    let (a, b) = (flat[k], flat[(k + 1) % flat.len()]);
                    s * ((b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0])) > 0.0
                })
            })
            .map(|p| p.tag)
    }

    /// The nearest polygon at `(x, y)` by ray casting (the oracle).
    fn nearest(polygons: &[Polygon], x: f64, y: f64) -> Option<usize> {
        polygons
            .iter()
            .filter(|p| seen(std::slice::from_ref(*p), x, y).is_some())
            .map(|p| (Plane::of(&p.points).unwrap().depth_at(x, y), p.tag))
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, t)| t)
    }

    fn check(polygons: Vec<Polygon>) {
        let order = painter_order(polygons.clone());
        let mut compared = 0;
        for i in 0..40 {
            for j in 0..40 {
                let (x, y) = (i as f64 * 2.5 + 0.37, j as f64 * 2.5 + 0.61);
                assert_eq!(
                    seen(&order, x, y),
                    nearest(&polygons, x, y),
                    "at ({x}, {y})"
                );
                compared += nearest(&polygons, x, y).is_some() as usize;
            }
        }
        assert!(compared > 100);
    }

    #[test]
    fn a_long_floor_under_a_small_tile_whose_centre_is_farther() {
        // A floor tilted away from the eye (depth grows with y), and a small tile hovering
        // just above its far end: the tile's centre is deeper than the floor's centre,
        // so a sort by centres would draw the floor over the tile.
        let floor = quad(
            0,
            [
                [0.0, 0.0, 0.0],
                [100.0, 0.0, 0.0],
                [100.0, 100.0, 100.0],
                [0.0, 100.0, 100.0],
            ],
        );
        let tile = quad(
            1,
            [
                [40.0, 80.0, 75.0],
                [60.0, 80.0, 75.0],
                [60.0, 95.0, 90.0],
                [40.0, 95.0, 90.0],
            ],
        );
        check(vec![floor.clone(), tile.clone()]);
        check(vec![tile, floor]);
    }

    /// A plank of half-width `half` along the segment `from` → `to`, its depth going
    /// from `d0` to `d1` along it (a planar quadrilateral).
    fn plank(tag: usize, from: [f64; 2], to: [f64; 2], d0: f64, d1: f64, half: f64) -> Polygon {
        let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
        let l = (dx * dx + dy * dy).sqrt();
        let (px, py) = (-dy / l * half, dx / l * half);
        quad(
            tag,
            [
                [from[0] + px, from[1] + py, d0],
                [to[0] + px, to[1] + py, d1],
                [to[0] - px, to[1] - py, d1],
                [from[0] - px, from[1] - py, d0],
            ],
        )
    }

    #[test]
    fn three_planks_overlapping_in_a_cycle_are_split() {
        // Each plank starts near the eye and ends far from it, and crosses the next one
        // near its far end while lying near its own start: 1 over 0, 2 over 1, 0 over 2.
        // No order of whole planks is right.
        let planks = vec![
            plank(0, [10.0, 20.0], [90.0, 20.0], 10.0, 30.0, 5.0),
            plank(1, [80.0, 10.0], [40.0, 90.0], 10.0, 30.0, 5.0),
            plank(2, [50.0, 85.0], [15.0, 10.0], 10.0, 30.0, 5.0),
        ];
        let mut on_a_floor = planks.clone();
        on_a_floor.push(quad(
            3,
            [
                [0.0, 0.0, 60.0],
                [100.0, 0.0, 60.0],
                [100.0, 100.0, 60.0],
                [0.0, 100.0, 60.0],
            ],
        ));
        let order = painter_order(planks.clone());
        assert!(order.len() > 3, "a cycle must be split");
        check(planks);
        check(on_a_floor);
    }

    #[test]
    fn two_squares_piercing_each_other() {
        let a = quad(
            0,
            [
                [10.0, 10.0, 0.0],
                [90.0, 10.0, 0.0],
                [90.0, 90.0, 80.0],
                [10.0, 90.0, 80.0],
            ],
        );
        let b = quad(
            1,
            [
                [10.0, 10.0, 80.0],
                [90.0, 10.0, 80.0],
                [90.0, 90.0, 0.0],
                [10.0, 90.0, 0.0],
            ],
        );
        check(vec![a, b]);
    }

    #[test]
    fn components_come_in_topological_order() {
        // 2 → 0 → 1, and 3 ↔ 4 after 1.
        let after = vec![vec![1], vec![3], vec![0], vec![4], vec![3]];
        let c = components_in_order(&after);
        assert_eq!(c, vec![vec![2], vec![0], vec![1], vec![3, 4]]);
    }
}
