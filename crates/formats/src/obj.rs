//! Wavefront OBJ, read with tobj (positions as `f64`, polygons kept as written).
//! Every `o` or `g` statement starts a new object; groups of the same name (tobj also
//! splits a group where its material changes) are merged back into one object.
//! Materials, normals, texture coordinates, vertex colours, points and lines are
//! ignored.
//!
//! Before tobj sees the file, every line is checked here, so that errors name the line
//! and the vertex or face: a vertex has three coordinates (and then nothing, a `w`
//! other than 0, or three colour values); a face has at least three vertices, each a
//! `v`, `v/vt`, `v//vn` or `v/vt/vn` reference whose vertex index (from 1, or negative,
//! counting back from the last vertex) names a vertex defined before the face. What
//! tobj is given is the file rewritten: absolute vertex indices, the ignored statements
//! left out (so that texture and normal indices, which are not read, cannot fail), and
//! bytes that are not UTF-8 replaced in names and comments.

use crate::escape::quoted;
use crate::raw::{Polygons, RawObject};
use crate::{Format, ReadError};
use std::fmt::Write as _;
use std::io::Write;

fn bad(line: usize, detail: impl std::fmt::Display) -> ReadError {
    ReadError::malformed(Format::Obj, format!("line {line}: {detail}"))
}

/// `8 vertices are`, `1 vertex is`.
fn defined(n: usize) -> String {
    match n {
        1 => "only 1 vertex is".to_string(),
        n => format!("only {n} vertices are"),
    }
}

/// The 1-based index of the vertex that `token` (`v`, `v/vt`, `v//vn`, `v/vt/vn`) names
/// in a face, when `count` vertices are defined before it.
fn vertex_reference(token: &str, count: usize) -> Result<usize, String> {
    let not_a_reference = || {
        format!(
            "{} is not a vertex reference (v, v/vt, v//vn or v/vt/vn)",
            quoted(token)
        )
    };
    let is_integer = |t: &str| {
        let digits = t.strip_prefix('-').unwrap_or(t);
        !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit())
    };
    let mut parts = token.split('/');
    let v = parts.next().unwrap_or("");
    let rest: Vec<&str> = parts.collect();
    if !is_integer(v) || rest.len() > 2 || rest.iter().any(|t| !t.is_empty() && !is_integer(t)) {
        return Err(not_a_reference());
    }
    let beyond = || {
        format!(
            "refers to vertex {v} but {} defined before it",
            defined(count)
        )
    };
    match v.parse::<i64>() {
        Ok(0) => Err(format!("refers to vertex {v}; OBJ indices start at 1")),
        Ok(i) if i > 0 && i as u64 <= count as u64 => Ok(i as usize),
        // Relative: -1 is the last vertex defined.
        Ok(i) if i < 0 && i.unsigned_abs() <= count as u64 => {
            Ok(count + 1 - i.unsigned_abs() as usize)
        }
        // Too far either way, also beyond the range of i64.
        _ => Err(beyond()),
    }
}

/// The tokens of a line before a `#` comment.
fn tokens(line: &str) -> impl Iterator<Item = &str> {
    line.split_whitespace().take_while(|t| !t.starts_with('#'))
}

/// The file checked line by line (see the module documentation) and rewritten for tobj.
fn checked(bytes: &[u8]) -> Result<String, ReadError> {
    let mut out = String::with_capacity(bytes.len());
    let (mut vertices, mut faces) = (0usize, 0usize);
    for (i, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let n = i + 1;
        let line = String::from_utf8_lossy(raw);
        let mut tok = tokens(&line);
        match tok.next() {
            Some("v") => {
                vertices += 1;
                let values: Vec<&str> = tok.collect();
                let number = |t: &&str| t.parse::<f64>().is_ok();
                if values.len() < 3 {
                    return Err(bad(
                        n,
                        format!("vertex {vertices} has {} coordinates, not 3", values.len()),
                    ));
                }
                if let Some(t) = values.iter().find(|t| !number(t)) {
                    return Err(bad(
                        n,
                        format!("vertex {vertices}: {} is not a number", quoted(t)),
                    ));
                }
                let keep = match values.len() {
                    3 | 6 => 3, // colours are not read
                    4 if values[3].parse::<f64>() == Ok(0.0) => {
                        return Err(bad(n, format!("vertex {vertices} has a weight w of 0")))
                    }
                    4 => 4,
                    k => {
                        return Err(bad(
                            n,
                            format!(
                                "vertex {vertices} has {k} numbers; a vertex is x y z, x y z w or x y z r g b"
                            ),
                        ))
                    }
                };
                out.push('v');
                for t in &values[..keep] {
                    out.push(' ');
                    out.push_str(t);
                }
                out.push('\n');
            }
            Some("f") => {
                faces += 1;
                let refs: Vec<&str> = tok.collect();
                if refs.len() < 3 {
                    return Err(bad(
                        n,
                        format!(
                            "face {faces} has {} vertices; a face needs at least 3",
                            refs.len()
                        ),
                    ));
                }
                out.push('f');
                for t in refs {
                    let v = vertex_reference(t, vertices)
                        .map_err(|why| bad(n, format!("face {faces} {why}")))?;
                    let _ = write!(out, " {v}");
                }
                out.push('\n');
            }
            Some(keyword @ ("o" | "g")) => {
                let at = line.find(keyword).unwrap_or(0) + 1;
                let _ = writeln!(out, "{keyword} {}", line[at..].trim());
            }
            // Comments and statements that are not read.
            _ => {}
        }
    }
    Ok(out)
}

/// Parses an OBJ file into one object per group.
pub fn read(bytes: &[u8]) -> Result<Vec<RawObject>, ReadError> {
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let text = checked(bytes)?;
    let mut reader = std::io::BufReader::new(text.as_bytes());
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
