//! Options of the loader, and the progress hook a program can drive a bar with.

use crate::tolerance::Tolerance;
use std::sync::Arc;

/// A long step of loading.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Reading mesh files (`total` = files).
    Reading,
    /// Snapping and validating parts and pieces (`total` = parts).
    Validating,
    /// Decomposing non-convex parts into convex pieces (`total` = parts).
    Decomposing,
    /// Checking pairs of parts and pieces for overlap (`total` = pairs).
    Overlaps,
}

impl Stage {
    /// A short label for a progress bar.
    pub fn label(self) -> &'static str {
        match self {
            Stage::Reading => "reading",
            Stage::Validating => "validating",
            Stage::Decomposing => "decomposing",
            Stage::Overlaps => "overlaps",
        }
    }
}

/// How far a stage has come: `done` of `total` items.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    /// The stage.
    pub stage: Stage,
    /// Items finished.
    pub done: usize,
    /// Items in the stage.
    pub total: usize,
}

/// Called from any thread as the loader advances (first with `done = 0` for each
/// stage); must be cheap.
pub type ProgressFn = Arc<dyn Fn(Progress) + Send + Sync>;

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
#[derive(Clone)]
pub struct LoadOptions {
    /// Bits of a snapped coordinate (see [`apart_kernel::grid`]).
    pub grid_bits: u32,
    /// Progress reports; `None` (the default) is silent.
    pub progress: Option<ProgressFn>,
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
            progress: None,
            decompose: Decompose::WhenNeeded,
            verify: false,
            tolerance: Tolerance::None,
            repair: true,
            split_bodies: true,
            allow_outside: false,
        }
    }
}

impl std::fmt::Debug for LoadOptions {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LoadOptions")
            .field("grid_bits", &self.grid_bits)
            .field("progress", &self.progress.is_some())
            .field("decompose", &self.decompose)
            .field("verify", &self.verify)
            .field("tolerance", &self.tolerance)
            .field("repair", &self.repair)
            .field("split_bodies", &self.split_bodies)
            .field("allow_outside", &self.allow_outside)
            .finish()
    }
}

/// Counts finished items of one stage and reports them.
pub(crate) struct Tracker<'a> {
    hook: Option<&'a ProgressFn>,
    stage: Stage,
    total: usize,
    done: std::sync::atomic::AtomicUsize,
}

impl<'a> Tracker<'a> {
    pub(crate) fn start(opts: &'a LoadOptions, stage: Stage, total: usize) -> Tracker<'a> {
        let hook = opts.progress.as_ref();
        if let Some(h) = hook {
            h(Progress {
                stage,
                done: 0,
                total,
            });
        }
        Tracker {
            hook,
            stage,
            total,
            done: 0.into(),
        }
    }

    pub(crate) fn tick(&self) {
        let done = self.done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        if let Some(h) = self.hook {
            h(Progress {
                stage: self.stage,
                done,
                total: self.total,
            });
        }
    }
}
