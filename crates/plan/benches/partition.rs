//! Partitioning benchmark: prints a table of phase times, sizes, peak memory and the
//! two-thread speed-up for growing assemblies. `cargo bench -p apart-plan --bench partition`
//! (add `-- --quick` for a short run).

#[path = "../tests/common/mod.rs"]
mod common;

use apart_plan::{partition_pieces, sequence, BlockingRegions, Options, Part, SequenceOptions};
use std::time::Instant;

/// Resets the process's peak resident set size (Linux), so each case reports its own.
fn reset_peak() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

/// Peak resident set size in MiB since the last reset.
fn peak_mib() -> f64 {
    let s = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    s.lines()
        .find(|l| l.starts_with("VmHWM:"))
        .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// A row of `n` parts laid like two courses of bricks: part i is a lower brick
/// [2i, 2i+2] and an upper brick [2i+1, 2i+3] (in x), so neighbours interlock.
fn brick_row(n: i64) -> Vec<Part> {
    (0..n)
        .map(|i| {
            common::part(
                &format!("b{i}"),
                vec![
                    common::cuboid([2 * i, 0, 0], [2 * i + 2, 2, 1]),
                    common::cuboid([2 * i + 1, 0, 1], [2 * i + 3, 2, 2]),
                ],
            )
        })
        .collect()
}

/// `n` random disjoint boxes linked into `k` parts (paper 003, section 5.2).
fn random_boxes(n: usize, k: usize, seed: u64) -> Vec<Part> {
    common::random_box_parts(n, k, seed)
}

/// Two rings (64 segments, 16-gon section, 2,048 triangles each, decomposed exactly)
/// stacked around a cone of 158 triangles (paper 000, fig. 2). Returns the parts and
/// the decomposition time.
fn ring_and_cone() -> (Vec<Part>, f64) {
    use apart_kernel::Vec3;
    let ring = apart_testkit::shapes::Ring::new(64);
    let r = ring.radius;
    let shape = ring.shape();
    let points: Vec<Vec3> = shape.points.iter().map(|&p| Vec3::from_i64(p)).collect();
    let t = Instant::now();
    let lower = apart_decompose::decompose(&points, &shape.tris, &Default::default()).unwrap();
    let decompose_s = t.elapsed().as_secs_f64();
    let lift = Vec3::new(0, 0, 16 * r);
    let upper: Vec<apart_pieces::Polytope> =
        lower.pieces.iter().map(|p| p.translated(&lift)).collect();
    // Cone: apex (0, 0, 40R), base radius 14R at z = -20R (0.8R inside the rings' hole).
    let n = 80;
    let mut pts: Vec<Vec3> = (0..n)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            Vec3::new(
                (14.0 * r as f64 * t.cos()).round() as i64,
                (14.0 * r as f64 * t.sin()).round() as i64,
                -20 * r,
            )
        })
        .collect();
    pts.push(Vec3::new(0, 0, 40 * r));
    let apex = n as u32;
    let mut tris: Vec<[u32; 3]> = (0..n as u32)
        .map(|k| [k, (k + 1) % n as u32, apex])
        .collect();
    for k in 1..n as u32 - 1 {
        tris.push([0, k + 1, k]);
    }
    let cone = apart_pieces::Polytope::from_triangles(&pts, &tris).unwrap();
    let parts = vec![
        common::part("ring_lower", lower.pieces),
        common::part("ring_upper", upper),
        common::part("cone", vec![cone]),
    ];
    (parts, 2.0 * decompose_s)
}

struct Row {
    name: String,
    parts: usize,
    pieces: usize,
    sums: usize,
    cells: (usize, usize, usize),
    phases: [f64; 5],
    t1: f64,
    t2: f64,
    peak: f64,
    solutions: usize,
}

fn run(name: &str, parts: &[Part], reps: usize) -> Row {
    let pool = |k| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(k)
            .build()
            .unwrap()
    };
    let time = |k: usize| -> (f64, apart_plan::Partitioning) {
        pool(k).install(|| {
            let mut best = f64::INFINITY;
            let mut last = None;
            for _ in 0..reps {
                let t = Instant::now();
                let r = partition_pieces(parts, &Options::default()).unwrap();
                best = best.min(t.elapsed().as_secs_f64());
                last = Some(r);
            }
            (best, last.unwrap())
        })
    };
    reset_peak();
    let (t1, r) = time(1);
    let peak = peak_mib();
    let (t2, _) = time(2);
    let s = r.stats;
    Row {
        name: name.to_string(),
        parts: parts.len(),
        pieces: s.pieces,
        sums: s.sums,
        cells: (s.vertices, s.edges, s.faces),
        phases: [
            s.seconds.sums,
            s.seconds.projection,
            s.seconds.unions,
            s.seconds.overlay,
            s.seconds.graphs,
        ],
        t1,
        t2,
        peak,
        solutions: r.solutions.len(),
    }
}

/// A 5 x 5 x 2 block of unit cubes (50 parts) on a base plate with a lid on top.
fn cube_block() -> Vec<Part> {
    let mut parts = vec![common::part(
        "base",
        vec![common::cuboid([-1, -1, -1], [6, 6, 0])],
    )];
    for z in 0..2 {
        for y in 0..5 {
            for x in 0..5 {
                parts.push(common::part(
                    &format!("c{x}{y}{z}"),
                    vec![common::cuboid([x, y, z], [x + 1, y + 1, z + 1])],
                ));
            }
        }
    }
    parts.push(common::part(
        "lid",
        vec![common::cuboid([-1, -1, 2], [6, 6, 3])],
    ));
    parts
}

/// Full disassembly plans: time for the shared pair regions (computed once) against the
/// time of all the per-step overlays and graphs.
fn sequences(quick: bool) {
    println!("\n| assembly (sequence) | parts | steps | complete | pair regions ms | steps ms | share of regions |");
    println!("|---|---|---|---|---|---|---|");
    let mut cases: Vec<(String, Vec<Part>)> = Vec::new();
    for seed in [1u64, 2, 3] {
        if quick && seed > 1 {
            break;
        }
        cases.push((
            format!("random boxes 128/16, seed {seed}"),
            random_boxes(128, 16, seed),
        ));
    }
    cases.push(("52 parts: 5 x 5 x 2 cubes, base, lid".into(), cube_block()));
    for (name, parts) in cases {
        let t = Instant::now();
        let regions = BlockingRegions::compute(&parts).unwrap();
        let tr = t.elapsed().as_secs_f64();
        let s = sequence(&regions, &SequenceOptions::default());
        println!(
            "| {name} | {} | {} | {} | {:.1} | {:.1} | {:.0}% |",
            parts.len(),
            s.steps.len(),
            s.complete(),
            tr * 1000.0,
            s.step_seconds * 1000.0,
            100.0 * tr / (tr + s.step_seconds)
        );
    }
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let mut rows = Vec::new();
    rows.push(run(
        "split star",
        &common::split_star(),
        if quick { 20 } else { 200 },
    ));
    for n in [4, 8, 16, 32, 64] {
        if quick && n > 16 {
            break;
        }
        rows.push(run(&format!("brick row {n}"), &brick_row(n), 3));
    }
    for (n, k) in [(4, 2), (8, 4), (16, 4), (32, 8), (64, 8), (128, 16)] {
        if quick && n > 32 {
            break;
        }
        rows.push(run(
            &format!("random boxes {n}/{k}"),
            &random_boxes(n, k, 7 + n as u64),
            3,
        ));
    }
    let (rc, dec) = ring_and_cone();
    let row = run("ring and cone", &rc, if quick { 1 } else { 3 });
    println!(
        "ring and cone: decomposition of the two rings {:.1} ms (64 pieces each), partition {:.1} ms (1 thread), {:.1} ms (2 threads): end to end {:.1} ms",
        dec * 1000.0,
        row.t1 * 1000.0,
        row.t2 * 1000.0,
        (dec + row.t1) * 1000.0
    );
    rows.push(row);
    println!(
        "| assembly | parts | pieces | sums | V/E/F | sums ms | proj ms | unions ms | overlay ms | graphs ms | total 1 thread ms | total 2 threads ms | speed-up | peak MiB | solutions |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for r in rows {
        let [a, b, c, d, e] = r.phases.map(|x| x * 1000.0);
        println!(
            "| {} | {} | {} | {} | {}/{}/{} | {a:.2} | {b:.2} | {c:.2} | {d:.2} | {e:.2} | {:.2} | {:.2} | {:.2}x | {:.1} | {} |",
            r.name, r.parts, r.pieces, r.sums, r.cells.0, r.cells.1, r.cells.2, r.t1 * 1000.0, r.t2 * 1000.0, r.t1 / r.t2, r.peak, r.solutions
        );
    }
    sequences(quick);
}
