//! Timing of partition and sequence on many unit cubes: a touching lattice
//! `n × n × n` (or `a × b × c`), or with `gap` > 0 separated cubes (of side 1, spaced `1 + gap`).
//!
//! `cargo run --release -p apart-plan --example lattice_timing -- N [GAP] [partition|sequence|both]`
//! (`PER_SET=k` in the environment lists `k` partition solutions per moving set and kind).
#[path = "../tests/common/mod.rs"]
mod common;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    // N for a cube of N³, or AxBxC.
    let dims: Vec<i64> = args
        .get(1)
        .map_or("3", |s| s.as_str())
        .split('x')
        .map(|s| s.parse().unwrap())
        .collect();
    let [nx, ny, nz] = match dims[..] {
        [n] => [n, n, n],
        [a, b, c] => [a, b, c],
        _ => panic!("N or AxBxC"),
    };
    let gap: i64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(0);
    let what = args.get(3).map_or("both", |s| s.as_str());
    let step = 1 + gap;
    let mut parts = Vec::new();
    for x in 0..nx {
        for y in 0..ny {
            for z in 0..nz {
                let o = [x * step, y * step, z * step];
                parts.push(common::part(
                    &format!("c{x}_{y}_{z}"),
                    vec![common::cuboid(o, [o[0] + 1, o[1] + 1, o[2] + 1])],
                ));
            }
        }
    }
    let t = Instant::now();
    let regions = apart_plan::BlockingRegions::compute(&parts).unwrap();
    println!("{} parts, regions {:.2?}", parts.len(), t.elapsed());
    if what == "partition" || what == "both" {
        let t = Instant::now();
        let all: Vec<usize> = (0..parts.len()).collect();
        // PER_SET=k lists k solutions of each kind per moving set (counting the rest).
        let opts = apart_plan::Options {
            max_per_set: std::env::var("PER_SET").ok().and_then(|s| s.parse().ok()),
            ..Default::default()
        };
        let (p, _) = apart_plan::partition_subset(&regions, &all, &opts);
        println!(
            "{} listed of {} in {} moving sets",
            p.solutions.len(),
            p.solution_count(),
            p.sets.len()
        );
        println!(
            "partition {:.2?} (overlay {:.2} s, graphs {:.2} s): {} solutions, arcs {} vertices {} edges {} faces {}",
            t.elapsed(),
            p.stats.seconds.overlay,
            p.stats.seconds.graphs,
            p.solutions.len(),
            p.stats.arcs,
            p.stats.vertices,
            p.stats.edges,
            p.stats.faces
        );
        let kinds = [
            apart_plan::CellKind::Face,
            apart_plan::CellKind::Edge,
            apart_plan::CellKind::Vertex,
        ]
        .map(|k| p.solutions.iter().filter(|s| s.cell == k).count());
        let singles = p.solutions.iter().filter(|s| s.moving.len() == 1).count();
        println!("faces, edges, vertices: {kinds:?}; single moving parts: {singles}");
    }
    {
        let t = Instant::now();
        let all: Vec<usize> = (0..parts.len()).collect();
        let e = apart_plan::MotionSpace::estimate(&regions, &all);
        println!("estimate {:.2?}: {e:?}", t.elapsed());
    }
    if what == "arr" {
        // The bare arrangement of all pair regions (no statuses).
        let t = Instant::now();
        let n = parts.len();
        let mut owned = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                let r = &regions.pair(i, j).region;
                owned.push(r.clone());
                owned.push(r.antipodal());
            }
        }
        let refs: Vec<&apart_sphere::region::RegionMap> = owned.iter().collect();
        let (arcs, points) = apart_sphere::region::region_inputs(&refs);
        let count = arcs.len();
        let (arr, st) = apart_sphere::Arrangement::build(arcs, points);
        println!(
            "arrangement {:.2?}: arcs {count} circles {} vertices {} edges {} faces {} {st:?}",
            t.elapsed(),
            arr.circles().len(),
            arr.vertices().len(),
            arr.edges().len(),
            arr.faces().len()
        );
        return;
    }
    if what == "step" {
        let all: Vec<usize> = (0..parts.len()).collect();
        let t = Instant::now();
        // PER_SET=k lists k solutions of each kind per moving set (counting the rest).
        let opts = apart_plan::Options {
            max_per_set: std::env::var("PER_SET").ok().and_then(|s| s.parse().ok()),
            ..Default::default()
        };
        let (p, _) = apart_plan::partition_subset(&regions, &all, &opts);
        println!(
            "{} listed of {} in {} moving sets",
            p.solutions.len(),
            p.solution_count(),
            p.sets.len()
        );
        println!(
            "partition {:.2?} (overlay {:.2} s, graphs {:.2} s)",
            t.elapsed(),
            p.stats.seconds.overlay,
            p.stats.seconds.graphs
        );
        let t = Instant::now();
        let s = apart_plan::sequence::best_step(&regions, &all, &Default::default());
        println!("best step {:.2?}: {:?}", t.elapsed(), s.map(|s| s.moving));
        return;
    }
    if what == "sequence" || what == "both" {
        let t = Instant::now();
        let s = apart_plan::sequence(&regions, &Default::default());
        println!(
            "sequence {:.2?}: {} steps, complete {}",
            t.elapsed(),
            s.steps.len(),
            s.complete()
        );
    }
}
