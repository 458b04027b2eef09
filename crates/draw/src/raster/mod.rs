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
//!
//! A new picture is written in its own module from the rooms here (crate-visible):
//! `camera` (the orthographic camera), `zbuffer` (rasterizing triangles at `SS` samples
//! per pixel), `render` (the shaded picture of placed parts) and `annotations` (the
//! legend, axis triad and scale bar).

pub(crate) mod annotations;
pub(crate) mod camera;
pub(crate) mod render;
pub(crate) mod steps;
pub(crate) mod svg;
pub(crate) mod zbuffer;

pub use annotations::AXIS_COLORS;
pub(crate) use annotations::{direction_label, names_list, vector_label};
pub use steps::step_pngs;
pub use svg::shapes_svg;

use crate::colors::{part_colors, Rgb, GREY};
use crate::shapes::{part_shapes, PartShape};
use crate::svg_png::{overlay, png_bytes};
use annotations::{annotations, legend_rows, legend_width, svg_open, ANNOTATION_H};
use apart_assembly::Assembly;
use apart_kernel::fvec::{add, dot};
use camera::Camera;
use render::render;
use zbuffer::{zbuffer, SS};

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

/// Every part in place: those in `highlight` (all when it is empty) in their colours,
/// the others grey and see-through.
pub(crate) fn lit_items(colors: &[Rgb], highlight: &[usize]) -> Vec<Item> {
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
pub(crate) fn framed(
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

/// A part placed in a picture.
#[derive(Clone, Debug)]
pub(crate) struct Item {
    /// The part's index.
    pub(crate) part: usize,
    /// Where it is moved to, from its place in the assembly.
    pub(crate) offset: [f64; 3],
    /// Its colour before shading.
    pub(crate) color: Rgb,
    /// Grey and see-through (not highlighted).
    pub(crate) ghost: bool,
}

/// Every corner of the items' triangles, moved to where the items are.
pub(crate) fn item_points(shapes: &[PartShape], items: &[Item]) -> Vec<[f64; 3]> {
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
