//! What every answer states about its input: the length unit, the tolerance it holds
//! under, the repairs made on load and the files not read.

use apart_assembly::Loaded;
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
