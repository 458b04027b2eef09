//! Assemblies from arrays: each part's vertices and triangles are handed to the
//! library's loader as a [`Description`] in memory, which it loads as it would the
//! manifest of those meshes. No file is written, and problems name the part and the
//! element only.

use apart_assembly::{
    load_description, DescribedPart, Description, LoadOptions, Loaded, MeshSource,
};

/// One part's triangle mesh.
pub struct MemMesh {
    name: String,
    vertices: Vec<[f64; 3]>,
    faces: Vec<[u32; 3]>,
}

/// A failure of one part's arrays: the element ("vertex 3", "face 7") and what is
/// wrong.
pub type MeshError = (Option<String>, String);

/// Reads one part's arrays: `vertices` as little-endian `f64` triples, `faces` as
/// little-endian `i64` triples of vertex indices.
pub fn mesh(name: &str, vertices: &[u8], faces: &[u8]) -> Result<MemMesh, MeshError> {
    if vertices.len() % 24 != 0 || faces.len() % 24 != 0 {
        return Err((None, "vertices and faces must have three columns".into()));
    }
    let f = |b: &[u8]| f64::from_le_bytes(b.try_into().unwrap_or([0; 8]));
    let vertices: Vec<[f64; 3]> = vertices
        .chunks_exact(24)
        .map(|c| [f(&c[..8]), f(&c[8..16]), f(&c[16..])])
        .collect();
    if let Some(k) = vertices
        .iter()
        .position(|p| p.iter().any(|x| !x.is_finite()))
    {
        return Err((
            Some(format!("vertex {k}")),
            "the coordinates must be finite numbers".into(),
        ));
    }
    let n = vertices.len();
    let mut tris = Vec::with_capacity(faces.len() / 24);
    for (k, c) in faces.chunks_exact(24).enumerate() {
        let mut t = [0u32; 3];
        for (j, slot) in t.iter_mut().enumerate() {
            let i = i64::from_le_bytes(c[8 * j..8 * j + 8].try_into().unwrap_or([0; 8]));
            *slot = match u32::try_from(i) {
                Ok(i) if (i as usize) < n => i,
                _ => {
                    return Err((
                        Some(format!("face {k}")),
                        format!("vertex index {i} is not one of the {n} vertices"),
                    ))
                }
            };
        }
        tris.push(t);
    }
    if tris.is_empty() {
        return Err((None, "the mesh has no face".into()));
    }
    Ok(MemMesh {
        name: name.to_string(),
        vertices,
        faces: tris,
    })
}

/// Loads the meshes as the parts of an assembly named `name`, in order.
pub fn load(name: String, meshes: Vec<MemMesh>, opts: &LoadOptions) -> Result<Loaded, String> {
    let parts = meshes
        .into_iter()
        .map(|m| {
            DescribedPart::new(
                m.name,
                MeshSource::Arrays {
                    vertices: m.vertices,
                    triangles: m.faces,
                },
            )
        })
        .collect();
    load_description(Description { name, parts }, opts).map_err(|e| e.to_string())
}
