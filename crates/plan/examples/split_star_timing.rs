//! Mean time of a whole partition of the Split Star from its pieces, over 200 runs:
//! `cargo run --release -p apart-plan --example split_star_timing`.
#[path = "../tests/common/mod.rs"]
mod common;
fn main() {
    let parts = common::split_star();
    let opts = apart_plan::Options::default();
    let r = apart_plan::partition_pieces(&parts, &opts).unwrap();
    println!("{:?}", r.stats);
    let n = 200;
    let t = std::time::Instant::now();
    for _ in 0..n {
        std::hint::black_box(apart_plan::partition_pieces(&parts, &opts).unwrap());
    }
    println!(
        "mean {:.3} ms",
        t.elapsed().as_secs_f64() * 1000.0 / n as f64
    );
}
