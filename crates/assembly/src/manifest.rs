//! The `assembly.json` manifest (schema: `docs/assembly.schema.json`).
//!
//! ```json
//! {"name": "star", "parts": [
//!   {"name": "red", "mesh": "red.off",
//!    "transform": {"translation": [1, 0, 0], "rotation": {"axis": [0, 0, 1], "angle_deg": 90}},
//!    "pieces": ["red/p0.off", "red/p1.off"]}]}
//! ```
//!
//! Paths are relative to the manifest's folder, and must resolve inside it when loaded
//! (the loader checks, through symbolic links; [`crate::LoadOptions::allow_outside`]
//! lifts this). `transform` is either
//! `{"matrix": [16 numbers]}` (4x4, row-major, last row `0 0 0 1`) or
//! `{"translation": [x, y, z], "rotation": ...}` with the rotation given as
//! `{"axis": [x, y, z], "angle_deg": a}` or `{"quaternion": [x, y, z, w]}`; the rotation
//! is applied first. Matrix entries within 4 ulps of 0, ±1/2 or ±1 are snapped to those
//! values. Unknown keys are ignored, except inside `transform`, where an unknown key or
//! both a matrix and a translation or rotation is an error.

use apart_formats::transform::{Affine, TOL_F64};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// One part of a manifest.
#[derive(Clone, Debug, PartialEq)]
pub struct ManifestPart {
    /// Its name.
    pub name: String,
    /// The boundary mesh, resolved against the manifest's folder.
    pub mesh: Option<PathBuf>,
    /// Convex pieces, resolved against the manifest's folder.
    pub pieces: Vec<PathBuf>,
    /// Applied to the mesh and the pieces before snapping.
    pub transform: Affine,
}

/// A parsed manifest.
#[derive(Clone, Debug, PartialEq)]
pub struct Manifest {
    /// The assembly's name, if given.
    pub name: Option<String>,
    /// The parts, in order.
    pub parts: Vec<ManifestPart>,
}

fn numbers<const N: usize>(v: &Value, what: &str) -> Result<[f64; N], String> {
    let a = v
        .as_array()
        .filter(|a| a.len() == N)
        .ok_or_else(|| format!("{what} must be an array of {N} numbers"))?;
    let mut out = [0.0; N];
    for (o, x) in out.iter_mut().zip(a) {
        *o = x
            .as_f64()
            .filter(|f| f.is_finite())
            .ok_or_else(|| format!("{what} must be an array of {N} finite numbers"))?;
    }
    Ok(out)
}

/// `dir/name`, or just `name` when `dir` is the current folder (for shorter messages).
pub(crate) fn join(dir: &Path, name: &Path) -> PathBuf {
    if dir.as_os_str().is_empty() || dir == Path::new(".") {
        name.to_path_buf()
    } else {
        dir.join(name)
    }
}

/// Fails on a key of `obj` not in `known`: in a transform, a misspelt or unsupported key
/// (a `scale`, say) would otherwise change the geometry without a word.
fn only_keys(
    obj: &serde_json::Map<String, Value>,
    what: &str,
    known: &[&str],
) -> Result<(), String> {
    match obj.keys().find(|k| !known.contains(&k.as_str())) {
        None => Ok(()),
        Some(k) => Err(format!(
            "{what} has an unknown key {k:?}; its keys are {}",
            known
                .iter()
                .map(|k| format!("{k:?}"))
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// Parses a `transform` object.
pub fn parse_transform(v: &Value) -> Result<Affine, String> {
    let obj = v.as_object().ok_or("transform must be an object")?;
    only_keys(obj, "transform", &["matrix", "translation", "rotation"])?;
    if obj.contains_key("matrix")
        && (obj.contains_key("translation") || obj.contains_key("rotation"))
    {
        return Err("transform gives both \"matrix\" and \"translation\" or \"rotation\"; give the matrix alone, or the translation and rotation".into());
    }
    let affine = if let Some(m) = obj.get("matrix") {
        let m: [f64; 16] = numbers(m, "transform.matrix")?;
        let rows = [0, 1, 2, 3].map(|i| [m[4 * i], m[4 * i + 1], m[4 * i + 2], m[4 * i + 3]]);
        Affine::from_rows(rows).ok_or("transform.matrix: the last row must be 0 0 0 1")?
    } else {
        let t = match obj.get("translation") {
            Some(t) => numbers::<3>(t, "transform.translation")?,
            None => [0.0; 3],
        };
        let r = match obj.get("rotation") {
            None => Affine::IDENTITY,
            Some(r) => {
                let r = r
                    .as_object()
                    .ok_or("transform.rotation must be an object")?;
                only_keys(
                    r,
                    "transform.rotation",
                    &["quaternion", "axis", "angle_deg"],
                )?;
                if r.contains_key("quaternion")
                    && (r.contains_key("axis") || r.contains_key("angle_deg"))
                {
                    return Err("transform.rotation gives both \"quaternion\" and \"axis\"/\"angle_deg\"; give one of them".into());
                }
                if let Some(q) = r.get("quaternion") {
                    let q: [f64; 4] = numbers(q, "transform.rotation.quaternion")?;
                    Affine::quaternion(q).ok_or("transform.rotation.quaternion must not be zero")?
                } else {
                    let axis: [f64; 3] = numbers(
                        r.get("axis").ok_or("transform.rotation needs \"axis\" and \"angle_deg\", or \"quaternion\"")?,
                        "transform.rotation.axis",
                    )?;
                    let angle = r
                        .get("angle_deg")
                        .and_then(Value::as_f64)
                        .filter(|a| a.is_finite())
                        .ok_or("transform.rotation.angle_deg must be a number")?;
                    Affine::rotation(axis, angle.to_radians())
                        .ok_or("transform.rotation.axis must not be zero")?
                }
            }
        };
        Affine::translation(t).then_after(&r)
    };
    let a = affine.snapped(TOL_F64);
    if a.det() == 0.0 || !a.is_finite() {
        return Err("transform must be invertible".into());
    }
    Ok(a)
}

/// Parses a manifest's text; relative paths are resolved against `dir`.
pub fn parse(text: &str, dir: &Path) -> Result<Manifest, String> {
    let v: Value = serde_json::from_str(text).map_err(|e| format!("invalid JSON: {e}"))?;
    let obj = v.as_object().ok_or("the manifest must be a JSON object")?;
    let name = match obj.get("name") {
        None | Some(Value::Null) => None,
        Some(Value::String(s)) => Some(s.clone()),
        Some(_) => return Err("\"name\" must be a string".into()),
    };
    let parts_v = obj
        .get("parts")
        .and_then(Value::as_array)
        .ok_or("the manifest needs a \"parts\" array")?;
    let mut parts = Vec::with_capacity(parts_v.len());
    for (i, p) in parts_v.iter().enumerate() {
        let ctx = |e: String| format!("parts[{i}]: {e}");
        let p = p
            .as_object()
            .ok_or_else(|| ctx("must be an object".into()))?;
        let name = p
            .get("name")
            .and_then(Value::as_str)
            .filter(|s| !s.is_empty())
            .ok_or_else(|| ctx("needs a non-empty \"name\"".into()))?
            .to_string();
        let ctx = |e: String| format!("part \"{name}\": {e}");
        let path = |v: &Value, what: &str| -> Result<PathBuf, String> {
            v.as_str()
                .filter(|s| !s.is_empty())
                .map(|s| join(dir, Path::new(s)))
                .ok_or_else(|| ctx(format!("{what} must be a file name")))
        };
        let mesh = match p.get("mesh") {
            None | Some(Value::Null) => None,
            Some(m) => Some(path(m, "\"mesh\"")?),
        };
        let pieces = match p.get("pieces") {
            None | Some(Value::Null) => Vec::new(),
            Some(Value::Array(a)) => a
                .iter()
                .map(|x| path(x, "each of \"pieces\""))
                .collect::<Result<_, _>>()?,
            Some(_) => return Err(ctx("\"pieces\" must be an array of file names".into())),
        };
        if mesh.is_none() && pieces.is_empty() {
            return Err(ctx("needs a \"mesh\" or \"pieces\"".into()));
        }
        let transform = match p.get("transform") {
            None | Some(Value::Null) => Affine::IDENTITY,
            Some(t) => parse_transform(t).map_err(ctx)?,
        };
        if parts.iter().any(|q: &ManifestPart| q.name == name) {
            return Err(format!("two parts are named \"{name}\""));
        }
        parts.push(ManifestPart {
            name,
            mesh,
            pieces,
            transform,
        });
    }
    if parts.is_empty() {
        return Err("the manifest lists no parts".into());
    }
    Ok(Manifest { name, parts })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_parts_pieces_and_transforms() {
        let text = r#"{"name": "x", "format": "ignored", "parts": [
            {"name": "a", "mesh": "a.off", "index": 0, "volume": "16/3", "convex": false},
            {"name": "b", "pieces": ["b/0.off", "b/1.off"],
             "transform": {"translation": [1, 2, 3], "rotation": {"axis": [0, 0, 1], "angle_deg": 90}}},
            {"name": "c", "mesh": "c.stl", "transform": {"matrix": [0,-1,0,5, 1,0,0,0, 0,0,1,0, 0,0,0,1]}},
            {"name": "d", "mesh": "d.off", "transform": {"rotation": {"quaternion": [0, 0, 0.7071067811865476, 0.7071067811865476]}}}
        ]}"#;
        let m = parse(text, Path::new("dir")).unwrap();
        assert_eq!(m.name.as_deref(), Some("x"));
        assert_eq!(m.parts[0].mesh.as_deref(), Some(Path::new("dir/a.off")));
        assert_eq!(m.parts[1].pieces.len(), 2);
        assert_eq!(m.parts[1].transform.apply([1.0, 0.0, 0.0]), [1.0, 3.0, 3.0]);
        assert_eq!(m.parts[2].transform.apply([1.0, 0.0, 0.0]), [5.0, 1.0, 0.0]);
        assert_eq!(m.parts[3].transform.apply([1.0, 0.0, 0.0]), [0.0, 1.0, 0.0]);
    }

    #[test]
    fn clear_errors() {
        let d = Path::new(".");
        assert!(parse("{", d).unwrap_err().contains("invalid JSON"));
        assert!(parse("{}", d).unwrap_err().contains("\"parts\""));
        assert!(parse(r#"{"parts": [{"name": "a"}]}"#, d)
            .unwrap_err()
            .contains("part \"a\""));
        let e = parse(
            r#"{"parts": [{"name": "a", "mesh": "a.off", "transform": {"matrix": [1]}}]}"#,
            d,
        );
        assert!(e.unwrap_err().contains("16 numbers"));
        let e = parse(
            r#"{"parts": [{"name": "a", "mesh": "a.off"}, {"name": "a", "mesh": "b.off"}]}"#,
            d,
        );
        assert!(e.unwrap_err().contains("two parts"));
        let e = parse(
            r#"{"parts": [{"name": "a", "mesh": "a.off", "transform": {"matrix": [0,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}}]}"#,
            d,
        );
        assert!(e.unwrap_err().contains("invertible"));
    }
}
