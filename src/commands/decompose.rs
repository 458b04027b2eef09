//! `apart decompose <assembly> -o <folder>`: exact convex decomposition of every part
//! without declared pieces, written as one OFF mesh per piece plus an assembly.json
//! manifest that declares them, all or nothing ([`output::NewFolder`]). Refuses to
//! write where the input is, and gives parts whose safe file names collide unique ones
//! (the job [`apart::jobs::decompose`] names the files and says which pieces are written).
//!
//! The output loads back as the same solids: every coordinate written is a grid point
//! (an integer times the grid step, exact in a double), so it snaps back to itself.

use crate::commands::load::load_valid;
use crate::output;
use crate::Global;
use apart::formats::off;
use apart::formats::Polygons;
use apart::jobs::decompose::{decompose, safe_name};
use apart::kernel::{int, Grid};
use apart::pieces::Polytope;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// Arguments of `apart decompose`.
#[derive(clap::Args, Debug)]
pub struct DecomposeArgs {
    /// A folder of mesh files, one mesh file, an assembly.json manifest, or a STEP file
    /// (.step, .stp: read by the Python package, pip install './python[step]').
    pub assembly: PathBuf,
    /// The folder to write the pieces and the manifest to. It is written whole or not
    /// at all (beside it, then renamed into place). An existing folder is replaced only
    /// when it is empty or an earlier `apart decompose` wrote it (it holds the hidden
    /// file .apart-output); any other is refused, as is the input folder, a folder
    /// inside it or one holding an input file.
    #[arg(short, long, value_name = "FOLDER")]
    pub output: PathBuf,
}

/// Runs the command.
pub fn run(args: &DecomposeArgs, global: &Global) -> anyhow::Result<ExitCode> {
    crate::input_facts::no_tolerance(global, "decompose")?;
    let t = Instant::now();
    let loaded = load_valid(&args.assembly, global)?;
    let seconds = t.elapsed().as_secs_f64();
    let asm = &loaded.assembly;
    let report = decompose(&loaded, &args.output, seconds);
    output::Inputs::of(&args.assembly, &loaded).check_folder("-o", &args.output)?;
    for (part, p) in asm.parts.iter().zip(&report.parts) {
        if p.file != safe_name(&part.name) && !global.quiet {
            output::eline(format_args!(
                "note: part \"{}\" is written as {}.off and {}/ (its file name would collide with another part's)",
                part.name, p.file, p.file
            ));
        }
    }
    let _phase = output::phase(global, "writing pieces");
    // Written beside the folder and put in place whole at the end: the folder holds
    // the whole output, or does not exist.
    let mut out = output::NewFolder::create(&args.output, "apart decompose")?;
    for ((part, files), r) in asm
        .parts
        .iter()
        .zip(&report.manifest.parts)
        .zip(&report.parts)
    {
        if let (Some(m), Some(file)) = (&part.mesh, &files.mesh) {
            let vertices = m.to_raw(&asm.grid, None).vertices;
            let faces = Polygons::from_triangles(&m.triangles);
            out.write(Path::new(file), true, |mut w| {
                off::write(&mut w, &vertices, &faces)
            })?;
        }
        for (p, file) in part.pieces.iter().zip(&files.pieces) {
            let (vertices, faces) = piece_mesh(p, &asm.grid);
            out.write(Path::new(file), false, |mut w| {
                off::write(&mut w, &vertices, &faces)
            })?;
        }
        if r.pieces_written {
            // One line for the folder of pieces, not one per piece (hundreds for a
            // finely tessellated part).
            out.announce(Path::new(&r.file));
        }
    }
    let text = serde_json::to_string_pretty(&report.manifest)? + "\n";
    out.write(Path::new("assembly.json"), true, |w| {
        w.write_all(text.as_bytes())
    })?;
    out.commit()?;
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
