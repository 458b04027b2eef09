//! What every answer states about its input: the length unit, the tolerance it holds
//! under, the repairs made on load and the files not read.

use apart_assembly::{Loaded, WindingReport};
use apart_mesh::repair::RepairReport;
use serde::Serialize;
use std::path::PathBuf;

/// The tolerance an answer holds under.
#[derive(Clone, Debug, Serialize)]
pub struct ToleranceFacts {
    /// Every convex piece was made at least this much smaller (input units).
    pub eps: f64,
    /// The same, exactly (a rational in input units).
    pub exact: String,
    /// Chosen automatically (the smallest tolerance that makes the assembly valid).
    pub auto: bool,
    /// The deepest overlap between parts before shrinking (input units).
    pub deepest_overlap: f64,
    /// Pairs of parts whose overlap became contact.
    pub accepted_overlaps: usize,
    /// Pieces thinner than twice the tolerance that vanished.
    pub vanished_pieces: usize,
    /// The farthest any face moved inward (input units, at least `eps`).
    pub max_shift: f64,
}

/// The repairs of one mesh, as answers list them.
#[derive(Clone, Debug, Serialize)]
pub struct RepairFacts {
    /// The mesh file; null for a mesh given in memory.
    #[serde(serialize_with = "apart_mesh::optional_path_text")]
    pub file: Option<PathBuf>,
    /// The parts made of it.
    pub parts: Vec<String>,
    /// The repairs, by kind.
    #[serde(flatten)]
    pub counts: RepairReport,
    /// The parts made by the winding rule from a surface that is not a closed
    /// manifold, and how (absent when none was).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub winding: Vec<WindingFacts>,
}

/// How one part was made the solid its surface winds around (winding number at least
/// 1), as answers list it.
#[derive(Clone, Debug, Serialize)]
pub struct WindingFacts {
    /// The part.
    pub part: String,
    /// Net boundary edges of the surface (used more often one way than the other).
    pub open_edges: usize,
    /// Edges used by more than two faces.
    pub nonmanifold_edges: usize,
    /// Pairs of faces that cross.
    pub crossing_pairs: usize,
    /// Boundary loops closed (planar or nearly so, or seams).
    pub loops_closed: usize,
    /// Of those, seams.
    pub seams_closed: usize,
    /// Triangles added to close them.
    pub cap_triangles: usize,
    /// Faces with the solid on both sides or on neither.
    pub faces_dropped: usize,
    /// Convex cells of winding number at least 1 kept.
    pub cells_kept: usize,
    /// Convex pieces they were merged into.
    pub pieces: usize,
    /// The surface was inside out and was reversed.
    pub inside_out: bool,
    /// The least and greatest winding numbers met.
    pub winding_range: [i64; 2],
    /// The surface's signed volume, in input units (exact, as a fraction).
    pub volume_before: String,
    /// The solid's volume, in input units (exact, as a fraction).
    pub volume_after: String,
}

impl WindingFacts {
    fn of(w: &WindingReport, grid: &apart_kernel::Grid) -> WindingFacts {
        let units = |v| apart_mesh::validate::volume_in_units(v, grid).to_string();
        WindingFacts {
            part: w.part.clone(),
            open_edges: w.open_edges,
            nonmanifold_edges: w.nonmanifold_edges,
            crossing_pairs: w.crossing_pairs,
            loops_closed: w.loops_closed,
            seams_closed: w.seams_closed,
            cap_triangles: w.cap_triangles,
            faces_dropped: w.faces_dropped,
            cells_kept: w.cells_kept,
            pieces: w.pieces,
            inside_out: w.inside_out,
            winding_range: [w.lowest_winding, w.highest_winding],
            volume_before: units(&w.volume_before),
            volume_after: units(&w.volume_after),
        }
    }
}

/// A file not read, and why.
#[derive(Clone, Debug, Serialize)]
pub struct SkippedFacts {
    /// The file or folder.
    #[serde(serialize_with = "apart_mesh::path_text")]
    pub file: PathBuf,
    /// Why it was not read.
    pub reason: String,
}

/// Unit, tolerance, repairs and files not read, flattened into every answer.
#[derive(Clone, Debug, Serialize)]
pub struct InputFacts {
    /// The unit of the input files, when the caller said which.
    pub units: Option<String>,
    /// The tolerance the answer holds under; null for the parts as given.
    pub tolerance: Option<ToleranceFacts>,
    /// Every repair made on load, per mesh.
    pub repairs: Vec<RepairFacts>,
    /// Files and folders of the assembly folder that were not read, with the reason.
    pub skipped_files: Vec<SkippedFacts>,
}

impl InputFacts {
    /// The facts of a loaded assembly, in the unit `units` when the caller knows it.
    pub fn of(loaded: &Loaded, units: Option<&str>) -> InputFacts {
        let asm = &loaded.assembly;
        InputFacts {
            units: units.map(str::to_string),
            tolerance: asm.tolerance.as_ref().map(|t| ToleranceFacts {
                eps: t.eps,
                exact: t.exact.to_string(),
                auto: t.auto,
                deepest_overlap: t.deepest_overlap,
                accepted_overlaps: t.accepted_overlaps,
                vanished_pieces: t.vanished_pieces,
                max_shift: t.max_shift,
            }),
            repairs: loaded
                .repairs
                .iter()
                .map(|r| RepairFacts {
                    file: (!r.file.as_os_str().is_empty()).then(|| r.file.clone()),
                    parts: r.parts.clone(),
                    counts: r.report.clone(),
                    winding: r
                        .winding
                        .iter()
                        .map(|w| WindingFacts::of(w, &asm.grid))
                        .collect(),
                })
                .collect(),
            skipped_files: loaded
                .skipped
                .iter()
                .map(|s| SkippedFacts {
                    file: s.path.clone(),
                    reason: s.reason.clone(),
                })
                .collect(),
        }
    }
}
