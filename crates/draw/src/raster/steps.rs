//! The step pictures: one render per step of a sequence, the moving side pulled out
//! along the step's direction, with a caption and an arrow.

use super::annotations::{
    annotations, direction_label, legend_rows, legend_width, names_list, svg_open, ANNOTATION_H,
};
use super::camera::Camera;
use super::render::{render, EDGE};
use super::{item_points, Item, View};
use crate::colors::{part_colors, Rgb, GREY};
use crate::shapes::{bounds_of, part_shapes, PartShape};
use crate::svg_png::{escape, overlay, png_bytes};
use apart_assembly::Assembly;
use apart_kernel::fvec::{add, dot, scale};
use apart_plan::{Sequence, Step};
use std::fmt::Write;

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

/// The names of the assembly's parts, in order.
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
    let mut svg = svg_open(width, height);
    step_caption(&mut svg, sequence, k, step, width);
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
        let colour = step.moving.first().map_or(EDGE, |&m| colors[m]);
        step_arrow(
            &mut svg,
            shapes,
            &moved,
            b.center(),
            step.unit,
            colour,
            camera,
            width,
            height,
        );
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

/// The two caption lines of step `k`: the step number, the moving parts and the
/// direction; then the cell kind, the clearance and the parts that stay. Each names as
/// many parts as fit the picture's `width`.
fn step_caption(svg: &mut String, sequence: &Sequence, k: usize, step: &Step, width: u32) {
    let names = &sequence.names;
    let rest: Vec<usize> = step.staying();
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
}

/// The unit direction `unit` drawn from `center`, the centre of the moving parts
/// `moved`: an arrow in `colour` along the projected direction, or, when the direction
/// runs along the line of sight, a ⊙ (towards the eye) or ⊗ (away from it).
#[allow(clippy::too_many_arguments)]
pub(crate) fn step_arrow(
    svg: &mut String,
    shapes: &[PartShape],
    moved: &[Item],
    center: [f64; 3],
    unit: [f64; 3],
    colour: Rgb,
    camera: &Camera,
    width: u32,
    height: u32,
) {
    let (x0, y0, _) = camera.project(center);
    let tip = add(center, scale(unit, 1.0));
    let (x1, y1, _) = camera.project(tip);
    let (dx, dy) = (x1 - x0, y1 - y0);
    let len = (dx * dx + dy * dy).sqrt();
    let size = (width.min(height) as f64 * 0.16).max(30.0);
    if len > 0.25 * camera.scale {
        // Arrow along the projected direction, just outside the moving side's
        // silhouette when the picture has room, else from its centre.
        let (ux, uy) = (dx / len, dy / len);
        let outline: Vec<(f64, f64)> = item_points(shapes, moved)
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
        let toward = dot(unit, camera.eye) > 0.0;
        sight_mark(svg, (x0, y0), toward);
    }
}

/// A direction along the line of sight at `(x0, y0)`: ⊙ towards the eye, ⊗ away from it.
fn sight_mark(svg: &mut String, (x0, y0): (f64, f64), toward: bool) {
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
}
