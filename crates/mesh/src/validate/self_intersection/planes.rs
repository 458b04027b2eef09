//! Each triangle's plane in exact integers, computed once: an exact filter that shows
//! most pairs of triangles with meeting boxes apart without the narrow phase.

use crate::mesh::Mesh;
use apart_kernel::orient;
use apart_kernel::Sign;

/// A triangle's plane `n · (x − a) = 0`, `n = (b − a) × (c − a)`, kept when the edge
/// vectors fit in 31 bits (so `n` fits in `i64`) and `n ≠ 0`, with the triangle's
/// projection along the dominant axis of `n`: the box phase's exact filter
/// ([`apart_by_planes`]) then needs no cross product per pair.
#[derive(Clone, Copy)]
pub(super) struct Flat {
    n: [i64; 3],
    pub(super) axis: u8,
    /// The corners projected along `axis` (see `orient::project`).
    pub(super) flat: [[i64; 2]; 3],
    pub(super) ok: bool,
}

/// Edge vector components below this bound (2^31) keep `n` and the filter's sums exact.
const FLAT_BOUND: i64 = 1 << 31;

impl Flat {
    /// The plane of triangle `t`, or one marked not `ok` (edges too long, no area).
    pub(super) fn of(mesh: &Mesh, t: &[u32; 3]) -> Flat {
        let [a, b, c] = t.map(|v| mesh.vertices[v as usize]);
        let none = Flat {
            n: [0; 3],
            axis: 0,
            flat: [[0; 2]; 3],
            ok: false,
        };
        let (u, v) = (
            [0, 1, 2].map(|k| b[k] - a[k]),
            [0, 1, 2].map(|k| c[k] - a[k]),
        );
        if u.iter()
            .chain(&v)
            .any(|x| x.unsigned_abs() >= FLAT_BOUND as u64)
        {
            return none;
        }
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        if n == [0; 3] {
            return none;
        }
        let axis = orient::dominant_axis(&n.map(|x| x as i128));
        Flat {
            n,
            axis: axis as u8,
            flat: [a, b, c].map(|p| orient::project(&p, axis)),
            ok: true,
        }
    }

    /// Signs of `n · (p − a)` for the corners `p` of `other`, `a` being `corner`
    /// (exact: the triangles' boxes meet and both have edges below 2^31, so every
    /// `p − a` is below 2^32 and each sum below 2^97).
    #[inline]
    fn sides(&self, corner: &[i64; 3], other: [&[i64; 3]; 3]) -> [Sign; 3] {
        let n = self.n.map(|x| x as i128);
        other.map(|p| {
            let d = [0, 1, 2].map(|k| (p[k] - corner[k]) as i128);
            debug_assert!(d.iter().all(|x| x.unsigned_abs() <= 1 << 32));
            Sign::of_i128(n[0] * d[0] + n[1] * d[1] + n[2] * d[2])
        })
    }
}

/// True when triangles `t` and `u` (no shared vertex index, meeting boxes) are shown
/// disjoint by one lying strictly on one side of the other's plane, or, when coplanar,
/// by an edge line of one with the other strictly outside (exact; `false` means
/// undecided).
pub(super) fn apart_by_planes(mesh: &Mesh, flats: &[Flat], t: u32, u: u32) -> bool {
    let (ft, fu) = (&flats[t as usize], &flats[u as usize]);
    if !ft.ok || !fu.ok {
        return false;
    }
    let corners = |x: u32| mesh.triangles[x as usize].map(|v| &mesh.vertices[v as usize]);
    let (ct, cu) = (corners(t), corners(u));
    let one_side = |s: [Sign; 3]| s[0] != Sign::Zero && s[0] == s[1] && s[1] == s[2];
    let su = ft.sides(ct[0], cu);
    if one_side(su) {
        return true;
    }
    if su != [Sign::Zero; 3] {
        return one_side(fu.sides(cu[0], ct));
    }
    // Coplanar, both non-degenerate: parallel normals have the same dominant axis.
    ft.axis == fu.axis && crate::intersect::coplanar_apart(&ft.flat, &fu.flat)
}
