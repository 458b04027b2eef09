//! Placement: interference-free positions of one part among the others of an assembly,
//! cheapest first, by the exact placement engine of [`apart_stack::partial`]
//! (Ayyadevara et al. 2002): c-space obstacles of the interfering piece pairs only, the
//! free space as convex cells, the cost minimized exactly in each cell, over discrete
//! orientations about z. What placing and stacking share lives here too: the part as a
//! placement model, options in input units made exact grid values, exact poses and the
//! engine's counters as answers state them.

use crate::JobError;
use apart_assembly::{Assembly, Loaded};
use apart_kernel::{Aabb, Rational, Vec3};
use apart_pieces::Polytope;
use apart_stack::orientation::{orientations, Base, Orientation};
use apart_stack::part::{PartModel, StackError};
use apart_stack::partial::{place as place_in, Cost, Moving, ObstacleStats, PlaceOptions};
use apart_stack::partial::{PlaceStats, Region};
use apart_stack::scene::Scene;
use apart_stack::stability::placed_pieces;
use serde::Serialize;
use std::time::Instant;

/// Largest error accepted between an exact rotation and its wanted angle, in degrees.
const MAX_ANGLE_ERROR_DEG: f64 = 0.05;

/// How to place a part, in input units (ranges checked by the front end).
#[derive(Clone, Debug)]
pub struct PlaceJobOptions {
    /// The part to place (its index in the assembly); every other part is fixed.
    pub part: usize,
    /// Desired translation `p_d` from where the part is given: the cost is `|p − p_d|²`
    /// unless `weight` is given.
    pub target: [f64; 3],
    /// Minimize eq. (1) with this weight in [0, 1] instead of the distance to `target`.
    pub weight: Option<f64>,
    /// The floor point of eq. (1), with `weight`.
    pub floor_point: [f64; 3],
    /// Box `[x0, y0, z0, x1, y1, z1]` the whole placed part must lie in (`None`: every
    /// part's box grown by the part's largest extent on every side).
    pub region: Option<[f64; 6]>,
    /// Box of the allowed translations themselves instead of `region`.
    pub translations: Option<[f64; 6]>,
    /// Step of the orientations about z, in degrees (360: the part as given).
    pub dtheta: f64,
    /// Base orientations to try (`None`: the part as given).
    pub bases: Option<Vec<Base>>,
    /// Clearance kept from the fixed parts.
    pub clearance: Option<f64>,
    /// Candidate positions to list at most (one per free-space cell).
    pub candidates: usize,
}

/// A position and orientation of a part, in input units and exactly.
#[derive(Clone, Debug, Serialize)]
pub struct PoseAnswer {
    /// The translation.
    pub translation: [f64; 3],
    /// The same, exactly (rationals in input units).
    pub exact_translation: [String; 3],
    /// Turns about x, y and z, in degrees.
    pub rotation_deg: [f64; 3],
    /// The exact turn about z as its rational cosine and sine, `["a/c", "b/c"]`.
    pub exact_rotation: [String; 2],
    /// Its cost (squared input units).
    pub cost: f64,
}

impl PoseAnswer {
    /// The pose of a translation and orientation in grid units (`h`: the grid step).
    pub fn of(translation: &[Rational; 3], o: &Orientation, cost: &Rational, h: f64) -> PoseAnswer {
        let step = Rational::from_f64(h).expect("the grid step is a finite power of two");
        let t = &o.theta;
        PoseAnswer {
            translation: translation.clone().map(|v| v.to_f64() * h),
            exact_translation: translation.clone().map(|v| (&v * &step).to_string()),
            rotation_deg: o.degrees(),
            exact_rotation: [format!("{}/{}", t.a, t.c), format!("{}/{}", t.b, t.c)],
            cost: cost.to_f64() * h * h,
        }
    }
}

/// Seconds of a placement, in all and by phase.
#[derive(Clone, Debug, Serialize)]
pub struct PlacementSeconds {
    /// Wall-clock seconds of the whole run (the front end may count its loading too).
    pub total: f64,
    /// Interference detection.
    pub detect: f64,
    /// Subtracting obstacles and minimizing in cells.
    pub cells: f64,
    /// Obstacles built afresh.
    pub obstacles: f64,
    /// Obstacles extrapolated between orientations.
    pub extrapolation: f64,
}

/// The placement engine's counters.
#[derive(Clone, Debug, Serialize)]
pub struct PlacementStats {
    /// Orientations whose desired position was tested.
    pub orientations_considered: usize,
    /// Piece pairs a complete c-space obstacle would need.
    pub pairs_total: u64,
    /// Piece pairs whose obstacle was built.
    pub pairs_evaluated: u64,
    /// Exact interference tests.
    pub interference_tests: u64,
    /// Free-space cells made.
    pub cells: u64,
    /// Quadratic programs solved.
    pub qps: u64,
    /// Obstacles built afresh.
    pub obstacles_fresh: u64,
    /// Obstacles extrapolated between orientations.
    pub obstacles_extrapolated: u64,
    /// Where the time went.
    pub seconds: PlacementSeconds,
}

impl PlacementStats {
    /// The counters of a placement or a stack that took `seconds` in all.
    pub fn of(p: &PlaceStats, o: &ObstacleStats, seconds: f64) -> PlacementStats {
        PlacementStats {
            orientations_considered: p.orientations_considered,
            pairs_total: p.pairs_total,
            pairs_evaluated: p.pairs_evaluated,
            interference_tests: p.interference_tests,
            cells: p.cells,
            qps: p.qps,
            obstacles_fresh: o.fresh,
            obstacles_extrapolated: o.extrapolated,
            seconds: PlacementSeconds {
                total: seconds,
                detect: p.detect_seconds,
                cells: p.cells_seconds,
                obstacles: o.fresh_seconds,
                extrapolation: o.extrapolate_seconds,
            },
        }
    }
}

/// The answer of a placement.
#[derive(Clone, Debug, Serialize)]
pub struct PlaceAnswer {
    /// The part placed.
    pub moving: String,
    /// The fixed parts.
    pub fixed: Vec<String>,
    /// "distance" (to `target`) or "stacking" (eq. (1) with `weight`).
    pub cost_kind: &'static str,
    /// The weight of eq. (1), when it is the cost.
    pub weight: Option<f64>,
    /// The desired translation.
    pub target: [f64; 3],
    /// The grid step (input units).
    pub grid_step: f64,
    /// Interference-free positions, cheapest first.
    pub candidates: Vec<PoseAnswer>,
    /// Counters and times.
    pub stats: PlacementStats,
}

/// A placement's answer, and what its picture needs.
pub struct PlaceRun {
    /// The answer.
    pub answer: PlaceAnswer,
    /// The fixed parts, as the engine saw them.
    pub scene: Scene,
    /// The pieces of the part at its cheapest position, when it fits.
    pub best: Option<Vec<Polytope>>,
}

/// Interference-free positions of one part among the others of a loaded (valid, but
/// for the overlaps of that part: see [`crate::gate`]) assembly, cheapest first.
pub fn place(loaded: &Loaded, opts: &PlaceJobOptions) -> Result<PlaceRun, JobError> {
    let start = Instant::now();
    let asm = &loaded.assembly;
    let h = asm.grid.step();
    let part = model_of(asm, opts.part)?;
    let mut scene = Scene::new();
    let mut fixed = Vec::new();
    for (i, p) in asm.parts.iter().enumerate() {
        if i != opts.part {
            scene.add_fixed_part(&p.pieces);
            fixed.push(p.name.clone());
        }
    }
    let g = |v: f64, setting: &'static str| grid_value(v, h, setting);
    let boxed = |v: &[f64; 6], setting| -> Result<Aabb<Rational>, JobError> {
        Ok(Aabb {
            min: [g(v[0], setting)?, g(v[1], setting)?, g(v[2], setting)?],
            max: [g(v[3], setting)?, g(v[4], setting)?, g(v[5], setting)?],
        })
    };
    let region = if let Some(t) = &opts.translations {
        Region::Translations(boxed(t, "translations")?)
    } else if let Some(r) = &opts.region {
        Region::Container(boxed(r, "region")?)
    } else {
        Region::Container(default_region(asm, &part)?)
    };
    let bases = opts.bases.clone().unwrap_or_else(|| vec![Base::IDENTITY]);
    let turns = orientations(opts.dtheta, &bases, MAX_ANGLE_ERROR_DEG);
    let moving = Moving::new(part, &turns, true);
    let t = opts.target;
    let cost = match opts.weight {
        None => Cost::Distance([g(t[0], "target")?, g(t[1], "target")?, g(t[2], "target")?]),
        Some(w) => {
            let f = opts.floor_point;
            Cost::Stacking {
                w: Rational::from_f64(w).ok_or(JobError::NotFinite {
                    setting: "weight",
                    value: w,
                })?,
                floor: [
                    g(f[0], "floor_point")?,
                    g(f[1], "floor_point")?,
                    g(f[2], "floor_point")?,
                ],
            }
        }
    };
    let engine = PlaceOptions {
        region,
        cost,
        clearance: opts.clearance.map(|c| g(c, "clearance")).transpose()?,
        extrapolate: true,
    };
    let result = place_in(&scene, &moving, &engine, opts.candidates)?;
    let seconds = start.elapsed().as_secs_f64();
    let best = result
        .candidates
        .first()
        .map(|c| placed_pieces(&moving.oriented[c.orientation].pieces, &c.translation));
    let candidates = result
        .candidates
        .iter()
        .map(|c| {
            PoseAnswer::of(
                &c.translation,
                &moving.orientations[c.orientation],
                &c.cost,
                h,
            )
        })
        .collect();
    let answer = PlaceAnswer {
        moving: moving.part.name.clone(),
        fixed,
        cost_kind: if opts.weight.is_some() {
            "stacking"
        } else {
            "distance"
        },
        weight: opts.weight,
        target: opts.target,
        grid_step: h,
        candidates,
        stats: PlacementStats::of(&result.stats, &result.obstacles, seconds),
    };
    Ok(PlaceRun {
        answer,
        scene,
        best,
    })
}

/// A value in input units, exactly in grid units (`h`, the grid step, is a power of
/// two); `setting` names it when it is no finite number of grid units.
pub fn grid_value(v: f64, h: f64, setting: &'static str) -> Result<Rational, JobError> {
    Rational::from_f64(v / h).ok_or(JobError::NotFinite { setting, value: v })
}

/// Part `k` of a loaded assembly as a placement model (its pieces and its mesh).
pub fn model_of(asm: &Assembly, k: usize) -> Result<PartModel, JobError> {
    let part = &asm.parts[k];
    let mut model = PartModel::from_pieces(&part.name, part.pieces.clone()).map_err(|error| {
        JobError::Part {
            part: part.name.clone(),
            error,
        }
    })?;
    model.mesh = part.mesh.as_ref().map(|m| {
        (
            m.vertices.iter().map(|&v| Vec3::from(v)).collect(),
            m.triangles.clone(),
        )
    });
    Ok(model)
}

/// The bounding box of every part's pieces grown by the new part's largest extent.
fn default_region(asm: &Assembly, part: &PartModel) -> Result<Aabb<Rational>, JobError> {
    let mut b: Option<Aabb<Rational>> = None;
    for p in &asm.parts {
        for piece in &p.pieces {
            let pb = Aabb::of_scaled(piece.vertices(), piece.den());
            b = Some(match b {
                None => pb,
                Some(a) => a.union(&pb),
            });
        }
    }
    let no_pieces = || StackError::Invalid("the assembly has no convex pieces".into());
    let b = b.ok_or_else(no_pieces)?;
    let e = part.orient(&Orientation::IDENTITY).extent;
    let grow = (0..3)
        .map(|i| &e.max[i] - &e.min[i])
        .max()
        .expect("three axes");
    Ok(Aabb {
        min: b.min.clone().map(|v| &v - &grow),
        max: b.max.clone().map(|v| &v + &grow),
    })
}
