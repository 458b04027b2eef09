//! Bounded listings of many parts: with `max_per_set` the planner keeps a few
//! solutions of each kind per moving set and counts the rest. Checked against the
//! unbounded listing of the same assembly, which is the oracle here: the counts must be
//! its counts, the kept solutions a subset of its solutions, and the faces kept the
//! widest of each set.

mod common;

use apart_plan::{partition_subset, BlockingRegions, CellKind, Options, Part, Partitioning};
use common::lattice;
use std::collections::HashMap;

fn kind(c: CellKind) -> usize {
    match c {
        CellKind::Face => 0,
        CellKind::Edge => 1,
        CellKind::Vertex => 2,
    }
}

fn run(parts: &[Part], opts: &Options) -> Partitioning {
    let regions = BlockingRegions::compute(parts).unwrap();
    let all: Vec<usize> = (0..parts.len()).collect();
    partition_subset(&regions, &all, opts).0
}

fn tally(p: &Partitioning) -> HashMap<Vec<usize>, [usize; 3]> {
    let mut t: HashMap<Vec<usize>, [usize; 3]> = HashMap::new();
    for s in &p.solutions {
        t.entry(s.moving.clone()).or_default()[kind(s.cell)] += 1;
    }
    t
}

/// Checks the listing bounded to `k` per set and kind; returns the full count.
fn check_bounded(parts: &[Part], k: usize) -> usize {
    let full = run(parts, &Options::default());
    let bounded = run(
        parts,
        &Options {
            max_per_set: Some(k),
            ..Default::default()
        },
    );
    let want = tally(&full);
    assert!(!full.truncated);
    assert_eq!(full.solution_count(), full.solutions.len());
    // Counts: every moving set, every solution, listed or not.
    let got: HashMap<Vec<usize>, [usize; 3]> = bounded
        .sets
        .iter()
        .map(|s| (s.moving.clone(), s.counts))
        .collect();
    assert_eq!(got, want);
    assert_eq!(bounded.solution_count(), full.solutions.len());
    assert_eq!(bounded.interlocked, full.interlocked);
    // At most k of each kind per set, and all of them when a set has no more.
    let listed = tally(&bounded);
    for (m, c) in &want {
        let l = listed.get(m).copied().unwrap_or_default();
        for i in 0..3 {
            assert_eq!(l[i], c[i].min(k), "set {m:?} kind {i}");
        }
    }
    assert_eq!(
        bounded.truncated,
        want.values().any(|c| c.iter().any(|&x| x > k))
    );
    // Every kept solution is one of the full listing's.
    for s in &bounded.solutions {
        assert!(
            full.solutions
                .iter()
                .any(|f| f.cell == s.cell && f.moving == s.moving && f.direction == s.direction),
            "{s:?} is not a solution of the full listing"
        );
    }
    // The faces kept for a set are its widest.
    for m in want.keys() {
        let mut all: Vec<f64> = full
            .solutions
            .iter()
            .filter(|s| s.cell == CellKind::Face && &s.moving == m)
            .map(|s| s.clearance_deg)
            .collect();
        all.sort_by(|a, b| b.total_cmp(a));
        let mut kept: Vec<f64> = bounded
            .solutions
            .iter()
            .filter(|s| s.cell == CellKind::Face && &s.moving == m)
            .map(|s| s.clearance_deg)
            .collect();
        kept.sort_by(|a, b| b.total_cmp(a));
        assert_eq!(kept, all[..kept.len()].to_vec(), "faces of {m:?}");
    }
    full.solutions.len()
}

#[test]
fn a_bounded_listing_of_separated_cubes_keeps_every_count() {
    // 27 cubes in channels one cube wide: thousands of sliding solutions.
    let n = check_bounded(&lattice(3, 1), 2);
    assert!(n > 1000, "{n} solutions");
}

#[test]
fn a_bounded_listing_of_touching_cubes_keeps_every_count() {
    check_bounded(&lattice(3, 0), 1);
    assert_eq!(check_bounded(&common::split_star(), 3), 8);
}

#[test]
fn a_total_limit_stops_the_listing() {
    let parts = lattice(3, 1);
    let full = run(&parts, &Options::default());
    let p = run(
        &parts,
        &Options {
            max_solutions: Some(10),
            ..Default::default()
        },
    );
    assert_eq!(p.solutions.len(), 10);
    assert!(p.truncated && !p.interlocked);
    assert!(full.solutions.len() > 10);
}
