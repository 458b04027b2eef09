//! Wavefront OBJ, read with tobj (positions as `f64`, polygons kept as written).
//! Every `o` or `g` statement starts a new object; groups of the same name (tobj also
//! splits a group where its material changes) are merged back into one object.
//! Materials, normals and texture coordinates are ignored.

use crate::raw::{Polygons, RawObject};
use crate::{Format, ReadError};
use std::io::Write;

/// Parses an OBJ file into one object per group.
pub fn read(bytes: &[u8]) -> Result<Vec<RawObject>, ReadError> {
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let mut reader = std::io::BufReader::new(bytes);
    let (models, _materials) = tobj::load_obj_buf(&mut reader, &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| ReadError::malformed(Format::Obj, e.to_string()))?;
    let mut objects: Vec<RawObject> = Vec::new();
    // Where each name's object is (a hash map: a file of many groups stays linear).
    let mut by_name: std::collections::HashMap<Option<String>, usize> = Default::default();
    for model in models {
        let m = &model.mesh;
        if m.indices.is_empty() {
            continue;
        }
        if m.positions.len() % 3 != 0 {
            return Err(ReadError::malformed(Format::Obj, "incomplete vertex"));
        }
        let vertices: Vec<[f64; 3]> = m
            .positions
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect();
        let n = vertices.len() as u32;
        if let Some(&bad) = m.indices.iter().find(|&&i| i >= n) {
            return Err(ReadError::malformed(
                Format::Obj,
                format!("face refers to vertex {}, which does not exist", bad + 1),
            ));
        }
        let mut faces = Polygons::new();
        if m.face_arities.is_empty() {
            for t in m.indices.chunks_exact(3) {
                faces.push(t);
            }
        } else {
            let mut start = 0usize;
            for &a in &m.face_arities {
                let end = start + a as usize;
                let poly = m.indices.get(start..end).ok_or_else(|| {
                    ReadError::malformed(Format::Obj, "face arities do not match the indices")
                })?;
                faces.push(poly);
                start = end;
            }
        }
        let name =
            (!model.name.is_empty() && model.name != "unnamed_object").then(|| model.name.clone());
        let object = RawObject {
            name,
            vertices,
            faces,
        };
        match by_name.get(&object.name) {
            Some(&k) => objects[k].append(&object),
            None => {
                by_name.insert(object.name.clone(), objects.len());
                objects.push(object);
            }
        }
    }
    Ok(objects)
}

/// Writes objects as OBJ, one `o` group each (1-based indices, as the format wants).
pub fn write(out: &mut impl Write, objects: &[RawObject]) -> std::io::Result<()> {
    let mut base = 1usize;
    for (k, o) in objects.iter().enumerate() {
        let name = o.name.clone().unwrap_or_else(|| format!("object{k}"));
        writeln!(out, "o {name}")?;
        for v in &o.vertices {
            writeln!(
                out,
                "v {} {} {}",
                crate::off::number(v[0]),
                crate::off::number(v[1]),
                crate::off::number(v[2])
            )?;
        }
        for f in o.faces.iter() {
            write!(out, "f")?;
            for &i in f {
                write!(out, " {}", i as usize + base)?;
            }
            writeln!(out)?;
        }
        base += o.vertices.len();
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_become_objects() {
        let text = b"# two parts\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n\
o first\nf 1 2 3\nf 1 3 4\no second\nv 5 5 5\nf 2 3 4 5\n";
        let objs = read(text).unwrap();
        assert_eq!(objs.len(), 2);
        assert_eq!(objs[0].name.as_deref(), Some("first"));
        assert_eq!(objs[0].faces.len(), 2);
        assert_eq!(objs[1].faces.get(0).len(), 4);
        // Indices are per object: the quad uses 4 distinct vertices of its own list.
        let q = objs[1].faces.get(0);
        assert_eq!(objs[1].vertices[q[3] as usize], [5.0, 5.0, 5.0]);
    }

    #[test]
    fn many_groups_take_linear_time() {
        let mut text = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
        for k in 0..30_000 {
            text.push_str(&format!("o part{}\nf 1 2 3\n", k % 20_000));
        }
        let t = std::time::Instant::now();
        let objs = read(text.as_bytes()).unwrap();
        assert_eq!(objs.len(), 20_000);
        assert_eq!(objs[5].faces.len(), 2);
        assert_eq!(objs[19_999].faces.len(), 1);
        assert!(t.elapsed().as_secs() < 20, "{:?}", t.elapsed());
    }

    #[test]
    fn write_then_read() {
        let o = RawObject {
            name: Some("a".into()),
            vertices: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.1, 0.0]],
            faces: Polygons::from_triangles(&[[0, 1, 2]]),
        };
        let mut buf = Vec::new();
        write(
            &mut buf,
            &[
                o.clone(),
                RawObject {
                    name: Some("b".into()),
                    ..o.clone()
                },
            ],
        )
        .unwrap();
        let back = read(&buf).unwrap();
        assert_eq!(back.len(), 2);
        assert_eq!(back[0], o);
        assert_eq!(back[1].vertices, o.vertices);
    }
}
