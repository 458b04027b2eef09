//! Decomposition: the exact convex pieces of every part as files would hold them, each
//! part's file names, and the manifest that declares them. The front end writes the
//! files.
//!
//! A piece with a vertex off the grid (an intersection of three face planes) cannot be
//! written exactly in any mesh format the loader reads, so a part with such pieces is
//! written as its mesh alone, and loading the output decomposes it again into the same
//! exact pieces.

use apart_assembly::{Loaded, Part};
use apart_kernel::Int;
use serde::Serialize;
use std::collections::HashSet;
use std::path::{Path, PathBuf};

/// One part in the manifest: its mesh file and the files of its declared pieces.
#[derive(Clone, Debug, Serialize)]
pub struct ManifestPart {
    /// Its name.
    pub name: String,
    /// Its mesh file (`FILE.off`), when it has a mesh.
    pub mesh: Option<String>,
    /// The files of its pieces (`FILE/piece_K.off`), when they are written.
    pub pieces: Vec<String>,
}

/// The `assembly.json` manifest that declares every part and its pieces.
#[derive(Clone, Debug, Serialize)]
pub struct Manifest {
    /// The assembly's name.
    pub name: String,
    /// Its parts, in order.
    pub parts: Vec<ManifestPart>,
}

/// One part as decomposed.
#[derive(Clone, Debug, Serialize)]
pub struct DecomposedPart {
    /// Its name.
    pub name: String,
    /// The part's files: `FILE.off` and the folder `FILE/` of its pieces.
    pub file: String,
    /// The part is convex.
    pub convex: bool,
    /// Reflex edges of its mesh.
    pub reflex_edges: usize,
    /// Its convex pieces.
    pub pieces: usize,
    /// The pieces come from the exact convex decomposition.
    pub decomposed: bool,
    /// The pieces were given with the part.
    pub declared_pieces: bool,
    /// Pieces with vertices off the grid.
    pub rational_pieces: usize,
    /// The pieces are written and declared in the manifest (every vertex on the grid);
    /// otherwise the part is written as its mesh alone and decomposed again on load.
    pub pieces_written: bool,
}

/// The answer of a decomposition.
#[derive(Clone, Debug, Serialize)]
pub struct DecomposeAnswer {
    /// The folder the front end writes the files to.
    pub output: PathBuf,
    /// Every part, in order.
    pub parts: Vec<DecomposedPart>,
    /// Seconds loading (and so decomposing) took.
    pub seconds: f64,
    /// The manifest to write beside the files.
    #[serde(skip)]
    pub manifest: Manifest,
}

/// The decomposition of a loaded (valid) assembly, to be written to the folder
/// `output`; `seconds` is what its loading took.
pub fn decompose(loaded: &Loaded, output: &Path, seconds: f64) -> DecomposeAnswer {
    let asm = &loaded.assembly;
    let files = file_names(&asm.parts);
    let parts: Vec<DecomposedPart> = asm
        .parts
        .iter()
        .zip(&files)
        .map(|(p, f)| part_report(p, f))
        .collect();
    let manifest = Manifest {
        name: asm.name.clone(),
        parts: asm
            .parts
            .iter()
            .zip(&parts)
            .map(|(part, r)| ManifestPart {
                name: part.name.clone(),
                mesh: part.mesh.as_ref().map(|_| format!("{}.off", r.file)),
                pieces: if r.pieces_written {
                    (0..part.pieces.len())
                        .map(|k| format!("{}/piece_{k}.off", r.file))
                        .collect()
                } else {
                    Vec::new()
                },
            })
            .collect(),
    };
    DecomposeAnswer {
        output: output.to_path_buf(),
        parts,
        seconds,
        manifest,
    }
}

fn part_report(p: &Part, file: &str) -> DecomposedPart {
    let rational = p.pieces.iter().filter(|q| *q.den() != Int::ONE).count();
    DecomposedPart {
        name: p.name.clone(),
        file: file.to_string(),
        convex: p.convex,
        reflex_edges: p.reflex_edges,
        pieces: p.pieces.len(),
        decomposed: p.decomposed,
        declared_pieces: p.declared_pieces,
        rational_pieces: rational,
        // A part without a mesh has declared pieces, read from files: on the grid.
        pieces_written: rational == 0 || p.mesh.is_none(),
    }
}

/// Each part's file name (`NAME.off`, and `NAME/` for its pieces): its name made safe
/// for file systems, then unique: two names that become the same (`a b` and `a_b`), or
/// differ only in case (file systems that ignore case), or a part named like another's
/// file (`x` and `x.off`) get `_2`, `_3`, ...; `assembly.json` is the manifest's.
fn file_names(parts: &[Part]) -> Vec<String> {
    let mut used: HashSet<String> = std::iter::once("assembly.json".to_string()).collect();
    parts
        .iter()
        .map(|p| {
            let base = safe_name(&p.name);
            let mut name = base.clone();
            let mut k = 2;
            let taken = |used: &HashSet<String>, n: &str| {
                let n = n.to_lowercase();
                used.contains(&n) || used.contains(&format!("{n}.off"))
            };
            while taken(&used, &name) {
                name = format!("{base}_{k}");
                k += 1;
            }
            used.insert(name.to_lowercase());
            used.insert(format!("{}.off", name.to_lowercase()));
            name
        })
        .collect()
}

/// A file-system-safe version of a part name.
pub fn safe_name(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || "-_.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() || s.starts_with('.') {
        format!("part_{s}")
    } else {
        s
    }
}
