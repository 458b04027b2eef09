//! The `apart` command line: flag definitions and dispatch. Each command lives in
//! `commands/<name>.rs`; shared output helpers in `output.rs`.

mod commands;
mod input_facts;
mod limits;
mod output;
mod step;

use clap::{Args, Parser, Subcommand};
use std::process::ExitCode;

/// Counts live heap bytes against the memory budget (`--max-memory`, 80 % of the
/// machine's memory by default; nothing is counted with `--max-memory none`).
#[global_allocator]
static ALLOCATOR: limits::Budget = limits::Budget;

/// The exit codes, in every `--help` and in the README.
const EXIT_CODES: &str = "\
Exit codes:
  0  the answer is yes (valid, comes apart, fits, every part stacked), or there is
     nothing to separate (an assembly of one part)
  1  usage error (unknown command or option, missing path, option value out of its
     range), invalid input, an output that would overwrite an input, a write error
     (standard output included; a closed pipe is not one), a failure, or a run
     stopped by the memory budget (after the partial answer of partition, sequence
     and stack, status \"out of memory\"), or by --timeout before it had a partial
     answer
  2  the answer is no: interlocked, inseparable, fits nowhere, stack incomplete
  3  stopped by --timeout with a partial answer (partition, sequence, stack): what was
     found until then, with status \"timeout\" in the JSON
130  interrupted by Ctrl-C: partition, sequence and stack print their partial answer
     (status \"interrupted\"); a second Ctrl-C, or one while loading, ends the run
     at once";

/// Exact assembly partitioning of polyhedral parts.
#[derive(Parser)]
#[command(name = "apart", version, about, long_about = None, after_help = EXIT_CODES)]
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
    /// Number of worker threads, 1 to 1024 (default: one per core).
    #[arg(long, global = true, value_name = "N", value_parser = limits::threads, allow_negative_numbers = true)]
    pub threads: Option<usize>,
    /// Print only errors and warnings, and no progress bar.
    #[arg(long, short, global = true)]
    pub quiet: bool,
    #[arg(
        long,
        global = true,
        value_name = "N",
        default_value_t = apart::kernel::grid::DEFAULT_BITS,
        value_parser = limits::grid_bits,
        allow_negative_numbers = true,
        help = limits::grid_bits_help()
    )]
    /// Bits of a snapped coordinate (the help text is built by `limits`).
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
    #[arg(long, global = true, value_name = "EPS|auto", value_parser = limits::tolerance, allow_negative_numbers = true)]
    pub tolerance: Option<String>,
    /// The length unit of the input files, stated in answers (coordinates are not
    /// rescaled). A STEP file's parts are converted to this unit (default mm).
    #[arg(long, global = true, value_enum, value_name = "UNIT")]
    pub units: Option<input_facts::Units>,
    /// STEP files only: the largest distance between a surface and its triangles, in
    /// the unit of --units (default: 1/1000 of the assembly's bounding-box diagonal).
    #[arg(long, global = true, value_name = "L", value_parser = step::chordal, allow_negative_numbers = true)]
    pub chordal_tolerance: Option<f64>,
    /// STEP files only: the largest angle between neighbouring triangles of a curved
    /// face, in radians (default 0.5).
    #[arg(long, global = true, value_name = "RAD", value_parser = step::angular, allow_negative_numbers = true)]
    pub angular_tolerance: Option<f64>,
    /// Repair nothing on load: any defect of a mesh is an error.
    #[arg(long, global = true)]
    pub strict: bool,
    /// Read each file as one part, even when it holds several separate solids.
    #[arg(long, global = true)]
    pub one_part_per_file: bool,
    /// Read mesh files (and glTF buffers) that lie outside the assembly's folder: by
    /// default every file an assembly names must resolve inside its folder, symbolic
    /// links included.
    #[arg(long, global = true)]
    pub allow_outside: bool,
    /// Stop the run after this many seconds (more than 0, at most 604800). partition,
    /// sequence and stack then print the answer found so far, marked "stopped by
    /// --timeout after S s during PHASE: partial answer" (JSON: "status": "timeout",
    /// "complete": false), write no picture or export, and exit with 3. While loading,
    /// in other commands, or when no partial answer comes within max(S/10, 5 s) more,
    /// the run ends with "stopped after S s: PHASE" and exit code 1.
    #[arg(long, global = true, value_name = "SECONDS", value_parser = limits::timeout, allow_negative_numbers = true)]
    pub timeout: Option<f64>,
    /// The memory budget: SIZE of live heap memory (4G, 500M, 1.5G or bytes; K, M, G, T
    /// are powers of 1024; at least 1M), or none (or 0) for no budget. Default: 80 % of
    /// the machine's memory (the smaller of the physical memory and the cgroup's limit;
    /// under an address-space limit, 80 % of it less 512M).
    /// Past 90 % of it partition, sequence and stack stop their planner and print the
    /// answer found so far (status "out of memory"); a run that would pass the budget
    /// itself ends at once. Either way the run ends with "out of memory budget
    /// (--max-memory SIZE) during PHASE" and exit code 1. Bounds the live heap and the
    /// growth of the resident size (sampled every 20 ms, at most 64M past the budget).
    #[arg(long, global = true, value_name = "SIZE|none", value_parser = limits::memory_budget, allow_negative_numbers = true)]
    pub max_memory: Option<u64>,
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
    /// and write them (one OFF mesh per piece, plus assembly.json). The output loads
    /// back as the same solids: a part whose pieces have vertices off the grid is
    /// written as its mesh alone and decomposed again on load.
    Decompose(commands::decompose::DecomposeArgs),
    /// A complete disassembly plan by recursive two-handed partitioning (its reverse is
    /// an assembly plan), with pictures and animated exports; exit 2 when a subassembly
    /// is interlocked.
    Sequence(commands::sequence::SequenceArgs),
    /// A plan of several moves (finite translations, then one to infinity, recursively)
    /// with the puzzle's level: exact and off the grid; exit 2 when no plan exists within
    /// the bounds.
    Disassemble(commands::disassemble::DisassembleArgs),
    /// Every direction along which one part leaves another: exact regions, sliding arcs,
    /// isolated directions, free area and the direction of largest clearance.
    Separate(commands::separate::SeparateArgs),
    /// Interference-free positions of a new part among fixed parts, cheapest first
    /// (exact c-space obstacles); exit 2 when it fits nowhere in the region.
    Place(commands::place::PlaceArgs),
    /// Stack identical parts on a floor region (stable, grippable from above, lowered
    /// along -z); exit 2 when not every part could be placed.
    Stack(commands::stack::StackArgs),
    /// Run partition, sequence or check on every assembly under a folder, in parallel
    /// across assemblies, each in its own process with its own time and memory bound;
    /// one JSON line per assembly (status, timings, counts), resumable; a summary table
    /// at the end. Exit code 1 when an assembly's process failed.
    Batch(commands::batch::BatchArgs),
}

fn main() -> ExitCode {
    limits::start_clock();
    // Made now, so that the allocator and the Ctrl-C handler only read it.
    let _ = limits::stop_flag();
    apart::formats::quiet_parser_panics();
    let mut cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage_error(e),
    };
    // A STEP file's parts come in millimetres unless --units asks for another unit, and
    // every answer states it (also a tolerance such as 5um then converts).
    if cli.global.units.is_none() && step_input(&cli.command).is_some() {
        cli.global.units = Some(step::DEFAULT_UNITS);
    }
    // Before any command runs, so that no "wrote FILE" line escapes --quiet.
    output::set_quiet(cli.global.quiet);
    limits::set_json(cli.global.json);
    // Every option is checked before any work: the numbers by their parsers, the
    // tolerance's unit against --units here.
    if let Err(e) = input_facts::tolerance(&cli.global) {
        output::fail(&cli.global, &e);
        return ExitCode::FAILURE;
    }
    match cli.global.max_memory {
        // --max-memory none
        Some(0) => {}
        Some(bytes) => limits::set_memory_budget(bytes, false),
        None => {
            if let Some(bytes) = limits::machine_budget() {
                limits::set_memory_budget(bytes, true);
            }
        }
    }
    if let Some(s) = cli.global.timeout {
        limits::start_watchdog(s);
    }
    if let Some(n) = cli.global.threads {
        // The main thread is one of the N: it runs the work itself instead of handing
        // it to a pool thread and waiting (with one thread, no thread is started).
        if let Err(e) = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .use_current_thread()
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
        Command::Disassemble(args) => commands::disassemble::run(args, &cli.global),
        Command::Separate(args) => commands::separate::run(args, &cli.global),
        Command::Place(args) => commands::place::run(args, &cli.global),
        Command::Stack(args) => commands::stack::run(args, &cli.global),
        Command::Batch(args) => commands::batch::run(args, &cli.global),
    };
    // An answer that could not be written is a failure, whatever it said.
    let result = result.and_then(|code| output::stdout_result().map(|()| code));
    match result {
        Ok(code) => code,
        Err(e) => {
            output::fail(&cli.global, &e);
            ExitCode::FAILURE
        }
    }
}

/// The STEP file the command reads as its assembly, if it reads one.
fn step_input(command: &Command) -> Option<&std::path::Path> {
    let path: &std::path::Path = match command {
        Command::Check(a) => &a.assembly,
        Command::Partition(a) => &a.assembly,
        Command::Sequence(a) => &a.assembly,
        Command::Disassemble(a) => &a.assembly,
        Command::Decompose(a) => &a.assembly,
        Command::Separate(a) => a.inputs.first()?.as_ref(),
        Command::Place(a) => a.inputs.first()?.as_ref(),
        Command::Stack(_) | Command::Batch(_) => return None,
    };
    step::is_step(path).then_some(path)
}

/// Help and version exit with 0; every other command-line error (no arguments, an
/// unknown command or option, a missing path, a value out of range) with 1, not clap's
/// 2, which apart reserves for a "no" answer.
fn usage_error(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    let printed = e.print();
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => match printed {
            Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
                output::eline(format_args!(
                    "error: cannot write to standard output: {}",
                    output::io_text(&e)
                ));
                ExitCode::FAILURE
            }
            _ => ExitCode::SUCCESS,
        },
        _ => {
            if std::env::args().any(|a| a == "--json") {
                let text = e.render().to_string();
                let msg = text.lines().next().unwrap_or("usage error");
                let msg = msg.strip_prefix("error: ").unwrap_or(msg);
                let _ = output::json(&serde_json::json!({ "valid": false, "error": msg }));
            }
            ExitCode::FAILURE
        }
    }
}
