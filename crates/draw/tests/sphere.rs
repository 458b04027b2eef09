//! The motion-space sphere for a plan step: legend by part names, the chosen direction
//! ringed where each projection puts it, and the PNG rendering.

mod common;

use apart_assembly::Assembly;
use apart_draw::colors::part_colors;
use apart_draw::{
    motion_space_png, motion_space_svg, step_motion_space_png, step_motion_space_svg,
    SphereProjection, SphereSvgOptions,
};
use apart_plan::{
    partition_subset, sequence, BlockingRegions, KeepSolutions, MotionSpace, Sequence,
    SequenceOptions,
};
use common::count_shades;
use resvg::tiny_skia::Pixmap;

/// The shared regions and the default plan, every step keeping its solutions to draw.
fn plan(a: &Assembly) -> (BlockingRegions, Sequence) {
    let regions = BlockingRegions::compute(apart_plan::parts_of(a).unwrap()).unwrap();
    let opts = SequenceOptions {
        keep_solutions: KeepSolutions::EveryStep,
        ..Default::default()
    };
    let plan = sequence(&regions, &opts);
    (regions, plan)
}

/// The motion space the sphere pictures draw, of the parts `subset`.
fn space(regions: &BlockingRegions, subset: &[usize]) -> MotionSpace {
    MotionSpace::build_split_at_equator(regions, subset)
}

/// Centre of the ring drawn around the chosen direction in the upper hemisphere.
fn ring_center(svg: &str) -> (f64, f64) {
    let line = svg
        .lines()
        .find(|l| l.contains(r#"r="12""#) && l.contains("chosen direction"))
        .expect("the chosen direction is ringed");
    let attr = |name: &str| -> f64 {
        let at = line.find(&format!(r#" {name}=""#)).unwrap() + name.len() + 3;
        line[at..].split('"').next().unwrap().parse().unwrap()
    };
    (attr("cx"), attr("cy"))
}

#[test]
fn the_chosen_direction_sits_where_each_projection_puts_it() {
    let a = common::example("split-star-3");
    let (regions, plan) = plan(&a);
    // The first step of the Split Star leaves along a diagonal (±1, ±1, ±1).
    let step = &plan.steps[0];
    let u = step.unit;
    assert!(u[2] > 0.0 && (u[0].abs() - u[1].abs()).abs() < 1e-12);
    let r = 200.0;
    // The upper disk is centred at (margin + r, margin + 40 + r) with margin 60.
    let (cx, cy) = (60.0 + r, 100.0 + r);
    for (projection, k) in [
        (SphereProjection::Orthographic, 1.0),
        (SphereProjection::EqualArea, (1.0 / (1.0 + u[2])).sqrt()),
    ] {
        let opts = SphereSvgOptions {
            radius: r,
            projection,
            ..Default::default()
        };
        let ms = space(&regions, &step.subassembly);
        let svg = step_motion_space_svg(&ms, regions.names(), step, &opts);
        let (x, y) = ring_center(&svg);
        assert!(
            (x - (cx + r * k * u[0])).abs() < 0.01,
            "{projection:?}: x {x}"
        );
        assert!(
            (y - (cy - r * k * u[1])).abs() < 0.01,
            "{projection:?}: y {y}"
        );
        // The legend names the parts, and the moving ones in the title.
        for p in &a.parts {
            assert!(svg.contains(&p.name));
        }
        assert!(svg.contains("move along (1, 1, 1)") || svg.contains("move along ("));
    }
}

#[test]
fn each_moving_subset_is_listed_by_part_names() {
    let a = common::example("split-star-3");
    let (regions, _) = plan(&a);
    let all: Vec<usize> = (0..a.parts.len()).collect();
    let (p, _) = partition_subset(&regions, &all, &Default::default());
    let ms = space(&regions, &all);
    let svg = motion_space_svg(
        &ms,
        regions.names(),
        &p.solutions,
        &SphereSvgOptions::default(),
    );
    // The eight diagonals each move three parts, one of each opposite pair.
    assert_eq!(p.solutions.len(), 8);
    for s in &p.solutions {
        let names: Vec<&str> = s.moving.iter().map(|&k| a.parts[k].name.as_str()).collect();
        assert!(
            svg.contains(&format!("{} move: 1 vertex", names.join(", "))),
            "{names:?}"
        );
    }
}

#[test]
fn the_png_shows_the_moving_parts_colours() {
    let a = common::example("split-star-3");
    let (regions, plan) = plan(&a);
    let colors = part_colors(&a.parts.iter().map(|p| p.name.clone()).collect::<Vec<_>>());
    // Step 2 moves one part through a face: its mark and its sliding edges are in the
    // part's colour.
    let step = &plan.steps[1];
    assert_eq!(step.moving.len(), 1);
    let ms = space(&regions, &step.subassembly);
    let png = step_motion_space_png(&ms, regions.names(), step, &SphereSvgOptions::default());
    let img = Pixmap::decode_png(&png).unwrap();
    assert!(img.width() > 900 && img.height() > 400);
    assert!(count_shades(&img, colors[step.moving[0]], img.width()) > 200);
    let all: Vec<usize> = (0..a.parts.len()).collect();
    let (p, _) = partition_subset(&regions, &all, &Default::default());
    let ms = space(&regions, &all);
    let png2 = motion_space_png(
        &ms,
        regions.names(),
        &p.solutions,
        &SphereSvgOptions::default(),
    );
    assert!(Pixmap::decode_png(&png2).is_ok());
}

/// The position of the text element whose content is `label`, the `nth` one.
fn text_at(svg: &str, label: &str, nth: usize) -> (f64, f64) {
    let line = svg
        .split("<text")
        .filter(|t| t.contains(&format!(">{label}</text>")))
        .nth(nth)
        .unwrap_or_else(|| panic!("no label {label} #{nth}"));
    let attr = |name: &str| -> f64 {
        let at = line.find(&format!(r#" {name}=""#)).unwrap() + name.len() + 3;
        line[at..].split('"').next().unwrap().parse().unwrap()
    };
    (attr("x"), attr("y"))
}

#[test]
fn both_hemispheres_name_their_axes_where_they_point() {
    let a = common::example("split-star-3");
    let (regions, plan) = plan(&a);
    let r = 200.0;
    let opts = SphereSvgOptions {
        radius: r,
        ..Default::default()
    };
    let step = &plan.steps[0];
    let ms = space(&regions, &step.subassembly);
    let svg = step_motion_space_svg(&ms, regions.names(), step, &opts);
    // The disks are centred at (60 + r, 100 + r) and one disk width and margin further.
    let upper = (60.0 + r, 100.0 + r);
    let lower = (upper.0 + 2.0 * r + 60.0, upper.1);
    // Seen from above, +x points right; seen from below, left. +y is up in both.
    let x_up = text_at(&svg, "+x", 0);
    let x_down = text_at(&svg, "+x", 1);
    assert!(
        x_up.0 > upper.0 + r && (x_up.1 - upper.1).abs() < 10.0,
        "{x_up:?}"
    );
    assert!(
        x_down.0 < lower.0 - r && (x_down.1 - lower.1).abs() < 10.0,
        "{x_down:?}"
    );
    for (k, centre) in [upper, lower].iter().enumerate() {
        let y = text_at(&svg, "+y", k);
        assert!((y.0 - centre.0).abs() < 1.0 && y.1 < centre.1 - r, "{y:?}");
    }
    // The poles: +z at the centre of the upper disk, −z at the centre of the lower one.
    let z_up = text_at(&svg, "+z", 0);
    let z_down = text_at(&svg, "−z", 0);
    assert!((z_up.0 - upper.0).abs() < 20.0 && (z_up.1 - upper.1).abs() < 20.0);
    assert!((z_down.0 - lower.0).abs() < 20.0 && (z_down.1 - lower.1).abs() < 20.0);
}
