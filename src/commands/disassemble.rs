//! `apart disassemble <assembly>`: a plan of several moves (finite translations, then
//! one to infinity, recursively on the separated groups), exact and off the grid, with
//! the puzzle's level. Exit code 0 when every part comes apart, 2 when no plan exists
//! within the bounds (the answer says whether the search was exhaustive or cut off),
//! 3 when `--timeout` stopped the run, 130 after Ctrl-C, 1 after the memory budget and
//! on error.

use crate::commands::load::load_valid;
use crate::input_facts::{tolerance_statement, Units};
use crate::output;
use crate::{limits, Global};
use apart::draw::{moves_glb, moves_html, moves_svg};
use apart::jobs::disassemble::{disassemble, DisassembleAnswer};
use apart::jobs::Status;
use apart::plan::MoveOptions;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Arguments of `apart disassemble`.
#[derive(clap::Args, Debug)]
pub struct DisassembleArgs {
    /// A folder of mesh files, one mesh file, an assembly.json manifest, or a STEP file
    /// (.step, .stp: read by the Python package, pip install './python[step]').
    pub assembly: PathBuf,
    /// Moves only along ±x, ±y, ±z (by any distance where something changes, and by
    /// every whole grid step: on voxel puzzles, the level of BurrTools).
    #[arg(long)]
    pub axes: bool,
    /// Moves allowed per subassembly, up to and including its first move to infinity.
    #[arg(long, value_name = "N", default_value_t = 200, value_parser = limits::positive, allow_negative_numbers = true)]
    pub max_moves: usize,
    /// States explored per subassembly at most.
    #[arg(long, value_name = "N", default_value_t = 2_000_000, value_parser = limits::positive, allow_negative_numbers = true)]
    pub max_states: usize,
    /// Treat congruent parts as different (by default states that differ only by
    /// swapping translated copies of one part are one state).
    #[arg(long)]
    pub no_symmetry: bool,
    /// Draw the plan move by move as SVG (each state, the moving parts highlighted).
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
    /// Write an animated glTF binary (GLB) of the moves.
    #[arg(long, value_name = "FILE")]
    pub glb: Option<PathBuf>,
    /// Write a self-contained HTML page that plays the moves in 3-D.
    #[arg(long, value_name = "FILE")]
    pub html: Option<PathBuf>,
}

/// Runs the command.
pub fn run(args: &DisassembleArgs, global: &Global) -> anyhow::Result<ExitCode> {
    let t = Instant::now();
    let loaded = load_valid(&args.assembly, global)?;
    let load = t.elapsed().as_secs_f64();
    let inputs = output::Inputs::of(&args.assembly, &loaded);
    for (flag, p) in [
        ("--svg", &args.svg),
        ("--glb", &args.glb),
        ("--html", &args.html),
    ] {
        if let Some(p) = p {
            inputs.check_file(flag, p)?;
        }
    }
    let asm = &loaded.assembly;
    let opts = MoveOptions {
        axes: args.axes,
        max_moves: args.max_moves,
        max_states: args.max_states,
        symmetry: !args.no_symmetry,
    };
    let mut answer = {
        let (_phase, progress) = output::planner(global, "move states");
        disassemble(&loaded, global.units.map(Units::symbol), &opts, &progress)
            .map_err(|e| limits::job_error(e, global))?
    };
    let plan = answer.plan.clone();
    let files = args.svg.is_some() || args.glb.is_some() || args.html.is_some();
    let stop = output::partial(global, plan.stopped, files);
    if stop.is_none() && !plan.moves.is_empty() {
        let _phase = output::phase(global, "pictures and exports");
        if let Some(p) = &args.svg {
            output::write_file(p, moves_svg(asm, &plan))?;
        }
        if let Some(p) = &args.glb {
            output::write_file(p, moves_glb(asm, &plan))?;
        }
        if let Some(p) = &args.html {
            output::write_file(p, moves_html(asm, &plan))?;
        }
    }
    let mut status = Status::of(plan.stopped);
    output::stamp(&mut status, &stop);
    answer.set_status(status);
    answer.stats.seconds.load = Some(load);
    if global.json {
        output::json(&answer)?;
    } else {
        text(
            &answer,
            &asm.name,
            &output::load_time(load, &loaded.seconds),
        );
        if let Some(t) = tolerance_statement(asm, global) {
            output::line(t);
        }
    }
    let code = if plan.complete {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(2)
    };
    Ok(output::exit_code(&stop, code))
}

/// The answer in words.
fn text(a: &DisassembleAnswer, name: &str, load: &str) {
    output::line(format_args!(
        "disassembly of \"{name}\" by moves ({} parts, {} directions):",
        a.parts.len(),
        if a.model == "axes" {
            "axis"
        } else {
            "free-cone"
        }
    ));
    match a.level {
        Some(l) => output::line(format_args!(
            "level {l}: {l} move{} up to the first that separates",
            if l == 1 { "" } else { "s" }
        )),
        None if a.parts.len() < 2 => output::line("one part: nothing to separate"),
        None => output::line("not separated"),
    }
    let mut search = usize::MAX;
    for (k, m) in a.moves.iter().enumerate() {
        let s = a.plan.moves[k].search;
        if s != search {
            search = s;
            output::line(format_args!("{{{}}}:", m.subassembly.join(", ")));
        }
        let d = &m.exact_direction;
        let how = if m.distance == "infinity" {
            format!("to infinity along ({}, {}, {})", d[0], d[1], d[2])
        } else {
            format!(
                "by {} × ({}, {}, {}) (length {:.6})",
                m.distance,
                d[0],
                d[1],
                d[2],
                m.length.unwrap_or(0.0)
            )
        };
        output::line(format_args!(
            "  {}. {{{}}} {how}",
            k + 1,
            m.moving.join(", ")
        ));
    }
    if let Some(v) = &a.verdict {
        output::line(v);
    }
    let s = &a.stats.seconds;
    output::line(format_args!(
        "{} states explored; time: {load}, obstacles {:.3} s, search {:.3} s",
        a.states_explored, s.obstacles, s.search
    ));
}
