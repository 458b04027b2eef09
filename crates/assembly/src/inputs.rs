//! What a path names: a folder of mesh files (with optional piece folders), one mesh
//! file with one or several objects, or an `assembly.json` manifest (directly, or in
//! the folder). The result is a list of part specifications, not yet read.

use crate::error::LoadError;
use crate::manifest;
use apart_mesh::formats::{read_file, Format};
use apart_mesh::transform::Affine;
use apart_mesh::{Problem, RawObject};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Where one solid comes from.
#[derive(Clone, Debug)]
pub(crate) struct SourceRef {
    /// The mesh file.
    pub path: PathBuf,
    /// One object of a multi-object file, or `None` for all of them merged.
    pub object: Option<usize>,
    /// Applied before snapping.
    pub transform: Affine,
}

/// A part to load.
#[derive(Clone, Debug)]
pub(crate) struct PartSpec {
    pub name: String,
    pub source: PathBuf,
    pub mesh: Option<SourceRef>,
    pub pieces: Vec<SourceRef>,
    /// The name comes from a file or object, not from the user: a mesh holding several
    /// separate solids may become several parts.
    pub splittable: bool,
}

/// The parts to load, with any problem found while looking for them, and files already
/// read (a multi-object file is read to learn its objects).
pub(crate) struct Plan {
    pub name: String,
    pub parts: Vec<PartSpec>,
    pub problems: Vec<Problem>,
    pub preloaded: HashMap<PathBuf, Vec<RawObject>>,
}

fn stem(p: &Path) -> String {
    p.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

fn plain(path: PathBuf) -> SourceRef {
    SourceRef {
        path,
        object: None,
        transform: Affine::IDENTITY,
    }
}

/// Decides what `path` is and lists its parts.
pub(crate) fn plan(path: &Path) -> Result<Plan, LoadError> {
    if !path.exists() {
        return Err(LoadError::NotFound(path.to_path_buf()));
    }
    if path.is_dir() {
        let m = path.join("assembly.json");
        if m.is_file() {
            return from_manifest(&m);
        }
        return from_folder(path);
    }
    let is_json = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"));
    if is_json {
        return from_manifest(path);
    }
    from_file(path)
}

fn from_manifest(path: &Path) -> Result<Plan, LoadError> {
    let text = std::fs::read_to_string(path).map_err(|e| LoadError::Manifest {
        path: path.to_path_buf(),
        detail: format!("cannot read: {e}"),
    })?;
    let dir = path.parent().unwrap_or(Path::new("."));
    let m = manifest::parse(&text, dir).map_err(|detail| LoadError::Manifest {
        path: path.to_path_buf(),
        detail,
    })?;
    let name = m.name.clone().unwrap_or_else(|| {
        dir.canonicalize()
            .ok()
            .and_then(|d| d.file_name().map(|n| n.to_string_lossy().into_owned()))
            .unwrap_or_else(|| "assembly".to_string())
    });
    let parts = m
        .parts
        .into_iter()
        .map(|p| {
            let r = |path: PathBuf| SourceRef {
                path,
                object: None,
                transform: p.transform,
            };
            PartSpec {
                source: p.mesh.clone().unwrap_or_else(|| path.to_path_buf()),
                name: p.name,
                mesh: p.mesh.map(r),
                pieces: p.pieces.into_iter().map(r).collect(),
                splittable: false,
            }
        })
        .collect();
    Ok(Plan {
        name,
        parts,
        problems: Vec::new(),
        preloaded: HashMap::new(),
    })
}

fn list(dir: &Path) -> Result<Vec<PathBuf>, LoadError> {
    let rd = std::fs::read_dir(dir).map_err(|cause| LoadError::Folder {
        path: dir.to_path_buf(),
        cause,
    })?;
    let mut out: Vec<PathBuf> = rd
        .filter_map(|e| {
            e.ok()
                .map(|e| crate::manifest::join(dir, Path::new(&e.file_name())))
        })
        .filter(|p| {
            !p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with('.'))
        })
        .collect();
    out.sort();
    Ok(out)
}

fn mesh_files(dir: &Path) -> Result<Vec<PathBuf>, LoadError> {
    Ok(list(dir)?
        .into_iter()
        .filter(|p| p.is_file() && Format::from_path(p).is_some())
        .collect())
}

fn from_folder(dir: &Path) -> Result<Plan, LoadError> {
    let mut files: HashMap<String, Vec<PathBuf>> = HashMap::new();
    let mut folders: HashMap<String, PathBuf> = HashMap::new();
    for p in list(dir)? {
        if p.is_dir() {
            folders.insert(stem(&p), p);
        } else if Format::from_path(&p).is_some() {
            files.entry(stem(&p)).or_default().push(p);
        }
    }
    let mut problems = Vec::new();
    let mut names: Vec<String> = files.keys().cloned().collect();
    for (name, folder) in &folders {
        if !files.contains_key(name) && !mesh_files(folder)?.is_empty() {
            names.push(name.clone());
        }
    }
    names.sort();
    let mut parts = Vec::new();
    for name in names {
        let mesh = files.get(&name).map(|fs| {
            if fs.len() > 1 {
                let list: Vec<String> = fs.iter().map(|f| f.display().to_string()).collect();
                problems.push(
                    Problem::error(format!(
                        "several files for one part: {}; using the first",
                        list.join(", ")
                    ))
                    .in_part(name.clone()),
                );
            }
            fs[0].clone()
        });
        let pieces = match folders.get(&name) {
            Some(f) => mesh_files(f)?,
            None => Vec::new(),
        };
        let source = mesh
            .clone()
            .or_else(|| folders.get(&name).cloned())
            .unwrap_or_else(|| dir.to_path_buf());
        parts.push(PartSpec {
            name,
            source,
            splittable: pieces.is_empty(),
            mesh: mesh.map(plain),
            pieces: pieces.into_iter().map(plain).collect(),
        });
    }
    if parts.is_empty() {
        return Err(LoadError::NoParts(dir.to_path_buf()));
    }
    let name = dir
        .canonicalize()
        .ok()
        .and_then(|d| d.file_name().map(|n| n.to_string_lossy().into_owned()))
        .unwrap_or_else(|| stem(dir));
    Ok(Plan {
        name,
        parts,
        problems,
        preloaded: HashMap::new(),
    })
}

fn from_file(path: &Path) -> Result<Plan, LoadError> {
    let objects = read_file(path).map_err(|cause| LoadError::Read {
        path: path.to_path_buf(),
        cause,
    })?;
    if objects.is_empty() {
        return Err(LoadError::NoParts(path.to_path_buf()));
    }
    let base = stem(path);
    let mut parts: Vec<PartSpec> = Vec::new();
    let single = objects.len() == 1;
    for (k, o) in objects.iter().enumerate() {
        let mut name = match &o.name {
            Some(n) if !n.trim().is_empty() => n.trim().to_string(),
            _ if single => base.clone(),
            _ => format!("{base}-{k}"),
        };
        if parts.iter().any(|p| p.name == name) {
            let mut i = 2;
            while parts.iter().any(|p| p.name == format!("{name}-{i}")) {
                i += 1;
            }
            name = format!("{name}-{i}");
        }
        parts.push(PartSpec {
            name,
            source: path.to_path_buf(),
            mesh: Some(SourceRef {
                path: path.to_path_buf(),
                object: Some(k),
                transform: Affine::IDENTITY,
            }),
            pieces: Vec::new(),
            splittable: true,
        });
    }
    let mut preloaded = HashMap::new();
    preloaded.insert(path.to_path_buf(), objects);
    Ok(Plan {
        name: base,
        parts,
        problems: Vec::new(),
        preloaded,
    })
}
