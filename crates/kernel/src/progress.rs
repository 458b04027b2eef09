//! Progress reports and cooperative stopping for the long planners.
//!
//! A [`Progress`] carries an optional callback, called with `(phase, done, total)` as a
//! planner advances, and a shared stop flag. The planners that take one (apart-plan's
//! `BlockingRegions::compute_with`, `partition_subset_with` and `sequence_with`, and
//! apart-stack's `stack_with`) check the flag between
//! units of work (part pairs, culling rounds, faces and cells scanned in batches,
//! sequence steps, stacked parts), never in inner loops, and when it is raised they
//! return what they have, marked as stopped. apart-assembly's loader takes one too
//! (in its `LoadOptions`): it checks the flag between parts and batches of part pairs
//! and, having no partial assembly to give, fails with a "stopped" error. Whoever holds the flag (a watchdog thread,
//! a Ctrl-C handler, the callback itself) raises it with [`Progress::request_stop`] or
//! by storing `true` into [`Progress::stop_flag`].
//!
//! The type is `Send + Sync` and knows nothing about terminals: a command line draws
//! bars from the callback, a Python binding could forward it and raise the flag on
//! `KeyboardInterrupt`. It lives in the kernel so that planners on every floor (the
//! assembly planners of apart-plan, the stacker of apart-stack) share one type;
//! apart-plan re-exports it as `apart_plan::progress`.
//!
//! Reports of one phase are monotone: `total` is fixed, `done` never decreases, and a
//! phase that runs to its end reports `done == total` last. They are thinned to about a
//! thousand per phase (every change of the thousandth, and the first and last), and
//! calls are serialized, so a callback needs no locking of its own.
//!
//! ```
//! use apart_kernel::progress::Progress;
//! use std::sync::{Arc, Mutex};
//! let seen = Arc::new(Mutex::new(Vec::new()));
//! let log = seen.clone();
//! let progress = Progress::with_callback(move |phase, done, total| {
//!     log.lock().unwrap().push((phase, done, total));
//! });
//! progress.report("demo", 0, 2);
//! progress.report("demo", 2, 2);
//! assert!(!progress.stopped());
//! progress.request_stop();
//! assert!(progress.stopped());
//! assert_eq!(seen.lock().unwrap().len(), 2);
//! ```

use std::sync::atomic::{AtomicBool, Ordering::Relaxed};
use std::sync::{Arc, Mutex};

/// A callback receiving `(phase, done, total)`.
pub type ProgressCallback = Arc<dyn Fn(&'static str, usize, usize) + Send + Sync>;

/// A callback asked `(phase, bytes)` before a planner builds something whose memory it
/// estimated: true when it may go ahead (see [`Progress::affordable`]).
pub type BudgetCallback = Arc<dyn Fn(&'static str, u64) -> bool + Send + Sync>;

/// A callback receiving `(phase, text)`: a note for the user from a planner, about
/// something large it is about to do (see [`Progress::note`]).
pub type NoteCallback = Arc<dyn Fn(&'static str, &str) + Send + Sync>;

/// The names of the phases reported, in the order a run meets them.
pub mod phases {
    /// apart-assembly's loader: mesh files read (and meshes given as arrays taken), of
    /// all.
    pub const READING: &str = "reading";
    /// The loader: parts snapped, repaired and validated, of all.
    pub const VALIDATING: &str = "validating";
    /// The loader: parts given their exact convex decomposition, of those that need one.
    pub const DECOMPOSING: &str = "decomposing";
    /// The loader: parts checked for overlaps with the others (one unit when a tolerance
    /// is measured instead).
    pub const OVERLAPS: &str = "overlaps";
    /// apart-plan's `BlockingRegions::compute_with`: pairs of parts whose blocked region
    /// is computed, of all pairs.
    pub const PAIR_REGIONS: &str = "pair regions";
    /// apart-plan's `partition_subset_with`: the overlay of the pair regions (0 of 1,
    /// then 1 of 1: one indivisible build).
    pub const MOTION_SPACE: &str = "motion space";
    /// Faces of the motion space scanned for the regions where a moving set is free.
    pub const FREE_REGIONS: &str = "free regions";
    /// Free regions whose deepest direction and clearance are found.
    pub const DIRECTIONS: &str = "solution directions";
    /// Edge and vertex cells of the motion space scanned for sliding and isolated
    /// solutions.
    pub const CELLS: &str = "edges and vertices";
    /// apart-plan's `sequence_with`: splits made, of the `parts - 1` a complete plan
    /// needs (a subassembly found interlocked or left whole counts as its `size - 1`).
    pub const SEQUENCE: &str = "sequence steps";
    /// apart-stack's `stack_with`: parts placed, of the count asked for.
    pub const STACKING: &str = "stacking";
    /// apart-plan's `disassemble_with`: states of the current subassembly's search
    /// explored, of the state limit.
    pub const MOVES: &str = "move states";
}

/// A progress callback and a stop flag, shared by a planner and its caller (see the
/// module documentation). Cloning shares both.
#[derive(Clone, Default)]
pub struct Progress {
    callback: Option<ProgressCallback>,
    stop: Arc<AtomicBool>,
    budget: Option<BudgetCallback>,
    notes: Option<NoteCallback>,
}

impl std::fmt::Debug for Progress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Progress")
            .field("callback", &self.callback.is_some())
            .field("stopped", &self.stopped())
            .finish()
    }
}

impl Progress {
    /// No callback, and a flag of its own that nobody raises unless asked to.
    pub fn new() -> Progress {
        Progress::default()
    }

    /// Reports to `callback`, with a flag of its own.
    pub fn with_callback(
        callback: impl Fn(&'static str, usize, usize) + Send + Sync + 'static,
    ) -> Progress {
        Progress {
            callback: Some(Arc::new(callback)),
            stop: Arc::default(),
            budget: None,
            notes: None,
        }
    }

    /// The same callback, watching `flag` (shared with a watchdog or a signal handler)
    /// instead of its own.
    pub fn with_stop_flag(mut self, flag: Arc<AtomicBool>) -> Progress {
        self.stop = flag;
        self
    }

    /// The same stop flag without the callback: for work nested in a phase that reports
    /// its own counts.
    pub fn silent(&self) -> Progress {
        Progress {
            callback: None,
            stop: self.stop.clone(),
            budget: self.budget.clone(),
            notes: self.notes.clone(),
        }
    }

    /// The same, asking `budget(phase, bytes)` before a planner builds something of an
    /// estimated size (a memory budget's keeper answers whether it fits).
    pub fn with_budget(
        mut self,
        budget: impl Fn(&'static str, u64) -> bool + Send + Sync + 'static,
    ) -> Progress {
        self.budget = Some(Arc::new(budget));
        self
    }

    /// The same, handing the planners' notes to `notes(phase, text)`.
    pub fn with_notes(
        mut self,
        notes: impl Fn(&'static str, &str) + Send + Sync + 'static,
    ) -> Progress {
        self.notes = Some(Arc::new(notes));
        self
    }

    /// A note for the user from `phase` (for example the estimated memory of a large
    /// structure about to be built); dropped without a notes callback.
    pub fn note(&self, phase: &'static str, text: &str) {
        if let Some(f) = &self.notes {
            f(phase, text);
        }
    }

    /// Whether `bytes`, estimated for what `phase` is about to build, may be spent: true
    /// without a budget callback. A planner told no stops as if the flag rose, with
    /// what it has (the callback records why).
    pub fn affordable(&self, phase: &'static str, bytes: u64) -> bool {
        self.budget.as_ref().is_none_or(|f| f(phase, bytes))
    }

    /// The stop flag: storing `true` asks every planner watching it to return what it
    /// has.
    pub fn stop_flag(&self) -> Arc<AtomicBool> {
        self.stop.clone()
    }

    /// Raises the stop flag.
    pub fn request_stop(&self) {
        self.stop.store(true, Relaxed);
    }

    /// Whether the stop flag is raised (one relaxed atomic load).
    #[inline]
    pub fn stopped(&self) -> bool {
        self.stop.load(Relaxed)
    }

    /// Calls the callback, if any, with `(phase, done, total)`.
    pub fn report(&self, phase: &'static str, done: usize, total: usize) {
        if let Some(f) = &self.callback {
            f(phase, done, total);
        }
    }

    /// A counter of `total` units of `phase`, reporting `0 of total` now: for a phase
    /// whose units are done from several threads.
    pub fn counter(&self, phase: &'static str, total: usize) -> Counter<'_> {
        self.report(phase, 0, total);
        Counter {
            progress: self,
            phase,
            total,
            state: Mutex::new((0, 0)),
        }
    }
}

/// Units of one phase done so far, reported monotonically from any thread (see
/// [`Progress::counter`]).
pub struct Counter<'a> {
    progress: &'a Progress,
    phase: &'static str,
    total: usize,
    /// Units done, and the thousandth last reported.
    state: Mutex<(usize, usize)>,
}

impl Counter<'_> {
    /// Adds `k` units done; reports when the thousandth changes or the phase is done.
    /// The report is made under the lock, so reports arrive in order.
    pub fn add(&self, k: usize) {
        if self.progress.callback.is_none() || k == 0 {
            return;
        }
        let mut s = self.state.lock().unwrap_or_else(|e| e.into_inner());
        s.0 = s.0.saturating_add(k).min(self.total);
        let permille = s.0 * 1000 / self.total.max(1);
        if permille > s.1 || s.0 == self.total {
            s.1 = permille;
            self.progress.report(self.phase, s.0, self.total);
        }
    }
}
