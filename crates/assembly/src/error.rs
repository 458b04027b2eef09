//! Why an assembly could not be loaded at all (problems with single parts are
//! [`apart_mesh::Problem`]s instead, collected in [`crate::Loaded`]).

use apart_formats::escape::{escape, path as escaped};
use apart_formats::ReadError;
use std::path::PathBuf;

/// A failure that leaves nothing to show.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The path does not exist.
    #[error("{}: no such file or folder", escaped(.0))]
    NotFound(PathBuf),
    /// A folder could not be listed.
    #[error("cannot read folder {}: {cause}", escaped(path))]
    Folder {
        /// The folder.
        path: PathBuf,
        /// The operating system's reason.
        cause: std::io::Error,
    },
    /// The single mesh file given could not be read.
    #[error("{}", read_message(path, cause))]
    Read {
        /// The file.
        path: PathBuf,
        /// Why (names the file).
        cause: ReadError,
    },
    /// The manifest is not valid.
    #[error("{}: {}", escaped(path), escape(detail))]
    Manifest {
        /// The manifest file.
        path: PathBuf,
        /// What is wrong.
        detail: String,
    },
    /// The path names something that is not a regular file or a folder (a named pipe, a
    /// socket, a device): it is never opened.
    #[error(
        "{}: is {kind}, not a regular file or a folder; only regular files are read",
        escaped(path)
    )]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What it is: "a named pipe (FIFO)", "a socket", "a character device"...
        kind: &'static str,
    },
    /// An assembly description in memory breaks a manifest's rules (see
    /// [`crate::load_description`]).
    #[error("{}", escape(.0))]
    Description(String),
    /// Nothing to load.
    #[error("{}: no parts found (expected mesh files .off .obj .stl .ply .gltf .glb, or assembly.json)", escaped(.0))]
    NoParts(PathBuf),
    /// No grid fits the coordinates.
    #[error("cannot choose the grid: {0}")]
    Grid(#[from] apart_kernel::GridError),
    /// The stop flag of [`crate::LoadOptions::progress`] was raised: there is no partial
    /// assembly.
    #[error("loading stopped during {phase}: the stop flag was raised")]
    Stopped {
        /// The phase it stopped in ([`apart_kernel::progress::phases`]).
        phase: &'static str,
    },
}

fn read_message(path: &std::path::Path, cause: &ReadError) -> String {
    if cause.names_file() {
        cause.to_string()
    } else {
        format!("{}: {cause}", crate::error::escaped(path))
    }
}
