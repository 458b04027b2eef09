//! Progress reports and the stop flag: the counts of every phase are
//! monotone and end at their totals, the planners with a [`Progress`] give the same
//! answers as without, and a planner stopped by the flag returns a partial answer whose
//! every step or solution is valid (re-checked by the brute-force oracle) and which is
//! marked as stopped.

mod common;

use apart_plan::progress::phases;
use apart_plan::{
    partition_pieces_with, partition_subset, partition_subset_with, sequence, sequence_with,
    BlockingRegions, CellKind, Options, Part, PlanError, Progress, Sequence, SequenceOptions,
    Solution,
};
use common::oracle::Oracle;
use common::{check_plan, lattice};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

type Log = Arc<Mutex<Vec<(&'static str, usize, usize)>>>;

/// A progress that records every report, with its own stop flag.
fn recording() -> (Progress, Log) {
    let log: Log = Arc::default();
    let l = log.clone();
    let p = Progress::with_callback(move |phase, done, total| {
        l.lock().unwrap().push((phase, done, total))
    });
    (p, log)
}

/// A progress whose callback raises its own stop flag at the first report of `phase`
/// with at least `done` units done.
fn stopping_at(phase: &'static str, done: usize) -> (Progress, Log) {
    let flag = Arc::new(AtomicBool::new(false));
    let raise = flag.clone();
    let log: Log = Arc::default();
    let l = log.clone();
    let p = Progress::with_callback(move |ph, d, t| {
        l.lock().unwrap().push((ph, d, t));
        if ph == phase && d >= done {
            raise.store(true, Ordering::Relaxed);
        }
    })
    .with_stop_flag(flag);
    (p, log)
}

/// Every phase in `log` has a fixed total, monotone counts within it, and ends at its
/// total; returns the phases in the order they first reported.
fn check_counts(log: &[(&'static str, usize, usize)]) -> Vec<&'static str> {
    let mut order: Vec<&'static str> = Vec::new();
    for &(phase, _, _) in log {
        if !order.contains(&phase) {
            order.push(phase);
        }
    }
    for &phase in &order {
        let reports: Vec<(usize, usize)> = log
            .iter()
            .filter(|r| r.0 == phase)
            .map(|r| (r.1, r.2))
            .collect();
        let total = reports[0].1;
        assert_eq!(reports[0].0, 0, "{phase} starts at 0: {reports:?}");
        for w in reports.windows(2) {
            assert_eq!(w[1].1, total, "{phase}: the total changed: {reports:?}");
            assert!(w[0].0 <= w[1].0, "{phase} went back: {reports:?}");
        }
        assert!(reports.iter().all(|r| r.0 <= total), "{phase}: {reports:?}");
        assert_eq!(
            reports.last().unwrap().0,
            total,
            "{phase} ends at its total: {reports:?}"
        );
        // Thinned to about a thousand reports per phase.
        assert!(reports.len() <= 1002, "{phase}: {} reports", reports.len());
    }
    order
}

/// Replays a plan's steps: each splits a subassembly still open (`check_plan` verifies
/// each with the oracle); the open subassemblies left, singletons aside, are exactly the
/// stuck, unsplit and pending ones, and the parts are all accounted for.
fn check_partial_plan(parts: &[Part], plan: &Sequence) {
    check_plan(parts, plan);
    let mut open: Vec<Vec<usize>> = vec![(0..parts.len()).collect()];
    for step in &plan.steps {
        let k = open.iter().position(|s| s == &step.subassembly).unwrap();
        open.remove(k);
        open.push(step.moving.clone());
        open.push(step.staying());
    }
    let mut left: Vec<Vec<usize>> = open.into_iter().filter(|s| s.len() > 1).collect();
    let mut reported: Vec<Vec<usize>> = plan
        .stuck
        .iter()
        .chain(&plan.unsplit)
        .chain(&plan.pending)
        .cloned()
        .collect();
    left.sort();
    reported.sort();
    assert_eq!(left, reported, "open subassemblies after the steps");
}

/// A solution is valid: its set moves along its direction without hitting the rest
/// (brute force), and is a minimal moving set there.
fn check_solution(oracle: &Oracle, n: usize, s: &Solution) {
    let rest: Vec<usize> = (0..n).filter(|k| !s.moving.contains(k)).collect();
    assert!(oracle.free(&s.moving, &rest, &s.direction), "{s:?}");
    let minimal = oracle.dbg(&s.direction).minimal_moving_sets();
    assert!(minimal.contains(&s.moving), "{s:?} among {minimal:?}");
}

#[test]
fn progress_counts_are_monotone_and_end_at_their_totals() {
    // Cubes in channels one cube wide: faces, sliding edges and isolated vertices.
    let parts = lattice(2, 1);
    let (progress, log) = recording();
    let regions = BlockingRegions::compute_with(&parts, &progress).unwrap();
    let all: Vec<usize> = (0..parts.len()).collect();
    let (p, ms) = partition_subset_with(&regions, &all, &Options::default(), &progress);
    assert!(ms.is_some() && !p.stopped);
    let log = log.lock().unwrap().clone();
    let order = check_counts(&log);
    assert_eq!(
        order,
        [
            phases::PAIR_REGIONS,
            phases::MOTION_SPACE,
            phases::FREE_REGIONS,
            phases::DIRECTIONS,
            phases::CELLS
        ]
    );
    // 8 parts: 28 pairs.
    assert!(log.contains(&(phases::PAIR_REGIONS, 28, 28)));
    // The same answer as without a progress.
    let plain = partition_subset(&regions, &all, &Options::default()).0;
    assert_eq!(p.solutions, plain.solutions);
    assert_eq!(p.sets, plain.sets);
    assert!(p.solutions.iter().any(|s| s.cell == CellKind::Vertex));

    // A sequence: one split per part but the last.
    let (progress, log) = recording();
    let plan = sequence_with(&regions, &SequenceOptions::default(), &progress);
    assert!(plan.complete() && !plan.stopped && plan.pending.is_empty());
    assert_eq!(
        plan.steps,
        sequence(&regions, &SequenceOptions::default()).steps
    );
    let log = log.lock().unwrap().clone();
    assert_eq!(check_counts(&log), [phases::SEQUENCE]);
    assert_eq!(log.last(), Some(&(phases::SEQUENCE, 7, 7)));
    assert_eq!(log.len(), 8, "a report per step: {log:?}");

    // Interlocked subassemblies count as their size less one: the total is reached.
    let rings = common::linked_rings();
    let regions = BlockingRegions::compute(&rings).unwrap();
    let (progress, log) = recording();
    let plan = sequence_with(&regions, &SequenceOptions::default(), &progress);
    assert_eq!(plan.stuck, vec![vec![0, 1]]);
    assert!(!plan.stopped);
    let log = log.lock().unwrap().clone();
    check_counts(&log);
    assert_eq!(log.last(), Some(&(phases::SEQUENCE, 1, 1)));
}

#[test]
fn a_sequence_stopped_from_its_callback_keeps_the_steps_found() {
    let parts = lattice(3, 0);
    let regions = BlockingRegions::compute(&parts).unwrap();
    let opts = SequenceOptions::default();
    let full = sequence(&regions, &opts);
    assert!(full.complete() && full.steps.len() == 26);
    // Stopped after the third split.
    let (progress, log) = stopping_at(phases::SEQUENCE, 3);
    let plan = sequence_with(&regions, &opts, &progress);
    assert!(plan.stopped && !plan.complete(), "{plan:?}");
    assert_eq!(plan.steps.len(), 3);
    assert_eq!(plan.steps[..], full.steps[..3], "the same first steps");
    assert!(plan.stuck.is_empty() && plan.unsplit.is_empty());
    assert!(!plan.pending.is_empty());
    check_partial_plan(&parts, &plan);
    let log = log.lock().unwrap().clone();
    assert_eq!(log.last(), Some(&(phases::SEQUENCE, 3, 26)));

    // Stopped from the start: no step, the whole assembly pending.
    let (progress, _) = stopping_at(phases::SEQUENCE, 0);
    let plan = sequence_with(&regions, &opts, &progress);
    assert!(plan.stopped && plan.steps.is_empty());
    assert_eq!(plan.pending, vec![(0..27).collect::<Vec<usize>>()]);
    check_partial_plan(&parts, &plan);

    // Stopped by another thread at any moment (inside a step, too: that step is dropped
    // and its subassembly pending): the steps are the full plan's first ones.
    for delay_ms in [0, 20, 60, 150] {
        let progress = Progress::new();
        let flag = progress.stop_flag();
        let raiser = std::thread::spawn(move || {
            std::thread::sleep(std::time::Duration::from_millis(delay_ms));
            flag.store(true, Ordering::Relaxed);
        });
        let plan = sequence_with(&regions, &opts, &progress);
        raiser.join().unwrap();
        assert_eq!(
            plan.steps[..],
            full.steps[..plan.steps.len()],
            "{delay_ms} ms"
        );
        assert_eq!(plan.stopped, plan.steps.len() < 26, "{delay_ms} ms");
        check_partial_plan(&parts, &plan);
    }
}

#[test]
fn a_run_stopped_from_the_start_returns_nothing_and_says_so() {
    let parts = lattice(2, 0);
    let progress = Progress::new();
    progress.request_stop();
    assert_eq!(
        BlockingRegions::compute_with(&parts, &progress).unwrap_err(),
        PlanError::Stopped {
            phase: phases::PAIR_REGIONS
        }
    );
    // Raised by the callback after the first pair region of a block: stopped too.
    let (midway, log) = stopping_at(phases::PAIR_REGIONS, 1);
    let err = BlockingRegions::compute_with(&lattice(3, 0), &midway).unwrap_err();
    assert!(matches!(err, PlanError::Stopped { .. }), "{err}");
    let log = log.lock().unwrap().clone();
    assert!(log.last().unwrap().1 < 351, "{log:?}");
    let p = partition_pieces_with(&parts, &Options::default(), &progress).unwrap();
    assert!(p.stopped && p.solutions.is_empty() && p.sets.is_empty());
    assert!(!p.interlocked, "unknown, not interlocked");
    assert_eq!(p.names.len(), 8);
    let regions = BlockingRegions::compute(&parts).unwrap();
    let all: Vec<usize> = (0..8).collect();
    let (p, ms) = partition_subset_with(&regions, &all, &Options::default(), &progress);
    assert!(p.stopped && p.solutions.is_empty() && ms.is_none());
    let plan = sequence_with(&regions, &SequenceOptions::default(), &progress);
    assert!(plan.stopped && plan.steps.is_empty() && !plan.complete());
    assert_eq!(plan.pending, vec![all]);
    // An assembly of one part has nothing to split, stopped or not.
    let one = &parts[..1];
    let regions = BlockingRegions::compute(one).unwrap();
    let plan = sequence_with(&regions, &SequenceOptions::default(), &progress);
    assert!(plan.complete() && !plan.stopped);
}

#[test]
fn a_partition_stopped_during_its_solutions_keeps_valid_ones() {
    let parts = lattice(3, 1);
    let regions = BlockingRegions::compute(&parts).unwrap();
    let all: Vec<usize> = (0..parts.len()).collect();
    let opts = Options::default();
    let full = partition_subset(&regions, &all, &opts).0;
    let oracle = Oracle::new(&parts);
    let faces: Vec<&Solution> = full
        .solutions
        .iter()
        .filter(|s| s.cell == CellKind::Face)
        .collect();
    assert!(
        faces.len() >= 20 && full.solutions.len() > faces.len(),
        "{} faces of {}",
        faces.len(),
        full.solutions.len()
    );

    // Stopped when the edges and vertices begin: every face solution, nothing else.
    let (progress, _) = stopping_at(phases::CELLS, 0);
    let (p, _) = partition_subset_with(&regions, &all, &opts, &progress);
    assert!(p.stopped && !p.interlocked);
    let got: Vec<&Solution> = p.solutions.iter().collect();
    assert_eq!(got, faces);
    assert_eq!(p.solution_count(), faces.len());

    // Stopped while the face solutions get their directions: some of them, each valid
    // and one of the full run's.
    let (progress, _) = stopping_at(phases::DIRECTIONS, 1);
    let (p, _) = partition_subset_with(&regions, &all, &opts, &progress);
    assert!(p.stopped && !p.interlocked);
    assert!(!p.solutions.is_empty() && p.solutions.len() < faces.len());
    for s in &p.solutions {
        assert!(full.solutions.contains(s), "{s:?}");
        check_solution(&oracle, parts.len(), s);
    }
    let counted: usize = p.sets.iter().map(|s| s.counts.iter().sum::<usize>()).sum();
    assert_eq!(counted, p.solutions.len());

    // Stopped while the faces are scanned: what was found is valid.
    let (progress, _) = stopping_at(phases::FREE_REGIONS, 1);
    let (p, _) = partition_subset_with(&regions, &all, &opts, &progress);
    assert!(p.stopped);
    for s in &p.solutions {
        assert!(full.solutions.contains(s), "{s:?}");
        check_solution(&oracle, parts.len(), s);
    }
}
