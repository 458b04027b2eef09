//! What the user reads when something is missing or wrong: a
//! forgotten part name is named as missing, a mistyped part name lists the closest
//! names, files of an assembly folder that are not read are listed with the reason,
//! temporary paths never show, and a step moving one part "moves".

use apart_testkit::Scratch;
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
fn folder(tag: &str) -> Scratch {
    Scratch::new(&format!("messages-{}", tag))
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

/// The OFF text of a comb of `teeth` teeth, the prism over the profile of a bar
/// `[0, 2·teeth + 1] × [0, 1]` with the teeth `[2i + 1, 2i + 2] × [1, 2]` on it, from
/// z = 0 to 1 and shifted by `at`. Every face is a unit square, so no edge meets a
/// vertex mid-way; the two reflex edges at each tooth make the automatic decomposition
/// give about one piece per tooth.
fn comb(teeth: usize, at: [i64; 3]) -> String {
    let w = 2 * teeth as i64 + 1;
    // The profile, counterclockwise seen from +z: the bottom edge at every integer x,
    // up the right end, then leftwards over the teeth.
    let mut profile: Vec<[i64; 2]> = (0..=w).map(|x| [x, 0]).collect();
    profile.push([w, 1]);
    for i in (0..teeth as i64).rev() {
        profile.extend([
            [2 * i + 2, 1],
            [2 * i + 2, 2],
            [2 * i + 1, 2],
            [2 * i + 1, 1],
        ]);
    }
    profile.push([0, 1]);
    let m = profile.len();
    let index = |x: i64, y: i64| profile.iter().position(|p| *p == [x, y]).unwrap();
    let mut faces: Vec<[usize; 4]> = Vec::new();
    // Top (z = 1, vertices m..2m) and bottom (z = 0, reversed): unit squares of the
    // bar, then the teeth.
    let mut squares: Vec<[usize; 4]> = (0..w)
        .map(|x| [index(x, 0), index(x + 1, 0), index(x + 1, 1), index(x, 1)])
        .collect();
    squares.extend((0..teeth as i64).map(|i| {
        let x = 2 * i + 1;
        [index(x, 1), index(x + 1, 1), index(x + 1, 2), index(x, 2)]
    }));
    for q in &squares {
        faces.push(q.map(|v| v + m));
        faces.push([q[3], q[2], q[1], q[0]]);
    }
    // The walls, one per profile edge, outward on the right of the walk.
    for k in 0..m {
        let (a, b) = (k, (k + 1) % m);
        faces.push([a, b, b + m, a + m]);
    }
    let mut s = format!("OFF\n{} {} 0\n", 2 * m, faces.len());
    for z in 0..2 {
        for p in &profile {
            s.push_str(&format!(
                "{} {} {}\n",
                p[0] + at[0],
                p[1] + at[1],
                z + at[2]
            ));
        }
    }
    for f in &faces {
        s.push_str(&format!("4 {} {} {} {}\n", f[0], f[1], f[2], f[3]));
    }
    s
}

#[test]
fn a_part_of_many_automatic_pieces_is_named_in_a_warning() {
    let dir = folder("many-pieces");
    // A comb of 210 teeth (about 210 pieces) and, above it, a comb of 2 teeth (a few
    // pieces): only the first is named.
    std::fs::write(dir.join("comb.off"), comb(210, [0, 0, 0])).unwrap();
    std::fs::write(dir.join("small.off"), comb(2, [0, 0, 3])).unwrap();
    let o = apart_in(&dir, &["check", ".", "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", err(&o));
    // The answer on standard output stays valid JSON; its piece counts are the ones
    // the warning names.
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let pieces = |name: &str| {
        let parts = v["parts"].as_array().unwrap();
        let p = parts.iter().find(|p| p["name"] == name).unwrap();
        assert_eq!(p["decomposed"], true, "{p}");
        p["pieces"].as_u64().unwrap()
    };
    let (many, few) = (pieces("comb"), pieces("small"));
    assert!(many >= 200, "the comb has only {many} pieces");
    assert!(few < 10, "{few}");
    let e = err(&o);
    let warning =
        format!("warning: part \"comb\": its automatic convex decomposition has {many} pieces");
    assert_eq!(e.matches(&warning).count(), 1, "{e}");
    assert!(
        e.contains("grow with the product of two parts' piece counts"),
        "{e}"
    );
    assert!(
        e.contains(&format!("{many} x {many} = {}", many * many)),
        "{e}"
    );
    assert!(!e.contains("\"small\""), "{e}");
    assert_eq!(e.matches("automatic convex decomposition has").count(), 1);

    // With a comb of 150 teeth (fewer than 200 pieces) nothing is named.
    std::fs::write(dir.join("comb.off"), comb(150, [0, 0, 0])).unwrap();
    let o = apart_in(&dir, &["check", ".", "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", err(&o));
    assert!(
        !err(&o).contains("automatic convex decomposition"),
        "{}",
        err(&o)
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let fewer = v["parts"][0]["pieces"].as_u64().unwrap();
    assert!((100..200).contains(&fewer), "{fewer}");
    let _ = std::fs::remove_dir_all(&dir);
}
