//! Pictures of a scene: PNG renders drawn without a GPU and SVG drawings, one colour per
//! part, every part named in the legend, with an axis triad and a scale bar, through
//! `apart-draw`.

use crate::planner::StackPlan;
use crate::scene::Scene;
use apart_draw::shapes::{pieces_shape, PartShape};
use apart_draw::View;
use apart_pieces::Polytope;

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
    apart_draw::shapes_png(&shapes, &names, &[], view, width, height)
}

/// An SVG drawing of a stacking plan, in the same picture as [`plan_png`] (faces in a
/// depth order that is right wherever they overlap).
pub fn plan_svg(plan: &StackPlan, step: f64, view: &View, width: u32, height: u32) -> String {
    let (shapes, names) = plan_shapes(plan, step);
    apart_draw::shapes_svg(&shapes, &names, view, width, height)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::q;
    use crate::parts::cube;
    use crate::planner::{stack, StackOptions};

    #[test]
    fn scene_parts_keep_their_names() {
        let mut scene = Scene::new();
        scene.add_fixed_part(&cube(1).pieces);
        scene.add_fixed_part(&cube(1).pieces);
        let names = ["base".to_string()];
        let (shapes, all) = scene_shapes(&scene, &names, &[("lid".into(), cube(1).pieces)], 1.0);
        assert_eq!(shapes.len(), 3);
        assert_eq!(all, ["base", "fixed 2", "lid"]);
    }

    #[test]
    fn pictures_show_every_part() {
        let mut opts = StackOptions::new(3, q(1), [q(-2), q(-2), q(2), q(2)], q(10));
        opts.dtheta_deg = 90.0;
        let plan = stack(&cube(1), &opts).unwrap();
        let (shapes, names) = plan_shapes(&plan, 1.0);
        assert_eq!(names, ["cube #1", "cube #2", "cube #3"]);
        // A cube: 6 square facets, 12 triangles, 6 planes.
        assert!(shapes.iter().all(|s| s.triangles.len() == 12));
        let svg = plan_svg(&plan, 1.0, &View::default(), 320, 240);
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        // Each cube shows at most three faces to the default view, one path each, and
        // the legend names every part.
        let drawing = svg.split("<g id=\"axes\"").next().unwrap();
        let faces = drawing.matches("<path d=\"M").count();
        assert!((3..=9).contains(&faces), "{faces} faces drawn");
        for name in &names {
            assert!(svg.contains(&format!(">{name}</text>")), "{name}");
        }
        for axis in ["x", "y", "z"] {
            assert!(svg.contains(&format!(">{axis}</text>")), "axis {axis}");
        }
        assert!(
            svg.contains(" units</text>") || svg.contains(" unit</text>"),
            "scale bar"
        );
        let png = plan_png(&plan, 1.0, &View::default(), 320, 240);
        let img = resvg::tiny_skia::Pixmap::decode_png(&png).unwrap();
        assert_eq!((img.width(), img.height()), (320, 240));
        let coloured = img
            .pixels()
            .iter()
            .filter(|p| (p.red(), p.green(), p.blue()) != (255, 255, 255))
            .count();
        assert!(coloured > 1000, "{coloured} coloured pixels");
    }
}
