//! glTF 2.0 (`.gltf` with embedded or external buffers, `.glb`), read with the gltf
//! crate. The default scene (or the first) is walked from its roots; every node with a
//! mesh is one object, named after the node (or its mesh), with the node's world
//! transform applied in `f64`. glTF stores transforms as `f32`, so matrix entries within
//! 4 `f32` ulps of 0, ±1/2 or ±1 are snapped to those values. Triangle lists, strips and
//! fans are read; points and lines are skipped. A mirroring transform reverses the faces
//! so that they stay outward.

use super::{Format, ReadError};
use crate::raw::RawObject;
use crate::transform::{Affine, TOL_F32};
use gltf::mesh::Mode;
use std::path::Path;

fn malformed(detail: impl Into<String>) -> ReadError {
    ReadError::malformed(Format::Gltf, detail)
}

fn local_transform(node: &gltf::Node) -> Affine {
    match node.transform() {
        gltf::scene::Transform::Matrix { matrix: c } => {
            // Column-major.
            let mut rows = [[0.0f64; 4]; 4];
            for (j, col) in c.iter().enumerate() {
                for (i, v) in col.iter().enumerate() {
                    rows[i][j] = *v as f64;
                }
            }
            rows[3] = [0.0, 0.0, 0.0, 1.0];
            Affine::from_rows(rows).unwrap_or_default()
        }
        gltf::scene::Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            let r = Affine::quaternion(rotation.map(|v| v as f64)).unwrap_or_default();
            let s = Affine::scale(scale.map(|v| v as f64));
            Affine::translation(translation.map(|v| v as f64)).then_after(&r.then_after(&s))
        }
    }
}

fn mesh_object(
    mesh: &gltf::Mesh,
    buffers: &[gltf::buffer::Data],
    to_world: &Affine,
    name: Option<String>,
) -> Result<RawObject, ReadError> {
    let mut object = RawObject {
        name,
        ..RawObject::default()
    };
    for prim in mesh.primitives() {
        let mode = prim.mode();
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            continue;
        }
        let reader = prim.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
        let Some(positions) = reader.read_positions() else {
            continue;
        };
        let base = object.vertices.len() as u32;
        object
            .vertices
            .extend(positions.map(|p| to_world.apply(p.map(|v| v as f64))));
        let n = object.vertices.len() as u32 - base;
        let idx: Vec<u32> = match reader.read_indices() {
            Some(i) => i.into_u32().collect(),
            None => (0..n).collect(),
        };
        if let Some(&bad) = idx.iter().find(|&&i| i >= n) {
            return Err(malformed(format!(
                "mesh \"{}\" refers to vertex {bad} of a primitive with {n} vertices",
                mesh.name().unwrap_or("")
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

/// `%XX` escapes of a URI replaced by their bytes.
fn percent_decoded(uri: &str) -> String {
    let b = uri.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        if b[i] == b'%' && i + 2 < b.len() {
            if let (Some(h), Some(l)) = (hex(b[i + 1]), hex(b[i + 2])) {
                out.push((h * 16 + l) as u8);
                i += 3;
                continue;
            }
        }
        out.push(b[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Parses a glTF or GLB file; `base_dir` resolves external buffer files.
pub fn read(bytes: &[u8], base_dir: Option<&Path>) -> Result<Vec<RawObject>, ReadError> {
    let gltf = gltf::Gltf::from_slice(bytes).map_err(|e| malformed(e.to_string()))?;
    let document = gltf.document;
    // External buffers must be regular files (not devices or pipes that never end).
    for b in document.buffers() {
        if let gltf::buffer::Source::Uri(uri) = b.source() {
            if uri.starts_with("data:") {
                continue;
            }
            let path = base_dir
                .unwrap_or(Path::new("."))
                .join(percent_decoded(uri));
            if !path.is_file() {
                return Err(malformed(format!(
                    "buffer \"{uri}\" is not a readable file"
                )));
            }
        }
    }
    let buffers = gltf::import_buffers(&document, base_dir, gltf.blob)
        .map_err(|e| malformed(format!("cannot load buffers: {e}")))?;
    let mut objects = Vec::new();
    let scene = document
        .default_scene()
        .or_else(|| document.scenes().next());
    let Some(scene) = scene else {
        // No scene: every mesh once, untransformed.
        for mesh in document.meshes() {
            let name = mesh.name().map(str::to_string);
            objects.push(mesh_object(&mesh, &buffers, &Affine::IDENTITY, name)?);
        }
        return Ok(objects);
    };
    // Depth-first, iteratively (a malicious file could nest deeply); `path` guards
    // against cycles, which the validator should already have refused.
    let mut stack: Vec<(gltf::Node, Affine, usize)> =
        scene.nodes().map(|n| (n, Affine::IDENTITY, 0)).collect();
    stack.reverse();
    let mut visits = 0usize;
    while let Some((node, parent, depth)) = stack.pop() {
        visits += 1;
        if depth > 256 || visits > 1_000_000 {
            return Err(malformed("node hierarchy too deep or cyclic"));
        }
        let world = parent.then_after(&local_transform(&node)).snapped(TOL_F32);
        if let Some(mesh) = node.mesh() {
            let name = node
                .name()
                .or_else(|| mesh.name())
                .map(str::to_string)
                .or_else(|| Some(format!("node{}", node.index())));
            objects.push(mesh_object(&mesh, &buffers, &world, name)?);
        }
        let children: Vec<_> = node.children().collect();
        for c in children.into_iter().rev() {
            stack.push((c, world, depth + 1));
        }
    }
    Ok(objects)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fmt::Write;

    /// A glTF with one triangle mesh used by two nodes: a parent translated by x+10 with
    /// a child turned a quarter about z.
    pub(crate) fn two_node_gltf() -> Vec<u8> {
        let mut bin = Vec::new();
        for v in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
            for c in v {
                bin.extend_from_slice(&c.to_le_bytes());
            }
        }
        for i in [0u16, 1, 2] {
            bin.extend_from_slice(&i.to_le_bytes());
        }
        bin.extend_from_slice(&[0, 0]);
        let mut b64 = String::new();
        // Minimal base64 encoder for the test data URI.
        const T: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        for chunk in bin.chunks(3) {
            let n = chunk
                .iter()
                .enumerate()
                .fold(0u32, |a, (i, &b)| a | (b as u32) << (16 - 8 * i));
            for k in 0..4 {
                if k <= chunk.len() {
                    b64.push(T[(n >> (18 - 6 * k) & 63) as usize] as char);
                } else {
                    b64.push('=');
                }
            }
        }
        let s = std::f32::consts::FRAC_1_SQRT_2;
        let mut j = String::new();
        write!(
            j,
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],
"nodes":[{{"name":"parent","mesh":0,"translation":[10,0,0],"children":[1]}},
{{"name":"child","mesh":0,"rotation":[0,0,{s},{s}]}}],
"meshes":[{{"name":"tri","primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
"buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{b64}"}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":6}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},
{{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}}]}}"#,
            bin.len()
        )
        .unwrap();
        j.into_bytes()
    }

    #[test]
    fn nodes_with_transforms() {
        let objs = read(&two_node_gltf(), None).unwrap();
        assert_eq!(objs.len(), 2);
        assert_eq!(objs[0].name.as_deref(), Some("parent"));
        assert_eq!(objs[0].vertices[1], [11.0, 0.0, 0.0]);
        // Child: quarter turn about z (exact after snapping), then the parent's shift.
        assert_eq!(objs[1].name.as_deref(), Some("child"));
        assert_eq!(objs[1].vertices[1], [10.0, 1.0, 0.0]);
        assert_eq!(objs[1].vertices[2], [9.0, 0.0, 0.0]);
        assert_eq!(objs[1].faces.get(0), &[0, 1, 2]);
    }

    #[test]
    fn external_buffers_must_be_files() {
        assert_eq!(percent_decoded("a%20b.bin"), "a b.bin");
        assert_eq!(percent_decoded("100%"), "100%");
        let j = String::from_utf8(two_node_gltf()).unwrap();
        let start = j.find("data:").unwrap();
        let end = start + j[start..].find('"').unwrap();
        let devzero = format!("{}/dev/zero{}", &j[..start], &j[end..]);
        let e = read(devzero.as_bytes(), None).unwrap_err().to_string();
        assert!(e.contains("not a readable file"), "{e}");
    }

    #[test]
    fn garbage() {
        assert!(read(b"{\"asset\":", None).is_err());
        assert!(read(b"glTF\x02\0\0\0", None).is_err());
    }
}
