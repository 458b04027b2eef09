//! Pictures of a plan of moves ([`apart_plan::moves`]): the HTML viewer and the animated
//! GLB playing the moves (a finite move translates its moving parts by exactly its
//! translation, a move to infinity moves its side out by the animation's fixed
//! distance: [`Keyframes::of_moves`]), and one SVG of the plan state by state.

use crate::colors::{part_colors, BACKGROUND, GREY};
use crate::gltf_export::animated_glb;
use crate::html_viewer::viewer_page;
use crate::motion::{AnimationOptions, Keyframes};
use crate::raster::annotations::{annotations, legend_rows, legend_width, svg_open, ANNOTATION_H};
use crate::raster::camera::Camera;
use crate::raster::steps::step_arrow;
use crate::raster::svg::faces_svg;
use crate::raster::{item_points, names_list, vector_label, Item, View};
use crate::shapes::{bounds_of, part_shapes, PartShape};
use crate::svg_png::escape;
use apart_assembly::Assembly;
use apart_plan::{Move, MovePlan, SearchEnd};
use serde_json::json;
use std::fmt::Write;

/// The HTML viewer page (as [`crate::disassembly_html`]) playing the moves of `plan`,
/// with the default [`AnimationOptions`].
pub fn moves_html(assembly: &Assembly, plan: &MovePlan) -> String {
    let opts = AnimationOptions::default();
    let shapes = part_shapes(assembly);
    let frames = keyframes(assembly, &shapes, plan, opts.distance_factor);
    let names = part_names(assembly);
    let step = assembly.grid.step();
    let depths = search_depths(plan);
    let steps: Vec<_> = plan
        .moves
        .iter()
        .enumerate()
        .map(|(k, mv)| {
            let how = match &mv.distance {
                Some(t) => format!("by {t}"),
                None => "to infinity".into(),
            };
            let length = move_length(mv, step)
                .map(|l| format!(", length {l:.6}"))
                .unwrap_or_default();
            json!({
                "subassembly": mv.subassembly,
                "moving": mv.moving,
                "direction": mv.unit,
                "label": format!("{} {how}", vector_label(&mv.direction, mv.unit)),
                "note": format!("{}{length}", move_title(plan, k, &names)),
                "depth": depths[mv.search],
            })
        })
        .collect();
    let warnings: Vec<String> = plan
        .searches
        .iter()
        .filter(|s| s.end != SearchEnd::Separated)
        .map(|s| {
            format!(
                "not taken apart ({}): {}",
                s.end.name(),
                names_list(&names, &s.subassembly, usize::MAX)
            )
        })
        .collect();
    viewer_page(assembly, &shapes, &frames, steps, &warnings, &opts)
}

/// The animated GLB (as [`crate::disassembly_glb`]) of the moves of `plan`, with the
/// default [`AnimationOptions`].
pub fn moves_glb(assembly: &Assembly, plan: &MovePlan) -> Vec<u8> {
    let opts = AnimationOptions::default();
    let shapes = part_shapes(assembly);
    let frames = keyframes(assembly, &shapes, plan, opts.distance_factor);
    animated_glb(assembly, &shapes, &frames, &opts)
}

/// Width of a panel of [`moves_svg`].
const PANEL_W: u32 = 440;
/// Height of a panel of [`moves_svg`].
const PANEL_H: u32 = 380;
/// Panels per row of [`moves_svg`].
const COLUMNS: usize = 3;
/// Height of the heading of [`moves_svg`].
const HEADING_H: f64 = 34.0;
/// Moves to infinity in [`moves_svg`] move their side by this many diagonals.
const SVG_DISTANCE_FACTOR: f64 = 0.6;

/// The plan of moves as one SVG: a grid of panels (`<g class="panel">`), one per
/// state, all seen by one camera: the assembled state, then the state after each move
/// with its moving parts in colour and the others grey, an arrow along its direction,
/// its title ("move 1 of 2 of the first separation (level 2)") and its translation
/// ("1/2 × (1, 1, 0)" in grid units, or "→ ∞ along (0, 0, 1)").
pub fn moves_svg(assembly: &Assembly, plan: &MovePlan) -> String {
    let shapes = part_shapes(assembly);
    let frames = keyframes(assembly, &shapes, plan, SVG_DISTANCE_FACTOR);
    let names = part_names(assembly);
    let colors = part_colors(&names);
    let n = shapes.len();
    let states = frames.offsets.len();
    // Panel k: every part after k moves; lit are every part at first, then the parts
    // the k-th move moved.
    let scenes: Vec<Vec<Item>> = (0..states)
        .map(|k| {
            (0..n)
                .map(|p| {
                    let lit = k == 0 || frames.moving[k - 1].contains(&p);
                    Item {
                        part: p,
                        offset: frames.offsets[k][p],
                        color: if lit { colors[p] } else { GREY },
                        ghost: !lit,
                    }
                })
                .collect()
        })
        .collect();
    let points: Vec<[f64; 3]> = scenes
        .iter()
        .flat_map(|items| item_points(&shapes, items))
        .collect();
    let legend_w = legend_width(PANEL_W);
    let camera = Camera::fit(
        &View::default(),
        &points,
        PANEL_W,
        PANEL_H,
        [58.0, ANNOTATION_H, 12.0, 12.0 + legend_w],
    );
    let columns = states.min(COLUMNS);
    let rows = states.div_ceil(COLUMNS);
    let (width, height) = (
        columns as u32 * PANEL_W,
        (rows as u32 * PANEL_H) + HEADING_H as u32,
    );
    let mut svg = svg_open(width, height);
    let _ = writeln!(
        svg,
        r#"<rect width="{width}" height="{height}" fill="{}"/>"#,
        BACKGROUND.hex()
    );
    let level = match plan.level {
        Some(l) => format!("level {l}"),
        None => "not separated".into(),
    };
    let _ = writeln!(
        svg,
        r##"<text x="12" y="23" font-size="17" font-weight="bold" fill="#111">{}: disassembly by {} move{}, {level}</text>"##,
        escape(&assembly.name),
        plan.moves.len(),
        if plan.moves.len() == 1 { "" } else { "s" }
    );
    for (k, items) in scenes.iter().enumerate() {
        let (x, y) = (
            (k % COLUMNS) as f64 * PANEL_W as f64,
            HEADING_H + (k / COLUMNS) as f64 * PANEL_H as f64,
        );
        let mv = k.checked_sub(1).map(|m| &plan.moves[m]);
        let lit: Vec<usize> = mv.map_or((0..n).collect(), |m| m.moving.clone());
        let _ = writeln!(
            svg,
            r##"<g class="panel" id="state-{k}" data-moving="{}" transform="translate({x:.0},{y:.0})"><rect x="0.5" y="0.5" width="{}" height="{}" fill="none" stroke="#ccc"/>"##,
            escape(&names_list(&names, &lit, usize::MAX)),
            PANEL_W - 1,
            PANEL_H - 1
        );
        svg.push_str(&faces_svg(&shapes, items, &camera, PANEL_W, PANEL_H));
        let (title, label) = match mv {
            None => ("Assembled".to_string(), String::new()),
            Some(m) => (
                move_title(plan, k - 1, &names),
                format!(
                    "{} {}",
                    names_list(&names, &m.moving, 4),
                    svg_translation(m)
                ),
            ),
        };
        let _ = writeln!(
            svg,
            r##"<text x="12" y="22" font-size="15" font-weight="bold" fill="#111">{}</text><text x="12" y="42" font-size="13" fill="#444">{}</text>"##,
            escape(&title),
            escape(&label)
        );
        if let Some(m) = mv {
            let moved: Vec<Item> = items.iter().filter(|i| !i.ghost).cloned().collect();
            let placed: Vec<PartShape> = moved.iter().map(|i| shapes[i.part].clone()).collect();
            let offsets: Vec<[f64; 3]> = moved.iter().map(|i| i.offset).collect();
            let b = bounds_of(&placed, Some(&offsets));
            if !b.is_empty() {
                let colour = colors[m.moving[0]];
                step_arrow(
                    &mut svg,
                    &shapes,
                    &moved,
                    b.center(),
                    m.unit,
                    colour,
                    &camera,
                    PANEL_W,
                    PANEL_H,
                );
            }
        }
        legend_rows(
            &mut svg,
            &names,
            &colors,
            &lit,
            70.0,
            PANEL_H,
            PANEL_W as f64 - legend_w,
        );
        if k == 0 {
            svg.push_str(&annotations(&camera, PANEL_W, PANEL_H));
        }
        svg.push_str("</g>\n");
    }
    svg.push_str("</svg>\n");
    svg
}

/// The keyframes of `plan`, moves to infinity moving `factor` × the diagonal.
fn keyframes(assembly: &Assembly, shapes: &[PartShape], plan: &MovePlan, factor: f64) -> Keyframes {
    let distance = factor * bounds_of(shapes, None).diagonal();
    Keyframes::of_moves(plan, shapes.len(), assembly.grid.step(), distance)
}

/// The names of the assembly's parts.
fn part_names(assembly: &Assembly) -> Vec<String> {
    assembly.parts.iter().map(|p| p.name.clone()).collect()
}

/// The length of a finite move in input units.
fn move_length(mv: &Move, grid_step: f64) -> Option<f64> {
    let norm: f64 = (0..3)
        .map(|c| mv.unit[c] * apart_kernel::int::to_f64(&mv.direction.get(c)))
        .sum();
    mv.distance.as_ref().map(|t| t.to_f64() * norm * grid_step)
}

/// "1/2 × (1, 1, 0)" (grid units) or "→ ∞ along (0, 0, 1)".
fn svg_translation(mv: &Move) -> String {
    let d = vector_label(&mv.direction, mv.unit);
    match &mv.distance {
        Some(t) => format!("{t} × {d}"),
        None => format!("→ ∞ along {d}"),
    }
}

/// "move 1 of 2 of the first separation (level 2)" for the moves of the whole
/// assembly, "move 1 of 2 separating a, b" for those of a subassembly.
fn move_title(plan: &MovePlan, k: usize, names: &[String]) -> String {
    let s = plan.moves[k].search;
    let of: Vec<usize> = (0..plan.moves.len())
        .filter(|&j| plan.moves[j].search == s)
        .collect();
    let j = of.iter().position(|&j| j == k).unwrap_or(0) + 1;
    if s == 0 {
        format!(
            "move {j} of {} of the first separation (level {})",
            of.len(),
            plan.level.unwrap_or(of.len())
        )
    } else {
        format!(
            "move {j} of {} separating {}",
            of.len(),
            names_list(names, &plan.searches[s].subassembly, 4)
        )
    }
}

/// How deep each search's subassembly lies in the tree of separations: the number of
/// earlier searches whose subassembly holds it.
fn search_depths(plan: &MovePlan) -> Vec<usize> {
    let s = &plan.searches;
    (0..s.len())
        .map(|k| {
            (0..k)
                .filter(|&j| {
                    s[j].subassembly.len() > s[k].subassembly.len()
                        && s[k]
                            .subassembly
                            .iter()
                            .all(|p| s[j].subassembly.contains(p))
                })
                .count()
        })
        .collect()
}
