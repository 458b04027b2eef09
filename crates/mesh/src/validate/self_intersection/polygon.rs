//! Simplicity of a closed polygon in the plane, decided exactly: the boundary test of
//! a certified face.

use super::slab::Slab;
use apart_kernel::orient;
use apart_kernel::Aabb;
use apart_kernel::Bvh;
use apart_kernel::Sign;

/// True when the closed polygon `q` (distinct points, at least 3) is simple: sides meet
/// only at the vertex two consecutive sides share, and there they do not fold back.
/// Sides are paired through a hierarchy of their boxes; each meeting pair is decided by
/// exact orientation tests (points of sides whose boxes meet differ by less than 2^33,
/// so the products fit `i128`).
pub(super) fn simple_polygon_2d(q: &[[i64; 2]]) -> bool {
    let n = q.len();
    if n < 3 {
        return false;
    }
    let side = |k: usize| (&q[k], &q[(k + 1) % n]);
    let boxes: Vec<Aabb> = (0..n)
        .map(|k| {
            let (a, b) = side(k);
            Aabb::of([&[a[0], a[1], 0], &[b[0], b[1], 0]])
        })
        .collect();
    if boxes
        .iter()
        .any(|b| (0..2).any(|k| b.max[k] - b.min[k] >= 1 << 31))
    {
        return false;
    }
    let bvh = Bvh::new(boxes);
    // Sides of deep thin teeth are nearly parallel: their boxes meet quadratically many
    // others, their slabs do not.
    let slabs = bvh.node_labels(|ks| Slab::of_sides(q, ks), Slab::join, Slab::NONE);
    let bad = bvh.self_pairs_pruned(
        || false,
        |bad, i, j| {
            if *bad {
                return;
            }
            let (i, j) = (i as usize, j as usize);
            let ((a, b), (c, d)) = (side(i), side(j));
            *bad = if (i + 1) % n == j || (j + 1) % n == i {
                // Consecutive: they share one vertex `m`; the others `x`, `y`.
                let (x, m, y) = if (i + 1) % n == j {
                    (a, b, d)
                } else {
                    (c, d, b)
                };
                let back = [0, 1].map(|k| (x[k] - m[k]) as i128 * (y[k] - m[k]) as i128);
                orient::orient2d(x, m, y) == Sign::Zero && back[0] + back[1] > 0
            } else {
                segments_meet(a, b, c, d)
            };
        },
        |x, y| x || y,
        |x, y| Slab::apart(&slabs[x], &slabs[y]),
    );
    !bad
}

/// True when the closed segments `ab` and `cd` share a point (exact).
pub(super) fn segments_meet(a: &[i64; 2], b: &[i64; 2], c: &[i64; 2], d: &[i64; 2]) -> bool {
    let within = |p: &[i64; 2], q: &[i64; 2], r: &[i64; 2]| {
        (0..2).all(|k| r[k] >= p[k].min(q[k]) && r[k] <= p[k].max(q[k]))
    };
    let (o1, o2) = (orient::orient2d(a, b, c), orient::orient2d(a, b, d));
    let (o3, o4) = (orient::orient2d(c, d, a), orient::orient2d(c, d, b));
    if o1 != Sign::Zero && o2 != Sign::Zero && o3 != Sign::Zero && o4 != Sign::Zero {
        return o1 != o2 && o3 != o4;
    }
    (o1 == Sign::Zero && within(a, b, c))
        || (o2 == Sign::Zero && within(a, b, d))
        || (o3 == Sign::Zero && within(c, d, a))
        || (o4 == Sign::Zero && within(c, d, b))
}
