//! What a path names: a folder of mesh files (with optional piece folders), one mesh
//! file with one or several objects, or an `assembly.json` manifest (directly, or in
//! the folder); and what a [`Description`] in memory lists, which a manifest becomes
//! once parsed. The result is a list of part specifications, not yet read (but for
//! meshes already in memory).

use crate::description::{DescribedPart, Description, MeshSource};
use crate::error::LoadError;
use crate::manifest;
use crate::model::Skipped;
use apart_formats::escape::path as escaped;
use apart_formats::transform::Affine;
use apart_formats::{file_kind, read_file_with, Format, Polygons, RawObject, ReadOptions};
use apart_mesh::Problem;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Where the mesh data of one solid comes from.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) enum Origin {
    /// A mesh file.
    File(PathBuf),
    /// The `k`-th mesh given as arrays (held in [`Plan::preloaded`]).
    Arrays(usize),
}

impl Origin {
    /// The file, when the data comes from one.
    pub(crate) fn file(&self) -> Option<&Path> {
        match self {
            Origin::File(p) => Some(p),
            Origin::Arrays(_) => None,
        }
    }
}

/// Where one solid comes from.
#[derive(Clone, Debug)]
pub(crate) struct SourceRef {
    /// The mesh file, or arrays.
    pub origin: Origin,
    /// One object of a multi-object file, or `None` for all of them merged.
    pub object: Option<usize>,
    /// Applied before snapping.
    pub transform: Affine,
}

impl SourceRef {
    /// `problem` naming this source's file, when it comes from one.
    pub(crate) fn locate(&self, problem: Problem) -> Problem {
        match self.origin.file() {
            Some(f) => problem.in_file(f),
            None => problem,
        }
    }
}

/// A part to load.
#[derive(Clone, Debug)]
pub(crate) struct PartSpec {
    pub name: String,
    /// Where the part comes from (see [`crate::Part::source`]; empty for arrays).
    pub source: PathBuf,
    pub mesh: Option<SourceRef>,
    pub pieces: Vec<SourceRef>,
    /// The name comes from a file or object, not from the user: a mesh holding several
    /// separate solids may become several parts.
    pub splittable: bool,
}

/// The parts to load, with any problem found while looking for them, and meshes already
/// in memory (a multi-object file is read to learn its objects; arrays are given).
pub(crate) struct Plan {
    pub name: String,
    /// The assembly's folder, which every mesh file it names must resolve inside (unless
    /// [`crate::LoadOptions::allow_outside`]); `None` for one mesh file named directly
    /// and for a description in memory, whose files the caller named.
    pub root: Option<PathBuf>,
    pub parts: Vec<PartSpec>,
    pub problems: Vec<Problem>,
    pub preloaded: HashMap<Origin, Vec<RawObject>>,
    /// Entries of an assembly folder that are not read, with the reason.
    pub skipped: Vec<Skipped>,
}

fn stem(p: &Path) -> String {
    p.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

fn plain(path: PathBuf) -> SourceRef {
    SourceRef {
        origin: Origin::File(path),
        object: None,
        transform: Affine::IDENTITY,
    }
}

/// What kind of file system entry `meta` describes, when it is not a regular file or a
/// folder: `"a named pipe (FIFO)"`, `"a socket"`, `"a character device"`...
pub(crate) fn special_kind(meta: &std::fs::Metadata) -> Option<&'static str> {
    if meta.is_dir() {
        return None;
    }
    file_kind(&meta.file_type())
}

/// Fails unless `path` (followed through symbolic links) is a regular file: a named
/// pipe would block the reader forever and a device such as `/dev/zero` would be read
/// until the memory runs out. Only the metadata is looked at; nothing is opened.
pub(crate) fn regular_file(path: &Path) -> Result<(), String> {
    match std::fs::metadata(path) {
        Ok(m) if m.is_dir() => Err("is a folder, not a mesh file".to_string()),
        Ok(m) => match special_kind(&m) {
            None => Ok(()),
            Some(kind) => Err(format!(
                "is {kind}, not a regular file; only regular files are read as meshes"
            )),
        },
        // The reader reports missing files and permissions with the system's words.
        Err(_) => Ok(()),
    }
}

/// `path` made absolute with `.` and `..` resolved by their names alone (no symbolic
/// link is followed): where a path that does not exist would lie.
fn lexical(path: &Path) -> PathBuf {
    let abs = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut out = PathBuf::new();
    for c in abs.components() {
        match c {
            std::path::Component::ParentDir => {
                out.pop();
            }
            std::path::Component::CurDir => {}
            c => out.push(c),
        }
    }
    out
}

/// The assembly folder, resolved once for [`inside`].
pub(crate) struct Root {
    /// As given, for messages.
    given: PathBuf,
    /// With every symbolic link resolved.
    real: PathBuf,
    /// Made absolute by name only.
    named: PathBuf,
}

impl Root {
    pub(crate) fn new(dir: &Path) -> Root {
        Root {
            given: dir.to_path_buf(),
            real: dir.canonicalize().unwrap_or_else(|_| lexical(dir)),
            named: lexical(dir),
        }
    }

    /// Fails when `path` resolves outside the folder: an absolute path or one whose
    /// `..` leave it, or a symbolic link (of the file or of a folder on the way) to a
    /// place outside.
    pub(crate) fn inside(&self, path: &Path) -> Result<(), String> {
        let inside = match path.canonicalize() {
            Ok(real) => real.starts_with(&self.real),
            // Not there (the reader will say so), unless its name alone leaves the folder.
            Err(_) => lexical(path).starts_with(&self.named),
        };
        if inside {
            return Ok(());
        }
        let target = path
            .canonicalize()
            .map(|r| format!(" (it resolves to {})", escaped(&r)))
            .unwrap_or_default();
        let folder = match self.given.as_os_str().is_empty() {
            true => Path::new("."),
            false => self.given.as_path(),
        };
        Err(format!(
            "lies outside the assembly folder {}{target}; the files and folders an assembly reads must be inside it (--allow-outside lifts this)",
            escaped(folder)
        ))
    }
}

/// Fails when the manifest at `m` resolves outside `dir` (a symbolic link to a manifest
/// elsewhere), unless `allow_outside`.
fn manifest_inside(m: &Path, dir: &Path, allow_outside: bool) -> Result<(), LoadError> {
    if allow_outside {
        return Ok(());
    }
    Root::new(dir)
        .inside(m)
        .map_err(|detail| LoadError::Manifest {
            path: m.to_path_buf(),
            detail,
        })
}

/// Decides what `path` is and lists its parts.
pub(crate) fn plan(path: &Path, read: &ReadOptions) -> Result<Plan, LoadError> {
    if !path.exists() {
        return Err(LoadError::NotFound(path.to_path_buf()));
    }
    if path.is_dir() {
        let m = path.join("assembly.json");
        if let Ok(meta) = std::fs::metadata(&m) {
            if let Some(kind) = special_kind(&meta) {
                return Err(LoadError::NotAFile { path: m, kind });
            }
            if meta.is_file() {
                manifest_inside(&m, path, read.allow_outside)?;
                return from_manifest(&m);
            }
        }
        return from_folder(path, read.allow_outside);
    }
    if let Some(kind) = std::fs::metadata(path).ok().and_then(|m| special_kind(&m)) {
        return Err(LoadError::NotAFile {
            path: path.to_path_buf(),
            kind,
        });
    }
    let is_json = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"));
    if is_json {
        manifest_inside(
            path,
            path.parent().unwrap_or(Path::new(".")),
            read.allow_outside,
        )?;
        return from_manifest(path);
    }
    from_file(path, read)
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
        .map(|p| DescribedPart {
            name: p.name,
            mesh: p.mesh.map(MeshSource::File),
            pieces: p.pieces.into_iter().map(MeshSource::File).collect(),
            transform: p.transform,
        })
        .collect();
    Ok(from_description(
        Description { name, parts },
        Some(dir.to_path_buf()),
        path,
    ))
}

/// The parts a description lists, each named by the caller (never split into bodies),
/// with its arrays moved into [`Plan::preloaded`]. `root` confines the files it names
/// (a manifest's folder); a part without a mesh has `source` as its source (a
/// manifest's path), a part whose mesh is arrays an empty one.
pub(crate) fn from_description(desc: Description, root: Option<PathBuf>, source: &Path) -> Plan {
    let mut preloaded = HashMap::new();
    let mut source_ref = |mesh: MeshSource, transform: Affine| {
        let origin = match mesh {
            MeshSource::File(p) => Origin::File(p),
            MeshSource::Arrays {
                vertices,
                triangles,
            } => {
                let origin = Origin::Arrays(preloaded.len());
                let faces = Polygons::from_triangles(&triangles);
                drop(triangles);
                let raw = RawObject {
                    name: None,
                    vertices,
                    faces,
                };
                preloaded.insert(origin.clone(), vec![raw]);
                origin
            }
        };
        SourceRef {
            origin,
            object: None,
            transform,
        }
    };
    let parts = desc
        .parts
        .into_iter()
        .map(|p| {
            let part_source = match &p.mesh {
                Some(MeshSource::File(f)) => f.clone(),
                Some(MeshSource::Arrays { .. }) => PathBuf::new(),
                None => source.to_path_buf(),
            };
            PartSpec {
                source: part_source,
                mesh: p.mesh.map(|m| source_ref(m, p.transform)),
                pieces: p
                    .pieces
                    .into_iter()
                    .map(|m| source_ref(m, p.transform))
                    .collect(),
                name: p.name,
                splittable: false,
            }
        })
        .collect();
    Plan {
        name: desc.name,
        root,
        parts,
        problems: Vec::new(),
        preloaded,
        skipped: Vec::new(),
    }
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

/// The mesh files of a piece folder: every entry with a mesh extension that is not a
/// folder. Entries that are not regular files (named pipes, sockets, devices) stay in
/// the list, so that reading reports them by name rather than skipping them silently;
/// nothing is opened here. The other entries are added to `skipped` with the reason.
fn mesh_files(dir: &Path, skipped: &mut Vec<Skipped>) -> Result<Vec<PathBuf>, LoadError> {
    let entries = list(dir)?;
    let gltf = has_gltf(&entries);
    let mut out = Vec::new();
    for p in entries {
        if p.is_dir() {
            skipped.push(Skipped {
                reason:
                    "a folder inside a piece folder (piece folders are not searched further down)"
                        .into(),
                path: p,
            });
        } else if Format::from_path(&p).is_some() {
            out.push(p);
        } else if let Some(reason) = not_a_mesh(&p, gltf) {
            skipped.push(Skipped { path: p, reason });
        }
    }
    Ok(out)
}

/// True when a listing holds a glTF file (whose buffers and images sit beside it).
fn has_gltf(entries: &[PathBuf]) -> bool {
    entries
        .iter()
        .any(|p| Format::from_path(p) == Some(Format::Gltf))
}

/// Why a file without a mesh extension is not read; `None` for the files a glTF file
/// beside it may name (buffers and images), which it reads itself.
fn not_a_mesh(p: &Path, gltf: bool) -> Option<String> {
    let ext = p
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let formats = ".off, .obj, .stl, .ply, .gltf or .glb";
    Some(match ext.as_deref() {
        Some("bin" | "png" | "jpg" | "jpeg" | "webp" | "ktx2") if gltf => return None,
        None => format!("no extension (mesh files are read by their extension: {formats})"),
        Some("json") => {
            "a JSON file not named assembly.json (only assembly.json is read as a manifest)".into()
        }
        Some(e @ ("step" | "stp")) => format!(
            "a CAD file (.{e}), not a mesh: give it to apart as the assembly itself \
             (`apart check FILE`), or convert it with `python -m apart.step FILE OUTDIR` \
             (both need pip install './python[step]'), or export its parts as {formats}"
        ),
        Some(
            e @ ("iges" | "igs" | "sat" | "x_t" | "x_b" | "3dm" | "sldprt" | "sldasm" | "ipt"
            | "iam" | "f3d" | "catpart" | "prt" | "brep" | "fcstd"),
        ) => {
            format!("a CAD file (.{e}), not a mesh: export the part as {formats}")
        }
        Some(_) => format!("not a mesh file (apart reads {formats})"),
    })
}

/// A folder: one part per mesh file, named by its stem. Only metadata is looked at
/// here; an entry with a mesh extension that is not a regular file (a named pipe, a
/// socket, a link to a device) becomes a part whose reading fails with an error naming
/// it, and entries without a mesh extension are ignored whatever they are.
/// A sub-folder that resolves outside the folder (a symbolic link) is not listed: it
/// becomes an error of the part it would hold, unless `allow_outside`.
fn from_folder(dir: &Path, allow_outside: bool) -> Result<Plan, LoadError> {
    let mut files: HashMap<String, Vec<PathBuf>> = HashMap::new();
    let mut folders: HashMap<String, PathBuf> = HashMap::new();
    let mut skipped = Vec::new();
    let mut problems = Vec::new();
    let root = Root::new(dir);
    let entries = list(dir)?;
    let gltf = has_gltf(&entries);
    for p in entries {
        if p.is_dir() {
            if let Err(e) = root
                .inside(&p)
                .or_else(|e| allow_outside.then_some(()).ok_or(e))
            {
                problems.push(
                    Problem::error(format!("its piece folder {} {e}", escaped(&p)))
                        .in_part(stem(&p)),
                );
                continue;
            }
            folders.insert(stem(&p), p);
        } else if Format::from_path(&p).is_some() {
            files.entry(stem(&p)).or_default().push(p);
        } else if let Some(reason) = not_a_mesh(&p, gltf) {
            skipped.push(Skipped { path: p, reason });
        }
    }
    let mut names: Vec<String> = files.keys().cloned().collect();
    let mut piece_lists: HashMap<String, Vec<PathBuf>> = HashMap::new();
    let mut folder_names: Vec<&String> = folders.keys().collect();
    folder_names.sort();
    for name in folder_names {
        let folder = &folders[name];
        let mut inside = Vec::new();
        let pieces = mesh_files(folder, &mut inside)?;
        if pieces.is_empty() && !files.contains_key(name) {
            // Not a piece folder: skipped whole, its entries unnamed.
            skipped.push(Skipped {
                path: folder.clone(),
                reason: "a folder without mesh files (a part's piece folder holds its convex pieces as mesh files)".into(),
            });
            continue;
        }
        skipped.extend(inside);
        if pieces.is_empty() {
            continue;
        }
        if !files.contains_key(name) {
            names.push(name.clone());
        }
        piece_lists.insert(name.clone(), pieces);
    }
    names.sort();
    let mut parts = Vec::new();
    for name in names {
        let mesh = files.get(&name).map(|fs| {
            if fs.len() > 1 {
                let list: Vec<String> = fs.iter().map(|f| escaped(f)).collect();
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
        let pieces = piece_lists.remove(&name).unwrap_or_default();
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
        return Err(match problems.first() {
            // The only parts were behind a refused folder: say why, not "no parts".
            Some(p) => LoadError::Folder {
                path: dir.to_path_buf(),
                cause: std::io::Error::other(p.to_string()),
            },
            None => LoadError::NoParts(dir.to_path_buf()),
        });
    }
    skipped.sort_by(|a, b| a.path.cmp(&b.path));
    let name = dir
        .canonicalize()
        .ok()
        .and_then(|d| d.file_name().map(|n| n.to_string_lossy().into_owned()))
        .unwrap_or_else(|| stem(dir));
    Ok(Plan {
        name,
        root: Some(dir.to_path_buf()),
        parts,
        problems,
        preloaded: HashMap::new(),
        skipped,
    })
}

fn from_file(path: &Path, read: &ReadOptions) -> Result<Plan, LoadError> {
    let objects = read_file_with(path, read).map_err(|cause| LoadError::Read {
        path: path.to_path_buf(),
        cause,
    })?;
    if objects.is_empty() {
        return Err(LoadError::NoParts(path.to_path_buf()));
    }
    let base = stem(path);
    let mut parts: Vec<PartSpec> = Vec::new();
    let single = objects.len() == 1;
    let mut names = Names::default();
    for (k, o) in objects.iter().enumerate() {
        let name = match &o.name {
            Some(n) if !n.trim().is_empty() => n.trim().to_string(),
            _ if single => base.clone(),
            _ => format!("{base}-{k}"),
        };
        let name = names.unique(name).unwrap_or_else(|(_, new)| new);
        parts.push(PartSpec {
            name,
            source: path.to_path_buf(),
            mesh: Some(SourceRef {
                origin: Origin::File(path.to_path_buf()),
                object: Some(k),
                transform: Affine::IDENTITY,
            }),
            pieces: Vec::new(),
            splittable: true,
        });
    }
    let mut preloaded = HashMap::new();
    preloaded.insert(Origin::File(path.to_path_buf()), objects);
    Ok(Plan {
        name: base,
        root: None,
        parts,
        problems: Vec::new(),
        preloaded,
        skipped: Vec::new(),
    })
}

/// Unique names in linear time: a name already taken becomes `name-k` with the smallest
/// `k >= 2` not taken. Each name remembers the next `k` to try, which stays correct
/// because names are never released, so `n` equal names cost `O(n)` rather than the
/// `O(n^2)` probes (each an `O(n)` search) of restarting from 2.
#[derive(Default)]
pub(crate) struct Names {
    taken: std::collections::HashSet<String>,
    next: HashMap<String, u64>,
}

impl Names {
    /// `Ok(name)` when it was free, `Err((name, new))` with the new name otherwise; either
    /// way the returned name is taken from now on.
    pub(crate) fn unique(&mut self, name: String) -> Result<String, (String, String)> {
        if self.taken.insert(name.clone()) {
            return Ok(name);
        }
        let k = self.next.entry(name.clone()).or_insert(2);
        loop {
            let candidate = format!("{name}-{k}");
            *k += 1;
            if self.taken.insert(candidate.clone()) {
                return Err((name, candidate));
            }
        }
    }
}
