//! The buffers' bytes: the GLB binary chunk, base64 `data:` URIs, or external files
//! kept inside the file's folder.

use super::malformed;
use crate::escape::quoted;
use crate::files::{read_regular, resolve_inside};
use crate::{ReadError, ReadOptions};
use std::path::{Path, PathBuf};

/// `%XX` escapes of a URI replaced by their bytes; `None` when they do not make UTF-8.
pub(super) fn percent_decoded(uri: &str) -> Option<String> {
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
pub(super) fn data_uri_bytes(uri: &str) -> Result<Vec<u8>, String> {
    let rest = uri.strip_prefix("data:").unwrap_or(uri);
    let Some((_, payload)) = rest.split_once(";base64,") else {
        return Err("a data: URI without \";base64,\" (only base64 data is read)".into());
    };
    base64_decode(payload)
}

/// Standard base64 (RFC 4648 §4: `A–Z a–z 0–9 + /`), the trailing `=` padding optional.
pub(super) fn base64_decode(text: &str) -> Result<Vec<u8>, String> {
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
pub(super) fn load_buffers(
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
