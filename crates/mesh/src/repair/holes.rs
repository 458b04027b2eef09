//! Closing small holes: loops of boundary edges (edges used by one triangle) are filled
//! with triangles, so that a surface with a few missing faces becomes closed.
//!
//! A loop is followed through boundary vertices that have exactly two boundary edges;
//! loops through a vertex with more (two holes touching at a corner) are left open, as
//! are loops longer than the limit and a loop that is exactly the rim of one existing
//! triangle (a stray triangle is not a hole). The loop is triangulated exactly by the
//! crate's polygon triangulation (exact when planar and simple, a fan or strip
//! otherwise, which validation then judges), and the new triangles are oriented against the faces
//! along the loop (by majority, since orientation is only made consistent afterwards).

use super::edges::{runs, uses, Use};
use super::RepairReport;
use crate::mesh::Mesh;
use crate::triangulate::triangulate;

/// Closes the boundary loops of at most `max_edges` edges.
pub(super) fn close(mesh: &mut Mesh, max_edges: usize, report: &mut RepairReport) {
    let uses = uses(mesh);
    let boundary: Vec<Use> = runs(&uses).filter(|r| r.len() == 1).map(|r| r[0]).collect();
    if boundary.is_empty() {
        return;
    }
    // Boundary edges at each vertex: (vertex, edge index), sorted.
    let mut at: Vec<(u32, u32)> = boundary
        .iter()
        .enumerate()
        .flat_map(|(i, u)| [(u.lo(), i as u32), (u.hi(), i as u32)])
        .collect();
    at.sort_unstable();
    let edges_at = |v: u32| -> &[(u32, u32)] {
        let lo = at.partition_point(|&(w, _)| w < v);
        let hi = at.partition_point(|&(w, _)| w <= v);
        &at[lo..hi]
    };
    // Existing triangles by vertex set, to recognise the rim of a stray triangle.
    let mut existing: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .map(|t| {
            let mut s = *t;
            s.sort_unstable();
            s
        })
        .collect();
    existing.sort_unstable();
    let mut visited = vec![false; boundary.len()];
    let mut new_triangles = Vec::new();
    let mut new_sources = Vec::new();
    let mut out = Vec::new();
    for start in 0..boundary.len() {
        if visited[start] {
            continue;
        }
        // Follow the loop: from edge `e` at vertex `v` to the other boundary edge at `v`.
        let mut loop_vertices = vec![boundary[start].lo()];
        let mut loop_edges = vec![start];
        visited[start] = true;
        let mut v = boundary[start].hi();
        let mut e = start;
        let mut simple = true;
        loop {
            let here = edges_at(v);
            if here.len() != 2 {
                simple = false;
                break;
            }
            let next = if here[0].1 as usize == e {
                here[1].1
            } else {
                here[0].1
            } as usize;
            if next == start {
                break;
            }
            if visited[next] {
                simple = false;
                break;
            }
            visited[next] = true;
            loop_vertices.push(v);
            loop_edges.push(next);
            let u = boundary[next];
            v = if u.lo() == v { u.hi() } else { u.lo() };
            e = next;
        }
        if !simple || loop_vertices.len() < 3 || loop_vertices.len() > max_edges {
            continue;
        }
        if loop_vertices.len() == 3 {
            let mut s = [loop_vertices[0], loop_vertices[1], loop_vertices[2]];
            s.sort_unstable();
            if existing.binary_search(&s).is_ok() {
                continue;
            }
        }
        out.clear();
        triangulate(&loop_vertices, &mesh.vertices, &mut out);
        if out.is_empty() {
            continue;
        }
        // Loop edge i runs loop_vertices[i] → loop_vertices[i + 1]; the new triangles
        // run that way too. They should run against the existing face on the edge.
        let n = loop_vertices.len();
        let same = (0..n)
            .filter(|&i| {
                let u = boundary[loop_edges[i]];
                let a = loop_vertices[i];
                (a == u.lo()) == u.forward
            })
            .count();
        if 2 * same > n {
            for t in &mut out {
                t.swap(1, 2);
            }
        }
        report.holes_closed += 1;
        report.hole_triangles += out.len();
        let source = mesh.source_faces[boundary[start].tri as usize];
        new_sources.resize(new_sources.len() + out.len(), source);
        new_triangles.append(&mut out);
    }
    mesh.triangles.extend(new_triangles);
    mesh.source_faces.extend(new_sources);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_open_pyramid_gets_its_base() {
        // A square pyramid, apex up, outward, without its base.
        let mut m = Mesh {
            vertices: vec![[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0], [1, 1, 3]],
            triangles: vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]],
            source_faces: vec![0, 1, 2, 3],
            source_vertices: (0..5).collect(),
        };
        let mut r = RepairReport::default();
        close(&mut m, 64, &mut r);
        assert_eq!((r.holes_closed, r.hole_triangles), (1, 2));
        assert_eq!(m.volume6(), apart_kernel::Int::from(2 * 2 * 3 * 2)); // 6 · (4 · 3 / 3)
                                                                         // Too long for the limit: left open.
        let mut m2 = m.clone();
        m2.triangles.truncate(4);
        m2.source_faces.truncate(4);
        let mut r = RepairReport::default();
        close(&mut m2, 3, &mut r);
        assert!(r.is_empty());
        // A stray triangle is not a hole.
        let mut m3 = Mesh {
            vertices: vec![[0, 0, 0], [2, 0, 0], [2, 2, 0]],
            triangles: vec![[0, 1, 2]],
            source_faces: vec![0],
            source_vertices: (0..3).collect(),
        };
        close(&mut m3, 64, &mut r);
        assert!(r.is_empty());
    }
}
