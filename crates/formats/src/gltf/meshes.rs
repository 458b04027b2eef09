//! Meshes made objects: the triangles of their primitives (lists, strips and fans),
//! with the node's world transform applied.

use super::accessors::Data;
use super::{malformed, mesh_label};
use crate::raw::RawObject;
use crate::transform::Affine;
use crate::ReadError;
use gltf::mesh::Mode;

/// True for the modes read: triangle lists, strips and fans.
fn is_triangles(mode: Mode) -> bool {
    matches!(
        mode,
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    )
}

/// Vertices and indices a mesh holds (what one instance of it costs).
pub(super) fn mesh_values(mesh: &gltf::Mesh) -> u64 {
    mesh.primitives()
        .filter(|p| is_triangles(p.mode()))
        .map(|p| {
            let v = p
                .get(&gltf::Semantic::Positions)
                .map_or(0, |a| a.count() as u64);
            let i = p.indices().map_or(0, |a| a.count() as u64);
            v + i
        })
        .sum()
}

/// One instance of `mesh` as an object named `name`, its vertices taken to the world
/// by `to_world`, its faces reversed when that mirrors.
pub(super) fn mesh_object(
    mesh: &gltf::Mesh,
    data: &Data,
    to_world: &Affine,
    name: Option<String>,
) -> Result<RawObject, ReadError> {
    let mut object = RawObject {
        name,
        ..RawObject::default()
    };
    for prim in mesh.primitives() {
        let mode = prim.mode();
        if !is_triangles(mode) {
            continue;
        }
        let what = format!("{}, primitive {}", mesh_label(mesh), prim.index());
        let Some(acc) = prim.get(&gltf::Semantic::Positions) else {
            continue;
        };
        let positions = data.positions(&what, &acc)?;
        let base = object.vertices.len() as u32;
        let n = positions.len() as u32;
        if object.vertices.len() + positions.len() > u32::MAX as usize {
            return Err(malformed(format!(
                "{what}: more than 2^32 vertices in one mesh"
            )));
        }
        object
            .vertices
            .extend(positions.into_iter().map(|p| to_world.apply(p)));
        let idx: Vec<u32> = match prim.indices() {
            Some(acc) => data.indices(&what, &acc)?,
            None => (0..n).collect(),
        };
        if let Some(&bad) = idx.iter().find(|&&i| i >= n) {
            return Err(malformed(format!(
                "{what} refers to vertex {bad}, but the primitive has {n} vertices"
            )));
        }
        if mode == Mode::Triangles && idx.len() % 3 != 0 {
            return Err(malformed(format!(
                "{what}: {} {} for TRIANGLES, not a multiple of 3",
                idx.len(),
                if prim.indices().is_some() {
                    "indices"
                } else {
                    "vertices (without indices)"
                }
            )));
        }
        let mut push = |a: u32, b: u32, c: u32| object.faces.push(&[base + a, base + b, base + c]);
        match mode {
            Mode::Triangles => idx.chunks_exact(3).for_each(|t| push(t[0], t[1], t[2])),
            Mode::TriangleStrip => {
                for k in 2..idx.len() {
                    if k % 2 == 0 {
                        push(idx[k - 2], idx[k - 1], idx[k]);
                    } else {
                        push(idx[k - 1], idx[k - 2], idx[k]);
                    }
                }
            }
            _ => (2..idx.len()).for_each(|k| push(idx[0], idx[k - 1], idx[k])),
        }
    }
    if to_world.det() < 0.0 {
        object.faces.reverse_each();
    }
    Ok(object)
}
