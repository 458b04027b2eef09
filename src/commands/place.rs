//! `apart place`: interference-free positions of a new part among fixed parts, cheapest
//! first (Ayyadevara et al. 2002, [`STACKING_PAPER`]): exact c-space obstacles of the interfering piece pairs only, free
//! space as convex cells, the squared distance to a desired position minimized exactly in
//! each cell, over discrete orientations about z. Exit code 0 when a position was found,
//! 2 when the part fits nowhere in the region.

use crate::commands::load::{load_valid_but, load_valid_named, named_files};
use crate::commands::placement_args::{
    parse_bases, parse_numbers, percent, write_pictures, PictureArgs, STACKING_PAPER,
};
use crate::output;
use crate::{limits, Global};
use apart::jobs::place::{place, PlaceAnswer, PlaceJobOptions};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Arguments of `apart place`.
#[derive(clap::Args, Debug)]
#[command(after_help = STACKING_PAPER)]
pub struct PlaceArgs {
    /// Either an assembly and the name of the part to place (`ASSEMBLY NAME`: every
    /// other part is fixed), or two mesh files (`FIXED.stl NEW.off`, in the same
    /// coordinates).
    #[arg(num_args = 2, required = true, value_name = "INPUT")]
    pub inputs: Vec<String>,
    /// Desired translation p_d "X,Y,Z" of the new part from where it is given (input
    /// units); the cost is |p − p_d|².
    #[arg(
        long,
        default_value = "0,0,0",
        value_name = "X,Y,Z",
        allow_hyphen_values = true,
        value_parser = limits::three_numbers
    )]
    pub target: String,
    /// Minimize eq. (1) of Ayyadevara et al. 2002 (reference below) with this weight in
    /// [0, 1] instead of the distance to --target: w times the spread of the part's vertices about the floor point in x
    /// and y, plus (1 − w) times the height of its centre of gravity above it.
    #[arg(long, value_name = "W", value_parser = limits::weight, allow_negative_numbers = true)]
    pub weight: Option<f64>,
    /// The floor point (x0, y0, z0) of eq. (1), with --weight.
    #[arg(
        long,
        default_value = "0,0,0",
        value_name = "X,Y,Z",
        allow_hyphen_values = true,
        value_parser = limits::three_numbers
    )]
    pub floor_point: String,
    /// Box "X0,Y0,Z0,X1,Y1,Z1" the whole placed part must lie in. Default: the bounding
    /// box of all parts grown by the new part's size on every side.
    #[arg(
        long,
        value_name = "X0,Y0,Z0,X1,Y1,Z1",
        conflicts_with = "translations",
        allow_hyphen_values = true,
        value_parser = limits::box_numbers
    )]
    pub region: Option<String>,
    /// Box "X0,Y0,Z0,X1,Y1,Z1" of allowed translations instead (Ω itself; Z0 = Z1 asks
    /// for positions in a plane).
    #[arg(long, value_name = "X0,Y0,Z0,X1,Y1,Z1", allow_hyphen_values = true, value_parser = limits::box_numbers)]
    pub translations: Option<String>,
    /// Step of the orientations about z, in degrees from 0.1 to 360 (360: keep the part
    /// as given).
    #[arg(long, default_value_t = 360.0, value_name = "DEG", value_parser = limits::dtheta, allow_negative_numbers = true)]
    pub dtheta: f64,
    /// A base orientation "PHI,PSI" (multiples of 90 degrees about x, then y) to try;
    /// repeat for several. Default: the part as given.
    #[arg(long = "base", value_name = "PHI,PSI", allow_hyphen_values = true, value_parser = limits::base)]
    pub bases: Vec<String>,
    /// Clearance kept from the fixed parts (robot positioning error, input units), 0 or
    /// more.
    #[arg(long, value_name = "C", value_parser = limits::nonnegative, allow_negative_numbers = true)]
    pub clearance: Option<f64>,
    /// Number of candidate positions to list (one per free-space cell, cheapest first),
    /// 1 to 1000.
    #[arg(long, default_value_t = 5, value_name = "K", value_parser = limits::candidates, allow_negative_numbers = true)]
    pub candidates: usize,
    #[command(flatten)]
    pub pictures: PictureArgs,
}

/// Runs the command.
pub fn run(args: &PlaceArgs, global: &Global) -> anyhow::Result<ExitCode> {
    crate::input_facts::no_tolerance(global, "place")?;
    let start = std::time::Instant::now();
    let (path, name, named) = match args.inputs.as_slice() {
        [asm, name] if !Path::new(name).is_file() => (PathBuf::from(asm), name.clone(), None),
        [fixed, new] => {
            let named = named_files(&[fixed, new])?;
            (PathBuf::from(fixed), named.names()[1].clone(), Some(named))
        }
        _ => anyhow::bail!("give an assembly and a part name, or two mesh files"),
    };
    let loaded = match &named {
        Some(named) => load_valid_named(named, global, Some(&name))?,
        None => load_valid_but(&path, global, Some(&name))?,
    };
    let mut inputs = output::Inputs::of(&path, &loaded);
    for given in &args.inputs {
        inputs.add(Path::new(given));
    }
    args.pictures.check(&inputs)?;
    let asm = &loaded.assembly;
    let part = asm
        .parts
        .iter()
        .position(|p| p.name == name)
        .ok_or_else(|| anyhow::anyhow!("the assembly has no part named \"{name}\""))?;
    let opts = options(args, part)?;
    let run = {
        let _phase = output::phase(global, "placement");
        place(&loaded, &opts).map_err(|e| limits::job_error(e, global))?
    };
    let mut answer = run.answer;
    answer.stats.seconds.total = start.elapsed().as_secs_f64();
    if let Some(best) = run.best {
        let h = answer.grid_step;
        write_pictures(&args.pictures, |view, w, hgt, svg| {
            let (shapes, names) = apart::draw::stack_render::scene_shapes(
                &run.scene,
                &answer.fixed,
                &[(answer.moving.clone(), best.clone())],
                h,
            );
            if svg {
                apart::draw::shapes_svg(&shapes, &names, view, w, hgt).into_bytes()
            } else {
                apart::draw::shapes_png(&shapes, &names, &[], view, w, hgt)
            }
        })?;
    }
    if global.json {
        output::json(&answer)?;
    } else {
        print_text(&answer);
    }
    Ok(if answer.candidates.is_empty() {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    })
}

/// The job's options from the command line's, for part `part`.
fn options(args: &PlaceArgs, part: usize) -> anyhow::Result<PlaceJobOptions> {
    let boxed = |text: &str, flag: &str| -> anyhow::Result<[f64; 6]> {
        let v = parse_numbers(text, 6, flag)?;
        anyhow::ensure!(
            (0..3).all(|i| v[i] <= v[i + 3]),
            "{flag} \"{text}\" is empty (a low corner above the high one)"
        );
        Ok([v[0], v[1], v[2], v[3], v[4], v[5]])
    };
    let three = |text: &str, flag: &str| -> anyhow::Result<[f64; 3]> {
        let v = parse_numbers(text, 3, flag)?;
        Ok([v[0], v[1], v[2]])
    };
    if let Some(w) = args.weight {
        anyhow::ensure!((0.0..=1.0).contains(&w), "--weight {w} is not in [0, 1]");
    }
    Ok(PlaceJobOptions {
        part,
        target: three(&args.target, "--target")?,
        weight: args.weight,
        floor_point: three(&args.floor_point, "--floor-point")?,
        region: args
            .region
            .as_deref()
            .map(|r| boxed(r, "--region"))
            .transpose()?,
        translations: args
            .translations
            .as_deref()
            .map(|t| boxed(t, "--translations"))
            .transpose()?,
        dtheta: args.dtheta,
        bases: (!args.bases.is_empty())
            .then(|| parse_bases(&args.bases))
            .transpose()?,
        clearance: args.clearance,
        candidates: args.candidates,
    })
}

fn print_text(j: &PlaceAnswer) {
    let cost = match j.weight {
        Some(w) => format!("cost eq. (1) with w = {w}"),
        None => format!(
            "target translation ({}, {}, {})",
            j.target[0], j.target[1], j.target[2]
        ),
    };
    output::line(format!(
        "place {} among {} fixed part{}, {cost}",
        j.moving,
        j.fixed.len(),
        if j.fixed.len() == 1 { "" } else { "s" },
    ));
    if j.candidates.is_empty() {
        output::line("no interference-free position in the region");
    }
    for (k, c) in j.candidates.iter().enumerate() {
        let [phi, psi, theta] = c.rotation_deg;
        let turn = if phi == 0.0 && psi == 0.0 {
            format!("turn {theta:.2} deg")
        } else {
            format!("rotation x {phi}, y {psi}, z {theta:.2} deg")
        };
        output::line(format!(
            "{:>3}. translation ({}, {}, {})  {turn}  cost {:.6}",
            k + 1,
            c.translation[0],
            c.translation[1],
            c.translation[2],
            c.cost
        ));
    }
    let s = &j.stats;
    output::line(format!(
        "piece pairs evaluated {} of {} ({:.2}%), {} orientations, {:.3} s",
        s.pairs_evaluated,
        s.pairs_total,
        percent(s.pairs_evaluated, s.pairs_total),
        s.orientations_considered,
        s.seconds.total
    ));
}
