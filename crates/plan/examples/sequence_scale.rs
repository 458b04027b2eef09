//! How `sequence_parts` grows with the part count, in one process: time, peak heap and
//! the planner's work per step, on lattices of touching unit cubes, loose cubes, random
//! boxes linked into parts (paper 003's benchmark), or any assembly folder; and the
//! memory taken by one pair region (resident sizes, from /proc/self/status).
//!
//! `cargo run --release -p apart-plan --example sequence_scale -- KIND N [auto|full|local|old]`
//!
//! KIND: `cubes` (an N×N×N touching lattice), `loose` (the same spaced by a cube),
//! `boxes` (N random boxes in 16 parts, seed 1), or a path to an assembly folder (N is
//! then ignored). `old` runs `sequence` over every pair region made up front. With
//! `STEPS=1` in the environment each step is listed.
#[path = "../tests/common/mod.rs"]
mod common;
use std::time::Instant;

/// The process's resident size now and at its peak (`VmRSS`, `VmHWM` of
/// /proc/self/status, in bytes; 0 where that file is missing).
fn resident() -> (usize, usize) {
    let text = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let field = |name: &str| -> usize {
        text.lines()
            .find(|l| l.starts_with(name))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|v| v.parse::<usize>().ok())
            .map_or(0, |kb| kb * 1024)
    };
    (field("VmRSS:"), field("VmHWM:"))
}

fn mib(b: usize) -> f64 {
    b as f64 / (1 << 20) as f64
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let kind = args.get(1).map_or("cubes", |s| s.as_str());
    let n: i64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(4);
    let mode = args.get(3).map_or("auto", |s| s.as_str());
    let parts = match kind {
        "cubes" => common::lattice(n, 0),
        "loose" => common::lattice(n, 1),
        "boxes" => common::random_box_parts(n as usize, 16, 1),
        dir => {
            let t = Instant::now();
            let l = apart_assembly::load(std::path::Path::new(dir), &Default::default()).unwrap();
            println!("loaded in {:.2} s", t.elapsed().as_secs_f64());
            l.assembly.parts
        }
    };
    let ranking = match mode {
        "full" => apart_plan::Ranking::Full,
        "local" => apart_plan::Ranking::Local,
        _ => apart_plan::Ranking::Auto,
    };
    let opts = apart_plan::SequenceOptions {
        ranking,
        ..Default::default()
    };
    let (base, _) = resident();
    let t = Instant::now();
    let s = if mode == "old" {
        let r = apart_plan::BlockingRegions::compute(&parts).unwrap();
        apart_plan::sequence(&r, &opts)
    } else {
        let progress = apart_plan::Progress::new();
        apart_plan::sequence_parts(&parts, &opts, &progress, &mut |_| {}).unwrap()
    };
    let seconds = t.elapsed().as_secs_f64();
    let steps = s.steps.len().max(1);
    println!(
        "{} parts, {} steps, complete {}: {:.2} s ({:.2} ms per step), peak resident {:.1} MiB ({:.1} MiB before planning)",
        parts.len(),
        s.steps.len(),
        s.complete(),
        seconds,
        1e3 * seconds / steps as f64,
        mib(resident().1),
        mib(base)
    );
    let w = s.local;
    println!(
        "work: {} singles and {} pairs computed ({:.1} per step), {} likely directions; steps: {} ranked, {} single, {} pair, {} likely, {} full searches",
        w.singles,
        w.pairs,
        (w.singles + w.pairs) as f64 / steps as f64,
        w.likely_directions,
        w.ranked,
        w.single_steps,
        w.pair_steps,
        w.likely_steps,
        w.full_searches
    );
    if let Some((made, r)) = s.regions {
        println!(
            "pair regions made: {made} ({:.2} per part), {} sums, {} contact cones, {:.2} s of sums",
            made as f64 / parts.len() as f64,
            r.sums,
            r.contact_cones,
            r.sums_seconds + r.projection_seconds + r.unions_seconds
        );
    }
    // The heap of the plan itself (its steps list their subassemblies).
    let held: usize = s
        .steps
        .iter()
        .map(|st| (st.subassembly.capacity() + st.moving.capacity()) * 8)
        .sum();
    println!("the plan's steps hold {:.1} MiB", mib(held));
    if std::env::var("STEPS").is_ok() {
        for st in &s.steps {
            println!(
                "  {:?} along {:?}: {} ({}, {:.2} deg)",
                st.moving,
                st.direction.to_strings(),
                st.rule.key(),
                st.cell.name(),
                st.clearance_deg
            );
        }
    }
    drop(s);
    // One pair region's heap: every pair of a small piece of the assembly made up front.
    let few: Vec<apart_plan::Part> = parts.iter().take(24).cloned().collect();
    let r = apart_plan::BlockingRegions::compute(&few).unwrap();
    // Counted from the sizes of what a region holds (machine-integer coordinates; a
    // coordinate beyond 2^62 adds its digits).
    let bytes = |p: &apart_plan::regions::PairRegion| -> usize {
        use std::mem::size_of;
        let polygons: usize = p
            .polygons
            .iter()
            .map(|q| {
                size_of::<apart_sphere::SphericalPolygon>()
                    + std::mem::size_of_val(q.normals())
                    + std::mem::size_of_val(q.boundary())
            })
            .sum();
        size_of::<apart_plan::regions::PairRegion>()
            + polygons
            + p.region.arcs.len() * size_of::<(apart_sphere::Arc, apart_sphere::region::Sides)>()
            + p.region.points.len() * size_of::<(apart_kernel::Vec3, bool)>()
    };
    for touching in [true, false] {
        let of: Vec<usize> = r
            .pairs()
            .iter()
            .filter(|p| p.contact == touching)
            .map(bytes)
            .collect();
        if !of.is_empty() {
            println!(
                "bytes per pair region of {} parts (the first {} parts' {} such pairs): {:.0} on average, {} at most",
                if touching { "touching" } else { "separate" },
                few.len(),
                of.len(),
                of.iter().sum::<usize>() as f64 / of.len() as f64,
                of.iter().max().unwrap()
            );
        }
    }
}
