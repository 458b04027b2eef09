//! The incremental sequence planner (`sequence_parts`): every step re-checked by the
//! brute-force oracle, its verdicts (split or interlocked) the same as the full
//! overlay's for every subassembly it meets, the full ranking reproduced step for step,
//! plans the same on one thread or two, and stopped runs keeping valid steps.

mod common;

use apart_kernel::Vec3;
use apart_plan::sequence::best_step;
use apart_plan::{
    sequence, sequence_parts, BlockingRegions, CellKind, Part, Progress, Ranking, Rule, Sequence,
    SequenceOptions,
};
use common::check_plan;
use proptest::prelude::*;

fn with(ranking: Ranking) -> SequenceOptions {
    SequenceOptions {
        ranking,
        ..Default::default()
    }
}

/// The plan of `parts` by `sequence_parts`, checked by the oracle.
fn plan(parts: &[Part], opts: &SequenceOptions) -> Sequence {
    let p = sequence_parts(parts, opts, &Progress::new(), &mut |_| {}).unwrap();
    check_plan(parts, &p);
    p
}

/// Every subassembly the plan split can be split by the full overlay, and every one it
/// calls interlocked cannot.
fn check_verdicts(parts: &[Part], p: &Sequence) {
    let regions = BlockingRegions::compute(parts).unwrap();
    let opts = SequenceOptions::default();
    for s in &p.steps {
        assert!(
            best_step(&regions, &s.subassembly, &opts).is_some(),
            "split by the local rules, not by the full overlay: {:?}",
            s.subassembly
        );
    }
    for s in &p.stuck {
        assert!(
            best_step(&regions, s, &opts).is_none(),
            "called interlocked, but the full overlay splits {s:?}"
        );
    }
}

/// Parts moved by `offset` (integer), renamed with a prefix.
fn shifted(parts: Vec<Part>, offset: [i64; 3], prefix: &str) -> Vec<Part> {
    parts
        .into_iter()
        .map(|p| {
            let pieces = p
                .pieces
                .iter()
                .map(|q| {
                    let pts: Vec<Vec3> = q
                        .vertices()
                        .iter()
                        .map(|v| v.add(&Vec3::from_i64(offset)))
                        .collect();
                    apart_pieces::Polytope::hull_of_points(&pts).unwrap()
                })
                .collect();
            common::part(&format!("{prefix}{}", p.name), pieces)
        })
        .collect()
}

#[test]
fn lattices_come_apart_by_the_local_rules() {
    for (n, gap) in [(3, 0), (4, 0), (3, 1), (5, 0)] {
        let parts = common::lattice(n, gap);
        let p = plan(&parts, &with(Ranking::Local));
        assert!(p.complete(), "{n} {gap}");
        // A touching block: every step moves one part, from its own free set.
        if gap == 0 {
            assert!(p.steps.iter().all(|s| s.moving.len() == 1), "{n}");
            assert!(p.local.full_searches == 0);
        }
        if n <= 3 {
            check_verdicts(&parts, &p);
        }
    }
}

/// The first step of a touching block: a corner cube along the diagonal of its free
/// octant, at the octant's deepest point (35.26° from its three planes).
#[test]
fn a_corner_cube_leaves_first_along_its_diagonal() {
    let parts = common::lattice(6, 0);
    let p = plan(&parts, &with(Ranking::Local));
    let first = &p.steps[0];
    assert_eq!(first.rule, Rule::Single);
    assert_eq!(first.cell, CellKind::Face);
    assert!((first.clearance_deg - 35.264).abs() < 0.01, "{first:?}");
    let d = first.direction.to_strings();
    let c: Vec<i64> = d
        .iter()
        .map(|x| x.parse::<i64>().unwrap().signum())
        .collect();
    assert!(c.iter().all(|&x| x != 0), "{d:?}");
}

/// A far part in the free directions of a part is found: a cube in the corner of a room
/// (floor and two walls, the base) is free in the octant facing away from the corner,
/// and far out along that octant's diagonal stands a closed cage around a block (the
/// two leave together, but neither alone). The cube leaves first, and must not leave
/// along the diagonal into the cage.
#[test]
fn far_parts_in_the_free_directions_block() {
    let slab = |lo: [i64; 3], hi: [i64; 3]| common::cuboid(lo, hi);
    let parts = vec![
        common::part("cube", vec![common::cuboid([0, 0, 0], [1, 1, 1])]),
        common::part(
            "room",
            vec![
                slab([-1, -1, -1], [3, 3, 0]),
                slab([-1, -1, 0], [0, 3, 3]),
                slab([0, -1, 0], [3, 0, 3]),
            ],
        ),
        common::part(
            "cage",
            vec![
                slab([38, 38, 38], [62, 62, 40]),
                slab([38, 38, 60], [62, 62, 62]),
                slab([38, 38, 40], [40, 62, 60]),
                slab([60, 38, 40], [62, 62, 60]),
                slab([40, 38, 40], [60, 40, 60]),
                slab([40, 60, 40], [60, 62, 60]),
            ],
        ),
        common::part("block", vec![common::cuboid([40, 40, 40], [60, 60, 60])]),
    ];
    let opts = SequenceOptions {
        base: Some(1),
        ..with(Ranking::Local)
    };
    let p = plan(&parts, &opts);
    // The block never leaves its closed cage.
    assert_eq!(p.stuck, vec![vec![2, 3]]);
    let first = &p.steps[0];
    assert_eq!(
        (first.moving.as_slice(), first.rule),
        (&[0][..], Rule::Single)
    );
    // Not along the diagonal: the cage's cap takes the octant's middle.
    assert_ne!(first.direction.primitive(), Vec3::new(1, 1, 1));
    check_verdicts(&parts, &p);
}

#[test]
fn interlocked_groups_are_found_among_free_parts() {
    // Two linked rings beside a loose lattice of cubes: the cubes all leave, the rings
    // are interlocked, and the full overlay agrees.
    let mut parts = shifted(common::linked_rings(), [0, 0, 0], "ring_");
    parts.extend(shifted(common::lattice(2, 0), [40, 0, 0], "cube_"));
    let p = plan(&parts, &with(Ranking::Local));
    assert_eq!(p.stuck.len(), 1);
    let rings: Vec<usize> = (0..2).collect();
    assert_eq!(p.stuck[0], rings);
    check_verdicts(&parts, &p);
}

#[test]
fn the_full_ranking_is_the_plan_of_sequence_with() {
    let cases = [
        common::split_star(),
        common::lattice(3, 0),
        common::random_box_parts(24, 6, 3),
        common::dovetail(),
        common::peg_in_hole(),
    ];
    for parts in cases {
        let regions = BlockingRegions::compute(&parts).unwrap();
        let old = sequence(&regions, &SequenceOptions::default());
        let new = plan(&parts, &with(Ranking::Full));
        assert_eq!(old.steps.len(), new.steps.len());
        for (a, b) in old.steps.iter().zip(&new.steps) {
            assert_eq!(
                (&a.subassembly, &a.moving, &a.direction, a.cell),
                (&b.subassembly, &b.moving, &b.direction, b.cell)
            );
            assert!((a.clearance_deg - b.clearance_deg).abs() < 1e-9);
        }
        assert_eq!(old.stuck, new.stuck);
    }
}

/// Small assemblies keep the full ranking under `Auto`: the shipped kinds of example
/// give the plans they always gave.
#[test]
fn small_assemblies_are_ranked_in_full_by_default() {
    for parts in [
        common::split_star(),
        common::lattice(2, 0),
        common::dovetail(),
        common::random_box_parts(24, 6, 3),
    ] {
        let regions = BlockingRegions::compute(&parts).unwrap();
        let old = sequence(&regions, &SequenceOptions::default());
        let new = plan(&parts, &SequenceOptions::default());
        assert!(new.steps.iter().all(|s| s.rule == Rule::Ranked));
        let key = |p: &Sequence| -> Vec<_> {
            p.steps
                .iter()
                .map(|s| (s.moving.clone(), s.direction.clone()))
                .collect()
        };
        assert_eq!(key(&old), key(&new));
    }
}

#[test]
fn plans_are_the_same_on_one_thread_or_two() {
    let cases = [
        common::lattice(5, 0),
        common::lattice(3, 1),
        common::random_box_parts(64, 8, 7),
    ];
    for parts in cases {
        let run = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| plan(&parts, &with(Ranking::Local)))
        };
        let (a, b) = (run(1), run(2));
        assert_eq!(a.steps, b.steps);
        assert_eq!(a.stuck, b.stuck);
    }
}

#[test]
fn steps_are_handed_over_as_they_are_found() {
    let parts = common::lattice(4, 0);
    let mut seen = Vec::new();
    let p = sequence_parts(&parts, &with(Ranking::Local), &Progress::new(), &mut |s| {
        seen.push(s.clone())
    })
    .unwrap();
    assert_eq!(seen, p.steps);
}

#[test]
fn a_stopped_plan_keeps_valid_steps() {
    let parts = common::lattice(5, 0);
    let progress = Progress::new();
    let flag = progress.clone();
    let mut count = 0;
    let p = sequence_parts(&parts, &with(Ranking::Local), &progress, &mut |_| {
        count += 1;
        if count == 10 {
            flag.request_stop();
        }
    })
    .unwrap();
    assert!(p.stopped && !p.complete());
    assert_eq!(p.steps.len(), 10);
    assert!(!p.pending.is_empty());
    check_plan(&parts, &p);
}

/// A budget that refuses every motion space stops the plan at the first subassembly
/// that needs one (the rings), with the cubes' steps kept.
#[test]
fn a_refused_motion_space_stops_the_plan() {
    let mut parts = shifted(common::linked_rings(), [0, 0, 0], "ring_");
    parts.extend(shifted(common::lattice(3, 0), [40, 0, 0], "cube_"));
    let progress = Progress::new().with_budget(|_, _| false);
    let p = sequence_parts(&parts, &with(Ranking::Local), &progress, &mut |_| {}).unwrap();
    assert!(p.stopped);
    assert!(p.stuck.is_empty());
    assert!(p.pending.iter().any(|s| s.contains(&0) && s.contains(&1)));
    check_plan(&parts, &p);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Random boxes linked into parts (paper 003's benchmark): the local plan is valid
    /// by the oracle, complete exactly when the full plan is, and its verdicts agree.
    #[test]
    fn random_box_plans_agree_with_the_full_overlay(n in 6usize..40, k in 2usize..9, seed in 0u64..1000) {
        prop_assume!(n >= k);
        let parts = common::random_box_parts(n, k, seed);
        let local = plan(&parts, &with(Ranking::Local));
        let regions = BlockingRegions::compute(&parts).unwrap();
        let full = sequence(&regions, &SequenceOptions::default());
        prop_assert_eq!(local.complete(), full.complete());
        check_verdicts(&parts, &local);
    }

    /// Unit cubes on a small grid owned by random parts (touching faces, coplanar faces,
    /// shared edges and corners: the degenerate cases), some left empty.
    #[test]
    fn degenerate_voxel_plans_agree_with_the_full_overlay(owners in prop::collection::vec(0usize..7, 27), k in 2usize..=6) {
        let mut pieces: Vec<Vec<apart_pieces::Polytope>> = vec![Vec::new(); k];
        for (c, &o) in owners.iter().enumerate() {
            if o >= k {
                continue;
            }
            let (x, y, z) = ((c % 3) as i64, ((c / 3) % 3) as i64, (c / 9) as i64);
            pieces[o].push(common::cuboid([x, y, z], [x + 1, y + 1, z + 1]));
        }
        let parts: Vec<Part> = pieces
            .into_iter()
            .enumerate()
            .filter(|(_, p)| !p.is_empty())
            .map(|(i, p)| common::part(&format!("p{i}"), p))
            .collect();
        prop_assume!(parts.len() >= 2);
        for ranking in [Ranking::Local, Ranking::Auto] {
            let p = plan(&parts, &with(ranking));
            check_verdicts(&parts, &p);
        }
    }
}
