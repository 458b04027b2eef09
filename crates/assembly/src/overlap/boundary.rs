//! Exact overlap test of two closed solids given by their boundaries.
//!
//! The interiors of A and B overlap exactly when some point of one boundary lies
//! strictly inside the other solid, or when they have coincident faces with both solids
//! on the same side. The test samples the boundary of each solid where that can first
//! happen:
//! 1. its vertices (exact point location in the other solid);
//! 2. its edges, split at every crossing with the other's faces: the midpoint of each
//!    piece between consecutive crossings;
//! 3. the centroid of every face whose three vertices lie on the other's boundary;
//! 4. coincident faces with the same outward normal and a common area;
//! 5. faces of the two that cross: just inside both, next to the midpoint of the
//!    segment they share (an overlap that reaches no vertex and crosses no edge, e.g.
//!    two tetrahedra each with an edge on the other's boundary, is found here).
//!
//! Each hit is turned into a point strictly inside both solids and verified by exact
//! point location. What it can miss: a face of one solid whose vertices and edges all
//! lie on the other's boundary, crossing the other's interior away from its centroid,
//! while the other solid likewise keeps its vertices and edges on the first one's
//! boundary (e.g. a face cutting through a pocket exactly between boundary edges). The
//! piece-based test has no such gap; it is used instead whenever both parts have convex
//! pieces, declared or from the loader's automatic decomposition ([`crate::Decompose`]).

use crate::witness::{below_both, into_both};
use apart_kernel::orient::{
    dominant_axis, in_closed_triangle_2d, normal, orient2d, orient3d, project, segments_meet_2d,
};
use apart_kernel::{Aabb, HPoint, Int, Rational, Sign};
use apart_mesh::intersect::{coplanar_overlap_area, segment_triangle_params};
use apart_mesh::locate::Locator;
use apart_mesh::Mesh;
use rayon::prelude::*;

/// A point strictly inside both solids, if their interiors overlap (see the module).
pub(crate) fn overlap(a: &Mesh, b: &Mesh) -> Option<HPoint> {
    let la = Locator::new(a);
    let lb = Locator::new(b);
    one_way(&la, &lb)
        .or_else(|| one_way(&lb, &la))
        .or_else(|| coincident(&la, &lb))
        .or_else(|| crossing_faces(&la, &lb))
}

/// Faces of A and B that cross (not coplanar): just inside both, next to the midpoint
/// of the segment where they meet. This finds overlaps that reach no vertex and cross
/// no edge (an edge of each lying on the other's boundary while their faces cross).
fn crossing_faces(la: &Locator, lb: &Locator) -> Option<HPoint> {
    let (a, b) = (la.mesh(), lb.mesh());
    let bbox_b = b.bbox()?;
    (0..a.triangles.len()).into_par_iter().find_map_first(|t| {
        let ta = a.corners(t);
        let tbox = Aabb::of(ta);
        if !tbox.overlaps(&bbox_b) {
            return None;
        }
        let na = normal(ta[0], ta[1], ta[2]);
        let mut found = None;
        lb.bvh().query(&tbox, |u| {
            if found.is_some() {
                return;
            }
            let tb = b.corners(u as usize);
            if tb
                .iter()
                .all(|v| orient3d(ta[0], ta[1], ta[2], v) == Sign::Zero)
            {
                return; // coplanar: `coincident` decides
            }
            // The points where either triangle's edges meet the other: the ends of the
            // segment the two triangles share.
            let mut pts: Vec<[Rational; 3]> = Vec::new();
            for (s, o) in [(ta, tb), (tb, ta)] {
                for k in 0..3 {
                    let (p, q) = (s[k], s[(k + 1) % 3]);
                    for tm in segment_triangle_params(p, q, o[0], o[1], o[2]) {
                        pts.push([0, 1, 2].map(|c| &rat(p[c]) + &(&rat(q[c] - p[c]) * &tm)));
                    }
                }
            }
            if pts.len() < 2 {
                return;
            }
            let (lo, hi) = (pts.iter().min().unwrap(), pts.iter().max().unwrap());
            if lo == hi {
                return; // the triangles only touch at a point
            }
            let half = Rational::new(Int::ONE, Int::from(2));
            let m = [0, 1, 2].map(|c| &(&lo[c] + &hi[c]) * &half);
            // Inward along both faces: the sum of their unit outward normals, on an
            // integer grid fine enough (any direction into the wedge works; the point
            // found is checked exactly).
            let nb = normal(tb[0], tb[1], tb[2]);
            let unit = |n: &[i128; 3]| {
                let f = n.map(|x| x as f64);
                let l = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
                f.map(|x| x / l)
            };
            let (ua, ub) = (unit(&na), unit(&nb));
            let dir: [i128; 3] =
                [0, 1, 2].map(|c| ((ua[c] + ub[c]) * (1u64 << 40) as f64).round() as i128);
            if dir != [0; 3] {
                found = below_both(la, lb, &m, dir);
            }
        });
        found
    })
}

fn rat(v: i64) -> Rational {
    Rational::from_int(v)
}

/// Points of A's boundary strictly inside B, moved into A.
fn one_way(la: &Locator, lb: &Locator) -> Option<HPoint> {
    let a = la.mesh();
    let bbox_b = lb.mesh().bbox()?;
    // Winding number of B around each vertex of A (None: on B's boundary).
    let status: Vec<Option<i64>> = a
        .vertices
        .par_iter()
        .map(|v| {
            if bbox_b.contains(v) {
                lb.winding(&HPoint::int(*v))
            } else {
                Some(0)
            }
        })
        .collect();
    let hit = (0..a.vertices.len()).into_par_iter().find_map_first(|v| {
        if status[v].is_some_and(|w| w > 0) {
            into_both(la, lb, &HPoint::int(a.vertices[v]))
        } else {
            None
        }
    });
    if hit.is_some() {
        return hit;
    }
    // Edges, each once (from the triangle that runs it upwards).
    let edges: Vec<(u32, u32)> = a
        .triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .filter(|(p, q)| p < q)
        .collect();
    let b = lb.mesh();
    let hit = edges.par_iter().find_map_first(|&(i, j)| {
        let (p, q) = (&a.vertices[i as usize], &a.vertices[j as usize]);
        let ebox = Aabb::of([p, q]);
        if !ebox.overlaps(&bbox_b) {
            return None;
        }
        let mut ts: Vec<Rational> = Vec::new();
        lb.bvh().query(&ebox, |u| {
            let [x, y, z] = b.corners(u as usize);
            ts.extend(segment_triangle_params(p, q, x, y, z));
        });
        let zero = Rational::zero();
        let one = rat(1);
        let crossings = ts.iter().any(|t| *t > zero && *t < one);
        if !crossings && status[i as usize].is_some() && status[j as usize].is_some() {
            return None; // no crossing: the edge is where its ends are
        }
        ts.push(zero);
        ts.push(one);
        ts.sort();
        ts.dedup();
        let pr = p.map(rat);
        let d = [0, 1, 2].map(|k| rat(q[k] - p[k]));
        let half = Rational::new(Int::ONE, Int::from(2));
        for w in ts.windows(2) {
            let tm = &(&w[0] + &w[1]) * &half;
            let m = [0, 1, 2].map(|k| &pr[k] + &(&d[k] * &tm));
            let m = HPoint::from_rationals(&m);
            if lb.strictly_inside(&m) {
                if let Some(x) = into_both(la, lb, &m) {
                    return Some(x);
                }
            }
        }
        None
    });
    if hit.is_some() {
        return hit;
    }
    // Faces whose corners are all on B's boundary: their centroids.
    (0..a.triangles.len()).into_par_iter().find_map_first(|t| {
        let tri = a.triangles[t];
        if tri.iter().any(|&v| status[v as usize].is_some()) {
            return None;
        }
        let [p, q, r] = a.corners(t);
        let num = [0, 1, 2].map(|k| Int::from(p[k]) + q[k] + r[k]);
        let c = HPoint::from_big(num, Int::from(3));
        if lb.strictly_inside(&c) {
            into_both(la, lb, &c)
        } else {
            None
        }
    })
}

/// Coincident faces with the same outward normal sharing an area: both solids lie just
/// below them.
fn coincident(la: &Locator, lb: &Locator) -> Option<HPoint> {
    let (a, b) = (la.mesh(), lb.mesh());
    let bbox_b = b.bbox()?;
    (0..a.triangles.len()).into_par_iter().find_map_first(|t| {
        let [p, q, r] = a.corners(t);
        let tbox = Aabb::of([p, q, r]);
        if !tbox.overlaps(&bbox_b) {
            return None;
        }
        let n = normal(p, q, r);
        let k = dominant_axis(&n);
        let mut found = None;
        lb.bvh().query(&tbox, |u| {
            if found.is_some() {
                return;
            }
            let [x, y, z] = b.corners(u as usize);
            if [x, y, z].iter().any(|v| orient3d(p, q, r, v) != Sign::Zero) {
                return;
            }
            let m = normal(x, y, z);
            if m[k].signum() != n[k].signum() {
                return; // opposite normals: the solids are on opposite sides
            }
            let t2 = [p, q, r].map(|v| project(v, k));
            let u2 = [x, y, z].map(|v| project(v, k));
            if !coplanar_overlap_area(&t2, &u2) {
                return;
            }
            let c = common_point([p, q, r], [x, y, z], k);
            found = below_both(la, lb, &c, n);
        });
        found
    })
}

/// A point in the relative interior of the intersection of two coplanar triangles that
/// share an area: the average of the intersection polygon's vertices (corners of one
/// inside the other and crossings of their edges).
fn common_point(t: [&[i64; 3]; 3], u: [&[i64; 3]; 3], k: usize) -> [Rational; 3] {
    let t2 = t.map(|v| project(v, k));
    let u2 = u.map(|v| project(v, k));
    let mut pts: Vec<[Rational; 3]> = Vec::new();
    for (i, v) in t.iter().enumerate() {
        if in_closed_triangle_2d(&t2[i], &u2[0], &u2[1], &u2[2]) {
            pts.push(v.map(rat));
        }
    }
    for (i, v) in u.iter().enumerate() {
        if in_closed_triangle_2d(&u2[i], &t2[0], &t2[1], &t2[2]) {
            pts.push(v.map(rat));
        }
    }
    for i in 0..3 {
        let (p, q) = (&t2[i], &t2[(i + 1) % 3]);
        for j in 0..3 {
            let (r, s) = (&u2[j], &u2[(j + 1) % 3]);
            if !segments_meet_2d(p, q, r, s) {
                continue;
            }
            let o = |x: &[i64; 2]| {
                (s[0] - r[0]) as i128 * (x[1] - r[1]) as i128
                    - (s[1] - r[1]) as i128 * (x[0] - r[0]) as i128
            };
            let (op, oq) = (o(p), o(q));
            if op == oq || orient2d(r, s, p) == Sign::Zero && orient2d(r, s, q) == Sign::Zero {
                continue; // parallel: its ends are counted above
            }
            let tm = Rational::new(Int::from(op), Int::from(op - oq));
            let (p3, q3) = (t[i], t[(i + 1) % 3]);
            pts.push([0, 1, 2].map(|c| &rat(p3[c]) + &(&rat(q3[c] - p3[c]) * &tm)));
        }
    }
    let n = Rational::new(Int::ONE, Int::from(pts.len().max(1)));
    let mut sum = [Rational::zero(), Rational::zero(), Rational::zero()];
    for p in &pts {
        for c in 0..3 {
            sum[c] = &sum[c] + &p[c];
        }
    }
    sum.map(|s| &s * &n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::overlap::polytope_mesh;
    use apart_kernel::Vec3;
    use apart_pieces::interference::interior_witness;
    use apart_pieces::Polytope;
    use proptest::prelude::*;

    fn box_poly(lo: [i64; 3], hi: [i64; 3]) -> Polytope {
        Polytope::cuboid(lo, hi).unwrap()
    }

    fn check(a: &Polytope, b: &Polytope) -> Option<HPoint> {
        let (ma, mb) = (polytope_mesh(a), polytope_mesh(b));
        let w = overlap(&ma, &mb);
        if let Some(w) = &w {
            // The witness is strictly inside both, by an independent test.
            let (num, den) = (w.num(), w.den());
            for p in [a, b] {
                for f in p.facets() {
                    let mut s = -(&f.offset * den);
                    for (k, x) in num.iter().enumerate() {
                        s += f.normal.get(k) * x;
                    }
                    assert!(s < Int::ZERO, "witness not strictly inside");
                }
            }
        }
        w
    }

    #[test]
    fn boxes_touching_or_overlapping() {
        let a = box_poly([0, 0, 0], [2, 2, 2]);
        assert!(check(&a, &box_poly([2, 0, 0], [4, 2, 2])).is_none()); // face contact
        assert!(check(&a, &box_poly([2, 2, 2], [3, 3, 3])).is_none()); // vertex contact
        assert!(check(&a, &box_poly([1, 1, 1], [3, 3, 3])).is_some());
        assert!(check(&a, &a).is_some()); // identical: coincident faces, same side
        assert!(check(&a, &box_poly([0, 0, 0], [1, 2, 2])).is_some()); // inside, sharing faces
        assert!(check(
            &box_poly([-4, -1, 0], [4, 1, 1]),
            &box_poly([-1, -4, 0], [1, 4, 1])
        )
        .is_some()); // plus sign
    }

    fn small_point() -> impl Strategy<Value = [i64; 3]> {
        [0i64..4, 0i64..4, 0i64..4]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        /// Random boxes on a small lattice (many touching and coincident cases): the
        /// boundary test agrees with comparing intervals.
        #[test]
        fn boxes_agree_with_intervals(a in small_point(), da in [1i64..3, 1i64..3, 1i64..3],
                                      b in small_point(), db in [1i64..3, 1i64..3, 1i64..3]) {
            let ha = [a[0] + da[0], a[1] + da[1], a[2] + da[2]];
            let hb = [b[0] + db[0], b[1] + db[1], b[2] + db[2]];
            let expect = (0..3).all(|k| a[k] < hb[k] && b[k] < ha[k]);
            prop_assert_eq!(check(&box_poly(a, ha), &box_poly(b, hb)).is_some(), expect);
        }

        /// Random convex polytopes (hulls of lattice points): the boundary test agrees
        /// with the separating-axis test of the pieces crate.
        #[test]
        fn hulls_agree_with_separating_axes(pa in prop::collection::vec(small_point(), 5..9),
                                            pb in prop::collection::vec(small_point(), 5..9)) {
            let hull = |p: &[[i64; 3]]| Polytope::hull_of_points(&p.iter().map(|&c| Vec3::from_i64(c)).collect::<Vec<_>>()).ok();
            if let (Some(a), Some(b)) = (hull(&pa), hull(&pb)) {
                let expect = interior_witness(&a, &b).is_some();
                prop_assert_eq!(check(&a, &b).is_some(), expect);
            }
        }
    }
}
