//! The validity gate of the planning jobs: a job plans only an assembly whose loading
//! found no error, except the overlaps of a part about to be placed.

use apart_assembly::Loaded;
use apart_mesh::{Problem, ProblemKind};

/// The errors that keep `loaded` from being planned: every problem of severity error,
/// except the overlaps of the part named `free` with the others (a part to place may
/// be given where others are).
pub fn errors<'a>(loaded: &'a Loaded, free: Option<&str>) -> Vec<&'a Problem> {
    let excused = |p: &Problem| {
        free.is_some_and(|n| match &p.kind {
            ProblemKind::Overlap { other } => other.as_str() == n || p.part.as_deref() == Some(n),
            _ => false,
        })
    };
    loaded
        .problems
        .iter()
        .filter(|p| p.is_error() && !excused(p))
        .collect()
}
