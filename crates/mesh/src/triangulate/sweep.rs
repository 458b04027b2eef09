//! Triangulation of a large simple polygon in `O(n log n)`, exactly: a sweep splits it
//! into monotone pieces (de Berg et al., *Computational Geometry*, ch. 3), then each
//! piece is triangulated in linear time by the stack algorithm. Every decision is an
//! exact orientation test on the projected integer points.
//!
//! The sweep runs from top to bottom; points of equal `y` are ordered by `x` (a sweep
//! line turned by an infinitesimal angle), so horizontal sides and vertices in the
//! middle of sides need no special case. The status (the sides crossing the sweep line
//! with the polygon's inside to their east) is a treap whose nodes are removed by
//! handle, so an inconsistent order (a polygon that is not simple) can make the answer
//! wrong but never makes a search loop.
//!
//! The result is then verified, which makes the method safe on any input: `n - 2`
//! triangles turning like the polygon, every side used once in its direction, every
//! other edge used once in each direction. Their sum is then a 2-chain whose boundary is
//! the polygon, covering each point as often as the polygon winds around it; all
//! triangles turning the same way, a simple polygon is covered exactly once. A polygon
//! the sweep cannot split (not simple, touching itself) returns `false`.

use apart_kernel::orient::orient2d;
use apart_kernel::Sign;
use std::cmp::Ordering;

const NIL: u32 = u32::MAX;

/// Sweep order: `a` before `b` when higher, or as high and further west.
fn sweep_cmp(a: &[i64; 2], b: &[i64; 2]) -> Ordering {
    b[1].cmp(&a[1]).then(a[0].cmp(&b[0]))
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Start,
    End,
    Split,
    Merge,
    /// On the west side of the inside: the polygon goes down here.
    RegularWest,
    /// On the east side: the polygon goes up here.
    RegularEast,
}

/// The status: sides `i` (from vertex `i` down to `i + 1`) ordered west to east.
struct Treap {
    left: Vec<u32>,
    right: Vec<u32>,
    parent: Vec<u32>,
    prio: Vec<u64>,
    root: u32,
}

impl Treap {
    fn new(n: usize) -> Treap {
        // Priorities: a fixed hash of the side (the output must not depend on chance).
        let prio = (0..n as u64)
            .map(|i| {
                let mut z = i.wrapping_add(0x9e37_79b9_7f4a_7c15);
                z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
                z ^ (z >> 31)
            })
            .collect();
        Treap {
            left: vec![NIL; n],
            right: vec![NIL; n],
            parent: vec![NIL; n],
            prio,
            root: NIL,
        }
    }

    /// Replaces `old` by `new` in the link from `old`'s parent.
    fn relink(&mut self, old: u32, new: u32) {
        let p = self.parent[old as usize];
        if p == NIL {
            self.root = new;
        } else if self.left[p as usize] == old {
            self.left[p as usize] = new;
        } else {
            self.right[p as usize] = new;
        }
        if new != NIL {
            self.parent[new as usize] = p;
        }
    }

    /// Turns `x` above its parent.
    fn rotate_up(&mut self, x: u32) {
        let p = self.parent[x as usize];
        self.relink(p, x);
        if self.left[p as usize] == x {
            let b = self.right[x as usize];
            self.left[p as usize] = b;
            if b != NIL {
                self.parent[b as usize] = p;
            }
            self.right[x as usize] = p;
        } else {
            let b = self.left[x as usize];
            self.right[p as usize] = b;
            if b != NIL {
                self.parent[b as usize] = p;
            }
            self.left[x as usize] = p;
        }
        self.parent[p as usize] = x;
    }

    /// Inserts `x`; `east(y)` says whether `x` goes east of the node `y` (`None`:
    /// undecidable, the polygon is not simple).
    fn insert(&mut self, x: u32, east: impl Fn(u32) -> Option<bool>) -> Option<()> {
        let (mut p, mut go_east) = (NIL, false);
        let mut y = self.root;
        while y != NIL {
            p = y;
            go_east = east(y)?;
            y = if go_east {
                self.right[y as usize]
            } else {
                self.left[y as usize]
            };
        }
        self.parent[x as usize] = p;
        if p == NIL {
            self.root = x;
        } else if go_east {
            self.right[p as usize] = x;
        } else {
            self.left[p as usize] = x;
        }
        while self.parent[x as usize] != NIL
            && self.prio[x as usize] < self.prio[self.parent[x as usize] as usize]
        {
            self.rotate_up(x);
        }
        Some(())
    }

    /// Removes `x` (by handle: no comparison).
    fn remove(&mut self, x: u32) {
        loop {
            let (l, r) = (self.left[x as usize], self.right[x as usize]);
            let child = match (l, r) {
                (NIL, NIL) => break,
                (c, NIL) | (NIL, c) => c,
                (l, r) => {
                    if self.prio[l as usize] < self.prio[r as usize] {
                        l
                    } else {
                        r
                    }
                }
            };
            self.rotate_up(child);
        }
        self.relink(x, NIL);
        self.parent[x as usize] = NIL;
    }

    /// The easternmost node `y` with `east(y)` true (the side just west of a point).
    fn last_west(&self, east: impl Fn(u32) -> Option<bool>) -> Option<u32> {
        let (mut y, mut found) = (self.root, None);
        while y != NIL {
            if east(y)? {
                found = Some(y);
                y = self.right[y as usize];
            } else {
                y = self.left[y as usize];
            }
        }
        found
    }
}

/// The diagonals splitting the counter-clockwise polygon `q` into monotone pieces;
/// `None` when the sweep finds it is not simple.
fn monotone_diagonals(q: &[[i64; 2]]) -> Option<Vec<(u32, u32)>> {
    let n = q.len();
    let prev = |i: usize| (i + n - 1) % n;
    let next = |i: usize| (i + 1) % n;
    let before = |a: usize, b: usize| sweep_cmp(&q[a], &q[b]) == Ordering::Less;
    let mut kind = Vec::with_capacity(n);
    for i in 0..n {
        let (p, x) = (prev(i), next(i));
        if q[p] == q[i] || q[x] == q[i] {
            return None;
        }
        let turn = orient2d(&q[p], &q[i], &q[x]);
        kind.push(match (before(i, p), before(i, x)) {
            (true, true) => match turn {
                Sign::Positive => Kind::Start,
                Sign::Negative => Kind::Split,
                Sign::Zero => return None, // a spike
            },
            (false, false) => match turn {
                Sign::Positive => Kind::End,
                Sign::Negative => Kind::Merge,
                Sign::Zero => return None,
            },
            (false, true) => Kind::RegularWest,
            (true, false) => Kind::RegularEast,
        });
    }
    let mut order: Vec<u32> = (0..n as u32).collect();
    order.sort_unstable_by(|&a, &b| sweep_cmp(&q[a as usize], &q[b as usize]).then(a.cmp(&b)));
    // Side `e` runs from vertex `e` down to `e + 1`; a vertex is east of it when the
    // turn (top, bottom, vertex) is counter-clockwise.
    let east_of = |v: usize, e: u32| -> Option<bool> {
        let e = e as usize;
        match orient2d(&q[e], &q[next(e)], &q[v]) {
            Sign::Positive => Some(true),
            Sign::Negative => Some(false),
            Sign::Zero => None,
        }
    };
    let mut status = Treap::new(n);
    let mut active = vec![false; n];
    let mut helper = vec![NIL; n];
    let mut diagonals = Vec::new();
    let is_merge = |h: u32| h != NIL && kind[h as usize] == Kind::Merge;
    for &v in &order {
        let i = v as usize;
        let e_prev = prev(i);
        // Ends the side arriving from above, joined to a merge vertex helping it.
        let close = |status: &mut Treap,
                     active: &mut [bool],
                     helper: &[u32],
                     diagonals: &mut Vec<(u32, u32)>|
         -> Option<()> {
            if !active[e_prev] {
                return None;
            }
            if is_merge(helper[e_prev]) {
                diagonals.push((v, helper[e_prev]));
            }
            status.remove(e_prev as u32);
            active[e_prev] = false;
            Some(())
        };
        match kind[i] {
            Kind::Start => {
                status.insert(v, |y| east_of(i, y))?;
                active[i] = true;
                helper[i] = v;
            }
            Kind::End => close(&mut status, &mut active, &helper, &mut diagonals)?,
            Kind::Split => {
                let j = status.last_west(|y| east_of(i, y))?;
                diagonals.push((v, helper[j as usize]));
                helper[j as usize] = v;
                status.insert(v, |y| east_of(i, y))?;
                active[i] = true;
                helper[i] = v;
            }
            Kind::Merge => {
                close(&mut status, &mut active, &helper, &mut diagonals)?;
                let j = status.last_west(|y| east_of(i, y))?;
                if is_merge(helper[j as usize]) {
                    diagonals.push((v, helper[j as usize]));
                }
                helper[j as usize] = v;
            }
            Kind::RegularWest => {
                close(&mut status, &mut active, &helper, &mut diagonals)?;
                status.insert(v, |y| east_of(i, y))?;
                active[i] = true;
                helper[i] = v;
            }
            Kind::RegularEast => {
                let j = status.last_west(|y| east_of(i, y))?;
                if is_merge(helper[j as usize]) {
                    diagonals.push((v, helper[j as usize]));
                }
                helper[j as usize] = v;
            }
        }
    }
    Some(diagonals)
}

/// Half-edge position of `a` in the angular order around `v`: directions by half
/// plane (up, or horizontal east, first), then counter-clockwise.
fn angle_cmp(q: &[[i64; 2]], v: usize, a: u32, b: u32) -> Ordering {
    let half = |w: u32| {
        let (dx, dy) = (q[w as usize][0] - q[v][0], q[w as usize][1] - q[v][1]);
        u8::from(!(dy > 0 || (dy == 0 && dx > 0)))
    };
    half(a)
        .cmp(&half(b))
        .then_with(|| match orient2d(&q[v], &q[a as usize], &q[b as usize]) {
            Sign::Positive => Ordering::Less,
            Sign::Negative => Ordering::Greater,
            Sign::Zero => Ordering::Equal,
        })
}

/// The pieces (counter-clockwise vertex cycles) the diagonals cut `q` into.
fn pieces(q: &[[i64; 2]], diagonals: &[(u32, u32)]) -> Option<Vec<Vec<u32>>> {
    let n = q.len();
    let mut start = vec![0usize; n + 1];
    for &(a, b) in diagonals {
        if a == b {
            return None;
        }
        start[a as usize + 1] += 1;
        start[b as usize + 1] += 1;
    }
    for v in 0..n {
        start[v + 1] += start[v] + 2;
    }
    let mut adj = vec![0u32; start[n]];
    let mut fill: Vec<usize> = start[..n].to_vec();
    let mut put = |a: u32, b: u32, fill: &mut Vec<usize>| {
        adj[fill[a as usize]] = b;
        fill[a as usize] += 1;
    };
    for v in 0..n {
        put(v as u32, ((v + 1) % n) as u32, &mut fill);
        put(v as u32, ((v + n - 1) % n) as u32, &mut fill);
    }
    for &(a, b) in diagonals {
        put(a, b, &mut fill);
        put(b, a, &mut fill);
    }
    for v in 0..n {
        let s = &mut adj[start[v]..start[v + 1]];
        s.sort_unstable_by(|&a, &b| angle_cmp(q, v, a, b));
        if s.windows(2)
            .any(|w| angle_cmp(q, v, w[0], w[1]) != Ordering::Less)
        {
            return None; // two edges leave v in the same direction
        }
    }
    // Half-edge (v, k): v to adj[start[v] + k]. Inside half-edges: sides forwards and
    // diagonals both ways; the next one around a piece turns the least clockwise.
    let mut used = vec![false; adj.len()];
    let mut out = Vec::new();
    for v0 in 0..n {
        for h0 in start[v0]..start[v0 + 1] {
            if used[h0] || adj[h0] as usize == (v0 + n - 1) % n {
                continue;
            }
            let mut piece = Vec::new();
            let (mut v, mut h) = (v0, h0);
            loop {
                if used[h] || piece.len() > n {
                    return None;
                }
                used[h] = true;
                piece.push(v as u32);
                let w = adj[h] as usize;
                let around = &adj[start[w]..start[w + 1]];
                let t = around.iter().position(|&x| x as usize == v)?;
                let k = (t + around.len() - 1) % around.len();
                let (nv, nh) = (w, start[w] + k);
                if adj[nh] as usize == (nv + n - 1) % n {
                    return None; // would follow the outside
                }
                (v, h) = (nv, nh);
                if h == h0 {
                    break;
                }
            }
            out.push(piece);
        }
    }
    Some(out)
}

/// Triangulates one monotone piece (counter-clockwise) by the stack algorithm,
/// appending counter-clockwise triangles of local indices.
fn monotone(q: &[[i64; 2]], piece: &[u32], out: &mut Vec<[u32; 3]>) -> Option<()> {
    let m = piece.len();
    if m < 3 {
        return None;
    }
    let at = |k: usize| &q[piece[k % m] as usize];
    let top = (0..m).min_by(|&a, &b| sweep_cmp(at(a), at(b)))?;
    let bottom = (0..m).max_by(|&a, &b| sweep_cmp(at(a), at(b)))?;
    // West chain: forwards from the top to the bottom; east chain: backwards.
    let west: Vec<usize> = (1..)
        .map(|d| (top + d) % m)
        .take_while(|&k| k != bottom)
        .collect();
    let east: Vec<usize> = (1..)
        .map(|d| (top + m - d) % m)
        .take_while(|&k| k != bottom)
        .collect();
    if west.len() + east.len() + 2 != m {
        return None;
    }
    let descending = |c: &[usize]| {
        c.windows(2)
            .all(|w| sweep_cmp(at(w[0]), at(w[1])) == Ordering::Less)
    };
    if !descending(&west) || !descending(&east) {
        return None; // not monotone
    }
    // Merge the chains: (position in piece, on the west chain).
    let mut u: Vec<(usize, bool)> = Vec::with_capacity(m);
    u.push((top, true));
    let (mut a, mut b) = (0, 0);
    while a < west.len() || b < east.len() {
        let take_west = b == east.len()
            || (a < west.len() && sweep_cmp(at(west[a]), at(east[b])) == Ordering::Less);
        if take_west {
            u.push((west[a], true));
            a += 1;
        } else {
            u.push((east[b], false));
            b += 1;
        }
    }
    u.push((bottom, true));
    let id = |k: usize| piece[k];
    let mut emit = |x: usize, y: usize, z: usize| -> Option<()> {
        let (a, b, c) = (id(x), id(y), id(z));
        match orient2d(&q[a as usize], &q[b as usize], &q[c as usize]) {
            Sign::Positive => out.push([a, b, c]),
            Sign::Negative => out.push([a, c, b]),
            Sign::Zero => return None,
        }
        Some(())
    };
    let mut stack: Vec<(usize, bool)> = vec![u[0], u[1]];
    for j in 2..m - 1 {
        let (uj, west_j) = u[j];
        let &(_, top_west) = stack.last()?;
        if west_j != top_west {
            while stack.len() > 1 {
                let (t, _) = stack.pop()?;
                let &(s, _) = stack.last()?;
                emit(uj, t, s)?;
            }
            stack.clear();
            stack.push(u[j - 1]);
            stack.push(u[j]);
        } else {
            let mut last = stack.pop()?;
            while let Some(&(t, _)) = stack.last() {
                let inside = if west_j {
                    orient2d(at(t), at(last.0), at(uj))
                } else {
                    orient2d(at(uj), at(last.0), at(t))
                } == Sign::Positive;
                if !inside {
                    break;
                }
                emit(uj, last.0, t)?;
                last = stack.pop()?;
            }
            stack.push(last);
            stack.push(u[j]);
        }
    }
    let (ul, _) = u[m - 1];
    while stack.len() > 1 {
        let (t, _) = stack.pop()?;
        let &(s, _) = stack.last()?;
        emit(ul, t, s)?;
    }
    Some(())
}

/// True when `tris` (counter-clockwise, local indices) triangulate the polygon of `n`
/// vertices: `n - 2` of them, each side used once forwards, every other edge once in
/// each direction (see the module's documentation).
fn verified(n: usize, tris: &[[u32; 3]]) -> bool {
    if tris.len() != n - 2 {
        return false;
    }
    let mut edges: Vec<(u32, u32)> = tris
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .collect();
    edges.sort_unstable();
    if edges.windows(2).any(|w| w[0] == w[1]) {
        return false;
    }
    let side = |a: u32, b: u32| (a as usize + 1) % n == b as usize;
    let mut sides = 0;
    for &(a, b) in &edges {
        if side(a, b) {
            sides += 1;
        } else if side(b, a) || edges.binary_search(&(b, a)).is_err() {
            return false;
        }
    }
    sides == n
}

/// Triangulates the simple polygon `q` of orientation `s` (projected points of the
/// vertices `p`), appending triangles of `p`'s indices that turn like it. False (and
/// nothing appended) when it cannot.
pub(super) fn triangulate(p: &[u32], q: &[[i64; 2]], s: Sign, out: &mut Vec<[u32; 3]>) -> bool {
    let n = p.len();
    // Counter-clockwise local order.
    let ccw: Vec<usize> = match s {
        Sign::Positive => (0..n).collect(),
        Sign::Negative => (0..n).rev().collect(),
        Sign::Zero => return false,
    };
    let lq: Vec<[i64; 2]> = ccw.iter().map(|&i| q[i]).collect();
    let Some(diagonals) = monotone_diagonals(&lq) else {
        return false;
    };
    let Some(pieces) = pieces(&lq, &diagonals) else {
        return false;
    };
    let mut tris = Vec::with_capacity(n - 2);
    for piece in &pieces {
        if monotone(&lq, piece, &mut tris).is_none() {
            return false;
        }
    }
    if !verified(n, &tris) {
        return false;
    }
    out.extend(tris.iter().map(|t| {
        let [a, b, c] = t.map(|k| p[ccw[k as usize]]);
        match s {
            Sign::Positive => [a, b, c],
            _ => [a, c, b],
        }
    }));
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::collections::HashMap;

    /// Twice the signed area of a polygon (shoelace, exact).
    fn area2(q: &[[i64; 2]]) -> i128 {
        (0..q.len())
            .map(|i| {
                let (a, b) = (q[i], q[(i + 1) % q.len()]);
                a[0] as i128 * b[1] as i128 - b[0] as i128 * a[1] as i128
            })
            .sum()
    }

    /// The oracle: `tris` triangulate the simple polygon `q` when there are `n - 2`,
    /// all turning like `q`, their areas add up to `q`'s, and as a 2-chain their
    /// boundary is `q`'s boundary (every edge used `+1` times along a side, `0` times
    /// net elsewhere): then each point is covered as often as `q` winds around it.
    fn check(q: &[[i64; 2]], tris: &[[u32; 3]]) -> Result<(), TestCaseError> {
        let n = q.len();
        let s = if area2(q) > 0 { 1 } else { -1 };
        prop_assert_eq!(tris.len(), n - 2);
        let mut net: HashMap<(u32, u32), i32> = HashMap::new();
        let mut sum = 0i128;
        for t in tris {
            let a = area2(&t.map(|k| q[k as usize]));
            prop_assert!(a * s > 0, "triangle {:?} turns the wrong way", t);
            sum += a;
            for (x, y) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                if x < y {
                    *net.entry((x, y)).or_default() += 1;
                } else {
                    *net.entry((y, x)).or_default() -= 1;
                }
            }
        }
        prop_assert_eq!(sum, area2(q));
        for i in 0..n as u32 {
            let j = (i + 1) % n as u32;
            let (k, v) = if i < j { ((i, j), -1) } else { ((j, i), 1) };
            *net.entry(k).or_default() += v;
        }
        prop_assert!(net.values().all(|&c| c == 0), "boundary is not the polygon");
        Ok(())
    }

    fn run(q: &[[i64; 2]]) -> Option<Vec<[u32; 3]>> {
        let p: Vec<u32> = (0..q.len() as u32).collect();
        let s = if area2(q) > 0 {
            Sign::Positive
        } else {
            Sign::Negative
        };
        let mut out = Vec::new();
        triangulate(&p, q, s, &mut out).then_some(out)
    }

    /// A star-shaped polygon: radii at increasing angles, rounded to the grid.
    fn star(radii: &[f64], clockwise: bool) -> Vec<[i64; 2]> {
        let n = radii.len();
        let mut q: Vec<[i64; 2]> = radii
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                [(r * a.cos()).round() as i64, (r * a.sin()).round() as i64]
            })
            .collect();
        if clockwise {
            q.reverse();
        }
        q
    }

    #[test]
    fn shapes() {
        // A comb with 50 teeth pointing up, in both orientations.
        let mut comb = vec![[0, 0], [200, 0]];
        for t in (0..50).rev() {
            let x = 4 * t;
            comb.extend([
                [x + 3, 10],
                [x + 2, 10],
                [x + 2, 1],
                [x + 1, 1],
                [x + 1, 10],
            ]);
            comb.push([x, 10]);
        }
        comb.dedup();
        for q in [comb.clone(), comb.iter().rev().copied().collect()] {
            check(&q, &run(&q).expect("comb")).unwrap();
        }
        // A square with 25 vertices in the middle of every side.
        let mut sq = Vec::new();
        for k in 0..26 {
            sq.push([k, 0]);
        }
        for k in 1..26 {
            sq.push([25, k]);
        }
        for k in (0..25).rev() {
            sq.push([k, 25]);
        }
        for k in (1..25).rev() {
            sq.push([0, k]);
        }
        check(&sq, &run(&sq).expect("square")).unwrap();
        // A gear of 1000 teeth, and a spiral.
        let gear: Vec<f64> = (0..2000)
            .map(|i| if i % 2 == 0 { 1e6 } else { 9e5 })
            .collect();
        let q = star(&gear, false);
        check(&q, &run(&q).expect("gear")).unwrap();
        let mut spiral = Vec::new();
        for k in 0..400 {
            let a = k as f64 * 0.05;
            let r = 100.0 + 20.0 * a;
            spiral.push([(r * a.cos()).round() as i64, (r * a.sin()).round() as i64]);
        }
        for k in (0..400).rev() {
            let a = k as f64 * 0.05;
            let r = 130.0 + 20.0 * a;
            spiral.push([(r * a.cos()).round() as i64, (r * a.sin()).round() as i64]);
        }
        spiral.dedup();
        check(&spiral, &run(&spiral).expect("spiral")).unwrap();
    }

    #[test]
    fn not_simple_is_refused() {
        // A bow tie, a polygon crossing itself, one touching itself at a vertex
        // (a keyhole), and a spike.
        for q in [
            vec![[0, 0], [2, 2], [2, 0], [0, 2]],
            vec![[0, 0], [10, 0], [10, 10], [5, -5], [0, 10]],
            vec![
                [0, 0],
                [10, 0],
                [10, 10],
                [5, 10],
                [5, 5],
                [7, 7],
                [5, 10],
                [0, 10],
            ],
            vec![
                [0, 0],
                [10, 0],
                [10, 10],
                [5, 10],
                [5, 20],
                [5, 10],
                [0, 10],
            ],
        ] {
            assert!(run(&q).is_none(), "{q:?}");
        }
    }

    #[test]
    fn large_polygons_take_n_log_n() {
        let gear: Vec<f64> = (0..200_000)
            .map(|i| if i % 2 == 0 { 1e8 } else { 9e7 })
            .collect();
        let q = star(&gear, true);
        let t = std::time::Instant::now();
        let tris = run(&q).expect("gear");
        assert_eq!(tris.len(), q.len() - 2);
        assert!(t.elapsed().as_secs() < 10, "{:?}", t.elapsed());
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]

        /// Star-shaped polygons on a coarse grid: collinear vertices, horizontal and
        /// vertical runs, vertices in the middle of sides.
        #[test]
        fn star_polygons(
            radii in prop::collection::vec(1u32..12, 4..80),
            scale in prop_oneof![Just(1.0), Just(3.0), Just(1000.0)],
            clockwise in any::<bool>(),
        ) {
            let r: Vec<f64> = radii.iter().map(|&x| x as f64 * scale).collect();
            let mut q = star(&r, clockwise);
            q.dedup();
            while q.len() > 1 && q.first() == q.last() {
                q.pop();
            }
            prop_assume!(q.len() >= 3 && area2(&q) != 0);
            // Rounding can make a star polygon touch or cross itself: the sweep then
            // declines, or answers right.
            if let Some(t) = run(&q) {
                check(&q, &t)?;
            }
        }

        /// Orthogonal polygons from a random staircase: many equal coordinates.
        #[test]
        fn staircases(steps in prop::collection::vec((1i64..4, 1i64..4), 2..40)) {
            let mut q = vec![[0, 0]];
            let (mut x, mut y) = (0, 0);
            for &(dx, dy) in &steps {
                x += dx;
                q.push([x, y]);
                y += dy;
                q.push([x, y]);
            }
            q.push([0, y]);
            let t = run(&q).expect("a staircase is simple");
            check(&q, &t)?;
        }
    }
}
