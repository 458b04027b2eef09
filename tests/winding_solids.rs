//! Soups that only the winding-number rule makes solid, end to end: each family of
//! `apart_testkit::soups` (a rim of doubled-back faces, a thread of crossing rings with
//! open seams and slivers and a nut on it, gear flanks that cross, a fillet folded over
//! itself, two overlapping shells of one part) written as OFF files, loaded, and
//! checked against the answer its generator states: the part loads as a solid through
//! the winding path (a repair warning says so), its volume (the sum of its convex
//! pieces') is the known one and agrees with the independent Monte Carlo estimate of
//! `apart_testkit::winding`, and the two-part assembly comes apart as it must, every
//! step re-checked by the brute-force oracle.
//!
//! Each file is one part (`split_bodies` off, `--one-part-per-file`): the rule makes
//! the part of all the faces of its file. The repair note's wording is matched loosely
//! (a warning that starts with "repaired" and mentions the winding number or "the
//! solid they enclose"), since the loader's wording is its own.

use apart::assembly::{load, LoadOptions, Loaded};
use apart::kernel::{Rational, Vec3};
use apart::mesh::validate::volume_in_units;
use apart::mesh::{ProblemKind, Severity};
use apart::plan::{sequence, BlockingRegions, CellKind, SequenceOptions};
use apart_testkit::soups::{families, write_off_dir, Family};
use apart_testkit::winding::monte_carlo_volume;
use apart_testkit::Scratch;
use serde_json::Value;
use std::process::Command;

mod common;
use common::{index, oracle_free, partition_checked};

/// The family called `name`, written into a fresh folder.
fn written(name: &str) -> (Family, Scratch) {
    let f = families()
        .into_iter()
        .find(|f| f.name == name)
        .expect("a family of apart_testkit::soups");
    let dir = Scratch::new(&format!("winding-{name}"));
    write_off_dir(&f.assembly, &dir).unwrap();
    (f, dir)
}

fn load_one_part_per_file(dir: &std::path::Path) -> Loaded {
    let opts = LoadOptions {
        split_bodies: false,
        ..LoadOptions::default()
    };
    load(dir, &opts).unwrap()
}

/// (a) and (b) through the library: the part is a valid solid made by the winding
/// path, and its volume, the sum of its convex pieces' volumes, is the known one and
/// agrees with the Monte Carlo estimate of the soup with its caps.
fn check_solid(f: &Family, loaded: &Loaded) {
    assert!(loaded.is_valid(), "{}: {:#?}", f.name, loaded.problems);
    let grid = &loaded.assembly.grid;
    let part = loaded.assembly.part(f.part).expect("the defective part");
    assert!(
        loaded.problems.iter().any(|p| {
            p.part.as_deref() == Some(f.part)
                && p.severity == Severity::Warning
                && p.kind == ProblemKind::Repaired
                && (p.message.contains("winding") || p.message.contains("the solid they enclose"))
        }),
        "{}: no note of the winding path: {:#?}",
        f.name,
        loaded.problems
    );
    assert!(!part.pieces.is_empty(), "{}: no pieces", f.name);
    let (n, d) = f.case.volume;
    let known = Rational::from_i128(n, d);
    let sum = part
        .pieces
        .iter()
        .fold(Rational::zero(), |s, p| &s + &p.volume());
    assert_eq!(
        volume_in_units(&sum, grid),
        known,
        "{}: pieces' volume",
        f.name
    );
    assert_eq!(part.volume_units(grid), known, "{}: part's volume", f.name);
    let e = monte_carlo_volume(&f.case.closed(), 20_000, 2024);
    assert!(e.agrees(known.to_f64()), "{}: {e:?}", f.name);
}

/// (a) and (b) through the CLI: `apart check --json --one-part-per-file` exits 0, lists
/// the part with the known exact volume, and warns of the repair.
fn check_cli(f: &Family, dir: &std::path::Path) {
    let out = Command::new(env!("CARGO_BIN_EXE_apart"))
        .args(["check", "--json", "--quiet", "--one-part-per-file"])
        .arg(dir)
        .output()
        .unwrap();
    let v: Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "{}: not JSON ({e}): {}",
            f.name,
            String::from_utf8_lossy(&out.stderr)
        )
    });
    assert_eq!(out.status.code(), Some(0), "{}: {v:#}", f.name);
    let part = v["parts"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == f.part)
        .expect("the part in check's JSON");
    let text = part["volume"].as_str().expect("a known volume");
    let (num, den) = match text.split_once('/') {
        Some((a, b)) => (a.parse::<i128>().unwrap(), b.parse::<i128>().unwrap()),
        None => (text.parse::<i128>().unwrap(), 1),
    };
    let (n, d) = f.case.volume;
    assert_eq!(num * d, n * den, "{}: volume {text}", f.name);
    assert!(
        v["problems"].as_array().unwrap().iter().any(|p| {
            p["part"] == f.part
                && p["severity"] == "warning"
                && p["message"].as_str().is_some_and(|m| {
                    m.starts_with("repaired")
                        && (m.contains("winding") || m.contains("the solid they enclose"))
                })
        }),
        "{}: {v:#}",
        f.name
    );
}

/// (c) for a part resting on a plate: the part leaves through the open upper
/// hemisphere and never downwards, the plate never upwards; with the plate as base
/// the plan is one step, the part moving up, which the oracle confirms.
fn check_on_plate(f: &Family, loaded: &Loaded) {
    let (parts, p) = partition_checked(loaded);
    assert!(!p.interlocked, "{}", f.name);
    let part = index(&p, f.part);
    let plate = index(&p, "plate");
    assert!(
        p.solutions
            .iter()
            .any(|s| s.moving == [part] && s.cell == CellKind::Face && s.unit[2] > 0.0),
        "{}: the part does not leave upwards",
        f.name
    );
    for s in &p.solutions {
        let z = s.unit[2];
        if s.moving == [part] {
            assert!(z >= 0.0, "{}: {s:?}", f.name);
        } else if s.moving == [plate] {
            assert!(z <= 0.0, "{}: {s:?}", f.name);
        }
    }
    let regions = BlockingRegions::compute(&parts).unwrap();
    let plan = sequence(
        &regions,
        &SequenceOptions {
            base: Some(plate),
            ..SequenceOptions::default()
        },
    );
    assert!(plan.complete(), "{}: {:?}", f.name, plan.stuck);
    assert_eq!(plan.steps.len(), 1, "{}", f.name);
    let s = &plan.steps[0];
    assert_eq!(s.moving, [part]);
    assert!(s.unit[2] >= 0.0, "{}: {s:?}", f.name);
    assert!(
        oracle_free(&parts, &[part], &s.direction),
        "{}: {s:?}",
        f.name
    );
}

fn run_plated(name: &str) {
    let (f, dir) = written(name);
    let loaded = load_one_part_per_file(&dir);
    check_solid(&f, &loaded);
    check_cli(&f, &dir);
    check_on_plate(&f, &loaded);
}

#[test]
fn a_box_with_a_lidded_rim_of_doubled_back_faces_is_the_box_and_leaves_its_plate() {
    run_plated("folded-rim");
}

#[test]
fn a_box_with_a_rim_folded_to_a_nearly_planar_loop_is_the_box_and_leaves_its_plate() {
    run_plated("warped-rim");
}

#[test]
fn a_box_with_an_open_rim_of_doubled_back_faces_is_the_box_not_the_box_less_a_frustum() {
    run_plated("folded-rim-open");
}

#[test]
fn a_gear_whose_flanks_cross_is_its_outline_and_leaves_its_plate() {
    run_plated("gear");
}

#[test]
fn a_fillet_folded_over_itself_loses_its_pocket_and_leaves_its_plate() {
    run_plated("folded-fillet");
}

#[test]
fn two_overlapping_shells_are_their_union_and_leave_their_plate() {
    run_plated("overlapping-shells");
}

#[test]
fn two_shells_crossing_in_general_position_are_their_union_and_leave_their_plate() {
    run_plated("crossing-shells");
}

#[test]
fn a_nut_on_a_thread_of_crossing_rings_with_open_seams_is_interlocked() {
    let (f, dir) = written("thread");
    let loaded = load_one_part_per_file(&dir);
    check_solid(&f, &loaded);
    check_cli(&f, &dir);
    let (parts, p) = partition_checked(&loaded);
    // Known answer: no translation separates the nut from the bolt.
    assert!(p.interlocked);
    assert!(p.solutions.is_empty(), "{:?}", p.solutions);
    let nut = index(&p, "nut");
    for d in [
        [0, 0, 1],
        [0, 0, -1],
        [1, 0, 0],
        [0, -1, 0],
        [1, 1, 5],
        [-1, 2, -9],
    ] {
        let d = Vec3::new(d[0], d[1], d[2]);
        assert!(!oracle_free(&parts, &[nut], &d), "{d:?}");
    }
    let regions = BlockingRegions::compute(&parts).unwrap();
    let plan = sequence(&regions, &SequenceOptions::default());
    assert!(!plan.complete());
    assert!(plan.steps.is_empty());
}
