//! Paper 004 fig. 2: 121 unit cubes on a floor, for three weights of eq. (1).

mod common;

use apart_kernel::Rational;
use apart_stack::planner::{stack, StackOptions, StackPlan};
use common::parts::cube;
use common::{assert_no_interference, assert_stable, height, q, qfrac};

fn cubes(w: Rational) -> StackPlan {
    // A 16 x 16 floor centred on the origin: room for all 121 cubes in one layer.
    let floor = [q(-8), q(-8), q(8), q(8)];
    let mut opts = StackOptions::new(121, w, floor, q(200));
    opts.dtheta_deg = 90.0; // the four turns of a cube are one shape: tried once
    let plan = stack(&cube(1), &opts).unwrap();
    assert!(plan.complete);
    assert_eq!(plan.placements.len(), 121);
    assert_eq!(plan.stats.orientations, 1);
    assert_no_interference(&plan);
    assert_stable(&plan, &q(0));
    assert_eq!(plan.stack_height, height(&plan, &q(0)));
    plan
}

/// Cubes per layer, bottom first.
fn layers(plan: &StackPlan) -> Vec<usize> {
    let mut count = Vec::new();
    for p in &plan.placements {
        let z = p.translation[2].to_f64() as usize;
        if count.len() <= z {
            count.resize(z + 1, 0);
        }
        count[z] += 1;
    }
    count
}

#[test]
fn weight_zero_gives_one_flat_layer() {
    let plan = cubes(q(0));
    assert_eq!(plan.stack_height, q(1));
    assert_eq!(layers(&plan), vec![121]);
}

#[test]
fn weight_one_gives_a_single_column() {
    let plan = cubes(q(1));
    assert_eq!(plan.stack_height, q(121));
    // Every cube right above the first.
    let t0 = &plan.placements[0].translation;
    for p in &plan.placements {
        assert_eq!(p.translation[..2], t0[..2]);
    }
}

#[test]
fn intermediate_weight_gives_a_pyramid() {
    let plan = cubes(qfrac(1, 2));
    let h = plan.stack_height.clone();
    assert!(h > q(1) && h < q(121), "height {h}");
    // Pyramid-like: no layer holds more cubes than the one below.
    let l = layers(&plan);
    assert!(l.windows(2).all(|w| w[1] <= w[0]), "layers {l:?}");
    println!("w = 1/2: height {h}, layers {l:?}");
}
