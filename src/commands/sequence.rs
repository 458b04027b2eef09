//! `apart sequence <assembly>`: a complete disassembly plan by recursive two-handed
//! partitioning (its reverse is an assembly plan), with pictures and animated exports.
//! Each step is printed as soon as it is found (text, or `--jsonl`: one JSON object per
//! line); `--json` prints the whole answer at the end. Exit code 0 when every part
//! comes apart (an assembly of one part: nothing to separate, no step), 2 when a
//! subassembly is interlocked (the partial plan is printed and names it), 3 when
//! `--timeout` stopped the run (the steps found until then are printed, and the
//! subassemblies not yet split), 130 when Ctrl-C did, 1 when the memory budget did (the
//! same partial answer, then the error line) and on error.

use crate::commands::load::{load_valid, part_index};
use crate::commands::partition::Projection;
use crate::input_facts::{tolerance_statement, Units};
use crate::limits::Stopped;
use crate::output;
use crate::{limits, Global};
use apart::draw::{
    assembly_png, disassembly_glb, disassembly_html, motion_space_png, motion_space_svg,
    step_motion_space_png, step_motion_space_svg, step_pngs, SphereSvgOptions, View,
};
use apart::jobs::sequence::{region_seconds, sequence, step_answer, SequenceJobOptions};
use apart::jobs::Status;
use apart::plan::sequence::Keys;
use apart::plan::{
    partition_subset, parts_of, BlockingRegions, CellKind, Growth, KeepSolutions, MotionSpace,
    Options, Part, Progress, Ranking, Rule, Sequence, SequenceOptions, Solution, Step,
};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// How each subassembly's step is chosen (`--ranking`).
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum RankingArg {
    /// Rank small subassemblies over their full motion space, larger ones by the local
    /// rules.
    Auto,
    /// Rank every subassembly over its full motion space.
    Full,
    /// Always the local rules.
    Local,
}

impl From<RankingArg> for Ranking {
    fn from(r: RankingArg) -> Ranking {
        match r {
            RankingArg::Auto => Ranking::Auto,
            RankingArg::Full => Ranking::Full,
            RankingArg::Local => Ranking::Local,
        }
    }
}

/// Arguments of `apart sequence`.
#[derive(clap::Args, Debug)]
pub struct SequenceArgs {
    /// A folder of mesh files, one mesh file, an assembly.json manifest, or a STEP file
    /// (.step, .stp: read by the Python package, pip install './python[step]').
    pub assembly: PathBuf,
    /// Split each subassembly along the first likely direction that frees a subset of
    /// it (the axes, the axes of tessellated cylinders, the normals of touching planes,
    /// each tested exactly), without the pair regions of the whole assembly: much faster
    /// on tessellated parts. The moving set is the smallest minimal one there; a
    /// subassembly that no likely direction splits gets the full, ranked search, so the
    /// plan is as complete as without --first. Steps are not ranked by clearance.
    #[arg(long, conflicts_with_all = ["prefer_single", "prefer_connected", "prefer_axes", "explain", "growth", "svg", "png"])]
    pub first: bool,
    /// How each subassembly's step is chosen. auto: a subassembly of at most 24 parts is
    /// ranked over its full motion space when that is cheap (few piece pairs, a small
    /// motion space), a larger one by the local rules: a single part along its own
    /// widest-clearance face, then two touching parts along their widest face, then a
    /// set of parts along the first likely direction (an axis, a tessellated cylinder's
    /// axis, a touching plane's normal) that frees one, then edges and vertices of
    /// those, and the full motion space only when nothing simpler splits the subassembly (so a
    /// subassembly is called interlocked only when no translation splits it). full:
    /// every subassembly ranked over its full motion space, as before (the pair regions
    /// of every pair; slow on many parts). local: always the local rules.
    #[arg(long, value_enum, value_name = "RULES", default_value_t = RankingArg::Auto, conflicts_with = "first")]
    pub ranking: RankingArg,
    /// Print the answer as JSON lines, each flushed as it is written: one object
    /// {"event": "step", "index": K, ...} per step as it is found (K from 1), then one
    /// {"event": "end", ...} with the rest of the --json answer (status, counts, times;
    /// "complete": false when the run was stopped). Not with --json.
    #[arg(long)]
    pub jsonl: bool,
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
    /// Print, under each step, the rule that chose it and why: its ranking keys, how
    /// many candidates were ranked, and the runner-up with the key it lost on (in the
    /// JSON: `choice`).
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
    /// face meets --prefer-single or --prefer-connected. A step chosen by the local
    /// rules (see --ranking) was ranked among single parts, or is the first likely
    /// direction that frees a set.
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
    /// into this folder, whole or not at all. An existing folder is replaced only when
    /// it is empty or an earlier --renders wrote it (it holds the hidden file
    /// .apart-output); any other is refused.
    #[arg(long, value_name = "FOLDER")]
    pub renders: Option<PathBuf>,
}

/// One line of --jsonl: an event and its fields.
#[derive(Serialize)]
struct Event<'a, T: Serialize> {
    event: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    index: Option<usize>,
    #[serde(flatten)]
    body: &'a T,
}

/// Writes one JSON line on standard output and flushes it (through
/// [`output::to_stdout`]: a write error fails the run at its end).
fn json_line<T: Serialize>(value: &T) {
    use std::io::Write;
    output::to_stdout(|out| {
        serde_json::to_writer(&mut *out, value)?;
        out.write_all(b"\n")?;
        out.flush()
    });
}

/// How the answer is printed.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    Text,
    Json,
    JsonLines,
}

/// Indentation stops growing at this depth (the depth is then written out).
const MAX_INDENT: usize = 20;
/// Part lists longer than this are abbreviated in text ...
const LIST_MAX: usize = 12;
/// ... to their first this many names.
const LIST_HEAD: usize = 8;

/// The names of `set`, comma-separated; more than [`LIST_MAX`] abbreviated to the first
/// [`LIST_HEAD`] and "… and N more" (the JSON keeps every name).
fn list(all: &[String], set: &[usize]) -> String {
    if set.len() <= LIST_MAX {
        return names_of(all, set).join(", ");
    }
    format!(
        "{}, … and {} more",
        names_of(all, &set[..LIST_HEAD]).join(", "),
        set.len() - LIST_HEAD
    )
}

/// Prints each step as the planner finds it.
struct Printer<'a> {
    mode: Mode,
    args: &'a SequenceArgs,
    names: &'a [String],
    step_unit: f64,
    /// Steps printed.
    count: usize,
}

impl Printer<'_> {
    fn step(&mut self, s: &Step, holds: Option<bool>) {
        let k = self.count;
        self.count += 1;
        match self.mode {
            Mode::Json => {}
            Mode::JsonLines => json_line(&Event {
                event: "step",
                index: Some(k + 1),
                body: &step_answer(self.names, s, self.step_unit, holds, self.args.explain),
            }),
            Mode::Text => self.text(k, s, holds),
        }
    }

    fn text(&self, k: usize, s: &Step, holds: Option<bool>) {
        let names = self.names;
        let pad = "  ".repeat(s.depth.min(MAX_INDENT));
        let deep = if s.depth > MAX_INDENT {
            format!("[depth {}] ", s.depth)
        } else {
            String::new()
        };
        output::line(format_args!(
            "{pad}{}. {deep}split {{{}}}",
            k + 1,
            list(names, &s.subassembly)
        ));
        let only = if holds == Some(false) {
            " (only under the tolerance)"
        } else {
            ""
        };
        output::line(format_args!(
            "{pad}   {}{only}",
            describe(names, s, self.step_unit)
        ));
        if self.args.explain {
            output::line(format_args!("{pad}   rule: {}", rule_text(s.rule)));
            output::line(format_args!("{pad}   {}", explain(names, s)));
        }
    }
}

/// Runs the command.
pub fn run(args: &SequenceArgs, global: &Global) -> anyhow::Result<ExitCode> {
    if args.jsonl && global.json {
        anyhow::bail!("--jsonl and --json are two forms of the answer: give one of them");
    }
    // Before loading, so that a run ended by the memory budget while loading ends its
    // JSON lines with an "end" event too.
    if args.jsonl {
        limits::set_json_lines();
    }
    let t = Instant::now();
    let loaded = load_valid(&args.assembly, global)?;
    let load = t.elapsed().as_secs_f64();
    check_outputs(args, &output::Inputs::of(&args.assembly, &loaded))?;
    let asm = &loaded.assembly;
    // A wrong name is told before the long work.
    let base = match &args.base {
        Some(name) => Some(part_index(asm, name, "--base")?),
        None => None,
    };
    let mode = if global.json {
        Mode::Json
    } else if args.jsonl {
        Mode::JsonLines
    } else {
        Mode::Text
    };
    let opts = SequenceOptions {
        prefer_single: args.prefer_single,
        prefer_connected: args.prefer_connected,
        prefer_axes: args.prefer_axes,
        base,
        max_depth: args.max_depth,
        tolerance: args.growth,
        // The step the sphere pictures draw keeps its solutions if it was ranked over
        // its full motion space (the picture lists them again otherwise).
        keep_solutions: if args.svg.is_some() || args.png.is_some() {
            KeepSolutions::Step(args.step.saturating_sub(1))
        } else {
            KeepSolutions::Nothing
        },
        ranking: args.ranking.into(),
    };
    let names: Vec<String> = asm.parts.iter().map(|p| p.name.clone()).collect();
    let step_unit = asm.grid.step();
    if mode == Mode::Text && names.len() >= 2 {
        output::line(format_args!(
            "disassembly of \"{}\" ({} parts):",
            asm.name,
            names.len()
        ));
        output::line("");
    }
    let mut printer = Printer {
        mode,
        args,
        names: &names,
        step_unit,
        count: 0,
    };
    let job = SequenceJobOptions {
        plan: opts,
        first: args.first,
        explain: args.explain,
    };
    let mut answer = {
        let (phase, progress) = output::planner(global, "sequence steps");
        let mut on_step = |s: &Step, holds: Option<bool>| phase.suspend(|| printer.step(s, holds));
        sequence(
            &loaded,
            global.units.map(Units::symbol),
            &job,
            &progress,
            &mut on_step,
        )
        .map_err(|e| limits::job_error(e, global))?
    };
    let plan = answer.plan.clone();
    let files = args.svg.is_some()
        || args.png.is_some()
        || args.glb.is_some()
        || args.html.is_some()
        || args.renders.is_some();
    let stop = output::partial(global, plan.stopped, files);
    if stop.is_none() && plan.names.len() >= 2 {
        let _phase = output::phase(global, "pictures and exports");
        pictures(args, asm, &plan)?;
    }
    let mut status = Status::of(plan.stopped);
    output::stamp(&mut status, &stop);
    answer.set_status(status);
    answer.seconds.load = Some(load);
    match mode {
        Mode::Json => output::json(&answer)?,
        Mode::JsonLines => {
            answer.without_steps();
            crate::limits::set_phase("writing the answer");
            json_line(&Event {
                event: "end",
                index: None,
                body: &answer,
            });
        }
        Mode::Text => {
            let load = output::load_time(load, &loaded.seconds);
            print_tail(&plan, args, asm, global, &load, &stop);
            if let Some(t) = tolerance_statement(asm, global) {
                output::line(t);
            }
        }
    }
    let answer = if plan.stuck.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(2)
    };
    Ok(output::exit_code(&stop, answer))
}

/// The pair regions of the parts `sub` (global indices, increasing) alone, in local
/// indices: what the sphere picture of a step of `sub` needs.
fn regions_of(asm: &apart::assembly::Assembly, sub: &[usize]) -> anyhow::Result<BlockingRegions> {
    let parts = parts_of(asm)?;
    let own: Vec<Part> = sub.iter().map(|&k| parts[k].clone()).collect();
    Ok(BlockingRegions::compute_with(&own, &Progress::new())?)
}

/// `step` in the local indices of its subassembly (`regions`, made by [`regions_of`]),
/// with every solution of that motion space: its own when it kept them (a step ranked
/// over the full motion space), else [`partition_subset`]'s.
fn local_step(step: &Step, regions: &BlockingRegions) -> Step {
    let sub = &step.subassembly;
    let local = |s: &[usize]| -> Vec<usize> {
        s.iter()
            .map(|k| {
                sub.binary_search(k)
                    .expect("a part of the step's subassembly")
            })
            .collect()
    };
    let all: Vec<usize> = (0..sub.len()).collect();
    let solutions: Vec<Solution> = match &step.solutions {
        Some(sols) => sols
            .iter()
            .map(|s| Solution {
                moving: local(&s.moving),
                ..s.clone()
            })
            .collect(),
        None => {
            partition_subset(regions, &all, &Options::default())
                .0
                .solutions
        }
    };
    let mut choice = step.choice.clone();
    if let Some(r) = choice.runner_up.as_mut() {
        r.moving = local(&r.moving);
    }
    Step {
        subassembly: all,
        moving: local(&step.moving),
        solutions: Some(solutions),
        choice,
        ..step.clone()
    }
}

/// The command named in the marker of a `--renders` folder.
const RENDERS: &str = "apart sequence --renders";

/// Refuses, before any work, a file or folder to write that would overwrite an input.
fn check_outputs(args: &SequenceArgs, inputs: &output::Inputs) -> anyhow::Result<()> {
    for (flag, p) in [
        ("--svg", &args.svg),
        ("--png", &args.png),
        ("--glb", &args.glb),
        ("--html", &args.html),
    ] {
        if let Some(p) = p {
            inputs.check_file(flag, p)?;
        }
    }
    if let Some(dir) = &args.renders {
        inputs.check_folder("--renders", dir)?;
        output::NewFolder::check(dir, RENDERS)?;
    }
    Ok(())
}

/// The files asked for. The sphere pictures (not with --first, which clap keeps apart
/// from --svg and --png) are drawn from the pair regions of the pictured subassembly
/// alone.
fn pictures(
    args: &SequenceArgs,
    asm: &apart::assembly::Assembly,
    plan: &Sequence,
) -> anyhow::Result<()> {
    if args.svg.is_some() || args.png.is_some() {
        let base = SphereSvgOptions {
            projection: args.projection.into(),
            ..Default::default()
        };
        match (
            plan.steps.get(args.step.wrapping_sub(1)),
            plan.stuck.first(),
        ) {
            (Some(step), _) => {
                let regions = regions_of(asm, &step.subassembly)?;
                let step = local_step(step, &regions);
                let names = regions.names();
                // One motion space for both pictures, cut at the equator (the planner's is not).
                let ms = MotionSpace::build_split_at_equator(&regions, &step.subassembly);
                if let Some(p) = &args.svg {
                    output::write_file(p, step_motion_space_svg(&ms, names, &step, &base))?;
                }
                if let Some(p) = &args.png {
                    output::write_file(p, step_motion_space_png(&ms, names, &step, &base))?;
                }
            }
            // No step at all: the whole assembly is interlocked. Its motion space, blocked
            // everywhere, is the picture of that answer.
            (None, Some(stuck)) if plan.steps.is_empty() && args.step == 1 => {
                let regions = regions_of(asm, stuck)?;
                let names = regions.names();
                let all: Vec<usize> = (0..stuck.len()).collect();
                let ms = MotionSpace::build_split_at_equator(&regions, &all);
                let opts = SphereSvgOptions {
                    title: format!(
                        "{}: interlocked, no subset of {{{}}} can move",
                        asm.name,
                        names.join(", ")
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
        // Put in place whole: no folder of some of the steps.
        let mut out = output::NewFolder::create(dir, RENDERS)?;
        let view = View::default();
        let png = assembly_png(asm, &[], &view, 1000, 750);
        out.write(Path::new("assembly.png"), true, |w| w.write_all(&png))?;
        for (k, png) in step_pngs(asm, plan, &view, 1000, 750).iter().enumerate() {
            let name = format!("step-{}.png", k + 1);
            out.write(Path::new(&name), true, |w| w.write_all(png))?;
        }
        out.commit()?;
    }
    Ok(())
}

fn names_of(all: &[String], set: &[usize]) -> Vec<String> {
    set.iter().map(|&k| all[k].clone()).collect()
}

fn describe(names: &[String], s: &Step, step_unit: f64) -> String {
    let d = s.direction.to_strings();
    let kind = match s.cell.name() {
        "face" => format!("face, clearance {:.2}°", s.clearance_deg),
        "edge" => "edge, sliding".to_string(),
        _ => "isolated direction".to_string(),
    };
    let tol = match s.tolerance.map(|t| match t {
        Growth::Finite(x) => Some(x * step_unit),
        Growth::Unbounded => None,
    }) {
        Some(Some(x)) => format!("; tolerates growth up to {x:.6}"),
        Some(None) => "; any growth".to_string(),
        None => String::new(),
    };
    format!(
        "{} {} along ({}, {}, {}) ≈ {} ({kind}{tol})",
        list(names, &s.moving),
        if s.moving.len() == 1 { "moves" } else { "move" },
        d[0],
        d[1],
        d[2],
        output::unit(&s.unit)
    )
}

/// The rule that chose a step, in words (--explain).
fn rule_text(r: Rule) -> &'static str {
    match r {
        Rule::Ranked => "ranked over the subassembly's full motion space",
        Rule::Single => {
            "a single part, from its own free directions (the widest-clearance face first)"
        }
        Rule::Pair => {
            "two touching parts together, from their own free directions (no single part leaves along a face)"
        }
        Rule::Likely => {
            "a set of parts along a likely direction (an axis, a cylinder's axis, a contact normal): the first that frees one"
        }
        Rule::Full => {
            "the full motion space, after no single part, touching pair or likely direction split the subassembly"
        }
    }
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
fn explain(names: &[String], s: &Step) -> String {
    let c = &s.choice;
    let mut out = format!("why: {}", keys_text(&c.keys));
    if s.rule == Rule::Likely {
        out.push_str(&format!(
            "; the first likely direction that frees a set ({} tried)",
            c.candidates
        ));
        return out;
    }
    match &c.runner_up {
        None => out.push_str("; the only candidate"),
        Some(r) => {
            let d = r.direction.to_strings();
            let others = c.candidates - 1;
            out.push_str(&format!(
                "; preferred over {others} other candidate{}: the runner-up, {{{}}} along ({}, {}, {}) ({}), lost on {}",
                if others == 1 { "" } else { "s" },
                list(names, &r.moving),
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

/// What text prints after the steps (printed as they were found): the subassemblies
/// left interlocked, whole or not yet split, the assembly sequence, the summary line
/// with the count and the status, and the times.
fn print_tail(
    plan: &Sequence,
    args: &SequenceArgs,
    asm: &apart::assembly::Assembly,
    global: &Global,
    load: &str,
    stop: &Option<Stopped>,
) {
    let names = &plan.names;
    if names.len() < 2 {
        output::line(format_args!(
            "disassembly of \"{}\" ({} part): nothing to separate",
            asm.name,
            names.len()
        ));
        return;
    }
    let status = if let Some(t) = stop {
        t.to_string()
    } else if plan.complete() {
        "complete".to_string()
    } else if !plan.stuck.is_empty() {
        "incomplete: interlocked subassembly".to_string()
    } else {
        "stopped at the depth limit".to_string()
    };
    for s in &plan.stuck {
        output::line(format_args!(
            "interlocked: {{{}}} cannot be split by one translation",
            list(names, s)
        ));
    }
    for s in &plan.unsplit {
        output::line(format_args!(
            "left whole (depth limit): {{{}}}",
            list(names, s)
        ));
    }
    for s in &plan.pending {
        output::line(format_args!(
            "not yet split ({}): {{{}}}",
            stop.as_ref().map_or("stopped", Stopped::short),
            list(names, s)
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
                list(names, &s.moving),
                list(names, &rest),
                d[0],
                d[1],
                d[2]
            ));
        }
    }
    output::line("");
    output::line(format_args!(
        "{} step{}, {status}",
        plan.steps.len(),
        if plan.steps.len() == 1 { "" } else { "s" }
    ));
    if args.first {
        output::line(format_args!(
            "--first: each step along the first likely direction that frees a subset, not ranked by clearance; {} subassembl{} searched in full",
            plan.full_searches,
            if plan.full_searches == 1 { "y" } else { "ies" }
        ));
    }
    if !global.quiet {
        let regions = match &plan.regions {
            Some((n, _)) => format!(
                "pair regions {:.1} ms ({n} made)",
                region_seconds(plan) * 1e3
            ),
            None => "pair regions 0.0 ms".to_string(),
        };
        output::line(format_args!(
            "time: {load}, {regions}, steps {:.1} ms",
            plan.step_seconds * 1e3
        ));
    }
}
