//! The answers as JSON values, field for field as the command line's `--json` prints
//! them (`apart check`, `partition`, `sequence`, `separate`), so that the Python
//! objects and the command line say the same thing. A partition lists what the command
//! line lists ([`Listing`]): by default at most 20 moving sets with at most 5 solutions
//! of each kind, every solution still counted.

use apart_assembly::Loaded;
use apart_jobs::partition::PartitionOptions;
use apart_jobs::sequence::SequenceJobOptions;
use apart_jobs::JobError;
use apart_kernel::{Grid, Vec3};
use apart_mesh::Problem;
use apart_plan::progress::Progress;
use apart_plan::SequenceOptions;
use serde_json::{json, Value};
use std::sync::Arc;

/// Every problem, as the command line's JSON lists them.
pub fn problems(problems: &[Problem]) -> Value {
    serde_json::to_value(problems).unwrap_or(Value::Null)
}

/// The check report.
pub fn check(loaded: &Loaded, units: Option<&str>) -> Value {
    serde_json::to_value(apart_jobs::check::check(loaded, units)).unwrap_or(Value::Null)
}

/// Snaps a direction like the command line's `--direction X,Y,Z`: to a primitive
/// integer vector on a grid of 30 bits.
pub fn snap_direction(v: [f64; 3]) -> Result<Vec3, String> {
    if v.iter().any(|x| !x.is_finite()) {
        return Err(format!("direction {v:?} has a non-finite number"));
    }
    let g = Grid::choose(v.iter().copied(), 30).map_err(|e| e.to_string())?;
    let d = Vec3::new(g.snap(v[0]), g.snap(v[1]), g.snap(v[2])).primitive();
    if d.is_zero() {
        return Err(format!("direction {v:?} is zero"));
    }
    Ok(d)
}

/// Partitioning: one direction's blocking graph (`direction`, with two parts or more),
/// or the job's partition (see [`apart_jobs::partition`]), with the seconds it took.
pub fn partition(
    loaded: &Loaded,
    units: Option<&str>,
    direction: Option<Vec3>,
    opts: &PartitionOptions,
    progress: &Progress,
) -> Result<Value, JobError> {
    if let Some(d) = direction.filter(|_| loaded.assembly.parts.len() >= 2) {
        let a = apart_jobs::partition::direction(loaded, units, &d)?;
        return Ok(serde_json::to_value(a).unwrap_or(Value::Null));
    }
    let t = std::time::Instant::now();
    let mut a = apart_jobs::partition::partition(loaded, units, opts, progress)?.answer;
    a.stats.seconds.total = Some(t.elapsed().as_secs_f64());
    Ok(serde_json::to_value(a).unwrap_or(Value::Null))
}

/// A disassembly plan (the job's, every step with why it was chosen) with the seconds
/// it took, and the plan itself (for its pictures).
pub fn sequence(
    loaded: &Loaded,
    units: Option<&str>,
    opts: &SequenceOptions,
    first: bool,
    progress: &Progress,
) -> Result<(Value, Arc<apart_plan::Sequence>), JobError> {
    let t = std::time::Instant::now();
    let job = SequenceJobOptions {
        plan: opts.clone(),
        first,
        explain: true,
    };
    let mut a = apart_jobs::sequence::sequence(loaded, units, &job, progress, &mut |_, _| {})?;
    a.seconds.total = Some(t.elapsed().as_secs_f64());
    let plan = a.plan.clone();
    Ok((serde_json::to_value(a).unwrap_or(Value::Null), plan))
}

/// Every direction along which part `a` leaves part `b`; `None` when the stop flag
/// ended the run before it had the pair regions.
pub fn separate(
    loaded: &Loaded,
    units: Option<&str>,
    a: usize,
    b: usize,
    progress: &Progress,
) -> Result<Option<Value>, JobError> {
    Ok(
        apart_jobs::separate::separate(loaded, units, a, b, progress)?
            .map(|s| serde_json::to_value(s).unwrap_or(Value::Null)),
    )
}

/// The stacker's options, in input units (checked by the Python side for their ranges).
pub struct StackArgs {
    /// The part to stack (index in the assembly).
    pub part: usize,
    /// Parts to place.
    pub count: usize,
    /// Weight of eq. (1), in [0, 1].
    pub weight: f64,
    /// Floor region x0, y0, x1, y1 (`None`: a square around the origin sized for the
    /// count, as the command line chooses it).
    pub floor: Option<[f64; 4]>,
    /// Height of the floor.
    pub floor_z: f64,
    /// Highest top of the stack (`None`: the part's height times the count).
    pub max_height: Option<f64>,
    /// Step of the rotations about z, in degrees.
    pub dtheta: f64,
    /// Base orientations as quarter turns about x and y (`None`: the library's).
    pub bases: Option<Vec<(u8, u8)>>,
    /// Clearance between parts.
    pub clearance: Option<f64>,
    /// Candidates examined per part at most.
    pub max_candidates: usize,
    /// Reuse obstacles between orientations.
    pub extrapolate: bool,
}

/// An exact rational of input units from a float (`what` names it in the error).
fn grid_value(v: f64, h: f64, what: &str) -> Result<apart_kernel::Rational, String> {
    apart_kernel::Rational::from_f64(v / h)
        .ok_or_else(|| format!("{what} {v} is not a finite number"))
}

/// A stack of identical parts on a floor (`apart stack --json`). A run stopped by the
/// flag has `"status": "stopped"`.
pub fn stack(loaded: &Loaded, args: &StackArgs, progress: &Progress) -> Result<Value, String> {
    use apart_kernel::Rational;
    use apart_stack::orientation::{Base, Orientation};
    use apart_stack::planner::{stack_with, StackOptions};
    use apart_stack::stability::ContactWith;
    let asm = &loaded.assembly;
    let h = asm.grid.step();
    let p = &asm.parts[args.part];
    let mut part = apart_stack::part::PartModel::from_pieces(&p.name, p.pieces.clone())
        .map_err(|e| format!("part \"{}\": {e}", p.name))?;
    part.mesh = p.mesh.as_ref().map(|m| {
        (
            m.vertices.iter().map(|&v| Vec3::from(v)).collect(),
            m.triangles.clone(),
        )
    });
    let extent = part.orient(&Orientation::IDENTITY).extent;
    let size = |i: usize| (&extent.max[i] - &extent.min[i]).to_f64() * h;
    let floor = args.floor.unwrap_or_else(|| {
        let side = (args.count as f64).sqrt().ceil() * size(0).max(size(1)) * 1.25;
        let half = side / 2.0;
        [-half, -half, half, half]
    });
    let weight = Rational::from_f64(args.weight).ok_or("weight is not a finite number")?;
    let max_height = match args.max_height {
        Some(m) => grid_value(m, h, "max_height")?,
        None => {
            let height = &extent.max[2] - &extent.min[2];
            &height * &Rational::from(args.count as i64)
        }
    };
    let mut opts = StackOptions::new(
        args.count,
        weight,
        [
            grid_value(floor[0], h, "floor")?,
            grid_value(floor[1], h, "floor")?,
            grid_value(floor[2], h, "floor")?,
            grid_value(floor[3], h, "floor")?,
        ],
        max_height,
    );
    opts.floor_z = grid_value(args.floor_z, h, "floor_z")?;
    opts.dtheta_deg = args.dtheta;
    if let Some(bases) = &args.bases {
        opts.bases = bases.iter().map(|&(phi, psi)| Base { phi, psi }).collect();
    }
    opts.clearance = args
        .clearance
        .map(|c| grid_value(c, h, "clearance"))
        .transpose()?;
    opts.max_candidates = args.max_candidates;
    opts.extrapolate = args.extrapolate;
    let plan = stack_with(&part, &opts, progress).map_err(|e| e.to_string())?;
    let units = |v: &Rational| v.to_f64() * h;
    let step = Rational::from_f64(h).ok_or("the grid step is not finite")?;
    let exact = |v: &Rational| (v * &step).to_string();
    let placements: Vec<Value> = plan
        .placements
        .iter()
        .map(|q| {
            let t = &q.orientation.theta;
            json!({
                "index": q.index,
                "translation": q.translation.clone().map(|v| units(&v)),
                "exact_translation": q.translation.clone().map(|v| exact(&v)),
                "rotation_deg": q.orientation.degrees(),
                "exact_rotation": [format!("{}/{}", t.a, t.c), format!("{}/{}", t.b, t.c)],
                "cost": q.cost.to_f64() * h * h,
                "stage": q.stage,
                "examined": q.examined,
                "contacts": q.contacts.iter().map(|c| json!({
                    "with": match c.with {
                        ContactWith::Floor => json!("floor"),
                        ContactWith::Part(k) => json!(k),
                    },
                    "supports": c.supports,
                })).collect::<Vec<_>>(),
            })
        })
        .collect();
    Ok(json!({
        "status": if plan.stopped { "stopped" } else { "done" },
        "part": p.name,
        "count": args.count,
        "complete": plan.complete,
        "placements": placements,
        "stack_height": units(&plan.stack_height),
        "grid_step": h,
        "unstable": plan.stats.unstable,
        "not_lowerable": plan.stats.not_lowerable,
        "orientations": plan.stats.orientations,
        "seconds": plan.stats.seconds,
    }))
}

/// The placement's options, in input units (checked by the Python side for their
/// ranges), as `apart place` takes them.
pub struct PlaceArgs {
    /// The part to place (index in the assembly); every other part is fixed.
    pub part: usize,
    /// Desired translation (the cost |p − target|²), when `weight` is `None`.
    pub target: [f64; 3],
    /// Weight of eq. (1) instead of the distance to `target`.
    pub weight: Option<f64>,
    /// The floor point of eq. (1).
    pub floor_point: [f64; 3],
    /// Box the whole placed part must lie in (`None`: the command line's default).
    pub region: Option<[f64; 6]>,
    /// Box of allowed translations instead.
    pub translations: Option<[f64; 6]>,
    /// Step of the rotations about z, in degrees.
    pub dtheta: f64,
    /// Base orientations as quarter turns about x and y (`None`: the part as given).
    pub bases: Option<Vec<(u8, u8)>>,
    /// Clearance from the fixed parts.
    pub clearance: Option<f64>,
    /// Candidates to list.
    pub candidates: usize,
}

/// The bounding box of every part's pieces grown by the new part's largest extent
/// (`apart place`'s default region).
fn default_region(
    asm: &apart_assembly::Assembly,
    part: &apart_stack::part::PartModel,
) -> Result<apart_kernel::Aabb<apart_kernel::Rational>, String> {
    use apart_kernel::Aabb;
    let mut b: Option<Aabb<apart_kernel::Rational>> = None;
    for p in &asm.parts {
        for piece in &p.pieces {
            let pb = Aabb::of_scaled(piece.vertices(), piece.den());
            b = Some(match b {
                None => pb,
                Some(a) => a.union(&pb),
            });
        }
    }
    let b = b.ok_or("the assembly has no convex pieces")?;
    let e = part
        .orient(&apart_stack::orientation::Orientation::IDENTITY)
        .extent;
    let grow = (0..3)
        .map(|i| &e.max[i] - &e.min[i])
        .max()
        .ok_or("no extent")?;
    Ok(Aabb {
        min: b.min.clone().map(|v| &v - &grow),
        max: b.max.clone().map(|v| &v + &grow),
    })
}

/// Interference-free positions of one part among the others, cheapest first
/// (`apart place ASSEMBLY NAME --json`).
pub fn place(loaded: &Loaded, args: &PlaceArgs) -> Result<Value, String> {
    use apart_kernel::{Aabb, Rational};
    use apart_stack::orientation::{orientations, Base};
    use apart_stack::partial::{place, Cost, Moving, PlaceOptions, Region};
    use apart_stack::scene::Scene;
    let start = std::time::Instant::now();
    let asm = &loaded.assembly;
    let h = asm.grid.step();
    let p = &asm.parts[args.part];
    let mut part = apart_stack::part::PartModel::from_pieces(&p.name, p.pieces.clone())
        .map_err(|e| format!("part \"{}\": {e}", p.name))?;
    part.mesh = p.mesh.as_ref().map(|m| {
        (
            m.vertices.iter().map(|&v| Vec3::from(v)).collect(),
            m.triangles.clone(),
        )
    });
    let mut scene = Scene::new();
    let mut fixed = Vec::new();
    for (i, q) in asm.parts.iter().enumerate() {
        if i != args.part {
            scene.add_fixed_part(&q.pieces);
            fixed.push(q.name.clone());
        }
    }
    let g = |v: f64, what: &str| grid_value(v, h, what);
    let boxed = |v: &[f64; 6], what: &str| -> Result<Aabb<Rational>, String> {
        Ok(Aabb {
            min: [g(v[0], what)?, g(v[1], what)?, g(v[2], what)?],
            max: [g(v[3], what)?, g(v[4], what)?, g(v[5], what)?],
        })
    };
    let region = if let Some(t) = &args.translations {
        Region::Translations(boxed(t, "translations")?)
    } else if let Some(r) = &args.region {
        Region::Container(boxed(r, "region")?)
    } else {
        Region::Container(default_region(asm, &part)?)
    };
    let bases = match &args.bases {
        None => vec![Base::IDENTITY],
        Some(b) => b.iter().map(|&(phi, psi)| Base { phi, psi }).collect(),
    };
    let moving = Moving::new(part, &orientations(args.dtheta, &bases, 0.05), true);
    let t = args.target;
    let opts = PlaceOptions {
        region,
        cost: match args.weight {
            None => Cost::Distance([g(t[0], "target")?, g(t[1], "target")?, g(t[2], "target")?]),
            Some(w) => {
                let f = args.floor_point;
                Cost::Stacking {
                    w: Rational::from_f64(w).ok_or("weight is not a finite number")?,
                    floor: [
                        g(f[0], "floor_point")?,
                        g(f[1], "floor_point")?,
                        g(f[2], "floor_point")?,
                    ],
                }
            }
        },
        clearance: args.clearance.map(|c| g(c, "clearance")).transpose()?,
        extrapolate: true,
    };
    let result = place(&scene, &moving, &opts, args.candidates).map_err(|e| e.to_string())?;
    let seconds = start.elapsed().as_secs_f64();
    let step = Rational::from_f64(h).ok_or("the grid step is not finite")?;
    let exact = |v: &Rational| (v * &step).to_string();
    let candidates: Vec<Value> = result
        .candidates
        .iter()
        .map(|c| {
            let o = &moving.orientations[c.orientation];
            let th = &o.theta;
            json!({
                "translation": c.translation.clone().map(|v| v.to_f64() * h),
                "exact_translation": c.translation.clone().map(|v| exact(&v)),
                "rotation_deg": o.degrees(),
                "exact_rotation": [format!("{}/{}", th.a, th.c), format!("{}/{}", th.b, th.c)],
                "cost": c.cost.to_f64() * h * h,
            })
        })
        .collect();
    let (s, o) = (&result.stats, &result.obstacles);
    Ok(json!({
        "moving": p.name,
        "fixed": fixed,
        "cost_kind": if args.weight.is_some() { "stacking" } else { "distance" },
        "weight": args.weight,
        "target": args.target,
        "grid_step": h,
        "candidates": candidates,
        "stats": {
            "orientations_considered": s.orientations_considered,
            "pairs_total": s.pairs_total,
            "pairs_evaluated": s.pairs_evaluated,
            "interference_tests": s.interference_tests,
            "cells": s.cells,
            "qps": s.qps,
            "obstacles_fresh": o.fresh,
            "obstacles_extrapolated": o.extrapolated,
            "seconds": {
                "total": seconds,
                "detect": s.detect_seconds,
                "cells": s.cells_seconds,
                "obstacles": o.fresh_seconds,
                "extrapolation": o.extrapolate_seconds,
            },
        },
    }))
}
