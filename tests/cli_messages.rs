//! What the user reads when something is missing or wrong (issue 11, messages): a
//! forgotten part name is named as missing, a mistyped part name lists the closest
//! names, files of an assembly folder that are not read are listed with the reason,
//! temporary paths never show, and a step moving one part "moves".

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn apart_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_apart"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn apart(args: &[&str]) -> Output {
    apart_in(&root(), args)
}

fn err(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn out(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// A fresh folder for one test's files.
fn folder(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("apart-messages-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The OFF text of the box `[lo, hi]`.
fn cube(lo: [f64; 3], hi: [f64; 3]) -> String {
    let mut s = String::from("OFF\n8 6 0\n");
    for k in 0..8 {
        let c = [0, 1, 2].map(|a| if k >> a & 1 == 1 { hi[a] } else { lo[a] });
        s.push_str(&format!("{} {} {}\n", c[0], c[1], c[2]));
    }
    // Vertex k has x from bit 0, y from bit 1, z from bit 2; faces point outward.
    s.push_str("4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n");
    s
}

#[test]
fn a_forgotten_part_name_is_named_as_missing() {
    let o = apart(&["separate", "examples/dovetail-and-cap", "tenon"]);
    assert_eq!(o.status.code(), Some(1));
    let e = err(&o);
    assert!(e.contains("one part name is missing"), "{e}");
    assert!(!e.contains("No such file"), "{e}");
    // The other part can be either of the two others.
    assert!(e.contains("\"slot\"") && e.contains("\"cap\""), "{e}");
    // With only the assembly, the usage names both values still missing.
    let o = apart(&["separate", "examples/dovetail-and-cap"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(err(&o).contains("<A|B_FILE>"), "{}", err(&o));
}

#[test]
fn a_mistyped_part_name_lists_the_closest_names() {
    let o = apart(&["separate", "examples/dovetail-and-cap", "tenon", "slto"]);
    assert_eq!(o.status.code(), Some(1));
    let e = err(&o);
    assert!(e.contains("no part named \"slto\""), "{e}");
    assert!(e.contains("did you mean \"slot\"?"), "{e}");
    // Three parts: all listed.
    for n in ["slot", "tenon", "cap"] {
        assert!(e.contains(&format!("\"{n}\"")), "{e}");
    }
    let o = apart(&["sequence", "examples/tray-of-cubes", "--base", "trya"]);
    assert_eq!(o.status.code(), Some(1));
    let e = err(&o);
    assert!(
        e.contains("--base") && e.contains("did you mean \"tray\"?"),
        "{e}"
    );
    // Twenty parts: a name far from all lists a few, not all twenty.
    let o = apart(&["sequence", "examples/tray-of-cubes", "--base", "cube"]);
    let e = err(&o);
    assert!(e.contains("20 parts include"), "{e}");
    assert!(e.matches("\"cube_").count() == 5, "{e}");
}

#[test]
fn files_of_a_folder_that_are_not_read_are_listed_with_the_reason() {
    let dir = folder("skipped");
    std::fs::write(dir.join("a.off"), cube([0.0; 3], [1.0; 3])).unwrap();
    std::fs::write(dir.join("b.off"), cube([1.0, 0.0, 0.0], [2.0, 1.0, 1.0])).unwrap();
    std::fs::write(dir.join("bracket.step"), "ISO-10303-21;").unwrap();
    std::fs::write(dir.join("notes.txt"), "read me").unwrap();
    std::fs::write(dir.join(".hidden"), "").unwrap();
    std::fs::create_dir_all(dir.join("b")).unwrap();
    std::fs::copy(dir.join("b.off"), dir.join("b/piece.off")).unwrap();
    std::fs::write(dir.join("b/readme.md"), "").unwrap();
    let o = apart_in(&dir, &["check", "."]);
    assert_eq!(o.status.code(), Some(0), "{}", err(&o));
    let e = err(&o);
    assert!(
        e.contains("bracket.step: not read: a CAD file (.step)"),
        "{e}"
    );
    assert!(e.contains("notes.txt: not read: not a mesh file"), "{e}");
    assert!(e.contains("readme.md: not read"), "{e}");
    assert!(!e.contains(".hidden"), "{e}");
    assert!(out(&o).contains("not read: 3 entries"), "{}", out(&o));
    // The same in the JSON, exactly the three files.
    let o = apart_in(&dir, &["check", ".", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let mut files: Vec<String> = v["skipped_files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            assert!(!s["reason"].as_str().unwrap().is_empty());
            let f = PathBuf::from(s["file"].as_str().unwrap());
            f.strip_prefix(".").unwrap_or(&f).display().to_string()
        })
        .collect();
    files.sort();
    assert_eq!(files, ["b/readme.md", "bracket.step", "notes.txt"]);
    // A manifest names what is read: nothing is reported skipped.
    let o = apart(&["check", "examples/dovetail-and-cap", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["skipped_files"].as_array().unwrap().len(), 0);
}

#[test]
fn two_files_are_named_as_given_never_by_a_temporary_path() {
    let dir = folder("named");
    std::fs::write(dir.join("a.off"), cube([0.0; 3], [1.0; 3])).unwrap();
    std::fs::write(dir.join("b.off"), cube([0.5, 0.0, 0.0], [1.5, 1.0, 1.0])).unwrap();
    std::fs::write(dir.join("bad.off"), "OFF\n3 1 0\n0 0 0\n1 0\n").unwrap();
    for (files, named) in [
        (["a.off", "b.off"], "a.off and b.off"),
        (["a.off", "bad.off"], "a.off and bad.off"),
    ] {
        for json in [false, true] {
            let mut args = vec!["separate", files[0], files[1]];
            if json {
                args.push("--json");
            }
            let o = apart_in(&dir, &args);
            assert_eq!(o.status.code(), Some(1));
            let all = format!("{}{}", out(&o), err(&o));
            assert!(all.contains(named), "{all}");
            assert!(!all.contains("assembly.json"), "{all}");
            assert!(!all.contains("apart-separate-"), "{all}");
            // Problems name the files as given, relative to where the command ran.
            if files[1] == "bad.off" {
                assert!(all.contains("error: bad.off (part \"bad\")"), "{all}");
            }
        }
    }
    // A missing second file is named as such.
    let o = apart_in(&dir, &["separate", "a.off", "c.off"]);
    assert!(err(&o).contains("c.off: no such file"), "{}", err(&o));
}

#[test]
fn one_part_moves_several_parts_move() {
    let o = apart(&["sequence", "examples/tray-of-cubes", "--base", "tray"]);
    assert_eq!(o.status.code(), Some(0));
    let text = out(&o);
    let mut lines = 0;
    for l in text.lines().map(str::trim) {
        if let Some((who, _)) = l.split_once(" moves along ") {
            assert!(!who.contains(','), "{l}");
            lines += 1;
        } else if let Some((who, _)) = l.split_once(" move along ") {
            assert!(who.contains(','), "{l}");
            lines += 1;
        }
    }
    assert_eq!(lines, 19);
}

#[test]
fn explain_gives_every_step_its_ranking_keys() {
    let args = [
        "sequence",
        "examples/tray-of-cubes",
        "--base",
        "tray",
        "--prefer-axes",
        "--explain",
    ];
    let o = apart(&args);
    assert_eq!(o.status.code(), Some(0));
    let why = out(&o)
        .lines()
        .filter(|l| l.trim().starts_with("why: "))
        .count();
    assert_eq!(why, 19);
    let mut json_args = args.to_vec();
    json_args.push("--json");
    let o = apart(&json_args);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    for s in v["steps"].as_array().unwrap() {
        let c = &s["choice"];
        assert!(c["candidates"].as_u64().unwrap() >= 1);
        let zeros = s["exact_direction"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|x| x.as_str() == Some("0"))
            .count();
        assert_eq!(c["axis"].as_bool().unwrap(), zeros == 2);
        assert_eq!(c["cell"], s["cell"]);
        assert_eq!(
            c["single"].as_bool().unwrap(),
            s["moving"].as_array().unwrap().len() == 1
        );
        if let Some(r) = c["runner_up"].as_object() {
            assert!(r["lost_on"].is_string());
        }
    }
    // Without --explain the JSON has no choice.
    let o = apart(&["sequence", "examples/tray-of-cubes", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v["steps"][0].get("choice").is_none());
}
