//! Helpers shared by the repository's root tests: the brute-force sweep oracle of
//! `apart_testkit` applied to a planner's parts, and a partition checked by it.
#![allow(dead_code)]

use apart::assembly::Loaded;
use apart::kernel::{Rational, Vec3};
use apart::pieces::Polytope;
use apart::plan::{partition, parts_of, CellKind, Options, Part, Partitioning};

/// True when piece `a` moving along `d` meets the interior of `b`: the oracle of
/// `apart_testkit` on the two pieces' facets at a common denominator.
pub fn sweep_meets_interior(a: &Polytope, b: &Polytope, d: &Vec3) -> bool {
    let rows = |p: &Polytope| -> Vec<([Rational; 3], Rational)> {
        let q = Rational::from_int;
        let f = p.facets().iter();
        f.map(|f| ([0, 1, 2].map(|k| q(f.normal.get(k))), q(f.offset.clone())))
            .collect()
    };
    let (a, b) = Polytope::common(a, b);
    let d = [0, 1, 2].map(|k| Rational::from_int(d.get(k)));
    apart_testkit::oracle::sweep_meets_interior(&rows(&a), &rows(&b), &d)
}

/// True when the parts in `moving` translate along `d` without meeting the others'
/// interiors, decided by the oracle over every piece pair.
pub fn oracle_free(parts: &[Part], moving: &[usize], d: &Vec3) -> bool {
    for (i, pi) in parts.iter().enumerate() {
        if !moving.contains(&i) {
            continue;
        }
        for (j, pj) in parts.iter().enumerate() {
            if moving.contains(&j) {
                continue;
            }
            for a in &pi.pieces {
                for b in &pj.pieces {
                    if sweep_meets_interior(a, b, d) {
                        return false;
                    }
                }
            }
        }
    }
    true
}

/// Partitions the loaded assembly and checks every solution with the oracle (only the
/// face solutions under a tolerance: the sliding and isolated directions on the rim of a
/// widened cone have components of hundreds of bits, too slow for the oracle's rational
/// simplex in a test).
pub fn partition_checked(loaded: &Loaded) -> (Vec<Part>, Partitioning) {
    assert!(loaded.is_valid(), "{:#?}", loaded.problems);
    let parts = parts_of(&loaded.assembly).unwrap().to_vec();
    let p = partition(&loaded.assembly, &Options::default()).unwrap();
    let all = loaded.assembly.tolerance.is_none();
    for s in p
        .solutions
        .iter()
        .filter(|s| all || s.cell == CellKind::Face)
    {
        assert!(
            oracle_free(&parts, &s.moving, &s.direction),
            "the oracle blocks {:?} along {:?}",
            s.moving,
            s.direction
        );
    }
    (parts, p)
}

/// The index of the part called `name`.
pub fn index(p: &Partitioning, name: &str) -> usize {
    p.names.iter().position(|n| n == name).unwrap()
}
