//! `apart check <assembly>`: load, validate, print a table of parts, the grid and every
//! problem. Exit code 0 when the assembly is valid (no error problem), 1 otherwise.

use crate::input_facts::{tolerance_statement, InputFacts};
use crate::output;
use crate::Global;
use apart::assembly::{fmt_volume, Decompose, Loaded};
use apart::mesh::Problem;
use serde::Serialize;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `apart check`.
#[derive(clap::Args, Debug)]
pub struct CheckArgs {
    /// A folder of mesh files, one mesh file, or an assembly.json manifest.
    pub assembly: PathBuf,
}

#[derive(Serialize)]
struct GridJson {
    exp: i32,
    step: f64,
    bits: u32,
    max_snap_displacement: f64,
}

#[derive(Serialize)]
struct BoxJson {
    min: [f64; 3],
    max: [f64; 3],
}

#[derive(Serialize)]
struct PartJson {
    name: String,
    #[serde(serialize_with = "apart::mesh::path_text")]
    source: PathBuf,
    vertices: Option<usize>,
    faces: Option<usize>,
    triangles: Option<usize>,
    /// Exact, in input units ("16/3"); null when unknown.
    volume: Option<String>,
    volume_decimal: Option<f64>,
    convex: bool,
    reflex_edges: usize,
    pieces: usize,
    declared_pieces: bool,
    /// The pieces come from the exact convex decomposition of a non-convex part.
    decomposed: bool,
    #[serde(serialize_with = "apart::mesh::path_texts")]
    piece_sources: Vec<PathBuf>,
    bbox: Option<BoxJson>,
}

#[derive(Serialize)]
struct CheckJson<'a> {
    assembly: &'a str,
    valid: bool,
    grid: GridJson,
    parts: Vec<PartJson>,
    problems: &'a [Problem],
    #[serde(flatten)]
    input: InputFacts,
}

/// Runs the command.
pub fn run(args: &CheckArgs, global: &Global) -> anyhow::Result<ExitCode> {
    let loaded = crate::commands::load::load_with(&args.assembly, global, Decompose::WhenNeeded)?;
    if global.json {
        output::json(&to_json(&loaded, InputFacts::of(&loaded, global)))?;
    } else {
        print_text(&loaded, global);
    }
    Ok(if loaded.is_valid() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn to_json(l: &Loaded, input: InputFacts) -> CheckJson<'_> {
    let a = &l.assembly;
    let g = &a.grid;
    let parts = a
        .parts
        .iter()
        .map(|p| {
            let known = p.volume_known();
            let v = p.volume_units(g);
            PartJson {
                name: p.name.clone(),
                source: p.source.clone(),
                vertices: p.info.as_ref().map(|i| i.vertices),
                faces: p.info.as_ref().map(|i| i.faces),
                triangles: p.info.as_ref().map(|i| i.triangles),
                volume: known.then(|| v.to_string()),
                volume_decimal: known.then(|| v.to_f64()),
                convex: p.convex,
                reflex_edges: p.reflex_edges,
                pieces: p.pieces.len(),
                declared_pieces: p.declared_pieces,
                decomposed: p.decomposed,
                piece_sources: p.piece_sources.clone(),
                bbox: p.bbox.map(|b| BoxJson {
                    min: b.min.map(|q| g.to_units(q)),
                    max: b.max.map(|q| g.to_units(q)),
                }),
            }
        })
        .collect();
    CheckJson {
        assembly: &a.name,
        valid: l.is_valid(),
        grid: GridJson {
            exp: g.exp,
            step: g.step(),
            bits: g.bits,
            max_snap_displacement: a.max_snap_displacement,
        },
        parts,
        problems: &l.problems,
        input,
    }
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
