//! `apart partition <assembly>`: every direction and minimal subset that separates the
//! assembly by one infinite translation; or, with `--direction`, the blocking graph of
//! one direction. Exit code 0 when some subset can move, 2 when the assembly is
//! interlocked, 1 on error.

use crate::commands::load::load_valid;
use crate::input_facts::{holds_without_tolerance, tolerance_statement, InputFacts, Motion};
use crate::output;
use crate::Global;
use anyhow::Context;
use apart::assembly::Loaded;
use apart::draw::{motion_space_png, motion_space_svg, SphereProjection, SphereSvgOptions};
use apart::kernel::{Grid, Vec3};
use apart::plan::{
    dbg_along, partition_first, partition_subset, parts_of, BlockingRegions, CellKind, Options,
    Partitioning, Solution,
};
use serde::Serialize;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

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
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
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
    /// In the text summary, list every solution instead of the first few per kind.
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
struct SolutionJson {
    cell: &'static str,
    direction: [f64; 3],
    exact_direction: [String; 3],
    moving: Vec<String>,
    clearance_deg: f64,
    /// Under a tolerance: the motion also holds for the parts as given.
    #[serde(skip_serializing_if = "Option::is_none")]
    holds_without_tolerance: Option<bool>,
}

#[derive(Serialize)]
struct Seconds {
    load: f64,
    sums: f64,
    projection: f64,
    unions: f64,
    overlay: f64,
    graphs: f64,
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

#[derive(Serialize)]
struct PartitionJson<'a> {
    #[serde(flatten)]
    input: InputFacts,
    interlocked: bool,
    parts: &'a [String],
    solutions: Vec<SolutionJson>,
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
    let asm = &loaded.assembly;
    let parts = parts_of(asm)?;
    if let Some(d) = &args.direction {
        // One direction: per-piece-pair tests only, no motion-space arrangement.
        return direction(global, &loaded, &parts, d, load_seconds);
    }
    let pictures = args.svg.is_some() || args.png.is_some();
    if args.first && !pictures {
        // Likely directions first; the full computation only when none separates.
        let p = partition_first(&parts)?;
        report(&p, &loaded, args, global, load_seconds)?;
        return Ok(if p.interlocked {
            ExitCode::from(2)
        } else {
            ExitCode::SUCCESS
        });
    }
    let regions = BlockingRegions::compute(&parts)?;
    let all: Vec<usize> = (0..parts.len()).collect();
    let (p, _) = partition_subset(&regions, &all, &Options { first: args.first });
    if pictures {
        let opts = SphereSvgOptions {
            title: format!("{}: motion space", asm.name),
            projection: args.projection.into(),
            ..Default::default()
        };
        if let Some(path) = &args.svg {
            output::write_file(path, motion_space_svg(&regions, &all, &p.solutions, &opts))?;
        }
        if let Some(path) = &args.png {
            output::write_file(path, motion_space_png(&regions, &all, &p.solutions, &opts))?;
        }
    }
    report(&p, &loaded, args, global, load_seconds)?;
    Ok(if p.interlocked {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    })
}

/// Prints the solutions (JSON or text), with the tolerance they hold under and, under a
/// tolerance, which of them also hold for the parts as given.
fn report(
    p: &Partitioning,
    loaded: &Loaded,
    args: &PartitionArgs,
    global: &Global,
    load: f64,
) -> anyhow::Result<()> {
    let asm = &loaded.assembly;
    let motions: Vec<Motion> = p
        .solutions
        .iter()
        .map(|s| (s.moving.as_slice(), None, &s.direction))
        .collect();
    let holds = holds_without_tolerance(asm, &motions)?;
    if global.json {
        output::json(&to_json(p, load, InputFacts::of(loaded, global), &holds))?;
    } else {
        print_text(p, asm, args, global, load, &holds);
        if let Some(t) = tolerance_statement(asm, global) {
            output::line(t);
        }
    }
    Ok(())
}

fn names_of(names: &[String], set: &[usize]) -> Vec<String> {
    set.iter().map(|&k| names[k].clone()).collect()
}

fn to_json<'a>(
    p: &'a Partitioning,
    load: f64,
    input: InputFacts,
    holds: &Option<Vec<bool>>,
) -> PartitionJson<'a> {
    let s = &p.stats;
    PartitionJson {
        input,
        interlocked: p.interlocked,
        parts: &p.names,
        solutions: p
            .solutions
            .iter()
            .enumerate()
            .map(|(k, s)| SolutionJson {
                cell: s.cell.name(),
                direction: s.unit,
                exact_direction: s.direction.to_strings(),
                moving: names_of(&p.names, &s.moving),
                clearance_deg: s.clearance_deg,
                holds_without_tolerance: holds.as_ref().map(|h| h[k]),
            })
            .collect(),
        stats: StatsJson {
            pieces: s.pieces,
            sums: s.sums,
            arcs: s.arcs,
            vertices: s.vertices,
            edges: s.edges,
            faces: s.faces,
            seconds: Seconds {
                load,
                sums: s.seconds.sums,
                projection: s.seconds.projection,
                unions: s.seconds.unions,
                overlay: s.seconds.overlay,
                graphs: s.seconds.graphs,
            },
        },
    }
}

fn print_text(
    p: &Partitioning,
    asm: &apart::assembly::Assembly,
    args: &PartitionArgs,
    global: &Global,
    load: f64,
    holds: &Option<Vec<bool>>,
) {
    let s = &p.stats;
    if !global.quiet {
        output::line(format_args!(
            "assembly \"{}\": {} parts, {} convex pieces, {} Minkowski sums",
            asm.name,
            p.names.len(),
            s.pieces,
            s.sums
        ));
        let n =
            |k: usize, one: &str, many: &str| format!("{k} {}", if k == 1 { one } else { many });
        output::line(format_args!(
            "motion space: {}, {}, {} ({})",
            n(s.vertices, "vertex", "vertices"),
            n(s.edges, "edge", "edges"),
            n(s.faces, "face", "faces"),
            n(s.arcs, "arc", "arcs")
        ));
    }
    if p.interlocked {
        output::line("interlocked: no subset of parts can translate away from the rest");
    } else {
        output::line(format_args!(
            "not interlocked: {} solution{}{}",
            p.solutions.len(),
            if p.solutions.len() == 1 { "" } else { "s" },
            if args.first {
                " (stopped at the first)"
            } else {
                ""
            }
        ));
    }
    // Group by moving subset, in the order of each subset's best solution.
    let mut groups: Vec<(Vec<usize>, Vec<&Solution>)> = Vec::new();
    for sol in &p.solutions {
        match groups.iter_mut().find(|(m, _)| *m == sol.moving) {
            Some((_, v)) => v.push(sol),
            None => groups.push((sol.moving.clone(), vec![sol])),
        }
    }
    let limit = if args.all { usize::MAX } else { 5 };
    for (moving, sols) in &groups {
        output::line("");
        output::line(format_args!(
            "{} move{}:",
            names_of(&p.names, moving).join(", "),
            if moving.len() == 1 { "s" } else { "" }
        ));
        for kind in [CellKind::Face, CellKind::Edge, CellKind::Vertex] {
            let of_kind: Vec<&&Solution> = sols.iter().filter(|x| x.cell == kind).collect();
            for sol in of_kind.iter().take(limit) {
                let d = sol.direction.to_strings();
                let mut extra = match kind {
                    CellKind::Face => format!("clearance {:.2}°", sol.clearance_deg),
                    CellKind::Edge => "sliding".into(),
                    CellKind::Vertex => "isolated direction".into(),
                };
                let k = p.solutions.iter().position(|x| std::ptr::eq(x, **sol));
                if let (Some(h), Some(k)) = (holds, k) {
                    if !h[k] {
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
            if of_kind.len() > limit {
                output::line(format_args!(
                    "  ... and {} more {}s (--all or --json)",
                    of_kind.len() - limit,
                    kind.name()
                ));
            }
        }
    }
    if !global.quiet {
        let t = &s.seconds;
        output::line("");
        output::line(format_args!(
            "time: load {:.1} ms, sums {:.1} ms, projection {:.1} ms, unions {:.1} ms, overlay {:.1} ms, graphs {:.1} ms",
            load * 1e3,
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
    parts: &[apart::plan::PartPieces],
    text: &str,
    load_seconds: f64,
) -> anyhow::Result<ExitCode> {
    let d = parse_direction(text)?;
    let t = Instant::now();
    let names: Vec<String> = parts.iter().map(|p| p.name.clone()).collect();
    let names = &names[..];
    let answer = dbg_along(parts, &d)?;
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
                "time: load {:.1} ms, direction {:.1} ms",
                load_seconds * 1e3,
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
