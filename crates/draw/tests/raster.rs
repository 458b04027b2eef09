//! Renders without a GPU: the highlighted parts appear in their colours (shaded), the
//! others do not, the corners are background, and the same input gives the same bytes.

mod common;

use apart_draw::colors::{part_colors, Rgb};
use apart_draw::{assembly_png, step_pngs, View};
use common::{count_shades, pixel};
use resvg::tiny_skia::Pixmap;

const W: u32 = 480;
const H: u32 = 360;

fn no_labels() -> View {
    View {
        labels: false,
        ..View::default()
    }
}

#[test]
fn highlighted_parts_in_colour_the_rest_grey() {
    let a = common::example("split-star-3");
    let colors = part_colors(&a.parts.iter().map(|p| p.name.clone()).collect::<Vec<_>>());
    let red = a.parts.iter().position(|p| p.name == "red").unwrap();
    let blue = a.parts.iter().position(|p| p.name == "blue").unwrap();
    let bytes = assembly_png(&a, &[red, blue], &no_labels(), W, H);
    let img = Pixmap::decode_png(&bytes).unwrap();
    assert_eq!((img.width(), img.height()), (W, H));
    assert!(count_shades(&img, colors[red], W) > 1000);
    assert!(count_shades(&img, colors[blue], W) > 1000);
    for (k, c) in colors.iter().enumerate() {
        if k != red && k != blue {
            assert!(
                count_shades(&img, *c, W) < 20,
                "{} is not highlighted and must not show its colour",
                a.parts[k].name
            );
        }
    }
    // Grey (the other parts) is there too, and the corners are background.
    let greys = (0..H)
        .flat_map(|y| (0..W).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            let [r, g, b] = pixel(&img, x, y);
            r == g && (b as i32 - r as i32).abs() <= 6 && r < 250 && r > 60
        })
        .count();
    assert!(greys > 1000, "{greys}");
    for (x, y) in [(0, 0), (W - 1, 0), (0, H - 1), (W - 1, H - 1)] {
        assert_eq!(pixel(&img, x, y), [255, 255, 255]);
    }
    // Deterministic.
    assert_eq!(bytes, assembly_png(&a, &[red, blue], &no_labels(), W, H));
}

#[test]
fn an_empty_highlight_draws_every_part_in_colour() {
    let a = common::example("split-star-3");
    let colors = part_colors(&a.parts.iter().map(|p| p.name.clone()).collect::<Vec<_>>());
    let img = Pixmap::decode_png(&assembly_png(&a, &[], &no_labels(), W, H)).unwrap();
    for (k, c) in colors.iter().enumerate() {
        assert!(count_shades(&img, *c, W) > 300, "{}", a.parts[k].name);
    }
}

#[test]
fn one_picture_per_step_with_its_moving_side_in_colour() {
    let a = common::example("split-star-3");
    let (_, plan) = common::plan(&a);
    let colors: Vec<Rgb> = part_colors(&a.parts.iter().map(|p| p.name.clone()).collect::<Vec<_>>());
    let pngs = step_pngs(&a, &plan, &no_labels(), W, H);
    assert_eq!(pngs.len(), plan.steps.len());
    for (png, step) in pngs.iter().zip(&plan.steps) {
        let img = Pixmap::decode_png(png).unwrap();
        for (k, &c) in colors.iter().enumerate() {
            let n = count_shades(&img, c, W);
            if step.moving.contains(&k) {
                assert!(
                    n > 300,
                    "step {step:?}: {} shows {n} pixels",
                    a.parts[k].name
                );
            } else {
                assert!(
                    n < 20,
                    "step {step:?}: {} shows {n} pixels",
                    a.parts[k].name
                );
            }
        }
        assert_eq!(pixel(&img, 0, 0), [255, 255, 255]);
    }
    assert_eq!(pngs, step_pngs(&a, &plan, &no_labels(), W, H));
}

#[test]
fn labels_write_text_without_hiding_the_parts() {
    if !apart_draw::svg_png::fonts_available() {
        eprintln!("skipped: no system font for the captions (Debian: apt-get install -y fonts-dejavu-core)");
        return;
    }
    let a = common::example("split-star-3");
    let (_, plan) = common::plan(&a);
    let with = step_pngs(&a, &plan, &View::default(), W, H);
    let without = step_pngs(&a, &plan, &no_labels(), W, H);
    let img = Pixmap::decode_png(&with[0]).unwrap();
    let bare = Pixmap::decode_png(&without[0]).unwrap();
    // The caption darkens pixels in the top band, where the bare render is background.
    let dark = |p: &Pixmap| {
        (0..40)
            .flat_map(|y| (0..W).map(move |x| (x, y)))
            .filter(|&(x, y)| pixel(p, x, y).iter().all(|&c| c < 100))
            .count()
    };
    assert_eq!(dark(&bare), 0);
    assert!(
        dark(&img) > 100,
        "caption text expected (needs a system font)"
    );
}

#[test]
fn pieces_only_parts_render() {
    let a = common::assembly_of("star", common::plan_common::split_star());
    let colors = part_colors(&a.parts.iter().map(|p| p.name.clone()).collect::<Vec<_>>());
    let img = Pixmap::decode_png(&assembly_png(&a, &[0], &no_labels(), W, H)).unwrap();
    assert!(count_shades(&img, colors[0], W) > 1000);
}
