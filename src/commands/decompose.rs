//! `apart decompose <assembly> -o <folder>`: exact convex decomposition of every part
//! without declared pieces, written as one OFF mesh per piece plus an assembly.json
//! manifest that declares them, all or nothing ([`output::NewFolder`]). Refuses to
//! write where the input is, and gives parts whose safe file names collide unique ones.
//!
//! The output loads back as the same solids: every coordinate written is a grid point
//! (an integer times the grid step, exact in a double), so it snaps back to itself. A
//! piece with a vertex off the grid (an intersection of three face planes) cannot be
//! written exactly in any mesh format the loader reads, so a part with such pieces is
//! written as its mesh alone, and loading the output decomposes it again into the same
//! exact pieces.

use crate::commands::load::load_valid;
use crate::output;
use crate::Global;
use apart::assembly::Part;
use apart::formats::off;
use apart::formats::Polygons;
use apart::kernel::{int, Grid};
use apart::pieces::Polytope;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// Arguments of `apart decompose`.
#[derive(clap::Args, Debug)]
pub struct DecomposeArgs {
    /// A folder of mesh files, one mesh file, or an assembly.json manifest.
    pub assembly: PathBuf,
    /// The folder to write the pieces and the manifest to. It is written whole or not
    /// at all (beside it, then renamed into place). An existing folder is replaced only
    /// when it is empty or an earlier `apart decompose` wrote it (it holds the hidden
    /// file .apart-output); any other is refused, as is the input folder, a folder
    /// inside it or one holding an input file.
    #[arg(short, long, value_name = "FOLDER")]
    pub output: PathBuf,
}

#[derive(Serialize)]
struct PartOut {
    name: String,
    mesh: Option<String>,
    pieces: Vec<String>,
}

#[derive(Serialize)]
struct Manifest {
    name: String,
    parts: Vec<PartOut>,
}

#[derive(Serialize)]
struct PartReport {
    name: String,
    /// The part's files: `FILE.off` and the folder `FILE/` of its pieces.
    file: String,
    convex: bool,
    reflex_edges: usize,
    pieces: usize,
    decomposed: bool,
    declared_pieces: bool,
    /// Pieces with vertices off the grid.
    rational_pieces: usize,
    /// The pieces are written and declared in the manifest (every vertex on the grid);
    /// otherwise the part is written as its mesh alone and decomposed again on load.
    pieces_written: bool,
}

#[derive(Serialize)]
struct Report {
    output: PathBuf,
    parts: Vec<PartReport>,
    seconds: f64,
}

/// Runs the command.
pub fn run(args: &DecomposeArgs, global: &Global) -> anyhow::Result<ExitCode> {
    crate::input_facts::no_tolerance(global, "decompose")?;
    let t = Instant::now();
    let loaded = load_valid(&args.assembly, global)?;
    let seconds = t.elapsed().as_secs_f64();
    let asm = &loaded.assembly;
    let files = file_names(&asm.parts);
    output::Inputs::of(&args.assembly, &loaded).check_folder("-o", &args.output)?;
    for (part, file) in asm.parts.iter().zip(&files) {
        if *file != safe_name(&part.name) && !global.quiet {
            output::eline(format_args!(
                "note: part \"{}\" is written as {file}.off and {file}/ (its file name would collide with another part's)",
                part.name
            ));
        }
    }
    let _phase = output::phase(global, "writing pieces");
    // Written beside the folder and put in place whole at the end: the folder holds
    // the whole output, or does not exist.
    let mut out = output::NewFolder::create(&args.output, "apart decompose")?;
    let mut manifest = Manifest {
        name: asm.name.clone(),
        parts: Vec::new(),
    };
    let mut report = Vec::new();
    for (part, dir) in asm.parts.iter().zip(&files) {
        let mesh = match &part.mesh {
            Some(m) => {
                let file = format!("{dir}.off");
                let vertices = m.to_raw(&asm.grid, None).vertices;
                let faces = Polygons::from_triangles(&m.triangles);
                out.write(Path::new(&file), true, |mut w| {
                    off::write(&mut w, &vertices, &faces)
                })?;
                Some(file)
            }
            None => None,
        };
        let report_part = part_report(part, dir);
        let mut pieces = Vec::new();
        if report_part.pieces_written {
            for (k, p) in part.pieces.iter().enumerate() {
                let file = format!("{dir}/piece_{k}.off");
                let (vertices, faces) = piece_mesh(p, &asm.grid);
                out.write(Path::new(&file), false, |mut w| {
                    off::write(&mut w, &vertices, &faces)
                })?;
                pieces.push(file);
            }
            // One line for the folder of pieces, not one per piece (hundreds for a
            // finely tessellated part).
            out.announce(Path::new(dir));
        }
        report.push(report_part);
        manifest.parts.push(PartOut {
            name: part.name.clone(),
            mesh,
            pieces,
        });
    }
    let text = serde_json::to_string_pretty(&manifest)? + "\n";
    out.write(Path::new("assembly.json"), true, |w| {
        w.write_all(text.as_bytes())
    })?;
    out.commit()?;
    let report = Report {
        output: args.output.clone(),
        parts: report,
        seconds,
    };
    if global.json {
        output::json(&report)?;
    } else {
        let rows: Vec<Vec<String>> = report
            .parts
            .iter()
            .map(|p| {
                vec![
                    p.name.clone(),
                    if p.convex { "yes" } else { "no" }.into(),
                    p.reflex_edges.to_string(),
                    p.pieces.to_string(),
                    if p.declared_pieces {
                        "declared"
                    } else if !p.pieces_written {
                        "decomposed, off the grid: mesh only"
                    } else if p.decomposed {
                        "decomposed"
                    } else {
                        "the part itself"
                    }
                    .into(),
                ]
            })
            .collect();
        output::table(
            &["part", "convex", "reflex edges", "pieces", "pieces from"],
            &rows,
        );
        for p in report.parts.iter().filter(|p| !p.pieces_written) {
            output::eline(format_args!(
                "note: part \"{}\": {} of its {} pieces {} vertices off the grid (intersections of face planes), which no mesh file holds exactly; the part is written as its mesh alone ({}.off), and loading the output decomposes it again into the same exact pieces",
                p.name,
                p.rational_pieces,
                p.pieces,
                if p.rational_pieces == 1 { "has" } else { "have" },
                p.file
            ));
        }
        // The files were announced on standard error as they were written.
        output::line(format_args!("load and decompose {:.1} ms", seconds * 1e3));
    }
    Ok(ExitCode::SUCCESS)
}

fn part_report(p: &Part, file: &str) -> PartReport {
    let rational = p
        .pieces
        .iter()
        .filter(|q| *q.den() != apart::kernel::Int::ONE)
        .count();
    PartReport {
        name: p.name.clone(),
        file: file.to_string(),
        convex: p.convex,
        reflex_edges: p.reflex_edges,
        pieces: p.pieces.len(),
        decomposed: p.decomposed,
        declared_pieces: p.declared_pieces,
        rational_pieces: rational,
        // A part without a mesh has declared pieces, read from files: on the grid.
        pieces_written: rational == 0 || p.mesh.is_none(),
    }
}

/// Each part's file name (`NAME.off`, and `NAME/` for its pieces): its name made safe
/// for file systems, then unique: two names that become the same (`a b` and `a_b`), or
/// differ only in case (file systems that ignore case), or a part named like another's
/// file (`x` and `x.off`) get `_2`, `_3`, ...; `assembly.json` is the manifest's.
fn file_names(parts: &[Part]) -> Vec<String> {
    let mut used: std::collections::HashSet<String> =
        std::iter::once("assembly.json".to_string()).collect();
    parts
        .iter()
        .map(|p| {
            let base = safe_name(&p.name);
            let mut name = base.clone();
            let mut k = 2;
            let taken = |used: &std::collections::HashSet<String>, n: &str| {
                let n = n.to_lowercase();
                used.contains(&n) || used.contains(&format!("{n}.off"))
            };
            while taken(&used, &name) {
                name = format!("{base}_{k}");
                k += 1;
            }
            used.insert(name.to_lowercase());
            used.insert(format!("{}.off", name.to_lowercase()));
            name
        })
        .collect()
}

/// A file-system-safe version of a part name.
fn safe_name(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || "-_.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() || s.starts_with('.') {
        format!("part_{s}")
    } else {
        s
    }
}

/// A piece on the grid (denominator 1): its vertices in input units, exact (an
/// integer times the step 2^e is a double), and its facets as polygons.
fn piece_mesh(p: &Polytope, grid: &Grid) -> (Vec<[f64; 3]>, Polygons) {
    debug_assert!(*p.den() == apart::kernel::Int::ONE);
    let vertices = p
        .vertices()
        .iter()
        .map(|v| {
            let c = v.to_ints();
            [0, 1, 2].map(|k| grid.to_units(int::to_i64(&c[k]).unwrap_or(0)))
        })
        .collect();
    let faces = Polygons::from(
        p.facets()
            .iter()
            .map(|f| f.cycle.clone())
            .collect::<Vec<Vec<u32>>>(),
    );
    (vertices, faces)
}
