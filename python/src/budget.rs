//! The extension's memory budget: the command line's counting allocator and budget
//! (apart-kernel's `budget`, one implementation for both), with the reactions a Python
//! session needs.
//!
//! The allocator counts the extension's Rust heap (not the interpreter's or numpy's).
//! The budget is by default the command line's (80 % of the machine's memory or of its
//! cgroup's limit), and `apart.set_memory_budget` changes it. During a call:
//! - past 90 % of the budget (the soft limit), a planner with partial answers is asked
//!   for it, as Ctrl-C asks ([`crate::work::run`] raises its stop flag): partition,
//!   sequence and stack return what they found, with `status` "out of memory";
//! - a planner refuses to build a structure estimated over what the budget leaves
//!   ([`affordable`]);
//! - past the budget itself, the allocation is still made (a failed allocation would
//!   abort the interpreter), the planners are asked to stop, and the call raises
//!   `apart.OutOfMemoryBudget` when its work returns (its answer is dropped).
//!
//! Only past a ceiling, the larger of the budget and the machine's default budget,
//! does the extension do what the command line does past its budget: print "out of
//! memory budget (SIZE) during PHASE" and end the process (exit code 1), rather than
//! let the system's allocator fail and abort it.

use apart_kernel::budget::{self, FixedText, Hooks, LimitText};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering::Relaxed};
use std::sync::Mutex;

/// The extension's allocator: the kernel's counting allocator.
#[global_allocator]
static ALLOCATOR: budget::Budget = budget::Budget;

/// Settlings of the live count past the soft limit, since the module was loaded.
static SOFT_PASSES: AtomicUsize = AtomicUsize::new(0);
/// Settlings past the budget.
static OVER_PASSES: AtomicUsize = AtomicUsize::new(0);
/// The most live bytes seen past the budget.
static OVER_LIVE: AtomicUsize = AtomicUsize::new(0);
/// Past this, the process ends (see the module documentation).
static CEILING: AtomicUsize = AtomicUsize::new(usize::MAX);
/// The machine's default budget (0: unknown).
static MACHINE: AtomicUsize = AtomicUsize::new(0);
/// The phase of the call that runs, for the message that ends the process.
static PHASE: Mutex<&'static str> = Mutex::new("starting");

fn soft(_live: usize) {
    SOFT_PASSES.fetch_add(1, Relaxed);
}

fn over(live: usize) {
    OVER_PASSES.fetch_add(1, Relaxed);
    OVER_LIVE.fetch_max(live, Relaxed);
    if live > CEILING.load(Relaxed) {
        end(live);
    }
}

/// Past the ceiling: the command line's message, then the end of the process (once).
#[cold]
fn end(live: usize) {
    static ENDING: AtomicBool = AtomicBool::new(false);
    if ENDING.swap(true, Relaxed) {
        return;
    }
    use std::fmt::Write;
    let phase = match PHASE.try_lock() {
        Ok(p) => *p,
        Err(_) => "?",
    };
    let mut text = FixedText::new();
    let _ = writeln!(
        text,
        "error: out of memory budget ({LimitText}) during {phase}: {} MiB of heap asked for; ending the process (apart.set_memory_budget sets the budget)",
        live >> 20
    );
    budget::raw_write(2, text.as_bytes());
    std::process::exit(1)
}

/// Installs the hooks and the default budget (when the module is loaded).
pub fn init() {
    budget::set_hooks(Hooks { soft, over });
    match budget::machine_budget() {
        Some(b) => {
            MACHINE.store(usize::try_from(b).unwrap_or(usize::MAX), Relaxed);
            set(Some(b), true);
        }
        None => set(None, false),
    }
}

/// Sets the budget (`None`: none; the live heap is still counted), and the ceiling.
pub fn set(bytes: Option<u64>, default: bool) {
    match bytes {
        Some(b) => {
            budget::set_memory_budget(b, default);
            let machine = MACHINE.load(Relaxed);
            let b = usize::try_from(b).unwrap_or(usize::MAX);
            CEILING.store(if machine == 0 { b } else { b.max(machine) }, Relaxed);
        }
        None => {
            budget::count_without_budget();
            CEILING.store(usize::MAX, Relaxed);
        }
    }
}

/// The machine's default budget (`None`: unknown, so no budget by default).
pub fn machine() -> Option<u64> {
    Some(MACHINE.load(Relaxed) as u64).filter(|&m| m > 0)
}

/// Notes the phase of the call that runs.
pub fn set_phase(phase: &'static str) {
    if let Ok(mut p) = PHASE.lock() {
        *p = phase;
    }
}

/// The budget as the messages name it: "2M", "12800M by default".
pub fn limit_text() -> String {
    LimitText.to_string()
}

/// What the budget saw since a call started.
#[derive(Clone, Copy)]
pub struct Watch {
    soft: usize,
    over: usize,
}

impl Watch {
    /// Starts watching.
    pub fn start() -> Watch {
        Watch {
            soft: SOFT_PASSES.load(Relaxed),
            over: OVER_PASSES.load(Relaxed),
        }
    }

    /// The live heap passed the soft limit since the start.
    pub fn soft_passed(&self) -> bool {
        SOFT_PASSES.load(Relaxed) != self.soft
    }

    /// The live heap passed the budget since the start: the most live bytes seen.
    pub fn over_passed(&self) -> Option<u64> {
        (OVER_PASSES.load(Relaxed) != self.over).then(|| OVER_LIVE.load(Relaxed) as u64)
    }
}

/// The planners' budget question: whether `bytes`, estimated for what `phase` is about
/// to build, fit in what the budget leaves; when they do not, what was refused (the
/// detail of the error), as the command line words it.
pub fn affordable(phase: &'static str, bytes: u64) -> Result<(), String> {
    match budget::memory_left() {
        Some(left) if bytes > left => Err(format!(
            "the {phase} needs at least {} MiB, {} MiB are left",
            bytes >> 20,
            left >> 20
        )),
        _ => Ok(()),
    }
}
