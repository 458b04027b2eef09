//! Property test: random unions of unit voxels, welded into one closed mesh (touching
//! edges and vertices included), decompose into exactly the voxel set.

mod common;

use apart_decompose::{decompose, verify, Options};
use apart_kernel::{Int, Rational};
use apart_pieces::Containment;
use apart_testkit::shapes;
use proptest::prelude::*;

const DIMS: [usize; 3] = [3, 3, 3];

fn check(on: &[bool]) {
    check_dims(DIMS, on)
}

fn check_dims(dims: [usize; 3], on: &[bool]) {
    let shape = common::exact(&shapes::voxels(dims, on));
    let d = decompose(&shape.points, &shape.tris, &Options::default()).expect("decompose");
    verify(&shape.points, &shape.tris, &d.pieces).expect("verify");
    let mut total = Rational::zero();
    for p in &d.pieces {
        total = &total + &p.volume();
    }
    let count = on.iter().filter(|&&b| b).count() as i64;
    assert_eq!(total, Rational::from_int(Int::from(count)));
    // Every cut plane passes through three grid points of [0, 4]^3 at most, so its
    // primitive normal has components of magnitude at most 2 * 4 * 4 = 32 < 37, and
    // it meets a voxel centre's neighbourhood only if it passes through the centre
    // (n · centre is then a half-integer and n · offset with |offset| < 1/100 would
    // have to be 0 or at least 1/2). The offset (1, 37, 1369) / 136900 lies on no such
    // plane through the centre (base-37 digits): each filled voxel's point is interior
    // to exactly one piece, each empty voxel's point to none.
    assert!(dims.iter().all(|&d| d <= 4));
    for i in 0..dims[0] {
        for j in 0..dims[1] {
            for k in 0..dims[2] {
                let filled = on[(i * dims[1] + j) * dims[2] + k];
                let w: i128 = 2 * 136900;
                let c = [i, j, k].map(|v| (2 * v as i128 + 1) * 136900);
                let x = [c[0] + 2, c[1] + 2 * 37, c[2] + 2 * 1369];
                let loc: Vec<Containment> =
                    d.pieces.iter().map(|p| common::locate(p, &x, w)).collect();
                let inside = loc.iter().filter(|c| **c == Containment::Inside).count();
                let touching = loc.iter().filter(|c| **c != Containment::Outside).count();
                if filled {
                    assert_eq!((inside, touching), (1, 1), "voxel {i} {j} {k}");
                } else {
                    assert_eq!(touching, 0, "empty voxel {i} {j} {k}");
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]
    #[test]
    fn voxel_unions_decompose_exactly(on in proptest::collection::vec(any::<bool>(), 27)) {
        prop_assume!(on.iter().any(|&b| b));
        check(&on);
    }
}

#[test]
fn hollow_cube_with_a_cavity() {
    // All voxels but the centre: a solid with an inner shell.
    let mut on = vec![true; 27];
    on[13] = false;
    check(&on);
}

#[test]
fn checkerboard_touching_everywhere() {
    // Voxels touching only along edges and at vertices.
    let on: Vec<bool> = (0..27)
        .map(|i| (i / 9 + i / 3 % 3 + i % 3) % 2 == 0)
        .collect();
    check(&on);
}

/// A longer run on 4 x 4 x 4 grids: `cargo test --release -- --ignored`.
#[test]
#[ignore]
fn voxel_stress() {
    let mut seed = 0x9e3779b97f4a7c15u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    for case in 0..3000 {
        let density = 1 + next() % 7;
        let on: Vec<bool> = (0..64).map(|_| next() % 8 < density).collect();
        if on.iter().any(|&b| b) {
            eprintln!("case {case}");
            check_dims([4, 4, 4], &on);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// Height fields over a 3 x 3 grid: generic planes, rational vertices.
    #[test]
    fn random_terrains_decompose_exactly(h in proptest::collection::vec(1i64..60, 16)) {
        let shape = common::exact(&shapes::terrain(3, 20, &h));
        let d = decompose(&shape.points, &shape.tris, &Options::default()).expect("decompose");
        verify(&shape.points, &shape.tris, &d.pieces).expect("verify");
        let mut total = Rational::zero();
        for p in &d.pieces {
            total = &total + &p.volume();
        }
        prop_assert_eq!(&total, &shape.volume);
        common::check_samples(&shape, &d.pieces);
    }
}

/// A longer run of random terrains up to 6 x 6: `cargo test --release -- --ignored`.
#[test]
#[ignore]
fn terrain_stress() {
    let mut seed = 0x2545f4914f6cdd1du64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    for case in 0..400 {
        let n = 2 + (next() % 5) as usize;
        let range = 1 + (next() % 1000) as i64;
        let h: Vec<i64> = (0..(n + 1) * (n + 1))
            .map(|_| 1 + (next() % range as u64) as i64)
            .collect();
        let shape = common::exact(&shapes::terrain(n, 1 + (next() % 500) as i64, &h));
        let d = decompose(&shape.points, &shape.tris, &Options::default()).expect("decompose");
        verify(&shape.points, &shape.tris, &d.pieces)
            .unwrap_or_else(|e| panic!("case {case}: {e}"));
        let mut total = Rational::zero();
        for p in &d.pieces {
            total = &total + &p.volume();
        }
        assert_eq!(total, shape.volume, "case {case}");
        common::check_samples(&shape, &d.pieces);
    }
}
