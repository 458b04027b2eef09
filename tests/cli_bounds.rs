//! Hostile and careless command lines, end to end on the built binary: every
//! numeric option checked with its range before any work, usage errors exiting with 1
//! (2 is the "no" answer), one-part assemblies meaning "nothing to separate" in every
//! command, partition listings bounded and grouped by moving set, decompose never losing
//! a part to a file-name collision nor writing into its input, --timeout returning the
//! partial answer with its status (exit code 3), and --timeout while loading and
//! --max-memory ending a run with a clear message.

use apart_testkit::Scratch;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn example(name: &str) -> String {
    root().join("examples").join(name).display().to_string()
}

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_apart"))
        .args(args)
        .output()
        .unwrap()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn json(out: &Output) -> Value {
    serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("not JSON ({e}): {}\n{}", stdout(out), stderr(out)))
}

/// A fresh folder for one test.
fn scratch(name: &str) -> Scratch {
    Scratch::new(&format!("bounds-{}", name))
}

/// The unit cube at `origin` as an OFF file.
fn cube_off(origin: [i64; 3]) -> String {
    let mut s = String::from("OFF\n8 6 0\n");
    for i in 0..8 {
        s.push_str(&format!(
            "{} {} {}\n",
            origin[0] + (i & 1),
            origin[1] + (i >> 1 & 1),
            origin[2] + (i >> 2 & 1)
        ));
    }
    for f in apart_testkit::solids::CUBOID_QUADS {
        s.push_str(&format!("4 {} {} {} {}\n", f[0], f[1], f[2], f[3]));
    }
    s
}

/// `n` unit cubes, 2 apart on a grid, one file each in `dir`: no cube touches another,
/// so every cube moves alone and the partition has a moving set per cube.
fn loose_cubes(dir: &Path, n: i64) {
    let side = (1..).find(|s| s * s * s >= n).unwrap();
    for k in 0..n {
        let o = [
            3 * (k % side),
            3 * (k / side % side),
            3 * (k / (side * side)),
        ];
        std::fs::write(dir.join(format!("c{k:04}.off")), cube_off(o)).unwrap();
    }
}

#[test]
fn numeric_options_are_checked_with_their_range_before_any_work() {
    // The path does not exist: a message about the value, not the path, shows that the
    // option was checked first.
    let cases: &[(&[&str], &str)] = &[
        (
            &["--threads", "1000000", "check", "nowhere"],
            "from 1 to 1024",
        ),
        (&["--threads", "0", "check", "nowhere"], "from 1 to 1024"),
        (&["check", "nowhere", "--threads", "-3"], "from 1 to 1024"),
        (
            &["check", "nowhere", "--tolerance", "-1"],
            "finite, positive length",
        ),
        (
            &["check", "nowhere", "--tolerance", "nan"],
            "finite, positive length",
        ),
        (
            &["check", "nowhere", "--tolerance", "0"],
            "finite, positive length",
        ),
        (&["check", "nowhere", "--tolerance", "5um"], "--units"),
        (&["check", "nowhere", "--timeout", "0"], "more than 0"),
        (&["check", "nowhere", "--timeout", "-5"], "more than 0"),
        (&["check", "nowhere", "--timeout", "nan"], "finite"),
        (&["check", "nowhere", "--timeout", "1e9"], "at most 604800"),
        (&["check", "nowhere", "--max-memory", "4X"], "such as 4G"),
        (&["check", "nowhere", "--max-memory", "100K"], "at least 1M"),
        (&["check", "nowhere", "--max-memory", "nothing"], "or none"),
        (
            &["stack", "nowhere.off", "--count", "1000000000"],
            "from 1 to 1000",
        ),
        (&["stack", "nowhere.off", "--count", "0"], "from 1 to 1000"),
        (
            &["stack", "nowhere.off", "--dtheta", "-90"],
            "between 0.1 and 360",
        ),
        (
            &["stack", "nowhere.off", "--dtheta", "1e-9"],
            "between 0.1 and 360",
        ),
        (
            &["stack", "nowhere.off", "--dtheta", "1e-7"],
            "between 0.1 and 360",
        ),
        (
            &["stack", "nowhere.off", "--dtheta", "nan"],
            "must be a finite number",
        ),
        (
            &["stack", "nowhere.off", "--weight", "2"],
            "between 0 and 1",
        ),
        (&["stack", "nowhere.off", "--weight", "nan"], "finite"),
        (
            &["stack", "nowhere.off", "--max-height", "-1"],
            "more than 0",
        ),
        (&["stack", "nowhere.off", "--clearance", "-1"], "0 or more"),
        (
            &["stack", "nowhere.off", "--max-candidates", "0"],
            "from 1 to 100000",
        ),
        (&["stack", "nowhere.off", "--floor", "1,1,0,0"], "is empty"),
        (
            &["stack", "nowhere.off", "--floor", "0,0,1"],
            "4 comma-separated",
        ),
        (&["stack", "nowhere.off", "--floor-z", "inf"], "finite"),
        (
            &["stack", "nowhere.off", "--base", "45,0"],
            "multiples of 90",
        ),
        (
            &["place", "a.off", "b.off", "--dtheta", "0"],
            "between 0.1 and 360",
        ),
        (
            &["place", "a.off", "b.off", "--candidates", "0"],
            "from 1 to 1000",
        ),
        (
            &["place", "a.off", "b.off", "--weight", "-0.5"],
            "between 0 and 1",
        ),
        (&["place", "a.off", "b.off", "--clearance", "nan"], "finite"),
        (
            &["place", "a.off", "b.off", "--target", "1,2"],
            "3 comma-separated",
        ),
        (
            &["place", "a.off", "b.off", "--region", "1,1,1,0,0,0"],
            "is empty",
        ),
        (&["sequence", "nowhere", "--max-depth", "0"], "at least 1"),
        (&["sequence", "nowhere", "--max-depth", "-1"], "at least 1"),
        (&["sequence", "nowhere", "--step", "0"], "at least 1"),
        (&["partition", "nowhere", "--limit", "0"], "at least 1"),
        (&["partition", "nowhere", "--direction", "0,0,0"], "is zero"),
        (
            &["partition", "nowhere", "--direction", "1,nan,0"],
            "non-finite",
        ),
    ];
    // --grid-bits: the range the kernel's grid supports.
    use apart::kernel::grid::{MAX_BITS, MIN_BITS};
    let above = (MAX_BITS + 1).to_string();
    let below = (MIN_BITS - 1).to_string();
    let bits = format!("from {MIN_BITS} to {MAX_BITS}");
    let over = ["check", "nowhere", "--grid-bits", &above];
    let under = ["check", "nowhere", "--grid-bits", &below];
    let mut cases = cases.to_vec();
    cases.push((&over, &bits));
    cases.push((&under, &bits));
    for (args, want) in &cases {
        let out = run(args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: wanted \"{want}\" in: {err}");
        assert!(!err.contains("nowhere"), "{args:?} did work first: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(!err.contains("grip"), "{args:?}: {err}");
    }
    // Negative values are values (not "unexpected argument '-9'").
    let err = stderr(&run(&["stack", "nowhere.off", "--dtheta", "-90"]));
    assert!(
        err.contains("'-90'") && !err.contains("unexpected argument"),
        "{err}"
    );
    // The ranges are in the help.
    let help = stdout(&run(&["stack", "--help"]));
    assert!(
        help.contains("1 to 1000") && help.contains("0.1 to 360"),
        "{help}"
    );
    // Values inside the ranges work.
    let cube = example("sheet-metal/cube.off");
    let out = run(&[
        "stack",
        &cube,
        "--count",
        "2",
        "--dtheta",
        "360",
        "--threads",
        "2",
        "--quiet",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
}

#[test]
fn usage_errors_exit_1_and_the_help_lists_the_exit_codes() {
    for args in [
        &[][..],
        &["frobnicate"][..],
        &["partition"][..],
        &["partition", "--no-such-flag", "x"][..],
        &["separate", "only-one"][..],
    ] {
        let out = run(args);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {}", stderr(&out));
        assert!(!stderr(&out).is_empty(), "{args:?}");
    }
    // With --json, a usage error is also a JSON object.
    let out = run(&["partition", "--json"]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(json(&out)["valid"], false);
    let out = run(&["--help"]);
    assert_eq!(out.status.code(), Some(0));
    let help = stdout(&out);
    assert!(help.contains("Exit codes:"), "{help}");
    assert!(help.contains("2  the answer is no"), "{help}");
    assert!(
        help.contains("--timeout") && help.contains("--max-memory"),
        "{help}"
    );
    assert_eq!(run(&["--version"]).status.code(), Some(0));
    assert_eq!(run(&["partition", "--help"]).status.code(), Some(0));
}

#[test]
fn a_one_part_assembly_has_nothing_to_separate_in_every_command() {
    let dir = scratch("one");
    std::fs::write(dir.join("only.off"), cube_off([0, 0, 0])).unwrap();
    let path = dir.display().to_string();
    for extra in [&[][..], &["--first"][..], &["--direction", "0,0,1"][..]] {
        let mut args = vec!["partition", path.as_str(), "--json"];
        args.extend_from_slice(extra);
        let out = run(&args);
        assert_eq!(out.status.code(), Some(0), "{extra:?}: {}", stderr(&out));
        let v = json(&out);
        assert_eq!(v["nothing_to_separate"], true, "{extra:?}");
        assert_eq!(v["interlocked"], false, "{extra:?}");
        assert_eq!(v["solutions"].as_array().unwrap().len(), 0);
    }
    let out = run(&["partition", &path]);
    assert_eq!(out.status.code(), Some(0));
    assert!(
        stdout(&out).contains("nothing to separate"),
        "{}",
        stdout(&out)
    );

    let out = run(&["sequence", &path, "--json"]);
    assert_eq!(out.status.code(), Some(0));
    let v = json(&out);
    assert_eq!(v["nothing_to_separate"], true);
    assert_eq!(v["complete"], true);
    assert_eq!(v["steps"].as_array().unwrap().len(), 0);
    let out = run(&["sequence", &path]);
    assert!(
        stdout(&out).contains("nothing to separate"),
        "{}",
        stdout(&out)
    );

    // separate names two parts: one part is an input error, said clearly.
    let out = run(&["separate", &path, "only", "only"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("needs two parts"), "{}", stderr(&out));

    // Two parts are not "nothing to separate".
    std::fs::write(dir.join("other.off"), cube_off([3, 0, 0])).unwrap();
    let v = json(&run(&["partition", &path, "--json"]));
    assert_eq!(v["nothing_to_separate"], false);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn partition_listings_are_grouped_by_moving_set_and_bounded() {
    let dir = scratch("loose");
    loose_cubes(&dir, 24);
    let path = dir.display().to_string();

    // Everything: every cube moves alone, in many cells.
    let out = run(&["partition", &path, "--json", "--all"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let all = json(&out);
    let total = all["solution_count"].as_u64().unwrap() as usize;
    assert_eq!(all["solutions"].as_array().unwrap().len(), total);
    assert_eq!(all["moving_set_count"], 24);
    assert_eq!(all["truncated"], false);
    assert!(all["limit"].is_null());
    let groups = all["groups"].as_array().unwrap();
    assert_eq!(groups.len(), 24);
    let sum: u64 = groups
        .iter()
        .map(|g| g["solutions"].as_u64().unwrap())
        .sum();
    assert_eq!(sum as usize, total);
    for g in groups {
        assert_eq!(g["moving"].as_array().unwrap().len(), 1);
        let n = ["faces", "edges", "vertices"]
            .iter()
            .map(|k| g[*k].as_u64().unwrap())
            .sum::<u64>();
        assert_eq!(n, g["solutions"].as_u64().unwrap());
    }
    assert!(total > 24 * 15, "{total}");

    // The default: 20 moving sets, at most 5 solutions of each kind each, a warning.
    let out = run(&["partition", &path, "--json"]);
    assert_eq!(out.status.code(), Some(0));
    let v = json(&out);
    assert_eq!(v["solution_count"].as_u64().unwrap() as usize, total);
    assert_eq!(v["moving_set_count"], 24);
    assert_eq!(v["limit"], 20);
    assert_eq!(v["truncated"], true);
    let groups = v["groups"].as_array().unwrap();
    assert_eq!(groups.len(), 20);
    // The same groups, in the same order, as the full listing.
    for (g, h) in groups.iter().zip(all["groups"].as_array().unwrap()) {
        assert_eq!(g["moving"], h["moving"]);
        assert_eq!(g["solutions"], h["solutions"]);
    }
    let sols = v["solutions"].as_array().unwrap();
    let listed: u64 = groups.iter().map(|g| g["listed"].as_u64().unwrap()).sum();
    assert_eq!(listed as usize, sols.len());
    assert!(sols.len() <= 20 * 15);
    for g in groups {
        for kind in ["face", "edge", "vertex"] {
            let n = sols
                .iter()
                .filter(|s| s["moving"] == g["moving"] && s["cell"] == kind)
                .count();
            assert!(n <= 5, "{kind}: {n}");
        }
    }
    // Every listed solution is one of the full listing.
    let key = |s: &Value| format!("{}{}{}", s["cell"], s["moving"], s["exact_direction"]);
    let every: std::collections::HashSet<String> = all["solutions"]
        .as_array()
        .unwrap()
        .iter()
        .map(key)
        .collect();
    assert!(sols.iter().all(|s| every.contains(&key(s))));
    assert!(stderr(&out).contains("warning:"), "{}", stderr(&out));
    assert!(stderr(&out).contains("--all"), "{}", stderr(&out));

    // --limit 3, in text: three moving sets, the rest counted.
    let out = run(&["partition", &path, "--limit", "3"]);
    assert_eq!(out.status.code(), Some(0));
    let text = stdout(&out);
    assert_eq!(text.matches(" moves (").count(), 3, "{text}");
    assert!(text.contains("... and 21 more moving sets"), "{text}");
    assert!(
        text.contains(&format!("{total} solutions in 24 moving sets")),
        "{text}"
    );
    assert!(stderr(&out).contains("warning:"));
    // --limit and --all contradict each other.
    assert_eq!(
        run(&["partition", &path, "--limit", "3", "--all"])
            .status
            .code(),
        Some(1)
    );

    // A small answer is listed whole, without a warning (the Split Star's eight).
    let out = run(&["partition", &example("split-star"), "--json"]);
    let v = json(&out);
    assert_eq!(v["truncated"], false);
    assert_eq!(v["solutions"].as_array().unwrap().len(), 8);
    assert_eq!(v["groups"].as_array().unwrap().len(), 8);
    assert!(!stderr(&out).contains("warning"), "{}", stderr(&out));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn decompose_keeps_parts_whose_file_names_collide_and_never_writes_into_its_input() {
    let dir = scratch("decompose");
    let input = dir.join("input");
    std::fs::create_dir_all(&input).unwrap();
    std::fs::write(input.join("one.off"), cube_off([0, 0, 0])).unwrap();
    std::fs::write(input.join("two.off"), cube_off([3, 0, 0])).unwrap();
    std::fs::write(input.join("three.off"), cube_off([6, 0, 0])).unwrap();
    let manifest = input.join("assembly.json");
    // "a b" and "a_b" become the same safe name; "A_B" differs only in case.
    let text = r#"{"name": "collide", "parts": [
        {"name": "a b", "mesh": "one.off"},
        {"name": "a_b", "mesh": "two.off"},
        {"name": "A_B", "mesh": "three.off"}]}"#;
    std::fs::write(&manifest, text).unwrap();
    let out_dir = dir.join("out");
    let out = run(&[
        "decompose",
        manifest.to_str().unwrap(),
        "-o",
        out_dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(stderr(&out).contains("collide"), "{}", stderr(&out));
    // Every part is read back, each from its own files.
    let out = run(&["check", out_dir.to_str().unwrap(), "--json"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v = json(&out);
    let parts = v["parts"].as_array().unwrap();
    let names: Vec<&str> = parts.iter().map(|p| p["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["a b", "a_b", "A_B"]);
    let mut files: Vec<String> = parts
        .iter()
        .map(|p| p["source"].as_str().unwrap().to_lowercase())
        .collect();
    files.sort();
    files.dedup();
    assert_eq!(files.len(), 3, "{files:?}");
    // Each part is where its input was (none overwrote another).
    let xs: Vec<f64> = parts
        .iter()
        .map(|p| p["bbox"]["min"][0].as_f64().unwrap())
        .collect();
    assert_eq!(xs, [0.0, 3.0, 6.0]);

    // Writing into the input is refused, and the input stays as it was.
    let before: Vec<Vec<u8>> = ["one.off", "two.off", "three.off", "assembly.json"]
        .iter()
        .map(|f| std::fs::read(input.join(f)).unwrap())
        .collect();
    let m = manifest.to_str().unwrap().to_string();
    let i = input.to_str().unwrap().to_string();
    let dotted = format!("{}/../input/.", i);
    let inside = format!("{i}/pieces");
    for (from, to) in [
        (&m, &i),
        (&m, &dotted),
        (&i, &i),
        (&i, &inside),
        (&input.join("one.off").to_str().unwrap().to_string(), &i),
    ] {
        let out = run(&["decompose", from, "-o", to]);
        assert_eq!(out.status.code(), Some(1), "{from} -o {to}");
        assert!(
            stderr(&out).contains("refusing to write"),
            "{}",
            stderr(&out)
        );
    }
    #[cfg(unix)]
    {
        // Also through a symbolic link to the input folder.
        let link = dir.join("link");
        std::os::unix::fs::symlink(&input, &link).unwrap();
        let out = run(&["decompose", &m, "-o", link.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(1));
        assert!(
            stderr(&out).contains("refusing to write"),
            "{}",
            stderr(&out)
        );
    }
    assert!(!input.join("pieces").exists());
    let after: Vec<Vec<u8>> = ["one.off", "two.off", "three.off", "assembly.json"]
        .iter()
        .map(|f| std::fs::read(input.join(f)).unwrap())
        .collect();
    assert_eq!(before, after);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Runs `args` with `--timeout T` for growing T until the run is stopped after loading
/// (exit code 3) and `accept`s its output: a loaded machine may still be loading at a
/// short timeout, which ends the run at once (exit code 1, "stopped after T s:
/// loading"), or a planner may stop before it found anything. Returns the run accepted.
fn stopped_after_loading(
    args: &[&str],
    timeouts: &[&str],
    accept: impl Fn(&Output) -> bool,
) -> (Output, String) {
    for t in timeouts {
        let mut a = args.to_vec();
        a.extend(["--timeout", t]);
        let out = run(&a);
        let err = stderr(&out);
        match out.status.code() {
            Some(1) => {
                assert!(err.contains(&format!("stopped after {t} s: ")), "{err}");
                assert!(err.contains("loading") || err.contains("starting"), "{err}");
            }
            Some(3) if accept(&out) => return (out, t.to_string()),
            Some(3) => {}
            code => panic!("{args:?} --timeout {t}: exit code {code:?}: {err}"),
        }
    }
    panic!("{args:?}: no partial answer with --timeout {timeouts:?}");
}

#[test]
fn timeout_returns_the_partial_plan_with_its_status() {
    let dir = scratch("timeout-sequence");
    // The full ranking (an overlay of every pair left, per step) keeps 216 cubes busy
    // for tens of seconds, whatever the machine: the timeouts below stop it mid-plan.
    lattice(&dir, 6);
    let path = dir.display().to_string();
    let names: Vec<String> = {
        let mut n: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| {
                e.unwrap()
                    .path()
                    .file_stem()
                    .unwrap()
                    .to_str()
                    .unwrap()
                    .to_string()
            })
            .collect();
        n.sort();
        n
    };
    let has_steps = |out: &Output| json(out)["steps"].as_array().is_some_and(|s| !s.is_empty());
    let start = std::time::Instant::now();
    let (out, t) = stopped_after_loading(
        &[
            "sequence",
            &path,
            "--json",
            "--ranking",
            "full",
            "--threads",
            "1",
            "--glb",
            dir.join("x.glb").to_str().unwrap(),
        ],
        &["1", "2", "4"],
        has_steps,
    );
    assert!(start.elapsed().as_secs_f64() < 60.0);
    let v = json(&out);
    assert_eq!(v["status"], "timeout");
    assert_eq!(v["complete"], false);
    assert_eq!(v["interlocked"], false);
    assert_eq!(v["stopped"]["by"], "--timeout");
    assert_eq!(
        v["stopped"]["after_seconds"].as_f64(),
        t.parse::<f64>().ok()
    );
    assert!(v["stopped"]["phase"]
        .as_str()
        .is_some_and(|p| !p.is_empty()));
    let err = stderr(&out);
    assert!(
        err.contains(&format!(
            "warning: stopped by --timeout after {t} s during "
        )),
        "{err}"
    );
    assert!(err.contains("no picture or export written"), "{err}");
    assert!(!dir.join("x.glb").exists(), "no export of a partial plan");
    // The steps are well-formed: each splits a subassembly still open into a moving
    // side and the rest, along a nonzero direction; what is left open, singletons aside,
    // is exactly what the answer says is not yet split.
    let set = |x: &Value| -> Vec<String> {
        let mut v: Vec<String> = x
            .as_array()
            .unwrap()
            .iter()
            .map(|n| n.as_str().unwrap().to_string())
            .collect();
        v.sort();
        v
    };
    let steps = v["steps"].as_array().unwrap();
    assert!(!steps.is_empty() && steps.len() < 999, "{}", steps.len());
    let mut open: Vec<Vec<String>> = vec![names.clone()];
    for s in steps {
        let sub = set(&s["subassembly"]);
        let moving = set(&s["moving"]);
        let k = open
            .iter()
            .position(|o| *o == sub)
            .unwrap_or_else(|| panic!("splits no open subassembly: {s}"));
        open.remove(k);
        assert!(!moving.is_empty() && moving.len() < sub.len(), "{s}");
        assert!(moving.iter().all(|m| sub.contains(m)), "{s}");
        let d: Vec<f64> = s["direction"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert!(
            (d.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-9,
            "{s}"
        );
        // A corner cube of what is left leaves along a diagonal of clearance > 0.
        assert_eq!(s["cell"], "face", "{s}");
        open.push(
            sub.iter()
                .filter(|p| !moving.contains(p))
                .cloned()
                .collect(),
        );
        open.push(moving);
    }
    let mut left: Vec<Vec<String>> = open.into_iter().filter(|o| o.len() > 1).collect();
    let mut pending: Vec<Vec<String>> = v["not_yet_split"]
        .as_array()
        .unwrap()
        .iter()
        .map(set)
        .collect();
    left.sort();
    pending.sort();
    assert!(!pending.is_empty());
    assert_eq!(left, pending);
    assert!(v["stuck"].as_array().unwrap().is_empty());

    // In text: the status line, the steps, and what is not yet split.
    let (out, t) = stopped_after_loading(
        &["sequence", &path, "--ranking", "full", "--threads", "1"],
        &["1", "2", "4"],
        |out| stdout(out).contains("1. split"),
    );
    let text = stdout(&out);
    assert!(
        text.contains(&format!("stopped by --timeout after {t} s during ")),
        "{text}"
    );
    assert!(text.contains("partial answer"), "{text}");
    assert!(
        text.contains("not yet split (stopped by --timeout): {"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn timeout_returns_the_partial_partition_and_stack() {
    // partition: the solutions found before the stop (none while the pair regions or the
    // motion space were built), each a listed solution of the whole run.
    let dir = scratch("timeout-partition");
    loose_cubes(&dir, 150);
    let path = dir.display().to_string();
    let (out, _) = stopped_after_loading(
        &["partition", &path, "--json", "--all"],
        &["0.3", "0.6", "1.2", "2.4"],
        |_| true,
    );
    let v = json(&out);
    assert_eq!(v["status"], "timeout");
    assert_eq!(v["complete"], false);
    assert_eq!(v["interlocked"], false, "unknown, not interlocked");
    let sols = v["solutions"].as_array().unwrap();
    assert_eq!(v["solution_count"].as_u64(), Some(sols.len() as u64));
    let whole = json(&run(&["partition", &path, "--json", "--all"]));
    assert_eq!(whole["status"], "done");
    assert_eq!(whole["complete"], true);
    assert!(whole.get("stopped").is_none());
    let key = |s: &Value| format!("{}{}{}", s["cell"], s["moving"], s["exact_direction"]);
    let every: std::collections::HashSet<String> = whole["solutions"]
        .as_array()
        .unwrap()
        .iter()
        .map(key)
        .collect();
    assert!(sols.len() < every.len());
    assert!(sols.iter().all(|s| every.contains(&key(s))));
    let _ = std::fs::remove_dir_all(&dir);

    // stack: the parts placed before the stop (300 cubes take far longer than 1 s).
    let cube = example("sheet-metal/cube.off");
    let (out, _) = stopped_after_loading(
        &["stack", &cube, "--count", "300", "--json"],
        &["1", "2"],
        |_| true,
    );
    let v = json(&out);
    assert_eq!(v["status"], "timeout");
    assert_eq!(v["complete"], false);
    let placed = v["placements"].as_array().unwrap();
    assert!(placed.len() < 300);
    for (k, p) in placed.iter().enumerate() {
        assert_eq!(p["index"].as_u64(), Some(k as u64));
    }
    let out = run(&["stack", &cube, "--count", "300", "--timeout", "1"]);
    assert_eq!(out.status.code(), Some(3), "{}", stderr(&out));
    assert!(
        stdout(&out).starts_with("stopped by --timeout after 1 s during stacking: partial answer"),
        "{}",
        stdout(&out)
    );
    assert!(!stdout(&out).contains("fits nowhere"), "{}", stdout(&out));
}

#[test]
fn timeout_while_loading_ends_the_run_at_once() {
    // No answer yet: the run ends at the deadline with exit code 1, as in every command
    // without a partial answer.
    let dir = scratch("timeout-loading");
    loose_cubes(&dir, 150);
    let start = std::time::Instant::now();
    let out = run(&["partition", dir.to_str().unwrap(), "--timeout", "0.001"]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("stopped after 0.001 s: "), "{err}");
    assert!(start.elapsed().as_secs_f64() < 30.0);
    // With --json the answer is a JSON error object.
    let out = run(&[
        "partition",
        dir.to_str().unwrap(),
        "--timeout",
        "0.001",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let v = json(&out);
    assert_eq!(v["valid"], false);
    assert!(v["error"]
        .as_str()
        .unwrap()
        .starts_with("stopped after 0.001 s"));
    // A run within its time is unchanged.
    let out = run(&[
        "partition",
        &example("split-star"),
        "--timeout",
        "600",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0));
    let v = json(&out);
    assert_eq!(v["solutions"].as_array().unwrap().len(), 8);
    assert_eq!(v["status"], "done");
    // The help lists exit code 3.
    let help = stdout(&run(&["--help"]));
    assert!(
        help.contains("3  stopped by --timeout with a partial answer"),
        "{help}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn max_memory_ends_a_run_over_its_budget_naming_its_phase() {
    let dir = scratch("memory");
    loose_cubes(&dir, 60);
    let out = run(&["partition", dir.to_str().unwrap(), "--max-memory", "2M"]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("out of memory budget (--max-memory 2M) during "),
        "{err}"
    );
    assert!(
        !err.contains("panicked") && !err.contains("memory allocation of"),
        "{err}"
    );
    let out = run(&[
        "partition",
        dir.to_str().unwrap(),
        "--max-memory",
        "2M",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let text = stdout(&out);
    let last = text.trim().lines().last().unwrap_or("");
    let v: Value = serde_json::from_str(last).unwrap_or_else(|e| panic!("{e}: {text}"));
    assert_eq!(v["valid"], false);
    // Within the budget the answer is the same as without one.
    let star = example("split-star");
    let free = json(&run(&["partition", &star, "--json"]));
    let out = run(&["partition", &star, "--json", "--max-memory", "1G"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(json(&out)["solutions"], free["solutions"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn max_memory_refuses_a_motion_space_estimated_over_budget_before_building_it() {
    // 150 loose cubes: the pair regions fit in 45M, the motion space is estimated at
    // about 50 MiB more: refused with the estimate, before the arrangement is built.
    let dir = scratch("estimate");
    loose_cubes(&dir, 150);
    let out = run(&["partition", dir.to_str().unwrap(), "--max-memory", "45M"]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("out of memory budget (--max-memory 45M): the motion space of 150 parts"),
        "{err}"
    );
    assert!(
        err.contains("needs at least") && err.contains("MiB are left"),
        "{err}"
    );
    // The full ranking of sequence asks the budget before it builds the motion space of
    // all 150 parts (its pair regions, kept for later steps, fit in 64M): refused, the
    // run returns its partial answer (no step yet), then the error with the estimate.
    let out = run(&[
        "sequence",
        dir.to_str().unwrap(),
        "--ranking",
        "full",
        "--max-memory",
        "64M",
        "--json",
    ]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains(
            "error: out of memory budget (--max-memory 64M) during motion space: the motion space needs at least"
        ) && err.contains("MiB are left"),
        "{err}"
    );
    let v = json(&out);
    assert_eq!(v["status"], "out of memory");
    assert_eq!(v["complete"], false);
    assert_eq!(v["stopped"]["by"], "--max-memory");
    assert_eq!(v["stopped"]["phase"], "motion space");
    assert_eq!(v["steps"].as_array().map(Vec::len), Some(0));
    assert_eq!(v["not_yet_split"][0].as_array().map(Vec::len), Some(150));
    let _ = std::fs::remove_dir_all(&dir);
}

/// An `n × n × n` lattice of touching unit cubes `c_X_Y_Z`, one file each in `dir`: a
/// block that comes apart a corner cube at a time, `n³ − 1` steps (10: about 8 s on one
/// thread of the 2-core machine).
fn lattice(dir: &Path, n: i64) {
    for x in 0..n {
        for y in 0..n {
            for z in 0..n {
                let name = format!("c_{x}_{y}_{z}.off");
                std::fs::write(dir.join(name), cube_off([x, y, z])).unwrap();
            }
        }
    }
}

/// The lines of a `sequence --jsonl` answer: the step events (checked to be numbered
/// 1, 2, ... in order) and the end event, if the run printed one.
fn json_lines(out: &Output) -> (Vec<Value>, Option<Value>) {
    let text = stdout(out);
    let mut steps = Vec::new();
    let mut end = None;
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        let v: Value = serde_json::from_str(line)
            .unwrap_or_else(|e| panic!("not a JSON line ({e}): {line}\n{}", stderr(out)));
        assert!(end.is_none(), "a line after the end event: {line}");
        match v["event"].as_str() {
            Some("step") => {
                assert_eq!(v["index"].as_u64(), Some(steps.len() as u64 + 1), "{line}");
                steps.push(v);
            }
            Some("end") => end = Some(v),
            _ => panic!("not an event: {line}"),
        }
    }
    (steps, end)
}

/// The names of a JSON list, sorted.
fn name_set(x: &Value) -> Vec<String> {
    let mut v: Vec<String> = x
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap().to_string())
        .collect();
    v.sort();
    v
}

/// Checks that `steps` split open subassemblies of `parts` in turn and that what is left
/// open (singletons aside) is exactly `pending`.
fn check_partial_plan(parts: &Value, steps: &[Value], pending: &Value) {
    let mut open: Vec<Vec<String>> = vec![name_set(parts)];
    for s in steps {
        let sub = name_set(&s["subassembly"]);
        let moving = name_set(&s["moving"]);
        let k = open
            .iter()
            .position(|o| *o == sub)
            .unwrap_or_else(|| panic!("splits no open subassembly: {s}"));
        open.remove(k);
        assert!(!moving.is_empty() && moving.len() < sub.len(), "{s}");
        assert!(moving.iter().all(|m| sub.contains(m)), "{s}");
        assert!(s["rule"].is_string(), "{s}");
        open.push(
            sub.iter()
                .filter(|p| !moving.contains(p))
                .cloned()
                .collect(),
        );
        open.push(moving);
    }
    let mut left: Vec<Vec<String>> = open.into_iter().filter(|o| o.len() > 1).collect();
    let mut pending: Vec<Vec<String>> = pending.as_array().unwrap().iter().map(name_set).collect();
    left.sort();
    pending.sort();
    assert_eq!(left, pending);
}

#[test]
fn a_sequence_over_its_memory_budget_keeps_the_steps_it_streamed() {
    // 216 touching cubes on one thread (so the heap counts do not depend on the machine):
    // the budget is bisected between one too small for any step and one the whole plan
    // fits in, until a run is stopped by the budget after some steps. Every run over its
    // budget ends with exit code 1 and the error naming the budget and the phase, after
    // the steps it found (each printed as a JSON line as it was found).
    let dir = scratch("memory-sequence");
    lattice(&dir, 6);
    let path = dir.display().to_string();
    let attempt = |bytes: u64| -> Output {
        run(&[
            "sequence",
            &path,
            "--jsonl",
            "--threads",
            "1",
            "--max-memory",
            &bytes.to_string(),
        ])
    };
    let (mut lo, mut hi) = (1u64 << 20, 1u64 << 30);
    let mut found = None;
    for _ in 0..24 {
        if hi - lo < 4096 {
            break;
        }
        let mid = (lo + hi) / 2;
        let out = attempt(mid);
        let err = stderr(&out);
        match out.status.code() {
            Some(0) => {
                let (steps, end) = json_lines(&out);
                let end = end.expect("an end line");
                assert_eq!(end["complete"], true, "{end}");
                assert_eq!(steps.len(), 215);
                hi = mid;
            }
            Some(1) => {
                assert!(
                    err.contains("error: out of memory budget (--max-memory ")
                        && err.contains(") during "),
                    "{err}"
                );
                assert!(!err.contains("panicked"), "{err}");
                let (steps, end) = json_lines(&out);
                if let Some(end) = &end {
                    // The soft limit's partial answer, or the hard limit's error object.
                    if end["valid"] == false {
                        assert!(end["error"]
                            .as_str()
                            .unwrap()
                            .contains("out of memory budget"));
                    } else {
                        assert_eq!(end["status"], "out of memory", "{end}");
                        assert_eq!(end["complete"], false, "{end}");
                        assert_eq!(end["stopped"]["by"], "--max-memory", "{end}");
                        assert_eq!(end["step_count"].as_u64(), Some(steps.len() as u64));
                        check_partial_plan(&end["parts"], &steps, &end["not_yet_split"]);
                        if !steps.is_empty() {
                            found = Some((mid, steps.len()));
                            break;
                        }
                    }
                }
                lo = mid;
            }
            code => panic!("--max-memory {mid}: exit code {code:?}: {err}"),
        }
    }
    let (bytes, steps) = found.expect("a budget that stops the plan after some steps");
    assert!(steps < 215, "{steps}");
    // The same budget with --json: the whole partial answer at the end, marked
    // incomplete, then the error.
    let out = run(&[
        "sequence",
        &path,
        "--json",
        "--threads",
        "1",
        "--max-memory",
        &bytes.to_string(),
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let v = json(&out);
    if v["valid"] != false {
        assert_eq!(v["status"], "out of memory");
        assert_eq!(v["complete"], false);
        check_partial_plan(
            &v["parts"],
            v["steps"].as_array().unwrap(),
            &v["not_yet_split"],
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_sequence_stopped_by_timeout_keeps_the_steps_it_streamed() {
    // 1000 touching cubes on one thread take seconds: --timeout stops the plan after
    // some steps, which were printed as they were found (JSON lines, then text). A
    // loaded machine may still be loading at a short timeout, a fast one may finish
    // the plan: longer timeouts are tried, and a complete plan is accepted as such.
    let dir = scratch("timeout-stream");
    lattice(&dir, 10);
    let path = dir.display().to_string();
    for t in ["1", "2", "4", "8"] {
        let out = run(&[
            "sequence",
            &path,
            "--jsonl",
            "--threads",
            "1",
            "--timeout",
            t,
        ]);
        let err = stderr(&out);
        match out.status.code() {
            // Still loading.
            Some(1) => assert!(err.contains(&format!("stopped after {t} s: ")), "{err}"),
            Some(0) => {
                let (steps, end) = json_lines(&out);
                assert_eq!(end.unwrap()["complete"], true);
                assert_eq!(steps.len(), 999);
                return;
            }
            Some(3) => {
                let (steps, end) = json_lines(&out);
                let end = end.expect("an end line");
                assert_eq!(end["status"], "timeout");
                assert_eq!(end["complete"], false);
                assert_eq!(end["stopped"]["by"], "--timeout");
                assert_eq!(end["step_count"].as_u64(), Some(steps.len() as u64));
                assert!(end.get("steps").is_none());
                check_partial_plan(&end["parts"], &steps, &end["not_yet_split"]);
                if steps.is_empty() {
                    continue;
                }
                // In text: the header first, each step numbered, the summary at the end.
                let out = run(&["sequence", &path, "--threads", "1", "--timeout", t]);
                if out.status.code() != Some(3) {
                    return;
                }
                let text = stdout(&out);
                assert!(
                    text.starts_with(&format!(
                        "disassembly of \"{}\" (1000 parts):\n",
                        dir.file_name().unwrap().to_str().unwrap()
                    )),
                    "{text}"
                );
                // (This second run may have stopped before its first step.)
                if text.contains("\n1. split {") {
                    assert!(text.contains("\n1. split {c_0_0_0, c_0_0_1, "), "{text}");
                    assert!(text.contains("… and 99"), "long lists abbreviated: {text}");
                }
                assert!(
                    text.contains("not yet split (stopped by --timeout): {"),
                    "{text}"
                );
                let summary = text
                    .lines()
                    .find(|l| l.contains(", stopped by --timeout after"))
                    .unwrap_or_else(|| panic!("no summary line: {text}"));
                let (count, status) = summary.split_once(", ").unwrap();
                let n: usize = count.split(' ').next().unwrap().parse().unwrap();
                assert_eq!(text.matches(" split {").count(), n, "{text}");
                assert_eq!(
                    status,
                    format!(
                        "stopped by --timeout after {t} s during sequence steps: partial answer"
                    )
                );
                return;
            }
            code => panic!("--timeout {t}: exit code {code:?}: {err}"),
        }
    }
    panic!("no partial answer with a step within 8 s");
}

#[cfg(unix)]
#[test]
fn ctrl_c_returns_the_partial_plan_and_exit_code_130() {
    // Ctrl-C (SIGINT) once the first step is printed: the plan stops with the steps
    // found, the end line says "interrupted", and the exit code is 130.
    use std::io::BufRead;
    let dir = scratch("interrupt");
    lattice(&dir, 10);
    let mut child = Command::new(env!("CARGO_BIN_EXE_apart"))
        .args([
            "sequence",
            dir.to_str().unwrap(),
            "--jsonl",
            "--threads",
            "1",
        ])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = std::io::BufReader::new(child.stdout.take().unwrap()).lines();
    let first = lines.next().unwrap().unwrap();
    assert!(first.starts_with("{\"event\":\"step\""), "{first}");
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let rest: Vec<String> = lines.map(Result::unwrap).collect();
    let status = child.wait().unwrap();
    let end: Value = serde_json::from_str(rest.last().unwrap()).unwrap();
    if status.code() == Some(0) {
        // Finished before the signal came.
        assert_eq!(end["complete"], true);
        return;
    }
    assert_eq!(status.code(), Some(130));
    assert_eq!(end["event"], "end");
    assert_eq!(end["status"], "interrupted");
    assert_eq!(end["complete"], false);
    assert_eq!(end["stopped"]["by"], "Ctrl-C");
    assert_eq!(end["step_count"].as_u64(), Some(rest.len() as u64));
    assert!(!end["not_yet_split"].as_array().unwrap().is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn files_outside_the_assembly_need_allow_outside() {
    // A manifest naming a mesh in a sibling folder: refused by default, naming the file
    // and the folder; read with --allow-outside; two files named on the command line
    // (place and separate build a temporary manifest) are always read.
    let dir = scratch("outside");
    let (asm, other) = (dir.join("asm"), dir.join("other"));
    std::fs::create_dir_all(&asm).unwrap();
    std::fs::create_dir_all(&other).unwrap();
    std::fs::write(asm.join("a.off"), cube_off([0, 0, 0])).unwrap();
    std::fs::write(other.join("b.off"), cube_off([1, 0, 0])).unwrap();
    std::fs::write(
        asm.join("assembly.json"),
        r#"{"parts": [{"name": "a", "mesh": "a.off"}, {"name": "b", "mesh": "../other/b.off"}]}"#,
    )
    .unwrap();
    let manifest = asm.join("assembly.json").display().to_string();
    let out = run(&["check", &manifest]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let text = stdout(&out) + &stderr(&out);
    assert!(text.contains("b.off") && text.contains("outside"), "{text}");
    let out = run(&["check", "--allow-outside", &manifest]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}{}",
        stdout(&out),
        stderr(&out)
    );
    let (a, b) = (
        asm.join("a.off").display().to_string(),
        other.join("b.off").display().to_string(),
    );
    let out = run(&["separate", &a, &b]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}{}",
        stdout(&out),
        stderr(&out)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Under an address-space limit (`ulimit -v`) and no `--max-memory`, the default budget
/// is taken from the limit: a motion space too big for it ends the run with apart's own
/// message and exit code 1, never with an allocation failure (an abort, signal 6).
#[cfg(target_os = "linux")]
#[test]
fn an_address_space_limit_sets_the_default_budget() {
    let dir = scratch("address-space");
    // 512 loose cubes: their motion space is estimated at 3.8 GiB.
    loose_cubes(&dir, 512);
    // 1.5 GiB of address space: a budget of 80 % of it less 512 MiB, about 800 MiB.
    let script = format!(
        "ulimit -v 1572864 && exec {} partition {}",
        env!("CARGO_BIN_EXE_apart"),
        dir.display()
    );
    let out = Command::new("sh").args(["-c", &script]).output().unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{:?}: {err}", out.status);
    assert!(
        err.contains("out of memory budget (") && err.contains("by default"),
        "{err}"
    );
}

/// A file whose name is not UTF-8 in an assembly folder: `check --json` writes whole
/// JSON naming it (escaped), rather than stopping in the middle of the answer.
#[cfg(unix)]
#[test]
fn a_file_name_that_is_not_utf8_is_written_escaped_in_json() {
    use std::os::unix::ffi::OsStrExt;
    let dir = scratch("not-utf8");
    let name = std::ffi::OsStr::from_bytes(b"b\xff.off");
    std::fs::write(dir.join("a.off"), cube_off([0, 0, 0])).unwrap();
    std::fs::write(dir.join(name), cube_off([1, 0, 0])).unwrap();
    let out = run(&["check", "--json", dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v = json(&out);
    assert_eq!(v["valid"], true);
    let sources: Vec<String> = v["parts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["source"].as_str().unwrap().to_string())
        .collect();
    assert_eq!(sources.len(), 2);
    assert!(
        sources
            .iter()
            .any(|s| s.contains(".off") && s.contains('b') && !s.contains("a.off")),
        "{sources:?}"
    );
}
