//! Nesting emerges for the channel and the triangle part (paper 004 figs. 18 and 19):
//! fifteen parts stacked with w = 1/2 on a floor only half again as large as one part's
//! footprint reach a stack height far below fifteen part heights, with no interference
//! and every part stable (both checked independently of the planner).

mod common;

use apart_stack::part::PartModel;
use apart_stack::planner::{stack, StackOptions};
use common::parts::{channel, triangle_part};
use common::{assert_no_interference, assert_stable, floor_around, height, q, qfrac};

/// Stacks fifteen copies and returns stack height / (15 × part height).
fn nested_ratio(part: &PartModel) -> f64 {
    let e = part
        .orient(&apart_stack::orientation::Orientation::IDENTITY)
        .extent;
    let part_height = &e.max[2] - &e.min[2];
    let floor = floor_around(part, 3, 2);
    let mut opts = StackOptions::new(15, qfrac(1, 2), floor, q(1000));
    opts.dtheta_deg = 90.0;
    let plan = stack(part, &opts).unwrap();
    assert!(
        plan.complete,
        "{}: only {} placed",
        part.name,
        plan.placements.len()
    );
    assert_no_interference(&plan);
    assert_stable(&plan, &q(0));
    let h = height(&plan, &q(0));
    assert_eq!(h.to_f64(), plan.stack_height.to_f64());
    // Nested: most parts start below the top of the part placed before them.
    let nested = plan
        .placements
        .windows(2)
        .filter(|w| w[1].translation[2] < &w[0].translation[2] + &part_height)
        .count();
    assert!(
        nested >= 10,
        "{}: only {nested} nested placements",
        part.name
    );
    let ratio = h.to_f64() / (15.0 * part_height.to_f64());
    println!(
        "{}: stack height {} for 15 parts of height {}: ratio {ratio:.3}",
        part.name, h, part_height
    );
    ratio
}

#[test]
fn channels_nest() {
    let r = nested_ratio(&channel());
    assert!(r < 0.25, "ratio {r}");
}

#[test]
fn triangle_parts_nest() {
    let r = nested_ratio(&triangle_part());
    assert!(r < 0.25, "ratio {r}");
}
