//! Assembly planning with infinite translations.
//!
//! [`regions::BlockingRegions`] computes, once per assembly, the blocked region of every
//! pair of parts (exact Minkowski sums of their convex pieces, projected onto the sphere
//! and united). [`motion_space::MotionSpace`] overlays the regions of any subset of parts
//! into an arrangement whose every vertex, edge and face carries its directional
//! blocking graph ([`dbg::Dbg`]); [`partition::partition`] reads off every direction and
//! minimal subset that separates the assembly.
//!
//! The long planners have `*_with` variants taking a [`progress::Progress`]: a callback
//! receiving `(phase, done, total)` and a stop flag, checked between units of work, on
//! which they return the partial answer found so far, marked as stopped.
//!
//! With an assembly loaded from files:
//!
//! ```no_run
//! use apart_assembly::{load, LoadOptions};
//! use apart_plan::{partition, Options};
//! let loaded = load(std::path::Path::new("examples/split-star-3"), &LoadOptions::default()).unwrap();
//! let result = partition(&loaded.assembly, &Options::default()).unwrap();
//! for s in &result.solutions {
//!     let moving: Vec<&str> = s.moving.iter().map(|&k| result.names[k].as_str()).collect();
//!     println!("{:?} along {:?} ({})", moving, s.unit, s.cell.name());
//! }
//! ```
//!
//! With pieces built in code:
//!
//! ```
//! use apart_kernel::Vec3;
//! use apart_pieces::Polytope;
//! use apart_plan::{partition_pieces, Options, Part, CellKind};
//! // Two unit cubes, one on top of the other.
//! let cube = |z: i64| {
//!     let pts: Vec<Vec3> = (0..8).map(|i| Vec3::new(i & 1, i >> 1 & 1, z + (i >> 2))).collect();
//!     Part::from_pieces(format!("cube{z}"), vec![Polytope::hull_of_points(&pts).unwrap()])
//! };
//! let result = partition_pieces(&[cube(0), cube(1)], &Options::default()).unwrap();
//! assert!(!result.interlocked);
//! // The top cube leaves through the open upper hemisphere (a face) ...
//! let up = result.solutions.iter().find(|s| s.cell == CellKind::Face && s.moving == vec![1]).unwrap();
//! assert!(up.unit[2] > 0.0);
//! // ... and slides off along the equator (edges).
//! assert!(result.solutions.iter().any(|s| s.cell == CellKind::Edge && s.moving == vec![1]));
//! ```

pub mod along;
pub mod clearance;
mod cull;
pub mod dbg;
pub mod motion_space;
pub mod moves;
mod pairs;
pub mod partition;
pub mod progress;
pub mod regions;
pub mod separate;
pub mod sequence;
pub mod store;

pub use along::{dbg_along, partition_first, DirectionAnswer, DirectionQuery, QueryStats};
pub use dbg::{BitGraph, Dbg};
pub use motion_space::{CellKind, MotionSpace, OverlayEstimate};
pub use moves::{disassemble, GroupSearch, Move, MoveOptions, MovePlan, SearchEnd};
pub use partition::{
    dbg_at, partition, partition_pieces, partition_pieces_with, partition_subset,
    partition_subset_with, MovingSet, Options, Partitioning, Solution, Stats,
};
pub use progress::{Progress, ProgressCallback};
pub use regions::parts_of;
pub use regions::{BlockingRegions, Part};
pub use separate::{separate, FreeFace, Separation};
pub use sequence::{
    sequence, sequence_first, sequence_first_with, sequence_parts, sequence_with, Growth,
    KeepSolutions, Ranking, Rule, Sequence, SequenceOptions, Step,
};
pub use store::PairStore;

/// Why planning could not run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PlanError {
    /// A part has no convex pieces (the loader decomposes every part it loads).
    NoPieces {
        /// Part index.
        part: usize,
        /// Part name.
        name: String,
    },
    /// Two parts' interiors overlap (pieces `pieces.0` of the first and `pieces.1` of the
    /// second).
    Overlap {
        /// Part indices.
        parts: (usize, usize),
        /// Part names.
        names: (String, String),
        /// Piece indices.
        pieces: (usize, usize),
    },
    /// An internal inconsistency (a bug): reported, never hidden.
    Internal(String),
    /// More parts than a planner takes (`apart disassemble`: 64 per assembly).
    TooManyParts {
        /// Parts given.
        parts: usize,
        /// Parts taken.
        limit: usize,
    },
    /// The stop flag of a [`Progress`] was raised before the planner had a partial
    /// answer to return (while it computed the pair regions).
    Stopped {
        /// The phase it was in ([`progress::phases`]).
        phase: &'static str,
    },
}

impl std::fmt::Display for PlanError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PlanError::NoPieces { name, .. } => write!(
                f,
                "part \"{name}\" has no convex pieces (apart_assembly::load decomposes the parts it loads)"
            ),
            PlanError::Overlap { names, pieces, .. } => write!(
                f,
                "parts \"{}\" and \"{}\" overlap (piece {} of the first and piece {} of the second share interior points)",
                names.0, names.1, pieces.0, pieces.1
            ),
            PlanError::Internal(m) => write!(f, "internal error: {m}"),
            PlanError::TooManyParts { parts, limit } => write!(
                f,
                "the assembly has {parts} parts; disassembly by moves takes at most {limit} (split it, or use sequence)"
            ),
            PlanError::Stopped { phase } => write!(f, "stopped during {phase}"),
        }
    }
}

impl std::error::Error for PlanError {}
