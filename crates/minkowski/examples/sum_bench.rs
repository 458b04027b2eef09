//! Times the exact Minkowski sums `b ⊕ (−a)` of every piece pair of different parts of
//! an assembly, single-threaded, and optionally checks each against the old exact path.
//!
//! `cargo run --release -p apart-minkowski --example sum_bench -- FOLDER [auto] [stride N] [check]`

#[path = "../tests/support/reference.rs"]
mod reference;

use apart_assembly::{load, LoadOptions, Tolerance};
use apart_minkowski::{project, sum_prepared, Summand};
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = std::path::PathBuf::from(&args[0]);
    let auto = args.iter().any(|a| a == "auto");
    let check = args.iter().any(|a| a == "check");
    let stride: usize = args
        .iter()
        .position(|a| a == "stride")
        .map(|i| args[i + 1].parse().unwrap())
        .unwrap_or(1);
    let opts = LoadOptions {
        tolerance: if auto {
            Tolerance::Auto
        } else {
            Tolerance::None
        },
        ..LoadOptions::default()
    };
    let t = Instant::now();
    let loaded = load(&path, &opts).expect("load");
    let parts = &loaded.assembly.parts;
    println!("loaded in {:.1} s", t.elapsed().as_secs_f64());
    let t = Instant::now();
    let fixed: Vec<Vec<Summand>> = parts
        .iter()
        .map(|p| p.pieces.iter().map(|x| Summand::new(x.clone())).collect())
        .collect();
    let refl: Vec<Vec<Summand>> = parts
        .iter()
        .map(|p| {
            p.pieces
                .iter()
                .map(|x| Summand::new(x.reflected()))
                .collect()
        })
        .collect();
    println!("summands in {:.1} ms", t.elapsed().as_secs_f64() * 1e3);
    let mut jobs = Vec::new();
    for i in 0..parts.len() {
        for j in 0..parts.len() {
            if i == j {
                continue;
            }
            for a in 0..parts[i].pieces.len() {
                for b in 0..parts[j].pieces.len() {
                    jobs.push((i, j, a, b));
                }
            }
        }
    }
    let jobs: Vec<_> = jobs.into_iter().step_by(stride).collect();
    let t = Instant::now();
    let mut facets = 0usize;
    for &(i, j, a, b) in &jobs {
        let m = sum_prepared(&fixed[j][b], &refl[i][a]).expect("sum");
        facets += m.facets().len();
    }
    let dt = t.elapsed().as_secs_f64();
    let sums: Vec<_> = jobs
        .iter()
        .map(|&(i, j, a, b)| sum_prepared(&fixed[j][b], &refl[i][a]).expect("sum"))
        .collect();
    let t = Instant::now();
    for m in &sums {
        project(m).expect("projection");
    }
    let dtp = t.elapsed().as_secs_f64();
    drop(sums);
    println!(
        "{} projections in {:.1} ms ({:.1} µs each)",
        jobs.len(),
        dtp * 1e3,
        dtp * 1e6 / jobs.len() as f64
    );
    println!(
        "{} sums in {:.1} ms ({:.1} µs each, {} facets)",
        jobs.len(),
        dt * 1e3,
        dt * 1e6 / jobs.len() as f64,
        facets
    );
    if check {
        let t = Instant::now();
        for &(i, j, a, b) in &jobs {
            let m = sum_prepared(&fixed[j][b], &refl[i][a]).expect("sum");
            let r = reference::reference_sum(fixed[j][b].polytope(), refl[i][a].polytope())
                .expect("reference");
            assert!(
                reference::identical(&m, &r),
                "sum of pieces {i}.{a} and {j}.{b} differs from the reference"
            );
            let (x, y) = (project(&m), reference::reference_project(&m));
            assert!(
                reference::same_projection(&x.expect("projection"), &y.expect("projection")),
                "projection of pieces {i}.{a} and {j}.{b} differs from the reference"
            );
        }
        println!(
            "all identical to the reference ({:.1} ms for both)",
            t.elapsed().as_secs_f64() * 1e3
        );
    }
}
