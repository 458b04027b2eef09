//! Checks [`project_apart`] against the projection of the whole sum on every piece pair
//! of two parts of an assembly, and times both (single-threaded).
//!
//! `cargo run --release -p apart-minkowski --example apart_check -- FOLDER [auto] [PART PART]`

use apart_assembly::{load, LoadOptions, Tolerance};
use apart_minkowski::{project, project_apart, sum_prepared, Projection, Summand};
use std::time::{Duration, Instant};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let auto = args.iter().any(|a| a == "auto");
    let names: Vec<&String> = args[1..].iter().filter(|a| *a != "auto").collect();
    let opts = LoadOptions {
        tolerance: if auto {
            Tolerance::Auto
        } else {
            Tolerance::None
        },
        ..LoadOptions::default()
    };
    let loaded = load(std::path::Path::new(&args[0]), &opts).expect("load");
    let parts = &loaded.assembly.parts;
    let index = |name: &str| parts.iter().position(|p| p.name == name).expect("a part");
    let pairs: Vec<(usize, usize)> = match names.as_slice() {
        [a, b] => vec![(index(a), index(b))],
        _ => (0..parts.len())
            .flat_map(|i| {
                (0..parts.len())
                    .filter(move |&j| j != i)
                    .map(move |j| (i, j))
            })
            .collect(),
    };
    let (mut apart, mut inside, mut whole_time, mut apart_time) =
        (0usize, 0usize, Duration::ZERO, Duration::ZERO);
    for (i, j) in pairs {
        let moving: Vec<Summand> = parts[i]
            .pieces
            .iter()
            .map(|a| Summand::new(a.reflected()))
            .collect();
        let fixed: Vec<Summand> = parts[j]
            .pieces
            .iter()
            .map(|b| Summand::new(b.clone()))
            .collect();
        for sa in &moving {
            for sb in &fixed {
                let t = Instant::now();
                let whole = sum_prepared(sb, sa).expect("sum");
                let projected = project(&whole).expect("projection");
                whole_time += t.elapsed();
                let t = Instant::now();
                let fast = project_apart(sb, sa);
                apart_time += t.elapsed();
                let outside = whole
                    .facets()
                    .iter()
                    .any(|f| f.offset < apart_kernel::Int::ZERO);
                match (fast, projected) {
                    (None, _) => {
                        assert!(!outside, "the origin lies outside");
                        inside += 1;
                    }
                    (Some(Ok(f)), Projection::Polygon(p)) => {
                        let key = |x: &apart_sphere::SphericalPolygon| {
                            let mut v: Vec<String> =
                                x.boundary().iter().map(|a| format!("{a:?}")).collect();
                            v.sort();
                            v
                        };
                        assert_eq!(key(&f), key(&p), "{} and {}", parts[i].name, parts[j].name);
                        apart += 1;
                    }
                    (f, p) => panic!("{f:?} against {p:?}"),
                }
            }
        }
    }
    let n = (apart + inside).max(1) as f64;
    println!(
        "{apart} pairs apart (same polygons), {inside} touching or overlapping; \
         whole sum and projection {:.3} ms per pair, project_apart {:.3} ms",
        whole_time.as_secs_f64() / n * 1e3,
        apart_time.as_secs_f64() / n * 1e3
    );
}
