//! `apart disassemble` end to end: the JSON of a plan of moves, its exact numbers
//! against the example's construction, and the exit codes of a plan that does not
//! exist within the bounds.

use serde_json::Value;
use std::path::PathBuf;
use std::process::Command;

fn example(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name)
        .display()
        .to_string()
}

/// Runs `apart disassemble ARGS --json` and returns (exit code, parsed standard output).
fn disassemble(args: &[&str]) -> (i32, Value) {
    let out = Command::new(env!("CARGO_BIN_EXE_apart"))
        .arg("disassemble")
        .args(args)
        .args(["--json", "--quiet"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    let v =
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{args:?}: not JSON ({e}): {text}"));
    (out.status.code().unwrap(), v)
}

#[test]
fn the_keyhole_slides_then_lifts_with_exact_numbers() {
    let (code, v) = disassemble(&[&example("keyhole")]);
    assert_eq!(code, 0, "{v}");
    assert_eq!(v["level"], 2);
    assert_eq!(v["complete"], true);
    assert_eq!(v["model"], "free cone");
    let moves = v["moves"].as_array().unwrap();
    assert_eq!(moves.len(), 2);
    let first = &moves[0];
    assert_eq!(first["moving"], serde_json::json!(["key"]));
    assert_eq!(
        first["exact_direction"],
        serde_json::json!(["-1", "0", "0"])
    );
    // The head reaches the keyhole's wide end after 9 units (the construction's least).
    assert_eq!(first["distance"], "9");
    assert_eq!(
        first["exact_positions"]["key"],
        serde_json::json!(["-9", "0", "0"])
    );
    assert_eq!(
        first["positions"]["box"],
        serde_json::json!([0.0, 0.0, 0.0])
    );
    assert_eq!(moves[1]["distance"], "infinity");
    assert_eq!(
        moves[1]["exact_direction"],
        serde_json::json!(["0", "0", "1"])
    );
    assert!(v["states_explored"].as_u64().unwrap() >= 2);
    assert!(v["stats"]["seconds"]["search"].as_f64().is_some());
    assert_eq!(v["searches"][0]["end"], "separated");
}

#[test]
fn no_plan_within_the_bounds_exits_2_and_says_whether_it_was_exhaustive() {
    let (code, v) = disassemble(&[&example("l-slot"), "--max-moves", "1"]);
    assert_eq!(code, 2);
    assert_eq!(v["complete"], false);
    assert!(v["level"].is_null());
    let verdict = v["verdict"].as_str().unwrap();
    assert!(
        verdict.contains("no plan with at most 1 moves exists"),
        "{verdict}"
    );
    let (code, v) = disassemble(&[&example("l-slot"), "--max-states", "1"]);
    assert_eq!(code, 2);
    assert!(v["verdict"].as_str().unwrap().contains("cut off"), "{v}");
    let (code, v) = disassemble(&[&example("linked-rings")]);
    assert_eq!(code, 2);
    assert!(
        v["verdict"].as_str().unwrap().contains("exhaustively"),
        "{v}"
    );
    assert_eq!(v["searches"][0]["end"], "interlocked");
}

#[test]
fn axes_only_on_a_diagonal_slide_finds_no_plan() {
    // The L-slot's block leaves only by sliding along (1, 1, 0) first.
    let (code, v) = disassemble(&[&example("l-slot"), "--axes"]);
    assert_eq!(code, 2, "{v}");
    assert_eq!(v["model"], "axes");
    assert_eq!(v["searches"][0]["end"], "interlocked");
}
