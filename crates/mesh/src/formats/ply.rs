//! Stanford PLY, ASCII and binary, read with ply-rs-bw into compact elements: the
//! `vertex` element's `x`, `y`, `z` (any numeric type, converted to `f64` exactly) and
//! the `face` element's `vertex_indices` (or `vertex_index`) list. Other elements and
//! properties are ignored. Values are read with the type the header declares: an ASCII
//! `float` property is an `f32`, as the format says; use `double` for full precision.

use super::{Format, ReadError};
use crate::raw::{Polygons, RawObject};
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{Property, PropertyAccess, PropertyAccessResult};

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

/// Parses a PLY file.
pub fn read(bytes: &[u8]) -> Result<RawObject, ReadError> {
    let mut src = bytes;
    let ply = Parser::<Element>::new()
        .read_ply(&mut src)
        .map_err(|e| ReadError::malformed(Format::Ply, e.to_string()))?;
    let vertex_elems = ply
        .payload
        .get("vertex")
        .ok_or_else(|| ReadError::malformed(Format::Ply, "no \"vertex\" element"))?;
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
    for (k, f) in ply.payload.get("face").into_iter().flatten().enumerate() {
        if f.negative_index {
            return Err(ReadError::malformed(
                Format::Ply,
                format!("face {k} has a negative vertex index"),
            ));
        }
        if let Some(&bad) = f.list.iter().find(|&&i| i as usize >= n) {
            return Err(ReadError::malformed(
                Format::Ply,
                format!("face {k} refers to vertex {bad}, but there are only {n} vertices"),
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
}
