//! Removing triangles and unused vertices while keeping `source_faces` and
//! `source_vertices` aligned with what remains.

use crate::mesh::Mesh;

/// Keeps the triangles `t` with `keep[t]` (and their source faces), in order.
pub(super) fn retain_triangles(mesh: &mut Mesh, keep: &[bool]) {
    let mut i = 0;
    mesh.triangles.retain(|_| {
        i += 1;
        keep[i - 1]
    });
    let mut i = 0;
    mesh.source_faces.retain(|_| {
        i += 1;
        keep[i - 1]
    });
}

/// Drops the vertices no triangle uses, renumbering the rest in order.
pub(super) fn drop_unused_vertices(mesh: &mut Mesh) {
    let mut map = vec![u32::MAX; mesh.vertices.len()];
    for t in &mesh.triangles {
        for &v in t {
            map[v as usize] = 0;
        }
    }
    let mut n = 0u32;
    let mut vertices = Vec::with_capacity(mesh.vertices.len());
    let mut sources = Vec::with_capacity(mesh.vertices.len());
    for (i, m) in map.iter_mut().enumerate() {
        if *m == 0 {
            *m = n;
            n += 1;
            vertices.push(mesh.vertices[i]);
            sources.push(mesh.source_vertices.get(i).copied().unwrap_or(i as u32));
        }
    }
    mesh.vertices = vertices;
    mesh.source_vertices = sources;
    for t in &mut mesh.triangles {
        *t = t.map(|v| map[v as usize]);
    }
}

/// The mesh made of the triangles listed in `tris` (in that order), with only the
/// vertices they use (in their order in `mesh`). Costs `O(k log k)` for `k` triangles,
/// whatever the size of `mesh`, so that splitting into many bodies stays linear.
pub(super) fn submesh(mesh: &Mesh, tris: &[u32]) -> Mesh {
    let mut used: Vec<u32> = tris
        .iter()
        .flat_map(|&t| mesh.triangles[t as usize])
        .collect();
    used.sort_unstable();
    used.dedup();
    let local = |v: u32| used.binary_search(&v).expect("a used vertex") as u32;
    Mesh {
        vertices: used.iter().map(|&v| mesh.vertices[v as usize]).collect(),
        triangles: tris
            .iter()
            .map(|&t| mesh.triangles[t as usize].map(local))
            .collect(),
        source_faces: tris
            .iter()
            .map(|&t| mesh.source_faces[t as usize])
            .collect(),
        source_vertices: used
            .iter()
            .map(|&v| mesh.source_vertices.get(v as usize).copied().unwrap_or(v))
            .collect(),
    }
}
