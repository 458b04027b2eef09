//! Real-CAD defect families, end to end: files written by the generators of
//! `apart-testkit` (each with a known answer), loaded with repair on, planned, and every
//! solution re-checked by the brute-force oracle (an exact linear program over two
//! pieces' facet inequalities) on the pieces the planner used — the shrunk pieces when a
//! tolerance applies.

use apart::assembly::{load, LoadOptions, Loaded, Tolerance};
use apart::kernel::Vec3;
use apart::plan::{partition, parts_of, CellKind, Options, Part, Partitioning};
use apart_testkit::curved::{self, NamedSoup};
use apart_testkit::defects;
use apart_testkit::Scratch;
use apart_testkit::Soup;

mod common;
use common::{index, oracle_free, partition_checked};

/// A fresh folder for one test's files.
fn folder(tag: &str) -> Scratch {
    Scratch::new(&format!("realcad-{}", tag))
}

fn write_off(dir: &std::path::Path, name: &str, soup: &Soup) {
    std::fs::write(dir.join(format!("{name}.off")), soup.to_off()).unwrap();
}

fn load_with(dir: &std::path::Path, tolerance: Tolerance) -> Loaded {
    let opts = LoadOptions {
        tolerance,
        ..LoadOptions::default()
    };
    load(dir, &opts).unwrap()
}

/// Whether part `k` alone has a face solution (an open region of directions) whose
/// direction points along `+e_axis`.
fn leaves_through_a_face(p: &Partitioning, k: usize, axis: usize) -> bool {
    p.solutions
        .iter()
        .any(|s| s.moving == [k] && s.cell == CellKind::Face && s.unit[axis] > 0.0)
}

#[test]
fn t_junction_seams_are_split_and_the_lid_leaves_upwards() {
    let dir = folder("seams");
    let div = [[2, 3], [3, 2], [1, 2], [2, 1], [3, 3], [2, 2]];
    let e = [6, 6, 6];
    write_off(&dir, "box", &defects::seamed_box(e, div));
    write_off(
        &dir,
        "lid",
        &defects::box_soup([0.0, 0.0, 6.0], [6.0, 6.0, 8.0]),
    );
    let strict = load(
        &dir,
        &LoadOptions {
            repair: false,
            ..LoadOptions::default()
        },
    )
    .unwrap();
    assert!(!strict.is_valid(), "seams are defects without repair");
    let loaded = load_with(&dir, Tolerance::None);
    let box_repairs = loaded.repairs.iter().find(|r| r.parts == ["box"]).unwrap();
    assert_eq!(
        box_repairs.report.tjunctions,
        defects::seamed_box_tjunctions(&div)
    );
    let box_part = loaded.assembly.part("box").unwrap();
    assert_eq!(box_part.volume_units(&loaded.assembly.grid).to_f64(), 216.0);
    let (_, p) = partition_checked(&loaded);
    let lid = index(&p, "lid");
    // Known answer: the lid leaves through the open upper hemisphere, and no solution
    // moves it downwards.
    assert!(leaves_through_a_face(&p, lid, 2));
    for s in &p.solutions {
        let z = s.unit[2];
        assert!(if s.moving == [lid] {
            z >= 0.0
        } else {
            z <= 0.0
        });
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn float32_binary_stl_far_from_the_origin_loads_and_plans() {
    let dir = folder("f32");
    let div = [[2, 2], [1, 1], [2, 1], [1, 2], [2, 2], [3, 1]];
    let e = [20, 30, 10];
    let base = defects::float32_rounded(&defects::decimal_seamed_box(e, div));
    let (lo, hi) = defects::decimal_seamed_box_corners(e);
    let lid = defects::float32_rounded(&defects::box_soup(
        [lo[0], lo[1], hi[2]],
        [hi[0], hi[1], hi[2] + 0.5],
    ));
    for (name, soup) in [("base", &base), ("lid", &lid)] {
        let mut bytes = Vec::new();
        soup.write_binary_stl(&mut bytes).unwrap();
        std::fs::write(dir.join(format!("{name}.stl")), bytes).unwrap();
    }
    let loaded = load_with(&dir, Tolerance::None);
    let (_, p) = partition_checked(&loaded);
    let lid = index(&p, "lid");
    assert!(leaves_through_a_face(&p, lid, 2));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn duplicated_and_flipped_faces_are_repaired_and_counted() {
    let dir = folder("dupflip");
    write_off(&dir, "a", &defects::duplicated_faces([2, 2, 2], &[0, 5, 7]));
    write_off(
        &dir,
        "b",
        &defects::flipped_faces([2, 2, 2], &[1, 4]).translated([2.0, 0.0, 0.0]),
    );
    let loaded = load_with(&dir, Tolerance::None);
    let rep = |n: &str| {
        loaded
            .repairs
            .iter()
            .find(|r| r.parts == [n])
            .unwrap()
            .report
            .clone()
    };
    assert_eq!(rep("a").duplicate_faces, 3);
    assert_eq!(rep("b").flipped_faces, 2);
    let (_, p) = partition_checked(&loaded);
    let b = index(&p, "b");
    // b sits beside a along +x: it leaves through the open +x hemisphere.
    assert!(leaves_through_a_face(&p, b, 0));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_lid_overlapping_by_a_micrometre_needs_and_gets_a_stated_tolerance() {
    let dir = folder("lid");
    write_off(&dir, "box", &defects::box_soup([0.0; 3], [1.0, 1.0, 1.0]));
    write_off(
        &dir,
        "lid",
        &defects::box_soup([0.0, 0.0, 1.0 - 1e-6], [1.0, 1.0, 1.2]),
    );
    let plain = load_with(&dir, Tolerance::None);
    let err = plain
        .problems
        .iter()
        .find(|p| p.is_error())
        .expect("an overlap");
    // The depth is the snapped overlap: 1e-6 within a grid step of 2^-30.
    let depth: f64 = err
        .message
        .split("by a depth of ")
        .nth(1)
        .and_then(|t| t.split(':').next())
        .and_then(|t| t.trim().parse().ok())
        .expect("a depth in the message");
    assert!((depth - 1e-6).abs() < 2e-9, "{}", err.message);
    let loaded = load_with(&dir, Tolerance::Fixed(1e-6));
    let (_, p) = partition_checked(&loaded);
    let lid = index(&p, "lid");
    assert!(leaves_through_a_face(&p, lid, 2));
    let t = loaded.assembly.tolerance.as_ref().unwrap();
    assert_eq!(t.eps, 1e-6);
    assert_eq!(t.accepted_overlaps, 1);
    let _ = std::fs::remove_dir_all(&dir);
}

fn write_parts(dir: &std::path::Path, parts: &[NamedSoup]) {
    curved::write_off_dir(parts, dir).unwrap();
}

#[test]
fn pins_in_holes_of_other_tessellations_leave_along_their_axis_under_auto_tolerance() {
    for (n, m, phase) in [(40, 48, 0.013), (48, 48, std::f64::consts::PI / 48.0)] {
        let dir = folder(&format!("pin{n}-{m}"));
        write_parts(&dir, &curved::pin_in_hole(n, m, phase));
        let depth = curved::pin_in_hole_depth(n, m, phase, curved::PIN_RADIUS);
        assert!(depth > 0.0);
        let plain = load_with(&dir, Tolerance::None);
        assert!(!plain.is_valid(), "the tessellations interpenetrate");
        let loaded = load_with(&dir, Tolerance::Auto);
        let t = loaded.assembly.tolerance.clone().expect("auto applied");
        assert!(
            t.eps >= depth / 2.0 && t.eps <= depth,
            "{} vs {depth}",
            t.eps
        );
        let (_, p) = partition_checked(&loaded);
        let pin = index(&p, "pin");
        // Known answer: the pin leaves along +z. Under the tolerance the isolated
        // direction widens into a small cone around +z; nothing else moves the pin.
        let ups: Vec<_> = p.solutions.iter().filter(|s| s.moving == [pin]).collect();
        assert!(!ups.is_empty());
        for s in ups {
            assert!(s.unit[2] > 0.999, "{:?}", s.unit);
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

#[test]
fn a_nut_on_a_bolt_with_a_ring_thread_is_interlocked() {
    let dir = folder("nut");
    write_parts(&dir, &curved::nut_on_bolt(12, 2));
    let loaded = load_with(&dir, Tolerance::None);
    let (parts, p) = partition_checked(&loaded);
    assert!(p.interlocked);
    // Independently: the oracle blocks the nut along both axis directions.
    let nut = index(&p, "nut");
    for d in [Vec3::new(0, 0, 1), Vec3::new(0, 0, -1)] {
        assert!(!oracle_free(&parts, &[nut], &d));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn faces_that_cross_become_the_solid_they_wind_around_even_a_fold() {
    // One file, two boxes crossing each other, read as one part: its union (volume
    // 4³ + 2·2·2 = 72, by hand), beside a box it touches at x = 6.
    let dir = folder("crossing");
    let mut cross = defects::box_soup([0.0; 3], [4.0; 3]);
    cross.append(&defects::box_soup([2.0, 1.0, 1.0], [6.0, 3.0, 3.0]));
    write_off(&dir, "cross", &cross);
    write_off(
        &dir,
        "side",
        &defects::box_soup([6.0, 0.0, 0.0], [8.0, 4.0, 4.0]),
    );
    let opts = LoadOptions {
        split_bodies: false,
        ..LoadOptions::default()
    };
    let loaded = load(&dir, &opts).unwrap();
    assert!(loaded
        .problems
        .iter()
        .any(|p| p.message.contains("winding number at least 1")));
    let part = loaded.assembly.part("cross").unwrap();
    assert_eq!(part.volume_units(&loaded.assembly.grid).to_f64(), 72.0);
    let (_, p) = partition_checked(&loaded);
    let side = index(&p, "side");
    assert!(leaves_through_a_face(&p, side, 0));
    // Split into bodies (the default), the two boxes still make one part: each lies
    // deep inside the other, far beyond any tolerance.
    let split = load_with(&dir, Tolerance::None);
    assert!(split.is_valid(), "{:#?}", split.problems);
    let part = split.assembly.part("cross").unwrap();
    assert_eq!(part.volume_units(&split.assembly.grid).to_f64(), 72.0);
    let _ = std::fs::remove_dir_all(&dir);

    // A corner pulled through the opposite face turns part of the box inside out
    // (winding number -1 there): the part is where it winds at least once, whose
    // volume the independent Monte Carlo oracle estimates.
    let dir = folder("fold");
    let fold = defects::self_crossing_fold();
    write_off(&dir, "fold", &fold);
    let loaded = load_with(&dir, Tolerance::None);
    assert!(loaded.is_valid(), "{:#?}", loaded.problems);
    let part = loaded.assembly.part("fold").unwrap();
    let w = part.winding.as_ref().expect("made by the winding rule");
    assert!(w.lowest_winding < 0, "{w:?}");
    let surface = apart_testkit::winding::TriSoup {
        points: fold.vertices.iter().map(|v| v.map(|c| c as i64)).collect(),
        triangles: fold
            .faces
            .iter()
            .flat_map(|f| (1..f.len() - 1).map(move |i| [f[0], f[i], f[i + 1]]))
            .collect(),
    };
    let e = apart_testkit::winding::monte_carlo_volume(&surface, 20_000, 7);
    let v = part.volume_units(&loaded.assembly.grid).to_f64();
    assert!(e.agrees(v), "{v} against {e:?}");
    assert!(
        v < 1000.0,
        "the inside-out corner is not part of the solid: {v}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_bolted_joint_of_five_differently_tessellated_parts_comes_apart_along_its_axis() {
    use apart::plan::{sequence, sequence_first, BlockingRegions, Progress, SequenceOptions};
    let dir = folder("joint");
    write_parts(
        &dir,
        &apart_testkit::joints::bolted_joint([24, 20, 28, 16, 32]),
    );
    assert!(!load_with(&dir, Tolerance::None).is_valid());
    let loaded = load_with(&dir, Tolerance::Auto);
    assert!(loaded.is_valid(), "{:#?}", loaded.problems);
    let parts = parts_of(&loaded.assembly).unwrap();
    let regions = BlockingRegions::compute(parts).unwrap();
    let base = parts.iter().position(|p| p.name == "bolt");
    let plan = sequence(
        &regions,
        &SequenceOptions {
            base,
            ..SequenceOptions::default()
        },
    );
    assert!(plan.complete());
    // Known answer: with the bolt fixed, the others leave upwards one at a time, top
    // first; every step checked by the oracle against the rest of its subassembly.
    let order: Vec<&str> = plan
        .steps
        .iter()
        .map(|s| {
            assert_eq!(s.moving.len(), 1, "one part at a time");
            assert!(s.unit[2] > 0.999, "{:?}", s.unit);
            let rest: Vec<Part> = s.subassembly.iter().map(|&k| parts[k].clone()).collect();
            let local = s
                .subassembly
                .iter()
                .position(|&k| k == s.moving[0])
                .unwrap();
            assert!(oracle_free(&rest, &[local], &s.direction));
            parts[s.moving[0]].name.as_str()
        })
        .collect();
    assert_eq!(order, ["nut", "washer", "plate_b", "plate_a"]);

    // The plan along likely directions (`sequence --first`) finds the same: the axis is
    // the first candidate, and no subassembly needs the full search. Without the base
    // the bolt may leave too; each step is re-checked by the oracle.
    for base in [base, None] {
        let first = sequence_first(
            parts,
            &SequenceOptions {
                base,
                ..SequenceOptions::default()
            },
            &Progress::new(),
        )
        .unwrap();
        assert!(first.complete());
        assert_eq!(first.full_searches, 0);
        for s in &first.steps {
            let rest: Vec<Part> = s.subassembly.iter().map(|&k| parts[k].clone()).collect();
            let local: Vec<usize> = s
                .moving
                .iter()
                .map(|m| s.subassembly.iter().position(|k| k == m).unwrap())
                .collect();
            assert!(oracle_free(&rest, &local, &s.direction), "{s:?}");
            assert!(s.unit[2].abs() > 0.999, "{:?}", s.unit);
        }
        if base.is_some() {
            let order: Vec<&str> = first
                .steps
                .iter()
                .map(|s| parts[s.moving[0]].name.as_str())
                .collect();
            assert_eq!(order, ["nut", "washer", "plate_b", "plate_a"]);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_rack_of_pins_in_blocks_under_a_plate_comes_apart_as_its_geometry_says() {
    // 2 x 2 pins in blocks that touch their neighbours along a vertical edge, under a
    // plate resting on every pin; no tolerance. The oracle checks the faces and the
    // isolated directions (the many sliding arcs would take it a minute).
    let dir = folder("rack");
    write_parts(&dir, &curved::pin_rack(2, 12));
    let loaded = load_with(&dir, Tolerance::None);
    assert!(loaded.is_valid(), "{:#?}", loaded.problems);
    let parts = parts_of(&loaded.assembly).unwrap().to_vec();
    let p = partition(&loaded.assembly, &Options::default()).unwrap();
    for s in p.solutions.iter().filter(|s| s.cell != CellKind::Edge) {
        assert!(oracle_free(&parts, &s.moving, &s.direction), "{s:?}");
    }
    let name = |k: &usize| p.names[*k].as_str();
    let mut sets: Vec<Vec<&str>> = p
        .sets
        .iter()
        .map(|s| s.moving.iter().map(name).collect())
        .collect();
    sets.sort();
    // Known answer (see `pin_rack`): the plate, each block alone, each block with its
    // pin (every block is at a corner); no pin alone, nothing bigger.
    let mut want: Vec<Vec<String>> = vec![vec!["plate".to_string()]];
    for (i, j) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
        want.push(vec![format!("block_{i}_{j}")]);
        want.push(vec![format!("block_{i}_{j}"), format!("pin_{i}_{j}")]);
    }
    want.sort();
    assert_eq!(sets, want);
    let plate = index(&p, "plate");
    assert!(leaves_through_a_face(&p, plate, 2));
    for (i, j) in [(0i64, 0i64), (0, 1), (1, 0), (1, 1)] {
        let block = index(&p, &format!("block_{i}_{j}"));
        let pin = index(&p, &format!("pin_{i}_{j}"));
        // Alone, the block slides off its pin straight down, and only so.
        for s in p.solutions.iter().filter(|s| s.moving == [block]) {
            assert_eq!(s.cell, CellKind::Vertex, "{s:?}");
            assert_eq!(s.direction, Vec3::new(0, 0, -1));
        }
        // With its pin it leaves downwards and away from the rack's centre.
        let out = [2 * i - 1, 2 * j - 1];
        assert!(p.solutions.iter().any(|s| s.moving == [block, pin]
            && s.cell == CellKind::Face
            && s.unit[2] < 0.0
            && (0..2).all(|k| s.unit[k] * out[k] as f64 > 0.0)));
    }
}

/// A 3 x 3 rack of 12-segment pins in blocks under a plate, sequenced by the local rules
/// (and by the default ranking): every step is checked by the oracle against the rest of
/// its subassembly, the plan is complete, the plate leaves first through the upper
/// hemisphere, and blocks leave with their pins as touching pairs.
#[test]
fn a_rack_is_sequenced_step_by_step_by_the_local_rules() {
    use apart::plan::{sequence_parts, Progress, Ranking, Rule, SequenceOptions};
    let dir = folder("rack-sequence");
    write_parts(&dir, &curved::pin_rack(3, 12));
    let loaded = load_with(&dir, Tolerance::None);
    assert!(loaded.is_valid(), "{:#?}", loaded.problems);
    let parts = parts_of(&loaded.assembly).unwrap().to_vec();
    for ranking in [Ranking::Local, Ranking::Auto] {
        let opts = SequenceOptions {
            ranking,
            ..SequenceOptions::default()
        };
        let plan = sequence_parts(&parts, &opts, &Progress::new(), &mut |_| {}).unwrap();
        assert!(plan.complete(), "{ranking:?}: {:?}", plan.stuck);
        for s in &plan.steps {
            let sub: Vec<Part> = s.subassembly.iter().map(|&k| parts[k].clone()).collect();
            let moving: Vec<usize> = (0..sub.len())
                .filter(|&k| s.moving.contains(&s.subassembly[k]))
                .collect();
            assert!(
                oracle_free(&sub, &moving, &s.direction),
                "{ranking:?}: {s:?}"
            );
        }
        let first = &plan.steps[0];
        assert_eq!(plan.names[first.moving[0]], "plate");
        assert_eq!((first.moving.len(), first.cell), (1, CellKind::Face));
        assert!(first.unit[2] > 0.0);
        if ranking == Ranking::Local {
            assert_eq!(first.rule, Rule::Single);
            assert_eq!(plan.local.full_searches, 0);
            let pairs: Vec<&apart::plan::Step> =
                plan.steps.iter().filter(|s| s.rule == Rule::Pair).collect();
            assert!(!pairs.is_empty());
            for s in pairs {
                let mut names: Vec<&str> =
                    s.moving.iter().map(|&k| plan.names[k].as_str()).collect();
                names.sort();
                assert!(names[0].starts_with("block_") && names[1].starts_with("pin_"));
                assert_eq!(names[0]["block_".len()..], names[1]["pin_".len()..]);
            }
        }
    }
}
