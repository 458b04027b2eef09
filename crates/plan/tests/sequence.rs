//! Disassembly sequences: every step re-checked by the brute-force oracle.

mod common;

use apart_kernel::Vec3;
use apart_plan::{
    sequence, sequence_first, BlockingRegions, CellKind, Growth, MotionSpace, Part, Progress,
    Sequence, SequenceOptions,
};
use common::check_plan;
use proptest::prelude::*;

fn plan(parts: &[Part], opts: &SequenceOptions) -> Sequence {
    let regions = BlockingRegions::compute(parts).unwrap();
    let p = sequence(&regions, opts);
    check_plan(parts, &p);
    p
}

#[test]
fn split_star_comes_apart_completely() {
    let p = plan(&common::split_star(), &SequenceOptions::default());
    assert!(p.complete());
    assert_eq!(p.steps.len(), 5);
    // The first split can only be one of the eight isolated directions.
    let first = &p.steps[0];
    assert_eq!(first.cell, CellKind::Vertex);
    assert_eq!(first.moving.len(), 3);
}

#[test]
fn linked_rings_are_stuck() {
    let p = plan(&common::linked_rings(), &SequenceOptions::default());
    assert!(p.steps.is_empty());
    assert_eq!(p.stuck, vec![vec![0, 1]]);
    assert!(!p.complete());
}

/// A 3 x 3 x 3 block of unit cubes: a corner cube is free exactly in the closed octant
/// facing away from the block, whose deepest direction is the diagonal, at angular
/// distance asin(1/sqrt 3) = 35.26 degrees from the octant's three bounding planes.
#[test]
fn a_corner_cube_of_a_block_leaves_along_the_diagonal() {
    let mut parts = Vec::new();
    for x in 0..3 {
        for y in 0..3 {
            for z in 0..3 {
                parts.push(common::part(
                    &format!("c{x}{y}{z}"),
                    vec![common::cuboid([x, y, z], [x + 1, y + 1, z + 1])],
                ));
            }
        }
    }
    let p = plan(&parts, &SequenceOptions::default());
    assert!(p.complete());
    let first = &p.steps[0];
    assert_eq!(first.moving.len(), 1);
    let k = first.moving[0] as i64;
    let (x, y, z) = (k / 9, k / 3 % 3, k % 3);
    assert!(
        [x, y, z].iter().all(|&c| c != 1),
        "a corner cube: {first:?}"
    );
    let away = |c: i64| if c == 0 { -1 } else { 1 };
    assert_eq!(
        first.direction.primitive(),
        Vec3::new(away(x), away(y), away(z))
    );
    let want = (1.0f64 / 3f64.sqrt()).asin().to_degrees();
    assert!((first.clearance_deg - want).abs() < 1e-9, "{first:?}");
}

#[test]
fn plans_are_deterministic() {
    let parts = common::split_star();
    let regions = BlockingRegions::compute(&parts).unwrap();
    let a = sequence(&regions, &SequenceOptions::default());
    let b = sequence(&regions, &SequenceOptions::default());
    assert_eq!(a.steps, b.steps);
}

#[test]
fn base_part_never_moves() {
    let parts = common::cubes_in_a_row(4);
    for (base, first) in (0..4).flat_map(|b| [(b, false), (b, true)]) {
        let opts = SequenceOptions {
            base: Some(base),
            ..Default::default()
        };
        // Both planners: ranked, and along the first likely direction.
        let p = if first {
            plan_first(&parts, &opts)
        } else {
            plan(&parts, &opts)
        };
        assert!(p.complete());
        assert!(
            p.steps.iter().all(|s| !s.moving.contains(&base)),
            "base {base}: {:?}",
            p.steps
        );
    }
}

#[test]
fn preferences() {
    // Single parts: cubes in a row come apart one at a time.
    let p = plan(
        &common::cubes_in_a_row(4),
        &SequenceOptions {
            prefer_single: true,
            ..Default::default()
        },
    );
    assert!(p.steps.iter().all(|s| s.moving.len() == 1));
    // Robust first: the stacked cubes split through the open hemisphere (a face).
    let p = plan(&common::stacked_cubes(), &SequenceOptions::default());
    assert_eq!(p.steps[0].cell, CellKind::Face);
    // Axes: the same split along ±z exactly.
    let p = plan(
        &common::stacked_cubes(),
        &SequenceOptions {
            prefer_axes: true,
            ..Default::default()
        },
    );
    let d = &p.steps[0].direction;
    assert!(
        *d == Vec3::new(0, 0, 1) || *d == Vec3::new(0, 0, -1),
        "{d:?}"
    );
    assert_eq!(p.steps[0].cell, CellKind::Face);
    assert!((p.steps[0].clearance_deg - 90.0).abs() < 1e-6);
    // Connected sides: in a row of four, taking out a middle cube would leave the rest
    // in two pieces; with the preference every side stays connected.
    let p = plan(
        &common::cubes_in_a_row(4),
        &SequenceOptions {
            prefer_connected: true,
            ..Default::default()
        },
    );
    for s in &p.steps {
        let rest: Vec<usize> = s.staying();
        for side in [&s.moving, &rest] {
            let (lo, hi) = (side.iter().min().unwrap(), side.iter().max().unwrap());
            assert_eq!(
                hi - lo + 1,
                side.len(),
                "side {side:?} of {s:?} is not contiguous"
            );
        }
    }
}

#[test]
fn growth_tolerance_of_a_peg_with_play() {
    // A peg of width 2 in a hole of width 4: 1 unit of play on each side.
    let block = vec![
        common::cuboid([-4, -4, 0], [4, 4, 1]),
        common::cuboid([-4, -4, 1], [-2, 4, 4]),
        common::cuboid([2, -4, 1], [4, 4, 4]),
        common::cuboid([-2, -4, 1], [2, -2, 4]),
        common::cuboid([-2, 2, 1], [2, 4, 4]),
    ];
    let peg = vec![common::cuboid([-1, -1, 1], [1, 1, 6])];
    let parts = vec![common::part("block", block), common::part("peg", peg)];
    let p = plan(
        &parts,
        &SequenceOptions {
            tolerance: true,
            prefer_axes: true,
            ..Default::default()
        },
    );
    let step = &p.steps[0];
    assert_eq!(
        step.direction.primitive().to_strings()[2].trim_start_matches('-'),
        "1"
    );
    // The peg rests on the floor (left at once going up): only the play limits growth.
    match step.tolerance {
        Some(Growth::Finite(s)) => assert!((s - 0.5).abs() < 1e-6, "{s}"),
        t => panic!("{t:?}"),
    }
    // Tight peg in a tight hole: zero tolerance; stacked cubes lifted apart: unbounded.
    let p = plan(
        &common::peg_in_hole(),
        &SequenceOptions {
            tolerance: true,
            ..Default::default()
        },
    );
    assert_eq!(p.steps[0].tolerance, Some(Growth::Finite(0.0)));
    let p = plan(
        &common::stacked_cubes(),
        &SequenceOptions {
            tolerance: true,
            ..Default::default()
        },
    );
    assert_eq!(p.steps[0].tolerance, Some(Growth::Unbounded));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Random box assemblies (several boxes per part, touching on a grid): every step is
    /// valid by the oracle.
    #[test]
    fn random_box_plans_are_valid(owners in prop::collection::vec(0usize..5, 12), k in 2usize..=4) {
        let mut parts: Vec<Vec<apart_pieces::Polytope>> = vec![Vec::new(); k];
        for (c, &o) in owners.iter().enumerate() {
            if o >= k {
                continue;
            }
            let (x, y, z) = ((c % 3) as i64, ((c / 3) % 2) as i64, (c / 6) as i64);
            parts[o].push(common::cuboid([x, y, z], [x + 1, y + 1, z + 1]));
        }
        let parts: Vec<Part> =
            parts.into_iter().enumerate().filter(|(_, p)| !p.is_empty()).map(|(i, p)| common::part(&format!("p{i}"), p)).collect();
        prop_assume!(parts.len() >= 2);
        let regions = BlockingRegions::compute(&parts).unwrap();
        let p = sequence(&regions, &SequenceOptions::default());
        check_plan(&parts, &p);
    }
}

/// A step keeps, when asked, exactly what partitioning its subassembly lists, so that a
/// picture of the step needs no second run of the planner; other steps keep nothing.
#[test]
fn kept_solutions_are_those_of_partitioning_the_step() {
    use apart_plan::{partition_subset, KeepSolutions};
    for parts in [
        common::split_star(),
        common::dovetail(),
        common::peg_in_hole(),
        common::cubes_in_a_row(4),
    ] {
        let regions = BlockingRegions::compute(&parts).unwrap();
        for prefer_axes in [false, true] {
            let opts = |keep_solutions| SequenceOptions {
                prefer_axes,
                keep_solutions,
                ..Default::default()
            };
            let plain = sequence(&regions, &opts(KeepSolutions::Nothing));
            let every = sequence(&regions, &opts(KeepSolutions::EveryStep));
            let one = sequence(&regions, &opts(KeepSolutions::Step(1)));
            assert!(!plain.steps.is_empty());
            for (k, step) in every.steps.iter().enumerate() {
                let (p, _) = partition_subset(&regions, &step.subassembly, &Default::default());
                assert_eq!(step.solutions.as_ref(), Some(&p.solutions));
                assert_eq!(plain.steps[k].solutions, None);
                assert_eq!(one.steps[k].solutions.is_some(), k == 1);
                // Keeping changes no choice.
                let bare = |s: &apart_plan::Step| apart_plan::Step {
                    solutions: None,
                    ..s.clone()
                };
                assert_eq!(bare(step), plain.steps[k]);
                assert_eq!(bare(&one.steps[k]), plain.steps[k]);
            }
        }
    }
}

/// [`sequence_first`], every step re-checked by the oracle (`check_plan`).
fn plan_first(parts: &[Part], opts: &SequenceOptions) -> Sequence {
    let p = sequence_first(parts, opts, &Progress::new()).unwrap();
    check_plan(parts, &p);
    p
}

/// Each step of a `sequence_first` plan lies in a cell of the kind it says, in the full
/// motion space of its subassembly, and moves a minimal moving set there (no proper
/// subset of it is free against the rest of the subassembly, by the oracle).
fn check_first_steps(name: &str, parts: &[Part], p: &Sequence) {
    let regions = BlockingRegions::compute(parts).unwrap();
    let oracle = common::oracle::Oracle::new(parts);
    for s in &p.steps {
        let ms = MotionSpace::build(&regions, &s.subassembly);
        assert_eq!(ms.locate(&s.direction).0, s.cell, "{name}: {s:?}");
        let rest: Vec<usize> = s.staying();
        if s.cell == CellKind::Face {
            // The distance to the nearest blocked direction, every piece pair summed (0
            // when the direction slides along a contact at the edge of its face).
            let want =
                common::exhaustive_clearance(parts, &s.moving, &rest, &s.direction).to_degrees();
            assert!(
                (s.clearance_deg - want).abs() <= 1e-6 * want.max(1.0),
                "{name}: {s:?}, exhaustively {want}"
            );
        } else {
            assert_eq!(s.clearance_deg, 0.0, "{name}: {s:?}");
        }
        for drop in &s.moving {
            let smaller: Vec<usize> = s.moving.iter().copied().filter(|k| k != drop).collect();
            if smaller.is_empty() {
                continue;
            }
            let others: Vec<usize> = s
                .subassembly
                .iter()
                .copied()
                .filter(|k| !smaller.contains(k))
                .collect();
            // A minimal moving set is a sink of the blocking graph with no smaller one in
            // it, so each of its proper subsets is blocked by the rest of the set.
            let free = oracle.free(&smaller, &others, &s.direction);
            assert!(!free, "{name}: {smaller:?} of {s:?} is free");
        }
    }
}

#[test]
fn first_plans_are_valid_and_as_complete_as_ranked_ones() {
    let cases: Vec<(&str, Vec<Part>)> = vec![
        ("split star", common::split_star()),
        ("linked rings", common::linked_rings()),
        ("dovetail", common::dovetail()),
        ("peg in hole", common::peg_in_hole()),
        ("stacked cubes", common::stacked_cubes()),
        ("cubes in a row", common::cubes_in_a_row(4)),
        ("block", common::lattice(2, 0)),
        ("channels", common::lattice(2, 1)),
        ("random boxes", common::random_box_parts(24, 5, 7)),
        ("random boxes 2", common::random_box_parts(30, 6, 11)),
    ];
    for (name, parts) in cases {
        let first = plan_first(&parts, &SequenceOptions::default());
        let ranked = plan(&parts, &SequenceOptions::default());
        assert_eq!(first.complete(), ranked.complete(), "{name}");
        assert_eq!(
            first.steps.len() + first.stuck.iter().map(|s| s.len() - 1).sum::<usize>(),
            parts.len() - 1,
            "{name}"
        );
        check_first_steps(name, &parts, &first);
    }
}

#[test]
fn first_plans_find_interlocked_subassemblies_by_the_full_search() {
    let p = plan_first(&common::linked_rings(), &SequenceOptions::default());
    assert!(p.steps.is_empty());
    assert_eq!(p.stuck, vec![vec![0, 1]]);
    assert_eq!(p.full_searches, 1);
}

/// A tetrahedron seated in a pocket of three walls, each a prism over one of its faces
/// at the apex: it can leave only inside the narrow cone of its edges from the apex
/// (about 7° around (3, 5, 7)), which holds no axis, no edge direction shared by four
/// pieces, and no normal of a touching plane (the faces' normals at the apex meet at
/// obtuse angles). So no likely direction frees anything and the full search must split
/// the pair; a far cube, part 0, makes the pair's indices global ones (1 and 2).
#[test]
fn first_plans_fall_back_to_the_full_search() {
    let (a, b, c, e) = ([0, 0, 0], [40, 44, 70], [28, 58, 65], [22, 48, 75]);
    let tet = common::hull(&[a, b, c, e]);
    let cross = |u: [i64; 3], v: [i64; 3]| {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    };
    let dot = |u: [i64; 3], v: [i64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    let mut walls = Vec::new();
    let mut normals = Vec::new();
    for (p, q, opposite) in [(b, c, e), (c, e, b), (e, b, c)] {
        let mut m = cross(p, q);
        if dot(m, opposite) > 0 {
            m = [-m[0], -m[1], -m[2]];
        }
        let up = |x: [i64; 3]| [x[0] + m[0], x[1] + m[1], x[2] + m[2]];
        walls.push(common::hull(&[a, p, q, up(a), up(p), up(q)]));
        normals.push(m);
    }
    // The premise: the outward normals at the apex pairwise obtuse.
    for i in 0..3 {
        assert!(dot(normals[i], normals[(i + 1) % 3]) < 0);
    }
    let parts = vec![
        common::part("far", vec![common::cuboid([-1000, 0, 0], [-990, 10, 10])]),
        common::part("walls", walls),
        common::part("tet", vec![tet]),
    ];
    let p = plan_first(&parts, &SequenceOptions::default());
    assert!(p.complete(), "{p:?}");
    assert_eq!(p.full_searches, 1);
    assert_eq!(p.steps[0].moving, vec![0]);
    let last = &p.steps[1];
    assert_eq!(last.subassembly, vec![1, 2]);
    assert_eq!(last.cell, CellKind::Face);
    // Whichever side moves, the tetrahedron's motion relative to the walls lies strictly
    // inside the cone of its edges (positive in all three edge-face normals' opposites).
    let d = last
        .direction
        .to_strings()
        .map(|s| s.parse::<i64>().unwrap());
    let d = if last.moving == vec![2] {
        d
    } else {
        d.map(|x| -x)
    };
    for m in &normals {
        assert!(dot(*m, d) < 0, "{last:?}");
    }
    check_first_steps("pocket", &parts, &p);
    // The ranked plan agrees that the pair splits only inside that cone.
    let ranked = plan(&parts, &SequenceOptions::default());
    assert!(ranked.complete());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// Random box assemblies: `sequence_first` is valid by the oracle and complete
    /// exactly when the ranked plan is.
    #[test]
    fn random_first_plans_match_the_ranked_ones(n in 6usize..20, k in 2usize..6, seed in 0u64..1000) {
        let parts = common::random_box_parts(n, k, seed);
        prop_assume!(parts.len() >= 2);
        let first = plan_first(&parts, &SequenceOptions::default());
        let ranked = plan(&parts, &SequenceOptions::default());
        prop_assert_eq!(first.complete(), ranked.complete());
        check_first_steps("random", &parts, &first);
    }
}
