//! `apart separate`: every direction along which part A leaves part B, as exact
//! spherical regions, sliding arcs and isolated directions, with the free area and the
//! direction of largest clearance. Exit code 0 when A can leave B, 2 when it cannot.

use crate::commands::load::{
    closest_names, load_valid, load_valid_named, load_with, named_files, part_index,
};
use crate::input_facts::{tolerance_statement, Units};
use crate::output;
use crate::{limits, Global};
use apart::assembly::Decompose;
use apart::formats::escape::escape;
use apart::jobs::Progress;
use apart::plan::Separation;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `apart separate`.
#[derive(clap::Args, Debug)]
pub struct SeparateArgs {
    /// Either an assembly and two part names (`ASSEMBLY A B`: A moves, B stays), or two
    /// mesh files (`A.off B.stl`), each one part in the same coordinates.
    #[arg(num_args = 2..=3, required = true, value_names = ["ASSEMBLY|A_FILE", "A|B_FILE", "B"])]
    pub inputs: Vec<String>,
}

/// Runs the command.
pub fn run(args: &SeparateArgs, global: &Global) -> anyhow::Result<ExitCode> {
    let (path, a_name, b_name, named) = match args.inputs.as_slice() {
        [asm, a, b] => (PathBuf::from(asm), a.clone(), b.clone(), None),
        [asm, a] if is_assembly(asm) => return Err(one_name_missing(asm, a, global)),
        [a, b] if std::path::Path::new(a).is_file() && !std::path::Path::new(b).exists() => {
            anyhow::bail!(
                "{}: no such file; to separate two parts of the one file {}, name both (apart separate {} A B)",
                escape(b),
                escape(a),
                escape(a)
            )
        }
        [a, b] => {
            let named = named_files(&[a, b])?;
            let [na, nb]: [String; 2] = named.names().to_vec().try_into().expect("two names");
            (PathBuf::new(), na, nb, Some(named))
        }
        _ => anyhow::bail!("give an assembly and two part names, or two mesh files"),
    };
    let loaded = match &named {
        Some(named) => load_valid_named(named, global, None)?,
        None => load_valid(&path, global)?,
    };
    let asm = &loaded.assembly;
    anyhow::ensure!(
        asm.parts.len() >= 2,
        "separate needs two parts, and {} has only one (\"{}\"): nothing to separate",
        args.inputs[0],
        asm.parts.first().map_or("", |p| p.name.as_str())
    );
    let (a, b) = (part_index(asm, &a_name, "")?, part_index(asm, &b_name, "")?);
    anyhow::ensure!(a != b, "the two parts must differ");
    let answer = {
        // Not stoppable: a timeout ends the run where it is, as while loading.
        let _phase = output::phase(global, "pair regions");
        let units = global.units.map(Units::symbol);
        apart::jobs::separate::separate(&loaded, units, a, b, &Progress::new())
            .map_err(|e| limits::job_error(e, global))?
            .ok_or_else(|| anyhow::anyhow!("stopped before an answer"))?
    };
    let separable = answer.separable;
    if global.json {
        output::json(&answer)?;
    } else {
        print_text(&answer.separation, &a_name, &b_name);
        if answer.best.as_ref().and_then(|b| b.holds_without_tolerance) == Some(false) {
            output::line("the best direction holds only under the tolerance");
        }
        if let Some(t) = tolerance_statement(asm, global) {
            output::line(t);
        }
    }
    Ok(if separable {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(2)
    })
}

/// True when `input` names an assembly rather than one mesh file: a folder or a
/// manifest.
fn is_assembly(input: &str) -> bool {
    let p = std::path::Path::new(input);
    p.is_dir()
        || p.extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("json"))
}

/// The error for `apart separate ASSEMBLY A` (one part name forgotten): it says what is
/// missing and, when the assembly loads, which parts the other name can be.
fn one_name_missing(asm: &str, a: &str, global: &Global) -> anyhow::Error {
    let mut msg = format!(
        "one part name is missing: `apart separate ASSEMBLY A B` takes the part that moves (A) and the part that stays (B), and only \"{}\" follows {}",
        escape(a),
        escape(asm)
    );
    // Decomposition is skipped: only the names are wanted.
    if let Ok(loaded) = load_with(std::path::Path::new(asm), global, Decompose::Never) {
        let names: Vec<&str> = loaded
            .assembly
            .parts
            .iter()
            .map(|p| p.name.as_str())
            .collect();
        if names.contains(&a) {
            let others: Vec<String> = names
                .iter()
                .filter(|n| **n != a)
                .map(|n| format!("\"{}\"", escape(n)))
                .collect();
            msg.push_str(&format!(". The other part can be {}", others.join(" or ")));
        } else {
            msg.push_str(&format!(
                ". \"{}\" is no part of it either{}",
                escape(a),
                closest_names(a, &names)
            ));
        }
    }
    anyhow::anyhow!(msg)
}

fn point(v: &apart::kernel::Vec3) -> String {
    let c = v.to_strings();
    format!("({}, {}, {})", c[0], c[1], c[2])
}

fn print_text(s: &Separation, a: &str, b: &str) {
    let pct = |x: f64| format!("{:.4}%", 100.0 * x);
    if s.faces.is_empty() && s.sliding.is_empty() && s.isolated.is_empty() {
        output::line(format_args!(
            "\"{a}\" cannot leave \"{b}\" by any single translation"
        ));
        return;
    }
    output::line(format_args!(
        "\"{a}\" leaves \"{b}\" along {} of the sphere of directions",
        pct(s.area_fraction())
    ));
    if let Some((d, c)) = s.best() {
        output::line(format_args!(
            "best direction {} ≈ {}, clearance {c:.2}°",
            point(&d),
            output::unit(&d.unit_f64())
        ));
    }
    for (k, f) in s.faces.iter().enumerate() {
        output::line(format_args!(
            "region {}: {} of the sphere, deepest direction {} ({:.2}° clearance), {} boundary loop{}",
            k + 1,
            pct(f.area / (4.0 * std::f64::consts::PI)),
            point(&f.direction),
            f.clearance_deg,
            f.loops.len(),
            if f.loops.len() == 1 { "" } else { "s" }
        ));
        for lp in &f.loops {
            let corners: Vec<String> = lp.iter().map(|arc| point(&arc.start)).collect();
            output::line(format_args!("  corners: {}", corners.join(" -> ")));
        }
    }
    for arc in &s.sliding {
        output::line(format_args!(
            "sliding arc from {} to {} on the circle with normal {}",
            point(&arc.start),
            point(&arc.end),
            point(&arc.normal)
        ));
    }
    for d in &s.isolated {
        output::line(format_args!(
            "isolated direction {} ≈ {}",
            point(d),
            output::unit(&d.unit_f64())
        ));
    }
}
