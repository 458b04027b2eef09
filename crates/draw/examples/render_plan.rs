//! Plans an assembly folder and writes every picture and export to an output folder:
//! `cargo run -p apart-draw --release --example render_plan -- examples/split-star-3 /tmp/out`
//! (`bricks` instead of a folder: a 20-part assembly built in code, four rows of five
//! interlocking stepped bricks).
#[path = "../tests/common/mod.rs"]
mod common;

use apart_draw::{SphereProjection, SphereSvgOptions, View};
use apart_plan::SequenceOptions;
use apart_plan::{parts_of, sequence, BlockingRegions, KeepSolutions, MotionSpace};
use std::time::Instant;

fn main() {
    let mut args = std::env::args().skip(1);
    let input = args
        .next()
        .unwrap_or_else(|| "examples/split-star-3".into());
    let out = std::path::PathBuf::from(args.next().unwrap_or_else(|| "/tmp/apart-draw".into()));
    std::fs::create_dir_all(&out).unwrap();
    let assembly = if input == "bricks" {
        // 20 parts given by convex pieces only.
        common::assembly_of("bricks-20", common::brick_rows())
    } else {
        let loaded =
            apart_assembly::load(std::path::Path::new(&input), &Default::default()).unwrap();
        assert!(loaded.is_valid(), "{:?}", loaded.problems);
        loaded.assembly
    };
    let a = &assembly;
    let regions = BlockingRegions::compute(parts_of(a).unwrap()).unwrap();
    // Every step keeps its solutions, for its sphere pictures.
    let opts = SequenceOptions {
        keep_solutions: KeepSolutions::EveryStep,
        ..Default::default()
    };
    let plan = sequence(&regions, &opts);
    println!(
        "{}: {} parts, {} steps",
        a.name,
        a.parts.len(),
        plan.steps.len()
    );

    let t = Instant::now();
    let glb = apart_draw::disassembly_glb(a, &plan);
    std::fs::write(out.join("plan.glb"), &glb).unwrap();
    println!(
        "glb: {} bytes in {:.3} s",
        glb.len(),
        t.elapsed().as_secs_f64()
    );

    let t = Instant::now();
    let html = apart_draw::disassembly_html(a, &plan);
    std::fs::write(out.join("plan.html"), &html).unwrap();
    println!(
        "html: {} bytes in {:.3} s",
        html.len(),
        t.elapsed().as_secs_f64()
    );

    let t = Instant::now();
    let png = apart_draw::assembly_png(a, &[], &View::default(), 800, 600);
    std::fs::write(out.join("assembly.png"), &png).unwrap();
    println!("assembly png in {:.3} s", t.elapsed().as_secs_f64());

    let t = Instant::now();
    let steps = apart_draw::step_pngs(a, &plan, &View::default(), 800, 600);
    for (k, png) in steps.iter().enumerate() {
        std::fs::write(out.join(format!("step-{}.png", k + 1)), png).unwrap();
    }
    println!(
        "{} step pngs in {:.3} s",
        steps.len(),
        t.elapsed().as_secs_f64()
    );

    let t = Instant::now();
    for (k, step) in plan.steps.iter().enumerate() {
        let ms = MotionSpace::build_split_at_equator(&regions, &step.subassembly);
        for (projection, tag) in [
            (SphereProjection::EqualArea, "equal-area"),
            (SphereProjection::Orthographic, "orthographic"),
        ] {
            let opts = SphereSvgOptions {
                projection,
                ..Default::default()
            };
            let svg = apart_draw::step_motion_space_svg(&ms, regions.names(), step, &opts);
            std::fs::write(out.join(format!("step-{}-sphere-{tag}.svg", k + 1)), &svg).unwrap();
            let png = apart_draw::step_motion_space_png(&ms, regions.names(), step, &opts);
            std::fs::write(out.join(format!("step-{}-sphere-{tag}.png", k + 1)), &png).unwrap();
        }
    }
    println!(
        "sphere svg+png for every step in {:.3} s",
        t.elapsed().as_secs_f64()
    );
}
