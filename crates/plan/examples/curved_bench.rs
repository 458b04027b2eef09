//! Planning times on generated tessellated curved assemblies (apart-testkit's `curved`):
//! `cargo run --release -p apart-plan --example curved_bench [-- plug:20000 nut:64 ...]`.
//!
//! Prints one row per assembly: triangles, convex pieces (per part), piece pairs, load
//! (mesh loading and convex decomposition), one direction (`dbg_along` at +z), the first
//! solution (`partition_first`), the full partition, and the peak resident memory of the
//! planning (the decomposition's own peak is reported separately).
use apart_plan::{partition_first, partition_subset, BlockingRegions, DirectionQuery, Options};
use apart_testkit::curved;
use std::time::Instant;

fn reset_peak() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

fn peak_mib() -> f64 {
    let s = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    s.lines()
        .find(|l| l.starts_with("VmHWM:"))
        .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let cases: Vec<String> = if args.is_empty() {
        vec![
            "pin:64".into(),
            "nut:64".into(),
            "plug:2000".into(),
            "plug:20000".into(),
        ]
    } else {
        args
    };
    println!(
        "| assembly | triangles | pieces | piece pairs | load s | load MiB | --direction s | --first s | full s | plan MiB |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for case in cases {
        let (kind, size) = case.split_once(':').expect("kind:size");
        let size: usize = size.parse().unwrap();
        let parts = match kind {
            "plug" => curved::plug_and_socket(size),
            "nut" => curved::nut_on_bolt(size, 3),
            "pin" => curved::pin_in_hole(size, size, 0.0),
            _ => panic!("unknown kind {kind}"),
        };
        let triangles = curved::triangle_count(&parts);
        let dir =
            std::env::temp_dir().join(format!("apart-curved-bench-{}-{case}", std::process::id()));
        curved::write_off_dir(&parts, &dir).unwrap();
        reset_peak();
        let t = Instant::now();
        let loaded = apart_assembly::load(&dir, &Default::default()).unwrap();
        assert!(loaded.is_valid(), "{case}: {:?}", loaded.problems);
        let pieces = apart_plan::parts_of(&loaded.assembly).unwrap();
        let load = t.elapsed().as_secs_f64();
        let load_mib = peak_mib();
        let _ = std::fs::remove_dir_all(&dir);
        let counts: Vec<String> = pieces.iter().map(|p| p.pieces.len().to_string()).collect();
        let pairs: usize = (0..pieces.len())
            .flat_map(|i| (i + 1..pieces.len()).map(move |j| (i, j)))
            .map(|(i, j)| pieces[i].pieces.len() * pieces[j].pieces.len())
            .sum();
        reset_peak();
        let t = Instant::now();
        let q = DirectionQuery::new(pieces).unwrap();
        let a = q.answer(&apart_kernel::Vec3::new(0, 0, 1)).unwrap();
        let one = t.elapsed().as_secs_f64();
        eprintln!("{case}: +z query work {:?}", q.stats());
        let t = Instant::now();
        let f = partition_first(pieces).unwrap();
        let first = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let regions = BlockingRegions::compute(pieces).unwrap();
        eprintln!("{case}: regions {:?}", regions.stats);
        let everything: Vec<usize> = (0..pieces.len()).collect();
        let full = partition_subset(&regions, &everything, &Options::default()).0;
        let all = t.elapsed().as_secs_f64();
        let mib = peak_mib();
        eprintln!(
            "{case}: +z {} moving {:?}; first {:?}; full {} solutions; phases {:?}",
            a.cell.name(),
            a.moving,
            f.solutions
                .first()
                .map(|s| (s.cell, s.direction.to_strings(), &s.moving)),
            full.solutions.len(),
            full.stats.seconds
        );
        println!(
            "| {case} | {triangles} | {} | {pairs} | {load:.2} | {load_mib:.0} | {one:.3} | {first:.3} | {all:.2} | {mib:.0} |",
            counts.join(" + ")
        );
    }
}
