//! Mesh files of apart: the readers and writers of every format, and the
//! floating-point objects they produce and consume, before anything is snapped.
//!
//! Readers return [`RawObject`]s (an optional name, `f64` vertices in input units, and
//! [`Polygons`]); writers take vertices and polygons. The affine input transforms
//! ([`transform`]: the glTF node transforms, which the glTF reader applies, and the
//! manifest's, which apart-assembly's loader applies) work in `f64`, before snapping.
//! The solid model built from a `RawObject` on the integer grid, its repair and its
//! validation are apart-mesh's; this crate knows nothing of grids.
//!
//! ```
//! let off = b"OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";
//! let objects = apart_formats::read_bytes(off, apart_formats::Format::Off, None).unwrap();
//! assert_eq!(objects.len(), 1);
//! assert_eq!(objects[0].vertices[3], [0.0, 0.0, 1.0]);
//! assert_eq!(objects[0].faces.get(0), &[0, 2, 1]);
//! let mut written = Vec::new();
//! apart_formats::off::write(&mut written, &objects[0].vertices, &objects[0].faces).unwrap();
//! let again = apart_formats::read_bytes(&written, apart_formats::Format::Off, None).unwrap();
//! assert_eq!(again[0], objects[0]);
//! ```
//!
//! | format | read | write | objects |
//! |---|---|---|---|
//! | OFF (`.off`) | ASCII, own parser | yes | one |
//! | OBJ (`.obj`) | tobj | yes | one per `o`/`g` group |
//! | STL (`.stl`) | ASCII and binary, own parser | binary (stl_io) | one |
//! | PLY (`.ply`) | ASCII and binary (ply-rs-bw) | no | one |
//! | glTF (`.gltf`, `.glb`) | gltf | no | one per mesh node, transforms applied |
//!
//! Decimal text is read as the nearest `f64` (Rust's correctly rounded parse); binary
//! `float` data is converted to `f64` exactly. Snapping to the grid happens later, once.
//!
//! Third-party parsers may panic on garbage; every parse runs under
//! [`std::panic::catch_unwind`] and a panic becomes [`ReadError::Malformed`].
//!
//! Hostile input is bounded before anything is allocated for it:
//!
//! - files: only regular files, at most [`MAX_FILE_BYTES`] (4 GiB), through the one
//!   function that opens files, [`read_regular`];
//! - declared counts (PLY elements, OFF header, binary STL triangles, glTF accessors)
//!   are compared with what the bytes could hold ([`ply`], [`off`], [`stl`], [`gltf`]),
//!   and then with what the file holds: data missing or left over after the declared
//!   counts (binary STL records, OFF and PLY entries, GLB chunks) is an error, as is a
//!   face of fewer than three vertices;
//! - errors name the line (text formats) or the element and byte offset (binary ones);
//! - glTF: referenced files stay in the file's folder ([`resolve_inside`], lifted by
//!   [`ReadOptions::allow_outside`]), node hierarchies are acyclic and expand to at
//!   most [`gltf::MAX_MESH_INSTANCES`] meshes, transforms are finite and rotations unit
//!   quaternions, positions `FLOAT` `VEC3` ([`gltf`]);
//! - messages escape whatever they quote from a file ([`crate::escape`]).

pub mod escape;
mod files;
pub mod gltf;
pub mod obj;
pub mod off;
pub mod ply;
mod raw;
pub mod stl;
pub mod transform;

pub use files::{file_kind, read_regular, resolve_inside, MAX_FILE_BYTES};
pub use raw::{Polygons, RawObject};

use std::cell::Cell;
use std::fmt;
use std::panic::{self, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::Once;

/// A mesh file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// Object File Format (ASCII).
    Off,
    /// Wavefront OBJ.
    Obj,
    /// STL, ASCII or binary.
    Stl,
    /// Stanford PLY, ASCII or binary.
    Ply,
    /// glTF 2.0, JSON (`.gltf`) or binary (`.glb`).
    Gltf,
}

impl Format {
    /// Every format, in the order of the table above.
    pub const ALL: [Format; 5] = [
        Format::Off,
        Format::Obj,
        Format::Stl,
        Format::Ply,
        Format::Gltf,
    ];

    /// The format named by a file extension (case-insensitive), if supported.
    pub fn from_extension(ext: &str) -> Option<Format> {
        match ext.to_ascii_lowercase().as_str() {
            "off" => Some(Format::Off),
            "obj" => Some(Format::Obj),
            "stl" => Some(Format::Stl),
            "ply" => Some(Format::Ply),
            "gltf" | "glb" => Some(Format::Gltf),
            _ => None,
        }
    }

    /// The format of a file, by its extension.
    pub fn from_path(path: &Path) -> Option<Format> {
        path.extension()
            .and_then(|e| e.to_str())
            .and_then(Format::from_extension)
    }

    /// The usual name of the format.
    pub fn name(self) -> &'static str {
        match self {
            Format::Off => "OFF",
            Format::Obj => "OBJ",
            Format::Stl => "STL",
            Format::Ply => "PLY",
            Format::Gltf => "glTF",
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// How files are read. The default is the safe one.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ReadOptions {
    /// Let a file refer to files outside its own folder (glTF buffers given by an
    /// absolute path, by `..` components climbing above the folder, or through a
    /// symbolic link leading out of it). Off by default: such a file is refused with
    /// [`ReadError::Outside`]. The command line's `--allow-outside` sets it.
    pub allow_outside: bool,
}

impl ReadOptions {
    /// The options with [`ReadOptions::allow_outside`] set to `allow`.
    pub fn allow_outside(mut self, allow: bool) -> ReadOptions {
        self.allow_outside = allow;
        self
    }
}

/// Why a file could not be read. Paths and text taken from files are shown escaped
/// (see [`crate::escape`]): no message carries raw bytes or control characters.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The file could not be opened or read.
    #[error("cannot read {}: {cause}", crate::escape::path(path))]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        cause: std::io::Error,
    },
    /// The path is not a regular file (a folder, a named pipe, a device, a socket);
    /// found before opening it.
    #[error(
        "cannot read {}: it is {kind}, not a regular file",
        crate::escape::path(path)
    )]
    NotRegular {
        /// The file.
        path: PathBuf,
        /// What it is instead: "a folder", "a named pipe (FIFO)", "a character device",
        /// "a block device", "a socket".
        kind: &'static str,
    },
    /// The file is larger than [`MAX_FILE_BYTES`]; nothing was read.
    #[error(
        "cannot read {}: it holds {size} bytes, more than the limit of {limit} bytes",
        crate::escape::path(path)
    )]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size.
        size: u64,
        /// The limit.
        limit: u64,
    },
    /// A path written in a file names a file outside that file's folder (see
    /// [`ReadOptions::allow_outside`]).
    #[error("{} lies outside the folder {} ({why}); --allow-outside reads it anyway", crate::escape::quoted(&reference.to_string_lossy()), crate::escape::path(folder))]
    Outside {
        /// The path as written.
        reference: PathBuf,
        /// The folder it must stay in.
        folder: PathBuf,
        /// How it leaves: "it is an absolute path", "a \"..\" component leaves the
        /// folder", "a symbolic link leads to ...".
        why: String,
    },
    /// A STEP file (`.step`, `.stp`) where a mesh is wanted: a CAD B-rep, which the
    /// command line reads (through the Python package) only as a whole assembly. The
    /// message says so, and how to convert it.
    #[error(
        "{} is a STEP file (a CAD model, not a mesh), which is read only as a whole assembly: \
         give it as the assembly (`apart check {}`), or convert it with \
         `python -m apart.step {} OUTDIR` (both need pip install './python[step]')",
        crate::escape::path(path),
        crate::escape::path(path),
        crate::escape::path(path)
    )]
    Step {
        /// The file.
        path: PathBuf,
    },
    /// The extension names no supported format.
    #[error(
        "unsupported file extension of {} (supported: .off, .obj, .stl, .ply, .gltf, .glb)",
        crate::escape::path(path)
    )]
    Unsupported {
        /// The file.
        path: PathBuf,
    },
    /// The content is not a valid file of its format.
    #[error("malformed {format} file: {detail}")]
    Malformed {
        /// The format that was expected.
        format: Format,
        /// What is wrong, with a line number or the element when known (escaped).
        detail: String,
    },
    /// A file the mesh file refers to (a glTF buffer) was refused or unreadable.
    #[error("{what}: {cause}")]
    Referenced {
        /// Which reference: `buffer 0 ("parts.bin")`.
        what: String,
        /// Why it could not be read.
        cause: Box<ReadError>,
    },
}

/// The longest detail of a [`ReadError::Malformed`], in characters: third-party
/// parsers quote whole lines.
const DETAIL: usize = 400;

impl ReadError {
    /// True when the message already names the file (not for malformed content, nor
    /// for the files it refers to, whose messages name only the reference).
    pub fn names_file(&self) -> bool {
        !matches!(
            self,
            ReadError::Malformed { .. } | ReadError::Referenced { .. } | ReadError::Outside { .. }
        )
    }

    /// Malformed content; `detail` is escaped and shortened here.
    pub(crate) fn malformed(format: Format, detail: impl Into<String>) -> ReadError {
        let detail = crate::escape::escape(&detail.into());
        let detail = match detail.char_indices().nth(DETAIL) {
            Some((cut, _)) => format!("{}...", &detail[..cut]),
            None => detail,
        };
        ReadError::Malformed { format, detail }
    }
}

/// Reads every object of a mesh file, choosing the format by the extension, with the
/// default (safe) [`ReadOptions`]: only a regular file of at most [`MAX_FILE_BYTES`]
/// is read, and the files it refers to must lie in its folder.
pub fn read_file(path: &Path) -> Result<Vec<RawObject>, ReadError> {
    read_file_with(path, &ReadOptions::default())
}

/// True when `path` has the extension of a STEP file (`.step`, `.stp`, any case).
pub fn is_step(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("step") || e.eq_ignore_ascii_case("stp"))
}

/// [`read_file`] with explicit options.
pub fn read_file_with(path: &Path, options: &ReadOptions) -> Result<Vec<RawObject>, ReadError> {
    let format = Format::from_path(path).ok_or_else(|| {
        if is_step(path) {
            ReadError::Step {
                path: path.to_path_buf(),
            }
        } else {
            ReadError::Unsupported {
                path: path.to_path_buf(),
            }
        }
    })?;
    let bytes = read_regular(path)?;
    // The folder, named "." rather than "" for a bare file name (messages show it).
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    read_bytes_with(&bytes, format, Some(folder), options)
}

/// Reads every object of a mesh held in memory. `base_dir` is the folder of the file
/// the bytes came from: it resolves the external buffers of `.gltf` files (other
/// formats ignore it; without it, external buffers are an error).
pub fn read_bytes(
    bytes: &[u8],
    format: Format,
    base_dir: Option<&Path>,
) -> Result<Vec<RawObject>, ReadError> {
    read_bytes_with(bytes, format, base_dir, &ReadOptions::default())
}

/// [`read_bytes`] with explicit options.
pub fn read_bytes_with(
    bytes: &[u8],
    format: Format,
    base_dir: Option<&Path>,
    options: &ReadOptions,
) -> Result<Vec<RawObject>, ReadError> {
    guarded(format, || match format {
        Format::Off => off::read(bytes).map(|o| vec![o]),
        Format::Obj => obj::read(bytes),
        Format::Stl => stl::read(bytes),
        Format::Ply => ply::read(bytes).map(|o| vec![o]),
        Format::Gltf => gltf::read(bytes, base_dir, options),
    })
}

thread_local! {
    static IN_GUARD: Cell<bool> = const { Cell::new(false) };
}

/// Runs a parser, turning a panic into [`ReadError::Malformed`].
pub(crate) fn guarded<T>(
    format: Format,
    f: impl FnOnce() -> Result<T, ReadError>,
) -> Result<T, ReadError> {
    let was = IN_GUARD.with(|g| g.replace(true));
    let result = panic::catch_unwind(AssertUnwindSafe(f));
    IN_GUARD.with(|g| g.set(was));
    match result {
        Ok(r) => r,
        Err(payload) => {
            let why = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "the parser gave up".to_string());
            Err(ReadError::malformed(
                format,
                format!("parser failed: {why}"),
            ))
        }
    }
}

/// Installs (once) a panic hook that stays silent for panics of third-party parsers
/// caught by this crate, and defers to the previous hook for every other panic.
/// Programs call it at start-up so that garbage input prints one clear error rather
/// than a panic message; libraries need not.
pub fn quiet_parser_panics() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if !IN_GUARD.with(|g| g.get()) {
                previous(info);
            }
        }));
    });
}

/// A short, safe size hint: never reserve more than the input could describe.
pub(crate) fn capped(count: usize, input_len: usize) -> usize {
    count.min(input_len / 2 + 16)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extensions() {
        assert_eq!(Format::from_path(Path::new("a/b.OFF")), Some(Format::Off));
        assert_eq!(Format::from_path(Path::new("x.glb")), Some(Format::Gltf));
        assert_eq!(Format::from_path(Path::new("x.step")), None);
        assert_eq!(Format::from_path(Path::new("noext")), None);
    }

    #[test]
    fn a_step_file_is_refused_with_how_to_convert_it() {
        let dir = std::env::temp_dir().join(format!("apart-formats-step-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for name in ["gearbox.step", "pin.STP"] {
            let path = dir.join(name);
            std::fs::write(&path, "ISO-10303-21;").unwrap();
            let e = read_file(&path).unwrap_err();
            assert!(matches!(e, ReadError::Step { .. }), "{e:?}");
            let m = e.to_string();
            assert!(m.contains(name) && m.contains("is a STEP file"), "{m}");
            assert!(
                m.contains("python -m apart.step") && m.contains("[step]"),
                "{m}"
            );
        }
        // Other unknown extensions keep the plain message.
        let other = dir.join("part.iges");
        std::fs::write(&other, "").unwrap();
        assert!(matches!(
            read_file(&other),
            Err(ReadError::Unsupported { .. })
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn panics_become_errors() {
        quiet_parser_panics();
        let r: Result<(), ReadError> = guarded(Format::Ply, || panic!("boom"));
        let e = r.unwrap_err().to_string();
        assert!(
            e.contains("malformed PLY file") && e.contains("boom"),
            "{e}"
        );
    }
}
