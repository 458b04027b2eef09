//! Bounds on a run: the phase it is in (named by every message that stops it), the
//! `--timeout` watchdog, the `--max-memory` budget (a counting global allocator), and the
//! parsers that check every numeric option, with its range, before any work starts.
//!
//! - `--timeout S`: a watchdog thread sleeps until the deadline. If a planner that
//!   returns partial answers has started (pair regions and the motion space of
//!   `partition`, the steps of `sequence`, the placements of `stack`: each is handed an
//!   `apart::plan::Progress` by `output::planner`), the watchdog raises the shared stop
//!   flag ([`stop_flag`]). The planners check it between units of work (part pairs,
//!   culling rounds, batches of faces and cells, steps, candidates) and return what
//!   they have, marked as stopped; the command prints that partial answer with the
//!   status line "stopped by --timeout after S s during PHASE: partial answer" (in the
//!   JSON `"status": "timeout"`, `"complete": false` and a `"stopped"` object), writes no
//!   picture or export, and exits with [`EXIT_PARTIAL`] (3). Hard fallback: when no
//!   answer is being printed [`grace`] seconds after the flag (a tenth of the timeout,
//!   at least 5 s: one indivisible step such as the overlay's build may run on), the
//!   watchdog prints "stopped after S s: PHASE" and ends the process with exit code 1,
//!   as it does at once while the run is still loading (no answer yet) or in a command
//!   without a partial answer (`check`, `decompose`, `place`, `separate`, `partition
//!   --first` and `--direction`). Files being written then may be incomplete.
//! - `--max-memory SIZE`: [`Budget`] wraps the system allocator and counts the bytes of
//!   live heap allocations (not stack, code or mapped files, so the resident size is a
//!   few MB larger). An allocation that would pass the budget prints "out of memory
//!   budget (--max-memory SIZE) during PHASE" with a raw write (no allocation inside the
//!   allocator) and exits with code 1 instead of allocating. Each thread settles its
//!   count with the shared one every 256 KiB of traffic, so the budget holds to within
//!   that much per thread. Without the flag nothing is counted: the allocator adds one
//!   relaxed atomic load per call.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicIsize, AtomicUsize, Ordering, Ordering::Relaxed};
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
/// With `--json`, a stopped run also prints a JSON error object on standard output.
static JSON: AtomicBool = AtomicBool::new(false);

/// A fixed buffer that formats without allocating (the allocator itself uses it).
struct Buf {
    bytes: [u8; 512],
    len: usize,
}

impl Buf {
    fn new() -> Buf {
        Buf {
            bytes: [0; 512],
            len: 0,
        }
    }

    fn as_bytes(&self) -> &[u8] {
        &self.bytes[..self.len]
    }
}

impl std::fmt::Write for Buf {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        let n = s.len().min(self.bytes.len() - self.len);
        self.bytes[self.len..self.len + n].copy_from_slice(&s.as_bytes()[..n]);
        self.len += n;
        Ok(())
    }
}

/// Writes bytes to file descriptor `fd` without a lock or an allocation.
#[cfg(unix)]
#[allow(unsafe_code)]
fn raw_write(fd: i32, bytes: &[u8]) {
    use std::io::Write;
    use std::os::fd::FromRawFd;
    // SAFETY: fd 1 and 2 stay open for the life of the process; ManuallyDrop keeps this
    // File from closing them.
    let mut f = std::mem::ManuallyDrop::new(unsafe { std::fs::File::from_raw_fd(fd) });
    let _ = f.write_all(bytes);
}

#[cfg(not(unix))]
fn raw_write(fd: i32, bytes: &[u8]) {
    use std::io::Write;
    if fd == 1 {
        let _ = std::io::stdout().write_all(bytes);
    } else {
        let _ = std::io::stderr().write_all(bytes);
    }
}

/// Ends the run: `message` (already free of characters that need JSON escaping) as an
/// error line on standard error, and as a JSON error object with `--json`; exit code 1.
/// Formats into fixed buffers, so it is safe to call from the allocator.
fn stop(message: std::fmt::Arguments) -> ! {
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
    if JSON.load(Relaxed) {
        let mut out = Buf::new();
        let _ = out.write_str("\n{\"valid\": false, \"error\": \"");
        let _ = out.write_str(std::str::from_utf8(text.as_bytes()).unwrap_or("stopped"));
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

/// Notes whether stopped runs also print a JSON error object.
pub fn set_json(json: bool) {
    JSON.store(json, Relaxed);
}

// ---------------------------------------------------------------------------
// --timeout

/// Largest `--timeout`, in seconds (one week).
pub const MAX_TIMEOUT: f64 = 604_800.0;

/// Exit code of a run stopped by `--timeout` that printed its partial answer.
pub const EXIT_PARTIAL: u8 = 3;

/// The stop flag every planner of the run watches (raised by the `--timeout` watchdog).
pub fn stop_flag() -> Arc<AtomicBool> {
    static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();
    FLAG.get_or_init(Arc::default).clone()
}

/// Set once a planner that returns partial answers has started: from then on the
/// deadline raises the stop flag instead of ending the process at once.
static PLANNING: AtomicBool = AtomicBool::new(false);
/// Set when the command starts printing an answer after the stop flag: the watchdog's
/// hard fallback then stays silent.
static ANSWERING: AtomicBool = AtomicBool::new(false);
/// The timeout and the phase the run was in when the watchdog raised the stop flag.
static TIMED_OUT: Mutex<Option<(f64, &'static str)>> = Mutex::new(None);

/// Notes that a planner returning partial answers has started (see the module comment).
pub fn begin_planning() {
    PLANNING.store(true, Relaxed);
}

/// Why a planner stopped early: `--timeout` after `seconds`, during `phase`.
#[derive(Clone, Copy, Debug)]
pub struct TimedOut {
    pub seconds: f64,
    pub phase: &'static str,
}

impl std::fmt::Display for TimedOut {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "stopped by --timeout after {} s during {}: partial answer",
            self.seconds, self.phase
        )
    }
}

/// Why a planner returned stopped (the `--timeout` watchdog raised its flag, and when),
/// called by the command before it prints the partial answer: from then on the
/// watchdog's hard fallback stays silent.
pub fn partial_answer(global: &crate::Global) -> TimedOut {
    ANSWERING.store(true, Relaxed);
    // (Acquire: pairs with the watchdog's release of the flag, after it noted the phase.)
    let _ = stop_flag().load(Ordering::Acquire);
    let noted = *TIMED_OUT.lock().unwrap_or_else(|e| e.into_inner());
    let (seconds, phase) = noted.unwrap_or((global.timeout.unwrap_or(0.0), phase()));
    TimedOut { seconds, phase }
}

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
                // Ask the planners for what they have.
                *TIMED_OUT.lock().unwrap_or_else(|e| e.into_inner()) = Some((seconds, phase()));
                stop_flag().store(true, Ordering::Release);
                let grace = grace(seconds);
                sleep_until(deadline + std::time::Duration::from_secs_f64(grace));
                if !ANSWERING.load(Relaxed) && claim_stop() {
                    stop(format_args!(
                        "stopped after {seconds} s: {} (--timeout {seconds}; no partial answer within {grace} s more)",
                        phase()
                    ));
                }
                return;
            }
            if claim_stop() {
                stop(format_args!(
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
// --max-memory

/// The budget in bytes; 0: no budget, nothing counted.
static LIMIT: AtomicUsize = AtomicUsize::new(0);
/// Live heap bytes allocated since the budget was set (frees of earlier allocations
/// can make it slightly negative).
static LIVE: AtomicIsize = AtomicIsize::new(0);
/// The budget as a size (`4G`), for the message.
static LIMIT_TEXT: OnceLock<String> = OnceLock::new();

/// A size in bytes as `4G`, `1536M`, `100K`, or bytes.
pub fn size_text(bytes: u64) -> String {
    for (unit, shift) in [("T", 40), ("G", 30), ("M", 20), ("K", 10)] {
        if bytes >= 1 << shift && bytes % (1 << shift) == 0 {
            return format!("{}{unit}", bytes >> shift);
        }
    }
    bytes.to_string()
}

/// Smallest accepted `--max-memory`: below this even loading a small assembly fails.
pub const MIN_MEMORY: u64 = 1 << 20;

/// Sets the heap budget.
pub fn set_memory_budget(bytes: u64) {
    let _ = LIMIT_TEXT.set(size_text(bytes));
    LIVE.store(0, Relaxed);
    LIMIT.store(usize::try_from(bytes).unwrap_or(usize::MAX), Relaxed);
}

/// The global allocator: the system allocator, counting live bytes against the
/// `--max-memory` budget when one is set.
pub struct Budget;

/// Bytes a thread may allocate or free before it settles with the shared count: the
/// shared atomic is touched once per this much traffic, not on every call (two threads
/// updating one counter on every allocation cost about 10% of the CPU time of an
/// allocation-heavy partition). The budget holds to within this much per thread; an
/// allocation at least this large is checked before it is made.
const SLACK: isize = 256 << 10;

thread_local! {
    /// This thread's allocations minus frees not yet added to [`LIVE`].
    static PENDING: std::cell::Cell<isize> = const { std::cell::Cell::new(0) };
}

/// Counts `delta` bytes (allocated: positive, freed: negative) when a budget is set,
/// and ends the run when the live bytes pass it.
#[inline]
fn account(delta: isize) {
    let limit = LIMIT.load(Relaxed);
    if limit == 0 {
        return;
    }
    let settle = PENDING
        .try_with(|p| {
            let v = p.get().saturating_add(delta);
            if v.unsigned_abs() < SLACK as usize {
                p.set(v);
                None
            } else {
                p.set(0);
                Some(v)
            }
        })
        .unwrap_or(Some(delta));
    if let Some(d) = settle {
        let live = LIVE.fetch_add(d, Relaxed).saturating_add(d);
        if d > 0 && live > 0 && live as usize > limit && claim_stop() {
            over_budget(live as usize);
        }
    }
}

#[inline]
fn charge(bytes: usize) {
    account(bytes.min(isize::MAX as usize) as isize);
}

#[cold]
fn over_budget(live: usize) -> ! {
    let text = LIMIT_TEXT.get().map_or("?", String::as_str);
    stop(format_args!(
        "out of memory budget (--max-memory {text}) during {}: {} MiB of heap asked for",
        phase(),
        live >> 20
    ))
}

/// Heap bytes still free under the `--max-memory` budget (`None`: no budget).
pub fn memory_left() -> Option<u64> {
    let limit = LIMIT.load(Relaxed);
    (limit != 0).then(|| (limit as i64 - LIVE.load(Relaxed).max(0) as i64).max(0) as u64)
}

/// An estimate of the motion space below this many bytes builds without a word.
const QUIET_ESTIMATE: u64 = 2 << 30;

/// Before the motion space of `subset` is built: refuses it when its estimated memory
/// (a lower bound: the arcs and the cells' blocking statuses, measured to be 1.5–3 times
/// below the real peak on lattices of 200–1000 cubes) exceeds what `--max-memory` leaves,
/// and warns when it is large and no budget is set.
pub fn check_motion_space(
    regions: &apart::plan::BlockingRegions,
    subset: &[usize],
    global: &crate::Global,
) -> anyhow::Result<()> {
    let e = apart::plan::MotionSpace::estimate(regions, subset);
    let what = format!(
        "the motion space of {} parts ({} arcs, {:.0} blocked pairs per cell) needs at least {} MiB",
        e.parts,
        e.arcs,
        e.blocked_per_cell,
        e.bytes >> 20
    );
    match memory_left() {
        Some(left) if e.bytes > left => {
            let text = LIMIT_TEXT.get().map_or("?", String::as_str);
            anyhow::bail!(
                "out of memory budget (--max-memory {text}): {what}, {} MiB are left",
                left >> 20
            )
        }
        None if e.bytes >= QUIET_ESTIMATE && !global.quiet => {
            crate::output::eline(format_args!(
                "warning: {what}; --max-memory SIZE stops the run before it is built"
            ));
        }
        _ => {}
    }
    Ok(())
}

#[inline]
fn refund(bytes: usize) {
    account(-(bytes.min(isize::MAX as usize) as isize));
}

// SAFETY: every call is forwarded to the system allocator with the same arguments;
// the counting around it never allocates.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Budget {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        charge(layout.size());
        // SAFETY: forwarded as given.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        charge(layout.size());
        // SAFETY: forwarded as given.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        refund(layout.size());
        // SAFETY: forwarded as given.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let old = layout.size();
        if new_size > old {
            charge(new_size - old);
        } else {
            refund(old - new_size);
        }
        // SAFETY: forwarded as given.
        unsafe { System.realloc(ptr, layout, new_size) }
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
    let t = text.trim();
    let bad = || {
        format!("must be a size such as 4G, 500M or 1048576 (bytes; K, M, G, T are powers of 1024), not \"{text}\"")
    };
    let t = t
        .strip_suffix("iB")
        .or_else(|| t.strip_suffix("ib"))
        .or_else(|| t.strip_suffix(['B', 'b']))
        .unwrap_or(t);
    let (number, scale) = match t.char_indices().last() {
        Some((k, c)) if c.is_ascii_alphabetic() => {
            let scale = match c.to_ascii_uppercase() {
                'K' => 1u64 << 10,
                'M' => 1 << 20,
                'G' => 1 << 30,
                'T' => 1 << 40,
                _ => return Err(bad()),
            };
            (&t[..k], scale)
        }
        _ => (t, 1),
    };
    let v: f64 = number.trim().parse().map_err(|_| bad())?;
    if !v.is_finite() {
        return Err(bad());
    }
    let bytes = v * scale as f64;
    if bytes < MIN_MEMORY as f64 {
        return Err(format!("must be at least 1M (1048576 bytes), not {text}"));
    }
    if bytes >= u64::MAX as f64 {
        return Err(format!("is too large: {text}"));
    }
    Ok(bytes as u64)
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
