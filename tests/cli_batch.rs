//! `apart batch`: every assembly under a folder gets one JSON line with the status its
//! own run gives (checked against `apart partition` run alone), a second run skips what
//! the output already holds, and a line removed is run again.

use apart_testkit::Scratch;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn apart(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_apart"))
        .args(args)
        .output()
        .unwrap()
}

fn example(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name)
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

fn lines(path: &Path) -> Vec<Value> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

fn status_of(lines: &[Value], key: &str) -> String {
    let hits: Vec<&Value> = lines.iter().filter(|l| l["assembly"] == key).collect();
    assert_eq!(hits.len(), 1, "one line for {key}: {lines:?}");
    hits[0]["status"].as_str().unwrap().to_string()
}

#[test]
fn batch_answers_each_assembly_as_its_own_run_and_resumes() {
    let dir = Scratch::new("cli-batch");
    let set = dir.join("set");
    // Three shipped assemblies (one interlocked), one nested a level deeper (a folder
    // of folders is not an assembly), and an open mesh (invalid input).
    copy_dir(&example("split-star"), &set.join("split-star"));
    copy_dir(&example("linked-rings"), &set.join("linked-rings"));
    copy_dir(&example("hinge"), &set.join("more/hinge"));
    std::fs::create_dir_all(set.join("open")).unwrap();
    std::fs::write(
        set.join("open/lid.off"),
        "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n",
    )
    .unwrap();
    let out = dir.join("results.jsonl");
    let (set_s, out_s) = (set.display().to_string(), out.display().to_string());

    let o = apart(&["batch", &set_s, "--out", &out_s, "--jobs", "2", "-q"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let first = lines(&out);
    assert_eq!(first.len(), 4, "{first:?}");
    // Each status is what the assembly's own run says: its exit code, 0 / 2 / 1.
    for (key, expected) in [
        ("split-star", "ok"),
        ("linked-rings", "interlocked"),
        ("more/hinge", "ok"),
        ("open", "invalid input"),
    ] {
        assert_eq!(status_of(&first, key), expected, "{key}");
        let alone = apart(&["partition", &set.join(key).display().to_string(), "-q"]);
        let code = match expected {
            "ok" => 0,
            "interlocked" => 2,
            _ => 1,
        };
        assert_eq!(alone.status.code(), Some(code), "{key} run alone");
    }
    let star = first
        .iter()
        .find(|l| l["assembly"] == "split-star")
        .unwrap();
    assert_eq!(star["solution_count"], 8, "the Split Star's eight motions");
    assert!(first.iter().all(|l| l["seconds"].as_f64().is_some()));
    let open = first.iter().find(|l| l["assembly"] == "open").unwrap();
    assert!(
        open["error"].as_str().unwrap().contains("lid.off"),
        "the error names the file: {open}"
    );

    // Resumed: nothing left to run, nothing appended.
    let o = apart(&["batch", &set_s, "--out", &out_s, "--json"]);
    assert_eq!(o.status.code(), Some(0));
    let summary: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(summary["run"], 0, "{summary}");
    assert_eq!(summary["skipped_as_done"], 4, "{summary}");
    assert_eq!(lines(&out).len(), 4);

    // A line removed is run again, and only that one.
    let kept: Vec<String> = first
        .iter()
        .filter(|l| l["assembly"] != "linked-rings")
        .map(|l| l.to_string())
        .collect();
    std::fs::write(&out, kept.join("\n") + "\n").unwrap();
    let o = apart(&["batch", &set_s, "--out", &out_s, "--json"]);
    let summary: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(summary["run"], 1, "{summary}");
    assert_eq!(summary["statuses"]["interlocked"], 1, "{summary}");
    assert_eq!(status_of(&lines(&out), "linked-rings"), "interlocked");
}

#[test]
fn each_assembly_is_bounded_in_time() {
    // A bound far below what the ring and cone need: its line says "timeout", the batch
    // itself goes on and ends normally.
    let dir = Scratch::new("cli-batch-timeout");
    let set = dir.join("set");
    copy_dir(&example("ring-and-cone"), &set.join("ring-and-cone"));
    let out = dir.join("r.jsonl");
    let o = apart(&[
        "batch",
        &set.display().to_string(),
        "--out",
        &out.display().to_string(),
        "--each-timeout",
        "0.01",
        "-q",
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let l = lines(&out);
    assert_eq!(status_of(&l, "ring-and-cone"), "timeout", "{l:?}");
}
