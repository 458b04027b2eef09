//! STL, ASCII and binary. Both are parsed here: the ASCII text as the nearest `f64`
//! (stl_io reads it as `f32`), and binary files are recognised by their size even when
//! their 80-byte header starts with `solid` (which many exporters write, and which makes
//! stl_io take them for ASCII). Facet normals are ignored: orientation comes from the
//! vertex order. Writing uses stl_io (binary, `f32`).

use crate::escape::quoted;
use crate::raw::{Polygons, RawObject};
use crate::{Format, ReadError};
use apart_kernel::fvec;
use rayon::prelude::*;
use std::io::Write;

const HEADER: usize = 80;
const RECORD: usize = 50;

/// Parses an STL file: one object per `solid` block of an ASCII file, one for a binary file.
pub fn read(bytes: &[u8]) -> Result<Vec<RawObject>, ReadError> {
    let declared = (bytes.len() >= HEADER + 4)
        .then(|| u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize);
    let exact_binary = declared.is_some_and(|n| HEADER + 4 + RECORD * n == bytes.len());
    let looks_ascii = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .is_some_and(|i| bytes[i..].starts_with(b"solid"));
    if exact_binary {
        return Ok(vec![read_binary(bytes)?]);
    }
    if looks_ascii && std::str::from_utf8(bytes).is_ok() {
        return read_ascii(bytes);
    }
    match declared {
        None => Err(ReadError::malformed(
            Format::Stl,
            "too short for a binary STL and not ASCII STL",
        )),
        Some(n) if HEADER + 4 + RECORD * n > bytes.len() => Err(ReadError::malformed(
            Format::Stl,
            format!(
                "binary STL declares {n} triangles but holds only {}",
                (bytes.len() - HEADER - 4) / RECORD
            ),
        )),
        Some(_) => Ok(vec![read_binary(bytes)?]),
    }
}

fn read_binary(bytes: &[u8]) -> Result<RawObject, ReadError> {
    let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
    let body = &bytes[HEADER + 4..HEADER + 4 + RECORD * n];
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
    Ok(RawObject {
        name: None,
        vertices,
        faces: Polygons::triangle_soup(n),
    })
}

fn read_ascii(bytes: &[u8]) -> Result<Vec<RawObject>, ReadError> {
    let text = std::str::from_utf8(bytes)
        .map_err(|_| ReadError::malformed(Format::Stl, "ASCII STL that is not UTF-8 text"))?;
    let bad =
        |line: usize, what: &str| ReadError::malformed(Format::Stl, format!("line {line}: {what}"));
    let mut objects = Vec::new();
    let mut current: Option<RawObject> = None;
    let mut in_loop: Option<Vec<u32>> = None;
    for (i, line) in text.lines().enumerate() {
        let n = i + 1;
        let mut tok = line.split_whitespace();
        let Some(word) = tok.next() else { continue };
        match word.to_ascii_lowercase().as_str() {
            "solid" => {
                if current.is_some() {
                    return Err(bad(n, "\"solid\" inside a solid"));
                }
                let name = line.trim_start()[5..].trim();
                current = Some(RawObject {
                    name: (!name.is_empty()).then(|| name.to_string()),
                    ..RawObject::default()
                });
            }
            "endsolid" => {
                let o = current
                    .take()
                    .ok_or_else(|| bad(n, "\"endsolid\" without \"solid\""))?;
                if in_loop.is_some() {
                    return Err(bad(n, "\"endsolid\" inside a facet"));
                }
                objects.push(o);
            }
            "facet" | "endfacet" => {
                if current.is_none() {
                    return Err(bad(n, "facet outside a solid"));
                }
            }
            "outer" => {
                if current.is_none() || in_loop.is_some() {
                    return Err(bad(n, "misplaced \"outer loop\""));
                }
                in_loop = Some(Vec::new());
            }
            "vertex" => {
                let (Some(o), Some(l)) = (current.as_mut(), in_loop.as_mut()) else {
                    return Err(bad(n, "vertex outside a facet loop"));
                };
                let mut c = [0f64; 3];
                for x in &mut c {
                    *x = tok
                        .next()
                        .and_then(|t| t.parse::<f64>().ok())
                        .ok_or_else(|| bad(n, "a vertex needs three numbers"))?;
                }
                l.push(o.vertices.len() as u32);
                o.vertices.push(c);
            }
            "endloop" => {
                let (Some(o), Some(l)) = (current.as_mut(), in_loop.take()) else {
                    return Err(bad(n, "\"endloop\" without \"outer loop\""));
                };
                o.faces.push(&l);
            }
            _ => return Err(bad(n, &format!("unexpected {}", quoted(word)))),
        }
    }
    if let Some(o) = current {
        // Tolerate a missing "endsolid" at the end of the file, not a cut facet.
        if in_loop.is_some() {
            return Err(ReadError::malformed(
                Format::Stl,
                "file ends inside a facet",
            ));
        }
        objects.push(o);
    }
    if objects.is_empty() {
        return Err(ReadError::malformed(Format::Stl, "no solid found"));
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
        assert!(e.contains("declares 2 triangles"), "{e}");
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
            e.contains("declares 4294967295 triangles but holds only 1"),
            "{e}"
        );
        let e = read(b"solid x\n\x1b[31m 1 2\n").unwrap_err().to_string();
        assert!(
            e.contains("line 2: unexpected \"\\x1b[31m\"") && !e.contains('\x1b'),
            "{e}"
        );
    }
}
