//! Hierarchical culling of piece pairs: parts of many pieces whose piece
//! pairs' projections overlap heavily, so that most groups of pairs are culled. The
//! pair region must still be exactly the union of every piece pair's projection:
//! checked against the brute-force oracle (swept pieces, no Minkowski sums) at integer
//! directions, many of them on the boundary of a projection, and at a sample point of
//! every face of the motion space.

mod common;

use apart_kernel::Vec3;
use apart_plan::{BlockingRegions, MotionSpace, Part};
// A small deterministic generator (the tests must not depend on a random seed's luck).
use apart_testkit::solids::Lcg;
use common::oracle::Oracle;
use common::{cuboid, part};

/// Two parts of `n` unit cubes each on the cells of a lattice of spacing 2 (cubes never
/// touch), the cells of the two parts drawn at random from one box of cells, so the
/// parts interleave; `shift` moves the second part's cells.
fn interleaved(seed: u64, n: usize, cells: i64, shift: [i64; 3]) -> Vec<Part> {
    let mut rng = Lcg(seed);
    let mut used = std::collections::HashSet::new();
    let mut parts = Vec::new();
    for (k, name) in ["a", "b"].iter().enumerate() {
        let mut pieces = Vec::new();
        while pieces.len() < n {
            let c = [0, 1, 2].map(|_| rng.below(cells as u64) as i64);
            let c = if k == 1 {
                [c[0] + shift[0], c[1] + shift[1], c[2] + shift[2]]
            } else {
                c
            };
            if used.insert(c) {
                let o = c.map(|x| 2 * x);
                pieces.push(cuboid(o, [o[0] + 1, o[1] + 1, o[2] + 1]));
            }
        }
        parts.push(part(name, pieces));
    }
    parts
}

/// Every integer direction in `[-r, r]³` (many lie on the boundary of a projection:
/// the cubes' corners are integer).
fn directions(r: i64) -> Vec<Vec3> {
    let mut out = Vec::new();
    for x in -r..=r {
        for y in -r..=r {
            for z in -r..=r {
                if (x, y, z) != (0, 0, 0) {
                    out.push(Vec3::new(x, y, z));
                }
            }
        }
    }
    out
}

fn check(parts: &[Part]) {
    let regions = BlockingRegions::compute(parts).unwrap();
    assert!(
        regions.stats.culled > 0,
        "the test must exercise culling: {:?}",
        regions.stats
    );
    let oracle = Oracle::new(parts);
    for d in directions(5) {
        assert_eq!(
            regions.blocks(0, 1, &d),
            !oracle.free(&[0], &[1], &d),
            "a hits b along {d:?}"
        );
        assert_eq!(
            regions.blocks(1, 0, &d),
            !oracle.free(&[1], &[0], &d),
            "b hits a along {d:?}"
        );
    }
    // The simplified region maps, through the motion space built from them.
    let ms = MotionSpace::build(&regions, &[0, 1]);
    let st = ms.statuses();
    for f in ms.arrangement().face_ids() {
        let d = ms.face_sample(f);
        assert_eq!(
            st.faces[f.index()].get(0),
            !oracle.free(&[0], &[1], &d),
            "face {f:?} at {d:?}"
        );
        assert_eq!(
            st.faces[f.index()].get(1),
            !oracle.free(&[1], &[0], &d),
            "face {f:?} at {d:?}"
        );
    }
}

#[test]
fn interleaved_cubes_are_culled_without_changing_the_region() {
    for seed in [1, 2] {
        check(&interleaved(seed, 72, 6, [0, 0, 0]));
    }
}

#[test]
fn parts_far_apart_are_culled_without_changing_the_region() {
    // The second part's cells are shifted away: every pair's projection is small and
    // most lie inside the union of the largest ones.
    check(&interleaved(3, 70, 5, [9, 4, 2]));
}
