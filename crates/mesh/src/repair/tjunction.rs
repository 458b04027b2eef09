//! T-junctions: a vertex lying strictly inside an edge of a triangle on the other side
//! of a seam (one side of the seam subdivided, the other not). Such an edge is used
//! unequally in its two directions, and its vertex looks like an open boundary. The
//! triangles along the edge are split at every such vertex, so that both sides of the
//! seam share the same edges.
//!
//! Only unpaired edges (used unequally in the two directions) are split, and only at
//! vertices that end an unpaired edge (the fine side of a seam is unpaired too). A
//! hierarchy over those vertices finds the ones in each edge's box; the test itself is
//! exact: collinear (an exact cross product) and strictly between the ends (a
//! comparison of integer coordinates along the edge's dominant axis).

use super::edges::{balance, runs, uses};
use super::RepairReport;
use crate::mesh::Mesh;
use crate::triangulate::triangulate;
use apart_kernel::orient::{collinear, P3};
use apart_kernel::Aabb;
use apart_kernel::Bvh;
use rayon::prelude::*;

/// Passes after which splitting stops even if a pass still split something. Each pass
/// splits triangles into triangles of strictly smaller area on the grid, so splitting
/// always ends; the bound only caps the work on adversarial input.
const MAX_PASSES: usize = 64;

/// Splits the triangles along unpaired edges at the vertices strictly inside them,
/// repeating until nothing changes.
pub(super) fn split(mesh: &mut Mesh, report: &mut RepairReport) {
    for _ in 0..MAX_PASSES {
        let inserted = pass(mesh);
        if inserted == 0 {
            break;
        }
        report.tjunctions += inserted;
    }
}

/// The axis along which `b - a` is longest.
fn long_axis(a: &P3, b: &P3) -> usize {
    let d = [0, 1, 2].map(|k| (b[k] as i128 - a[k] as i128).unsigned_abs());
    if d[0] >= d[1] && d[0] >= d[2] {
        0
    } else if d[1] >= d[2] {
        1
    } else {
        2
    }
}

/// True when `p` lies strictly between `a` and `b` on the segment `a b` (exact).
pub(super) fn strictly_inside_segment(p: &P3, a: &P3, b: &P3) -> bool {
    if !collinear(a, b, p) {
        return false;
    }
    let k = long_axis(a, b);
    let (lo, hi) = (a[k].min(b[k]), a[k].max(b[k]));
    lo < p[k] && p[k] < hi
}

/// One round of splitting; the number of vertex insertions into edges.
fn pass(mesh: &mut Mesh) -> usize {
    let uses = uses(mesh);
    let unpaired: Vec<u64> = runs(&uses)
        .filter(|run| {
            let (f, b) = balance(run);
            f != b
        })
        .map(|run| run[0].key)
        .collect();
    drop(uses);
    if unpaired.is_empty() {
        return 0;
    }
    let mut candidates: Vec<u32> = unpaired
        .iter()
        .flat_map(|&k| [(k >> 32) as u32, k as u32])
        .collect();
    candidates.par_sort_unstable();
    candidates.dedup();
    let v = &mesh.vertices;
    let bvh = Bvh::new(
        candidates
            .iter()
            .map(|&c| Aabb::point(&v[c as usize]))
            .collect(),
    );
    // For every unpaired edge, the candidates strictly inside it, ordered from lo to hi.
    let splits: Vec<(u64, Vec<u32>)> = unpaired
        .par_iter()
        .with_min_len(256)
        .filter_map(|&key| {
            let (lo, hi) = ((key >> 32) as u32, key as u32);
            let (a, b) = (&v[lo as usize], &v[hi as usize]);
            let mut inside = Vec::new();
            bvh.query(&Aabb::of([a, b]), |i| {
                let c = candidates[i as usize];
                if c != lo && c != hi && strictly_inside_segment(&v[c as usize], a, b) {
                    inside.push(c);
                }
            });
            if inside.is_empty() {
                return None;
            }
            let k = long_axis(a, b);
            inside.sort_unstable_by_key(|&c| v[c as usize][k]);
            if a[k] > b[k] {
                inside.reverse();
            }
            Some((key, inside))
        })
        .collect();
    if splits.is_empty() {
        return 0;
    }
    let inserted = splits.iter().map(|s| s.1.len()).sum();
    let along = |a: u32, b: u32| -> Option<(&[u32], bool)> {
        let key = super::edges::key(a, b);
        let i = splits.binary_search_by_key(&key, |s| s.0).ok()?;
        Some((&splits[i].1, a < b))
    };
    let mut triangles = Vec::with_capacity(mesh.triangles.len() + 2 * inserted);
    let mut sources = Vec::with_capacity(triangles.capacity());
    let mut polygon = Vec::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        polygon.clear();
        let mut split = false;
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            polygon.push(a);
            if let Some((inside, forward)) = along(a, b) {
                split = true;
                if forward {
                    polygon.extend_from_slice(inside);
                } else {
                    polygon.extend(inside.iter().rev());
                }
            }
        }
        if split {
            let before = triangles.len();
            triangulate(&polygon, v, &mut triangles);
            sources.resize(triangles.len(), mesh.source_faces[t]);
            debug_assert!(triangles.len() >= before);
        } else {
            triangles.push(*tri);
            sources.push(mesh.source_faces[t]);
        }
    }
    mesh.triangles = triangles;
    mesh.source_faces = sources;
    inserted
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strictly_inside_is_exact() {
        let (a, b) = ([0, 0, 0], [6, 3, 9]);
        assert!(strictly_inside_segment(&[2, 1, 3], &a, &b));
        assert!(!strictly_inside_segment(&[0, 0, 0], &a, &b));
        assert!(!strictly_inside_segment(&[6, 3, 9], &a, &b));
        assert!(!strictly_inside_segment(&[8, 4, 12], &a, &b));
        assert!(!strictly_inside_segment(&[2, 1, 4], &a, &b));
        // Far from the origin, with 53-bit coordinates.
        let big = 1i64 << 52;
        let (a, b) = ([-big, -big, 3], [big - 2, big - 2, 3]);
        assert!(strictly_inside_segment(&[-1, -1, 3], &a, &b));
        assert!(!strictly_inside_segment(&[-1, 0, 3], &a, &b));
    }

    #[test]
    fn a_coarse_triangle_meets_a_split_edge() {
        // Triangle (0, 1, 2) and, across its edge 0-1, two triangles through vertex 4,
        // the midpoint of 0-1.
        let mut m = Mesh {
            vertices: vec![[0, 0, 0], [4, 0, 0], [0, 4, 0], [2, -4, 0], [2, 0, 0]],
            triangles: vec![[0, 1, 2], [0, 3, 4], [4, 3, 1]],
            source_faces: vec![7, 8, 9],
            source_vertices: (0..5).collect(),
        };
        let mut r = RepairReport::default();
        split(&mut m, &mut r);
        assert_eq!(r.tjunctions, 1);
        assert_eq!(m.triangles.len(), 4);
        assert_eq!(m.source_faces.iter().filter(|&&f| f == 7).count(), 2);
        assert!(m.triangles.contains(&[4, 1, 2]) || m.triangles.contains(&[1, 2, 4]));
    }
}
