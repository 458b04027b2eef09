//! What every answer states about its input: the length unit, the tolerance it holds
//! under, the repairs made on load and the files not read. Parsing of `--units` and `--tolerance`.

use crate::Global;
use apart::assembly::{Assembly, Loaded, Tolerance};
use apart::mesh::repair::RepairReport;

use serde::Serialize;

/// Length units of input files.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Units {
    /// Metres.
    M,
    /// Centimetres.
    Cm,
    /// Millimetres.
    Mm,
    /// Micrometres.
    Um,
    /// Inches.
    In,
    /// Feet.
    Ft,
}

impl Units {
    /// The unit's symbol.
    pub fn symbol(self) -> &'static str {
        match self {
            Units::M => "m",
            Units::Cm => "cm",
            Units::Mm => "mm",
            Units::Um => "um",
            Units::In => "in",
            Units::Ft => "ft",
        }
    }

    /// The unit in metres.
    pub fn metres(self) -> f64 {
        match self {
            Units::M => 1.0,
            Units::Cm => 0.01,
            Units::Mm => 1e-3,
            Units::Um => 1e-6,
            Units::In => 0.0254,
            Units::Ft => 0.3048,
        }
    }

    fn from_symbol(s: &str) -> Option<Units> {
        [
            Units::M,
            Units::Cm,
            Units::Mm,
            Units::Um,
            Units::In,
            Units::Ft,
        ]
        .into_iter()
        .find(|u| u.symbol() == s || (s == "µm" && *u == Units::Um))
    }
}

/// Parses `--tolerance`: `auto`, or a positive length in input units, optionally with a
/// unit (`5um`, `0.01mm`, `1e-4in`), which needs `--units` to convert.
pub fn parse_tolerance(text: &str, units: Option<Units>) -> anyhow::Result<Tolerance> {
    let t = text.trim();
    if t.eq_ignore_ascii_case("auto") {
        return Ok(Tolerance::Auto);
    }
    let positive = |v: f64| {
        anyhow::ensure!(
            v.is_finite() && v > 0.0,
            "--tolerance must be a finite, positive length, not \"{text}\""
        );
        Ok(())
    };
    if let Ok(v) = t.parse::<f64>() {
        // Also "nan" and "inf", which would otherwise read as a number and a unit.
        positive(v)?;
        return Ok(Tolerance::Fixed(v));
    }
    let split = t
        .find(|c: char| c.is_ascii_alphabetic() && c != 'e' && c != 'E' || c == 'µ')
        .unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let v: f64 = number.trim().parse().map_err(|_| {
        anyhow::anyhow!("--tolerance \"{text}\" is neither `auto` nor a length such as 1e-6 or 5um")
    })?;
    positive(v)?;
    let unit = unit.trim();
    if unit.is_empty() {
        return Ok(Tolerance::Fixed(v));
    }
    let given = Units::from_symbol(unit).ok_or_else(|| {
        anyhow::anyhow!("--tolerance \"{text}\": unknown unit \"{unit}\" (m, cm, mm, um, in, ft)")
    })?;
    let input = units.ok_or_else(|| {
        anyhow::anyhow!(
            "--tolerance \"{text}\" names a unit: say which unit the input files use with --units"
        )
    })?;
    Ok(Tolerance::Fixed(v * given.metres() / input.metres()))
}

/// The tolerance asked for on the command line.
pub fn tolerance(global: &Global) -> anyhow::Result<Tolerance> {
    match &global.tolerance {
        None => Ok(Tolerance::None),
        Some(t) => parse_tolerance(t, global.units),
    }
}

/// Fails for a command that has no use for a tolerance (it would silently do nothing).
pub fn no_tolerance(global: &Global, command: &str) -> anyhow::Result<()> {
    anyhow::ensure!(
        global.tolerance.is_none(),
        "--tolerance does not apply to `apart {command}`: it is for check, partition, sequence and separate"
    );
    Ok(())
}

/// A length in input units, with the unit when known.
pub fn length(v: f64, units: Option<Units>) -> String {
    match units {
        Some(u) => format!("{v:.4e} {}", u.symbol()),
        None => format!("{v:.4e}"),
    }
}

/// The tolerance of an answer, as JSON.
#[derive(Serialize)]
pub struct ToleranceJson {
    /// Every convex piece was made at least this much smaller (input units).
    eps: f64,
    /// The same, exactly (a rational in input units).
    exact: String,
    /// Chosen by `--tolerance auto`.
    auto: bool,
    /// The deepest overlap between parts before shrinking (input units).
    deepest_overlap: f64,
    /// Pairs of parts whose overlap became contact.
    accepted_overlaps: usize,
    /// Pieces thinner than twice the tolerance that vanished.
    vanished_pieces: usize,
    /// The farthest any face moved inward (input units, at least `eps`).
    max_shift: f64,
}

/// Unit, tolerance and repairs, flattened into every command's JSON.
#[derive(Serialize)]
pub struct InputFacts {
    /// The unit of the input files, when given with `--units`.
    units: Option<&'static str>,
    /// The tolerance the answer holds under; null for the parts as given.
    tolerance: Option<ToleranceJson>,
    /// Every repair made on load, per mesh file.
    repairs: Vec<RepairJson>,
    /// Files and folders of the assembly folder that were not read, with the reason.
    skipped_files: Vec<SkippedJson>,
}

/// A file not read, as JSON.
#[derive(Serialize)]
pub struct SkippedJson {
    #[serde(serialize_with = "apart::mesh::path_text")]
    file: std::path::PathBuf,
    reason: String,
}

/// The repairs of one mesh file, as JSON.
#[derive(Serialize)]
pub struct RepairJson {
    #[serde(serialize_with = "apart::mesh::path_text")]
    file: std::path::PathBuf,
    parts: Vec<String>,
    #[serde(flatten)]
    counts: RepairReport,
}

impl InputFacts {
    /// The facts of a loaded assembly.
    pub fn of(loaded: &Loaded, global: &Global) -> InputFacts {
        let asm = &loaded.assembly;
        InputFacts {
            repairs: loaded
                .repairs
                .iter()
                .map(|r| RepairJson {
                    file: r.file.clone(),
                    parts: r.parts.clone(),
                    counts: r.report.clone(),
                })
                .collect(),
            skipped_files: loaded
                .skipped
                .iter()
                .map(|s| SkippedJson {
                    file: s.path.clone(),
                    reason: s.reason.clone(),
                })
                .collect(),
            units: global.units.map(Units::symbol),
            tolerance: asm.tolerance.as_ref().map(|t| ToleranceJson {
                eps: t.eps,
                exact: t.exact.to_string(),
                auto: t.auto,
                deepest_overlap: t.deepest_overlap,
                accepted_overlaps: t.accepted_overlaps,
                vanished_pieces: t.vanished_pieces,
                max_shift: t.max_shift,
            }),
        }
    }
}

/// A motion found by a planner (the library's [`apart::plan::along::Motion`]).
pub type Motion<'a> = apart::plan::along::Motion<'a>;

/// [`apart::plan::along::holds_without_tolerance`], with the CLI's error type.
pub fn holds_without_tolerance(
    asm: &Assembly,
    motions: &[Motion],
) -> anyhow::Result<Option<Vec<bool>>> {
    Ok(apart::plan::along::holds_without_tolerance(asm, motions)?)
}

/// The sentence every text answer under a tolerance ends with; `None` without one.
pub fn tolerance_statement(asm: &Assembly, global: &Global) -> Option<String> {
    let t = asm.tolerance.as_ref()?;
    let by = if t.max_shift > t.eps * (1.0 + 1e-9) {
        format!(
            "by {} to {}",
            length(t.eps, global.units),
            length(t.max_shift, global.units)
        )
    } else {
        format!("by {}", length(t.eps, global.units))
    };
    Some(format!(
        "tolerance: this answer holds for parts made {} smaller{} (every convex piece's faces moved inward {by}; overlaps up to a depth of {} count as contact)",
        length(t.eps, global.units),
        if t.auto { ", the smallest tolerance that makes the assembly valid (--tolerance auto)" } else { "" },
        length(2.0 * t.eps, global.units),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tolerance_values() {
        assert_eq!(parse_tolerance("auto", None).unwrap(), Tolerance::Auto);
        assert_eq!(
            parse_tolerance("1e-6", None).unwrap(),
            Tolerance::Fixed(1e-6)
        );
        // 5 µm in a millimetre file is 0.005 input units.
        match parse_tolerance("5um", Some(Units::Mm)).unwrap() {
            Tolerance::Fixed(v) => assert!((v - 0.005).abs() < 1e-15, "{v}"),
            t => panic!("{t:?}"),
        }
        assert_eq!(
            parse_tolerance("0.001 in", Some(Units::In)).unwrap(),
            Tolerance::Fixed(0.001)
        );
        assert!(parse_tolerance("5um", None).is_err());
        assert!(parse_tolerance("-1", None).is_err());
        assert!(parse_tolerance("0", None).is_err());
        assert!(parse_tolerance("nan", None).is_err());
        assert!(parse_tolerance("3parsecs", Some(Units::Mm)).is_err());
        assert!(parse_tolerance("", None).is_err());
    }
}
