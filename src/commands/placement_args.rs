//! What `apart place` and `apart stack` share: the paper they cite, the picture flags,
//! exact grid values parsed from the command line, the part to place as a placement
//! model, and the JSON of exact values and of the placement engine's counters.

use crate::output;
use apart::assembly::Assembly;
use apart::draw::View;
use apart::kernel::Rational;
use apart::stack::orientation::{Base, Orientation};
use apart::stack::part::PartModel;
use apart::stack::partial::{ObstacleStats, PlaceStats};
use serde::Serialize;
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

/// Counters shared by the JSON of `place` and `stack`.
#[derive(Serialize)]
pub struct StatsJson {
    orientations_considered: usize,
    pairs_total: u64,
    pairs_evaluated: u64,
    interference_tests: u64,
    cells: u64,
    qps: u64,
    obstacles_fresh: u64,
    obstacles_extrapolated: u64,
    /// Where the time went.
    pub seconds: StatsSeconds,
}

/// Seconds of a placement, in all and by phase.
#[derive(Serialize)]
pub struct StatsSeconds {
    /// Wall-clock seconds of the whole command.
    pub total: f64,
    detect: f64,
    cells: f64,
    obstacles: f64,
    extrapolation: f64,
}

/// The counters as JSON.
pub fn stats_json(p: &PlaceStats, o: &ObstacleStats, seconds: f64) -> StatsJson {
    StatsJson {
        orientations_considered: p.orientations_considered,
        pairs_total: p.pairs_total,
        pairs_evaluated: p.pairs_evaluated,
        interference_tests: p.interference_tests,
        cells: p.cells,
        qps: p.qps,
        obstacles_fresh: o.fresh,
        obstacles_extrapolated: o.extrapolated,
        seconds: StatsSeconds {
            total: seconds,
            detect: p.detect_seconds,
            cells: p.cells_seconds,
            obstacles: o.fresh_seconds,
            extrapolation: o.extrapolate_seconds,
        },
    }
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

/// A value given in input units, exactly in grid units (`h` is a power of two).
pub fn grid_value(v: f64, h: f64, flag: &str) -> anyhow::Result<Rational> {
    Rational::from_f64(v / h).ok_or_else(|| anyhow::anyhow!("{flag} {v} is not a finite number"))
}

/// The exact turn about z as its rational cosine and sine, `["a/c", "b/c"]`.
pub fn exact_rotation(o: &Orientation) -> [String; 2] {
    let t = o.theta;
    [format!("{}/{}", t.a, t.c), format!("{}/{}", t.b, t.c)]
}

/// A grid-unit rational in input units, as `f64`.
pub fn qunits(v: &Rational, h: f64) -> f64 {
    v.to_f64() * h
}

/// A grid-unit rational in input units, exactly (`h` is a power of two).
pub fn exact_units(v: &Rational, h: f64) -> String {
    let step = Rational::from_f64(h).expect("the grid step is a finite power of two");
    (v * &step).to_string()
}

/// The part named `name` (or the only part) of a loaded assembly, as a placement model.
pub fn load_part(asm: &Assembly, name: Option<&str>, path: &Path) -> anyhow::Result<PartModel> {
    let k = match name {
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
    };
    model_of(asm, k)
}

/// Part `k` of a loaded assembly as a placement model (its pieces and its mesh).
pub fn model_of(asm: &Assembly, k: usize) -> anyhow::Result<PartModel> {
    let part = &asm.parts[k];
    let mut model = PartModel::from_pieces(&part.name, part.pieces.clone())
        .map_err(|e| anyhow::anyhow!("part \"{}\": {e}", part.name))?;
    model.mesh = part.mesh.as_ref().map(|m| {
        (
            m.vertices
                .iter()
                .map(|&v| apart::kernel::Vec3::from(v))
                .collect(),
            m.triangles.clone(),
        )
    });
    Ok(model)
}

/// `100 a / b`, 0 for an empty total.
pub fn percent(a: u64, b: u64) -> f64 {
    if b == 0 {
        0.0
    } else {
        100.0 * a as f64 / b as f64
    }
}
