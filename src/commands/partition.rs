//! `apart partition <assembly>`: every direction and minimal subset that separates the
//! assembly by one infinite translation; or, with `--direction`, the blocking graph of
//! one direction. Exit code 0 when some subset can move (or the assembly has one part:
//! nothing to separate), 2 when the assembly is interlocked, 3 when `--timeout` stopped
//! the run and the solutions found until then are printed (130 after Ctrl-C, 1 after
//! the memory budget, with the same partial answer), 1 on error. The listing is
//! grouped by moving set and bounded (`--limit`, `--all`): assemblies of many loose
//! parts have millions of solutions.

use crate::commands::load::load_valid;
use crate::input_facts::{tolerance_statement, Units};
use crate::limits::Stopped;
use crate::output;
use crate::{limits, Global};
use anyhow::Context;
use apart::assembly::Loaded;
use apart::draw::{motion_space_png, motion_space_svg, SphereProjection, SphereSvgOptions};
use apart::jobs::partition::Listing;
use apart::jobs::partition::{
    partition, GroupAnswer, LoadStages, PartitionAnswer, PartitionOptions, DEFAULT_LIMIT,
    EXAMPLES_PER_KIND,
};
use apart::jobs::Progress;
use apart::kernel::Vec3;
use apart::plan::{CellKind, MotionSpace};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// A count of solutions worth a warning even when all of them are asked for.
const LARGE: usize = 10_000;

/// Arguments of `apart partition`.
#[derive(clap::Args, Debug)]
pub struct PartitionArgs {
    /// A folder of mesh files, one mesh file, an assembly.json manifest, or a STEP file
    /// (.step, .stp: read by the Python package, pip install './python[step]').
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
    if asm.parts.len() < 2 {
        return nothing_to_separate(&loaded, global, load_seconds);
    }
    if let Some(d) = &args.direction {
        // One direction: per-piece-pair tests only, no motion-space arrangement.
        return direction(global, &loaded, d, load_seconds);
    }
    let pictures = args.svg.is_some() || args.png.is_some();
    let opts = PartitionOptions {
        first: args.first,
        max_solutions: None,
        listing: if args.all {
            Listing::all()
        } else {
            Listing {
                sets: Some(args.limit.unwrap_or(DEFAULT_LIMIT)),
                per_set: Some(EXAMPLES_PER_KIND),
            }
        },
        keep_for_pictures: pictures,
    };
    let label = if args.first && !pictures {
        "first solution"
    } else {
        "pair regions"
    };
    let run = {
        let (_phase, progress) = output::planner(global, label);
        partition(&loaded, global.units.map(Units::symbol), &opts, &progress)
            .map_err(|e| limits::job_error(e, global))?
    };
    let mut answer = run.answer;
    let stop = output::partial(global, !answer.status.complete, pictures);
    if let Some((regions, p)) = run.for_pictures.filter(|_| stop.is_none()) {
        let _phase = output::phase(global, "pictures");
        let opts = SphereSvgOptions {
            title: format!("{}: motion space", asm.name),
            projection: args.projection.into(),
            ..Default::default()
        };
        // One motion space for both pictures, with the solutions planned above.
        let all: Vec<usize> = (0..asm.parts.len()).collect();
        let ms = MotionSpace::build_split_at_equator(&regions, &all);
        let names = regions.names();
        if let Some(path) = &args.svg {
            output::write_file(path, motion_space_svg(&ms, names, &p.solutions, &opts))?;
        }
        if let Some(path) = &args.png {
            output::write_file(path, motion_space_png(&ms, names, &p.solutions, &opts))?;
        }
    }
    output::stamp(&mut answer.status, &stop);
    answer.stats.seconds.load = Some(load_seconds);
    answer.stats.seconds.load_stages = Some(LoadStages::of(&loaded.seconds));
    report(&answer, &loaded, args, global, load_seconds, &stop)?;
    let yes = if answer.interlocked {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    };
    Ok(output::exit_code(&stop, yes))
}

/// The answer for an assembly of one part: nothing to separate, which is not "no"
/// (exit code 0), the same meaning in partition, sequence and separate.
fn nothing_to_separate(loaded: &Loaded, global: &Global, load: f64) -> anyhow::Result<ExitCode> {
    let asm = &loaded.assembly;
    if global.json {
        let opts = PartitionOptions::default();
        let progress = Progress::new();
        let mut answer = partition(loaded, global.units.map(Units::symbol), &opts, &progress)
            .map_err(|e| limits::job_error(e, global))?
            .answer;
        answer.stats.seconds.load = Some(load);
        answer.stats.seconds.load_stages = Some(LoadStages::of(&loaded.seconds));
        output::json(&answer)?;
    } else {
        let n = asm.parts.len();
        output::line(format_args!(
            "assembly \"{}\" has {} part{}: nothing to separate",
            asm.name,
            n,
            if n == 1 { "" } else { "s" }
        ));
    }
    Ok(ExitCode::SUCCESS)
}

/// Prints the answer (JSON or text), with the tolerance it holds under and, under a
/// tolerance, which of the listed solutions also hold for the parts as given.
fn report(
    a: &PartitionAnswer,
    loaded: &Loaded,
    args: &PartitionArgs,
    global: &Global,
    load: f64,
    stop: &Option<Stopped>,
) -> anyhow::Result<()> {
    warn_size(a, global);
    if global.json {
        output::json(a)?;
    } else {
        print_text(
            a,
            &loaded.assembly.name,
            args,
            global,
            output::load_time(load, &loaded.seconds),
            stop,
        );
        if let Some(t) = tolerance_statement(&loaded.assembly, global) {
            output::line(t);
        }
    }
    Ok(())
}

/// A warning on standard error when the listing leaves out moving sets, when the JSON
/// leaves out solutions, or when the count is large.
fn warn_size(a: &PartitionAnswer, global: &Global) {
    let total = a.solution_count;
    let sets = a.moving_set_count;
    let counts = format!(
        "{total} solution{} in {sets} moving set{}",
        if total == 1 { "" } else { "s" },
        if sets == 1 { "" } else { "s" }
    );
    let listed = a.groups.len();
    match a.limit {
        None if total > LARGE => output::eline(format_args!(
            "warning: {counts}: listing all of them (--all)"
        )),
        Some(n) if a.truncated && (sets > n || global.json || total > LARGE) => {
            output::eline(format_args!(
                "warning: {counts}; listing {listed} moving set{} with at most {EXAMPLES_PER_KIND} solutions of each kind (--limit N for more moving sets, --all for every solution)",
                if listed == 1 { "" } else { "s" }
            ))
        }
        _ => {}
    }
}

fn plural(k: usize, one: &str, many: &str) -> String {
    format!("{k} {}", if k == 1 { one } else { many })
}

fn print_text(
    a: &PartitionAnswer,
    name: &str,
    args: &PartitionArgs,
    global: &Global,
    load: String,
    stop: &Option<Stopped>,
) {
    let s = &a.stats;
    if !global.quiet {
        output::line(format_args!(
            "assembly \"{}\": {}, {}, {}",
            name,
            plural(a.parts.len(), "part", "parts"),
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
            plural(a.solution_count, "solution", "solutions"),
            plural(a.moving_set_count, "moving set", "moving sets"),
        ));
    } else if a.interlocked {
        output::line("interlocked: no subset of parts can translate away from the rest");
    } else {
        output::line(format_args!(
            "not interlocked: {} in {}{}",
            plural(a.solution_count, "solution", "solutions"),
            plural(a.moving_set_count, "moving set", "moving sets"),
            if args.first {
                " (stopped at the first)"
            } else {
                ""
            }
        ));
    }
    // Per moving set, in the order of each set's best solution.
    for g in &a.groups {
        print_group(a, g);
    }
    let more = a.moving_set_count - a.groups.len();
    if more > 0 {
        output::line("");
        output::line(format_args!(
            "... and {} more moving set{} ({}) (--limit N, --all)",
            more,
            if more == 1 { "" } else { "s" },
            plural(a.unlisted_solutions, "solution", "solutions")
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

/// One moving set: its counts, then its listed solutions by kind.
fn print_group(a: &PartitionAnswer, g: &GroupAnswer) {
    let counts: Vec<String> = [
        (g.faces, plural(g.faces, "face", "faces")),
        (g.edges, plural(g.edges, "edge", "edges")),
        (g.vertices, plural(g.vertices, "vertex", "vertices")),
    ]
    .into_iter()
    .filter(|(k, _)| *k > 0)
    .map(|(_, t)| t)
    .collect();
    output::line("");
    output::line(format_args!(
        "{} move{} ({}):",
        g.moving.join(", "),
        if g.moving.len() == 1 { "s" } else { "" },
        counts.join(", ")
    ));
    for (kind, count) in [
        (CellKind::Face, g.faces),
        (CellKind::Edge, g.edges),
        (CellKind::Vertex, g.vertices),
    ] {
        let mut shown = 0;
        for &i in &g.members {
            if a.kinds[i] != kind {
                continue;
            }
            shown += 1;
            let sol = &a.solutions[i];
            let d = &sol.exact_direction;
            let mut extra = match kind {
                CellKind::Face => format!("clearance {:.2}°", sol.clearance_deg),
                CellKind::Edge => "sliding".into(),
                CellKind::Vertex => "isolated direction".into(),
            };
            if sol.holds_without_tolerance == Some(false) {
                extra.push_str(" (only under the tolerance)");
            }
            output::line(format_args!(
                "  {:6}  {}  ({}, {}, {})  {}",
                kind.name(),
                output::unit(&sol.direction),
                d[0],
                d[1],
                d[2],
                extra
            ));
        }
        let more = count - shown;
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
    use apart::jobs::partition::{snap_direction, DirectionError};
    snap_direction([v[0], v[1], v[2]]).map_err(|e| match e {
        DirectionError::NonFinite => {
            anyhow::anyhow!("direction \"{text}\" has a non-finite number")
        }
        DirectionError::Zero => anyhow::anyhow!("direction \"{text}\" is zero"),
    })
}

fn direction(
    global: &Global,
    loaded: &Loaded,
    text: &str,
    load_seconds: f64,
) -> anyhow::Result<ExitCode> {
    let d = parse_direction(text)?;
    let t = Instant::now();
    let a = {
        let _phase = output::phase(global, "direction");
        apart::jobs::partition::direction(loaded, global.units.map(Units::symbol), &d)
            .map_err(|e| limits::job_error(e, global))?
    };
    let direction_seconds = t.elapsed().as_secs_f64();
    if global.json {
        output::json(&a)?;
    } else {
        let e = &a.exact_direction;
        output::line(format_args!(
            "direction ({}, {}, {}) ≈ {} lies in a {} of the motion space",
            e[0],
            e[1],
            e[2],
            output::unit(&a.direction),
            a.cell
        ));
        output::line("blocking graph (a -> b: a, moving along the direction, hits b):");
        if a.blocks.is_empty() {
            output::line("  (no arc: every part is free)");
        }
        for [x, y] in &a.blocks {
            output::line(format_args!("  {x} -> {y}"));
        }
        if a.moving.is_empty() {
            output::line("no proper subset can move along this direction");
        }
        for (k, m) in a.moving.iter().enumerate() {
            let only = match &a.holds_without_tolerance {
                Some(h) if !h[k] => " (only under the tolerance)",
                _ => "",
            };
            output::line(format_args!("can move: {}{only}", m.join(", ")));
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
    Ok(if a.moving.is_empty() {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    })
}
