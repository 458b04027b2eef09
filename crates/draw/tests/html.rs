//! The HTML viewer: one self-contained file with the geometry and the plan embedded, and
//! (when Chromium is installed) a headless screenshot showing the parts in their colours.

mod common;

use apart_draw::colors::part_colors;
use apart_draw::disassembly_html;
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
    let profile = png.with_extension("profile");
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
        .arg(format!("--screenshot={}", png.display()))
        .arg(format!("--window-size={width},{height}"))
        .arg(url)
        .stdout(Stdio::null())
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
    let dir = std::env::temp_dir().join(format!("apart-draw-html-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
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
