//! The command line end to end: JSON shapes and exit codes of every planning command,
//! on the shipped examples, against facts known independently of the program (the
//! Split Star's eight isolated directions ±(1,1,1)… from paper 001, the geometry of the
//! hand-made examples, and exact re-checks of what the JSON claims).

use apart_testkit::Scratch;
use serde_json::Value;
use std::path::PathBuf;
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn example(name: &str) -> String {
    root().join("examples").join(name).display().to_string()
}

/// Runs `apart ARGS --json` and returns (exit code, parsed standard output).
fn apart_json(args: &[&str]) -> (i32, Value) {
    let out = Command::new(env!("CARGO_BIN_EXE_apart"))
        .args(args)
        .arg("--json")
        .arg("--quiet")
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    let v = serde_json::from_str(&text).unwrap_or_else(|e| {
        panic!(
            "{args:?}: not JSON ({e}): {text}\n{}",
            String::from_utf8_lossy(&out.stderr)
        )
    });
    (out.status.code().unwrap(), v)
}

fn strs(v: &Value) -> Vec<String> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|s| s.as_str().unwrap().to_string())
        .collect()
}

fn ints(v: &Value) -> [i64; 3] {
    let s = strs(v);
    [0, 1, 2].map(|k| s[k].parse().unwrap())
}

#[test]
fn partition_json_of_the_split_star_has_exactly_the_eight_diagonals() {
    let (code, v) = apart_json(&["partition", &example("split-star")]);
    assert_eq!(code, 0);
    assert_eq!(v["interlocked"], false);
    assert_eq!(
        strs(&v["parts"]),
        ["red", "green", "blue", "purple", "yellow", "turquoise"]
    );
    let sols = v["solutions"].as_array().unwrap();
    assert_eq!(sols.len(), 8);
    let mut dirs: Vec<[i64; 3]> = sols
        .iter()
        .map(|s| {
            assert_eq!(s["cell"], "vertex");
            assert_eq!(s["clearance_deg"], 0.0);
            // Three parts move along each diagonal (paper 001 fig. 1).
            assert_eq!(s["moving"].as_array().unwrap().len(), 3);
            let d = ints(&s["exact_direction"]);
            let u: Vec<f64> = s["direction"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            let n = 3f64.sqrt();
            for k in 0..3 {
                assert!((u[k] - d[k] as f64 / n).abs() < 1e-12);
            }
            d
        })
        .collect();
    dirs.sort();
    let mut want: Vec<[i64; 3]> = (0..8)
        .map(|k| [0, 1, 2].map(|b| if k >> b & 1 == 1 { 1 } else { -1 }))
        .collect();
    want.sort();
    assert_eq!(dirs, want);
    for key in ["sums", "projection", "unions", "overlay", "graphs"] {
        assert!(v["stats"]["seconds"][key].is_number(), "{key}");
    }
    // d and -d: the complementary triple moves along -d.
    for s in sols {
        let d = ints(&s["exact_direction"]);
        let moving = strs(&s["moving"]);
        let opposite = sols
            .iter()
            .find(|t| ints(&t["exact_direction"]) == d.map(|x| -x))
            .unwrap();
        let mut all: Vec<String> = moving
            .into_iter()
            .chain(strs(&opposite["moving"]))
            .collect();
        all.sort();
        assert_eq!(all.len(), 6);
        all.dedup();
        assert_eq!(all.len(), 6);
    }
}

#[test]
fn partition_first_stops_at_one_solution_and_direction_gives_the_graph() {
    let (code, v) = apart_json(&["partition", &example("split-star"), "--first"]);
    assert_eq!(code, 0);
    assert_eq!(v["solutions"].as_array().unwrap().len(), 1);

    // Along z every part is blocked by another: no subset moves.
    let (code, v) = apart_json(&["partition", &example("split-star"), "--direction", "0,0,1"]);
    assert_eq!(code, 2);
    assert_eq!(v["moving"].as_array().unwrap().len(), 0);
    assert!(!v["blocks"].as_array().unwrap().is_empty());
    // Along a diagonal the direction lies on a vertex of the arrangement.
    let (_, v) = apart_json(&["partition", &example("split-star"), "--direction", "1,1,1"]);
    assert_eq!(v["cell"], "vertex");
    assert_eq!(v["moving"].as_array().unwrap().len(), 1);
}

#[test]
fn sequence_takes_the_hinge_apart_and_stops_at_linked_rings() {
    let (code, v) = apart_json(&["sequence", &example("hinge")]);
    assert_eq!(code, 0);
    assert_eq!(v["interlocked"], false);
    let steps = v["steps"].as_array().unwrap();
    let parts = v["parts"].as_array().map_or(0, |p| p.len());
    // A complete binary split of n parts takes n - 1 steps.
    if parts > 0 {
        assert_eq!(steps.len(), parts - 1);
    }
    let first = &steps[0];
    assert_eq!(strs(&first["moving"]), ["bolt"]);
    for s in steps {
        assert!(["face", "edge", "vertex"].contains(&s["cell"].as_str().unwrap()));
        assert!(!strs(&s["subassembly"]).is_empty());
        ints(&s["exact_direction"]);
    }

    let (code, v) = apart_json(&["sequence", &example("linked-rings")]);
    assert_eq!(code, 2);
    assert_eq!(v["interlocked"], true);
    assert_eq!(v["full_searches"], Value::Null);

    // --first: the rings are found interlocked by the full search all the same.
    let (code, v) = apart_json(&["sequence", "--first", &example("linked-rings")]);
    assert_eq!(code, 2);
    assert_eq!(v["interlocked"], true);
    assert_eq!(v["full_searches"], 1);
    let (code, v) = apart_json(&["sequence", "--first", &example("hinge")]);
    assert_eq!(code, 0);
    assert_eq!(v["complete"], true);
    assert_eq!(
        v["steps"].as_array().unwrap().len(),
        v["parts"].as_array().unwrap().len() - 1
    );
    // It ranks nothing, so it takes no ranking flag.
    let out = Command::new(env!("CARGO_BIN_EXE_apart"))
        .args(["sequence", "--first", "--growth", &example("hinge")])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot be used with"));
}

#[test]
fn separate_names_the_free_directions_of_two_parts() {
    let (code, v) = apart_json(&["separate", &example("hinge"), "bolt", "bracket"]);
    assert_eq!(code, 0);
    assert_eq!(v["separable"], true);
    let f = v["area_fraction"].as_f64().unwrap();
    assert!((0.0..1.0).contains(&f), "{f}");

    let (code, v) = apart_json(&["separate", &example("linked-rings"), "ring_a", "ring_b"]);
    assert_eq!(code, 2, "{v}");
    assert_eq!(v["separable"], false);
}

#[test]
fn stack_of_cubes_with_weight_one_is_a_column() {
    let cube = example("sheet-metal/cube.off");
    let (code, v) = apart_json(&["stack", &cube, "--count", "4", "--weight", "1"]);
    assert_eq!(code, 0, "{v}");
    let ps = v["placements"].as_array().unwrap();
    assert_eq!(ps.len(), 4);
    // A column: same x and y, z climbing by the cube's side (10).
    let t: Vec<Vec<f64>> = ps
        .iter()
        .map(|p| {
            p["translation"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        })
        .collect();
    let mut zs: Vec<f64> = t.iter().map(|p| p[2]).collect();
    zs.sort_by(f64::total_cmp);
    assert_eq!(zs, [0.0, 10.0, 20.0, 30.0]);
    assert!(t.iter().all(|p| p[0] == t[0][0] && p[1] == t[0][1]));
    assert_eq!(v["stack_height"], 40.0);

    // No room: a 1-high stack of 4 on a floor for one cube is incomplete (exit 2).
    let (code, v) = apart_json(&[
        "stack",
        &cube,
        "--count",
        "4",
        "--floor",
        "-5,-5,5,5",
        "--max-height",
        "10",
    ]);
    assert_eq!(code, 2);
    assert_eq!(v["complete"], false);
    assert_eq!(v["placements"].as_array().unwrap().len(), 1);
}

#[test]
fn place_puts_a_copy_next_to_the_original_without_overlap() {
    let cube = example("sheet-metal/cube.off");
    let (code, v) = apart_json(&["place", &cube, &cube, "--candidates", "3"]);
    assert_eq!(code, 0, "{v}");
    let c = v["candidates"].as_array().unwrap();
    assert!(!c.is_empty());
    // The nearest free translations of a cube of side 10 from itself touch a face:
    // squared distance 100.
    assert_eq!(c[0]["cost"], 100.0);
    let t: Vec<f64> = c[0]["translation"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let moved: Vec<f64> = t.iter().map(|x| x.abs()).collect();
    let mut sorted = moved.clone();
    sorted.sort_by(f64::total_cmp);
    assert_eq!(sorted, [0.0, 0.0, 10.0]);

    // Eq. (1) with w = 0 is 4 (z_cg − z0)²: lowest on the floor of the region, beside the
    // original (which fills z in [0, 10]), centre of gravity 5 above the floor point.
    let (code, v) = apart_json(&[
        "place",
        &cube,
        &cube,
        "--weight",
        "0",
        "--region",
        "-30,-30,0,30,30,40",
    ]);
    assert_eq!(code, 0, "{v}");
    let best = &v["candidates"][0];
    assert_eq!(best["cost"], 100.0);
    assert_eq!(best["translation"][2], 0.0);
    assert_eq!(v["cost_kind"], "stacking");
}

#[test]
fn bad_input_fails_with_a_message_and_no_panic() {
    let dir = Scratch::new("cli");
    let bad = dir.join("broken.off");
    std::fs::write(&bad, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n").unwrap();
    for cmd in ["partition", "sequence", "stack"] {
        let out = Command::new(env!("CARGO_BIN_EXE_apart"))
            .args([cmd, bad.to_str().unwrap()])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{cmd}: {err}");
        assert!(err.contains("broken.off"), "{cmd}: {err}");
        assert!(!err.contains("panicked"), "{cmd}: {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn holding_without_tolerance_concerns_only_the_parts_that_overlapped() {
    // A lid 1e-6 into its box, and a block beside the box, apart from both: under the
    // tolerance the lid lifts off the box, which does not hold for the parts as given;
    // the block leaves the box (the pair without an overlap) as it would anyway.
    let dir = Scratch::new("cli-holds");
    let write = |name: &str, lo, hi| {
        std::fs::write(
            dir.join(name),
            apart_testkit::defects::box_soup(lo, hi).to_off(),
        )
        .unwrap()
    };
    write("box.off", [0.0, 0.0, 0.0], [1.0, 1.0, 1.0]);
    write("lid.off", [0.0, 0.0, 1.0 - 1e-6], [1.0, 1.0, 1.2]);
    write("block.off", [2.0, 0.0, 0.0], [3.0, 1.0, 1.0]);
    let path = dir.path().to_str().unwrap().to_string();
    let separate = |a: &str, b: &str| {
        let (code, v) = apart_json(&["separate", &path, a, b, "--tolerance", "auto"]);
        assert_eq!(code, 0, "{a} {b}: {v}");
        assert!(v["tolerance"]["eps"].as_f64().unwrap() > 0.0);
        v["best"]["holds_without_tolerance"].clone()
    };
    assert_eq!(separate("lid", "box"), false);
    assert_eq!(separate("block", "box"), true);
    assert_eq!(separate("lid", "block"), true);
}

#[test]
fn real_cad_flags_repair_split_and_tolerance() {
    // Seams and two washers in one file: repaired and split by default...
    let (code, v) = apart_json(&["check", &example("cad-seams")]);
    assert_eq!(code, 0);
    let names: Vec<String> = v["parts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap().to_string())
        .collect();
    assert_eq!(names, ["base", "lid", "washers_1", "washers_2"]);
    let repairs = v["repairs"].as_array().unwrap();
    let base = repairs
        .iter()
        .find(|r| strs(&r["parts"]) == ["base"])
        .unwrap();
    // The generator's seams: every box edge where two faces' subdivisions differ.
    assert!(base["tjunctions"].as_u64().unwrap() > 0);
    assert!(v["tolerance"].is_null());
    // ... refused with --strict, and one part per file with --one-part-per-file.
    let (code, _) = apart_json(&["check", &example("cad-seams"), "--strict"]);
    assert_eq!(code, 1);
    let (_, v) = apart_json(&[
        "check",
        &example("cad-seams"),
        "--one-part-per-file",
        "--strict",
    ]);
    assert_eq!(v["parts"].as_array().unwrap().len(), 3);

    // The pin pokes out of the hole by 4 (1 - cos(pi/64)): an error without tolerance,
    // valid with --tolerance auto, which states the tolerance in the JSON.
    let depth = 4.0 * (1.0 - (std::f64::consts::PI / 64.0).cos());
    let (code, _) = apart_json(&["check", &example("cad-pin-in-hole")]);
    assert_eq!(code, 1);
    let (code, v) = apart_json(&[
        "partition",
        &example("cad-pin-in-hole"),
        "--tolerance",
        "auto",
        "--units",
        "mm",
    ]);
    assert_eq!(code, 0);
    assert_eq!(v["units"], "mm");
    let eps = v["tolerance"]["eps"].as_f64().unwrap();
    assert!(eps >= depth / 2.0 && eps <= depth, "{eps} vs {depth}");
    assert_eq!(v["tolerance"]["auto"], true);
    // The parts as given overlap, so no motion separating them holds without the
    // tolerance, and every solution says so.
    for s in v["solutions"].as_array().unwrap() {
        assert_eq!(s["holds_without_tolerance"], false);
    }
    // Parts that only touch: the base leaves downwards (the rest upwards) either way,
    // while the lid sliding out from under the washers tilted slightly upwards needs
    // the gap the shrink opens between lid and washers (without it the lid slides
    // exactly horizontally or not at all): marked.
    let (code, v) = apart_json(&["partition", &example("cad-seams"), "--tolerance", "1e-3"]);
    assert_eq!(code, 0);
    let sols = v["solutions"].as_array().unwrap();
    let face = |s: &&Value| s["cell"] == "face";
    assert!(sols
        .iter()
        .filter(face)
        .any(|s| strs(&s["moving"]) == ["base"]
            && s["direction"][2].as_f64().unwrap() < -0.99
            && s["holds_without_tolerance"] == true));
    assert!(sols
        .iter()
        .filter(face)
        .any(|s| strs(&s["moving"]) == ["lid"]
            && s["direction"][2].as_f64().unwrap() > 0.0
            && s["holds_without_tolerance"] == false));
    assert!(sols
        .iter()
        .all(|s| s["holds_without_tolerance"].is_boolean()));
    // A stated tolerance with a unit in a millimetre file: 2 µm is less than half the
    // depth (2.41e-3 mm) and leaves the overlap; 3 µm is enough.
    let (code, _) = apart_json(&[
        "check",
        &example("cad-pin-in-hole"),
        "--tolerance",
        "2um",
        "--units",
        "mm",
    ]);
    assert_eq!(code, 1);
    let (code, _) = apart_json(&[
        "check",
        &example("cad-pin-in-hole"),
        "--tolerance",
        "3um",
        "--units",
        "mm",
    ]);
    assert_eq!(code, 0);
    // A unit without --units, and a tolerance where it has no meaning, are errors.
    let (code, _) = apart_json(&["check", &example("cad-pin-in-hole"), "--tolerance", "3um"]);
    assert_eq!(code, 1);
    let (code, _) = apart_json(&[
        "stack",
        &example("sheet-metal/cube.off"),
        "--tolerance",
        "1e-3",
    ]);
    assert_eq!(code, 1);
}
