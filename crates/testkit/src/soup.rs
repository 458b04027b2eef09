//! A mesh as plain data, and writers for it.

use std::io::Write;

/// Vertices and polygons (indices into `vertices`, counter-clockwise seen from outside
/// unless a generator says otherwise).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Soup {
    /// Vertex coordinates.
    pub vertices: Vec<[f64; 3]>,
    /// Polygons as vertex index lists.
    pub faces: Vec<Vec<u32>>,
}

impl Soup {
    /// Appends `other`, renumbering its vertices (no welding).
    pub fn append(&mut self, other: &Soup) {
        let base = self.vertices.len() as u32;
        self.vertices.extend_from_slice(&other.vertices);
        self.faces.extend(
            other
                .faces
                .iter()
                .map(|f| f.iter().map(|&v| v + base).collect()),
        );
    }

    /// The soup moved by `t`.
    pub fn translated(mut self, t: [f64; 3]) -> Soup {
        for v in &mut self.vertices {
            for k in 0..3 {
                v[k] += t[k];
            }
        }
        self
    }

    /// Writes the soup as an ASCII OFF file (coordinates printed exactly: Rust's
    /// shortest round-trip decimal).
    pub fn write_off(&self, out: &mut impl Write) -> std::io::Result<()> {
        writeln!(out, "OFF")?;
        writeln!(out, "{} {} 0", self.vertices.len(), self.faces.len())?;
        for v in &self.vertices {
            writeln!(out, "{:?} {:?} {:?}", v[0], v[1], v[2])?;
        }
        for f in &self.faces {
            write!(out, "{}", f.len())?;
            for i in f {
                write!(out, " {i}")?;
            }
            writeln!(out)?;
        }
        Ok(())
    }

    /// The OFF file as bytes.
    pub fn to_off(&self) -> Vec<u8> {
        let mut out = Vec::new();
        self.write_off(&mut out).expect("writing to a vector");
        out
    }

    /// Writes the soup as a binary STL file: polygons fanned into triangles, coordinates
    /// rounded to `f32` as binary STL stores them (the float32 rounding of real exports).
    pub fn write_binary_stl(&self, out: &mut impl Write) -> std::io::Result<()> {
        let tris: Vec<[u32; 3]> = self
            .faces
            .iter()
            .flat_map(|f| (1..f.len().saturating_sub(1)).map(move |k| [f[0], f[k], f[k + 1]]))
            .collect();
        out.write_all(&[0u8; 80])?;
        out.write_all(&(tris.len() as u32).to_le_bytes())?;
        for t in tris {
            out.write_all(&[0u8; 12])?;
            for v in t {
                for c in self.vertices[v as usize] {
                    out.write_all(&(c as f32).to_le_bytes())?;
                }
            }
            out.write_all(&[0u8; 2])?;
        }
        Ok(())
    }
}

/// Standard base64 with padding, for the data URIs of test glTF files.
pub fn base64(bin: &[u8]) -> String {
    const T: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for chunk in bin.chunks(3) {
        let n = chunk
            .iter()
            .enumerate()
            .fold(0u32, |a, (i, &b)| a | (b as u32) << (16 - 8 * i));
        for k in 0..4 {
            s.push(if k <= chunk.len() {
                T[(n >> (18 - 6 * k) & 63) as usize] as char
            } else {
                '='
            });
        }
    }
    s
}
