//! `apart stack <part>`: a stack of identical parts on a floor region (Ayyadevara et
//! al. 2002, [`STACKING_PAPER`](crate::commands::placement_args::STACKING_PAPER)): each
//! part placed by the exact placement engine with the cost of eq. (1), accepted only if
//! stable, grippable from above and lowerable along −z. Exit code 0 when every part was
//! placed, 2 when the stack is incomplete, 3 when `--timeout` stopped the run (the parts
//! placed until then are printed; 130 after Ctrl-C, 1 after the memory budget, with
//! the same partial answer).

use crate::commands::load::load_valid;
use crate::commands::placement_args::{
    exact_rotation, exact_units, grid_value, load_part, parse_bases, parse_numbers, percent,
    qunits, stats_json, write_pictures, PictureArgs, StatsJson,
};
use crate::limits::Stopped;
use crate::output;
use crate::{limits, Global};
use apart::kernel::Rational;
use apart::stack::planner::{stack_with, StackOptions, StackPlan};
use apart::stack::stability::ContactWith;
use serde::Serialize;
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

#[derive(Serialize)]
struct ContactJson {
    /// "floor" or the index of a part of the stack.
    with: serde_json::Value,
    supports: bool,
}

#[derive(Serialize)]
struct PlacementJson {
    index: usize,
    translation: [f64; 3],
    exact_translation: [String; 3],
    rotation_deg: [f64; 3],
    exact_rotation: [String; 2],
    cost: f64,
    stage: u8,
    examined: usize,
    contacts: Vec<ContactJson>,
}

#[derive(Serialize)]
struct StackJson {
    /// "done", or "timeout", "out of memory", "interrupted": --timeout, the memory
    /// budget or Ctrl-C stopped the run and `placements` are the parts placed until then.
    status: &'static str,
    /// What stopped the run, and where; absent when it ran to its end.
    #[serde(skip_serializing_if = "Option::is_none")]
    stopped: Option<output::StoppedJson>,
    part: String,
    count: usize,
    complete: bool,
    placements: Vec<PlacementJson>,
    stack_height: f64,
    grid_step: f64,
    stats: StatsJson,
    unstable: usize,
    not_lowerable: usize,
    orientations: usize,
}

/// Runs the command.
pub fn run(args: &StackArgs, global: &Global) -> anyhow::Result<ExitCode> {
    crate::input_facts::no_tolerance(global, "stack")?;
    let loaded = load_valid(&args.part, global)?;
    args.pictures
        .check(&output::Inputs::of(&args.part, &loaded))?;
    let grid = loaded.assembly.grid;
    let part = load_part(&loaded.assembly, args.part_name.as_deref(), &args.part)?;
    let h = grid.step();
    let to_grid = |v: f64, flag: &str| grid_value(v, h, flag);
    let extent = part
        .orient(&apart::stack::orientation::Orientation::IDENTITY)
        .extent;
    let size = |i: usize| (&extent.max[i] - &extent.min[i]).to_f64() * h;
    let floor = match &args.floor {
        Some(text) => {
            let v = parse_numbers(text, 4, "--floor")?;
            [v[0], v[1], v[2], v[3]]
        }
        None => {
            let side = (args.count as f64).sqrt().ceil() * size(0).max(size(1)) * 1.25;
            let half = side / 2.0;
            [-half, -half, half, half]
        }
    };
    let mut opts = StackOptions::new(
        args.count,
        Rational::from_f64(args.weight).expect("checked finite"),
        [
            to_grid(floor[0], "--floor")?,
            to_grid(floor[1], "--floor")?,
            to_grid(floor[2], "--floor")?,
            to_grid(floor[3], "--floor")?,
        ],
        match args.max_height {
            Some(m) => to_grid(m, "--max-height")?,
            None => {
                let height = &extent.max[2] - &extent.min[2];
                &height * &Rational::from(args.count as i64)
            }
        },
    );
    opts.floor_z = to_grid(args.floor_z, "--floor-z")?;
    opts.dtheta_deg = args.dtheta;
    if !args.bases.is_empty() {
        opts.bases = parse_bases(&args.bases)?;
    }
    opts.clearance = args
        .clearance
        .map(|c| to_grid(c, "--clearance"))
        .transpose()?;
    opts.max_candidates = args.max_candidates;
    opts.extrapolate = !args.no_extrapolation;
    let plan = {
        let (_phase, progress) = output::planner(global, "stacking");
        stack_with(&part, &opts, &progress)?
    };
    let files = args.pictures.png.is_some() || args.pictures.svg.is_some();
    let stop = output::partial(global, plan.stopped, files);
    if stop.is_none() {
        write_pictures(&args.pictures, |view, w, hgt, svg| {
            if svg {
                apart::draw::stack_render::plan_svg(&plan, h, view, w, hgt).into_bytes()
            } else {
                apart::draw::stack_render::plan_png(&plan, h, view, w, hgt)
            }
        })?;
    }
    if global.json {
        output::json(&to_json(&plan, &part.name, args.count, h, &stop))?;
    } else {
        print_text(&plan, &part.name, args.count, h, &stop);
    }
    let answer = if plan.complete {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(2)
    };
    Ok(output::exit_code(&stop, answer))
}

fn to_json(
    plan: &StackPlan,
    name: &str,
    count: usize,
    h: f64,
    stop: &Option<Stopped>,
) -> StackJson {
    StackJson {
        status: output::status(stop),
        stopped: output::stopped_json(stop),
        part: name.to_string(),
        count,
        complete: plan.complete,
        placements: plan
            .placements
            .iter()
            .map(|p| PlacementJson {
                index: p.index,
                translation: p.translation.clone().map(|t| qunits(&t, h)),
                exact_translation: p.translation.clone().map(|t| exact_units(&t, h)),
                rotation_deg: p.orientation.degrees(),
                exact_rotation: exact_rotation(&p.orientation),
                cost: p.cost.to_f64() * h * h,
                stage: p.stage,
                examined: p.examined,
                contacts: p
                    .contacts
                    .iter()
                    .map(|c| ContactJson {
                        with: match c.with {
                            ContactWith::Floor => "floor".into(),
                            ContactWith::Part(k) => k.into(),
                        },
                        supports: c.supports,
                    })
                    .collect(),
            })
            .collect(),
        stack_height: qunits(&plan.stack_height, h),
        grid_step: h,
        stats: stats_json(&plan.stats.place, &plan.stats.obstacles, plan.stats.seconds),
        unstable: plan.stats.unstable,
        not_lowerable: plan.stats.not_lowerable,
        orientations: plan.stats.orientations,
    }
}

fn print_text(plan: &StackPlan, name: &str, count: usize, h: f64, stop: &Option<Stopped>) {
    if let Some(t) = stop {
        output::line(t);
    }
    output::line(format!(
        "{name}: {} of {count} {} stacked, stack height {}",
        plan.placements.len(),
        if count == 1 { "part" } else { "parts" },
        qunits(&plan.stack_height, h)
    ));
    output::line("   #  stage  translation                      turn (deg)   cost        rests on");
    for p in &plan.placements {
        let t = p.translation.clone().map(|t| qunits(&t, h));
        let rests: Vec<String> = p
            .contacts
            .iter()
            .filter(|c| c.supports)
            .map(|c| match c.with {
                ContactWith::Floor => "floor".to_string(),
                ContactWith::Part(k) => format!("#{}", k + 1),
            })
            .collect();
        let [phi, psi, theta] = p.orientation.degrees();
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
            p.cost.to_f64() * h * h,
            rests.join(", ")
        ));
    }
    if !plan.complete && stop.is_none() {
        output::line(format!(
            "incomplete: part {} fits nowhere in the region (raise --max-height or widen --floor)",
            plan.placements.len() + 1
        ));
    }
    let s = &plan.stats;
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
