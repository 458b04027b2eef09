//! `apart check` on the shipped examples.

use std::path::Path;
use std::process::Command;

fn check_json(dir: &str) -> (i32, serde_json::Value) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Command::new(env!("CARGO_BIN_EXE_apart"))
        .args(["--json", "check"])
        .arg(root.join(dir))
        .output()
        .unwrap();
    let v = serde_json::from_slice(&out.stdout).expect("JSON");
    (out.status.code().unwrap_or(-1), v)
}

/// Six times the volume of a closed OFF mesh with integer coordinates, by the
/// divergence theorem over fans of its faces: an independent little computation.
fn off_volume6(path: &Path) -> i64 {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'));
    assert_eq!(lines.next(), Some("OFF"));
    let counts: Vec<usize> = lines
        .next()
        .unwrap()
        .split_whitespace()
        .map(|t| t.parse().unwrap())
        .collect();
    let v: Vec<[i64; 3]> = (0..counts[0])
        .map(|_| {
            let c: Vec<i64> = lines
                .next()
                .unwrap()
                .split_whitespace()
                .map(|t| t.parse().unwrap())
                .collect();
            [c[0], c[1], c[2]]
        })
        .collect();
    let mut total = 0;
    for _ in 0..counts[1] {
        let f: Vec<usize> = lines
            .next()
            .unwrap()
            .split_whitespace()
            .skip(1)
            .map(|t| t.parse().unwrap())
            .collect();
        for k in 1..f.len() - 1 {
            let (a, b, c) = (v[f[0]], v[f[k]], v[f[k + 1]]);
            total += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]);
        }
    }
    total
}

#[test]
fn split_star_has_six_valid_parts_of_volume_16_thirds() {
    let (code, v) = check_json("examples/split-star");
    assert_eq!(code, 0);
    assert_eq!(v["valid"], true);
    let names: Vec<&str> = v["parts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        ["red", "green", "blue", "purple", "yellow", "turquoise"]
    );
    // Independent: the three convex pieces of each part in split-star-3 (an octahedron
    // of volume 2 * 4/3 and two pyramids of 4/3, by hand), summed by our own formula.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/split-star-3");
    for name in names {
        let six: i64 = (0..3)
            .map(|k| off_volume6(&root.join(format!("{name}/piece_{k}.off"))))
            .sum();
        assert_eq!(six, 32, "{name}"); // 6 * 16/3
        let p = v["parts"]
            .as_array()
            .unwrap()
            .iter()
            .find(|p| p["name"] == name)
            .unwrap();
        assert_eq!(p["volume"], "16/3");
        assert_eq!(p["convex"], false);
        assert_eq!(p["vertices"], 10);
        assert_eq!(p["faces"], 16);
    }
}

#[test]
fn every_shipped_example_is_valid() {
    for dir in [
        "split-star",
        "split-star-3",
        "split-star-5",
        "split-star-8",
        "peg-in-the-hole",
    ] {
        let (code, v) = check_json(&format!("examples/{dir}"));
        assert_eq!(code, 0, "{dir}: {v}");
        assert!(v["problems"].as_array().unwrap().is_empty(), "{dir}: {v}");
    }
    // Peg in the hole: the peg is a 2 x 4 x 2 box (16), the block 4^3 minus a 2 x 2 x 2 hole (56).
    let (_, v) = check_json("examples/peg-in-the-hole");
    assert_eq!(v["parts"][0]["volume"], "16");
    assert_eq!(v["parts"][0]["convex"], true);
    assert_eq!(v["parts"][1]["volume"], "56");
}

#[test]
fn load_errors_are_one_clear_line() {
    let out = Command::new(env!("CARGO_BIN_EXE_apart"))
        .args(["check", "does/not/exist"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.trim(), "error: does/not/exist: no such file or folder");
}
