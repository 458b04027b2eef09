//! Renders without a GPU: the highlighted parts appear in their colours (shaded), the
//! others do not, the corners are background, and the same input gives the same bytes.

mod common;

use apart_draw::colors::{part_colors, Rgb};
use apart_draw::raster::AXIS_COLORS;
use apart_draw::{assembly_png, step_pngs, View};
use common::{count_shades, part_of, pixel};
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
    let a = common::assembly_of(
        "star",
        common::parts(apart_testkit::assemblies::split_star()),
    );
    let colors = part_colors(&a.parts.iter().map(|p| p.name.clone()).collect::<Vec<_>>());
    let img = Pixmap::decode_png(&assembly_png(&a, &[0], &no_labels(), W, H)).unwrap();
    assert!(count_shades(&img, colors[0], W) > 1000);
}

#[test]
fn the_svg_shows_the_part_the_zbuffer_shows() {
    // Non-convex parts interlocking (every face of the Split Star overlaps others in
    // the picture), a bolt through a bracket and a tongue, and bricks in rows.
    let assemblies = [
        common::example("split-star"),
        common::example("hinge"),
        common::assembly_of("bricks", common::brick_rows()),
    ];
    let views = [
        no_labels(),
        View {
            azimuth_deg: 150.0,
            elevation_deg: -30.0,
            ..no_labels()
        },
    ];
    for a in &assemblies {
        let shapes = apart_draw::shapes::part_shapes(a);
        let names: Vec<String> = a.parts.iter().map(|p| p.name.clone()).collect();
        let colors = part_colors(&names);
        for view in &views {
            let ids = apart_draw::shapes_part_ids(&shapes, &names, view, W, H);
            let svg = apart_draw::shapes_svg(&shapes, &names, view, W, H);
            let img = apart_draw::svg_png::svg_to_pixmap(&svg, 1.0).unwrap();
            let png = Pixmap::decode_png(&apart_draw::shapes_png(&shapes, &names, &[], view, W, H))
                .unwrap();
            let id = |x: u32, y: u32| ids[(y * W + x) as usize];
            let (mut compared, mut wrong) = (0, Vec::new());
            for y in (2..H - 2).step_by(3) {
                for x in (2..W - 2).step_by(3) {
                    let here = id(x, y);
                    // Away from edges: no change of part in the z-buffer, no outline in
                    // the PNG, within two pixels.
                    let inside = (y - 2..=y + 2).all(|v| {
                        (x - 2..=x + 2).all(|u| {
                            id(u, v) == here && part_of(pixel(&png, u, v), &colors) == Some(here)
                        })
                    });
                    if inside {
                        compared += 1;
                        let seen = part_of(pixel(&img, x, y), &colors);
                        if seen != Some(here) {
                            wrong.push((x, y, here, seen));
                        }
                    }
                }
            }
            assert!(
                wrong.is_empty(),
                "{} from {:?}: {} of {compared} pixels differ, e.g. {:?}",
                a.name,
                (view.azimuth_deg, view.elevation_deg),
                wrong.len(),
                &wrong[..wrong.len().min(6)]
            );
            assert!(compared > 1000, "{}: {compared} compared", a.name);
        }
    }
}

#[test]
fn labels_add_an_axis_triad_and_a_scale_bar_in_every_render() {
    let a = common::example("split-star-3");
    let (_, plan) = common::plan(&a);
    let names: Vec<String> = a.parts.iter().map(|p| p.name.clone()).collect();
    let shapes = apart_draw::shapes::part_shapes(&a);
    // The lower left corner holds the triad: pixels of the three axis colours, and
    // none without labels.
    let axis_pixels = |img: &Pixmap, c: Rgb| {
        (H - 80..H)
            .flat_map(|y| (0..90).map(move |x| (x, y)))
            .filter(|&(x, y)| {
                let p = pixel(img, x, y);
                (0..3).all(|i| (p[i] as i32 - [c.0, c.1, c.2][i] as i32).abs() <= 30)
            })
            .count()
    };
    let labelled = [
        assembly_png(&a, &[], &View::default(), W, H),
        step_pngs(&a, &plan, &View::default(), W, H).remove(0),
    ];
    let bare = [
        assembly_png(&a, &[], &no_labels(), W, H),
        step_pngs(&a, &plan, &no_labels(), W, H).remove(0),
    ];
    for (with, without) in labelled.iter().zip(&bare) {
        let with = Pixmap::decode_png(with).unwrap();
        let without = Pixmap::decode_png(without).unwrap();
        for c in AXIS_COLORS {
            assert!(axis_pixels(&with, c) > 20, "{c:?}");
            assert_eq!(axis_pixels(&without, c), 0, "{c:?}");
        }
    }
    // The SVG has them as elements: the letters, the scale bar and the part names.
    let svg = apart_draw::shapes_svg(&shapes, &names, &View::default(), W, H);
    for axis in ["x", "y", "z"] {
        assert!(svg.contains(&format!(">{axis}</text>")), "{axis}");
    }
    assert!(svg.contains(r#"<g id="scale""#));
    for n in &names {
        assert!(svg.contains(&format!(">{n}</text>")), "{n}");
    }
    assert!(!apart_draw::shapes_svg(&shapes, &names, &no_labels(), W, H).contains("id=\"axes\""));
}

/// The scale bar's length in pixels and the length it stands for, from an SVG.
fn scale_bar(svg: &str) -> (f64, f64) {
    let g = &svg[svg.find(r#"<g id="scale""#).expect("a scale bar")..];
    let d = &g[g.find(r#" d=""#).unwrap() + 4..];
    let d = &d[..d.find('"').unwrap()];
    // "M x0,y0 L x0,y L x1,y L x1,y0": the bar runs from x0 to x1.
    let xs: Vec<f64> = d
        .split(['M', 'L', ' '])
        .filter(|s| !s.is_empty())
        .map(|p| p.split(',').next().unwrap().parse().unwrap())
        .collect();
    let text = &g[g.find("text-anchor=\"middle\">").unwrap() + 21..];
    let text = text.trim_start_matches('>');
    let text = &text[..text.find(' ').unwrap()];
    (xs[2] - xs[0], text.parse().unwrap())
}

#[test]
fn the_scale_bar_measures_what_the_picture_shows() {
    // A cube of side 3 seen from straight above: its top is a square whose width in
    // pixels, divided by 3, is the picture's pixels per unit.
    let cube = common::cuboid([0, 0, 0], [3, 3, 3]);
    let a = common::assembly_of("cube", vec![common::part("cube", vec![cube])]);
    let shapes = apart_draw::shapes::part_shapes(&a);
    let names = vec!["cube".to_string()];
    let color = part_colors(&names)[0];
    // (From straight above with azimuth 0, the square's sides run along the picture.)
    let view = View {
        azimuth_deg: 0.0,
        elevation_deg: 90.0,
        ..View::default()
    };
    let img =
        Pixmap::decode_png(&apart_draw::shapes_png(&shapes, &names, &[], &view, W, H)).unwrap();
    // The widest row of cube colour, left of the legend (its swatch has the colour too).
    let width = (0..H)
        .map(|y| {
            (0..W - 116)
                .filter(|&x| common::is_shade_of(pixel(&img, x, y), color))
                .count()
        })
        .max()
        .unwrap() as f64;
    let per_unit = width / 3.0;
    let (bar, length) = scale_bar(&apart_draw::shapes_svg(&shapes, &names, &view, W, H));
    assert!(
        (bar / length - per_unit).abs() < 0.03 * per_unit,
        "bar {bar} px for {length} units, the cube {per_unit} px per unit"
    );
    // A round length, at most 140 pixels long.
    let mantissa = length / 10f64.powf(length.log10().floor());
    assert!([1.0, 2.0, 5.0].iter().any(|m| (mantissa - m).abs() < 1e-9));
    assert!(bar <= 140.0 + 1e-9 && bar > 140.0 / 5.0);
}
