//! The vector drawing of part surfaces: the triangles the z-buffer shows, flat-shaded
//! and ordered by the painter's algorithm.

use super::annotations::{annotations, legend_rows, svg_open};
use super::camera::Camera;
use super::render::shade;
use super::zbuffer::{shown_triangles, PictureTriangle};
use super::{framed, lit_items, Item, View};
use crate::colors::{part_colors, Rgb, BACKGROUND, GREY};
use crate::painter::{painter_order, Polygon};
use crate::shapes::PartShape;
use apart_kernel::fvec::{add, dot};
use std::fmt::Write;

/// A vector drawing of part surfaces as SVG text, for pictures that should scale: the
/// same camera as [`shapes_png`](super::shapes_png), flat-shaded in the part colours, with a legend, the
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
    let mut svg = svg_open(width, height);
    let _ = writeln!(
        svg,
        r#"<rect width="{width}" height="{height}" fill="{}"/>"#,
        BACKGROUND.hex()
    );
    svg.push_str(&faces_svg(shapes, &items, &camera, width, height));
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

/// The faces of the placed `items` seen by `camera`, flat-shaded in the items' colours
/// (grey items see-through) and in painter's order, as SVG paths in picture
/// coordinates.
pub(crate) fn faces_svg(
    shapes: &[PartShape],
    items: &[Item],
    camera: &Camera,
    width: u32,
    height: u32,
) -> String {
    let light = camera.light();
    // Triangles facing the eye, in picture coordinates, with their faces (one per
    // plane of a part, shaded once like the PNG's).
    let mut tris: Vec<PictureTriangle> = Vec::new();
    let mut face_of: Vec<usize> = Vec::new();
    let mut fill: Vec<Option<Rgb>> = Vec::new();
    let mut ghost: Vec<bool> = Vec::new();
    for it in items {
        let shape = &shapes[it.part];
        let base = fill.len();
        fill.resize(
            base + shape.plane.iter().max().map_or(0, |&m| m as usize + 1),
            None,
        );
        ghost.resize(fill.len(), it.ghost);
        for (t, tri) in shape.triangles.iter().enumerate() {
            let n = shape.normal(t);
            if dot(n, camera.eye) <= 0.0 {
                continue; // facing away
            }
            let face = base + shape.plane[t] as usize;
            fill[face].get_or_insert_with(|| shade(it.color, n, light));
            tris.push((
                tri.map(|v| camera.project(add(v, it.offset))),
                tris.len() as u32 + 1,
            ));
            face_of.push(face);
        }
    }
    // Only what the z-buffer shows somewhere: hidden faces (between convex pieces, or
    // behind other parts) would only lengthen the file and the sort, and a face that is
    // hidden but along an edge would draw a line there.
    let (w, h) = (width.max(1) as usize, height.max(1) as usize);
    let mut shown = shown_triangles(&tris, w, h);
    if ghost.contains(&true) {
        // Coloured parts show through grey ones: what the grey ones hide is drawn too.
        let lit: Vec<usize> = (0..tris.len()).filter(|&t| !ghost[face_of[t]]).collect();
        let lit_tris: Vec<PictureTriangle> = lit.iter().map(|&t| tris[t]).collect();
        for (j, seen) in shown_triangles(&lit_tris, w, h).into_iter().enumerate() {
            shown[lit[j]] |= seen;
        }
    }
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
    let mut svg = String::new();
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
        if ghost[face] {
            // Grey parts are see-through, as in the PNG (no stroke: where it overlapped
            // the fill it would draw the triangles' edges).
            let _ = writeln!(svg, r#"<path d="{d}" fill="{c}" fill-opacity="0.55"/>"#);
        } else {
            // A thin stroke of the fill colour closes the hairline seams left between
            // faces drawn apart.
            let _ = writeln!(
                svg,
                r#"<path d="{d}" fill="{c}" stroke="{c}" stroke-width="1" stroke-linejoin="round"/>"#
            );
        }
    }
    svg
}
