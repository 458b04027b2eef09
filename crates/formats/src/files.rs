//! The one place where files are opened: mesh files, and the files a mesh file refers
//! to (glTF buffers).
//!
//! - Only regular files are read. The type of the path (symbolic links followed) is
//!   checked before opening, so a named pipe (whose opening blocks until a writer
//!   comes), a device such as `/dev/zero` (which never ends), a socket or a folder is
//!   an error at once. Where the platform allows, the file is also opened
//!   non-blocking and its type checked again on the open handle.
//! - At most [`MAX_FILE_BYTES`] (4 GiB) are read from one file; a larger file is an
//!   error before anything is read.
//! - A file referred to from another one must lie inside the referring file's folder,
//!   unless [`crate::ReadOptions::allow_outside`] is set: [`resolve_inside`].

use crate::ReadError;
use std::fs::{File, FileType, Metadata};
use std::io::Read;
use std::path::{Component, Path, PathBuf};

/// The largest file read: 4 GiB (a binary STL of 85 million triangles).
pub const MAX_FILE_BYTES: u64 = 4 << 30;

fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> ReadError + '_ {
    move |cause| ReadError::Io {
        path: path.to_path_buf(),
        cause,
    }
}

/// What a path that is not a regular file is, for messages: `"a folder"`, `"a named
/// pipe (FIFO)"`, `"a character device"`...; `None` for a regular file.
pub fn file_kind(t: &FileType) -> Option<&'static str> {
    if t.is_file() {
        return None;
    }
    if t.is_dir() {
        return Some("a folder");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return Some("a named pipe (FIFO)");
        }
        if t.is_char_device() {
            return Some("a character device");
        }
        if t.is_block_device() {
            return Some("a block device");
        }
        if t.is_socket() {
            return Some("a socket");
        }
    }
    Some("not a regular file")
}

/// Errors unless `meta` describes a regular file of at most `limit` bytes.
fn check(path: &Path, meta: &Metadata, limit: u64) -> Result<(), ReadError> {
    if let Some(kind) = file_kind(&meta.file_type()) {
        return Err(ReadError::NotRegular {
            path: path.to_path_buf(),
            kind,
        });
    }
    if meta.len() > limit {
        return Err(ReadError::TooLarge {
            path: path.to_path_buf(),
            size: meta.len(),
            limit,
        });
    }
    Ok(())
}

/// `O_NONBLOCK` where its value is known: opening a FIFO that appeared after the type
/// check then fails or returns at once instead of blocking.
#[cfg(all(
    target_os = "linux",
    any(
        target_arch = "x86_64",
        target_arch = "x86",
        target_arch = "aarch64",
        target_arch = "arm",
        target_arch = "riscv64"
    )
))]
const NONBLOCK: Option<i32> = Some(0o4000);
#[cfg(target_os = "macos")]
const NONBLOCK: Option<i32> = Some(0x4);
#[cfg(not(any(
    target_os = "macos",
    all(
        target_os = "linux",
        any(
            target_arch = "x86_64",
            target_arch = "x86",
            target_arch = "aarch64",
            target_arch = "arm",
            target_arch = "riscv64"
        )
    )
)))]
const NONBLOCK: Option<i32> = None;

fn open(path: &Path) -> std::io::Result<File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    if let Some(flag) = NONBLOCK {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(flag);
    }
    let _ = NONBLOCK;
    options.open(path)
}

/// The bytes of the regular file `path`, at most [`MAX_FILE_BYTES`] of them. Named
/// pipes, devices, sockets and folders are refused before they are opened.
pub fn read_regular(path: &Path) -> Result<Vec<u8>, ReadError> {
    read_regular_limited(path, MAX_FILE_BYTES)
}

/// [`read_regular`] with another size limit.
pub(crate) fn read_regular_limited(path: &Path, limit: u64) -> Result<Vec<u8>, ReadError> {
    check(
        path,
        &std::fs::metadata(path).map_err(io_error(path))?,
        limit,
    )?;
    let file = open(path).map_err(io_error(path))?;
    // The path may have been replaced between the check and the opening.
    let meta = file.metadata().map_err(io_error(path))?;
    check(path, &meta, limit)?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(io_error(path))?;
    if bytes.len() as u64 > limit {
        return Err(ReadError::TooLarge {
            path: path.to_path_buf(),
            size: bytes.len() as u64,
            limit,
        });
    }
    Ok(bytes)
}

/// Resolves `reference` (a path written in a file of `folder`) and checks that it lies
/// inside `folder`: it must be relative, its `..` components may not climb above
/// `folder`, and the file it names, symbolic links resolved, must lie in `folder` or
/// below (`folder`'s own path is resolved too). Returns the resolved path, which is
/// the one to open. With `allow_outside`, nothing is checked and `folder/reference`
/// is returned (`reference` itself when absolute).
pub fn resolve_inside(
    folder: &Path,
    reference: &Path,
    allow_outside: bool,
) -> Result<PathBuf, ReadError> {
    let joined = folder.join(reference);
    if allow_outside {
        return Ok(joined);
    }
    let outside = |why: String| ReadError::Outside {
        reference: reference.to_path_buf(),
        folder: folder.to_path_buf(),
        why,
    };
    let mut depth = 0usize;
    for c in reference.components() {
        match c {
            Component::Prefix(_) | Component::RootDir => {
                return Err(outside("it is an absolute path".into()))
            }
            Component::CurDir => {}
            Component::ParentDir => {
                depth = depth
                    .checked_sub(1)
                    .ok_or_else(|| outside("a \"..\" component leaves the folder".into()))?;
            }
            Component::Normal(_) => depth += 1,
        }
    }
    let base = if folder.as_os_str().is_empty() {
        Path::new(".")
    } else {
        folder
    };
    let base = base.canonicalize().map_err(io_error(base))?;
    let target = joined.canonicalize().map_err(io_error(&joined))?;
    if !target.starts_with(&base) {
        return Err(outside(format!(
            "a symbolic link leads to {}",
            crate::escape::path(&target)
        )));
    }
    Ok(target)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("apart-mesh-files-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn only_regular_files_are_read() {
        let d = scratch("regular");
        std::fs::write(d.join("a.off"), b"OFF\n").unwrap();
        assert_eq!(read_regular(&d.join("a.off")).unwrap(), b"OFF\n");
        let e = read_regular(&d).unwrap_err().to_string();
        assert!(e.contains("is a folder, not a regular file"), "{e}");
        let e = read_regular(&d.join("missing.off"))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("cannot read ") && e.contains("missing.off"),
            "{e}"
        );
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink("/dev/zero", d.join("zero.stl")).unwrap();
            let e = read_regular(&d.join("zero.stl")).unwrap_err().to_string();
            assert!(
                e.contains("zero.stl") && e.contains("a character device"),
                "{e}"
            );
            let fifo = d.join("pipe.obj");
            let made = std::process::Command::new("mkfifo").arg(&fifo).status();
            if made.is_ok_and(|s| s.success()) {
                // Would block forever if it were opened.
                let e = read_regular(&fifo).unwrap_err().to_string();
                assert!(
                    e.contains("pipe.obj") && e.contains("named pipe (FIFO)"),
                    "{e}"
                );
            }
            let sock = d.join("s.ply");
            if let Ok(_l) = std::os::unix::net::UnixListener::bind(&sock) {
                let e = read_regular(&sock).unwrap_err().to_string();
                assert!(e.contains("a socket"), "{e}");
            }
        }
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn size_is_bounded() {
        let d = scratch("size");
        let p = d.join("big.stl");
        std::fs::write(&p, [0u8; 100]).unwrap();
        let e = read_regular_limited(&p, 99).unwrap_err().to_string();
        assert!(
            e.contains("100 bytes") && e.contains("limit of 99 bytes"),
            "{e}"
        );
        assert_eq!(read_regular_limited(&p, 100).unwrap().len(), 100);
        // A sparse file one byte beyond 4 GiB: refused without reading anything.
        let f = File::create(&p).unwrap();
        if f.set_len(MAX_FILE_BYTES + 1).is_ok() {
            let e = read_regular(&p).unwrap_err().to_string();
            assert!(e.contains("4294967297 bytes"), "{e}");
        }
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn references_stay_inside_the_folder() {
        let d = scratch("inside");
        std::fs::create_dir_all(d.join("sub")).unwrap();
        std::fs::write(d.join("sub/b.bin"), b"x").unwrap();
        std::fs::write(d.join("a.bin"), b"x").unwrap();
        let sub = d.join("sub");
        assert!(resolve_inside(&sub, Path::new("b.bin"), false).is_ok());
        assert!(resolve_inside(&d, Path::new("sub/../a.bin"), false).is_ok());
        let e = resolve_inside(&sub, Path::new("../a.bin"), false)
            .unwrap_err()
            .to_string();
        assert!(e.contains("\"..\" component leaves the folder"), "{e}");
        assert!(e.contains("--allow-outside"), "{e}");
        let e = resolve_inside(&sub, Path::new("/etc/passwd"), false)
            .unwrap_err()
            .to_string();
        assert!(e.contains("absolute path"), "{e}");
        assert!(resolve_inside(&sub, Path::new("../a.bin"), true).is_ok());
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink("../a.bin", sub.join("link.bin")).unwrap();
            let e = resolve_inside(&sub, Path::new("link.bin"), false)
                .unwrap_err()
                .to_string();
            assert!(e.contains("symbolic link"), "{e}");
            // A link inside the folder is fine.
            std::os::unix::fs::symlink("b.bin", sub.join("ok.bin")).unwrap();
            assert!(resolve_inside(&sub, Path::new("ok.bin"), false).is_ok());
        }
        let _ = std::fs::remove_dir_all(&d);
    }
}
