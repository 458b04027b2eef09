//! An assembly described in memory: in effect an `assembly.json` manifest held by the
//! caller, whose meshes may be files or arrays. [`crate::load_description`] loads it
//! through the same reading, validation, repair, decomposition, tolerance and overlap
//! checks as a manifest (a manifest is read into a description first).
//!
//! ```no_run
//! use apart_assembly::{load_description, DescribedPart, Description, LoadOptions, MeshSource};
//! let tetrahedron = |x: f64| MeshSource::Arrays {
//!     vertices: vec![[x, 0.0, 0.0], [x + 1.0, 0.0, 0.0], [x, 1.0, 0.0], [x, 0.0, 1.0]],
//!     triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
//! };
//! let description = Description {
//!     name: "two tetrahedra".into(),
//!     parts: vec![
//!         DescribedPart::new("left", tetrahedron(0.0)),
//!         DescribedPart::new("right", MeshSource::File("right.off".into())),
//!     ],
//! };
//! let loaded = load_description(description, &LoadOptions::default()).unwrap();
//! assert_eq!(loaded.assembly.parts.len(), 2);
//! ```

use apart_formats::transform::Affine;
use std::path::PathBuf;

/// A mesh of a [`DescribedPart`]: a file, or triangles in memory.
#[derive(Clone, Debug, PartialEq)]
pub enum MeshSource {
    /// A mesh file (OFF, OBJ, STL, PLY, glTF/GLB; several objects are merged), read
    /// where it lies: the caller named it, so it is not confined to a folder. Problems
    /// name it exactly as given.
    File(PathBuf),
    /// Vertices (input units) and triangles of vertex indices, counter-clockwise seen
    /// from outside. Problems name the part and the element ("face 7"), never a file.
    Arrays {
        /// Vertex coordinates.
        vertices: Vec<[f64; 3]>,
        /// Triangles as indices into `vertices`.
        triangles: Vec<[u32; 3]>,
    },
}

impl MeshSource {
    /// The file, for a mesh given as one.
    pub fn file(&self) -> Option<&std::path::Path> {
        match self {
            MeshSource::File(p) => Some(p),
            MeshSource::Arrays { .. } => None,
        }
    }
}

/// One part of a [`Description`]: a manifest's part.
#[derive(Clone, Debug, PartialEq)]
pub struct DescribedPart {
    /// Its name: not empty, and no other part's.
    pub name: String,
    /// The boundary mesh (optional when pieces are given).
    pub mesh: Option<MeshSource>,
    /// Convex pieces whose union is the part.
    pub pieces: Vec<MeshSource>,
    /// Applied to the mesh and the pieces before snapping (a manifest's `transform`).
    pub transform: Affine,
}

impl DescribedPart {
    /// A part of one mesh, without pieces or transform.
    pub fn new(name: impl Into<String>, mesh: MeshSource) -> DescribedPart {
        DescribedPart {
            name: name.into(),
            mesh: Some(mesh),
            pieces: Vec::new(),
            transform: Affine::IDENTITY,
        }
    }
}

/// An assembly in memory: its name and its parts, in order.
#[derive(Clone, Debug, PartialEq)]
pub struct Description {
    /// The assembly's name.
    pub name: String,
    /// The parts, in order.
    pub parts: Vec<DescribedPart>,
}

impl Description {
    /// What makes the description unloadable, by a manifest's rules: no parts, a part
    /// without a name, two parts of one name, a part with neither a mesh nor pieces.
    pub(crate) fn check(&self) -> Result<(), String> {
        if self.parts.is_empty() {
            return Err("the assembly lists no parts".into());
        }
        let mut names = std::collections::HashSet::new();
        for (i, p) in self.parts.iter().enumerate() {
            if p.name.is_empty() {
                return Err(format!("parts[{i}]: needs a non-empty name"));
            }
            if p.mesh.is_none() && p.pieces.is_empty() {
                return Err(format!("part \"{}\": needs a mesh or pieces", p.name));
            }
            if !names.insert(p.name.as_str()) {
                return Err(format!("two parts are named \"{}\"", p.name));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_manifest_rules_hold() {
        let part = |name: &str| DescribedPart::new(name, MeshSource::File("a.off".into()));
        let d = |parts: Vec<DescribedPart>| Description {
            name: "x".into(),
            parts,
        };
        assert!(d(vec![part("a"), part("b")]).check().is_ok());
        assert!(d(vec![]).check().unwrap_err().contains("no parts"));
        assert!(d(vec![part("")]).check().unwrap_err().contains("parts[0]"));
        let e = d(vec![part("a"), part("a")]).check().unwrap_err();
        assert!(e.contains("two parts are named \"a\""), "{e}");
        let mut empty = part("a");
        empty.mesh = None;
        assert!(d(vec![empty])
            .check()
            .unwrap_err()
            .contains("a mesh or pieces"));
    }
}
