//! Splitting a repaired mesh into its separate solids, so that several parts exported
//! as one file can be loaded as several parts.
//!
//! Shells are the connected components of the surface across manifold edges (edges
//! used by exactly two triangles running opposite ways). An edge or vertex where a
//! surface touches itself therefore does not join shells: two cubes sharing an edge
//! (four faces at the edge) or a corner are two bodies, which is what separate parts
//! touching in an assembly are. A single solid that touches itself stays one body,
//! since its surface is connected elsewhere. A cavity (a closed shell of negative volume
//! inside other shells) goes with the innermost shell that contains it; every other
//! shell starts a body of its own.

use super::compact::submesh;
use super::edges::{runs, uses};
use super::nesting::containers;
use crate::mesh::Mesh;
use crate::validate::orientation::shell_volumes;
use apart_kernel::Int;

/// The separate solids of a repaired mesh, each with its cavities, ordered by their
/// smallest source face. Triangles keep their order, source faces and source vertices.
/// A mesh with one body (or none) comes back whole (as one body, or none).
pub fn bodies(mesh: &Mesh) -> Vec<Mesh> {
    let n = mesh.triangles.len();
    if n == 0 {
        return Vec::new();
    }
    let uses = uses(mesh);
    let mut dsu: Vec<u32> = (0..n as u32).collect();
    fn find(d: &mut [u32], mut x: u32) -> u32 {
        while d[x as usize] != x {
            d[x as usize] = d[d[x as usize] as usize];
            x = d[x as usize];
        }
        x
    }
    let mut open = Vec::new();
    for run in runs(&uses) {
        if run.len() == 2 && run[0].forward != run[1].forward {
            let (a, b) = (find(&mut dsu, run[0].tri), find(&mut dsu, run[1].tri));
            if a != b {
                dsu[a.max(b) as usize] = a.min(b);
            }
        } else {
            open.push(run);
        }
    }
    let mut shell_of = vec![0u32; n];
    let mut label = vec![u32::MAX; n];
    let mut members: Vec<Vec<u32>> = Vec::new();
    for t in 0..n as u32 {
        let r = find(&mut dsu, t) as usize;
        if label[r] == u32::MAX {
            label[r] = members.len() as u32;
            members.push(Vec::new());
        }
        shell_of[t as usize] = label[r];
        members[label[r] as usize].push(t);
    }
    let shells = members.len();
    if shells == 1 {
        return vec![mesh.clone()];
    }
    // A shell is closed when, along every edge that is not manifold, its triangles
    // run as often one way as the other.
    let mut closed = vec![true; shells];
    for run in open {
        let mut per: Vec<(u32, i64)> = run
            .iter()
            .map(|u| (shell_of[u.tri as usize], if u.forward { 1 } else { -1 }))
            .collect();
        per.sort_unstable();
        for g in per.chunk_by(|a, b| a.0 == b.0) {
            if g.iter().map(|x| x.1).sum::<i64>() != 0 {
                closed[g[0].0 as usize] = false;
            }
        }
    }
    let volumes = shell_volumes(mesh, &shell_of, shells);
    let eligible: Vec<bool> = (0..shells)
        .map(|s| closed[s] && volumes[s] != Int::ZERO)
        .collect();
    let inside = containers(mesh, &shell_of, &members, &eligible);
    // The owner of each shell: itself, or for a cavity the innermost container (the
    // one inside the most others).
    let owner: Vec<usize> = (0..shells)
        .map(|s| {
            if eligible[s] && volumes[s] < Int::ZERO {
                if let Some(&c) = inside[s].iter().max_by_key(|&&c| inside[c as usize].len()) {
                    return c as usize;
                }
            }
            s
        })
        .collect();
    let mut groups: Vec<Vec<u32>> = vec![Vec::new(); shells];
    for t in 0..n {
        groups[owner[shell_of[t] as usize]].push(t as u32);
    }
    let mut out: Vec<(u32, Mesh)> = groups
        .into_iter()
        .filter(|g| !g.is_empty())
        .map(|g| {
            let first = g.iter().map(|&t| mesh.source_faces[t as usize]).min();
            (first.unwrap_or(0), submesh(mesh, &g))
        })
        .collect();
    out.sort_by_key(|(f, _)| *f);
    out.into_iter().map(|(_, m)| m).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cube `lo..lo + s` as 12 outward triangles (vertices appended to `v`).
    fn cube(v: &mut Vec<[i64; 3]>, t: &mut Vec<[u32; 3]>, lo: [i64; 3], s: i64) {
        use crate::test_shapes::{cuboid_corners, CUBOID_QUADS};
        let b = v.len() as u32;
        v.extend(cuboid_corners(lo, lo.map(|c| c + s)));
        for q in CUBOID_QUADS {
            t.push([b + q[0], b + q[1], b + q[2]]);
            t.push([b + q[0], b + q[2], b + q[3]]);
        }
    }

    #[test]
    fn cubes_meeting_at_a_corner_are_two_bodies() {
        let (mut v, mut t) = (Vec::new(), Vec::new());
        cube(&mut v, &mut t, [0, 0, 0], 2);
        cube(&mut v, &mut t, [2, 2, 2], 2);
        // Weld the shared corner (2, 2, 2): vertex 7 of the first, 8 of the second.
        for tri in &mut t {
            for x in tri.iter_mut() {
                if *x == 8 {
                    *x = 7;
                }
            }
        }
        let m = Mesh {
            vertices: v,
            source_faces: (0..24).collect(),
            triangles: t,
            source_vertices: (0..16).collect(),
        };
        let parts = bodies(&m);
        assert_eq!(parts.len(), 2);
        assert!(parts
            .iter()
            .all(|p| p.vertices.len() == 8 && p.volume6() == Int::from(48)));
        assert_eq!(parts[1].source_faces[0], 12);
        assert!(parts[1].source_vertices.contains(&7));
    }
}
