//! The `apart` command line: flag definitions and dispatch. Each command lives in
//! `commands/<name>.rs`; shared output helpers in `output.rs`.

mod commands;
mod input_facts;
mod output;

use clap::{Args, Parser, Subcommand};
use std::process::ExitCode;

/// Exact assembly partitioning of polyhedral parts.
#[derive(Parser)]
#[command(name = "apart", version, about, long_about = None)]
struct Cli {
    #[command(flatten)]
    global: Global,
    #[command(subcommand)]
    command: Command,
}

/// Flags every command takes.
#[derive(Args, Clone, Debug)]
pub struct Global {
    /// Print the result as JSON on standard output.
    #[arg(long, global = true)]
    pub json: bool,
    /// Number of worker threads (default: one per core).
    #[arg(long, global = true, value_name = "N")]
    pub threads: Option<usize>,
    /// Print only errors and warnings, and no progress bar.
    #[arg(long, short, global = true)]
    pub quiet: bool,
    /// Bits of a snapped coordinate: the grid is the finest power of two that keeps
    /// every coordinate below 2^N steps.
    #[arg(long, global = true, value_name = "N", default_value_t = apart::kernel::grid::DEFAULT_BITS)]
    pub grid_bits: u32,
    /// Verify every automatic convex decomposition exactly (pieces convex, interiors
    /// disjoint, inside the part, volumes adding up).
    #[arg(long, global = true)]
    pub verify: bool,
    /// Accept overlaps between parts as contact for parts made EPS smaller: every
    /// convex piece's faces move inward by EPS (input units, or with a unit such as
    /// 5um, 0.01mm, 1e-4in together with --units), and every answer says it holds for
    /// parts made EPS smaller. `auto` finds the smallest EPS, up to 1e-3 of the
    /// assembly's size, that makes the assembly valid.
    #[arg(long, global = true, value_name = "EPS|auto")]
    pub tolerance: Option<String>,
    /// The length unit of the input files, stated in answers (coordinates are not
    /// rescaled).
    #[arg(long, global = true, value_enum, value_name = "UNIT")]
    pub units: Option<input_facts::Units>,
    /// Repair nothing on load: any defect of a mesh is an error.
    #[arg(long, global = true)]
    pub strict: bool,
    /// Read each file as one part, even when it holds several separate solids.
    #[arg(long, global = true)]
    pub one_part_per_file: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Load an assembly (folder, mesh file or assembly.json), validate every part and
    /// the parts together, and print what was found. Exit code 0 when valid.
    Check(commands::check::CheckArgs),
    /// Every direction and minimal subset of parts that separates the assembly by one
    /// infinite translation (exit 2 when interlocked); or, with --direction, the blocking
    /// graph of one direction.
    Partition(commands::partition::PartitionArgs),
    /// Decompose every non-convex part without declared pieces into exact convex pieces
    /// and write them (one OFF mesh per piece, plus assembly.json).
    Decompose(commands::decompose::DecomposeArgs),
    /// A complete disassembly plan by recursive two-handed partitioning (its reverse is
    /// an assembly plan), with pictures and animated exports; exit 2 when a subassembly
    /// is interlocked.
    Sequence(commands::sequence::SequenceArgs),
    /// Every direction along which one part leaves another: exact regions, sliding arcs,
    /// isolated directions, free area and the direction of largest clearance.
    Separate(commands::separate::SeparateArgs),
    /// Interference-free positions of a new part among fixed parts, cheapest first
    /// (exact c-space obstacles); exit 2 when it fits nowhere in the region.
    Place(commands::place::PlaceArgs),
    /// Stack identical parts on a floor region (stable, grippable from above, lowered
    /// along -z); exit 2 when not every part could be placed.
    Stack(commands::stack::StackArgs),
}

fn main() -> ExitCode {
    apart::mesh::formats::quiet_parser_panics();
    let cli = Cli::parse();
    if let Some(n) = cli.global.threads {
        if let Err(e) = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
        {
            output::fail(
                &cli.global,
                &anyhow::anyhow!("cannot start {n} threads: {e}"),
            );
            return ExitCode::FAILURE;
        }
    }
    let result = match &cli.command {
        Command::Check(args) => commands::check::run(args, &cli.global),
        Command::Partition(args) => commands::partition::run(args, &cli.global),
        Command::Decompose(args) => commands::decompose::run(args, &cli.global),
        Command::Sequence(args) => commands::sequence::run(args, &cli.global),
        Command::Separate(args) => commands::separate::run(args, &cli.global),
        Command::Place(args) => commands::place::run(args, &cli.global),
        Command::Stack(args) => commands::stack::run(args, &cli.global),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            output::fail(&cli.global, &e);
            ExitCode::FAILURE
        }
    }
}
