//! Every output all or nothing, never over an input, every write error an error:
//! `decompose` and `batch` killed at every write (through the hidden test hook
//! `APART_TEST_STOP_AFTER_WRITES`) or at a random moment leave a whole output or none, a
//! results file with a cut last line is resumed without loss or repetition, a full disk
//! (`/dev/full` for standard output, the hook `APART_TEST_FAIL_WRITES` for files) is exit
//! code 1 with the previous file intact, and an output naming an input is refused.

use apart_testkit::Scratch;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn apart() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_apart"));
    c.env_remove("APART_TEST_STOP_AFTER_WRITES")
        .env_remove("APART_TEST_FAIL_WRITES")
        .stdin(Stdio::null());
    c
}

fn run(args: &[&str]) -> Output {
    apart().args(args).output().unwrap()
}

/// A run with one of the test hooks set to `n`.
fn run_hooked(hook: &str, n: usize, args: &[&str]) -> Output {
    apart()
        .args(args)
        .env(hook, n.to_string())
        .output()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn example(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name)
}

fn s(p: &Path) -> String {
    p.display().to_string()
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let target = to.join(e.file_name());
        if e.file_type().unwrap().is_dir() {
            copy_dir(&e.path(), &target);
        } else {
            std::fs::copy(e.path(), target).unwrap();
        }
    }
}

/// Every file under `dir` (hidden ones included) by relative path, with its bytes.
fn tree(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let rel = p.strip_prefix(dir).unwrap().display().to_string();
                out.insert(rel, std::fs::read(&p).unwrap());
            }
        }
    }
    out
}

/// The hidden temporary names left in `dir` (`.NAME.tmp-PID`, `.NAME.old-PID`).
fn leftovers(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".tmp-") || n.contains(".old-"))
        .collect()
}

/// Whether the run was ended by the stop hook (exit code 9, no cleanup).
fn aborted(o: &Output) -> bool {
    o.status.code() == Some(9)
}

/// A results line without its timings, which differ from run to run.
fn untimed(v: &Value) -> Value {
    match v {
        Value::Object(m) => Value::Object(
            m.iter()
                .filter(|(k, _)| !k.contains("seconds"))
                .map(|(k, v)| (k.clone(), untimed(v)))
                .collect(),
        ),
        Value::Array(a) => Value::Array(a.iter().map(untimed).collect()),
        _ => v.clone(),
    }
}

/// The lines of a results file, each parsed and without timings, sorted by assembly;
/// every line must be a whole JSON line.
fn results(path: &Path) -> Vec<Value> {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.is_empty() || text.ends_with('\n'), "{text:?}");
    let mut lines: Vec<Value> = text
        .lines()
        .map(|l| untimed(&serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}"))))
        .collect();
    lines.sort_by_key(|l| l["assembly"].as_str().unwrap().to_string());
    lines
}

/// Three small assemblies to run `batch --command check` over.
fn batch_set(dir: &Path) -> PathBuf {
    let set = dir.join("set");
    for name in ["hinge", "split-star", "linked-rings"] {
        copy_dir(&example(name), &set.join(name));
    }
    set
}

#[test]
fn decompose_killed_at_every_write_leaves_the_whole_output_or_none() {
    let dir = Scratch::new("outputs-decompose-kill");
    let input = s(&example("hinge"));
    let full = dir.join("full");
    let o = run(&["decompose", &input, "-o", &s(&full), "-q"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let whole = tree(&full);
    // The marker, every file, and putting the folder in place are the writes.
    let writes = whole.len() + 1;
    for n in 1..=writes {
        let out = dir.join(format!("out{n}"));
        let o = run_hooked(
            "APART_TEST_STOP_AFTER_WRITES",
            n,
            &["decompose", &input, "-o", &s(&out), "-q"],
        );
        assert!(aborted(&o), "write {n}: {:?} {}", o.status, stderr(&o));
        if n < writes {
            // Stopped before the folder was put in place: it does not exist, and
            // `apart check` loads nothing from it.
            assert!(!out.exists(), "write {n} of {writes}: a partial folder");
            let c = run(&["check", &s(&out)]);
            assert_eq!(c.status.code(), Some(1), "write {n}");
        } else {
            assert_eq!(tree(&out), whole, "write {n}");
            let c = run(&["check", &s(&out), "-q"]);
            assert_eq!(c.status.code(), Some(0), "{}", stderr(&c));
        }
    }
    // The run after a kill is as if nothing had happened.
    let again = dir.join("out1");
    let o = run(&["decompose", &input, "-o", &s(&again), "-q"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(tree(&again), whole);
    // No hook count passes the last write: the run then ends normally.
    let o = run_hooked(
        "APART_TEST_STOP_AFTER_WRITES",
        writes + 1,
        &["decompose", &input, "-o", &s(&dir.join("last")), "-q"],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

/// A pseudo-random number below `n` (a different sequence in every test run).
fn random_below(state: &mut u64, n: u64) -> u64 {
    *state = state
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*state >> 33) % n.max(1)
}

/// A seed from the clock, printed so that a failure can be looked into.
fn seed() -> u64 {
    let seed = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_nanos() as u64;
    eprintln!("seed {seed}");
    seed
}

/// Runs `args` and kills it (SIGKILL) after `ms` milliseconds, unless it ended before.
fn killed_after(args: &[&str], ms: u64) {
    let mut child = apart()
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(ms));
    let _ = child.kill();
    let _ = child.wait();
}

#[test]
fn decompose_killed_at_random_moments_leaves_the_whole_output_or_none() {
    let dir = Scratch::new("outputs-decompose-sigkill");
    let input = s(&example("tray-of-cubes"));
    let full = dir.join("full");
    let t = std::time::Instant::now();
    let o = run(&["decompose", &input, "-o", &s(&full), "-q"]);
    let took = t.elapsed().as_millis() as u64;
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let whole = tree(&full);
    let mut state = seed();
    for k in 0..8 {
        let out = dir.join(format!("out{k}"));
        // Somewhere in the run, mostly while it writes (after loading).
        let ms = random_below(&mut state, took + 20);
        killed_after(&["decompose", &input, "-o", &s(&out), "-q"], ms);
        if out.exists() {
            assert_eq!(tree(&out), whole, "killed after {ms} ms");
        } else {
            assert_eq!(run(&["check", &s(&out)]).status.code(), Some(1));
        }
    }
}

#[test]
fn decompose_replaces_only_its_own_output_and_refuses_other_folders() {
    let dir = Scratch::new("outputs-decompose-existing");
    let input = s(&example("hinge"));
    // A folder holding the user's files is refused, and left as it was.
    let theirs = dir.join("theirs");
    std::fs::create_dir_all(&theirs).unwrap();
    std::fs::write(theirs.join("notes.txt"), "keep me").unwrap();
    let o = run(&["decompose", &input, "-o", &s(&theirs)]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains(&format!("refusing to write to {}", s(&theirs))),
        "{}",
        stderr(&o)
    );
    assert_eq!(tree(&theirs).len(), 1);
    // An empty folder is filled, and decompose's own output replaced whole (nothing
    // of the earlier output stays).
    let mine = dir.join("mine");
    std::fs::create_dir_all(&mine).unwrap();
    let o = run(&["decompose", &input, "-o", &s(&mine), "-q"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let first = tree(&mine);
    std::fs::write(mine.join("stale.off"), "OFF\n0 0 0\n").unwrap();
    let o = run(&["decompose", &input, "-o", &s(&mine), "-q"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(tree(&mine), first);
    assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));
}

#[test]
fn batch_killed_after_every_line_loses_and_repeats_nothing() {
    let dir = Scratch::new("outputs-batch-kill");
    let set = batch_set(&dir);
    let reference = dir.join("reference.jsonl");
    let args = |out: &Path| {
        vec![
            "batch".to_string(),
            s(&set),
            "--command".into(),
            "check".into(),
            "--jobs".into(),
            "1".into(),
            "--out".into(),
            s(out),
            "-q".into(),
        ]
    };
    let argv = args(&reference);
    let argv: Vec<&str> = argv.iter().map(String::as_str).collect();
    let o = run(&argv);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let expected = results(&reference);
    assert_eq!(expected.len(), 3);
    for n in 1..=3 {
        let out = dir.join(format!("out{n}.jsonl"));
        let argv = args(&out);
        let argv: Vec<&str> = argv.iter().map(String::as_str).collect();
        let o = run_hooked("APART_TEST_STOP_AFTER_WRITES", n, &argv);
        assert!(aborted(&o), "line {n}: {:?} {}", o.status, stderr(&o));
        assert_eq!(results(&out).len(), n);
        let o = run(&argv);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        assert_eq!(results(&out), expected, "killed after line {n}");
    }
}

#[test]
fn batch_killed_at_random_moments_loses_and_repeats_nothing() {
    let dir = Scratch::new("outputs-batch-sigkill");
    let set = batch_set(&dir);
    for name in [
        "split-star-3",
        "dovetail-and-cap",
        "peg-in-the-hole",
        "tray-of-cubes",
    ] {
        copy_dir(&example(name), &set.join(name));
    }
    let argv = |out: &Path| {
        [
            "batch",
            &s(&set),
            "--command",
            "check",
            "--jobs",
            "1",
            "--out",
            &s(out),
            "-q",
        ]
        .map(str::to_string)
    };
    let reference = dir.join("reference.jsonl");
    let t = std::time::Instant::now();
    let o = run(&argv(&reference).each_ref().map(String::as_str));
    let took = t.elapsed().as_millis() as u64;
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let expected = results(&reference);
    assert_eq!(expected.len(), 7);
    let mut state = seed();
    for k in 0..8 {
        let out = dir.join(format!("out{k}.jsonl"));
        let args = argv(&out);
        let args = args.each_ref().map(String::as_str);
        // Killed once or twice, then run to its end.
        for _ in 0..=k % 2 {
            killed_after(&args, random_below(&mut state, took + 20));
        }
        let o = run(&args);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        assert_eq!(results(&out), expected, "run {k}");
    }
}

#[test]
fn batch_resume_drops_a_cut_last_line_with_a_warning() {
    let dir = Scratch::new("outputs-batch-torn");
    let set = batch_set(&dir);
    let out = dir.join("results.jsonl");
    let argv = [
        "batch",
        &s(&set),
        "--command",
        "check",
        "--jobs",
        "1",
        "--out",
        &s(&out),
        "-q",
    ];
    let o = run(&argv);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let expected = results(&out);
    let text = std::fs::read_to_string(&out).unwrap();
    let last_start = text[..text.len() - 1].rfind('\n').unwrap() + 1;
    // Cut in the middle of the last line, and cut just before its newline (a whole
    // JSON object, but not known to be whole).
    for cut in [last_start + 20, text.len() - 1] {
        std::fs::write(&out, &text[..cut]).unwrap();
        let o = run(&argv);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let warning = format!("warning: {} line 3 is cut", s(&out));
        assert!(stderr(&o).contains(&warning), "{}", stderr(&o));
        assert_eq!(results(&out), expected);
    }
    // A results file that is whole is resumed without a word.
    let o = run(&argv);
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
    assert_eq!(results(&out), expected);
}

/// `args` run with standard output on a full disk.
fn to_full_disk(args: &[&str]) -> Output {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    apart()
        .args(args)
        .stdout(Stdio::from(full))
        .stderr(Stdio::piped())
        .output()
        .unwrap()
}

#[test]
fn a_full_standard_output_is_exit_code_1_in_every_command() {
    if !Path::new("/dev/full").exists() {
        eprintln!("skipped: no /dev/full");
        return;
    }
    let dir = Scratch::new("outputs-stdout-full");
    let (hinge, star) = (s(&example("hinge")), s(&example("split-star")));
    let cube = s(&example("sheet-metal/cube.off"));
    let set = s(&batch_set(&dir));
    let results = s(&dir.join("results.jsonl"));
    let pieces = s(&dir.join("pieces"));
    let runs: Vec<Vec<&str>> = vec![
        vec!["check", &hinge],
        vec!["check", &hinge, "--json"],
        vec!["partition", &star],
        vec!["partition", &star, "--json"],
        vec!["sequence", &hinge],
        vec!["sequence", &hinge, "--jsonl"],
        vec!["sequence", &hinge, "--json"],
        vec!["separate", &hinge, "bolt", "bracket"],
        vec!["place", &cube, &cube],
        vec!["stack", &cube, "--count", "2"],
        vec!["decompose", &hinge, "-o", &pieces],
        vec!["batch", &set, "--command", "check", "--out", &results],
    ];
    for args in runs {
        let o = to_full_disk(&args);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("error: cannot write to standard output: No space left on device"),
            "{args:?}: {}",
            stderr(&o)
        );
    }
}

#[test]
fn a_closed_pipe_ends_quietly_with_the_answers_exit_code() {
    for (args, code) in [
        (vec!["partition", &s(&example("split-star"))], 0),
        (vec!["partition", &s(&example("linked-rings"))], 2),
    ] {
        let mut child = apart()
            .args(&args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // The reader goes away before anything is written.
        drop(child.stdout.take());
        let o = child.wait_with_output().unwrap();
        assert_eq!(o.status.code(), Some(code), "{args:?}: {}", stderr(&o));
        assert!(!stderr(&o).contains("error"), "{}", stderr(&o));
    }
}

#[test]
fn a_file_on_a_full_disk_is_exit_code_1_and_the_previous_file_stays() {
    let dir = Scratch::new("outputs-file-full");
    let hinge = s(&example("hinge"));
    let svg = dir.join("step1.svg");
    let glb = dir.join("hinge.glb");
    std::fs::write(&svg, "the previous picture").unwrap();
    for (flag, path) in [("--svg", &svg), ("--glb", &glb)] {
        let o = run_hooked(
            "APART_TEST_FAIL_WRITES",
            1,
            &["sequence", &hinge, flag, &s(path), "-q"],
        );
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        let message = format!("error: cannot write {}: No space left on device", s(path));
        assert!(stderr(&o).contains(&message), "{}", stderr(&o));
    }
    assert_eq!(
        std::fs::read_to_string(&svg).unwrap(),
        "the previous picture"
    );
    assert!(!glb.exists());
    assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));

    // decompose: a write in the middle fails; no folder, and no temporary one, remains.
    let out = dir.join("pieces");
    let o = run_hooked(
        "APART_TEST_FAIL_WRITES",
        3,
        &["decompose", &hinge, "-o", &s(&out), "-q"],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("No space left on device"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
    assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));

    // batch: the second line fails; the run ends with exit code 1 and the file holds
    // the first line, whole.
    let set = batch_set(&dir);
    let results_file = dir.join("results.jsonl");
    let o = run_hooked(
        "APART_TEST_FAIL_WRITES",
        2,
        &[
            "batch",
            &s(&set),
            "--command",
            "check",
            "--jobs",
            "1",
            "--out",
            &s(&results_file),
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let message = format!(
        "error: cannot write {}: No space left on device",
        s(&results_file)
    );
    assert!(stderr(&o).contains(&message), "{}", stderr(&o));
    assert!(!String::from_utf8_lossy(&o.stdout).contains("| ok |"));
    assert_eq!(results(&results_file).len(), 1);
}

#[test]
fn an_output_naming_an_input_is_refused_and_the_input_stays() {
    let dir = Scratch::new("outputs-inputs");
    let set = dir.join("set");
    let hinge = set.join("hinge");
    copy_dir(&example("hinge"), &hinge);
    let cube = dir.join("cube.off");
    std::fs::copy(example("sheet-metal/cube.off"), &cube).unwrap();
    let (h, mesh, manifest) = (
        s(&hinge),
        s(&hinge.join("bolt.off")),
        s(&hinge.join("assembly.json")),
    );
    let dotted = format!("{h}/../hinge/bracket.off");
    #[allow(unused_mut)]
    let mut targets = vec![mesh.clone(), manifest.clone(), dotted, h.clone()];
    #[cfg(unix)]
    {
        // A symbolic link to an input mesh, made outside the assembly folder.
        let l = dir.join("link.off");
        std::os::unix::fs::symlink(hinge.join("tongue.off"), &l).unwrap();
        targets.push(s(&l));
    }
    let before = tree(&dir);
    for target in &targets {
        for flag in ["--svg", "--glb", "--html", "--png"] {
            let o = run(&["sequence", &h, flag, target]);
            assert_eq!(o.status.code(), Some(1), "{flag} {target}: {}", stderr(&o));
            let e = stderr(&o);
            assert!(
                e.contains(&format!("refusing to write {flag} {target}")),
                "{e}"
            );
        }
    }
    // The message names both paths.
    let o = run(&["partition", &h, "--svg", &mesh]);
    assert_eq!(o.status.code(), Some(1));
    let bolt = std::fs::canonicalize(hinge.join("bolt.off")).unwrap();
    assert!(
        stderr(&o).contains(&format!(
            "error: refusing to write --svg {mesh}: it is the input file {}",
            s(&bolt)
        )),
        "{}",
        stderr(&o)
    );
    for args in [
        vec![
            "partition".to_string(),
            manifest.clone(),
            "--png".into(),
            manifest.clone(),
        ],
        vec!["sequence".into(), h.clone(), "--renders".into(), h.clone()],
        vec![
            "sequence".into(),
            h.clone(),
            "--renders".into(),
            format!("{h}/steps"),
        ],
        vec![
            "stack".into(),
            s(&cube),
            "--count".into(),
            "1".into(),
            "--png".into(),
            s(&cube),
        ],
        vec!["place".into(), s(&cube), s(&cube), "--svg".into(), s(&cube)],
        vec!["decompose".into(), h.clone(), "-o".into(), h.clone()],
        vec!["decompose".into(), h.clone(), "-o".into(), s(&set)],
        vec!["batch".into(), s(&set), "--out".into(), mesh.clone()],
        vec!["batch".into(), s(&set), "--out".into(), h.clone()],
        vec!["batch".into(), s(&set), "--out".into(), s(&set)],
        vec![
            "batch".into(),
            s(&set),
            "--out".into(),
            format!("{h}/new.stl"),
        ],
    ] {
        let argv: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = run(&argv);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("refusing to write"),
            "{args:?}: {}",
            stderr(&o)
        );
    }
    assert_eq!(tree(&dir), before, "an input changed");
    // A new file inside the assembly folder is fine.
    let o = run(&["partition", &h, "--svg", &format!("{h}/motion.svg"), "-q"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}
