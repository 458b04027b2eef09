//! One direction without the arrangement (`dbg_along`) and the quick first solution,
//! checked against the full motion space (today's computation), the brute-force LP
//! oracle and the generators' known answers.

mod common;

use apart_assembly::{load, LoadOptions};
use apart_kernel::Vec3;
use apart_plan::{
    dbg_along, dbg_at, partition_first, parts_of, BlockingRegions, CellKind, DirectionQuery,
    MotionSpace, Part,
};
use apart_testkit::curved;
use apart_testkit::Scratch;
use std::path::{Path, PathBuf};

fn example(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

/// The shipped examples' folder names, sorted.
fn example_names() -> Vec<String> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.path().is_dir())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn load_parts(dir: &Path) -> Vec<Part> {
    try_load(dir).unwrap_or_else(|| panic!("{dir:?} is not a valid assembly"))
}

/// The parts of a valid assembly (`None` for the examples of other commands, such as
/// the overlapping sheet-metal parts of `stack`).
fn try_load(dir: &Path) -> Option<Vec<Part>> {
    let loaded = load(dir, &LoadOptions::default()).unwrap();
    loaded
        .is_valid()
        .then(|| parts_of(&loaded.assembly).unwrap().to_vec())
}

fn generated(name: &str, parts: &[curved::NamedSoup]) -> Vec<Part> {
    let dir = Scratch::new(&format!("along-{name}"));
    curved::write_off_dir(parts, &dir).unwrap();
    load_parts(&dir)
}

/// The 26 directions of {-1,0,1}^3, some random ones, and every vertex and an interior
/// point of every edge of the full motion space (where the cell kind is not a face).
fn directions(ms: &MotionSpace) -> Vec<Vec3> {
    let mut out: Vec<Vec3> = (0..27)
        .map(|i| Vec3::new(i % 3 - 1, (i / 3) % 3 - 1, i / 9 - 1))
        .filter(|d| !d.is_zero())
        .collect();
    let mut rng = apart_testkit::solids::Lcg(99);
    let mut next = |m: i64| rng.below(m as u64) as i64;
    for _ in 0..20 {
        let d = Vec3::new(next(11) - 5, next(11) - 5, next(11) - 5);
        if !d.is_zero() {
            out.push(d);
        }
    }
    let arr = ms.arrangement();
    for v in ms.real_vertices().take(20) {
        out.push(arr.vertices()[v].point.clone());
    }
    for cell in ms.edge_cells().iter().take(20) {
        out.push(arr.edge_arc(cell[0]).interior_point().primitive());
    }
    out
}

/// `dbg_along` agrees with the full computation (blocking graph from the pair regions,
/// cell kind from the overlay) and with the LP oracle at every test direction.
fn check_against_full(name: &str, parts: &[Part]) {
    let regions = BlockingRegions::compute(parts).unwrap();
    let all: Vec<usize> = (0..parts.len()).collect();
    let ms = MotionSpace::build(&regions, &all);
    let oracle = common::oracle::Oracle::new(parts);
    let q = DirectionQuery::new(parts).unwrap();
    // The LP oracle solves one program per piece pair and direction: on assemblies of
    // many piece pairs (the ring and cone's tessellated curves) it checks four
    // directions spread over the list, the full motion space checks them all.
    let pairs: usize = (0..parts.len())
        .flat_map(|i| (i + 1..parts.len()).map(move |j| (i, j)))
        .map(|(i, j)| parts[i].pieces.len() * parts[j].pieces.len())
        .sum();
    let dirs = directions(&ms);
    let stride = if pairs > 500 {
        (dirs.len() / 4).max(1)
    } else {
        1
    };
    for (k, d) in dirs.into_iter().enumerate() {
        let got = q.answer(&d).unwrap();
        let want = dbg_at(&regions, &all, &d);
        assert_eq!(
            got.dbg.arcs(),
            want.arcs(),
            "{name} at {d:?}: blocking graph"
        );
        if k % stride == 0 {
            assert_eq!(
                got.dbg.arcs(),
                oracle.dbg(&d).arcs(),
                "{name} at {d:?}: oracle"
            );
        }
        assert_eq!(got.moving, want.minimal_moving_sets(), "{name} at {d:?}");
        assert_eq!(got.cell, ms.locate(&d).0, "{name} at {d:?}: cell kind");
    }
}

#[test]
fn shipped_examples_agree_with_the_full_motion_space() {
    let names = example_names();
    assert!(names.len() >= 5);
    for name in names {
        if let Some(parts) = try_load(&example(&name)) {
            check_against_full(&name, &parts);
        }
    }
}

#[test]
fn built_assemblies_agree_with_the_full_motion_space() {
    for (name, parts) in [
        ("split star", common::split_star()),
        ("dovetail", common::dovetail()),
        ("peg", common::peg_in_hole()),
        ("rings", common::linked_rings()),
        ("row", common::cubes_in_a_row(4)),
    ] {
        check_against_full(name, &parts);
    }
}

#[test]
fn curved_assemblies_agree_and_have_their_known_answers() {
    let plug = generated("plug", &curved::plug_and_socket(20 * 12 - 8));
    check_against_full("plug", &plug);
    let pin = generated("pin", &curved::pin_in_hole(10, 10, 0.0));
    check_against_full("pin", &pin);
    let nut = generated("nut", &curved::nut_on_bolt(8, 1));
    check_against_full("nut", &nut);

    // Known answers: the plug (part 0) leaves along +z only, as an isolated direction.
    let up = dbg_along(&plug, &Vec3::new(0, 0, 1)).unwrap();
    assert_eq!(up.cell, CellKind::Vertex);
    assert_eq!(up.moving, vec![vec![0]]);
    let down = dbg_along(&plug, &Vec3::new(0, 0, -1)).unwrap();
    assert_eq!(down.moving, vec![vec![1]]);
    for d in [[1, 0, 0], [1, 1, 5], [0, 1, 40]] {
        assert!(dbg_along(&plug, &Vec3::from_i64(d))
            .unwrap()
            .moving
            .is_empty());
    }
    let pin_up = dbg_along(&pin, &Vec3::new(0, 0, 1)).unwrap();
    assert_eq!(
        (pin_up.cell, pin_up.moving),
        (CellKind::Vertex, vec![vec![1]])
    );
    // The nut and bolt are interlocked: nothing moves along the axis either.
    for d in [[0, 0, 1], [0, 0, -1], [1, 0, 0]] {
        assert!(dbg_along(&nut, &Vec3::from_i64(d))
            .unwrap()
            .moving
            .is_empty());
    }
}

/// The first solution separates (oracle), its set is a minimal moving set there, and its
/// kind is the cell the full motion space puts the direction in.
fn check_first(name: &str, parts: &[Part]) {
    let r = partition_first(parts).unwrap();
    let regions = BlockingRegions::compute(parts).unwrap();
    let all: Vec<usize> = (0..parts.len()).collect();
    let full = apart_plan::partition_subset(&regions, &all, &Default::default()).0;
    assert_eq!(r.interlocked, full.interlocked, "{name}");
    let Some(s) = r.solutions.first() else {
        return;
    };
    let oracle = common::oracle::Oracle::new(parts);
    let rest: Vec<usize> = all
        .iter()
        .copied()
        .filter(|k| !s.moving.contains(k))
        .collect();
    assert!(oracle.free(&s.moving, &rest, &s.direction), "{name}: {s:?}");
    assert!(
        oracle
            .dbg(&s.direction)
            .minimal_moving_sets()
            .contains(&s.moving),
        "{name}: {s:?}"
    );
    let ms = MotionSpace::build(&regions, &all);
    assert_eq!(ms.locate(&s.direction).0, s.cell, "{name}: {s:?}");
    if s.cell == CellKind::Face {
        // The clearance is the distance to the blocked directions: no face solution of the
        // same set in the full answer can be farther from them than the largest one.
        assert!(s.clearance_deg > 0.0, "{name}: {s:?}");
        let most = full
            .solutions
            .iter()
            .filter(|f| f.cell == CellKind::Face)
            .map(|f| f.clearance_deg)
            .fold(0.0, f64::max);
        assert!(s.clearance_deg <= most + 1e-6, "{name}: {s:?} vs {most}");
        // And it is that distance: every piece pair's polygon summed and measured.
        let rest: Vec<usize> = (0..parts.len()).filter(|k| !s.moving.contains(k)).collect();
        let want = common::exhaustive_clearance(parts, &s.moving, &rest, &s.direction).to_degrees();
        assert!(
            (s.clearance_deg - want).abs() <= 1e-6 * want.max(1.0),
            "{name}: {s:?}, exhaustively {want}"
        );
    }
}

#[test]
fn first_solutions_are_verified() {
    let names = example_names();
    for name in names {
        if let Some(parts) = try_load(&example(&name)) {
            check_first(&name, &parts);
        }
    }
    for (name, parts) in [
        ("split star", common::split_star()),
        ("rings", common::linked_rings()),
        ("dovetail", common::dovetail()),
        (
            "plug",
            generated("plug-first", &curved::plug_and_socket(20 * 12 - 8)),
        ),
        ("nut", generated("nut-first", &curved::nut_on_bolt(8, 1))),
    ] {
        check_first(name, &parts);
    }
}
