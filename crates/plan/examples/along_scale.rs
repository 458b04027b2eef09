//! Timing of `DirectionQuery` on lattices of unit cubes (scratch bench): the query's
//! set-up, its candidates, one answer per direction, and the first solution.
//!
//! `cargo run --release -p apart-plan --example along_scale -- N [GAP] [DIRS...]`
#[path = "../tests/common/mod.rs"]
mod common;
use apart_kernel::Vec3;
use apart_plan::DirectionQuery;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Some(dir) = args.get(1).filter(|a| a.contains('/')) {
        let t = Instant::now();
        let l = apart_assembly::load(std::path::Path::new(dir), &Default::default()).unwrap();
        println!("load {:.3} s", t.elapsed().as_secs_f64());
        let parts = apart_plan::parts_of(&l.assembly).unwrap();
        if args.get(2).is_some_and(|a| a == "cand") {
            let q = DirectionQuery::new(parts).unwrap();
            let t = Instant::now();
            let c = q.candidates();
            println!("candidates {:.3} s: {}", t.elapsed().as_secs_f64(), c.len());
            return;
        }
        let t = Instant::now();
        let r = apart_plan::partition_first(parts).unwrap();
        println!(
            "partition_first {:.3} s: {:?}",
            t.elapsed().as_secs_f64(),
            r.solutions
                .first()
                .map(|s| (&s.moving, s.direction.to_strings(), s.cell.name()))
        );
        let t = Instant::now();
        let q = DirectionQuery::new(parts).unwrap();
        println!("new {:.3} s", t.elapsed().as_secs_f64());
        let t = Instant::now();
        let c = q.candidates();
        println!("candidates {:.3} s: {}", t.elapsed().as_secs_f64(), c.len());
        println!("{:?}", q.stats());
        println!(
            "box of part 0: {:?}",
            parts[0].pieces[0]
                .vertices()
                .iter()
                .map(|v| v.to_strings())
                .collect::<Vec<_>>()
        );
        for d in [[0, 0, 1], [1, 0, 0]].map(Vec3::from_i64) {
            let t = Instant::now();
            let a = q.answer(&d).unwrap();
            println!(
                "answer {:?} {:.3} s: {} arcs, {}",
                d.to_strings(),
                t.elapsed().as_secs_f64(),
                a.dbg.arcs().len(),
                a.cell.name()
            );
        }
        println!("{:?}", q.stats());
        return;
    }
    let n: i64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(10);
    let gap: i64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(0);
    let dirs: Vec<Vec3> = if args.len() > 3 {
        args[3..]
            .iter()
            .map(|s| {
                let c: Vec<i64> = s.split(',').map(|x| x.parse().unwrap()).collect();
                Vec3::new(c[0], c[1], c[2])
            })
            .collect()
    } else {
        [
            [0, 0, 1],
            [1, 0, 0],
            [1, 1, 0],
            [1, 1, 1],
            [1, 2, 3],
            [3, -1, 2],
        ]
        .map(Vec3::from_i64)
        .to_vec()
    };
    // Cubes of side 2^20 (a loaded assembly's grid is that fine: the piece boxes'
    // widening by 2 is negligible).
    let s = 1i64 << 20;
    let mut parts = Vec::new();
    for x in 0..n {
        for y in 0..n {
            for z in 0..n {
                let o = [x, y, z].map(|c| c * (s + gap * s));
                let hi = o.map(|c| c + s);
                parts.push(common::part(
                    &format!("c{x}{y}{z}"),
                    vec![common::cuboid(o, hi)],
                ));
            }
        }
    }
    let t = Instant::now();
    let q = DirectionQuery::new(&parts).unwrap();
    println!(
        "{} parts: new {:.3} s",
        parts.len(),
        t.elapsed().as_secs_f64()
    );
    let t = Instant::now();
    let c = q.candidates();
    println!("candidates {:.3} s: {}", t.elapsed().as_secs_f64(), c.len());
    for d in &dirs {
        for round in 0..2 {
            let t = Instant::now();
            let a = q.answer(d).unwrap();
            let took = t.elapsed().as_secs_f64();
            let t = Instant::now();
            let sets = a.dbg.minimal_moving_sets().len();
            println!(
                "answer {:?} (round {round}) {took:.3} s (of which minimal moving sets {:.3} s, {sets}): {} arcs, {} moving sets, {}",
                d.to_strings(),
                t.elapsed().as_secs_f64(),
                a.dbg.arcs().len(),
                a.moving.len(),
                a.cell.name()
            );
        }
    }
    // A subassembly: every other part (a hierarchy of its own per call).
    let half: Vec<usize> = (0..parts.len()).filter(|k| k % 2 == 0).collect();
    for d in &dirs {
        let t = Instant::now();
        let a = q.answer_in(&half, d).unwrap();
        println!(
            "answer_in {} parts {:?} {:.3} s: {} arcs, {}",
            half.len(),
            d.to_strings(),
            t.elapsed().as_secs_f64(),
            a.dbg.arcs().len(),
            a.cell.name()
        );
    }
    let t = Instant::now();
    let s = q.first_solution().unwrap();
    println!(
        "first {:.3} s: {:?}",
        t.elapsed().as_secs_f64(),
        s.map(|s| (
            s.moving,
            s.direction.to_strings(),
            s.cell.name(),
            s.clearance_deg
        ))
    );
    println!("{:?}", q.stats());
}
