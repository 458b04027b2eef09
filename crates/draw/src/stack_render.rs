//! Pictures of apart-stack's placements and stacks: PNG renders drawn without a GPU
//! and SVG drawings, one colour per part, every part named in the legend, with an axis
//! triad and a scale bar. Drawn from the scene or plan they are handed.

use crate::shapes::{pieces_shape, PartShape};
use crate::View;
use apart_pieces::Polytope;
use apart_stack::planner::StackPlan;
use apart_stack::scene::Scene;

/// The surfaces of the scene's parts (pieces grouped by part), then of `extra` parts
/// given by their placed pieces, in input units for a grid of the given step, with
/// their names: `names[k]` for scene part `k` (`fixed k+1` where `names` runs out), and
/// the given names for the extra ones.
pub fn scene_shapes(
    scene: &Scene,
    names: &[String],
    extra: &[(String, Vec<Polytope>)],
    step: f64,
) -> (Vec<PartShape>, Vec<String>) {
    let mut by_part: Vec<Vec<Polytope>> = vec![Vec::new(); scene.part_count()];
    for (k, sp) in scene.pieces().iter().enumerate() {
        by_part[sp.part].push(scene.placed(k));
    }
    let mut shapes: Vec<PartShape> = by_part.iter().map(|p| pieces_shape(p, step)).collect();
    let mut names: Vec<String> = (0..shapes.len())
        .map(|k| {
            names
                .get(k)
                .cloned()
                .unwrap_or_else(|| format!("fixed {}", k + 1))
        })
        .collect();
    for (name, pieces) in extra {
        shapes.push(pieces_shape(pieces, step));
        names.push(name.clone());
    }
    (shapes, names)
}

/// The parts of a stacking plan in place, named after the part and numbered in placing
/// order (`channel #1`, `channel #2`, …, as the text answer numbers them).
pub fn plan_shapes(plan: &StackPlan, step: f64) -> (Vec<PartShape>, Vec<String>) {
    let shapes = (0..plan.placements.len())
        .map(|k| pieces_shape(&plan.pieces_of(k), step))
        .collect();
    let name = &plan.moving.part.name;
    let names = (1..=plan.placements.len())
        .map(|k| format!("{name} #{k}"))
        .collect();
    (shapes, names)
}

/// A PNG render of a stacking plan (every part in its colour, legend in placing order,
/// axis triad and scale bar when `view.labels`).
pub fn plan_png(plan: &StackPlan, step: f64, view: &View, width: u32, height: u32) -> Vec<u8> {
    let (shapes, names) = plan_shapes(plan, step);
    crate::shapes_png(&shapes, &names, &[], view, width, height)
}

/// An SVG drawing of a stacking plan, in the same picture as [`plan_png`] (faces in a
/// depth order that is right wherever they overlap).
pub fn plan_svg(plan: &StackPlan, step: f64, view: &View, width: u32, height: u32) -> String {
    let (shapes, names) = plan_shapes(plan, step);
    crate::shapes_svg(&shapes, &names, view, width, height)
}
