//! The stacker with a progress: counts of parts placed, monotone and ending at
//! the count; the same plan as without; and stopped by the flag, the parts placed so far,
//! each still free of interference and stable, marked as stopped.

mod common;

use apart_kernel::progress::{phases, Progress};
use apart_stack::planner::{stack, stack_with, StackOptions};
use common::parts::cube;
use common::{assert_no_interference, assert_stable, q, qfrac};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

type Log = Arc<Mutex<Vec<(&'static str, usize, usize)>>>;

fn options() -> StackOptions {
    let mut opts = StackOptions::new(12, qfrac(1, 2), [q(-4), q(-4), q(4), q(4)], q(20));
    opts.dtheta_deg = 90.0;
    opts
}

#[test]
fn stacking_reports_each_part_and_stops_when_asked() {
    let opts = options();
    let full = stack(&cube(1), &opts).unwrap();
    assert!(full.complete && !full.stopped && full.placements.len() == 12);

    let log: Log = Arc::default();
    let l = log.clone();
    let progress = Progress::with_callback(move |phase, done, total| {
        l.lock().unwrap().push((phase, done, total));
    });
    let plan = stack_with(&cube(1), &opts, &progress).unwrap();
    assert!(plan.complete && !plan.stopped);
    assert_eq!(plan.total_cost(), full.total_cost());
    let log = log.lock().unwrap().clone();
    let want: Vec<(&str, usize, usize)> = (0..=12).map(|k| (phases::STACKING, k, 12)).collect();
    assert_eq!(log, want);

    // Stopped by the callback once four parts are placed.
    let flag = Arc::new(AtomicBool::new(false));
    let raise = flag.clone();
    let progress = Progress::with_callback(move |_, done, _| {
        if done == 4 {
            raise.store(true, Ordering::Relaxed);
        }
    })
    .with_stop_flag(flag);
    let plan = stack_with(&cube(1), &opts, &progress).unwrap();
    assert!(plan.stopped && !plan.complete);
    assert_eq!(plan.placements.len(), 4);
    for (a, b) in plan.placements.iter().zip(&full.placements) {
        assert_eq!(a.translation, b.translation);
        assert_eq!(a.cost, b.cost);
    }
    assert_no_interference(&plan);
    assert_stable(&plan, &q(0));

    // Stopped from the start: nothing placed.
    let progress = Progress::new();
    progress.request_stop();
    let plan = stack_with(&cube(1), &opts, &progress).unwrap();
    assert!(plan.stopped && !plan.complete && plan.placements.is_empty());
}
