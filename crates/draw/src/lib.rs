//! Pictures and exports of apart's results, for people.
//!
//! Every picture gives a part the same colour ([`colors::part_colors`]: a part named
//! after a colour gets that colour, the others distinct palette colours).
//!
//! - **The motion-space sphere** of a (sub)assembly, for any step:
//!   [`motion_space_svg`] / [`motion_space_png`], or [`step_motion_space_svg`] /
//!   [`step_motion_space_png`] for a step of a plan. They draw the motion space and the
//!   solutions they are handed and never run the planner. Both hemispheres in Lambert
//!   equal-area or orthographic projection ([`SphereProjection`]), faces shaded by how
//!   many ordered pairs of parts block them, region boundaries drawn, the solutions
//!   (isolated directions as dots, sliding edges as thick arcs, faces as dots at their
//!   deepest direction) coloured by moving subset, a legend naming the parts of each
//!   subset, and the chosen direction ringed.
//! - **Renders without a GPU** ([`raster`]): [`assembly_png`] draws the assembly with
//!   some parts highlighted and the rest grey; [`step_pngs`] draws one picture per step
//!   (the subassembly being split, its moving side pulled out, a caption and an arrow);
//!   [`shapes_png`] and [`shapes_svg`] draw any set of part surfaces, the SVG in a depth
//!   order that is right wherever faces overlap ([`painter`]). With labels, every render
//!   names its coloured parts in a legend and carries an axis triad and a scale bar.
//! - **An animated glTF 2.0 file** ([`disassembly_glb`]): one node and mesh per part, and
//!   an animation moving each step's side out along its direction, in order.
//! - **A self-contained HTML viewer** ([`disassembly_html`]): the assembly in 3-D with a
//!   small canvas renderer, orbit and zoom, play and step buttons, the list of steps,
//!   the parts by name, an axis triad and a scale bar.
//! - **Plans of moves** ([`apart_plan::moves`]): [`moves_html`] and [`moves_glb`] play
//!   the moves (finite ones by their exact translations), [`moves_svg`] draws the plan
//!   state by state, the moving parts highlighted.
//! - **Placements and stacks** of apart-stack ([`stack_render`]): a scene with a placed
//!   part, or a stacking plan, every part by its name.
//!
//! ```no_run
//! use apart_assembly::{load, LoadOptions};
//! use apart_plan::{parts_of, sequence, BlockingRegions, KeepSolutions, MotionSpace};
//! use apart_plan::SequenceOptions;
//! let loaded = load(std::path::Path::new("examples/split-star-3"), &LoadOptions::default()).unwrap();
//! let assembly = &loaded.assembly;
//! let regions = BlockingRegions::compute(parts_of(assembly).unwrap()).unwrap();
//! // The first step keeps its solutions, for its sphere picture.
//! let opts = SequenceOptions { keep_solutions: KeepSolutions::Step(0), ..Default::default() };
//! let plan = sequence(&regions, &opts);
//! std::fs::write("plan.glb", apart_draw::disassembly_glb(assembly, &plan)).unwrap();
//! std::fs::write("plan.html", apart_draw::disassembly_html(assembly, &plan)).unwrap();
//! for (k, png) in apart_draw::step_pngs(assembly, &plan, &Default::default(), 800, 600)
//!     .iter()
//!     .enumerate()
//! {
//!     std::fs::write(format!("step-{}.png", k + 1), png).unwrap();
//! }
//! let step = &plan.steps[0];
//! let ms = MotionSpace::build_split_at_equator(&regions, &step.subassembly);
//! let sphere = apart_draw::step_motion_space_svg(&ms, regions.names(), step, &Default::default());
//! std::fs::write("step-1-sphere.svg", sphere).unwrap();
//! ```

pub mod colors;
pub mod gltf_export;
pub mod html_viewer;
pub mod motion;
pub mod moves;
pub mod painter;
pub mod raster;
pub mod shapes;
pub mod sphere_svg;
pub mod stack_render;
pub mod svg_png;

pub use gltf_export::{disassembly_glb, disassembly_glb_with};
pub use html_viewer::{disassembly_html, disassembly_html_with};
pub use motion::{AnimationOptions, Keyframes};
pub use moves::{moves_glb, moves_html, moves_svg};
pub use raster::{assembly_png, shapes_part_ids, shapes_png, shapes_svg, step_pngs, View};
pub use sphere_svg::{
    motion_space_png, motion_space_svg, step_motion_space_png, step_motion_space_svg,
    SphereProjection, SphereSvgOptions,
};
