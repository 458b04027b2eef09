//! `apart batch`: one command over every assembly under a folder, in parallel across
//! assemblies, one JSON line per assembly, resumable.
//!
//! Each assembly runs in a child process of this same binary (`apart partition DIR
//! --json --threads 1 --timeout S --max-memory M`), so that its time and memory are
//! bounded on their own and a crash or an exhausted budget ends that assembly only.

use crate::{limits, output, Global};
use clap::{Args, ValueEnum};
use serde_json::{json, Value};
use std::collections::{BTreeMap, HashSet};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

/// The command run on each assembly.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum BatchCommand {
    /// `apart partition` (every solution, counted; 20 moving sets listed).
    Partition,
    /// `apart sequence` (a complete disassembly plan).
    Sequence,
    /// `apart check` (validation only).
    Check,
}

impl BatchCommand {
    fn name(self) -> &'static str {
        match self {
            BatchCommand::Partition => "partition",
            BatchCommand::Sequence => "sequence",
            BatchCommand::Check => "check",
        }
    }
}

/// Arguments of `apart batch`.
#[derive(Args, Debug)]
pub struct BatchArgs {
    /// Folder holding the assemblies: every folder below it with an assembly.json or
    /// with mesh files of its own is one assembly (its sub-folders are its parts'
    /// pieces, not assemblies).
    pub dir: PathBuf,
    /// What to run on each assembly.
    #[arg(long, value_enum, default_value_t = BatchCommand::Partition)]
    pub command: BatchCommand,
    /// The JSON lines file, one line per assembly; assemblies already in it are skipped
    /// (a run can be resumed), new lines are appended, each whole and synced. A last
    /// line cut by an interrupted write is dropped with a warning, and its assembly
    /// runs again. It may not be an input of an assembly.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Assemblies run at the same time (default: one per core).
    #[arg(long, value_name = "N", value_parser = limits::threads, allow_negative_numbers = true)]
    pub jobs: Option<usize>,
    /// Time bound of one assembly, in seconds: past it the assembly's answer is its
    /// partial answer (status "timeout").
    #[arg(long, value_name = "SECONDS", default_value_t = 300.0, value_parser = limits::timeout, allow_negative_numbers = true)]
    pub each_timeout: f64,
    /// Memory bound of one assembly (4G, 500M, bytes): past it the assembly ends with
    /// status "out of memory".
    #[arg(long, value_name = "SIZE", default_value = "4G", value_parser = limits::memory_size)]
    pub each_memory: u64,
}

/// The assemblies under `dir`, sorted: folders with an `assembly.json` or with mesh
/// files of their own (not descending into them).
pub fn assemblies_under(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let mut subdirs = Vec::new();
        let mut is_assembly = false;
        for e in std::fs::read_dir(&d)? {
            let e = e?;
            let p = e.path();
            let hidden = e.file_name().to_string_lossy().starts_with('.');
            let t = e.file_type()?;
            if hidden {
                continue;
            }
            if t.is_dir() {
                subdirs.push(p);
            } else if t.is_file()
                && (e.file_name() == "assembly.json"
                    || apart::formats::Format::from_path(&p).is_some())
            {
                is_assembly = true;
            }
        }
        if is_assembly {
            out.push(d);
        } else {
            stack.extend(subdirs);
        }
    }
    out.sort();
    Ok(out)
}

/// The key of an assembly in the output: its path relative to the batch folder.
fn key(dir: &Path, asm: &Path) -> String {
    asm.strip_prefix(dir)
        .ok()
        .filter(|r| !r.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
        .to_string_lossy()
        .into_owned()
}

/// The "assembly" key of a results line, when it is one.
fn line_key(line: &[u8]) -> Option<String> {
    let v: Value = serde_json::from_slice(line).ok()?;
    v["assembly"].as_str().map(str::to_string)
}

/// The assemblies a previous run already answered (their "assembly" keys). A last
/// line cut by an interrupted write (no newline at its end, or not a results line) is
/// dropped with a warning: the file is cut back to its last whole line, and that
/// assembly runs again. Another line that is not a results line is ignored with a
/// warning.
fn done_before(out: &Path) -> anyhow::Result<HashSet<String>> {
    let text = match std::fs::read(out) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(HashSet::new()),
        Err(e) => anyhow::bail!("cannot read {}: {}", out.display(), output::io_text(&e)),
    };
    let mut done = HashSet::new();
    let mut start = 0;
    let mut number = 0;
    while start < text.len() {
        number += 1;
        let end = text[start..].iter().position(|&b| b == b'\n');
        let line = &text[start..end.map_or(text.len(), |e| start + e)];
        let key = line_key(line);
        let last = end.is_none_or(|e| start + e + 1 == text.len());
        if last && (end.is_none() || key.is_none()) {
            output::eline(format_args!(
                "warning: {} line {number} is cut (an interrupted write?): dropped, and its assembly runs again: {}",
                out.display(),
                excerpt(line)
            ));
            cut_to(out, start as u64)?;
            break;
        }
        match key {
            Some(k) => {
                done.insert(k);
            }
            None if line.iter().all(u8::is_ascii_whitespace) => {}
            None => output::eline(format_args!(
                "warning: {} line {number} is not a results line: ignored: {}",
                out.display(),
                excerpt(line)
            )),
        }
        start = end.map_or(text.len(), |e| start + e + 1);
    }
    Ok(done)
}

/// The start of a line, for a warning.
fn excerpt(line: &[u8]) -> String {
    let text = String::from_utf8_lossy(line);
    match text.char_indices().nth(60) {
        Some((k, _)) => format!("{}...", &text[..k]),
        None => text.into_owned(),
    }
}

/// Cuts the file `out` to its first `len` bytes, synced.
fn cut_to(out: &Path, len: u64) -> anyhow::Result<()> {
    let cut = std::fs::OpenOptions::new()
        .write(true)
        .open(out)
        .and_then(|f| f.set_len(len).and_then(|()| f.sync_all()));
    cut.map_err(|e| anyhow::anyhow!("cannot write {}: {}", out.display(), output::io_text(&e)))
}

/// Refuses an `--out` that would overwrite or join an input: an assembly's folder, a
/// file in it that is read (a mesh file, a manifest, a piece file), or a file anywhere
/// under `dir` that a later run would read as one (named like a mesh or a manifest).
fn check_out(dir: &Path, assemblies: &[PathBuf], out: &Path) -> anyhow::Result<()> {
    let mut inputs = output::Inputs::default();
    inputs.add(dir);
    let mut stack = assemblies.to_vec();
    while let Some(d) = stack.pop() {
        inputs.add(&d);
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if is_read(&p) {
                inputs.add(&p);
            }
        }
    }
    // The batch folder itself may hold the output file, so it is checked as a file.
    inputs.check_file("--out", out)?;
    let (r, root) = (output::resolved(out)?, output::resolved(dir)?);
    if r.starts_with(&root) && is_read(&r) {
        anyhow::bail!(
            "refusing to write --out {}: a file so named under {} is read as part of an assembly; choose another path",
            out.display(),
            dir.display()
        );
    }
    Ok(())
}

/// Whether a file so named is read as part of an assembly.
fn is_read(p: &Path) -> bool {
    p.file_name().is_some_and(|n| n == "assembly.json")
        || apart::formats::Format::from_path(p).is_some()
}

/// The child's arguments beside the command and the folder: the loading options of
/// this run, and the bounds of one assembly.
fn child_args(args: &BatchArgs, global: &Global) -> Vec<String> {
    let mut a = vec![
        "--json".to_string(),
        "--quiet".into(),
        "--threads".into(),
        "1".into(),
        "--timeout".into(),
        args.each_timeout.to_string(),
        "--max-memory".into(),
        args.each_memory.to_string(),
        "--grid-bits".into(),
        global.grid_bits.to_string(),
    ];
    for (on, flag) in [
        (global.verify, "--verify"),
        (global.strict, "--strict"),
        (global.one_part_per_file, "--one-part-per-file"),
        (global.allow_outside, "--allow-outside"),
    ] {
        if on {
            a.push(flag.into());
        }
    }
    if let Some(t) = &global.tolerance {
        a.extend(["--tolerance".into(), t.clone()]);
    }
    if let Some(u) = global.units {
        let u = u.to_possible_value().expect("a unit has a name");
        a.extend(["--units".into(), u.get_name().to_string()]);
    }
    a
}

/// One assembly's line: its key, status, exit code, wall time, the answer's own
/// timings and counts, and its error message when it has no answer.
fn run_one(exe: &Path, command: BatchCommand, asm: &Path, key: String, extra: &[String]) -> Value {
    let t = Instant::now();
    let out = Command::new(exe)
        .arg(command.name())
        .arg(asm)
        .args(extra)
        .stdin(Stdio::null())
        // Its warnings and error line are not read: its JSON says what happened.
        .stderr(Stdio::null())
        .output();
    let seconds = t.elapsed().as_secs_f64();
    let out = match out {
        Ok(o) => o,
        Err(e) => {
            return json!({"assembly": key, "status": "failed", "error": e.to_string(), "seconds": seconds})
        }
    };
    let answer = answer_of(&out.stdout);
    let code = out.status.code();
    // The status its answer or its JSON error object states: "out of memory" or
    // "timeout" tell a run that ended with exit code 1 from invalid input.
    let reported = answer
        .as_ref()
        .and_then(|a| a.get("status"))
        .and_then(Value::as_str);
    // The exit codes of the README's table (`check` exits 1 on invalid input too).
    let status = match code {
        Some(0) => "ok",
        Some(2) => "interlocked",
        Some(3) => "timeout",
        Some(130) => "interrupted",
        Some(1) if reported == Some("out of memory") => "out of memory",
        Some(1) if reported == Some("timeout") => "timeout",
        Some(1) => "invalid input",
        _ => "failed",
    };
    let error_line = match &answer {
        Some(a) => error_of(a),
        None => Some(format!("no answer ({})", out.status)),
    };
    let mut line = json!({
        "assembly": key,
        "command": command.name(),
        "status": status,
        "exit_code": code,
        "seconds": seconds,
    });
    if let Some(a) = &answer {
        for k in [
            "parts",
            "solution_count",
            "moving_set_count",
            "interlocked",
            "complete",
            "steps",
            "valid",
            "tolerance",
            "repairs",
            "stats",
        ] {
            if let Some(v) = a.get(k) {
                line[k] = match k {
                    // A plan's steps in brief: who moves along what.
                    "steps" => Value::from(v.as_array().map_or(0, Vec::len)),
                    _ => v.clone(),
                };
            }
        }
        if status != "ok" && status != "interlocked" {
            if let Some(e) = error_line {
                line["error"] = e.into();
            }
        }
    } else if let Some(e) = error_line {
        line["error"] = e.into();
    }
    line
}

/// A child's JSON on standard output: its answer, or its JSON error object (the last
/// line, after a partial answer cut short).
fn answer_of(stdout: &[u8]) -> Option<Value> {
    serde_json::from_slice(stdout).ok().or_else(|| {
        let text = String::from_utf8_lossy(stdout);
        let last = text.lines().rev().find(|l| !l.trim().is_empty())?;
        serde_json::from_str(last).ok()
    })
}

/// What went wrong, from a child's JSON: its error object's `"error"`, or where its
/// partial answer stopped.
fn error_of(answer: &Value) -> Option<String> {
    // An invalid assembly: its first error, which names the file, part and element.
    if let Some(p) = answer
        .get("problems")
        .and_then(Value::as_array)
        .and_then(|ps| ps.iter().find(|p| p["severity"] == "error"))
    {
        let text = |k: &str| p.get(k).and_then(Value::as_str);
        let mut at: Vec<String> = Vec::new();
        match (text("file"), text("part")) {
            (Some(f), Some(n)) => at.push(format!("{f} (part \"{n}\")")),
            (Some(f), None) => at.push(f.to_string()),
            (None, Some(n)) => at.push(format!("part \"{n}\"")),
            (None, None) => {}
        }
        at.extend(text("element").map(str::to_string));
        let message = text("message").unwrap_or("?");
        return Some(if at.is_empty() {
            format!("error: {message}")
        } else {
            format!("error: {}: {message}", at.join(", "))
        });
    }
    if let Some(e) = answer.get("error").and_then(Value::as_str) {
        return Some(e.to_string());
    }
    let stopped = answer.get("stopped")?;
    let by = stopped.get("by").and_then(Value::as_str).unwrap_or("?");
    let phase = stopped.get("phase").and_then(Value::as_str).unwrap_or("?");
    let after = stopped
        .get("after_seconds")
        .and_then(Value::as_f64)
        .unwrap_or(0.0);
    let mut e = format!("stopped by {by} after {after} s during {phase}: partial answer");
    if let Some(d) = stopped.get("detail").and_then(Value::as_str) {
        e.push_str(&format!(" ({d})"));
    }
    Some(e)
}

/// Runs `apart batch`.
pub fn run(args: &BatchArgs, global: &Global) -> anyhow::Result<ExitCode> {
    if !args.dir.is_dir() {
        anyhow::bail!("{} is not a folder", args.dir.display());
    }
    let all = assemblies_under(&args.dir)
        .map_err(|e| anyhow::anyhow!("cannot list {}: {e}", args.dir.display()))?;
    check_out(&args.dir, &all, &args.out)?;
    let before = done_before(&args.out)?;
    let todo: Vec<(PathBuf, String)> = all
        .iter()
        .map(|a| (a.clone(), key(&args.dir, a)))
        .filter(|(_, k)| !before.contains(k))
        .collect();
    let skipped = all.len() - todo.len();
    let exe = std::env::current_exe()?;
    let extra = child_args(args, global);
    let mut file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&args.out)
        .map_err(|e| {
            anyhow::anyhow!(
                "cannot write {}: {}",
                args.out.display(),
                output::io_text(&e)
            )
        })?;
    let jobs = args
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .min(todo.len().max(1));
    let bar = output::counter(global, "assemblies", todo.len() as u64);
    let next = AtomicUsize::new(0);
    // The file, the lines written, and the first write error (which stops the run).
    let sink = Mutex::new((&mut file, Vec::<Value>::new(), None::<anyhow::Error>));
    let t = Instant::now();
    std::thread::scope(|s| {
        for _ in 0..jobs {
            s.spawn(|| loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                let Some((asm, key)) = todo.get(k) else { break };
                if sink.lock().expect("no panic holds the lock").2.is_some() {
                    break;
                }
                let line = run_one(&exe, args.command, asm, key.clone(), &extra);
                let mut g = sink.lock().expect("no panic holds the lock");
                if g.2.is_some() {
                    break;
                }
                // One whole line per write, synced, so that an interrupted run leaves
                // whole lines (a cut one is dropped when the run is resumed).
                match output::append_line(g.0, &args.out, &line.to_string()) {
                    Ok(()) => g.1.push(line),
                    Err(e) => g.2 = Some(e),
                }
                bar.inc(1);
            });
        }
    });
    bar.finish_and_clear();
    let (_, lines, failed) = sink.into_inner().expect("no panic holds the lock");
    if let Some(e) = failed {
        return Err(e);
    }
    let mut counts: BTreeMap<String, usize> = BTreeMap::new();
    for l in &lines {
        *counts
            .entry(l["status"].as_str().unwrap_or("failed").to_string())
            .or_default() += 1;
    }
    let total = t.elapsed().as_secs_f64();
    if global.json {
        output::json(&json!({
            "folder": args.dir,
            "command": args.command.name(),
            "out": args.out,
            "assemblies": all.len(),
            "run": lines.len(),
            "skipped_as_done": skipped,
            "statuses": counts,
            "seconds": total,
        }))?;
    } else {
        output::line(format!(
            "{} assemblies under {}: {} run, {} already in {} (skipped)",
            all.len(),
            args.dir.display(),
            lines.len(),
            skipped,
            args.out.display()
        ));
        output::line("| status | assemblies |".to_string());
        output::line("|---|---:|".to_string());
        for (s, n) in &counts {
            output::line(format!("| {s} | {n} |"));
        }
        output::line(format!("time: {total:.1} s with {jobs} at a time"));
    }
    let failed = lines.iter().any(|l| l["status"] == "failed");
    Ok(if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    })
}
