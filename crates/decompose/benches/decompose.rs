//! Decomposition benchmark over the test shapes: prints a markdown table of reflex edges,
//! pieces and times (best of several runs), sequential and parallel.

#[path = "../tests/common/shapes.rs"]
mod shapes;

use apart_decompose::{decompose, verify, Decomposition, Options};
use std::time::Instant;

fn best_of(shape: &shapes::Shape, opts: &Options, runs: usize) -> (Decomposition, f64) {
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

fn main() {
    let seq = Options {
        parallel: false,
        ..Options::default()
    };
    let par = Options::default();
    println!(
        "| shape | triangles | reflex edges r | pieces | before merging | splits | max den bits | sequential ms | parallel ms | verify ms |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for shape in shapes::all() {
        let runs = if shape.tris.len() > 1000 { 10 } else { 30 };
        let (d, ts) = best_of(&shape, &seq, runs);
        let (_, tp) = best_of(&shape, &par, runs);
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
            "| {} | {} | {} | {} | {} | {} | {} | {:.2} | {:.2} | {:.1} |",
            shape.name,
            shape.tris.len(),
            d.reflex_edges,
            d.pieces.len(),
            d.stats.partition_pieces,
            d.stats.splits,
            bits.saturating_sub(1),
            ts * 1e3,
            tp * 1e3,
            tv * 1e3
        );
    }
}
