//! The pictures and exports the commands write: every file is announced on standard
//! error ("wrote FILE") unless `--quiet`, standard output keeps only the answer (valid
//! JSON with `--json`), and the pictures name the parts by their names.

use apart_testkit::Scratch;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn example(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name)
        .display()
        .to_string()
}

/// A fresh temporary folder for one test.
fn scratch(tag: &str) -> Scratch {
    Scratch::new(&format!("cli-pictures-{}", tag))
}

fn apart(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_apart"))
        .args(args)
        .output()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The lines "wrote …" on standard error.
fn announced(o: &Output) -> Vec<String> {
    stderr(o)
        .lines()
        .filter_map(|l| l.strip_prefix("wrote ").map(str::to_string))
        .collect()
}

fn path(p: &Path) -> String {
    p.display().to_string()
}

#[test]
fn sequence_announces_every_file_it_writes_and_quiet_hides_it() {
    let dir = scratch("sequence");
    let (glb, html, svg, renders) = (
        dir.join("hinge.glb"),
        dir.join("hinge.html"),
        dir.join("step1.svg"),
        dir.join("steps"),
    );
    let args = [
        "sequence",
        &example("hinge"),
        "--glb",
        &path(&glb),
        "--html",
        &path(&html),
        "--svg",
        &path(&svg),
        "--renders",
        &path(&renders),
        "--json",
    ];
    let out = apart(&args);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    // Standard output is the JSON answer alone.
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON on stdout");
    let steps = v["steps"].as_array().unwrap().len();
    assert!(!String::from_utf8_lossy(&out.stdout).contains("wrote"));
    // Every file that exists now was announced, and nothing else.
    let mut written = vec![path(&glb), path(&html), path(&svg)];
    written.push(path(&renders.join("assembly.png")));
    for k in 1..=steps {
        written.push(path(&renders.join(format!("step-{k}.png"))));
    }
    let mut said = announced(&out);
    said.sort();
    written.sort();
    assert_eq!(said, written);
    for f in &written {
        assert!(Path::new(f).is_file(), "{f}");
    }
    let quiet = apart(&[&args[..], &["--quiet"]].concat());
    assert_eq!(quiet.status.code(), Some(0));
    assert!(announced(&quiet).is_empty(), "{}", stderr(&quiet));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn stack_pictures_are_announced_and_carry_axes_scale_and_names() {
    let dir = scratch("stack");
    let (png, svg) = (dir.join("stack.png"), dir.join("stack.svg"));
    let out = apart(&[
        "stack",
        &example("sheet-metal/cube.off"),
        "--count",
        "3",
        "--png",
        &path(&png),
        "--svg",
        &path(&svg),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let mut said = announced(&out);
    said.sort();
    assert_eq!(said, [path(&png), path(&svg)]);
    assert!(!String::from_utf8_lossy(&out.stdout).contains("wrote"));
    let text = std::fs::read_to_string(&svg).unwrap();
    for label in ["cube #1", "cube #2", "cube #3", "x", "y", "z"] {
        assert!(text.contains(&format!(">{label}</text>")), "{label}");
    }
    assert!(text.contains(" units</text>") || text.contains(" unit</text>"));
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn place_pictures_name_the_fixed_parts() {
    let dir = scratch("place");
    let svg = dir.join("place.svg");
    // An assembly and one of its parts: the others are fixed, and keep their names.
    let out = apart(&[
        "place",
        &example("hinge"),
        "bolt",
        "--translations",
        "-20,-20,-20,20,20,20",
        "--target",
        "0,-10,0",
        "--svg",
        &path(&svg),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(announced(&out), [path(&svg)]);
    let text = std::fs::read_to_string(&svg).unwrap();
    for name in ["bracket", "tongue", "bolt"] {
        assert!(text.contains(&format!(">{name}</text>")), "{name}");
    }
    assert!(
        !text.contains("fixed 1"),
        "scene parts are named, not numbered"
    );
    // Two files: the fixed one is named after its file.
    let cube = example("sheet-metal/cube.off");
    let out = apart(&["place", &cube, &cube, "--svg", &path(&svg), "--quiet"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(announced(&out).is_empty());
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains(">cube</text>") && text.contains(">cube_2</text>"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_interlocked_sequence_still_answers_and_draws_its_blocked_motion_space() {
    // The rings cannot be split: the answer is "no" (exit code 2) with the JSON plan, and
    // the sphere picture shows the interlocked subassembly instead of failing on a
    // missing step 1. Asking for a step the plan cannot have stays a usage error.
    let dir = scratch("interlocked");
    let svg = dir.join("rings.svg");
    let o = apart(&[
        "sequence",
        &example("linked-rings"),
        "--json",
        "--svg",
        &path(&svg),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let answer: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(
        answer["steps"].as_array().map(Vec::len),
        Some(0),
        "{answer}"
    );
    assert_eq!(announced(&o), vec![path(&svg)]);
    let drawn = std::fs::read_to_string(&svg).unwrap();
    assert!(drawn.contains("interlocked"), "the title says why");
    assert!(
        drawn.contains("ring_a") && drawn.contains("ring_b"),
        "parts named"
    );

    let o = apart(&[
        "sequence",
        &example("linked-rings"),
        "--svg",
        &path(&svg),
        "--step",
        "2",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("--step 2: the plan has 0 steps"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn disassemble_writes_the_moves_as_svg_glb_and_html() {
    // A frame with an L-shaped slot open at the top, and a key at the slot's bottom
    // end: it slides along the slot (a finite move), then lifts out.
    let dir = scratch("disassemble");
    let input = dir.join("key-in-slot");
    std::fs::create_dir_all(&input).unwrap();
    let slot = [[1, 1, 1], [1, 2, 1], [1, 2, 2]];
    let on: Vec<bool> = (0..36)
        .map(|i| [i / 12, i / 3 % 4, i % 3])
        .map(|c| !slot.contains(&c))
        .collect();
    let frame = apart_testkit::solids::voxels([3, 4, 3], &on);
    let mut key = apart_testkit::solids::voxels([1, 1, 1], &[true]);
    for p in &mut key.points {
        *p = p.map(|c| c + 1);
    }
    std::fs::write(input.join("frame.off"), frame.off_text()).unwrap();
    std::fs::write(input.join("key.off"), key.off_text()).unwrap();
    let (svg, glb, html) = (dir.join("m.svg"), dir.join("m.glb"), dir.join("m.html"));
    let out = apart(&[
        "disassemble",
        &path(&input),
        "--svg",
        &path(&svg),
        "--glb",
        &path(&glb),
        "--html",
        &path(&html),
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON on stdout");
    assert_eq!(v["level"], 2, "{v}");
    let moves = v["moves"].as_array().unwrap();
    assert_eq!(moves.len(), 2);
    assert_ne!(moves[0]["distance"], "infinity");
    let mut said = announced(&out);
    said.sort();
    let mut written = vec![path(&svg), path(&glb), path(&html)];
    written.sort();
    assert_eq!(said, written);
    // One panel per state, the key lit after each move.
    let text = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(text.matches(r#"<g class="panel""#).count(), 3);
    assert_eq!(text.matches(r#"data-moving="key""#).count(), 2);
    assert!(text.contains("→ ∞ along"));
    assert!(std::fs::read(&glb).unwrap().starts_with(b"glTF"));
    let page = std::fs::read_to_string(&html).unwrap();
    for needle in [
        "\"frame\"",
        "\"key\"",
        "to infinity",
        "first separation (level 2)",
    ] {
        assert!(page.contains(needle), "{needle}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
