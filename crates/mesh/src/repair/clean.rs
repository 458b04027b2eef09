//! Removing triangles that cannot be part of a valid surface: zero-area ones (exact
//! collinearity), extra copies of a triangle, and pairs of copies running opposite ways
//! (two coincident faces with opposite normals enclose nothing, e.g. the shared wall of
//! two boxes exported together).

use super::compact::retain_triangles;
use super::RepairReport;
use crate::mesh::Mesh;
use apart_kernel::orient::collinear;
use rayon::prelude::*;

/// The triangle's vertices rotated to start at the smallest, and whether the other
/// two then increase (one orientation) or not (the other).
fn canonical(t: &[u32; 3]) -> ([u32; 3], bool) {
    let k = (0..3).min_by_key(|&k| t[k]).expect("three corners");
    let r = [t[k], t[(k + 1) % 3], t[(k + 2) % 3]];
    let even = r[1] < r[2];
    let sorted = if even { r } else { [r[0], r[2], r[1]] };
    (sorted, even)
}

/// Removes zero-area, duplicate and cancelling triangles, counting them in `report`.
pub(super) fn clean(mesh: &mut Mesh, report: &mut RepairReport) {
    let n = mesh.triangles.len();
    let mut keep: Vec<bool> = (0..n)
        .into_par_iter()
        .with_min_len(4096)
        .map(|t| {
            let [a, b, c] = mesh.corners(t);
            !collinear(a, b, c)
        })
        .collect();
    report.degenerate_faces += keep.iter().filter(|k| !**k).count();
    let mut order: Vec<([u32; 3], bool, u32)> = (0..n)
        .filter(|&t| keep[t])
        .map(|t| {
            let (s, even) = canonical(&mesh.triangles[t]);
            (s, even, t as u32)
        })
        .collect();
    order.par_sort_unstable();
    for group in order.chunk_by(|x, y| x.0 == y.0) {
        if group.len() == 1 {
            continue;
        }
        // `group` lists the odd copies, then the even ones, each by triangle index.
        let odd = group.iter().filter(|g| !g.1).count();
        let (odds, evens) = group.split_at(odd);
        for side in [odds, evens] {
            for g in side.iter().skip(1) {
                keep[g.2 as usize] = false;
                report.duplicate_faces += 1;
            }
        }
        if !odds.is_empty() && !evens.is_empty() {
            keep[odds[0].2 as usize] = false;
            keep[evens[0].2 as usize] = false;
            report.cancelled_faces += 2;
        }
    }
    if keep.iter().any(|k| !k) {
        retain_triangles(mesh, &keep);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(triangles: Vec<[u32; 3]>) -> Mesh {
        let n = triangles.len() as u32;
        Mesh {
            vertices: vec![[0, 0, 0], [1, 0, 0], [0, 1, 0], [2, 0, 0]],
            triangles,
            source_faces: (0..n).collect(),
            source_vertices: (0..4).collect(),
        }
    }

    #[test]
    fn canonical_orientation() {
        assert_eq!(canonical(&[2, 0, 1]), ([0, 1, 2], true));
        assert_eq!(canonical(&[1, 0, 2]), ([0, 1, 2], false));
        assert!(!canonical(&[0, 2, 1]).1);
    }

    #[test]
    fn duplicates_cancellations_and_slivers() {
        // Three copies one way, one the other way, a sliver (0, 1, 3 collinear).
        let mut m = mesh(vec![[0, 1, 2], [1, 2, 0], [2, 1, 0], [0, 1, 3], [2, 0, 1]]);
        let mut r = RepairReport::default();
        clean(&mut m, &mut r);
        assert_eq!(r.degenerate_faces, 1);
        assert_eq!(r.duplicate_faces, 2);
        assert_eq!(r.cancelled_faces, 2);
        assert!(m.triangles.is_empty() && m.source_faces.is_empty());
        // Two copies the same way: one stays, with the first one's source face.
        let mut m = mesh(vec![[1, 2, 0], [0, 1, 2]]);
        let mut r = RepairReport::default();
        clean(&mut m, &mut r);
        assert_eq!((r.duplicate_faces, m.triangles.len()), (1, 1));
        assert_eq!(m.source_faces, vec![0]);
    }
}
