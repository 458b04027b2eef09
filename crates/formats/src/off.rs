//! Object File Format (ASCII): `OFF` header (optional, with the usual `C`, `N`, `ST`
//! prefixes), counts `vertices faces [edges]`, one vertex per line, one polygon per line
//! (`n i1 ... in`, then nothing or a colour of 1, 3 or 4 numbers, which is ignored), `#`
//! comments. The file holds exactly the declared vertices and faces (of at least three
//! vertices each); every error names the line.

use crate::escape::quoted;
use crate::raw::{Polygons, RawObject};
use crate::{capped, Format, ReadError};
use std::io::Write;

fn bad(line: usize, detail: impl std::fmt::Display) -> ReadError {
    ReadError::malformed(Format::Off, format!("line {line}: {detail}"))
}

/// Lines with their 1-based numbers, comments stripped, blank lines skipped.
fn content_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines().enumerate().filter_map(|(i, l)| {
        let l = l.split('#').next().unwrap_or("").trim();
        (!l.is_empty()).then_some((i + 1, l))
    })
}

/// Splits an optional header keyword off the first line; `Ok(rest)` is what follows it.
fn strip_header(first: &str, line: usize) -> Result<&str, ReadError> {
    let word = first.split_whitespace().next().unwrap_or("");
    if word.parse::<f64>().is_ok() {
        return Ok(first); // no header: the counts come first
    }
    let Some(prefix) = word.strip_suffix("OFF") else {
        return Err(bad(
            line,
            format!("expected an OFF header, found {}", quoted(word)),
        ));
    };
    let rest = first[word.len()..].trim_start();
    if rest.split_whitespace().next() == Some("BINARY") {
        return Err(bad(line, "binary OFF is not supported"));
    }
    let mut p = prefix;
    for flag in ["ST", "C", "N", "4", "n"] {
        if let Some(r) = p.strip_prefix(flag) {
            if flag == "4" || flag == "n" {
                return Err(bad(line, "only three-dimensional OFF is supported"));
            }
            p = r;
        }
    }
    if !p.is_empty() {
        return Err(bad(line, format!("unknown OFF header {}", quoted(word))));
    }
    Ok(rest)
}

/// Checks what follows the indices of face `k` (`count` of them) on line `n`: nothing,
/// or a colour (a colour-map index, RGB or RGBA).
fn check_face_colour<'a>(
    rest: impl Iterator<Item = &'a str>,
    k: usize,
    count: usize,
    n: usize,
) -> Result<(), ReadError> {
    let rest: Vec<&str> = rest.collect();
    if let Some(t) = rest.iter().find(|t| t.parse::<f64>().is_err()) {
        return Err(bad(
            n,
            format!("face {k}: {} after its indices is not a number", quoted(t)),
        ));
    }
    if !matches!(rest.len(), 0 | 1 | 3 | 4) {
        return Err(bad(
            n,
            format!(
                "face {k} declares {count} vertices but the line holds {} more values (a colour after the indices is 1, 3 or 4 numbers)",
                rest.len()
            ),
        ));
    }
    Ok(())
}

/// Parses an OFF file.
pub fn read(bytes: &[u8]) -> Result<RawObject, ReadError> {
    let text = std::str::from_utf8(bytes)
        .map_err(|e| ReadError::malformed(Format::Off, format!("not UTF-8 text ({e})")))?;
    let mut lines = content_lines(text);
    let (n0, first) = lines
        .next()
        .ok_or_else(|| ReadError::malformed(Format::Off, "empty file"))?;
    let rest = strip_header(first, n0)?;
    // The counts may follow the header on the same line, or come on the next one.
    let (nc, counts) = if rest.is_empty() {
        lines
            .next()
            .ok_or_else(|| bad(n0, "missing vertex and face counts"))?
    } else {
        (n0, rest)
    };
    let mut it = counts.split_whitespace().map(|t| t.parse::<usize>());
    let (nv, nf) = match (it.next(), it.next()) {
        (Some(Ok(v)), Some(Ok(f))) => (v, f),
        _ => return Err(bad(nc, "expected vertex and face counts")),
    };
    if nv > u32::MAX as usize {
        return Err(bad(nc, "too many vertices"));
    }
    // Each vertex takes a line of at least 5 characters, each face one of at least 1.
    let need = 6 * nv as u128 + 2 * nf as u128;
    if need > bytes.len() as u128 + 1 {
        return Err(bad(
            nc,
            format!(
                "{nv} vertices and {nf} faces declared, more than the {} bytes of the file can hold",
                bytes.len()
            ),
        ));
    }
    let mut vertices = Vec::with_capacity(capped(nv, bytes.len()));
    for k in 0..nv {
        let (n, l) = lines.next().ok_or_else(|| {
            bad(
                text.lines().count(),
                format!(
                    "expected {nv} {}, found {k}",
                    if nv == 1 { "vertex" } else { "vertices" }
                ),
            )
        })?;
        let mut c = [0f64; 3];
        let mut tokens = l.split_whitespace();
        for x in &mut c {
            let t = tokens
                .next()
                .ok_or_else(|| bad(n, "a vertex needs three coordinates"))?;
            *x = t
                .parse::<f64>()
                .map_err(|_| bad(n, format!("{} is not a number", quoted(t))))?;
        }
        vertices.push(c);
    }
    let mut faces = Polygons::with_capacity(capped(nf, bytes.len()), capped(3 * nf, bytes.len()));
    let mut poly: Vec<u32> = Vec::new();
    for k in 0..nf {
        let (n, l) = lines.next().ok_or_else(|| {
            bad(
                text.lines().count(),
                format!(
                    "expected {nf} {}, found {k}",
                    if nf == 1 { "face" } else { "faces" }
                ),
            )
        })?;
        let mut tokens = l.split_whitespace();
        let count: usize = tokens
            .next()
            .and_then(|t| t.parse().ok())
            .ok_or_else(|| bad(n, "a face starts with its number of vertices"))?;
        if count < 3 {
            return Err(bad(
                n,
                format!("face {k} has {count} vertices; a face needs at least 3"),
            ));
        }
        poly.clear();
        for listed in 0..count {
            let t = tokens.next().ok_or_else(|| {
                bad(
                    n,
                    format!("face {k} declares {count} vertices but lists {listed}"),
                )
            })?;
            let i: usize = t
                .parse()
                .map_err(|_| bad(n, format!("{} is not a vertex index", quoted(t))))?;
            if i >= nv {
                return Err(bad(
                    n,
                    format!("face {k} refers to vertex {i}, but there are only {nv} vertices"),
                ));
            }
            poly.push(i as u32);
        }
        check_face_colour(tokens, k, count, n)?;
        faces.push(&poly);
    }
    if let Some((n, _)) = lines.next() {
        return Err(bad(
            n,
            format!(
                "data after the {nf} declared {}",
                if nf == 1 { "face" } else { "faces" }
            ),
        ));
    }
    Ok(RawObject {
        name: None,
        vertices,
        faces,
    })
}

/// Formats a coordinate as the shortest decimal that reads back as the same `f64`
/// (as the writers write it; apart-mesh shows grid points in messages with it).
pub fn number(v: f64) -> String {
    if v == 0.0 {
        "0".to_string() // no "-0"
    } else {
        format!("{v}")
    }
}

/// Writes an OFF file.
pub fn write(out: &mut impl Write, vertices: &[[f64; 3]], faces: &Polygons) -> std::io::Result<()> {
    writeln!(out, "OFF")?;
    writeln!(out, "{} {} 0", vertices.len(), faces.len())?;
    for v in vertices {
        writeln!(out, "{} {} {}", number(v[0]), number(v[1]), number(v[2]))?;
    }
    for f in faces.iter() {
        write!(out, "{}", f.len())?;
        for i in f {
            write!(out, " {i}")?;
        }
        writeln!(out)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_variants_and_comments() {
        let a =
            read(b"OFF\n# a comment\n3 1 0\n0 0 0\n1 0 0 # trailing\n0 1 0\n3 0 1 2\n").unwrap();
        assert_eq!(a.vertices.len(), 3);
        assert_eq!(a.faces.get(0), &[0, 1, 2]);
        let b = read(b"COFF 3 1 3\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n0 1 0 1 1 1 1\n3 0 1 2 255 0 0\n")
            .unwrap();
        assert_eq!(b.vertices[1], [1.0, 0.0, 0.0]);
        let c = read(b"3 1\n0 0 0\n0.1 0 0\n0 1e3 0\n3 2 1 0\n").unwrap();
        assert_eq!(c.vertices[1][0], 0.1);
        assert_eq!(c.vertices[2][1], 1000.0);
        let d = read(b"OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n").unwrap();
        assert_eq!(d.faces.get(0).len(), 4);
    }

    #[test]
    fn errors_name_the_line() {
        let e = read(b"OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n").unwrap_err();
        assert!(e.to_string().contains("line 4"), "{e}");
        let e = read(b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n").unwrap_err();
        assert!(e.to_string().contains("vertex 7"), "{e}");
        assert!(read(b"").is_err());
        assert!(read(b"4OFF\n").is_err());
        assert!(read(b"OFF BINARY\n").is_err());
        assert!(read(b"OFF\n3 1 0\n0 0 0\n").is_err());
    }

    #[test]
    fn nan_is_read_not_rejected() {
        // Non-finite values are a validation problem that names the vertex.
        let a = read(b"OFF\n3 1 0\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
        assert!(a.vertices[0][0].is_nan());
    }

    #[test]
    fn write_then_read() {
        let v = vec![[0.0, -0.0, 1.5], [0.1, 2.0, -3.25], [1e-300, 0.0, 0.0]];
        let f = Polygons::from(vec![vec![0, 1, 2]]);
        let mut buf = Vec::new();
        write(&mut buf, &v, &f).unwrap();
        let back = read(&buf).unwrap();
        assert_eq!(
            back.vertices,
            vec![[0.0, 0.0, 1.5], [0.1, 2.0, -3.25], [1e-300, 0.0, 0.0]]
        );
        assert_eq!(back.faces, f);
    }

    #[test]
    fn huge_counts_and_hostile_tokens() {
        let e = read(b"OFF\n4000000000 4000000000 0\n0 0 0\n")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("line 2: 4000000000 vertices and 4000000000 faces declared, more than the 34 bytes of the file can hold"),
            "{e}"
        );
        assert!(read(b"OFF\n0 40 0\n").is_err());
        // Tokens are quoted escaped, and long ones cut.
        let e = read(b"OFF\n3 1 0\n\x1b[2J 0 0\n").unwrap_err().to_string();
        assert!(
            e.contains("\"\\x1b[2J\" is not a number") && !e.contains('\x1b'),
            "{e}"
        );
        let mut long = b"OFF\n1 0 0\n".to_vec();
        long.extend(std::iter::repeat_n(b'x', 10_000));
        let e = read(&long).unwrap_err().to_string();
        assert!(e.len() < 200, "{e}");
        let e = read(b"\x07OFF\n").unwrap_err().to_string();
        assert!(e.contains("\\x07OFF") && !e.contains('\x07'), "{e}");
    }
}
