//! Partial c-space obstacles give the same best cost as the complete c-space for the
//! same orientation (paper 004 §V-B), on random scenes; and the best configuration is
//! free and no free grid point is cheaper (an independent brute force).

use apart_kernel::{Aabb, Rational};
use apart_pieces::interference::interiors_disjoint;
use apart_pieces::Polytope;
use apart_stack::orientation::{orientations, Base};
use apart_stack::part::PartModel;
use apart_stack::partial::{best_full, place, Cost, Moving, PlaceOptions, Region};
use apart_stack::scene::Scene;
use apart_stack::stability::placed_pieces;
use proptest::prelude::*;

fn boxp(lo: [i64; 3], size: [i64; 3]) -> Polytope {
    Polytope::cuboid(lo, [lo[0] + size[0], lo[1] + size[1], lo[2] + size[2]]).unwrap()
}

/// Fixed boxes (overlapping ones dropped) and a moving L of two boxes.
fn scene_of(fixed: &[([i64; 3], [i64; 3])]) -> (Scene, Vec<Polytope>) {
    let mut kept: Vec<Polytope> = Vec::new();
    for (lo, s) in fixed {
        let b = boxp(*lo, *s);
        if kept.iter().all(|k| interiors_disjoint(k, &b)) {
            kept.push(b);
        }
    }
    let mut scene = Scene::new();
    for b in &kept {
        scene.add_fixed_part(std::slice::from_ref(b));
    }
    (scene, kept)
}

fn moving_l(a: i64, b: i64) -> PartModel {
    PartModel::from_pieces(
        "L",
        vec![boxp([0, 0, 0], [a, 2, 1]), boxp([0, 2, 0], [1, b, 1])],
    )
    .unwrap()
}

fn q(v: i64) -> Rational {
    Rational::from(v)
}

fn qfrac(n: i64, d: i64) -> Rational {
    Rational::from_i128(n.into(), d.into())
}

fn opts(target: [Rational; 3], w: Option<Rational>) -> PlaceOptions {
    PlaceOptions {
        region: Region::Container(Aabb {
            min: [q(-4), q(-4), q(0)],
            max: [q(16), q(16), q(12)],
        }),
        cost: match w {
            None => Cost::Distance(target),
            Some(w) => Cost::Stacking {
                w,
                floor: [q(6), q(6), q(0)],
            },
        },
        clearance: None,
        extrapolate: true,
    }
}

fn free(moving: &Moving, o: usize, t: &[Rational; 3], fixed: &[Polytope]) -> bool {
    placed_pieces(&moving.oriented[o].pieces, t)
        .iter()
        .all(|a| fixed.iter().all(|b| interiors_disjoint(a, b)))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn partial_equals_full(
        fixed in prop::collection::vec(((0i64..10, 0i64..10, 0i64..4), (1i64..5, 1i64..5, 1i64..4)), 1..5),
        a in 1i64..4,
        b in 1i64..3,
        target in (0i64..24, 0i64..24, 0i64..8),
        weighted in any::<bool>(),
        turn in 0usize..4,
        clear in 0i64..3,
    ) {
        let fixed: Vec<([i64; 3], [i64; 3])> =
            fixed.iter().map(|((x, y, z), (u, v, w))| ([*x, *y, *z], [*u, *v, *w])).collect();
        let (scene, kept) = scene_of(&fixed);
        let all = orientations(30.0, &[Base::IDENTITY], 0.05);
        // One orientation: a multiple of 30 degrees (exact Pythagorean rotation).
        let moving = Moving::new(moving_l(a, b), &all[turn * 2..turn * 2 + 1], false);
        let t = [qfrac(target.0, 2), qfrac(target.1, 2), qfrac(target.2, 2)];
        let mut o = opts(t, weighted.then(|| qfrac(1, 3)));
        // A horizontal clearance of 0, 1/2 or 1 (grown obstacles).
        o.clearance = (clear > 0).then(|| qfrac(clear, 2));
        let partial = place(&scene, &moving, &o, 1).unwrap();
        let full = best_full(&scene, &moving, &o, 0).unwrap();
        match (partial.candidates.first(), full) {
            (Some(p), Some(f)) => {
                prop_assert_eq!(&p.cost, &f.cost);
                prop_assert!(free(&moving, 0, &p.translation, &kept));
                prop_assert!(free(&moving, 0, &f.translation, &kept));
                if clear > 0 {
                    // Kept apart horizontally: moved by the clearance along x or y, still free.
                    let c = qfrac(clear, 2);
                    for d in [[c.clone(), q(0)], [-&c, q(0)], [q(0), c.clone()], [q(0), -&c]] {
                        let moved = [&p.translation[0] + &d[0], &p.translation[1] + &d[1], p.translation[2].clone()];
                        prop_assert!(free(&moving, 0, &moved, &kept));
                    }
                }
            }
            (None, None) => {}
            (p, f) => prop_assert!(false, "partial {:?} full {:?}", p, f),
        }
    }
}

/// Brute force on a grid: every free grid translation costs at least the best found.
#[test]
fn no_free_grid_point_is_cheaper() {
    let fixed = [
        ([2, 2, 0], [4, 3, 2]),
        ([7, 1, 0], [2, 6, 3]),
        ([3, 6, 0], [3, 2, 1]),
        ([2, 2, 2], [2, 2, 2]),
    ];
    let (scene, kept) = scene_of(&fixed);
    let moving = Moving::new(
        moving_l(3, 2),
        &orientations(90.0, &[Base::IDENTITY], 0.05),
        false,
    );
    for target in [[4, 4, 0], [8, 3, 1], [5, 7, 0], [3, 3, 2]] {
        let t = target.map(q);
        let o = opts(t.clone(), None);
        let best = place(&scene, &moving, &o, 1).unwrap().candidates[0].clone();
        assert!(free(&moving, best.orientation, &best.translation, &kept));
        // Every translation on the half-integer grid keeping the part in the container.
        for (k, part) in moving.oriented.iter().enumerate() {
            let e = &part.extent;
            for x in -16..=40 {
                for y in -16..=40 {
                    for z in 0..=24 {
                        let p = [qfrac(x, 2), qfrac(y, 2), qfrac(z, 2)];
                        let lo = [q(-4), q(-4), q(0)];
                        let hi = [q(16), q(16), q(12)];
                        if (0..3).any(|i| &e.min[i] + &p[i] < lo[i] || &e.max[i] + &p[i] > hi[i]) {
                            continue;
                        }
                        let d = [&p[0] - &t[0], &p[1] - &t[1], &p[2] - &t[2]];
                        let cost = &(&(&d[0] * &d[0]) + &(&d[1] * &d[1])) + &(&d[2] * &d[2]);
                        if cost < best.cost {
                            assert!(
                                !free(&moving, k, &p, &kept),
                                "free {p:?} (orientation {k}) costs {cost} < {}",
                                best.cost
                            );
                        }
                    }
                }
            }
        }
    }
}
