//! Timing of the motion space of a row of N interlocking bricks (two cuboids each):
//! `cargo run --release -p apart-plan --example brick_timing -- N`.
#[path = "../tests/common/mod.rs"]
mod common;
fn main() {
    let n: i64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(16);
    let parts: Vec<apart_plan::Part> = (0..n)
        .map(|i| {
            common::part(
                &format!("b{i}"),
                vec![
                    common::cuboid([2 * i, 0, 0], [2 * i + 2, 2, 1]),
                    common::cuboid([2 * i + 1, 0, 1], [2 * i + 3, 2, 2]),
                ],
            )
        })
        .collect();
    let regions = apart_plan::BlockingRegions::compute(&parts).unwrap();
    let all: Vec<usize> = (0..parts.len()).collect();
    for _ in 0..3 {
        let t = std::time::Instant::now();
        let ms = apart_plan::MotionSpace::build(&regions, &all);
        println!(
            "{:?} arcs {} circles {} {:?}",
            t.elapsed(),
            ms.input_arcs,
            ms.arrangement().circles().len(),
            ms.build_stats
        );
    }
}
