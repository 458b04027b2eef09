//! The HTML viewer: one self-contained file with the geometry and the plan embedded, and
//! (when Chromium is installed) a headless screenshot showing the parts in their colours
//! and the axis triad, and the page as the browser built it (its DOM after the script
//! ran) holding the axis letters, a scale bar in model units and every part's name.

mod common;

use apart_draw::colors::part_colors;
use apart_draw::disassembly_html;
use apart_draw::raster::AXIS_COLORS;
use apart_testkit::Scratch;
use common::count_shades;
use resvg::tiny_skia::Pixmap;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const CHROMIUM: &str = "/usr/bin/chromium";

/// The JSON embedded in the page.
fn embedded(html: &str) -> serde_json::Value {
    let start = html
        .find(r#"<script id="data" type="application/json">"#)
        .unwrap();
    let rest = &html[start..];
    let body = &rest[rest.find('>').unwrap() + 1..rest.find("</script>").unwrap()];
    serde_json::from_str(body).unwrap()
}

#[test]
fn the_page_is_self_contained_and_embeds_geometry_and_steps() {
    let a = common::example("split-star-3");
    let (_, plan) = common::plan(&a);
    let html = disassembly_html(&a, &plan);
    // Nothing is fetched: no external scripts, styles, images or fonts.
    for needle in ["src=", "href=", "http://", "https://", "@import", "url("] {
        assert!(!html.contains(needle), "{needle}");
    }
    let data = embedded(&html);
    let parts = data["parts"].as_array().unwrap();
    assert_eq!(parts.len(), a.parts.len());
    for (p, part) in parts.iter().zip(&a.parts) {
        assert_eq!(p["name"], part.name.as_str());
        let tri = p["tri"].as_array().unwrap().len();
        let triangles = part.mesh.as_ref().unwrap().triangles.len();
        assert_eq!(tri, 9 * triangles);
        assert_eq!(p["plane"].as_array().unwrap().len(), triangles);
    }
    let steps = data["steps"].as_array().unwrap();
    assert_eq!(steps.len(), plan.steps.len());
    for (s, step) in steps.iter().zip(&plan.steps) {
        let moving: Vec<usize> = s["moving"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_u64().unwrap() as usize)
            .collect();
        assert_eq!(moving, step.moving);
        assert_eq!(s["cell"], step.cell.name());
    }
    // Quantised coordinates come back to the input units within one quantum.
    let q = data["quantum"].as_f64().unwrap();
    let c: Vec<f64> = data["center"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let first: Vec<f64> = parts[0]["tri"].as_array().unwrap()[..3]
        .iter()
        .map(|v| v.as_f64().unwrap() * q)
        .collect();
    let mesh = a.parts[0].mesh.as_ref().unwrap();
    let v = mesh.vertices[mesh.triangles[0][0] as usize].map(|x| a.grid.to_units(x));
    for k in 0..3 {
        assert!((first[k] + c[k] - v[k]).abs() <= q);
    }
}

#[test]
fn a_part_name_cannot_close_the_script() {
    let mut a = common::example("split-star-3");
    a.parts[0].name = "</script><b>".into();
    let (_, plan) = common::plan(&common::example("split-star-3"));
    let html = disassembly_html(&a, &plan);
    assert_eq!(html.matches("</script>").count(), 2);
    assert_eq!(embedded(&html)["parts"][0]["name"], "</script><b>");
}

/// Runs headless Chromium on `url`, writing a `width` × `height` screenshot to `png`.
fn screenshot(url: &str, png: &Path, width: u32, height: u32) {
    chromium(
        url,
        png,
        &format!("--screenshot={}", png.display()),
        width,
        height,
        None,
    );
}

/// The page at `url` as headless Chromium built it (the DOM after its scripts ran).
fn dump_dom(url: &str, dir: &Path, width: u32, height: u32) -> String {
    let out = dir.join("dom.html");
    let file = std::fs::File::create(&out).unwrap();
    chromium(url, &out, "--dump-dom", width, height, Some(file));
    std::fs::read_to_string(&out).unwrap()
}

/// Runs headless Chromium on `url` with `action` (a screenshot or a DOM dump into
/// `stdout`), with a profile folder beside `file`, for at most 120 s.
fn chromium(
    url: &str,
    file: &Path,
    action: &str,
    width: u32,
    height: u32,
    stdout: Option<std::fs::File>,
) {
    let profile = file.with_extension("profile");
    let mut child = Command::new(CHROMIUM)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(action)
        .arg(format!("--window-size={width},{height}"))
        .arg(url)
        .stdout(stdout.map_or_else(Stdio::null, Stdio::from))
        .stderr(Stdio::null())
        .spawn()
        .expect("chromium starts");
    let deadline = Instant::now() + Duration::from_secs(120);
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            assert!(status.success(), "chromium failed: {status}");
            break;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            panic!("chromium did not finish within 120 s");
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}

#[test]
fn headless_chromium_draws_every_part_in_its_colour() {
    if !Path::new(CHROMIUM).exists() {
        eprintln!("skipped: {CHROMIUM} is absent (Debian: apt-get install -y chromium)");
        return;
    }
    let a = common::example("split-star-3");
    let (_, plan) = common::plan(&a);
    let colors = part_colors(&a.parts.iter().map(|p| p.name.clone()).collect::<Vec<_>>());
    let dir = Scratch::new("draw-html");
    let page = dir.join("split-star.html");
    std::fs::write(&page, disassembly_html(&a, &plan)).unwrap();
    let (w, h) = (1000, 700);
    // The 3-D view is left of the 330-pixel side panel (which has colour swatches too).
    let view_w = w - 340;

    // Assembled: every part of the Split Star shows on its outside.
    let png = dir.join("assembled.png");
    screenshot(&format!("file://{}", page.display()), &png, w, h);
    let img = Pixmap::decode_png(&std::fs::read(&png).unwrap()).unwrap();
    assert_eq!((img.width(), img.height()), (w, h));
    for (k, c) in colors.iter().enumerate() {
        let n = count_shades(&img, *c, view_w);
        assert!(n > 500, "{}: {n} pixels", a.parts[k].name);
    }
    // Background around the assembly.
    assert_eq!(common::pixel(&img, 5, h / 2), [255, 255, 255]);
    // The axis triad in the lower left corner: strokes in the three axis colours.
    for (axis, c) in ["x", "y", "z"].iter().zip(AXIS_COLORS) {
        let n = (h - 110..h)
            .flat_map(|y| (0..110).map(move |x| (x, y)))
            .filter(|&(x, y)| {
                let p = common::pixel(&img, x, y);
                (0..3).all(|i| (p[i] as i32 - [c.0, c.1, c.2][i] as i32).abs() <= 40)
            })
            .count();
        assert!(n > 15, "axis {axis}: {n} pixels of its colour");
    }

    // Halfway through step 2: its moving part in colour, the others faded.
    let png = dir.join("step2.png");
    screenshot(&format!("file://{}#t=1.5", page.display()), &png, w, h);
    let img = Pixmap::decode_png(&std::fs::read(&png).unwrap()).unwrap();
    let moving = plan.steps[1].moving[0];
    assert!(count_shades(&img, colors[moving], view_w) > 300);
    for (k, c) in colors.iter().enumerate() {
        if k != moving {
            assert!(count_shades(&img, *c, view_w) < 100, "{}", a.parts[k].name);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The text of the element that starts with `open` (up to the first `close` after it).
fn element<'a>(dom: &'a str, open: &str, close: &str) -> &'a str {
    let start = dom
        .find(open)
        .unwrap_or_else(|| panic!("no {open} in the page"));
    let rest = &dom[start..];
    &rest[..rest.find(close).expect("the element ends")]
}

#[test]
fn headless_chromium_builds_a_page_with_axes_a_scale_and_every_part_name() {
    if !Path::new(CHROMIUM).exists() {
        eprintln!("skipped: {CHROMIUM} is absent (Debian: apt-get install -y chromium)");
        return;
    }
    let a = common::example("hinge");
    let (_, plan) = common::plan(&a);
    let dir = Scratch::new("draw-dom");
    let page = dir.join("hinge.html");
    std::fs::write(&page, disassembly_html(&a, &plan)).unwrap();
    let dom = dump_dom(&format!("file://{}", page.display()), &dir, 1000, 700);
    // The axis triad: the three letters, each with a stroke the script has aimed.
    let axes = element(&dom, r#"<svg id="axes""#, "</svg>");
    for axis in ["x", "y", "z"] {
        let g = element(axes, &format!(r#"<g id="axis-{axis}""#), "</g>");
        assert!(g.contains(&format!(">{axis}</text>")), "{g}");
        assert!(
            g.contains("x2=") && g.contains("y2="),
            "axis {axis} not drawn: {g}"
        );
    }
    // The scale bar: a round length in model units, and a bar of some width.
    let scale = element(&dom, r#"<div id="scale""#, "</div></div>");
    let label = element(scale, r#"<span id="scale-label">"#, "</span>");
    let length = label
        .trim_start_matches(r#"<span id="scale-label">"#)
        .strip_suffix(" units")
        .or_else(|| {
            label
                .trim_start_matches(r#"<span id="scale-label">"#)
                .strip_suffix(" unit")
        })
        .unwrap_or_else(|| panic!("scale label: {label}"));
    let value: f64 = length.parse().unwrap();
    let mantissa = value / 10f64.powf(value.log10().floor());
    assert!(
        [1.0, 2.0, 5.0].iter().any(|m| (mantissa - m).abs() < 1e-9),
        "{value} is not a round length"
    );
    // The hinge is a few units across: the bar is shorter than the assembly.
    assert!(value > 0.0 && value <= common::diagonal(&a), "{value}");
    assert!(scale.contains("width:"), "{scale}");
    // The legend names every part (in the list the script filled, not only in the data).
    let parts = element(&dom, r#"<ol id="parts">"#, "</ol>");
    for part in &a.parts {
        assert!(
            parts.contains(&format!("</span>{}</li>", part.name)),
            "{} is not named: {parts}",
            part.name
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
