//! `apart check <assembly>`: load, validate, print a table of parts, the grid and every
//! problem. Exit code 0 when the assembly is valid (no error problem), 1 otherwise.

use crate::input_facts::{tolerance_statement, Units};
use crate::output;
use crate::Global;
use apart::assembly::{fmt_volume, Decompose, Loaded};
use apart::jobs::check::check;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `apart check`.
#[derive(clap::Args, Debug)]
pub struct CheckArgs {
    /// A folder of mesh files, one mesh file, an assembly.json manifest, or a STEP file
    /// (.step, .stp: read by the Python package, pip install './python[step]').
    pub assembly: PathBuf,
}

/// Runs the command.
pub fn run(args: &CheckArgs, global: &Global) -> anyhow::Result<ExitCode> {
    let loaded = crate::commands::load::load_with(&args.assembly, global, Decompose::WhenNeeded)?;
    if global.json {
        output::json(&check(&loaded, global.units.map(Units::symbol)))?;
    } else {
        print_text(&loaded, global);
    }
    Ok(if loaded.is_valid() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn print_text(l: &Loaded, global: &Global) {
    let a = &l.assembly;
    let g = &a.grid;
    if !global.quiet {
        output::line(format_args!(
            "assembly \"{}\": {} part{}",
            a.name,
            a.parts.len(),
            if a.parts.len() == 1 { "" } else { "s" }
        ));
        output::line(format_args!(
            "grid: h = {} ({} bits), largest snap displacement {}",
            output::step(g),
            g.bits,
            a.max_snap_displacement
        ));
        output::line("");
        let rows: Vec<Vec<String>> = a
            .parts
            .iter()
            .map(|p| {
                let count = |f: fn(&apart::mesh::validate::MeshInfo) -> usize| {
                    p.info
                        .as_ref()
                        .map_or("-".to_string(), |i| f(i).to_string())
                };
                vec![
                    p.name.clone(),
                    count(|i| i.vertices),
                    count(|i| i.faces),
                    if p.volume_known() {
                        fmt_volume(&p.volume, g)
                    } else {
                        "-".into()
                    },
                    if p.convex { "yes" } else { "no" }.into(),
                    p.reflex_edges.to_string(),
                    if p.declared_pieces {
                        format!("{} declared", p.pieces.len())
                    } else if p.decomposed {
                        format!("{} decomposed", p.pieces.len())
                    } else {
                        p.pieces.len().to_string()
                    },
                    output::bbox(g, &p.bbox),
                ]
            })
            .collect();
        output::table(
            &[
                "part",
                "vertices",
                "faces",
                "volume",
                "convex",
                "reflex edges",
                "pieces",
                "bounding box",
            ],
            &rows,
        );
        output::line("");
    }
    output::problems(global, &l.problems);
    let count = |s| l.problems.iter().filter(|p| p.severity == s).count();
    use apart::mesh::Severity::*;
    let (e, w, n) = (count(Error), count(Warning), count(Note));
    if let Some(t) = tolerance_statement(a, global) {
        output::line(t);
    }
    if !l.skipped.is_empty() {
        let k = l.skipped.len();
        output::line(format_args!(
            "not read: {k} entr{} of the folder (named in the warnings on standard error)",
            if k == 1 { "y" } else { "ies" }
        ));
    }
    let verdict = if l.is_valid() { "valid" } else { "invalid" };
    output::line(format_args!(
        "{verdict}: {e} error(s), {w} warning(s), {n} note(s)"
    ));
}
