//! The disassembly plans of the assemblies shipped under `examples/`, loaded from disk.
//!
//! Every step of every plan is re-checked by the brute-force oracle (`check_plan`); on top
//! of that each example has an expected plan read off its geometry by hand: which part
//! must come off first, along which exact direction, and which cell kind the direction
//! lies in.

mod common;

use apart_assembly::{load, LoadOptions};
use apart_kernel::Vec3;
use apart_plan::{
    partition_pieces, parts_of, sequence, BlockingRegions, CellKind, Options, Part, Sequence,
    SequenceOptions, Step,
};
use common::check_plan;
use std::path::PathBuf;

fn example(name: &str) -> Vec<Part> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    let loaded = load(&dir, &LoadOptions::default()).unwrap();
    assert!(loaded.is_valid(), "{name}: {:?}", loaded.problems);
    parts_of(&loaded.assembly).unwrap().to_vec()
}

fn index(parts: &[Part], name: &str) -> usize {
    parts
        .iter()
        .position(|p| p.name == name)
        .unwrap_or_else(|| panic!("no part {name}"))
}

fn plan(parts: &[Part], opts: &SequenceOptions) -> Sequence {
    let regions = BlockingRegions::compute(parts).unwrap();
    let p = sequence(&regions, opts);
    check_plan(parts, &p);
    // Deterministic: the same input gives the same plan.
    assert_eq!(sequence(&regions, opts).steps, p.steps);
    p
}

/// The two sides of a step as sorted sets: (moving, staying).
fn sides(step: &Step) -> (Vec<usize>, Vec<usize>) {
    (step.moving.clone(), step.staying())
}

/// The step's direction as seen by `part`: unchanged when it moves, reversed when the
/// other side moves (relative motion is what the geometry fixes).
fn direction_of(step: &Step, part: usize) -> Vec3 {
    if step.moving.contains(&part) {
        step.direction.primitive()
    } else {
        step.direction.neg().primitive()
    }
}

#[test]
fn dovetail_cap_comes_off_first_then_the_tenon_slides_out_along_x() {
    let parts = example("dovetail-and-cap");
    let (slot, tenon, cap) = (
        index(&parts, "slot"),
        index(&parts, "tenon"),
        index(&parts, "cap"),
    );
    // With the cap on, the tenon is closed in: no solution moves it alone.
    let p = partition_pieces(&parts, &Options::default()).unwrap();
    assert!(p.solutions.iter().all(|s| s.moving != vec![tenon]));

    let plan = plan(&parts, &SequenceOptions::default());
    assert!(plan.complete());
    assert_eq!(plan.steps.len(), 2);
    let (m, r) = sides(&plan.steps[0]);
    assert!(
        (m == vec![cap] && r == vec![slot, tenon]) || (r == vec![cap] && m == vec![slot, tenon])
    );
    // The cap leaves through the open half-space beyond the slot's end: a face.
    assert_eq!(plan.steps[0].cell, CellKind::Face);
    assert!(direction_of(&plan.steps[0], cap).unit_f64()[0] > 0.0);
    // The dovetail locks y and z; the end wall of the slot blocks −x: exactly +x.
    let second = &plan.steps[1];
    assert_eq!(second.cell, CellKind::Vertex);
    assert_eq!(direction_of(second, tenon), Vec3::new(1, 0, 0));
}

#[test]
fn hinge_bolt_leaves_along_its_axis_then_the_tongue_slides() {
    let parts = example("hinge");
    let (bracket, tongue, bolt) = (
        index(&parts, "bracket"),
        index(&parts, "tongue"),
        index(&parts, "bolt"),
    );
    let plan = plan(&parts, &SequenceOptions::default());
    assert!(plan.complete());
    assert_eq!(plan.steps.len(), 2);
    // The shaft fills the holes and the head rests on the −y cheek: exactly −y, isolated.
    let first = &plan.steps[0];
    let (m, r) = sides(first);
    assert!((m == vec![bolt]) || (r == vec![bolt]), "{first:?}");
    assert_eq!(first.cell, CellKind::Vertex);
    assert_eq!(direction_of(first, bolt), Vec3::new(0, -1, 0));
    // The tongue touches both cheeks: it slides in the plane y = 0 (an edge cell).
    let second = &plan.steps[1];
    let (m, r) = sides(second);
    assert_eq!(
        {
            let mut both = vec![m, r];
            both.sort();
            both
        },
        vec![vec![bracket], vec![tongue]]
    );
    assert_eq!(second.cell, CellKind::Edge);
    assert_eq!(second.direction.to_strings()[1], "0");
}

#[test]
fn tray_of_cubes_lid_first_then_every_cube_upwards_top_layer_first() {
    let parts = example("tray-of-cubes");
    assert_eq!(parts.len(), 20);
    let tray = index(&parts, "tray");
    let lid = index(&parts, "lid");

    // Default preferences: complete, one part at a time, the lid first through the open
    // upper half-space.
    let plan_default = plan(&parts, &SequenceOptions::default());
    assert!(plan_default.complete());
    assert_eq!(plan_default.steps.len(), 19);
    let first = &plan_default.steps[0];
    assert!(first.moving == vec![lid] || sides(first).1 == vec![lid]);
    assert_eq!(first.cell, CellKind::Face);
    // Nothing lies above the lid: it is free in the whole closed upper half-space, so the
    // deepest direction is straight up with a quarter turn of clearance.
    assert_eq!(direction_of(first, lid), Vec3::new(0, 0, 1));
    assert!((first.clearance_deg - 90.0).abs() < 1e-9, "{first:?}");

    // With the tray as the base: every cube comes out upwards, a top cube before the
    // bottom cube under it.
    let based = plan(
        &parts,
        &SequenceOptions {
            base: Some(tray),
            ..Default::default()
        },
    );
    assert!(based.complete());
    assert_eq!(based.steps.len(), 19);
    assert_eq!(based.steps[0].moving, vec![lid]);
    let mut removed = Vec::new();
    for step in &based.steps {
        assert_eq!(step.moving.len(), 1, "{step:?}");
        assert!(step.unit[2] > 0.0, "{step:?} does not go up");
        removed.push(parts[step.moving[0]].name.clone());
    }
    for x in 1..=3 {
        for y in 1..=3 {
            let at = |z: i32| {
                removed
                    .iter()
                    .position(|n| *n == format!("cube_{x}{y}{z}"))
                    .unwrap()
            };
            assert!(at(2) < at(1), "cube_{x}{y}2 must leave before cube_{x}{y}1");
        }
    }
}

#[test]
fn linked_rings_are_interlocked() {
    let parts = example("linked-rings");
    let plan = plan(&parts, &SequenceOptions::default());
    assert!(plan.steps.is_empty());
    assert_eq!(plan.stuck, vec![vec![0, 1]]);
}

#[test]
fn ring_and_cone_rings_leave_along_the_axis_first() {
    let parts = example("ring-and-cone");
    let cone = index(&parts, "cone");
    let plan = plan(&parts, &SequenceOptions::default());
    assert!(plan.complete());
    assert_eq!(plan.steps.len(), 2);
    // The upper ring is the only part free at first (the lower one rests under it on the
    // cone), and it leaves upwards through a face around +z.
    let first = &plan.steps[0];
    let upper = index(&parts, "ring_upper");
    let (m, r) = sides(first);
    assert!(m == vec![upper] || r == vec![upper], "{first:?}");
    assert_eq!(first.cell, CellKind::Face);
    assert!(direction_of(first, upper).unit_f64()[2] > 0.9);
    // Then the lower ring and the cone split along the axis.
    let second = &plan.steps[1];
    assert!(second.subassembly.contains(&cone));
    assert!(direction_of(second, cone).unit_f64()[2].abs() > 0.9);
}
