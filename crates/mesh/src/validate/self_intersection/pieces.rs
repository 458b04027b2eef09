//! Thin triangles boxed in pieces: the boxes of a triangle's parts in slabs along its
//! box's longest side, which meet far fewer other boxes than the whole box.

use crate::mesh::Mesh;
use apart_kernel::Aabb;
use apart_kernel::Bvh;

/// Slabs a thin triangle's box is cut into along its longest side.
const SLABS: usize = 4;
/// Coordinates below this bound (2^48) are interpolated in `f64` well within the
/// boxes' margin.
const SLAB_BOUND: f64 = (1u64 << 48) as f64;

/// The boxes covering triangle `t` (not degenerate): its own box (`bvh`'s), or, when
/// the triangle is thin across its box, the boxes of its parts in [`SLABS`] slabs along the box's
/// longest side (computed in floating point, grown by 2 units and cut to the whole
/// box: each still contains its part) when their areas add up to less than half of it.
pub(super) fn piece_boxes(mesh: &Mesh, t: usize, bvh: &Bvh) -> Vec<Aabb> {
    let whole = bvh.boxes()[t];
    let ext = [0, 1, 2].map(|k| whole.max[k] - whole.min[k]);
    // Area across the two largest sides (flat boxes of flat caps have a zero side).
    let area = |e: [i64; 3]| {
        let mut e = e.map(|x| x as f64 + 1.0);
        e.sort_by(f64::total_cmp);
        e[1] * e[2]
    };
    let axis = (0..3).max_by_key(|&k| ext[k]).unwrap_or(0);
    let corners = mesh.corners(t).map(|c| c.map(|x| x as f64));
    if ext[axis] < 64 || corners.iter().flatten().any(|x| x.abs() >= SLAB_BOUND) {
        return vec![whole];
    }
    let (lo, w) = (whole.min[axis] as f64, ext[axis] as f64 / SLABS as f64);
    let mut out = Vec::with_capacity(SLABS);
    for i in 0..SLABS {
        let (s0, s1) = (lo + w * i as f64, lo + w * (i + 1) as f64);
        let mut b = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
        let mut add = |p: [f64; 3]| {
            for k in 0..3 {
                b[0][k] = b[0][k].min(p[k]);
                b[1][k] = b[1][k].max(p[k]);
            }
        };
        for (j, p) in corners.iter().enumerate() {
            if (s0..=s1).contains(&p[axis]) {
                add(*p);
            }
            let q = corners[(j + 1) % 3];
            for cut in [s0, s1] {
                let (dp, dq) = (p[axis] - cut, q[axis] - cut);
                if (dp < 0.0) != (dq < 0.0) {
                    let l = dp / (dp - dq);
                    add([0, 1, 2].map(|k| p[k] + l * (q[k] - p[k])));
                }
            }
        }
        if b[0][0] > b[1][0] {
            continue; // nothing of the triangle in this slab
        }
        let part = Aabb {
            min: [0, 1, 2].map(|k| (b[0][k].floor() as i64 - 2).max(whole.min[k])),
            max: [0, 1, 2].map(|k| (b[1][k].ceil() as i64 + 2).min(whole.max[k])),
        };
        out.push(part);
    }
    let parts: f64 = out
        .iter()
        .map(|b| area([0, 1, 2].map(|k| b.max[k] - b.min[k])))
        .sum();
    if out.is_empty() || 2.0 * parts >= area(ext) {
        return vec![whole];
    }
    out
}
