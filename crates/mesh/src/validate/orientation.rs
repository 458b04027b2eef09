//! Orientation of a closed surface: the sign of its volume decides inside-out (every
//! face is then flipped), and with several shells the nesting is checked with exact
//! winding numbers. Every point just behind a face must be inside the solid (winding
//! number one) and every point just in front of it outside (winding number zero). So a
//! shell with positive volume must lie outside all other shells, and a shell with
//! negative volume (a cavity) inside exactly one layer of material.

use crate::locate::Locator;
use crate::mesh::Mesh;
use apart_kernel::predicates::det3_i128;
use apart_kernel::HPoint;
use apart_kernel::{Int, Vec3};

/// Six times the signed volume of each shell (`i128` while it fits, exact big
/// integers for a shell that overflows).
pub(crate) fn shell_volumes(mesh: &Mesh, shell_of: &[u32], shells: usize) -> Vec<Int> {
    let o = mesh.vertices[0];
    let rel = |p: &[i64; 3]| [p[0] - o[0], p[1] - o[1], p[2] - o[2]];
    let small = mesh
        .vertices
        .iter()
        .all(|p| rel(p).iter().all(|c| c.unsigned_abs() < 1 << 40));
    let mut fast = vec![if small { Some(0i128) } else { None }; shells];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let s = shell_of[t] as usize;
        if let Some(acc) = fast[s] {
            let [a, b, c] = tri.map(|v| rel(&mesh.vertices[v as usize]));
            fast[s] = acc.checked_add(det3_i128(&a, &b, &c));
        }
    }
    (0..shells)
        .map(|s| match fast[s] {
            Some(v) => Int::from(v),
            None => {
                let mut total = Int::ZERO;
                for (t, tri) in mesh.triangles.iter().enumerate() {
                    if shell_of[t] as usize == s {
                        let [a, b, c] =
                            tri.map(|v| Vec3::from_i64(rel(&mesh.vertices[v as usize])));
                        total += a.dot(&b.cross(&c));
                    }
                }
                total
            }
        })
        .collect()
}

/// The winding number of the other shells around a point of shell `s` (the centroid
/// of one of its triangles, avoiding points that lie on other shells), or `None` when
/// every tried point is on another shell.
pub(crate) fn winding_of_others(
    locator: &Locator,
    shell_of: &[u32],
    s: u32,
    members: &[u32],
) -> Option<i64> {
    let mesh = locator.mesh();
    for &t in members.iter().take(16) {
        let [a, b, c] = mesh.corners(t as usize);
        let num = [0, 1, 2].map(|k| Int::from(a[k]) + Int::from(b[k]) + Int::from(c[k]));
        let p = HPoint::from_big(num, Int::from(3));
        if let Some(w) = locator.winding_filtered(&p, |u| shell_of[u as usize] != s) {
            return Some(w);
        }
    }
    None
}
