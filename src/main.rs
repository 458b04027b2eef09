//! The `apart` command line: flag definitions and dispatch. Each command lives in
//! `commands/<name>.rs`; shared output helpers in `output.rs`.

mod commands;
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
}

#[derive(Subcommand)]
enum Command {
    /// Load an assembly (folder, mesh file or assembly.json), validate every part and
    /// the parts together, and print what was found. Exit code 0 when valid.
    Check(commands::check::CheckArgs),
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
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            output::fail(&cli.global, &e);
            ExitCode::FAILURE
        }
    }
}
