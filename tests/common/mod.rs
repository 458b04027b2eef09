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

/// Voxel cells merged greedily into boxes (runs along x, then rows along y, then
/// layers along z), each cell `s` grid units wide.
pub fn voxel_boxes(cells: &[[i64; 3]], s: i64) -> Vec<Polytope> {
    use std::collections::BTreeSet;
    let mut left: BTreeSet<[i64; 3]> = cells.iter().copied().collect();
    let mut out = Vec::new();
    while let Some(&c) = left.iter().next() {
        let full = |l: &BTreeSet<[i64; 3]>, lo: [i64; 3], hi: [i64; 3]| {
            (lo[0]..hi[0])
                .all(|x| (lo[1]..hi[1]).all(|y| (lo[2]..hi[2]).all(|z| l.contains(&[x, y, z]))))
        };
        let mut hi = [c[0] + 1, c[1] + 1, c[2] + 1];
        for k in 0..3 {
            loop {
                let (mut lo2, mut hi2) = (c, hi);
                lo2[k] = hi[k];
                hi2[k] = hi[k] + 1;
                if !full(&left, lo2, hi2) {
                    break;
                }
                hi[k] += 1;
            }
        }
        for x in c[0]..hi[0] {
            for y in c[1]..hi[1] {
                for z in c[2]..hi[2] {
                    left.remove(&[x, y, z]);
                }
            }
        }
        out.push(Polytope::cuboid(c.map(|v| v * s), hi.map(|v| v * s)).unwrap());
    }
    out
}

/// A voxel puzzle's pieces as parts `p0, p1, ...`.
pub fn voxel_parts(pieces: &[Vec<[i64; 3]>], s: i64) -> Vec<Part> {
    pieces
        .iter()
        .enumerate()
        .map(|(k, p)| Part::from_pieces(format!("p{k}"), voxel_boxes(p, s)))
        .collect()
}

/// `p` with every true coordinate multiplied by `k` (a multiple of its denominator)
/// and then translated by `t` (integers): integer vertices, denominator one.
fn scaled(p: &Polytope, k: &apart::kernel::Int, t: &[Rational; 3]) -> Polytope {
    let r = Rational::from_int(k.clone());
    let t = Vec3::from_ints(t.clone().map(|c| (&c * &r).numer()));
    p.rescaled(&(k / p.den()))
        .with_den(apart::kernel::Int::ONE)
        .translated(&t)
}

/// Replays a plan of moves from the assembled pose and checks it exactly, piece pair by
/// piece pair, without the planner's obstacles: a finite move's swept volume (the hull
/// of a moving piece at both ends) shares no interior point with a fixed piece of its
/// subassembly; a move to infinity passes the sweep oracle; every offset the plan states
/// is the sum of its finite moves; each subassembly is split by its last move. Returns
/// the first failure in words.
pub fn replay_moves(parts: &[Part], plan: &apart::plan::MovePlan) -> Result<(), String> {
    use apart::kernel::int::lcm;
    let zero = || [0, 1, 2].map(|_| Rational::zero());
    let mut at: Vec<[Rational; 3]> = parts.iter().map(|_| zero()).collect();
    for (k, m) in plan.moves.iter().enumerate() {
        if m.moving.is_empty() || m.moving.iter().any(|p| !m.subassembly.contains(p)) {
            return Err(format!("move {k}: moving set not in its subassembly"));
        }
        let d = [0, 1, 2].map(|c| Rational::from_int(m.direction.get(c)));
        let step = m
            .distance
            .as_ref()
            .map(|t| [0, 1, 2].map(|c| &d[c] * t))
            .unwrap_or_else(zero);
        for &i in &m.moving {
            for &j in m.subassembly.iter().filter(|j| !m.moving.contains(j)) {
                for a in &parts[i].pieces {
                    for b in &parts[j].pieces {
                        let mut l = lcm(a.den(), b.den());
                        for c in at[i].iter().chain(&at[j]).chain(&step) {
                            l = lcm(&l, &c.denom());
                        }
                        let (a0, b0) = (scaled(a, &l, &at[i]), scaled(b, &l, &at[j]));
                        let meets = if m.distance.is_some() {
                            let a1 = scaled(a, &l, &apart::kernel::rational::add(&at[i], &step));
                            let ends: Vec<Vec3> =
                                a0.vertices().iter().chain(a1.vertices()).cloned().collect();
                            let hull = Polytope::hull_of_points(&ends).unwrap();
                            !apart::pieces::interference::interiors_disjoint(&hull, &b0)
                        } else {
                            sweep_meets_interior(&a0, &b0, &m.direction)
                        };
                        if meets {
                            return Err(format!(
                                "move {k}: part {i} meets part {j} on the way ({:?} by {:?})",
                                m.direction, m.distance
                            ));
                        }
                    }
                }
            }
        }
        for &i in &m.moving {
            at[i] = apart::kernel::rational::add(&at[i], &step);
        }
        for (g, p) in &m.offsets {
            if *p != at[*g] {
                return Err(format!(
                    "move {k}: part {g} is stated at {p:?}, not {:?}",
                    at[*g]
                ));
            }
        }
    }
    Ok(())
}
