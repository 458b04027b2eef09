//! Output shared by the commands: numbers in input units, tables, problems, JSON, the
//! progress bars, the status of a partial answer, and the one-line failure message.

use crate::limits::Stopped;
use crate::Global;
use apart::assembly::{LoadSeconds, Progress, ProgressFn};
use apart::kernel::Aabb;
use apart::kernel::Grid;
use apart::mesh::Problem;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

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

/// Writes `bytes` to `path`, creating its folder if needed (`--svg out/star.svg`), with
/// the path in the error, and announces it on standard error ("wrote hinge.html") unless
/// `--quiet`. Every file a command writes for the user goes through here (or through
/// [`wrote`]), so that none appears unannounced; standard output, which may carry the
/// JSON answer, stays untouched.
pub fn write_file(path: &std::path::Path, bytes: impl AsRef<[u8]>) -> anyhow::Result<()> {
    if let Some(folder) = path.parent().filter(|f| !f.as_os_str().is_empty()) {
        std::fs::create_dir_all(folder)
            .map_err(|e| anyhow::anyhow!("cannot create {}: {e}", folder.display()))?;
    }
    std::fs::write(path, bytes)
        .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))?;
    wrote(path);
    Ok(())
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

/// The loader's hook: records each loading stage as the run's phase (for the messages
/// of `--timeout` and `--max-memory`) and, on a terminal, drives a progress bar.
pub fn progress(global: &Global) -> (Option<ProgressBar>, ProgressFn) {
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
    let hook: ProgressFn = Arc::new(move |p: Progress| {
        if p.done == 0 {
            crate::limits::set_phase(match p.stage.label() {
                "reading" => "loading (reading files)",
                "validating" => "loading (validating parts)",
                "decomposing" => "loading (convex decomposition)",
                "overlaps" => "loading (overlaps between parts)",
                _ => "loading",
            });
        }
        if let Some(b) = &b {
            b.set_message(p.stage.label());
            b.set_length(p.total as u64);
            b.set_position(p.done as u64);
        }
    });
    (bar, hook)
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
    .with_budget(crate::limits::affordable);
    (Phase(bar), progress)
}

/// Where a partial answer stopped, in the JSON (`"stopped"`).
#[derive(serde::Serialize)]
pub struct StoppedJson {
    /// What stopped it: "--timeout", "--max-memory" (the memory budget, given or by
    /// default) or "Ctrl-C".
    pub by: &'static str,
    /// The `--timeout` given; otherwise the seconds from the start of the run.
    pub after_seconds: f64,
    pub phase: &'static str,
    /// For the memory budget: the estimate refused, or the heap in use.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detail: Option<String>,
}

/// The status of an answer in the JSON: "done", or for a partial answer "timeout",
/// "out of memory" or "interrupted".
pub fn status(stop: &Option<Stopped>) -> &'static str {
    stop.as_ref().map_or("done", Stopped::status)
}

/// The `"stopped"` object of a partial answer.
pub fn stopped_json(stop: &Option<Stopped>) -> Option<StoppedJson> {
    stop.as_ref().map(|t| StoppedJson {
        by: t.by_key(),
        after_seconds: t.seconds,
        phase: t.phase,
        detail: t.detail.clone(),
    })
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
        let _ = json(&serde_json::json!({ "valid": false, "error": msg }));
    } else if crate::limits::json_lines() {
        let end = serde_json::json!({ "event": "end", "valid": false, "error": msg });
        to_stdout(|out| writeln!(out, "{end}").and_then(|()| out.flush()));
    }
    let _ = writeln!(std::io::stderr().lock(), "error: {msg}");
}
