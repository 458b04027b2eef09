//! `apart decompose <assembly> -o <folder>`: exact convex decomposition of every part
//! without declared pieces, written as one OFF mesh per piece plus an assembly.json
//! manifest that declares them.

use crate::commands::load::load_valid;
use crate::output;
use crate::Global;
use apart::assembly::Part;
use apart::kernel::{int, Grid};
use apart::mesh::formats::off;
use apart::mesh::Polygons;
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
    /// The folder to write the pieces and the manifest to (created if needed).
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
    convex: bool,
    reflex_edges: usize,
    pieces: usize,
    decomposed: bool,
    declared_pieces: bool,
    /// Pieces with vertices off the grid (written to the nearest double).
    rational_pieces: usize,
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
    std::fs::create_dir_all(&args.output)
        .map_err(|e| anyhow::anyhow!("cannot create {}: {e}", args.output.display()))?;
    let mut manifest = Manifest {
        name: asm.name.clone(),
        parts: Vec::new(),
    };
    let mut report = Vec::new();
    for part in &asm.parts {
        let dir = safe_name(&part.name);
        let mesh = match &part.mesh {
            Some(m) => {
                let file = format!("{dir}.off");
                write_off(
                    &args.output.join(&file),
                    &m.to_raw(&asm.grid, None).vertices,
                    &Polygons::from_triangles(&m.triangles),
                )?;
                Some(file)
            }
            None => None,
        };
        let piece_dir = args.output.join(&dir);
        std::fs::create_dir_all(&piece_dir)
            .map_err(|e| anyhow::anyhow!("cannot create {}: {e}", piece_dir.display()))?;
        let mut pieces = Vec::new();
        for (k, p) in part.pieces.iter().enumerate() {
            let file = format!("{dir}/piece_{k}.off");
            let (vertices, faces) = piece_mesh(p, &asm.grid);
            write_off(&args.output.join(&file), &vertices, &faces)?;
            pieces.push(file);
        }
        report.push(part_report(part));
        manifest.parts.push(PartOut {
            name: part.name.clone(),
            mesh,
            pieces,
        });
    }
    output::write_file(
        &args.output.join("assembly.json"),
        serde_json::to_string_pretty(&manifest)? + "\n",
    )?;
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
        let rational: usize = report.parts.iter().map(|p| p.rational_pieces).sum();
        if rational > 0 {
            output::eline(format_args!(
                "note: {rational} piece(s) have vertices off the grid (intersections of face planes); they are written to the nearest double and snap back to the grid when loaded"
            ));
        }
        output::line(format_args!(
            "wrote {} (load and decompose {:.1} ms)",
            args.output.join("assembly.json").display(),
            seconds * 1e3
        ));
    }
    Ok(ExitCode::SUCCESS)
}

fn part_report(p: &Part) -> PartReport {
    PartReport {
        name: p.name.clone(),
        convex: p.convex,
        reflex_edges: p.reflex_edges,
        pieces: p.pieces.len(),
        decomposed: p.decomposed,
        declared_pieces: p.declared_pieces,
        rational_pieces: p
            .pieces
            .iter()
            .filter(|q| *q.den() != apart::kernel::Int::ONE)
            .count(),
    }
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

/// A piece's vertices in input units and its facets as polygons.
fn piece_mesh(p: &Polytope, grid: &Grid) -> (Vec<[f64; 3]>, Polygons) {
    let den = p.den();
    let vertices = p
        .vertices()
        .iter()
        .map(|v| {
            let c = v.to_ints();
            [0, 1, 2].map(|k| {
                let r = apart::kernel::Rational::new(c[k].clone(), den.clone());
                // Grid integer (exact when den divides it) times the step 2^e.
                let q = r.to_f64();
                if *den == apart::kernel::Int::ONE {
                    grid.to_units(int::to_i64(&c[k]).unwrap_or(0))
                } else {
                    q * grid.step()
                }
            })
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

fn write_off(path: &Path, vertices: &[[f64; 3]], faces: &Polygons) -> anyhow::Result<()> {
    let file = std::fs::File::create(path)
        .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))?;
    let mut w = std::io::BufWriter::new(file);
    off::write(&mut w, vertices, faces)
        .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))?;
    use std::io::Write;
    w.flush()
        .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))
}
