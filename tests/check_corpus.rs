//! Runs `apart check` on every case of `tests/corpus/<case>/`, each with an
//! `expected.txt`: a line `exit N`, an optional line `input PATH` (default: the case
//! folder itself), an optional line `args FLAG ...` (e.g. `--strict`, so that a
//! validation rule is seen before repair), and `contains TEXT` lines that must all
//! appear in the output.
//! The cases were written by hand, one per validation rule, so the expectations are
//! independent of the program's output.

use std::path::Path;
use std::process::Command;

struct Expected {
    exit: i32,
    input: String,
    args: Vec<String>,
    contains: Vec<String>,
}

fn parse(text: &str) -> Expected {
    let mut e = Expected {
        exit: -1,
        input: ".".into(),
        args: Vec::new(),
        contains: Vec::new(),
    };
    for line in text.lines() {
        if let Some(v) = line.strip_prefix("exit ") {
            e.exit = v.trim().parse().expect("exit code");
        } else if let Some(v) = line.strip_prefix("input ") {
            e.input = v.trim().to_string();
        } else if let Some(v) = line.strip_prefix("args ") {
            e.args = v.split_whitespace().map(str::to_string).collect();
        } else if let Some(v) = line.strip_prefix("contains ") {
            e.contains.push(v.to_string());
        }
    }
    e
}

#[test]
fn corpus() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus");
    let mut cases: Vec<_> = std::fs::read_dir(&root)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .collect();
    cases.sort();
    assert!(cases.len() >= 20, "corpus is missing");
    let mut failures = Vec::new();
    for case in &cases {
        let name = case.file_name().unwrap().to_string_lossy().to_string();
        let expected = parse(&std::fs::read_to_string(case.join("expected.txt")).unwrap());
        let out = Command::new(env!("CARGO_BIN_EXE_apart"))
            .args(["check", &expected.input])
            .args(&expected.args)
            .current_dir(case)
            .output()
            .unwrap();
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        let code = out.status.code().unwrap_or(-1);
        if code != expected.exit {
            failures.push(format!(
                "{name}: exit {code}, expected {}\n{text}",
                expected.exit
            ));
        }
        for c in &expected.contains {
            if !text.contains(c.as_str()) {
                failures.push(format!("{name}: output lacks \"{c}\"\n{text}"));
            }
        }
        if text.contains("panicked") || text.contains("RUST_BACKTRACE") {
            failures.push(format!("{name}: panic\n{text}"));
        }
        // The same through --json: valid JSON with the same verdict.
        let out = Command::new(env!("CARGO_BIN_EXE_apart"))
            .args(["--json", "check", &expected.input])
            .args(&expected.args)
            .current_dir(case)
            .output()
            .unwrap();
        let v: serde_json::Value = serde_json::from_slice(&out.stdout)
            .unwrap_or_else(|e| panic!("{name}: --json output is not JSON: {e}"));
        if v["valid"].as_bool() != Some(expected.exit == 0) {
            failures.push(format!("{name}: --json verdict {}", v["valid"]));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
