//! Greedy merging of pieces whose union is convex.
//!
//! Exact test, without any hull: let A and B be convex with disjoint interiors, A having
//! a facet plane F whose flip is a facet plane of B. If every vertex of B satisfies every
//! facet inequality of A except F, and every vertex of A every inequality of B except
//! F's flip, then P = (A's other facets) ∩ (B's other facets) satisfies P ∩ (A's side of
//! F) = A and P ∩ (B's side) = B, so A ∪ B = P is convex. Conversely, if A ∪ B is convex,
//! a plane separating A and B cuts it, so both have a facet there, and every other facet
//! plane of A or B supports the union: the test succeeds.

use crate::cell::{spans, CVert, Cell};
use apart_kernel::plane::{HPoint, Plane};
use apart_kernel::{Aabb, Sign};
use rustc_hash::FxHashMap;

/// Merges pieces pairwise while some pair has a convex union; returns the pieces and the
/// number of merges.
pub(crate) fn merge(cells: Vec<Cell>) -> (Vec<Cell>, usize) {
    let mut slot: Vec<Option<Cell>> = cells.into_iter().map(Some).collect();
    let mut boxes: Vec<Aabb<f64>> = slot.iter().map(|c| c.as_ref().unwrap().bbox()).collect();
    let mut counts: Vec<Vec<u32>> = slot
        .iter()
        .map(|c| facet_counts(c.as_ref().unwrap()))
        .collect();
    let mut by_plane: FxHashMap<Plane, Vec<usize>> = FxHashMap::default();
    for (i, c) in slot.iter().enumerate() {
        for f in &c.as_ref().unwrap().facets {
            by_plane.entry(*f).or_default().push(i);
        }
    }
    let mut merges = 0;
    let mut queue: Vec<usize> = (0..slot.len()).rev().collect();
    while let Some(i) = queue.pop() {
        let Some(a) = slot[i].as_ref() else { continue };
        let mut found = None;
        'search: for f in &a.facets {
            if let Some(js) = by_plane.get(&f.flipped()) {
                for &j in js {
                    if j == i || !touching(&boxes[i], &boxes[j]) {
                        continue;
                    }
                    if let Some(b) = slot[j].as_ref() {
                        let c = [&counts[i][..], &counts[j][..]];
                        if let Some(m) = union(a, b, c, &boxes[i], &boxes[j]) {
                            found = Some((j, m));
                            break 'search;
                        }
                    }
                }
            }
        }
        if let Some((j, m)) = found {
            merges += 1;
            slot[i] = None;
            slot[j] = None;
            let k = slot.len();
            boxes.push(m.bbox());
            counts.push(facet_counts(&m));
            for f in &m.facets {
                by_plane.entry(*f).or_default().push(k);
            }
            slot.push(Some(m));
            queue.push(k);
        }
    }
    (slot.into_iter().flatten().collect(), merges)
}

/// Float boxes overlap or touch, with a relative slack far above rounding errors (a
/// filter: convex unions need a shared facet, hence touching boxes).
fn touching(a: &Aabb<f64>, b: &Aabb<f64>) -> bool {
    (0..3).all(|k| {
        let slack =
            1e-9 * (a.max[k].abs() + b.max[k].abs() + a.min[k].abs() + b.min[k].abs() + 1.0);
        a.min[k] <= b.max[k] + slack && b.min[k] <= a.max[k] + slack
    })
}

/// Whether the float box `b` (of points whose floating-point shadows are within a few
/// ulps) lies clearly inside the plane's inner side: then every point does, and the
/// exact tests can be skipped. The slack, 1e-9 of the terms' magnitude, is far above
/// the rounding of the shadows and of this evaluation.
fn box_inside(pl: &Plane, b: &Aabb<f64>) -> bool {
    let n = pl.n.map(|v| v as f64);
    let mut v = -(pl.c as f64);
    let mut mag = (pl.c as f64).abs();
    for (k, &nk) in n.iter().enumerate() {
        let x = if nk > 0.0 { b.max[k] } else { b.min[k] };
        v += nk * x;
        mag += (nk * x).abs();
    }
    v.is_finite() && mag.is_finite() && v < -1e-9 * mag
}

/// The number of vertices on each facet.
fn facet_counts(c: &Cell) -> Vec<u32> {
    let mut n = vec![0; c.facets.len()];
    for v in &c.verts {
        for &f in &v.on {
            n[f as usize] += 1;
        }
    }
    n
}

/// The union of `a` and `b` (vertices per facet `counts`, float boxes `ba`, `bb`) when
/// it is convex.
fn union(a: &Cell, b: &Cell, counts: [&[u32]; 2], ba: &Aabb<f64>, bb: &Aabb<f64>) -> Option<Cell> {
    let fa = a
        .facets
        .iter()
        .position(|f| b.facets.contains(&f.flipped()))?;
    let shared = a.facets[fa];
    let fb = b.facets.iter().position(|f| *f == shared.flipped())?;
    // A convex union is cut by the shared plane in one polygon, the facet of both
    // pieces there: the same vertices (vertex lists are complete), so as many.
    if counts[0][fa] != counts[1][fb] {
        return None;
    }
    // Every facet of one (but the shared one) holds the other's vertices. A facet whose
    // inner side clearly holds the other's float box needs no exact test (most facets,
    // when a large piece such as the disc of a lathe meets each of its many wedges).
    // A facet plane of both holds both. Small piece first: its facets against the large
    // one's vertices are the likely failures.
    let inside = |p: &[Plane], skip: usize, other: &Cell, bx: &Aabb<f64>| {
        let filter = other.verts.iter().all(|v| v.p.filterable());
        p.iter()
            .enumerate()
            .filter(|&(k, pl)| {
                k != skip && !(filter && box_inside(pl, bx)) && !other.facets.contains(pl)
            })
            .all(|(_, pl)| other.verts.iter().all(|v| pl.side(&v.p) != Sign::Positive))
    };
    let ((x, fx, bx), (y, fy, by)) = if a.facets.len() <= b.facets.len() {
        ((a, fa, ba), (b, fb, bb))
    } else {
        ((b, fb, bb), (a, fa, ba))
    };
    if !inside(&x.facets, fx, y, by) || !inside(&y.facets, fy, x, bx) {
        return None;
    }
    let mut facets: Vec<Plane> = Vec::new();
    for (k, f) in a.facets.iter().enumerate() {
        if k != fa {
            facets.push(*f);
        }
    }
    for (k, f) in b.facets.iter().enumerate() {
        if k != fb && !facets.contains(f) {
            facets.push(*f);
        }
    }
    let mut pts: Vec<HPoint> = Vec::new();
    let mut seen = rustc_hash::FxHashSet::default();
    for v in a.verts.iter().chain(&b.verts) {
        if seen.insert(&v.p) {
            pts.push(v.p.clone());
        }
    }
    let mut verts = Vec::new();
    for p in pts {
        let on: Vec<u32> = (0..facets.len() as u32)
            .filter(|&f| facets[f as usize].side(&p) == Sign::Zero)
            .collect();
        if spans(&facets, &on) {
            verts.push(CVert { p, on });
        }
    }
    Some(Cell { facets, verts })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halves_of_a_box_merge_back() {
        let c = Cell::boxed([0, 0, 0], [4, 2, 2]);
        let h = Plane::new([1, 0, 0], 1);
        let (a, b) = c.split(&h, true);
        let g = Plane::new([0, 1, 1], 1);
        let (b1, b2) = b.unwrap().split(&g, true);
        let (cells, merges) = merge(vec![a.unwrap(), b1.unwrap(), b2.unwrap()]);
        // The three parts of the box merge back into one piece.
        assert_eq!((cells.len(), merges), (1, 2));
        assert_eq!(cells[0].verts.len(), 8);
        assert_eq!(cells[0].facets.len(), 6);
    }

    #[test]
    fn l_shape_does_not_merge() {
        let a = Cell::boxed([0, 0, 0], [2, 1, 1]);
        let b = Cell::boxed([0, 1, 0], [1, 2, 1]);
        let (cells, merges) = merge(vec![a, b]);
        assert_eq!((cells.len(), merges), (2, 0));
    }
}
