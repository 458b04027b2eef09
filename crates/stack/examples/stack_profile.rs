//! One stacking run with every counter printed, for profiling (`perf record`):
//! `cargo run --release -p apart-stack --example stack_profile -- complex 15 90`
//! (part, count, angle step; a fourth argument `fresh` turns extrapolation off).

#[path = "../tests/common/parts.rs"]
mod parts;

use apart_kernel::Rational;
use apart_stack::orientation::Orientation;
use apart_stack::planner::{stack, StackOptions};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let name = args.get(1).map_or("complex", |s| s.as_str());
    let n: usize = args.get(2).map_or(15, |s| s.parse().unwrap());
    let dtheta: f64 = args.get(3).map_or(90.0, |s| s.parse().unwrap());
    let part = match name {
        "cube" => parts::cube(1),
        "channel" => parts::channel(),
        "triangle" => parts::triangle_part(),
        _ => parts::complex_part(),
    };
    let e = part.orient(&Orientation::IDENTITY).extent;
    let size = (0..2)
        .map(|i| (&e.max[i] - &e.min[i]).to_f64())
        .fold(0.0, f64::max);
    let side = ((n as f64).sqrt().ceil() * size * 1.25).ceil() as i64;
    let half = side / 2 + 1;
    let height = &(&e.max[2] - &e.min[2]) * &Rational::from(n as i64);
    let h = Rational::from(half);
    let mut opts = StackOptions::new(
        n,
        Rational::from_i128(1, 2),
        [-&h, -&h, h.clone(), h.clone()],
        height,
    );
    opts.dtheta_deg = dtheta;
    opts.extrapolate = args.get(4).is_none_or(|s| s != "fresh");
    let plan = stack(&part, &opts).unwrap();
    println!("{:#?}", plan.stats);
    println!("height {} complete {}", plan.stack_height, plan.complete);
    println!("total cost {}", plan.total_cost());
    for p in &plan.placements {
        println!(
            "{} o{} stage{} examined {} t {:?} cost {}",
            p.index,
            p.orientation_index,
            p.stage,
            p.examined,
            p.translation
                .iter()
                .map(|v| v.to_string())
                .collect::<Vec<_>>(),
            p.cost
        );
    }
}
