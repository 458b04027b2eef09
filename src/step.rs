//! STEP files on the command line: `apart check model.step` hands the file to the
//! Python package's reader (`apart.step.emit`, OpenCASCADE through OCP) in a child
//! Python and loads the parts it prints, so that the assembly is the one
//! `apart.load("model.step")` gives: same solids, placement, names, tessellation and
//! unit. No file is written: the parts come back on the child's standard output as JSON
//! (coordinates as the bit patterns of doubles, so not one bit changes on the way).

use crate::input_facts::Units;
use crate::Global;
use apart::assembly::{DescribedPart, Description, MeshSource};
use apart::formats::escape::path as escaped;
use std::path::Path;
use std::process::{Command, Stdio};

/// The environment variable naming the Python to run (default `python3`).
pub const PYTHON_VAR: &str = "APART_PYTHON";

/// The one command that installs what reading a STEP file needs (from the source
/// folder of apart).
pub const INSTALL: &str = "pip install './python[step]'";

/// The unit of a STEP file's parts when `--units` names none: OpenCASCADE's.
pub const DEFAULT_UNITS: Units = Units::Mm;

/// The child's exit status when the Python lacks the `apart` package, its `step`
/// module's reader, or OCP (as `apart.step.EXIT_NEEDS_EXTRA`).
const NEEDS_EXTRA: i32 = 3;

/// Run by the child Python with the arguments after it.
const BOOT: &str = "\
import sys
try:
    from apart.step import emit
except ImportError as e:
    sys.stderr.write(f'{e}\\n')
    sys.exit(3)
sys.exit(emit(sys.argv[1:]))
";

/// True for a path with the extension `.step` or `.stp` (any case) that is not a
/// folder.
pub fn is_step(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("step") || e.eq_ignore_ascii_case("stp"))
        && !path.is_dir()
}

/// What the child prints.
#[derive(serde::Deserialize)]
struct Converted {
    name: String,
    parts: Vec<ConvertedPart>,
}

#[derive(serde::Deserialize)]
struct ConvertedPart {
    name: String,
    /// 3n coordinates, each an `f64`'s bits.
    vertices: Vec<u64>,
    /// 3m vertex indices.
    triangles: Vec<u32>,
}

/// The Python to run, and how messages name it.
fn python() -> (String, String) {
    match std::env::var(PYTHON_VAR) {
        Ok(p) if !p.is_empty() => (p.clone(), format!("{PYTHON_VAR}={p}")),
        _ => ("python3".into(), "python3".into()),
    }
}

/// The message when the Python cannot read STEP files: what is missing and the command
/// that installs it.
fn needs_extra(file: &str, which: &str, why: &str) -> anyhow::Error {
    anyhow::anyhow!(
        "{file}: reading a STEP file needs Python with the apart package and its step extra \
         (OpenCASCADE): install them with `{INSTALL}` (in apart's source folder), or set \
         {PYTHON_VAR} to a Python that has them ({which}: {why})"
    )
}

/// The STEP file `path` as an assembly description, read by the Python package with the
/// tessellation and unit options of `global` (`--units` default millimetres).
pub fn description(path: &Path, global: &Global) -> anyhow::Result<Description> {
    let file = escaped(path);
    let (exe, which) = python();
    let mut cmd = Command::new(&exe);
    cmd.arg("-c").arg(BOOT).arg(path);
    if let Some(l) = global.chordal_tolerance {
        cmd.arg("--chordal-tolerance").arg(format!("{l:?}"));
    }
    if let Some(a) = global.angular_tolerance {
        cmd.arg("--angular-tolerance").arg(format!("{a:?}"));
    }
    cmd.arg("--units")
        .arg(global.units.unwrap_or(DEFAULT_UNITS).symbol());
    cmd.stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let out = match cmd.output() {
        Ok(out) => out,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(needs_extra(&file, &which, "no such program"))
        }
        Err(e) => return Err(needs_extra(&file, &which, &format!("cannot run it: {e}"))),
    };
    let stderr = String::from_utf8_lossy(&out.stderr);
    let last = stderr
        .lines()
        .rev()
        .map(str::trim)
        .find(|l| !l.is_empty())
        .unwrap_or("")
        .to_string();
    match out.status.code() {
        Some(0) => {}
        Some(NEEDS_EXTRA) => return Err(needs_extra(&file, &which, &last)),
        Some(code) => {
            let why = if last.is_empty() {
                format!("the STEP reader ({which}) failed with exit status {code}")
            } else {
                last
            };
            // The reader's own messages name the file as given; others get it in front.
            let given = path.to_string_lossy();
            return Err(if why.contains(given.as_ref()) {
                anyhow::anyhow!("{why}")
            } else {
                anyhow::anyhow!("{file}: {why}")
            });
        }
        None => anyhow::bail!("{file}: the STEP reader ({which}) was stopped by a signal"),
    }
    let converted: Converted = serde_json::from_slice(&out.stdout).map_err(|e| {
        anyhow::anyhow!("{file}: the STEP reader ({which}) printed no assembly apart reads ({e})")
    })?;
    let mut parts = Vec::with_capacity(converted.parts.len());
    for p in converted.parts {
        anyhow::ensure!(
            p.vertices.len() % 3 == 0 && p.triangles.len() % 3 == 0,
            "{file}: the STEP reader ({which}) printed part \"{}\" with a coordinate or index count that is not a multiple of 3",
            p.name
        );
        let vertices = p
            .vertices
            .chunks_exact(3)
            .map(|c| [0, 1, 2].map(|k| f64::from_bits(c[k])))
            .collect();
        let triangles = p
            .triangles
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect();
        parts.push(DescribedPart::new(
            p.name,
            MeshSource::Arrays {
                vertices,
                triangles,
            },
        ));
    }
    Ok(Description {
        name: converted.name,
        parts,
    })
}

/// Fails when `--chordal-tolerance` or `--angular-tolerance` is given for an input that
/// is not a STEP file (they would silently do nothing).
pub fn no_tessellation(global: &Global) -> anyhow::Result<()> {
    anyhow::ensure!(
        global.chordal_tolerance.is_none() && global.angular_tolerance.is_none(),
        "--chordal-tolerance and --angular-tolerance apply to STEP files (.step, .stp) only"
    );
    Ok(())
}

/// `--chordal-tolerance`: a finite, positive length.
pub fn chordal(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("must be a finite, positive length, not {text}")),
    }
}

/// `--angular-tolerance`: an angle in (0, pi] radians.
pub fn angular(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v > 0.0 && v <= std::f64::consts::PI => Ok(v),
        _ => Err(format!("must be an angle in (0, pi] radians, not {text}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_files_by_extension() {
        assert!(is_step(Path::new("a/gearbox.step")));
        assert!(is_step(Path::new("PIN.STP")));
        assert!(!is_step(Path::new("a.stl")));
        assert!(!is_step(Path::new("step")));
    }

    #[test]
    fn tessellation_values() {
        assert_eq!(chordal("0.01"), Ok(0.01));
        assert!(chordal("0").is_err() && chordal("-1").is_err() && chordal("inf").is_err());
        assert_eq!(angular("0.5"), Ok(0.5));
        assert!(angular("0").is_err() && angular("4").is_err() && angular("nan").is_err());
    }
}
