//! Greedy merging of pieces whose union is convex.
//!
//! Exact test, without any hull: let A and B be convex with disjoint interiors, A having
//! a facet plane F whose flip is a facet plane of B. If every vertex of B satisfies every
//! facet inequality of A except F, and every vertex of A every inequality of B except
//! F's flip, then P = (A's other facets) ∩ (B's other facets) satisfies P ∩ (A's side of
//! F) = A and P ∩ (B's side) = B, so A ∪ B = P is convex. Conversely, if A ∪ B is convex,
//! a plane separating A and B cuts it, so both have a facet there, and every other facet
//! plane of A or B supports the union: the test succeeds.

use crate::cell::{CVert, Cell};
use crate::exact::{normals_det_sign, HPoint, Plane};
use apart_kernel::Sign;
use rustc_hash::FxHashMap;

/// Merges pieces pairwise while some pair has a convex union; returns the pieces and the
/// number of merges.
pub(crate) fn merge(cells: Vec<Cell>) -> (Vec<Cell>, usize) {
    let mut slot: Vec<Option<Cell>> = cells.into_iter().map(Some).collect();
    let mut boxes: Vec<[[f64; 3]; 2]> = slot.iter().map(|c| c.as_ref().unwrap().bbox()).collect();
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
                        if let Some(m) = union(a, b) {
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
fn touching(a: &[[f64; 3]; 2], b: &[[f64; 3]; 2]) -> bool {
    (0..3).all(|k| {
        let slack = 1e-9 * (a[1][k].abs() + b[1][k].abs() + a[0][k].abs() + b[0][k].abs() + 1.0);
        a[0][k] <= b[1][k] + slack && b[0][k] <= a[1][k] + slack
    })
}

/// The union of `a` and `b` when it is convex.
fn union(a: &Cell, b: &Cell) -> Option<Cell> {
    let fa = a
        .facets
        .iter()
        .position(|f| b.facets.contains(&f.flipped()))?;
    let shared = a.facets[fa];
    let fb = b.facets.iter().position(|f| *f == shared.flipped())?;
    let inside = |p: &[Plane], skip: usize, verts: &[CVert]| {
        p.iter()
            .enumerate()
            .filter(|&(k, _)| k != skip)
            .all(|(_, pl)| verts.iter().all(|v| pl.side(&v.p) != Sign::Positive))
    };
    if !inside(&a.facets, fa, &b.verts) || !inside(&b.facets, fb, &a.verts) {
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

/// Whether the normals of the listed facets span space (the point is a vertex).
fn spans(facets: &[Plane], on: &[u32]) -> bool {
    let f = |i: u32| &facets[i as usize];
    for x in 0..on.len() {
        for y in x + 1..on.len() {
            for z in y + 1..on.len() {
                if normals_det_sign(f(on[x]), f(on[y]), f(on[z])) != Sign::Zero {
                    return true;
                }
            }
        }
    }
    false
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
