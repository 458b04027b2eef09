//! The SVG drawing of a stack shows, pixel by pixel, the part the PNG's z-buffer shows:
//! the SVG is rasterized with resvg, each pixel's colour is traced back to the part whose
//! colour it is a shade of, and a sampled grid is compared with the z-buffer's part per
//! pixel, away from edges (within two pixels of a change of part in the z-buffer or of
//! an outline in the PNG, where anti-aliasing mixes colours and the two pictures may
//! differ by a pixel). A painter's sort by one depth per triangle fails this on long
//! faces; the SVG's order must be right wherever faces overlap. Every part is named in
//! the legend, in placing order.

mod common;

use apart_draw::colors::{part_colors, Rgb};
use apart_draw::stack_render::{plan_png, plan_shapes, plan_svg, scene_shapes};
use apart_draw::svg_png::svg_to_pixmap;
use apart_draw::{shapes_part_ids, shapes_png, shapes_svg, View};
use apart_stack::part::PartModel;
use apart_stack::planner::{stack, StackOptions};
use apart_stack::scene::Scene;
use apart_testkit::sheet_metal::{channel, complex_part, cube, triangle_part};
use common::{floor_around, part_of, q, qfrac, sheet_model};
use resvg::tiny_skia::Pixmap;

const W: u32 = 480;
const H: u32 = 360;

/// The part a pixel of a picture shows, by its colour.
fn seen_at(img: &Pixmap, x: i64, y: i64, colors: &[Rgb]) -> Option<Option<usize>> {
    let c = img.pixel(x as u32, y as u32).unwrap();
    part_of([c.red(), c.green(), c.blue()], colors)
}

/// Compares the SVG with the z-buffer on every third pixel that is at least two pixels
/// from any edge (a change of part in the z-buffer, an outline in the PNG); returns how
/// many pixels were compared.
fn svg_matches_zbuffer(part: &PartModel, opts: &StackOptions, view: &View) -> usize {
    let plan = stack(part, opts).unwrap();
    assert!(plan.complete, "{}: incomplete stack", part.name);
    let (shapes, names) = plan_shapes(&plan, 1.0);
    let colors = part_colors(&names);
    let ids = shapes_part_ids(&shapes, &names, view, W, H);
    let svg = shapes_svg(&shapes, &names, view, W, H);
    let png = Pixmap::decode_png(&shapes_png(&shapes, &names, &[], view, W, H)).unwrap();
    let img = svg_to_pixmap(&svg, 1.0).expect("the SVG parses");
    assert_eq!((img.width(), img.height()), (W, H));
    let id = |x: i64, y: i64| ids[(y as usize) * W as usize + x as usize];
    let (mut compared, mut wrong) = (0, Vec::new());
    for y in (2..H as i64 - 2).step_by(3) {
        for x in (2..W as i64 - 2).step_by(3) {
            let here = id(x, y);
            let inside = (-2..=2).all(|dy| {
                (-2..=2).all(|dx| {
                    id(x + dx, y + dy) == here
                        && seen_at(&png, x + dx, y + dy, &colors) == Some(here)
                })
            });
            if !inside {
                continue;
            }
            let seen = seen_at(&img, x, y, &colors);
            compared += 1;
            if seen != Some(here) {
                wrong.push((x, y, here, seen));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "{}: {} of {compared} pixels differ from the z-buffer, e.g. {:?}",
        part.name,
        wrong.len(),
        &wrong[..wrong.len().min(8)]
    );
    // The stack fills a good part of the picture, and every part shows in the z-buffer.
    assert!(compared > 1500, "{compared} pixels compared");
    for (k, name) in names.iter().enumerate() {
        assert!(ids.contains(&Some(k)), "{name} hidden");
    }
    compared
}

fn no_labels() -> View {
    View {
        labels: false,
        ..View::default()
    }
}

#[test]
fn nested_channels_in_svg_as_in_the_zbuffer() {
    let part = sheet_model(channel());
    let mut opts = StackOptions::new(8, qfrac(1, 2), floor_around(&part, 3, 2), q(1000));
    opts.dtheta_deg = 90.0;
    svg_matches_zbuffer(&part, &opts, &no_labels());
}

#[test]
fn channels_side_by_side_seen_from_several_sides() {
    // w = 0 keeps the stack low: the channels lie side by side on a wide floor, long
    // faces next to short ones.
    let part = sheet_model(channel());
    let mut opts = StackOptions::new(6, q(0), floor_around(&part, 4, 1), q(1000));
    opts.dtheta_deg = 90.0;
    for (azimuth, elevation) in [(-60.0, 25.0), (30.0, 40.0), (200.0, 15.0)] {
        let view = View {
            azimuth_deg: azimuth,
            elevation_deg: elevation,
            ..no_labels()
        };
        svg_matches_zbuffer(&part, &opts, &view);
    }
}

#[test]
fn triangle_parts_and_cubes_in_svg_as_in_the_zbuffer() {
    let part = sheet_model(triangle_part());
    let mut opts = StackOptions::new(6, qfrac(1, 2), floor_around(&part, 2, 1), q(1000));
    opts.dtheta_deg = 90.0;
    svg_matches_zbuffer(&part, &opts, &no_labels());
    let part = sheet_model(cube(1));
    let mut opts = StackOptions::new(9, q(0), [q(-2), q(-2), q(2), q(2)], q(10));
    opts.dtheta_deg = 90.0;
    svg_matches_zbuffer(&part, &opts, &no_labels());
}

#[test]
fn complex_parts_with_holes_and_flanges_in_svg_as_in_the_zbuffer() {
    let part = sheet_model(complex_part());
    let mut opts = StackOptions::new(3, qfrac(1, 2), floor_around(&part, 2, 1), q(100000));
    opts.dtheta_deg = 90.0;
    svg_matches_zbuffer(&part, &opts, &no_labels());
}

#[test]
fn scene_parts_keep_their_names() {
    let mut scene = Scene::new();
    scene.add_fixed_part(&sheet_model(cube(1)).pieces);
    scene.add_fixed_part(&sheet_model(cube(1)).pieces);
    let names = ["base".to_string()];
    let (shapes, all) = scene_shapes(
        &scene,
        &names,
        &[("lid".into(), sheet_model(cube(1)).pieces)],
        1.0,
    );
    assert_eq!(shapes.len(), 3);
    assert_eq!(all, ["base", "fixed 2", "lid"]);
}

#[test]
fn pictures_show_every_part() {
    let mut opts = StackOptions::new(3, q(1), [q(-2), q(-2), q(2), q(2)], q(10));
    opts.dtheta_deg = 90.0;
    let plan = stack(&sheet_model(cube(1)), &opts).unwrap();
    let (shapes, names) = plan_shapes(&plan, 1.0);
    assert_eq!(names, ["cube #1", "cube #2", "cube #3"]);
    // A cube: 6 square facets, 12 triangles, 6 planes.
    assert!(shapes.iter().all(|s| s.triangles.len() == 12));
    let svg = plan_svg(&plan, 1.0, &View::default(), 320, 240);
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    // Each cube shows at most three faces to the default view, one path each, and
    // the legend names every part.
    let drawing = svg.split("<g id=\"axes\"").next().unwrap();
    let faces = drawing.matches("<path d=\"M").count();
    assert!((3..=9).contains(&faces), "{faces} faces drawn");
    for name in &names {
        assert!(svg.contains(&format!(">{name}</text>")), "{name}");
    }
    for axis in ["x", "y", "z"] {
        assert!(svg.contains(&format!(">{axis}</text>")), "axis {axis}");
    }
    assert!(
        svg.contains(" units</text>") || svg.contains(" unit</text>"),
        "scale bar"
    );
    let png = plan_png(&plan, 1.0, &View::default(), 320, 240);
    let img = resvg::tiny_skia::Pixmap::decode_png(&png).unwrap();
    assert_eq!((img.width(), img.height()), (320, 240));
    let coloured = img
        .pixels()
        .iter()
        .filter(|p| (p.red(), p.green(), p.blue()) != (255, 255, 255))
        .count();
    assert!(coloured > 1000, "{coloured} coloured pixels");
}
