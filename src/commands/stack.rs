//! `apart stack <part>`: a stack of identical parts on a floor region (Ayyadevara et
//! al. 2002, [`STACKING_PAPER`](crate::commands::placement_args::STACKING_PAPER)): each
//! part placed by the exact placement engine with the cost of eq. (1), accepted only if
//! stable, grippable from above and lowerable along −z. Exit code 0 when every part was
//! placed, 2 when the stack is incomplete, 3 when `--timeout` stopped the run (the parts
//! placed until then are printed; 130 after Ctrl-C, 1 after the memory budget, with
//! the same partial answer).

use crate::commands::load::load_valid;
use crate::commands::placement_args::{
    parse_bases, parse_numbers, part_index, percent, write_pictures, PictureArgs,
};
use crate::limits::Stopped;
use crate::output;
use crate::{limits, Global};
use apart::jobs::stack::{stack, StackAnswer, StackJobOptions, Support};
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `apart stack`.
#[derive(clap::Args, Debug)]
#[command(after_help = crate::commands::placement_args::STACKING_PAPER)]
pub struct StackArgs {
    /// The part: a mesh file, or an assembly with one part (or pick one with --part-name).
    pub part: PathBuf,
    /// The part to stack when the input holds several.
    #[arg(long, value_name = "NAME")]
    pub part_name: Option<String>,
    /// Number of parts to stack, 1 to 1000 (the time grows about with the cube of the
    /// count: 400 cubes take 46 s, 1000 several minutes).
    #[arg(long, short = 'n', default_value_t = 10, value_parser = limits::stack_count, allow_negative_numbers = true)]
    pub count: usize,
    /// Weight w of eq. (1) of Ayyadevara et al. 2002 (reference below) in [0, 1]: 0 keeps
    /// the stack low, 1 keeps its footprint small.
    #[arg(long, short = 'w', default_value_t = 0.5, value_parser = limits::weight, allow_negative_numbers = true)]
    pub weight: f64,
    /// Floor region "X0,Y0,X1,Y1" (input units); its centre is eq. (1)'s (x0, y0).
    /// Default: a square centred on the origin with room for all parts side by side.
    #[arg(long, value_name = "X0,Y0,X1,Y1", allow_hyphen_values = true, value_parser = limits::floor_box)]
    pub floor: Option<String>,
    /// Height of the floor (eq. (1)'s z0), any finite number.
    #[arg(
        long,
        default_value_t = 0.0,
        value_name = "Z0",
        allow_hyphen_values = true,
        value_parser = limits::number
    )]
    pub floor_z: f64,
    /// Maximum height of the stack above the floor, more than 0 (default: count × part
    /// height).
    #[arg(long, value_name = "H", value_parser = limits::positive_length, allow_negative_numbers = true)]
    pub max_height: Option<f64>,
    /// Step of the orientations about z, in degrees from 0.1 to 360 (360: never turn the
    /// part).
    #[arg(long, default_value_t = 90.0, value_name = "DEG", value_parser = limits::dtheta, allow_negative_numbers = true)]
    pub dtheta: f64,
    /// A base orientation "PHI,PSI" (multiples of 90 degrees about x, then y) to try;
    /// repeat for several. Default: the part as given.
    #[arg(long = "base", value_name = "PHI,PSI", allow_hyphen_values = true, value_parser = limits::base)]
    pub bases: Vec<String>,
    /// Horizontal clearance kept between parts (robot positioning error, input units),
    /// 0 or more.
    #[arg(long, value_name = "C", value_parser = limits::nonnegative, allow_negative_numbers = true)]
    pub clearance: Option<f64>,
    /// Candidates examined per stage before a part is given up, 1 to 100000.
    #[arg(long, default_value_t = 500, value_parser = limits::max_candidates, allow_negative_numbers = true)]
    pub max_candidates: usize,
    /// Build every obstacle afresh instead of extrapolating between orientations.
    #[arg(long)]
    pub no_extrapolation: bool,
    #[command(flatten)]
    pub pictures: PictureArgs,
}

/// Runs the command.
pub fn run(args: &StackArgs, global: &Global) -> anyhow::Result<ExitCode> {
    crate::input_facts::no_tolerance(global, "stack")?;
    let loaded = load_valid(&args.part, global)?;
    args.pictures
        .check(&output::Inputs::of(&args.part, &loaded))?;
    let part = part_index(&loaded.assembly, args.part_name.as_deref(), &args.part)?;
    let opts = StackJobOptions {
        part,
        count: args.count,
        weight: args.weight,
        floor: match &args.floor {
            Some(text) => {
                let v = parse_numbers(text, 4, "--floor")?;
                Some([v[0], v[1], v[2], v[3]])
            }
            None => None,
        },
        floor_z: args.floor_z,
        max_height: args.max_height,
        dtheta: args.dtheta,
        bases: (!args.bases.is_empty())
            .then(|| parse_bases(&args.bases))
            .transpose()?,
        clearance: args.clearance,
        max_candidates: args.max_candidates,
        extrapolate: !args.no_extrapolation,
    };
    let mut answer = {
        let (_phase, progress) = output::planner(global, "stacking");
        stack(&loaded, &opts, &progress).map_err(|e| limits::job_error(e, global))?
    };
    let files = args.pictures.png.is_some() || args.pictures.svg.is_some();
    let stop = output::partial(global, answer.plan.stopped, files);
    if stop.is_none() {
        let (plan, h) = (&answer.plan, answer.grid_step);
        write_pictures(&args.pictures, |view, w, hgt, svg| {
            if svg {
                apart::draw::stack_render::plan_svg(plan, h, view, w, hgt).into_bytes()
            } else {
                apart::draw::stack_render::plan_png(plan, h, view, w, hgt)
            }
        })?;
    }
    if let Some(t) = &stop {
        answer.stopped_by(t.status(), output::stop_facts(t));
    }
    if global.json {
        output::json(&answer)?;
    } else {
        print_text(&answer, &stop);
    }
    let done = if answer.complete {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(2)
    };
    Ok(output::exit_code(&stop, done))
}

fn print_text(a: &StackAnswer, stop: &Option<Stopped>) {
    if let Some(t) = stop {
        output::line(t);
    }
    let count = a.count;
    output::line(format!(
        "{}: {} of {count} {} stacked, stack height {}",
        a.part,
        a.placements.len(),
        if count == 1 { "part" } else { "parts" },
        a.stack_height
    ));
    output::line("   #  stage  translation                      turn (deg)   cost        rests on");
    for p in &a.placements {
        let t = p.pose.translation;
        let rests: Vec<String> = p
            .contacts
            .iter()
            .filter(|c| c.supports)
            .map(|c| match c.with {
                Support::Floor => "floor".to_string(),
                Support::Part(k) => format!("#{}", k + 1),
            })
            .collect();
        let [phi, psi, theta] = p.pose.rotation_deg;
        let turn = if phi == 0.0 && psi == 0.0 {
            format!("{theta:.2}")
        } else {
            format!("{phi}/{psi}/{theta:.2}")
        };
        output::line(format!(
            "{:>4}  {:>5}  ({:>9.4}, {:>9.4}, {:>9.4})  {:>10}   {:<10.4}  {}",
            p.index + 1,
            p.stage,
            t[0],
            t[1],
            t[2],
            turn,
            p.pose.cost,
            rests.join(", ")
        ));
    }
    if !a.complete && stop.is_none() {
        output::line(format!(
            "incomplete: part {} fits nowhere in the region (raise --max-height or widen --floor)",
            a.placements.len() + 1
        ));
    }
    let s = &a.plan.stats;
    output::line(format!(
        "{} orientations; piece pairs evaluated {} of {} ({:.3}%); {} candidates rejected as unstable, {} as not lowerable; {:.3} s",
        s.orientations,
        s.place.pairs_evaluated,
        s.place.pairs_total,
        percent(s.place.pairs_evaluated, s.place.pairs_total),
        s.unstable,
        s.not_lowerable,
        s.seconds
    ));
}
