//! Orientation: within each shell (triangles connected across edges used by exactly
//! two triangles) every triangle is made to agree with its neighbours, by a breadth-
//! first walk that flips a neighbour running the same way along the shared edge. Then
//! each closed shell is made to face the right way: a shell inside an odd number of
//! other shells bounds a cavity and must have negative volume, any other shell
//! positive volume (signs exact, nesting by exact ray-crossing parity).
//!
//! Counting is by input face (source face), so that a face split at T-junctions or
//! triangulated from a polygon counts once: a shell whose final orientation differs
//! from the input in more than half of its faces counts as one flipped shell, plus the
//! faces that had to be flipped against the rest (those that were right before the
//! shell was reversed); otherwise its flipped faces are counted as such. An open or
//! zero-volume shell keeps the orientation that changes fewer triangles.

use super::edges::{runs, uses};
use super::nesting::containers;
use super::RepairReport;
use crate::mesh::Mesh;
use crate::validate::orientation::shell_volumes;
use apart_kernel::Int;
use std::collections::VecDeque;

/// The shells of a mesh and what orienting them needs.
pub(super) struct Shells {
    /// The shell of each triangle.
    pub shell_of: Vec<u32>,
    /// The triangles of each shell, in order.
    pub members: Vec<Vec<u32>>,
}

/// Makes every shell consistent and outward (cavities inward), counting in `report`.
pub(super) fn orient(mesh: &mut Mesh, report: &mut RepairReport) {
    let n = mesh.triangles.len();
    if n == 0 {
        return;
    }
    let uses = uses(mesh);
    // Neighbours across edges used by exactly two triangles: (t, u, same direction).
    let mut adj: Vec<(u32, u32, bool)> = Vec::new();
    for run in runs(&uses) {
        if run.len() == 2 && run[0].tri != run[1].tri {
            let same = run[0].forward == run[1].forward;
            adj.push((run[0].tri, run[1].tri, same));
            adj.push((run[1].tri, run[0].tri, same));
        }
    }
    adj.sort_unstable();
    let neighbours = |t: u32| -> &[(u32, u32, bool)] {
        let lo = adj.partition_point(|x| x.0 < t);
        let hi = adj.partition_point(|x| x.0 <= t);
        &adj[lo..hi]
    };
    let mut shell_of = vec![u32::MAX; n];
    let mut flip = vec![false; n];
    let mut members: Vec<Vec<u32>> = Vec::new();
    let mut queue = VecDeque::new();
    for seed in 0..n as u32 {
        if shell_of[seed as usize] != u32::MAX {
            continue;
        }
        let s = members.len() as u32;
        let mut list = vec![seed];
        shell_of[seed as usize] = s;
        queue.push_back(seed);
        while let Some(t) = queue.pop_front() {
            for &(_, u, same) in neighbours(t) {
                if shell_of[u as usize] == u32::MAX {
                    shell_of[u as usize] = s;
                    flip[u as usize] = flip[t as usize] ^ same;
                    list.push(u);
                    queue.push_back(u);
                }
            }
        }
        list.sort_unstable();
        members.push(list);
    }
    for (t, tri) in mesh.triangles.iter_mut().enumerate() {
        if flip[t] {
            tri.swap(1, 2);
        }
    }
    let shells = Shells { shell_of, members };
    let closed = closed_shells(&shells, &uses, &flip);
    let volumes = shell_volumes(mesh, &shells.shell_of, shells.members.len());
    let eligible: Vec<bool> = (0..shells.members.len())
        .map(|s| closed[s] && volumes[s] != Int::ZERO)
        .collect();
    let inside = containers(mesh, &shells.shell_of, &shells.members, &eligible);
    let mut faces: Vec<(u32, bool)> = Vec::new();
    for (s, list) in shells.members.iter().enumerate() {
        let changed = list.iter().filter(|&&t| flip[t as usize]).count();
        let reverse = if eligible[s] {
            let want_positive = inside[s].len() % 2 == 0;
            (volumes[s] > Int::ZERO) != want_positive
        } else {
            2 * changed > list.len()
        };
        if reverse {
            for &t in list {
                mesh.triangles[t as usize].swap(1, 2);
            }
        }
        // Count input faces (a split or triangulated face counts once): a face is
        // changed when most of its triangles are.
        faces.clear();
        faces.extend(
            list.iter()
                .map(|&t| (mesh.source_faces[t as usize], flip[t as usize] ^ reverse)),
        );
        faces.sort_unstable();
        let mut size = 0;
        let mut changed = 0;
        for group in faces.chunk_by(|a, b| a.0 == b.0) {
            size += 1;
            if 2 * group.iter().filter(|g| g.1).count() >= group.len() {
                changed += 1;
            }
        }
        if 2 * changed > size {
            report.flipped_shells += 1;
            report.flipped_faces += size - changed;
        } else {
            report.flipped_faces += changed;
        }
    }
}

/// Whether each shell is closed: along every edge, its triangles (after `flip`) run
/// as often one way as the other.
fn closed_shells(shells: &Shells, uses: &[super::edges::Use], flip: &[bool]) -> Vec<bool> {
    let mut closed = vec![true; shells.members.len()];
    let mut per_shell: Vec<(u32, i64)> = Vec::new();
    for run in runs(uses) {
        let dir = |i: usize| run[i].forward ^ flip[run[i].tri as usize];
        let shell = |i: usize| shells.shell_of[run[i].tri as usize];
        if run.len() == 2 && shell(0) == shell(1) && dir(0) != dir(1) {
            continue;
        }
        per_shell.clear();
        for i in 0..run.len() {
            per_shell.push((shell(i), if dir(i) { 1 } else { -1 }));
        }
        per_shell.sort_unstable();
        for group in per_shell.chunk_by(|a, b| a.0 == b.0) {
            if group.iter().map(|g| g.1).sum::<i64>() != 0 {
                closed[group[0].0 as usize] = false;
            }
        }
    }
    closed
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetra(offset: i64, outward: bool) -> (Vec<[i64; 3]>, Vec<[u32; 3]>) {
        let o = offset;
        let v = vec![[o, 0, 0], [o + 6, 0, 0], [o, 6, 0], [o, 0, 6]];
        let mut t = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        if !outward {
            t.iter_mut().for_each(|x| x.swap(1, 2));
        }
        (v, t)
    }

    #[test]
    fn one_reversed_face_and_one_inside_out_shell() {
        let (mut v, mut t) = tetra(0, true);
        t[2].swap(0, 1);
        let (v2, t2) = tetra(10, false);
        v.extend(v2);
        t.extend(t2.iter().map(|x| x.map(|i| i + 4)));
        let mut m = Mesh {
            vertices: v,
            source_faces: (0..t.len() as u32).collect(),
            triangles: t,
            source_vertices: (0..8).collect(),
        };
        let mut r = RepairReport::default();
        orient(&mut m, &mut r);
        assert_eq!((r.flipped_faces, r.flipped_shells), (1, 1));
        assert_eq!(m.volume6(), Int::from(2 * 216));
    }

    #[test]
    fn an_open_shell_keeps_most_of_its_faces() {
        // Three faces of a tetrahedron, one reversed: the two others decide.
        let (v, mut t) = tetra(0, false);
        t.pop();
        t[0].swap(0, 1);
        let mut m = Mesh {
            vertices: v,
            source_faces: vec![0, 1, 2],
            triangles: t.clone(),
            source_vertices: (0..4).collect(),
        };
        let mut r = RepairReport::default();
        orient(&mut m, &mut r);
        assert_eq!((r.flipped_faces, r.flipped_shells), (1, 0));
        assert_eq!(&m.triangles[1..], &t[1..]);
    }
}
