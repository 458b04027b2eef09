//! Options of the loader, with the [`Progress`] that reports its phases and can stop
//! it.

use crate::error::LoadError;
use crate::tolerance::Tolerance;
use apart_kernel::progress::Progress;

/// When to decompose valid non-convex parts that declare no pieces into exact convex
/// pieces (`apart-decompose`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Decompose {
    /// Never (overlap checks then compare boundaries; planners decompose themselves).
    Never,
    /// When the assembly has two parts or more: the overlap check between parts becomes
    /// complete, and planners reuse the pieces. The default.
    WhenNeeded,
    /// Always, also for a single part.
    Always,
}

/// How to load an assembly.
#[derive(Clone, Debug)]
pub struct LoadOptions {
    /// Bits of a snapped coordinate (see [`apart_kernel::grid`]).
    pub grid_bits: u32,
    /// Reports the phases of loading ([`apart_kernel::progress::phases`]: `READING`,
    /// `VALIDATING`, `DECOMPOSING`, `OVERLAPS`; first with `done = 0` for each, from any
    /// thread, in order), and a stop flag checked between parts and batches of part
    /// pairs: when raised, loading fails with [`LoadError::Stopped`]. The default is
    /// silent, with a flag nobody raises.
    pub progress: Progress,
    /// When to decompose non-convex parts without declared pieces.
    pub decompose: Decompose,
    /// Verify every decomposition exactly (pieces convex, interiors disjoint, inside the
    /// part, volumes adding up), reporting a failure as an error.
    pub verify: bool,
    /// Accept overlaps between parts as contact for parts made this much smaller.
    pub tolerance: Tolerance,
    /// Repair meshes on load (exact: T-junctions, duplicate and cancelling faces, small
    /// holes, shell orientation), reporting every repair. `false` (strict): any defect
    /// is an error.
    pub repair: bool,
    /// Load a mesh that holds several separate solids as several parts (only where the
    /// part name comes from a file or object, not from a manifest).
    pub split_bodies: bool,
    /// Read mesh files that resolve outside the assembly's folder (absolute paths, `..`
    /// leaving it, symbolic links to elsewhere) named by a manifest or found in a folder.
    /// `false` (the default): such a file is an error and is never opened.
    pub allow_outside: bool,
}

impl Default for LoadOptions {
    fn default() -> LoadOptions {
        LoadOptions {
            grid_bits: apart_kernel::grid::DEFAULT_BITS,
            progress: Progress::new(),
            decompose: Decompose::WhenNeeded,
            verify: false,
            tolerance: Tolerance::None,
            repair: true,
            split_bodies: true,
            allow_outside: false,
        }
    }
}

/// Fails with [`LoadError::Stopped`] when the stop flag of `opts` is raised: called
/// between the phases of loading, whose loops stop taking new work once it is.
pub(crate) fn check_stop(opts: &LoadOptions, phase: &'static str) -> Result<(), LoadError> {
    match opts.progress.stopped() {
        true => Err(LoadError::Stopped { phase }),
        false => Ok(()),
    }
}
