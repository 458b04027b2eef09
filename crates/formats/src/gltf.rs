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

use crate::escape::quoted;
use crate::files::{read_regular, resolve_inside};
use crate::raw::RawObject;
use crate::transform::{Affine, TOL_F32};
use crate::{Format, ReadError, ReadOptions};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;
use std::path::{Path, PathBuf};

/// The most node instances a scene may expand to.
pub const MAX_NODE_INSTANCES: usize = 1_000_000;
/// The most mesh instances (objects) a scene may expand to.
pub const MAX_MESH_INSTANCES: usize = 100_000;
/// The most vertices and indices, each mesh counted once per instance, a scene may
/// expand to (as many as a binary STL at the file size limit holds, about 2^28).
pub const MAX_EXPANDED_VALUES: u64 = 1 << 28;
/// How far from 1 the norm of a rotation quaternion may be (it is then normalised).
pub const QUATERNION_TOLERANCE: f64 = 1e-3;

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

fn list(v: &[f32]) -> String {
    let items: Vec<String> = v.iter().map(|x| x.to_string()).collect();
    format!("[{}]", items.join(", "))
}

/// The node's own transform; errors for values that are not finite, a matrix that is
/// not affine, and a rotation that is not a unit quaternion.
fn local_transform(node: &gltf::Node) -> Result<Affine, ReadError> {
    let bad = |what: String| malformed(format!("{}: {what}", node_label(node)));
    match node.transform() {
        gltf::scene::Transform::Matrix { matrix: c } => {
            let flat: Vec<f32> = c.iter().flatten().copied().collect();
            if flat.iter().any(|v| !v.is_finite()) {
                return Err(bad(format!(
                    "its matrix {} has a value that is not a finite number",
                    list(&flat)
                )));
            }
            // Column-major.
            let mut rows = [[0.0f64; 4]; 4];
            for (j, col) in c.iter().enumerate() {
                for (i, v) in col.iter().enumerate() {
                    rows[i][j] = *v as f64;
                }
            }
            let last = rows[3];
            if last
                .iter()
                .zip([0.0, 0.0, 0.0, 1.0])
                .any(|(v, want)| (v - want).abs() > TOL_F32)
            {
                return Err(bad(format!(
                    "its matrix is not affine: the last row is {}, not [0, 0, 0, 1]",
                    list(&last.map(|v| v as f32))
                )));
            }
            rows[3] = [0.0, 0.0, 0.0, 1.0];
            Ok(Affine::from_rows(rows).expect("last row set"))
        }
        gltf::scene::Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            for (what, v) in [
                ("translation", &translation[..]),
                ("rotation", &rotation[..]),
                ("scale", &scale[..]),
            ] {
                if v.iter().any(|x| !x.is_finite()) {
                    return Err(bad(format!(
                        "its {what} {} has a value that is not a finite number",
                        list(v)
                    )));
                }
            }
            let q = rotation.map(|v| v as f64);
            let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
            // Finite: the components are finite f32 values.
            if (norm - 1.0).abs() > QUATERNION_TOLERANCE {
                return Err(bad(format!(
                    "its rotation {} is not a unit quaternion (norm {norm}, which must be 1 within {QUATERNION_TOLERANCE})",
                    list(&rotation)
                )));
            }
            let r = Affine::quaternion(q).expect("a norm near 1");
            let s = Affine::scale(scale.map(|v| v as f64));
            Ok(Affine::translation(translation.map(|v| v as f64)).then_after(&r.then_after(&s)))
        }
    }
}

fn type_name(d: Dimensions) -> &'static str {
    match d {
        Dimensions::Scalar => "SCALAR",
        Dimensions::Vec2 => "VEC2",
        Dimensions::Vec3 => "VEC3",
        Dimensions::Vec4 => "VEC4",
        Dimensions::Mat2 => "MAT2",
        Dimensions::Mat3 => "MAT3",
        Dimensions::Mat4 => "MAT4",
    }
}

fn component_name(t: DataType) -> String {
    let (code, name) = match t {
        DataType::I8 => (5120, "BYTE"),
        DataType::U8 => (5121, "UNSIGNED_BYTE"),
        DataType::I16 => (5122, "SHORT"),
        DataType::U16 => (5123, "UNSIGNED_SHORT"),
        DataType::U32 => (5125, "UNSIGNED_INT"),
        DataType::F32 => (5126, "FLOAT"),
    };
    format!("{code} ({name})")
}

/// Reads accessors, checking every declared size against the data.
struct Data<'a> {
    buffers: &'a [Vec<u8>],
    /// Bytes of the file and its buffers: what an accessor without data may declare.
    budget: u128,
}

impl Data<'_> {
    /// The bytes of `count` elements of `size` bytes at `stride` from `offset` in
    /// buffer view `view`, checked to lie in the view and the view in its buffer.
    fn view_bytes(
        &self,
        what: &str,
        view: &gltf::buffer::View,
        offset: usize,
        count: usize,
        size: usize,
        stride: usize,
    ) -> Result<&[u8], ReadError> {
        let b = view.buffer().index();
        let buffer = self
            .buffers
            .get(b)
            .ok_or_else(|| malformed(format!("{what}: buffer {b} does not exist")))?;
        let (start, len) = (view.offset() as u128, view.length() as u128);
        if start + len > buffer.len() as u128 {
            return Err(malformed(format!(
                "{what}: buffer view {} (bytes {start} to {}) lies beyond the end of buffer {b} ({} bytes)",
                view.index(),
                start + len,
                buffer.len()
            )));
        }
        let data = &buffer[start as usize..(start + len) as usize];
        if count == 0 {
            return Ok(&[]);
        }
        let need = offset as u128 + stride as u128 * (count as u128 - 1) + size as u128;
        if need > len {
            return Err(malformed(format!(
                "{what}: {count} elements of {size} bytes at a stride of {stride} from byte {offset} need {need} bytes, but buffer view {} holds {len}",
                view.index()
            )));
        }
        Ok(&data[offset..need as usize])
    }

    /// Every element of `acc` (`size` bytes each) decoded, sparse substitutions
    /// applied; elements without data are all zero bytes. Every size is checked before
    /// anything is allocated for the elements.
    fn elements<T: Copy>(
        &self,
        what: &str,
        acc: &gltf::Accessor,
        size: usize,
        decode: impl Fn(&[u8]) -> T,
    ) -> Result<Vec<T>, ReadError> {
        let count = acc.count();
        // The dense data (bytes and stride), or `None` for zeros.
        let dense = match acc.view() {
            Some(view) => {
                let stride = view.stride().unwrap_or(size);
                if stride < size {
                    return Err(malformed(format!(
                        "{what}: buffer view {} has a byteStride of {stride}, less than an element ({size} bytes)",
                        view.index()
                    )));
                }
                Some((
                    self.view_bytes(what, &view, acc.offset(), count, size, stride)?,
                    stride,
                ))
            }
            None => {
                if count as u128 * size as u128 > self.budget {
                    return Err(malformed(format!(
                        "{what}: {count} elements without a buffer view, more than the {} bytes of the file and its buffers could describe",
                        self.budget
                    )));
                }
                None
            }
        };
        let sparse = match acc.sparse() {
            None => None,
            Some(sparse) => {
                let n = sparse.count();
                if n > count {
                    return Err(malformed(format!(
                        "{what}: {n} sparse substitutions for {count} elements"
                    )));
                }
                let indices = sparse.indices();
                let isize = indices.index_type().size();
                let ibytes = self.view_bytes(
                    &format!("{what}, sparse indices"),
                    &indices.view(),
                    indices.offset(),
                    n,
                    isize,
                    isize,
                )?;
                let values = sparse.values();
                let vbytes = self.view_bytes(
                    &format!("{what}, sparse values"),
                    &values.view(),
                    values.offset(),
                    n,
                    size,
                    size,
                )?;
                Some((n, isize, ibytes, vbytes))
            }
        };
        let mut out = match dense {
            Some((bytes, stride)) => (0..count)
                .map(|k| decode(&bytes[k * stride..k * stride + size]))
                .collect(),
            None => vec![decode(&vec![0u8; size]); count],
        };
        if let Some((n, isize, ibytes, vbytes)) = sparse {
            for j in 0..n {
                let b = &ibytes[j * isize..(j + 1) * isize];
                let k = match isize {
                    1 => b[0] as usize,
                    2 => u16::from_le_bytes([b[0], b[1]]) as usize,
                    _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize,
                };
                if k >= count {
                    return Err(malformed(format!(
                        "{what}: sparse index {k} is not below the count {count}"
                    )));
                }
                out[k] = decode(&vbytes[j * size..(j + 1) * size]);
            }
        }
        Ok(out)
    }

    fn positions(&self, what: &str, acc: &gltf::Accessor) -> Result<Vec<[f64; 3]>, ReadError> {
        if acc.data_type() != DataType::F32 || acc.dimensions() != Dimensions::Vec3 {
            return Err(malformed(format!(
                "{what}: POSITION accessor {} has componentType {} and type {}; positions must be 5126 (FLOAT) VEC3 (quantized positions are not read)",
                acc.index(),
                component_name(acc.data_type()),
                type_name(acc.dimensions())
            )));
        }
        self.elements(what, acc, 12, |b| {
            let f = |o: usize| f32::from_le_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]]) as f64;
            [f(0), f(4), f(8)]
        })
    }

    fn indices(&self, what: &str, acc: &gltf::Accessor) -> Result<Vec<u32>, ReadError> {
        let size = match acc.data_type() {
            DataType::U8 => 1,
            DataType::U16 => 2,
            DataType::U32 => 4,
            _ => 0,
        };
        if size == 0 || acc.dimensions() != Dimensions::Scalar {
            return Err(malformed(format!(
                "{what}: index accessor {} has componentType {} and type {}; indices must be 5121 (UNSIGNED_BYTE), 5123 (UNSIGNED_SHORT) or 5125 (UNSIGNED_INT) SCALAR",
                acc.index(),
                component_name(acc.data_type()),
                type_name(acc.dimensions())
            )));
        }
        self.elements(what, acc, size, |b| match size {
            1 => b[0] as u32,
            2 => u16::from_le_bytes([b[0], b[1]]) as u32,
            _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        })
    }
}

fn is_triangles(mode: Mode) -> bool {
    matches!(
        mode,
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    )
}

/// Vertices and indices a mesh holds (what one instance of it costs).
fn mesh_values(mesh: &gltf::Mesh) -> u64 {
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

fn mesh_object(
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

/// `%XX` escapes of a URI replaced by their bytes; `None` when they do not make UTF-8.
fn percent_decoded(uri: &str) -> Option<String> {
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
    String::from_utf8(out).ok()
}

/// The file path an external buffer URI names: relative (percent-decoded) or `file:`.
fn uri_path(uri: &str) -> Result<PathBuf, String> {
    let path = if let Some(rest) = uri
        .strip_prefix("file://")
        .or_else(|| uri.strip_prefix("file:"))
    {
        rest
    } else if uri.contains(':') {
        return Err("uses a URI scheme other than data: and file:".into());
    } else {
        uri
    };
    percent_decoded(path)
        .map(PathBuf::from)
        .ok_or_else(|| "has percent escapes that do not make UTF-8 text".into())
}

/// The bytes of a `data:[<media type>];base64,<data>` URI (RFC 2397; glTF embeds
/// buffers so). Decoded here rather than by the gltf crate, whose decoder comes with its
/// `import` feature and that feature's image codecs, which apart never uses.
fn data_uri_bytes(uri: &str) -> Result<Vec<u8>, String> {
    let rest = uri.strip_prefix("data:").unwrap_or(uri);
    let Some((_, payload)) = rest.split_once(";base64,") else {
        return Err("a data: URI without \";base64,\" (only base64 data is read)".into());
    };
    base64_decode(payload)
}

/// Standard base64 (RFC 4648 §4: `A–Z a–z 0–9 + /`), the trailing `=` padding optional.
fn base64_decode(text: &str) -> Result<Vec<u8>, String> {
    let body = text.strip_suffix("==").or_else(|| text.strip_suffix('='));
    let body = body.unwrap_or(text).as_bytes();
    if body.len() % 4 == 1 {
        return Err(format!(
            "base64 data of {} characters, which no byte count gives",
            text.len()
        ));
    }
    let value = |(at, c): (usize, &u8)| -> Result<u32, String> {
        Ok(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => {
                return Err(format!(
                    "base64 data has {} at character {at}",
                    quoted(&String::from_utf8_lossy(&[*c]))
                ))
            }
        } as u32)
    };
    let mut out = Vec::with_capacity(body.len() / 4 * 3 + 2);
    for (k, chunk) in body.chunks(4).enumerate() {
        let mut n = 0u32;
        for (j, c) in chunk.iter().enumerate() {
            n |= value((4 * k + j, c))? << (18 - 6 * j);
        }
        // 4 characters give 3 bytes, 3 give 2, 2 give 1.
        out.extend_from_slice(&n.to_be_bytes()[1..chunk.len()]);
    }
    Ok(out)
}

/// Every buffer's bytes: the GLB binary chunk, a `data:` URI, or a regular file in
/// `base_dir` (see [`resolve_inside`]); each at least its declared `byteLength`.
fn load_buffers(
    document: &gltf::Document,
    mut blob: Option<Vec<u8>>,
    base_dir: Option<&Path>,
    options: &ReadOptions,
) -> Result<Vec<Vec<u8>>, ReadError> {
    let mut out = Vec::new();
    for b in document.buffers() {
        let i = b.index();
        let mut data = match b.source() {
            gltf::buffer::Source::Bin => blob.take().ok_or_else(|| {
                malformed(format!(
                    "buffer {i} is the binary chunk, which the file does not have"
                ))
            })?,
            gltf::buffer::Source::Uri(uri) if uri.starts_with("data:") => {
                data_uri_bytes(uri).map_err(|why| malformed(format!("buffer {i}: {why}")))?
            }
            gltf::buffer::Source::Uri(uri) => {
                let what = format!("buffer {i} ({})", quoted(uri));
                let path = uri_path(uri).map_err(|why| malformed(format!("{what} {why}")))?;
                let Some(dir) = base_dir else {
                    return Err(malformed(format!(
                        "{what} is an external file, but the folder to find it in is unknown"
                    )));
                };
                let referenced = |cause: ReadError| ReadError::Referenced {
                    what: what.clone(),
                    cause: Box::new(cause),
                };
                let file = resolve_inside(dir, &path, options.allow_outside).map_err(referenced)?;
                read_regular(&file).map_err(referenced)?
            }
        };
        if data.len() < b.length() {
            return Err(malformed(format!(
                "buffer {i} holds {} bytes, fewer than its byteLength {}",
                data.len(),
                b.length()
            )));
        }
        // The BIN chunk is the buffer padded to a multiple of 4 bytes, no more.
        if matches!(b.source(), gltf::buffer::Source::Bin) && data.len() > b.length() + 3 {
            return Err(malformed(format!(
                "buffer {i} is the BIN chunk of {} bytes, more than its byteLength {} and at most 3 bytes of padding",
                data.len(),
                b.length()
            )));
        }
        // Buffer views are checked against the declared length.
        data.truncate(b.length());
        out.push(data);
    }
    Ok(out)
}

/// Checks the hierarchy below `roots` before it is walked: no cycle, and at most
/// [`MAX_NODE_INSTANCES`] nodes, [`MAX_MESH_INSTANCES`] meshes and
/// [`MAX_EXPANDED_VALUES`] vertices and indices once every node is instanced under
/// each parent that lists it. Counts are summed bottom-up over the graph (each node
/// once), so a small file describing billions of instances is refused in linear time.
/// Returns which nodes are reachable from the roots.
fn check_hierarchy(
    document: &gltf::Document,
    roots: &[gltf::Node],
) -> Result<Vec<bool>, ReadError> {
    let nodes: Vec<gltf::Node> = document.nodes().collect();
    // Per node: (nodes, meshes, values) in the subtree it expands to, saturating.
    let mut below: Vec<Option<[u64; 3]>> = vec![None; nodes.len()];
    let mut on_path = vec![false; nodes.len()];
    for root in roots {
        // Iterative depth-first search: (node, next child to visit).
        let mut stack: Vec<(usize, usize)> = Vec::new();
        if below[root.index()].is_none() {
            stack.push((root.index(), 0));
            on_path[root.index()] = true;
        }
        while let Some(&mut (n, ref mut next)) = stack.last_mut() {
            let child = nodes[n].children().nth(*next);
            *next += 1;
            match child {
                Some(c) => {
                    let c = c.index();
                    if on_path[c] {
                        return Err(malformed(format!(
                            "{} lists {} as a child, which is also its ancestor: the node hierarchy has a cycle",
                            node_label(&nodes[n]),
                            node_label(&nodes[c])
                        )));
                    }
                    if below[c].is_none() {
                        on_path[c] = true;
                        stack.push((c, 0));
                    }
                }
                None => {
                    let node = &nodes[n];
                    let mut sum = [1, 0, 0];
                    if let Some(m) = node.mesh() {
                        sum[1] = 1;
                        sum[2] = mesh_values(&m);
                    }
                    for c in node.children() {
                        let b = below[c.index()].expect("children are done first");
                        for k in 0..3 {
                            sum[k] = sum[k].saturating_add(b[k]);
                        }
                    }
                    below[n] = Some(sum);
                    on_path[n] = false;
                    stack.pop();
                }
            }
        }
    }
    let mut total = [0u64; 3];
    for r in roots {
        let b = below[r.index()].expect("every root was walked");
        for k in 0..3 {
            total[k] = total[k].saturating_add(b[k]);
        }
    }
    let saturated = |v: u64| {
        if v == u64::MAX {
            "more than 2^64".to_string()
        } else {
            v.to_string()
        }
    };
    let why = "a node listed as the child of several nodes is instanced under each";
    if total[0] > MAX_NODE_INSTANCES as u64 {
        return Err(malformed(format!(
            "the scene's node hierarchy expands to {} node instances ({why}), more than the limit of {MAX_NODE_INSTANCES}",
            saturated(total[0])
        )));
    }
    if total[1] > MAX_MESH_INSTANCES as u64 {
        return Err(malformed(format!(
            "the scene's node hierarchy expands to {} mesh instances ({why}), more than the limit of {MAX_MESH_INSTANCES}",
            saturated(total[1])
        )));
    }
    if total[2] > MAX_EXPANDED_VALUES {
        return Err(malformed(format!(
            "the scene's meshes, each counted once per instance ({why}), hold {} vertices and indices, more than the limit of {MAX_EXPANDED_VALUES}",
            saturated(total[2])
        )));
    }
    Ok(below.iter().map(Option::is_some).collect())
}

/// Checks that every primitive's `POSITION` names an accessor that exists (the gltf
/// crate's validation indexes it without checking, and panics).
fn check_position_indices(root: &gltf::json::Root) -> Result<(), ReadError> {
    let positions = gltf::json::validation::Checked::Valid(gltf::Semantic::Positions);
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            if let Some(a) = prim.attributes.get(&positions) {
                if a.value() >= root.accessors.len() {
                    return Err(malformed(format!(
                        "mesh {m}, primitive {p}: POSITION is accessor {}, but there are only {} accessors",
                        a.value(),
                        root.accessors.len()
                    )));
                }
            }
        }
    }
    Ok(())
}

/// The name of a GLB chunk type, as a message shows it.
fn chunk_type(ty: &[u8]) -> String {
    match ty {
        b"JSON" => "JSON".to_string(),
        b"BIN\0" => "BIN".to_string(),
        _ => quoted(&String::from_utf8_lossy(ty)),
    }
}

/// Checks the GLB container before the gltf crate reads it: the header's length is the
/// file's, and the chunks (JSON first, then BIN if any, then any others) tile the rest
/// exactly.
fn check_glb(bytes: &[u8]) -> Result<(), ReadError> {
    let word =
        |at: usize| u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    if bytes.len() < 12 {
        return Err(malformed(format!(
            "the GLB file has {} bytes, fewer than its 12-byte header",
            bytes.len()
        )));
    }
    let declared = word(8) as usize;
    if declared != bytes.len() {
        return Err(malformed(format!(
            "the GLB header declares {declared} bytes but the file has {}",
            bytes.len()
        )));
    }
    let mut at = 12;
    for k in 0.. {
        let left = bytes.len() - at;
        if left == 0 {
            break;
        }
        if left < 8 {
            let after = match k {
                0 => "the header".to_string(),
                k => format!("chunk {}", k - 1),
            };
            return Err(malformed(format!(
                "{left} bytes at byte offset {at}, after {after}, are too few for a chunk header (8 bytes)"
            )));
        }
        let (length, ty) = (word(at) as usize, &bytes[at + 4..at + 8]);
        let what = format!("GLB chunk {k} ({}) at byte offset {at}", chunk_type(ty));
        if k == 0 && ty != b"JSON" {
            return Err(malformed(format!("{what}: the first chunk must be JSON")));
        }
        if length > left - 8 {
            return Err(malformed(format!(
                "{what} declares {length} bytes of data, but only {} are left in the file",
                left - 8
            )));
        }
        at += 8 + length;
    }
    Ok(())
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::fmt::Write;

    /// Positions of one triangle (36 bytes), its u16 indices (6 bytes) and padding.
    fn triangle_bin() -> Vec<u8> {
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
        bin
    }

    #[test]
    fn base64_data_decodes_with_or_without_padding() {
        for n in 0..40usize {
            let bin: Vec<u8> = (0..n).map(|k| (k * 37 + 11) as u8).collect();
            let text = apart_testkit::base64(&bin);
            assert_eq!(base64_decode(&text).unwrap(), bin, "{text}");
            assert_eq!(base64_decode(text.trim_end_matches('=')).unwrap(), bin);
            let uri = format!("data:application/octet-stream;base64,{text}");
            assert_eq!(data_uri_bytes(&uri).unwrap(), bin);
        }
        assert_eq!(base64_decode("TWFu").unwrap(), b"Man");
        assert_eq!(base64_decode("+/+/").unwrap(), [0xfb, 0xff, 0xbf]);
        let e = base64_decode("TW-u").unwrap_err();
        assert!(e.contains("\"-\" at character 2"), "{e}");
        assert!(base64_decode("TWFuT").unwrap_err().contains("5 characters"));
        assert!(data_uri_bytes("data:text/plain,hello")
            .unwrap_err()
            .contains(";base64,"));
    }

    const ACCESSORS: &str = r#"[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]"#;

    /// A glTF of the triangle mesh with the given nodes, scene roots, accessors and
    /// buffer URI (`None`: the data inline).
    fn doc(nodes: &str, roots: &str, accessors: &str, uri: Option<&str>) -> Vec<u8> {
        let bin = triangle_bin();
        let uri = match uri {
            Some(u) => u.to_string(),
            None => format!(
                "data:application/octet-stream;base64,{}",
                apart_testkit::base64(&bin)
            ),
        };
        let mut j = String::new();
        write!(
            j,
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":{roots}}}],
"nodes":{nodes},
"meshes":[{{"name":"tri","primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
"buffers":[{{"byteLength":{},"uri":"{uri}"}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":6}}],
"accessors":{accessors}}}"#,
            bin.len()
        )
        .unwrap();
        j.into_bytes()
    }

    /// One node with the mesh and the given extra properties.
    fn one_node(props: &str) -> Vec<u8> {
        let sep = if props.is_empty() { "" } else { "," };
        doc(
            &format!(r#"[{{"name":"n","mesh":0{sep}{props}}}]"#),
            "[0]",
            ACCESSORS,
            None,
        )
    }

    fn err(bytes: &[u8]) -> String {
        read(bytes, None, &ReadOptions::default())
            .unwrap_err()
            .to_string()
    }

    /// A glTF with one triangle mesh used by two nodes: a parent translated by x+10 with
    /// a child turned a quarter about z.
    pub(crate) fn two_node_gltf() -> Vec<u8> {
        let s = std::f32::consts::FRAC_1_SQRT_2;
        doc(
            &format!(
                r#"[{{"name":"parent","mesh":0,"translation":[10,0,0],"children":[1]}},
{{"name":"child","mesh":0,"rotation":[0,0,{s},{s}]}}]"#
            ),
            "[0]",
            ACCESSORS,
            None,
        )
    }

    #[test]
    fn nodes_with_transforms() {
        let objs = read(&two_node_gltf(), None, &ReadOptions::default()).unwrap();
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
    fn percent_escapes() {
        assert_eq!(percent_decoded("a%20b.bin").unwrap(), "a b.bin");
        assert_eq!(percent_decoded("100%").unwrap(), "100%");
        assert_eq!(percent_decoded("%2e%2e/x").unwrap(), "../x");
        assert!(percent_decoded("%ff").is_none());
    }

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("apart-gltf-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(d.join("model")).unwrap();
        d
    }

    #[test]
    fn external_buffers_stay_in_the_folder() {
        let d = scratch("outside");
        let dir = d.join("model");
        std::fs::write(dir.join("tri.bin"), triangle_bin()).unwrap();
        // A secret outside the folder, with a control character.
        let mut secret = b"SECRET\x1b[2J".to_vec();
        secret.resize(44, b'!');
        std::fs::write(d.join("secret.bin"), &secret).unwrap();
        let nodes = r#"[{"name":"n","mesh":0}]"#;
        let safe = ReadOptions::default();
        let load = |uri: &str, options: &ReadOptions| {
            read(
                &doc(nodes, "[0]", ACCESSORS, Some(uri)),
                Some(&dir),
                options,
            )
        };
        let objs = load("tri.bin", &safe).unwrap();
        assert_eq!(objs[0].vertices[1], [1.0, 0.0, 0.0]);
        assert!(load("./sub/../tri.bin", &safe).is_err()); // no folder "sub"
        assert!(load("tri%2ebin", &safe).is_ok());
        for (uri, why) in [
            ("../secret.bin", "component leaves the folder"),
            ("%2e%2e/secret.bin", "component leaves the folder"),
            ("/etc/passwd", "absolute path"),
            ("file:///etc/passwd", "absolute path"),
        ] {
            let e = load(uri, &safe).unwrap_err().to_string();
            assert!(e.starts_with("buffer 0 (\""), "{e}");
            assert!(
                e.contains(why) && e.contains("--allow-outside"),
                "{uri}: {e}"
            );
        }
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink("../secret.bin", dir.join("link.bin")).unwrap();
            let e = load("link.bin", &safe).unwrap_err().to_string();
            assert!(e.contains("symbolic link"), "{e}");
            std::os::unix::fs::symlink("/dev/zero", dir.join("zero.bin")).unwrap();
            let lifted = ReadOptions::default().allow_outside(true);
            let e = load("zero.bin", &lifted).unwrap_err().to_string();
            assert!(e.contains("character device, not a regular file"), "{e}");
            let e = load("/dev/zero", &lifted).unwrap_err().to_string();
            assert!(e.contains("character device"), "{e}");
        }
        // Lifted: the outside file is read; its bytes never reach a message.
        let lifted = ReadOptions::default().allow_outside(true);
        match load("../secret.bin", &lifted) {
            Ok(objs) => assert_eq!(objs.len(), 1),
            Err(e) => {
                let e = e.to_string();
                assert!(!e.contains("SECRET") && !e.contains('\x1b'), "{e}");
            }
        }
        let e = load("http://example.com/a.bin", &safe)
            .unwrap_err()
            .to_string();
        assert!(e.contains("URI scheme"), "{e}");
        // Without a folder, an external buffer is an error, not a path from the
        // current directory.
        let e = read(&doc(nodes, "[0]", ACCESSORS, Some("tri.bin")), None, &safe)
            .unwrap_err()
            .to_string();
        assert!(e.contains("folder to find it in is unknown"), "{e}");
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn node_hierarchies_are_bounded() {
        // 17 levels each listing the next level twice, the mesh at the bottom:
        // 2^17 = 131,072 instances from a file of a few hundred bytes.
        let mut nodes: Vec<String> = (0..17)
            .map(|k| format!(r#"{{"children":[{},{}]}}"#, k + 1, k + 1))
            .collect();
        nodes.push(r#"{"mesh":0}"#.into());
        let e = err(&doc(
            &format!("[{}]", nodes.join(",")),
            "[0]",
            ACCESSORS,
            None,
        ));
        assert!(
            e.contains("expands to 131072 mesh instances")
                && e.contains("more than the limit of 100000"),
            "{e}"
        );
        // Empty nodes, 60 levels: counted without walking them.
        let mut nodes: Vec<String> = (0..60)
            .map(|k| format!(r#"{{"children":[{},{}]}}"#, k + 1, k + 1))
            .collect();
        nodes.push("{}".into());
        let t = std::time::Instant::now();
        let e = err(&doc(
            &format!("[{}]", nodes.join(",")),
            "[0]",
            ACCESSORS,
            None,
        ));
        assert!(e.contains("node instances"), "{e}");
        assert!(t.elapsed().as_secs() < 5);
        // A few shared instances are fine.
        let objs = read(
            &doc(
                r#"[{"children":[1,1,1]},{"mesh":0}]"#,
                "[0, 0]",
                ACCESSORS,
                None,
            ),
            None,
            &ReadOptions::default(),
        )
        .unwrap();
        assert_eq!(objs.len(), 6);
        // Cycles, through two nodes and through one.
        for nodes in [
            r#"[{"children":[1]},{"mesh":0,"children":[0]}]"#,
            r#"[{"mesh":0,"children":[0]}]"#,
        ] {
            let e = err(&doc(nodes, "[0]", ACCESSORS, None));
            assert!(e.contains("has a cycle") && e.contains("node 0"), "{e}");
        }
    }

    #[test]
    fn transforms_must_be_finite_and_rotations_unit() {
        for (props, want) in [
            (r#""rotation":[0,0,0,0]"#, "not a unit quaternion (norm 0,"),
            (r#""rotation":[1e39,0,0,1]"#, "not a finite number"),
            (r#""rotation":[0,0,0,2]"#, "not a unit quaternion (norm 2,"),
            (r#""rotation":[0,0,1e30,1e30]"#, "not a unit quaternion"),
            (r#""translation":[1e39,0,0]"#, "translation"),
            (r#""scale":[1,-1e39,1]"#, "scale"),
            (
                r#""matrix":[1,0,0,0, 0,1,0,0, 0,0,1,0, 1e39,0,0,1]"#,
                "not a finite number",
            ),
            (
                r#""matrix":[1,0,0,0.5, 0,1,0,0, 0,0,1,0, 0,0,0,1]"#,
                "not affine",
            ),
        ] {
            // 1e39 is read as an infinite f32.
            let e = err(&one_node(props));
            assert!(
                e.contains(want) && e.contains("node 0 (\"n\"): its "),
                "{props}: {e}"
            );
        }
        // Near-unit quaternions (f32 rounding) are normalised.
        let o = read(
            &one_node(r#""rotation":[0,0,0,1.0004]"#),
            None,
            &ReadOptions::default(),
        )
        .unwrap();
        assert_eq!(o[0].vertices[1], [1.0, 0.0, 0.0]);
    }

    #[test]
    fn accessor_types_are_checked() {
        let node = r#"[{"mesh":0}]"#;
        for (accessors, want) in [
            (
                ACCESSORS.replace("5126", "5121"),
                "POSITION accessor 0 has componentType 5121 (UNSIGNED_BYTE) and type VEC3",
            ),
            (
                ACCESSORS.replace("\"VEC3\"", "\"VEC2\""),
                "componentType 5126 (FLOAT) and type VEC2",
            ),
            (
                ACCESSORS.replace("5123", "5126"),
                "index accessor 1 has componentType 5126 (FLOAT) and type SCALAR",
            ),
            (
                ACCESSORS.replace("5123", "5122"),
                "index accessor 1 has componentType 5122 (SHORT)",
            ),
        ] {
            let e = err(&doc(node, "[0]", &accessors, None));
            assert!(
                e.contains(want) && e.contains("mesh 0 (\"tri\"), primitive 0"),
                "{e}"
            );
        }
    }

    #[test]
    fn declared_sizes_are_checked() {
        let node = r#"[{"mesh":0}]"#;
        for (accessors, want) in [
            // Four billion positions: refused before the views are looked at.
            (
                ACCESSORS.replace("\"count\":3,\"type\":\"VEC3\"", "\"count\":4000000000,\"type\":\"VEC3\""),
                "hold 4000000003 vertices and indices, more than the limit of 268435456",
            ),
            // A hundred million positions in a 36-byte view.
            (
                ACCESSORS.replace("\"count\":3,\"type\":\"VEC3\"", "\"count\":100000000,\"type\":\"VEC3\""),
                "100000000 elements of 12 bytes at a stride of 12 from byte 0 need 1200000000 bytes, but buffer view 0 holds 36",
            ),
            (
                ACCESSORS.replace("\"count\":3,\"type\":\"SCALAR\"", "\"count\":4,\"type\":\"SCALAR\""),
                "need 8 bytes, but buffer view 1 holds 6",
            ),
            // Sparse without a buffer view: zeros, but not more than the file could
            // describe.
            (
                ACCESSORS.replace("\"bufferView\":0,", "").replace(
                    "\"count\":3,\"type\":\"VEC3\"",
                    r#""count":100000000,"type":"VEC3","sparse":{"count":1,"indices":{"bufferView":1,"componentType":5123},"values":{"bufferView":0}}"#,
                ),
                "100000000 elements without a buffer view",
            ),
        ] {
            let e = err(&doc(node, "[0]", &accessors, None));
            assert!(e.contains(want), "{e}");
        }
        // Without a scene, every mesh once: bounded too.
        let j = String::from_utf8(doc(
            node,
            "[0]",
            &ACCESSORS.replace(
                "\"count\":3,\"type\":\"VEC3\"",
                "\"count\":200000000,\"type\":\"VEC3\"",
            ),
            None,
        ))
        .unwrap();
        let no_scene = j.replace("\"scene\":0,\"scenes\":[{\"nodes\":[0]}],", "");
        let three = no_scene.replace(
            r#"[{"attributes":{"POSITION":0},"indices":1}]"#,
            r#"[{"attributes":{"POSITION":0}},{"attributes":{"POSITION":0}}]"#,
        );
        let e = err(three.as_bytes());
        assert!(
            e.contains("the meshes hold 400000000 vertices and indices"),
            "{e}"
        );
        let t = std::time::Instant::now();
        let e = err(no_scene.as_bytes());
        assert!(
            e.contains("need 2400000000 bytes, but buffer view 0 holds 36"),
            "{e}"
        );
        assert!(t.elapsed().as_millis() < 500);
        // A buffer view beyond its buffer, and a buffer shorter than its byteLength.
        let j = String::from_utf8(doc(node, "[0]", ACCESSORS, None)).unwrap();
        let e = err(j
            .replace(
                "\"byteOffset\":36,\"byteLength\":6",
                "\"byteOffset\":36,\"byteLength\":600",
            )
            .as_bytes());
        assert!(
            e.contains("lies beyond the end of buffer 0 (44 bytes)"),
            "{e}"
        );
        let e = err(j
            .replace("\"byteLength\":44", "\"byteLength\":4000000000")
            .as_bytes());
        assert!(e.contains("fewer than its byteLength 4000000000"), "{e}");
    }

    #[test]
    fn sparse_accessors() {
        // Three zero positions, the second and third replaced by the view's first two.
        let accessors = r#"[{"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,0,0],"sparse":{"count":2,"indices":{"bufferView":1,"componentType":5123,"byteOffset":2},"values":{"bufferView":0}}},
{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]"#;
        let o = read(
            &doc(r#"[{"mesh":0}]"#, "[0]", accessors, None),
            None,
            &ReadOptions::default(),
        )
        .unwrap();
        assert_eq!(
            o[0].vertices,
            vec![[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]
        );
    }

    #[test]
    fn garbage() {
        assert!(read(b"{\"asset\":", None, &ReadOptions::default()).is_err());
        assert!(read(b"glTF\x02\0\0\0", None, &ReadOptions::default()).is_err());
        // Names quoted in messages are escaped.
        let j = String::from_utf8(doc(
            r#"[{"mesh":0}]"#,
            "[0]",
            &ACCESSORS.replace("5126", "5121"),
            None,
        ))
        .unwrap();
        let e = err(j
            .replace("\"name\":\"tri\"", "\"name\":\"t\\u001b[2Jri\"")
            .as_bytes());
        assert!(
            e.contains("mesh 0 (\"t\\x1b[2Jri\")") && !e.contains('\x1b'),
            "{e}"
        );
    }
}
