//! Micro-benchmarks of the kernel predicates: ns per call on each evaluation path.
//!
//! - `small`: grid-sized inputs (30-bit coordinates), decided in machine integers;
//! - `filtered`: constructed inputs (~130-bit intersection points), decided by the
//!   floating-point filter;
//! - `exact`: the same sizes on exactly degenerate inputs, where the filter must give up
//!   and arbitrary precision decides.

use apart_kernel::predicates::{det3_sign, det3_sign_exact, dot_sign, dot_sign_exact};
use apart_kernel::spherical::{arc_position, circle_intersection};
use apart_kernel::Vec3;
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn lcg(seed: &mut u64) -> i64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    ((*seed >> 33) as i64) - (1 << 30)
}

fn grid_vec(seed: &mut u64) -> Vec3 {
    Vec3::new(lcg(seed), lcg(seed), lcg(seed))
}

/// An intersection point of two great circles whose normals are crosses of grid points:
/// the biggest sphere point the partitioner builds (4B + 7 bits).
fn constructed(seed: &mut u64) -> Vec3 {
    let n1 = grid_vec(seed).cross(&grid_vec(seed));
    let n2 = grid_vec(seed).cross(&grid_vec(seed));
    circle_intersection(&n1, &n2).unwrap()
}

fn bench(c: &mut Criterion) {
    let mut seed = 7u64;
    let smalls: Vec<[Vec3; 3]> = (0..64)
        .map(|_| {
            [
                grid_vec(&mut seed),
                grid_vec(&mut seed),
                grid_vec(&mut seed),
            ]
        })
        .collect();
    let bigs: Vec<[Vec3; 3]> = (0..64)
        .map(|_| {
            [
                constructed(&mut seed),
                constructed(&mut seed),
                constructed(&mut seed),
            ]
        })
        .collect();
    // Exactly degenerate inputs of the same sizes: (a, b, a + b) is coplanar, a ⟂ a × b.
    let coplanar: Vec<[Vec3; 3]> = bigs
        .iter()
        .map(|[a, b, _]| [a.clone(), b.clone(), a.add(b)])
        .collect();
    let perpendicular: Vec<[Vec3; 2]> = bigs
        .iter()
        .map(|[a, b, _]| [a.clone(), a.cross(b)])
        .collect();

    let mut g = c.benchmark_group("det3_sign");
    g.bench_function("small", |bch| {
        bch.iter(|| {
            smalls
                .iter()
                .map(|[a, b, c]| det3_sign(black_box(a), b, c) as i32)
                .sum::<i32>()
        })
    });
    g.bench_function("filtered", |bch| {
        bch.iter(|| {
            bigs.iter()
                .map(|[a, b, c]| det3_sign(black_box(a), b, c) as i32)
                .sum::<i32>()
        })
    });
    g.bench_function("exact", |bch| {
        bch.iter(|| {
            coplanar
                .iter()
                .map(|[a, b, c]| det3_sign(black_box(a), b, c) as i32)
                .sum::<i32>()
        })
    });
    g.bench_function("exact_forced", |bch| {
        bch.iter(|| {
            bigs.iter()
                .map(|[a, b, c]| det3_sign_exact(black_box(a), b, c) as i32)
                .sum::<i32>()
        })
    });
    g.finish();

    let mut g = c.benchmark_group("dot_sign");
    g.bench_function("small", |bch| {
        bch.iter(|| {
            smalls
                .iter()
                .map(|[a, b, _]| dot_sign(black_box(a), b) as i32)
                .sum::<i32>()
        })
    });
    g.bench_function("filtered", |bch| {
        bch.iter(|| {
            bigs.iter()
                .map(|[a, b, _]| dot_sign(black_box(a), b) as i32)
                .sum::<i32>()
        })
    });
    g.bench_function("exact", |bch| {
        bch.iter(|| {
            perpendicular
                .iter()
                .map(|[a, p]| dot_sign(black_box(a), p) as i32)
                .sum::<i32>()
        })
    });
    g.bench_function("exact_forced", |bch| {
        bch.iter(|| {
            bigs.iter()
                .map(|[a, b, _]| dot_sign_exact(black_box(a), b) as i32)
                .sum::<i32>()
        })
    });
    g.finish();

    let mut g = c.benchmark_group("constructions");
    g.bench_function("cross_small", |bch| {
        bch.iter(|| {
            smalls
                .iter()
                .map(|[a, b, _]| black_box(a).cross(b).bits())
                .sum::<u32>()
        })
    });
    g.bench_function("circle_intersection", |bch| {
        let normals: Vec<(Vec3, Vec3)> = smalls
            .iter()
            .map(|[a, b, c]| (a.cross(b), b.cross(c)))
            .collect();
        bch.iter(|| {
            normals
                .iter()
                .map(|(m, n)| circle_intersection(black_box(m), n).map_or(0, |p| p.bits()))
                .sum::<u32>()
        })
    });
    g.bench_function("arc_position_degenerate", |bch| {
        // The point is the arc's own end point: every test is exactly zero once.
        let arcs: Vec<(Vec3, Vec3, Vec3)> = bigs
            .iter()
            .map(|[a, b, _]| (a.cross(b), a.clone(), b.clone()))
            .collect();
        bch.iter(|| {
            arcs.iter()
                .map(|(n, s, e)| arc_position(black_box(n), s, e, e) as u32)
                .sum::<u32>()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
