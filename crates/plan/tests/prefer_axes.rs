//! `prefer_axes`: whenever one of ±x, ±y, ±z is free for a step's moving set, the step
//! moves along an axis. Checked on the tray of cubes and on a generated family of box
//! stacks (guillotine partitions, some boxes cut in two wedges), with the brute-force
//! oracle deciding independently, for each step and each of the six axes, whether the
//! moving set is free along it. The explanation each step carries (`Step::choice`) is
//! checked against the same oracle and against the ranking order.

mod common;

use apart_assembly::{load, LoadOptions};
use apart_kernel::Vec3;
use apart_pieces::Polytope;
use apart_plan::sequence::{Choice, Criterion, Keys};
use apart_plan::{parts_of, sequence, BlockingRegions, Part, SequenceOptions, Step};
use common::oracle::Oracle;
use common::{check_plan, cuboid, hull, part};
use std::path::PathBuf;

fn axes() -> Vec<Vec3> {
    (0..6)
        .map(|k| {
            let mut c = [0i64; 3];
            c[k % 3] = if k < 3 { 1 } else { -1 };
            Vec3::from_i64(c)
        })
        .collect()
}

/// True for a positive multiple of ±x, ±y or ±z, read off the coordinates.
fn along_axis(d: &Vec3) -> bool {
    let c = d.approx();
    c.iter().filter(|x| **x == 0.0).count() == 2
}

/// The axes along which the step's moving set is free, by the oracle.
fn free_axes(oracle: &Oracle, step: &Step) -> Vec<Vec3> {
    let rest = step.staying();
    axes()
        .into_iter()
        .filter(|d| oracle.free(&step.moving, &rest, d))
        .collect()
}

/// What a plan made with `prefer_axes` must satisfy; returns how many steps had a free
/// axis.
fn check_axes(parts: &[Part], opts: &SequenceOptions) -> usize {
    let regions = BlockingRegions::compute(parts).unwrap();
    let plan = sequence(&regions, opts);
    check_plan(parts, &plan);
    assert!(plan.complete(), "{:?}", plan.stuck);
    let oracle = Oracle::new(parts);
    let mut with_axis = 0;
    for step in &plan.steps {
        let free = free_axes(&oracle, step);
        if !free.is_empty() {
            with_axis += 1;
            assert!(
                along_axis(&step.direction),
                "{:?} is free along {:?}, but the step moves along {:?}",
                step.moving,
                free,
                step.direction.to_strings()
            );
        }
        check_choice(parts, &oracle, opts, step);
    }
    with_axis
}

/// The explanation agrees with the step, and the runner-up is a real candidate that
/// loses on the key it names.
fn check_choice(parts: &[Part], oracle: &Oracle, opts: &SequenceOptions, step: &Step) {
    let Choice {
        keys,
        candidates,
        runner_up,
    } = &step.choice;
    assert!(*candidates >= 1);
    assert_eq!(keys.cell, step.cell);
    assert_eq!(keys.single, step.moving.len() == 1);
    assert_eq!(keys.parts, step.moving.len());
    assert_eq!(keys.axis, along_axis(&step.direction));
    assert_eq!(keys.clearance_deg, step.clearance_deg);
    assert_eq!(keys.connected.is_some(), opts.prefer_connected);
    let Some(r) = runner_up else {
        assert_eq!(*candidates, 1);
        return;
    };
    assert!(*candidates >= 2);
    let others: Vec<usize> = step
        .subassembly
        .iter()
        .copied()
        .filter(|k| !r.moving.contains(k))
        .collect();
    assert!(
        oracle.free(&r.moving, &others, &r.direction),
        "the runner-up {r:?} is not free"
    );
    if let Some(b) = opts.base {
        assert!(!r.moving.contains(&b) || !step.subassembly.contains(&b));
    }
    assert_eq!(r.keys.axis, along_axis(&r.direction));
    assert_eq!(r.keys.parts, r.moving.len());
    // Every key before the deciding one is equal; the deciding one favours the step.
    let rank = |k: &Keys| {
        [
            opts.prefer_connected && k.connected == Some(false),
            opts.prefer_single && !k.single,
            opts.prefer_axes && !k.axis,
        ]
    };
    let (a, b) = (rank(keys), rank(&r.keys));
    let decided = match r.lost_on {
        Criterion::Connected => 0,
        Criterion::Single => 1,
        Criterion::Axis => 2,
        _ => 3,
    };
    for k in 0..decided.min(3) {
        assert_eq!(a[k], b[k], "{:?} vs {r:?} ({})", step.choice, parts.len());
    }
    if decided < 3 {
        assert!(!a[decided] && b[decided], "{:?} vs {r:?}", step.choice);
    } else {
        assert_eq!(a, b);
        match r.lost_on {
            Criterion::Cell => assert!(keys.cell < r.keys.cell),
            Criterion::Clearance => {
                assert_eq!(keys.cell, r.keys.cell);
                assert!(keys.clearance_deg > r.keys.clearance_deg);
            }
            Criterion::FewerParts => assert!(keys.parts < r.keys.parts),
            _ => {}
        }
    }
}

fn example(name: &str) -> Vec<Part> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    let loaded = load(&dir, &LoadOptions::default()).unwrap();
    assert!(loaded.is_valid(), "{name}: {:?}", loaded.problems);
    parts_of(&loaded.assembly).unwrap().to_vec()
}

#[test]
fn tray_of_cubes_every_cube_leaves_along_an_axis() {
    let parts = example("tray-of-cubes");
    let tray = parts.iter().position(|p| p.name == "tray").unwrap();
    let opts = SequenceOptions {
        prefer_axes: true,
        base: Some(tray),
        ..Default::default()
    };
    // Every cube can rise straight up once the cubes above it are gone.
    assert_eq!(check_axes(&parts, &opts), 19);
    for single in [false, true] {
        for connected in [false, true] {
            let opts = SequenceOptions {
                prefer_single: single,
                prefer_connected: connected,
                ..opts.clone()
            };
            check_axes(&parts, &opts);
        }
    }
}

#[test]
fn without_the_preference_the_tray_has_oblique_steps_where_an_axis_is_free() {
    // The preference changes something: the default plan takes the widest face, which
    // is oblique for a cube held in a corner although +z is free (so the test above is
    // not vacuous).
    let parts = example("tray-of-cubes");
    let tray = parts.iter().position(|p| p.name == "tray").unwrap();
    let regions = BlockingRegions::compute(&parts).unwrap();
    let plan = sequence(
        &regions,
        &SequenceOptions {
            base: Some(tray),
            ..Default::default()
        },
    );
    let oracle = Oracle::new(&parts);
    let oblique = plan
        .steps
        .iter()
        .filter(|s| !free_axes(&oracle, s).is_empty() && !along_axis(&s.direction))
        .count();
    assert!(oblique > 0);
}

/// A small deterministic generator (xorshift64*).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// Box `[lo, hi]` cut by the plane through its diagonal in the (a, b) coordinate plane
/// into two wedges (triangular prisms).
fn wedges(lo: [i64; 3], hi: [i64; 3], a: usize, b: usize) -> [Polytope; 2] {
    let c = 3 - a - b;
    let at = |x: i64, y: i64, z: i64| {
        let mut p = [0i64; 3];
        p[a] = x;
        p[b] = y;
        p[c] = z;
        p
    };
    let (x0, x1, y0, y1) = (lo[a], hi[a], lo[b], hi[b]);
    let mut w0 = Vec::new();
    let mut w1 = Vec::new();
    for z in [lo[c], hi[c]] {
        w0.extend([at(x0, y0, z), at(x1, y0, z), at(x0, y1, z)]);
        w1.extend([at(x1, y0, z), at(x1, y1, z), at(x0, y1, z)]);
    }
    [hull(&w0), hull(&w1)]
}

/// A guillotine partition of `[lo, hi]` into about `k` convex parts: boxes, and now and
/// then a box cut in two wedges. Every subset of such parts comes apart by translations
/// (the cut tree separates it), so every plan is complete.
fn guillotine(rng: &mut Rng, lo: [i64; 3], hi: [i64; 3], k: usize, out: &mut Vec<Polytope>) {
    let splittable: Vec<usize> = (0..3).filter(|&a| hi[a] - lo[a] >= 2).collect();
    if k <= 1 || splittable.is_empty() {
        if k >= 2 && rng.below(2) == 0 {
            let a = rng.below(3) as usize;
            let b = (a + 1 + rng.below(2) as usize) % 3;
            out.extend(wedges(lo, hi, a, b));
        } else {
            out.push(cuboid(lo, hi));
        }
        return;
    }
    let a = splittable[rng.below(splittable.len() as u64) as usize];
    let cut = lo[a] + 1 + rng.below((hi[a] - lo[a] - 1) as u64) as i64;
    let k1 = 1 + rng.below(k as u64 - 1) as usize;
    let (mut hi1, mut lo2) = (hi, lo);
    hi1[a] = cut;
    lo2[a] = cut;
    guillotine(rng, lo, hi1, k1, out);
    guillotine(rng, lo2, hi, k - k1, out);
}

#[test]
fn generated_stacks_of_boxes_and_wedges_move_along_axes_whenever_one_is_free() {
    let mut steps_with_axis = 0;
    let mut oblique_by_default = 0;
    for seed in 1..=40u64 {
        let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
        let k = 3 + rng.below(5) as usize;
        let mut pieces = Vec::new();
        guillotine(&mut rng, [0, 0, 0], [6, 6, 6], k, &mut pieces);
        let parts: Vec<Part> = pieces
            .into_iter()
            .enumerate()
            .map(|(i, p)| part(&format!("p{i}"), vec![p]))
            .collect();
        let base = (rng.below(3) == 0).then(|| rng.below(parts.len() as u64) as usize);
        let opts = SequenceOptions {
            prefer_axes: true,
            prefer_single: rng.below(2) == 0,
            prefer_connected: rng.below(3) == 0,
            base,
            ..Default::default()
        };
        steps_with_axis += check_axes(&parts, &opts);
        // The same assembly without the preference, for the count below.
        let regions = BlockingRegions::compute(&parts).unwrap();
        let plain = sequence(
            &regions,
            &SequenceOptions {
                prefer_axes: false,
                ..opts.clone()
            },
        );
        let oracle = Oracle::new(&parts);
        oblique_by_default += plain
            .steps
            .iter()
            .filter(|s| !free_axes(&oracle, s).is_empty() && !along_axis(&s.direction))
            .count();
    }
    assert!(steps_with_axis > 100, "{steps_with_axis}");
    // The family exercises the preference: without it, some steps with a free axis
    // take an oblique direction.
    assert!(oblique_by_default > 0);
}

#[test]
fn a_wedge_in_a_v_groove_has_no_free_axis_and_keeps_its_oblique_direction() {
    // The wedge (0,0) (2,1) (1,2) sits in a V groove whose sides lie on the lines
    // through (0,0) and (2,1), and through (0,0) and (1,2), between a floor (z <= 0) and
    // a roof (z >= 1) of the same holder. It can leave only along the directions
    // d = (x, y, 0) with -x + 2y >= 0 and 2x - y >= 0: a cone strictly inside the first
    // quadrant, with no axis in it.
    let prism = |pts: &[[i64; 2]]| {
        let v: Vec<[i64; 3]> = [0, 1]
            .iter()
            .flat_map(|&z| pts.iter().map(move |p| [p[0], p[1], z]))
            .collect();
        hull(&v)
    };
    let holder = vec![
        prism(&[[0, -1], [2, -1], [2, 1], [0, 0]]),
        prism(&[[-1, 0], [0, 0], [1, 2], [-1, 2]]),
        cuboid([-2, -2, -1], [3, 3, 0]),
        cuboid([-2, -2, 1], [3, 3, 2]),
    ];
    let parts = vec![
        part("holder", holder),
        part("wedge", vec![prism(&[[0, 0], [2, 1], [1, 2]])]),
    ];
    let regions = BlockingRegions::compute(&parts).unwrap();
    let opts = SequenceOptions {
        prefer_axes: true,
        base: Some(0),
        ..Default::default()
    };
    let plan = sequence(&regions, &opts);
    check_plan(&parts, &plan);
    assert_eq!(plan.steps.len(), 1);
    let step = &plan.steps[0];
    assert_eq!(step.moving, vec![1]);
    let oracle = Oracle::new(&parts);
    assert!(free_axes(&oracle, step).is_empty());
    assert!(!along_axis(&step.direction));
    let c = step.direction.approx();
    assert!(c[2] == 0.0 && -c[0] + 2.0 * c[1] >= 0.0 && 2.0 * c[0] - c[1] >= 0.0);
    check_choice(&parts, &oracle, &opts, step);
}
