//! Mesh file formats: readers return [`RawObject`]s, writers take vertices and polygons.
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

pub mod gltf;
pub mod obj;
pub mod off;
pub mod ply;
pub mod stl;

use crate::raw::RawObject;
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

/// Why a file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The file could not be opened or read.
    #[error("cannot read {}: {cause}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        cause: std::io::Error,
    },
    /// The extension names no supported format.
    #[error("unsupported file extension of {} (supported: .off, .obj, .stl, .ply, .gltf, .glb)", path.display())]
    Unsupported {
        /// The file.
        path: PathBuf,
    },
    /// The content is not a valid file of its format.
    #[error("malformed {format} file: {detail}")]
    Malformed {
        /// The format that was expected.
        format: Format,
        /// What is wrong, with a line number when known.
        detail: String,
    },
}

impl ReadError {
    /// True when the message already names the file (not for malformed content).
    pub fn names_file(&self) -> bool {
        !matches!(self, ReadError::Malformed { .. })
    }

    pub(crate) fn malformed(format: Format, detail: impl Into<String>) -> ReadError {
        ReadError::Malformed {
            format,
            detail: detail.into(),
        }
    }
}

/// Reads every object of a mesh file, choosing the format by the extension.
pub fn read_file(path: &Path) -> Result<Vec<RawObject>, ReadError> {
    let format = Format::from_path(path).ok_or_else(|| ReadError::Unsupported {
        path: path.to_path_buf(),
    })?;
    let bytes = std::fs::read(path).map_err(|cause| ReadError::Io {
        path: path.to_path_buf(),
        cause,
    })?;
    read_bytes(&bytes, format, path.parent())
}

/// Reads every object of a mesh held in memory. `base_dir` resolves external buffers
/// of `.gltf` files (other formats ignore it).
pub fn read_bytes(
    bytes: &[u8],
    format: Format,
    base_dir: Option<&Path>,
) -> Result<Vec<RawObject>, ReadError> {
    guarded(format, || match format {
        Format::Off => off::read(bytes).map(|o| vec![o]),
        Format::Obj => obj::read(bytes),
        Format::Stl => stl::read(bytes),
        Format::Ply => ply::read(bytes).map(|o| vec![o]),
        Format::Gltf => gltf::read(bytes, base_dir),
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
