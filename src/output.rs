//! Output shared by the commands: numbers in input units, tables, problems, JSON, the
//! progress bars, the status of a partial answer, and the one-line failure message.

use crate::limits::Stopped;
use crate::Global;
use apart::assembly::LoadSeconds;
use apart::kernel::progress::{phases, Progress};
use apart::kernel::Aabb;
use apart::kernel::Grid;
use apart::mesh::Problem;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// "load T ms (read a, validate b, ...)": the load's wall time and its stages (the
/// stages that took under 0.05 ms are left out).
pub fn load_time(total: f64, s: &LoadSeconds) -> String {
    let stages: Vec<String> = [
        ("read", s.read),
        ("validate", s.validate),
        ("decompose", s.decompose),
        ("snapping", s.snapping),
        ("overlaps", s.overlaps),
    ]
    .iter()
    .filter(|(_, t)| *t >= 5e-5)
    .map(|(name, t)| format!("{name} {:.1}", t * 1e3))
    .collect();
    format!("load {:.1} ms ({})", total * 1e3, stages.join(", "))
}

/// Prints one line on standard output (through [`to_stdout`]: a write error fails the
/// run at its end, a closed pipe only drops the rest of the output).
pub fn line(text: impl std::fmt::Display) {
    use std::io::Write;
    to_stdout(|out| writeln!(out, "{text}"));
}

/// The first error met writing standard output, if any: later writes are skipped.
static STDOUT_ERROR: std::sync::Mutex<Option<std::io::Error>> = std::sync::Mutex::new(None);

/// An I/O error's text without its "(os error N)": "No space left on device".
pub fn io_text(e: &std::io::Error) -> String {
    let text = e.to_string();
    match text.find(" (os error ") {
        Some(k) => text[..k].to_string(),
        None => text,
    }
}

/// Writes on standard output with `write`, unless an earlier write failed; an error is
/// recorded for [`stdout_result`] (every answer written on standard output goes through
/// here, so that none is lost silently).
pub fn to_stdout(write: impl FnOnce(&mut std::io::StdoutLock) -> std::io::Result<()>) {
    let mut failed = STDOUT_ERROR.lock().unwrap_or_else(|e| e.into_inner());
    if failed.is_some() {
        return;
    }
    if let Err(e) = write(&mut std::io::stdout().lock()) {
        *failed = Some(e);
    }
}

/// Flushes standard output, and fails with "cannot write to standard output: No space
/// left on device" when a write to it failed (exit code 1). A closed pipe (`apart check
/// x | head`) is not a failure: the reader wanted no more, and the run keeps the exit
/// code of its answer.
pub fn stdout_result() -> anyhow::Result<()> {
    use std::io::Write;
    to_stdout(|out| out.flush());
    let failed = STDOUT_ERROR.lock().unwrap_or_else(|e| e.into_inner());
    match failed.as_ref() {
        None => Ok(()),
        Some(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Some(e) => anyhow::bail!("cannot write to standard output: {}", io_text(e)),
    }
}

/// Writes one line on standard error.
pub fn eline(text: impl std::fmt::Display) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr().lock(), "{text}");
}

/// A unit direction as `[x, y, z]` with three decimals.
pub fn unit(u: &[f64; 3]) -> String {
    let f = |x: f64| {
        let r = (x * 1000.0).round() / 1000.0;
        if r == 0.0 {
            "0".to_string()
        } else {
            format!("{r}")
        }
    };
    format!("[{}, {}, {}]", f(u[0]), f(u[1]), f(u[2]))
}

/// Whether `--quiet` was given, for messages printed without a [`Global`] at hand
/// ("wrote FILE"). Set by [`set_quiet`]; [`progress`] and [`phase`], which every
/// command goes through before it writes anything, set it too.
static QUIET: AtomicBool = AtomicBool::new(false);

/// Records `--quiet` for [`write_file`] and [`wrote`].
pub fn set_quiet(quiet: bool) {
    QUIET.store(quiet, Ordering::Relaxed);
}

/// Whether `--quiet` is on.
pub fn is_quiet() -> bool {
    QUIET.load(Ordering::Relaxed)
}

/// Writes `bytes` to `path` all or nothing ([`write_with`]), creating its folder if
/// needed (`--svg out/star.svg`), and announces it on standard error ("wrote
/// hinge.html") unless `--quiet`. Every file a command writes for the user goes through
/// here (or through [`write_with`] and [`wrote`]), so that none appears unannounced;
/// standard output, which may carry the JSON answer, stays untouched.
pub fn write_file(path: &Path, bytes: impl AsRef<[u8]>) -> anyhow::Result<()> {
    write_with(path, |w| w.write_all(bytes.as_ref()))?;
    wrote(path);
    Ok(())
}

/// Writes the file `path` all or nothing: `fill` writes into a temporary file beside it
/// (`.NAME.tmp-PID`, in the same folder, so on the same file system), which is flushed,
/// synced to the disk and renamed over `path` (a symbolic link is followed: its target
/// is replaced); the folder is synced too. On any error the temporary file is removed
/// and `path` is as it was; the error names `path`. The one way apart writes a file.
pub fn write_with(
    path: &Path,
    fill: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
) -> anyhow::Result<()> {
    let target = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
    let folder = match target.parent() {
        Some(f) if !f.as_os_str().is_empty() => f.to_path_buf(),
        _ => PathBuf::from("."),
    };
    std::fs::create_dir_all(&folder)
        .map_err(|e| anyhow::anyhow!("cannot create {}: {e}", folder.display()))?;
    let name = target
        .file_name()
        .ok_or_else(|| anyhow::anyhow!("cannot write {}: not a file name", path.display()))?;
    let tmp = folder.join(temporary_name(name, "tmp"));
    let written = fill_file(&tmp, &target, fill).and_then(|()| {
        test_hook_fail()?;
        std::fs::rename(&tmp, &target)
    });
    if let Err(e) = written {
        let _ = std::fs::remove_file(&tmp);
        anyhow::bail!("cannot write {}: {}", path.display(), io_text(&e));
    }
    sync_folder(&folder);
    test_hook_stop();
    Ok(())
}

/// `.NAME.KIND-PID`: a hidden name beside `NAME` for this process's temporary copy.
fn temporary_name(name: &std::ffi::OsStr, kind: &str) -> std::ffi::OsString {
    let mut t = std::ffi::OsString::from(".");
    t.push(name);
    t.push(format!(".{kind}-{}", std::process::id()));
    t
}

/// Creates `tmp`, writes it with `fill`, gives it the permissions of `target` when that
/// exists, and syncs it.
fn fill_file(
    tmp: &Path,
    target: &Path,
    fill: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    use std::io::Write;
    let file = std::fs::File::create(tmp)?;
    let mut w = std::io::BufWriter::new(file);
    fill(&mut w)?;
    w.flush()?;
    let file = w
        .into_inner()
        .map_err(std::io::IntoInnerError::into_error)?;
    if let Ok(m) = std::fs::metadata(target) {
        file.set_permissions(m.permissions())?;
    }
    file.sync_all()
}

/// Syncs a folder's entries to the disk (a rename in it is durable after this), where
/// the system allows it; a failure is ignored: the data itself was synced.
fn sync_folder(folder: &Path) {
    if let Ok(f) = std::fs::File::open(folder) {
        let _ = f.sync_all();
    }
}

/// Appends `line` (with its `\n`) to `file` in one write and syncs it: a results file
/// holds whole lines only. When the write fails, the file is cut back to its length
/// before it, so that no part of the line stays; `path` names it in the error.
pub fn append_line(file: &mut std::fs::File, path: &Path, line: &str) -> anyhow::Result<()> {
    use std::io::{Seek, Write};
    let text = format!("{line}\n");
    let start = file.seek(std::io::SeekFrom::End(0));
    let written = test_hook_fail()
        .and_then(|()| file.write_all(text.as_bytes()))
        .and_then(|()| file.sync_data());
    if let Err(e) = written {
        if let Ok(len) = start {
            let _ = file.set_len(len);
        }
        anyhow::bail!("cannot write {}: {}", path.display(), io_text(&e));
    }
    test_hook_stop();
    Ok(())
}

/// A folder written all or nothing (`decompose -o`, `sequence --renders`): its files go
/// into a hidden temporary folder beside it (`.NAME.tmp-PID`), which [`NewFolder::commit`]
/// renames into place; until then the folder does not exist (or is as it was), and a
/// run that fails removes the temporary folder. An existing folder is replaced only
/// when it is empty or was written by the same command (its marker file
/// [`MARKER`] says which); any other is refused, so that no user file is lost.
pub struct NewFolder {
    /// The folder as the user named it (in messages).
    shown: PathBuf,
    /// The folder's resolved path, where the temporary folder is renamed to.
    target: PathBuf,
    /// The temporary folder.
    tmp: PathBuf,
    /// Paths relative to the folder to announce once it is in place.
    announce: Vec<PathBuf>,
    committed: bool,
}

/// The marker file of a folder apart wrote, holding the command that wrote it ("apart
/// decompose"): such a folder may be replaced by the same command.
pub const MARKER: &str = ".apart-output";

impl NewFolder {
    /// Starts writing the folder `path` for `command` ("apart decompose"), or refuses
    /// when `path` exists and is not a folder that may be replaced.
    pub fn create(path: &Path, command: &str) -> anyhow::Result<NewFolder> {
        NewFolder::check(path, command)?;
        let target = resolved(path)?;
        let parent = target.parent().unwrap_or(Path::new("/")).to_path_buf();
        std::fs::create_dir_all(&parent)
            .map_err(|e| anyhow::anyhow!("cannot create {}: {e}", parent.display()))?;
        let name = target.file_name().unwrap_or(std::ffi::OsStr::new("output"));
        let tmp = parent.join(temporary_name(name, "tmp"));
        let _ = std::fs::remove_dir_all(&tmp);
        std::fs::create_dir(&tmp)
            .map_err(|e| anyhow::anyhow!("cannot create {}: {e}", tmp.display()))?;
        let mut folder = NewFolder {
            shown: path.to_path_buf(),
            target,
            tmp,
            announce: Vec::new(),
            committed: false,
        };
        folder.write(Path::new(MARKER), false, |w| writeln!(w, "{command}"))?;
        Ok(folder)
    }

    /// Refuses `path` when it exists and is not a folder that `command` may replace:
    /// an empty folder, or one holding `command`'s [`MARKER`]. For a check before
    /// long work; [`NewFolder::create`] checks again.
    pub fn check(path: &Path, command: &str) -> anyhow::Result<()> {
        let target = resolved(path)?;
        if let Ok(m) = std::fs::symlink_metadata(&target) {
            let replaceable = m.is_dir() && (is_empty(&target) || marked(&target, command));
            if !replaceable {
                anyhow::bail!(
                    "refusing to write to {}: it exists and is not a folder that {command} wrote (no {MARKER} file in it); remove it or choose another folder",
                    path.display()
                );
            }
        }
        Ok(())
    }

    /// Writes the file `rel` (relative to the folder, its own folders made) with `fill`
    /// through [`write_with`]; `announce`: name it in the "wrote" lines at the end.
    pub fn write(
        &mut self,
        rel: &Path,
        announce: bool,
        fill: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
    ) -> anyhow::Result<()> {
        write_with(&self.tmp.join(rel), fill).map_err(|e| self.unstaged(&e))?;
        if announce {
            self.announce.push(rel.to_path_buf());
        }
        Ok(())
    }

    /// Names `rel` (a sub-folder) in the "wrote" lines at the end.
    pub fn announce(&mut self, rel: &Path) {
        self.announce.push(rel.to_path_buf());
    }

    /// Puts the folder in place: renames the temporary folder to it (an existing folder
    /// that may be replaced is first renamed aside, then removed), and announces what
    /// was written.
    pub fn commit(mut self) -> anyhow::Result<()> {
        let shown = self.shown.clone();
        let err = |e: std::io::Error| {
            anyhow::anyhow!("cannot write {}: {}", shown.display(), io_text(&e))
        };
        sync_folder(&self.tmp);
        test_hook_fail().map_err(err)?;
        let parent = self.target.parent().unwrap_or(Path::new("/")).to_path_buf();
        let name = self
            .target
            .file_name()
            .unwrap_or(std::ffi::OsStr::new("output"));
        let old = parent.join(temporary_name(name, "old"));
        let replaced = self.target.exists();
        if replaced {
            let _ = std::fs::remove_dir_all(&old);
            std::fs::rename(&self.target, &old).map_err(err)?;
        }
        if let Err(e) = std::fs::rename(&self.tmp, &self.target) {
            if replaced {
                let _ = std::fs::rename(&old, &self.target);
            }
            return Err(err(e));
        }
        self.committed = true;
        sync_folder(&parent);
        if replaced {
            let _ = std::fs::remove_dir_all(&old);
        }
        test_hook_stop();
        for rel in std::mem::take(&mut self.announce) {
            wrote(&self.shown.join(rel));
        }
        Ok(())
    }

    /// An error of a file in the temporary folder, told by its place in the folder.
    fn unstaged(&self, e: &anyhow::Error) -> anyhow::Error {
        let text = e.to_string().replace(
            &self.tmp.display().to_string(),
            &self.shown.display().to_string(),
        );
        anyhow::anyhow!(text)
    }
}

impl Drop for NewFolder {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.tmp);
        }
    }
}

/// Whether the folder `dir` has no entry.
fn is_empty(dir: &Path) -> bool {
    std::fs::read_dir(dir).is_ok_and(|mut d| d.next().is_none())
}

/// Whether the folder `dir` holds the [`MARKER`] of `command`.
fn marked(dir: &Path, command: &str) -> bool {
    std::fs::read_to_string(dir.join(MARKER)).is_ok_and(|t| t.trim() == command)
}

/// Writes completed so far (files, folders put in place, lines), for the test hooks.
static WRITES: AtomicUsize = AtomicUsize::new(0);

/// The number in the environment variable `name`, if set.
fn hook(name: &str) -> Option<usize> {
    std::env::var(name).ok()?.parse().ok()
}

/// Test hook (hidden, for the fault-injection tests): with `APART_TEST_FAIL_WRITES=N`,
/// the N-th write (1 for the first) fails as on a full disk, after its bytes are
/// written to the temporary file and before it is put in place.
fn test_hook_fail() -> std::io::Result<()> {
    let n = WRITES.load(Ordering::Relaxed) + 1;
    if hook("APART_TEST_FAIL_WRITES") == Some(n) {
        return Err(std::io::Error::from_raw_os_error(libc::ENOSPC));
    }
    Ok(())
}

/// Test hook (hidden, for the fault-injection tests): with
/// `APART_TEST_STOP_AFTER_WRITES=N`, the process ends at once with exit code 9 just
/// after its N-th completed write (a file, a folder put in place, a results line), as
/// if killed there: no destructor runs, so temporary files stay as a kill leaves them
/// (an abort would do the same, but may leave a core file).
fn test_hook_stop() {
    let n = WRITES.fetch_add(1, Ordering::Relaxed) + 1;
    if hook("APART_TEST_STOP_AFTER_WRITES") == Some(n) {
        std::process::exit(9);
    }
}

/// `path` made absolute with symbolic links and `..` resolved, also when its last
/// components do not exist yet (they are appended to the nearest existing ancestor,
/// resolved).
pub fn resolved(path: &Path) -> anyhow::Result<PathBuf> {
    let abs = if path.is_absolute() {
        path.to_path_buf()
    } else {
        std::env::current_dir()?.join(path)
    };
    let mut rest = Vec::new();
    let mut base = abs.as_path();
    loop {
        if let Ok(c) = std::fs::canonicalize(base) {
            let mut out = c;
            for part in rest.iter().rev() {
                match part {
                    std::path::Component::ParentDir => {
                        out.pop();
                    }
                    std::path::Component::CurDir => {}
                    c => out.push(c.as_os_str()),
                }
            }
            return Ok(out);
        }
        match (base.parent(), base.components().next_back()) {
            (Some(parent), Some(last)) => {
                rest.push(last);
                base = parent;
            }
            _ => return Ok(abs),
        }
    }
}

/// Announces a written file or folder on standard error ("wrote out/pieces"), unless
/// `--quiet`: for commands that write through their own writers (a folder of pieces).
pub fn wrote(path: &std::path::Path) {
    if !QUIET.load(Ordering::Relaxed) {
        eline(format_args!("wrote {}", path.display()));
    }
}

/// A coordinate in input units, as the shortest decimal of its `f64`.
pub fn units(grid: &Grid, q: i64) -> String {
    let v = grid.to_units(q);
    if v == 0.0 {
        "0".into()
    } else {
        format!("{v}")
    }
}

/// A point in input units: `(x, y, z)`.
pub fn point(grid: &Grid, p: &[i64; 3]) -> String {
    format!(
        "({}, {}, {})",
        units(grid, p[0]),
        units(grid, p[1]),
        units(grid, p[2])
    )
}

/// A box in input units: `(x, y, z)-(x, y, z)`.
pub fn bbox(grid: &Grid, b: &Option<Aabb>) -> String {
    match b {
        Some(b) => format!("{}-{}", point(grid, &b.min), point(grid, &b.max)),
        None => "-".into(),
    }
}

/// The grid step as a power of two.
pub fn step(grid: &Grid) -> String {
    format!("2^{}", grid.exp)
}

/// Prints rows as left-aligned columns separated by two spaces.
pub fn table(header: &[&str], rows: &[Vec<String>]) {
    let mut width: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for r in rows {
        for (w, c) in width.iter_mut().zip(r) {
            *w = (*w).max(c.chars().count());
        }
    }
    let line = |cells: Vec<String>| {
        let n = cells.len();
        let mut s = String::new();
        for (i, (c, w)) in cells.into_iter().zip(&width).enumerate() {
            s.push_str(&c);
            if i + 1 < n {
                s.push_str(&" ".repeat(w - c.chars().count() + 2));
            }
        }
        line(s);
    };
    line(header.iter().map(|h| h.to_string()).collect());
    for r in rows {
        line(r.clone());
    }
}

/// Prints problems, one per line, skipping notes when quiet.
pub fn problems(global: &Global, problems: &[Problem]) {
    for p in problems {
        if global.quiet && p.severity == apart::mesh::Severity::Note {
            continue;
        }
        line(p);
    }
}

/// Prints a value as pretty JSON on standard output, written as it is serialized (a
/// large answer is never held in memory as one string), through [`to_stdout`].
pub fn json<T: serde::Serialize>(value: &T) -> anyhow::Result<()> {
    use std::io::Write;
    crate::limits::set_phase("writing the answer");
    let mut failed = None;
    to_stdout(|out| {
        let mut w = std::io::BufWriter::new(out);
        match serde_json::to_writer_pretty(&mut w, value) {
            Ok(()) => {}
            Err(e) if e.is_io() => return Err(e.into()),
            Err(e) => {
                failed = Some(e);
                return Ok(());
            }
        }
        writeln!(w)?;
        w.flush()
    });
    match failed {
        Some(e) => Err(e.into()),
        None => Ok(()),
    }
}

/// Whether progress is drawn: standard error is a terminal, and neither `--quiet` nor
/// `--json` was given.
fn shows_progress(global: &Global) -> bool {
    !global.quiet && !global.json && std::io::stderr().is_terminal()
}

/// The loader's progress: records each loading phase as the run's phase (for the
/// messages of `--timeout` and `--max-memory`) and, on a terminal, drives a progress
/// bar.
pub fn progress(global: &Global) -> (Option<ProgressBar>, Progress) {
    set_quiet(global.quiet);
    crate::limits::set_phase("loading");
    let bar = shows_progress(global).then(|| {
        let bar = ProgressBar::new(0);
        bar.set_style(
            ProgressStyle::with_template("{msg:>10} [{bar:30}] {pos}/{len} {elapsed}")
                .unwrap_or_else(|_| ProgressStyle::default_bar())
                .progress_chars("=> "),
        );
        // Redrawn every 200 ms, so the time keeps counting while one long item (the
        // convex decomposition of a large part) runs.
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        bar
    });
    let b = bar.clone();
    let progress = Progress::with_callback(move |phase, done, total| {
        if done == 0 {
            crate::limits::set_phase(match phase {
                phases::READING => "loading (reading files)",
                phases::VALIDATING => "loading (validating parts)",
                phases::DECOMPOSING => "loading (convex decomposition)",
                phases::OVERLAPS => "loading (overlaps between parts)",
                _ => "loading",
            });
        }
        if let Some(b) = &b {
            b.set_message(phase);
            b.set_length(total as u64);
            b.set_position(done as u64);
        }
    });
    (bar, progress)
}

/// A bar counting `total` items of `label` with the time left (`apart batch`), hidden
/// off a terminal, with `--quiet` or with `--json`.
pub fn counter(global: &Global, label: &'static str, total: u64) -> ProgressBar {
    if !shows_progress(global) {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} {elapsed}, about {eta} left")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar.set_message(label);
    bar.enable_steady_tick(std::time::Duration::from_millis(500));
    bar
}

/// A phase of a run, from [`phase`] until dropped.
pub struct Phase(Option<ProgressBar>);

impl Phase {
    /// Runs `f` (which prints on standard output) with the phase's bar, if any, hidden
    /// meanwhile, so that lines printed while it runs are not drawn over.
    pub fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        match &self.0 {
            Some(bar) => bar.suspend(f),
            None => f(),
        }
    }
}

impl Drop for Phase {
    fn drop(&mut self) {
        if let Some(bar) = &self.0 {
            bar.finish_and_clear();
        }
    }
}

/// Enters a phase: names it to the `--timeout` and `--max-memory` messages and, on a
/// terminal, shows it with a spinner and the time spent (for work that reports no
/// counts of its own: a long phase shows that it is still working and for how long).
/// Planners that report counts go through [`planner`].
pub fn phase(global: &Global, label: &'static str) -> Phase {
    set_quiet(global.quiet);
    crate::limits::set_phase(label);
    Phase(shows_progress(global).then(|| {
        let bar = ProgressBar::new_spinner();
        bar.set_style(
            ProgressStyle::with_template("{spinner} {msg} {elapsed}")
                .unwrap_or_else(|_| ProgressStyle::default_spinner()),
        );
        bar.set_message(label);
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        bar
    }))
}

/// Enters a planner's phase: like [`phase`], and hands out the
/// [`Progress`](apart::plan::Progress) to give the planner. Its callback names each of
/// the planner's own phases to the `--timeout` and `--max-memory` messages and, on a
/// terminal, drives a bar with the counts ("pair regions [=====>    ] 5120/11175 3s");
/// its stop flag is the run's ([`crate::limits::stop_flag`]), which `--timeout`, the
/// memory budget's soft limit and Ctrl-C raise: from here on they ask for the partial
/// answer instead of ending the process; and it asks the memory budget before it builds
/// a motion space whose memory it estimated ([`crate::limits::affordable`]).
pub fn planner(global: &Global, label: &'static str) -> (Phase, apart::plan::Progress) {
    set_quiet(global.quiet);
    crate::limits::set_phase(label);
    crate::limits::begin_planning();
    let bar = shows_progress(global).then(|| {
        let bar = ProgressBar::new(0);
        bar.set_style(
            ProgressStyle::with_template("{spinner} {msg} [{bar:30}] {pos}/{len} {elapsed}")
                .unwrap_or_else(|_| ProgressStyle::default_bar())
                .progress_chars("=> "),
        );
        bar.set_message(label);
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        bar
    });
    let b = bar.clone();
    let progress = apart::plan::Progress::with_callback(move |phase, done, total| {
        crate::limits::set_phase(phase);
        if let Some(b) = &b {
            b.set_message(phase);
            b.set_length(total as u64);
            b.set_position(done as u64);
        }
    })
    .with_stop_flag(crate::limits::stop_flag())
    .with_budget(crate::limits::affordable)
    .with_notes(crate::limits::large_estimate);
    (Phase(bar), progress)
}

/// States in `status` why a partial answer stopped, as the front end knows it.
pub fn stamp(status: &mut apart::jobs::Status, stop: &Option<Stopped>) {
    if let Some(t) = stop {
        status.stopped_by(t.status(), stop_facts(t));
    }
}

/// Where and why a partial answer stopped, as answers state it (`"stopped"`).
pub fn stop_facts(t: &Stopped) -> apart::jobs::StopFacts {
    apart::jobs::StopFacts {
        by: t.by_key().to_string(),
        after_seconds: t.seconds,
        phase: t.phase.to_string(),
        detail: t.detail.clone(),
    }
}

/// The status of a planner's answer: `None` when it ran to its end; for a partial
/// answer (`stopped`), why, announced on standard error ("warning: stopped by --timeout
/// after 2 s during sequence steps: partial answer", and that the pictures and exports
/// asked for, when `files`, are not written). From here on Ctrl-C ends the run at once.
pub fn partial(global: &Global, stopped: bool, files: bool) -> Option<Stopped> {
    crate::limits::end_planning();
    if !stopped {
        return None;
    }
    let t = crate::limits::partial_answer(global);
    eline(format_args!("warning: {t}"));
    if files {
        eline("warning: no picture or export written for a partial answer");
    }
    Some(t)
}

/// The exit code of an answer printed: for a partial answer its stop's (3 after
/// `--timeout`, 130 after Ctrl-C, 1 after the memory budget, whose error line "out of
/// memory budget (--max-memory SIZE) during PHASE" is printed now, after the answer);
/// otherwise `answer`.
pub fn exit_code(stop: &Option<Stopped>, answer: std::process::ExitCode) -> std::process::ExitCode {
    match stop {
        None => answer,
        Some(t) => {
            if let Some(e) = t.error() {
                use std::io::Write;
                to_stdout(|out| out.flush());
                eline(format_args!("error: {e}"));
            }
            std::process::ExitCode::from(t.exit_code())
        }
    }
}

/// An assembly that is not valid: the error that ends a planning command, with the
/// problems that make it so (in the JSON error object's `"problems"`).
#[derive(Debug)]
pub struct Invalid {
    /// The error line.
    pub message: String,
    /// Its errors.
    pub problems: Vec<apart::mesh::Problem>,
}

impl std::fmt::Display for Invalid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Invalid {}

/// The JSON error object of a failure: `{"valid": false, "error": ..., "status": ...}`,
/// with the problems of an invalid assembly.
fn failure_json(e: &anyhow::Error, msg: &str) -> serde_json::Value {
    let mut v = serde_json::json!({ "valid": false, "error": msg, "status": failure_status(e) });
    if let Some(i) = e.downcast_ref::<Invalid>() {
        v["problems"] = serde_json::to_value(&i.problems).unwrap_or_default();
    }
    v
}

/// The `"status"` of a failure's JSON error object: "out of memory" when the memory
/// budget refused the work, "error" otherwise (the exit code tells the rest).
fn failure_status(e: &anyhow::Error) -> &'static str {
    if e.downcast_ref::<crate::limits::OverBudget>().is_some() {
        "out of memory"
    } else {
        "error"
    }
}

/// Reports a failure that stopped a command: one clear line on standard error (and a
/// JSON object on standard output with `--json`, an "end" line with `sequence --jsonl`).
pub fn fail(global: &Global, e: &anyhow::Error) {
    // The chain of causes, skipping a cause whose text its parent already shows.
    let mut msg = e.to_string();
    for cause in e.chain().skip(1) {
        let c = cause.to_string();
        if !msg.contains(&c) {
            msg = format!("{msg}: {c}");
        }
    }
    use std::io::Write;
    if global.json {
        let _ = json(&failure_json(e, &msg));
    } else if crate::limits::json_lines() {
        let mut end = failure_json(e, &msg);
        end["event"] = "end".into();
        to_stdout(|out| writeln!(out, "{end}").and_then(|()| out.flush()));
    }
    let _ = writeln!(std::io::stderr().lock(), "error: {msg}");
}

/// What a run reads, resolved (symbolic links and `..`): the files and folders that no
/// output may overwrite, replace or be written into.
#[derive(Default)]
pub struct Inputs {
    /// Files read: the manifest, every mesh and piece file, glTF buffers.
    files: Vec<PathBuf>,
    /// Folders read: the assembly's folder, piece folders.
    folders: Vec<PathBuf>,
}

impl Inputs {
    /// The inputs of the assembly loaded from `given`: `given` itself (and its manifest
    /// when it is a folder), and every part's mesh and piece files (with the external
    /// buffers of glTF files).
    pub fn of(given: &Path, loaded: &apart::assembly::Loaded) -> Inputs {
        let mut inputs = Inputs::default();
        inputs.add(given);
        // A folder's manifest is read, but named by no part.
        inputs.add(&given.join("assembly.json"));
        for part in &loaded.assembly.parts {
            inputs.add(&part.source);
            for p in &part.piece_sources {
                inputs.add(p);
            }
        }
        inputs
    }

    /// Adds the file or folder `path` (nothing when it does not exist).
    pub fn add(&mut self, path: &Path) {
        let Ok(c) = std::fs::canonicalize(path) else {
            return;
        };
        if c.is_dir() {
            self.folders.push(c);
        } else {
            for b in gltf_buffers(&c) {
                self.add(&b);
            }
            self.files.push(c);
        }
    }

    /// Refuses the output file `out` (`what` names its flag: "--svg") when it is an
    /// input file, or an input folder or a folder holding an input.
    pub fn check_file(&self, what: &str, out: &Path) -> anyhow::Result<()> {
        self.check(what, out, false)
    }

    /// Refuses the output folder `out` as [`Inputs::check_file`] does, and also when it
    /// lies inside an input folder.
    pub fn check_folder(&self, what: &str, out: &Path) -> anyhow::Result<()> {
        self.check(what, out, true)
    }

    fn check(&self, what: &str, out: &Path, folder: bool) -> anyhow::Result<()> {
        let r = resolved(out)?;
        let refuse = |how: &str, input: &Path| {
            anyhow::anyhow!(
                "refusing to write {what} {}: {how} {}; choose another path",
                out.display(),
                input.display()
            )
        };
        if let Some(f) = self.files.iter().find(|f| **f == r) {
            return Err(refuse("it is the input file", f));
        }
        if let Some(f) = self.folders.iter().find(|f| **f == r) {
            return Err(refuse("it is the input folder", f));
        }
        if let Some(f) = self
            .folders
            .iter()
            .chain(&self.files)
            .find(|f| f.starts_with(&r))
        {
            return Err(refuse("it holds the input", f));
        }
        if folder {
            if let Some(f) = self.folders.iter().find(|f| r.starts_with(f)) {
                return Err(refuse("it is inside the input folder", f));
            }
        }
        Ok(())
    }
}

/// The external buffer files a glTF file (`.gltf`) names, next to it (none for a
/// `.glb`, whose buffer is inside, or for `data:` URIs); read leniently: the loader has
/// read the file already and reports its defects.
fn gltf_buffers(file: &Path) -> Vec<PathBuf> {
    let is_gltf = file
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gltf"));
    let Some(text) = is_gltf.then(|| std::fs::read(file).ok()).flatten() else {
        return Vec::new();
    };
    let Ok(doc) = serde_json::from_slice::<serde_json::Value>(&text) else {
        return Vec::new();
    };
    let folder = file.parent().unwrap_or(Path::new("."));
    doc["buffers"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|b| b["uri"].as_str())
        .filter(|u| !u.starts_with("data:"))
        .map(|u| {
            u.strip_prefix("file://")
                .or(u.strip_prefix("file:"))
                .unwrap_or(u)
        })
        .map(|u| folder.join(percent_decoded(u)))
        .collect()
}

/// `%20` and the like decoded (bytes that do not decode are kept as written).
fn percent_decoded(uri: &str) -> String {
    let b = uri.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut k = 0;
    while k < b.len() {
        let hex = b
            .get(k + 1..k + 3)
            .and_then(|h| u8::from_str_radix(std::str::from_utf8(h).ok()?, 16).ok());
        match (b[k], hex) {
            (b'%', Some(v)) => {
                out.push(v);
                k += 3;
            }
            (c, _) => {
                out.push(c);
                k += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}
