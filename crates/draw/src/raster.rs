//! Renders of the assembly without a GPU: a z-buffer rasterizer of our own, flat
//! shading, 2×2 supersampling, outlines where the visible part or face plane changes,
//! and a caption drawn over it with resvg.
//!
//! With `View::labels`, every picture (PNG render, step render, SVG drawing) carries the
//! same annotations: a legend naming the coloured parts, an axis triad (x red, y green,
//! z blue, as the camera sees them) in the lower left corner, and a scale bar of a round
//! length in model units beside it.
//!
//! Highlighted parts are opaque, in their colours; the others are grey and slightly
//! transparent (the nearest grey surface is blended over what lies behind it), so a
//! highlighted part inside the assembly still shows through.

use crate::colors::{mix, part_colors, Rgb, BACKGROUND, GREY};
use crate::painter::{painter_order, Polygon};
use crate::shapes::{bounds_of, part_shapes, PartShape};
use crate::svg_png::{escape, overlay, png_bytes, FONT_FAMILY};
use apart_assembly::Assembly;
use apart_kernel::fvec::{add, cross, dot, normalize, scale, sub};
use apart_plan::{Sequence, Step};
use resvg::tiny_skia::{Pixmap, PremultipliedColorU8};
use std::fmt::Write;

/// An orthographic camera looking at the assembly's centre, and what to write on the
/// picture.
#[derive(Clone, Debug, PartialEq)]
pub struct View {
    /// Angle of the eye around the up axis, in degrees (0: the eye on the +x side for a
    /// z-up view; 90: on the +y side).
    pub azimuth_deg: f64,
    /// Height of the eye above the horizontal plane, in degrees (90: from straight
    /// above).
    pub elevation_deg: f64,
    /// The input axis pointing up in the picture.
    pub up: [f64; 3],
    /// Write part names (a legend), the axis triad and the scale bar, and, for steps, a
    /// caption and an arrow.
    pub labels: bool,
}

impl Default for View {
    fn default() -> Self {
        View {
            azimuth_deg: -60.0,
            elevation_deg: 25.0,
            up: [0.0, 0.0, 1.0],
            labels: true,
        }
    }
}

/// A render of the whole assembly in place as PNG bytes: the parts listed in
/// `highlight` (part indices) in their colours, the others grey; an empty `highlight`
/// draws every part in its colour. With `view.labels`, a legend names the coloured
/// parts.
pub fn assembly_png(
    assembly: &Assembly,
    highlight: &[usize],
    view: &View,
    width: u32,
    height: u32,
) -> Vec<u8> {
    let names: Vec<String> = assembly.parts.iter().map(|p| p.name.clone()).collect();
    shapes_png(
        &part_shapes(assembly),
        &names,
        highlight,
        view,
        width,
        height,
    )
}

/// A render of arbitrary part surfaces (for instance placed pieces) as PNG bytes, with
/// the same conventions as [`assembly_png`]: `names` give colours and the legend.
pub fn shapes_png(
    shapes: &[PartShape],
    names: &[String],
    highlight: &[usize],
    view: &View,
    width: u32,
    height: u32,
) -> Vec<u8> {
    let colors = part_colors(names);
    let items = lit_items(&colors, highlight);
    let (camera, legend_w) = framed(shapes, &items, view, width, height);
    let mut pixmap = render(shapes, &items, &camera, width, height);
    if view.labels {
        let lit: Vec<usize> = items.iter().filter(|i| !i.ghost).map(|i| i.part).collect();
        let mut svg = svg_open(width, height);
        legend_rows(
            &mut svg,
            names,
            &colors,
            &lit,
            20.0,
            height,
            width as f64 - legend_w,
        );
        svg.push_str(&annotations(&camera, width, height));
        svg.push_str("</svg>\n");
        overlay(&mut pixmap, &svg);
    }
    png_bytes(&pixmap)
}

/// The part seen at each pixel of [`shapes_png`]'s picture (same camera and framing,
/// nothing highlighted), row by row: `Some(k)` for part `k`, `None` for background. It
/// is the z-buffer's answer at one sample per pixel, for comparing other drawings of
/// the same scene with it (the SVG's depth order is tested so).
pub fn shapes_part_ids(
    shapes: &[PartShape],
    names: &[String],
    view: &View,
    width: u32,
    height: u32,
) -> Vec<Option<usize>> {
    let colors = part_colors(names);
    let items = lit_items(&colors, &[]);
    let (camera, _) = framed(shapes, &items, view, width, height);
    let (w, h) = (width.max(1) as usize, height.max(1) as usize);
    let mut tris = Vec::new();
    for it in &items {
        for (t, tri) in shapes[it.part].triangles.iter().enumerate() {
            if dot(shapes[it.part].normal(t), camera.eye) > 0.0 {
                tris.push((
                    tri.map(|p| camera.project(add(p, it.offset))),
                    it.part as u32 + 1,
                ));
            }
        }
    }
    let layer = zbuffer(&tris, w, h);
    let mut out = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let f = layer.face[(y * SS + SS / 2) * w * SS + x * SS + SS / 2];
            out.push(f.checked_sub(1).map(|k| k as usize));
        }
    }
    out
}

/// A triangle in picture coordinates (x, y, depth) with its face id (at least 1).
type PictureTriangle = ([(f64, f64, f64); 3], u32);

/// Which triangles (given in picture coordinates, face id `t + 1` for triangle `t`) are
/// nearest at some sample of a z-buffer at `SS` samples per pixel along each axis,
/// strictly: a sample where two triangles are at the same depth (up to rounding) shows
/// neither. A face hidden inside a part (the top of a piece under another piece, flush
/// with it) meets the visible faces only along an edge, where its depth ties with
/// theirs; it is not shown.
fn shown_triangles(tris: &[PictureTriangle], width: usize, height: usize) -> Vec<bool> {
    let (w, h) = (width * SS, height * SS);
    let mut depth = vec![f64::INFINITY; w * h];
    let mut owner = vec![u32::MAX; w * h];
    let mut tied = vec![false; w * h];
    let scale = tris
        .iter()
        .flat_map(|(v, _)| v.iter().map(|p| p.2.abs()))
        .fold(0.0f64, f64::max);
    let eps = 1e-9 * scale.max(1.0);
    for (t, (v, _)) in tris.iter().enumerate() {
        let v = v.map(|(x, y, z)| (x * SS as f64, y * SS as f64, z));
        raster_triangle(w, h, v, |p, z| {
            if z < depth[p] - eps {
                depth[p] = z;
                owner[p] = t as u32;
                tied[p] = false;
            } else if z <= depth[p] + eps {
                tied[p] = true;
                if z < depth[p] {
                    depth[p] = z;
                    owner[p] = t as u32;
                }
            }
        });
    }
    let mut shown = vec![false; tris.len()];
    for p in 0..w * h {
        if owner[p] != u32::MAX && !tied[p] {
            shown[owner[p] as usize] = true;
        }
    }
    shown
}

/// A z-buffer at `SS` samples per pixel along each axis of triangles given in picture
/// coordinates with their face ids.
fn zbuffer(tris: &[PictureTriangle], width: usize, height: usize) -> Layer {
    let (w, h) = (width * SS, height * SS);
    let mut layer = Layer::new(w * h);
    for (v, face) in tris {
        let v = v.map(|(x, y, z)| (x * SS as f64, y * SS as f64, z));
        fill_triangle(&mut layer, w, h, v, *face);
    }
    layer
}

/// Every part in place: those in `highlight` (all when it is empty) in their colours,
/// the others grey and see-through.
fn lit_items(colors: &[Rgb], highlight: &[usize]) -> Vec<Item> {
    (0..colors.len())
        .map(|k| {
            let lit = highlight.is_empty() || highlight.contains(&k);
            Item {
                part: k,
                offset: [0.0; 3],
                color: if lit { colors[k] } else { GREY },
                ghost: !lit,
            }
        })
        .collect()
}

/// The camera fitting `items` with room for a legend on the right when `view.labels`,
/// and the legend's width.
fn framed(
    shapes: &[PartShape],
    items: &[Item],
    view: &View,
    width: u32,
    height: u32,
) -> (Camera, f64) {
    let legend_w = if view.labels {
        legend_width(width)
    } else {
        0.0
    };
    let points = item_points(shapes, items);
    let bottom = if view.labels { ANNOTATION_H } else { 12.0 };
    let margins = [12.0, bottom, 12.0, legend_w + 12.0];
    (Camera::fit(view, &points, width, height, margins), legend_w)
}

/// A vector drawing of part surfaces as SVG text, for pictures that should scale: the
/// same camera as [`shapes_png`], flat-shaded in the part colours, with a legend, the
/// axis triad and the scale bar. Only triangles that the z-buffer shows somewhere are
/// drawn, in an order that is right wherever they overlap ([`crate::painter`]: pairs
/// compared over their common region, cycles split by a binary space partition), so
/// the drawing shows the same part as the PNG at every pixel but along outlines.
pub fn shapes_svg(
    shapes: &[PartShape],
    names: &[String],
    view: &View,
    width: u32,
    height: u32,
) -> String {
    let colors = part_colors(names);
    let items = lit_items(&colors, &[]);
    let (camera, legend_w) = framed(shapes, &items, view, width, height);
    let light = camera.light();
    // Triangles facing the eye, in picture coordinates, with their faces (one per
    // plane of a part, shaded once like the PNG's).
    let mut tris: Vec<PictureTriangle> = Vec::new();
    let mut face_of: Vec<usize> = Vec::new();
    let mut fill: Vec<Option<Rgb>> = Vec::new();
    for (k, shape) in shapes.iter().enumerate() {
        let base = fill.len();
        fill.resize(
            base + shape.plane.iter().max().map_or(0, |&m| m as usize + 1),
            None,
        );
        for (t, tri) in shape.triangles.iter().enumerate() {
            let n = shape.normal(t);
            if dot(n, camera.eye) <= 0.0 {
                continue; // facing away
            }
            let face = base + shape.plane[t] as usize;
            fill[face].get_or_insert_with(|| shade(colors[k], n, light));
            tris.push((tri.map(|v| camera.project(v)), tris.len() as u32 + 1));
            face_of.push(face);
        }
    }
    // Only what the z-buffer shows somewhere: hidden faces (between convex pieces, or
    // behind other parts) would only lengthen the file and the sort, and a face that is
    // hidden but along an edge would draw a line there.
    let (w, h) = (width.max(1) as usize, height.max(1) as usize);
    let shown = shown_triangles(&tris, w, h);
    let polygons: Vec<Polygon> = tris
        .iter()
        .enumerate()
        .filter(|(t, _)| shown[*t])
        .map(|(t, (v, _))| Polygon {
            // Depth in pixels too, so that picture space is the scene scaled.
            points: v
                .iter()
                .map(|&(x, y, z)| [x, y, z * camera.scale])
                .collect(),
            tag: t,
            group: face_of[t],
        })
        .collect();
    let mut svg = svg_open(width, height);
    let _ = writeln!(
        svg,
        r#"<rect width="{width}" height="{height}" fill="{}"/>"#,
        BACKGROUND.hex()
    );
    // Consecutive polygons of one face make one path: a path's pieces are covered
    // together, so anti-aliasing leaves no seam between them.
    let order = painter_order(polygons);
    let mut k = 0;
    while k < order.len() {
        let face = order[k].group;
        let mut d = String::new();
        while k < order.len() && order[k].group == face {
            for (j, q) in order[k].points.iter().enumerate() {
                let _ = write!(
                    d,
                    "{}{:.2},{:.2} ",
                    if j == 0 { "M" } else { "L" },
                    q[0],
                    q[1]
                );
            }
            d.push('Z');
            k += 1;
        }
        let c = fill[face].unwrap_or(GREY).hex();
        // A thin stroke of the fill colour closes the hairline seams left between
        // faces drawn apart.
        let _ = writeln!(
            svg,
            r#"<path d="{d}" fill="{c}" stroke="{c}" stroke-width="1" stroke-linejoin="round"/>"#
        );
    }
    if view.labels {
        let all: Vec<usize> = (0..shapes.len()).collect();
        legend_rows(
            &mut svg,
            names,
            &colors,
            &all,
            20.0,
            height,
            width as f64 - legend_w,
        );
        svg.push_str(&annotations(&camera, width, height));
    }
    svg.push_str("</svg>\n");
    svg
}

/// One render per step of `sequence`, as PNG bytes, all with the same camera: the
/// subassembly being split, its moving side in colour and pulled a little way out along
/// the step's direction, the side that stays in grey; with `view.labels`, a caption
/// (step number, moving and staying parts, direction, cell kind, clearance) and an
/// arrow along the direction.
pub fn step_pngs(
    assembly: &Assembly,
    sequence: &Sequence,
    view: &View,
    width: u32,
    height: u32,
) -> Vec<Vec<u8>> {
    let shapes = part_shapes(assembly);
    let colors = part_colors(&part_names(assembly));
    let scenes: Vec<Vec<Item>> = sequence
        .steps
        .iter()
        .map(|s| step_items(&shapes, &colors, s))
        .collect();
    let top = if view.labels { 58.0 } else { 12.0 };
    let bottom = if view.labels { ANNOTATION_H } else { 12.0 };
    let legend_w = if view.labels {
        legend_width(width)
    } else {
        0.0
    };
    sequence
        .steps
        .iter()
        .zip(&scenes)
        .enumerate()
        .map(|(k, (step, items))| {
            // Fit the subassembly, its pulled-out side, and room for the arrow beyond.
            let mut points = item_points(&shapes, items);
            let ahead: Vec<Item> = items
                .iter()
                .filter(|i| !i.ghost)
                .map(|i| Item {
                    offset: scale(i.offset, 1.8),
                    ..i.clone()
                })
                .collect();
            points.extend(item_points(&shapes, &ahead));
            let camera = Camera::fit(
                view,
                &points,
                width,
                height,
                [top, bottom, 12.0, 12.0 + legend_w],
            );
            let mut pixmap = render(&shapes, items, &camera, width, height);
            if view.labels {
                let svg = step_svg(
                    &shapes, sequence, k, step, items, &colors, &camera, width, height, legend_w,
                );
                overlay(&mut pixmap, &svg);
            }
            png_bytes(&pixmap)
        })
        .collect()
}

fn part_names(assembly: &Assembly) -> Vec<&str> {
    assembly.parts.iter().map(|p| p.name.as_str()).collect()
}

/// The parts of a step's subassembly: the moving ones in colour, pulled out by a third
/// of the subassembly's diagonal; the others grey.
fn step_items(shapes: &[PartShape], colors: &[Rgb], step: &Step) -> Vec<Item> {
    let sub: Vec<PartShape> = step
        .subassembly
        .iter()
        .filter_map(|&k| shapes.get(k).cloned())
        .collect();
    let pull = scale(step.unit, bounds_of(&sub, None).diagonal() / 3.0);
    step.subassembly
        .iter()
        .filter(|&&k| k < shapes.len())
        .map(|&k| {
            let moving = step.moving.contains(&k);
            Item {
                part: k,
                offset: if moving { pull } else { [0.0; 3] },
                color: if moving { colors[k] } else { GREY },
                ghost: !moving,
            }
        })
        .collect()
}

/// A part placed in a picture.
#[derive(Clone, Debug)]
struct Item {
    part: usize,
    offset: [f64; 3],
    color: Rgb,
    /// Grey and see-through (not highlighted).
    ghost: bool,
}

fn item_points(shapes: &[PartShape], items: &[Item]) -> Vec<[f64; 3]> {
    items
        .iter()
        .flat_map(|it| {
            shapes[it.part]
                .triangles
                .iter()
                .flatten()
                .map(move |p| add(*p, it.offset))
        })
        .collect()
}

/// Orthographic projection onto the picture.
#[derive(Clone, Debug)]
struct Camera {
    right: [f64; 3],
    up: [f64; 3],
    /// Unit vector from the scene towards the eye.
    eye: [f64; 3],
    center: [f64; 3],
    scale: f64,
    /// Picture coordinates of `center`.
    origin: (f64, f64),
}

impl Camera {
    /// The camera of `view` scaled and centred so that `points` fill the picture less
    /// the margins (top, bottom, left, right).
    fn fit(view: &View, points: &[[f64; 3]], width: u32, height: u32, margins: [f64; 4]) -> Camera {
        let u = normalize(view.up);
        let u = if u == [0.0; 3] { [0.0, 0.0, 1.0] } else { u };
        let reference = if u[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let x = normalize(sub(reference, scale(u, dot(reference, u))));
        let y = cross(u, x);
        let (az, el) = (
            view.azimuth_deg.to_radians(),
            view.elevation_deg.to_radians(),
        );
        let eye = normalize(add(
            add(scale(x, el.cos() * az.cos()), scale(y, el.cos() * az.sin())),
            scale(u, el.sin()),
        ));
        let mut right = normalize(cross(scale(eye, -1.0), u));
        if right == [0.0; 3] {
            // Looking along the up axis: keep x to the right.
            right = x;
        }
        let up = cross(right, scale(eye, -1.0));
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in points {
            let (a, b) = (dot(*p, right), dot(*p, up));
            lo = [lo[0].min(a), lo[1].min(b)];
            hi = [hi[0].max(a), hi[1].max(b)];
        }
        if points.is_empty() {
            (lo, hi) = ([-1.0; 2], [1.0; 2]);
        }
        let [top, bottom, left, right_margin] = margins;
        let avail_w = (width as f64 - left - right_margin).max(1.0);
        let avail_h = (height as f64 - top - bottom).max(1.0);
        let span = [(hi[0] - lo[0]).max(1e-12), (hi[1] - lo[1]).max(1e-12)];
        let s = (avail_w / span[0]).min(avail_h / span[1]);
        let mid = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
        Camera {
            right,
            up,
            eye,
            center: add(scale(right, mid[0]), scale(up, mid[1])),
            scale: s,
            origin: (left + avail_w / 2.0, top + avail_h / 2.0),
        }
    }

    /// Picture coordinates (x right, y down) and depth (smaller is nearer).
    fn project(&self, p: [f64; 3]) -> (f64, f64, f64) {
        let q = sub(p, self.center);
        (
            self.origin.0 + self.scale * dot(q, self.right),
            self.origin.1 - self.scale * dot(q, self.up),
            -dot(q, self.eye),
        )
    }

    /// The light: from the upper left, in front.
    fn light(&self) -> [f64; 3] {
        normalize(add(
            add(scale(self.eye, 0.75), scale(self.up, 0.55)),
            scale(self.right, -0.35),
        ))
    }
}

/// Samples per pixel along each axis.
const SS: usize = 2;
/// Opacity of the grey parts.
const GHOST_ALPHA: f64 = 0.72;
/// Colour of outlines.
const EDGE: Rgb = Rgb(35, 35, 40);

/// The flat-shaded colour of a face with unit normal `n`.
fn shade(base: Rgb, n: [f64; 3], light: [f64; 3]) -> Rgb {
    let s = 0.42 + 0.58 * dot(n, light).max(0.0);
    let f = |c: u8| (c as f64 * s).round().min(255.0) as u8;
    Rgb(f(base.0), f(base.1), f(base.2))
}

/// One depth layer: nearest depth and face id (0 = nothing) per sample.
struct Layer {
    depth: Vec<f32>,
    face: Vec<u32>,
}

impl Layer {
    fn new(n: usize) -> Layer {
        Layer {
            depth: vec![f32::INFINITY; n],
            face: vec![0; n],
        }
    }
}

/// A visible face: its shaded colour and the item it belongs to.
struct Face {
    color: Rgb,
    item: u32,
}

fn render(
    shapes: &[PartShape],
    items: &[Item],
    camera: &Camera,
    width: u32,
    height: u32,
) -> Pixmap {
    let (w, h) = (width.max(1) as usize * SS, height.max(1) as usize * SS);
    let mut opaque = Layer::new(w * h);
    let mut ghost = Layer::new(w * h);
    let mut faces = vec![Face {
        color: BACKGROUND,
        item: u32::MAX,
    }];
    let light = camera.light();
    for (i, it) in items.iter().enumerate() {
        let shape = &shapes[it.part];
        let planes = shape.plane.iter().max().map_or(0, |&m| m as usize + 1);
        let base = faces.len() as u32;
        let mut shaded = vec![false; planes];
        faces.extend((0..planes).map(|_| Face {
            color: it.color,
            item: i as u32,
        }));
        let layer = if it.ghost { &mut ghost } else { &mut opaque };
        for (t, tri) in shape.triangles.iter().enumerate() {
            let n = shape.normal(t);
            if dot(n, camera.eye) <= 0.0 {
                continue;
            }
            let plane = shape.plane[t] as usize;
            if !shaded[plane] {
                faces[base as usize + plane].color = shade(it.color, n, light);
                shaded[plane] = true;
            }
            let v = tri.map(|p| {
                let (x, y, z) = camera.project(add(p, it.offset));
                (x * SS as f64, y * SS as f64, z)
            });
            fill_triangle(layer, w, h, v, base + plane as u32);
        }
    }

    // Compose: the grey layer over the coloured one where it is in front.
    let mut color = vec![BACKGROUND; w * h];
    let mut front = vec![0u32; w * h];
    for p in 0..w * h {
        let (o, g) = (opaque.face[p], ghost.face[p]);
        let c = faces[o as usize].color;
        if g != 0 && ghost.depth[p] < opaque.depth[p] {
            color[p] = mix(c, faces[g as usize].color, GHOST_ALPHA);
            front[p] = g;
        } else {
            color[p] = c;
            front[p] = o;
        }
    }
    // Outlines: both samples on either side of a change of visible face.
    let mut edge = vec![0f64; w * h];
    for y in 0..h {
        for x in 0..w {
            let p = y * w + x;
            for q in [(x + 1 < w).then(|| p + 1), (y + 1 < h).then(|| p + w)]
                .into_iter()
                .flatten()
            {
                let (a, b) = (front[p], front[q]);
                if a != b {
                    let strength = if faces[a as usize].item != faces[b as usize].item {
                        0.9
                    } else {
                        0.45
                    };
                    edge[p] = edge[p].max(strength);
                    edge[q] = edge[q].max(strength);
                }
            }
        }
    }
    // Average each SS × SS block.
    let mut pixmap = Pixmap::new(width.max(1), height.max(1)).expect("non-zero size");
    let out = pixmap.pixels_mut();
    for py in 0..height.max(1) as usize {
        for px in 0..width.max(1) as usize {
            let mut sum = [0f64; 3];
            for dy in 0..SS {
                for dx in 0..SS {
                    let p = (py * SS + dy) * w + px * SS + dx;
                    let c = mix(color[p], EDGE, edge[p]);
                    sum[0] += c.0 as f64;
                    sum[1] += c.1 as f64;
                    sum[2] += c.2 as f64;
                }
            }
            let n = (SS * SS) as f64;
            let [r, g, b] = sum.map(|s| (s / n).round() as u8);
            out[py * width.max(1) as usize + px] =
                PremultipliedColorU8::from_rgba(r, g, b, 255).expect("opaque");
        }
    }
    pixmap
}

/// Z-buffered fill of one triangle (sample centres at half-integers).
fn fill_triangle(layer: &mut Layer, w: usize, h: usize, v: [(f64, f64, f64); 3], face: u32) {
    raster_triangle(w, h, v, |p, z| {
        let z = z as f32;
        if z < layer.depth[p] {
            layer.depth[p] = z;
            layer.face[p] = face;
        }
    });
}

/// Calls `sample(index, depth)` for every sample of a `w` × `h` grid (centres at
/// half-integers) inside the triangle `v` (picture coordinates and depth), edges
/// included, with the depth interpolated there.
fn raster_triangle(
    w: usize,
    h: usize,
    v: [(f64, f64, f64); 3],
    mut sample: impl FnMut(usize, f64),
) {
    let [(x0, y0, z0), (x1, y1, z1), (x2, y2, z2)] = v;
    let area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
    if area.abs() < 1e-12 || !area.is_finite() {
        return;
    }
    let min_x = x0.min(x1).min(x2).floor().max(0.0) as usize;
    let max_x = (x0.max(x1).max(x2).ceil() as isize).min(w as isize - 1);
    let min_y = y0.min(y1).min(y2).floor().max(0.0) as usize;
    let max_y = (y0.max(y1).max(y2).ceil() as isize).min(h as isize - 1);
    if max_x < 0 || max_y < 0 {
        return;
    }
    let inv = 1.0 / area;
    for y in min_y..=max_y as usize {
        let py = y as f64 + 0.5;
        for x in min_x..=max_x as usize {
            let px = x as f64 + 0.5;
            // Barycentric weights; all of one sign inside (either orientation).
            let w0 = ((x1 - px) * (y2 - py) - (x2 - px) * (y1 - py)) * inv;
            let w1 = ((x2 - px) * (y0 - py) - (x0 - px) * (y2 - py)) * inv;
            let w2 = 1.0 - w0 - w1;
            if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                continue;
            }
            sample(y * w + x, w0 * z0 + w1 * z1 + w2 * z2);
        }
    }
}

/// Width of the legend column for a picture `width` wide.
fn legend_width(width: u32) -> f64 {
    (width as f64 * 0.24).clamp(90.0, 200.0)
}

/// The legend's rows (a colour swatch and a name per lit part) at `x`, the first
/// baseline at `top`, as many as fit above the scale bar.
fn legend_rows(
    svg: &mut String,
    names: &[String],
    colors: &[Rgb],
    lit: &[usize],
    top: f64,
    height: u32,
    x: f64,
) {
    let line = 18.0;
    let fit = ((height as f64 - top - ANNOTATION_H + 14.0) / line)
        .floor()
        .max(1.0) as usize;
    for (row, &k) in lit.iter().enumerate() {
        let y = top + row as f64 * line;
        if row + 1 == fit && lit.len() > fit {
            let _ = writeln!(
                svg,
                r##"<text x="{x:.1}" y="{y:.1}" font-size="12" fill="#333">… and {} more</text>"##,
                lit.len() - row
            );
            break;
        }
        let _ = writeln!(
            svg,
            r##"<rect x="{x:.1}" y="{:.1}" width="12" height="12" fill="{}" stroke="#333" stroke-width="0.6"/><text x="{:.1}" y="{y:.1}" font-size="13" fill="#222">{}</text>"##,
            y - 10.5,
            colors[k].hex(),
            x + 18.0,
            escape(&names[k])
        );
    }
}

fn svg_open(width: u32, height: u32) -> String {
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="{FONT_FAMILY}">"#
    ) + "\n"
}

/// Room kept below the scene, when labels are on, for the axis triad and the scale bar.
const ANNOTATION_H: f64 = 78.0;

/// Colours of the x, y and z axes: red, green, blue, pure enough that no part colour
/// shaded by the light looks like them.
pub const AXIS_COLORS: [Rgb; 3] = [Rgb(225, 0, 0), Rgb(0, 150, 0), Rgb(0, 70, 235)];

/// The axis triad (lower left: the x, y and z axes as the camera sees them, far ones
/// first, each an arrow with its letter; an axis seen end-on is a ⊙ or ⊗) and the scale
/// bar beside it (a round length in model units: 1, 2 or 5 times a power of ten, and
/// its label), as SVG elements in picture coordinates.
fn annotations(camera: &Camera, width: u32, height: u32) -> String {
    let mut svg = String::from(r#"<g id="axes" font-weight="bold" font-size="13">"#);
    let (ox, oy) = (40.0, height as f64 - 38.0);
    let len = 26.0;
    let mut axes: Vec<(usize, f64, f64, f64)> = (0..3)
        .map(|k| {
            let mut a = [0.0; 3];
            a[k] = 1.0;
            // Picture direction (x right, y down) and depth (larger is farther).
            (
                k,
                dot(a, camera.right),
                -dot(a, camera.up),
                -dot(a, camera.eye),
            )
        })
        .collect();
    axes.sort_by(|a, b| b.3.total_cmp(&a.3));
    let _ = write!(
        svg,
        r##"<circle cx="{ox:.1}" cy="{oy:.1}" r="2.2" fill="#333"/>"##
    );
    for (k, dx, dy, depth) in axes {
        let c = AXIS_COLORS[k].hex();
        let name = ["x", "y", "z"][k];
        let l = (dx * dx + dy * dy).sqrt();
        if l < 0.2 {
            // Along the line of sight: ⊙ towards the eye, ⊗ away from it.
            let (cx, cy) = (ox + 14.0 + 12.0 * k as f64, oy + 18.0);
            let _ = write!(
                svg,
                r##"<circle cx="{cx:.1}" cy="{cy:.1}" r="5" fill="white" stroke="{c}" stroke-width="1.6"/>"##
            );
            if depth < 0.0 {
                let _ = write!(
                    svg,
                    r##"<circle cx="{cx:.1}" cy="{cy:.1}" r="1.6" fill="{c}"/>"##
                );
            } else {
                let _ = write!(
                    svg,
                    r##"<path d="M{:.1},{:.1} L{:.1},{:.1} M{:.1},{:.1} L{:.1},{:.1}" stroke="{c}" stroke-width="1.4"/>"##,
                    cx - 3.0,
                    cy - 3.0,
                    cx + 3.0,
                    cy + 3.0,
                    cx - 3.0,
                    cy + 3.0,
                    cx + 3.0,
                    cy - 3.0
                );
            }
            let _ = write!(
                svg,
                r##"<text x="{cx:.1}" y="{:.1}" fill="{c}" text-anchor="middle">{name}</text>"##,
                cy + 18.0
            );
            continue;
        }
        let (ux, uy) = (dx / l, dy / l);
        let (bx, by) = (ox + dx * len, oy + dy * len);
        let head = 7.0;
        let (lx, ly) = (
            bx - ux * head - uy * head * 0.5,
            by - uy * head + ux * head * 0.5,
        );
        let (rx, ry) = (
            bx - ux * head + uy * head * 0.5,
            by - uy * head - ux * head * 0.5,
        );
        let _ = write!(
            svg,
            r##"<line x1="{ox:.1}" y1="{oy:.1}" x2="{:.1}" y2="{:.1}" stroke="{c}" stroke-width="2.2" stroke-linecap="round"/><path d="M{lx:.1},{ly:.1} L{bx:.1},{by:.1} L{rx:.1},{ry:.1} Z" fill="{c}"/><text x="{:.1}" y="{:.1}" fill="{c}" text-anchor="middle">{name}</text>"##,
            bx - ux * head * 0.8,
            by - uy * head * 0.8,
            ox + dx * len + ux * 12.0,
            oy + dy * len + uy * 12.0 + 4.5
        );
    }
    svg.push_str("</g>\n");
    // The scale bar: the largest round length at most 140 pixels long (less in a
    // narrow picture).
    let x0 = 92.0;
    let room = (width as f64 - x0 - 16.0).min(140.0);
    if room > 20.0 && camera.scale.is_finite() && camera.scale > 0.0 {
        if let Some((length, label)) = round_length(room / camera.scale) {
            let px = length * camera.scale;
            let y = height as f64 - 20.0;
            let _ = writeln!(
                svg,
                r##"<g id="scale" stroke="#222" stroke-width="1.6" fill="#222"><path d="M{x0:.1},{:.1} L{x0:.1},{y:.1} L{:.1},{y:.1} L{:.1},{:.1}" fill="none"/><text x="{:.1}" y="{:.1}" font-size="12" stroke="none" text-anchor="middle">{label} {}</text></g>"##,
                y - 5.0,
                x0 + px,
                x0 + px,
                y - 5.0,
                x0 + px / 2.0,
                y - 8.0,
                if label == "1" { "unit" } else { "units" }
            );
        }
    }
    svg
}

/// The largest of 1, 2 or 5 times a power of ten not above `max`, and its decimal text
/// (`None` for a length that is not a positive finite number).
pub(crate) fn round_length(max: f64) -> Option<(f64, String)> {
    if !max.is_finite() || max <= 0.0 {
        return None;
    }
    let mut e = max.log10().floor() as i32;
    // log10 may round across a power of ten.
    if 10f64.powi(e) > max {
        e -= 1;
    }
    let m = [5u32, 2, 1]
        .into_iter()
        .find(|&m| m as f64 * 10f64.powi(e) <= max)
        .unwrap_or(1);
    let value = m as f64 * 10f64.powi(e);
    let text = if (0..=15).contains(&e) {
        format!("{}", m as u64 * 10u64.pow(e as u32))
    } else if (-15..0).contains(&e) {
        format!("{:.*}", (-e) as usize, value)
    } else {
        format!("{m}e{e}")
    };
    Some((value, text))
}

/// "(0.577, 0.577, 0.577)" with the exact integer direction when it is short.
pub(crate) fn direction_label(step: &Step) -> String {
    let exact = step.direction.to_strings();
    if exact.iter().all(|s| s.len() <= 6) {
        format!("({})", exact.join(", "))
    } else {
        let u = step.unit;
        format!("({:.3}, {:.3}, {:.3})", u[0], u[1], u[2])
    }
}

/// Names of parts `ks` joined by commas, shortened past `max` names.
pub(crate) fn names_list(names: &[String], ks: &[usize], max: usize) -> String {
    let mut out: Vec<&str> = ks
        .iter()
        .take(max)
        .map(|&k| names.get(k).map_or("?", |s| s.as_str()))
        .collect();
    let more;
    if ks.len() > max {
        more = format!("… ({} more)", ks.len() - max);
        out.push(&more);
    }
    out.join(", ")
}

/// Caption and arrow of step `k`.
#[allow(clippy::too_many_arguments)]
fn step_svg(
    shapes: &[PartShape],
    sequence: &Sequence,
    k: usize,
    step: &Step,
    items: &[Item],
    colors: &[Rgb],
    camera: &Camera,
    width: u32,
    height: u32,
    legend_w: f64,
) -> String {
    let names = &sequence.names;
    let rest: Vec<usize> = step.staying();
    let mut svg = svg_open(width, height);
    let verb = if step.moving.len() == 1 {
        "moves"
    } else {
        "move"
    };
    // As many names as fit the width (about 0.6 em per character).
    let fits =
        |text: &str, size: f64| text.chars().count() as f64 * 0.6 * size <= width as f64 - 24.0;
    let head = format!("Step {} of {}: ", k + 1, sequence.steps.len());
    let line1 = |max: usize| {
        format!(
            "{} {verb} along {}",
            names_list(names, &step.moving, max),
            direction_label(step)
        )
    };
    let max1 = (1..=6)
        .rev()
        .find(|&m| fits(&(head.clone() + &line1(m)), 16.0))
        .unwrap_or(1);
    let _ = writeln!(
        svg,
        r##"<text x="12" y="22" font-size="16" fill="#111"><tspan font-weight="bold">{head}</tspan>{}</text>"##,
        escape(&line1(max1))
    );
    let clearance = if step.clearance_deg > 0.0 {
        format!(", clearance {:.1}°", step.clearance_deg)
    } else {
        String::new()
    };
    let line2 = |max: usize| {
        format!(
            "{} cell{clearance}; {} {} in place",
            step.cell.name(),
            names_list(names, &rest, max),
            if rest.len() == 1 { "stays" } else { "stay" }
        )
    };
    let max2 = (1..=6).rev().find(|&m| fits(&line2(m), 13.0)).unwrap_or(1);
    let _ = writeln!(
        svg,
        r##"<text x="12" y="42" font-size="13" fill="#444">{}</text>"##,
        escape(&line2(max2))
    );
    // Swatches of the moving parts' colours after the caption would crowd it; instead
    // the arrow takes the colour of the first moving part.
    let moved: Vec<Item> = items.iter().filter(|i| !i.ghost).cloned().collect();
    let b = crate::shapes::bounds_of(
        &moved
            .iter()
            .map(|i| shapes[i.part].clone())
            .collect::<Vec<_>>(),
        Some(&moved.iter().map(|i| i.offset).collect::<Vec<_>>()),
    );
    if !b.is_empty() {
        let (x0, y0, _) = camera.project(b.center());
        let tip = add(b.center(), scale(step.unit, 1.0));
        let (x1, y1, _) = camera.project(tip);
        let (dx, dy) = (x1 - x0, y1 - y0);
        let len = (dx * dx + dy * dy).sqrt();
        let colour = step.moving.first().map_or(EDGE, |&m| colors[m]);
        let size = (width.min(height) as f64 * 0.16).max(30.0);
        if len > 0.25 * camera.scale {
            // Arrow along the projected direction, just outside the moving side's
            // silhouette when the picture has room, else from its centre.
            let (ux, uy) = (dx / len, dy / len);
            let outline: Vec<(f64, f64)> = item_points(shapes, &moved)
                .into_iter()
                .map(|p| {
                    let (x, y, _) = camera.project(p);
                    (x, y)
                })
                .collect();
            let reach = ray_exit(&convex_hull(outline), (x0, y0), (ux, uy));
            let room = |t: f64| {
                let (x, y) = (x0 + ux * t, y0 + uy * t);
                x >= 8.0 && y >= 52.0 && x <= width as f64 - 8.0 && y <= height as f64 - 8.0
            };
            let arrow = size * 0.6;
            let start = if room(reach + 10.0 + arrow) {
                reach + 10.0
            } else {
                size * 0.1
            };
            let (ax, ay) = (x0 + ux * start, y0 + uy * start);
            let (bx, by) = (x0 + ux * (start + arrow), y0 + uy * (start + arrow));
            let head = 12.0;
            let (lx, ly) = (
                bx - ux * head - uy * head * 0.55,
                by - uy * head + ux * head * 0.55,
            );
            let (rx, ry) = (
                bx - ux * head + uy * head * 0.55,
                by - uy * head - ux * head * 0.55,
            );
            let _ = writeln!(
                svg,
                r##"<g stroke="#111" stroke-linecap="round" stroke-linejoin="round"><line x1="{ax:.1}" y1="{ay:.1}" x2="{bx:.1}" y2="{by:.1}" stroke-width="5"/><path d="M{lx:.1},{ly:.1} L{bx:.1},{by:.1} L{rx:.1},{ry:.1} Z" fill="#111" stroke-width="3"/></g><g stroke="{c}" stroke-linecap="round" stroke-linejoin="round"><line x1="{ax:.1}" y1="{ay:.1}" x2="{bx:.1}" y2="{by:.1}" stroke-width="2.5"/><path d="M{lx:.1},{ly:.1} L{bx:.1},{by:.1} L{rx:.1},{ry:.1} Z" fill="{c}" stroke-width="1"/></g>"##,
                c = colour.hex()
            );
        } else {
            // Along the line of sight: ⊙ towards the eye, ⊗ away from it.
            let toward = dot(step.unit, camera.eye) > 0.0;
            let _ = writeln!(
                svg,
                r##"<circle cx="{x0:.1}" cy="{y0:.1}" r="11" fill="white" stroke="#111" stroke-width="2.5"/>"##
            );
            if toward {
                let _ = writeln!(
                    svg,
                    r##"<circle cx="{x0:.1}" cy="{y0:.1}" r="3.5" fill="#111"/>"##
                );
            } else {
                let _ = writeln!(
                    svg,
                    r##"<path d="M{:.1},{:.1} L{:.1},{:.1} M{:.1},{:.1} L{:.1},{:.1}" stroke="#111" stroke-width="2.5"/>"##,
                    x0 - 6.0,
                    y0 - 6.0,
                    x0 + 6.0,
                    y0 + 6.0,
                    x0 - 6.0,
                    y0 + 6.0,
                    x0 + 6.0,
                    y0 - 6.0
                );
            }
        }
    }
    // The moving parts by name, under the caption, and the axes and scale.
    legend_rows(
        &mut svg,
        names,
        colors,
        &step.moving,
        70.0,
        height,
        width as f64 - legend_w,
    );
    svg.push_str(&annotations(camera, width, height));
    svg.push_str("</svg>\n");
    svg
}

/// The convex hull of points, counter-clockwise in a y-up frame (Andrew's monotone chain).
pub(crate) fn convex_hull(mut pts: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    pts.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut hull: Vec<(f64, f64)> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &(f64, f64)>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// How far the ray from `c` (inside) along unit `u` runs inside the convex polygon
/// `hull` (0 when the polygon is degenerate).
pub(crate) fn ray_exit(hull: &[(f64, f64)], c: (f64, f64), u: (f64, f64)) -> f64 {
    if hull.len() < 3 {
        return 0.0;
    }
    let mut t = f64::INFINITY;
    for k in 0..hull.len() {
        let (a, b) = (hull[k], hull[(k + 1) % hull.len()]);
        // Outward normal of edge a→b of a counter-clockwise polygon.
        let n = (b.1 - a.1, a.0 - b.0);
        let along = n.0 * u.0 + n.1 * u.1;
        if along > 0.0 {
            t = t.min((n.0 * (a.0 - c.0) + n.1 * (a.1 - c.1)) / along);
        }
    }
    if t.is_finite() {
        t.max(0.0)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_fills_its_samples_and_keeps_the_nearest() {
        let mut layer = Layer::new(16);
        fill_triangle(
            &mut layer,
            4,
            4,
            [(0.0, 0.0, 1.0), (4.0, 0.0, 1.0), (0.0, 4.0, 1.0)],
            1,
        );
        fill_triangle(
            &mut layer,
            4,
            4,
            [(0.0, 0.0, 0.5), (0.0, 4.0, 0.5), (4.0, 0.0, 0.5)],
            2,
        );
        fill_triangle(
            &mut layer,
            4,
            4,
            [(0.0, 0.0, 2.0), (4.0, 0.0, 2.0), (4.0, 4.0, 2.0)],
            3,
        );
        // The lower-left half (x + y < 4) is face 2 (nearer than 1); the upper-right
        // corner only face 3 covers.
        assert_eq!(layer.face[0], 2);
        assert_eq!(layer.face[15], 3);
        assert_eq!(layer.face.iter().filter(|&&f| f == 1).count(), 0);
    }

    #[test]
    fn scale_bars_have_round_lengths() {
        let l = round_length;
        assert_eq!(l(140.0), Some((100.0, "100".to_string())));
        assert_eq!(l(3.7), Some((2.0, "2".to_string())));
        assert_eq!(l(0.07), Some((0.05, "0.05".to_string())));
        assert_eq!(l(1.0), Some((1.0, "1".to_string())));
        assert_eq!(l(0.001), Some((0.001, "0.001".to_string())));
        assert_eq!(l(6.0e20).map(|p| p.1), Some("5e20".to_string()));
        assert_eq!(l(0.0), None);
        assert_eq!(l(f64::NAN), None);
    }

    #[test]
    fn a_ray_leaves_a_square_at_its_side() {
        let square = convex_hull(vec![
            (0.0, 0.0),
            (2.0, 0.0),
            (2.0, 2.0),
            (0.0, 2.0),
            (1.0, 1.0),
        ]);
        assert_eq!(square.len(), 4);
        assert!((ray_exit(&square, (1.0, 1.0), (1.0, 0.0)) - 1.0).abs() < 1e-12);
        let d = std::f64::consts::FRAC_1_SQRT_2;
        assert!((ray_exit(&square, (1.0, 1.0), (d, d)) - std::f64::consts::SQRT_2).abs() < 1e-12);
    }

    #[test]
    fn the_default_camera_keeps_z_up_and_looks_from_the_front_left() {
        let c = Camera::fit(
            &View::default(),
            &[[1.0, 1.0, 1.0], [-1.0, -1.0, -1.0]],
            100,
            100,
            [0.0; 4],
        );
        assert!(c.up[2] > 0.8);
        assert!(dot(c.right, c.up).abs() < 1e-12 && dot(c.eye, c.up).abs() < 1e-12);
        let (_, y_top, _) = c.project([0.0, 0.0, 1.0]);
        let (_, y_bottom, _) = c.project([0.0, 0.0, -1.0]);
        assert!(y_top < y_bottom);
    }
}
