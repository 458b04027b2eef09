//! `apart sequence <assembly>`: a complete disassembly plan by recursive two-handed
//! partitioning (its reverse is an assembly plan), with pictures and animated exports.
//! Exit code 0 when every part comes apart (an assembly of one part: nothing to
//! separate, no step), 2 when a subassembly is interlocked (the partial plan is printed
//! and names it), 3 when `--timeout` stopped the run (the steps found until then are
//! printed, and the subassemblies not yet split), 1 on error.

use crate::commands::load::{load_valid, part_index};
use crate::commands::partition::Projection;
use crate::input_facts::{holds_without_tolerance, tolerance_statement, InputFacts};
use crate::limits::TimedOut;
use crate::output;
use crate::{limits, Global};
use apart::draw::{
    assembly_png, disassembly_glb, disassembly_html, motion_space_png, motion_space_svg,
    step_motion_space_png, step_motion_space_svg, step_pngs, SphereSvgOptions, View,
};
use apart::plan::sequence::{Choice, Keys};
use apart::plan::{
    parts_of, sequence_first, sequence_with, BlockingRegions, CellKind, KeepSolutions, MotionSpace,
    PlanError, Sequence, SequenceOptions, Step, Tolerance,
};
use serde::Serialize;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Arguments of `apart sequence`.
#[derive(clap::Args, Debug)]
pub struct SequenceArgs {
    /// A folder of mesh files, one mesh file, or an assembly.json manifest.
    pub assembly: PathBuf,
    /// Split each subassembly along the first likely direction that frees a subset of
    /// it (the axes, the axes of tessellated cylinders, the normals of touching planes,
    /// each tested exactly), without the pair regions of the whole assembly: much faster
    /// on tessellated parts. The moving set is the smallest minimal one there; a
    /// subassembly that no likely direction splits gets the full, ranked search, so the
    /// plan is as complete as without --first. Steps are not ranked by clearance.
    #[arg(long, conflicts_with_all = ["prefer_single", "prefer_connected", "prefer_axes", "explain", "growth", "svg", "png"])]
    pub first: bool,
    /// Prefer steps that move a single part.
    #[arg(long)]
    pub prefer_single: bool,
    /// Prefer steps whose two sides each stay connected through contacts.
    #[arg(long)]
    pub prefer_connected: bool,
    /// Prefer directions along the coordinate axes: a step moves along ±x, ±y or ±z
    /// whenever one of them is free for its moving set (ahead of a face of larger
    /// clearance; after --prefer-connected and --prefer-single).
    #[arg(long)]
    pub prefer_axes: bool,
    /// Print, under each step, why it was chosen: its ranking keys, how many candidates
    /// were ranked, and the runner-up with the key it lost on (in the JSON: `choice`).
    ///
    /// Candidates (a moving set and a direction along which it is free) are compared by
    /// these keys in order, the first difference deciding: (1) with --prefer-connected,
    /// both sides stay connected through contacts; (2) with --prefer-single, one part
    /// moves; (3) with --prefer-axes, the direction is ±x, ±y or ±z; (4) a face (an
    /// open region of free directions) before an edge (a sliding arc) before a vertex
    /// (an isolated direction); (5) the larger clearance; (6) fewer moving parts; (7)
    /// the lowest part indices, then the direction. The candidates are the deepest
    /// direction of each free region of each minimal moving set, with --prefer-axes
    /// also the six axis directions (tested exactly), and edges and vertices when no
    /// face meets --prefer-single or --prefer-connected.
    #[arg(long)]
    pub explain: bool,
    /// A part that never moves (the other side moves instead).
    #[arg(long, value_name = "NAME")]
    pub base: Option<String>,
    /// Split at most this many levels deep, 1 or more (subassemblies below stay whole).
    #[arg(long, value_name = "N", value_parser = limits::positive, allow_negative_numbers = true)]
    pub max_depth: Option<usize>,
    /// For each step, the largest uniform growth of the parts that keeps it possible
    /// (compare with manufacturing tolerances).
    #[arg(long)]
    pub growth: bool,
    /// Draw the motion-space sphere of step K (see --step) as SVG.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
    /// The same picture as PNG.
    #[arg(long, value_name = "FILE")]
    pub png: Option<PathBuf>,
    /// The step (1-based) the sphere pictures show.
    #[arg(long, value_name = "K", default_value_t = 1, value_parser = limits::positive, allow_negative_numbers = true)]
    pub step: usize,
    /// Projection of the sphere pictures.
    #[arg(long, value_enum, default_value_t = Projection::EqualArea)]
    pub projection: Projection,
    /// Write an animated glTF binary (GLB) of the disassembly.
    #[arg(long, value_name = "FILE")]
    pub glb: Option<PathBuf>,
    /// Write a self-contained HTML page that plays the disassembly in 3-D.
    #[arg(long, value_name = "FILE")]
    pub html: Option<PathBuf>,
    /// Write PNG renders (the assembly, then each step with its moving side highlighted)
    /// into this folder.
    #[arg(long, value_name = "FOLDER")]
    pub renders: Option<PathBuf>,
}

#[derive(Serialize)]
struct StepJson {
    subassembly: Vec<String>,
    moving: Vec<String>,
    direction: [f64; 3],
    exact_direction: [String; 3],
    cell: &'static str,
    clearance_deg: f64,
    depth: usize,
    /// Largest uniform growth in input units (--growth); null when unbounded.
    #[serde(skip_serializing_if = "Option::is_none")]
    growth: Option<Option<f64>>,
    /// Under a tolerance: the step also holds for the parts as given.
    #[serde(skip_serializing_if = "Option::is_none")]
    holds_without_tolerance: Option<bool>,
    /// With --explain: why the step was chosen.
    #[serde(skip_serializing_if = "Option::is_none")]
    choice: Option<ChoiceJson>,
}

/// A candidate's ranking keys.
#[derive(Serialize)]
struct KeysJson {
    /// Both sides connected through contacts; null unless --prefer-connected.
    connected: Option<bool>,
    single: bool,
    axis: bool,
    cell: &'static str,
    clearance_deg: f64,
    parts: usize,
}

/// The best candidate the chosen one beat.
#[derive(Serialize)]
struct RivalJson {
    moving: Vec<String>,
    exact_direction: [String; 3],
    #[serde(flatten)]
    keys: KeysJson,
    /// The first key it lost on: connected, single, axis, cell, clearance, fewer_parts,
    /// order.
    lost_on: &'static str,
}

/// Why a step was chosen.
#[derive(Serialize)]
struct ChoiceJson {
    candidates: usize,
    #[serde(flatten)]
    keys: KeysJson,
    runner_up: Option<RivalJson>,
}

#[derive(Serialize)]
struct SequenceJson {
    /// "done", or "timeout": --timeout stopped the run; `steps` are the steps found
    /// until then and `not_yet_split` the subassemblies still to split.
    status: &'static str,
    /// Where --timeout stopped the run; absent when it ran to its end.
    #[serde(skip_serializing_if = "Option::is_none")]
    stopped: Option<output::StoppedJson>,
    interlocked: bool,
    complete: bool,
    /// The assembly has one part: there is nothing to separate (complete, no step).
    nothing_to_separate: bool,
    parts: Vec<String>,
    steps: Vec<StepJson>,
    /// Subassemblies no single translation can split.
    stuck: Vec<Vec<String>>,
    /// Subassemblies left whole by --max-depth.
    unsplit: Vec<Vec<String>>,
    /// Subassemblies not yet split when --timeout stopped the run (empty otherwise), in
    /// the order they would have been split.
    not_yet_split: Vec<Vec<String>>,
    /// With --first: subassemblies that no likely direction split, searched in full
    /// (their own pair regions); null without --first.
    full_searches: Option<usize>,
    seconds: SecondsJson,
    #[serde(flatten)]
    input: InputFacts,
}

#[derive(Serialize)]
struct SecondsJson {
    load: f64,
    regions: f64,
    steps: f64,
}

/// Runs the command.
pub fn run(args: &SequenceArgs, global: &Global) -> anyhow::Result<ExitCode> {
    let t = Instant::now();
    let loaded = load_valid(&args.assembly, global)?;
    let load = t.elapsed().as_secs_f64();
    let asm = &loaded.assembly;
    // A wrong name is told before the long work.
    let base = match &args.base {
        Some(name) => Some(part_index(asm, name, "--base")?),
        None => None,
    };
    let t = Instant::now();
    let regions = if args.first {
        None
    } else {
        let (_phase, progress) = output::planner(global, "pair regions");
        match BlockingRegions::compute_with(parts_of(asm)?, &progress) {
            Ok(r) => Some(r),
            Err(PlanError::Stopped { .. }) => None,
            Err(e) => return Err(e.into()),
        }
    };
    let regions_s = t.elapsed().as_secs_f64();
    let opts = SequenceOptions {
        prefer_single: args.prefer_single,
        prefer_connected: args.prefer_connected,
        prefer_axes: args.prefer_axes,
        base,
        max_depth: args.max_depth,
        tolerance: args.growth,
        // The step the sphere pictures draw keeps its solutions: drawing plans nothing.
        keep_solutions: if args.svg.is_some() || args.png.is_some() {
            KeepSolutions::Step(args.step.saturating_sub(1))
        } else {
            KeepSolutions::Nothing
        },
    };
    let plan = match &regions {
        None if args.first => {
            let (_phase, progress) = output::planner(global, "sequence steps");
            sequence_first(parts_of(asm)?, &opts, &progress)?
        }
        // Stopped while the pair regions were computed: no step yet.
        None => Sequence::stopped_before_steps(asm.parts.iter().map(|p| p.name.clone()).collect()),
        Some(regions) => {
            // The first step's motion space, of every part, is the largest.
            let all: Vec<usize> = (0..regions.names().len()).collect();
            crate::limits::check_motion_space(regions, &all, global)?;
            let (_phase, progress) = output::planner(global, "sequence steps");
            sequence_with(regions, &opts, &progress)
        }
    };
    let files = args.svg.is_some()
        || args.png.is_some()
        || args.glb.is_some()
        || args.html.is_some()
        || args.renders.is_some();
    let stop = output::partial(global, plan.stopped, files);
    if stop.is_none() && (regions.is_some() || args.first) {
        let _phase = output::phase(global, "pictures and exports");
        pictures(args, asm, regions.as_ref(), &plan)?;
    }
    let step_unit = asm.grid.step();
    let motions = plan.motions();
    let holds = {
        let _phase = output::phase(global, "checking the steps without the tolerance");
        holds_without_tolerance(asm, &motions)?
    };
    if global.json {
        let input = InputFacts::of(&loaded, global);
        let times = (load, regions_s);
        output::json(&to_json(
            &plan, args, step_unit, times, input, &holds, &stop,
        ))?;
    } else {
        let times = (output::load_time(load, &loaded.seconds), regions_s);
        print_text(&plan, args, asm, global, step_unit, times, &holds, &stop);
        if let Some(t) = tolerance_statement(asm, global) {
            output::line(t);
        }
    }
    Ok(if stop.is_some() {
        ExitCode::from(limits::EXIT_PARTIAL)
    } else if plan.stuck.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(2)
    })
}

/// The files asked for; the sphere pictures need the pair regions (`None` with
/// --first, which clap keeps apart from --svg and --png).
fn pictures(
    args: &SequenceArgs,
    asm: &apart::assembly::Assembly,
    regions: Option<&BlockingRegions>,
    plan: &Sequence,
) -> anyhow::Result<()> {
    if let Some(regions) = regions.filter(|_| args.svg.is_some() || args.png.is_some()) {
        let names = regions.names();
        let base = SphereSvgOptions {
            projection: args.projection.into(),
            ..Default::default()
        };
        match (
            plan.steps.get(args.step.wrapping_sub(1)),
            plan.stuck.first(),
        ) {
            (Some(step), _) => {
                // One motion space for both pictures, cut at the equator (the planner's is not).
                let ms = MotionSpace::build_split_at_equator(regions, &step.subassembly);
                if let Some(p) = &args.svg {
                    output::write_file(p, step_motion_space_svg(&ms, names, step, &base))?;
                }
                if let Some(p) = &args.png {
                    output::write_file(p, step_motion_space_png(&ms, names, step, &base))?;
                }
            }
            // No step at all: the whole assembly is interlocked. Its motion space, blocked
            // everywhere, is the picture of that answer.
            (None, Some(stuck)) if plan.steps.is_empty() && args.step == 1 => {
                let ms = MotionSpace::build_split_at_equator(regions, stuck);
                let opts = SphereSvgOptions {
                    title: format!(
                        "{}: interlocked, no subset of {{{}}} can move",
                        asm.name,
                        names_of(regions.names(), stuck).join(", ")
                    ),
                    ..base
                };
                if let Some(p) = &args.svg {
                    output::write_file(p, motion_space_svg(&ms, names, &[], &opts))?;
                }
                if let Some(p) = &args.png {
                    output::write_file(p, motion_space_png(&ms, names, &[], &opts))?;
                }
            }
            _ => anyhow::bail!(
                "--step {}: the plan has {} step{}",
                args.step,
                plan.steps.len(),
                if plan.steps.len() == 1 { "" } else { "s" }
            ),
        }
    }
    if let Some(p) = &args.glb {
        output::write_file(p, disassembly_glb(asm, plan))?;
    }
    if let Some(p) = &args.html {
        output::write_file(p, disassembly_html(asm, plan))?;
    }
    if let Some(dir) = &args.renders {
        std::fs::create_dir_all(dir)
            .map_err(|e| anyhow::anyhow!("cannot create {}: {e}", dir.display()))?;
        let view = View::default();
        output::write_file(
            &dir.join("assembly.png"),
            assembly_png(asm, &[], &view, 1000, 750),
        )?;
        for (k, png) in step_pngs(asm, plan, &view, 1000, 750).iter().enumerate() {
            output::write_file(&dir.join(format!("step-{}.png", k + 1)), png)?;
        }
    }
    Ok(())
}

fn names(plan: &Sequence, set: &[usize]) -> Vec<String> {
    names_of(&plan.names, set)
}

fn names_of(all: &[String], set: &[usize]) -> Vec<String> {
    set.iter().map(|&k| all[k].clone()).collect()
}

fn tolerance_units(t: &Option<Tolerance>, step_unit: f64) -> Option<Option<f64>> {
    t.map(|t| match t {
        Tolerance::Finite(s) => Some(s * step_unit),
        Tolerance::Unbounded => None,
    })
}

fn keys_json(k: &Keys) -> KeysJson {
    KeysJson {
        connected: k.connected,
        single: k.single,
        axis: k.axis,
        cell: k.cell.name(),
        clearance_deg: k.clearance_deg,
        parts: k.parts,
    }
}

fn choice_json(plan: &Sequence, c: &Choice) -> ChoiceJson {
    ChoiceJson {
        candidates: c.candidates,
        keys: keys_json(&c.keys),
        runner_up: c.runner_up.as_ref().map(|r| RivalJson {
            moving: names(plan, &r.moving),
            exact_direction: r.direction.to_strings(),
            keys: keys_json(&r.keys),
            lost_on: r.lost_on.key(),
        }),
    }
}

fn to_json(
    plan: &Sequence,
    args: &SequenceArgs,
    step_unit: f64,
    (load, regions): (f64, f64),
    input: InputFacts,
    holds: &Option<Vec<bool>>,
    stop: &Option<TimedOut>,
) -> SequenceJson {
    SequenceJson {
        input,
        status: output::status(stop),
        stopped: output::stopped_json(stop),
        not_yet_split: plan.pending.iter().map(|s| names(plan, s)).collect(),
        interlocked: !plan.stuck.is_empty(),
        complete: plan.complete(),
        nothing_to_separate: plan.names.len() < 2,
        parts: plan.names.clone(),
        steps: plan
            .steps
            .iter()
            .enumerate()
            .map(|(k, s)| StepJson {
                holds_without_tolerance: holds.as_ref().map(|h| h[k]),
                subassembly: names(plan, &s.subassembly),
                moving: names(plan, &s.moving),
                direction: s.unit,
                exact_direction: s.direction.to_strings(),
                cell: s.cell.name(),
                clearance_deg: s.clearance_deg,
                depth: s.depth,
                growth: tolerance_units(&s.tolerance, step_unit),
                choice: args.explain.then(|| choice_json(plan, &s.choice)),
            })
            .collect(),
        stuck: plan.stuck.iter().map(|s| names(plan, s)).collect(),
        unsplit: plan.unsplit.iter().map(|s| names(plan, s)).collect(),
        full_searches: args.first.then_some(plan.full_searches),
        seconds: SecondsJson {
            load,
            regions,
            steps: plan.step_seconds,
        },
    }
}

fn describe(plan: &Sequence, s: &Step, step_unit: f64) -> String {
    let d = s.direction.to_strings();
    let kind = match s.cell.name() {
        "face" => format!("face, clearance {:.2}°", s.clearance_deg),
        "edge" => "edge, sliding".to_string(),
        _ => "isolated direction".to_string(),
    };
    let tol = match tolerance_units(&s.tolerance, step_unit) {
        Some(Some(x)) => format!("; tolerates growth up to {x:.6}"),
        Some(None) => "; any growth".to_string(),
        None => String::new(),
    };
    format!(
        "{} {} along ({}, {}, {}) ≈ {} ({kind}{tol})",
        names(plan, &s.moving).join(", "),
        if s.moving.len() == 1 { "moves" } else { "move" },
        d[0],
        d[1],
        d[2],
        output::unit(&s.unit)
    )
}

/// A candidate's keys in words: "single part, axis direction, face with clearance
/// 45.00°".
fn keys_text(k: &Keys) -> String {
    let mut out = Vec::new();
    if let Some(c) = k.connected {
        out.push(
            if c {
                "both sides connected"
            } else {
                "a side not connected"
            }
            .to_string(),
        );
    }
    out.push(match k.parts {
        1 => "single part".to_string(),
        n => format!("{n} parts"),
    });
    out.push(
        if k.axis {
            "axis direction"
        } else {
            "oblique direction"
        }
        .to_string(),
    );
    out.push(match k.cell {
        CellKind::Face => format!("face with clearance {:.2}°", k.clearance_deg),
        CellKind::Edge => "edge (sliding)".to_string(),
        CellKind::Vertex => "vertex (isolated direction)".to_string(),
    });
    out.join(", ")
}

/// Why a step was chosen, in one sentence.
fn explain(plan: &Sequence, c: &Choice) -> String {
    let mut out = format!("why: {}", keys_text(&c.keys));
    match &c.runner_up {
        None => out.push_str("; the only candidate"),
        Some(r) => {
            let d = r.direction.to_strings();
            let others = c.candidates - 1;
            out.push_str(&format!(
                "; preferred over {others} other candidate{}: the runner-up, {{{}}} along ({}, {}, {}) ({}), lost on {}",
                if others == 1 { "" } else { "s" },
                names(plan, &r.moving).join(", "),
                d[0],
                d[1],
                d[2],
                keys_text(&r.keys),
                r.lost_on.describe()
            ));
        }
    }
    out
}

#[allow(clippy::too_many_arguments)]
fn print_text(
    plan: &Sequence,
    args: &SequenceArgs,
    asm: &apart::assembly::Assembly,
    global: &Global,
    step_unit: f64,
    (load, regions): (String, f64),
    holds: &Option<Vec<bool>>,
    stop: &Option<TimedOut>,
) {
    let status = if let Some(t) = stop {
        t.to_string()
    } else if plan.complete() {
        "complete".to_string()
    } else if !plan.stuck.is_empty() {
        "incomplete: interlocked subassembly".to_string()
    } else {
        "stopped at the depth limit".to_string()
    };
    if plan.names.len() < 2 {
        output::line(format_args!(
            "disassembly of \"{}\" ({} part): nothing to separate",
            asm.name,
            plan.names.len()
        ));
        return;
    }
    output::line(format_args!(
        "disassembly of \"{}\" ({} part{}): {} step{}, {status}",
        asm.name,
        plan.names.len(),
        if plan.names.len() == 1 { "" } else { "s" },
        plan.steps.len(),
        if plan.steps.len() == 1 { "" } else { "s" }
    ));
    output::line("");
    for (k, s) in plan.steps.iter().enumerate() {
        let pad = "  ".repeat(s.depth);
        output::line(format_args!(
            "{pad}{}. split {{{}}}",
            k + 1,
            names(plan, &s.subassembly).join(", ")
        ));
        let only = match holds {
            Some(h) if !h[k] => " (only under the tolerance)",
            _ => "",
        };
        output::line(format_args!(
            "{pad}   {}{only}",
            describe(plan, s, step_unit)
        ));
        if args.explain {
            output::line(format_args!("{pad}   {}", explain(plan, &s.choice)));
        }
    }
    for s in &plan.stuck {
        output::line(format_args!(
            "interlocked: {{{}}} cannot be split by one translation",
            names(plan, s).join(", ")
        ));
    }
    for s in &plan.unsplit {
        output::line(format_args!(
            "left whole (depth limit): {{{}}}",
            names(plan, s).join(", ")
        ));
    }
    for s in &plan.pending {
        output::line(format_args!(
            "not yet split (stopped by --timeout): {{{}}}",
            names(plan, s).join(", ")
        ));
    }
    if !plan.steps.is_empty() {
        output::line("");
        output::line(if stop.is_some() {
            "assembly sequence (the reverse; what is not yet split taken whole):"
        } else {
            "assembly sequence (the reverse):"
        });
        for (k, s) in plan.steps.iter().rev().enumerate() {
            let rest: Vec<usize> = s.staying();
            let d = s.direction.neg().to_strings();
            output::line(format_args!(
                "{}. bring {{{}}} to {{{}}} along ({}, {}, {})",
                k + 1,
                names(plan, &s.moving).join(", "),
                names(plan, &rest).join(", "),
                d[0],
                d[1],
                d[2]
            ));
        }
    }
    if args.first {
        output::line("");
        output::line(format_args!(
            "--first: each step along the first likely direction that frees a subset, not ranked by clearance; {} subassembl{} searched in full",
            plan.full_searches,
            if plan.full_searches == 1 { "y" } else { "ies" }
        ));
    }
    if !global.quiet {
        output::line("");
        output::line(format_args!(
            "time: {load}, pair regions {:.1} ms, steps {:.1} ms",
            regions * 1e3,
            plan.step_seconds * 1e3
        ));
    }
}
