//! Stanford PLY, ASCII and binary, read with ply-rs-bw into compact elements: the
//! `vertex` element's `x`, `y`, `z` (any numeric type, converted to `f64` exactly) and
//! the `face` element's `vertex_indices` (or `vertex_index`) list. Other elements and
//! properties are ignored. Values are read with the type the header declares: an ASCII
//! `float` property is an `f32`, as the format says; use `double` for full precision.
//!
//! Before any payload is read, every element's declared count is compared with what
//! the bytes after the header can hold (each entry at least its binary size, or one
//! digit and one separator per ASCII value, and at least one byte even without
//! properties), so a 250-byte file declaring four billion faces is an error at once.
//!
//! The data must then match the header exactly: in ASCII, one line per entry holding
//! the values its properties take (a list its length and that many values), then only
//! blank lines; in binary, no bytes after the last entry. Faces have at least three
//! vertices. Errors name the line in ASCII, the element and entry in binary.

use crate::escape::quoted;
use crate::raw::{Polygons, RawObject};
use crate::{Format, ReadError};
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{
    ElementDef, Encoding, Header, Property, PropertyAccess, PropertyAccessResult, PropertyType,
    ScalarType,
};

#[derive(Default)]
struct Element {
    xyz: [f64; 3],
    seen: u8,
    list: Vec<u32>,
    negative_index: bool,
}

fn scalar(p: &Property) -> Option<f64> {
    Some(match *p {
        Property::Char(v) => v as f64,
        Property::UChar(v) => v as f64,
        Property::Short(v) => v as f64,
        Property::UShort(v) => v as f64,
        Property::Int(v) => v as f64,
        Property::UInt(v) => v as f64,
        Property::Float(v) => v as f64,
        Property::Double(v) => v,
        _ => return None,
    })
}

impl Element {
    fn set_list<T: Copy + TryInto<u32>>(&mut self, v: &[T]) {
        self.list.clear();
        for &x in v {
            match x.try_into() {
                Ok(i) => self.list.push(i),
                Err(_) => self.negative_index = true,
            }
        }
    }
}

impl PropertyAccess for Element {
    fn new() -> Self {
        Element::default()
    }

    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        let axis = match name {
            "x" => Some(0),
            "y" => Some(1),
            "z" => Some(2),
            _ => None,
        };
        if let Some(k) = axis {
            if let Some(v) = scalar(&property) {
                self.xyz[k] = v;
                self.seen |= 1 << k;
            }
            return PropertyAccessResult::Set;
        }
        if name == "vertex_indices" || name == "vertex_index" {
            match &property {
                Property::ListChar(v) => self.set_list(v),
                Property::ListUChar(v) => self.set_list(v),
                Property::ListShort(v) => self.set_list(v),
                Property::ListUShort(v) => self.set_list(v),
                Property::ListInt(v) => self.set_list(v),
                Property::ListUInt(v) => self.set_list(v),
                _ => return PropertyAccessResult::UnsupportedType,
            }
            return PropertyAccessResult::Set;
        }
        PropertyAccessResult::Ignored
    }
}

/// Elements other than `vertex` and `face`: read (they must be skipped) but not kept.
struct Skip;

impl PropertyAccess for Skip {
    fn new() -> Self {
        Skip
    }
}

fn scalar_size(t: &ScalarType) -> u64 {
    match t {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
}

/// The fewest bytes one entry of `e` takes: in binary, its scalars and list lengths
/// (empty lists); in ASCII, one digit and one separator per value. An entry without
/// properties counts as one byte, so that no element, even an empty one, may declare
/// more entries than the file has bytes.
fn min_entry_bytes(e: &ElementDef, encoding: &Encoding) -> u64 {
    let bytes: u64 = match encoding {
        Encoding::Ascii => 2 * e.properties.len() as u64,
        _ => e
            .properties
            .values()
            .map(|p| match &p.data_type {
                PropertyType::Scalar(t) | PropertyType::List(t, _) => scalar_size(t),
            })
            .sum(),
    };
    bytes.max(1)
}

/// Compares every element's declared count with what the `payload` bytes after the
/// header could hold, before anything is allocated for them.
fn check_counts(header: &Header, payload: usize) -> Result<(), ReadError> {
    let mut need: u128 = 0;
    for e in header.elements.values() {
        let min = min_entry_bytes(e, &header.encoding);
        need += e.count as u128 * min as u128;
        // An ASCII file's last line may lack its line break.
        let slack = u128::from(header.encoding == Encoding::Ascii);
        if need > payload as u128 + slack {
            return Err(ReadError::malformed(
                Format::Ply,
                format!(
                    "element {} declares {} entries of at least {min} byte{} each, more than the {payload} bytes after the header can hold",
                    quoted(&e.name),
                    e.count,
                    if min == 1 { "" } else { "s" },
                ),
            ));
        }
    }
    Ok(())
}

/// `face 3`, `vertex 0`, or `entry 2 of element "junk"`.
fn entry(element: &str, k: usize) -> String {
    match element {
        "vertex" | "face" => format!("{element} {k}"),
        _ => format!("entry {k} of element {}", quoted(element)),
    }
}

/// Checks that the ASCII `payload`, whose first line is line `first` of the file, holds
/// one line per declared entry with exactly the values its properties take (a list
/// takes its length and that many values), then nothing but blank lines. Returns the
/// line of the first face. Values themselves are left to the parser.
fn check_ascii_lines(header: &Header, payload: &[u8], first: usize) -> Result<usize, ReadError> {
    let bad = |line: usize, detail: String| {
        ReadError::malformed(Format::Ply, format!("line {line}: {detail}"))
    };
    // Lines end with a line break (the last may lack it); no bytes, no lines.
    let body = payload.strip_suffix(b"\n").unwrap_or(payload);
    let mut lines = (!payload.is_empty())
        .then(|| body.split(|&b| b == b'\n'))
        .into_iter()
        .flatten();
    let mut n = first - 1;
    let mut face_line = 0;
    for e in header.elements.values() {
        if e.name == "face" {
            face_line = n + 1;
        }
        for k in 0..e.count {
            n += 1;
            let line = lines.next().ok_or_else(|| {
                bad(
                    n - 1,
                    format!(
                        "the file ends after {k} of the {} declared entries of element {}",
                        e.count,
                        quoted(&e.name)
                    ),
                )
            })?;
            let tokens: Vec<&[u8]> = line
                .split(|b| b.is_ascii_whitespace())
                .filter(|t| !t.is_empty())
                .collect();
            let mut want = 0usize;
            for p in e.properties.values() {
                want = want.saturating_add(1);
                if let PropertyType::List(..) = p.data_type {
                    let Some(len) = tokens.get(want - 1) else {
                        break;
                    };
                    let Some(len) = std::str::from_utf8(len)
                        .ok()
                        .and_then(|t| t.parse::<usize>().ok())
                    else {
                        // Not a length: the parser says why.
                        return Ok(face_line);
                    };
                    want = want.saturating_add(len);
                }
            }
            if tokens.len() != want {
                return Err(bad(
                    n,
                    format!(
                        "{} has {} values, but its properties (and list lengths) call for {want}",
                        entry(&e.name, k),
                        tokens.len()
                    ),
                ));
            }
        }
    }
    for line in lines {
        n += 1;
        if !line.trim_ascii().is_empty() {
            return Err(bad(n, "data after the declared elements".to_string()));
        }
    }
    Ok(face_line)
}

/// Parses a PLY file.
pub fn read(bytes: &[u8]) -> Result<RawObject, ReadError> {
    let bad = |e: ply_rs_bw::parser::ParseError| ReadError::malformed(Format::Ply, e.to_string());
    let mut reader = Reader::new(bytes);
    let header = Parser::<Skip>::new()
        .read_header(&mut reader)
        .map_err(bad)?;
    let payload = reader.get_ref().len();
    let header_bytes = bytes.len() - payload;
    check_counts(&header, payload)?;
    // Where each face is, for messages: its line in ASCII.
    let face_at = match header.encoding {
        Encoding::Ascii => {
            let first = bytes[..header_bytes]
                .iter()
                .filter(|&&b| b == b'\n')
                .count()
                + 1;
            let face_line = check_ascii_lines(&header, &bytes[header_bytes..], first)?;
            Some(face_line)
        }
        _ => None,
    };
    let face = |k: usize| match face_at {
        Some(line) => format!("line {}: face {k}", line + k),
        None => format!("face {k}"),
    };
    // Binary data has no lines: the parser's line number would mislead.
    let bad = |e: ply_rs_bw::parser::ParseError| {
        let text = e.to_string();
        let text = match (face_at, e.line()) {
            (None, Some(l)) => text
                .strip_prefix(&format!("Line {l}: "))
                .unwrap_or(&text)
                .to_string(),
            _ => text,
        };
        ReadError::malformed(Format::Ply, text)
    };
    let vertex = header
        .elements
        .get("vertex")
        .ok_or_else(|| ReadError::malformed(Format::Ply, "no \"vertex\" element"))?;
    for axis in ["x", "y", "z"] {
        if !matches!(
            vertex.properties.get(axis).map(|p| &p.data_type),
            Some(PropertyType::Scalar(_))
        ) {
            return Err(ReadError::malformed(
                Format::Ply,
                format!("the \"vertex\" element has no number property \"{axis}\""),
            ));
        }
    }
    let keep = Parser::<Element>::new();
    let skip = Parser::<Skip>::new();
    let mut vertex_elems = Vec::new();
    let mut face_elems = Vec::new();
    for (name, def) in &header.elements {
        match name.as_str() {
            "vertex" => {
                vertex_elems = keep
                    .read_payload_for_element(&mut reader, def, &header)
                    .map_err(bad)?
            }
            "face" => {
                face_elems = keep
                    .read_payload_for_element(&mut reader, def, &header)
                    .map_err(bad)?
            }
            _ => drop(
                skip.read_payload_for_element(&mut reader, def, &header)
                    .map_err(bad)?,
            ),
        }
    }
    let mut vertices = Vec::with_capacity(vertex_elems.len());
    for (i, v) in vertex_elems.iter().enumerate() {
        if v.seen != 7 {
            return Err(ReadError::malformed(
                Format::Ply,
                format!("vertex {i} lacks an x, y or z property"),
            ));
        }
        vertices.push(v.xyz);
    }
    let n = vertices.len();
    let mut faces = Polygons::new();
    // Binary: nothing after the elements (ASCII was checked line by line).
    let rest = reader.get_ref().len();
    if face_at.is_none() && rest > 0 {
        return Err(ReadError::malformed(
            Format::Ply,
            format!(
                "{rest} bytes after the declared elements, from byte offset {}",
                bytes.len() - rest
            ),
        ));
    }
    for (k, f) in face_elems.iter().enumerate() {
        if f.negative_index {
            return Err(ReadError::malformed(
                Format::Ply,
                format!("{} has a negative vertex index", face(k)),
            ));
        }
        if f.list.len() < 3 {
            return Err(ReadError::malformed(
                Format::Ply,
                format!(
                    "{} has {} vertices; a face needs at least 3",
                    face(k),
                    f.list.len()
                ),
            ));
        }
        if let Some(&bad) = f.list.iter().find(|&&i| i as usize >= n) {
            let only = if n == 1 {
                "is only 1 vertex".to_string()
            } else {
                format!("are only {n} vertices")
            };
            return Err(ReadError::malformed(
                Format::Ply,
                format!("{} refers to vertex {bad}, but there {only}", face(k)),
            ));
        }
        faces.push(&f.list);
    }
    Ok(RawObject {
        name: None,
        vertices,
        faces,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_ply() {
        let text = "ply\nformat ascii 1.0\ncomment hi\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\nproperty uchar red\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0 1\n1 0 0 1\n0 1 0.1 1\n0 0 1 1\n3 0 2 1\n4 0 1 2 3\n";
        let o = read(text.as_bytes()).unwrap();
        assert_eq!(o.vertices.len(), 4);
        assert_eq!(o.vertices[2], [0.0, 1.0, 0.1]);
        assert_eq!(o.faces.get(0), &[0, 2, 1]);
        assert_eq!(o.faces.get(1).len(), 4);
    }

    #[test]
    fn binary_ply() {
        let mut b = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n".to_vec();
        for v in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.5, 0.0]] {
            for c in v {
                b.extend_from_slice(&c.to_le_bytes());
            }
        }
        b.push(3);
        for i in [0u32, 1, 2] {
            b.extend_from_slice(&i.to_le_bytes());
        }
        let o = read(&b).unwrap();
        assert_eq!(o.vertices[2], [0.0, 0.5, 0.0]);
        assert_eq!(o.faces.get(0), &[0, 1, 2]);
        assert!(read(&b[..b.len() - 3]).is_err());
    }

    #[test]
    fn bad_index() {
        let text = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n3 0 1 2\n";
        assert!(read(text.as_bytes())
            .unwrap_err()
            .to_string()
            .contains("vertex 1"));
    }

    #[test]
    fn huge_counts_are_refused_before_allocating() {
        let xyz = "property float x\nproperty float y\nproperty float z\n";
        for (format, elements, want) in [
            // No properties at all: each entry still counts one byte.
            (
                "binary_little_endian",
                "element vertex 4000000000\n".to_string(),
                "element \"vertex\" declares 4000000000 entries of at least 1 byte each",
            ),
            (
                "binary_little_endian",
                format!("element vertex 3\n{xyz}element junk 4000000000\n"),
                "element \"junk\" declares 4000000000 entries of at least 1 byte each",
            ),
            (
                "binary_big_endian",
                format!("element vertex 3\n{xyz}element face 4000000000\nproperty list uchar int vertex_indices\n"),
                "element \"face\" declares 4000000000 entries of at least 1 byte each",
            ),
            (
                "ascii",
                format!("element vertex 3\n{xyz}element face 4000000000\nproperty list uchar int vertex_indices\n"),
                "element \"face\" declares 4000000000 entries of at least 2 bytes each",
            ),
            (
                "binary_little_endian",
                format!("element vertex 1000\n{xyz}"),
                "element \"vertex\" declares 1000 entries of at least 12 bytes each",
            ),
        ] {
            let mut b = format!("ply\nformat {format} 1.0\n{elements}end_header\n").into_bytes();
            b.resize(250, b'0');
            let t = std::time::Instant::now();
            let e = read(&b).unwrap_err().to_string();
            assert!(e.contains(want) && e.contains("bytes after the header can hold"), "{e}");
            assert!(t.elapsed().as_secs() < 2);
        }
        // A vertex element without coordinates is refused from the header.
        let e = read(b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("no number property \"y\""), "{e}");
        // Elements other than vertex and face are read past, and not kept.
        let text = format!("ply\nformat ascii 1.0\nelement vertex 3\n{xyz}element junk 2\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n\n\n3 0 1 2\n");
        let o = read(text.as_bytes()).unwrap();
        assert_eq!(o.faces.get(0), &[0, 1, 2]);
    }

    #[test]
    fn messages_escape_file_text() {
        let text = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 \x1b[2J\n";
        let e = read(text.as_bytes()).unwrap_err().to_string();
        assert!(!e.contains('\x1b') && !e.contains('\n'), "{e}");
    }
}
