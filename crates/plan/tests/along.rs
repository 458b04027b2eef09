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

/// Subsets of `0..n`: everything, and `count` random ones of at least two parts (each
/// part kept with probability 1/2), increasing.
fn random_subsets(n: usize, count: usize, seed: u64) -> Vec<Vec<usize>> {
    let mut rng = apart_testkit::solids::Lcg(seed);
    let mut out = vec![(0..n).collect::<Vec<usize>>()];
    while out.len() <= count {
        let sub: Vec<usize> = (0..n).filter(|_| rng.below(2) == 1).collect();
        if sub.len() >= 2 {
            out.push(sub);
        }
    }
    out
}

/// The coordinate axes, face and space diagonals (both signs) and random directions of
/// coordinates in `[-3, 3]`.
fn test_directions(seed: u64) -> Vec<Vec3> {
    let mut out: Vec<Vec3> = [
        [1, 0, 0],
        [0, 1, 0],
        [0, 0, 1],
        [1, 1, 0],
        [0, 1, -1],
        [1, 1, 1],
        [1, -1, 1],
    ]
    .into_iter()
    .flat_map(|d| [Vec3::from_i64(d), Vec3::from_i64(d.map(|c| -c))])
    .collect();
    let mut rng = apart_testkit::solids::Lcg(seed);
    while out.len() < 22 {
        let d = Vec3::new(rng.range(-3, 4), rng.range(-3, 4), rng.range(-3, 4));
        if !d.is_zero() {
            out.push(d);
        }
    }
    out
}

/// `answer_in` on subassemblies of generated assemblies (a block of touching unit cubes,
/// cubes a gap apart, random boxes, cubes cut into prisms; at axes, diagonals, random directions and vertices
/// and edges of the subassembly's motion space) looks only at the pairs of parts near
/// the line along `±d`: its blocking graph must still be the brute force's (every ordered pair of the
/// subassembly by the LP oracle, and by the pair regions' polygons), its moving sets
/// those of that graph, its cell kind the one the subassembly's full motion space gives,
/// and a face solution's clearance the distance to every piece pair's polygon.
#[test]
fn subassemblies_agree_with_brute_force() {
    // Cubes of side 2 each cut along a diagonal plane into two triangular prisms (pieces
    // that are no boxes: their sums are made), some a gap apart.
    let prisms = |n: i64| -> Vec<Part> {
        let mut parts = Vec::new();
        for x in 0..n {
            for y in 0..n {
                for z in 0..n {
                    let o = [2 * x + x / 2, 2 * y, 2 * z];
                    let prism = |corners: [[i64; 2]; 3]| {
                        let pts: Vec<[i64; 3]> = corners
                            .iter()
                            .flat_map(|&[u, v]| [0, 2].map(|w| [o[0] + u, o[1] + v, o[2] + w]))
                            .collect();
                        common::hull(&pts)
                    };
                    let pieces = vec![
                        prism([[0, 0], [2, 0], [0, 2]]),
                        prism([[2, 0], [2, 2], [0, 2]]),
                    ];
                    parts.push(common::part(&format!("p{x}{y}{z}"), pieces));
                }
            }
        }
        parts
    };
    let assemblies = [
        ("block", common::lattice(4, 0)),
        ("loose", common::lattice(3, 1)),
        ("boxes", common::random_box_parts(40, 12, 7)),
        ("prisms", prisms(3)),
    ];
    for (name, parts) in assemblies {
        let regions = BlockingRegions::compute(&parts).unwrap();
        let oracle = common::oracle::Oracle::new(&parts);
        let q = DirectionQuery::new(&parts).unwrap();
        let dirs = test_directions(parts.len() as u64);
        let mut faces = 0;
        let mut kinds = std::collections::BTreeSet::new();
        for (s, sub) in random_subsets(parts.len(), 3, 17).into_iter().enumerate() {
            let ms = MotionSpace::build(&regions, &sub);
            // And a few vertices and edges of the subassembly's motion space.
            let arr = ms.arrangement();
            let mut dirs = dirs.clone();
            dirs.extend(
                ms.real_vertices()
                    .take(8)
                    .map(|v| arr.vertices()[v].point.clone()),
            );
            dirs.extend(
                ms.edge_cells()
                    .iter()
                    .take(8)
                    .map(|c| arr.edge_arc(c[0]).interior_point().primitive()),
            );
            for d in &dirs {
                let got = q.answer_in(&sub, d).unwrap();
                let mut arcs = Vec::new();
                for (li, &i) in sub.iter().enumerate() {
                    for (lj, &j) in sub.iter().enumerate() {
                        if i != j && !oracle.free(&[i], &[j], d) {
                            arcs.push((li, lj));
                        }
                    }
                }
                let want = apart_plan::Dbg::new(sub.len(), arcs);
                let at = format!("{name}, subset {s} at {:?}", d.to_strings());
                assert_eq!(got.dbg.arcs(), want.arcs(), "{at}: oracle");
                assert_eq!(
                    got.dbg.arcs(),
                    dbg_at(&regions, &sub, d).arcs(),
                    "{at}: regions"
                );
                let moving: Vec<Vec<usize>> = want
                    .minimal_moving_sets()
                    .into_iter()
                    .map(|m| m.into_iter().map(|k| sub[k]).collect())
                    .collect();
                assert_eq!(got.moving, moving, "{at}: moving sets");
                assert_eq!(got.cell, ms.locate(d).0, "{at}: cell kind");
                kinds.insert(got.cell);
                if got.cell == CellKind::Face && !got.moving.is_empty() && faces < 6 {
                    faces += 1;
                    let m = &got.moving[0];
                    let rest: Vec<usize> = sub.iter().copied().filter(|k| !m.contains(k)).collect();
                    let c = q.clearance_against(d, m, &rest).unwrap();
                    let want = common::exhaustive_clearance(&parts, m, &rest, d);
                    assert!(
                        (c - want).abs() <= 1e-6 * want.max(1.0),
                        "{at}: clearance {c} vs {want}"
                    );
                }
            }
        }
        // The cases that matter were met: faces with a clearance, edges and vertices.
        println!("{name}: {kinds:?}, {faces} clearances");
        assert!(
            faces > 0 && kinds.len() == 3,
            "{name}: {kinds:?}, {faces} clearances"
        );
    }
}
