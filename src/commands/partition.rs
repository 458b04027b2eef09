//! `apart partition <assembly>`: every direction and minimal subset that separates the
//! assembly by one infinite translation; or, with `--direction`, the blocking graph of
//! one direction. Exit code 0 when some subset can move (or the assembly has one part:
//! nothing to separate), 2 when the assembly is interlocked, 3 when `--timeout` stopped
//! the run and the solutions found until then are printed (130 after Ctrl-C, 1 after
//! the memory budget, with the same partial answer), 1 on error. The listing is
//! grouped by moving set and bounded (`--limit`, `--all`): assemblies of many loose
//! parts have millions of solutions.

use crate::commands::load::load_valid;
use crate::input_facts::{holds_without_tolerance, tolerance_statement, InputFacts, Motion};
use crate::limits::Stopped;
use crate::output;
use crate::{limits, Global};
use anyhow::Context;
use apart::assembly::Loaded;
use apart::draw::{motion_space_png, motion_space_svg, SphereProjection, SphereSvgOptions};
use apart::kernel::{Grid, Vec3};
use apart::plan::{
    dbg_along, partition_first, partition_subset_with, parts_of, BlockingRegions, CellKind,
    MotionSpace, Options, Partitioning, PlanError,
};
use serde::Serialize;
use std::collections::HashMap;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Moving sets listed by default (text and JSON).
pub const DEFAULT_LIMIT: usize = 20;
/// Solutions of each kind (face, edge, vertex) listed per moving set, unless `--all`.
pub const EXAMPLES_PER_KIND: usize = 5;
/// A count of solutions worth a warning even when all of them are asked for.
const LARGE: usize = 10_000;

/// Arguments of `apart partition`.
#[derive(clap::Args, Debug)]
pub struct PartitionArgs {
    /// A folder of mesh files, one mesh file, or an assembly.json manifest.
    pub assembly: PathBuf,
    /// Stop at the first solution found (faces, then edges, then vertices): decides
    /// quickly whether the assembly comes apart.
    #[arg(long)]
    pub first: bool,
    /// Evaluate one direction exactly instead ("X,Y,Z", snapped like coordinates): its
    /// blocking graph, the kind of cell it lies in, and the minimal subsets that move.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = limits::direction)]
    pub direction: Option<String>,
    /// Draw the motion-space sphere (both hemispheres, blocked regions shaded by how
    /// many pairs block them, solutions marked) as SVG.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
    /// The same picture as PNG.
    #[arg(long, value_name = "FILE")]
    pub png: Option<PathBuf>,
    /// Projection of the sphere pictures.
    #[arg(long, value_enum, default_value_t = Projection::EqualArea)]
    pub projection: Projection,
    /// List at most N moving sets (default 20), each with at most 5 solutions of each
    /// kind (face, edge, vertex), in the text and the JSON; the counts always cover every
    /// solution. N is 1 or more.
    #[arg(long, value_name = "N", value_parser = limits::limit, conflicts_with = "all", allow_negative_numbers = true)]
    pub limit: Option<usize>,
    /// List every moving set and every solution, in the text and the JSON (assemblies of
    /// many loose parts have millions).
    #[arg(long)]
    pub all: bool,
}

/// Sphere projections.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum Projection {
    /// Lambert azimuthal equal-area.
    EqualArea,
    /// Orthographic (as seen from far away).
    Orthographic,
}

impl From<Projection> for SphereProjection {
    fn from(p: Projection) -> SphereProjection {
        match p {
            Projection::EqualArea => SphereProjection::EqualArea,
            Projection::Orthographic => SphereProjection::Orthographic,
        }
    }
}

#[derive(Serialize)]
struct SolutionJson<'a> {
    cell: &'static str,
    direction: [f64; 3],
    exact_direction: [String; 3],
    moving: Vec<&'a str>,
    clearance_deg: f64,
    /// Under a tolerance: the motion also holds for the parts as given.
    #[serde(skip_serializing_if = "Option::is_none")]
    holds_without_tolerance: Option<bool>,
}

#[derive(Serialize)]
struct Seconds {
    load: f64,
    /// The load's stages (see [`apart::assembly::LoadSeconds`]).
    load_stages: LoadStages,
    sums: f64,
    projection: f64,
    unions: f64,
    overlay: f64,
    graphs: f64,
}

#[derive(Serialize)]
struct LoadStages {
    read: f64,
    validate: f64,
    decompose: f64,
    snapping: f64,
    overlaps: f64,
}

impl LoadStages {
    fn of(s: &apart::assembly::LoadSeconds) -> LoadStages {
        LoadStages {
            read: s.read,
            validate: s.validate,
            decompose: s.decompose,
            snapping: s.snapping,
            overlaps: s.overlaps,
        }
    }
}

#[derive(Serialize)]
struct StatsJson {
    pieces: usize,
    sums: usize,
    arcs: usize,
    vertices: usize,
    edges: usize,
    faces: usize,
    seconds: Seconds,
}

/// One moving set and how many solutions move it.
#[derive(Serialize)]
struct GroupJson<'a> {
    moving: Vec<&'a str>,
    /// Solutions moving this set (faces + edges + vertices).
    solutions: usize,
    faces: usize,
    edges: usize,
    vertices: usize,
    /// The largest clearance of its face solutions; null without a face solution.
    best_clearance_deg: Option<f64>,
    /// How many of its solutions `solutions` lists.
    listed: usize,
}

#[derive(Serialize)]
struct PartitionJson<'a> {
    #[serde(flatten)]
    input: InputFacts,
    /// "done", or "timeout", "out of memory", "interrupted": --timeout, the memory
    /// budget or Ctrl-C stopped the run and the solutions are those found until then.
    status: &'static str,
    /// Every solution was searched for (false after a stop).
    complete: bool,
    /// What stopped the run, and where; absent when it ran to its end.
    #[serde(skip_serializing_if = "Option::is_none")]
    stopped: Option<output::StoppedJson>,
    /// No subset can move (false when the search was stopped: unknown).
    interlocked: bool,
    /// The assembly has one part: there is nothing to separate (exit code 0).
    nothing_to_separate: bool,
    parts: &'a [String],
    /// Every solution found (not only those listed).
    solution_count: usize,
    /// Distinct moving sets among them.
    moving_set_count: usize,
    /// Moving sets listed at most (null with --all).
    limit: Option<usize>,
    /// Some solutions are counted but not listed (--limit, --all).
    truncated: bool,
    /// The listed moving sets, in the order of their best solution.
    groups: Vec<GroupJson<'a>>,
    /// The listed solutions: faces by decreasing clearance, then edges, then vertices.
    solutions: Listed<'a>,
    stats: StatsJson,
}

#[derive(Serialize)]
struct DirectionJson {
    #[serde(flatten)]
    input: InputFacts,
    direction: [f64; 3],
    exact_direction: [String; 3],
    cell: &'static str,
    blocks: Vec<[String; 2]>,
    moving: Vec<Vec<String>>,
    /// Under a tolerance: for each moving set, the motion also holds for the parts as
    /// given.
    #[serde(skip_serializing_if = "Option::is_none")]
    holds_without_tolerance: Option<Vec<bool>>,
}

/// Runs the command.
pub fn run(args: &PartitionArgs, global: &Global) -> anyhow::Result<ExitCode> {
    let t = Instant::now();
    let loaded = load_valid(&args.assembly, global)?;
    let load_seconds = t.elapsed().as_secs_f64();
    let inputs = output::Inputs::of(&args.assembly, &loaded);
    for (flag, p) in [("--svg", &args.svg), ("--png", &args.png)] {
        if let Some(p) = p {
            inputs.check_file(flag, p)?;
        }
    }
    let asm = &loaded.assembly;
    let parts = parts_of(asm)?;
    if parts.len() < 2 {
        return nothing_to_separate(&loaded, global, load_seconds);
    }
    if let Some(d) = &args.direction {
        // One direction: per-piece-pair tests only, no motion-space arrangement.
        return direction(global, &loaded, parts, d, load_seconds);
    }
    let pictures = args.svg.is_some() || args.png.is_some();
    if args.first && !pictures {
        // Likely directions first; the full computation only when none separates.
        let p = {
            let _phase = output::phase(global, "first solution");
            partition_first(parts)?
        };
        report(&p, &loaded, args, global, load_seconds, &None)?;
        return Ok(if p.interlocked {
            ExitCode::from(2)
        } else {
            ExitCode::SUCCESS
        });
    }
    let regions = {
        let (_phase, progress) = output::planner(global, "pair regions");
        match BlockingRegions::compute_with(parts, &progress) {
            Ok(r) => Some(r),
            Err(PlanError::Stopped { .. }) => None,
            Err(e) => return Err(e.into()),
        }
    };
    let all: Vec<usize> = (0..parts.len()).collect();
    let (p, regions) = match regions {
        // Stopped while the pair regions were computed: no solution yet.
        None => {
            let names = parts.iter().map(|p| p.name.clone()).collect();
            let pieces = parts.iter().map(|p| p.pieces.len()).sum();
            (Partitioning::stopped_before_solutions(names, pieces), None)
        }
        Some(regions) => {
            limits::check_motion_space(&regions, &all, global)?;
            let (_phase, progress) = output::planner(global, "motion space and solutions");
            let opts = Options {
                first: args.first,
                ..Default::default()
            };
            // (Its motion space is dropped here: the picture needs one cut at the equator.)
            let (p, _) = partition_subset_with(&regions, &all, &opts, &progress);
            (p, Some(regions))
        }
    };
    let stop = output::partial(global, p.stopped, pictures);
    if let Some(regions) = regions.filter(|_| pictures && stop.is_none()) {
        let _phase = output::phase(global, "pictures");
        let opts = SphereSvgOptions {
            title: format!("{}: motion space", asm.name),
            projection: args.projection.into(),
            ..Default::default()
        };
        // One motion space for both pictures, with the solutions planned above.
        let ms = MotionSpace::build_split_at_equator(&regions, &all);
        let names = regions.names();
        if let Some(path) = &args.svg {
            output::write_file(path, motion_space_svg(&ms, names, &p.solutions, &opts))?;
        }
        if let Some(path) = &args.png {
            output::write_file(path, motion_space_png(&ms, names, &p.solutions, &opts))?;
        }
    }
    report(&p, &loaded, args, global, load_seconds, &stop)?;
    let answer = if p.interlocked {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    };
    Ok(output::exit_code(&stop, answer))
}

/// The answer for an assembly of one part: nothing to separate, which is not "no"
/// (exit code 0), the same meaning in partition, sequence and separate.
fn nothing_to_separate(loaded: &Loaded, global: &Global, load: f64) -> anyhow::Result<ExitCode> {
    let asm = &loaded.assembly;
    let names: Vec<String> = asm.parts.iter().map(|p| p.name.clone()).collect();
    if global.json {
        let p = Partitioning::nothing_to_separate(names.clone());
        let list = listing(&p, Some(DEFAULT_LIMIT));
        let mut json = to_json(
            &p,
            &list,
            (load, &loaded.seconds),
            InputFacts::of(loaded, global),
            &None,
            &None,
        );
        json.nothing_to_separate = true;
        output::json(&json)?;
    } else {
        output::line(format_args!(
            "assembly \"{}\" has {} part{}: nothing to separate",
            asm.name,
            names.len(),
            if names.len() == 1 { "" } else { "s" }
        ));
    }
    Ok(ExitCode::SUCCESS)
}

/// The solutions grouped by moving set, and which of them are listed.
struct Listing {
    /// Every moving set, in the order of its first (best) solution.
    groups: Vec<Group>,
    /// How many groups are listed.
    listed_groups: usize,
    /// Indices of the listed solutions, in the planner's order.
    kept: Vec<usize>,
    /// The moving sets listed at most (`None`: all).
    limit: Option<usize>,
}

struct Group {
    /// The group's first solution (its moving set, and its best).
    first: usize,
    /// Solutions per kind: face, edge, vertex.
    counts: [usize; 3],
    best_clearance: Option<f64>,
    /// Positions in `Listing::kept` of the group's listed solutions.
    kept: Vec<usize>,
}

impl Listing {
    fn truncated(&self, total: usize) -> bool {
        self.kept.len() < total
    }
}

fn kind_index(c: CellKind) -> usize {
    match c {
        CellKind::Face => 0,
        CellKind::Edge => 1,
        CellKind::Vertex => 2,
    }
}

/// Groups the solutions by moving set (one pass, a hash of the sets): with `limit`,
/// the first `limit` groups are listed with at most [`EXAMPLES_PER_KIND`] solutions of
/// each kind; without, everything.
fn listing(p: &Partitioning, limit: Option<usize>) -> Listing {
    let mut index: HashMap<&[usize], usize> = HashMap::new();
    let mut groups: Vec<Group> = Vec::new();
    let mut kept = Vec::new();
    for (k, s) in p.solutions.iter().enumerate() {
        let g = *index.entry(s.moving.as_slice()).or_insert_with(|| {
            groups.push(Group {
                first: k,
                counts: [0; 3],
                best_clearance: None,
                kept: Vec::new(),
            });
            groups.len() - 1
        });
        let group = &mut groups[g];
        let kind = kind_index(s.cell);
        let listed = match limit {
            None => true,
            Some(n) => g < n && group.counts[kind] < EXAMPLES_PER_KIND,
        };
        if listed {
            group.kept.push(kept.len());
            kept.push(k);
        }
        group.counts[kind] += 1;
        if s.cell == CellKind::Face {
            let c = group.best_clearance.get_or_insert(s.clearance_deg);
            *c = c.max(s.clearance_deg);
        }
    }
    // The planner counts every solution, listed or not (it keeps only a few per set
    // unless --all).
    let tally: HashMap<&[usize], [usize; 3]> = p
        .sets
        .iter()
        .map(|s| (s.moving.as_slice(), s.counts))
        .collect();
    for g in &mut groups {
        if let Some(c) = tally.get(p.solutions[g.first].moving.as_slice()) {
            g.counts = *c;
        }
    }
    Listing {
        listed_groups: limit.map_or(groups.len(), |n| n.min(groups.len())),
        groups,
        kept,
        limit,
    }
}

/// Prints the solutions (JSON or text), with the tolerance they hold under and, under a
/// tolerance, which of the listed ones also hold for the parts as given.
fn report(
    p: &Partitioning,
    loaded: &Loaded,
    args: &PartitionArgs,
    global: &Global,
    load: f64,
    stop: &Option<Stopped>,
) -> anyhow::Result<()> {
    let asm = &loaded.assembly;
    let limit = if args.all {
        None
    } else {
        Some(args.limit.unwrap_or(DEFAULT_LIMIT))
    };
    let list = listing(p, limit);
    warn_size(p, &list, global);
    let holds = {
        let _phase = output::phase(
            global,
            "checking the listed solutions without the tolerance",
        );
        let motions: Vec<Motion> = list
            .kept
            .iter()
            .map(|&k| {
                let s = &p.solutions[k];
                (s.moving.as_slice(), None, &s.direction)
            })
            .collect();
        holds_without_tolerance(asm, &motions)?
    };
    if global.json {
        output::json(&to_json(
            p,
            &list,
            (load, &loaded.seconds),
            InputFacts::of(loaded, global),
            &holds,
            stop,
        ))?;
    } else {
        print_text(
            p,
            &list,
            asm,
            args,
            global,
            output::load_time(load, &loaded.seconds),
            &holds,
            stop,
        );
        if let Some(t) = tolerance_statement(asm, global) {
            output::line(t);
        }
    }
    Ok(())
}

/// A warning on standard error when the listing leaves out moving sets, when the JSON
/// leaves out solutions, or when the count is large.
fn warn_size(p: &Partitioning, list: &Listing, global: &Global) {
    let total = p.solution_count();
    let sets = list.groups.len();
    let counts = format!(
        "{total} solution{} in {sets} moving set{}",
        if total == 1 { "" } else { "s" },
        if sets == 1 { "" } else { "s" }
    );
    match list.limit {
        None if total > LARGE => output::eline(format_args!(
            "warning: {counts}: listing all of them (--all)"
        )),
        Some(n) if list.truncated(total)
            && (sets > n || global.json || total > LARGE) =>
        {
            output::eline(format_args!(
                "warning: {counts}; listing {} moving set{} with at most {EXAMPLES_PER_KIND} solutions of each kind (--limit N for more moving sets, --all for every solution)",
                list.listed_groups,
                if list.listed_groups == 1 { "" } else { "s" }
            ))
        }
        _ => {}
    }
}

fn names_of(names: &[String], set: &[usize]) -> Vec<String> {
    set.iter().map(|&k| names[k].clone()).collect()
}

fn name_refs<'a>(names: &'a [String], set: &[usize]) -> Vec<&'a str> {
    set.iter().map(|&k| names[k].as_str()).collect()
}

/// The listed solutions, serialized one at a time (never all built in memory).
struct Listed<'a> {
    p: &'a Partitioning,
    kept: &'a [usize],
    holds: &'a Option<Vec<bool>>,
}

impl Serialize for Listed<'_> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.kept.iter().enumerate().map(|(i, &k)| {
            let s = &self.p.solutions[k];
            SolutionJson {
                cell: s.cell.name(),
                direction: s.unit,
                exact_direction: s.direction.to_strings(),
                moving: name_refs(&self.p.names, &s.moving),
                clearance_deg: s.clearance_deg,
                holds_without_tolerance: self.holds.as_ref().map(|h| h[i]),
            }
        }))
    }
}

fn to_json<'a>(
    p: &'a Partitioning,
    list: &'a Listing,
    (load, stages): (f64, &apart::assembly::LoadSeconds),
    input: InputFacts,
    holds: &'a Option<Vec<bool>>,
    stop: &Option<Stopped>,
) -> PartitionJson<'a> {
    let s = &p.stats;
    PartitionJson {
        input,
        status: output::status(stop),
        complete: stop.is_none(),
        stopped: output::stopped_json(stop),
        interlocked: p.interlocked,
        nothing_to_separate: false,
        parts: &p.names,
        solution_count: p.solution_count(),
        moving_set_count: list.groups.len(),
        limit: list.limit,
        truncated: list.truncated(p.solution_count()),
        groups: list.groups[..list.listed_groups]
            .iter()
            .map(|g| GroupJson {
                moving: name_refs(&p.names, &p.solutions[g.first].moving),
                solutions: g.counts.iter().sum(),
                faces: g.counts[0],
                edges: g.counts[1],
                vertices: g.counts[2],
                best_clearance_deg: g.best_clearance,
                listed: g.kept.len(),
            })
            .collect(),
        solutions: Listed {
            p,
            kept: &list.kept,
            holds,
        },
        stats: StatsJson {
            pieces: s.pieces,
            sums: s.sums,
            arcs: s.arcs,
            vertices: s.vertices,
            edges: s.edges,
            faces: s.faces,
            seconds: Seconds {
                load,
                load_stages: LoadStages::of(stages),
                sums: s.seconds.sums,
                projection: s.seconds.projection,
                unions: s.seconds.unions,
                overlay: s.seconds.overlay,
                graphs: s.seconds.graphs,
            },
        },
    }
}

fn plural(k: usize, one: &str, many: &str) -> String {
    format!("{k} {}", if k == 1 { one } else { many })
}

#[allow(clippy::too_many_arguments)]
fn print_text(
    p: &Partitioning,
    list: &Listing,
    asm: &apart::assembly::Assembly,
    args: &PartitionArgs,
    global: &Global,
    load: String,
    holds: &Option<Vec<bool>>,
    stop: &Option<Stopped>,
) {
    let s = &p.stats;
    if !global.quiet {
        output::line(format_args!(
            "assembly \"{}\": {}, {}, {}",
            asm.name,
            plural(p.names.len(), "part", "parts"),
            plural(s.pieces, "convex piece", "convex pieces"),
            plural(s.sums, "Minkowski sum", "Minkowski sums")
        ));
        output::line(format_args!(
            "motion space: {}, {}, {} ({})",
            plural(s.vertices, "vertex", "vertices"),
            plural(s.edges, "edge", "edges"),
            plural(s.faces, "face", "faces"),
            plural(s.arcs, "arc", "arcs")
        ));
    }
    if let Some(t) = stop {
        output::line(t);
        output::line(format_args!(
            "found before the stop: {} in {}",
            plural(p.solution_count(), "solution", "solutions"),
            plural(list.groups.len(), "moving set", "moving sets"),
        ));
    } else if p.interlocked {
        output::line("interlocked: no subset of parts can translate away from the rest");
    } else {
        output::line(format_args!(
            "not interlocked: {} in {}{}",
            plural(p.solution_count(), "solution", "solutions"),
            plural(list.groups.len(), "moving set", "moving sets"),
            if args.first {
                " (stopped at the first)"
            } else {
                ""
            }
        ));
    }
    // Per moving set, in the order of each set's best solution.
    for g in &list.groups[..list.listed_groups] {
        let moving = &p.solutions[g.first].moving;
        let [faces, edges, vertices] = g.counts;
        let counts: Vec<String> = [
            (faces, plural(faces, "face", "faces")),
            (edges, plural(edges, "edge", "edges")),
            (vertices, plural(vertices, "vertex", "vertices")),
        ]
        .into_iter()
        .filter(|(k, _)| *k > 0)
        .map(|(_, t)| t)
        .collect();
        output::line("");
        output::line(format_args!(
            "{} move{} ({}):",
            names_of(&p.names, moving).join(", "),
            if moving.len() == 1 { "s" } else { "" },
            counts.join(", ")
        ));
        for kind in [CellKind::Face, CellKind::Edge, CellKind::Vertex] {
            let mut shown = 0;
            for &i in &g.kept {
                let sol = &p.solutions[list.kept[i]];
                if sol.cell != kind {
                    continue;
                }
                shown += 1;
                let d = sol.direction.to_strings();
                let mut extra = match kind {
                    CellKind::Face => format!("clearance {:.2}°", sol.clearance_deg),
                    CellKind::Edge => "sliding".into(),
                    CellKind::Vertex => "isolated direction".into(),
                };
                if let Some(h) = holds {
                    if !h[i] {
                        extra.push_str(" (only under the tolerance)");
                    }
                }
                output::line(format_args!(
                    "  {:6}  {}  ({}, {}, {})  {}",
                    kind.name(),
                    output::unit(&sol.unit),
                    d[0],
                    d[1],
                    d[2],
                    extra
                ));
            }
            let more = g.counts[kind_index(kind)] - shown;
            if more > 0 {
                let what = match (kind, more) {
                    (CellKind::Face, 1) => "face",
                    (CellKind::Face, _) => "faces",
                    (CellKind::Edge, 1) => "edge",
                    (CellKind::Edge, _) => "edges",
                    (CellKind::Vertex, 1) => "vertex",
                    (CellKind::Vertex, _) => "vertices",
                };
                output::line(format_args!("  ... and {more} more {what} (--all)"));
            }
        }
    }
    if list.groups.len() > list.listed_groups {
        let more = list.groups.len() - list.listed_groups;
        let solutions: usize = list.groups[list.listed_groups..]
            .iter()
            .map(|g| g.counts.iter().sum::<usize>())
            .sum();
        output::line("");
        output::line(format_args!(
            "... and {} more moving set{} ({}) (--limit N, --all)",
            more,
            if more == 1 { "" } else { "s" },
            plural(solutions, "solution", "solutions")
        ));
    }
    if !global.quiet {
        let t = &s.seconds;
        output::line("");
        output::line(format_args!(
            "time: {load}, sums {:.1} ms, projection {:.1} ms, unions {:.1} ms, overlay {:.1} ms, graphs {:.1} ms",
            t.sums * 1e3,
            t.projection * 1e3,
            t.unions * 1e3,
            t.overlay * 1e3,
            t.graphs * 1e3
        ));
    }
}

/// Parses "X,Y,Z" and snaps it like coordinates to an integer direction.
pub fn parse_direction(text: &str) -> anyhow::Result<Vec3> {
    let v: Vec<f64> = text
        .split(',')
        .map(|s| s.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .with_context(|| format!("direction \"{text}\" is not three numbers X,Y,Z"))?;
    anyhow::ensure!(
        v.len() == 3,
        "direction \"{text}\" needs three numbers X,Y,Z"
    );
    anyhow::ensure!(
        v.iter().all(|x| x.is_finite()),
        "direction \"{text}\" has a non-finite number"
    );
    let g = Grid::choose(v.iter().copied(), 30)?;
    let d = Vec3::new(g.snap(v[0]), g.snap(v[1]), g.snap(v[2])).primitive();
    anyhow::ensure!(!d.is_zero(), "direction \"{text}\" is zero");
    Ok(d)
}

fn direction(
    global: &Global,
    loaded: &Loaded,
    parts: &[apart::plan::Part],
    text: &str,
    load_seconds: f64,
) -> anyhow::Result<ExitCode> {
    let d = parse_direction(text)?;
    let t = Instant::now();
    let names: Vec<String> = parts.iter().map(|p| p.name.clone()).collect();
    let names = &names[..];
    let answer = {
        let _phase = output::phase(global, "direction");
        dbg_along(parts, &d)?
    };
    let (cell, g, moving) = (answer.cell, answer.dbg, answer.moving);
    let direction_seconds = t.elapsed().as_secs_f64();
    let blocks: Vec<[String; 2]> = g
        .arcs()
        .iter()
        .map(|&(a, b)| [names[a].clone(), names[b].clone()])
        .collect();
    let motions: Vec<Motion> = moving.iter().map(|m| (m.as_slice(), None, &d)).collect();
    let holds = holds_without_tolerance(&loaded.assembly, &motions)?;
    if global.json {
        output::json(&DirectionJson {
            input: InputFacts::of(loaded, global),
            holds_without_tolerance: holds,
            direction: d.unit_f64(),
            exact_direction: d.to_strings(),
            cell: cell.name(),
            blocks,
            moving: moving.iter().map(|m| names_of(names, m)).collect(),
        })?;
    } else {
        let e = d.to_strings();
        output::line(format_args!(
            "direction ({}, {}, {}) ≈ {} lies in a {} of the motion space",
            e[0],
            e[1],
            e[2],
            output::unit(&d.unit_f64()),
            cell.name()
        ));
        output::line("blocking graph (a -> b: a, moving along the direction, hits b):");
        if blocks.is_empty() {
            output::line("  (no arc: every part is free)");
        }
        for [a, b] in &blocks {
            output::line(format_args!("  {a} -> {b}"));
        }
        if moving.is_empty() {
            output::line("no proper subset can move along this direction");
        }
        for (k, m) in moving.iter().enumerate() {
            let only = match &holds {
                Some(h) if !h[k] => " (only under the tolerance)",
                _ => "",
            };
            output::line(format_args!(
                "can move: {}{only}",
                names_of(names, m).join(", ")
            ));
        }
        if let Some(t) = tolerance_statement(&loaded.assembly, global) {
            output::line(t);
        }
        if !global.quiet {
            output::line("");
            output::line(format_args!(
                "time: {}, direction {:.1} ms",
                output::load_time(load_seconds, &loaded.seconds),
                direction_seconds * 1e3
            ));
        }
    }
    Ok(if moving.is_empty() {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    })
}
