//! Exact convex hull of coplanar integer points, used for facet polygons.

use apart_kernel::int::sign_of;
use apart_kernel::{Int, Sign, Vec3};

/// The strictly convex hull of points lying in one plane with normal `normal`: indices
/// into `points` of the extreme points in counter-clockwise order around `normal`
/// (points in the middle of hull edges and duplicates are dropped). Returns fewer than
/// three indices when the points are collinear or coincide.
///
/// Works in the projection that drops the coordinate where `normal` is largest; the
/// orientation there is exact in `i128` for inputs below 2^62 and in arbitrary precision
/// otherwise, and is flipped when that normal component is negative.
pub fn hull_in_plane(normal: &Vec3, points: &[Vec3]) -> Vec<usize> {
    let (u, v, flip) = plane_axes(normal);
    let mut hull = if points.iter().all(|p| p.as_small().is_some()) {
        // Coordinates below 2^62: differences below 2^63, products below 2^126.
        let proj: Vec<[i128; 2]> = points
            .iter()
            .map(|p| {
                let c = p.as_small().unwrap();
                [c[u] as i128, c[v] as i128]
            })
            .collect();
        monotone_chain(&proj, |o, p, q| {
            Sign::of_i128((p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0]))
        })
    } else {
        let proj: Vec<[Int; 2]> = points.iter().map(|p| [p.get(u), p.get(v)]).collect();
        monotone_chain(&proj, |o, p, q| {
            sign_of(&((&p[0] - &o[0]) * (&q[1] - &o[1]) - (&p[1] - &o[1]) * (&q[0] - &o[0])))
        })
    };
    if flip && hull.len() >= 3 {
        hull.reverse();
    }
    hull
}

/// The projection [`hull_in_plane`] works in for a plane with normal `normal` (non-zero):
/// the two kept coordinates `(u, v)` (the dropped one, `k`, is where the normal is
/// largest in floating point, or its first non-zero component if that one is zero, and
/// `(u, v) = (k + 1, k + 2) mod 3`) and whether the normal's `k` component is negative
/// (counter-clockwise around the normal is then clockwise in `(u, v)`).
///
/// [`hull_in_plane`] returns its hull starting at the point that is smallest in the
/// lexicographic order of `(u, v)`, counter-clockwise in `(u, v)`, and reversed when
/// flipped: code that builds facet cycles another way can reproduce its exact output.
pub fn plane_axes(normal: &Vec3) -> (usize, usize, bool) {
    let a = normal.approx();
    let k = if a[0].abs() >= a[1].abs() && a[0].abs() >= a[2].abs() {
        0
    } else if a[1].abs() >= a[2].abs() {
        1
    } else {
        2
    };
    // The float choice of axis only needs a non-zero component; make sure it is one.
    let k = if normal.get(k) != Int::ZERO {
        k
    } else {
        (0..3)
            .find(|&i| normal.get(i) != Int::ZERO)
            .expect("zero normal")
    };
    let flip = normal.get(k) < Int::ZERO;
    ((k + 1) % 3, (k + 2) % 3, flip)
}

/// Andrew's monotone chain on 2-D points, keeping only strict left turns; returns the
/// counter-clockwise hull, or the two extreme points when all are collinear, or the one
/// point when all coincide.
fn monotone_chain<T: Ord>(
    proj: &[[T; 2]],
    orient: impl Fn(&[T; 2], &[T; 2], &[T; 2]) -> Sign,
) -> Vec<usize> {
    let mut order: Vec<usize> = (0..proj.len()).collect();
    order.sort_by(|&i, &j| proj[i].cmp(&proj[j]));
    order.dedup_by(|i, j| proj[*i] == proj[*j]);
    if order.len() < 3 {
        return order;
    }
    let turn = |a: usize, b: usize, c: usize| orient(&proj[a], &proj[b], &proj[c]);
    let mut hull: Vec<usize> = Vec::with_capacity(order.len() * 2);
    for &i in order.iter() {
        while hull.len() >= 2
            && turn(hull[hull.len() - 2], hull[hull.len() - 1], i) != Sign::Positive
        {
            hull.pop();
        }
        hull.push(i);
    }
    let lower = hull.len() + 1;
    for &i in order.iter().rev().skip(1) {
        while hull.len() >= lower
            && turn(hull[hull.len() - 2], hull[hull.len() - 1], i) != Sign::Positive
        {
            hull.pop();
        }
        hull.push(i);
    }
    hull.pop();
    if hull.len() < 3 {
        return vec![order[0], *order.last().unwrap()];
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;
    use apart_kernel::predicates::det3_sign;

    #[test]
    fn square_with_extra_points() {
        let n = Vec3::new(0, 0, -3);
        let pts = vec![
            Vec3::new(0, 0, 5),
            Vec3::new(2, 0, 5),
            Vec3::new(1, 0, 5), // middle of an edge
            Vec3::new(2, 2, 5),
            Vec3::new(0, 2, 5),
            Vec3::new(1, 1, 5), // interior
            Vec3::new(2, 2, 5), // duplicate
        ];
        let h = hull_in_plane(&n, &pts);
        assert_eq!(h.len(), 4);
        for i in 0..4 {
            let (p, q, r) = (&pts[h[i]], &pts[h[(i + 1) % 4]], &pts[h[(i + 2) % 4]]);
            assert_eq!(det3_sign(&n, &q.sub(p), &r.sub(q)), Sign::Positive);
        }
    }

    #[test]
    fn collinear_points() {
        let n = Vec3::new(0, 0, 1);
        let pts = vec![Vec3::new(0, 0, 0), Vec3::new(3, 3, 0), Vec3::new(1, 1, 0)];
        let mut h = hull_in_plane(&n, &pts);
        h.sort();
        assert_eq!(h, vec![0, 1]);
    }
}
