//! The length unit and the tolerance of the command line: parsing of `--units` and
//! `--tolerance`, and the sentence a text answer under a tolerance ends with (the
//! JSON's facts are the jobs' `InputFacts`).

use crate::Global;
use apart::assembly::{Assembly, Tolerance};

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
