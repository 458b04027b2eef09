//! The memory budget: a counting global allocator, the budget it counts against, and
//! what is left of it, shared by the command line (`apart --max-memory`) and the
//! Python extension (`apart.set_memory_budget`), so that both count and refuse alike.
//!
//! A program installs [`Budget`] as its `#[global_allocator]`, sets a budget with
//! [`set_memory_budget`] (by default [`machine_budget`]: 80 % of the machine's memory
//! or of its cgroup's limit), and says with [`set_hooks`] what happens when the live
//! heap passes the soft limit (90 % of the budget: ask the running planners for their
//! partial answers) and the budget itself. The hooks run inside the allocator: they
//! must not allocate (atomic operations, writes of a [`FixedText`] with [`raw_write`],
//! ending the process). Whatever a hook does, the allocation it was called for is then
//! made: nothing here ever fails an allocation, since a failed allocation aborts a Rust
//! process. The command line's hook ends the run with a message past the budget; the
//! Python extension's lets the call finish and raises its error then, and ends the
//! process only past a ceiling (the machine's default budget).
//!
//! Planners ask before they build a structure whose memory they estimated
//! ([`crate::progress::Progress::with_budget`], answered from [`memory_left`]).
//!
//! [`Budget`] counts the bytes of live heap allocations (not stack, code or mapped
//! files). Each thread settles its count with the shared one every 256 KiB of traffic,
//! so the budget holds to within that much per thread. Without a budget nothing is
//! counted: the allocator adds one relaxed atomic load per call. [`watch_resident`]
//! bounds the resident size too, and an address-space limit lowers the default.

use std::alloc::{GlobalAlloc, Layout, System};
use std::fmt;
use std::sync::atomic::{AtomicBool, AtomicIsize, AtomicUsize, Ordering::Relaxed};
use std::sync::OnceLock;

/// The budget in bytes; 0: no budget, nothing counted; `usize::MAX`: counted, no budget.
static LIMIT: AtomicUsize = AtomicUsize::new(0);
/// The soft limit, 90 % of the budget.
static SOFT: AtomicUsize = AtomicUsize::new(usize::MAX);
/// Live heap bytes allocated since counting started (frees of earlier allocations can
/// make it slightly negative).
static LIVE: AtomicIsize = AtomicIsize::new(0);
/// The budget is the machine's default (named so in the messages).
static BY_DEFAULT: AtomicBool = AtomicBool::new(false);

/// Smallest budget accepted: below this even loading a small assembly fails.
pub const MIN_MEMORY: u64 = 1 << 20;

/// The share of the machine's memory the default budget takes.
pub const DEFAULT_SHARE: f64 = 0.8;

/// The default budget: [`DEFAULT_SHARE`] of the smaller of the physical memory
/// (`/proc/meminfo`'s MemTotal) and the cgroup's memory limit if one is set (v2
/// `memory.max`, not "max"; v1 `memory.limit_in_bytes`), rounded down to a whole MiB;
/// `None` where neither can be read.
pub fn machine_budget() -> Option<u64> {
    let read = |p: &str| std::fs::read_to_string(p).ok();
    let total = read("/proc/meminfo").and_then(|t| {
        t.lines()
            .find_map(|l| l.strip_prefix("MemTotal:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
            .map(|kb| kb.saturating_mul(1024))
    });
    // The cgroup's own folder (v2: the line "0::/path" of /proc/self/cgroup), and the
    // root of the cgroup namespace, which a container sees as its own.
    let own = read("/proc/self/cgroup").and_then(|t| {
        t.lines()
            .find_map(|l| l.strip_prefix("0::"))
            .map(|p| p.trim().to_string())
    });
    let mut files = vec!["/sys/fs/cgroup/memory.max".to_string()];
    if let Some(p) = own.filter(|p| p != "/" && !p.contains("..")) {
        files.push(format!("/sys/fs/cgroup{p}/memory.max"));
    }
    files.push("/sys/fs/cgroup/memory/memory.limit_in_bytes".into());
    let cgroup = files
        .iter()
        .filter_map(|f| read(f))
        .filter_map(|t| t.trim().parse::<u64>().ok())
        // v1 says "no limit" with a huge number.
        .filter(|&b| b > 0 && b < 1 << 60)
        .min();
    let memory = match (total, cgroup) {
        (Some(t), Some(c)) => t.min(c),
        (t, c) => t.or(c)?,
    };
    let mut budget = (memory as f64 * DEFAULT_SHARE) as u64;
    // An address-space limit (`ulimit -v`) fails allocations before the memory runs
    // out: the heap gets its share of what is left after the code, the stacks and the
    // allocator's reserved arenas (512 MiB set aside for them).
    if let Some(space) = read("/proc/self/limits").and_then(|t| address_space_limit(&t)) {
        let heap = (space.saturating_sub(AS_RESERVED) as f64 * DEFAULT_SHARE) as u64;
        budget = budget.min(heap);
    }
    let budget = budget >> 20 << 20;
    (budget >= MIN_MEMORY).then_some(budget)
}

/// Address space set aside for what is not heap (code, stacks, the allocator's arenas)
/// when the default budget comes from an address-space limit.
const AS_RESERVED: u64 = 512 << 20;

/// The soft "Max address space" limit in bytes from the text of `/proc/self/limits`
/// (`None`: unlimited or not found).
fn address_space_limit(limits: &str) -> Option<u64> {
    let line = limits
        .lines()
        .find(|l| l.starts_with("Max address space"))?;
    line["Max address space".len()..]
        .split_whitespace()
        .next()?
        .parse::<u64>()
        .ok()
}

/// How far the resident size may grow past the budget before the run ends: the
/// allocator's own pages and the threads' stacks, which the counted heap leaves out,
/// are some MiB on a small run.
const RESIDENT_SLACK: usize = 64 << 20;

/// Watches the resident size as well as the counted heap, from now on: a thread reads
/// `/proc/self/status` every 20 ms and calls the hooks when the growth of `VmRSS`
/// passes the budget by more than 64 MiB. The soft limit stays the counted heap's, so that where a planner
/// is asked to stop does not depend on the sampling's timing. The counted heap misses what the allocator keeps beyond
/// the bytes asked for (headers, fragments, freed pages not yet returned), which made
/// a 3 GiB budget end at 3.5 GiB resident; a program alone in its process (the command
/// line, not an interpreter holding other data) bounds both. Started once.
pub fn watch_resident() {
    static STARTED: AtomicBool = AtomicBool::new(false);
    if STARTED.swap(true, Relaxed) {
        return;
    }
    let _ = std::thread::Builder::new()
        .name("apart-resident".into())
        .spawn(|| {
            let mut buf = [0u8; 4096];
            // What was resident before (the program's code and data), not counted.
            let base = resident(&mut buf)
                .unwrap_or(0)
                .saturating_sub(live() as usize);
            loop {
                std::thread::sleep(std::time::Duration::from_millis(20));
                let limit = LIMIT.load(Relaxed);
                if limit == 0 || limit == usize::MAX {
                    continue;
                }
                if let Some(rss) = resident(&mut buf) {
                    let grown = rss.saturating_sub(base);
                    if grown > limit.saturating_add(RESIDENT_SLACK) {
                        passed(grown, limit);
                    }
                }
            }
        });
}

/// `VmRSS` of `/proc/self/status` in bytes, read into `buf`.
fn resident(buf: &mut [u8]) -> Option<usize> {
    use std::io::Read;
    let mut f = std::fs::File::open("/proc/self/status").ok()?;
    let mut n = 0;
    while n < buf.len() {
        match f.read(&mut buf[n..]) {
            Ok(0) => break,
            Ok(k) => n += k,
            Err(_) => return None,
        }
    }
    let text = std::str::from_utf8(&buf[..n]).ok()?;
    let line = text.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kb: usize = line["VmRSS:".len()..]
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()?;
    Some(kb.saturating_mul(1024))
}

/// Sets the heap budget to `bytes` (`default`: the machine's default, named so in the
/// messages), its soft limit to 90 % of it. Counting starts at the first budget set;
/// a later one keeps the count.
pub fn set_memory_budget(bytes: u64, default: bool) {
    let limit = usize::try_from(bytes)
        .unwrap_or(usize::MAX)
        .min(usize::MAX - 1);
    set_limit(limit, limit / 10 * 9, default);
}

/// Counts the live heap without a budget (the Python extension's "no budget": the
/// count stays right for a budget set later).
pub fn count_without_budget() {
    set_limit(usize::MAX, usize::MAX, false);
}

fn set_limit(limit: usize, soft: usize, default: bool) {
    BY_DEFAULT.store(default, Relaxed);
    SOFT.store(soft, Relaxed);
    if LIMIT.swap(limit, Relaxed) == 0 {
        LIVE.store(0, Relaxed);
    }
}

/// The budget in bytes (`None`: none).
pub fn limit() -> Option<u64> {
    match LIMIT.load(Relaxed) {
        0 | usize::MAX => None,
        l => Some(l as u64),
    }
}

/// Live heap bytes counted (0 when nothing is counted).
pub fn live() -> u64 {
    LIVE.load(Relaxed).max(0) as u64
}

/// Heap bytes still free under the memory budget (`None`: no budget).
pub fn memory_left() -> Option<u64> {
    limit().map(|l| l.saturating_sub(live()))
}

/// A size in bytes as `4G`, `1536M`, `100K`, or bytes; written without allocating.
#[derive(Clone, Copy, Debug)]
pub struct Size(pub u64);

impl fmt::Display for Size {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let bytes = self.0;
        for (unit, shift) in [("T", 40), ("G", 30), ("M", 20), ("K", 10)] {
            if bytes >= 1 << shift && bytes % (1 << shift) == 0 {
                return write!(f, "{}{unit}", bytes >> shift);
            }
        }
        write!(f, "{bytes}")
    }
}

/// A size in bytes as `4G`, `1536M`, `100K`, or bytes.
pub fn size_text(bytes: u64) -> String {
    Size(bytes).to_string()
}

/// The budget as the messages name it (`4G`, `19280M by default`, `none`); written
/// without allocating.
#[derive(Clone, Copy, Debug)]
pub struct LimitText;

impl fmt::Display for LimitText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match limit() {
            None => f.write_str("none"),
            Some(l) if BY_DEFAULT.load(Relaxed) => write!(f, "{} by default", Size(l)),
            Some(l) => write!(f, "{}", Size(l)),
        }
    }
}

/// The budget as the messages name it ([`LimitText`]).
pub fn limit_text() -> LimitText {
    LimitText
}

/// Reads a size such as `4G`, `500M`, `1.5G` or `1048576` (bytes): K, M, G, T are
/// powers of 1024, an optional trailing `B` or `iB` is ignored. At least
/// [`MIN_MEMORY`]. The error says what is wrong, without naming the option.
pub fn parse_size(text: &str) -> Result<u64, String> {
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

/// What happens when the live heap passes the soft limit (`soft`) or the budget
/// (`over`), each called with the live bytes at every settling past it (so usually
/// more than once: a hook that acts once keeps its own flag). They run inside the
/// allocator and must not allocate; when they return, the allocation is made.
#[derive(Clone, Copy, Debug)]
pub struct Hooks {
    /// Past 90 % of the budget.
    pub soft: fn(usize),
    /// Past the budget.
    pub over: fn(usize),
}

static HOOKS: OnceLock<Hooks> = OnceLock::new();

/// Sets the hooks (once; later calls are ignored). Without hooks, passing the soft
/// limit does nothing and passing the budget ends the process with "error: out of
/// memory budget (SIZE): N MiB of heap asked for" (exit code 1).
pub fn set_hooks(hooks: Hooks) {
    let _ = HOOKS.set(hooks);
}

fn no_soft_hook(_live: usize) {}

/// Ends the process past the budget (the default `over` hook), once.
fn end_over_budget(live: usize) {
    static ENDING: AtomicBool = AtomicBool::new(false);
    if ENDING.swap(true, Relaxed) {
        return;
    }
    use fmt::Write;
    let mut text = FixedText::new();
    let _ = writeln!(
        text,
        "error: out of memory budget ({}): {} MiB of heap asked for",
        LimitText,
        live >> 20
    );
    raw_write(2, text.as_bytes());
    std::process::exit(1)
}

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
/// and calls the hooks past the soft limit and past the budget.
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
        if d > 0 && live > 0 {
            passed(live as usize, limit);
        }
    }
}

/// The live heap grew to `live`: the hooks of the limits it passes.
#[cold]
fn passed(live: usize, limit: usize) {
    let hooks = HOOKS.get().copied().unwrap_or(Hooks {
        soft: no_soft_hook,
        over: end_over_budget,
    });
    if live > limit {
        (hooks.over)(live);
    }
    if live > SOFT.load(Relaxed) {
        (hooks.soft)(live);
    }
}

#[inline]
fn charge(bytes: usize) {
    account(bytes.min(isize::MAX as usize) as isize);
}

#[inline]
fn refund(bytes: usize) {
    account(-(bytes.min(isize::MAX as usize) as isize));
}

/// The global allocator: the system allocator, counting live bytes against the
/// memory budget when one is set (see the module documentation).
pub struct Budget;

// SAFETY: every call is forwarded to the system allocator with the same arguments;
// the counting around it never allocates (nor do the hooks, by their contract).
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

/// A fixed buffer that formats without allocating (for messages written from inside
/// the allocator or a signal handler); text past its 512 bytes is cut.
pub struct FixedText {
    bytes: [u8; 512],
    len: usize,
}

impl FixedText {
    /// An empty buffer.
    pub fn new() -> FixedText {
        FixedText {
            bytes: [0; 512],
            len: 0,
        }
    }

    /// The bytes written.
    pub fn as_bytes(&self) -> &[u8] {
        &self.bytes[..self.len]
    }
}

impl Default for FixedText {
    fn default() -> FixedText {
        FixedText::new()
    }
}

impl fmt::Write for FixedText {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let n = s.len().min(self.bytes.len() - self.len);
        self.bytes[self.len..self.len + n].copy_from_slice(&s.as_bytes()[..n]);
        self.len += n;
        Ok(())
    }
}

/// Writes bytes to file descriptor `fd` (1 or 2) without a lock or an allocation.
#[cfg(unix)]
#[allow(unsafe_code)]
pub fn raw_write(fd: i32, bytes: &[u8]) {
    use std::io::Write;
    use std::os::fd::FromRawFd;
    // SAFETY: fd 1 and 2 stay open for the life of the process; ManuallyDrop keeps this
    // File from closing them.
    let mut f = std::mem::ManuallyDrop::new(unsafe { std::fs::File::from_raw_fd(fd) });
    let _ = f.write_all(bytes);
}

/// Writes bytes to standard output (`fd` 1) or standard error.
#[cfg(not(unix))]
pub fn raw_write(fd: i32, bytes: &[u8]) {
    use std::io::Write;
    if fd == 1 {
        let _ = std::io::stdout().write_all(bytes);
    } else {
        let _ = std::io::stderr().write_all(bytes);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn address_space_limits_are_read_from_proc_limits() {
        let text = "Limit                     Soft Limit           Hard Limit           Units     \n\
                    Max cpu time              unlimited            unlimited            seconds   \n\
                    Max address space         8589934592           unlimited            bytes     \n";
        assert_eq!(address_space_limit(text), Some(8 << 30));
        let text = text.replace("8589934592", "unlimited");
        assert_eq!(address_space_limit(&text), None);
        let mut buf = [0u8; 4096];
        assert!(resident(&mut buf).is_some_and(|r| r > 0));
    }

    #[test]
    fn sizes() {
        assert_eq!(parse_size("4G"), Ok(4 << 30));
        assert_eq!(parse_size("1.5GiB"), Ok(3 << 29));
        for bad in ["", "G", "4X", "-1G", "nan", "0", "1K"] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
        assert_eq!(size_text(4 << 30), "4G");
        assert_eq!(size_text(1536 << 20), "1536M");
        assert_eq!(size_text(1000), "1000");
    }
}
