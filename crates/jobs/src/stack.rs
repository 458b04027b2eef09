//! Stacking: copies of one part placed one by one on a floor region by the exact
//! placement engine with the cost of eq. (1) of Ayyadevara et al. 2002, each accepted
//! only if stable, grippable from above and lowerable along −z.

use crate::place::{grid_value, model_of, PlacementStats, PoseAnswer};
use crate::{JobError, Progress, StopFacts};
use apart_assembly::Loaded;
use apart_kernel::Rational;
use apart_stack::orientation::{Base, Orientation};
use apart_stack::planner::{stack_with, StackOptions, StackPlan};
use apart_stack::stability::ContactWith;
use serde::Serialize;

/// How to stack, in input units (ranges checked by the front end).
#[derive(Clone, Debug)]
pub struct StackJobOptions {
    /// The part to stack (its index in the assembly).
    pub part: usize,
    /// Copies to place.
    pub count: usize,
    /// Weight w of eq. (1) in [0, 1]: 0 keeps the stack low, 1 its footprint small.
    pub weight: f64,
    /// Floor region `[x0, y0, x1, y1]`, its centre eq. (1)'s `(x0, y0)` (`None`: a
    /// square centred on the origin with room for every copy side by side).
    pub floor: Option<[f64; 4]>,
    /// Height of the floor (eq. (1)'s `z0`).
    pub floor_z: f64,
    /// Highest top of the stack above the floor (`None`: the part's height times the
    /// count).
    pub max_height: Option<f64>,
    /// Step of the orientations about z, in degrees.
    pub dtheta: f64,
    /// Base orientations to try (`None`: the part as given).
    pub bases: Option<Vec<Base>>,
    /// Horizontal clearance kept between parts.
    pub clearance: Option<f64>,
    /// Candidates examined per stage before a part is given up.
    pub max_candidates: usize,
    /// Extrapolate obstacles between orientations instead of building each afresh.
    pub extrapolate: bool,
}

/// What a placed part touches.
#[derive(Clone, Copy, Debug)]
pub enum Support {
    /// The floor.
    Floor,
    /// An earlier part of the stack (its index).
    Part(usize),
}

impl Serialize for Support {
    /// "floor", or the index of the part.
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Support::Floor => serializer.serialize_str("floor"),
            Support::Part(k) => serializer.serialize_u64(*k as u64),
        }
    }
}

/// A contact of a placed part.
#[derive(Clone, Debug, Serialize)]
pub struct ContactAnswer {
    /// What it touches.
    pub with: Support,
    /// The contact carries the part's weight.
    pub supports: bool,
}

/// One part of the stack.
#[derive(Clone, Debug, Serialize)]
pub struct PlacedAnswer {
    /// Its index in the stack (placing order).
    pub index: usize,
    /// Where it is, and its term of eq. (1).
    #[serde(flatten)]
    pub pose: PoseAnswer,
    /// 1: inside the stack's grown bounding box; 2: anywhere.
    pub stage: u8,
    /// Candidates examined before it was accepted (itself included).
    pub examined: usize,
    /// Its contacts with the floor and earlier parts.
    pub contacts: Vec<ContactAnswer>,
}

/// The answer of a stack.
#[derive(Clone, Debug, Serialize)]
pub struct StackAnswer {
    /// "done", or "stopped" when the stop flag cut the run short (the front ends name
    /// the cause: "timeout", "out of memory", "interrupted").
    pub status: String,
    /// What stopped the run, and where; absent when it ran to its end or the front end
    /// does not say.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped: Option<StopFacts>,
    /// The part stacked.
    pub part: String,
    /// Copies asked for.
    pub count: usize,
    /// Every copy was placed.
    pub complete: bool,
    /// The copies placed, in order.
    pub placements: Vec<PlacedAnswer>,
    /// Height of the stack above the floor.
    pub stack_height: f64,
    /// The grid step (input units).
    pub grid_step: f64,
    /// The placement engine's counters, when the front end states them (the command
    /// line does).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stats: Option<PlacementStats>,
    /// Candidates rejected as unstable.
    pub unstable: usize,
    /// Candidates rejected as not lowerable into place.
    pub not_lowerable: usize,
    /// Orientations kept.
    pub orientations: usize,
    /// Wall-clock seconds, when the front end states them here instead of in `stats`
    /// (the Python binding does).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seconds: Option<f64>,
    /// The plan itself (for pictures).
    #[serde(skip)]
    pub plan: StackPlan,
}

impl StackAnswer {
    /// States the cause the front end knows of a stop: `status` names it ("timeout")
    /// and `facts` says where.
    pub fn stopped_by(&mut self, status: &str, facts: StopFacts) {
        self.status = status.to_string();
        self.stopped = Some(facts);
    }
}

/// A stack of copies of one part of a loaded (valid) assembly on a floor. A run
/// stopped by the flag of `progress` returns the parts placed until then, with the
/// status "stopped".
pub fn stack(
    loaded: &Loaded,
    opts: &StackJobOptions,
    progress: &Progress,
) -> Result<StackAnswer, JobError> {
    let h = loaded.assembly.grid.step();
    let part = model_of(&loaded.assembly, opts.part)?;
    let g = |v: f64, setting: &'static str| grid_value(v, h, setting);
    let extent = part.orient(&Orientation::IDENTITY).extent;
    let size = |i: usize| (&extent.max[i] - &extent.min[i]).to_f64() * h;
    let floor = opts.floor.unwrap_or_else(|| {
        let side = (opts.count as f64).sqrt().ceil() * size(0).max(size(1)) * 1.25;
        let half = side / 2.0;
        [-half, -half, half, half]
    });
    let weight = Rational::from_f64(opts.weight).ok_or(JobError::NotFinite {
        setting: "weight",
        value: opts.weight,
    })?;
    let floor = [
        g(floor[0], "floor")?,
        g(floor[1], "floor")?,
        g(floor[2], "floor")?,
        g(floor[3], "floor")?,
    ];
    let max_height = match opts.max_height {
        Some(m) => g(m, "max_height")?,
        None => {
            let height = &extent.max[2] - &extent.min[2];
            &height * &Rational::from(opts.count as i64)
        }
    };
    let mut engine = StackOptions::new(opts.count, weight, floor, max_height);
    engine.floor_z = g(opts.floor_z, "floor_z")?;
    engine.dtheta_deg = opts.dtheta;
    if let Some(bases) = &opts.bases {
        engine.bases = bases.clone();
    }
    engine.clearance = opts.clearance.map(|c| g(c, "clearance")).transpose()?;
    engine.max_candidates = opts.max_candidates;
    engine.extrapolate = opts.extrapolate;
    let plan = stack_with(&part, &engine, progress)?;
    let placements = plan
        .placements
        .iter()
        .map(|p| PlacedAnswer {
            index: p.index,
            pose: PoseAnswer::of(&p.translation, &p.orientation, &p.cost, h),
            stage: p.stage,
            examined: p.examined,
            contacts: p
                .contacts
                .iter()
                .map(|c| ContactAnswer {
                    with: match c.with {
                        ContactWith::Floor => Support::Floor,
                        ContactWith::Part(k) => Support::Part(k),
                    },
                    supports: c.supports,
                })
                .collect(),
        })
        .collect();
    let s = &plan.stats;
    Ok(StackAnswer {
        status: if plan.stopped { "stopped" } else { "done" }.to_string(),
        stopped: None,
        part: part.name.clone(),
        count: opts.count,
        complete: plan.complete,
        placements,
        stack_height: plan.stack_height.to_f64() * h,
        grid_step: h,
        stats: Some(PlacementStats::of(&s.place, &s.obstacles, s.seconds)),
        unstable: s.unstable,
        not_lowerable: s.not_lowerable,
        orientations: s.orientations,
        seconds: None,
        plan,
    })
}
