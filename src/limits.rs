//! Bounds on a run: the phase it is in (named by every message that stops it), the
//! `--timeout` watchdog, the memory budget (a counting global allocator), Ctrl-C, and
//! the parsers that check every numeric option, with its range, before any work starts.
//!
//! Three things raise the planners' shared stop flag ([`stop_flag`]) once a planner
//! that returns partial answers has started (pair regions and the motion space of
//! `partition`, the steps of `sequence`, the placements of `stack`: each is handed an
//! `apart::plan::Progress` by `output::planner`): the `--timeout` deadline, the memory
//! budget's soft limit (or a motion space the planner estimates over what the budget
//! leaves) and Ctrl-C. The first of them is recorded as the reason ([`Stopped`]). The
//! planners check the flag between units of work (part pairs, culling rounds, batches
//! of faces and cells, steps, candidates) and return what they have, marked as
//! stopped; the command prints that partial answer with its status line ("stopped by
//! --timeout after S s during PHASE: partial answer", and in the JSON `"complete":
//! false`, `"status"` "timeout", "out of memory" or "interrupted" and a `"stopped"`
//! object), writes no picture or export, and exits with [`EXIT_PARTIAL`] (3) after a
//! timeout, 1 after the memory budget (with the error line "out of memory budget
//! (--max-memory SIZE) during PHASE" after the answer), [`EXIT_INTERRUPTED`] (130)
//! after Ctrl-C.
//!
//! - `--timeout S`: a watchdog thread sleeps until the deadline and raises the flag.
//!   Hard fallback: when no answer is being printed [`grace`] seconds after the flag (a
//!   tenth of the timeout, at least 5 s: one indivisible step such as the overlay's
//!   build may run on), the watchdog prints "stopped after S s: PHASE" and ends the
//!   process with exit code 1, as it does at once while the run is still loading (no
//!   answer yet) or in a command without a partial answer (`check`, `decompose`,
//!   `place`, `separate`, `partition --first` and `--direction`). Files being written
//!   then may be incomplete.
//! - The memory budget: `--max-memory SIZE`, or by default 80 % of the machine's memory
//!   (the smaller of the physical memory and the cgroup's limit, [`machine_budget`]);
//!   `--max-memory none` (or 0) sets none. [`Budget`] (the kernel's
//!   `apart::kernel::budget`, shared with the Python extension) wraps the system
//!   allocator and counts the bytes of live heap allocations, and a thread samples the
//!   resident size every 20 ms (what the allocator keeps beyond the bytes asked for). Past 90 % of the budget while a planner runs
//!   (the soft limit) it raises the stop flag (an atomic store, nothing allocated) for
//!   the partial answer; an allocation that would pass the budget itself prints "out of
//!   memory budget (--max-memory SIZE) during PHASE" with a raw write (no allocation
//!   inside the allocator) and exits with code 1 instead of allocating. Each thread
//!   settles its count with the shared one every 256 KiB of traffic, so the budget
//!   holds to within that much per thread. Without a budget nothing is counted: the
//!   allocator adds one relaxed atomic load per call.
//! - Ctrl-C: while a planner with partial answers runs, the first Ctrl-C raises the
//!   stop flag ([`install_interrupt`]); a second one, or one at any other time once the
//!   handler is installed, ends the process at once with exit code 130. Before a
//!   planner starts (loading), Ctrl-C keeps the system's default: the run ends at once.

pub use apart::kernel::budget::{limit_text, machine_budget, memory_left, Budget};
use apart::kernel::budget::{raw_write, FixedText as Buf};
use std::sync::atomic::{
    AtomicBool, AtomicU64, AtomicU8, AtomicUsize, Ordering, Ordering::Relaxed,
};
use std::sync::{Arc, Mutex, OnceLock};

/// What the run is doing now, for the messages that stop it.
static PHASE: Mutex<&'static str> = Mutex::new("starting");

/// Records the phase the run enters.
pub fn set_phase(phase: &'static str) {
    *PHASE.lock().unwrap_or_else(|e| e.into_inner()) = phase;
}

/// The phase the run is in (`"?"` if another thread is just changing it).
pub fn phase() -> &'static str {
    match PHASE.try_lock() {
        Ok(p) => *p,
        Err(std::sync::TryLockError::Poisoned(p)) => *p.into_inner(),
        Err(std::sync::TryLockError::WouldBlock) => "?",
    }
}

/// Set once a limit has stopped the run: a second report (another thread passing the
/// budget meanwhile) stays silent.
static STOPPING: AtomicBool = AtomicBool::new(false);
/// With `--json` (1), a stopped run also prints a JSON error object on standard output;
/// with `sequence --jsonl` (2), a last line `{"event": "end", "valid": false, ...}`.
static JSON: AtomicU8 = AtomicU8::new(0);

/// Ends the run: `message` (already free of characters that need JSON escaping) as an
/// error line on standard error, and as a JSON error object with `--json` whose
/// `"status"` is `status` ("timeout", "out of memory"); exit code 1. Formats into fixed
/// buffers, so it is safe to call from the allocator.
fn stop(status: &str, message: std::fmt::Arguments) -> ! {
    use std::fmt::Write;
    let mut text = Buf::new();
    let _ = text.write_fmt(message);
    let mut err = Buf::new();
    {
        use std::io::IsTerminal;
        if std::io::stderr().is_terminal() {
            // Clear a progress bar drawn on this line.
            let _ = err.write_str("\r\x1b[2K");
        }
    }
    let _ = err.write_str("error: ");
    let _ = err.write_str(std::str::from_utf8(text.as_bytes()).unwrap_or("stopped"));
    let _ = err.write_str("\n");
    let json = JSON.load(Relaxed);
    if json != 0 {
        let mut out = Buf::new();
        let _ = out.write_str(if json == 2 {
            "\n{\"event\": \"end\", \"valid\": false, \"error\": \""
        } else {
            "\n{\"valid\": false, \"error\": \""
        });
        let _ = out.write_str(std::str::from_utf8(text.as_bytes()).unwrap_or("stopped"));
        let _ = out.write_str("\", \"status\": \"");
        let _ = out.write_str(status);
        let _ = out.write_str("\"}\n");
        raw_write(1, out.as_bytes());
    }
    raw_write(2, err.as_bytes());
    std::process::exit(1)
}

/// Whether a limit has already ended the run.
fn claim_stop() -> bool {
    !STOPPING.swap(true, Relaxed)
}

/// Notes whether stopped runs also print a JSON error object (`--json`).
pub fn set_json(json: bool) {
    JSON.store(u8::from(json), Relaxed);
}

/// Notes that the answer is printed as JSON lines (`sequence --jsonl`): a stopped or
/// failed run ends them with an "end" event holding the error.
pub fn set_json_lines() {
    JSON.store(2, Relaxed);
}

/// Whether the answer is printed as JSON lines ([`set_json_lines`]).
pub fn json_lines() -> bool {
    JSON.load(Relaxed) == 2
}

// ---------------------------------------------------------------------------
// The stop flag and why it was raised

/// Exit code of a run stopped by `--timeout` that printed its partial answer.
pub const EXIT_PARTIAL: u8 = 3;

/// Exit code of a run ended by Ctrl-C (128 + SIGINT, as a shell reports a run killed by
/// it), with or without a partial answer.
pub const EXIT_INTERRUPTED: u8 = 130;

/// When the run started, for the times of stops ([`start_clock`]).
static START: OnceLock<std::time::Instant> = OnceLock::new();

/// Starts the run's clock (first thing in `main`).
pub fn start_clock() {
    let _ = START.get_or_init(std::time::Instant::now);
}

/// Milliseconds since [`start_clock`] (0 before it); allocates nothing, so the allocator
/// and the Ctrl-C handler may call it.
fn elapsed_ms() -> u64 {
    START.get().map_or(0, |t| {
        u64::try_from(t.elapsed().as_millis()).unwrap_or(u64::MAX)
    })
}

/// The stop flag every planner of the run watches.
static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();

/// The stop flag every planner of the run watches (raised by the `--timeout` watchdog,
/// the memory budget and Ctrl-C). `main` makes it before the budget is set, so that
/// the allocator and the signal handler only read it ([`raise_stop_flag`]).
pub fn stop_flag() -> Arc<AtomicBool> {
    FLAG.get_or_init(Arc::default).clone()
}

/// Raises the stop flag if it exists, without allocating (the allocator and the Ctrl-C
/// handler call it).
fn raise_stop_flag() {
    if let Some(f) = FLAG.get() {
        f.store(true, Ordering::Release);
    }
}

/// Why the stop flag was raised: nothing yet, `--timeout`, the memory budget, Ctrl-C.
const BY_NONE: u8 = 0;
const BY_TIMEOUT: u8 = 1;
const BY_MEMORY: u8 = 2;
const BY_INTERRUPT: u8 = 3;
/// The first reason to raise the stop flag (the one the answer names).
static STOP_BY: AtomicU8 = AtomicU8::new(BY_NONE);
/// Milliseconds after the start at which the reason was recorded.
static STOP_AT_MS: AtomicU64 = AtomicU64::new(0);

/// Records `by` as the reason for the stop unless another came first; true when it is
/// the reason. Atomic stores only (the allocator and the signal handler call it).
fn claim_reason(by: u8) -> bool {
    let first = STOP_BY
        .compare_exchange(BY_NONE, by, Relaxed, Relaxed)
        .is_ok();
    if first {
        STOP_AT_MS.store(elapsed_ms(), Relaxed);
    }
    first
}

/// What the watchdog and the budget keeper note about a stop, beside its reason: the
/// seconds to report, the phase, and a detail (the estimate refused).
#[derive(Clone, Debug)]
struct Note {
    seconds: f64,
    phase: &'static str,
    detail: Option<String>,
}

static NOTE: Mutex<Option<Note>> = Mutex::new(None);

fn note(n: Note) {
    *NOTE.lock().unwrap_or_else(|e| e.into_inner()) = Some(n);
}

/// Set once a planner that returns partial answers has started: from then on the
/// deadline raises the stop flag instead of ending the process at once.
static PLANNING: AtomicBool = AtomicBool::new(false);
/// Set while a planner that returns partial answers runs, until the command has its
/// answer ([`end_planning`]): Ctrl-C then asks for the partial answer.
static INTERRUPTIBLE: AtomicBool = AtomicBool::new(false);
/// Set when the command starts printing an answer after the stop flag: the watchdog's
/// hard fallback then stays silent.
static ANSWERING: AtomicBool = AtomicBool::new(false);

/// Notes that a planner returning partial answers has started (see the module comment),
/// and installs the Ctrl-C handler.
pub fn begin_planning() {
    PLANNING.store(true, Relaxed);
    INTERRUPTIBLE.store(true, Relaxed);
    install_interrupt();
}

/// Notes that the planners are done: from here on Ctrl-C ends the run at once.
pub fn end_planning() {
    INTERRUPTIBLE.store(false, Relaxed);
}

/// What stopped a planner early.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopBy {
    /// The `--timeout` deadline.
    Timeout,
    /// The memory budget: its soft limit, or an estimate over what it leaves.
    Memory,
    /// Ctrl-C.
    Interrupt,
}

/// Why a planner stopped early, when, and in which phase.
#[derive(Clone, Debug)]
pub struct Stopped {
    pub by: StopBy,
    /// For a timeout, the `--timeout` given; otherwise the seconds since the start.
    pub seconds: f64,
    pub phase: &'static str,
    /// For the memory budget: what was refused or how much was in use.
    pub detail: Option<String>,
}

impl Stopped {
    /// The answer's `"status"`: "timeout", "out of memory" or "interrupted".
    pub fn status(&self) -> &'static str {
        match self.by {
            StopBy::Timeout => "timeout",
            StopBy::Memory => "out of memory",
            StopBy::Interrupt => "interrupted",
        }
    }

    /// Who stopped the run, in the JSON's `"stopped"`: "--timeout", "--max-memory" (the
    /// memory budget, given or by default) or "Ctrl-C".
    pub fn by_key(&self) -> &'static str {
        match self.by {
            StopBy::Timeout => "--timeout",
            StopBy::Memory => "--max-memory",
            StopBy::Interrupt => "Ctrl-C",
        }
    }

    /// The words for what is left unsplit: "stopped by --timeout".
    pub fn short(&self) -> &'static str {
        match self.by {
            StopBy::Timeout => "stopped by --timeout",
            StopBy::Memory => "stopped by the memory budget",
            StopBy::Interrupt => "interrupted",
        }
    }

    /// The exit code of the partial answer: 3 (timeout), 1 (memory), 130 (Ctrl-C).
    pub fn exit_code(&self) -> u8 {
        match self.by {
            StopBy::Timeout => EXIT_PARTIAL,
            StopBy::Memory => 1,
            StopBy::Interrupt => EXIT_INTERRUPTED,
        }
    }

    /// The error line printed after the partial answer, for a run that fails: "out of
    /// memory budget (--max-memory SIZE) during PHASE".
    pub fn error(&self) -> Option<String> {
        (self.by == StopBy::Memory).then(|| {
            let mut e = format!(
                "out of memory budget (--max-memory {}) during {}",
                limit_text(),
                self.phase
            );
            if let Some(d) = &self.detail {
                e.push_str(": ");
                e.push_str(d);
            }
            e
        })
    }
}

impl std::fmt::Display for Stopped {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.by {
            StopBy::Timeout => write!(
                f,
                "stopped by --timeout after {} s during {}: partial answer",
                self.seconds, self.phase
            ),
            StopBy::Memory => write!(
                f,
                "stopped by the memory budget (--max-memory {}) during {}: partial answer",
                limit_text(),
                self.phase
            ),
            StopBy::Interrupt => write!(
                f,
                "interrupted (Ctrl-C) after {:.1} s during {}: partial answer",
                self.seconds, self.phase
            ),
        }
    }
}

/// Why a planner returned stopped (which limit raised its flag, when, in which phase),
/// called by the command before it prints the partial answer: from then on the
/// watchdog's hard fallback stays silent.
pub fn partial_answer(global: &crate::Global) -> Stopped {
    ANSWERING.store(true, Relaxed);
    // (Acquire: pairs with the release of the flag, after the reason was noted.)
    let _ = stop_flag().load(Ordering::Acquire);
    let noted = NOTE.lock().unwrap_or_else(|e| e.into_inner()).clone();
    let since_start = STOP_AT_MS.load(Relaxed) as f64 / 1e3;
    match STOP_BY.load(Relaxed) {
        BY_MEMORY => {
            let n = noted.unwrap_or_else(|| Note {
                seconds: since_start,
                phase: phase(),
                detail: Some(format!(
                    "{} MiB of heap in use, past 90 % of the budget",
                    SOFT_LIVE.load(Relaxed) >> 20
                )),
            });
            Stopped {
                by: StopBy::Memory,
                seconds: n.seconds,
                phase: n.phase,
                detail: n.detail,
            }
        }
        BY_INTERRUPT => Stopped {
            by: StopBy::Interrupt,
            seconds: since_start,
            phase: phase(),
            detail: None,
        },
        // The watchdog's, or a flag raised by nobody known (taken as the timeout's).
        _ => {
            let n = noted.unwrap_or_else(|| Note {
                seconds: global.timeout.unwrap_or(0.0),
                phase: phase(),
                detail: None,
            });
            Stopped {
                by: StopBy::Timeout,
                seconds: n.seconds,
                phase: n.phase,
                detail: None,
            }
        }
    }
}

// ---------------------------------------------------------------------------
// --timeout

/// Largest `--timeout`, in seconds (one week).
pub const MAX_TIMEOUT: f64 = 604_800.0;

/// Seconds a planner has, after the stop flag, to return its partial answer before the
/// process is ended anyway: a tenth of the timeout, at least 5 s.
pub fn grace(seconds: f64) -> f64 {
    (seconds / 10.0).max(5.0)
}

/// Starts the watchdog that ends the run after `seconds` (see the module comment).
pub fn start_watchdog(seconds: f64) {
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs_f64(seconds);
    let sleep_until = |t: std::time::Instant| loop {
        let now = std::time::Instant::now();
        if now >= t {
            break;
        }
        std::thread::sleep(t - now);
    };
    let spawned = std::thread::Builder::new()
        .name("apart-timeout".into())
        .spawn(move || {
            sleep_until(deadline);
            if PLANNING.load(Relaxed) {
                // Ask the planners for what they have (unless another limit already did).
                if claim_reason(BY_TIMEOUT) {
                    note(Note {
                        seconds,
                        phase: phase(),
                        detail: None,
                    });
                }
                raise_stop_flag();
                let grace = grace(seconds);
                sleep_until(deadline + std::time::Duration::from_secs_f64(grace));
                if !ANSWERING.load(Relaxed) && claim_stop() {
                    stop("timeout", format_args!(
                        "stopped after {seconds} s: {} (--timeout {seconds}; no partial answer within {grace} s more)",
                        phase()
                    ));
                }
                return;
            }
            if claim_stop() {
                stop("timeout", format_args!(
                    "stopped after {seconds} s: {} (--timeout {seconds})",
                    phase()
                ));
            }
        });
    if let Err(e) = spawned {
        crate::output::eline(format_args!(
            "warning: cannot start the --timeout watchdog: {e}"
        ));
    }
}

// ---------------------------------------------------------------------------
// Ctrl-C

/// Ctrl-C presses seen by the handler.
static INTERRUPTS: AtomicUsize = AtomicUsize::new(0);

/// Installs the SIGINT handler (once): while a planner with partial answers runs, the
/// first Ctrl-C records the reason and raises the stop flag; a second one, or one when
/// no planner runs, ends the process at once with exit code 130. The handler only
/// stores atomics, reads the clock and, to end the run, writes a fixed line and calls
/// `_exit`: all async-signal-safe.
#[cfg(unix)]
#[allow(unsafe_code)]
pub fn install_interrupt() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    extern "C" fn on_interrupt(_signal: libc::c_int) {
        let first = INTERRUPTS.fetch_add(1, Relaxed) == 0;
        if first && INTERRUPTIBLE.load(Relaxed) && !ANSWERING.load(Relaxed) {
            claim_reason(BY_INTERRUPT);
            raise_stop_flag();
            const ASK: &[u8] = b"\ninterrupted: stopping for the partial answer (Ctrl-C again ends the run at once)\n";
            // SAFETY: writing a static buffer to fd 2 is async-signal-safe.
            unsafe { libc::write(2, ASK.as_ptr().cast(), ASK.len()) };
            return;
        }
        const END: &[u8] = b"\nerror: interrupted (Ctrl-C)\n";
        // SAFETY: write and _exit are async-signal-safe.
        unsafe {
            libc::write(2, END.as_ptr().cast(), END.len());
            libc::_exit(EXIT_INTERRUPTED.into());
        }
    }
    ONCE.call_once(|| {
        // SAFETY: a zeroed sigaction is a valid value to fill in; the handler is an
        // `extern "C"` function of the signature SIGINT expects.
        unsafe {
            let mut action: libc::sigaction = std::mem::zeroed();
            action.sa_sigaction = on_interrupt as extern "C" fn(libc::c_int) as libc::sighandler_t;
            action.sa_flags = libc::SA_RESTART;
            libc::sigemptyset(&raw mut action.sa_mask);
            libc::sigaction(libc::SIGINT, &raw const action, std::ptr::null_mut());
        }
    });
}

/// Without Unix signals, Ctrl-C keeps the system's default.
#[cfg(not(unix))]
pub fn install_interrupt() {}

// ---------------------------------------------------------------------------
// The memory budget

/// Set once the soft limit raised the stop flag.
static SOFT_FIRED: AtomicBool = AtomicBool::new(false);
/// The live bytes when the soft limit fired.
static SOFT_LIVE: AtomicUsize = AtomicUsize::new(0);

/// Sets the heap budget: `bytes` from `--max-memory`, or the machine's default
/// (`default`, named so in the messages). The counting allocator and the budget are
/// the kernel's ([`apart::kernel::budget`], shared with the Python extension); the
/// run's reactions are these: past the soft limit the stop flag ([`soft_limit`]), past
/// the budget the end of the run ([`over_budget`]).
pub fn set_memory_budget(bytes: u64, default: bool) {
    apart::kernel::budget::set_hooks(apart::kernel::budget::Hooks {
        soft: soft_limit,
        over: over_budget,
    });
    apart::kernel::budget::set_memory_budget(bytes, default);
    apart::kernel::budget::watch_resident();
}

/// Past the soft limit: while a planner runs, asks it for its partial answer (once).
/// Atomic operations only: it runs inside the allocator.
#[cold]
fn soft_limit(live: usize) {
    if !INTERRUPTIBLE.load(Relaxed) || SOFT_FIRED.swap(true, Relaxed) {
        return;
    }
    if claim_reason(BY_MEMORY) {
        SOFT_LIVE.store(live, Relaxed);
    }
    raise_stop_flag();
}

/// Past the budget: ends the run with the error line (once; the allocation that
/// passed it is not made). Formats into fixed buffers: it runs inside the allocator.
#[cold]
fn over_budget(live: usize) {
    if !claim_stop() {
        return;
    }
    stop(
        "out of memory",
        format_args!(
            "out of memory budget (--max-memory {}) during {}: {} MiB of heap asked for",
            limit_text(),
            phase(),
            live >> 20
        ),
    )
}

/// The planners' budget question ([`apart::plan::Progress::with_budget`]): whether
/// `bytes`, estimated for what `phase` is about to build, fit in what the budget
/// leaves. When they do not, the reason and the estimate are recorded (the planner
/// then raises the stop flag and returns its partial answer).
pub fn affordable(phase: &'static str, bytes: u64) -> bool {
    let Some(left) = memory_left() else {
        return true;
    };
    if bytes <= left {
        return true;
    }
    if claim_reason(BY_MEMORY) {
        note(Note {
            seconds: elapsed_ms() as f64 / 1e3,
            phase,
            detail: Some(format!(
                "the {phase} needs at least {} MiB, {} MiB are left",
                bytes >> 20,
                left >> 20
            )),
        });
    }
    false
}

/// A planner's note of a large structure it is about to build: a warning when no
/// memory budget is set (`--max-memory none`), which would have stopped it in time.
pub fn large_estimate(_phase: &'static str, what: &str) {
    if memory_left().is_none() && !crate::output::is_quiet() {
        crate::output::eline(format_args!(
            "warning: {what}; --max-memory SIZE stops the run before it is built"
        ));
    }
}

/// The memory budget refused what a job was about to build: the error that ends the
/// run (its JSON error object says `"status": "out of memory"`).
#[derive(Debug)]
pub struct OverBudget(pub String);

impl std::fmt::Display for OverBudget {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for OverBudget {}

/// A job's error for the command line: the memory budget's refusal words the budget
/// and what is left.
pub fn job_error(e: apart::jobs::JobError, _global: &crate::Global) -> anyhow::Error {
    match e {
        apart::jobs::JobError::Plan(e) => e.into(),
        apart::jobs::JobError::OverBudget { what, .. } => anyhow::Error::new(OverBudget(format!(
            "out of memory budget (--max-memory {}): {what}, {} MiB are left",
            limit_text(),
            memory_left().unwrap_or(0) >> 20
        ))),
        apart::jobs::JobError::Stack(e) => e.into(),
        e @ apart::jobs::JobError::Part { .. } => anyhow::anyhow!("{e}"),
        apart::jobs::JobError::NotFinite { setting, value } => anyhow::anyhow!(
            "--{} {value} is not a finite number",
            setting.replace('_', "-")
        ),
    }
}

// ---------------------------------------------------------------------------
// Option parsers: every numeric option is checked here, with its range in the error,
// while the command line is read.

/// Parses a finite number.
fn finite(text: &str) -> Result<f64, String> {
    let v: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("\"{text}\" is not a number"))?;
    if !v.is_finite() {
        return Err(format!("must be a finite number, not \"{text}\""));
    }
    Ok(v)
}

/// Parses a whole number in `lo..=hi`.
fn whole(text: &str, lo: u64, hi: u64) -> Result<u64, String> {
    let range = || {
        if hi >= u32::MAX.into() {
            format!("a whole number of at least {lo}")
        } else {
            format!("a whole number from {lo} to {hi}")
        }
    };
    let t = text.trim();
    let v: i128 = t
        .parse()
        .map_err(|_| format!("must be {}, not \"{text}\"", range()))?;
    if v < lo as i128 || v > hi as i128 {
        return Err(format!("must be {}, not {text}", range()));
    }
    Ok(v as u64)
}

/// Largest `--threads`.
pub const MAX_THREADS: u64 = 1024;

/// `--threads`: 1 to [`MAX_THREADS`].
pub fn threads(text: &str) -> Result<usize, String> {
    whole(text, 1, MAX_THREADS).map(|v| v as usize)
}

/// The help of `--grid-bits`, with the range the kernel's grid supports.
pub fn grid_bits_help() -> String {
    use apart::kernel::grid::{MAX_BITS, MIN_BITS};
    format!(
        "Bits of a snapped coordinate, {MIN_BITS} to {MAX_BITS}: the grid is the finest power of two that keeps every coordinate below 2^N steps"
    )
}

/// `--grid-bits`: the range the kernel's grid supports.
pub fn grid_bits(text: &str) -> Result<u32, String> {
    use apart::kernel::grid::{MAX_BITS, MIN_BITS};
    whole(text, MIN_BITS.into(), MAX_BITS.into()).map(|v| v as u32)
}

/// `--timeout`: seconds, more than 0 and at most [`MAX_TIMEOUT`].
pub fn timeout(text: &str) -> Result<f64, String> {
    let v = finite(text)?;
    if v <= 0.0 || v > MAX_TIMEOUT {
        return Err(format!(
            "must be more than 0 and at most {MAX_TIMEOUT} seconds (one week), not {text}"
        ));
    }
    Ok(v)
}

/// `--max-memory`: a size such as `4G`, `500M`, `1.5G` or `1048576` (bytes); K, M, G, T
/// are powers of 1024, an optional trailing `B` or `iB` is ignored. At least 1M.
pub fn memory_size(text: &str) -> Result<u64, String> {
    apart::kernel::budget::parse_size(text)
}

/// `--max-memory`: a size as [`memory_size`] reads it, or `none` (or `0`) for no
/// budget, given as 0.
pub fn memory_budget(text: &str) -> Result<u64, String> {
    let t = text.trim();
    if t.eq_ignore_ascii_case("none") || t.parse::<f64>().is_ok_and(|v| v == 0.0) {
        return Ok(0);
    }
    memory_size(text).map_err(|e| {
        if e.starts_with("must be a size") {
            format!("{e} (or none: no budget)")
        } else {
            e
        }
    })
}

/// `--limit`: 1 or more moving sets.
pub fn limit(text: &str) -> Result<usize, String> {
    positive(text)
}

/// Whole numbers of at least 1 (`--max-depth`, `--step`).
pub fn positive(text: &str) -> Result<usize, String> {
    whole(text, 1, usize::MAX as u64).map(|v| v as usize)
}

/// Most parts `stack --count` takes: the stacker's time grows about with the cube of
/// the count (200 cubes: 6 s, 400: 46 s on a 2-core machine), so 1000 is already
/// minutes and more would run for hours.
pub const MAX_STACK_COUNT: u64 = 1000;

/// `stack --count`: 1 to [`MAX_STACK_COUNT`].
pub fn stack_count(text: &str) -> Result<usize, String> {
    whole(text, 1, MAX_STACK_COUNT).map(|v| v as usize)
}

/// `--max-candidates` of stack: 1 to 100000.
pub fn max_candidates(text: &str) -> Result<usize, String> {
    whole(text, 1, 100_000).map(|v| v as usize)
}

/// `--candidates` of place: 1 to 1000.
pub fn candidates(text: &str) -> Result<usize, String> {
    whole(text, 1, 1000).map(|v| v as usize)
}

/// Smallest `--dtheta`: twice the 0.05° error allowed to the exact (Pythagorean)
/// rotations, so that successive orientations stay distinct; 3600 orientations.
pub const MIN_DTHETA: f64 = 0.1;

/// `--dtheta`: degrees in [[`MIN_DTHETA`], 360].
pub fn dtheta(text: &str) -> Result<f64, String> {
    let v = finite(text)?;
    if !(MIN_DTHETA..=360.0).contains(&v) {
        return Err(format!(
            "must be between {MIN_DTHETA} and 360 degrees, not {text}"
        ));
    }
    Ok(v)
}

/// `--weight`: in [0, 1].
pub fn weight(text: &str) -> Result<f64, String> {
    let v = finite(text)?;
    if !(0.0..=1.0).contains(&v) {
        return Err(format!("must be between 0 and 1, not {text}"));
    }
    Ok(v)
}

/// A length that may be zero (`--clearance`).
pub fn nonnegative(text: &str) -> Result<f64, String> {
    let v = finite(text)?;
    if v < 0.0 {
        return Err(format!("must be 0 or more, not {text}"));
    }
    Ok(v)
}

/// A length that must be more than zero (`--max-height`).
pub fn positive_length(text: &str) -> Result<f64, String> {
    let v = finite(text)?;
    if v <= 0.0 {
        return Err(format!("must be more than 0, not {text}"));
    }
    Ok(v)
}

/// Any finite number (`--floor-z`).
pub fn number(text: &str) -> Result<f64, String> {
    finite(text)
}

/// `N` comma-separated finite numbers, checked now and kept as text.
fn numbers(text: &str, n: usize) -> Result<String, String> {
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() != n {
        return Err(format!("needs {n} comma-separated numbers, not \"{text}\""));
    }
    for p in parts {
        finite(p)?;
    }
    Ok(text.to_string())
}

/// "X,Y,Z" (`--target`, `--floor-point`).
pub fn three_numbers(text: &str) -> Result<String, String> {
    numbers(text, 3)
}

/// "X0,Y0,X1,Y1" (`--floor`), low corner not above the high one.
pub fn floor_box(text: &str) -> Result<String, String> {
    numbers(text, 4)?;
    let v: Vec<f64> = text
        .split(',')
        .map(|s| s.trim().parse().unwrap_or(0.0))
        .collect();
    if v[0] > v[2] || v[1] > v[3] {
        return Err(format!(
            "\"{text}\" is empty: X0 must not exceed X1, nor Y0 Y1"
        ));
    }
    Ok(text.to_string())
}

/// "X0,Y0,Z0,X1,Y1,Z1" (`--region`, `--translations`), low corner not above the high
/// one.
pub fn box_numbers(text: &str) -> Result<String, String> {
    numbers(text, 6)?;
    let v: Vec<f64> = text
        .split(',')
        .map(|s| s.trim().parse().unwrap_or(0.0))
        .collect();
    if (0..3).any(|i| v[i] > v[i + 3]) {
        return Err(format!(
            "\"{text}\" is empty: a low corner above the high one"
        ));
    }
    Ok(text.to_string())
}

/// "PHI,PSI" in degrees, multiples of 90 (`--base`).
pub fn base(text: &str) -> Result<String, String> {
    numbers(text, 2)?;
    for p in text.split(',') {
        let d: f64 = p.trim().parse().unwrap_or(0.0);
        if d.rem_euclid(90.0) != 0.0 {
            return Err(format!(
                "\"{text}\": angles must be multiples of 90 degrees"
            ));
        }
    }
    Ok(text.to_string())
}

/// `--tolerance`: `auto` or a positive finite length, optionally with a unit (whether
/// `--units` is given is checked right after the command line is read).
pub fn tolerance(text: &str) -> Result<String, String> {
    crate::input_facts::parse_tolerance(text, Some(crate::input_facts::Units::M))
        .map_err(|e| e.to_string().trim_start_matches("--tolerance ").to_string())?;
    Ok(text.to_string())
}

/// `--direction` of partition: three numbers, not all zero.
pub fn direction(text: &str) -> Result<String, String> {
    crate::commands::partition::parse_direction(text).map_err(|e| e.to_string())?;
    Ok(text.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_ranges() {
        assert_eq!(memory_size("4G"), Ok(4 << 30));
        assert_eq!(memory_size("500M"), Ok(500 << 20));
        assert_eq!(memory_size("500MB"), Ok(500 << 20));
        assert_eq!(memory_size("1.5GiB"), Ok(3 << 29));
        assert_eq!(memory_size("1048576"), Ok(1 << 20));
        for bad in ["", "G", "4X", "-1G", "nan", "inf", "0", "1K", "1e300T"] {
            assert!(memory_size(bad).is_err(), "{bad}");
        }
        assert_eq!(memory_budget("none"), Ok(0));
        assert_eq!(memory_budget("0"), Ok(0));
        assert_eq!(memory_budget("2M"), Ok(2 << 20));
        for bad in ["", "4X", "1K", "-1"] {
            assert!(memory_budget(bad).is_err(), "{bad}");
        }
        assert_eq!(threads("1"), Ok(1));
        assert_eq!(threads("1024"), Ok(1024));
        for bad in ["0", "1025", "1000000", "-1", "2.5", "x"] {
            assert!(threads(bad).is_err(), "{bad}");
        }
        assert!(dtheta("0.1").is_ok() && dtheta("360").is_ok());
        for bad in ["-90", "0", "1e-9", "nan", "inf", "361"] {
            assert!(dtheta(bad).is_err(), "{bad}");
        }
        assert!(dtheta("nan").unwrap_err().contains("finite"));
        assert!(timeout("0.5").is_ok());
        for bad in ["0", "-1", "nan", "1e9"] {
            assert!(timeout(bad).is_err(), "{bad}");
        }
        assert!(floor_box("-1,-1,1,1").is_ok());
        assert!(floor_box("1,-1,-1,1").is_err());
        assert!(base("90,-180").is_ok());
        assert!(base("45,0").is_err());
        assert!(tolerance("auto").is_ok() && tolerance("5um").is_ok());
        assert!(tolerance("-1").is_err() && tolerance("nan").is_err());
    }
}
