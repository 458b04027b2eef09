//! Timing of a whole disassembly plan of N random boxes in K parts, step by step:
//! `cargo run --release -p apart-plan --example sequence_timing -- N K SEED`.
#[path = "../tests/common/mod.rs"]
mod common;
use std::time::Instant;
fn main() {
    let arg = |k: usize, d: u64| {
        std::env::args()
            .nth(k)
            .and_then(|s| s.parse().ok())
            .unwrap_or(d)
    };
    let (n, k, seed) = (arg(1, 128) as usize, arg(2, 16) as usize, arg(3, 1));
    let parts = common::random_box_parts(n, k, seed);
    let t = Instant::now();
    let regions = apart_plan::BlockingRegions::compute(&parts).unwrap();
    println!("pair regions {:.1} ms", t.elapsed().as_secs_f64() * 1e3);
    let all: Vec<usize> = (0..parts.len()).collect();
    let t = Instant::now();
    let ms = apart_plan::MotionSpace::build(&regions, &all);
    println!(
        "first motion space {:.1} ms: {} input arcs, {:?}",
        t.elapsed().as_secs_f64() * 1e3,
        ms.input_arcs,
        ms.build_stats
    );
    let st = ms.statuses();
    for (name, v) in [
        ("vertices", &st.vertices),
        ("edges", &st.edges),
        ("faces", &st.faces),
        ("cycles", &st.cycles),
    ] {
        let total: usize = v.iter().map(|s| s.iter().count()).sum();
        println!(
            "{name}: {} cells, {:.1} maps each",
            v.len(),
            total as f64 / v.len().max(1) as f64
        );
    }
    let t = Instant::now();
    drop(ms);
    println!("drop {:.1} ms", t.elapsed().as_secs_f64() * 1e3);
    if std::env::args().any(|a| a == "--first-only") {
        return;
    }
    let t = Instant::now();
    let s = apart_plan::sequence(&regions, &apart_plan::SequenceOptions::default());
    println!(
        "sequence {:.1} ms: {} steps, complete {}",
        t.elapsed().as_secs_f64() * 1e3,
        s.steps.len(),
        s.complete()
    );
    for st in &s.steps {
        println!(
            "  {:?} moves {:?} along {:?} ({}, {:.2} deg)",
            st.subassembly,
            st.moving,
            st.unit,
            st.cell.name(),
            st.clearance_deg
        );
    }
}
