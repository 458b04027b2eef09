//! Placement and stacking benchmark (paper 004 Tables I and II): per-call times of
//! obstacle construction, extrapolation and interference tests, the share of piece
//! pairs evaluated by partial c-space, and whole stacking runs. Prints tables;
//! `cargo bench -p apart-stack --bench stack` (add `-- --quick` to skip the longest run).

#[path = "../tests/common/parts.rs"]
mod parts;

use apart_kernel::{HPoint, Rational};
use apart_pieces::interference::interiors_meet_translated;
use apart_stack::extrapolate::Template;
use apart_stack::obstacle::ObstacleShape;
use apart_stack::orientation::{Orientation, ZRotation};
use apart_stack::part::PartModel;
use apart_stack::planner::{stack, StackOptions};
use parts::{channel, complex_part, cube, triangle_part};
use std::time::Instant;

/// Mean seconds per call of `f` over enough calls to take about 0.2 s.
fn per_call(mut f: impl FnMut()) -> f64 {
    let t = Instant::now();
    f();
    let once = t.elapsed().as_secs_f64().max(1e-7);
    let n = ((0.2 / once) as usize).clamp(3, 200_000);
    let t = Instant::now();
    for _ in 0..n {
        f();
    }
    t.elapsed().as_secs_f64() / n as f64
}

fn micro() {
    println!("## Per call (one convex piece pair)\n");
    println!("| operation | pieces | µs per call |");
    println!("|---|---|---:|");
    let c = cube(10);
    let complex = complex_part();
    // The largest and a typical piece of the complex part.
    let mut by_size: Vec<_> = complex.pieces.iter().collect();
    by_size.sort_by_key(|p| p.vertices().len());
    let small = by_size[by_size.len() / 2];
    let large = by_size[by_size.len() - 1];
    let cases = [
        ("cube pieces", &c.pieces[0], &c.pieces[0]),
        (
            "complex part, typical pieces",
            small as &apart_pieces::Polytope,
            small,
        ),
        ("complex part, largest pieces", large, large),
    ];
    for (name, a, b) in cases {
        let label = format!("{} + {} vertices", a.vertices().len(), b.vertices().len());
        let t = per_call(|| {
            std::hint::black_box(ObstacleShape::compute(a, b).unwrap());
        });
        println!(
            "| obstacle construction, {name} | {label} | {:.1} |",
            t * 1e6
        );
        let turn = ZRotation::nearest(10.0, 0.05);
        let o = ObstacleShape::compute(a, &apart_stack::extrapolate::rotate_z(b, turn)).unwrap();
        if let Some(tpl) = Template::new(a, b, turn, &o) {
            let other = ZRotation::nearest(10.5, 0.05);
            let quarter = ZRotation::nearest(100.0, 0.05);
            let t = per_call(|| {
                std::hint::black_box(tpl.valid_at(quarter));
            });
            println!(
                "| structure check (a miss, 90° away), {name} | {label} | {:.1} |",
                t * 1e6
            );
            if tpl.valid_at(other) {
                let t = per_call(|| {
                    std::hint::black_box(tpl.extrapolate(other));
                });
                println!("| extrapolation, {name} | {label} | {:.1} |", t * 1e6);
            }
        }
        let shift = HPoint::from_rationals(&[qfrac(1, 2), q(1), q(0)]);
        let zero = HPoint::from_rationals(&[q(0), q(0), q(0)]);
        let t = per_call(|| {
            std::hint::black_box(interiors_meet_translated(a, &shift.sub(&zero), b));
        });
        println!("| interference test, {name} | {label} | {:.1} |", t * 1e6);
    }
    println!();
}

/// The options of a bench run: `n` parts on a square floor about `sqrt(n)` parts wide.
fn bench_options(part: &PartModel, n: usize, w: (i64, i64), dtheta: f64) -> StackOptions {
    let e = part.orient(&Orientation::IDENTITY).extent;
    let size = (0..2)
        .map(|i| (&e.max[i] - &e.min[i]).to_f64())
        .fold(0.0, f64::max);
    let side = ((n as f64).sqrt().ceil() * size * 1.25).ceil() as i64;
    let half = side / 2 + 1;
    let height = &(&e.max[2] - &e.min[2]) * &q(n as i64);
    let mut opts = StackOptions::new(
        n,
        qfrac(w.0, w.1),
        [q(-half), q(-half), q(half), q(half)],
        height,
    );
    opts.dtheta_deg = dtheta;
    opts
}

fn run(part: &PartModel, n: usize, w: (i64, i64), dtheta: f64, phases: &mut Vec<String>) {
    let opts = bench_options(part, n, w, dtheta);
    let plan = stack(part, &opts).unwrap();
    let s = &plan.stats;
    let pct = 100.0 * s.place.pairs_evaluated as f64 / s.place.pairs_total.max(1) as f64;
    let fresh = s.obstacles.fresh_seconds / s.obstacles.fresh.max(1) as f64;
    let tried = s.obstacles.extrapolated + s.obstacles.extrapolation_misses;
    let extra = s.obstacles.extrapolate_seconds;
    println!(
        "| {} ({} pieces) | {n} | {}/{} | {} | {:.3} | {} / {} ({pct:.3}%) | {} ({:.1} µs) | {} of {} tried ({:.1} ms with templates) | {:.2} |",
        part.name,
        part.pieces.len(),
        w.0,
        w.1,
        s.orientations,
        plan.stack_height.to_f64(),
        s.place.pairs_evaluated,
        s.place.pairs_total,
        s.obstacles.fresh,
        fresh * 1e6,
        s.obstacles.extrapolated,
        tried,
        extra * 1e3,
        s.seconds
    );
    phases.push(format!(
        "| {} ({n}, w = {}/{}, {dtheta}°) | {:.2} | {:.2} | {:.2} | {:.2} | {} | {} | {} | {:.2} |",
        part.name,
        w.0,
        w.1,
        s.place.detect_seconds,
        s.place.cells_seconds,
        s.stability_seconds,
        s.lowering_seconds,
        s.unstable,
        s.place.unsupported,
        s.place.cells,
        s.seconds
    ));
}

/// Stacking runs with and without extrapolation: the obstacle time of each (fresh
/// construction, plus templates and extrapolation) and their ratio. The plans are the
/// same (extrapolated obstacles are the fresh ones).
fn extrapolation_run(part: &PartModel, n: usize, dtheta: f64) {
    // Alternating runs, the least obstacle time of three each (the machine is shared).
    let mut opts = bench_options(part, n, (1, 2), dtheta);
    let mut runs = Vec::new();
    for _ in 0..3 {
        for extrapolate in [true, false] {
            opts.extrapolate = extrapolate;
            runs.push((extrapolate, stack(part, &opts).unwrap()));
        }
    }
    let obstacle_time = |p: &apart_stack::planner::StackPlan| {
        p.stats.obstacles.fresh_seconds + p.stats.obstacles.extrapolate_seconds
    };
    let best = |e: bool| {
        runs.iter()
            .filter(|r| r.0 == e)
            .map(|r| &r.1)
            .min_by(|x, y| obstacle_time(x).total_cmp(&obstacle_time(y)))
            .expect("three runs")
    };
    let (with, without) = (best(true), best(false));
    let (a, b) = (&with.stats.obstacles, &without.stats.obstacles);
    let t_with = obstacle_time(with);
    let t_without = obstacle_time(without);
    println!(
        "| {} ({n}) | {dtheta}° | {} | {} fresh + {} extrapolated ({} misses) | {:.1} ms | {} fresh | {:.1} ms | {:.2}x | {:.1} / {:.1} µs | {:.2} / {:.2} |",
        part.name,
        with.stats.orientations,
        a.fresh,
        a.extrapolated,
        a.extrapolation_misses,
        t_with * 1e3,
        b.fresh,
        t_without * 1e3,
        t_without / t_with.max(1e-9),
        1e6 * a.extrapolate_seconds / a.extrapolated.max(1) as f64,
        1e6 * b.fresh_seconds / b.fresh.max(1) as f64,
        with.stats.seconds,
        without.stats.seconds,
    );
}

fn q(v: i64) -> Rational {
    Rational::from(v)
}

fn qfrac(n: i64, d: i64) -> Rational {
    Rational::from_i128(n.into(), d.into())
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    println!(
        "apart-stack benchmark, {} threads available\n",
        std::thread::available_parallelism().map_or(1, |n| n.get())
    );
    micro();
    println!("## Stacking runs (Δθ = 90°)\n");
    println!("| part | n | w | orientations | stack height | piece pairs evaluated / total | fresh obstacles (mean) | extrapolated | seconds |");
    println!("|---|---:|---|---:|---:|---:|---:|---:|---:|");
    let mut phases = Vec::new();
    for w in [(0, 1), (1, 2), (1, 1)] {
        run(&cube(1), 121, w, 90.0, &mut phases);
    }
    run(&channel(), 15, (1, 2), 90.0, &mut phases);
    run(&triangle_part(), 15, (1, 2), 90.0, &mut phases);
    if !quick {
        run(&complex_part(), 15, (1, 2), 90.0, &mut phases);
    }
    println!("\n## Stacking runs with finer steps\n");
    println!("| part | n | w | orientations | stack height | piece pairs evaluated / total | fresh obstacles (mean) | extrapolated | seconds |");
    println!("|---|---:|---|---:|---:|---:|---:|---:|---:|");
    for step in [30.0, 15.0] {
        run(&channel(), 15, (1, 2), step, &mut phases);
        run(&triangle_part(), 15, (1, 2), step, &mut phases);
        run(&complex_part(), 3, (1, 2), step, &mut phases);
    }
    println!("\n## Where the time goes (seconds)\n");
    println!("| run | interference detection | cells and QPs | stability | lowering check | unstable candidates | cells dropped unsupported | cells | total |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for p in phases {
        println!("{p}");
    }
    println!("\n## Extrapolation against fresh construction (same plans)\n");
    println!("| part | step | orientations | obstacles, extrapolating | obstacle time | obstacles, fresh only | obstacle time | speed-up | per extrapolated / per fresh obstacle | run seconds with / without |");
    println!("|---|---:|---:|---|---:|---|---:|---:|---:|---:|");
    for step in [30.0, 15.0] {
        extrapolation_run(&triangle_part(), 15, step);
        extrapolation_run(&complex_part(), 3, step);
    }
}
