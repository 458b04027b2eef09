//! STL, ASCII and binary. Both are parsed here: the ASCII text as the nearest `f64`
//! (stl_io reads it as `f32`), and binary files are recognised by their size even when
//! their 80-byte header starts with `solid` (which many exporters write, and which makes
//! stl_io take them for ASCII). Facet normals are ignored: orientation comes from the
//! vertex order. Writing uses stl_io (binary, `f32`).
//!
//! A binary file must hold exactly the records its triangle count declares (no fewer,
//! no trailing bytes). ASCII keywords are read in any case, a UTF-8 byte-order mark is
//! skipped, and the name after `solid` may be any bytes (UTF-8, or else read as
//! Latin-1); only keywords and numbers must be ASCII. Every facet loop holds exactly
//! three vertices. A file that is neither says what it looked like as each.

use crate::escape::quoted;
use crate::raw::{Polygons, RawObject};
use crate::{Format, ReadError};
use apart_kernel::fvec;
use rayon::prelude::*;
use std::io::Write;

const HEADER: usize = 80;
const RECORD: usize = 50;
/// The UTF-8 byte-order mark some editors write before `solid`.
const BOM: &[u8] = b"\xef\xbb\xbf";

/// The triangle count of a binary header, if the file is long enough to have one.
fn declared(bytes: &[u8]) -> Option<u32> {
    let c = bytes.get(HEADER..HEADER + 4)?;
    Some(u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
}

/// The size of a binary STL of `n` triangles (in `u64`: no overflow on any target).
fn binary_size(n: u32) -> u64 {
    (HEADER + 4) as u64 + RECORD as u64 * n as u64
}

/// What is wrong with `bytes` read as binary STL (`"it declares ..."`), or `None`
/// when they are one.
fn binary_mismatch(bytes: &[u8]) -> Option<String> {
    match declared(bytes) {
        None => Some(format!(
            "it has {} bytes, fewer than the 84 of a binary STL's header and count",
            bytes.len()
        )),
        Some(n) if binary_size(n) != bytes.len() as u64 => Some(format!(
            "it declares {n} triangles ({} bytes) but the file has {} bytes",
            binary_size(n),
            bytes.len()
        )),
        Some(_) => None,
    }
}

/// The text after a byte-order mark and leading whitespace, when it starts with `solid`
/// (in any case): what is read as ASCII STL.
fn ascii_start(bytes: &[u8]) -> Option<&[u8]> {
    let b = bytes.strip_prefix(BOM).unwrap_or(bytes);
    let b = &b[b.iter().position(|c| !c.is_ascii_whitespace())?..];
    b.get(..5)
        .is_some_and(|w| w.eq_ignore_ascii_case(b"solid"))
        .then_some(b)
}

/// Parses an STL file: one object per `solid` block of an ASCII file, one for a binary file.
pub fn read(bytes: &[u8]) -> Result<Vec<RawObject>, ReadError> {
    let binary = binary_mismatch(bytes);
    if binary.is_none() {
        return Ok(vec![read_binary(bytes)]);
    }
    let binary = binary.unwrap_or_default();
    let Some(text) = ascii_start(bytes) else {
        return Err(ReadError::malformed(
            Format::Stl,
            format!(
                "not binary STL: {binary}; and not ASCII STL: it does not start with \"solid\""
            ),
        ));
    };
    // The lines before `text`: leading blank lines (the mark has no line of its own).
    let skipped = bytes[..bytes.len() - text.len()]
        .iter()
        .filter(|&&c| c == b'\n')
        .count();
    read_ascii(text, skipped).map_err(|ascii| {
        ReadError::malformed(
            Format::Stl,
            format!("not ASCII STL: {ascii}; and not binary STL: {binary}"),
        )
    })
}

fn read_binary(bytes: &[u8]) -> RawObject {
    let n = declared(bytes).unwrap_or(0) as usize;
    let body = &bytes[HEADER + 4..];
    let mut vertices = vec![[0f64; 3]; 3 * n];
    vertices
        .par_chunks_mut(3)
        .zip(body.par_chunks_exact(RECORD))
        .with_min_len(4096)
        .for_each(|(out, rec)| {
            let f =
                |o: usize| f32::from_le_bytes([rec[o], rec[o + 1], rec[o + 2], rec[o + 3]]) as f64;
            for (k, v) in out.iter_mut().enumerate() {
                let o = 12 + 12 * k;
                *v = [f(o), f(o + 4), f(o + 8)];
            }
        });
    RawObject {
        name: None,
        vertices,
        faces: Polygons::triangle_soup(n),
    }
}

/// A solid's name: the bytes after the keyword, trimmed; UTF-8 text, or else Latin-1.
/// Control bytes (found in binary data, never in names) are an error.
fn solid_name(rest: &[u8]) -> Result<Option<String>, String> {
    let rest = rest.trim_ascii();
    if let Some(&c) = rest.iter().find(|&&c| c.is_ascii_control() && c != b'\t') {
        return Err(format!(
            "the name after \"solid\" holds the control byte 0x{c:02x} (binary data?)"
        ));
    }
    if rest.is_empty() {
        return Ok(None);
    }
    Ok(Some(match std::str::from_utf8(rest) {
        Ok(s) => s.to_string(),
        Err(_) => rest.iter().map(|&b| b as char).collect(),
    }))
}

/// A token for a message: its text, with bytes that are not UTF-8 replaced.
fn shown(token: &[u8]) -> String {
    quoted(&String::from_utf8_lossy(token))
}

/// Parses ASCII STL text whose first line is line `skipped + 1` of the file; the error
/// is the detail, `line N: ...`.
fn read_ascii(text: &[u8], skipped: usize) -> Result<Vec<RawObject>, String> {
    let mut objects = Vec::new();
    let mut current: Option<RawObject> = None;
    let mut in_loop: Option<Vec<u32>> = None;
    let mut facets = 0usize;
    let mut last = skipped;
    for (i, line) in text.split(|&c| c == b'\n').enumerate() {
        let n = skipped + i + 1;
        last = n;
        let bad = |what: String| format!("line {n}: {what}");
        let mut tok = line
            .split(|c| c.is_ascii_whitespace())
            .filter(|t| !t.is_empty());
        let Some(word) = tok.next() else { continue };
        let keyword = word.to_ascii_lowercase();
        match keyword.as_slice() {
            b"solid" => {
                if current.is_some() {
                    return Err(bad("\"solid\" inside a solid".into()));
                }
                let at = line.len() - line.trim_ascii_start().len() + word.len();
                current = Some(RawObject {
                    name: solid_name(&line[at..]).map_err(bad)?,
                    ..RawObject::default()
                });
            }
            b"endsolid" => {
                let o = current
                    .take()
                    .ok_or_else(|| bad("\"endsolid\" without \"solid\"".into()))?;
                if in_loop.is_some() {
                    return Err(bad("\"endsolid\" inside a facet".into()));
                }
                objects.push(o);
            }
            b"facet" | b"endfacet" => {
                if current.is_none() {
                    return Err(bad("facet outside a solid".into()));
                }
            }
            b"outer" => {
                if current.is_none() || in_loop.is_some() {
                    return Err(bad("misplaced \"outer loop\"".into()));
                }
                facets += 1;
                in_loop = Some(Vec::new());
            }
            b"vertex" => {
                let (Some(o), Some(l)) = (current.as_mut(), in_loop.as_mut()) else {
                    return Err(bad("vertex outside a facet loop".into()));
                };
                let mut c = [0f64; 3];
                for x in &mut c {
                    let t = tok
                        .next()
                        .ok_or_else(|| bad("a vertex needs three numbers".into()))?;
                    *x = std::str::from_utf8(t)
                        .ok()
                        .and_then(|t| t.parse::<f64>().ok())
                        .ok_or_else(|| bad(format!("{} is not a number", shown(t))))?;
                }
                l.push(o.vertices.len() as u32);
                o.vertices.push(c);
            }
            b"endloop" => {
                let (Some(o), Some(l)) = (current.as_mut(), in_loop.take()) else {
                    return Err(bad("\"endloop\" without \"outer loop\"".into()));
                };
                if l.len() != 3 {
                    return Err(bad(format!(
                        "facet {facets} has {} vertices; an STL facet has 3",
                        l.len()
                    )));
                }
                o.faces.push(&l);
            }
            _ => return Err(bad(format!("unexpected {}", shown(word)))),
        }
    }
    if let Some(o) = current {
        // Tolerate a missing "endsolid" at the end of the file, not a cut facet.
        if in_loop.is_some() {
            return Err(format!("line {last}: the file ends inside facet {facets}"));
        }
        objects.push(o);
    }
    if objects.is_empty() {
        return Err(format!("line {last}: no solid found"));
    }
    Ok(objects)
}

/// Writes triangles as binary STL (coordinates rounded to `f32`, as the format holds).
pub fn write(
    out: &mut impl Write,
    vertices: &[[f64; 3]],
    triangles: &[[u32; 3]],
) -> std::io::Result<()> {
    let tris: Vec<stl_io::Triangle> = triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| vertices[i as usize]);
            let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
            let n = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let len = fvec::norm(n);
            let n = if len > 0.0 {
                n.map(|x| x / len)
            } else {
                [0.0; 3]
            };
            stl_io::Triangle {
                normal: stl_io::Normal::new(n.map(|x| x as f32)),
                vertices: [a, b, c].map(|p| stl_io::Vertex::new(p.map(|x| x as f32))),
            }
        })
        .collect();
    stl_io::write_stl(out, tris.iter())
}

#[cfg(test)]
mod tests {
    use super::*;

    const ASCII: &str = "solid cube part\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 0.1 0\n  endloop\n endfacet\nendsolid cube part\n";

    #[test]
    fn ascii_reads_f64() {
        let o = read(ASCII.as_bytes()).unwrap();
        assert_eq!(o.len(), 1);
        assert_eq!(o[0].name.as_deref(), Some("cube part"));
        assert_eq!(o[0].vertices[2][1], 0.1); // nearest f64, not f32
        assert_eq!(o[0].faces.get(0), &[0, 1, 2]);
    }

    #[test]
    fn binary_with_solid_header() {
        let v = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.5, 0.0]];
        let mut buf = Vec::new();
        write(&mut buf, &v, &[[0, 1, 2], [0, 2, 1]]).unwrap();
        buf[..6].copy_from_slice(b"solid ");
        let o = read(&buf).unwrap();
        assert_eq!(o[0].vertices.len(), 6);
        assert_eq!(o[0].vertices[..3], v[..]);
        assert_eq!(o[0].faces.get(1), &[3, 4, 5]);
        // Truncated: a clear error.
        let e = read(&buf[..buf.len() - 10]).unwrap_err().to_string();
        assert!(
            e.contains("not ASCII STL: line 1: the name after \"solid\" holds the control byte 0x00 (binary data?); and not binary STL: it declares 2 triangles (184 bytes) but the file has 174 bytes"),
            "{e}"
        );
    }

    #[test]
    fn garbage_is_an_error() {
        assert!(read(b"solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0\n").is_err());
        assert!(read(b"hello").is_err());
    }

    #[test]
    fn huge_counts_and_hostile_tokens() {
        // A binary header declaring 2^32 - 1 triangles in a 134-byte file.
        let mut b = vec![0u8; 134];
        b[80..84].copy_from_slice(&u32::MAX.to_le_bytes());
        let e = read(&b).unwrap_err().to_string();
        assert!(
            e.contains(
                "declares 4294967295 triangles (214748364834 bytes) but the file has 134 bytes"
            ),
            "{e}"
        );
        let e = read(b"solid x\n\x1b[31m 1 2\n").unwrap_err().to_string();
        assert!(
            e.contains("line 2: unexpected \"\\x1b[31m\"") && !e.contains('\x1b'),
            "{e}"
        );
    }
}
