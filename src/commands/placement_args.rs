//! What `apart place` and `apart stack` share: the paper they cite, the picture flags,
//! the numbers and base orientations parsed from the command line, and the part named.

use crate::output;
use apart::assembly::Assembly;
use apart::draw::View;
use apart::stack::orientation::Base;
use std::path::{Path, PathBuf};

/// The paper whose eq. (1) `place --weight` and `stack` minimize, cited in full in their
/// `--help` (and in the README's references, as paper 004).
pub const STACKING_PAPER: &str = "\
Reference (eq. (1), partial c-space obstacles, extrapolation between orientations):
  V. R. Ayyadevara, D. A. Bourne, K. Shimada and R. H. Sturges, Jr., \"Interference-free
  polyhedral configurations for stacking\", journal paper, manuscript received
  August 7, 2000, revised September 1, 2001; usually cited as IEEE Transactions on
  Robotics and Automation 18(2):147-165, 2002 (the README's reference [004] says which
  of these details the paper itself prints).";

/// Picture flags shared by `place` and `stack`.
#[derive(clap::Args, Debug)]
pub struct PictureArgs {
    /// Write a PNG render (drawn without a GPU).
    #[arg(long, value_name = "FILE")]
    pub png: Option<PathBuf>,
    /// Write an SVG drawing.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
}

impl PictureArgs {
    /// Refuses a picture path that would overwrite one of the `inputs`.
    pub fn check(&self, inputs: &output::Inputs) -> anyhow::Result<()> {
        for (flag, p) in [("--png", &self.png), ("--svg", &self.svg)] {
            if let Some(p) = p {
                inputs.check_file(flag, p)?;
            }
        }
        Ok(())
    }
}

/// Writes the requested pictures; `draw(view, width, height, svg)` makes the bytes.
pub fn write_pictures(
    args: &PictureArgs,
    draw: impl Fn(&View, u32, u32, bool) -> Vec<u8>,
) -> anyhow::Result<()> {
    let view = View::default();
    if let Some(p) = &args.png {
        output::write_file(p, draw(&view, 1000, 750, false))?;
    }
    if let Some(p) = &args.svg {
        output::write_file(p, draw(&view, 1000, 750, true))?;
    }
    Ok(())
}

/// Parses `n` comma-separated finite numbers.
pub fn parse_numbers(text: &str, n: usize, flag: &str) -> anyhow::Result<Vec<f64>> {
    let v: Vec<f64> = text
        .split(',')
        .map(|s| s.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| anyhow::anyhow!("{flag} \"{text}\" is not {n} comma-separated numbers"))?;
    anyhow::ensure!(
        v.len() == n,
        "{flag} \"{text}\" needs {n} comma-separated numbers"
    );
    anyhow::ensure!(
        v.iter().all(|x| x.is_finite()),
        "{flag} \"{text}\" has a non-finite number"
    );
    Ok(v)
}

/// Parses base orientations "PHI,PSI" in degrees (multiples of 90).
pub fn parse_bases(texts: &[String]) -> anyhow::Result<Vec<Base>> {
    texts
        .iter()
        .map(|t| {
            let v = parse_numbers(t, 2, "--base")?;
            let quarter = |d: f64| -> anyhow::Result<u8> {
                anyhow::ensure!(
                    d.rem_euclid(90.0) == 0.0,
                    "--base \"{t}\": angles must be multiples of 90 degrees"
                );
                Ok((d / 90.0).rem_euclid(4.0) as u8)
            };
            Ok(Base {
                phi: quarter(v[0])?,
                psi: quarter(v[1])?,
            })
        })
        .collect()
}

/// The index of the part named `name` (or of the only part) of a loaded assembly.
pub fn part_index(asm: &Assembly, name: Option<&str>, path: &Path) -> anyhow::Result<usize> {
    Ok(match name {
        Some(n) => asm
            .parts
            .iter()
            .position(|p| p.name == n)
            .ok_or_else(|| anyhow::anyhow!("{} has no part named \"{n}\"", path.display()))?,
        None => {
            anyhow::ensure!(
                asm.parts.len() == 1,
                "{} holds {} parts; name the one to use with --part-name",
                path.display(),
                asm.parts.len()
            );
            0
        }
    })
}

/// `100 a / b`, 0 for an empty total.
pub fn percent(a: u64, b: u64) -> f64 {
    if b == 0 {
        0.0
    } else {
        100.0 * a as f64 / b as f64
    }
}
