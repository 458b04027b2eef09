//! Reflex edges, and the angular pairing of triangles around non-manifold edges.

use crate::solid::{third, Solid};
use apart_kernel::predicates::det3_sign;
use apart_kernel::{int, Sign, Vec3};
use std::cmp::Ordering;

/// The reflex edges of a closed solid, as vertex index pairs (smaller index first).
///
/// An edge is reflex when the opposite vertex of one of its two triangles lies strictly
/// outside the plane of the other (exact). Around a non-manifold edge (the solid touches
/// itself along it) the triangles are paired by angular order, each with its neighbour
/// across the solid's wedge, and the edge is reflex when some pair is. Returns an empty
/// list when the input is not a valid closed solid.
pub fn reflex_edges(points: &[Vec3], triangles: &[[u32; 3]]) -> Vec<[u32; 2]> {
    match Solid::new(points, triangles) {
        Ok(s) => s
            .edges
            .iter()
            .filter(|e| e.reflex)
            .map(|e| e.ends)
            .collect(),
        Err(_) => Vec::new(),
    }
}

/// Pairs the triangles around edge `ends = [u, v]`: `uses` lists each triangle with
/// whether it runs `u -> v`. Sorted counter-clockwise about `v - u`, a triangle running
/// `u -> v` has the solid on its clockwise side and pairs with its predecessor; the
/// directions must alternate. Returns `(forward, backward)` pairs, or `None` when the
/// triangles do not alternate or two of them coincide in angle (faces touching).
pub(crate) fn pair_around_edge(
    pts: &[[i64; 3]],
    tris: &[[u32; 3]],
    ends: [u32; 2],
    uses: &[(u32, bool)],
) -> Option<Vec<(u32, u32)>> {
    let [u, v] = ends;
    let pu = Vec3::from_i64(pts[u as usize]);
    let d = Vec3::from_i64(pts[v as usize]).sub(&pu);
    let dir: Vec<Vec3> = uses
        .iter()
        .map(|&(t, _)| Vec3::from_i64(pts[third(&tris[t as usize], u, v) as usize]).sub(&pu))
        .collect();
    let r0 = &dir[0];
    let dd = d.dot(&d);
    // Perpendicular parts: same direction as r0's when det = 0 and the product is positive.
    let perp_dot =
        |a: &Vec3, b: &Vec3| -> Sign { int::sign_of(&(a.dot(b) * &dd - a.dot(&d) * b.dot(&d))) };
    let half = |r: &Vec3| -> u8 {
        match det3_sign(&d, r0, r) {
            Sign::Positive => 0,
            Sign::Negative => 1,
            Sign::Zero => {
                if perp_dot(r0, r) == Sign::Positive {
                    0
                } else {
                    1
                }
            }
        }
    };
    let halves: Vec<u8> = dir.iter().map(half).collect();
    let mut order: Vec<usize> = (0..uses.len()).collect();
    let mut clash = false;
    order.sort_by(|&a, &b| {
        halves[a].cmp(&halves[b]).then_with(|| {
            if a == b {
                return Ordering::Equal;
            }
            match det3_sign(&d, &dir[a], &dir[b]) {
                Sign::Positive => Ordering::Less,
                Sign::Negative => Ordering::Greater,
                Sign::Zero => {
                    clash = true;
                    Ordering::Equal
                }
            }
        })
    });
    // Equal angles within one half (or exactly opposite directions in the same half,
    // impossible by construction) mean two faces on one half-plane.
    for w in order.windows(2) {
        if halves[w[0]] == halves[w[1]]
            && det3_sign(&d, &dir[w[0]], &dir[w[1]]) == Sign::Zero
            && perp_dot(&dir[w[0]], &dir[w[1]]) == Sign::Positive
        {
            clash = true;
        }
    }
    if clash {
        return None;
    }
    let n = order.len();
    let mut pairs = Vec::with_capacity(n / 2);
    for i in 0..n {
        let (t, fwd) = uses[order[i]];
        let (p, pfwd) = uses[order[(i + n - 1) % n]];
        if fwd {
            if pfwd {
                return None;
            }
            pairs.push((t, p));
        } else if !pfwd {
            return None;
        }
    }
    Some(pairs)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(o: [i64; 3], pts: &mut Vec<Vec3>, tris: &mut Vec<[u32; 3]>) {
        let base = pts.len() as u32;
        for i in 0..8 {
            pts.push(Vec3::new(
                o[0] + (i & 1),
                o[1] + (i >> 1 & 1),
                o[2] + (i >> 2),
            ));
        }
        for q in apart_testkit::solids::CUBOID_QUADS {
            tris.push([base + q[0], base + q[1], base + q[2]]);
            tris.push([base + q[0], base + q[2], base + q[3]]);
        }
    }

    #[test]
    fn cube_has_no_reflex_edge() {
        let (mut p, mut t) = (Vec::new(), Vec::new());
        cube([0, 0, 0], &mut p, &mut t);
        assert!(reflex_edges(&p, &t).is_empty());
        assert!(Solid::new(&p, &t).is_ok());
    }

    #[test]
    fn cubes_sharing_an_edge_pair_up_convexly() {
        // Two unit cubes touching along the edge x = 1, y = 1; welded into one mesh.
        let (mut p, mut t) = (Vec::new(), Vec::new());
        cube([0, 0, 0], &mut p, &mut t);
        cube([1, 1, 0], &mut p, &mut t);
        // Weld equal points.
        let mut map = std::collections::HashMap::new();
        let mut pts = Vec::new();
        let remap: Vec<u32> = p
            .iter()
            .map(|q| {
                *map.entry(q.clone()).or_insert_with(|| {
                    pts.push(q.clone());
                    pts.len() as u32 - 1
                })
            })
            .collect();
        let tris: Vec<[u32; 3]> = t.iter().map(|tr| tr.map(|v| remap[v as usize])).collect();
        let s = Solid::new(&pts, &tris).unwrap();
        assert!(s.edges.iter().any(|e| e.non_manifold));
        assert!(s.edges.iter().all(|e| !e.reflex));
    }
}
