//! glTF 2.0 (`.gltf` with embedded or external buffers, `.glb`), its JSON read with
//! the gltf crate, its data read here. The default scene (or the first) is walked
//! from its roots; every node with a mesh is one object, named after the node (or its
//! mesh), with the node's world transform applied in `f64`. glTF stores transforms as
//! `f32`, so matrix entries within 4 `f32` ulps of 0, ±1/2 or ±1 are snapped to those
//! values. Triangle lists, strips and fans are read; points and lines are skipped. A
//! mirroring transform reverses the faces so that they stay outward.
//!
//! What is refused, with the element named:
//!
//! - external buffers outside the file's folder (absolute paths, `..` climbing above
//!   it, symbolic links leading out), unless [`ReadOptions::allow_outside`]; files that
//!   are not regular or larger than [`crate::MAX_FILE_BYTES`]; URI schemes other than
//!   `data:` and `file:`. Images are never opened (only geometry is read), so their
//!   URIs are not looked at;
//! - a GLB whose header length is not the file's, whose chunks (JSON, then BIN if any)
//!   do not tile the file exactly, or whose BIN chunk is more than 3 bytes (padding)
//!   longer than buffer 0's `byteLength`;
//! - a buffer shorter than its declared `byteLength`, a buffer view beyond it,
//!   an accessor whose `count` elements (at its stride) do not fit its buffer view, an
//!   accessor without a buffer view (all zeros, or sparse) declaring more bytes than
//!   the file and its buffers hold; a `TRIANGLES` primitive whose index (or vertex)
//!   count is not a multiple of 3;
//! - `POSITION` accessors other than `FLOAT` (5126) `VEC3`: quantized positions
//!   (KHR_mesh_quantization) are not read; index accessors other than
//!   `UNSIGNED_BYTE` (5121), `UNSIGNED_SHORT` (5123) or `UNSIGNED_INT` (5125) `SCALAR`;
//! - node hierarchies with a cycle, or expanding (a node listed as a child of several
//!   nodes is instanced under each) to more than [`MAX_NODE_INSTANCES`] nodes,
//!   [`MAX_MESH_INSTANCES`] meshes, or [`MAX_EXPANDED_VALUES`] vertices and indices;
//! - transforms with a value that is not finite, a matrix whose last row is not
//!   `0 0 0 1`, and rotations that are not unit quaternions: a norm further than
//!   [`QUATERNION_TOLERANCE`] from 1 (such as `[0, 0, 0, 0]`, or `1e39` which `f32`
//!   makes infinite) is an error; a norm within it is normalised (`f32` rounding).

mod accessors;
mod buffers;
mod checks;
mod meshes;
#[cfg(test)]
mod tests;
mod transform;

use crate::escape::quoted;
use crate::raw::RawObject;
use crate::transform::{Affine, TOL_F32};
use crate::{Format, ReadError, ReadOptions};
use accessors::Data;
use buffers::load_buffers;
use checks::{check_glb, check_hierarchy, check_position_indices};
use meshes::{mesh_object, mesh_values};
use std::path::Path;
use transform::local_transform;

/// The most node instances a scene may expand to.
pub const MAX_NODE_INSTANCES: usize = 1_000_000;
/// The most mesh instances (objects) a scene may expand to.
pub const MAX_MESH_INSTANCES: usize = 100_000;
/// The most vertices and indices, each mesh counted once per instance, a scene may
/// expand to (as many as a binary STL at the file size limit holds, about 2^28).
pub const MAX_EXPANDED_VALUES: u64 = 1 << 28;
/// How far from 1 the norm of a rotation quaternion may be (it is then normalised).
pub const QUATERNION_TOLERANCE: f64 = 1e-3;

/// A malformed-glTF error with `detail`.
fn malformed(detail: impl Into<String>) -> ReadError {
    ReadError::malformed(Format::Gltf, detail)
}

/// `node 3 ("arm")`, or `node 3`.
fn node_label(node: &gltf::Node) -> String {
    match node.name() {
        Some(n) => format!("node {} ({})", node.index(), quoted(n)),
        None => format!("node {}", node.index()),
    }
}

/// `mesh 0 ("tri")`, or `mesh 0`.
fn mesh_label(mesh: &gltf::Mesh) -> String {
    match mesh.name() {
        Some(n) => format!("mesh {} ({})", mesh.index(), quoted(n)),
        None => format!("mesh {}", mesh.index()),
    }
}

/// Parses a glTF or GLB file; `base_dir` (the file's folder) resolves external buffer
/// files, which must lie inside it unless `options` allow otherwise.
pub fn read(
    bytes: &[u8],
    base_dir: Option<&Path>,
    options: &ReadOptions,
) -> Result<Vec<RawObject>, ReadError> {
    if bytes.starts_with(b"glTF") {
        check_glb(bytes)?;
    }
    let gltf =
        gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| malformed(e.to_string()))?;
    check_position_indices(gltf.document.as_json())?;
    let document = gltf::Document::from_json(gltf.document.into_json())
        .map_err(|e| malformed(e.to_string()))?;
    let buffers = load_buffers(&document, gltf.blob, base_dir, options)?;
    let data = Data {
        budget: bytes.len() as u128 + buffers.iter().map(|b| b.len() as u128).sum::<u128>(),
        buffers: &buffers,
    };
    let mut objects = Vec::new();
    let scene = document
        .default_scene()
        .or_else(|| document.scenes().next());
    let Some(scene) = scene else {
        // No scene: every mesh once, untransformed.
        let values = document
            .meshes()
            .map(|m| mesh_values(&m))
            .fold(0u64, u64::saturating_add);
        if values > MAX_EXPANDED_VALUES {
            return Err(malformed(format!(
                "the meshes hold {values} vertices and indices, more than the limit of {MAX_EXPANDED_VALUES}"
            )));
        }
        for mesh in document.meshes() {
            let name = mesh.name().map(str::to_string);
            objects.push(mesh_object(&mesh, &data, &Affine::IDENTITY, name)?);
        }
        return Ok(objects);
    };
    let roots: Vec<gltf::Node> = scene.nodes().collect();
    let reachable = check_hierarchy(&document, &roots)?;
    // Each reachable node's own transform, checked once however often it is instanced.
    let local: Vec<Affine> = document
        .nodes()
        .map(|n| match reachable[n.index()] {
            true => local_transform(&n),
            false => Ok(Affine::IDENTITY),
        })
        .collect::<Result<_, _>>()?;
    // Depth-first, iteratively (bounded by the check above).
    let mut stack: Vec<(gltf::Node, Affine)> = roots
        .into_iter()
        .rev()
        .map(|n| (n, Affine::IDENTITY))
        .collect();
    while let Some((node, parent)) = stack.pop() {
        let world = parent.then_after(&local[node.index()]).snapped(TOL_F32);
        if let Some(mesh) = node.mesh() {
            let name = node
                .name()
                .or_else(|| mesh.name())
                .map(str::to_string)
                .or_else(|| Some(format!("node{}", node.index())));
            objects.push(mesh_object(&mesh, &data, &world, name)?);
        }
        let children: Vec<_> = node.children().collect();
        for c in children.into_iter().rev() {
            stack.push((c, world));
        }
    }
    Ok(objects)
}
