//! Writes the motion-space SVG of an assembly built in code (for eyeballing).
#[path = "../tests/common/mod.rs"]
mod common;

use apart_testkit::assemblies;

fn main() {
    let which = std::env::args().nth(1).unwrap_or_else(|| "star".into());
    let parts = match which.as_str() {
        "cubes" => assemblies::stacked_cubes(),
        "peg" => assemblies::peg_in_hole(),
        "dovetail" => assemblies::dovetail(),
        "row" => assemblies::cubes_in_a_row(4),
        _ => assemblies::split_star(),
    };
    let parts = common::parts(parts);
    let regions = apart_plan::BlockingRegions::compute(&parts).unwrap();
    let all: Vec<usize> = (0..parts.len()).collect();
    let (p, _) = apart_plan::partition_subset(&regions, &all, &Default::default());
    let ms = apart_plan::MotionSpace::build_split_at_equator(&regions, &all);
    let svg = apart_draw::motion_space_svg(
        &ms,
        regions.names(),
        &p.solutions,
        &apart_draw::SphereSvgOptions {
            title: which.clone(),
            ..Default::default()
        },
    );
    std::fs::write(format!("/tmp/{which}.svg"), svg).unwrap();
}
