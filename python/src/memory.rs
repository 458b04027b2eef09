//! Assemblies from arrays: each part's triangles are written as an OFF file (every
//! `f64` in its shortest exact decimal, so nothing is rounded) beside an
//! `assembly.json` manifest in a temporary folder, which the library's loader reads as
//! any manifest. Paths of that folder never reach the user: problems name the part.

use apart_assembly::{LoadOptions, Loaded};
use apart_formats::Polygons;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

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
    let f64s = |b: &[u8]| -> Vec<f64> {
        b.chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
            .collect()
    };
    let v = f64s(vertices);
    let vertices: Vec<[f64; 3]> = v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
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

/// A temporary folder, removed when dropped.
struct TempDir(PathBuf);

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Loads the meshes as the parts of an assembly named `name`, in order.
pub fn load(name: &str, meshes: &[MemMesh], opts: &LoadOptions) -> Result<Loaded, String> {
    static COUNT: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "apart-python-{}-{}",
        std::process::id(),
        COUNT.fetch_add(1, Ordering::Relaxed)
    ));
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let guard = TempDir(dir.clone());
    let mut parts = Vec::new();
    for (k, m) in meshes.iter().enumerate() {
        let file = format!("part{k}.off");
        let mut bytes = Vec::new();
        let polygons = Polygons::from_triangles(&m.faces);
        apart_formats::off::write(&mut bytes, &m.vertices, &polygons)
            .map_err(|e| format!("part \"{}\": {e}", m.name))?;
        std::fs::write(dir.join(&file), bytes)
            .map_err(|e| format!("cannot write a temporary file: {e}"))?;
        parts.push(serde_json::json!({"name": m.name, "mesh": file}));
    }
    let manifest = dir.join("assembly.json");
    let text = serde_json::json!({"name": name, "parts": parts}).to_string();
    std::fs::write(&manifest, text).map_err(|e| format!("cannot write a temporary file: {e}"))?;
    let loaded = apart_assembly::load(&manifest, opts).map_err(|e| hide(&e.to_string(), &dir))?;
    let loaded = forget_files(loaded, &dir);
    drop(guard);
    Ok(loaded)
}

/// `text` without the temporary folder's path (its files become their part's number).
fn hide(text: &str, dir: &Path) -> String {
    let d = dir.display().to_string();
    text.replace(&format!("{d}/"), "").replace(&d, "")
}

/// The loaded assembly with no path of the temporary folder: problems and repairs name
/// no file, parts have no source.
fn forget_files(mut loaded: Loaded, dir: &Path) -> Loaded {
    for p in &mut loaded.problems {
        if p.file.as_deref().is_some_and(|f| f.starts_with(dir)) {
            p.file = None;
        }
        p.message = hide(&p.message, dir);
    }
    for r in &mut loaded.repairs {
        r.file = PathBuf::new();
    }
    for part in &mut loaded.assembly.parts {
        part.source = PathBuf::new();
    }
    loaded
}
