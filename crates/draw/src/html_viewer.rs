//! The disassembly as one self-contained HTML page: no network, no library. The page
//! (`viewer.html`) holds a small software renderer of its own (orthographic z-buffer on
//! a 2-D canvas, flat shading, outlines where the visible part or face plane changes),
//! orbit by dragging, zoom with the wheel, buttons to play the plan and to step forward
//! and back, a time slider, the list of steps (moving parts, direction, cell kind and
//! clearance or a note; click one to go there), and the parts with their colours (click one to
//! hide it), an axis triad (x red, y green, z blue, turning with the view) and a scale
//! bar of a round length in model units; the triad, the scale and the part names are
//! page elements (not pixels of the canvas), so a test can read them from the page. The
//! geometry is embedded as JSON: per part its colour and triangles, with
//! coordinates quantised to integers (2^20 steps across the bounding box), and the
//! motion as keyframes ([`Keyframes`]: every part's offset after each step).

use crate::colors::part_colors;
use crate::motion::{AnimationOptions, Keyframes};
use crate::raster::{direction_label, names_list};
use crate::shapes::{bounds_of, part_shapes, PartShape};
use crate::svg_png::escape;
use apart_assembly::Assembly;
use apart_plan::Sequence;
use serde_json::{json, Value};

/// The page template; `__TITLE__` and `__DATA__` are replaced.
const TEMPLATE: &str = include_str!("viewer.html");

/// Quantisation steps across the largest extent of the bounding box.
const QUANTA: f64 = (1u32 << 20) as f64;

/// The viewer page for `assembly` and its plan `sequence`, with the default
/// [`AnimationOptions`] (each step moves its side 1.5 bounding-box diagonals).
pub fn disassembly_html(assembly: &Assembly, sequence: &Sequence) -> String {
    disassembly_html_with(assembly, sequence, &AnimationOptions::default())
}

/// [`disassembly_html`] with chosen distances and timings.
pub fn disassembly_html_with(
    assembly: &Assembly,
    sequence: &Sequence,
    opts: &AnimationOptions,
) -> String {
    let shapes = part_shapes(assembly);
    let distance = opts.distance_factor * bounds_of(&shapes, None).diagonal();
    let frames = Keyframes::of_sequence(sequence, shapes.len(), distance);
    let steps: Vec<_> = sequence
        .steps
        .iter()
        .map(|s| {
            json!({
                "subassembly": s.subassembly,
                "moving": s.moving,
                "direction": s.unit,
                "label": direction_label(s),
                "cell": s.cell.name(),
                "clearance": s.clearance_deg,
                "depth": s.depth,
            })
        })
        .collect();
    let names: Vec<String> = assembly.parts.iter().map(|p| p.name.clone()).collect();
    let warnings: Vec<String> = sequence
        .stuck
        .iter()
        .map(|s| {
            format!(
                "interlocked: {} cannot be taken apart by single translations",
                names_list(&names, s, usize::MAX)
            )
        })
        .chain(sequence.unsplit.iter().map(|s| {
            format!(
                "left whole (depth limit): {}",
                names_list(&names, s, usize::MAX)
            )
        }))
        .collect();
    viewer_page(assembly, &shapes, &frames, steps, &warnings, opts)
}

/// The viewer page of `assembly` (its surfaces `shapes`) playing `frames`: `steps`
/// describe the steps for the list and the caption (`subassembly`, `moving`, unit
/// `direction` for the arrow, `label` of the direction, `depth` for the indent, and
/// either `note` or the `cell` kind and `clearance`), `warnings` are shown under the
/// list.
pub(crate) fn viewer_page(
    assembly: &Assembly,
    shapes: &[PartShape],
    frames: &Keyframes,
    steps: Vec<Value>,
    warnings: &[String],
    opts: &AnimationOptions,
) -> String {
    let names: Vec<&str> = assembly.parts.iter().map(|p| p.name.as_str()).collect();
    let colors = part_colors(&names);
    let bounds = bounds_of(shapes, None);
    let center = bounds.center();
    let extent = (0..3)
        .map(|k| bounds.max[k] - bounds.min[k])
        .fold(0.0, f64::max);
    let quantum = if extent > 0.0 { extent / QUANTA } else { 1.0 };
    let parts: Vec<_> = shapes
        .iter()
        .enumerate()
        .map(|(k, s)| {
            let tri: Vec<i64> = s
                .triangles
                .iter()
                .flatten()
                .flat_map(|p| (0..3).map(move |c| ((p[c] - center[c]) / quantum).round() as i64))
                .collect();
            json!({
                "name": names[k],
                "color": colors[k].hex(),
                "tri": tri,
                "plane": s.plane,
            })
        })
        .collect();
    let data = json!({
        "name": assembly.name,
        "parts": parts,
        "steps": steps,
        "frames": frames.offsets,
        "quantum": quantum,
        "center": center,
        "stepSeconds": opts.step_seconds.max(0.05),
        "pauseSeconds": opts.pause_seconds.max(0.0),
        "warnings": warnings,
    });
    // "</" cannot end the script element once escaped as "<\/" (same JSON string).
    let data = serde_json::to_string(&data)
        .expect("JSON of plain values")
        .replace("</", "<\\/");
    let (head, tail) = TEMPLATE
        .split_once("__DATA__")
        .expect("the template has a data slot");
    head.replace("__TITLE__", &escape(&assembly.name)) + &data + tail
}
