//! Checking: the parts of a loaded assembly, its grid and every problem found.

use crate::InputFacts;
use apart_assembly::Loaded;
use apart_mesh::Problem;
use serde::Serialize;
use std::path::PathBuf;

/// The grid an assembly was snapped to.
#[derive(Clone, Debug, Serialize)]
pub struct GridFacts {
    /// The step is `2^exp` input units.
    pub exp: i32,
    /// The step in input units.
    pub step: f64,
    /// Bits of a snapped coordinate.
    pub bits: u32,
    /// The farthest snapping moved a vertex (input units).
    pub max_snap_displacement: f64,
}

/// A box in input units.
#[derive(Clone, Debug, Serialize)]
pub struct BoxFacts {
    /// Lower corner.
    pub min: [f64; 3],
    /// Upper corner.
    pub max: [f64; 3],
}

/// One part as checked.
#[derive(Clone, Debug, Serialize)]
pub struct PartFacts {
    /// Its name.
    pub name: String,
    /// Its mesh file; null for a mesh given in memory.
    #[serde(serialize_with = "apart_mesh::optional_path_text")]
    pub source: Option<PathBuf>,
    /// Vertices of its mesh, when it was read.
    pub vertices: Option<usize>,
    /// Faces of its mesh.
    pub faces: Option<usize>,
    /// Triangles of its mesh.
    pub triangles: Option<usize>,
    /// Exact volume in input units ("16/3"); null when unknown.
    pub volume: Option<String>,
    /// The same as a decimal.
    pub volume_decimal: Option<f64>,
    /// The part is convex.
    pub convex: bool,
    /// Reflex edges of its mesh.
    pub reflex_edges: usize,
    /// Its convex pieces.
    pub pieces: usize,
    /// The pieces were given with the part.
    pub declared_pieces: bool,
    /// The pieces come from the exact convex decomposition of a non-convex part.
    pub decomposed: bool,
    /// The files of declared pieces.
    #[serde(serialize_with = "apart_mesh::path_texts")]
    pub piece_sources: Vec<PathBuf>,
    /// Its bounding box.
    pub bbox: Option<BoxFacts>,
}

/// The answer of a check.
#[derive(Clone, Debug, Serialize)]
pub struct CheckAnswer {
    /// The assembly's name.
    pub assembly: String,
    /// No error was found.
    pub valid: bool,
    /// The grid.
    pub grid: GridFacts,
    /// The parts, in order.
    pub parts: Vec<PartFacts>,
    /// Every problem found.
    pub problems: Vec<Problem>,
    /// What the answer holds under.
    #[serde(flatten)]
    pub input: InputFacts,
}

/// The check of a loaded assembly (loading did the work: this states it).
pub fn check(loaded: &Loaded, units: Option<&str>) -> CheckAnswer {
    let a = &loaded.assembly;
    let g = &a.grid;
    let parts = a
        .parts
        .iter()
        .map(|p| {
            let known = p.volume_known();
            let v = p.volume_units(g);
            PartFacts {
                name: p.name.clone(),
                source: (!p.source.as_os_str().is_empty()).then(|| p.source.clone()),
                vertices: p.info.as_ref().map(|i| i.vertices),
                faces: p.info.as_ref().map(|i| i.faces),
                triangles: p.info.as_ref().map(|i| i.triangles),
                volume: known.then(|| v.to_string()),
                volume_decimal: known.then(|| v.to_f64()),
                convex: p.convex,
                reflex_edges: p.reflex_edges,
                pieces: p.pieces.len(),
                declared_pieces: p.declared_pieces,
                decomposed: p.decomposed,
                piece_sources: p.piece_sources.clone(),
                bbox: p.bbox.map(|b| BoxFacts {
                    min: b.min.map(|q| g.to_units(q)),
                    max: b.max.map(|q| g.to_units(q)),
                }),
            }
        })
        .collect();
    CheckAnswer {
        assembly: a.name.clone(),
        valid: loaded.is_valid(),
        grid: GridFacts {
            exp: g.exp,
            step: g.step(),
            bits: g.bits,
            max_snap_displacement: a.max_snap_displacement,
        },
        parts,
        problems: loaded.problems.clone(),
        input: InputFacts::of(loaded, units),
    }
}
