//! Which closed shells lie inside which: decided by the exact parity of ray crossings
//! (crate::locate) from a point of one shell against the triangles of another, so it
//! does not depend on how either shell is oriented.

use crate::locate::Locator;
use crate::mesh::Mesh;
use apart_kernel::Aabb;
use apart_kernel::Bvh;
use apart_kernel::HPoint;
use apart_kernel::Int;

/// For every shell, the shells that contain it. Only shells with `closed[s]` take
/// part (the others contain nothing and are in nothing). A shell whose sample points
/// (centroids of its first triangles) all lie on the other shell is taken as not
/// inside it.
pub(super) fn containers(
    mesh: &Mesh,
    shell_of: &[u32],
    members: &[Vec<u32>],
    closed: &[bool],
) -> Vec<Vec<u32>> {
    let shells = members.len();
    let mut out = vec![Vec::new(); shells];
    if shells < 2 || closed.iter().filter(|c| **c).count() < 2 {
        return out;
    }
    let bbox: Vec<Aabb> = members
        .iter()
        .map(|m| {
            m.iter().fold(Aabb::EMPTY, |b, &t| {
                b.union(&Aabb::of(mesh.corners(t as usize)))
            })
        })
        .collect();
    let boxes: Vec<Aabb> = (0..shells)
        .map(|s| if closed[s] { bbox[s] } else { Aabb::EMPTY })
        .collect();
    let shell_bvh = Bvh::new(boxes);
    let locator = Locator::new(mesh);
    for s in 0..shells {
        if !closed[s] {
            continue;
        }
        let mut around = Vec::new();
        shell_bvh.query(&bbox[s], |t| {
            let t = t as usize;
            if t != s && closed[t] && contains_box(&bbox[t], &bbox[s]) {
                around.push(t as u32);
            }
        });
        around.sort_unstable();
        for t in around {
            if inside(&locator, shell_of, &members[s], t) {
                out[s].push(t);
            }
        }
    }
    out
}

fn contains_box(outer: &Aabb, inner: &Aabb) -> bool {
    (0..3).all(|k| outer.min[k] <= inner.min[k] && inner.max[k] <= outer.max[k])
}

/// True when a point of the triangles `members` (the first one not on shell `t`) has
/// an odd number of crossings with shell `t`.
fn inside(locator: &Locator, shell_of: &[u32], members: &[u32], t: u32) -> bool {
    let mesh = locator.mesh();
    for &m in members.iter().take(16) {
        let [a, b, c] = mesh.corners(m as usize);
        let num = [0, 1, 2].map(|k| Int::from(a[k]) + Int::from(b[k]) + Int::from(c[k]));
        let p = HPoint::from_big(num, Int::from(3));
        if let Some(w) = locator.winding_filtered(&p, |u| shell_of[u as usize] == t) {
            return w % 2 != 0;
        }
    }
    false
}
