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
use crate::input_facts::{holds_without_tolerance, tolerance_statement, InputFacts};
use crate::limits::Stopped;
use crate::output;
use crate::{limits, Global};
use apart::draw::{
    assembly_png, disassembly_glb, disassembly_html, motion_space_png, motion_space_svg,
    step_motion_space_png, step_motion_space_svg, step_pngs, SphereSvgOptions, View,
};
use apart::plan::sequence::{Choice, Keys, LocalStats};
use apart::plan::{
    partition_subset, parts_of, sequence_first_with, sequence_parts, BlockingRegions, CellKind,
    KeepSolutions, MotionSpace, Options, Part, Progress, Ranking, Rule, Sequence, SequenceOptions,
    Solution, Step, Tolerance,
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

impl RankingArg {
    fn key(self) -> &'static str {
        match self {
            RankingArg::Auto => "auto",
            RankingArg::Full => "full",
            RankingArg::Local => "local",
        }
    }
}

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

#[derive(Serialize)]
struct StepJson {
    subassembly: Vec<String>,
    moving: Vec<String>,
    direction: [f64; 3],
    exact_direction: [String; 3],
    cell: &'static str,
    clearance_deg: f64,
    depth: usize,
    /// The rule that chose the step: "ranked" (over the subassembly's full motion
    /// space), "single" (a single part from its own free directions), "likely" (a set
    /// along a likely direction), "full" (the full motion space after nothing simpler
    /// split the subassembly).
    rule: &'static str,
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

/// The planner's work (not with --first).
#[derive(Serialize)]
struct WorkJson {
    /// Parts whose free directions alone were computed (recomputations included).
    singles: usize,
    /// Pairs of touching parts whose free directions together were computed.
    pairs: usize,
    /// Likely directions tested over a whole subassembly.
    likely_directions: usize,
    /// Steps by rule.
    single_steps: usize,
    pair_steps: usize,
    likely_steps: usize,
    ranked_steps: usize,
    /// Subassemblies searched over their full motion space because no single part and
    /// no likely direction split them.
    full_searches: usize,
}

impl From<&LocalStats> for WorkJson {
    fn from(s: &LocalStats) -> WorkJson {
        WorkJson {
            singles: s.singles,
            pairs: s.pairs,
            likely_directions: s.likely_directions,
            single_steps: s.single_steps,
            pair_steps: s.pair_steps,
            likely_steps: s.likely_steps,
            ranked_steps: s.ranked,
            full_searches: s.full_searches,
        }
    }
}

/// Every step of a plan as JSON, each made as it is written (a plan of thousands of
/// steps is never held as JSON values at once).
struct StepsJson<'a> {
    plan: &'a Sequence,
    args: &'a SequenceArgs,
    step_unit: f64,
    holds: &'a Option<Vec<bool>>,
}

impl Serialize for StepsJson<'_> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeSeq;
        let steps = &self.plan.steps;
        let mut seq = serializer.serialize_seq(Some(steps.len()))?;
        for (k, s) in steps.iter().enumerate() {
            let holds = self.holds.as_ref().map(|h| h[k]);
            seq.serialize_element(&step_json(
                &self.plan.names,
                s,
                self.args,
                self.step_unit,
                holds,
            ))?;
        }
        seq.end()
    }
}

#[derive(Serialize)]
struct SequenceJson<'a> {
    /// "done", or "timeout", "out of memory", "interrupted": --timeout, the memory
    /// budget or Ctrl-C stopped the run; `steps` are the steps found until then and
    /// `not_yet_split` the subassemblies still to split.
    status: &'static str,
    /// What stopped the run, and where; absent when it ran to its end.
    #[serde(skip_serializing_if = "Option::is_none")]
    stopped: Option<output::StoppedJson>,
    interlocked: bool,
    complete: bool,
    /// The assembly has one part: there is nothing to separate (complete, no step).
    nothing_to_separate: bool,
    parts: Vec<String>,
    /// Every step (absent from the "end" line of --jsonl, whose step lines came before).
    #[serde(skip_serializing_if = "Option::is_none")]
    steps: Option<StepsJson<'a>>,
    /// The number of steps (in the "end" line of --jsonl only).
    #[serde(skip_serializing_if = "Option::is_none")]
    step_count: Option<usize>,
    /// Subassemblies no single translation can split.
    stuck: Vec<Vec<String>>,
    /// Subassemblies left whole by --max-depth.
    unsplit: Vec<Vec<String>>,
    /// Subassemblies not yet split when the run was stopped (empty otherwise), in the
    /// order they would have been split.
    not_yet_split: Vec<Vec<String>>,
    /// With --first: subassemblies that no likely direction split, searched in full
    /// (their own pair regions); null without --first (see `work`).
    full_searches: Option<usize>,
    /// How steps were chosen (--ranking); null with --first.
    ranking: Option<&'static str>,
    /// Pair regions made (lazily, as steps needed them); null with --first.
    pair_regions: Option<usize>,
    /// The planner's work; null with --first.
    work: Option<WorkJson>,
    seconds: SecondsJson,
    #[serde(flatten)]
    input: InputFacts,
}

#[derive(Serialize)]
struct SecondsJson {
    load: f64,
    /// Making the pair regions (their sums, projections and unions), a part of `steps`.
    regions: f64,
    steps: f64,
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

/// Prints each step as the planner finds it, and keeps what the answer needs of it.
struct Printer<'a> {
    mode: Mode,
    args: &'a SequenceArgs,
    asm: &'a apart::assembly::Assembly,
    names: &'a [String],
    step_unit: f64,
    /// Per step found: whether it holds without the tolerance (`None`: no tolerance).
    holds: Vec<Option<bool>>,
    /// The first error met while checking a step without the tolerance.
    error: Option<anyhow::Error>,
}

impl Printer<'_> {
    fn step(&mut self, s: &Step) {
        let k = self.holds.len();
        let motion = [(
            s.moving.as_slice(),
            Some(s.subassembly.as_slice()),
            &s.direction,
        )];
        let holds = match holds_without_tolerance(self.asm, &motion) {
            Ok(h) => h.map(|h| h[0]),
            Err(e) => {
                self.error.get_or_insert(e);
                None
            }
        };
        self.holds.push(holds);
        match self.mode {
            Mode::Json => {}
            Mode::JsonLines => json_line(&Event {
                event: "step",
                index: Some(k + 1),
                body: &step_json(self.names, s, self.args, self.step_unit, holds),
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
        asm,
        names: &names,
        step_unit,
        holds: Vec::new(),
        error: None,
    };
    let plan = if names.len() < 2 {
        Sequence::empty(names.clone())
    } else {
        let parts = parts_of(asm)?;
        let (phase, progress) = output::planner(global, "sequence steps");
        let mut on_step = |s: &Step| phase.suspend(|| printer.step(s));
        if args.first {
            sequence_first_with(parts, &opts, &progress, &mut on_step)?
        } else {
            sequence_parts(parts, &opts, &progress, &mut on_step)?
        }
    };
    if let Some(e) = printer.error.take() {
        return Err(e);
    }
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
    let holds: Option<Vec<bool>> = printer.holds.iter().copied().collect();
    match mode {
        Mode::Json | Mode::JsonLines => {
            let input = InputFacts::of(&loaded, global);
            let mut answer = to_json(&plan, args, step_unit, load, input, &holds, &stop);
            if mode == Mode::Json {
                output::json(&answer)?;
            } else {
                answer.step_count = answer.steps.take().map(|s| s.plan.steps.len());
                crate::limits::set_phase("writing the answer");
                json_line(&Event {
                    event: "end",
                    index: None,
                    body: &answer,
                });
            }
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

fn choice_json(names: &[String], c: &Choice) -> ChoiceJson {
    ChoiceJson {
        candidates: c.candidates,
        keys: keys_json(&c.keys),
        runner_up: c.runner_up.as_ref().map(|r| RivalJson {
            moving: names_of(names, &r.moving),
            exact_direction: r.direction.to_strings(),
            keys: keys_json(&r.keys),
            lost_on: r.lost_on.key(),
        }),
    }
}

fn step_json(
    names: &[String],
    s: &Step,
    args: &SequenceArgs,
    step_unit: f64,
    holds: Option<bool>,
) -> StepJson {
    StepJson {
        holds_without_tolerance: holds,
        subassembly: names_of(names, &s.subassembly),
        moving: names_of(names, &s.moving),
        direction: s.unit,
        exact_direction: s.direction.to_strings(),
        cell: s.cell.name(),
        clearance_deg: s.clearance_deg,
        depth: s.depth,
        rule: s.rule.key(),
        growth: tolerance_units(&s.tolerance, step_unit),
        choice: args.explain.then(|| choice_json(names, &s.choice)),
    }
}

/// The seconds spent making pair regions (their sums, projections and unions).
fn region_seconds(plan: &Sequence) -> f64 {
    plan.regions.as_ref().map_or(0.0, |(_, s)| {
        s.sums_seconds + s.projection_seconds + s.unions_seconds
    })
}

fn to_json<'a>(
    plan: &'a Sequence,
    args: &'a SequenceArgs,
    step_unit: f64,
    load: f64,
    input: InputFacts,
    holds: &'a Option<Vec<bool>>,
    stop: &Option<Stopped>,
) -> SequenceJson<'a> {
    let names = &plan.names;
    let sets =
        |s: &[Vec<usize>]| -> Vec<Vec<String>> { s.iter().map(|s| names_of(names, s)).collect() };
    SequenceJson {
        input,
        status: output::status(stop),
        stopped: output::stopped_json(stop),
        not_yet_split: sets(&plan.pending),
        interlocked: !plan.stuck.is_empty(),
        complete: plan.complete(),
        nothing_to_separate: plan.names.len() < 2,
        parts: plan.names.clone(),
        steps: Some(StepsJson {
            plan,
            args,
            step_unit,
            holds,
        }),
        step_count: None,
        stuck: sets(&plan.stuck),
        unsplit: sets(&plan.unsplit),
        full_searches: args.first.then_some(plan.full_searches),
        ranking: (!args.first).then(|| args.ranking.key()),
        pair_regions: if args.first {
            None
        } else {
            Some(plan.regions.as_ref().map_or(0, |(n, _)| *n))
        },
        work: (!args.first).then(|| WorkJson::from(&plan.local)),
        seconds: SecondsJson {
            load,
            regions: region_seconds(plan),
            steps: plan.step_seconds,
        },
    }
}

fn describe(names: &[String], s: &Step, step_unit: f64) -> String {
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
