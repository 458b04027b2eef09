//! Decomposition benchmark over the test shapes: prints a markdown table of reflex edges,
//! pieces and times (best of several runs), sequential and parallel.

#[path = "../tests/common/mod.rs"]
mod common;

use apart_decompose::{decompose, verify, Decomposition, Options};
use apart_testkit::shapes;
use std::time::Instant;

fn best_of(shape: &common::Exact, opts: &Options, runs: usize) -> (Decomposition, f64) {
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..runs {
        let t = Instant::now();
        let d = decompose(&shape.points, &shape.tris, opts).expect("decompose");
        best = best.min(t.elapsed().as_secs_f64());
        last = Some(d);
    }
    (last.unwrap(), best)
}

fn row(shape: &shapes::Shape, seq: &Options, par: &Options) {
    let shape = &common::exact(shape);
    let runs = if shape.tris.len() > 5000 {
        3
    } else if shape.tris.len() > 1000 {
        10
    } else {
        30
    };
    let (d, ts) = best_of(shape, seq, runs);
    let (_, tp) = best_of(shape, par, runs);
    let t = Instant::now();
    verify(&shape.points, &shape.tris, &d.pieces).expect("verify");
    let tv = t.elapsed().as_secs_f64();
    let bits = d
        .pieces
        .iter()
        .map(|p| apart_kernel::int::bit_len(p.den()))
        .max()
        .unwrap_or(0);
    println!(
        "| {} | {} | {} | {} | {} | {} | {} / {} | {:.2} | {:.2} | {:.1} |",
        shape.name,
        shape.tris.len(),
        d.reflex_edges,
        d.pieces.len(),
        d.stats.partition_pieces,
        d.stats.splits,
        d.stats.max_den_bits,
        bits.saturating_sub(1),
        ts * 1e3,
        tp * 1e3,
        tv * 1e3
    );
}

fn main() {
    let seq = Options {
        parallel: false,
        ..Options::default()
    };
    let par = Options::default();
    println!(
        "| shape | triangles | reflex edges r | pieces | before merging | splits | den bits (vertex / piece) | sequential ms | parallel ms | verify ms |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for shape in shapes::all() {
        row(&shape, &seq, &par);
    }
    println!();
    println!("Scaling and generic planes:");
    println!();
    println!(
        "| shape | triangles | reflex edges r | pieces | before merging | splits | den bits (vertex / piece) | sequential ms | parallel ms | verify ms |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    row(
        &shapes::Ring::with_section(256, 1105, 40, 5 * 13 * 17 * 29 * 37).shape(),
        &seq,
        &par,
    );
    let mut comb = shapes::comb(200);
    comb.name = "comb, 200 teeth";
    row(&comb, &seq, &par);
    let mut seed = 12345u64;
    let on: Vec<bool> = (0..10 * 10 * 6)
        .map(|_| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 33) % 2 == 0
        })
        .collect();
    let mut vox = shapes::voxels([10, 10, 6], &on);
    vox.name = "random voxels 10 x 10 x 6 (half full)";
    row(&vox, &seq, &par);
    let h: Vec<i64> = (0..21 * 21)
        .map(|_| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            2000 + (seed >> 33) as i64 % 3000
        })
        .collect();
    let mut terrain = shapes::terrain(20, 1000, &h);
    terrain.name = "random terrain 20 x 20";
    row(&terrain, &seq, &par);
    let shear = [[3, 1, 0], [1, 4, 1], [0, 2, 5]];
    for base in [shapes::box_with_hole(), shapes::sheet_metal(), vox] {
        let mut t = shapes::transformed(&base, shear);
        t.name = match base.name {
            "box with through-hole" => "box with hole, sheared",
            "voxels" | "random voxels 10 x 10 x 6 (half full)" => "random voxels, sheared",
            _ => "sheet metal, sheared",
        };
        row(&t, &seq, &par);
    }
}
